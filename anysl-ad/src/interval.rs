//! [`Interval`]: a conservative range `[lo, hi]` per lane, rounded outward after every
//! operation, so that one evaluation bounds a shader over a whole box of inputs.

use crate::bits::IBits;
use crate::mask::IMask;
use crate::name::{as_str, prefixed, NAME_CAP};
use crate::round::{down, inf, sum_error, up, EXACT_OP_ULPS, TRANSCENDENTAL_ULPS};
use anysl_core::{Blend, ShadingFloat};
use core::f64::consts::PI;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// A closed range `[lo, hi]` per lane of the inner type `F` that contains every value the
/// computation could take for inputs in the boxes it started from.
///
/// Bounds are never NaN and `lo <= hi`; "nothing known" (including a possible NaN) is the
/// entire line `(-∞, +∞)`. See the crate docs for the rounding margins and the NaN policy.
#[derive(Clone, Copy, Debug)]
pub struct Interval<F> {
    lo: F,
    hi: F,
}

/// Min and max of `f` over the four corners of `[a0, a1] × [b0, b1]` (NaN corners ignored).
#[inline(always)]
fn corners<F: ShadingFloat>(a0: F, a1: F, b0: F, b1: F, f: impl Fn(F, F) -> F) -> (F, F) {
    let (p, q, r, s) = (f(a0, b0), f(a0, b1), f(a1, b0), f(a1, b1));
    (p.min(q).min(r.min(s)), p.max(q).max(r.max(s)))
}

impl<F: ShadingFloat> Interval<F> {
    const NAME_BUF: ([u8; NAME_CAP], usize) = prefixed("interval-", F::NAME);
    const NAME_BYTES: &'static [u8; NAME_CAP] = &Self::NAME_BUF.0;

    /// `[lo, hi]` lane by lane; bounds in the wrong order are swapped, a NaN bound gives the
    /// entire line.
    #[inline(always)]
    #[must_use]
    pub fn new(lo: F, hi: F) -> Self {
        let ordered = lo.le(hi);
        Self::exact(F::select(ordered, lo, hi), F::select(ordered, hi, lo))
    }
    /// The single value `x` (the entire line where `x` is NaN).
    #[inline(always)]
    #[must_use]
    pub fn point(x: F) -> Self {
        Self::exact(x, x)
    }
    /// The entire real line: nothing known.
    #[inline(always)]
    #[must_use]
    pub fn entire() -> Self {
        Self { lo: -inf::<F>(), hi: inf() }
    }
    /// The smallest interval containing both.
    #[inline(always)]
    #[must_use]
    pub fn hull(a: Self, b: Self) -> Self {
        Self { lo: a.lo.min(b.lo), hi: a.hi.max(b.hi) }
    }
    /// Lower bound.
    #[inline(always)]
    #[must_use]
    pub fn lo(self) -> F {
        self.lo
    }
    /// Upper bound.
    #[inline(always)]
    #[must_use]
    pub fn hi(self) -> F {
        self.hi
    }
    /// `hi - lo`, rounded up (`+∞` for unbounded intervals).
    #[inline(always)]
    #[must_use]
    pub fn width(self) -> F {
        up(self.hi - self.lo, EXACT_OP_ULPS).max(F::c(0.0))
    }
    /// Lanes where `x` lies in the interval.
    #[inline(always)]
    #[must_use]
    pub fn contains(self, x: F) -> F::Mask {
        self.lo.le(x) & x.le(self.hi)
    }
    /// Lanes where the interval holds a single value.
    #[inline(always)]
    #[must_use]
    pub fn is_point(self) -> F::Mask {
        self.lo.eq(self.hi)
    }
    /// Lanes that are the entire line.
    #[inline(always)]
    #[must_use]
    pub fn is_entire(self) -> F::Mask {
        self.lo.eq(-inf::<F>()) & self.hi.eq(inf())
    }

