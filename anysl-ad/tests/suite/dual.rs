//! `Dual<F>` against central finite differences in f64, for every primitive and for
//! compositions, in `Dual<f64>` and `Dual<f32>`; the singular-point policy; the rest of the
//! `ShadingFloat` surface.
//!
//! Tolerances. The finite difference uses `h = 1e-5·max(|x|, 1e-3)` in f64 at the same
//! point the dual number is evaluated at. Its truncation error is `h²·|f'''|/6` (≤ 1e-8
//! relative on the sampled smooth regions, which stay away from poles and branch points) and
//! its cancellation error `u_64·|f|/h` (≤ 1e-10). A `Dual<f64>` derivative is a few f64
//! roundings off the exact one, so `|d - fd| ≤ 1e-6·(|fd| + 1)` leaves a margin of 100×. A
//! `Dual<f32>` derivative is a chain of a few f32 operations of ≤ 1 ulp each (libm included),
//! i.e. ≤ ~5e-7 relative, so `1e-5·(|fd| + 1)` leaves a margin of 20×.

use crate::common;

use anysl_ad::{Dual, Interval};
use anysl_core::stdlib::{smoothstep, snoise3};
use anysl_core::{ShadingFloat, Vec3};
use common::{Binary, Rng, Unary, UNARY};

const TOL_F64: f64 = 1e-6;
const TOL_F32: f64 = 1e-5;

/// Central difference of `f` at `x` in f64.
fn central(f: impl Fn(f64) -> f64, x: f64) -> f64 {
    let h = 1e-5 * x.abs().max(1e-3);
    (f(x + h) - f(x - h)) / (2.0 * h)
}

/// Inner float of a dual number under test: f32 or f64, with its tolerance.
trait Inner: ShadingFloat {
    const TOL: f64;
    fn from_f64(x: f64) -> Self;
    fn to_f64(self) -> f64;
}
impl Inner for f32 {
    const TOL: f64 = TOL_F32;
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
}
impl Inner for f64 {
    const TOL: f64 = TOL_F64;
    fn from_f64(x: f64) -> Self {
        x
    }
    fn to_f64(self) -> f64 {
        self
    }
}

fn close(d: f64, fd: f64, tol: f64) -> bool {
    (d - fd).abs() <= tol * (fd.abs() + 1.0)
}

/// A point in the smooth region of `p`.
fn smooth_point(p: Unary, rng: &mut Rng) -> f64 {
    let k = rng.range(-6.0, 6.0).round();
    match p {
        Unary::Neg | Unary::Abs => rng.sign() * rng.range(0.1, 10.0),
        Unary::Floor | Unary::Ceil | Unary::Round | Unary::Trunc => k + rng.range(0.1, 0.4) * rng.sign(),
        Unary::Sqrt => rng.log(-2.0, 2.0),
        Unary::Exp | Unary::Exp2 => rng.range(-20.0, 20.0),
        Unary::Ln | Unary::Log2 => rng.log(-2.0, 4.0),
        Unary::Sin | Unary::Cos => rng.range(-20.0, 20.0),
        Unary::Tan => k * core::f64::consts::PI + rng.range(-1.3, 1.3),
        Unary::Asin | Unary::Acos => rng.range(-0.95, 0.95),
        Unary::Atan => rng.range(-50.0, 50.0),
    }
}

fn unary_matches_fd<F: Inner>() {
    let mut rng = Rng::new(0xD0A1);
    for p in UNARY {
        for _ in 0..300 {
            let x = F::from_f64(smooth_point(p, &mut rng)).to_f64();
            let fd = central(|t| p.apply(t), x);
            let dx = p.apply(Dual::seed_x(F::from_f64(x)));
            let dy = p.apply(Dual::seed_y(F::from_f64(x)));
            assert!(close(dx.ddx.to_f64(), fd, F::TOL), "{p:?}'({x}) = {:?}, fd {fd}", dx.ddx);
            assert!(close(dy.ddy.to_f64(), fd, F::TOL), "{p:?} ∂/∂y at {x}");
            assert_eq!(dx.ddy.to_f64(), 0.0, "{p:?}: ∂/∂y of an x seed");
            assert_eq!(dx.val.to_f64(), p.apply(F::from_f64(x)).to_f64(), "{p:?}: value");
        }
    }
}

#[test]
fn unary_primitives_match_finite_differences_f64() {
    unary_matches_fd::<f64>();
}

