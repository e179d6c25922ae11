//! `plastic` — the paper's "Phong": Lambertian diffuse plus a Blinn highlight.

use crate::common::{view_frame, Finish, VIEW_GLOBALS};
use anysl_core::prelude::*;
use anysl_core::GlobalSet;

anysl_core::shader_params! {
    /// RSL `plastic` (RenderMan Interface 3.2 standard shader): `Oi = Os`,
    /// `Ci = Os·(Cs·(Ka·ambient() + Kd·diffuse(Nf)) + specularcolor·Ks·specular(Nf, V, roughness))`.
    pub struct Plastic: surface "plastic" {
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 0.5;
        /// Specular coefficient.
        uniform float Ks = 0.5;
        /// Highlight roughness (Blinn exponent `1/roughness`).
        uniform float roughness = 0.1;
        /// Highlight colour.
        uniform color specularcolor = [1.0, 1.0, 1.0];
    }
}

impl Plastic {
    /// The illumination coefficients.
    #[inline(always)]
    pub(crate) fn finish(&self) -> Finish {
        Finish { ka: self.Ka, kd: self.Kd, ks: self.Ks, roughness: self.roughness, specularcolor: self.specularcolor }
    }
}

impl SurfaceShader for Plastic {
    #[inline(always)]
    fn globals_read(&self) -> GlobalSet {
        VIEW_GLOBALS | GlobalSet::CS
    }

    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let (nf, v) = view_frame(&g);
        let c = self.finish().plastic(ctx, e, nf, v, g.Cs);
        SurfaceOutput { Ci: g.Os * c, Oi: g.Os }
    }
}
