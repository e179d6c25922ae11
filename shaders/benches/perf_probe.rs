//! Quick timing probe for the kernel benchmark's two ratios (not a test of correctness; run
//! with `cargo bench -p anysl-shaders --bench perf_probe`):
//! generic `F32x8` Phong and Checker against the hand-written `wide::f32x8` kernels, and
//! `Dual<f32>` against `f32` on every shader. Runs are interleaved; the median is reported.

use anysl_ad::Dual;
use anysl_core::points::{shade_points, PointSet, ShadeOut};
use anysl_shaders::native::shade_point_set;
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::F32x8;
use std::time::Instant;

type Runner = fn(&Surface, &[Light], &PointSet, &mut ShadeOut<f32>);

/// Median seconds per run of each runner, timed round-robin.
fn time(surface: &Surface, lights: &[Light], set: &PointSet, runners: &[Runner], rounds: usize) -> Vec<f64> {
    let mut out = ShadeOut::<f32>::new(set.len());
    let mut times = vec![Vec::new(); runners.len()];
    for round in 0..=rounds {
        for (k, r) in runners.iter().enumerate() {
            let t = Instant::now();
            r(surface, lights, set, &mut out);
            if round > 0 {
                times[k].push(t.elapsed().as_secs_f64());
            }
        }
    }
    times
        .into_iter()
        .map(|mut v| {
            v.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
            v[v.len() / 2]
        })
        .collect()
}

fn generic_vs_native_and_dual_vs_f32() {
    let lights = table1_lights();
    let set = PointSet::random(32768, 0x5eed_2010);
    let rounds = std::env::var("PROBE_ROUNDS").ok().and_then(|s| s.parse().ok()).unwrap_or(15);
    let only: Vec<String> =
        std::env::var("PROBE_SHADERS").map(|s| s.split(',').map(str::to_string).collect()).unwrap_or_default();
    let want = |n: &str| only.is_empty() || only.iter().any(|o| o == n);
    for name in ["phong", "checker"].into_iter().filter(|n| want(n)) {
        let s = Surface::by_name(name).expect("known");
        let t = time(&s, &lights, &set, &[shade_points::<F32x8, Surface, Light>, shade_point_set], rounds);
        println!(
            "{name:<9} generic-x8 {:7.2} Mpts/s  native-x8 {:7.2} Mpts/s  generic/native time {:.3}",
            set.len() as f64 / t[0] / 1e6,
            set.len() as f64 / t[1] / 1e6,
            t[0] / t[1]
        );
    }
    for name in Surface::NAMES.into_iter().filter(|n| want(n)) {
        let s = Surface::by_name(name).expect("known");
        let t = time(
            &s,
            &lights,
            &set,
            &[shade_points::<f32, Surface, Light>, shade_points::<Dual<f32>, Surface, Light>],
            rounds,
        );
        println!(
            "{name:<9} f32 {:7.2} Mpts/s  dual-f32 {:7.2} Mpts/s  dual/f32 rate {:.3}",
            set.len() as f64 / t[0] / 1e6,
            set.len() as f64 / t[1] / 1e6,
            t[0] / t[1]
        );
    }
}

fn main() {
    generic_vs_native_and_dual_vs_f32();
}
