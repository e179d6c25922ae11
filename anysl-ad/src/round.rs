//! Outward rounding for [`crate::Interval`]: nudging a computed bound past every value the
//! exact result (and the inner type's own function) could take.
//!
//! The inner operations round to nearest. A bound `x` is moved down by
//! `δ = |x|·2n·u + n·tiny` (`u` = [`ShadingFloat::UNIT_ROUNDOFF`], `tiny` = the smallest
//! subnormal), computed in the inner type. Since one ulp of `x` is at most `2u·|x|` (or `tiny`
//! below the normal range), `δ` is at least `n` ulps, the subtraction cannot round back above
//! `x` minus one ulp, and the result lies at least `n` representable steps below `x`.
//! An infinite bound pointing the wrong way (`+∞` as a lower bound) becomes the largest
//! finite number, so an overflowed result still contains the finite exact value.

use anysl_core::ShadingFloat;

/// Ulps of widening for correctly rounded operations (`+ - × ÷ √`).
pub(crate) const EXACT_OP_ULPS: f64 = 1.0;
/// Ulps of widening for transcendental functions. libm and SIMD polynomials are not
/// correctly rounded: `δ = 16u·|x|` (≈ 9.5e-7 relative in f32) covers an inner error of up
/// to 2e-7 relative (anysl-simd's documented bound, ≈ 3.4 f32 ulps) at each of two points.
pub(crate) const TRANSCENDENTAL_ULPS: f64 = 8.0;

/// True when the inner lanes are IEEE binary32 (told apart from binary64 by the roundoff).
#[inline(always)]
fn is_binary32<F: ShadingFloat>() -> bool {
    F::UNIT_ROUNDOFF > 1e-12
}

/// The smallest positive subnormal of the inner format.
#[inline(always)]
pub(crate) fn tiny<F: ShadingFloat>() -> F {
    F::c(if is_binary32::<F>() { f64::from(f32::from_bits(1)) } else { f64::from_bits(1) })
}

/// The largest finite number of the inner format.
#[inline(always)]
pub(crate) fn max_finite<F: ShadingFloat>() -> F {
    F::c(if is_binary32::<F>() { f64::from(f32::MAX) } else { f64::MAX })
}

/// `+∞`.
#[inline(always)]
pub(crate) fn inf<F: ShadingFloat>() -> F {
    F::c(f64::INFINITY)
}

/// `x` moved down by at least `ulps` ulps (`-∞` stays, `+∞` becomes the largest finite).
#[inline(always)]
pub(crate) fn down<F: ShadingFloat>(x: F, ulps: f64) -> F {
    let r = x - (x.abs() * F::c(2.0 * ulps * F::UNIT_ROUNDOFF) + tiny::<F>() * F::c(ulps));
    F::select(x.eq(inf()), max_finite(), r)
}

/// `x` moved up by at least `ulps` ulps (`+∞` stays, `-∞` becomes the lowest finite).
#[inline(always)]
pub(crate) fn up<F: ShadingFloat>(x: F, ulps: f64) -> F {
    let r = x + (x.abs() * F::c(2.0 * ulps * F::UNIT_ROUNDOFF) + tiny::<F>() * F::c(ulps));
    F::select(x.eq(-inf::<F>()), -max_finite::<F>(), r)
}

/// The rounding error of `s = a + b` (Knuth's TwoSum: exact when nothing overflows; NaN
/// when something did). Positive means the exact sum is above `s`.
#[inline(always)]
pub(crate) fn sum_error<F: ShadingFloat>(a: F, b: F, s: F) -> F {
    let bb = s - a;
    (a - (s - bb)) + (b - bb)
}
