//! `checker` — an antialiased checkerboard in (s, t) with plastic lighting.

use crate::common::{filtered_square, view_frame, Finish, VIEW_GLOBALS};
use anysl_core::prelude::*;
use anysl_core::GlobalSet;

anysl_core::shader_params! {
    /// The classic RenderMan checkerboard on (s, t): `whitecolor` where `mod(s·frequency, 1)`
    /// and `mod(t·frequency, 1)` fall in the same half period, `blackcolor` elsewhere. Both
    /// check edges are box-filtered with `filterstep` (exactly `step` without derivatives),
    /// then lit like plastic: `Ci = Os·(Ct·(Ka·ambient() + Kd·diffuse(Nf)) +
    /// specularcolor·Ks·specular(Nf, V, roughness))`, `Oi = Os`.
    pub struct Checker: surface "checker" uses_derivatives = true {
        /// Diffuse coefficient.
        uniform float Kd = 0.5;
        /// Ambient coefficient.
        uniform float Ka = 0.1;
        /// Specular coefficient.
        uniform float Ks = 0.3;
        /// Highlight roughness.
        uniform float roughness = 0.1;
        /// Check periods per unit of s and t (each period holds one white and one black check).
        uniform float frequency = 10.0;
        /// Colour of the black checks.
        uniform color blackcolor = [0.0, 0.0, 0.0];
        /// Colour of the white checks.
        uniform color whitecolor = [1.0, 1.0, 1.0];
        /// Highlight colour.
        uniform color specularcolor = [1.0, 1.0, 1.0];
    }
}

impl Checker {
    /// The illumination coefficients.
    #[inline(always)]
    pub(crate) fn finish(&self) -> Finish {
        Finish { ka: self.Ka, kd: self.Kd, ks: self.Ks, roughness: self.roughness, specularcolor: self.specularcolor }
    }

    /// The pattern alone: the weight of `blackcolor` at (s, t), in [0, 1] (0 or 1 without
    /// derivatives).
    #[inline(always)]
    #[must_use]
    pub fn black_weight<F: ShadingFloat>(&self, s: F, t: F) -> F {
        let f = F::c(self.frequency);
        let a = filtered_square(s * f);
        let b = filtered_square(t * f);
        // Filtered XOR: black where exactly one coordinate is in its upper half period.
        a + b - F::c(2.0) * a * b
    }
}

impl SurfaceShader for Checker {
    #[inline(always)]
    fn globals_read(&self) -> GlobalSet {
        VIEW_GLOBALS | GlobalSet::S | GlobalSet::T
    }

    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let (nf, v) = view_frame(&g);
        let k = self.black_weight(g.s, g.t);
        let white = Color::from_array(self.whitecolor);
        let ct = white + (Color::from_array(self.blackcolor) - white) * k;
        let c = self.finish().plastic(ctx, e, nf, v, ct);
        SurfaceOutput { Ci: g.Os * c, Oi: g.Os }
    }
}
