//! A renderer that is not part of this crate: an analytic sphere, no BVH, no packets — just a
//! [`ShadingContext`] for its own tiny types. It shows what AnySL's type replacement buys a
//! renderer author:
//!
//! 1. the shader renders with plain `f32`;
//! 2. with `Dual<f32>` the *same code* — camera, intersection and shader — carries
//!    screen-space derivatives: seed the pixel coordinates with ∂x = (1, 0), ∂y = (0, 1) and
//!    every global, and the shaded colour, knows how it changes per pixel;
//! 3. with `Interval<f32>` the pixel coordinates become the ranges of a whole image tile, and
//!    the result bounds the shader's output over every point of the tile.
//!
//! Run with `cargo run -p anysl-renderers --example minimal_renderer`.

use anysl_ad::{Dual, Interval};
use anysl_core::{
    run_illuminance, sum_ambient, Color, Exec, Globals, LightQuery, ShadingContext, ShadingFloat, SurfaceShader, Vec3,
};
use anysl_shaders::{table1_lights, Light, Surface};

const SIZE: f64 = 64.0;

/// The renderer's context: the globals of the points and the lights (no shadows).
struct Tiny<'a, F: ShadingFloat> {
    globals: Globals<F>,
    lights: &'a [Light],
}

impl<F: ShadingFloat> ShadingContext<F> for Tiny<'_, F> {
    fn globals(&self) -> &Globals<F> {
        &self.globals
    }
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        e: &mut Exec<F>,
        q: LightQuery<'_, F>,
        body: B,
    ) {
        run_illuminance(self.lights, e, q, |_, _, _| None, body);
    }
    fn ambient(&mut self, e: &Exec<F>) -> Color<F> {
        sum_ambient(self.lights, e, self.globals.P)
    }
    fn trace(&mut self, _e: &Exec<F>, _p: Vec3<F>, _dir: Vec3<F>) -> Color<F> {
        Color::c(0.5, 0.5, 0.5)
    }
}

/// Camera ray through image point `(x, y)` and its hit on the unit sphere, written once over
/// `F` (the camera and sphere of the AnySL paper's Table 1). Returns the lanes that hit.
fn hit_sphere<F: ShadingFloat>(x: F, y: F) -> (F::Mask, Globals<F>) {
    let k = F::c(2.0 / SIZE);
    let (sx, sy) = ((x * k - F::c(1.0)) * F::c(0.375), (F::c(1.0) - y * k) * F::c(0.375));
    let d = Vec3::new(sx, sy, F::c(-1.0)).normalize();
    let o = Vec3::c(0.0, 0.0, 3.0);
    let b = o.dot(d);
    let q = o - d * b;
    let h = F::c(1.0) - q.dot(q);
    let hit = h.gt(F::c(0.0));
    let t = -b - h.max(F::c(0.0)).sqrt();
    let p = o + d * t;
    let tau = F::c(std::f64::consts::TAU);
    let s = (-p.z).atan2(p.x) / tau + F::c(0.5);
    let tt = p.y.max(F::c(-1.0)).min(F::c(1.0)).acos() / F::c(std::f64::consts::PI);
    let zero = F::c(0.0);
    let globals = Globals {
        P: p,
        N: p,
        Ng: p,
        I: p - o,
        E: o,
        s,
        t: tt,
        u: s,
        v: tt,
        du: zero,
        dv: zero,
        dPdu: Vec3::new(-p.z, zero, p.x) * tau,
        dPdv: Vec3::new(p.x * p.y, p.y * p.y - F::c(1.0), p.z * p.y) * F::c(std::f64::consts::PI),
        Cs: Color::c(1.0, 1.0, 1.0),
        Os: Color::c(1.0, 1.0, 1.0),
    };
    (hit, globals)
}

/// Shades the sphere at image point `(x, y)` with any number type.
fn shade<F: ShadingFloat>(shader: &Surface, lights: &[Light], x: F, y: F) -> Color<F> {
    let (hit, globals) = hit_sphere(x, y);
    let mut ctx = Tiny { globals, lights };
    let mut e = Exec::with_mask(hit);
    Color::select(hit, shader.shade(&mut ctx, &mut e).Ci, Color::zero())
}

fn main() {
    let shader = Surface::by_name("checker").expect("checker is in the collection");
    let lights = table1_lights();

    // 1. f32: a coarse picture of the luminance.
    let ramp = b" .:-=+*#%@";
    for row in (0..64).step_by(4) {
        let line: String = (0..64)
            .step_by(2)
            .map(|col| {
                let c = shade::<f32>(&shader, &lights, col as f32 + 0.5, row as f32 + 0.5);
                let l = c.luminance().clamp(0.0, 0.999);
                ramp[(l * ramp.len() as f32) as usize] as char
            })
            .collect();
        println!("{line}");
    }

    // 2. Dual<f32>: derivatives of the shaded colour per pixel, against finite differences.
    let (x, y) = (30.5f32, 40.5f32);
    let c = shade(&shader, &lights, Dual::seed_x(x), Dual::seed_y(y));
    let fd = (shade::<f32>(&shader, &lights, x + 0.25, y).g - shade::<f32>(&shader, &lights, x - 0.25, y).g) / 0.5;
    println!("pixel ({x}, {y}): Ci.g = {:.4}, ∂Ci.g/∂x = {:.5} (finite difference {fd:.5})", c.g.val, c.g.ddx);
    let (_, g) = hit_sphere(Dual::seed_x(x), Dual::seed_y(y));
    println!("  ∂s/∂x = {:.5}, ∂t/∂y = {:.5}", g.s.ddx, g.t.ddy);

    // 3. Interval<f32>: one evaluation bounds the shader over a whole 8×8 tile.
    let (x0, y0) = (24.0f32, 24.0f32);
    let tile = |lo: f32| Interval::new(lo, lo + 8.0);
    let bound = shade(&shader, &lights, tile(x0), tile(y0));
    println!("tile [{x0}, {}]×[{y0}, {}]: Ci.g ∈ [{:.4}, {:.4}]", x0 + 8.0, y0 + 8.0, bound.g.lo(), bound.g.hi());
    let mut samples = 0;
    for j in 0..=16 {
        for i in 0..=16 {
            let (px, py) = (x0 + i as f32 * 0.5, y0 + j as f32 * 0.5);
            let v = shade::<f32>(&shader, &lights, px, py).g;
            assert!(bound.g.lo() <= v && v <= bound.g.hi(), "sample ({px}, {py}) = {v} outside the bound");
            samples += 1;
        }
    }
    println!("  all {samples} point samples of the tile lie inside the bound");
}
