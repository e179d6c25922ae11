//! The *pbrt-like* renderer: one camera ray at a time handed to an [`Integrator`], a closed
//! set dispatched by `match` (pbrt's style), with a fixed-seed random number generator per
//! pixel so that pictures do not depend on the thread count.
//!
//! - [`Integrator::Passive`] treats the surface shader as a **material**: it evaluates the
//!   shader for local quantities only and does its own lighting:
//!   - *base colour* = the shader's `Ci` with the scene's lights replaced by a single unit
//!     white probe light from the viewer-facing normal direction (`L = faceforward(N, I)`,
//!     `Cl = 1`), `ambient() = 0` and `trace()` returning black ([`ProbeContext`]); for a
//!     Lambertian shader that is `Kd · Cs`; it is premultiplied by opacity, as RSL `Ci` is;
//!   - *opacity* = the shader's `Oi` under the same probe;
//!   - *roughness* = the shader's `roughness` parameter if it has one; then a Blinn lobe
//!     with exponent `1 / roughness`, weighted by the shader's `Ks` (0 if it has none), is
//!     added for each light. (The probe's base colour already holds whatever the shader
//!     computes for a light along the normal, so specular shaders count a little twice.)
//!
//!   Lighting: every light shader is evaluated at the hit for its `Cl` and `L`; ambient
//!   lights add `base · Cl`; local and distant lights add `base · Cl · max(0, Nf·L̂)` (the
//!   RSL `diffuse()` convention, no 1/π) when a shadow ray reaches them; one bounce of
//!   diffuse indirect light follows one cosine-distributed direction per pixel sample (so
//!   `spp` samples per pixel give `spp` indirect samples), lit directly at the bounce point
//!   or by the sky. Opacity composites what lies behind: `L + (1 − Oi) · behind`.
//! - [`Integrator::Active`] runs the shader's own `illuminance` / `ambient` / `trace` through
//!   the same [`SceneContext`](crate::shading::SceneContext) as the other renderers
//!   (in `f32`, `Dual<f32>` for shaders that use derivatives), so its picture matches theirs.
//!
//! Both integrators evaluate a shader that uses derivatives with `Dual<f32>` seeded from the
//! camera ray's differentials (unless [`RenderOptions::derivatives`] is off); the passive
//! material does so too, so its base colour is filtered like the other renderers' pictures.

use super::{render_bands, sample_offset, RenderOptions};
use crate::camera::RayDifferential;
use crate::image::Image;
use crate::scene::{Scene, SurfaceHit};
use crate::shading::{
    gather_globals, ray_epsilon, shade_lanes_by, Depth, FilteredShading, Lanes, LightTables, ProbeContext, Tracer,
    MAX_LAYERS,
};
use anysl_ad::Dual;
use anysl_core::points::SplitMix64;
use anysl_core::{Emission, Exec, LightShader, ParamValue, Spaces, SurfaceShader, Vec3};
use glam::Vec3A;

/// How the pbrt-like renderer computes the light leaving a surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// The shader as a passive material; the integrator lights it (see the module docs).
    Passive,
    /// The shader's own lighting, as in the other renderers.
    Active,
}

/// What the passive integrator reads from a shader's parameters, once per render.
#[derive(Clone, Copy, Debug)]
struct MaterialParams {
    roughness: Option<f32>,
    ks: f32,
}

fn float_param<S: SurfaceShader>(s: &S, name: &str) -> Option<f32> {
    match s.param(name) {
        Some(ParamValue::Float(v)) => Some(v as f32),
        _ => None,
    }
}

