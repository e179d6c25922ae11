//! Every shader in shaders/rsl: JIT variants against the interpreter at the same float type.

use anysl_ad::Dual;
use anysl_core::points::{shade_points, PointSet, ShadeOut};
use anysl_core::ShadingFloat;
use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_shaders::{table1_lights, Light};
use anysl_simd::F32x8;
use std::path::PathBuf;

fn rsl_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"))
}

fn max_diff(a: &ShadeOut<f32>, b: &ShadeOut<f32>) -> f32 {
    let mut m = 0.0f32;
    for c in 0..6 {
        for (x, y) in a.channels[c].iter().zip(&b.channels[c]) {
            let d = (x - y).abs();
            if d.is_nan() {
                return f32::INFINITY;
            }
            m = m.max(d);
        }
    }
    m
}

fn check<F: ShadingFloat>(name: &str, jit: &JitShader, set: &PointSet) -> f32 {
    let lights = table1_lights();
    let mut a = ShadeOut::new(set.len());
    let mut b = ShadeOut::new(set.len());
    shade_points::<F, JitShader, Light>(jit, &lights, set, &mut a);
    shade_points::<F, _, Light>(jit.interp(), &lights, set, &mut b);
    let d = max_diff(&a, &b);
    eprintln!("{name:12} {:10} max diff {d:e}", F::NAME);
    d
}

#[test]
fn shaders_match_interpreter() {
    let set = PointSet::random(256, 7);
    for name in ["plastic", "checker", "brick", "wood", "granite", "parquet", "screen", "starball", "venus", "glass"] {
        let path = rsl_dir().join(format!("{name}.sl"));
        let jit = JitShader::from_file(&path, &[rsl_dir().join("include")], JitOptions::default()).unwrap();
        for v in [Variant::F32, Variant::X8, Variant::DualF32] {
            if let Err(e) = jit.variant(v) {
                panic!("{name} {v:?}: {e}");
            }
        }
        assert!(check::<f32>(name, &jit, &set) < 1e-4, "{name} f32");
        assert!(check::<F32x8>(name, &jit, &set) < 1e-4, "{name} x8");
        assert!(check::<Dual<f32>>(name, &jit, &set) < 1e-4, "{name} dual");
    }
}

/// The inline-IR noise (`JitOptions::inline_noise`) computes what the library noise computes.
#[test]
fn inline_noise_matches_library_noise() {
    let set = PointSet::random(256, 11);
    let lights = table1_lights();
    for name in ["wood", "granite", "venus", "parquet"] {
        let path = rsl_dir().join(format!("{name}.sl"));
        let inc = [rsl_dir().join("include")];
        let lib = JitShader::from_file(&path, &inc, JitOptions::default()).unwrap();
        let inline =
            JitShader::from_file(&path, &inc, JitOptions { inline_noise: true, ..JitOptions::default() }).unwrap();
        let run = |j: &JitShader, dual: bool, wide: bool| {
            let mut o = ShadeOut::new(set.len());
            match (dual, wide) {
                (true, _) => shade_points::<Dual<f32>, JitShader, Light>(j, &lights, &set, &mut o),
                (false, true) => shade_points::<F32x8, JitShader, Light>(j, &lights, &set, &mut o),
                (false, false) => shade_points::<f32, JitShader, Light>(j, &lights, &set, &mut o),
            }
            o
        };
        for (dual, wide) in [(false, false), (false, true), (true, false)] {
            let d = max_diff(&run(&lib, dual, wide), &run(&inline, dual, wide));
            assert!(d <= 1e-6, "{name} dual={dual} wide={wide}: inline noise differs by {d:e}");
        }
    }
}
