//! Polygons (RI 3.2 §5.1): `Polygon`, `GeneralPolygon`, `PointsPolygons`,
//! `PointsGeneralPolygons`.
//!
//! Each polygon is cut on its best-fit plane (Newell's normal of its outer loop): convex ones
//! as a fan, concave ones and those with holes by ear clipping (holes are first bridged to the
//! outer loop). The normal is the face normal, oriented by the vertex winding (the outer loop
//! runs counter-clockwise about it), unless `"N"` is given.
//!
//! u, v: polygons have no natural parametrization, and we found no convention in the RI spec
//! for their u and v. Here u, v are the coordinates of the point on the polygon's plane along
//! two axes (e1 = the object x axis projected onto the plane, or y when the plane faces x;
//! e2 = N × e1), normalized to the polygon's bounds, so each polygon spans [0, 1]² and
//! dPdu = e1 · width, dPdv = e2 · height. s, t default to u, v.
//!
//! Vertices are not shared between polygons (the face normal and the uniform and
//! facevarying variables differ across an edge).

use super::primvars::{self, Counts, Interp, POSITION_NAMES};
use super::{err, unit, Detail, Result, Tessellation, MAX_TRIANGLES};
use anysl_rib::{Class, ParamList};
use glam::{DVec2, DVec3};

/// Polygons with more points than this are cut as a fan of their outer loop (with a warning):
/// ear clipping costs O(n²) or worse.
const MAX_EAR_CLIP_POINTS: usize = 1024;

/// One polygon: its loops (outer first, then holes) as indices into "P".
struct Poly {
    loops: Vec<Vec<usize>>,
}

/// `Polygon`: one convex polygon of as many vertices as "P" has points.
pub fn polygon(params: &ParamList, d: &Detail) -> Result<Tessellation> {
    let n = point_count("Polygon", params)?;
    build("Polygon", vec![Poly { loops: vec![(0..n).collect()] }], n, true, false, params, d)
}

/// `GeneralPolygon nloops`: one polygon, the first loop its outline, the others holes.
pub fn general_polygon(nverts: &[i32], params: &ParamList, d: &Detail) -> Result<Tessellation> {
    let request = "GeneralPolygon";
    let counts = sizes(request, "nverts", nverts)?;
    let total: usize = counts.iter().sum();
    let n = point_count(request, params)?;
    if n != total {
        return err(format!("{request}: \"P\" has {n} points, but the loops have {total} vertices"));
    }
    let mut next = 0;
    let loops = counts
        .iter()
        .map(|&c| {
            next += c;
            (next - c..next).collect()
        })
        .collect();
    build(request, vec![Poly { loops }], n, false, false, params, d)
}

/// `PointsPolygons nverts vertids`: convex polygons sharing points.
pub fn points_polygons(nverts: &[i32], verts: &[i32], params: &ParamList, d: &Detail) -> Result<Tessellation> {
    let request = "PointsPolygons";
    let counts = sizes(request, "nverts", nverts)?;
    let ids = indices(request, counts.iter().sum(), verts)?;
    let mut next = 0;
    let polys = counts
        .iter()
        .map(|&c| {
            next += c;
            Poly { loops: vec![ids[next - c..next].to_vec()] }
        })
        .collect();
    let needed = ids.iter().max().map_or(0, |m| m + 1);
    build(request, polys, needed, true, true, params, d)
}

