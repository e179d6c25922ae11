//! Derivatives: RSL `Du`, `Dv`, `Deriv`, `area`, `filterwidth`, `calculatenormal` and
//! `filterstep`, through the screen-space derivatives that dual numbers carry.
//!
//! With a number type that has no derivatives (`F::HAS_DERIVS == false`) every derivative is
//! 0, `area` and `filterwidth` are 0 and `filterstep` falls back to `step`.
//! Du/Dv convert the screen-space derivatives of a value into derivatives with respect to
//! the surface parameters u and v by the chain rule: with J the Jacobian of (u, v) over
//! screen (x, y), `(∂f/∂u, ∂f/∂v) = (∂f/∂x, ∂f/∂y) · J⁻¹`. Where J is singular (no
//! derivatives, a degenerate parameterization) the result is 0, never NaN.

use super::math::{clamp, step};
use crate::float::ShadingFloat;
use crate::globals::Globals;
use crate::vec::Vec3;

/// Inverse-Jacobian weights `(a, b, c, d)` with `∂/∂u = a·∂/∂x + b·∂/∂y`,
/// `∂/∂v = c·∂/∂x + d·∂/∂y`.
#[inline(always)]
fn uv_weights<F: ShadingFloat>(g: &Globals<F>) -> (F, F, F, F) {
    let z = F::c(0.0);
    let (ux, uy, vx, vy) = (g.u.dx().value(), g.u.dy().value(), g.v.dx().value(), g.v.dy().value());
    let det = ux * vy - uy * vx;
    let singular = det.eq(z) | det.is_nan();
    let inv = F::select(singular, z, F::c(1.0) / F::select(singular, F::c(1.0), det));
    (vy * inv, -vx * inv, -uy * inv, ux * inv)
}

/// RSL `Du(f)`: ∂f/∂u (a value without further derivatives).
#[inline(always)]
#[must_use]
pub fn du<F: ShadingFloat>(g: &Globals<F>, f: F) -> F {
    if !F::HAS_DERIVS {
        return F::c(0.0);
    }
    let (a, b, _, _) = uv_weights(g);
    f.dx().value() * a + f.dy().value() * b
}

/// RSL `Dv(f)`: ∂f/∂v.
#[inline(always)]
#[must_use]
pub fn dv<F: ShadingFloat>(g: &Globals<F>, f: F) -> F {
    if !F::HAS_DERIVS {
        return F::c(0.0);
    }
    let (_, _, c, d) = uv_weights(g);
    f.dx().value() * c + f.dy().value() * d
}

/// `Du` of a triple.
#[inline(always)]
#[must_use]
pub fn du_vec<F: ShadingFloat>(g: &Globals<F>, p: Vec3<F>) -> Vec3<F> {
    p.map(|c| du(g, c))
}

/// `Dv` of a triple.
#[inline(always)]
#[must_use]
pub fn dv_vec<F: ShadingFloat>(g: &Globals<F>, p: Vec3<F>) -> Vec3<F> {
    p.map(|c| dv(g, c))
}

/// RSL `Deriv(num, den)`: `Du(num)/Du(den) + Dv(num)/Dv(den)`, each term dropped where its
/// denominator is 0.
#[inline(always)]
#[must_use]
pub fn deriv<F: ShadingFloat>(g: &Globals<F>, num: F, den: F) -> F {
    let z = F::c(0.0);
    let q = |n: F, d: F| F::select(d.eq(z), z, n / F::select(d.eq(z), F::c(1.0), d));
    q(du(g, num), du(g, den)) + q(dv(g, num), dv(g, den))
}

/// RSL `area(P)`: the area of the pixel footprint, `|∂P/∂x × ∂P/∂y|`.
#[inline(always)]
#[must_use]
pub fn area<F: ShadingFloat>(p: Vec3<F>) -> F {
    if !F::HAS_DERIVS {
        return F::c(0.0);
    }
    let px = p.map(|c| c.dx().value());
    let py = p.map(|c| c.dy().value());
    px.cross(py).length()
}

/// `filterwidth(x)`: how much `x` changes across a pixel, `|∂x/∂x| + |∂x/∂y|`.
#[inline(always)]
#[must_use]
pub fn filterwidth<F: ShadingFloat>(x: F) -> F {
    // Without derivatives the width is 0 — said here rather than left to constant folding,
    // which vector comparisons downstream (`filterstep`) do not get.
    if !F::HAS_DERIVS {
        return F::c(0.0);
    }
    x.dx().value().abs() + x.dy().value().abs()
}

/// `filterwidth` of a point: the square root of its footprint area.
#[inline(always)]
#[must_use]
pub fn filterwidth_point<F: ShadingFloat>(p: Vec3<F>) -> F {
    area(p).sqrt()
}

/// RSL `calculatenormal(P)`: `Du(P) × Dv(P)`; in screen terms `∂P/∂x × ∂P/∂y` oriented like
/// `dPdu × dPdv`. Zero without derivatives.
#[inline(always)]
#[must_use]
pub fn calculatenormal<F: ShadingFloat>(g: &Globals<F>, p: Vec3<F>) -> Vec3<F> {
    du_vec(g, p).cross(dv_vec(g, p))
}

/// RSL `filterstep(edge, x)`: `step(edge, x)` box-filtered over the pixel footprint of `x`
/// (a linear ramp of width `filterwidth(x)` centred on the edge). Where the width is 0 (no
/// derivatives) it is exactly `step`.
#[inline(always)]
#[must_use]
pub fn filterstep<F: ShadingFloat>(edge: F, x: F) -> F {
    if !F::HAS_DERIVS {
        return step(edge, x);
    }
    let w = filterwidth(x);
    let z = F::c(0.0);
    let has = w.gt(z);
    let ramp = clamp((x.value() - edge.value()) / F::select(has, w, F::c(1.0)) + F::c(0.5), z, F::c(1.0));
    F::select(has, ramp, step(edge.value(), x.value()))
}

/// Two-edge `filterstep`: the filtered pulse `filterstep(e0, x) - filterstep(e1, x)`.
#[inline(always)]
#[must_use]
pub fn filteredpulse<F: ShadingFloat>(e0: F, e1: F, x: F) -> F {
    filterstep(e0, x) - filterstep(e1, x)
}
