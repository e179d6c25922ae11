//! The "native" rows of the kernel benchmark: hand-written `wide::f32x8` Phong and Checker
//! run over the same point set as the generic shaders.

use anysl_core::points::{field, PointSet, ShadeOut};
use anysl_shaders::native::{checker_x8, native_lights, plastic_x8, PointsX8};
use anysl_shaders::{Light, Surface};
use wide::f32x8;

/// A native runner: same signature as the generic instantiations.
pub type NativeRunner = fn(&Surface, &[Light], &PointSet, &mut ShadeOut<f32>);

/// The native kernel for `surface`, if one exists.
pub fn runner(surface: &Surface) -> Option<NativeRunner> {
    match surface {
        Surface::Plastic(_) | Surface::Checker(_) => Some(run as NativeRunner),
        _ => None,
    }
}

#[inline(always)]
fn load8(set: &PointSet, k: usize, i: usize) -> f32x8 {
    let a: [f32; 8] = set.field(k)[i..i + 8].try_into().expect("8 lanes");
    f32x8::from(a)
}

#[inline(always)]
fn load3(set: &PointSet, k: usize, i: usize) -> [f32x8; 3] {
    [load8(set, k, i), load8(set, k + 1, i), load8(set, k + 2, i)]
}

#[inline(never)]
fn run(surface: &Surface, lights: &[Light], set: &PointSet, out: &mut ShadeOut<f32>) {
    let (points, ambient) = native_lights(lights).expect("table-1 lights are point + ambient lights");
    let one = [f32x8::splat(1.0); 3];
    let mut i = 0;
    while i + 8 <= set.len() {
        let x = PointsX8 {
            p: load3(set, field::P, i),
            n: load3(set, field::N, i),
            i: load3(set, field::I, i),
            s: load8(set, field::S, i),
            t: load8(set, field::T, i),
            cs: one,
            os: one,
        };
        let (ci, oi) = match surface {
            Surface::Plastic(p) => plastic_x8(p, &points, ambient, &x),
            Surface::Checker(c) => checker_x8(c, &points, ambient, &x),
            _ => unreachable!("runner() only offers plastic and checker"),
        };
        for (ch, v) in ci.iter().chain(oi.iter()).enumerate() {
            out.channels[ch][i..i + 8].copy_from_slice(&v.to_array());
        }
        i += 8;
    }
}
