//! Depth passes for shadow maps: a frame whose `Display` is of type `"zfile"` or `"shadow"`
//! with mode `"z"` keeps, under the display's name in the run's texture store
//! ([`anysl_rt::texture::store`]), the camera-space depth of the nearest surface at each pixel
//! centre (infinity where there is none) with the frame's camera matrices. `MakeShadow` of that
//! name, or `shadow()` of it directly, reads it; no file is written.
//!
//! The depth is traced with one ray through each pixel centre, the same camera rays the
//! renderers shoot (so clipping planes and the screen window hold), ignoring surface shaders:
//! every primitive casts a shadow, as in a RenderMan depth pass without shading.

use crate::build::FrameDesc;
use anysl_renderers::{Camera, Projection, Scene};
use anysl_rt::texture::{store, DepthCamera, Map, MapKind, MipMap};

/// The depth map of `frame` seen by its camera at its resolution (crop window ignored).
#[must_use]
pub fn depth_map<S, L>(frame: &FrameDesc, scene: &Scene<S, L>) -> Map {
    let (w, h) = (frame.film.xres.max(1), frame.film.yres.max(1));
    let spec = &frame.camera;
    let camera = Camera::from_spec(spec, w, h);
    let w2c = spec.camera_to_world.inverse().as_dmat4();
    let mut depth = vec![f32::INFINITY; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let ray = camera.primary_ray(x as f32 + 0.5, y as f32 + 0.5, 0.0);
            if let Some(hit) = scene.intersect_camera(ray.origin, ray.dir, ray.tmin, ray.tmax) {
                let p = ray.origin + ray.dir * hit.t;
                let z = w2c.transform_point3(glam::DVec3::new(f64::from(p.x), f64::from(p.y), f64::from(p.z))).z;
                depth[(y * w + x) as usize] = z as f32;
            }
        }
    }
    let mut map = Map::texture(MipMap::new(w as usize, h as usize, 1, depth));
    map.kind = MapKind::Shadow;
    map.camera = Some(DepthCamera { world_to_camera: w2c.to_cols_array(), projection: projection(spec) });
    map
}

/// Camera space → the screen window mapped onto [-1, 1]² (y up), homogeneous; column-major.
fn projection(spec: &anysl_renderers::CameraSpec) -> [f64; 16] {
    let [l, r, b, t] = spec.screen_window.map(f64::from);
    let (cx, cy, hx, hy) = ((l + r) * 0.5, (b + t) * 0.5, (r - l) * 0.5, (t - b) * 0.5);
    match spec.projection {
        // x_screen = x / (z tan), NDC = (x_screen - cx) / hx; w = z.
        Projection::Perspective { fov } => {
            let tan = (f64::from(fov) * 0.5).tan();
            [
                1.0 / (tan * hx),
                0.0,
                0.0,
                0.0,
                0.0,
                1.0 / (tan * hy),
                0.0,
                0.0,
                -cx / hx,
                -cy / hy,
                1.0,
                1.0,
                0.0,
                0.0,
                0.0,
                0.0,
            ]
        }
        Projection::Orthographic => {
            [1.0 / hx, 0.0, 0.0, 0.0, 0.0, 1.0 / hy, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -cx / hx, -cy / hy, 0.0, 1.0]
        }
    }
}

/// Renders the depth passes `frame` asks for and keeps each in the texture store.
pub fn keep_depth_maps<S, L>(frame: &FrameDesc, scene: &Scene<S, L>) {
    if frame.depth_maps.is_empty() {
        return;
    }
    let map = depth_map(frame, scene);
    for name in &frame.depth_maps {
        store::insert(name, map.clone());
    }
}
