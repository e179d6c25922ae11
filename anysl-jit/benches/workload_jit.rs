//! Timing probe for the JIT on the shared workload (`anysl bench workload` runs the full
//! table; this builds without the CLI): each workload `.sl` shader compiled for x8 and x16,
//! against the ahead-of-time generic shaders at the same widths, one thread, round-robin,
//! median and best of `ROUNDS` calls (default 31), and each row's max abs error.
//!
//! `cargo bench -p anysl-jit --bench workload_jit`; `SHADERS=plastic,wood` selects,
//! `ROWS=aot-x8,jit-x8` selects rows, `OPT=3` compiles at LLVM's `default<O3>` (`POINTS_OPT=2` the points entries at level 2; 3 by default), `INLINE_NOISE=1` emits the noise as IR in every variant, `INLINE_NOISE=0` in none (unset: the variant's default, `JitOptions::inline_noise`); `SPECIALIZE=0` reads the parameters at run time (`JitOptions::specialize`), as the ahead-of-time shaders do; `DUMP_IR=DIR` writes each variant's optimized LLVM IR
//! to `DIR/<shader>-<variant>.ll`.
//!
//! `COUNT_OPS=1` also compiles each shader with `JitOptions::count_ops` and shades the same
//! inputs once per JIT row, untimed, printing the operations the optimized code executed
//! (`anysl_jit::opcount`): vector floating-point operations per hit point and per packet
//! (one packet = the variant's native lanes, 8 or 16; the padding points are shaded too and
//! counted, so per hit point is the total over 183 020), vector integer/mask operations,
//! scalar float operations and calls into Rust per hit point.

use anysl_core::LightData;
use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_shaders::workload::reference::{self, ProbeRun};
use anysl_shaders::workload::{self, WorkloadScene, WorkloadShader};
use anysl_simd::{F32x16, F32x8, Pair};

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
        let inline_noise = env("INLINE_NOISE").map(|s| s == "1");
        let points_opt: u32 =
            env("POINTS_OPT").and_then(|s| s.parse().ok()).unwrap_or(JitOptions::new().points_opt_level);
        let specialize = env("SPECIALIZE").is_none_or(|s| s != "0");
        let opts =
            JitOptions { opt_level: opt, inline_noise, points_opt_level: points_opt, specialize, ..JitOptions::new() };
        let jit = JitShader::from_source(sh.sl_file_name(), sh.sl_source(), &[], opts).expect("compiles");
        const VARIANTS: [Variant; 4] = [Variant::X8, Variant::X16, Variant::X8x4, Variant::X16x2];
        for v in VARIANTS {
            jit.variant(v).expect("machine code");
        }
        if let Some(dir) = env("DUMP_IR") {
            // The optimized LLVM IR of each variant, for reading the code a row runs.
            for v in VARIANTS {
                let c = anysl_jit::compile_with(&jit.module, &jit.values, v, &jit.opts, true).expect("machine code");
                let path = format!("{dir}/{name}-{v:?}.ll");
                std::fs::write(&path, c.llvm_ir.as_deref().unwrap_or_default()).expect("writable");
                eprintln!("wrote {path}");
            }
        }
        let rows = env("ROWS");
        let selected = |label: &str| rows.as_deref().is_none_or(|r| r.split(',').any(|x| x == label));
        let runs: Vec<ProbeRun<'_>> =
            probe_runs(&scene, &sh, &lights, &jit).into_iter().filter(|(label, _)| selected(label)).collect();
        reference::probe_rounds(&scene, name, &reference, &runs, rounds);
        if env("COUNT_OPS").is_some_and(|s| s == "1") {
            let counting = JitShader::from_source(
                sh.sl_file_name(),
                sh.sl_source(),
                &[],
                JitOptions { count_ops: true, ..jit.opts.clone() },
            )
            .expect("compiles");
            count_ops(&scene, name, &reference, &probe_runs(&scene, &sh, &lights, &counting), &counting, &selected);
        }
    }
}

type P8x2 = Pair<F32x8>;
type P8x4 = Pair<Pair<F32x8>>;
type P16x2 = Pair<F32x16>;

/// The JIT rows' variants: the code whose operations a row's run counts.
const JIT_ROWS: [(&str, Variant); 8] = [
    ("jit-x8", Variant::X8),
    ("jit-x16", Variant::X16),
    ("jit-x8x4", Variant::X8x4),
    ("jit-x16x2", Variant::X16x2),
    ("jitp-x8", Variant::X8),
    ("jitp-x16", Variant::X16),
    ("jitp-x8x4", Variant::X8x4),
    ("jitp-x16x2", Variant::X16x2),
];

