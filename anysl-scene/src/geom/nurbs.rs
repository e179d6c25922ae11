//! `NuPatch` (RI 3.2 §5.2.2): a non-uniform rational B-spline surface.
//!
//! The basis functions and their first derivatives come from the Cox–de Boor recurrence
//! (Piegl and Tiller, *The NURBS Book*, A2.2 and eq. 2.7), in f64. "Pw" control points are
//! homogeneous (x, y, z, w): the surface is evaluated in 4D and divided by w, so the partials
//! are exact for rational surfaces too. Each non-empty knot span inside [umin, umax] ×
//! [vmin, vmax] is one face of the tessellation grid, so creases at repeated knots fall on
//! grid lines.
//!
//! u and v are the knot-space parameters themselves (umin ≤ u ≤ umax), as the RI spec
//! defines them for NuPatch; s, t default to u, v. Uniform variables are per segment
//! ((nu − uorder + 1) × (nv − vorder + 1)), varying ones on the segment corners
//! ((nu − uorder + 2) × (nv − vorder + 2)), vertex ones per control point. Trim curves are
//! not applied (the scene builder warns).

use super::grid::{self, bilinear, Eval, Surface};
use super::patches::rational;
use super::primvars::{self, Counts, POSITION_NAMES};
use super::{err, Detail, Result, Tessellation};
use anysl_rib::ParamList;
use glam::{DVec4, Vec2, Vec4};

/// Highest order accepted (evaluation costs order² per point and direction).
const MAX_ORDER: usize = 64;

/// One parametric direction: knots, order, control points, and the faces (spans) in use.
struct Dir {
    knots: Vec<f64>,
    order: usize,
    n: usize,
    /// (span index k, lo, hi): the part [lo, hi] of [knot[k], knot[k+1]] inside [min, max].
    faces: Vec<(usize, f64, f64)>,
}

impl Dir {
    fn new(request: &str, which: &str, n: i32, order: i32, knots: &[f32], min: f32, max: f32) -> Result<Self> {
        let (Ok(n), Ok(order)) = (usize::try_from(n), usize::try_from(order)) else {
            return err(format!("{request}: n{which} = {n} and {which}order = {order} must be positive"));
        };
        if !(2..=MAX_ORDER).contains(&order) {
            return err(format!("{request}: {which}order is {order}; it must be 2 to {MAX_ORDER}"));
        }
        if n < order {
            return err(format!("{request}: n{which} = {n} control points are fewer than the order {order}"));
        }
        if knots.len() != n + order {
            return err(format!(
                "{request}: {which}knot has {} values, expected n{which} + {which}order = {}",
                knots.len(),
                n + order
            ));
        }
        if let Some(i) = knots.iter().position(|k| !k.is_finite()) {
            return err(format!("{request}: {which}knot[{i}] is {}, not a finite number", knots[i]));
        }
        if let Some(i) = knots.windows(2).position(|w| w[1] < w[0]) {
            return err(format!(
                "{request}: {which}knot decreases at index {} ({} > {})",
                i + 1,
                knots[i],
                knots[i + 1]
            ));
        }
        if !min.is_finite() || !max.is_finite() {
            return err(format!("{request}: {which}min and {which}max must be finite ({min}, {max})"));
        }
        let knots: Vec<f64> = knots.iter().map(|&k| k as f64).collect();
        let p = order - 1;
        let (lo, hi) = (knots[p].max(min as f64), knots[n].min(max as f64));
        let faces = (p..n)
            .filter_map(|k| {
                let (a, b) = (knots[k].max(lo), knots[k + 1].min(hi));
                (a < b).then_some((k, a, b))
            })
            .collect();
        Ok(Self { knots, order, n, faces })
    }

