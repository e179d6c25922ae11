//! Rough timings (ignored by default): `cargo test -p anysl-jit --test perf_probe -- --ignored --nocapture`.

use anysl_core::points::{shade_points, PointSet, ShadeOut};
use anysl_jit::{compile, JitOptions, JitShader, Variant};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::F32x8;
use std::path::PathBuf;
use std::time::Instant;

fn rsl_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"))
}

#[test]
#[ignore]
fn probe() {
    let set = PointSet::random(1 << 15, 1);
    let lights = table1_lights();
    for name in ["plastic", "checker", "brick", "wood", "granite", "parquet", "screen", "starball", "venus", "glass"] {
        let path = rsl_dir().join(format!("{name}.sl"));
        let jit = JitShader::from_file(&path, &[rsl_dir().join("include")], JitOptions::default()).unwrap();
        let t = Instant::now();
        let cs = compile(&jit.module, &jit.values, Variant::X8, &jit.opts).unwrap();
        let ct = t.elapsed().as_secs_f64() * 1e3;
        let _ = jit.variant(Variant::X8);
        let mut out = ShadeOut::new(set.len());
        let aot = Surface::by_name(if name == "plastic" { "phong" } else { name }).unwrap();
        let mut time = |f: &mut dyn FnMut(&mut ShadeOut<f32>)| {
            let mut best = f64::MAX;
            for _ in 0..5 {
                let t = Instant::now();
                f(&mut out);
                best = best.min(t.elapsed().as_secs_f64());
            }
            set.len() as f64 / best
        };
        let j = time(&mut |o| shade_points::<F32x8, _, Light>(&jit, &lights, &set, o));
        let a = time(&mut |o| shade_points::<F32x8, _, Light>(&aot, &lights, &set, o));
        eprintln!(
            "{name:10} compile {ct:6.1} ms {:?} insts {:?}  jit-x8 {j:.3e} aot-x8 {a:.3e} ratio {:.2}",
            cs.stats.times_ms.iter().map(|(s, t)| format!("{s}={t:.1}")).collect::<Vec<_>>(),
            cs.stats.insts.iter().filter(|(s, _)| s.starts_with("llvm")).map(|(_, n)| *n).collect::<Vec<_>>(),
            j / a
        );
    }
}

#[test]
#[ignore]
fn dump_ir() {
    let name = std::env::var("SHADER").unwrap_or_else(|_| "plastic".into());
    let path = rsl_dir().join(format!("{name}.sl"));
    let jit = JitShader::from_file(&path, &[rsl_dir().join("include")], JitOptions::default()).unwrap();
    let cs = anysl_jit::compile_with(&jit.module, &jit.values, Variant::X8, &jit.opts, true).unwrap();
    std::fs::write("/tmp/h6_ir.ll", cs.llvm_ir.unwrap()).unwrap();
}
