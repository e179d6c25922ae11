//! The seven quadrics of RI 3.2 §5.3, with their exact parametrizations.
//!
//! Each sweeps an angle φ = u · thetamax about z (degrees in the request, clamped to
//! ±360); v runs along the profile:
//!
//! | request | point at (u, v) |
//! |---|---|
//! | Sphere r zmin zmax | θ = θmin + v (θmax − θmin), θmin = asin(zmin/r), θmax = asin(zmax/r); (r cosθ cosφ, r cosθ sinφ, r sinθ) |
//! | Cone h r | (r (1−v) cosφ, r (1−v) sinφ, v h) |
//! | Cylinder r zmin zmax | (r cosφ, r sinφ, zmin + v (zmax − zmin)) |
//! | Hyperboloid p1 p2 | the point (1−v) p1 + v p2 rotated by φ about z |
//! | Paraboloid rmax zmin zmax | z = zmin + v (zmax − zmin), r = rmax √(z/zmax); (r cosφ, r sinφ, z) |
//! | Disk h r | (r (1−v) cosφ, r (1−v) sinφ, h) |
//! | Torus R r φmin φmax | θ = φmin + v (φmax − φmin), ρ = R + r cosθ; (ρ cosφ, ρ sinφ, r sinθ) |
//!
//! s, t default to u, v. The partials are the analytic ones; the normal is
//! normalize(dPdu × dPdv), which points away from the z axis for the defaults (+z for a disk).
//! Degenerate requests (a zero radius, thetamax 0, an empty z range) give an empty
//! tessellation, not an error; NaN or infinite arguments are errors.

use super::grid::{self, bilinear, Eval, Surface};
use super::primvars::{Counts, POSITION_NAMES};
use super::{err, Detail, Result, Tessellation};
use anysl_rib::ParamList;
use glam::{Vec2, Vec3};

/// Which quadric, with its arguments converted to radians and clamped.
#[derive(Clone, Copy, Debug)]
enum Shape {
    Sphere { r: f32, th0: f32, th1: f32 },
    Cone { h: f32, r: f32 },
    Cylinder { r: f32, z0: f32, z1: f32 },
    Hyperboloid { p1: Vec3, p2: Vec3 },
    Paraboloid { rmax: f32, z0: f32, z1: f32 },
    Disk { h: f32, r: f32 },
    Torus { major: f32, minor: f32, ph0: f32, ph1: f32 },
}

/// A quadric as a one-face [`Surface`].
struct Quadric {
    shape: Shape,
    /// The sweep, in radians.
    tmax: f32,
}

impl Surface for Quadric {
    fn faces(&self) -> (usize, usize) {
        (1, 1)
    }

    #[inline]
    fn eval(&self, _fu: usize, _fv: usize, u: f32, v: f32) -> Eval {
        let phi = u * self.tmax;
        let (sp, cp) = phi.sin_cos();
        // Every quadric is a profile (radius ρ, height z) swept about z; dρ/dv and dz/dv give dPdv.
        let (rho, z, drho, dz) = match self.shape {
            Shape::Sphere { r, th0, th1 } => {
                let th = th0 + v * (th1 - th0);
                let (st, ct) = th.sin_cos();
                // cos θ ≥ 0 on [-π/2, π/2]; rounding at a pole must not flip the point (and normal).
                let ct = ct.max(0.0);
                (r * ct, r * st, -r * st * (th1 - th0), r * ct * (th1 - th0))
            }
            Shape::Cone { h, r } => (r * (1.0 - v), v * h, -r, h),
            Shape::Cylinder { r, z0, z1 } => (r, z0 + v * (z1 - z0), 0.0, z1 - z0),
            Shape::Paraboloid { rmax, z0, z1 } => {
                let z = z0 + v * (z1 - z0);
                // r = rmax √(z/z1); the derivative is infinite at the apex (z = 0): keep it finite.
                let q = (z / z1).max(0.0);
                let sq = q.sqrt();
                let dr = rmax * 0.5 / (z1 * sq.max(1e-6)) * (z1 - z0);
                (rmax * sq, z, dr, z1 - z0)
            }
            Shape::Disk { h, r } => (r * (1.0 - v), h, -r, 0.0),
            Shape::Torus { major, minor, ph0, ph1 } => {
                let th = ph0 + v * (ph1 - ph0);
                let (st, ct) = th.sin_cos();
                (major + minor * ct, minor * st, -minor * st * (ph1 - ph0), minor * ct * (ph1 - ph0))
            }
            Shape::Hyperboloid { p1, p2 } => {
                let q = p1 + v * (p2 - p1);
                let dq = p2 - p1;
                let rot = |a: Vec3| Vec3::new(a.x * cp - a.y * sp, a.x * sp + a.y * cp, a.z);
                let p = rot(q);
                return Eval { p, ds: self.tmax * Vec3::new(-p.y, p.x, 0.0), dt: rot(dq) };
            }
        };
        let p = Vec3::new(rho * cp, rho * sp, z);
        Eval { p, ds: self.tmax * Vec3::new(-p.y, p.x, 0.0), dt: Vec3::new(drho * cp, drho * sp, dz) }
    }

