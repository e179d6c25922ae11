//! RSL `spline` over float, colour and point knots, with the standard bases.

use super::math::clamp;
use crate::float::{Blend, ShadingFloat};
use core::ops::{Add, Mul};

/// A spline basis: its 4×4 matrix and the knot step between segments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplineBasis {
    /// Basis matrix (rows multiply `[t³, t², t, 1]`).
    pub m: [[f64; 4]; 4],
    /// Knots advanced per segment.
    pub step: usize,
}

impl SplineBasis {
    /// Catmull-Rom (interpolating; RSL's default).
    pub const CATMULL_ROM: Self = Self {
        m: [[-0.5, 1.5, -1.5, 0.5], [1.0, -2.5, 2.0, -0.5], [-0.5, 0.0, 0.5, 0.0], [0.0, 1.0, 0.0, 0.0]],
        step: 1,
    };
    /// Cubic Bézier.
    pub const BEZIER: Self = Self {
        m: [[-1.0, 3.0, -3.0, 1.0], [3.0, -6.0, 3.0, 0.0], [-3.0, 3.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]],
        step: 3,
    };
    /// Uniform cubic B-spline.
    pub const BSPLINE: Self = Self {
        m: [
            [-1.0 / 6.0, 0.5, -0.5, 1.0 / 6.0],
            [0.5, -1.0, 0.5, 0.0],
            [-0.5, 0.0, 0.5, 0.0],
            [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0],
        ],
        step: 1,
    };
    /// Hermite (knots are point, tangent, point, tangent, …).
    pub const HERMITE: Self = Self {
        m: [[2.0, 1.0, -2.0, 1.0], [-3.0, -2.0, 3.0, -1.0], [0.0, 1.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]],
        step: 2,
    };
    /// Power basis (knots are polynomial coefficients).
    pub const POWER: Self =
        Self { m: [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]], step: 4 };
    /// Piecewise linear between the inner knots (first and last knot ignored, like
    /// Catmull-Rom).
    pub const LINEAR: Self =
        Self { m: [[0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], [0.0, -1.0, 1.0, 0.0], [0.0, 1.0, 0.0, 0.0]], step: 1 };

    /// The basis called `name` in RSL (`"catmull-rom"`, `"bezier"`, `"bspline"`, `"hermite"`,
    /// `"power"`, `"linear"`).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "catmull-rom" | "catrom" => Self::CATMULL_ROM,
            "bezier" => Self::BEZIER,
            "bspline" | "b-spline" => Self::BSPLINE,
            "hermite" => Self::HERMITE,
            "power" => Self::POWER,
            "linear" => Self::LINEAR,
            _ => return None,
        })
    }

    /// Number of segments for `n` knots (0 if there are fewer than 4).
    #[must_use]
    pub fn segments(&self, n: usize) -> usize {
        if n < 4 {
            0
        } else {
            (n - 4) / self.step + 1
        }
    }
}

/// RSL `spline(basis, x, k0, k1, …)`: `x` in [0, 1] (clamped) maps across all segments.
/// Works per lane: each lane may fall in a different segment (segments are blended by
/// mask, so SIMD and intervals need no gather). Needs at least 4 knots; fewer gives the
/// first knot (or zero).
#[inline(always)]
#[must_use]
pub fn spline<F, T>(basis: &SplineBasis, x: F, knots: &[T]) -> T
where
    F: ShadingFloat,
    T: Blend<F> + Add<Output = T> + Mul<F, Output = T>,
{
    let nseg = basis.segments(knots.len());
    if nseg == 0 {
        return *knots.first().expect("spline needs at least one knot (the RSL checker requires four)");
    }
    let xs = clamp(x, F::c(0.0), F::c(1.0)) * F::c(nseg as f64);
    let seg = xs.floor().min(F::c((nseg - 1) as f64));
    let t = xs - seg;
    let (t2, t3) = (t * t, t * t * t);
    let m = &basis.m;
    // Everything here is inlined into the caller, so that parts of the result nobody reads
    // (e.g. derivatives) are not computed: the weights without `array::from_fn` (whose
    // closure stayed out of line), a segment as a function (a closure called from several
    // places stayed out of line).
    let wj = |j: usize| t3 * F::c(m[0][j]) + t2 * F::c(m[1][j]) + t * F::c(m[2][j]) + F::c(m[3][j]);
    let w = [wj(0), wj(1), wj(2), wj(3)];
    #[inline(always)]
    fn segment<F: ShadingFloat, T: Add<Output = T> + Mul<F, Output = T> + Copy>(
        knots: &[T],
        at: usize,
        w: &[F; 4],
    ) -> T {
        let k = &knots[at..at + 4];
        k[0] * w[0] + k[1] * w[1] + k[2] * w[2] + k[3] * w[3]
    }
    let mut result = segment(knots, 0, &w);
    for s in 1..nseg {
        let here = seg.ge(F::c(s as f64));
        // Only segments some lane needs are evaluated.
        if crate::float::Mask::any(here) {
            result = T::blend(here, segment(knots, s * basis.step, &w), result);
        }
    }
    result
}
