//! Volume and imager shaders through all three back ends: `tests/build.rs` generates Rust for
//! the standard ones (`fog`, `depthcue`, `background`), the scenes' (`smoke`) and those of
//! `tests/data/rsl/stages`; each runs on the same inputs through generated Rust, the
//! interpreter and the JIT, at `f32` (lane by lane) and at 8 lanes, and the outputs agree.
//! Two shaders also have their answers computed here: `tintfog` (a `Ci` that does not start
//! as what arrives shows) and `vignette` (reads `P`, `Ci`, `Oi`, `alpha`; writes all three).

use anysl_core::prelude::*;
use anysl_core::{ImagerPixel, ImagerShader, PointContext, VolumeShader};
use anysl_jit::{JitOptions, JitShader};
use anysl_rsl::back::interp::{InterpShader, Program};
use anysl_shaders::{table1_lights, Light};
use anysl_simd::F32x8;
use std::path::Path;
use std::sync::Arc;

/// Receives the generated shaders.
pub trait StageVisitor {
    /// A volume shader: file stem, source path, the generated shader with its defaults.
    fn volume<S: VolumeShader + Clone>(&mut self, stem: &str, path: &str, s: S);
    /// An imager shader.
    fn imager<S: ImagerShader + Clone>(&mut self, stem: &str, path: &str, s: S);
}

include!(concat!(env!("OUT_DIR"), "/stages.rs"));

const N: usize = 8;

fn module(path: &str) -> anysl_rsl::ir::Module {
    anysl_rsl::compile_file(Path::new(path), &anysl_rsl::CompileOptions::default())
        .unwrap_or_else(|e| panic!("{path}: {e}"))
        .module
}

fn interp(path: &str) -> InterpShader {
    let m = anysl_rsl::passes::optimize(module(path), &anysl_rsl::passes::PassOptions::default());
    InterpShader::new(Arc::new(Program::new(m).unwrap_or_else(|e| panic!("{path}: {e}"))))
}

fn jit(path: &str) -> JitShader {
    JitShader::new(module(path), JitOptions::default()).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Eight ray segments: lengths from 0 to 40, varied directions; what arrives varies too.
struct Segments {
    e: [[f32; 3]; N],
    p: [[f32; 3]; N],
    ci: [[f32; 3]; N],
    oi: [[f32; 3]; N],
}

fn segments() -> Segments {
    let len = [0.0, 0.3, 0.49, 0.51, 1.0, 2.5, 7.0, 40.0];
    let mut s = Segments { e: [[0.0; 3]; N], p: [[0.0; 3]; N], ci: [[0.0; 3]; N], oi: [[0.0; 3]; N] };
    for k in 0..N {
        let a = k as f32 * 0.7;
        let dir = [a.cos() * 0.6, a.sin() * 0.6, 0.8];
        s.e[k] = [0.1 * k as f32, -0.2, 0.3];
        s.p[k] = core::array::from_fn(|c| s.e[k][c] + len[k] * dir[c]);
        s.ci[k] = [0.9 - 0.1 * k as f32, 0.2 + 0.05 * k as f32, 0.5];
        s.oi[k] = [0.25 * (k % 4) as f32 + 0.25; 3];
    }
    s
}

fn gather<F: ShadingFloat>(v: &[[f32; 3]], base: usize, c: usize) -> F {
    let lanes: Vec<f32> = (0..F::LANES).map(|i| v[base + i][c]).collect();
    F::load(&lanes)
}

fn gather3<F: ShadingFloat>(v: &[[f32; 3]], base: usize) -> Vec3<F> {
    Vec3::new(gather(v, base, 0), gather(v, base, 1), gather(v, base, 2))
}

/// `Ci` and `Oi` (six values per lane) of `s` on the segments, at float type `F`.
fn run_volume<F: ShadingFloat, S: VolumeShader>(s: &S, seg: &Segments, lights: &[Light]) -> Vec<[f64; 6]> {
    let mut out = Vec::new();
    for base in (0..N).step_by(F::LANES) {
        let (e, p) = (gather3::<F>(&seg.e, base), gather3::<F>(&seg.p, base));
        let i = p - e;
        let mut g = Globals::at(p);
        (g.E, g.I, g.N, g.Ng) =
            (e, i, Vec3::new(F::c(0.0), F::c(0.0), F::c(-1.0)), Vec3::new(F::c(0.0), F::c(0.0), F::c(-1.0)));
        let mut ctx = PointContext::new(g, lights);
        let entering =
            SurfaceOutput { Ci: gather3::<F>(&seg.ci, base).to_color(), Oi: gather3::<F>(&seg.oi, base).to_color() };
        let r = s.volume(&mut ctx, &mut Exec::new(), entering);
        for l in 0..F::LANES {
            let (c, o) = (r.Ci.lane(l), r.Oi.lane(l));
            out.push([c[0], c[1], c[2], o[0], o[1], o[2]]);
        }
    }
    out
}

/// Eight pixels of a 64 × 48 raster with varied colour and coverage.
fn pixels() -> Vec<[f32; 6]> {
    (0..N)
        .map(|k| {
            let (x, y) = ((k * 9 % 64) as f32 + 0.5, (k * 7 % 48) as f32 + 0.5);
            let alpha = [0.0, 0.25, 0.5, 1.0][k % 4];
            [x, y, 0.8 * alpha, 0.1 + 0.1 * k as f32, 0.3 * alpha, alpha]
        })
        .collect()
}

/// `Ci`, `Oi` and `alpha` (seven values per lane) of `s` on the pixels, at float type `F`.
fn run_imager<F: ShadingFloat, S: ImagerShader>(s: &S, px: &[[f32; 6]]) -> Vec<[f64; 7]> {
    let mut out = Vec::new();
    for base in (0..N).step_by(F::LANES) {
        let col = |c: usize| -> F { F::load(&(0..F::LANES).map(|i| px[base + i][c]).collect::<Vec<_>>()) };
        let alpha = col(5);
        let pixel = ImagerPixel {
            P: Vec3::new(col(0), col(1), F::c(0.0)),
            Ci: Color::new(col(2), col(3), col(4)),
            Oi: Color::new(alpha, alpha, alpha),
            alpha,
        };
        let r = s.image(&mut Exec::new(), pixel);
        for l in 0..F::LANES {
            let (c, o) = (r.Ci.lane(l), r.Oi.lane(l));
            out.push([c[0], c[1], c[2], o[0], o[1], o[2], r.alpha.lane(l)]);
        }
    }
    out
}

fn agree<const K: usize>(what: &str, a: &[[f64; K]], b: &[[f64; K]], tol: f64) {
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        for c in 0..K {
            let d = (x[c] - y[c]).abs();
            assert!(d <= tol * x[c].abs().max(1.0), "{what}: lane {k} value {c}: {} against {}", x[c], y[c]);
        }
    }
}

