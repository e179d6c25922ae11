//! The [`Camera`]: primary rays and their differentials, for a pinhole (perspective) or an
//! orthographic projection. [`Camera::new`] places a perspective camera by eye, target and up;
//! [`Camera::from_spec`] takes what a RenderMan scene says ([`CameraSpec`]: a camera-to-world
//! transform of RenderMan's left-handed camera space, +x right, +y up, +z into the screen, a
//! projection, a screen window and clipping planes).

use glam::{Mat4, Vec3, Vec3A};

/// How camera space projects onto the screen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Pinhole at the camera-space origin looking along +z; the screen is the plane at
    /// distance 1 scaled by `tan(fov / 2)`: camera direction `(x·tan, y·tan, 1)` for screen
    /// point `(x, y)`. `fov` in radians.
    Perspective {
        /// Field of view of the screen-window span `[-1, 1]`, in radians.
        fov: f32,
    },
    /// Parallel rays along +z from the plane z = 0; screen point `(x, y)` is camera point
    /// `(x, y, 0)`.
    Orthographic,
}

/// Everything a RenderMan scene says about its camera, independent of the image size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSpec {
    /// Camera-to-world transform (the inverse of the transform current at `WorldBegin`).
    pub camera_to_world: Mat4,
    /// The projection.
    pub projection: Projection,
    /// Screen window `[left, right, bottom, top]`, mapped onto the whole image.
    pub screen_window: [f32; 4],
    /// Near and far clipping distances along camera-space z (`far` may be infinite).
    pub clipping: [f32; 2],
}

/// How a camera ray changes from pixel to pixel (scaled by the footprint): its origin (the
/// orthographic camera's rays differ in origin only) and its direction (the perspective
/// camera's share the eye).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RayDifferential {
    /// ∂origin/∂x.
    pub dodx: Vec3A,
    /// ∂origin/∂y.
    pub dody: Vec3A,
    /// ∂dir/∂x.
    pub ddx: Vec3A,
    /// ∂dir/∂y.
    pub ddy: Vec3A,
}

/// A camera ray: origin, unit direction, its per-pixel derivatives and the clipped `t` range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimaryRay {
    /// Origin.
    pub origin: Vec3A,
    /// Unit direction.
    pub dir: Vec3A,
    /// ∂dir/∂x (scaled by the footprint; zero for an orthographic camera).
    pub ddx: Vec3A,
    /// ∂dir/∂y.
    pub ddy: Vec3A,
    /// ∂origin/∂x (scaled by the footprint; zero for a perspective camera).
    pub dodx: Vec3A,
    /// ∂origin/∂y.
    pub dody: Vec3A,
    /// Nearest `t` (the near clipping plane).
    pub tmin: f32,
    /// Farthest `t` (the far clipping plane).
    pub tmax: f32,
}

impl PrimaryRay {
    /// The ray's differentials.
    #[inline(always)]
    #[must_use]
    pub fn differential(&self) -> RayDifferential {
        RayDifferential { dodx: self.dodx, dody: self.dody, ddx: self.ddx, ddy: self.ddy }
    }
}

/// A perspective or orthographic camera. Pixel coordinates are continuous: `(0, 0)` is the
/// top-left corner of the image, `(x + 0.5, y + 0.5)` the centre of pixel `(x, y)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    position: Vec3A,
    look_at: Vec3A,
    up: Vec3A,
    vfov: f32,
    width: u32,
    height: u32,
    // Derived: the image plane at distance 1 spans `forward ± right ± up_v`.
    forward: Vec3A,
    right: Vec3A,
    up_v: Vec3A,
    // RenderMan cameras: the spec, whether rays are parallel, camera-space z of a world
    // vector (for the clipping planes), near and far.
    spec: Option<CameraSpec>,
    orthographic: bool,
    z_row: Vec3A,
    near: f32,
    far: f32,
}

