//! `Interval<f32>` containment: for every primitive, random boxes (straddling 0, around
//! poles, extrema and domain edges, huge and tiny magnitudes, unbounded) with ≥ 100 point
//! samples each; the result must contain the inner f32 function *and* the f64 function at
//! every sample where they are not NaN. Plus tightness checks, constants and the NaN policy.

use crate::common;

use anysl_ad::Interval;
use anysl_core::{Mask, ShadingFloat};
use common::{Binary, Rng, Unary, BINARY, UNARY};
use core::f64::consts::{FRAC_PI_2, PI};

type I = Interval<f32>;

const BOXES: usize = 1500;
const SAMPLES: usize = 100;

/// Floats as monotone integers (±0 both map to 0), for sampling across magnitudes.
fn ordered(x: f32) -> i64 {
    let b = x.to_bits();
    if b >> 31 == 1 {
        -i64::from(b & 0x7FFF_FFFF)
    } else {
        i64::from(b)
    }
}
fn from_ordered(v: i64) -> f32 {
    if v >= 0 {
        f32::from_bits(v as u32)
    } else {
        f32::from_bits((-v) as u32 | 0x8000_0000)
    }
}

/// Points the primitive finds interesting (poles, extrema, domain edges, overflow limits).
fn specials(p: &str) -> Vec<f64> {
    let mut v = vec![0.0, 1.0, -1.0, 0.5, -0.5, 2.0, -2.0];
    match p {
        "Sin" | "Cos" | "Tan" => {
            for k in -40..=40 {
                v.push(f64::from(k) * FRAC_PI_2);
            }
            for k in [1e3, 1e5, 3.3e6, 1e9, 7e14] {
                v.push(k * FRAC_PI_2);
            }
        }
        "Exp" | "Exp2" => v.extend([88.7, 89.0, -87.3, -103.9, 128.0, -126.0, -149.0, -150.0]),
        "Floor" | "Ceil" | "Round" | "Trunc" => v.extend((-10..=10).map(|k| f64::from(k) + 0.5)),
        "Div" => v.extend([1e-40, -1e-40]),
        _ => {}
    }
    v
}

/// A random box `[lo, hi]` (never NaN).
fn gen_box(rng: &mut Rng, sp: &[f64]) -> (f32, f32) {
    loop {
        let (c, w) = match rng.below(9) {
            0 => (rng.range(-10.0, 10.0), rng.log(-7.0, 1.0)),
            1 => {
                let c = rng.sign() * rng.log(-45.0, 38.5);
                (c, c.abs() * rng.log(-8.0, 0.5))
            }
            2 => {
                let (a, b) = (rng.log(-45.0, 5.0), rng.log(-45.0, 5.0));
                ((b - a) / 2.0, a + b)
            }
            3 | 4 => {
                let s = sp[rng.below(sp.len() as u64) as usize];
                let scale = s.abs().max(1.0);
                let off = if rng.below(4) == 0 { 0.0 } else { rng.sign() * rng.log(-8.0, -1.0) * scale };
                (s + off, rng.log(-9.0, 0.0) * scale)
            }
            5 => {
                // A point, somewhere.
                let c = if rng.below(2) == 0 { rng.range(-10.0, 10.0) } else { rng.sign() * rng.log(-45.0, 38.5) };
                (c, 0.0)
            }
            6 => {
                let (a, b) = (f32::from_bits(rng.next_u64() as u32), f32::from_bits(rng.next_u64() as u32));
                if a.is_nan() || b.is_nan() {
                    continue;
                }
                return (a.min(b), a.max(b));
            }
            7 => {
                let x = (rng.sign() * rng.log(-3.0, 6.0)) as f32;
                return if rng.below(2) == 0 { (x, f32::INFINITY) } else { (f32::NEG_INFINITY, x) };
            }
            _ => {
                let m = rng.log(0.0, 38.0);
                (0.0, 2.0 * m)
            }
        };
        let (lo, hi) = ((c - w / 2.0) as f32, (c + w / 2.0) as f32);
        if !lo.is_nan() && !hi.is_nan() {
            return (lo.min(hi), lo.max(hi));
        }
    }
}

/// `n` points of `[lo, hi]`: the endpoints and their neighbours, special points inside,
/// then uniform samples, half linear and half across magnitudes.
fn gen_samples(rng: &mut Rng, lo: f32, hi: f32, sp: &[f64], n: usize) -> Vec<f32> {
    let mut out = vec![lo, hi];
    let (olo, ohi) = (ordered(lo), ordered(hi));
    for v in [olo + 1, ohi - 1] {
        if olo <= v && v <= ohi {
            out.push(from_ordered(v));
        }
    }
    for &s in sp {
        let s = s as f32;
        for v in [ordered(s) - 1, ordered(s), ordered(s) + 1] {
            if olo <= v && v <= ohi && out.len() < n / 2 {
                out.push(from_ordered(v));
            }
        }
    }
    while out.len() < n {
        let x = if rng.below(2) == 0 && lo.is_finite() && hi.is_finite() {
            (f64::from(lo) + rng.unit() * (f64::from(hi) - f64::from(lo))) as f32
        } else {
            from_ordered(olo + (rng.unit() * (ohi - olo) as f64) as i64)
        };
        out.push(x.clamp(lo, hi));
    }
    out
}

