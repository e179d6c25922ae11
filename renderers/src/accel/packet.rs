//! Packet traversal (RTfact-like): up to 16 rays walk one 4-wide BVH together, each child
//! box of a node and each leaf's triangles tested against every ray of the packet at once in
//! the lanes of a `wide` vector ([`RayLanes`]). Coherent rays — a camera packet over a pixel block,
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

/// Entries of the traversal stack kept in place; a deeper tree (degenerate input) walks
/// with a stack on the heap.
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

/// Children per node of the packet BVH.
const ARITY: usize = 4;

/// Marks an unused child slot (`count`); the used slots come first.
const EMPTY: u32 = u32::MAX;

/// A node of the packet BVH (128 bytes, two cache lines): the boxes of up to [`ARITY`]
/// children side by side, axis by axis, and for child `j` either an inner node at
/// `first[j]` (`count[j] == 0`) or `count[j]` triangles from `first[j]`. The tree is the
/// binary one obvhs builds with pairs of levels merged: half the nodes on a ray's way down,
/// so half the dependent loads and data-dependent branches a walk waits on, while the box
/// tests of one node's children are independent of each other.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Node {
    min: [[f32; ARITY]; 3],
    max: [[f32; ARITY]; 3],
    first: [u32; ARITY],
    count: [u32; ARITY],
}

impl Default for Node {
    fn default() -> Self {
        Self { min: [[0.0; ARITY]; 3], max: [[0.0; ARITY]; 3], first: [0; ARITY], count: [EMPTY; ARITY] }
    }
}

/// The packet BVH, triangles in leaf order.
#[derive(Clone, Debug, Default)]
pub(super) struct PacketBvh {
    /// Node 0 is the root.
    nodes: Vec<Node>,
    tris: Vec<PackedTri>,
    /// Stack entries a walk may need.
    stack_need: usize,
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

    /// The lanes whose ray overlaps the box of child `j` of `node` within `(tmin, tfar)`
    /// (bits), and where each ray enters it.
    #[inline(always)]
    fn enter(&self, node: &Node, j: usize, tfar: W) -> (u32, W) {
        let slab = |k: usize| {
            let a = (W::splat(node.min[k][j]) - self.o[k]) * self.inv[k];
            let b = (W::splat(node.max[k][j]) - self.o[k]) * self.inv[k];
            (a.min_or(b), a.max_or(b))
        };
        let ((nx, fx), (ny, fy), (nz, fz)) = (slab(0), slab(1), slab(2));
        let near = nx.max_or(ny).max_or(nz.max_or(self.tmin));
        let far = fx.min_or(fy).min_or(fz.min_or(tfar)) * W::splat(FAR_SCALE);
        (W::bits(near.le(far)), near)
    }
}

/// How a walk tests the boxes of all children of a node against its rays: child by child
/// in the packet's own lanes, or — for packets of 4 and 8 rays — several children side by
/// side in the 16 lanes of one `f32x16` (child `j` of a group in lanes `j·N .. j·N + N`), so
/// a 4-ray packet tests a node's four boxes with the instructions of one. Every lane
/// computes what [`Lanes::enter`] computes, operation for operation.
trait ChildTests: RayLanes {
    /// The rays as the tests want them, made once per walk.
    type Rays;
    /// [`ChildTests::Rays`] of `lanes`.
    fn rays(lanes: &Lanes<Self>) -> Self::Rays;
    /// For each child slot `j` of `node`: the bits of the rays that enter its box within
    /// `(tmin, far)` (none for an unused slot) and where ray `rep` enters it.
    fn children(lanes: &Lanes<Self>, rays: &Self::Rays, node: &Node, far: Self, rep: usize) -> [(u32, f32); ARITY];
}

/// [`ChildTests::children`] one child at a time.
#[inline(always)]
fn child_by_child<W: RayLanes>(lanes: &Lanes<W>, node: &Node, far: W, rep: usize) -> [(u32, f32); ARITY] {
    let mut tested = [(0u32, 0.0f32); ARITY];
    for (j, t) in tested.iter_mut().enumerate() {
        if node.count[j] == EMPTY {
            break;
        }
        let (m, near) = lanes.enter(node, j, far);
        *t = (m, near.lane(rep));
    }
    tested
}

macro_rules! child_by_child {
    ($($W:ty),+) => {$(
        impl ChildTests for $W {
            type Rays = ();
            #[inline(always)]
            fn rays(_: &Lanes<Self>) {}
            #[inline(always)]
            fn children(lanes: &Lanes<Self>, _: &(), node: &Node, far: Self, rep: usize) -> [(u32, f32); ARITY] {
                child_by_child(lanes, node, far, rep)
            }
        }
    )+};
}
child_by_child!(f32, f32x16);