impl Camera {
    /// A camera at `position` looking at `look_at`, `up` roughly up, vertical field of view
    /// `vfov` (radians), an image of `width × height` pixels (square pixels).
    ///
    /// # Panics
    /// When the view direction is zero or parallel to `up`, or the image is empty.
    #[must_use]
    pub fn new(position: Vec3A, look_at: Vec3A, up: Vec3A, vfov: f32, width: u32, height: u32) -> Self {
        assert!(width > 0 && height > 0, "empty image {width}×{height}");
        let forward = (look_at - position).try_normalize().expect("camera looks at its own position");
        let right = forward.cross(up).try_normalize().expect("camera up is parallel to the view direction");
        let up_unit = right.cross(forward);
        let tan_half = (vfov * 0.5).tan();
        let aspect = width as f32 / height as f32;
        Self {
            position,
            look_at,
            up,
            vfov,
            width,
            height,
            forward,
            right: right * (tan_half * aspect),
            up_v: up_unit * tan_half,
            spec: None,
            orthographic: false,
            z_row: forward,
            near: 0.0,
            far: f32::INFINITY,
        }
    }

    /// The camera a RenderMan scene describes, for an image of `width × height` pixels: the
    /// screen window is stretched over the whole image (so pixels are square only when the
    /// window's aspect is the image's).
    ///
    /// # Panics
    /// When the image is empty or the camera-to-world transform is singular.
    #[must_use]
    pub fn from_spec(spec: &CameraSpec, width: u32, height: u32) -> Self {
        assert!(width > 0 && height > 0, "empty image {width}×{height}");
        let c = spec.camera_to_world;
        assert!(c.determinant().abs() > 0.0, "singular camera transform {c}");
        let [l, r, b, t] = spec.screen_window;
        let (cx, cy, hx, hy) = ((l + r) * 0.5, (b + t) * 0.5, (r - l) * 0.5, (t - b) * 0.5);
        let v = |x: f32, y: f32, z: f32| Vec3A::from(c.transform_vector3(Vec3::new(x, y, z)));
        let w2c = c.inverse();
        let z_row = Vec3A::new(w2c.x_axis.z, w2c.y_axis.z, w2c.z_axis.z);
        let (position, forward, right, up_v, orthographic) = match spec.projection {
            Projection::Perspective { fov } => {
                let tan = (fov * 0.5).tan();
                let eye = Vec3A::from(c.transform_point3(Vec3::ZERO));
                (eye, v(cx * tan, cy * tan, 1.0), v(hx * tan, 0.0, 0.0), v(0.0, hy * tan, 0.0), false)
            }
            Projection::Orthographic => {
                let centre = Vec3A::from(c.transform_point3(Vec3::new(cx, cy, 0.0)));
                (centre, v(0.0, 0.0, 1.0).normalize(), v(hx, 0.0, 0.0), v(0.0, hy, 0.0), true)
            }
        };
        let look_at = position + forward;
        let up = up_v.normalize_or_zero();
        let vfov = match spec.projection {
            Projection::Perspective { fov } => fov,
            Projection::Orthographic => 0.0,
        };
        Self {
            position,
            look_at,
            up,
            vfov,
            width,
            height,
            forward,
            right,
            up_v,
            spec: Some(*spec),
            orthographic,
            z_row,
            near: spec.clipping[0].max(0.0),
            far: spec.clipping[1],
        }
    }

    /// The same camera with another image size (the field of view is kept vertically; a
    /// RenderMan camera keeps its screen window).
    #[must_use]
    pub fn with_size(&self, width: u32, height: u32) -> Self {
        match &self.spec {
            Some(spec) => Self::from_spec(spec, width, height),
            None => Self::new(self.position, self.look_at, self.up, self.vfov, width, height),
        }
    }

    /// Whether rays are parallel (an orthographic projection).
    #[must_use]
    pub fn is_orthographic(&self) -> bool {
        self.orthographic
    }

