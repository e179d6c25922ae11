//! Intervals through the shared code: three-valued masks, `Exec` branches and loops, and
//! noise / cellnoise through `IBits`.

use crate::common;

use anysl_ad::{IBits, IMask, Interval};
use anysl_core::stdlib::{cellnoise, noise3, NoiseDomain};
use anysl_core::{Blend, Exec, LatticeBits, Mask, ShadingFloat, Vec3, INTERVAL_LOOP_LIMIT};
use common::Rng;

type I = Interval<f32>;
type M = IMask<bool>;

/// (possibly true, possibly false) of a scalar interval mask.
fn tf(m: M) -> (bool, bool) {
    (m.possibly_true(), m.possibly_false())
}

#[test]
fn comparisons_are_three_valued() {
    let a = I::new(1.0, 2.0);
    let b = I::new(3.0, 4.0);
    let c = I::new(1.5, 3.5);
    assert_eq!(tf(a.lt(b)), (true, false), "surely less");
    assert_eq!(tf(b.lt(a)), (false, true), "surely not less");
    assert_eq!(tf(a.lt(c)), (true, true), "maybe");
    assert_eq!(tf(I::new(1.0, 2.0).lt(I::new(2.0, 3.0))), (true, true), "touching: 2 < 2 fails");
    assert_eq!(tf(I::new(1.0, 2.0).le(I::new(2.0, 3.0))), (true, false), "touching: ≤ holds");
    assert_eq!(tf(I::point(2.0).eq(I::point(2.0))), (true, false));
    assert_eq!(tf(a.eq(c)), (true, true));
    assert_eq!(tf(a.eq(b)), (false, true));
    assert_eq!(tf(a.ne(b)), (true, false));
    assert_eq!(tf(a.gt(b)), (false, true));
    assert_eq!(tf(b.ge(a)), (true, false));
    // `any` = possibly true, `all` = surely true, `lane` = possibly true.
    let maybe = a.lt(c);
    assert!(maybe.any() && !maybe.all() && maybe.lane(0) && !maybe.none());
    const { assert!(<M as Mask>::THREE_VALUED) };
}

#[test]
fn kleene_logic() {
    let yes = M::splat(true);
    let no = M::splat(false);
    let maybe = M::new(true, true);
    assert_eq!(tf(maybe & no), (false, true));
    assert_eq!(tf(maybe & yes), (true, true));
    assert_eq!(tf(maybe | yes), (true, false));
    assert_eq!(tf(maybe | no), (true, true));
    assert_eq!(tf(!maybe), (true, true));
    assert_eq!(tf(!yes), (false, true));
    assert_eq!(tf(yes & yes), (true, false));
    assert_eq!(tf(no | no), (false, true));
    assert!(maybe.maybe() && yes.surely_true() && no.surely_false() && !maybe.surely_true());
    // select_mask: a maybe condition between two equal truths is that truth.
    assert_eq!(tf(M::select_mask(maybe, yes, yes)), (true, false));
    assert_eq!(tf(M::select_mask(maybe, yes, no)), (true, true));
    assert_eq!(tf(M::select_mask(yes, no, yes)), (false, true));
}

#[test]
fn select_and_blend() {
    let a = I::new(1.0, 2.0);
    let b = I::new(5.0, 6.0);
    let pick = |m: M| {
        let r = I::select(m, a, b);
        (r.lo(), r.hi())
    };
    assert_eq!(pick(M::splat(true)), (1.0, 2.0));
    assert_eq!(pick(M::splat(false)), (5.0, 6.0));
    assert_eq!(pick(M::new(true, true)), (1.0, 6.0));
    let w = Blend::<I>::widen(a);
    assert!(w.is_entire());
    // Vec3 blends go through the same select.
    let v = Vec3::<I>::select(M::new(true, true), Vec3::splat(a), Vec3::splat(b));
    assert_eq!((v.z.lo(), v.z.hi()), (1.0, 6.0));
}