fn inside(r: I, y: f64) -> bool {
    f64::from(r.lo()) <= y && y <= f64::from(r.hi())
}

fn well_formed(r: I) -> bool {
    !r.lo().is_nan() && !r.hi().is_nan() && r.lo() <= r.hi()
}

#[test]
fn unary_primitives_contain_every_sample() {
    let mut rng = Rng::new(0x1A7E);
    for p in UNARY {
        let sp = specials(&format!("{p:?}"));
        let mut misses = Vec::new();
        let mut checked = 0usize;
        for _ in 0..BOXES {
            let (lo, hi) = gen_box(&mut rng, &sp);
            let r = p.apply(I::new(lo, hi));
            assert!(well_formed(r), "{p:?}[{lo:e}, {hi:e}] = {r:?}");
            for x in gen_samples(&mut rng, lo, hi, &sp, SAMPLES) {
                for y in [f64::from(p.apply(x)), p.apply(f64::from(x))] {
                    if !y.is_nan() {
                        checked += 1;
                        if !inside(r, y) {
                            misses.push(format!(
                                "{p:?}[{lo:e}, {hi:e}] = [{:e}, {:e}] misses f({x:e}) = {y:e}",
                                r.lo(),
                                r.hi()
                            ));
                        }
                    }
                }
            }
        }
        assert!(misses.is_empty(), "{} misses, e.g.\n{}", misses.len(), misses[..misses.len().min(10)].join("\n"));
        assert!(checked > BOXES * SAMPLES / 4, "{p:?}: only {checked} non-NaN samples");
    }
}

#[test]
fn binary_primitives_contain_every_sample() {
    let mut rng = Rng::new(0xB0C5);
    for p in BINARY {
        let name = format!("{p:?}");
        let (spa, spb) = match p {
            Binary::Pow => (vec![0.0, 1.0, -1.0, -2.0, 0.5, -0.5], vec![0.0, 1.0, 2.0, 3.0, -1.0, -2.0, 0.5, -0.5]),
            _ => (specials(&name), specials(&name)),
        };
        let mut misses = Vec::new();
        let mut checked = 0usize;
        for i in 0..BOXES {
            let (alo, ahi) = gen_box(&mut rng, &spa);
            let (blo, bhi) = if p == Binary::Pow && i % 3 == 0 {
                // Integer exponents (points or short runs), for negative bases.
                let n = rng.range(-6.0, 6.0).round() as f32;
                (n, n + rng.below(3) as f32)
            } else {
                gen_box(&mut rng, &spb)
            };
            let r = p.apply(I::new(alo, ahi), I::new(blo, bhi));
            assert!(well_formed(r), "{p:?}([{alo:e}, {ahi:e}], [{blo:e}, {bhi:e}]) = {r:?}");
            let xs = gen_samples(&mut rng, alo, ahi, &spa, 10);
            let ys = gen_samples(&mut rng, blo, bhi, &spb, 10);
            for &x in &xs {
                for &y in &ys {
                    for z in [f64::from(p.apply(x, y)), p.apply(f64::from(x), f64::from(y))] {
                        if !z.is_nan() {
                            checked += 1;
                            if !inside(r, z) {
                                misses.push(format!(
                                    "{p:?}([{alo:e}, {ahi:e}], [{blo:e}, {bhi:e}]) = [{:e}, {:e}] misses f({x:e}, {y:e}) = {z:e}",
                                    r.lo(),
                                    r.hi()
                                ));
                            }
                        }
                    }
                }
            }
        }
        assert!(misses.is_empty(), "{} misses, e.g.\n{}", misses.len(), misses[..misses.len().min(10)].join("\n"));
        assert!(checked > BOXES * 100 / 4, "{p:?}: only {checked} non-NaN samples");
    }
}

