//! Criterion bench of the shading kernels: every shader × the main instantiations on one
//! fixed random point set (the same workload as `anysl bench kernels`, smaller).

use anysl_ad::Dual;
use anysl_core::points::{shade_points, PointSet, ShadeOut};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::{F32x16, F32x8};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

macro_rules! bench_instantiations {
    ($group:expr, $name:expr, $surface:expr, $lights:expr, $set:expr, $out:expr, $($label:literal => $ty:ty),+ $(,)?) => {
        $(
            $group.bench_with_input(BenchmarkId::new($label, $name), &(), |b, _| {
                b.iter(|| shade_points::<$ty, Surface, Light>($surface, $lights, $set, $out))
            });
        )+
    };
}

fn kernels(c: &mut Criterion) {
    let lights = table1_lights();
    let set = PointSet::random(4096, 0x5eed_2010);
    let mut out = ShadeOut::<f32>::new(set.len());
    let mut group = c.benchmark_group("kernels");
    group.throughput(Throughput::Elements(set.len() as u64));
    group.sample_size(20);
    for name in Surface::NAMES {
        let surface = Surface::by_name(name).expect("known shader");
        bench_instantiations!(group, name, &surface, &lights, &set, &mut out,
            "f32" => f32, "f32x8" => F32x8, "f32x16" => F32x16, "dual-f32" => Dual<f32>);
    }
    group.finish();
}

criterion_group!(benches, kernels);
criterion_main!(benches);