/// `PointsGeneralPolygons nloops nverts vertids`: polygons with holes sharing points.
pub fn points_general_polygons(
    nloops: &[i32],
    nverts: &[i32],
    verts: &[i32],
    params: &ParamList,
    d: &Detail,
) -> Result<Tessellation> {
    let request = "PointsGeneralPolygons";
    let loops_per = sizes(request, "nloops", nloops)?;
    let total_loops: usize = loops_per.iter().sum();
    if total_loops != nverts.len() {
        return err(format!("{request}: nloops adds up to {total_loops} loops, but nverts has {}", nverts.len()));
    }
    let counts = sizes(request, "nverts", nverts)?;
    let ids = indices(request, counts.iter().sum(), verts)?;
    let (mut next_loop, mut next_vert) = (0, 0);
    let mut polys = Vec::with_capacity(loops_per.len());
    for &nl in &loops_per {
        let mut loops = Vec::with_capacity(nl);
        for &c in &counts[next_loop..next_loop + nl] {
            loops.push(ids[next_vert..next_vert + c].to_vec());
            next_vert += c;
        }
        next_loop += nl;
        polys.push(Poly { loops });
    }
    let needed = ids.iter().max().map_or(0, |m| m + 1);
    build(request, polys, needed, false, true, params, d)
}

/// Non-negative sizes.
fn sizes(request: &str, what: &str, v: &[i32]) -> Result<Vec<usize>> {
    v.iter()
        .enumerate()
        .map(|(i, &n)| usize::try_from(n).or_else(|_| err(format!("{request}: {what}[{i}] is {n}, not a count (≥ 0)"))))
        .collect()
}

/// Vertex indices: `total` of them, none negative.
fn indices(request: &str, total: usize, verts: &[i32]) -> Result<Vec<usize>> {
    if verts.len() != total {
        return err(format!("{request}: vertids has {} entries, but nverts adds up to {total}", verts.len()));
    }
    sizes(request, "vertids", verts)
}

/// Points in "P" or "Pw".
fn point_count(request: &str, params: &ParamList) -> Result<usize> {
    Ok(primvars::positions(request, params, false)?.0.len())
}

/// Where each output vertex's values come from.
struct PolyInterp {
    counts: Counts,
    /// (polygon, face-vertex, point) per output vertex.
    records: Vec<(u32, u32, u32)>,
}

impl Interp for PolyInterp {
    fn counts(&self) -> Counts {
        self.counts
    }
    fn vertices(&self) -> usize {
        self.records.len()
    }
    fn weights(&self, class: Class, vertex: usize, out: &mut Vec<(usize, f32)>) {
        out.clear();
        let (face, fv, point) = self.records[vertex];
        out.push((
            match class {
                Class::Constant => 0,
                Class::Uniform => face as usize,
                Class::Varying | Class::Vertex => point as usize,
                Class::FaceVarying | Class::FaceVertex => fv as usize,
            },
            1.0,
        ));
    }
}

