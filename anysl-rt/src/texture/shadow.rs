//! `shadow(name, P)`: percentage-closer filtering of a depth map.
//!
//! A depth map holds, per pixel of a pass rendered from a light's camera, the camera-space z
//! of the nearest surface (infinity where nothing was hit). `P` is taken to the map's camera
//! and screen ([`DepthCamera`]); the footprint is P's screen-space derivatives (plus `"blur"`,
//! times `"width"`); `"samples"` points on a stratified grid over it each compare P's depth,
//! less `"bias"`, with the nearest texel's depth. The answer is the fraction of samples in
//! shadow (0 lit, 1 occluded).

use super::store::{self, DepthCamera, MapKind};
use super::{TexOptions, MAX_LANES};
use anysl_core::prelude::*;

/// `a · b` of 4 × 4 matrices stored column-major (column vectors).
#[must_use]
pub fn mat_mul(a: &[f64; 16], b: &[f64; 16]) -> [f64; 16] {
    let mut out = [0.0; 16];
    for c in 0..4 {
        for r in 0..4 {
            out[c * 4 + r] = (0..4).map(|k| a[k * 4 + r] * b[c * 4 + k]).sum();
        }
    }
    out
}

/// `m · (p, 1)` for a column-major matrix, in the shading float (derivatives follow).
fn transform<F: ShadingFloat>(m: &[f64; 16], p: Vec3<F>) -> [F; 4] {
    let row = |r: usize| p.x * F::c(m[r]) + p.y * F::c(m[4 + r]) + p.z * F::c(m[8 + r]) + F::c(m[12 + r]);
    [row(0), row(1), row(2), row(3)]
}

/// Where `p` (world space) falls in the depth map: screen x, y in [-1, 1] (y up) and the
/// camera-space depth.
fn project<F: ShadingFloat>(cam: &DepthCamera, p: Vec3<F>) -> (F, F, F) {
    let c = transform(&cam.world_to_camera, p);
    let cp = Vec3::new(c[0], c[1], c[2]);
    let s = transform(&cam.projection, cp);
    let w = s[3];
    (s[0] / w, s[1] / w, c[2])
}

/// `shadow(name, P1, P2, P3, P4)`: [`lookup`] at the four points' centre with the footprint
/// they span (P2 − P1 across, P4 − P1 down).
#[must_use]
pub fn lookup_quad<F: ShadingFloat>(name: &str, p: [Vec3<F>; 4], o: &TexOptions<F>) -> F {
    let c = (p[0] + p[1] + p[2] + p[3]) * F::c(0.25);
    let (dx, dy) = (p[1] - p[0], p[3] - p[0]);
    let c = Vec3::new(c.x.with_derivs(dx.x, dy.x), c.y.with_derivs(dx.y, dy.y), c.z.with_derivs(dx.z, dy.z));
    lookup(name, c, o)
}

/// `shadow(name, P)`: the fraction of the footprint of `p` that the depth map `name` sees
/// behind a nearer surface; 0 where the map is missing or `p` lies outside it.
#[must_use]
pub fn lookup<F: ShadingFloat>(name: &str, p: Vec3<F>, o: &TexOptions<F>) -> F {
    let Some(map) = store::map(name, MapKind::Shadow) else { return F::c(0.0) };
    let Some(cam) = map.camera.as_ref() else {
        store::warn_once(&format!("shadow:{name}"), || {
            format!("warning[W0003]: \"{name}\" is not a depth map; shadow() reads it as unoccluded")
        });
        return F::c(0.0);
    };
    let img = &map.faces[0];
    let (w, h) = img.resolution();
    let depth = &img.levels()[0];
    let (sx, sy, z) = project(cam, p);
    let mut out = [0.0f64; MAX_LANES];
    for (i, slot) in out.iter_mut().enumerate().take(F::LANES) {
        // Texture space: s right, t down, over the screen window [-1, 1]².
        let (s, t, zi) = ((sx.lane(i) + 1.0) * 0.5, (1.0 - sy.lane(i)) * 0.5, z.lane(i));
        if !(s.is_finite() && t.is_finite() && zi.is_finite()) || zi <= 0.0 {
            continue;
        }
        let d = |x: F| (x.dx().lane(i).abs() + x.dy().lane(i).abs()) * 0.5;
        let ws = d(sx) * o.width[0].lane(i) + o.blur[0].lane(i).abs();
        let wt = d(sy) * o.width[1].lane(i) + o.blur[1].lane(i).abs();
        let n = (o.samples.lane(i).max(1.0).sqrt().round() as usize).clamp(1, 16);
        let bias = o.bias.lane(i);
        let (mut hits, mut total) = (0usize, 0usize);
        for a in 0..n {
            for b in 0..n {
                let (u, v) = if n == 1 {
                    (s, t)
                } else {
                    (s + ((a as f64 + 0.5) / n as f64 - 0.5) * ws, t + ((b as f64 + 0.5) / n as f64 - 0.5) * wt)
                };
                let (x, y) = ((u * w as f64).floor(), (v * h as f64).floor());
                total += 1;
                if x < 0.0 || y < 0.0 || x >= w as f64 || y >= h as f64 {
                    continue;
                }
                let texel = f64::from(depth.texel(x as usize, y as usize, 0));
                if zi - bias > texel {
                    hits += 1;
                }
            }
        }
        *slot = hits as f64 / total as f64;
    }
    F::from_lanes(&out[..F::LANES])
}
