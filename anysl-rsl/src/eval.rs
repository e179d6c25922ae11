//! The shading points of `anysl rslc eval` (and of the conformance suite): a grid on a unit
//! square facing the camera, like OSL's `testshade`.

use anysl_core::{Color, Globals, ShadingFloat, Vec3};

/// The globals `--global NAME=VALUE` may override.
pub const GLOBAL_NAMES: [&str; 15] =
    ["P", "N", "Ng", "I", "E", "s", "t", "u", "v", "du", "dv", "dPdu", "dPdv", "Cs", "Os"];

/// True for the float (not triple) globals among [`GLOBAL_NAMES`].
#[must_use]
pub fn is_float_global(name: &str) -> bool {
    matches!(name, "s" | "t" | "u" | "v" | "du" | "dv")
}

/// The globals of grid point `(i, j)` of a `w × h` grid: `u = (i + ½)/w`, `v = (j + ½)/h`,
/// `s = u`, `t = v`, `du = 1/w`, `dv = 1/h`, `P = (u, v, 0)`, `N = Ng = (0, 0, 1)`,
/// `E = (0, 0, 3)`, `I = P − E`, `dPdu = (1, 0, 0)`, `dPdv = (0, 1, 0)`, `Cs = Os = 1`, then the
/// overrides in order (one number, or three for triples; setting `P` also sets `I = P − E`),
/// constant over the grid. With dual numbers screen x follows u and y follows v, one grid step
/// per pixel: `∂u/∂x = du`, `∂v/∂y = dv`.
#[must_use]
pub fn grid_globals<F: ShadingFloat, S: AsRef<str>>(
    i: usize,
    j: usize,
    w: usize,
    h: usize,
    overrides: &[(S, Vec<f64>)],
) -> Globals<F> {
    let (du_, dv_) = (1.0 / w.max(1) as f64, 1.0 / h.max(1) as f64);
    let (uu, vv) = ((i as f64 + 0.5) * du_, (j as f64 + 0.5) * dv_);
    let z = F::c(0.0);
    let u = F::c(uu).with_derivs(F::c(du_), z);
    let v = F::c(vv).with_derivs(z, F::c(dv_));
    let p = Vec3::new(u, v, z);
    let e = Vec3::c(0.0, 0.0, 3.0);
    let mut g = Globals {
        P: p,
        N: Vec3::c(0.0, 0.0, 1.0),
        Ng: Vec3::c(0.0, 0.0, 1.0),
        I: p - e,
        E: e,
        s: u,
        t: v,
        u,
        v,
        du: F::c(du_),
        dv: F::c(dv_),
        dPdu: Vec3::c(1.0, 0.0, 0.0),
        dPdv: Vec3::c(0.0, 1.0, 0.0),
        Cs: Color::c(1.0, 1.0, 1.0),
        Os: Color::c(1.0, 1.0, 1.0),
    };
    for (name, vals) in overrides {
        if vals.is_empty() {
            continue;
        }
        let t = |k: usize| F::c(vals[k.min(vals.len() - 1)]);
        let v3 = Vec3::new(t(0), t(1), t(2));
        let c3 = Color::new(t(0), t(1), t(2));
        match name.as_ref() {
            "P" => {
                g.P = v3;
                g.I = v3 - g.E;
            }
            "N" => g.N = v3,
            "Ng" => g.Ng = v3,
            "I" => g.I = v3,
            "E" => g.E = v3,
            "dPdu" => g.dPdu = v3,
            "dPdv" => g.dPdv = v3,
            "Cs" => g.Cs = c3,
            "Os" => g.Os = c3,
            "s" => g.s = t(0),
            "t" => g.t = t(0),
            "u" => g.u = t(0),
            "v" => g.v = t(0),
            "du" => g.du = t(0),
            "dv" => g.dv = t(0),
            _ => {}
        }
    }
    g
}