#[test]
fn unary_primitives_match_finite_differences_f32() {
    unary_matches_fd::<f32>();
}

/// Operands `(a, b)` in the smooth region of `p`.
fn smooth_pair(p: Binary, rng: &mut Rng) -> (f64, f64) {
    match p {
        Binary::Add | Binary::Sub | Binary::Mul | Binary::Div => {
            (rng.sign() * rng.range(0.1, 10.0), rng.sign() * rng.range(0.1, 10.0))
        }
        Binary::Min | Binary::Max => {
            let a = rng.range(-10.0, 10.0);
            (a, a + rng.sign() * rng.range(0.1, 5.0))
        }
        Binary::Pow => (rng.range(0.05, 20.0), rng.range(-4.0, 4.0)),
        Binary::Atan2 => {
            let (r, phi) = (rng.log(-1.0, 1.0), rng.range(-3.0, 3.0));
            (r * phi.sin(), r * phi.cos())
        }
    }
}

fn binary_matches_fd<F: Inner>() {
    let mut rng = Rng::new(0xB1A2);
    for p in common::BINARY {
        for _ in 0..300 {
            let (a, b) = smooth_pair(p, &mut rng);
            let (a, b) = (F::from_f64(a).to_f64(), F::from_f64(b).to_f64());
            let d = p.apply(Dual::seed_x(F::from_f64(a)), Dual::seed_y(F::from_f64(b)));
            let fa = central(|t| p.apply(t, b), a);
            let fb = central(|t| p.apply(a, t), b);
            assert!(close(d.ddx.to_f64(), fa, F::TOL), "{p:?}({a}, {b}) ∂/∂a {:?} vs {fa}", d.ddx);
            assert!(close(d.ddy.to_f64(), fb, F::TOL), "{p:?}({a}, {b}) ∂/∂b {:?} vs {fb}", d.ddy);
        }
    }
    // Negative bases with integer exponents: ∂/∂x = y·x^(y-1); ∂/∂y has no meaning (0).
    for _ in 0..200 {
        let a = F::from_f64(-rng.range(0.1, 5.0)).to_f64();
        let n = rng.range(-4.0, 4.0).round();
        let d = Dual::seed_x(F::from_f64(a)).pow(Dual::seed_y(F::from_f64(n)));
        let fa = central(|t| t.powf(n), a);
        assert!(close(d.ddx.to_f64(), fa, F::TOL), "pow({a}, {n})' = {:?} vs {fa}", d.ddx);
        assert_eq!(d.ddy.to_f64(), 0.0, "pow({a}, {n}) ∂/∂y");
    }
}

#[test]
fn binary_primitives_match_finite_differences_f64() {
    binary_matches_fd::<f64>();
}

#[test]
fn binary_primitives_match_finite_differences_f32() {
    binary_matches_fd::<f32>();
}

fn comp1<F: ShadingFloat>(x: F) -> F {
    (F::c(1.0) + x * x).sqrt() * (F::c(3.0) * x).sin() / (x * F::c(0.25)).exp()
}
fn comp2<F: ShadingFloat>(x: F) -> F {
    let base = x.atan2(F::c(1.0) + x * x) + F::c(2.0);
    base.pow(x.cos()) + (F::c(2.0) + (x * F::c(0.3)).tan()).ln()
}
fn comp3<F: ShadingFloat>(x: F) -> F {
    smoothstep(F::c(-1.0), F::c(1.0), x.sin()) * (F::c(0.5) * x.cos()).asin()
        + (F::c(0.3) * (F::c(2.0) * x).sin()).acos()
        + (x * x + F::c(1.0)).log2().exp2()
        + (x * F::c(0.1)).atan()
        - x.abs().max(F::c(0.5)).min(F::c(3.0))
}
fn comp4<F: ShadingFloat>(x: F) -> F {
    snoise3(Vec3::new(x, F::c(0.3) * x + F::c(0.1), F::c(0.7)))
}
/// Two variables: both partial derivatives are checked.
fn comp2d<F: ShadingFloat>(x: F, y: F) -> F {
    y.atan2(x) * (x * x + y * y).ln() + (x * x + F::c(1.0)).pow(y) - (x / (F::c(2.0) + y.cos()))
}

