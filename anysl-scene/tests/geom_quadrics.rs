//! Quadrics: every vertex on the analytic surface (implicit equation), normals along the
//! analytic gradient, sweep and z limits, u v at the spec's corners, partials against central
//! finite differences of an independent f64 parametrization, chord error within tolerance.

// Tests index parallel per-vertex arrays.
#![allow(clippy::needless_range_loop)]

use anysl_rib::ParamList;
use anysl_scene::geom::{cone, cylinder, disk, hyperboloid, paraboloid, sphere, torus, Detail, Tessellation};
use glam::{DVec3, Vec3};
use std::f64::consts::PI;

/// A quadric request and its oracle, all in f64.
#[derive(Clone, Copy, Debug)]
enum Q {
    Sphere(f64, f64, f64, f64),
    Cone(f64, f64, f64),
    Cylinder(f64, f64, f64, f64),
    Hyperboloid([f64; 3], [f64; 3], f64),
    Paraboloid(f64, f64, f64, f64),
    Disk(f64, f64, f64),
    Torus(f64, f64, f64, f64, f64),
}

impl Q {
    fn run(self, d: &Detail) -> Tessellation {
        let f = |x: f64| x as f32;
        let p = ParamList::new();
        match self {
            Q::Sphere(r, z0, z1, tm) => sphere(f(r), f(z0), f(z1), f(tm), &p, d),
            Q::Cone(h, r, tm) => cone(f(h), f(r), f(tm), &p, d),
            Q::Cylinder(r, z0, z1, tm) => cylinder(f(r), f(z0), f(z1), f(tm), &p, d),
            Q::Hyperboloid(a, b, tm) => hyperboloid(a.map(f), b.map(f), f(tm), &p, d),
            Q::Paraboloid(r, z0, z1, tm) => paraboloid(f(r), f(z0), f(z1), f(tm), &p, d),
            Q::Disk(h, r, tm) => disk(f(h), f(r), f(tm), &p, d),
            Q::Torus(a, b, p0, p1, tm) => torus(f(a), f(b), f(p0), f(p1), f(tm), &p, d),
        }
        .unwrap()
    }

    fn thetamax(self) -> f64 {
        match self {
            Q::Sphere(.., tm) | Q::Cone(.., tm) | Q::Cylinder(.., tm) | Q::Hyperboloid(.., tm) => tm,
            Q::Paraboloid(.., tm) | Q::Disk(.., tm) | Q::Torus(.., tm) => tm,
        }
    }

    /// The RI 3.2 parametrization, written independently of the crate.
    fn point(self, u: f64, v: f64) -> DVec3 {
        let phi = u * self.thetamax().to_radians();
        let around = |rho: f64, z: f64| DVec3::new(rho * phi.cos(), rho * phi.sin(), z);
        match self {
            Q::Sphere(r, z0, z1, _) => {
                let t0 = (z0 / r).clamp(-1.0, 1.0).asin();
                let t1 = (z1 / r).clamp(-1.0, 1.0).asin();
                let th = t0 + v * (t1 - t0);
                around(r * th.cos(), r * th.sin())
            }
            Q::Cone(h, r, _) => around(r * (1.0 - v), v * h),
            Q::Cylinder(r, z0, z1, _) => around(r, z0 + v * (z1 - z0)),
            Q::Hyperboloid(a, b, _) => {
                let q = DVec3::from(a) + v * (DVec3::from(b) - DVec3::from(a));
                DVec3::new(q.x * phi.cos() - q.y * phi.sin(), q.x * phi.sin() + q.y * phi.cos(), q.z)
            }
            Q::Paraboloid(r, z0, z1, _) => {
                let z = z0 + v * (z1 - z0);
                around(r * (z / z1).sqrt(), z)
            }
            Q::Disk(h, r, _) => around(r * (1.0 - v), h),
            Q::Torus(a, b, p0, p1, _) => {
                let th = (p0 + v * (p1 - p0)).to_radians();
                around(a + b * th.cos(), b * th.sin())
            }
        }
    }

