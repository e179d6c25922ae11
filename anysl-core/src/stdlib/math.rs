//! Scalar and geometric built-ins (RenderMan Interface 3.2, §15.1–15.2).

use crate::float::ShadingFloat;
use crate::vec::Vec3;

/// π.
pub const PI: f64 = core::f64::consts::PI;

/// Float constant (shorthand for `F::c`).
#[inline(always)]
#[must_use]
pub fn k<F: ShadingFloat>(v: f64) -> F {
    F::c(v)
}

/// -1, 0 or 1 (0 for NaN).
#[inline(always)]
#[must_use]
pub fn sign<F: ShadingFloat>(x: F) -> F {
    let z = F::c(0.0);
    F::select(x.gt(z), F::c(1.0), F::select(x.lt(z), F::c(-1.0), z))
}

/// RSL `mod(a, b)`: `a - b·floor(a/b)`, result in [0, b) for b > 0. `mod(a, 0)` is 0.
#[inline(always)]
#[must_use]
pub fn fmod<F: ShadingFloat>(a: F, b: F) -> F {
    let z = F::c(0.0);
    let bz = b.eq(z);
    let bb = F::select(bz, F::c(1.0), b);
    let r = a - bb * (a / bb).floor();
    // Rounding can land exactly on b; fold it back so the result stays in [0, b).
    let r = F::select(r.ge(bb) & bb.gt(z), r - bb, r);
    F::select(bz, z, r)
}

/// Clamps `x` to `[lo, hi]`.
#[inline(always)]
#[must_use]
pub fn clamp<F: ShadingFloat>(x: F, lo: F, hi: F) -> F {
    x.max(lo).min(hi)
}

/// Linear interpolation `a + t·(b - a)` (RSL `mix(a, b, t)` is `(1-t)·a + t·b`).
#[inline(always)]
#[must_use]
pub fn mix<F: ShadingFloat>(a: F, b: F, t: F) -> F {
    a + t * (b - a)
}

/// 0 if `x < edge`, else 1.
#[inline(always)]
#[must_use]
pub fn step<F: ShadingFloat>(edge: F, x: F) -> F {
    F::select(x.lt(edge), F::c(0.0), F::c(1.0))
}

/// Hermite ramp from 0 at `e0` to 1 at `e1`; with `e0 == e1` it is `step(e0, x)` (no NaN).
#[inline(always)]
#[must_use]
pub fn smoothstep<F: ShadingFloat>(e0: F, e1: F, x: F) -> F {
    let w = e1 - e0;
    let degenerate = w.eq(F::c(0.0));
    let t = clamp((x - e0) / F::select(degenerate, F::c(1.0), w), F::c(0.0), F::c(1.0));
    let s = t * t * (F::c(3.0) - F::c(2.0) * t);
    F::select(degenerate, step(e0, x), s)
}

/// 1/√x ([`ShadingFloat::rsqrt`]).
#[inline(always)]
#[must_use]
pub fn inversesqrt<F: ShadingFloat>(x: F) -> F {
    x.rsqrt()
}

/// RSL `log(x, base)`.
#[inline(always)]
#[must_use]
pub fn log_base<F: ShadingFloat>(x: F, base: F) -> F {
    x.ln() / base.ln()
}

/// Degrees → radians.
#[inline(always)]
#[must_use]
pub fn radians<F: ShadingFloat>(deg: F) -> F {
    deg * F::c(PI / 180.0)
}

/// Radians → degrees.
#[inline(always)]
#[must_use]
pub fn degrees<F: ShadingFloat>(rad: F) -> F {
    rad * F::c(180.0 / PI)
}

/// `x·x`.
#[inline(always)]
#[must_use]
pub fn sqr<F: ShadingFloat>(x: F) -> F {
    x * x
}

/// Distance between two points.
#[inline(always)]
#[must_use]
pub fn distance<F: ShadingFloat>(a: Vec3<F>, b: Vec3<F>) -> F {
    (a - b).length()
}

/// Distance from `q` to the segment `p0`–`p1` (RSL `ptlined`).
#[inline(always)]
#[must_use]
pub fn ptlined<F: ShadingFloat>(p0: Vec3<F>, p1: Vec3<F>, q: Vec3<F>) -> F {
    let d = p1 - p0;
    let l2 = d.length_squared();
    let z = F::c(0.0);
    let t = clamp((q - p0).dot(d) / F::select(l2.eq(z), F::c(1.0), l2), z, F::c(1.0));
    distance(q, p0 + d * F::select(l2.eq(z), z, t))
}