    /// Bounds taken as they are; lanes with a NaN bound become the entire line.
    #[inline(always)]
    fn exact(lo: F, hi: F) -> Self {
        let nan = lo.is_nan() | hi.is_nan();
        Self { lo: F::select(nan, -inf::<F>(), lo), hi: F::select(nan, inf(), hi) }
    }
    /// Bounds from round-to-nearest results, each pushed outward by `ulps`.
    #[inline(always)]
    fn rounded(lo: F, hi: F, ulps: f64) -> Self {
        Self::exact(down(lo, ulps), up(hi, ulps))
    }
    /// `self` where `m`, else the entire line (e.g. outside a function's domain).
    #[inline(always)]
    fn or_entire(self, m: F::Mask) -> Self {
        Self { lo: F::select(m, self.lo, -inf::<F>()), hi: F::select(m, self.hi, inf()) }
    }
    /// Lanes that surely do not contain 0.
    #[inline(always)]
    fn excludes_zero(self) -> F::Mask {
        let z = F::c(0.0);
        self.lo.gt(z) | self.hi.lt(z)
    }
    /// A monotone increasing transcendental `f` over `[lo, hi]`.
    #[inline(always)]
    fn increasing(lo: F, hi: F, f: impl Fn(F) -> F) -> Self {
        Self::rounded(f(lo), f(hi), TRANSCENDENTAL_ULPS)
    }
}

impl<F: ShadingFloat> Add for Interval<F> {
    type Output = Self;
    /// Exact sums (checked with TwoSum) keep their bound; inexact ones move one ulp out.
    #[inline(always)]
    fn add(self, r: Self) -> Self {
        let (lo, hi) = (self.lo + r.lo, self.hi + r.hi);
        let z = F::c(0.0);
        let lo = F::select(sum_error(self.lo, r.lo, lo).ge(z), lo, down(lo, EXACT_OP_ULPS));
        let hi = F::select(sum_error(self.hi, r.hi, hi).le(z), hi, up(hi, EXACT_OP_ULPS));
        Self::exact(lo, hi)
    }
}

impl<F: ShadingFloat> Sub for Interval<F> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, r: Self) -> Self {
        self + -r
    }
}

impl<F: ShadingFloat> Neg for Interval<F> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self { lo: -self.hi, hi: -self.lo }
    }
}

impl<F: ShadingFloat> Mul for Interval<F> {
    type Output = Self;
    /// Hull of the four endpoint products (`0·∞` products are ignored: a bound at infinity
    /// stands for "unbounded", not for a value).
    #[inline(always)]
    fn mul(self, r: Self) -> Self {
        let (lo, hi) = corners(self.lo, self.hi, r.lo, r.hi, |a, b| a * b);
        Self::rounded(lo, hi, EXACT_OP_ULPS)
    }
}

impl<F: ShadingFloat> Div for Interval<F> {
    type Output = Self;
    /// Hull of the four endpoint quotients; a divisor that may be 0 gives the entire line.
    #[inline(always)]
    fn div(self, r: Self) -> Self {
        let (lo, hi) = corners(self.lo, self.hi, r.lo, r.hi, |a, b| a / b);
        Self::rounded(lo, hi, EXACT_OP_ULPS).or_entire(r.excludes_zero())
    }
}

macro_rules! assign_ops {
    ($($Tr:ident $m:ident $op:tt),*) => {$(
        impl<F: ShadingFloat> $Tr for Interval<F> {
            #[inline(always)]
            fn $m(&mut self, r: Self) {
                *self = *self $op r;
            }
        }
    )*};
}
assign_ops!(AddAssign add_assign +, SubAssign sub_assign -, MulAssign mul_assign *, DivAssign div_assign /);

impl<F: ShadingFloat> Blend<Interval<F>> for Interval<F> {
    #[inline(always)]
    fn blend(m: IMask<F::Mask>, a: Self, b: Self) -> Self {
        <Self as ShadingFloat>::select(m, a, b)
    }
    #[inline(always)]
    fn widen(self) -> Self {
        Self::entire()
    }
}

