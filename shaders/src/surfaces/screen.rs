//! `screen` — a wire mesh: metal wires with plastic lighting, holes that let the ray through.

use crate::common::{view_frame, Finish, VIEW_GLOBALS};
use anysl_core::prelude::*;
use anysl_core::GlobalSet;

anysl_core::shader_params! {
    /// The classic RenderMan wire screen: lanes where `mod(s·frequency, 1) < density` or
    /// `mod(t·frequency, 1) < density` are wire (plastic lighting, `Oi = Os`); the rest are
    /// holes (`Ci = 0`, `Oi = 0`, the renderer continues the ray). Masked, so lighting runs
    /// only for wire lanes and is skipped when a packet sees only holes.
    pub struct Screen: surface "screen" {
        /// Ambient coefficient.
        uniform float Ka = 0.1;
        /// Diffuse coefficient.
        uniform float Kd = 0.5;
        /// Specular coefficient.
        uniform float Ks = 0.5;
        /// Highlight roughness.
        uniform float roughness = 0.1;
        /// Highlight colour.
        uniform color specularcolor = [1.0, 1.0, 1.0];
        /// Fraction of each period covered by wire.
        uniform float density = 0.25;
        /// Wires per unit of s and t.
        uniform float frequency = 20.0;
    }
}

impl Screen {
    /// The wire lanes at (s, t).
    #[inline(always)]
    #[must_use]
    pub fn wire<F: ShadingFloat>(&self, s: F, t: F) -> F::Mask {
        let (f, d, one) = (F::c(self.frequency), F::c(self.density), F::c(1.0));
        fmod(s * f, one).lt(d) | fmod(t * f, one).lt(d)
    }
}

impl SurfaceShader for Screen {
    #[inline(always)]
    fn globals_read(&self) -> GlobalSet {
        VIEW_GLOBALS | GlobalSet::CS | GlobalSet::S | GlobalSet::T
    }

    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let mut out = SurfaceOutput { Ci: Color::zero(), Oi: Color::zero() };
        let finish = Finish {
            ka: self.Ka,
            kd: self.Kd,
            ks: self.Ks,
            roughness: self.roughness,
            specularcolor: self.specularcolor,
        };
        e.if_(
            self.wire(g.s, g.t),
            #[inline(always)]
            |e| {
                let (nf, v) = view_frame(&g);
                let c = finish.plastic(ctx, e, nf, v, g.Cs);
                e.assign(&mut out, SurfaceOutput { Ci: g.Os * c, Oi: g.Os });
            },
        );
        out
    }
}