/// `if (x < 0) y = -1 else y = x + 10` with a box straddling 0 runs both arms: y is the hull.
#[test]
fn exec_if_else_with_maybe_takes_the_hull() {
    let run = |x: I| {
        let mut e = Exec::<I>::new();
        let mut y = I::c(0.0);
        let mut arms = (0, 0);
        e.if_else(x.lt(I::c(0.0)), |e, then| {
            if then {
                arms.0 += 1;
                e.assign(&mut y, I::c(-1.0));
            } else {
                arms.1 += 1;
                e.assign(&mut y, x + I::c(10.0));
            }
        });
        (y, arms)
    };
    let (y, arms) = run(I::new(-1.0, 3.0));
    assert_eq!(arms, (1, 1));
    assert_eq!((y.lo(), y.hi()), (-1.0, 13.0));
    let (y, arms) = run(I::new(1.0, 3.0));
    assert_eq!(arms, (0, 1));
    assert_eq!((y.lo(), y.hi()), (11.0, 13.0));
    let (y, arms) = run(I::new(-3.0, -1.0));
    assert_eq!(arms, (1, 0));
    assert_eq!((y.lo(), y.hi()), (-1.0, -1.0));
    // choose() blends the same way.
    let mut e = Exec::<I>::new();
    let v = e.choose(I::new(-1.0, 1.0).gt(I::c(0.0)), |_, then| if then { I::c(10.0) } else { I::c(20.0) });
    assert_eq!((v.lo(), v.hi()), (10.0, 20.0));
}

/// `i = 0; while (i < n) i += 1;`: a point n settles exactly; a box n keeps the condition
/// "maybe", and the loop stops after INTERVAL_LOOP_LIMIT iterations with i widened.
#[test]
fn exec_loop_with_maybe_condition_terminates_and_widens() {
    let run = |n: I| {
        let mut e = Exec::<I>::new();
        let mut i = I::c(0.0);
        let mut bodies = 0usize;
        e.loop_(|e| {
            bodies += 1;
            e.break_if(!i.lt(n));
            e.update(&mut i, |i| i + I::c(1.0));
        });
        (i, bodies)
    };
    let (i, bodies) = run(I::point(3.0));
    assert_eq!((i.lo(), i.hi()), (3.0, 3.0), "integer steps stay exact");
    assert_eq!(bodies, 4);
    let (i, bodies) = run(I::new(2.5, 3.5));
    assert!(i.is_entire(), "{i:?}");
    assert_eq!(bodies, INTERVAL_LOOP_LIMIT + 1);
    // The widened value is conservative: every point run ends inside it.
    for n in [2.5f32, 3.0, 3.5] {
        let mut e = Exec::<f32>::new();
        let mut p = 0.0f32;
        e.loop_(|e| {
            e.break_if(!p.lt(n));
            e.update(&mut p, |p| p + 1.0);
        });
        assert!(i.contains(p));
    }
}

fn ib(bits: u32, known: bool) -> IBits<f32> {
    IBits::new(bits, known)
}

#[test]
fn lattice_bits_track_knowledge() {
    let fb = I::new(2.2, 2.9).floor_bits();
    assert!(fb.known() && fb.bits() == 2);
    let fb = I::new(-0.5, -0.1).floor_bits();
    assert!(fb.known() && fb.bits() == (-1i32) as u32);
    assert!(!I::new(2.9, 3.1).floor_bits().known());
    let (k, u) = (ib(0xF0, true), ib(0x0F, false));
    for r in [k & u, k | u, k ^ u, k.wrapping_add(u), k.wrapping_mul(u)] {
        assert!(!r.known());
    }
    for r in [k & k, k >> 4, k << 4, k.wrapping_mul(IBits::splat(3))] {
        assert!(r.known());
    }
    assert_eq!((k >> 4).bits(), 0x0F);
    assert_eq!(tf(k.eq_mask(ib(0xF0, true))), (true, false));
    assert_eq!(tf(k.eq_mask(ib(0xF1, true))), (false, true));
    assert_eq!(tf(k.eq_mask(ib(0xF0, false))), (true, true));
    assert_eq!(k.lane(0), 0xF0);
    let unit = I::bits_to_unit(ib(0x1234_5600, true));
    assert_eq!((unit.lo(), unit.hi()), (f32::bits_to_unit(0x1234_5600), f32::bits_to_unit(0x1234_5600)));
    let unit = I::bits_to_unit(ib(0, false));
    assert_eq!((unit.lo(), unit.hi()), (0.0, 1.0 - 1.0 / 16_777_216.0));
    let s = I::bits_to_float_signed(ib((-5i32) as u32, true));
    assert_eq!((s.lo(), s.hi()), (-5.0, -5.0));
    let s = I::bits_to_float_signed(ib(123_456_789, true));
    assert!(s.contains(123_456_789.0) && f64::from(s.lo()) <= 123_456_789.0 && f64::from(s.hi()) >= 123_456_789.0);
    let s = I::bits_to_float_signed(ib(0, false));
    assert!(s.contains(i32::MIN as f32) && s.contains(i32::MAX as f32));
}

