//! `environment()`: latitude-longitude and cube-face maps, filtered over the footprint of the
//! direction (its derivatives, or the spread of four directions).
//!
//! Orientation as the RenderMan Interface 3.2 states it (§ "Making environment maps"): a
//! lat-long image has longitude 0 at its left edge and 360° at its right, latitude +90° at the
//! top and −90° at the bottom, the direction of (longitude φ, latitude λ) being
//! `(cos φ cos λ, sin φ cos λ, sin λ)` — z is the pole. Cube faces, in the order px nx py ny
//! pz nz, are pictures taken from the origin looking along the axis with these up and right
//! axes: px (+y, −z), nx (+y, +z), py (−z, +x), ny (+z, +x), pz (+y, +x), nz (+y, −x), each
//! spanning `fov` degrees.

use super::mip::Wrap;
use super::store::{self, Map, MapKind};
use super::{TexOptions, MAX_LANES};
use anysl_core::prelude::*;
use std::f64::consts::PI;

/// The direction(s) of an environment look-up.
#[derive(Clone, Copy, Debug)]
pub enum Dir<F> {
    /// One direction; the footprint from its derivatives.
    Ray(Vec3<F>),
    /// Four directions bounding the region to average.
    Quad([Vec3<F>; 4]),
}

/// (forward, up, right) of each cube face, in the order px nx py ny pz nz.
const FACES: [([f64; 3], [f64; 3], [f64; 3]); 6] = [
    ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]),
    ([-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
    ([0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]),
    ([0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
    ([0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
    ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]),
];

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// The lat-long texture coordinates of direction `d` (not necessarily unit; not zero).
#[must_use]
pub fn latlong_st(d: [f64; 3]) -> (f64, f64) {
    let len = norm(d);
    let s = d[1].atan2(d[0]).rem_euclid(2.0 * PI) / (2.0 * PI);
    let t = (d[2] / len).clamp(-1.0, 1.0).acos() / PI;
    (s, t)
}

/// The cube face `d` points into and its texture coordinates there, for faces spanning `fov`
/// degrees.
#[must_use]
pub fn cube_st(d: [f64; 3], fov: f64) -> (usize, f64, f64) {
    let axis = if d[0].abs() >= d[1].abs() && d[0].abs() >= d[2].abs() {
        0
    } else if d[1].abs() >= d[2].abs() {
        1
    } else {
        2
    };
    let face = axis * 2 + usize::from(d[axis] < 0.0);
    let (fwd, up, right) = FACES[face];
    let half = (fov.to_radians() * 0.5).tan().max(1e-6);
    let z = dot(d, fwd);
    let (x, y) = (dot(d, right) / z / half, dot(d, up) / z / half);
    (face, (x + 1.0) * 0.5, (1.0 - y) * 0.5)
}

/// One lane: the direction and the angle its footprint spans.
fn lane_dir<F: ShadingFloat>(dir: &Dir<F>, i: usize) -> ([f64; 3], f64) {
    let v = |p: &Vec3<F>| [p.x.lane(i), p.y.lane(i), p.z.lane(i)];
    match dir {
        Dir::Ray(d) => {
            let c = v(d);
            let len = norm(c).max(1e-30);
            let dx = [d.x.dx().lane(i), d.y.dx().lane(i), d.z.dx().lane(i)];
            let dy = [d.x.dy().lane(i), d.y.dy().lane(i), d.z.dy().lane(i)];
            (c, (norm(dx) + norm(dy)) / len)
        }
        Dir::Quad(q) => {
            let ds = q.map(|p| {
                let c = v(&p);
                let l = norm(c).max(1e-30);
                [c[0] / l, c[1] / l, c[2] / l]
            });
            let c = [0, 1, 2].map(|k| ds.iter().map(|d| d[k]).sum::<f64>() * 0.25);
            let mut spread: f64 = 0.0;
            for a in &ds {
                for b in &ds {
                    spread = spread.max(norm([a[0] - b[0], a[1] - b[1], a[2] - b[2]]));
                }
            }
            (c, spread)
        }
    }
}

/// Samples `map` (lat-long or cube) in direction `d` over an angular footprint `angle` (plus
/// blur), channels `first..first + out.len()`.
fn sample(map: &Map, d: [f64; 3], angle: f64, o: &TexOptions<f64>, out: &mut [f64]) {
    let filter = o.filter.unwrap_or(map.filter);
    if !(d.iter().all(|x| x.is_finite()) && norm(d) > 0.0) {
        out.fill(o.fill);
        return;
    }
    let gray = map.channels() == 1 && o.first == 0;
    let n = if gray { 1 } else { out.len() };
    if map.kind == MapKind::CubeFace && map.faces.len() == 6 {
        let (face, s, t) = cube_st(d, map.fov);
        let w = angle / (2.0 * (map.fov.to_radians() * 0.5).tan().max(1e-6));
        let (ws, wt) = (w * o.width[0] + o.blur[0], w * o.width[1] + o.blur[1]);
        map.faces[face].filter(s, t, ws, wt, (Wrap::Clamp, Wrap::Clamp), filter, o.first, o.fill, &mut out[..n]);
    } else {
        let (s, t) = latlong_st(d);
        let sin = (t * PI).sin().max(1e-3);
        let ws = (angle / (2.0 * PI * sin)).min(1.0) * o.width[0] + o.blur[0];
        let wt = angle / PI * o.width[1] + o.blur[1];
        map.faces[0].filter(s, t, ws, wt, (Wrap::Periodic, Wrap::Clamp), filter, o.first, o.fill, &mut out[..n]);
    }
    if gray {
        let g = out[0];
        out.fill(g);
    }
}

/// `environment(name, dir…)`: channels `o.first..o.first + 3` of map `name` seen in the
/// direction(s) `dir`; `"fill"` when the map is missing (or named `"raytrace"`, which the
/// renderers answer by tracing before they get here).
#[must_use]
pub fn lookup<F: ShadingFloat>(name: &str, dir: Dir<F>, o: &TexOptions<F>) -> Color<F> {
    let Some(map) = store::map(name, MapKind::LatLong) else { return Color::splat(o.fill) };
    let mut out = [[0.0f64; MAX_LANES]; 3];
    for i in 0..F::LANES {
        let (d, angle) = lane_dir(&dir, i);
        let oi = TexOptions {
            first: o.first,
            blur: o.blur.map(|b| b.lane(i).abs()),
            width: o.width.map(|w| w.lane(i)),
            fill: o.fill.lane(i),
            filter: o.filter,
            samples: 0.0,
            bias: 0.0,
        };
        let mut v = [0.0; 3];
        sample(&map, d, angle, &oi, &mut v);
        for (o, x) in out.iter_mut().zip(v) {
            o[i] = x;
        }
    }
    let lanes = |c: usize| F::from_lanes(&out[c][..F::LANES]);
    Color::new(lanes(0), lanes(1), lanes(2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latlong_follows_the_interface_spec() {
        // +x: longitude 0 (left edge), equator.
        assert_eq!(latlong_st([1.0, 0.0, 0.0]), (0.0, 0.5));
        // +y: longitude 90°.
        let (s, t) = latlong_st([0.0, 2.0, 0.0]);
        assert!((s - 0.25).abs() < 1e-12 && (t - 0.5).abs() < 1e-12);
        // +z: the north pole at the top.
        assert_eq!(latlong_st([0.0, 0.0, 1.0]).1, 0.0);
        assert_eq!(latlong_st([0.0, 0.0, -3.0]).1, 1.0);
    }

    #[test]
    fn cube_faces_follow_the_interface_spec() {
        // Straight along each axis: the centre of its face.
        for (k, (fwd, _, _)) in FACES.iter().enumerate() {
            let (face, s, t) = cube_st(*fwd, 90.0);
            assert_eq!((face, s, t), (k, 0.5, 0.5));
        }
        // px: a direction tilted towards -z lies right of centre, towards +y above it.
        let (face, s, t) = cube_st([1.0, 0.5, -0.5], 90.0);
        assert!(face == 0 && (s - 0.75).abs() < 1e-12 && (t - 0.25).abs() < 1e-12, "{s} {t}");
        // A wider fov moves the point towards the centre.
        let (_, s, _) = cube_st([1.0, 0.0, -1.0], 120.0);
        assert!((s - (1.0 + 1.0 / 3f64.sqrt()) * 0.5).abs() < 1e-12);
    }
}