    fn uv(&self, _fu: usize, _fv: usize, s: f32, t: f32) -> (Vec2, Vec2) {
        (Vec2::new(s, t), Vec2::ONE)
    }

    fn counts(&self) -> Counts {
        Counts { uniform: 1, varying: 4, vertex: 4, facevarying: 4, vertex_at_least: false }
    }

    fn uniform_index(&self, _fu: usize, _fv: usize) -> usize {
        0
    }

    fn varying_weights(&self, _fu: usize, _fv: usize, s: f32, t: f32, out: &mut Vec<(usize, f32)>) {
        out.extend(bilinear(s, t).into_iter().enumerate());
    }

    fn vertex_weights(&self, fu: usize, fv: usize, s: f32, t: f32, out: &mut Vec<(usize, f32)>) {
        self.varying_weights(fu, fv, s, t, out);
    }
}

/// Checks that every argument is finite.
fn finite(request: &str, args: &[(&str, f32)]) -> Result<()> {
    match args.iter().find(|(_, v)| !v.is_finite()) {
        Some((name, v)) => err(format!("{request}: {name} is {v}, not a finite number")),
        None => Ok(()),
    }
}

/// The sweep in radians, clamped to ±2π.
fn sweep(thetamax: f32) -> f32 {
    thetamax.clamp(-360.0, 360.0).to_radians()
}

fn build(shape: Shape, thetamax: f32, request: &str, params: &ParamList, d: &Detail) -> Result<Tessellation> {
    let q = Quadric { shape, tmax: sweep(thetamax) };
    if q.tmax == 0.0 {
        return Ok(Tessellation::default());
    }
    grid::tessellate(&q, request, params, d, POSITION_NAMES)
}

/// `Sphere radius zmin zmax thetamax`: zmin and zmax are clamped to ±radius.
pub fn sphere(
    radius: f32,
    zmin: f32,
    zmax: f32,
    thetamax: f32,
    params: &ParamList,
    d: &Detail,
) -> Result<Tessellation> {
    finite("Sphere", &[("radius", radius), ("zmin", zmin), ("zmax", zmax), ("thetamax", thetamax)])?;
    if radius == 0.0 || zmin == zmax {
        return Ok(Tessellation::default());
    }
    let th = |z: f32| (z / radius).clamp(-1.0, 1.0).asin();
    let (th0, th1) = (th(zmin), th(zmax));
    if th0 == th1 {
        return Ok(Tessellation::default());
    }
    build(Shape::Sphere { r: radius, th0, th1 }, thetamax, "Sphere", params, d)
}

/// `Cone height radius thetamax`: apex at (0, 0, height), base circle at z = 0.
pub fn cone(height: f32, radius: f32, thetamax: f32, params: &ParamList, d: &Detail) -> Result<Tessellation> {
    finite("Cone", &[("height", height), ("radius", radius), ("thetamax", thetamax)])?;
    if radius == 0.0 {
        return Ok(Tessellation::default());
    }
    build(Shape::Cone { h: height, r: radius }, thetamax, "Cone", params, d)
}

