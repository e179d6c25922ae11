//! The pinhole [`Camera`]: primary rays and their differentials.

use glam::Vec3A;

/// A pinhole camera. Pixel coordinates are continuous: `(0, 0)` is the top-left corner of the
/// image, `(x + 0.5, y + 0.5)` the centre of pixel `(x, y)`.
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
        }
    }

    /// The same camera with another image size (the field of view is kept vertically).
    #[must_use]
    pub fn with_size(&self, width: u32, height: u32) -> Self {
        Self::new(self.position, self.look_at, self.up, self.vfov, width, height)
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
        // shared/bench/shading_workload.md §1: sx = ((col + 0.5)·2/512 − 1)·0.375, …
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
