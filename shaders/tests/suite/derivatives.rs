//! The filtered shaders with dual numbers: antialiased edges with derivatives, exactly the
//! unfiltered pattern without.

use anysl_ad::Dual;
use anysl_core::prelude::*;
use anysl_core::PointContext;
use anysl_shaders::{table1_lights, Brick, Checker, Surface};

type D = Dual<f64>;

#[test]
fn checker_edges_are_filtered_with_derivatives() {
    let c = Checker::default(); // frequency 10: edges at s = 0.05·k
    let t = D::new(0.22, 0.0, 0.0); // lower half period in t
    let w = |s: f64, ds: f64| c.black_weight(D::new(s, ds, 0.0), t).lane(0);
    // On the rising edge (s·f = 0.5) and on the falling edge (s·f = 1): half covered.
    assert!((w(0.05, 0.01) - 0.5).abs() < 1e-12);
    assert!((w(0.1, 0.01) - 0.5).abs() < 1e-12);
    // A quarter footprint past the rising edge: 0.75; far from edges: the plain step.
    assert!((w(0.05 + 0.0025, 0.01) - 0.75).abs() < 1e-12);
    assert_eq!(w(0.025, 0.01), 0.0);
    assert_eq!(w(0.075, 0.01), 1.0);
    // Without derivatives it is exactly step, on both edges.
    for s in [0.0499, 0.05, 0.0501, 0.0999, 0.1, 0.1001] {
        let plain: f64 = c.black_weight(s, 0.22);
        assert_eq!(w(s, 0.0), plain, "s = {s}");
        assert_eq!(plain, if (s * 10.0f64).fract() >= 0.5 { 1.0 } else { 0.0 });
    }
}

#[test]
fn brick_joints_are_filtered_with_derivatives() {
    let b = Brick::default();
    let t = D::new(0.04, 0.0, 0.0); // middle of the first row
                                    // The first vertical joint is centred on s = 0 (mortar half-width 0.005).
    let inb = |s: f64, ds: f64| b.pattern(D::new(s, ds, 0.0), t).0.lane(0);
    assert_eq!(inb(0.1, 0.001), 1.0);
    let edge = inb(0.005, 0.002);
    assert!(edge > 0.3 && edge < 0.7, "half-covered joint edge gives {edge}");
    assert_eq!(inb(0.005, 0.0), 1.0);
    assert_eq!(inb(0.0049, 0.0), 0.0);
}

#[test]
fn every_surface_with_zero_derivatives_matches_f64() {
    let lights = table1_lights();
    for surface in Surface::all() {
        for (u, v) in [(0.13, 0.71), (0.52, 0.27), (0.91, 0.64)] {
            let mut cd =
                PointContext::new(Globals::<D>::unit_square(D::new(u, 0.0, 0.0), D::new(v, 0.0, 0.0)), &lights);
            let a = surface.shade(&mut cd, &mut Exec::new());
            let mut cf = PointContext::new(Globals::<f64>::unit_square(u, v), &lights);
            let b = surface.shade(&mut cf, &mut Exec::new());
            for k in 0..3 {
                assert!((a.Ci.lane(0)[k] - b.Ci.lane(0)[k]).abs() < 1e-12, "{} at ({u}, {v})", surface.name());
                assert_eq!(a.Oi.lane(0)[k], b.Oi.lane(0)[k]);
            }
        }
    }
}

#[test]
fn every_surface_with_derivatives_is_finite() {
    let lights = table1_lights();
    for surface in Surface::all() {
        for (u, v) in [(0.05, 0.71), (0.5, 0.5), (0.25, 0.08)] {
            let g = Globals::<D>::unit_square(D::new(u, 0.004, 0.0), D::new(v, 0.0, 0.004));
            let mut ctx = PointContext::new(g, &lights);
            let out = surface.shade(&mut ctx, &mut Exec::new());
            for c in out.Ci.lane(0).into_iter().chain(out.Oi.lane(0)) {
                assert!(c.is_finite(), "{} at ({u}, {v})", surface.name());
            }
        }
    }
}