    /// Implicit equation (0 on the surface) and its gradient, for those that have one.
    fn implicit(self, p: DVec3) -> Option<(f64, DVec3)> {
        let rho = (p.x * p.x + p.y * p.y).sqrt();
        Some(match self {
            Q::Sphere(r, ..) => (p.length() - r.abs(), p),
            Q::Cone(h, r, _) => (rho - r * (1.0 - p.z / h), DVec3::new(h * p.x / rho, h * p.y / rho, r)),
            Q::Cylinder(r, ..) => (rho - r, DVec3::new(p.x, p.y, 0.0)),
            Q::Paraboloid(r, _, z1, _) => (rho * rho - r * r * p.z / z1, DVec3::new(2.0 * p.x, 2.0 * p.y, -r * r / z1)),
            Q::Disk(h, _, _) => (p.z - h, DVec3::Z),
            Q::Torus(a, b, ..) => {
                ((rho - a).powi(2) + p.z * p.z - b * b, DVec3::new((rho - a) * p.x / rho, (rho - a) * p.y / rho, p.z))
            }
            Q::Hyperboloid(..) => return None,
        })
    }
}

fn cases() -> Vec<Q> {
    vec![
        Q::Sphere(1.0, -1.0, 1.0, 360.0),
        Q::Sphere(2.0, -0.5, 1.5, 90.0),
        Q::Sphere(1.0, -3.0, 0.25, 270.0),
        Q::Cone(2.0, 1.0, 360.0),
        Q::Cone(1.0, 0.5, 90.0),
        Q::Cylinder(1.0, -1.0, 2.0, 360.0),
        Q::Cylinder(0.5, 0.0, 1.0, 90.0),
        Q::Hyperboloid([1.0, 0.0, -1.0], [0.0, 1.0, 1.0], 360.0),
        Q::Hyperboloid([0.5, 0.5, 0.0], [1.0, -0.25, 2.0], 90.0),
        Q::Paraboloid(1.0, 0.25, 2.0, 360.0),
        Q::Paraboloid(2.0, 0.5, 1.0, 90.0),
        Q::Disk(0.5, 1.0, 360.0),
        Q::Disk(-1.0, 2.0, 90.0),
        Q::Torus(1.0, 0.25, 0.0, 360.0, 360.0),
        Q::Torus(2.0, 0.5, -90.0, 90.0, 90.0),
    ]
}

fn detail() -> Detail {
    Detail { tolerance: 1e-3, min_segments: 4, max_segments: 128 }
}

#[test]
fn points_lie_on_the_analytic_surface_with_the_gradient_as_normal() {
    for q in cases() {
        let t = q.run(&detail());
        assert!(!t.triangles.is_empty(), "{q:?}");
        for i in 0..t.positions.len() {
            let p = t.positions[i].as_dvec3();
            let n = t.normals[i].as_dvec3();
            assert!((n.length() - 1.0).abs() < 1e-4, "{q:?}: normal {n} not unit");
            let (u, v) = (t.uv[i].x as f64, t.uv[i].y as f64);
            assert!((0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v), "{q:?}: uv {u} {v}");
            let expect = q.point(u, v);
            assert!((p - expect).length() < 1e-4, "{q:?}: P({u}, {v}) = {p}, expected {expect}");
            if let Some((f, grad)) = q.implicit(p) {
                assert!(f.abs() < 1e-4, "{q:?}: implicit {f} at {p}");
                let g = grad.normalize();
                // At a pole or apex the gradient is undefined: skip those points.
                if grad.length() > 1e-3 && (p.x * p.x + p.y * p.y) > 1e-6 {
                    assert!(n.dot(g) > 0.999, "{q:?}: normal {n} vs gradient {g} at {p} (uv {u} {v})");
                }
            }
        }
    }
}

#[test]
fn sweep_and_z_limits_hold() {
    for q in cases() {
        let t = q.run(&detail());
        let tm = q.thetamax();
        // A hyperboloid's profile turns along v: its parametrization test covers it.
        if matches!(q, Q::Hyperboloid(..)) {
            continue;
        }
        for p in &t.positions {
            let p = p.as_dvec3();
            if p.x * p.x + p.y * p.y < 1e-8 {
                continue;
            }
            let mut phi = p.y.atan2(p.x).to_degrees();
            if phi < -1e-3 {
                phi += 360.0;
            }
            assert!(phi >= -1e-3 && phi <= tm + 1e-3, "{q:?}: phi {phi} outside [0, {tm}]");
        }
        let (zlo, zhi) = match q {
            Q::Sphere(r, z0, z1, _) => (z0.max(-r), z1.min(r)),
            Q::Cylinder(_, z0, z1, _) | Q::Paraboloid(_, z0, z1, _) => (z0, z1),
            Q::Cone(h, ..) => (0.0, h),
            Q::Disk(h, ..) => (h, h),
            _ => continue,
        };
        for p in &t.positions {
            assert!(p.z as f64 >= zlo - 1e-5 && p.z as f64 <= zhi + 1e-5, "{q:?}: z {} outside [{zlo}, {zhi}]", p.z);
        }
    }
}