/// Cuts `polys` into triangles. `needed` is the number of points the vertex indices use;
/// `convex` says the request promises convex polygons (a fan, unless the outline turns out
/// concave); `shared` says the points are shared (PointsPolygons), so "P" may hold more.
fn build(
    request: &str,
    polys: Vec<Poly>,
    needed: usize,
    convex: bool,
    shared: bool,
    params: &ParamList,
    d: &Detail,
) -> Result<Tessellation> {
    let _ = d; // Polygons are exact: the tolerance does not matter.
    let (hpoints, pname) = primvars::positions(request, params, false)?;
    if hpoints.len() < needed {
        return err(format!(
            "{request}: the vertex indices need {needed} points, but \"{pname}\" has {}",
            hpoints.len()
        ));
    }
    let points: Vec<DVec3> = hpoints.iter().map(|h| (h.truncate() / h.w).as_dvec3()).collect();
    let facevarying: usize = polys.iter().map(|p| p.loops.iter().map(Vec::len).sum::<usize>()).sum();
    if facevarying.saturating_sub(2 * polys.len()) > MAX_TRIANGLES {
        return err(format!("{request}: {facevarying} vertices exceed the limit of {MAX_TRIANGLES} triangles"));
    }
    let counts = Counts {
        uniform: polys.len(),
        varying: if shared { needed } else { hpoints.len() },
        vertex: if shared { needed } else { hpoints.len() },
        facevarying,
        vertex_at_least: shared,
    };
    let mut t = Tessellation::default();
    let mut records = Vec::with_capacity(facevarying);
    let mut fv_base = 0usize;
    let mut skipped = 0usize;
    for (face, poly) in polys.iter().enumerate() {
        let nfv: usize = poly.loops.iter().map(Vec::len).sum();
        let fv0 = fv_base;
        fv_base += nfv;
        let loops: Vec<Vec<DVec3>> = poly.loops.iter().map(|l| l.iter().map(|&i| points[i]).collect()).collect();
        let normal = loops.first().and_then(|outer| newell(outer).or_else(|| newell(&loops.concat())));
        let Some(normal) = normal else {
            skipped += 1;
            continue;
        };
        let e1 = {
            let x = DVec3::X - normal * normal.x;
            if normal.x.abs() < 0.9 {
                x
            } else {
                DVec3::Y - normal * normal.y
            }
        }
        .normalize();
        let e2 = normal.cross(e1);
        let flat: Vec<Vec<DVec2>> =
            loops.iter().map(|l| l.iter().map(|p| DVec2::new(p.dot(e1), p.dot(e2))).collect()).collect();
        let all = flat.iter().flatten();
        let lo = all.clone().fold(DVec2::splat(f64::INFINITY), |a, &b| a.min(b));
        let hi = all.fold(DVec2::splat(f64::NEG_INFINITY), |a, &b| a.max(b));
        let size = (hi - lo).max(DVec2::splat(1e-300));
        let base = t.positions.len();
        let Ok(base32) = u32::try_from(base) else {
            return err(format!("{request}: too many vertices"));
        };
        let n = normal.as_vec3();
        let mut k = 0;
        for (l, lp) in poly.loops.iter().zip(&flat) {
            for (&point, q) in l.iter().zip(lp) {
                let uv = ((*q - lo) / size).as_vec2();
                t.positions.push(points[point].as_vec3());
                t.normals.push(n);
                t.uv.push(uv);
                t.st.push(uv);
                t.dpdu.push((e1 * size.x).as_vec3());
                t.dpdv.push((e2 * size.y).as_vec3());
                records.push((face as u32, (fv0 + k) as u32, point as u32));
                k += 1;
            }
        }
        let tris = if nfv > MAX_EAR_CLIP_POINTS {
            t.warnings.push(format!(
                "{request}: polygon {face} has {nfv} vertices (more than {MAX_EAR_CLIP_POINTS}): cut as a fan of its outline"
            ));
            fan(flat[0].len())
        } else if convex && flat.len() == 1 && is_convex(&flat[0]) {
            fan(flat[0].len())
        } else {
            triangulate(&flat)
        };
        t.triangles.extend(tris.into_iter().map(|tri| tri.map(|i| base32 + i as u32)));
    }
    if skipped > 0 {
        t.warnings.push(format!("{request}: {skipped} degenerate polygon(s) (no area) skipped"));
    }
    let interp = PolyInterp { counts, records };
    primvars::apply(&mut t, request, params, &interp, POSITION_NAMES)?;
    t.check(request)
}

