//! Patches (RI 3.2 §5.2): `Patch` (bilinear, bicubic) and `PatchMesh`, with the bases of
//! `Basis`.
//!
//! A bicubic patch is P(u, v) = Σᵢ Σⱼ Bᵢ(u) Bⱼ(v) P[j·4 + i] (u varies fastest in "P"), with
//! Bᵢ(u) = Σₖ uᵏ' M[k][i] for the row vector (u³, u², u, 1) and the basis matrix M as RIB
//! writes it (row-major). In a mesh, patch (i, j) starts at control point (i·ustep, j·vstep)
//! (modulo nu, nv when periodic), and u, v run over [0, 1] across the whole mesh: patch i of
//! n covers u ∈ [i/n, (i+1)/n]. Varying variables sit on the patch corners (nupatches + 1 per
//! row when nonperiodic, nupatches when periodic), uniform ones on the patches, vertex ones on
//! the control points (interpolated with the same basis). "Pw" makes the patch rational
//! (evaluated in homogeneous space, then divided by w). With "Pz" the control points are
//! placed evenly over [0, 1]² in x and y (x = i/(nu−1), y = j/(nv−1)) at height z.

use super::grid::{self, bilinear, Eval, Surface};
use super::primvars::{self, Counts, POSITION_NAMES};
use super::{err, Detail, GeomError, Result, Tessellation};
use anysl_rib::{Basis, ParamList};
use glam::{DVec4, Mat4, Vec2, Vec4};

/// Patch bases and steps, as set by `Basis` (default bezier 3 / bezier 3).
///
/// The matrices are the basis matrices M of the RI spec: `u.row(k)[i]` is M[k][i] for the
/// row vector (u³, u², u, 1).
#[derive(Clone, Debug, PartialEq)]
pub struct PatchBasis {
    /// Basis along u.
    pub u: Mat4,
    /// Control points from one patch to the next along u.
    pub ustep: u32,
    /// Basis along v.
    pub v: Mat4,
    /// Control points from one patch to the next along v.
    pub vstep: u32,
}

impl Default for PatchBasis {
    /// Bézier, step 3, in both directions.
    fn default() -> Self {
        let (m, step) = PatchBasis::named("bezier").unwrap_or((Mat4::IDENTITY, 3));
        Self { u: m, ustep: step, v: m, vstep: step }
    }
}

/// A matrix from 16 numbers in row-major order.
fn rows(m: [f32; 16]) -> Mat4 {
    Mat4::from_cols_array(&m).transpose()
}

impl PatchBasis {
    /// The matrix and the usual step of a standard basis: `bezier` (3), `b-spline` (1),
    /// `catmull-rom` (1), `hermite` (2), `power` (4), as RI 3.2 defines them.
    #[must_use]
    pub fn named(name: &str) -> Option<(Mat4, u32)> {
        let s = 1.0 / 6.0;
        Some(match name.to_ascii_lowercase().as_str() {
            "bezier" => (rows([-1., 3., -3., 1., 3., -6., 3., 0., -3., 3., 0., 0., 1., 0., 0., 0.]), 3),
            "b-spline" | "bspline" => (
                rows([-s, 3. * s, -3. * s, s, 3. * s, -6. * s, 3. * s, 0., -3. * s, 0., 3. * s, 0., s, 4. * s, s, 0.]),
                1,
            ),
            "catmull-rom" | "catmullrom" => {
                (rows([-0.5, 1.5, -1.5, 0.5, 1., -2.5, 2., -0.5, -0.5, 0., 0.5, 0., 0., 1., 0., 0.]), 1)
            }
            "hermite" => (rows([2., 1., -2., 1., -3., -2., 3., -1., 0., 1., 0., 0., 1., 0., 0., 0.]), 2),
            "power" => (Mat4::IDENTITY, 4),
            _ => return None,
        })
    }

    /// The bases of a `Basis` request: names as in [`PatchBasis::named`] or 16 numbers in
    /// row-major order. Steps must be positive.
    pub fn from_rib(u: &Basis, ustep: i32, v: &Basis, vstep: i32) -> Result<Self> {
        let one = |b: &Basis, which: &str| {
            match b {
            Basis::Named(n) => PatchBasis::named(n).map(|(m, _)| m).ok_or_else(|| {
                GeomError(format!(
                    "Basis: unknown {which} basis \"{n}\" (known: bezier, b-spline, catmull-rom, hermite, power, or 16 numbers)"
                ))
            }),
            Basis::Matrix(m) if m.iter().all(|x| x.is_finite()) => Ok(rows(*m)),
            Basis::Matrix(_) => err(format!("Basis: the {which} basis matrix has a non-finite number")),
        }
        };
        let step = |s: i32, which: &str| {
            u32::try_from(s)
                .ok()
                .filter(|&s| s > 0)
                .ok_or_else(|| GeomError(format!("Basis: {which} is {s}, not a positive step")))
        };
        Ok(Self { u: one(u, "u")?, ustep: step(ustep, "ustep")?, v: one(v, "v")?, vstep: step(vstep, "vstep")? })
    }
}

