//! `glass` — a dielectric: Fresnel-weighted reflection and refraction rays plus a highlight.

use crate::common::{view_frame, Finish, VIEW_GLOBALS};
use anysl_core::prelude::*;
use anysl_core::GlobalSet;

anysl_core::shader_params! {
    /// Classic ray-traced glass (after BMRT's `glass`): with `fresnel(I, Nf, η)` giving
    /// `kr`, `kt`, `R`, `T`,
    /// `Ci = Cs·(Ka·ambient() + Kd·diffuse(Nf)) + specularcolor·Ks·specular(Nf, V, roughness)
    ///      + Kr·kr·trace(P, R) + Kt·kt·trace(P, T)`, `Oi = 1`.
    /// `η` is `1/eta` where the ray enters (`I·N < 0`) and `eta` where it leaves. Each ray is
    /// traced only for the lanes whose weight is nonzero, so lanes under total internal
    /// reflection (`kt = 0`) never trace the refraction ray.
    pub struct Glass: surface "glass" {
        /// Ambient coefficient (0: clear glass has no matte part).
        uniform float Ka = 0.0;
        /// Diffuse coefficient.
        uniform float Kd = 0.0;
        /// Specular coefficient.
        uniform float Ks = 0.5;
        /// Weight of the reflection ray.
        uniform float Kr = 1.0;
        /// Weight of the refraction ray.
        uniform float Kt = 1.0;
        /// Highlight roughness.
        uniform float roughness = 0.05;
        /// Index of refraction of the glass (relative to the outside).
        uniform float eta = 1.5;
        /// Highlight colour.
        uniform color specularcolor = [1.0, 1.0, 1.0];
    }
}

impl SurfaceShader for Glass {
    #[inline(always)]
    fn globals_read(&self) -> GlobalSet {
        VIEW_GLOBALS | GlobalSet::CS
    }

    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let (nf, v) = view_frame(&g);
        let zero = F::c(0.0);
        let finish = Finish {
            ka: self.Ka,
            kd: self.Kd,
            ks: self.Ks,
            roughness: self.roughness,
            specularcolor: self.specularcolor,
        };
        let mut ci = if self.Ka != 0.0 || self.Kd != 0.0 {
            finish.plastic(ctx, e, nf, v, g.Cs)
        } else if self.Ks != 0.0 {
            finish.specular_part(&finish.light_sums_specular_only(ctx, e, nf, v))
        } else {
            Color::zero()
        };
        let eta = F::c(self.eta);
        let entering = g.I.dot(g.N).lt(zero);
        let ratio = F::select(entering, F::c(1.0) / eta, eta);
        let fr = fresnel(g.I, nf, ratio);
        let wr = fr.kr * F::c(self.Kr);
        let wt = fr.kt * F::c(self.Kt);
        e.if_(
            wr.gt(zero),
            #[inline(always)]
            |e| {
                let c = ctx.trace(e, g.P, fr.r);
                e.update(&mut ci, |ci| ci + c * wr);
            },
        );
        e.if_(
            wt.gt(zero),
            #[inline(always)]
            |e| {
                let c = ctx.trace(e, g.P, fr.t);
                e.update(&mut ci, |ci| ci + c * wt);
            },
        );
        SurfaceOutput { Ci: ci, Oi: Color::splat(F::c(1.0)) }
    }
}
