//! The *scalar* renderer (Manta-like): one ray at a time, scanline by scanline, in `f32`.
//! Every camera ray carries ray differentials (∂origin/∂x = 0 for the pinhole, ∂dir/∂x,
//! ∂dir/∂y); at the hit they are transferred to the tangent plane to give ∂P/∂x, ∂P/∂y and,
//! through the triangle's barycentric derivatives, ∂N, ∂s, ∂t. A shader whose metadata says
//! `uses_derivatives` is then shaded with `Dual<f32>` seeded with them, every other shader
//! (and every shader when [`RenderOptions::derivatives`] is off) with plain `f32`.

use super::{render_bands, sample_offset, RenderOptions};
use crate::image::Image;
use crate::scene::Scene;
use crate::shading::{shade_lanes, Depth, FilteredShading, Lanes, LightTables, Tracer};
use anysl_ad::Dual;
use anysl_core::{Color, LightShader, ShadingFloat, SurfaceShader};

/// Renders `scene` one ray at a time; see the module docs.
#[must_use]
pub fn render_scalar<S, L>(scene: &Scene<S, L>, opts: &RenderOptions) -> Image
where
    S: SurfaceShader,
    L: LightShader,
{
    render_scalar_as::<f32, Dual<f32>, S, L>(scene, opts)
}

/// The scalar renderer with other number types: `P` shades plain points, `D` the points of
/// shaders that use derivatives (`render_scalar_as::<f64, Dual<f64>, _, _>` is the f64
/// reference of [`render_scalar`]).
///
/// # Panics
/// When `P` or `D` has more than one lane.
#[must_use]
pub fn render_scalar_as<P, D, S, L>(scene: &Scene<S, L>, opts: &RenderOptions) -> Image
where
    P: ShadingFloat,
    D: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    assert!(P::LANES == 1 && D::LANES == 1, "the scalar renderer shades one point at a time");
    let cam = &scene.camera;
    let (width, height) = (cam.width(), cam.height());
    // Shader metadata is looked up once per render, not per ray.
    let wants_derivs = FilteredShading::flags(&scene.surfaces, opts.derivatives);
    let n = opts.grid();
    let weight = 1.0 / (n * n) as f32;
    let footprint = 1.0 / n as f32;
    let light_data = LightTables::of::<P, _, _>(scene);
    let tracer = Tracer::new(scene, opts.shadows, &light_data);
    let label = format!("scalar {}", P::NAME);

    render_bands(width, height, 1, opts, &label, |y, row| {
        for (x, pixel) in row.iter_mut().enumerate() {
            let mut acc = [0.0f32; 3];
            for k in 0..n * n {
                let (ox, oy) = sample_offset(k, n);
                let ray = cam.primary_ray(x as f32 + ox, y as f32 + oy, footprint);
                let (o, d) = (ray.origin, ray.dir);
                let dirs = [d];
                let c = match scene.intersect_camera(o, d, ray.tmin, ray.tmax) {
                    None => {
                        let lanes = Lanes { hits: &[Default::default()], dirs: &dirs, active: 1, hit: 0, camera: true };
                        to_rgb(shade_lanes::<P, S, L>(tracer, &lanes, Depth::default()))
                    }
                    Some(h) => {
                        let hits = [scene.surface_hit(&h, o, d, Some(ray.differential()))];
                        let lanes = Lanes { hits: &hits, dirs: &dirs, active: 1, hit: 1, camera: true };
                        if wants_derivs[hits[0].surface as usize] {
                            to_rgb(shade_lanes::<D, S, L>(tracer, &lanes, Depth::default()))
                        } else {
                            to_rgb(shade_lanes::<P, S, L>(tracer, &lanes, Depth::default()))
                        }
                    }
                };
                for ch in 0..3 {
                    acc[ch] += c[ch];
                }
            }
            *pixel = acc.map(|v| v * weight);
        }
    })
}

#[inline(always)]
fn to_rgb<F: ShadingFloat>(c: Color<F>) -> [f32; 3] {
    [c.r.lane(0) as f32, c.g.lane(0) as f32, c.b.lane(0) as f32]
}
