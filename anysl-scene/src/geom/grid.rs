//! The engine shared by every parametric surface (quadrics, patches, patch meshes, NURBS).
//!
//! A [`Surface`] is a grid of faces (one for a quadric, one per patch of a mesh, one per
//! non-empty knot span of a NURBS), each with local parameters (s, t) in [0, 1]². The engine
//! picks the segments per face from a bound on the second derivatives (so that the distance
//! between surface and triangles stays under [`Detail::tolerance`]), evaluates point and
//! partials exactly at every grid vertex, and interpolates the primitive variables through
//! the surface's own weights.

use super::primvars::{self, Counts, Interp};
use super::{err, unit, Detail, Result, Tessellation, MAX_TRIANGLES};
use anysl_rib::{Class, ParamList};
use glam::{Vec2, Vec3};

/// A point of a surface with its partials along the face's local parameters.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Eval {
    pub p: Vec3,
    pub ds: Vec3,
    pub dt: Vec3,
}

/// A parametric surface made of a grid of faces.
pub(crate) trait Surface {
    /// Faces along u and along v.
    fn faces(&self) -> (usize, usize);
    /// Point and partials along the local (s, t) of face (fu, fv).
    fn eval(&self, fu: usize, fv: usize, s: f32, t: f32) -> Eval;
    /// The global (u, v) of a local point, and (du/ds, dv/dt) of the face (never 0).
    fn uv(&self, fu: usize, fv: usize, s: f32, t: f32) -> (Vec2, Vec2);
    /// Items per storage class.
    fn counts(&self) -> Counts;
    /// Index of the face's uniform item.
    fn uniform_index(&self, fu: usize, fv: usize) -> usize;
    /// Varying items blended at a local point.
    fn varying_weights(&self, fu: usize, fv: usize, s: f32, t: f32, out: &mut Vec<(usize, f32)>);
    /// Vertex items blended at a local point.
    fn vertex_weights(&self, fu: usize, fv: usize, s: f32, t: f32, out: &mut Vec<(usize, f32)>);
}

/// Bilinear weights of the four corners (s, t) = (0,0), (1,0), (0,1), (1,1).
#[inline]
pub(crate) fn bilinear(s: f32, t: f32) -> [f32; 4] {
    [(1.0 - s) * (1.0 - t), s * (1.0 - t), (1.0 - s) * t, s * t]
}

/// Segments for a direction whose second derivative is bounded by `m`, for error `tol`.
fn segments_for(m: f32, tol: f32, d: &Detail) -> u32 {
    let (lo, hi) = clamp_range(d);
    // NaN too: no bound, no reason to cut finer.
    if m.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return lo;
    }
    let n = (m / (8.0 * tol)).sqrt().ceil();
    if n.is_finite() {
        (n.min(hi as f32) as u32).clamp(lo, hi)
    } else {
        hi
    }
}

/// `[min_segments, max_segments]`, repaired: at least 1, at most 65536, min ≤ max.
fn clamp_range(d: &Detail) -> (u32, u32) {
    let lo = d.min_segments.clamp(1, 65536);
    let hi = d.max_segments.clamp(lo, 65536);
    (lo, hi)
}

/// The tolerance, repaired: a NaN, zero or negative tolerance asks for the finest grid.
fn tolerance(d: &Detail) -> f32 {
    if d.tolerance > 0.0 && d.tolerance.is_finite() {
        d.tolerance
    } else {
        f32::MIN_POSITIVE
    }
}

/// Bounds of |P_ss|, |P_st|, |P_tt| over a face, from central differences of the exact
/// partials at k × k points.
fn second_derivative_bounds<S: Surface + ?Sized>(surf: &S, fu: usize, fv: usize, k: usize) -> [f32; 3] {
    let h = 1e-3f32;
    let mut m = [0.0f32; 3];
    for j in 0..k {
        for i in 0..k {
            let s = i as f32 / (k - 1) as f32;
            let t = j as f32 / (k - 1) as f32;
            let (s0, s1) = ((s - h).max(0.0), (s + h).min(1.0));
            let (t0, t1) = ((t - h).max(0.0), (t + h).min(1.0));
            let a = surf.eval(fu, fv, s0, t);
            let b = surf.eval(fu, fv, s1, t);
            let c = surf.eval(fu, fv, s, t0);
            let e = surf.eval(fu, fv, s, t1);
            let pss = (b.ds - a.ds) / (s1 - s0);
            let ptt = (e.dt - c.dt) / (t1 - t0);
            let pst = 0.5 * ((e.ds - c.ds) / (t1 - t0) + (b.dt - a.dt) / (s1 - s0));
            for (mi, v) in m.iter_mut().zip([pss, pst, ptt]) {
                let l = v.length();
                // A NaN or infinite second derivative asks for the finest grid.
                *mi = if l.is_finite() { mi.max(l) } else { f32::INFINITY };
            }
        }
    }
    m
}