/// Newell's normal of a loop: unit, oriented so the loop runs counter-clockwise about it.
fn newell(points: &[DVec3]) -> Option<DVec3> {
    let mut n = DVec3::ZERO;
    for (i, a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        n += DVec3::new((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    let l = n.length();
    (l.is_finite() && l > 0.0).then(|| n / l).filter(|v| unit(v.as_vec3()).is_some())
}

/// A fan from the first vertex.
fn fan(n: usize) -> Vec<[usize; 3]> {
    (1..n.saturating_sub(1)).map(|i| [0, i, i + 1]).collect()
}

/// Twice the signed area of the triangle abc (positive when counter-clockwise).
#[inline]
fn cross(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Twice the signed area of a loop.
fn signed_area(l: &[DVec2]) -> f64 {
    (0..l.len()).map(|i| l[i].perp_dot(l[(i + 1) % l.len()])).sum()
}

/// Convex and counter-clockwise, turning once (a pentagram turns left everywhere too).
fn is_convex(l: &[DVec2]) -> bool {
    let n = l.len();
    if n < 3 {
        return false;
    }
    let mut turning = 0.0;
    for i in 0..n {
        let (a, b, c) = (l[i], l[(i + 1) % n], l[(i + 2) % n]);
        let (e, f) = (b - a, c - b);
        if e.perp_dot(f) < 0.0 {
            return false;
        }
        if e != DVec2::ZERO && f != DVec2::ZERO {
            turning += e.perp_dot(f).atan2(e.dot(f));
        }
    }
    (turning - std::f64::consts::TAU).abs() < 1e-6
}

/// Triangulates a polygon with holes (loops of 2D points, the outline first) by ear clipping;
/// indices run over the loops' points in order. Never panics, always ends: where no ear is
/// found (self-intersecting or degenerate input) it drops a degenerate vertex or clips the
/// most convex one anyway.
pub(crate) fn triangulate(loops: &[Vec<DVec2>]) -> Vec<[usize; 3]> {
    let mut pts = Vec::new();
    let mut rings: Vec<Vec<usize>> = Vec::new();
    for (k, l) in loops.iter().enumerate() {
        let start = pts.len();
        pts.extend_from_slice(l);
        let mut ring: Vec<usize> = (start..pts.len()).collect();
        ring.dedup_by(|a, b| pts[*a] == pts[*b]);
        while ring.len() > 1 && pts[ring[0]] == pts[*ring.last().unwrap_or(&0)] {
            ring.pop();
        }
        if ring.len() < 3 {
            if k == 0 {
                return Vec::new();
            }
            continue;
        }
        let area = signed_area(&ring.iter().map(|&i| pts[i]).collect::<Vec<_>>());
        // The outline counter-clockwise, holes clockwise.
        if (k == 0) != (area > 0.0) {
            ring.reverse();
        }
        if k == 0 {
            rings.insert(0, ring);
        } else {
            rings.push(ring);
        }
    }
    if rings.is_empty() {
        return Vec::new();
    }
    let mut ring = rings.remove(0);
    // Holes from the rightmost inwards, each bridged from its rightmost vertex.
    let rightmost =
        |r: &[usize]| r.iter().enumerate().max_by(|a, b| pts[*a.1].x.total_cmp(&pts[*b.1].x)).map_or(0, |(i, _)| i);
    rings.sort_by(|a, b| pts[b[rightmost(b)]].x.total_cmp(&pts[a[rightmost(a)]].x));
    for h in 0..rings.len() {
        let hole = &rings[h];
        let mi = rightmost(hole);
        let m = hole[mi];
        let others: Vec<&Vec<usize>> = rings[h..].iter().collect();
        let v = bridge_target(&pts, &ring, m, &others);
        let mut spliced = Vec::with_capacity(ring.len() + hole.len() + 2);
        spliced.extend_from_slice(&ring[..=v]);
        spliced.extend(hole[mi..].iter().chain(&hole[..mi]));
        spliced.push(m);
        spliced.extend_from_slice(&ring[v..]);
        ring = spliced;
    }
    ear_clip(&pts, ring)
}

/// The index in `ring` of the vertex that `m` (on a hole) is bridged to: the nearest one whose
/// segment to `m` stays inside (crosses no edge and leaves the vertex into the interior).
fn bridge_target(pts: &[DVec2], ring: &[usize], m: usize, holes: &[&Vec<usize>]) -> usize {
    let pm = pts[m];
    let n = ring.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| pts[ring[a]].distance_squared(pm).total_cmp(&pts[ring[b]].distance_squared(pm)));
    let crosses = |a: DVec2, b: DVec2, r: &[usize]| {
        (0..r.len()).any(|i| {
            let (c, d) = (pts[r[i]], pts[r[(i + 1) % r.len()]]);
            if c == a || c == b || d == a || d == b {
                return false;
            }
            segments_cross(a, b, c, d)
        })
    };
    for &k in &order {
        let pv = pts[ring[k]];
        let (prev, next) = (pts[ring[(k + n - 1) % n]], pts[ring[(k + 1) % n]]);
        let into_interior = if cross(prev, pv, next) >= 0.0 {
            cross(pv, next, pm) >= 0.0 && cross(prev, pv, pm) >= 0.0
        } else {
            cross(pv, next, pm) >= 0.0 || cross(prev, pv, pm) >= 0.0
        };
        if into_interior && !crosses(pv, pm, ring) && !holes.iter().any(|h| crosses(pv, pm, h)) {
            return k;
        }
    }
    order.first().copied().unwrap_or(0)
}

/// Segments ab and cd cross (touching counts).
fn segments_cross(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let (d1, d2) = (cross(a, b, c), cross(a, b, d));
    let (d3, d4) = (cross(c, d, a), cross(c, d, b));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
        return true;
    }
    let on = |p: DVec2, q: DVec2, r: DVec2| {
        r.x >= p.x.min(q.x) && r.x <= p.x.max(q.x) && r.y >= p.y.min(q.y) && r.y <= p.y.max(q.y)
    };
    (d1 == 0.0 && on(a, b, c)) || (d2 == 0.0 && on(a, b, d)) || (d3 == 0.0 && on(c, d, a)) || (d4 == 0.0 && on(c, d, b))
}

/// Point p in the closed triangle abc (counter-clockwise).
fn in_triangle(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0
}

/// Ear clipping of a counter-clockwise ring (which may touch itself at bridge vertices).
fn ear_clip(pts: &[DVec2], mut ring: Vec<usize>) -> Vec<[usize; 3]> {
    let mut tris = Vec::with_capacity(ring.len().saturating_sub(2));
    let mut start = 0;
    while ring.len() > 3 {
        let n = ring.len();
        let at = |i: usize| ring[i % n];
        let is_ear = |i: usize| {
            let (a, b, c) = (at(i + n - 1), at(i), at(i + 1));
            let (pa, pb, pc) = (pts[a], pts[b], pts[c]);
            cross(pa, pb, pc) > 0.0
                && ring.iter().all(|&p| {
                    let q = pts[p];
                    q == pa || q == pb || q == pc || !in_triangle(q, pa, pb, pc)
                })
        };
        let found = (0..n).map(|k| (start + k) % n).find(|&i| is_ear(i));
        let i = match found {
            Some(i) => {
                tris.push([at(i + n - 1), at(i), at(i + 1)]);
                i
            }
            None => {
                // No ear: drop a vertex with no area (collinear or repeated) if there is one,
                // else clip the most convex vertex anyway so that the loop always ends.
                let area = |i: usize| cross(pts[at(i + n - 1)], pts[at(i)], pts[at(i + 1)]);
                match (0..n).find(|&i| area(i).abs() <= 1e-12 * scale(pts, &ring)) {
                    Some(i) => i,
                    None => {
                        let i = (0..n).max_by(|&a, &b| area(a).total_cmp(&area(b))).unwrap_or(0);
                        tris.push([at(i + n - 1), at(i), at(i + 1)]);
                        i
                    }
                }
            }
        };
        ring.remove(i);
        start = if i == 0 { 0 } else { i - 1 };
    }
    if ring.len() == 3 && cross(pts[ring[0]], pts[ring[1]], pts[ring[2]]) != 0.0 {
        tris.push([ring[0], ring[1], ring[2]]);
    }
    tris
}

/// The squared size of a ring's bounds, for a relative zero-area test.
fn scale(pts: &[DVec2], ring: &[usize]) -> f64 {
    let (lo, hi) = ring.iter().fold((DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)), |(lo, hi), &i| {
        (lo.min(pts[i]), hi.max(pts[i]))
    });
    (hi - lo).length_squared()
}
