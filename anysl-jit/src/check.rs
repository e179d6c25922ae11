//! The cross-check's comparison of two shadings (`anysl jit check` and its test): outputs
//! more than [`MAX_ULPS`] apart *and* more than [`ABS_FLOOR`]`· max(1, |x|)` apart are
//! mismatches (values near zero after cancellation, and the SIMD polynomial
//! transcendentals, differ in ulps without differing in value).

use anysl_core::points::ShadeOut;

/// Ulps two outputs may differ by.
pub const MAX_ULPS: u64 = 4;
/// The absolute floor, relative to `max(1, |x|)`, under which more ulps are still a match.
pub const ABS_FLOOR: f64 = 2e-6;

/// Distance in units in the last place between two f32s (NaN against anything: infinite).
#[must_use]
pub fn ulps(a: f32, b: f32) -> u64 {
    if a == b {
        return 0;
    }
    if a.is_nan() || b.is_nan() {
        return u64::MAX;
    }
    let key = |x: f32| {
        let i = x.to_bits() as i32;
        i64::from(if i < 0 { i32::MIN - i } else { i })
    };
    (key(a) - key(b)).unsigned_abs()
}

/// How two shadings of the same points compare.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Comparison {
    /// Max ulps over all outputs.
    pub max_ulps: u64,
    /// Max finite absolute difference.
    pub max_abs: f64,
    /// Outputs beyond the bound.
    pub mismatches: usize,
}

/// Compares every output (Ci and Oi) of `a` and `b`.
#[must_use]
pub fn compare(a: &ShadeOut<f32>, b: &ShadeOut<f32>) -> Comparison {
    let mut r = Comparison::default();
    for (ca, cb) in a.channels.iter().zip(&b.channels) {
        for (x, y) in ca.iter().zip(cb) {
            let u = ulps(*x, *y);
            let d = f64::from((x - y).abs());
            r.max_ulps = r.max_ulps.max(u);
            if d.is_finite() {
                r.max_abs = r.max_abs.max(d);
            }
            let scale = f64::from(x.abs().max(y.abs())).max(1.0);
            if u > MAX_ULPS && !(d <= ABS_FLOOR * scale) {
                r.mismatches += 1;
            }
        }
    }
    r
}
