//! Ray queries over all triangles of a scene: single rays through a compressed wide BVH
//! built and traversed by obvhs ([`Accel::closest_hit`], [`Accel::occluded`]), packets of up
//! to 16 rays through a binary BVH in SIMD lanes ([`Accel::closest_hits`],
//! [`Accel::occluded_packet`], see [`packet`]) and, beside them, the brute-force reference
//! intersector the tests compare both with (same triangle test, every triangle).

mod lanes;
pub mod packet;

pub use lanes::RayLanes;
pub use packet::{RayPacket, MAX_PACKET};

use glam::Vec3A;
use obvhs::bvh2::builder::build_bvh2_from_tris;
use obvhs::cwbvh::{builder::build_cwbvh_from_tris, CwBvh};
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use packet::{tri_test, PacketBvh};
use std::time::Duration;

/// Most triangles in a leaf of the packet BVH.
const PACKET_LEAF: u32 = 4;

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
    /// Möller–Trumbore: `(t, b1, b2)` for a hit with `tmin < t < tmax` — the packet test of
    /// [`packet::tri_test`] on one lane, so single rays and packets agree to the bit.
    #[inline(always)]
    fn intersect(&self, o: Vec3A, d: Vec3A, tmin: f32, tmax: f32) -> Option<(f32, f32, f32)> {
        let (hit, t, b1, b2) = tri_test::<f32>(self, o.to_array(), d.to_array(), tmin, tmax);
        hit.then_some((t, b1, b2))
    }
}

/// Triangles in world space with BVHs over them: a compressed wide one for single rays, a
/// binary one for packets.
#[derive(Clone, Debug)]
pub struct Accel {
    bvh: CwBvh,
    packet: PacketBvh,
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
            return Self { bvh: CwBvh::default(), packet: PacketBvh::default(), bvh_tris: Vec::new(), tris };
        }
        let obvhs_tris: Vec<Triangle> = triangles.iter().map(|[a, b, c]| Triangle { v0: *a, v1: *b, v2: *c }).collect();
        let bvh = build_cwbvh_from_tris(&obvhs_tris, BvhBuildParams::medium_build(), &mut Duration::default());
        let bvh_tris = bvh.primitive_indices.iter().map(|&i| tris[i as usize]).collect();
        // Packets pay for every triangle test in all lanes: small leaves.
        let params = BvhBuildParams { max_prims_per_leaf: PACKET_LEAF, ..BvhBuildParams::medium_build() };
        let packet = PacketBvh::new(&build_bvh2_from_tris(&obvhs_tris, params, &mut Duration::default()), &tris);
        Self { bvh, packet, bvh_tris, tris }
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

    /// The closest hit of every active ray of `rays`, traced together (see [`packet`]):
    /// returns the bits of the rays that hit and stores their hits in `out` (other entries are
    /// left as they were). Each ray's hit is the one [`Accel::closest_hit`] finds, up to the
    /// choice between triangles at the same distance.
    #[inline]
    pub fn closest_hits(&self, rays: &RayPacket, out: &mut [Hit; MAX_PACKET]) -> u32 {
        if rays.active.count_ones() == 1 || !self.packet.usable() {
            return self.each_ray(rays, |i, o, d, tmin, tmax| {
                self.closest_hit(o, d, tmin, tmax).map(|h| out[i] = h).is_some()
            });
        }
        self.packet.closest_hits(rays, out)
    }

    /// The active rays of `rays` that some triangle blocks (bits), traced together; each bit
    /// is what [`Accel::occluded`] says of its ray.
    #[inline]
    #[must_use]
    pub fn occluded_packet(&self, rays: &RayPacket) -> u32 {
        if rays.active.count_ones() == 1 || !self.packet.usable() {
            return self.each_ray(rays, |_, o, d, tmin, tmax| self.occluded(o, d, tmin, tmax));
        }
        self.packet.occluded(rays)
    }

    /// The bits of the active rays for which `query(i, origin, dir, tmin, tmax)` holds.
    #[inline]
    fn each_ray(&self, rays: &RayPacket, mut query: impl FnMut(usize, Vec3A, Vec3A, f32, f32) -> bool) -> u32 {
        let mut bits = 0;
        let mut rest = rays.active;
        while rest != 0 {
            let i = rest.trailing_zeros() as usize;
            if query(i, rays.origins[i], rays.dirs[i], rays.tmin[i], rays.tmax[i]) {
                bits |= 1 << i;
            }
            rest &= rest - 1;
        }
        bits
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
