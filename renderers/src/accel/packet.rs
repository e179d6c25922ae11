//! Packet traversal (RTfact-like): up to 16 rays walk one binary BVH together, each node's
//! box and each leaf's triangles tested against every ray of the packet at once in the lanes
//! of a `wide` vector ([`RayLanes`]). Coherent rays — a camera packet over a pixel block,
//! the refracted rays of that block, shadow rays towards one light — visit nearly the same
//! nodes, so a packet costs little more than one of its rays.
//!
//! The triangle test is the single-ray one ([`tri_test`], written once over [`RayLanes`]),
//! so a ray finds in a packet the hit it finds alone: the same distance and barycentrics to
//! the bit, and the same triangle except where two triangles share the hit distance (a ray
//! through a shared edge or vertex), where either is right.

use super::lanes::RayLanes;
use super::{Hit, PackedTri};
use glam::Vec3A;
use obvhs::bvh2::Bvh2;
use wide::{f32x16, f32x4, f32x8};

/// The most rays a packet holds.
pub const MAX_PACKET: usize = 16;

/// Entries of the traversal stack; deeper trees are traced ray by ray (see
/// [`PacketBvh::usable`]).
const STACK: usize = 128;

/// Up to [`MAX_PACKET`] rays traced together: ray `i` is `origins[i] + t · dirs[i]` with
/// `tmin[i] < t < tmax[i]`; rays whose bit is clear in `active` are ignored (their fields
/// may hold anything, NaN included).
#[derive(Clone, Copy, Debug)]
pub struct RayPacket {
    /// Ray origins.
    pub origins: [Vec3A; MAX_PACKET],
    /// Ray directions (any length; a zero direction hits nothing).
    pub dirs: [Vec3A; MAX_PACKET],
    /// Lower ends of the ray intervals (exclusive).
    pub tmin: [f32; MAX_PACKET],
    /// Upper ends of the ray intervals (exclusive).
    pub tmax: [f32; MAX_PACKET],
    /// Rays in use (bit `i` = ray `i`).
    pub active: u32,
}

impl Default for RayPacket {
    fn default() -> Self {
        Self {
            origins: [Vec3A::ZERO; MAX_PACKET],
            dirs: [Vec3A::Z; MAX_PACKET],
            tmin: [0.0; MAX_PACKET],
            tmax: [f32::INFINITY; MAX_PACKET],
            active: 0,
        }
    }
}

impl RayPacket {
    /// Sets ray `i` and marks it active.
    #[inline]
    pub fn set(&mut self, i: usize, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) {
        self.origins[i] = origin;
        self.dirs[i] = dir;
        self.tmin[i] = tmin;
        self.tmax[i] = tmax;
        self.active |= 1 << i;
    }

    /// Lanes the packet spans: one past its highest active ray.
    #[inline]
    #[must_use]
    pub fn span(&self) -> usize {
        32 - self.active.leading_zeros() as usize
    }
}

/// A node of the packet BVH (32 bytes): its box, and either two children at `first` and
/// `first + 1` (`count == 0`) or `count` triangles from `first`.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(32))]
struct Node {
    min: [f32; 3],
    count: u32,
    max: [f32; 3],
    first: u32,
}

/// The binary BVH that packets traverse, triangles in leaf order.
#[derive(Clone, Debug, Default)]
pub(super) struct PacketBvh {
    nodes: Vec<Node>,
    tris: Vec<PackedTri>,
    /// Whether the tree fits the traversal stack.
    usable: bool,
}