/// Flips `n` to face against `i` as judged by `nref`: `sign(-i·nref)·n` (RSL `faceforward`);
/// when `i·nref == 0` (grazing), `n` is kept.
#[inline(always)]
#[must_use]
pub fn faceforward<F: ShadingFloat>(n: Vec3<F>, i: Vec3<F>, nref: Vec3<F>) -> Vec3<F> {
    let flip = i.dot(nref).gt(F::c(0.0));
    Vec3::select(flip, -n, n)
}

/// `faceforward(normalize(n), i, n)`, the shading normal of nearly every RSL surface, with
/// the flip folded into the normalization (see [`Vec3::normalize_signed`]): the same vector,
/// bit for bit, for less work.
#[inline(always)]
#[must_use]
pub fn faceforward_normalize<F: ShadingFloat>(n: Vec3<F>, i: Vec3<F>) -> Vec3<F> {
    n.normalize_signed(i.dot(n).gt(F::c(0.0)))
}

/// Mirror direction of `i` about `n` (`n` unit length).
#[inline(always)]
#[must_use]
pub fn reflect<F: ShadingFloat>(i: Vec3<F>, n: Vec3<F>) -> Vec3<F> {
    i - n * (F::c(2.0) * i.dot(n))
}

/// Refracted direction of `i` (unit) through a surface with normal `n` (unit, facing `i`),
/// `eta` = ratio of indices (outside / inside). Total internal reflection gives the zero
/// vector, as RSL specifies.
#[inline(always)]
#[must_use]
pub fn refract<F: ShadingFloat>(i: Vec3<F>, n: Vec3<F>, eta: F) -> Vec3<F> {
    let idotn = i.dot(n);
    let k = F::c(1.0) - eta * eta * (F::c(1.0) - idotn * idotn);
    let tir = k.lt(F::c(0.0));
    let t = i * eta - n * (eta * idotn + k.max(F::c(0.0)).sqrt());
    Vec3::select(tir, Vec3::zero(), t)
}

/// The result of RSL `fresnel`.
#[derive(Clone, Copy, Debug)]
pub struct Fresnel<F> {
    /// Reflected fraction.
    pub kr: F,
    /// Transmitted fraction (`1 - kr`).
    pub kt: F,
    /// Reflection direction.
    pub r: Vec3<F>,
    /// Refraction direction (zero under total internal reflection).
    pub t: Vec3<F>,
}

/// RSL `fresnel(I, N, eta, Kr, Kt [, R, T])`: unpolarized dielectric Fresnel factors
/// (Cook & Torrance 1982 form: with `c = |I·N|` and `g² = 1/eta² + c² - 1`,
/// `Kr = ½((g-c)/(g+c))²(1 + ((c(g+c)-1)/(c(g-c)+1))²)`). `I` need not be normalized.
/// Total internal reflection (`g² < 0`) and exact grazing incidence give `Kr = 1`.
#[inline(always)]
#[must_use]
pub fn fresnel<F: ShadingFloat>(i: Vec3<F>, n: Vec3<F>, eta: F) -> Fresnel<F> {
    let one = F::c(1.0);
    let zero = F::c(0.0);
    let iu = i.normalize();
    let c = iu.dot(n).abs().min(one);
    let inv_eta = one / eta;
    // (1/η² - 1) first: exactly 0 at η = 1, so that g = √(c²) = c and glass of index 1
    // reflects nothing (and the small difference keeps its bits elsewhere).
    let g2 = (inv_eta * inv_eta - one) + c * c;
    let tir = g2.lt(zero);
    let g = g2.max(zero).sqrt();
    let gpc = g + c;
    let gmc = g - c;
    let degenerate = gpc.le(zero) | tir;
    let safe_gpc = F::select(degenerate, one, gpc);
    let a = gmc / safe_gpc;
    let num = c * gpc - one;
    let den = c * gmc + one;
    let safe_den = F::select(den.eq(zero), one, den);
    let b = num / safe_den;
    let kr = (F::c(0.5) * a * a * (one + b * b)).min(one);
    let kr = F::select(degenerate, one, kr);
    Fresnel { kr, kt: one - kr, r: reflect(iu, n), t: refract(iu, n, eta) }
}

/// Rotates point `q` by `angle` radians about the axis through `p0` and `p1` (RSL `rotate`).
#[inline]
#[must_use]
pub fn rotate<F: ShadingFloat>(q: Vec3<F>, angle: F, p0: Vec3<F>, p1: Vec3<F>) -> Vec3<F> {
    let m = crate::vec::Matrix4::rotate(angle, p1 - p0);
    m.transform_vector(q - p0) + p0
}
