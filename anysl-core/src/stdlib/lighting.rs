//! Built-in illumination functions over the [`ShadingContext`]: RSL `ambient`, `diffuse`,
//! `specular`, `phong` and `specularbrdf`. Each is an `illuminance` loop written once.

use crate::context::ShadingContext;
use crate::exec::Exec;
use crate::float::ShadingFloat;
use crate::light::LightQuery;
use crate::vec::{Color, Vec3};

/// RSL `ambient()`.
#[inline(always)]
#[must_use]
pub fn ambient<F: ShadingFloat, C: ShadingContext<F>>(ctx: &mut C, e: &Exec<F>) -> Color<F> {
    ctx.ambient(e)
}

/// RSL `diffuse(N)`: `Σ Cl · max(0, normalize(L)·N)` over lights in the hemisphere of `N`.
#[inline(always)]
#[must_use]
pub fn diffuse<F: ShadingFloat, C: ShadingContext<F>>(ctx: &mut C, e: &mut Exec<F>, n: Vec3<F>) -> Color<F> {
    let p = ctx.globals().P;
    let mut c = Color::zero();
    ctx.illuminance(
        e,
        LightQuery::hemisphere(p, n),
        #[inline(always)]
        |e, l, cl| {
            let w = l.normalize().dot(n).max(F::c(0.0));
            e.update(&mut c, |c| cl.mul_add(w, c));
        },
    );
    c
}

/// `(diffuse(N), specular(N, V, roughness))` in one light loop: each light is evaluated and
/// `L` normalized once for both sums (what `plastic`-like shaders need). The hemisphere of
/// `N` that `illuminance(P, N, π/2)` would test is already in the body — `max(0, L·N)` and the
/// `N·L > 0` condition of the highlight give exactly zero for lights behind the surface — so
/// the loop runs without a cone test and gives the same sums as `diffuse` and `specular`.
#[inline(always)]
#[must_use]
pub fn diffuse_specular<F: ShadingFloat, C: ShadingContext<F>>(
    ctx: &mut C,
    e: &mut Exec<F>,
    n: Vec3<F>,
    v: Vec3<F>,
    roughness: F,
) -> (Color<F>, Color<F>) {
    let p = ctx.globals().P;
    let mut diff = Color::zero();
    let mut spec = Color::zero();
    let exponent = F::c(1.0) / roughness;
    let zero = F::c(0.0);
    ctx.illuminance(
        e,
        LightQuery::new("", p, None),
        #[inline(always)]
        |e, l, cl| {
            let lu = l.normalize();
            let ndl = lu.dot(n);
            e.update(&mut diff, |d| cl.mul_add(ndl.max(zero), d));
            // n·normalize(h) without forming normalize(h).
            let h = lu + v;
            let h2 = h.dot(h);
            let ndh = (n.dot(h) * F::select(h2.gt(zero), h2.rsqrt(), zero)).max(zero);
            let s = ndh.pow(exponent);
            e.update(&mut spec, |sp| cl.mul_add(F::select(ndl.gt(zero), s, zero), sp));
        },
    );
    (diff, spec)
}

/// Blinn's specular lobe for one light: `max(0, N·H)^(1/roughness)` with
/// `H = normalize(normalize(L) + V)`, zero where `N·L ≤ 0`.
#[inline(always)]
#[must_use]
pub fn specularbrdf<F: ShadingFloat>(l: Vec3<F>, n: Vec3<F>, v: Vec3<F>, roughness: F) -> F {
    let lu = l.normalize();
    let h = (lu + v).normalize();
    let ndh = n.dot(h).max(F::c(0.0));
    let s = ndh.pow(F::c(1.0) / roughness);
    F::select(n.dot(lu).gt(F::c(0.0)), s, F::c(0.0))
}

/// RSL `specular(N, V, roughness)`: `Σ Cl · specularbrdf(L, N, V, roughness)`.
#[inline(always)]
#[must_use]
pub fn specular<F: ShadingFloat, C: ShadingContext<F>>(
    ctx: &mut C,
    e: &mut Exec<F>,
    n: Vec3<F>,
    v: Vec3<F>,
    roughness: F,
) -> Color<F> {
    let p = ctx.globals().P;
    let mut c = Color::zero();
    ctx.illuminance(
        e,
        LightQuery::hemisphere(p, n),
        #[inline(always)]
        |e, l, cl| {
            // The lobe outside the update closure: that closure is not always inlined, and
            // out of line it would compute every derivative of a dual number.
            let w = specularbrdf(l, n, v, roughness);
            e.update(&mut c, |c| cl.mul_add(w, c));
        },
    );
    c
}

/// RSL `phong(N, V, size)`: `Σ Cl · max(0, R·normalize(L))^size` with `R = reflect(-V, N)`.
#[inline(always)]
#[must_use]
pub fn phong<F: ShadingFloat, C: ShadingContext<F>>(
    ctx: &mut C,
    e: &mut Exec<F>,
    n: Vec3<F>,
    v: Vec3<F>,
    size: F,
) -> Color<F> {
    let p = ctx.globals().P;
    let r = super::math::reflect(-v, n);
    let mut c = Color::zero();
    ctx.illuminance(
        e,
        LightQuery::hemisphere(p, n),
        #[inline(always)]
        |e, l, cl| {
            let w = r.dot(l.normalize()).max(F::c(0.0)).pow(size);
            e.update(&mut c, |c| cl.mul_add(w, c));
        },
    );
    c
}
