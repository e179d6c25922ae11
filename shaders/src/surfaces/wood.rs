//! `wood` — growth rings around the z axis, perturbed by noise, with fine grain.

use crate::common::{view_frame, Finish, VIEW_GLOBALS};
use anysl_core::prelude::*;
use anysl_core::GlobalSet;

anysl_core::shader_params! {
    /// Classic solid wood (after the RenderMan Companion / BMRT `wood`), as in the shading
    /// workload (`shaders/assets/workload_ref/shading_workload.md` §5(c)):
    /// `r = ringscale·√(x² + y²) + 1.5·snoise(2P + (0.375, 1.25, 2.625))`,
    /// `ring = smoothstep(0, 0.8, f) - smoothstep(0.83, 1, f)` with `f = r - floor(r)`,
    /// `grain = 0.8 + 0.2·snoise(grainscale·x, grainscale·y, grainscale/32·z)`,
    /// `Ct = mix(lightwood, darkwood, ring)·grain`, plastic lighting. The defaults are the
    /// workload's except roughness (0.1; the workload uses 0.08).
    pub struct Wood: surface "wood" {
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 0.75;
        /// Specular coefficient.
        uniform float Ks = 0.4;
        /// Highlight roughness.
        uniform float roughness = 0.1;
        /// Highlight colour.
        uniform color specularcolor = [1.0, 1.0, 1.0];
        /// Rings per unit distance from the z axis.
        uniform float ringscale = 8.0;
        /// Frequency of the fine grain across the rings (along z it is 1/32 of this).
        uniform float grainscale = 48.0;
        /// Colour between the rings.
        uniform color lightwood = [0.70, 0.45, 0.22];
        /// Colour of the rings.
        uniform color darkwood = [0.30, 0.15, 0.06];
    }
}

impl Wood {
    /// The wood colour at `p` (before lighting).
    #[inline(always)]
    #[must_use]
    pub fn color<F: ShadingFloat>(&self, p: Vec3<F>) -> Color<F> {
        let n1 = snoise3(p * F::c(2.0) + Vec3::c(0.375, 1.25, 2.625));
        let r = F::c(self.ringscale) * (p.x * p.x + p.y * p.y).sqrt() + F::c(1.5) * n1;
        let f = r - r.floor();
        let ring = smoothstep(F::c(0.0), F::c(0.8), f) - smoothstep(F::c(0.83), F::c(1.0), f);
        let gs = F::c(self.grainscale);
        let n2 = snoise3(Vec3::new(gs * p.x, gs * p.y, F::c(self.grainscale / 32.0) * p.z));
        let grain = F::c(0.8) + F::c(0.2) * n2;
        let light = Color::from_array(self.lightwood);
        (light + (Color::from_array(self.darkwood) - light) * ring) * grain
    }
}

impl SurfaceShader for Wood {
    #[inline(always)]
    fn globals_read(&self) -> GlobalSet {
        VIEW_GLOBALS
    }

    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let (nf, v) = view_frame(&g);
        let ct = self.color(g.P);
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