impl<F: ShadingFloat> ShadingFloat for Interval<F> {
    type Mask = IMask<F::Mask>;
    type Bits = IBits<F>;
    const LANES: usize = F::LANES;
    const UNIT_ROUNDOFF: f64 = F::UNIT_ROUNDOFF;
    const NAME: &'static str = as_str(Self::NAME_BYTES, Self::NAME_BUF.1);

    /// A point when `v` is representable in `F`, else the two neighbours around it.
    #[inline(always)]
    fn c(v: f64) -> Self {
        let x = F::c(v);
        if x.lane(0) == v {
            Self::point(x)
        } else {
            Self::rounded(x, x, EXACT_OP_ULPS)
        }
    }
    /// The midpoint (0 for the entire line).
    #[inline(always)]
    fn lane(self, i: usize) -> f64 {
        let (lo, hi) = (self.lo.lane(i), self.hi.lane(i));
        if lo == f64::NEG_INFINITY && hi == f64::INFINITY {
            0.0
        } else {
            0.5 * lo + 0.5 * hi
        }
    }
    /// Point intervals containing the given values (widened when `F` cannot hold them).
    #[inline(always)]
    fn from_lanes(lanes: &[f64]) -> Self {
        let x = F::from_lanes(lanes);
        if lanes.iter().enumerate().all(|(i, &v)| x.lane(i) == v) {
            Self::point(x)
        } else {
            Self::rounded(x, x, EXACT_OP_ULPS)
        }
    }

    #[inline(always)]
    fn load(src: &[f32]) -> Self {
        // f32 data is exact in any inner precision of at least f32.
        Self::point(F::load(src))
    }

    /// Surely-true lanes take `a`, surely-false lanes `b`, "maybe" lanes the hull of both.
    #[inline(always)]
    fn select(m: IMask<F::Mask>, a: Self, b: Self) -> Self {
        let surely_true = m.surely_true();
        let surely_false = m.surely_false();
        let h = Self::hull(a, b);
        Self {
            lo: F::select(surely_true, a.lo, F::select(surely_false, b.lo, h.lo)),
            hi: F::select(surely_true, a.hi, F::select(surely_false, b.hi, h.hi)),
        }
    }
    /// Surely true iff `self.hi < rhs.lo`, surely false iff `self.lo >= rhs.hi`.
    #[inline(always)]
    fn lt(self, rhs: Self) -> IMask<F::Mask> {
        IMask::new(self.lo.lt(rhs.hi), self.hi.ge(rhs.lo))
    }
    /// Surely true iff `self.hi <= rhs.lo`, surely false iff `self.lo > rhs.hi`.
    #[inline(always)]
    fn le(self, rhs: Self) -> IMask<F::Mask> {
        IMask::new(self.lo.le(rhs.hi), self.hi.gt(rhs.lo))
    }
    /// Possibly true where the intervals overlap, surely true only for equal points.
    #[inline(always)]
    fn eq(self, rhs: Self) -> IMask<F::Mask> {
        let overlap = self.lo.le(rhs.hi) & rhs.lo.le(self.hi);
        let same_point = self.lo.eq(self.hi) & rhs.lo.eq(rhs.hi) & self.lo.eq(rhs.lo);
        IMask::new(overlap, !same_point)
    }
    /// "Maybe" on the entire line (which stands for unknown values, NaN included), surely
    /// false elsewhere.
    #[inline(always)]
    fn is_nan(self) -> IMask<F::Mask> {
        IMask::maybe_where(self.is_entire())
    }

