//! Timing probe for the JIT on the shared workload (`anysl bench workload` runs the full
//! table; this builds without the CLI): each workload `.sl` shader compiled for x8 and x16,
//! against the ahead-of-time generic shaders at the same widths, one thread, round-robin,
//! median and best of `ROUNDS` calls (default 31), and each row's max abs error.
//!
//! `cargo bench -p anysl-jit --bench workload_jit`; `SHADERS=plastic,wood` selects,
//! `OPT=3` compiles at LLVM's `default<O3>`; `DUMP_IR=DIR` writes each variant's optimized LLVM IR
//! to `DIR/<shader>-<variant>.ll`.

use anysl_core::{LightData, ShadingFloat};
use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_shaders::workload::reference::{self, ProbeRun};
use anysl_shaders::workload::{self, WorkloadScene, WorkloadShader};
use anysl_simd::{F32x16, F32x8};

fn main() {
    let env = |k: &str| std::env::var(k).ok();
    let rounds: usize = env("ROUNDS").and_then(|s| s.parse().ok()).unwrap_or(31);
    let opt: u32 = env("OPT").and_then(|s| s.parse().ok()).unwrap_or(JitOptions::new().opt_level);
    let shaders: Vec<String> = env("SHADERS")
        .map(|s| s.split(',').map(str::to_string).collect())
        .unwrap_or_else(|| WorkloadShader::NAMES.iter().map(|s| s.to_string()).collect());
    let scene = WorkloadScene::new();
    let lights: Vec<LightData> = workload::light_data();
    for name in &shaders {
        let sh = WorkloadShader::by_name(name).expect("a workload shader");
        let reference = reference::load_reference(sh.name()).expect("reference");
        let opts = JitOptions { opt_level: opt, ..JitOptions::new() };
        let jit = JitShader::from_source(sh.sl_file_name(), sh.sl_source(), &[], opts.clone()).expect("compiles");
        for v in [Variant::X8, Variant::X16] {
            jit.variant(v).expect("machine code");
        }
        if let Some(dir) = env("DUMP_IR") {
            // The optimized LLVM IR of each variant, for reading the code a row runs.
            let m = anysl_rsl::compile_source(sh.sl_file_name(), sh.sl_source(), &Default::default())
                .expect("compiles")
                .module;
            let values: Vec<_> = m.params.iter().map(|p| p.default.clone()).collect();
            for v in [Variant::X8, Variant::X16] {
                let c = anysl_jit::compile_with(&m, &values, v, &opts, true).expect("machine code");
                let path = format!("{dir}/{name}-{v:?}.ll");
                std::fs::write(&path, c.llvm_ir.as_deref().unwrap_or_default()).expect("writable");
                eprintln!("wrote {path}");
            }
        }
        let (scene, sh, lights, jit) = (&scene, &sh, &lights, &jit);
        fn aot<'a, F: ShadingFloat>(
            label: &'a str,
            s: &'a WorkloadScene,
            sh: &'a WorkloadShader,
            l: &'a [LightData],
        ) -> ProbeRun<'a> {
            (label, Box::new(move |[r, g, b]: &mut [Vec<f32>; 3]| s.shade::<F, LightData>(sh, l, 0, [r, g, b])))
        }
        fn jitted<'a, F: ShadingFloat>(
            label: &'a str,
            s: &'a WorkloadScene,
            j: &'a JitShader,
            l: &'a [LightData],
        ) -> ProbeRun<'a> {
            (
                label,
                Box::new(move |[r, g, b]: &mut [Vec<f32>; 3]| s.shade_surface::<F, _, LightData>(j, l, 0, [r, g, b])),
            )
        }
        let runs = [
            aot::<F32x8>("aot-x8", scene, sh, lights),
            jitted::<F32x8>("jit-x8", scene, jit, lights),
            aot::<F32x16>("aot-x16", scene, sh, lights),
            jitted::<F32x16>("jit-x16", scene, jit, lights),
        ];
        reference::probe_rounds(scene, name, &reference, &runs, rounds);
    }
}