/// The rays of a 4- or 8-ray packet repeated across 16 lanes.
struct Spread {
    o: [f32x16; 3],
    inv: [f32x16; 3],
    tmin: f32x16,
}

macro_rules! side_by_side {
    ($($W:ty: $n:literal),+) => {$(
        impl ChildTests for $W {
            type Rays = Spread;
            #[inline(always)]
            fn rays(lanes: &Lanes<Self>) -> Spread {
                let repeat = |v: $W| {
                    let a = v.to_array();
                    f32x16::new(core::array::from_fn(|i| a[i % $n]))
                };
                Spread { o: lanes.o.map(repeat), inv: lanes.inv.map(repeat), tmin: repeat(lanes.tmin) }
            }
            #[inline(always)]
            fn children(_: &Lanes<Self>, r: &Spread, node: &Node, far: Self, rep: usize) -> [(u32, f32); ARITY] {
                const PER: usize = 16 / $n;
                let fa = far.to_array();
                let tfar = f32x16::new(core::array::from_fn(|i| fa[i % $n]));
                let mut out = [(0u32, 0.0f32); ARITY];
                for g in 0..ARITY / PER {
                    let spread = |b: &[f32; ARITY]| f32x16::new(core::array::from_fn(|i| b[g * PER + i / $n]));
                    let slab = |k: usize| {
                        let a = (spread(&node.min[k]) - r.o[k]) * r.inv[k];
                        let b = (spread(&node.max[k]) - r.o[k]) * r.inv[k];
                        (a.fast_min(b), a.fast_max(b))
                    };
                    let ((nx, fx), (ny, fy), (nz, fz)) = (slab(0), slab(1), slab(2));
                    let near = nx.fast_max(ny).fast_max(nz.fast_max(r.tmin));
                    let far = fx.fast_min(fy).fast_min(fz.fast_min(tfar)) * f32x16::splat(FAR_SCALE);
                    let bits = near.simd_le(far).to_bitmask();
                    let near = near.to_array();
                    for c in 0..PER {
                        let j = g * PER + c;
                        let m = if node.count[j] == EMPTY { 0 } else { (bits >> (c * $n)) & ((1 << $n) - 1) };
                        out[j] = (m, near[c * $n + rep]);
                    }
                }
                out
            }
        }
    )+};
}
side_by_side!(f32x4: 4, f32x8: 8);

impl PacketBvh {
    /// The packet form of `bvh` over `tris` (scene order; `bvh.primitive_indices` maps leaf
    /// slots to them): each node takes the children of a binary node, and where fewer than
    /// [`ARITY`], opens the inner child with the largest surface (the one most rays enter)
    /// in its place, until it has [`ARITY`] children or only leaves.
    pub(super) fn new(bvh: &Bvh2, tris: &[PackedTri]) -> Self {
        if bvh.nodes.is_empty() || tris.is_empty() {
            return Self::default();
        }
        let area = |i: u32| {
            let e = bvh.nodes[i as usize].aabb.max - bvh.nodes[i as usize].aabb.min;
            e.x * e.y + e.y * e.z + e.z * e.x
        };
        let mut nodes = vec![Node::default()];
        // (binary node, packet node it becomes, depth of that node)
        let mut todo = vec![(0u32, 0usize, 0usize)];
        let mut deepest = 0;
        while let Some((binary, at, depth)) = todo.pop() {
            deepest = deepest.max(depth);
            let b = &bvh.nodes[binary as usize];
            // A lone leaf at the root becomes a root with one child.
            let mut kids = [binary; ARITY];
            let mut len = 1;
            if b.prim_count == 0 {
                (kids[0], kids[1]) = (b.first_index, b.first_index + 1);
                len = 2;
            }
            while len < ARITY {
                let open = (0..len)
                    .filter(|&k| bvh.nodes[kids[k] as usize].prim_count == 0)
                    .max_by(|&x, &y| area(kids[x]).total_cmp(&area(kids[y])));
                let Some(k) = open else { break };
                let first = bvh.nodes[kids[k] as usize].first_index;
                (kids[k], kids[len]) = (first, first + 1);
                len += 1;
            }
            let mut node = Node::default();
            for (j, &kid) in kids[..len].iter().enumerate() {
                let c = &bvh.nodes[kid as usize];
                for k in 0..3 {
                    node.min[k][j] = c.aabb.min[k];
                    node.max[k][j] = c.aabb.max[k];
                }
                if c.prim_count > 0 {
                    (node.first[j], node.count[j]) = (c.first_index, c.prim_count);
                } else {
                    (node.first[j], node.count[j]) = (nodes.len() as u32, 0);
                    todo.push((kid, nodes.len(), depth + 1));
                    nodes.push(Node::default());
                }
            }
            nodes[at] = node;
        }
        let leaf_tris = bvh.primitive_indices.iter().map(|&i| tris[i as usize]).collect();
        // A walk keeps at most ARITY − 1 waiting children per level above it, plus the
        // children of the node it tests.
        Self { nodes, tris: leaf_tris, stack_need: (deepest + 1) * ARITY }
    }