    #[inline(always)]
    fn abs(self) -> Self {
        let z = F::c(0.0);
        let (pos, neg) = (self.lo.ge(z), self.hi.le(z));
        Self {
            lo: F::select(pos, self.lo, F::select(neg, -self.hi, z)),
            hi: F::select(pos, self.hi, F::select(neg, -self.lo, (-self.lo).max(self.hi))),
        }
    }
    #[inline(always)]
    fn floor(self) -> Self {
        Self { lo: self.lo.floor(), hi: self.hi.floor() }
    }
    #[inline(always)]
    fn ceil(self) -> Self {
        Self { lo: self.lo.ceil(), hi: self.hi.ceil() }
    }
    #[inline(always)]
    fn round(self) -> Self {
        Self { lo: self.lo.round(), hi: self.hi.round() }
    }
    #[inline(always)]
    fn trunc(self) -> Self {
        Self { lo: self.lo.trunc(), hi: self.hi.trunc() }
    }
    #[inline(always)]
    fn min(self, rhs: Self) -> Self {
        Self { lo: self.lo.min(rhs.lo), hi: self.hi.min(rhs.hi) }
    }
    #[inline(always)]
    fn max(self, rhs: Self) -> Self {
        Self { lo: self.lo.max(rhs.lo), hi: self.hi.max(rhs.hi) }
    }
    /// √ of the non-negative part; entirely negative (all NaN) gives the entire line.
    #[inline(always)]
    fn sqrt(self) -> Self {
        let z = F::c(0.0);
        let r = Self::rounded(self.lo.max(z).sqrt(), self.hi.sqrt(), EXACT_OP_ULPS);
        Self { lo: r.lo.max(z), hi: r.hi }.or_entire(self.hi.ge(z))
    }
    #[inline(always)]
    fn exp(self) -> Self {
        let r = Self::increasing(self.lo, self.hi, F::exp);
        Self { lo: r.lo.max(F::c(0.0)), hi: r.hi }
    }
    #[inline(always)]
    fn exp2(self) -> Self {
        let r = Self::increasing(self.lo, self.hi, F::exp2);
        Self { lo: r.lo.max(F::c(0.0)), hi: r.hi }
    }
    /// ln of the non-negative part (`ln 0 = -∞`); entirely negative gives the entire line.
    #[inline(always)]
    fn ln(self) -> Self {
        let z = F::c(0.0);
        Self::increasing(self.lo.max(z), self.hi, F::ln).or_entire(self.hi.ge(z))
    }
    /// log2 of the non-negative part; entirely negative gives the entire line.
    #[inline(always)]
    fn log2(self) -> Self {
        let z = F::c(0.0);
        Self::increasing(self.lo.max(z), self.hi, F::log2).or_entire(self.hi.ge(z))
    }
    /// Non-negative bases: hull over the four corners (x^y is monotone in each argument on
    /// x ≥ 0). Negative finite bases: only integer exponents in the box count, with the sign
    /// of their parity (a base of -∞ counts for every exponent, as in C). No defined point at
    /// all gives the entire line.
    #[inline(always)]
    fn pow(self, y: Self) -> Self {
        let (z, one) = (F::c(0.0), F::c(1.0));
        let infinity = inf::<F>();
        // Non-negative part of the base.
        let has_pos = self.hi.ge(z);
        let (plo, phi) = corners(self.lo.max(z), self.hi.max(z), y.lo, y.hi, F::pow);
        // Negative part (a lower bound of -0 counts: pow(-0, odd) keeps the sign).
        let neg_zero = self.lo.eq(z) & (one / self.lo).lt(z);
        let (n0, n1) = (y.lo.ceil(), y.hi.floor());
        let has_neg = (self.lo.lt(z) | neg_zero) & n0.le(n1);
        let (m0, m1) = ((-self.hi).max(z), -self.lo);
        let (mlo, mhi) = corners(m0, m1, n0, n1, F::pow);
        let single = n0.eq(n1);
        let even = ((n0 * F::c(0.5)).floor() * F::c(2.0)).eq(n0);
        let nlo = F::select(single & even, mlo, -mhi);
        let nhi = F::select(single & !even, -mlo, mhi);
        // A base of -∞ is defined for every exponent: ±∞, ±0 or 1 (only [0, ∞] matters
        // beyond what the integer exponents gave).
        let minus_inf = self.lo.eq(-infinity);
        let lo = F::select(has_pos, plo, infinity).min(F::select(has_neg, nlo, infinity));
        let hi = F::select(has_pos, phi, -infinity).max(F::select(has_neg, nhi, -infinity));
        let lo = F::select(minus_inf, lo.min(z), lo);
        let hi = F::select(minus_inf, infinity, hi);
        let r = Self::rounded(lo, hi, TRANSCENDENTAL_ULPS);
        let lo = F::select(has_neg, r.lo, r.lo.max(z));
        Self { lo, hi: r.hi }.or_entire(has_pos | has_neg | minus_inf)
    }
    /// Endpoint values, plus ±1 where a maximum/minimum may lie inside (found from the sign
    /// of cos at the endpoints when the width is below 3.125; wider intervals give [-1, 1]).
    #[inline(always)]
    fn sin(self) -> Self {
        let (sl, sh) = (self.lo.sin(), self.hi.sin());
        let (cl, ch) = (self.lo.cos(), self.hi.cos());
        periodic_hull(self, sl, sh, cl, ch)
    }
    /// As `sin`, with `-sin` as the derivative.
    #[inline(always)]
    fn cos(self) -> Self {
        let (cl, ch) = (self.lo.cos(), self.hi.cos());
        let (sl, sh) = (self.lo.sin(), self.hi.sin());
        periodic_hull(self, cl, ch, -sl, -sh)
    }
    /// Monotone between poles; a possible pole inside (cos may change sign, or the width
    /// reaches π) gives the entire line.
    #[inline(always)]
    fn tan(self) -> Self {
        let (cl, ch) = (self.lo.cos(), self.hi.cos());
        let eps = sign_slack::<F>();
        let narrow = (self.hi - self.lo).lt(F::c(NARROW));
        let same_sign = (cl.gt(eps) & ch.gt(eps)) | (cl.lt(-eps) & ch.lt(-eps));
        Self::increasing(self.lo, self.hi, F::tan).or_entire(narrow & same_sign)
    }
    /// asin of the part inside [-1, 1]; entirely outside gives the entire line.
    #[inline(always)]
    fn asin(self) -> Self {
        let one = F::c(1.0);
        let inside = self.hi.ge(-one) & self.lo.le(one);
        Self::increasing(self.lo.max(-one), self.hi.min(one), F::asin).or_entire(inside)
    }
    /// acos of the part inside [-1, 1] (decreasing); entirely outside gives the entire line.
    #[inline(always)]
    fn acos(self) -> Self {
        let one = F::c(1.0);
        let inside = self.hi.ge(-one) & self.lo.le(one);
        let (lo, hi) = (self.lo.max(-one), self.hi.min(one));
        Self::rounded(hi.acos(), lo.acos(), TRANSCENDENTAL_ULPS).or_entire(inside)
    }
    #[inline(always)]
    fn atan(self) -> Self {
        Self::increasing(self.lo, self.hi, F::atan)
    }
    /// Hull over the four corners where the box avoids the origin and the branch cut
    /// (x > 0, or y of one sign: atan2 is monotone in each argument there); else [-π, π].
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        let z = F::c(0.0);
        let y = self;
        let monotone = x.lo.gt(z) | y.lo.gt(z) | y.hi.lt(z);
        let (lo, hi) = corners(y.lo, y.hi, x.lo, x.hi, F::atan2);
        let r = Self::rounded(lo, hi, TRANSCENDENTAL_ULPS);
        let all = Self::rounded(F::c(-PI), F::c(PI), TRANSCENDENTAL_ULPS);
        Self { lo: F::select(monotone, r.lo, all.lo), hi: F::select(monotone, r.hi, all.hi) }
    }

    /// Known where `floor(lo) == floor(hi)`.
    #[inline(always)]
    fn floor_bits(self) -> IBits<F> {
        IBits::new(self.lo.floor_bits(), self.lo.floor().eq(self.hi.floor()))
    }
    /// Known where the interval is one integer.
    #[inline(always)]
    fn lattice_bits(self) -> IBits<F> {
        IBits::new(self.lo.lattice_bits(), self.lo.eq(self.hi))
    }
    /// The table entry where the bits are known, the hull of the table elsewhere.
    #[inline(always)]
    fn lookup16(table: &[f32; 16], h: IBits<F>) -> Self {
        let v = F::lookup16(table, h.bits());
        let known = h.known();
        let lo = table.iter().fold(f32::INFINITY, |a, &b| a.min(b));
        let hi = table.iter().fold(f32::NEG_INFINITY, |a, &b| a.max(b));
        Self { lo: F::select(known, v, F::c(f64::from(lo))), hi: F::select(known, v, F::c(f64::from(hi))) }
    }
    /// The exact value where known, `[0, 1 - 2^-24]` (every possible value) elsewhere.
    #[inline(always)]
    fn bits_to_unit(h: IBits<F>) -> Self {
        let v = F::bits_to_unit(h.bits());
        let known = h.known();
        Self { lo: F::select(known, v, F::c(0.0)), hi: F::select(known, v, F::c(1.0 - 1.0 / 16_777_216.0)) }
    }
    /// The integer where known (widened when `F` cannot hold it exactly), the whole i32
    /// range elsewhere.
    #[inline(always)]
    fn bits_to_float_signed(h: IBits<F>) -> Self {
        let v = F::bits_to_float_signed(h.bits());
        let exact = v.abs().le(F::c(1.0 / F::UNIT_ROUNDOFF));
        let w = Self::rounded(v, v, EXACT_OP_ULPS);
        let known = h.known();
        let two31 = F::c(2_147_483_648.0);
        Self {
            lo: F::select(known, F::select(exact, v, w.lo), -two31),
            hi: F::select(known, F::select(exact, v, w.hi), two31),
        }
    }

    #[inline(always)]
    fn lower(self, i: usize) -> f64 {
        self.lo.lane(i)
    }
    #[inline(always)]
    fn upper(self, i: usize) -> f64 {
        self.hi.lane(i)
    }
}

