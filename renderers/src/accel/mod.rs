//! Ray queries over all triangles of a scene: single rays through a compressed wide BVH
//! built and traversed by obvhs ([`Accel::closest_hit`], [`Accel::occluded`]), packets of up
//! to 16 rays through a 4-wide BVH in SIMD lanes ([`Accel::closest_hits`],
//! [`Accel::occluded_packet`], see [`packet`]) and, beside them, the brute-force reference
//! intersector the tests compare both with (same triangle test, every triangle).

mod lanes;
pub mod packet;

pub use lanes::RayLanes;
pub use packet::{RayPacket, MAX_PACKET};

use glam::Vec3A;
use obvhs::bvh2::builder::build_bvh2_from_tris;
use obvhs::cwbvh::{bvh2_to_cwbvh::bvh2_to_cwbvh, CwBvh};
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use packet::{tri_test, PacketBvh};
use std::time::Duration;

/// Most triangles in a leaf of the packet BVH.
const PACKET_LEAF: u32 = 4;

/// Deepest compressed wide BVH obvhs' single-ray traversal handles: its stack holds 32
/// levels, and a deeper tree (degenerate input, e.g. hundreds of triangles on one spot)
/// would silently lose nodes.
const CWBVH_MAX_DEPTH: usize = 31;

/// Levels of a compressed wide BVH below its root (a lone root: 0).
fn cwbvh_depth(bvh: &CwBvh) -> usize {
    let mut deepest = 0;
    let mut todo = if bvh.nodes.is_empty() { vec![] } else { vec![(0u32, 0usize)] };
    while let Some((i, d)) = todo.pop() {
        deepest = deepest.max(d);
        let node = &bvh.nodes[i as usize];
        for ch in 0..8 {
            if !node.is_child_empty(ch) && !node.is_leaf(ch) {
                todo.push((node.child_node_index(ch), d + 1));
            }
        }
    }
    deepest
}

/// Scenes up to this many triangles get obvhs' most thorough build (see [`build_quality`]).
const THOROUGH_BUILD_MAX: usize = 1 << 19;

/// The build settings of both BVHs for a scene of `triangles`: obvhs' `very_slow_build`
/// (pre-split triangles, reinsertion over all nodes) up to [`THOROUGH_BUILD_MAX`]
/// triangles, `medium_build` beyond. The thorough build costs ~30 ms more on the 26 k
/// triangles of the `gallery` scene and traces secondary packets ~8 % faster (single rays
/// ~3 %); on millions of triangles it would cost seconds.
fn build_quality(triangles: usize) -> BvhBuildParams {
    if triangles <= THOROUGH_BUILD_MAX {
        BvhBuildParams::very_slow_build()
    } else {
        BvhBuildParams::medium_build()
    }
}

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
/// 4-wide one for packets (obvhs' binary BVH with pairs of levels merged).
#[derive(Clone, Debug)]
pub struct Accel {
    /// `None` when the scene's tree is too deep for obvhs' traversal.
    bvh: Option<CwBvh>,
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
            return Self { bvh: None, packet: PacketBvh::default(), bvh_tris: Vec::new(), tris };
        }
        let obvhs_tris: Vec<Triangle> = triangles.iter().map(|[a, b, c]| Triangle { v0: *a, v1: *b, v2: *c }).collect();
        let quality = build_quality(triangles.len());
        // Single rays: obvhs' compressed wide BVH, converted here from a binary one with
        // leaves of one triangle (obvhs' own builder does the same, but checks the result
        // with assertions that fail on degenerate input) — kept only when its traversal
        // can walk it (see `CWBVH_MAX_DEPTH`); otherwise single rays walk the packet BVH.
        let single = build_bvh2_from_tris(
            &obvhs_tris,
            BvhBuildParams { max_prims_per_leaf: 1, post_collapse_reinsertion_batch_ratio_multiplier: 0.0, ..quality },
            &mut Duration::default(),
        );
        let bvh = Some(bvh2_to_cwbvh(&single, 3, true, false)).filter(|b| cwbvh_depth(b) <= CWBVH_MAX_DEPTH);
        let bvh_tris =
            bvh.as_ref().map(|b| b.primitive_indices.iter().map(|&i| tris[i as usize]).collect()).unwrap_or_default();
        // Packets pay for every triangle test in all lanes: small leaves.
        let params = BvhBuildParams { max_prims_per_leaf: PACKET_LEAF, ..quality };
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
        let Some(bvh) = &self.bvh else { return self.closest_hit_without_cwbvh(origin, dir, tmin, tmax) };
        let ray = Ray::new(origin, dir, tmin, tmax);
        let mut rh = RayHit::none();
        let mut best = Hit { t: tmax, prim: u32::MAX, b1: 0.0, b2: 0.0 };
        let found = bvh.ray_traverse(ray, &mut rh, |r, slot| {
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
        let Some(bvh) = &self.bvh else { return self.occluded_without_cwbvh(origin, dir, tmin, tmax) };
        let ray = Ray::new(origin, dir, tmin, tmax);
        !bvh.ray_traverse_miss(ray, |r, slot| {
            self.bvh_tris[slot].intersect(r.origin, r.direction, r.tmin, r.tmax).map_or(f32::INFINITY, |h| h.0)
        })
    }

    /// [`Accel::closest_hit`] for scenes without a compressed wide BVH (none, or a
    /// degenerate tree): one ray through the packet BVH, else every triangle.
    #[cold]
    fn closest_hit_without_cwbvh(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> Option<Hit> {
        if self.packet.usable() {
            self.packet.closest_one(origin, dir, tmin, tmax)
        } else {
            self.closest_hit_brute_force(origin, dir, tmin, tmax)
        }
    }

    /// [`Accel::occluded`] without a compressed wide BVH, as [`Accel::closest_hit_without_cwbvh`].
    #[cold]
    fn occluded_without_cwbvh(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> bool {
        if self.packet.usable() {
            self.packet.occluded_one(origin, dir, tmin, tmax)
        } else {
            self.occluded_brute_force(origin, dir, tmin, tmax)
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_trees_leave_the_compressed_bvh_out() {
        let one = [Vec3A::ZERO, Vec3A::X, Vec3A::Y];
        let copies = Accel::build(&[one; 300]);
        let depth = copies.bvh.as_ref().map(cwbvh_depth);
        assert!(depth.is_none(), "300 copies of a triangle: a compressed BVH of depth {depth:?}");
        assert!(copies.packet.usable());
        let mesh = crate::Mesh::uv_sphere(1.0, 16, 8);
        let sphere = Accel::build(
            &mesh.triangles.iter().map(|t| t.map(|i| Vec3A::from(mesh.positions[i as usize]))).collect::<Vec<_>>(),
        );
        assert!(sphere.bvh.as_ref().is_some_and(|b| cwbvh_depth(b) < 8));
    }
}