/// `Cylinder radius zmin zmax thetamax`.
pub fn cylinder(
    radius: f32,
    zmin: f32,
    zmax: f32,
    thetamax: f32,
    params: &ParamList,
    d: &Detail,
) -> Result<Tessellation> {
    finite("Cylinder", &[("radius", radius), ("zmin", zmin), ("zmax", zmax), ("thetamax", thetamax)])?;
    if radius == 0.0 || zmin == zmax {
        return Ok(Tessellation::default());
    }
    build(Shape::Cylinder { r: radius, z0: zmin, z1: zmax }, thetamax, "Cylinder", params, d)
}

/// `Hyperboloid point1 point2 thetamax`: the line from point1 to point2 swept about z.
pub fn hyperboloid(p1: [f32; 3], p2: [f32; 3], thetamax: f32, params: &ParamList, d: &Detail) -> Result<Tessellation> {
    let names = ["point1.x", "point1.y", "point1.z", "point2.x", "point2.y", "point2.z"];
    let vals = [p1[0], p1[1], p1[2], p2[0], p2[1], p2[2]];
    let args: Vec<_> = names.into_iter().zip(vals).chain([("thetamax", thetamax)]).collect();
    finite("Hyperboloid", &args)?;
    let (a, b) = (Vec3::from(p1), Vec3::from(p2));
    // A segment on the z axis, or a point, sweeps no area.
    let on_axis = |p: Vec3| p.x == 0.0 && p.y == 0.0;
    if a == b || (on_axis(a) && on_axis(b)) {
        return Ok(Tessellation::default());
    }
    build(Shape::Hyperboloid { p1: a, p2: b }, thetamax, "Hyperboloid", params, d)
}

/// `Paraboloid rmax zmin zmax thetamax`: radius rmax at z = zmax, r = rmax √(z / zmax).
pub fn paraboloid(
    rmax: f32,
    zmin: f32,
    zmax: f32,
    thetamax: f32,
    params: &ParamList,
    d: &Detail,
) -> Result<Tessellation> {
    finite("Paraboloid", &[("rmax", rmax), ("zmin", zmin), ("zmax", zmax), ("thetamax", thetamax)])?;
    if rmax == 0.0 || zmax == 0.0 || zmin == zmax {
        return Ok(Tessellation::default());
    }
    build(Shape::Paraboloid { rmax, z0: zmin, z1: zmax }, thetamax, "Paraboloid", params, d)
}

/// `Disk height radius thetamax`: normal +z.
pub fn disk(height: f32, radius: f32, thetamax: f32, params: &ParamList, d: &Detail) -> Result<Tessellation> {
    finite("Disk", &[("height", height), ("radius", radius), ("thetamax", thetamax)])?;
    if radius == 0.0 {
        return Ok(Tessellation::default());
    }
    build(Shape::Disk { h: height, r: radius }, thetamax, "Disk", params, d)
}

/// `Torus majorradius minorradius phimin phimax thetamax`: the circle of radius minor, centred
/// at distance major from z in the xz plane, from angle phimin to phimax, swept about z.
pub fn torus(
    major: f32,
    minor: f32,
    phimin: f32,
    phimax: f32,
    thetamax: f32,
    params: &ParamList,
    d: &Detail,
) -> Result<Tessellation> {
    finite(
        "Torus",
        &[
            ("majorradius", major),
            ("minorradius", minor),
            ("phimin", phimin),
            ("phimax", phimax),
            ("thetamax", thetamax),
        ],
    )?;
    let (ph0, ph1) = (phimin.clamp(-720.0, 720.0).to_radians(), phimax.clamp(-720.0, 720.0).to_radians());
    if minor == 0.0 || ph0 == ph1 {
        return Ok(Tessellation::default());
    }
    build(Shape::Torus { major, minor, ph0, ph1 }, thetamax, "Torus", params, d)
}