/// Renders `scene` with the pbrt-like renderer and the given integrator.
#[must_use]
pub fn render_pbrt<S, L>(scene: &Scene<S, L>, opts: &RenderOptions, integrator: Integrator) -> Image
where
    S: SurfaceShader,
    L: LightShader,
{
    let cam = &scene.camera;
    let (width, height) = (cam.width(), cam.height());
    let params: Vec<MaterialParams> = scene
        .surfaces
        .iter()
        .map(|s| MaterialParams {
            roughness: float_param(s, "roughness").filter(|r| *r > 0.0),
            ks: float_param(s, "Ks").unwrap_or(0.0),
        })
        .collect();
    let n = opts.grid();
    let weight = 1.0 / (n * n) as f32;
    let footprint = 1.0 / n as f32;
    let light_data = LightTables::of::<f32, _, _>(scene);
    let tracer = Tracer::new(scene, opts.shadows, &light_data);
    let derivs = FilteredShading::flags(&scene.surfaces, opts.derivatives);
    let filtered = FilteredShading { uses_derivatives: &derivs };
    let passive = Passive { scene, params: &params, shadows: opts.shadows, derivs: &derivs };
    let label = match integrator {
        Integrator::Passive => "pbrt passive",
        Integrator::Active => "pbrt active",
    };

    render_bands(width, height, 16, opts, label, |y0, pixels| {
        for (k_px, pixel) in pixels.iter_mut().enumerate() {
            let (x, y) = ((k_px as u32) % width, y0 + (k_px as u32) / width);
            let mut rng =
                SplitMix64(opts.seed ^ (u64::from(y) << 32 | u64::from(x)).wrapping_mul(0x9E37_79B9_7F4A_7C15));
            let mut acc = Vec3A::ZERO;
            for k in 0..n * n {
                let (ox, oy) = sample_offset(k, n);
                let ray = cam.primary_ray(x as f32 + ox, y as f32 + oy, footprint);
                let (o, d, diff) = (ray.origin, ray.dir, ray.differential());
                acc += match integrator {
                    Integrator::Active => li_active(tracer, filtered, o, d, diff, (ray.tmin, ray.tmax)),
                    Integrator::Passive => passive.li(o, d, Some(diff), 0, 0, true, &mut rng),
                };
            }
            *pixel = (acc * weight).to_array();
        }
    })
}

/// The active integrator: the shader's own lighting for one camera ray.
fn li_active<S: SurfaceShader, L: LightShader>(
    tracer: Tracer<'_, S, L>,
    how: FilteredShading<'_>,
    o: Vec3A,
    d: Vec3A,
    diff: RayDifferential,
    (tmin, tmax): (f32, f32),
) -> Vec3A {
    let scene = tracer.scene;
    let dirs = [d];
    let hit = scene.intersect_camera(o, d, tmin, tmax);
    let hits = [hit.map(|h| scene.surface_hit(&h, o, d, Some(diff))).unwrap_or_default()];
    let lanes = Lanes { hits: &hits, dirs: &dirs, active: 1, hit: u32::from(hit.is_some()), camera: true };
    let c = shade_lanes_by::<f32, S, L, _>(tracer, &lanes, Depth::default(), how);
    Vec3A::new(c.r, c.g, c.b)
}

/// The passive integrator's state.
struct Passive<'a, S, L> {
    scene: &'a Scene<S, L>,
    params: &'a [MaterialParams],
    shadows: bool,
    /// Per surface shader: evaluate it with `Dual<f32>`.
    derivs: &'a [bool],
}