/// `(a × b)` per lane, products and differences rounded one by one.
#[inline(always)]
fn cross<W: RayLanes>(a: [W; 3], b: [W; 3]) -> [W; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `a · b` per lane as `(x + y) + z`.
#[inline(always)]
fn dot<W: RayLanes>(a: [W; 3], b: [W; 3]) -> W {
    (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]
}

#[inline(always)]
fn splat3<W: RayLanes>(v: Vec3A) -> [W; 3] {
    [W::splat(v.x), W::splat(v.y), W::splat(v.z)]
}

/// Möller–Trumbore for one triangle against the rays in the lanes of `o`, `d`: the lanes
/// with a hit at `tmin < t < tmax`, and `(t, b1, b2)` (meaningful in those lanes). A
/// degenerate or non-finite determinant is a miss.
#[inline(always)]
pub(super) fn tri_test<W: RayLanes>(tri: &PackedTri, o: [W; 3], d: [W; 3], tmin: W, tmax: W) -> (W::Mask, W, W, W) {
    let (v0, e1, e2) = (splat3::<W>(tri.v0), splat3::<W>(tri.e1), splat3::<W>(tri.e2));
    let pvec = cross(d, e2);
    let det = dot(e1, pvec);
    let ok = det.ne(W::splat(0.0)) & det.abs().lt(W::splat(f32::INFINITY));
    let inv = W::splat(1.0) / det;
    let tvec = [o[0] - v0[0], o[1] - v0[1], o[2] - v0[2]];
    let b1 = dot(tvec, pvec) * inv;
    let ok = ok & b1.ge(W::splat(0.0)) & b1.le(W::splat(1.0));
    let qvec = cross(tvec, e1);
    let b2 = dot(d, qvec) * inv;
    let ok = ok & b2.ge(W::splat(0.0)) & (b1 + b2).le(W::splat(1.0));
    let t = dot(e2, qvec) * inv;
    (ok & t.gt(tmin) & t.lt(tmax), t, b1, b2)
}

/// Rounding slack of the box test (Ize, "Robust BVH Ray Traversal", JCGT 2013): the far
/// distance is scaled by `1 + 2γ₃` so a ray grazing a box's face is not lost to rounding.
const FAR_SCALE: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// Direction components closer to zero than this are moved to it (keeping their sign), so
/// that the box test never forms `0 · ∞`; the ray then moves by less than `1e-30` per unit
/// of `t` along that axis, far below any box.
const MIN_DIR: f32 = 1e-30;

/// What a leaf triangle did to the rays of a walk.
enum Visit {
    /// Nothing.
    Missed,
    /// Shortened some ray's interval.
    Shortened,
    /// Ended the walk (every ray is answered).
    Done,
}

/// The rays of a packet in the lanes of `W`, prepared for traversal.
struct Lanes<W> {
    o: [W; 3],
    d: [W; 3],
    inv: [W; 3],
    tmin: W,
}

impl<W: RayLanes> Lanes<W> {
    #[inline(always)]
    fn new(rays: &RayPacket) -> Self {
        let comp = |f: fn(&Vec3A) -> f32, v: &[Vec3A; MAX_PACKET]| W::from_fn(|i| f(&v[i]));
        let o = [comp(|v| v.x, &rays.origins), comp(|v| v.y, &rays.origins), comp(|v| v.z, &rays.origins)];
        let d = [comp(|v| v.x, &rays.dirs), comp(|v| v.y, &rays.dirs), comp(|v| v.z, &rays.dirs)];
        let nudge = |c: f32| if c.abs() < MIN_DIR { MIN_DIR.copysign(c) } else { c };
        let inv = [
            W::from_fn(|i| 1.0 / nudge(rays.dirs[i].x)),
            W::from_fn(|i| 1.0 / nudge(rays.dirs[i].y)),
            W::from_fn(|i| 1.0 / nudge(rays.dirs[i].z)),
        ];
        // Inactive lanes get an empty interval (and a finite `tmin`), so no box holds them.
        let tmin = W::from_fn(|i| if (rays.active >> i) & 1 != 0 { rays.tmin[i] } else { 0.0 });
        Self { o, d, inv, tmin }
    }

    /// The interval ends a ray's `tmax` gives: `-∞` for inactive lanes.
    #[inline(always)]
    fn far(rays: &RayPacket) -> W {
        W::from_fn(|i| if (rays.active >> i) & 1 != 0 { rays.tmax[i] } else { f32::NEG_INFINITY })
    }

    /// The lanes whose ray overlaps `node`'s box within `(tmin, tfar)` (bits), and where
    /// each ray enters it.
    #[inline(always)]
    fn enter(&self, node: &Node, tfar: W) -> (u32, W) {
        let slab = |k: usize| {
            let a = (W::splat(node.min[k]) - self.o[k]) * self.inv[k];
            let b = (W::splat(node.max[k]) - self.o[k]) * self.inv[k];
            (a.min_or(b), a.max_or(b))
        };
        let ((nx, fx), (ny, fy), (nz, fz)) = (slab(0), slab(1), slab(2));
        let near = nx.max_or(ny).max_or(nz.max_or(self.tmin));
        let far = fx.min_or(fy).min_or(fz.min_or(tfar)) * W::splat(FAR_SCALE);
        (W::bits(near.le(far)), near)
    }
}

impl PacketBvh {
    /// The packet form of `bvh` over `tris` (scene order; `bvh.primitive_indices` maps leaf
    /// slots to them).
    pub(super) fn new(bvh: &Bvh2, tris: &[PackedTri]) -> Self {
        if bvh.nodes.is_empty() || tris.is_empty() {
            return Self::default();
        }
        let nodes: Vec<Node> = bvh
            .nodes
            .iter()
            .map(|n| Node {
                min: n.aabb.min.to_array(),
                count: n.prim_count,
                max: n.aabb.max.to_array(),
                first: n.first_index,
            })
            .collect();
        let leaf_tris = bvh.primitive_indices.iter().map(|&i| tris[i as usize]).collect();
        let usable = depth(&nodes) < STACK;
        Self { nodes, tris: leaf_tris, usable }
    }

    /// Whether packets can traverse this tree (it is not empty and not deeper than the
    /// stack); otherwise callers trace ray by ray.
    pub(super) fn usable(&self) -> bool {
        self.usable
    }

    /// The closest hit of every active ray: bits of the rays that hit, their hits in
    /// `out[i]`. Lanes: the narrowest `wide` vector holding the packet's span.
    pub(super) fn closest_hits(&self, rays: &RayPacket, out: &mut [Hit; MAX_PACKET]) -> u32 {
        match rays.span() {
            0 => 0,
            1..=4 => self.closest::<f32x4>(rays, out),
            5..=8 => self.closest::<f32x8>(rays, out),
            _ => self.closest::<f32x16>(rays, out),
        }
    }

    /// The active rays that some triangle blocks (any hit), as bits.
    pub(super) fn occluded(&self, rays: &RayPacket) -> u32 {
        match rays.span() {
            0 => 0,
            1..=4 => self.any_hit::<f32x4>(rays),
            5..=8 => self.any_hit::<f32x8>(rays),
            _ => self.any_hit::<f32x16>(rays),
        }
    }

    /// Walks the tree for the rays of `lanes` with interval ends `far`: every leaf triangle
    /// whose node some ray enters goes to `visit(triangle, &mut far)`, which may shorten the
    /// intervals and says what it did. Both children of an inner node are tested
    /// at once; the one most rays enter first is walked first, the other waits on the stack
    /// and is tested again when popped if the intervals have shortened since.
    #[inline(always)]
    fn walk<W: RayLanes>(&self, lanes: &Lanes<W>, mut far: W, mut visit: impl FnMut(&PackedTri, &mut W) -> Visit) {
        // Stack entries: a node whose box some ray entered, and the `epoch` it was tested in.
        let mut stack = [(0u32, 0u32); STACK];
        let mut sp = 0;
        let mut epoch = 0u32;
        if lanes.enter(&self.nodes[0], far).0 == 0 {
            return;
        }
        let mut node = 0u32;
        loop {
            let n = &self.nodes[node as usize];
            if n.count == 0 {
                let (ia, ib) = (n.first, n.first + 1);
                let (ma, near_a) = lanes.enter(&self.nodes[ia as usize], far);
                let (mb, near_b) = lanes.enter(&self.nodes[ib as usize], far);
                if ma != 0 && mb != 0 {
                    let both = ma & mb;
                    let a_first = (W::bits(near_a.le(near_b)) & both).count_ones() * 2 >= both.count_ones();
                    let (first, second) = if a_first { (ia, ib) } else { (ib, ia) };
                    stack[sp] = (second, epoch);
                    sp += 1;
                    node = first;
                    continue;
                }
                if ma | mb != 0 {
                    node = if ma != 0 { ia } else { ib };
                    continue;
                }
            } else {
                for slot in n.first..n.first + n.count {
                    match visit(&self.tris[slot as usize], &mut far) {
                        Visit::Missed => {}
                        Visit::Shortened => epoch += 1,
                        Visit::Done => return,
                    }
                }
            }
            // Next: the nearest waiting node some ray still enters.
            loop {
                if sp == 0 {
                    return;
                }
                sp -= 1;
                let (next, tested) = stack[sp];
                if tested == epoch || lanes.enter(&self.nodes[next as usize], far).0 != 0 {
                    node = next;
                    break;
                }
            }
        }
    }

    #[inline(always)]
    fn closest<W: RayLanes>(&self, rays: &RayPacket, out: &mut [Hit; MAX_PACKET]) -> u32 {
        let lanes = Lanes::<W>::new(rays);
        let (mut b1_best, mut b2_best) = (W::splat(0.0), W::splat(0.0));
        let mut t_best = W::splat(0.0);
        let mut prim = [u32::MAX; MAX_PACKET];
        let mut found = 0u32;
        self.walk(&lanes, Lanes::<W>::far(rays), |tri, far| {
            let (hit, t, b1, b2) = tri_test(tri, lanes.o, lanes.d, lanes.tmin, *far);
            let bits = W::bits(hit);
            if bits != 0 {
                *far = W::select(hit, t, *far);
                t_best = *far;
                b1_best = W::select(hit, b1, b1_best);
                b2_best = W::select(hit, b2, b2_best);
                found |= bits;
                let mut rest = bits;
                while rest != 0 {
                    prim[rest.trailing_zeros() as usize] = tri.prim;
                    rest &= rest - 1;
                }
                Visit::Shortened
            } else {
                Visit::Missed
            }
        });
        let mut rest = found;
        while rest != 0 {
            let i = rest.trailing_zeros() as usize;
            out[i] = Hit { t: t_best.lane(i), prim: prim[i], b1: b1_best.lane(i), b2: b2_best.lane(i) };
            rest &= rest - 1;
        }
        found
    }

    #[inline(always)]
    fn any_hit<W: RayLanes>(&self, rays: &RayPacket) -> u32 {
        let lanes = Lanes::<W>::new(rays);
        let mut blocked = 0u32;
        self.walk(&lanes, Lanes::<W>::far(rays), |tri, far| {
            let bits = W::bits(tri_test(tri, lanes.o, lanes.d, lanes.tmin, *far).0);
            if bits == 0 {
                return Visit::Missed;
            }
            blocked |= bits;
            if blocked == rays.active {
                return Visit::Done;
            }
            // A blocked ray is done: an empty interval keeps it out of every box.
            *far = W::from_fn(|i| if (blocked >> i) & 1 != 0 { f32::NEG_INFINITY } else { far.lane(i) });
            Visit::Shortened
        });
        blocked
    }
}

/// Depth of the tree below the root (a lone leaf: 0).
fn depth(nodes: &[Node]) -> usize {
    let mut deepest = 0;
    let mut todo = vec![(0u32, 0usize)];
    while let Some((i, d)) = todo.pop() {
        let n = &nodes[i as usize];
        deepest = deepest.max(d);
        if n.count == 0 {
            todo.push((n.first, d + 1));
            todo.push((n.first + 1, d + 1));
        }
    }
    deepest
}