/// Interval noise over a box contains the point noise of every sample in it.
#[test]
fn noise_of_a_box_contains_point_noise() {
    let mut rng = Rng::new(0x0015E);
    let mut narrow_hits = 0;
    for n in 0..1000 {
        let scale = if n % 4 == 0 { rng.log(0.0, 6.0) } else { 10.0 };
        let c = [0, 1, 2].map(|_| rng.range(-scale, scale));
        let w = [0, 1, 2].map(|_| if rng.below(3) == 0 { 0.0 } else { rng.log(-6.0, 0.0) });
        let lo = [0, 1, 2].map(|k| c[k] as f32);
        let hi = [0, 1, 2].map(|k| (c[k] + w[k]) as f32);
        let b = Vec3::new(I::new(lo[0], hi[0]), I::new(lo[1], hi[1]), I::new(lo[2], hi[2]));
        let r = noise3(b);
        let cell = cellnoise(NoiseDomain::D3(b));
        if r.hi() - r.lo() < 0.5 {
            narrow_hits += 1;
        }
        for s in 0..100 {
            let mut t = |k: usize| {
                let f = if s == 0 {
                    0.0
                } else if s == 1 {
                    1.0
                } else {
                    rng.unit()
                };
                (f64::from(lo[k]) + f * (f64::from(hi[k]) - f64::from(lo[k]))) as f32
            };
            let p = Vec3::new(t(0).clamp(lo[0], hi[0]), t(1).clamp(lo[1], hi[1]), t(2).clamp(lo[2], hi[2]));
            let v = noise3(p);
            assert!(r.contains(v), "noise3 box {lo:?}..{hi:?} = {r:?} misses {v} at {p:?}");
            let cv = cellnoise(NoiseDomain::D3(p));
            assert!(cell.contains(cv), "cellnoise box {lo:?}..{hi:?} = {cell:?} misses {cv}");
        }
    }
    // Most small boxes give informative (not just [0, 1]) bounds.
    assert!(narrow_hits > 500, "only {narrow_hits} narrow results");
}

/// A box inside one lattice cell has known bits: cellnoise is the exact point value.
#[test]
fn cellnoise_inside_one_cell_is_exact() {
    let mut rng = Rng::new(0xCE11);
    for _ in 0..1000 {
        let base = [0, 1, 2].map(|_| rng.range(-1e4, 1e4).floor());
        let lo = [0, 1, 2].map(|k| (base[k] + rng.range(0.0, 0.5)) as f32);
        let hi = [0, 1, 2].map(|k| (base[k] + rng.range(0.5, 0.99)) as f32);
        let b = Vec3::new(I::new(lo[0], hi[0]), I::new(lo[1], hi[1]), I::new(lo[2], hi[2]));
        let r = cellnoise(NoiseDomain::D3(b));
        let p = cellnoise(NoiseDomain::D3(Vec3::new(lo[0], lo[1], lo[2])));
        assert_eq!((r.lo(), r.hi()), (p, p));
        // Straddling a cell boundary in one axis: unknown bits, every value possible.
        let s = Vec3::new(I::new(lo[0] - 1.0, hi[0]), b.y, b.z);
        let r = cellnoise(NoiseDomain::D3(s));
        assert_eq!((r.lo(), r.hi()), (0.0, 1.0 - 1.0 / 16_777_216.0));
    }
}