#[test]
fn corners_follow_the_spec() {
    // u = 0 at φ = 0 and v = 0 at zmin: the corner (0, 0) of a sphere is (r cos θmin, 0, zmin).
    let t = Q::Sphere(2.0, -1.0, 1.5, 90.0).run(&detail());
    let corner = |u: f32, v: f32| t.uv.iter().position(|w| (w.x - u).abs() < 1e-6 && (w.y - v).abs() < 1e-6).unwrap();
    let p00 = t.positions[corner(0.0, 0.0)];
    assert!((p00.z + 1.0).abs() < 1e-5 && p00.y.abs() < 1e-6 && p00.x > 0.0, "{p00}");
    let p11 = t.positions[corner(1.0, 1.0)];
    assert!((p11.z - 1.5).abs() < 1e-5 && p11.x.abs() < 1e-5 && p11.y > 0.0, "{p11}");
    // st defaults to uv.
    assert_eq!(t.uv, t.st);
    // Disk: v = 0 on the rim, v = 1 at the centre; its normal is +z.
    let t = Q::Disk(0.5, 1.0, 360.0).run(&detail());
    for i in 0..t.positions.len() {
        let r = t.positions[i].truncate().length();
        assert!((r - (1.0 - t.uv[i].y)).abs() < 1e-5);
        assert!((t.normals[i] - Vec3::Z).length() < 1e-5);
    }
}

#[test]
fn partials_match_central_differences() {
    let h = 1e-5;
    for q in cases() {
        let t = q.run(&detail());
        for i in (0..t.positions.len()).step_by(7) {
            let (u, v) = (t.uv[i].x as f64, t.uv[i].y as f64);
            // Stay inside the domain, away from the paraboloid's apex where dP/dv is infinite.
            let (u, v) = (u.clamp(h, 1.0 - h), v.clamp(h, 1.0 - h));
            let fd_u = (q.point(u + h, v) - q.point(u - h, v)) / (2.0 * h);
            let fd_v = (q.point(u, v + h) - q.point(u, v - h)) / (2.0 * h);
            let j =
                t.uv.iter()
                    .position(|w| (w.x as f64 - u).abs() < 2.0 * h && (w.y as f64 - v).abs() < 2.0 * h)
                    .unwrap_or(i);
            let (du, dv) = (t.dpdu[j].as_dvec3(), t.dpdv[j].as_dvec3());
            let tol = |fd: DVec3| 2e-3 * (1.0 + fd.length());
            assert!((du - fd_u).length() < tol(fd_u), "{q:?}: dPdu {du} vs {fd_u} at {u} {v}");
            assert!((dv - fd_v).length() < tol(fd_v), "{q:?}: dPdv {dv} vs {fd_v} at {u} {v}");
        }
    }
}

/// Largest distance between the true surface at parameter points of each triangle (edge
/// midpoints, centroid) and the triangle's point with the same barycentric coordinates.
fn chord_error(q: Q, t: &Tessellation) -> f64 {
    let bary = [[0.5, 0.5, 0.0], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5], [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0]];
    let mut worst: f64 = 0.0;
    for tri in &t.triangles {
        let [a, b, c] = tri.map(|i| i as usize);
        for w in bary {
            let uv = t.uv[a].as_dvec2() * w[0] + t.uv[b].as_dvec2() * w[1] + t.uv[c].as_dvec2() * w[2];
            let on_tri =
                t.positions[a].as_dvec3() * w[0] + t.positions[b].as_dvec3() * w[1] + t.positions[c].as_dvec3() * w[2];
            worst = worst.max((q.point(uv.x, uv.y) - on_tri).length());
        }
    }
    worst
}

#[test]
fn chord_error_within_tolerance() {
    for tol in [1e-2f32, 1e-3] {
        let d = Detail { tolerance: tol, min_segments: 1, max_segments: 512 };
        for q in
            [Q::Sphere(1.0, -1.0, 1.0, 360.0), Q::Torus(1.0, 0.3, 0.0, 360.0, 360.0), Q::Sphere(3.0, -1.0, 2.0, 200.0)]
        {
            let t = q.run(&d);
            let e = chord_error(q, &t);
            assert!(e <= tol as f64, "{q:?} at tolerance {tol}: chord error {e}");
            // Not wastefully fine either: within 20 times the tolerance of the error bound.
            assert!(e > tol as f64 / 20.0, "{q:?} at tolerance {tol}: chord error {e} is far below it");
        }
    }
    let _ = PI;
}