/// Weights of the four control points at `x` and their derivatives, for basis matrix `m`
/// (in f64: at a collapsed patch edge the derivative is a sum that cancels, and f32 rounding
/// would leave noise that looks like a direction).
#[inline]
pub(crate) fn cubic_weights(m: &Mat4, x: f32) -> ([f64; 4], [f64; 4]) {
    let x = x as f64;
    let pw = [x * x * x, x * x, x, 1.0];
    let dpw = [3.0 * x * x, 2.0 * x, 1.0, 0.0];
    let mut w = [0.0; 4];
    let mut dw = [0.0; 4];
    for k in 0..4 {
        let r = m.row(k).as_dvec4().to_array();
        for i in 0..4 {
            w[i] += pw[k] * r[i];
            dw[i] += dpw[k] * r[i];
        }
    }
    (w, dw)
}

/// A patch mesh (a single patch is a 1 × 1 mesh).
pub(crate) struct Mesh {
    pub bicubic: bool,
    pub nu: usize,
    pub nv: usize,
    pub uperiodic: bool,
    pub vperiodic: bool,
    pub npu: usize,
    pub npv: usize,
    pub ustep: usize,
    pub vstep: usize,
    pub bu: Mat4,
    pub bv: Mat4,
    /// Homogeneous control points, u fastest.
    pub pts: Vec<Vec4>,
}

impl Mesh {
    /// Weights and derivative weights along one direction, and the control-point indices.
    #[inline]
    fn dir(&self, along_u: bool, face: usize, x: f32) -> ([f64; 4], [f64; 4], [usize; 4], usize) {
        let (m, step, n) = if along_u { (&self.bu, self.ustep, self.nu) } else { (&self.bv, self.vstep, self.nv) };
        let first = face * step;
        let idx = [0, 1, 2, 3].map(|k| (first + k) % n.max(1));
        if self.bicubic {
            let (w, dw) = cubic_weights(m, x);
            (w, dw, idx, 4)
        } else {
            let x = x as f64;
            ([1.0 - x, x, 0.0, 0.0], [-1.0, 1.0, 0.0, 0.0], idx, 2)
        }
    }
}

impl Surface for Mesh {
    fn faces(&self) -> (usize, usize) {
        (self.npu, self.npv)
    }

    fn eval(&self, fu: usize, fv: usize, s: f32, t: f32) -> Eval {
        let (wu, dwu, iu, ku) = self.dir(true, fu, s);
        let (wv, dwv, iv, kv) = self.dir(false, fv, t);
        let (mut h, mut hs, mut ht) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        for j in 0..kv {
            let row = iv[j] * self.nu;
            for i in 0..ku {
                let p = self.pts[row + iu[i]].as_dvec4();
                h += wu[i] * wv[j] * p;
                hs += dwu[i] * wv[j] * p;
                ht += wu[i] * dwv[j] * p;
            }
        }
        rational(h, hs, ht)
    }

    fn uv(&self, fu: usize, fv: usize, s: f32, t: f32) -> (Vec2, Vec2) {
        let (nu, nv) = (self.npu as f32, self.npv as f32);
        (Vec2::new((fu as f32 + s) / nu, (fv as f32 + t) / nv), Vec2::new(1.0 / nu, 1.0 / nv))
    }

    fn counts(&self) -> Counts {
        let (vu, vv) = self.varying_dims();
        let varying = vu * vv;
        Counts {
            uniform: self.npu * self.npv,
            varying,
            vertex: self.nu * self.nv,
            facevarying: varying,
            vertex_at_least: false,
        }
    }

    fn uniform_index(&self, fu: usize, fv: usize) -> usize {
        fv * self.npu + fu
    }

    fn varying_weights(&self, fu: usize, fv: usize, s: f32, t: f32, out: &mut Vec<(usize, f32)>) {
        let (vu, vv) = self.varying_dims();
        let (u0, u1) = (fu % vu, (fu + 1) % vu);
        let (v0, v1) = (fv % vv, (fv + 1) % vv);
        let w = bilinear(s, t);
        out.extend([(v0 * vu + u0, w[0]), (v0 * vu + u1, w[1]), (v1 * vu + u0, w[2]), (v1 * vu + u1, w[3])]);
    }

    fn vertex_weights(&self, fu: usize, fv: usize, s: f32, t: f32, out: &mut Vec<(usize, f32)>) {
        let (wu, _, iu, ku) = self.dir(true, fu, s);
        let (wv, _, iv, kv) = self.dir(false, fv, t);
        for j in 0..kv {
            for i in 0..ku {
                out.push((iv[j] * self.nu + iu[i], (wu[i] * wv[j]) as f32));
            }
        }
    }
}

impl Mesh {
    /// Varying items along u and v.
    fn varying_dims(&self) -> (usize, usize) {
        (if self.uperiodic { self.npu } else { self.npu + 1 }, if self.vperiodic { self.npv } else { self.npv + 1 })
    }
}