/// Segments per face (s, t) for the whole surface, within the triangle budget.
pub(crate) fn choose_segments<S: Surface + ?Sized>(surf: &S, request: &str, d: &Detail) -> Result<(u32, u32)> {
    let (nfu, nfv) = surf.faces();
    let faces = nfu.saturating_mul(nfv);
    if faces.saturating_mul(2) > MAX_TRIANGLES {
        return err(format!("{request}: {faces} patches exceed the limit of {} triangles", MAX_TRIANGLES));
    }
    let k = match faces {
        0..=16 => 9,
        17..=1024 => 5,
        _ => 3,
    };
    let mut m = [0.0f32; 3];
    for fv in 0..nfv {
        for fu in 0..nfu {
            let b = second_derivative_bounds(surf, fu, fv, k);
            for (mi, bi) in m.iter_mut().zip(b) {
                *mi = mi.max(bi);
            }
        }
    }
    // Safety for maxima between the samples.
    let m = m.map(|x| x * 1.5);
    // The linear interpolation error over a cell is at most (Mss hs² + 2 Mst hs ht + Mtt ht²) / 8:
    // a third of the tolerance for each term.
    let tol3 = tolerance(d) / 3.0;
    let (lo, hi) = clamp_range(d);
    let mut ns = segments_for(m[0], tol3, d);
    let mut nt = segments_for(m[2], tol3, d);
    let cross = 2.0 * m[1] / (ns as f32 * nt as f32) / 8.0;
    if cross > tol3 {
        let f = (cross / tol3).sqrt();
        let grow =
            |n: u32| if f.is_finite() { ((n as f32 * f).ceil().min(hi as f32) as u32).clamp(lo, hi) } else { hi };
        ns = grow(ns);
        nt = grow(nt);
    }
    // The triangle budget.
    let total = |ns: u32, nt: u32| faces as f64 * ns as f64 * nt as f64 * 2.0;
    if total(ns, nt) > MAX_TRIANGLES as f64 {
        let f = (MAX_TRIANGLES as f64 / total(ns, nt)).sqrt();
        ns = ((ns as f64 * f).floor() as u32).max(1);
        nt = ((nt as f64 * f).floor() as u32).max(1);
        while total(ns, nt) > MAX_TRIANGLES as f64 {
            if ns >= nt && ns > 1 {
                ns -= 1;
            } else if nt > 1 {
                nt -= 1;
            } else {
                break;
            }
        }
    }
    Ok((ns, nt))
}

/// The normal at a local point: `normalize(dPdu × dPdv)`, or where that is degenerate (a
/// pole, an apex, a collapsed patch edge) the normal a little inside the face.
fn normal_at<S: Surface + ?Sized>(
    surf: &S,
    fu: usize,
    fv: usize,
    s: f32,
    t: f32,
    e: &Eval,
    scale: Vec2,
) -> Option<Vec3> {
    let cross = |e: &Eval| {
        let (a, b) = (e.ds / scale.x, e.dt / scale.y);
        let c = a.cross(b);
        // Relative tests: a partial tiny next to the other one (a collapsed patch edge, whose
        // partial is rounding noise in any direction), or a cross product tiny next to its
        // factors, is degenerate.
        let (la, lb) = (a.length(), b.length());
        (la > 1e-6 * lb && lb > 1e-6 * la && c.length() > 1e-7 * la * lb).then_some(c).and_then(unit)
    };
    if let Some(n) = cross(e) {
        return Some(n);
    }
    let toward = |x: f32, d: f32| if x < 0.5 { x + d } else { x - d };
    for d in [1e-6f32, 1e-5, 1e-4, 1e-3, 1e-2] {
        for (ss, tt) in [(s, toward(t, d)), (toward(s, d), t), (toward(s, d), toward(t, d))] {
            if let Some(n) = cross(&surf.eval(fu, fv, ss, tt)) {
                return Some(n);
            }
        }
    }
    None
}

/// Per-vertex record: face and local parameters.
struct GridInterp<'a, S: ?Sized> {
    surf: &'a S,
    records: Vec<(u32, u32, f32, f32)>,
}