    /// The camera ray through image point `(x, y)` with its differentials scaled by
    /// `footprint` (see [`Camera::ray_differential`]) and its `t` range between the clipping
    /// planes. For a perspective camera the origin is the eye and the direction and
    /// differentials are [`Camera::ray_differential`]'s, bit for bit.
    #[inline(always)]
    #[must_use]
    pub fn primary_ray(&self, x: f32, y: f32, footprint: f32) -> PrimaryRay {
        if self.orthographic {
            let sx = x * (2.0 / self.width as f32) - 1.0;
            let sy = 1.0 - y * (2.0 / self.height as f32);
            let origin = self.position + self.right * sx + self.up_v * sy;
            let z = self.z_row.dot(self.forward);
            PrimaryRay {
                origin,
                dir: self.forward,
                ddx: Vec3A::ZERO,
                ddy: Vec3A::ZERO,
                dodx: self.right * (2.0 * footprint / self.width as f32),
                dody: -self.up_v * (2.0 * footprint / self.height as f32),
                tmin: self.near / z,
                tmax: self.far / z,
            }
        } else {
            let (dir, ddx, ddy) = self.ray_differential(x, y, footprint);
            let (tmin, tmax) = if self.spec.is_none() {
                (0.0, f32::INFINITY)
            } else {
                let z = self.z_row.dot(dir);
                (self.near / z, self.far / z)
            };
            PrimaryRay { origin: self.position, dir, ddx, ddy, dodx: Vec3A::ZERO, dody: Vec3A::ZERO, tmin, tmax }
        }
    }

    /// Eye position.
    #[must_use]
    pub fn position(&self) -> Vec3A {
        self.position
    }
    /// The point looked at.
    #[must_use]
    pub fn look_at(&self) -> Vec3A {
        self.look_at
    }
    /// Vertical field of view in radians.
    #[must_use]
    pub fn vfov(&self) -> f32 {
        self.vfov
    }
    /// Image width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }
    /// Image height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The unnormalized direction through image point `(x, y)` (on the plane at distance 1).
    #[inline(always)]
    #[must_use]
    pub fn plane_dir(&self, x: f32, y: f32) -> Vec3A {
        let sx = x * (2.0 / self.width as f32) - 1.0;
        let sy = 1.0 - y * (2.0 / self.height as f32);
        self.forward + self.right * sx + self.up_v * sy
    }

    /// The unit direction of the primary ray through image point `(x, y)`.
    #[inline(always)]
    #[must_use]
    pub fn ray_dir(&self, x: f32, y: f32) -> Vec3A {
        self.plane_dir(x, y).normalize()
    }