/// Point and partials from homogeneous sums: P = H/w, P' = (H' − P w')/w.
#[inline]
pub(crate) fn rational(h: DVec4, hs: DVec4, ht: DVec4) -> Eval {
    let p = h.truncate() / h.w;
    let (ds, dt) = ((hs.truncate() - p * hs.w) / h.w, (ht.truncate() - p * ht.w) / h.w);
    Eval { p: p.as_vec3(), ds: ds.as_vec3(), dt: dt.as_vec3() }
}

/// `Patch type`: one `"bilinear"` (4 points) or `"bicubic"` (16 points) patch.
pub fn patch(kind: &str, basis: &PatchBasis, params: &ParamList, d: &Detail) -> Result<Tessellation> {
    let n = match kind {
        "bilinear" => 2,
        "bicubic" => 4,
        _ => return err(format!("Patch: unknown type \"{kind}\" (bilinear or bicubic)")),
    };
    mesh("Patch", kind, n, false, n, false, basis, params, d)
}

/// `PatchMesh type nu uwrap nv vwrap`: a mesh of nu × nv control points.
#[allow(clippy::too_many_arguments)]
pub fn patch_mesh(
    kind: &str,
    nu: i32,
    uwrap: &str,
    nv: i32,
    vwrap: &str,
    basis: &PatchBasis,
    params: &ParamList,
    d: &Detail,
) -> Result<Tessellation> {
    let request = "PatchMesh";
    if kind != "bilinear" && kind != "bicubic" {
        return err(format!("{request}: unknown type \"{kind}\" (bilinear or bicubic)"));
    }
    let wrap = |w: &str, which: &str| match w {
        "periodic" => Ok(true),
        "nonperiodic" => Ok(false),
        _ => err(format!("{request}: {which} is \"{w}\", not \"periodic\" or \"nonperiodic\"")),
    };
    let (up, vp) = (wrap(uwrap, "uwrap")?, wrap(vwrap, "vwrap")?);
    let count = |n: i32, which: &str| {
        usize::try_from(n)
            .ok()
            .filter(|&n| n > 0)
            .ok_or_else(|| GeomError(format!("{request}: {which} is {n}, not a positive count")))
    };
    mesh(request, kind, count(nu, "nu")?, up, count(nv, "nv")?, vp, basis, params, d)
}

/// Patches along one direction, or an error saying why `n` control points do not fit.
fn patches_along(request: &str, which: &str, bicubic: bool, n: usize, periodic: bool, step: usize) -> Result<usize> {
    let fit = match (bicubic, periodic) {
        (false, false) => (n >= 2).then(|| n - 1),
        (false, true) => (n >= 2).then_some(n),
        (true, false) => (n >= 4 && (n - 4).is_multiple_of(step)).then(|| (n - 4) / step + 1),
        (true, true) => (n >= step.max(1) && n.is_multiple_of(step)).then(|| n / step),
    };
    fit.filter(|&p| p > 0).ok_or_else(|| {
        let need = match (bicubic, periodic) {
            (false, _) => "at least 2".to_string(),
            (true, false) => format!("4 + a multiple of the step {step}"),
            (true, true) => format!("a positive multiple of the step {step}"),
        };
        GeomError(format!(
            "{request}: {which} = {n} control points do not make whole {} patches ({} wants {need})",
            if bicubic { "bicubic" } else { "bilinear" },
            if periodic { "periodic" } else { "nonperiodic" },
        ))
    })
}

#[allow(clippy::too_many_arguments)]
fn mesh(
    request: &str,
    kind: &str,
    nu: usize,
    uperiodic: bool,
    nv: usize,
    vperiodic: bool,
    basis: &PatchBasis,
    params: &ParamList,
    d: &Detail,
) -> Result<Tessellation> {
    let bicubic = kind == "bicubic";
    let (ustep, vstep) = if bicubic { (basis.ustep as usize, basis.vstep as usize) } else { (1, 1) };
    let npu = patches_along(request, "nu", bicubic, nu, uperiodic, ustep.max(1))?;
    let npv = patches_along(request, "nv", bicubic, nv, vperiodic, vstep.max(1))?;
    let Some(total) = nu.checked_mul(nv) else {
        return err(format!("{request}: nu × nv = {nu} × {nv} is too large"));
    };
    let (mut pts, name) = primvars::positions(request, params, true)?;
    if pts.len() != total {
        return err(format!(
            "{request}: \"{name}\" has {} points, expected nu × nv = {nu} × {nv} = {total}",
            pts.len()
        ));
    }
    if name == "Pz" {
        let (du, dv) = (1.0 / (nu.max(2) - 1) as f32, 1.0 / (nv.max(2) - 1) as f32);
        for (k, p) in pts.iter_mut().enumerate() {
            p.x = (k % nu) as f32 * du;
            p.y = (k / nu) as f32 * dv;
        }
    }
    let m = Mesh {
        bicubic,
        nu,
        nv,
        uperiodic,
        vperiodic,
        npu,
        npv,
        ustep: ustep.max(1),
        vstep: vstep.max(1),
        bu: basis.u,
        bv: basis.v,
        pts,
    };
    grid::tessellate(&m, request, params, d, POSITION_NAMES)
}