fn compositions_match<F: Inner>() {
    type Pair<F> = (&'static str, fn(Dual<F>) -> Dual<F>, fn(f64) -> f64);
    let fns: [Pair<F>; 4] =
        [("comp1", comp1, comp1), ("comp2", comp2, comp2), ("comp3", comp3, comp3), ("comp4", comp4, comp4)];
    let mut rng = Rng::new(0xC0);
    for (name, fd_dual, f) in fns {
        for _ in 0..400 {
            let x = F::from_f64(rng.range(-3.0, 3.0)).to_f64();
            // Stay off the kinks of abs/max/min in comp3.
            if [0.0, 0.5, -0.5, 3.0, -3.0].iter().any(|k| (x - k).abs() < 1e-3) {
                continue;
            }
            let d = fd_dual(Dual::seed_x(F::from_f64(x)));
            let fd = central(f, x);
            assert!(close(d.ddx.to_f64(), fd, F::TOL), "{name}'({x}) = {:?} vs {fd}", d.ddx);
        }
    }
    for _ in 0..400 {
        let (x, y) = (F::from_f64(rng.range(0.2, 3.0)).to_f64(), F::from_f64(rng.range(-3.0, 3.0)).to_f64());
        let d = comp2d(Dual::seed_x(F::from_f64(x)), Dual::seed_y(F::from_f64(y)));
        let fx = central(|t| comp2d(t, y), x);
        let fy = central(|t| comp2d(x, t), y);
        assert!(close(d.ddx.to_f64(), fx, F::TOL), "comp2d ∂/∂x at ({x}, {y})");
        assert!(close(d.ddy.to_f64(), fy, F::TOL), "comp2d ∂/∂y at ({x}, {y})");
    }
}

#[test]
fn compositions_match_finite_differences_f64() {
    compositions_match::<f64>();
}

#[test]
fn compositions_match_finite_differences_f32() {
    compositions_match::<f32>();
}

#[test]
fn singular_points_have_the_documented_derivatives() {
    type D = Dual<f32>;
    let x = D::seed_x;
    let c = D::constant;
    let check = |name: &str, d: D, val: f32, ddx: f32, ddy: f32| {
        assert_eq!((d.val, d.ddx, d.ddy), (val, ddx, ddy), "{name}");
    };
    check("sqrt'(0)", x(0.0).sqrt(), 0.0, 0.0, 0.0);
    check("pow'(0, 0.5)", x(0.0).pow(c(0.5)), 0.0, 0.0, 0.0);
    check("pow'(0, 1)", x(0.0).pow(c(1.0)), 0.0, 1.0, 0.0);
    check("pow'(0, 2)", x(0.0).pow(c(2.0)), 0.0, 0.0, 0.0);
    check("pow'(0, 0)", x(0.0).pow(c(0.0)), 1.0, 0.0, 0.0);
    check("∂pow(0, y)/∂y", c(0.0).pow(D::seed_y(2.0)), 0.0, 0.0, 0.0);
    check("asin'(1)", x(1.0).asin(), core::f32::consts::FRAC_PI_2, 0.0, 0.0);
    check("asin'(-1)", x(-1.0).asin(), -core::f32::consts::FRAC_PI_2, 0.0, 0.0);
    check("acos'(1)", x(1.0).acos(), 0.0, 0.0, 0.0);
    check("acos'(-1)", x(-1.0).acos(), core::f32::consts::PI, 0.0, 0.0);
    check("atan2'(0, 0)", D::seed_y(0.0).atan2(x(0.0)), 0.0, 0.0, 0.0);
    let l = x(0.0).ln();
    assert_eq!((l.val, l.ddx, l.ddy), (f32::NEG_INFINITY, 0.0, 0.0), "ln'(0)");
    let l = x(0.0).log2();
    assert_eq!((l.val, l.ddx, l.ddy), (f32::NEG_INFINITY, 0.0, 0.0), "log2'(0)");
    // abs passes the derivative through at 0; floor & co. are flat.
    check("abs'(0)", x(0.0).abs(), 0.0, 1.0, 0.0);
    check("floor'", x(2.5).floor(), 2.0, 0.0, 0.0);
    // min/max ties take self; a NaN operand yields the other (with its derivatives).
    check("min tie", x(1.0).min(D::seed_y(1.0)), 1.0, 1.0, 0.0);
    check("max tie", D::seed_y(1.0).max(x(1.0)), 1.0, 0.0, 1.0);
    check("min NaN", D::new(f32::NAN, 5.0, 5.0).min(x(2.0)), 2.0, 1.0, 0.0);
}

/// Where the value is finite, no derivative is NaN or infinite — over all of f32.
#[test]
fn finite_values_have_finite_derivatives() {
    let mut rng = Rng::new(0xF1);
    let special = [0.0f32, -0.0, 1.0, -1.0, f32::MIN_POSITIVE, 1e-45, -1e-45, f32::MAX, f32::MIN, 0.5, 2.0];
    let mut values: Vec<f32> = special.to_vec();
    while values.len() < 40_000 {
        let v = f32::from_bits(rng.next_u64() as u32);
        if !v.is_nan() {
            values.push(v);
        }
    }
    let finite = |d: Dual<f32>| !d.val.is_finite() || (d.ddx.is_finite() && d.ddy.is_finite());
    for p in UNARY {
        for &v in &values {
            let d = p.apply(Dual::seed_x(v));
            assert!(finite(d), "{p:?}({v:e}) = {d:?}");
        }
    }
    for (i, &a) in values.iter().enumerate() {
        let b = values[(i * 7919 + 13) % values.len()];
        for p in [Binary::Pow, Binary::Atan2] {
            for (a, b) in [(a, b), (a.abs(), b), (a, b.round()), (a % 4.0, b % 8.0)] {
                let d = p.apply(Dual::seed_x(a), Dual::seed_y(b));
                assert!(finite(d), "{p:?}({a:e}, {b:e}) = {d:?}");
            }
        }
    }
}

#[test]
fn derivative_accessors_and_select() {
    type D = Dual<f64>;
    let a = D::new(2.0, 3.0, 4.0);
    assert_eq!(a.dx().val, 3.0);
    assert_eq!(a.dy().val, 4.0);
    assert_eq!((a.dx().ddx, a.dx().ddy), (0.0, 0.0));
    let v = a.value();
    assert_eq!((v.val, v.ddx, v.ddy), (2.0, 0.0, 0.0));
    let w = a.with_derivs(D::c(-1.0), D::new(7.0, 9.0, 9.0));
    assert_eq!((w.val, w.ddx, w.ddy), (2.0, -1.0, 7.0));
    let b = D::new(1.0, -1.0, -2.0);
    // Comparisons look at values only; select takes all three parts from one side.
    assert!(b.lt(a) && a.gt(b) && !a.eq(b) && a.eq(D::constant(2.0)));
    let s = D::select(a.lt(b), a, b);
    assert_eq!((s.val, s.ddx, s.ddy), (1.0, -1.0, -2.0));
    const { assert!(<D as ShadingFloat>::HAS_DERIVS) };
    assert_eq!(a.lane(0), 2.0);
    assert_eq!(D::from_lanes(&[5.0]).val, 5.0);
    assert_eq!(D::from_lanes(&[5.0]).ddx, 0.0);
    assert_eq!(D::c(-2.5).floor_bits(), (-3i32) as u32);
    assert_eq!(D::bits_to_unit(0xFFFF_FF00).val, 1.0 - 1.0 / 16_777_216.0);
    assert_eq!(D::bits_to_float_signed((-7i32) as u32).val, -7.0);
    assert_eq!((a.lower(0), a.upper(0)), (2.0, 2.0));
}

#[test]
fn names_compose() {
    assert_eq!(<Dual<f32> as ShadingFloat>::NAME, "dual-f32");
    assert_eq!(<Dual<f64> as ShadingFloat>::NAME, "dual-f64");
    assert_eq!(<Interval<f32> as ShadingFloat>::NAME, "interval-f32");
    assert_eq!(<Dual<Interval<f64>> as ShadingFloat>::NAME, "dual-interval-f64");
}

/// `Dual<Interval<f32>>`: derivative ranges that contain the point derivatives.
#[test]
fn dual_of_interval_bounds_derivatives() {
    let mut rng = Rng::new(0xAB);
    for _ in 0..200 {
        let lo = rng.range(-3.0, 3.0) as f32;
        let hi = lo + rng.log(-4.0, -0.5) as f32;
        let d = comp1(Dual::seed_x(Interval::new(lo, hi)));
        for i in 0..=50 {
            let x = lo + (hi - lo) * i as f32 / 50.0;
            let p = comp1(Dual::seed_x(x));
            assert!(d.val.lo() <= p.val && p.val <= d.val.hi(), "value at {x}");
            assert!(d.ddx.lo() <= p.ddx && p.ddx <= d.ddx.hi(), "derivative at {x}");
        }
    }
}