    /// `(dir, ∂dir/∂x, ∂dir/∂y)` of the primary ray through `(x, y)`: the derivatives of the
    /// unit direction per pixel, scaled by `footprint` (1 for one sample per pixel,
    /// 1/√spp when supersampling, as pbrt scales its differentials).
    #[inline(always)]
    #[must_use]
    pub fn ray_differential(&self, x: f32, y: f32, footprint: f32) -> (Vec3A, Vec3A, Vec3A) {
        let p = self.plane_dir(x, y);
        let inv_len = p.length_recip();
        let d = p * inv_len;
        // d(p/|p|) = (dp - d (d·dp)) / |p|, with dp/dx, dp/dy constant on the plane.
        let dpx = self.right * (2.0 / self.width as f32);
        let dpy = self.up_v * (-2.0 / self.height as f32);
        let ddx = (dpx - d * d.dot(dpx)) * (inv_len * footprint);
        let ddy = (dpy - d * d.dot(dpy)) * (inv_len * footprint);
        (d, ddx, ddy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn workload_camera_matches_the_spec() {
        // shaders/assets/workload_ref/shading_workload.md §1: sx = ((col + 0.5)·2/512 − 1)·0.375, …
        let cam = Camera::new(Vec3A::new(0.0, 0.0, 3.0), Vec3A::ZERO, Vec3A::Y, 2.0 * 0.375f32.atan(), 512, 512);
        for (col, row) in [(0u32, 0u32), (100, 300), (511, 511)] {
            let sx = ((col as f32 + 0.5) * (2.0 / 512.0) - 1.0) * 0.375;
            let sy = (1.0 - (row as f32 + 0.5) * (2.0 / 512.0)) * 0.375;
            let want = Vec3A::new(sx, sy, -1.0).normalize();
            let got = cam.ray_dir(col as f32 + 0.5, row as f32 + 0.5);
            assert!((got - want).length() < 1e-6, "{got} vs {want}");
        }
    }

    #[test]
    fn renderman_camera_looks_along_plus_z() {
        // Camera at the world origin (identity): +z is forward, +x right, +y up.
        let spec = CameraSpec {
            camera_to_world: Mat4::IDENTITY,
            projection: Projection::Perspective { fov: 90f32.to_radians() },
            screen_window: [-1.0, 1.0, -1.0, 1.0],
            clipping: [0.5, 10.0],
        };
        let cam = Camera::from_spec(&spec, 64, 64);
        let r = cam.primary_ray(32.0, 32.0, 1.0);
        assert!((r.dir - Vec3A::Z).length() < 1e-6 && r.origin == Vec3A::ZERO);
        assert!((r.tmin - 0.5).abs() < 1e-6 && (r.tmax - 10.0).abs() < 1e-5);
        // The top-right corner is at screen (1, 1): direction (1, 1, 1).
        let c = cam.primary_ray(64.0, 0.0, 1.0).dir;
        assert!((c - Vec3A::ONE.normalize()).length() < 1e-6, "{c}");
        // An off-centre screen window shifts the view.
        let shifted = CameraSpec { screen_window: [0.0, 2.0, -1.0, 1.0], ..spec };
        let d = Camera::from_spec(&shifted, 64, 64).primary_ray(0.0, 32.0, 1.0).dir;
        assert!((d - Vec3A::Z).length() < 1e-6, "{d}");
        // Orthographic: parallel rays from the window on z = 0.
        let ortho = CameraSpec { projection: Projection::Orthographic, screen_window: [-2.0, 2.0, -1.0, 1.0], ..spec };
        let cam = Camera::from_spec(&ortho, 40, 20);
        let r = cam.primary_ray(40.0, 20.0, 1.0);
        assert!((r.origin - Vec3A::new(2.0, -1.0, 0.0)).length() < 1e-6 && r.dir == Vec3A::Z);
        // Its differentials are in the origin: one pixel (0.1 of the window) per pixel.
        let (a, b) = (cam.primary_ray(10.0, 5.0, 0.5), cam.primary_ray(11.0, 6.0, 0.5));
        assert!(a.ddx == Vec3A::ZERO && a.ddy == Vec3A::ZERO);
        assert!((a.dodx * 2.0 - Vec3A::new(b.origin.x - a.origin.x, 0.0, 0.0)).length() < 1e-6, "{}", a.dodx);
        assert!((a.dody * 2.0 - Vec3A::new(0.0, b.origin.y - a.origin.y, 0.0)).length() < 1e-6, "{}", a.dody);
    }

    #[test]
    fn preset_primary_rays_are_the_differentials() {
        let cam = Camera::new(Vec3A::new(1.0, 2.0, 5.0), Vec3A::ZERO, Vec3A::Y, 0.8, 64, 48);
        let r = cam.primary_ray(20.5, 10.5, 0.5);
        let (d, dx, dy) = cam.ray_differential(20.5, 10.5, 0.5);
        assert_eq!((r.origin, r.dir, r.ddx, r.ddy, r.tmin, r.tmax), (cam.position(), d, dx, dy, 0.0, f32::INFINITY));
    }

    #[test]
    fn differentials_match_finite_differences() {
        let cam = Camera::new(Vec3A::new(1.0, 2.0, 5.0), Vec3A::ZERO, Vec3A::Y, 0.8, 64, 48);
        let (d, dx, dy) = cam.ray_differential(20.5, 10.5, 1.0);
        let h = 0.1;
        let fx = (cam.ray_dir(20.5 + h, 10.5) - cam.ray_dir(20.5 - h, 10.5)) / (2.0 * h);
        let fy = (cam.ray_dir(20.5, 10.5 + h) - cam.ray_dir(20.5, 10.5 - h)) / (2.0 * h);
        assert!((d - cam.ray_dir(20.5, 10.5)).length() < 1e-6);
        assert!((dx - fx).length() < 1e-3 * dx.length(), "{dx} vs {fx}");
        assert!((dy - fy).length() < 1e-3 * dy.length(), "{dy} vs {fy}");
    }
}
