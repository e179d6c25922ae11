//! Quick timing probe for the kernel benchmark's two ratios (not a test of correctness; run
//! with `cargo bench -p anysl-shaders --bench perf_probe`):
//! generic `F32x8` Phong and Checker against the hand-written `wide::f32x8` kernels, and
//! `Dual<f32>` against `f32` on every shader. Runs are interleaved; the median is reported.

use anysl_ad::Dual;
use anysl_core::points::{field, shade_points, PointSet, ShadeOut};
use anysl_shaders::native::{checker_x8, native_lights, plastic_x8, PointsX8};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::F32x8;
use std::time::Instant;
use wide::f32x8;

type Runner = fn(&Surface, &[Light], &PointSet, &mut ShadeOut<f32>);

#[inline(always)]
fn load8(set: &PointSet, k: usize, i: usize) -> f32x8 {
    let a: [f32; 8] = set.field(k)[i..i + 8].try_into().expect("8 lanes");
    f32x8::from(a)
}

/// The native kernels over a point set.
#[inline(never)]
fn native(surface: &Surface, lights: &[Light], set: &PointSet, out: &mut ShadeOut<f32>) {
    let (points, ambient) = native_lights(lights).expect("point and ambient lights");
    let one = [f32x8::splat(1.0); 3];
    let l3 = |k, i| [load8(set, k, i), load8(set, k + 1, i), load8(set, k + 2, i)];
    let mut i = 0;
    while i + 8 <= set.len() {
        let x = PointsX8 {
            p: l3(field::P, i),
            n: l3(field::N, i),
            i: l3(field::I, i),
            s: load8(set, field::S, i),
            t: load8(set, field::T, i),
            cs: one,
            os: one,
        };
        let (ci, oi) = match surface {
            Surface::Plastic(p) => plastic_x8(p, &points, ambient, &x),
            Surface::Checker(c) => checker_x8(c, &points, ambient, &x),
            _ => unreachable!("native kernels exist for plastic and checker"),
        };
        for (ch, v) in ci.iter().chain(oi.iter()).enumerate() {
            out.channels[ch][i..i + 8].copy_from_slice(&v.to_array());
        }
        i += 8;
    }
}

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
        let t = time(&s, &lights, &set, &[shade_points::<F32x8, Surface, Light>, native], rounds);
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