/// Results are not just conservative but tight: each expected range `[a, b]` must hold
/// `[lo, hi]` within the rounding margin (16 f32 epsilons relative, plus 1e-6 absolute).
#[test]
fn results_are_tight() {
    let inf = f64::INFINITY;
    let u = |p: Unary, lo: f32, hi: f32| p.apply(I::new(lo, hi));
    let b = |p: Binary, a: (f32, f32), c: (f32, f32)| p.apply(I::new(a.0, a.1), I::new(c.0, c.1));
    let cases: Vec<(&str, I, f64, f64)> = vec![
        ("sin [0, 3]", u(Unary::Sin, 0.0, 3.0), 0.0, 1.0),
        ("sin [0, 3.1]", u(Unary::Sin, 0.0, 3.1), 0.0, 1.0),
        ("sin [-0.5, 0.5]", u(Unary::Sin, -0.5, 0.5), -(0.5f64.sin()), 0.5f64.sin()),
        ("sin [1, 10]", u(Unary::Sin, 1.0, 10.0), -1.0, 1.0),
        ("sin at 1e7", u(Unary::Sin, 1e7, 1e7), f64::from(1e7f32.sin()), f64::from(1e7f32.sin())),
        ("cos [-1, 1]", u(Unary::Cos, -1.0, 1.0), 1f64.cos(), 1.0),
        ("cos [2, 4]", u(Unary::Cos, 2.0, 4.0), -1.0, 2f64.cos().max(4f64.cos())),
        ("tan [-1, 1]", u(Unary::Tan, -1.0, 1.0), -(1f64.tan()), 1f64.tan()),
        ("tan [1, 2]", u(Unary::Tan, 1.0, 2.0), -inf, inf),
        ("sqrt [-1, 4]", u(Unary::Sqrt, -1.0, 4.0), 0.0, 2.0),
        ("sqrt [-2, -1]", u(Unary::Sqrt, -2.0, -1.0), -inf, inf),
        ("ln [-1, e]", u(Unary::Ln, -1.0, core::f32::consts::E), -inf, 1.0),
        ("log2 [0.25, 8]", u(Unary::Log2, 0.25, 8.0), -2.0, 3.0),
        ("exp [0, 1]", u(Unary::Exp, 0.0, 1.0), 1.0, core::f64::consts::E),
        ("exp2 [-1, 3]", u(Unary::Exp2, -1.0, 3.0), 0.5, 8.0),
        ("asin [-2, 0.5]", u(Unary::Asin, -2.0, 0.5), -FRAC_PI_2, 0.5f64.asin()),
        ("acos [0, 2]", u(Unary::Acos, 0.0, 2.0), 0.0, FRAC_PI_2),
        ("atan [-inf, 1]", u(Unary::Atan, f32::NEG_INFINITY, 1.0), -FRAC_PI_2, 1f64.atan()),
        ("abs [-3, 2]", u(Unary::Abs, -3.0, 2.0), 0.0, 3.0),
        ("floor [-1.5, 2.5]", u(Unary::Floor, -1.5, 2.5), -2.0, 2.0),
        ("round [-1.5, 2.5]", u(Unary::Round, -1.5, 2.5), -2.0, 3.0),
        ("mul", b(Binary::Mul, (-2.0, 3.0), (-5.0, 4.0)), -15.0, 12.0),
        ("mul 0·∞", b(Binary::Mul, (0.0, 1.0), (1.0, f32::INFINITY)), 0.0, inf),
        ("div", b(Binary::Div, (1.0, 2.0), (4.0, 8.0)), 0.125, 0.5),
        ("div by 0", b(Binary::Div, (1.0, 2.0), (-1.0, 1.0)), -inf, inf),
        ("add exact", b(Binary::Add, (1.0, 2.0), (3.0, 4.0)), 4.0, 6.0),
        ("sub exact", b(Binary::Sub, (1.0, 2.0), (3.0, 4.0)), -3.0, -1.0),
        ("min", b(Binary::Min, (1.0, 5.0), (2.0, 3.0)), 1.0, 3.0),
        ("pow", b(Binary::Pow, (2.0, 3.0), (2.0, 3.0)), 4.0, 27.0),
        ("pow 0 base", b(Binary::Pow, (0.0, 4.0), (0.5, 0.5)), 0.0, 2.0),
        ("pow neg odd", b(Binary::Pow, (-3.0, -2.0), (3.0, 3.0)), -27.0, -8.0),
        ("pow neg even", b(Binary::Pow, (-3.0, -2.0), (2.0, 2.0)), 4.0, 9.0),
        ("pow neg run", b(Binary::Pow, (-2.0, -2.0), (1.5, 3.5)), -8.0, 8.0),
        ("pow neg none", b(Binary::Pow, (-2.0, -1.0), (0.2, 0.8)), -inf, inf),
        ("atan2 x>0", b(Binary::Atan2, (-1.0, 1.0), (1.0, 2.0)), -FRAC_PI_2 / 2.0, FRAC_PI_2 / 2.0),
        ("atan2 y>0", b(Binary::Atan2, (1.0, 2.0), (-1.0, 1.0)), 1f64.atan2(1.0), 1f64.atan2(-1.0)),
        ("atan2 cut", b(Binary::Atan2, (-1.0, 1.0), (-2.0, -1.0)), -PI, PI),
    ];
    for (name, r, a, bnd) in cases {
        let slack = |v: f64| 1e-6 + 16.0 * f64::from(f32::EPSILON) * v.abs();
        let (lo, hi) = (f64::from(r.lo()), f64::from(r.hi()));
        let ok_lo = if a.is_infinite() { lo == a } else { lo <= a && lo >= a - slack(a) };
        let ok_hi = if bnd.is_infinite() { hi == bnd } else { hi >= bnd && hi <= bnd + slack(bnd) };
        assert!(ok_lo && ok_hi, "{name}: [{lo}, {hi}] vs expected [{a}, {bnd}]");
    }
    // Exact sums stay exact; inexact ones move one ulp outward, on the side of the error (two
    // just below a power of two, where the spacing halves).
    let s = I::point(1.0) + I::point(2.0);
    assert_eq!((s.lo(), s.hi()), (3.0, 3.0));
    let s = I::point(1.0) + I::point(1e-8);
    assert_eq!((s.lo(), s.hi()), (1.0, 1.0 + f32::EPSILON));
    let s = I::point(1.0) - I::point(1e-8);
    assert!(s.hi() == 1.0 && s.lo() < 1.0 && s.lo() >= 1.0 - f32::EPSILON);
    let s = I::point(3.0) - I::point(1e-7);
    let ulp = 2.0 * f32::EPSILON;
    assert!(s.hi() == 3.0 && s.lo() <= 3.0 - ulp && s.lo() >= 3.0 - 2.0 * ulp, "{s:?}");
}