impl<S: SurfaceShader, L: LightShader> Passive<'_, S, L> {
    /// Radiance along `o + t·d`; `bounce` 0 gathers one indirect sample, `layer` counts
    /// transparent surfaces passed.
    #[allow(clippy::too_many_arguments)]
    fn li(
        &self,
        o: Vec3A,
        d: Vec3A,
        diff: Option<RayDifferential>,
        bounce: u32,
        layer: u32,
        camera: bool,
        rng: &mut SplitMix64,
    ) -> Vec3A {
        let scene = self.scene;
        let tmin = if camera && layer == 0 { 0.0 } else { ray_epsilon(o) };
        let found = if camera && layer == 0 {
            scene.intersect_camera(o, d, tmin, f32::INFINITY)
        } else {
            scene.intersect(o, d, tmin, f32::INFINITY)
        };
        let Some(hit) = found else {
            return if camera && !scene.sky.visible_to_camera { Vec3A::ZERO } else { Vec3A::from(scene.sky.color(d)) };
        };
        let sh = scene.surface_hit(&hit, o, d, diff);
        let (base, opacity) = self.material(&sh);
        let nf = if sh.n.dot(sh.i) < 0.0 { sh.n } else { -sh.n };
        let mut radiance = self.direct(&sh, nf, base);
        if bounce == 0 {
            let dir = cosine_direction(nf, rng);
            radiance += base * self.li(sh.p, dir, None, 1, layer, false, rng);
        }
        if opacity.min_element() < 1.0 && layer < MAX_LAYERS {
            let behind = self.li(sh.p, d, None, bounce, layer + 1, camera, rng);
            radiance += (Vec3A::ONE - opacity) * behind;
        }
        radiance
    }

    /// Base colour and opacity: the shader under the probe light (in `Dual<f32>` when it
    /// uses derivatives; hits of secondary rays carry none).
    fn material(&self, sh: &SurfaceHit) -> (Vec3A, Vec3A) {
        let shader = &self.scene.surfaces[sh.surface as usize];
        let spaces = self.scene.surface_spaces.get(sh.surface as usize).unwrap_or(Spaces::standard());
        if self.derivs[sh.surface as usize] {
            let mut ctx = ProbeContext { globals: gather_globals::<Dual<f32>>(std::slice::from_ref(sh), 1, 0), spaces };
            let out = shader.shade(&mut ctx, &mut Exec::<Dual<f32>>::new());
            let (ci, oi) = (out.Ci, out.Oi);
            (Vec3A::new(ci.r.val, ci.g.val, ci.b.val), Vec3A::new(oi.r.val, oi.g.val, oi.b.val))
        } else {
            let mut ctx = ProbeContext { globals: gather_globals::<f32>(std::slice::from_ref(sh), 1, 0), spaces };
            let out = shader.shade(&mut ctx, &mut Exec::<f32>::new());
            (Vec3A::new(out.Ci.r, out.Ci.g, out.Ci.b), Vec3A::new(out.Oi.r, out.Oi.g, out.Oi.b))
        }
    }

    /// Direct light from the scene's lights (with shadow rays) and the specular lobe.
    fn direct(&self, sh: &SurfaceHit, nf: Vec3A, base: Vec3A) -> Vec3A {
        let p = sh.p;
        let ps = Vec3::<f32>::new(p.x, p.y, p.z);
        let view = -sh.i.normalize_or_zero();
        let params = self.params[sh.surface as usize];
        let eps = ray_epsilon(p);
        let mut diffuse = Vec3A::ZERO;
        let mut specular = Vec3A::ZERO;
        for light in self.scene.lights_for(sh.surface) {
            let out = light.light::<f32>(&mut Exec::new(), ps);
            if !out.lit {
                continue;
            }
            let cl = Vec3A::new(out.cl.r, out.cl.g, out.cl.b);
            let to_light = -Vec3A::new(out.l.x, out.l.y, out.l.z);
            let (dir, tmax) = match out.emission {
                Emission::Ambient => {
                    diffuse += cl;
                    continue;
                }
                Emission::Local => {
                    let dist = to_light.length();
                    if dist <= 2.0 * eps {
                        continue;
                    }
                    (to_light / dist, dist - eps)
                }
                Emission::Distant => match to_light.try_normalize() {
                    Some(dir) => (dir, f32::INFINITY),
                    None => continue,
                },
            };
            let cos = nf.dot(dir);
            if cos <= 0.0 || (self.shadows && self.scene.accel().occluded(p, dir, eps, tmax)) {
                continue;
            }
            diffuse += cl * cos;
            if let Some(r) = params.roughness {
                let h = (dir + view).normalize_or_zero();
                specular += cl * (params.ks * nf.dot(h).max(0.0).powf(1.0 / r));
            }
        }
        base * diffuse + specular
    }
}

/// A cosine-distributed direction around `n`.
fn cosine_direction(n: Vec3A, rng: &mut SplitMix64) -> Vec3A {
    let (u1, u2) = (rng.uniform(0.0, 1.0) as f32, rng.uniform(0.0, 1.0) as f32);
    let r = u1.sqrt();
    let phi = std::f32::consts::TAU * u2;
    let (a, b) = n.any_orthonormal_pair();
    (a * (r * phi.cos()) + b * (r * phi.sin()) + n * (1.0 - u1).max(0.0).sqrt()).normalize_or(n)
}
