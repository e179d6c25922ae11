//! # anysl-ad
//!
//! Two more instantiations of [`ShadingFloat`], each generic over the inner float so they
//! compose with every other one (`Dual<f32>`, `Dual<f64>`, `Dual<F32x8>`, `Interval<f32>`, …):
//!
//! - [`Dual<F>`]: a value with its screen-space derivatives ∂/∂x, ∂/∂y (forward-mode
//!   automatic differentiation). This is what RSL's `Du`, `Dv`, `area`, `filterwidth`,
//!   `filterstep` and `calculatenormal` in [`anysl_core::stdlib`] read.
//! - [`Interval<F>`]: a range `[lo, hi]` rounded outward, whose comparisons give
//!   three-valued [`IMask`]s and whose noise-hash bits are [`IBits`] (known or not).
//!
//! ```
//! use anysl_ad::{Dual, Interval};
//! use anysl_core::ShadingFloat;
//!
//! // One shading function, written once…
//! fn bump<F: ShadingFloat>(x: F) -> F {
//!     x * x.sin() + x.sqrt()
//! }
//!
//! // …differentiated: d/dx (x sin x + √x) = sin x + x cos x + 1/(2√x).
//! let d = bump(Dual::seed_x(1.5f32));
//! let exact = 1.5f64.sin() + 1.5 * 1.5f64.cos() + 0.5 / 1.5f64.sqrt();
//! assert!((f64::from(d.ddx) - exact).abs() < 1e-5);
//!
//! // …and bounded over a whole range of inputs.
//! let r = bump(Interval::new(1.0f32, 2.0));
//! for i in 0..=100 {
//!     let x = 1.0 + i as f32 / 100.0;
//!     assert!(r.lo() <= bump(x) && bump(x) <= r.hi());
//! }
//! ```
//!
//! ## Derivatives at singular points
//!
//! Where a value is finite its derivatives are never NaN or infinite: a chain-rule factor
//! that would be (the derivative has no finite limit there) is replaced by **0**, with a
//! select. Concretely:
//!
//! | primitive | singular point | derivative used |
//! |---|---|---|
//! | `sqrt` | x = 0 | 0 |
//! | `ln`, `log2` | x = 0 (value -∞) | 0 |
//! | `pow(x, y)`, ∂/∂x | x = 0 | 1 if y = 1, else 0 (the limit for y > 1; clamped for y < 1) |
//! | `pow(x, y)`, ∂/∂y | x ≤ 0 (`ln x` not finite) | 0 |
//! | `asin`, `acos` | x = ±1 | 0 |
//! | `atan2(y, x)` | origin | 0 (both partials) |
//! | `tan` | factor `1 + tan²` overflowing | 0 |
//! | `abs` | x = 0 | the derivative passes through (the right derivative) |
//! | `min`, `max` | tie | the derivatives of `self` |
//! | `floor`, `ceil`, `round`, `trunc` | everywhere | 0 |
//! | `a / b` | b at or near 0 (`1/b` overflows, e.g. a denormal b) | 0 where the quotient rule's result is not finite |
//! | `Vec3::normalize` (anysl-core) | \|v\| → 0 (derivative ∝ 1/\|v\|) | 0 where not finite; the value stays the unit vector |
//!
//! So `x / x` with x the smallest subnormal is 1 with derivative 0 (the plain quotient rule
//! gives `0 · ∞ = NaN`), and `pow(ndh, 1/roughness)` with roughness 0 keeps finite
//! derivatives. Derivatives of NaN or infinite values are unspecified (they may be NaN). Other
//! than in division, a genuine overflow of a finite derivative times a large factor still
//! gives ±∞, as any product would. `tests/tests/integration/stability.rs` checks the policy at each of
//! these points for `Dual<f32>`, `Dual<f64>` and `Dual<F32x8>`.
//!
//! ## Outward rounding margins
//!
//! Inner operations round to nearest; every computed bound is then moved outward by
//! `|b|·2n·u + n·tiny` (u = [`ShadingFloat::UNIT_ROUNDOFF`], tiny = the smallest subnormal),
//! which is at least `n` ulps of the bound:
//!
//! - **n = 1** for the correctly rounded `×`, `÷`, `√` and for constants that `F` cannot
//!   represent exactly ([`ShadingFloat::c`], [`ShadingFloat::from_lanes`]);
//! - `+` and `-` check exactness with TwoSum and move a bound one ulp only when the sum was
//!   inexact, in the direction of the error (so integer arithmetic stays exact);
//! - **n = 8** (δ = 16u·|b|, ≈ 9.5e-7 relative in f32) for `exp`, `exp2`, `ln`, `log2`,
//!   `pow`, `sin`, `cos`, `tan`, `asin`, `acos`, `atan` and `atan2`: libm and SIMD
//!   polynomials are not correctly rounded, and this covers an inner error (or a
//!   non-monotone step) of up to 2e-7 relative — anysl-simd's documented bound, ≈ 3.4 f32
//!   ulps — at each of two points (glibc's f32 functions would need only 1 ulp);
//! - `abs`, `min`, `max`, negation, `floor`, `ceil`, `round`, `trunc` are exact.
//!
//! The extremum test of `sin`/`cos` and the pole test of `tan` read the sign of the inner
//! cos/sin at the endpoints with an absolute slack of 16u, so they rely on the inner
//! functions being accurate to that on the endpoints (libm is, at every magnitude). The
//! formats are told apart by `UNIT_ROUNDOFF`: inner lanes must be IEEE binary32 or binary64.
//! Each result encloses both the exact mathematical range and the inner type's own function
//! at every point of the input box.
//!
//! ## NaN policy
//!
//! Interval bounds are never NaN. A NaN input (to [`Interval::new`], [`Interval::point`],
//! [`ShadingFloat::c`], …) and any operation whose bound would be NaN (`∞ - ∞`) give the
//! **entire line** `(-∞, +∞)`, which stands for "nothing known, NaN included".
//! Functions with a restricted domain (`sqrt`, `ln`, `log2`, `asin`, `acos`, `pow` with a
//! negative base) follow IEEE 1788's set semantics: points of the box outside the domain,
//! where the inner function returns NaN, are dropped, and the result encloses the function
//! over the rest; a box entirely outside the domain gives the entire line. Accordingly
//! [`ShadingFloat::is_nan`] is "maybe" on the entire line and surely false elsewhere.
//! `0 · ∞` products and `∞ / ∞` quotients of bounds are ignored (a bound at infinity means
//! "unbounded"). A divisor interval containing 0 gives the entire line.
//!
//! ## Masks and control flow
//!
//! Interval comparisons are three-valued: `a < b` is surely true iff `a.hi < b.lo`, surely
//! false iff `a.lo >= b.hi`, else "maybe". [`anysl_core::Exec`] runs both arms of a "maybe"
//! branch and blends with the hull; a loop that stays "maybe" stops after
//! [`anysl_core::INTERVAL_LOOP_LIMIT`] iterations with its variables widened to the entire
//! line ([`anysl_core::Blend::widen`]).
//!
//! [`ShadingFloat`]: anysl_core::ShadingFloat
//! [`ShadingFloat::UNIT_ROUNDOFF`]: anysl_core::ShadingFloat::UNIT_ROUNDOFF
//! [`ShadingFloat::c`]: anysl_core::ShadingFloat::c
//! [`ShadingFloat::from_lanes`]: anysl_core::ShadingFloat::from_lanes
//! [`ShadingFloat::is_nan`]: anysl_core::ShadingFloat::is_nan
#![warn(missing_docs)]

mod bits;
mod dual;
mod interval;
mod mask;
mod name;
mod round;

pub use bits::IBits;
pub use dual::Dual;
pub use interval::Interval;
pub use mask::IMask;
