//! Ray queries over all triangles of a scene: a compressed wide BVH built and traversed by
//! obvhs ([`Accel::closest_hit`], [`Accel::occluded`]) and, beside it, the brute-force
//! reference intersector the tests compare it with (same triangle test, every triangle).

use glam::Vec3A;
use obvhs::cwbvh::{builder::build_cwbvh_from_tris, CwBvh};
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use std::time::Duration;

/// The closest intersection of a ray: distance along the (unnormalized) direction,
/// triangle index and barycentric coordinates of vertices 1 and 2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// Index of the triangle in the scene's triangle list.
    pub prim: u32,
    /// Barycentric weight of vertex 1.
    pub b1: f32,
    /// Barycentric weight of vertex 2.
    pub b2: f32,
}

/// A triangle prepared for the intersection test: a vertex and its two edges.
#[derive(Clone, Copy, Debug)]
struct PackedTri {
    v0: Vec3A,
    e1: Vec3A,
    e2: Vec3A,
    prim: u32,
}

impl PackedTri {
    /// Möller–Trumbore: `(t, b1, b2)` for a hit with `tmin < t < tmax`.
    #[inline(always)]
    fn intersect(&self, o: Vec3A, d: Vec3A, tmin: f32, tmax: f32) -> Option<(f32, f32, f32)> {
        let pvec = d.cross(self.e2);
        let det = self.e1.dot(pvec);
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let inv = 1.0 / det;
        let tvec = o - self.v0;
        let b1 = tvec.dot(pvec) * inv;
        if !(0.0..=1.0).contains(&b1) {
            return None;
        }
        let qvec = tvec.cross(self.e1);
        let b2 = d.dot(qvec) * inv;
        if b2 < 0.0 || b1 + b2 > 1.0 {
            return None;
        }
        let t = self.e2.dot(qvec) * inv;
        (t > tmin && t < tmax).then_some((t, b1, b2))
    }
}

/// Triangles in world space with a BVH over them.
#[derive(Clone, Debug)]
pub struct Accel {
    bvh: CwBvh,
    /// Triangles in BVH leaf order (index = obvhs primitive slot).
    bvh_tris: Vec<PackedTri>,
    /// Triangles in scene order (the brute-force reference walks these).
    tris: Vec<PackedTri>,
}

impl Accel {
    /// Builds the BVH over `triangles` (`[v0, v1, v2]` each, world space).
    #[must_use]
    pub fn build(triangles: &[[Vec3A; 3]]) -> Self {
        let tris: Vec<PackedTri> = triangles
            .iter()
            .enumerate()
            .map(|(i, [a, b, c])| PackedTri { v0: *a, e1: *b - *a, e2: *c - *a, prim: i as u32 })
            .collect();
        if triangles.is_empty() {
            return Self { bvh: CwBvh::default(), bvh_tris: Vec::new(), tris };
        }
        let obvhs_tris: Vec<Triangle> = triangles.iter().map(|[a, b, c]| Triangle { v0: *a, v1: *b, v2: *c }).collect();
        let bvh = build_cwbvh_from_tris(&obvhs_tris, BvhBuildParams::medium_build(), &mut Duration::default());
        let bvh_tris = bvh.primitive_indices.iter().map(|&i| tris[i as usize]).collect();
        Self { bvh, bvh_tris, tris }
    }

    /// Number of triangles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.tris.len()
    }

    /// True when there are no triangles.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// The closest hit with `tmin < t < tmax` along `origin + t · dir`.
    #[inline]
    #[must_use]
    pub fn closest_hit(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> Option<Hit> {
        if self.bvh_tris.is_empty() {
            return None;
        }
        let ray = Ray::new(origin, dir, tmin, tmax);
        let mut rh = RayHit::none();
        let mut best = Hit { t: tmax, prim: u32::MAX, b1: 0.0, b2: 0.0 };
        let found = self.bvh.ray_traverse(ray, &mut rh, |r, slot| {
            let tri = &self.bvh_tris[slot];
            match tri.intersect(r.origin, r.direction, r.tmin, r.tmax) {
                Some((t, b1, b2)) => {
                    best = Hit { t, prim: tri.prim, b1, b2 };
                    t
                }
                None => f32::INFINITY,
            }
        });
        found.then_some(best)
    }

    /// True when some triangle intersects the ray with `tmin < t < tmax` (shadow rays).
    #[inline]
    #[must_use]
    pub fn occluded(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> bool {
        if self.bvh_tris.is_empty() {
            return false;
        }
        let ray = Ray::new(origin, dir, tmin, tmax);
        !self.bvh.ray_traverse_miss(ray, |r, slot| {
            self.bvh_tris[slot].intersect(r.origin, r.direction, r.tmin, r.tmax).map_or(f32::INFINITY, |h| h.0)
        })
    }

    /// Reference for [`Accel::closest_hit`]: tests every triangle (ties keep the lowest index).
    #[must_use]
    pub fn closest_hit_brute_force(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut tmax = tmax;
        for tri in &self.tris {
            if let Some((t, b1, b2)) = tri.intersect(origin, dir, tmin, tmax) {
                best = Some(Hit { t, prim: tri.prim, b1, b2 });
                tmax = t;
            }
        }
        best
    }

    /// Reference for [`Accel::occluded`].
    #[must_use]
    pub fn occluded_brute_force(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> bool {
        self.tris.iter().any(|tri| tri.intersect(origin, dir, tmin, tmax).is_some())
    }
}