#[test]
fn degenerate_inputs_are_empty_or_errors() {
    let p = ParamList::new();
    let d = Detail::default();
    assert!(sphere(0.0, -1.0, 1.0, 360.0, &p, &d).unwrap().is_empty());
    assert!(sphere(1.0, -1.0, 1.0, 0.0, &p, &d).unwrap().is_empty());
    assert!(sphere(1.0, 0.5, 0.5, 360.0, &p, &d).unwrap().is_empty());
    assert!(cylinder(1.0, 0.0, 0.0, 360.0, &p, &d).unwrap().is_empty());
    assert!(torus(1.0, 0.0, 0.0, 360.0, 360.0, &p, &d).unwrap().is_empty());
    assert!(hyperboloid([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 360.0, &p, &d).unwrap().is_empty());
    let e = sphere(f32::NAN, -1.0, 1.0, 360.0, &p, &d).unwrap_err();
    assert_eq!(e.to_string(), "Sphere: radius is NaN, not a finite number");
    let e = torus(1.0, 0.5, 0.0, f32::INFINITY, 360.0, &p, &d).unwrap_err();
    assert!(e.to_string().starts_with("Torus: phimax is inf"), "{e}");
    // Negative radius and reversed z range: still on the sphere, no NaN.
    for t in [sphere(-1.0, -1.0, 1.0, 360.0, &p, &d).unwrap(), sphere(1.0, 1.0, -1.0, -180.0, &p, &d).unwrap()] {
        assert!(!t.is_empty());
        assert!(t.positions.iter().all(|p| (p.length() - 1.0).abs() < 1e-5));
        assert!(t.normals.iter().all(|n| n.is_finite() && (n.length() - 1.0).abs() < 1e-4));
    }
    // Huge values overflow to an error, not to infinities in the output.
    let e = torus(3e38, 3e38, 0.0, 360.0, 360.0, &p, &d).unwrap_err();
    assert!(e.to_string().contains("non-finite"), "{e}");
}

#[test]
fn pole_and_apex_normals_are_the_limits() {
    let d = detail();
    let t = Q::Sphere(1.0, -1.0, 1.0, 360.0).run(&d);
    for i in 0..t.positions.len() {
        if t.uv[i].y == 1.0 {
            assert!((t.normals[i] - Vec3::Z).length() < 1e-3, "{}", t.normals[i]);
        }
        if t.uv[i].y == 0.0 {
            assert!((t.normals[i] + Vec3::Z).length() < 1e-3, "{}", t.normals[i]);
        }
    }
    // The paraboloid's apex and the disk's centre: straight down and straight up.
    for (t, n) in [(Q::Paraboloid(1.0, 0.0, 1.0, 360.0).run(&d), -Vec3::Z), (Q::Disk(0.0, 1.0, 360.0).run(&d), Vec3::Z)]
    {
        let apex: Vec<usize> = (0..t.positions.len()).filter(|&i| t.positions[i].truncate().length() < 1e-6).collect();
        assert!(!apex.is_empty());
        for i in apex {
            assert!((t.normals[i] - n).length() < 1e-2, "{} vs {n}", t.normals[i]);
        }
    }
    // The cone's apex: the normal of the cone line through that u.
    let t = Q::Cone(1.0, 1.0, 360.0).run(&d);
    for i in 0..t.positions.len() {
        if t.uv[i].y == 1.0 {
            let phi = t.uv[i].x * std::f32::consts::TAU;
            let expect = Vec3::new(phi.cos(), phi.sin(), 1.0).normalize();
            assert!((t.normals[i] - expect).length() < 1e-2, "{} vs {expect}", t.normals[i]);
        }
    }
}

#[test]
fn triangles_wind_counter_clockwise_about_the_normals() {
    for q in cases() {
        let t = q.run(&detail());
        for tri in &t.triangles {
            let [a, b, c] = tri.map(|i| t.positions[i as usize]);
            let g = (b - a).cross(c - a);
            let n: Vec3 = tri.iter().map(|&i| t.normals[i as usize]).sum();
            assert!(g.dot(n) >= 0.0, "{q:?}: triangle {tri:?} winds against its normals");
        }
    }
}