#[test]
fn constants_contain_their_value() {
    // Representable: a point.
    let c = I::c(0.25);
    assert_eq!((c.lo(), c.hi()), (0.25, 0.25));
    // Not representable: neighbours around it, tight.
    for v in [0.1, -0.1, PI, 1e-40, 3e38, 1e39, -1e39, 1.0 / 3.0] {
        let c = I::c(v);
        assert!(f64::from(c.lo()) <= v && v <= f64::from(c.hi()), "c({v}) = {c:?}");
        assert!(c.lo() < c.hi());
        if v.abs() < 1e38 && v.abs() > 1e-30 {
            assert!(f64::from(c.hi()) - f64::from(c.lo()) <= 4.0 * f64::from(f32::EPSILON) * v.abs());
        }
    }
    let l = I::from_lanes(&[0.1]);
    assert!(f64::from(l.lo()) <= 0.1 && 0.1 <= f64::from(l.hi()));
    let l = I::from_lanes(&[0.5]);
    assert_eq!((l.lo(), l.hi()), (0.5, 0.5));
    assert_eq!(I::new(1.0, 3.0).lane(0), 2.0);
    assert_eq!((I::new(1.0, 3.0).lower(0), I::new(1.0, 3.0).upper(0)), (1.0, 3.0));
    assert_eq!(I::entire().lane(0), 0.0);
}

#[test]
fn nan_policy() {
    for r in [I::new(f32::NAN, 1.0), I::point(f32::NAN), I::c(f64::NAN), I::from_lanes(&[f64::NAN])] {
        assert_eq!((r.lo(), r.hi()), (f32::NEG_INFINITY, f32::INFINITY));
        assert!(r.is_nan().any() && !r.is_nan().all());
    }
    // ∞ - ∞ as bounds: nothing known.
    let r = I::point(f32::INFINITY) - I::point(f32::INFINITY);
    assert!(r.is_entire());
    // Entirely outside the domain: entire; partly outside: the defined part.
    assert!(I::new(-3.0, -2.0).ln().is_entire());
    assert!(I::new(2.0, 3.0).asin().is_entire());
    assert!(!I::new(-3.0, 4.0).sqrt().is_nan().any());
    // Wrong order is swapped.
    let r = I::new(3.0, 1.0);
    assert_eq!((r.lo(), r.hi()), (1.0, 3.0));
    // An overflowed bound still contains the finite exact value.
    let r = I::point(3e38) + I::point(3e38);
    assert_eq!((r.lo(), r.hi()), (f32::MAX, f32::INFINITY));
}

#[test]
fn helpers() {
    let a = I::new(1.0, 2.0);
    let b = I::new(4.0, 5.0);
    let h = I::hull(a, b);
    assert_eq!((h.lo(), h.hi()), (1.0, 5.0));
    assert_eq!(h.width(), 4.0 + 8.0 * f32::EPSILON / 2.0 + f32::from_bits(1));
    assert!(h.contains(3.0) && h.contains(1.0) && !h.contains(5.5));
    assert!(I::point(2.0).is_point() && !a.is_point());
    assert!(I::entire().width().is_infinite());
}