/// Widths below this (< π even after the rounding of `hi - lo`) hold at most one critical
/// point of sin/cos and at most one pole of tan.
const NARROW: f64 = 3.125;

/// Absolute slack on the sign of a derivative computed by the inner sin/cos (16 units of
/// roundoff: far above the error of libm or SIMD polynomials on values in [-1, 1]).
#[inline(always)]
fn sign_slack<F: ShadingFloat>() -> F {
    F::c(16.0 * F::UNIT_ROUNDOFF)
}

/// Range of sin or cos over `x`, from the endpoint values `(fl, fh)` and endpoint
/// derivatives `(dl, dh)`. Below width π there is at most one critical point; a maximum
/// inside needs `f' ≥ 0` at `lo` and `≤ 0` at `hi` (a minimum the reverse), tested with
/// slack, so an extremum is never missed.
#[inline(always)]
fn periodic_hull<F: ShadingFloat>(x: Interval<F>, fl: F, fh: F, dl: F, dh: F) -> Interval<F> {
    let eps = sign_slack::<F>();
    let one = F::c(1.0);
    let narrow = (x.hi - x.lo).lt(F::c(NARROW));
    let has_max = !narrow | (dl.ge(-eps) & dh.le(eps));
    let has_min = !narrow | (dl.le(eps) & dh.ge(-eps));
    let lo = F::select(has_min, -one, fl.min(fh));
    let hi = F::select(has_max, one, fl.max(fh));
    Interval::rounded(lo, hi, TRANSCENDENTAL_ULPS)
}
