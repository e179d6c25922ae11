//! `granite` — turbulence (a fractal sum of |noise|) between a dark and a light stone colour.

use crate::common::{view_frame, Finish, VIEW_GLOBALS};
use anysl_core::prelude::*;
use anysl_core::GlobalSet;

anysl_core::shader_params! {
    /// Classic granite (RenderMan Companion / BMRT `granite`): turbulence
    /// `sum = Σ_o |snoise(2^o·PP)| / 2^o` over `octaves` octaves of `PP = frequency·P + offset`
    /// (the classic `|0.5 - noise(f·PP)|/f` is half of each term, absorbed in `contrast`),
    /// `Ct = Cs·mix(darkcolor, lightcolor, clamp(contrast·sum, 0, 1))`, plastic lighting.
    /// The defaults (apart from roughness 0.1) are the granite of the shading workload
    /// (`shaders/assets/workload_ref/shading_workload.md` §5(d)); with `roughness = 0.08` and its lights it
    /// reproduces that reference image.
    pub struct Granite: surface "granite" {
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 0.8;
        /// Specular coefficient.
        uniform float Ks = 0.2;
        /// Highlight roughness.
        uniform float roughness = 0.1;
        /// Highlight colour.
        uniform color specularcolor = [1.0, 1.0, 1.0];
        /// Base frequency of the turbulence (scale of P).
        uniform float frequency = 4.0;
        /// Offset of the noise domain (decorrelates it from the lattice at the origin).
        uniform vector offset = [1.5, 0.75, 2.25];
        /// Number of octaves (a uniform trip count, rounded; 1 to 16).
        uniform float octaves = 6.0;
        /// Gain from turbulence to the dark→light mix.
        uniform float contrast = 1.5;
        /// Colour where the turbulence is 0.
        uniform color darkcolor = [0.20, 0.18, 0.17];
        /// Colour where the scaled turbulence reaches 1.
        uniform color lightcolor = [0.95, 0.92, 0.88];
    }
}

impl Granite {
    /// The turbulence sum at `p`.
    #[inline(always)]
    #[must_use]
    pub fn turbulence<F: ShadingFloat>(&self, p: Vec3<F>) -> F {
        let pp = p * F::c(self.frequency) + Vec3::from_array(self.offset);
        let octaves = self.octaves.round().clamp(1.0, 16.0) as u32;
        let mut sum = F::c(0.0);
        let mut freq = 1.0f64;
        // A uniform trip count: a plain loop, the same for every lane.
        for _ in 0..octaves {
            sum += snoise3(pp * F::c(freq)).abs() * F::c(1.0 / freq);
            freq *= 2.0;
        }
        sum
    }
}

impl SurfaceShader for Granite {
    #[inline(always)]
    fn globals_read(&self) -> GlobalSet {
        VIEW_GLOBALS | GlobalSet::CS
    }

    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let (nf, v) = view_frame(&g);
        let t = clamp(F::c(self.contrast) * self.turbulence(g.P), F::c(0.0), F::c(1.0));
        let dark = Color::from_array(self.darkcolor);
        let ct = g.Cs * (dark + (Color::from_array(self.lightcolor) - dark) * t);
        let finish = Finish {
            ka: self.Ka,
            kd: self.Kd,
            ks: self.Ks,
            roughness: self.roughness,
            specularcolor: self.specularcolor,
        };
        let c = finish.plastic(ctx, e, nf, v, ct);
        SurfaceOutput { Ci: g.Os * c, Oi: g.Os }
    }
}
