//! Glass: Fresnel weights, which rays are traced, η → 1 and total internal reflection.

use anysl_core::prelude::*;
use anysl_core::PointContext;
use anysl_shaders::{table1_lights, Glass, Light};
use std::sync::OnceLock;

/// A [`PointContext`] that records every `trace` call (direction of lane 0).
struct Recording<'a> {
    inner: PointContext<'a, f64, Light>,
    traced: Vec<[f64; 3]>,
}

impl ShadingContext<f64> for Recording<'_> {
    fn globals(&self) -> &Globals<f64> {
        self.inner.globals()
    }
    fn illuminance<B: FnMut(&mut Exec<f64>, Vec3<f64>, Color<f64>)>(
        &mut self,
        e: &mut Exec<f64>,
        q: LightQuery<'_, f64>,
        body: B,
    ) {
        self.inner.illuminance(e, q, body);
    }
    fn ambient(&mut self, e: &Exec<f64>) -> Color<f64> {
        self.inner.ambient(e)
    }
    fn trace(&mut self, e: &Exec<f64>, p: Vec3<f64>, dir: Vec3<f64>) -> Color<f64> {
        assert!(e.mask(), "trace called for a dead lane");
        self.traced.push(dir.lane(0));
        self.inner.trace(e, p, dir)
    }
}

/// Shades `glass` at the origin with normal +z and incident direction `i`.
fn shade(glass: &Glass, i: [f64; 3]) -> (SurfaceOutput<f64>, Vec<[f64; 3]>, PointContext<'static, f64, Light>) {
    static LIGHTS: OnceLock<Vec<Light>> = OnceLock::new();
    let lights = LIGHTS.get_or_init(table1_lights).as_slice();
    let mut g = Globals::<f64>::unit_square(0.5, 0.5);
    g.I = Vec3::from_array(i);
    g.E = g.P - g.I;
    let mut ctx = Recording { inner: PointContext::new(g, lights), traced: Vec::new() };
    let out = glass.shade(&mut ctx, &mut Exec::new());
    (out, ctx.traced, PointContext::new(g, lights))
}

fn norm(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / l)
}

#[test]
fn entering_glass_traces_reflection_and_refraction() {
    let glass = Glass::default();
    let (out, traced, _) = shade(&glass, [0.5, 0.0, -1.0]);
    assert_eq!(traced.len(), 2, "reflection and refraction");
    let i = norm([0.5, 0.0, -1.0]);
    assert!((traced[0][0] - i[0]).abs() < 1e-12 && (traced[0][2] + i[2]).abs() < 1e-12, "mirror direction");
    // Refraction bends towards the normal: |sin| shrinks by 1/eta.
    let t = norm(traced[1]);
    assert!((t[0] - i[0] / 1.5).abs() < 1e-12 && t[2] < 0.0, "Snell: {t:?}");
    assert_eq!(out.Oi.lane(0), [1.0; 3]);
    assert!(out.Ci.lane(0).iter().all(|c| c.is_finite() && *c > 0.0));
}

#[test]
fn total_internal_reflection_skips_the_refraction_ray() {
    let glass = Glass { Ks: 0.0, ..Glass::default() };
    // Leaving the glass (I·N > 0) at 60° > asin(1/1.5) ≈ 41.8°: total internal reflection.
    let a = 60f64.to_radians();
    let (out, traced, mut sky) = shade(&glass, [a.sin(), 0.0, a.cos()]);
    assert_eq!(traced.len(), 1, "only the reflection ray: {traced:?}");
    assert!((traced[0][2] + a.cos()).abs() < 1e-12, "mirrored back inside");
    // kr = 1: Ci is exactly the reflected colour.
    let refl = sky.trace(&Exec::new(), Vec3::zero(), Vec3::from_array(traced[0])).lane(0);
    let ci = out.Ci.lane(0);
    assert!((0..3).all(|k| (ci[k] - refl[k]).abs() < 1e-12), "{ci:?} vs {refl:?}");
    // Below the critical angle, leaving the glass refracts again.
    let b = 30f64.to_radians();
    let (_, traced, _) = shade(&glass, [b.sin(), 0.0, b.cos()]);
    assert_eq!(traced.len(), 2);
}

#[test]
fn eta_one_is_invisible_glass() {
    let glass = Glass { Ks: 0.0, eta: 1.0, ..Glass::default() };
    let i = [0.3, -0.2, -1.0];
    let (out, traced, mut sky) = shade(&glass, i);
    // kr = 0: no reflection ray; the refraction ray goes straight on.
    assert_eq!(traced.len(), 1, "{traced:?}");
    let t = norm(traced[0]);
    let iu = norm(i);
    assert!((0..3).all(|k| (t[k] - iu[k]).abs() < 1e-12), "{t:?} vs {iu:?}");
    let behind = sky.trace(&Exec::new(), Vec3::zero(), Vec3::from_array(iu)).lane(0);
    let ci = out.Ci.lane(0);
    assert!((0..3).all(|k| (ci[k] - behind[k]).abs() < 1e-12));
    // Approaching η = 1 continuously: reflection vanishes like ((η-1)/(η+1))².
    let mut last = f64::INFINITY;
    for eta in [1.5, 1.1, 1.01, 1.001] {
        let f = fresnel(Vec3::<f64>::from_array(i), Vec3::c(0.0, 0.0, 1.0), 1.0 / eta);
        assert!(f.kr < last && f.kr >= 0.0);
        last = f.kr;
    }
    assert!(last < 1e-5);
}