impl<S: Surface + ?Sized> Interp for GridInterp<'_, S> {
    fn counts(&self) -> Counts {
        self.surf.counts()
    }
    fn vertices(&self) -> usize {
        self.records.len()
    }
    fn weights(&self, class: Class, vertex: usize, out: &mut Vec<(usize, f32)>) {
        out.clear();
        let (fu, fv, s, t) = self.records[vertex];
        let (fu, fv) = (fu as usize, fv as usize);
        match class {
            Class::Constant => out.push((0, 1.0)),
            Class::Uniform => out.push((self.surf.uniform_index(fu, fv), 1.0)),
            Class::Varying | Class::FaceVarying => self.surf.varying_weights(fu, fv, s, t, out),
            Class::Vertex | Class::FaceVertex => self.surf.vertex_weights(fu, fv, s, t, out),
        }
    }
}

/// Tessellates `surf`: positions, normals, u v, s t (= u v), partials, triangles, then the
/// primitive variables of `params` except `skip`.
pub(crate) fn tessellate<S: Surface + ?Sized>(
    surf: &S,
    request: &str,
    params: &ParamList,
    d: &Detail,
    skip: &[&str],
) -> Result<Tessellation> {
    let (ns, nt) = choose_segments(surf, request, d)?;
    let (nfu, nfv) = surf.faces();
    let per_face = (ns as usize + 1) * (nt as usize + 1);
    let nverts = per_face * nfu * nfv;
    if u32::try_from(nverts).is_err() {
        return err(format!("{request}: too many vertices"));
    }
    let mut t = Tessellation {
        positions: Vec::with_capacity(nverts),
        normals: Vec::with_capacity(nverts),
        uv: Vec::with_capacity(nverts),
        st: Vec::with_capacity(nverts),
        dpdu: Vec::with_capacity(nverts),
        dpdv: Vec::with_capacity(nverts),
        triangles: Vec::with_capacity(nfu * nfv * ns as usize * nt as usize * 2),
        ..Tessellation::default()
    };
    let mut records = Vec::with_capacity(nverts);
    let mut missing = Vec::new();
    for fv in 0..nfv {
        for fu in 0..nfu {
            let base = t.positions.len() as u32;
            for j in 0..=nt {
                for i in 0..=ns {
                    let (s, tt) = (i as f32 / ns as f32, j as f32 / nt as f32);
                    let e = surf.eval(fu, fv, s, tt);
                    let (uv, scale) = surf.uv(fu, fv, s, tt);
                    let scale = Vec2::new(
                        if scale.x != 0.0 && scale.x.is_finite() { scale.x } else { 1.0 },
                        if scale.y != 0.0 && scale.y.is_finite() { scale.y } else { 1.0 },
                    );
                    let n = normal_at(surf, fu, fv, s, tt, &e, scale);
                    if n.is_none() {
                        missing.push(t.positions.len());
                    }
                    t.positions.push(e.p);
                    t.normals.push(n.unwrap_or(Vec3::ZERO));
                    t.uv.push(uv);
                    t.st.push(uv);
                    t.dpdu.push(e.ds / scale.x);
                    t.dpdv.push(e.dt / scale.y);
                    records.push((fu as u32, fv as u32, s, tt));
                }
            }
            let row = ns + 1;
            for j in 0..nt {
                for i in 0..ns {
                    let v00 = base + j * row + i;
                    let (v10, v01) = (v00 + 1, v00 + row);
                    let v11 = v01 + 1;
                    for tri in [[v00, v10, v11], [v00, v11, v01]] {
                        let [a, b, c] = tri.map(|k| t.positions[k as usize]);
                        if a != b && b != c && a != c {
                            t.triangles.push(tri);
                        }
                    }
                }
            }
        }
    }
    fill_missing_normals(&mut t, &missing);
    let interp = GridInterp { surf, records };
    primvars::apply(&mut t, request, params, &interp, skip)?;
    t.check(request)
}

/// Gives the vertices without a normal (a wholly degenerate neighbourhood) the mean normal of
/// the triangles around them, else that of the whole surface, else +z.
pub(crate) fn fill_missing_normals(t: &mut Tessellation, missing: &[usize]) {
    if missing.is_empty() {
        return;
    }
    let mut acc = vec![Vec3::ZERO; t.positions.len()];
    let mut total = Vec3::ZERO;
    for tri in &t.triangles {
        let [a, b, c] = tri.map(|i| t.positions[i as usize]);
        let n = (b - a).cross(c - a);
        if n.is_finite() {
            total += n;
            for &i in tri {
                acc[i as usize] += n;
            }
        }
    }
    let fallback = unit(total).unwrap_or(Vec3::Z);
    for &i in missing {
        t.normals[i] = unit(acc[i]).unwrap_or(fallback);
    }
}
