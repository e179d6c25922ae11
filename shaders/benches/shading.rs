//! Shading throughput: every Table 1 surface with f32 and with `F32x8`, and the native SIMD
//! plastic/checker against the generic ones (the paper's "Native" column). Fixed-seed inputs:
//! 1024 points on the unit sphere seen from (0, 0, 3).

use anysl_core::{Exec, Globals, PointContext, ShadingFloat, SurfaceShader, Vec3};
use anysl_shaders::native::{checker_x8, native_lights, plastic_x8, PointsX8};
use anysl_shaders::{table1_lights, Checker, Light, Plastic, Surface};
use anysl_simd::F32x8;
use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use wide::f32x8;

const N: usize = 1024;

/// Fixed-seed points on the front of the unit sphere, with s, t from the position.
fn points() -> Vec<[f32; 5]> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f64 / (1u64 << 24) as f64
    };
    (0..N)
        .map(|_| {
            let z = next();
            let phi = 2.0 * std::f64::consts::PI * next();
            let r = (1.0 - z * z).sqrt();
            let p = [r * phi.cos(), r * phi.sin(), z];
            [p[0] as f32, p[1] as f32, p[2] as f32, (0.5 + 0.5 * p[0]) as f32, (0.5 + 0.5 * p[1]) as f32]
        })
        .collect()
}

/// Globals of `F::LANES` consecutive points.
fn globals<F: ShadingFloat>(pts: &[[f32; 5]]) -> Globals<F> {
    let lane = |k: usize| F::from_lanes(&pts.iter().map(|p| p[k] as f64).collect::<Vec<_>>());
    let mut g = Globals::<F>::unit_square(F::c(0.0), F::c(0.0));
    g.P = Vec3::new(lane(0), lane(1), lane(2));
    g.N = g.P;
    g.Ng = g.P;
    g.E = Vec3::c(0.0, 0.0, 3.0);
    g.I = g.P - g.E;
    g.s = lane(3);
    g.t = lane(4);
    g
}

fn shade_all<F: ShadingFloat, S: SurfaceShader>(s: &S, lights: &[Light], gs: &[Globals<F>]) -> f64 {
    let mut acc = 0.0;
    for g in gs {
        let mut ctx = PointContext::new(*g, lights);
        acc += s.shade(&mut ctx, &mut Exec::new()).Ci.r.lane(0);
    }
    acc
}

fn table1(c: &mut Criterion) {
    let lights = table1_lights();
    let pts = points();
    let g1: Vec<Globals<f32>> = pts.chunks(1).map(globals).collect();
    let g8: Vec<Globals<F32x8>> = pts.chunks(8).map(globals).collect();
    let mut group = c.benchmark_group("table1");
    group.throughput(Throughput::Elements(N as u64));
    for s in Surface::all() {
        group.bench_function(format!("{}/f32", s.name()), |b| b.iter(|| shade_all(black_box(&s), &lights, &g1)));
        group.bench_function(format!("{}/f32x8", s.name()), |b| b.iter(|| shade_all(black_box(&s), &lights, &g8)));
    }
    group.finish();
}

fn native(c: &mut Criterion) {
    let lights = table1_lights();
    let (nl, amb) = native_lights(&lights).expect("table 1 lights are native");
    let pts = points();
    let g8: Vec<Globals<F32x8>> = pts.chunks(8).map(globals).collect();
    let x8: Vec<PointsX8> = pts
        .chunks(8)
        .map(|c| {
            let l = |k: usize| f32x8::from(core::array::from_fn::<f32, 8, _>(|i| c[i][k]));
            let p = [l(0), l(1), l(2)];
            let i = [p[0], p[1], p[2] - f32x8::splat(3.0)];
            PointsX8 { p, n: p, i, s: l(3), t: l(4), cs: [f32x8::ONE; 3], os: [f32x8::ONE; 3] }
        })
        .collect();
    let (plastic, checker) = (Plastic::default(), Checker::default());
    let mut group = c.benchmark_group("native");
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function("plastic/generic-f32x8", |b| b.iter(|| shade_all(black_box(&plastic), &lights, &g8)));
    group.bench_function("plastic/native-f32x8", |b| {
        b.iter(|| x8.iter().map(|x| plastic_x8(black_box(&plastic), &nl, amb, x).0[0].to_array()[0]).sum::<f32>())
    });
    group.bench_function("checker/generic-f32x8", |b| b.iter(|| shade_all(black_box(&checker), &lights, &g8)));
    group.bench_function("checker/native-f32x8", |b| {
        b.iter(|| x8.iter().map(|x| checker_x8(black_box(&checker), &nl, amb, x).0[0].to_array()[0]).sum::<f32>())
    });
    group.finish();
}

criterion_group!(benches, table1, native);
criterion_main!(benches);
