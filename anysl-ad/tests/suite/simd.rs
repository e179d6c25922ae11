//! Composition with anysl-simd: `Dual<F32x8>` computes, lane by lane, what `Dual<f32>`
//! computes, and `Interval<F32x8>` bounds its own inner SIMD functions.
//!
//! Exact operations (`+ - × ÷ √`, rounding, abs, min, max) are bit-identical lane by lane.
//! Transcendentals differ by anysl-simd's kernel error (≤ 2e-7 relative, documented there);
//! a chain-rule factor combines at most three such results, so values and derivatives of
//! single primitives agree to 1e-6 relative, and compositions (≈ 10 operations) to 1e-5
//! of the size of their O(1) terms (a result may cancel to near 0).

use crate::common;

use anysl_ad::{Dual, Interval};
use anysl_core::stdlib::smoothstep;
use anysl_core::ShadingFloat;
use anysl_simd::F32x8;
use common::{Binary, Rng, Unary, BINARY, UNARY};

fn lanes(x: F32x8) -> [f32; 8] {
    x.to_array()
}

/// `|a - b| ≤ rel·(|b| + floor)`: `floor` is the magnitude of the terms a result may have
/// cancelled (1e-6 for single primitives, 1 for compositions of O(1) terms).
fn agree(a: f32, b: f32, rel: f64, floor: f64) -> bool {
    let (a, b) = (f64::from(a), f64::from(b));
    a == b || (a.is_nan() && b.is_nan()) || (a - b).abs() <= rel * (b.abs() + floor)
}

fn check_lanes(name: &str, wide: Dual<F32x8>, scalar: impl Fn(usize) -> Dual<f32>, rel: f64) {
    let floor = if rel > 1e-6 { 1.0 } else { 1e-6 };
    let agree = |a, b| agree(a, b, rel, floor);
    let (v, dx, dy) = (lanes(wide.val), lanes(wide.ddx), lanes(wide.ddy));
    for i in 0..8 {
        let s = scalar(i);
        assert!(
            agree(v[i], s.val) && agree(dx[i], s.ddx) && agree(dy[i], s.ddy),
            "{name} lane {i}: ({}, {}, {}) vs {s:?}",
            v[i],
            dx[i],
            dy[i]
        );
    }
}

fn exact_unary(p: Unary) -> bool {
    matches!(p, Unary::Neg | Unary::Abs | Unary::Floor | Unary::Ceil | Unary::Round | Unary::Trunc | Unary::Sqrt)
}

fn point(rng: &mut Rng, p: Unary) -> f32 {
    (match p {
        Unary::Asin | Unary::Acos => rng.range(-1.0, 1.0),
        Unary::Sqrt | Unary::Ln | Unary::Log2 => rng.log(-3.0, 3.0),
        _ => rng.sign() * rng.log(-3.0, 1.3),
    }) as f32
}

#[test]
fn dual_f32x8_matches_dual_f32_per_lane() {
    assert_eq!(<Dual<F32x8> as ShadingFloat>::NAME, "dual-f32x8");
    let mut rng = Rng::new(0x5EED);
    for p in UNARY {
        for _ in 0..200 {
            let x: [f32; 8] = core::array::from_fn(|_| point(&mut rng, p));
            let wide = p.apply(Dual::seed_x(F32x8::from(x)));
            let rel = if exact_unary(p) { 0.0 } else { 1e-6 };
            check_lanes(&format!("{p:?}"), wide, |i| p.apply(Dual::seed_x(x[i])), rel);
        }
    }
    for p in BINARY {
        for _ in 0..200 {
            let a: [f32; 8] = core::array::from_fn(|_| {
                let v = rng.log(-2.0, 1.0) as f32;
                if p == Binary::Pow {
                    v
                } else {
                    v * rng.sign() as f32
                }
            });
            let b: [f32; 8] = core::array::from_fn(|_| (rng.sign() * rng.log(-2.0, 0.6)) as f32);
            let wide = p.apply(Dual::seed_x(F32x8::from(a)), Dual::seed_y(F32x8::from(b)));
            let rel = if matches!(p, Binary::Pow | Binary::Atan2) { 1e-6 } else { 0.0 };
            check_lanes(&format!("{p:?}"), wide, |i| p.apply(Dual::seed_x(a[i]), Dual::seed_y(b[i])), rel);
        }
    }
}

fn shade<F: ShadingFloat>(x: F, y: F) -> F {
    let r = (x * x + y * y + F::c(0.1)).sqrt();
    smoothstep(F::c(0.2), F::c(1.5), r) * (F::c(3.0) * x).sin() + y.atan2(x) * r.ln()
        - (x * F::c(0.5)).exp().pow(F::c(0.7)) / (F::c(1.0) + y.abs())
}

#[test]
fn dual_f32x8_compositions_match_per_lane() {
    let mut rng = Rng::new(0xC0FFEE);
    for _ in 0..500 {
        let x: [f32; 8] = core::array::from_fn(|_| rng.range(-2.0, 2.0) as f32);
        let y: [f32; 8] = core::array::from_fn(|_| rng.range(-2.0, 2.0) as f32);
        let wide = shade(Dual::seed_x(F32x8::from(x)), Dual::seed_y(F32x8::from(y)));
        check_lanes("shade", wide, |i| shade(Dual::seed_x(x[i]), Dual::seed_y(y[i])), 1e-5);
        // Selects and comparisons act lane-wise on values, derivatives follow.
        let a = Dual::seed_x(F32x8::from(x));
        let b = Dual::seed_y(F32x8::from(y));
        let m = Dual::select(a.lt(b), a, b);
        check_lanes("select", m, |i| Dual::select(x[i] < y[i], Dual::seed_x(x[i]), Dual::seed_y(y[i])), 0.0);
    }
}

/// `Interval<F32x8>`: per lane, the interval contains the SIMD function at sample points.
#[test]
fn interval_f32x8_contains_its_own_function() {
    let mut rng = Rng::new(0x1F32);
    for p in UNARY {
        for _ in 0..200 {
            let lo: [f32; 8] = core::array::from_fn(|_| (rng.sign() * rng.log(-3.0, 2.0)) as f32);
            let hi: [f32; 8] = core::array::from_fn(|i| lo[i] + rng.log(-6.0, 0.7) as f32);
            let r = p.apply(Interval::new(F32x8::from(lo), F32x8::from(hi)));
            let (rlo, rhi) = (lanes(r.lo()), lanes(r.hi()));
            for s in 0..=100 {
                let t = s as f32 / 100.0;
                let x: [f32; 8] = core::array::from_fn(|i| (lo[i] + t * (hi[i] - lo[i])).clamp(lo[i], hi[i]));
                let y = lanes(p.apply(F32x8::from(x)));
                for i in 0..8 {
                    if !y[i].is_nan() {
                        assert!(
                            rlo[i] <= y[i] && y[i] <= rhi[i],
                            "{p:?} lane {i}: [{}, {}] misses f({}) = {}",
                            rlo[i],
                            rhi[i],
                            x[i],
                            y[i]
                        );
                    }
                }
            }
        }
    }
}