    /// Whether there is a tree to walk (the scene has triangles).
    pub(super) fn usable(&self) -> bool {
        !self.nodes.is_empty()
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

    /// The closest hit of one ray, walked in plain `f32` (for trees obvhs' single-ray
    /// traversal cannot take).
    pub(super) fn closest_one(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> Option<Hit> {
        let mut ray = RayPacket::default();
        ray.set(0, origin, dir, tmin, tmax);
        let mut out = [Hit { t: 0.0, prim: 0, b1: 0.0, b2: 0.0 }; MAX_PACKET];
        (self.closest::<f32>(&ray, &mut out) != 0).then_some(out[0])
    }

    /// Whether some triangle blocks one ray, walked in plain `f32` (as [`PacketBvh::closest_one`]).
    pub(super) fn occluded_one(&self, origin: Vec3A, dir: Vec3A, tmin: f32, tmax: f32) -> bool {
        let mut ray = RayPacket::default();
        ray.set(0, origin, dir, tmin, tmax);
        self.any_hit::<f32>(&ray) != 0
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
    /// whose box some ray enters goes to `visit(triangle, &mut far)`, which may shorten the
    /// intervals and says what it did. All children of a node are tested at once and wait on
    /// the stack nearest on top, by where ray `rep` enters them; a waiting child is tested
    /// again when popped if the intervals have shortened since.
    #[inline(always)]
    fn walk<W: ChildTests>(
        &self,
        lanes: &Lanes<W>,
        mut far: W,
        rep: usize,
        mut visit: impl FnMut(&PackedTri, &mut W) -> Visit,
    ) {
        // Stack entries: child `r % ARITY` of node `r / ARITY`, whose box some ray entered,
        // and the `epoch` it was tested in.
        let (mut in_place, mut on_heap) = ([(0u32, 0u32); STACK], Vec::new());
        let stack: &mut [(u32, u32)] = if self.stack_need <= STACK {
            &mut in_place
        } else {
            on_heap.resize(self.stack_need, (0, 0));
            &mut on_heap
        };
        let prepared = W::rays(lanes);
        let mut sp = 0;
        let mut epoch = 0u32;
        let mut node = 0u32;
        loop {
            let n = &self.nodes[node as usize];
            // The entered children, nearest last.
            let mut found = [(0.0f32, 0u32); ARITY];
            let mut k = 0;
            for (j, (m, key)) in W::children(lanes, &prepared, n, far, rep).into_iter().enumerate() {
                if m != 0 {
                    let mut at = k;
                    while at > 0 && found[at - 1].0 < key {
                        found[at] = found[at - 1];
                        at -= 1;
                    }
                    found[at] = (key, node * ARITY as u32 + j as u32);
                    k += 1;
                }
            }
            for &(_, r) in &found[..k] {
                stack[sp] = (r, epoch);
                sp += 1;
            }
            // Next: the nearest waiting child some ray still enters; leaves on the way are
            // visited.
            loop {
                if sp == 0 {
                    return;
                }
                sp -= 1;
                let (r, tested) = stack[sp];
                let (parent, j) = (&self.nodes[(r / ARITY as u32) as usize], (r % ARITY as u32) as usize);
                if tested != epoch && lanes.enter(parent, j, far).0 == 0 {
                    continue;
                }
                let (first, count) = (parent.first[j], parent.count[j]);
                if count == 0 {
                    node = first;
                    break;
                }
                for slot in first..first + count {
                    match visit(&self.tris[slot as usize], &mut far) {
                        Visit::Missed => {}
                        Visit::Shortened => epoch += 1,
                        Visit::Done => return,
                    }
                }
            }
        }
    }

    #[inline(always)]
    fn closest<W: ChildTests>(&self, rays: &RayPacket, out: &mut [Hit; MAX_PACKET]) -> u32 {
        let lanes = Lanes::<W>::new(rays);
        let (mut b1_best, mut b2_best) = (W::splat(0.0), W::splat(0.0));
        let mut t_best = W::splat(0.0);
        let mut prim = [u32::MAX; MAX_PACKET];
        let mut found = 0u32;
        self.walk(&lanes, Lanes::<W>::far(rays), rays.active.trailing_zeros() as usize, |tri, far| {
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
    fn any_hit<W: ChildTests>(&self, rays: &RayPacket) -> u32 {
        let lanes = Lanes::<W>::new(rays);
        let mut blocked = 0u32;
        self.walk(&lanes, Lanes::<W>::far(rays), rays.active.trailing_zeros() as usize, |tri, far| {
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
