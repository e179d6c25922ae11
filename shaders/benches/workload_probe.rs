//! Timing probe for the shared workload's ahead-of-time rows (`anysl bench workload` runs the
//! full table; this builds in a fraction of the time): every shader × `VARIANTS`
//! (default: all), one thread, round-robin: the median and the best of `ROUNDS` calls
//! (default 31), with each row's max abs error against the reference. On a shared machine the
//! best call is the steadier figure for comparing builds.
//!
//! `cargo bench -p anysl-shaders --bench workload_probe`; `SHADERS=plastic,wood` selects.

use anysl_core::{LightData, ShadingFloat};
use anysl_shaders::workload::{self, reference, WorkloadScene, WorkloadShader};
use anysl_simd::{F32x16, F32x8, Pair};
use std::time::Instant;

type Run = fn(&WorkloadScene, &WorkloadShader, &[LightData], &mut [Vec<f32>; 3]);

fn run<F: ShadingFloat>(s: &WorkloadScene, sh: &WorkloadShader, l: &[LightData], out: &mut [Vec<f32>; 3]) {
    let [r, g, b] = out;
    s.shade::<F, LightData>(sh, l, 0, [r, g, b]);
}

fn main() {
    let env = |k: &str| std::env::var(k).ok();
    let rounds: usize = env("ROUNDS").and_then(|s| s.parse().ok()).unwrap_or(31);
    let variants: Vec<String> = env("VARIANTS")
        .unwrap_or_else(|| "f32x8,f32x16,f32x8x2,f32x16x2".into())
        .split(',')
        .map(str::to_string)
        .collect();
    let shaders: Vec<String> = env("SHADERS")
        .map(|s| s.split(',').map(str::to_string).collect())
        .unwrap_or_else(|| WorkloadShader::NAMES.iter().map(|s| s.to_string()).collect());
    let all: [(&str, Run); 4] = [
        ("f32x8", run::<F32x8>),
        ("f32x16", run::<F32x16>),
        ("f32x8x2", run::<Pair<F32x8>>),
        ("f32x16x2", run::<Pair<F32x16>>),
    ];
    let runs: Vec<(&str, Run)> = all.into_iter().filter(|(n, _)| variants.iter().any(|v| v == n)).collect();
    let scene = WorkloadScene::new();
    let lights = workload::light_data();
    let n = scene.padded_len();
    for name in &shaders {
        let sh = WorkloadShader::by_name(name).expect("a workload shader");
        let reference = reference::load_reference(sh.name()).expect("reference");
        let mut outs: Vec<[Vec<f32>; 3]> = runs.iter().map(|_| [vec![0.0; n], vec![0.0; n], vec![0.0; n]]).collect();
        let mut times = vec![Vec::new(); runs.len()];
        for round in 0..=rounds {
            for (k, (_, f)) in runs.iter().enumerate() {
                let t = Instant::now();
                f(&scene, &sh, &lights, &mut outs[k]);
                if round > 0 {
                    times[k].push(t.elapsed().as_secs_f64());
                }
            }
        }
        for (k, (v, _)) in runs.iter().enumerate() {
            let mut t = std::mem::take(&mut times[k]);
            t.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
            let err = reference::image_error(&scene.to_image(&outs[k]), &reference);
            let mpts = |secs: f64| scene.n_hit() as f64 / secs / 1e6;
            println!(
                "{name:<8} {v:<8} {:8.2} Mpts/s  best {:8.2}  max_abs_err {:.3e}",
                mpts(t[t.len() / 2]),
                mpts(t[0]),
                err.max_abs_err
            );
        }
    }
}
