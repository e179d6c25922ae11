//! `venus` — a cloudy planetary atmosphere: fBm with a Coriolis twist, coloured by a spline.

use crate::common::{view_frame, Finish, VIEW_GLOBALS};
use anysl_core::prelude::*;
use anysl_core::GlobalSet;

/// The cloud palette, from deep haze to bright cloud tops (Catmull-Rom knots; the first and
/// last are repeated so the curve ends on them).
const PALETTE: [[f64; 3]; 7] = [
    [0.30, 0.16, 0.06],
    [0.30, 0.16, 0.06],
    [0.55, 0.34, 0.13],
    [0.80, 0.62, 0.33],
    [0.93, 0.83, 0.58],
    [1.00, 0.96, 0.84],
    [1.00, 0.96, 0.84],
];

anysl_core::shader_params! {
    /// Musgrave's Venus (*Texturing & Modeling*, 2nd ed., ch. 15 "venus"), with +y as the
    /// planet's axis: `P` is rotated about the axis by
    /// `angle = twist·2π·rsq + distortion·snoise(2P)`, where `rsq = x² + z²` of
    /// `normalize(P)` (cos² of the latitude: a Coriolis shear that is strongest at the
    /// equator, roughened by noise); then `a = Σ omega^o·snoise(2^o·PP)` over `octaves`
    /// octaves, `value = |offset + scale·a|`, and the colour is a Catmull-Rom spline of
    /// `value/2` through a haze-to-cloud palette.
    /// Matte lighting: `Ci = Os·Ct·(Ka·ambient() + Kd·diffuse(Nf))`, `Oi = Os`.
    pub struct Venus: surface "venus" {
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 1.0;
        /// Offset added to the fBm before `abs`.
        uniform float offset = 1.0;
        /// Scale of the fBm.
        uniform float scale = 0.6;
        /// Coriolis twist, in turns at the equator.
        uniform float twist = 0.22;
        /// Noise added to the twist angle, in radians.
        uniform float distortion = 0.3;
        /// Amplitude ratio between octaves.
        uniform float omega = 0.65;
        /// Number of octaves (a uniform trip count, rounded; 1 to 16).
        uniform float octaves = 8.0;
    }
}

impl Venus {
    /// The cloud value `|offset + scale·fBm(twisted P)|` at `p`.
    #[inline(always)]
    #[must_use]
    pub fn value<F: ShadingFloat>(&self, p: Vec3<F>) -> F {
        let pn = p.normalize();
        let rsq = pn.x * pn.x + pn.z * pn.z;
        let angle = F::c(self.twist * 2.0 * PI) * rsq + F::c(self.distortion) * snoise3(p * F::c(2.0));
        let (sn, cs) = (angle.sin(), angle.cos());
        let pp = Vec3::new(p.x * cs + p.z * sn, p.y, p.z * cs - p.x * sn);
        let octaves = self.octaves.round().clamp(1.0, 16.0) as u32;
        let (mut a, mut l, mut o) = (F::c(0.0), 1.0f64, 1.0f64);
        for _ in 0..octaves {
            a += F::c(o) * snoise3(pp * F::c(l));
            l *= 2.0;
            o *= self.omega;
        }
        (F::c(self.offset) + F::c(self.scale) * a).abs()
    }

    /// The cloud colour for a value (the palette spline over `value/2`).
    #[inline(always)]
    #[must_use]
    pub fn color<F: ShadingFloat>(value: F) -> Color<F> {
        let knots = PALETTE.map(Color::from_array);
        spline(&SplineBasis::CATMULL_ROM, value * F::c(0.5), &knots)
    }
}

impl SurfaceShader for Venus {
    #[inline(always)]
    fn globals_read(&self) -> GlobalSet {
        VIEW_GLOBALS
    }

    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let (nf, v) = view_frame(&g);
        let ct = Self::color(self.value(g.P));
        let finish = Finish { ka: self.Ka, kd: self.Kd, ks: 0.0, roughness: 1.0, specularcolor: [0.0; 3] };
        let l = finish.light_sums(ctx, e, nf, v);
        SurfaceOutput { Ci: g.Os * finish.matte_part(ct, &l), Oi: g.Os }
    }
}