    /// The nonzero basis functions at x in span k and their derivatives (order of each).
    fn basis(&self, k: usize, x: f64, nb: &mut [f64; MAX_ORDER], db: &mut [f64; MAX_ORDER]) {
        let p = self.order - 1;
        let u = &self.knots;
        let mut left = [0.0f64; MAX_ORDER];
        let mut right = [0.0f64; MAX_ORDER];
        let mut prev = [0.0f64; MAX_ORDER];
        nb[0] = 1.0;
        for j in 1..=p {
            if j == p {
                prev[..p].copy_from_slice(&nb[..p]);
            }
            left[j] = x - u[k + 1 - j];
            right[j] = u[k + j] - x;
            let mut saved = 0.0;
            for r in 0..j {
                let den = right[r + 1] + left[j - r];
                let temp = if den != 0.0 { nb[r] / den } else { 0.0 };
                nb[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            nb[j] = saved;
        }
        // N'ᵢ,ₚ = p Nᵢ,ₚ₋₁ / (uᵢ₊ₚ − uᵢ) − p Nᵢ₊₁,ₚ₋₁ / (uᵢ₊ₚ₊₁ − uᵢ₊₁), with prev[m] = N_{k−p+1+m, p−1}.
        for i in 0..=p {
            let g = k - p + i;
            let a = if i >= 1 { prev[i - 1] } else { 0.0 };
            let b = if i < p { prev[i] } else { 0.0 };
            let da = u[g + p] - u[g];
            let dbk = u[g + p + 1] - u[g + 1];
            db[i] = p as f64 * (if da != 0.0 { a / da } else { 0.0 } - if dbk != 0.0 { b / dbk } else { 0.0 });
        }
    }

    /// The parameter at local x of face f, and the face's width.
    fn param(&self, f: usize, x: f32) -> (usize, f64, f64) {
        let (k, lo, hi) = self.faces[f];
        (k, lo + (hi - lo) * x as f64, hi - lo)
    }
}

struct NuSurface {
    u: Dir,
    v: Dir,
    /// Homogeneous control points, u fastest.
    pts: Vec<Vec4>,
}

impl NuSurface {
    /// Segments (spans of the full knot range) along u and v.
    fn segments(&self) -> (usize, usize) {
        (self.u.n - self.u.order + 1, self.v.n - self.v.order + 1)
    }
}

impl Surface for NuSurface {
    fn faces(&self) -> (usize, usize) {
        (self.u.faces.len(), self.v.faces.len())
    }

    fn eval(&self, fu: usize, fv: usize, s: f32, t: f32) -> Eval {
        let (ku, x, wu) = self.u.param(fu, s);
        let (kv, y, wv) = self.v.param(fv, t);
        let (mut nu, mut dnu, mut nv, mut dnv) =
            ([0.0; MAX_ORDER], [0.0; MAX_ORDER], [0.0; MAX_ORDER], [0.0; MAX_ORDER]);
        self.u.basis(ku, x, &mut nu, &mut dnu);
        self.v.basis(kv, y, &mut nv, &mut dnv);
        let (pu, pv) = (self.u.order - 1, self.v.order - 1);
        let (mut h, mut hs, mut ht) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        for j in 0..=pv {
            let row = (kv - pv + j) * self.u.n;
            for i in 0..=pu {
                let p = self.pts[row + ku - pu + i].as_dvec4();
                h += nu[i] * nv[j] * p;
                hs += dnu[i] * nv[j] * p;
                ht += nu[i] * dnv[j] * p;
            }
        }
        // Partials along the local (s, t): times the face widths.
        rational(h, hs * wu, ht * wv)
    }

    fn uv(&self, fu: usize, fv: usize, s: f32, t: f32) -> (Vec2, Vec2) {
        let (_, x, wu) = self.u.param(fu, s);
        let (_, y, wv) = self.v.param(fv, t);
        (Vec2::new(x as f32, y as f32), Vec2::new(wu as f32, wv as f32))
    }

    fn counts(&self) -> Counts {
        let (su, sv) = self.segments();
        let varying = (su + 1) * (sv + 1);
        Counts { uniform: su * sv, varying, vertex: self.u.n * self.v.n, facevarying: varying, vertex_at_least: false }
    }

    fn uniform_index(&self, fu: usize, fv: usize) -> usize {
        let (su, _) = self.segments();
        (self.v.faces[fv].0 + 1 - self.v.order) * su + (self.u.faces[fu].0 + 1 - self.u.order)
    }

    fn varying_weights(&self, fu: usize, fv: usize, s: f32, t: f32, out: &mut Vec<(usize, f32)>) {
        let (su, _) = self.segments();
        let corner = |d: &Dir, f: usize, x: f32| {
            let (k, x, _) = d.param(f, x);
            let (a, b) = (d.knots[k], d.knots[k + 1]);
            (k + 1 - d.order, ((x - a) / (b - a)) as f32)
        };
        let (i, a) = corner(&self.u, fu, s);
        let (j, b) = corner(&self.v, fv, t);
        let w = bilinear(a, b);
        let row = su + 1;
        out.extend([
            (j * row + i, w[0]),
            (j * row + i + 1, w[1]),
            ((j + 1) * row + i, w[2]),
            ((j + 1) * row + i + 1, w[3]),
        ]);
    }

    fn vertex_weights(&self, fu: usize, fv: usize, s: f32, t: f32, out: &mut Vec<(usize, f32)>) {
        let (ku, x, _) = self.u.param(fu, s);
        let (kv, y, _) = self.v.param(fv, t);
        let (mut nu, mut dnu, mut nv, mut dnv) =
            ([0.0; MAX_ORDER], [0.0; MAX_ORDER], [0.0; MAX_ORDER], [0.0; MAX_ORDER]);
        self.u.basis(ku, x, &mut nu, &mut dnu);
        self.v.basis(kv, y, &mut nv, &mut dnv);
        let (pu, pv) = (self.u.order - 1, self.v.order - 1);
        for (j, wv) in nv[..=pv].iter().enumerate() {
            for (i, wu) in nu[..=pu].iter().enumerate() {
                out.push(((kv - pv + j) * self.u.n + ku - pu + i, (wu * wv) as f32));
            }
        }
    }
}

/// `NuPatch nu uorder uknot umin umax nv vorder vknot vmin vmax`.
#[allow(clippy::too_many_arguments)]
pub fn nu_patch(
    nu: i32,
    uorder: i32,
    uknot: &[f32],
    umin: f32,
    umax: f32,
    nv: i32,
    vorder: i32,
    vknot: &[f32],
    vmin: f32,
    vmax: f32,
    params: &ParamList,
    d: &Detail,
) -> Result<Tessellation> {
    let request = "NuPatch";
    let u = Dir::new(request, "u", nu, uorder, uknot, umin, umax)?;
    let v = Dir::new(request, "v", nv, vorder, vknot, vmin, vmax)?;
    let Some(total) = u.n.checked_mul(v.n) else {
        return err(format!("{request}: nu × nv is too large"));
    };
    let (pts, name) = primvars::positions(request, params, false)?;
    if pts.len() != total {
        return err(format!(
            "{request}: \"{name}\" has {} points, expected nu × nv = {} × {} = {total}",
            pts.len(),
            u.n,
            v.n
        ));
    }
    let surf = NuSurface { u, v, pts };
    if surf.u.faces.is_empty() || surf.v.faces.is_empty() {
        // umin ≥ umax, or a range outside the knots: nothing to draw.
        return Ok(Tessellation::default());
    }
    grid::tessellate(&surf, request, params, d, POSITION_NAMES)
}