#[derive(Default)]
struct Run {
    volumes: Vec<String>,
    imagers: Vec<String>,
}

impl StageVisitor for Run {
    fn volume<S: VolumeShader + Clone>(&mut self, stem: &str, path: &str, generated: S) {
        let (i, j) = (interp(path), jit(path));
        let seg = segments();
        let lights = table1_lights();
        let reference = run_volume::<f32, _>(&i, &seg, &lights);
        for (name, got) in [
            ("generated f32", run_volume::<f32, _>(&generated, &seg, &lights)),
            ("generated f32x8", run_volume::<F32x8, _>(&generated, &seg, &lights)),
            ("interpreter f32x8", run_volume::<F32x8, _>(&i, &seg, &lights)),
            ("jit f32", run_volume::<f32, _>(&j, &seg, &lights)),
            ("jit f32x8", run_volume::<F32x8, _>(&j, &seg, &lights)),
        ] {
            agree(&format!("{stem}: {name} against the interpreter"), &got, &reference, 2e-6);
        }
        assert!(
            j.compiled().contains(&anysl_jit::Variant::F32) && j.compiled().contains(&anysl_jit::Variant::X8),
            "{stem}: the JIT ran {:?}",
            j.compiled()
        );
        if stem == "tintfog" {
            for (k, r) in reference.iter().enumerate() {
                let len = (0..3).map(|c| f64::from(seg.p[k][c] - seg.e[k][c]).powi(2)).sum::<f64>().sqrt();
                let d = 1.0 - (-len / 2.0).exp();
                let bg = [0.1, 0.2, 0.7];
                for c in 0..3 {
                    let ci = 0.8 * (f64::from(seg.ci[k][c]) * (1.0 - d) + bg[c] * d);
                    let oi = f64::from(seg.oi[k][c]);
                    let oi = if len > 0.5 { oi * (1.0 - d) + d } else { oi };
                    assert!((r[c] - ci).abs() < 1e-5, "tintfog lane {k}: Ci {} against {ci}", r[c]);
                    assert!((r[3 + c] - oi).abs() < 1e-5, "tintfog lane {k}: Oi {} against {oi}", r[3 + c]);
                }
            }
        }
        self.volumes.push(stem.to_string());
    }

    fn imager<S: ImagerShader + Clone>(&mut self, stem: &str, path: &str, generated: S) {
        let (i, j) = (interp(path), jit(path));
        let px = pixels();
        let reference = run_imager::<f32, _>(&i, &px);
        for (name, got) in [
            ("generated f32", run_imager::<f32, _>(&generated, &px)),
            ("generated f32x8", run_imager::<F32x8, _>(&generated, &px)),
            ("interpreter f32x8", run_imager::<F32x8, _>(&i, &px)),
            ("jit f32", run_imager::<f32, _>(&j, &px)),
            ("jit f32x8", run_imager::<F32x8, _>(&j, &px)),
        ] {
            agree(&format!("{stem}: {name} against the interpreter"), &got, &reference, 2e-6);
        }
        if stem == "vignette" {
            for (k, (r, p)) in reference.iter().zip(&px).enumerate() {
                let (x, y) = (2.0 * f64::from(p[0]) / 64.0 - 1.0, 2.0 * f64::from(p[1]) / 48.0 - 1.0);
                let kk = 1.0 - 0.6 * (x * x + y * y) / 2.0;
                let a = f64::from(p[5]);
                let bg = [0.2, 0.3, 0.4];
                for c in 0..3 {
                    let want = kk * f64::from(p[2 + c]) + (1.0 - a) * bg[c];
                    assert!((r[c] - want).abs() < 1e-5, "vignette pixel {k}: Ci {} against {want}", r[c]);
                    assert!((r[3 + c] - a).abs() < 1e-6, "vignette pixel {k}: Oi {}", r[3 + c]);
                }
                assert!((r[6] - (0.5 + 0.5 * a)).abs() < 1e-6, "vignette pixel {k}: alpha {}", r[6]);
            }
        }
        self.imagers.push(stem.to_string());
    }
}

#[test]
fn volume_and_imager_shaders_agree_through_generated_rust_the_interpreter_and_the_jit() {
    assert!(STAGE_ERRORS.is_empty(), "{STAGE_ERRORS:?}");
    let mut run = Run::default();
    visit_stages(&mut run);
    for want in ["fog", "depthcue", "smoke", "tintfog"] {
        assert!(run.volumes.iter().any(|v| v == want), "{want} not among {:?}", run.volumes);
    }
    for want in ["background", "vignette"] {
        assert!(run.imagers.iter().any(|v| v == want), "{want} not among {:?}", run.imagers);
    }
}
