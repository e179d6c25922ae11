//! JIT = monomorphized build: every shader in `shaders/rsl` (the standard volumes and imager
//! included), `scenes/`, `tests/data/rsl/stages` and every conformance program,
//! JIT-compiled for `f32`, `F32x8` and `Dual<f32>`, against the same shader monomorphized at
//! that type (the hand-written generic Rust for the Table-1 shaders, the interpreter for the
//! rest) on random points; displacement, volume and imager shaders through their own entries
//! (`anysl_jit::check::StageAsSurface`), light shaders not here. Bound: no output more than 4 ulps *and* more than 2e-6·max(1, |x|)
//! apart (transcendentals and cancellations near zero differ in ulps without differing in
//! value). `ANYSL_JIT_POINTS` sets the number of points (default 10 000).

use anysl_ad::Dual;
use anysl_core::points::{shade_points, PointSet, ShadeOut};
use anysl_core::ShadingFloat;
use anysl_jit::check::StageAsSurface;
use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_rsl::back::interp::InterpShader;
use anysl_rsl::ir::ShaderKind;
use anysl_rsl::CompileOptions;
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::F32x8;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

fn mismatches(a: &ShadeOut<f32>, b: &ShadeOut<f32>) -> (usize, u64) {
    let c = anysl_jit::check::compare(a, b);
    (c.mismatches, c.max_ulps)
}

fn pair<F: ShadingFloat>(jit: &JitShader, aot: Option<&Surface>, set: &PointSet, lights: &[Light]) -> (usize, u64) {
    let mut a = ShadeOut::new(set.len());
    let mut b = ShadeOut::new(set.len());
    shade_points::<F, JitShader, Light>(jit, lights, set, &mut a);
    match aot {
        Some(s) => shade_points::<F, Surface, Light>(s, lights, set, &mut b),
        None => shade_points::<F, InterpShader, Light>(jit.interp(), lights, set, &mut b),
    }
    mismatches(&a, &b)
}

fn stage_pair<F: ShadingFloat>(
    jit: &StageAsSurface<JitShader>,
    interp: &StageAsSurface<InterpShader>,
    set: &PointSet,
    lights: &[Light],
) -> (usize, u64) {
    let mut a = ShadeOut::new(set.len());
    let mut b = ShadeOut::new(set.len());
    shade_points::<F, _, Light>(jit, lights, set, &mut a);
    shade_points::<F, _, Light>(interp, lights, set, &mut b);
    mismatches(&a, &b)
}

fn files() -> Vec<PathBuf> {
    let mut out = Vec::new();
    for dir in [
        root().join("shaders/rsl"),
        root().join("shaders/rsl/standard"),
        root().join("shaders/rsl/standard/volume"),
        root().join("shaders/rsl/standard/imager"),
        root().join("scenes"),
        root().join("tests/data/rsl/stages"),
        root().join("tests/data/rsl/conformance"),
    ] {
        let mut v: Vec<PathBuf> = std::fs::read_dir(&dir)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "sl"))
            .collect();
        v.sort();
        out.extend(v);
    }
    out
}

fn check(file: &Path, n: usize, failures: &mut Vec<String>, skipped: &mut Vec<String>, stages: &mut usize) -> usize {
    let include = vec![root().join("shaders/rsl/include")];
    let Ok(c) = anysl_rsl::compile_file(file, &CompileOptions { include_dirs: include, ..Default::default() }) else {
        return 0;
    };
    let kind = c.module.kind;
    if kind == ShaderKind::Light {
        return 0;
    }
    let stem = file.file_stem().unwrap().to_string_lossy().to_string();
    let jit = match JitShader::new(c.module, JitOptions::default()) {
        Ok(j) => j,
        Err(e) => {
            failures.push(format!("{stem}: {e}"));
            return 0;
        }
    };
    for v in [Variant::F32, Variant::X8, Variant::DualF32] {
        if let Err(e) = jit.variant(v) {
            // Run-time strings (`format` with numbers), textures: the JIT shader runs on the
            // interpreter; listed, not failed.
            if e.contains("not supported by the JIT") {
                skipped.push(format!("{stem}: {e}"));
            } else {
                failures.push(format!("{stem} {v:?}: {e}"));
            }
            return 0;
        }
    }
    let set = PointSet::random(n, 0x5eed_0005);
    let lights = table1_lights();
    let results = if kind == ShaderKind::Surface {
        let aot = Surface::by_name(if stem == "plastic" { "phong" } else { &stem });
        [
            ("f32", pair::<f32>(&jit, aot.as_ref(), &set, &lights)),
            ("x8", pair::<F32x8>(&jit, aot.as_ref(), &set, &lights)),
            ("dual-f32", pair::<Dual<f32>>(&jit, aot.as_ref(), &set, &lights)),
        ]
    } else {
        // Displacement, volume and imager shaders through their own entries, as surfaces,
        // against the interpreter.
        let j = StageAsSurface { shader: jit.clone(), kind };
        let i = StageAsSurface { shader: jit.interp().clone(), kind };
        [
            ("f32", stage_pair::<f32>(&j, &i, &set, &lights)),
            ("x8", stage_pair::<F32x8>(&j, &i, &set, &lights)),
            ("dual-f32", stage_pair::<Dual<f32>>(&j, &i, &set, &lights)),
        ]
    };
    *stages += usize::from(kind != ShaderKind::Surface);
    let mut count = 0;
    for (label, (bad, worst)) in results {
        count += 1;
        if bad > 0 {
            failures.push(format!("{stem} jit-{label}: {bad} outputs beyond the bound (max {worst} ulps)"));
        }
    }
    count
}

#[test]
fn jit_matches_monomorphized_build() {
    let n: usize = std::env::var("ANYSL_JIT_POINTS").ok().and_then(|s| s.parse().ok()).unwrap_or(10_000);
    let mut failures = Vec::new();
    let mut skipped = Vec::new();
    let (mut pairs, mut stages) = (0, 0);
    for f in files() {
        pairs += check(&f, n, &mut failures, &mut skipped, &mut stages);
    }
    // fog, depthcue, background, smoke, dented, tintfog, vignette.
    assert!(stages >= 7, "only {stages} displacement, volume and imager shaders checked");
    eprintln!("{pairs} comparisons; interpreter fallback for:\n{}", skipped.join("\n"));
    assert!(skipped.len() <= 8, "too many shaders the JIT cannot compile:\n{}", skipped.join("\n"));
    assert!(pairs > 100, "only {pairs} comparisons ran");
    assert!(failures.is_empty(), "{} failures:\n{}", failures.len(), failures.join("\n"));
}