/// Every row: the ahead-of-time shader `sh` and the JIT-compiled `jit` at each packet shape.
fn probe_runs<'a>(
    sc: &'a WorkloadScene,
    sh: &'a WorkloadShader,
    l: &'a [LightData],
    jit: &'a JitShader,
) -> [ProbeRun<'a>; 13] {
    [
        ("aot-x8", Box::new(|[r, g, b]: &mut _| sc.shade::<F32x8, LightData>(sh, l, 0, [r, g, b]))),
        ("jit-x8", Box::new(|[r, g, b]: &mut _| sc.shade_surface::<F32x8, _, LightData>(jit, l, 0, [r, g, b]))),
        ("aot-x16", Box::new(|[r, g, b]: &mut _| sc.shade::<F32x16, LightData>(sh, l, 0, [r, g, b]))),
        ("jit-x16", Box::new(|[r, g, b]: &mut _| sc.shade_surface::<F32x16, _, LightData>(jit, l, 0, [r, g, b]))),
        ("aot-x8x2", Box::new(|[r, g, b]: &mut _| sc.shade::<P8x2, LightData>(sh, l, 0, [r, g, b]))),
        ("aot-x8x4", Box::new(|[r, g, b]: &mut _| sc.shade::<P8x4, LightData>(sh, l, 0, [r, g, b]))),
        ("jit-x8x4", Box::new(|[r, g, b]: &mut _| sc.shade_surface::<P8x4, _, LightData>(jit, l, 0, [r, g, b]))),
        ("aot-x16x2", Box::new(|[r, g, b]: &mut _| sc.shade::<P16x2, LightData>(sh, l, 0, [r, g, b]))),
        ("jit-x16x2", Box::new(|[r, g, b]: &mut _| sc.shade_surface::<P16x2, _, LightData>(jit, l, 0, [r, g, b]))),
        ("jitp-x8", Box::new(|out: &mut _| points::<F32x8>(sc, jit, l, out))),
        ("jitp-x16", Box::new(|out: &mut _| points::<F32x16>(sc, jit, l, out))),
        ("jitp-x8x4", Box::new(|out: &mut _| points::<P8x4>(sc, jit, l, out))),
        ("jitp-x16x2", Box::new(|out: &mut _| points::<P16x2>(sc, jit, l, out))),
    ]
}

/// The points entry (`JitShader::shade_points`): the loop over the packets compiled with the
/// shader.
fn points<F: anysl_core::ShadingFloat>(
    sc: &WorkloadScene,
    jit: &JitShader,
    l: &[LightData],
    [r, g, b]: &mut [Vec<f32>; 3],
) {
    use anysl_jit::rsl::ir::Global;
    let n = r.len();
    let mut ctx = anysl_core::PointContext::new(sc.globals::<F>(0), l);
    let [p, nn, i] = sc.varying_f32(0, n);
    let varying: [(Global, &[&[f32]]); 4] = [(Global::P, &p), (Global::N, &nn), (Global::Ng, &nn), (Global::I, &i)];
    assert!(jit
        .shade_points::<F, _>(&mut ctx, &varying, &mut [r.as_mut_slice(), g.as_mut_slice(), b.as_mut_slice()])
        .expect("points entry"));
}

/// One untimed call of each selected JIT row of `runs` (compiled with `count_ops`), the
/// operations it executed printed per hit point and per packet; the image is checked against
/// the reference as the timed rows' are (counting must not change what is computed).
fn count_ops(
    sc: &WorkloadScene,
    shader: &str,
    reference: &[f32],
    runs: &[ProbeRun<'_>],
    jit: &JitShader,
    selected: &dyn Fn(&str) -> bool,
) {
    let n = sc.padded_len();
    for (label, f) in runs {
        let Some(&(_, v)) = JIT_ROWS.iter().find(|(l, _)| l == label).filter(|(l, _)| selected(l)) else {
            continue;
        };
        let mut out = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        f(&mut out); // compiles the variant (and the points entry)
        jit.reset_op_counts();
        f(&mut out);
        let c = jit.op_counts(v).expect("compiled with count_ops");
        let err = reference::image_error(&sc.to_image(&out), reference).max_abs_err;
        let [vec, vint, scalar, calls] = c.per(sc.n_hit() as u64);
        let packets = (n / v.native_lanes() as usize) as u64;
        println!(
            "{shader:<8} {label:<10} ops per hit point: vector {vec:8.2} vector-int {vint:8.2} scalar {scalar:8.2} \
             calls {calls:6.3}; vector per {}-lane packet {:8.1}; max_abs_err {err:.3e}",
            v.native_lanes(),
            c.per(packets)[0],
        );
    }
}
