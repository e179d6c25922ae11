//! Volume and imager shaders run by the interpreter: programs that start with `Ci`, `Oi` (and,
//! for imagers, `alpha`) holding what arrives instead of zero.

use super::exec::{release, run_erased_with, Incoming, InterpShader, LightCtx};
use super::frame::{Frame, Loc};
use super::prepare::Program;
use crate::ir::Global;
use anysl_core::prelude::*;
use anysl_core::{Erased, ErasedContext, ImagerPixel, ImagerShader, VolumeShader};

/// Global `g` of chunk `k` after the run, if the program has it.
fn read_color<F: ShadingFloat>(fr: &Frame<F>, p: &Program, g: Global, k: usize) -> Option<Color<F>> {
    match p.global_loc(g) {
        Some(Loc::Num { off, .. }) => Some(fr.color(off, k)),
        _ => None,
    }
}

impl VolumeShader for InterpShader {
    fn volume<F: ShadingFloat, C: ShadingContext<F>>(
        &self,
        ctx: &mut C,
        e: &mut Exec<F>,
        entering: SurfaceOutput<F>,
    ) -> SurfaceOutput<F> {
        let p = &*self.program;
        let incoming = [Incoming { ci: entering.Ci, oi: entering.Oi, alpha: F::c(1.0) }];
        let fr =
            run_erased_with(p, &self.values, &mut [Erased(ctx as &mut dyn ErasedContext<F>)], &[e.mask()], &incoming);
        let out = SurfaceOutput {
            Ci: read_color(&fr, p, Global::Ci, 0).unwrap_or(entering.Ci),
            Oi: read_color(&fr, p, Global::Oi, 0).unwrap_or(entering.Oi),
        };
        release(fr);
        out
    }
}

impl ImagerShader for InterpShader {
    fn image<F: ShadingFloat>(&self, e: &mut Exec<F>, pixel: ImagerPixel<F>) -> ImagerPixel<F> {
        let mut px = [pixel];
        self.image_batch(&mut px, &[e.mask()]);
        px[0]
    }

    /// All chunks in one run of the program: the ops are decoded once per batch.
    fn image_batch<F: ShadingFloat>(&self, pixels: &mut [ImagerPixel<F>], masks: &[F::Mask]) {
        assert!(masks.len() >= pixels.len(), "{} chunks, {} masks", pixels.len(), masks.len());
        let p = &*self.program;
        let mut ctxs: Vec<LightCtx<'_, F>> = pixels.iter().map(LightCtx::imager).collect();
        let incoming: Vec<Incoming<F>> =
            pixels.iter().map(|px| Incoming { ci: px.Ci, oi: px.Oi, alpha: px.alpha }).collect();
        let mut erased: Vec<Erased<'_, F>> = ctxs.iter_mut().map(|c| Erased(c as &mut dyn ErasedContext<F>)).collect();
        let fr = run_erased_with(p, &self.values, &mut erased, &masks[..pixels.len()], &incoming);
        for (k, px) in pixels.iter_mut().enumerate() {
            px.Ci = read_color(&fr, p, Global::Ci, k).unwrap_or(px.Ci);
            px.Oi = read_color(&fr, p, Global::Oi, k).unwrap_or(px.Oi);
            if let Some(Loc::Num { off, .. }) = p.global_loc(Global::Alpha) {
                px.alpha = fr.get(off, k);
            }
        }
        release(fr);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::back::interp::Program;
    use anysl_core::PointContext;
    use std::sync::Arc;

    fn shader(src: &str) -> InterpShader {
        let m = crate::compile_source("t.sl", src, &crate::CompileOptions::default()).unwrap().module;
        let m = crate::passes::optimize(m, &crate::passes::PassOptions::default());
        InterpShader::new(Arc::new(Program::new(m).unwrap()))
    }

    #[test]
    fn a_volume_shader_starts_from_the_incoming_colour() {
        let s = shader("volume half(float k = 0.5) { Ci *= k; Oi = mix(Oi, color 1, k) + length(I); }");
        let g = Globals::at(Vec3::new(1.0f32, 2.0, 3.0));
        let mut ctx = PointContext::<f32, anysl_core::LightData>::new(g, &[]);
        let entering = SurfaceOutput { Ci: Color::c(0.8, 0.4, 0.2), Oi: Color::c(0.5, 0.5, 0.0) };
        let out = s.volume(&mut ctx, &mut Exec::new(), entering);
        assert_eq!((out.Ci.r, out.Ci.g, out.Ci.b), (0.4, 0.2, 0.1));
        assert_eq!((out.Oi.r, out.Oi.b), (0.75, 0.5));
    }

    #[test]
    fn an_imager_sees_the_pixel_and_may_set_alpha() {
        let s = shader(
            "imager bg(color background = color(0, 0, 1)) { Ci += (1 - alpha) * background; Oi = 1; alpha = 1; }",
        );
        let px = ImagerPixel {
            P: Vec3::new(3.5, 2.5, 0.0),
            Ci: Color::c(0.2, 0.2, 0.2),
            Oi: Color::c(0.25, 0.25, 0.25),
            alpha: 0.25f32,
        };
        let out = s.image(&mut Exec::new(), px);
        assert_eq!((out.Ci.r, out.Ci.b, out.Oi.g, out.alpha), (0.2, 0.95, 1.0, 1.0));
        let s = shader("imager vig() { Ci *= xcomp(P); }");
        let out = s.image(&mut Exec::new(), px);
        assert!((out.Ci.r - 0.7).abs() < 1e-6 && out.alpha == 0.25, "{out:?}");
    }
}
