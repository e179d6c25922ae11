//! RSL derivative built-ins of `anysl_core::stdlib` through `Dual`, with `Globals` whose u
//! and v carry screen-space derivatives, against analytic values.

use crate::common;

use anysl_ad::Dual;
use anysl_core::stdlib::{
    area, calculatenormal, deriv, du, dv, filteredpulse, filterstep, filterwidth, filterwidth_point,
};
use anysl_core::{Globals, ShadingFloat, Vec3};
use common::Rng;

/// A shading point: u, v and the Jacobian `[[ux, uy], [vx, vy]]` of (u, v) over (x, y).
#[derive(Clone, Copy, Debug)]
struct Case {
    u: f64,
    v: f64,
    ux: f64,
    uy: f64,
    vx: f64,
    vy: f64,
}

impl Case {
    fn random(rng: &mut Rng) -> Self {
        loop {
            let c = Case {
                u: rng.range(0.0, 1.0),
                v: rng.range(0.0, 1.0),
                ux: rng.range(-0.01, 0.01),
                uy: rng.range(-0.01, 0.01),
                vx: rng.range(-0.01, 0.01),
                vy: rng.range(-0.01, 0.01),
            };
            if c.det().abs() > 1e-5 && c.ux.abs() + c.uy.abs() > 2e-3 {
                return c;
            }
        }
    }
    fn det(&self) -> f64 {
        self.ux * self.vy - self.uy * self.vx
    }
    fn globals<F: ShadingFloat>(&self) -> Globals<Dual<F>> {
        let u = Dual::new(F::c(self.u), F::c(self.ux), F::c(self.uy));
        let v = Dual::new(F::c(self.v), F::c(self.vx), F::c(self.vy));
        Globals::unit_square(u, v)
    }
}

fn check<F: ShadingFloat>(tol: f64) {
    let close = |name: &str, c: &Case, got: Dual<F>, want: f64| {
        let g = got.lane(0);
        assert!((g - want).abs() <= tol * (want.abs() + 1.0), "{name} at {c:?}: {g} vs {want}");
    };
    let mut rng = Rng::new(0xDE21);
    for _ in 0..500 {
        let c = Case::random(&mut rng);
        let g = c.globals::<F>();
        let (u, v) = (g.u, g.v);
        // f = u² + 3v + uv: ∂f/∂u = 2u + v, ∂f/∂v = 3 + u.
        let f = u * u + Dual::c(3.0) * v + u * v;
        close("Du", &c, du(&g, f), 2.0 * c.u + c.v);
        close("Dv", &c, dv(&g, f), 3.0 + c.u);
        // Deriv(u², u + v) = 2u/1 + 0/1.
        close("Deriv", &c, deriv(&g, u * u, u + v), 2.0 * c.u);
        // P = (u - ½, v - ½, 0): ∂P/∂x × ∂P/∂y = (0, 0, det J).
        close("area", &c, area(g.P), c.det().abs());
        close("filterwidth(P)", &c, filterwidth_point(g.P), c.det().abs().sqrt());
        let (fu, fv) = (2.0 * c.u + c.v, 3.0 + c.u);
        let (fx, fy) = (fu * c.ux + fv * c.vx, fu * c.uy + fv * c.vy);
        close("filterwidth", &c, filterwidth(f), fx.abs() + fy.abs());
        // filterstep(edge, u): a ramp of width |ux| + |uy| centred on the edge.
        let w = c.ux.abs() + c.uy.abs();
        for edge in [c.u - 0.7 * w, c.u - 0.2 * w, c.u, c.u + 0.3 * w, c.u + 2.0 * w] {
            let want = ((c.u - edge) / w + 0.5).clamp(0.0, 1.0);
            close("filterstep", &c, filterstep(Dual::c(edge), u), want);
            let pulse = ((c.u - edge) / w + 0.5).clamp(0.0, 1.0) - ((c.u - edge - 0.5) / w + 0.5).clamp(0.0, 1.0);
            close("filteredpulse", &c, filteredpulse(Dual::c(edge), Dual::c(edge + 0.5), u), pulse);
        }
        // P on the paraboloid (u, v, u² + v²): Du(P) × Dv(P) = (-2u, -2v, 1).
        let p = Vec3::new(u, v, u * u + v * v);
        let n = calculatenormal(&g, p);
        close("N.x", &c, n.x, -2.0 * c.u);
        close("N.y", &c, n.y, -2.0 * c.v);
        close("N.z", &c, n.z, 1.0);
    }
}

#[test]
fn derivative_builtins_through_dual_f64() {
    check::<f64>(1e-9);
}

/// In f32 the worst term is filterstep's `(u - edge)/w`: an O(1) difference rounded to f32
/// (≤ 2·6e-8 absolute) divided by the footprint `w ≥ 2e-3`, i.e. ≤ 6e-5; the 2×2 inverse
/// (entries ≤ 1e-2, det ≥ 1e-5, condition ≤ 40) adds ≤ 3e-6. Tolerance 1e-4.
#[test]
fn derivative_builtins_through_dual_f32() {
    check::<f32>(1e-4);
}

#[test]
fn degenerate_and_missing_derivatives_give_zero() {
    // No derivatives on u, v: Du/Dv are 0, filterstep is step.
    let g = Globals::unit_square(Dual::constant(0.3f32), Dual::constant(0.6));
    let f = g.u * g.v;
    assert_eq!(du(&g, f).val, 0.0);
    assert_eq!(dv(&g, f).val, 0.0);
    assert_eq!(filterwidth(g.u).val, 0.0);
    assert_eq!(filterstep(Dual::c(0.2), g.u).val, 1.0);
    assert_eq!(filterstep(Dual::c(0.4), g.u).val, 0.0);
    // Singular Jacobian (u and v vary together): 0, never NaN.
    let u = Dual::new(0.3f32, 0.01, 0.02);
    let v = Dual::new(0.6f32, 0.02, 0.04);
    let g = Globals::unit_square(u, v);
    assert_eq!(du(&g, u * v).val, 0.0);
    assert_eq!(area(g.P).val, 0.0);
    // The results are values: no derivatives of their own.
    let g = Globals::unit_square(Dual::new(0.3f32, 0.01, 0.0), Dual::new(0.6f32, 0.0, 0.01));
    let d = du(&g, g.u * g.u);
    assert!((d.val - 0.6).abs() < 1e-5 && d.ddx == 0.0 && d.ddy == 0.0);
}
