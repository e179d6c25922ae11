//! Texture look-ups for `texture()`, `environment()` and `shadow()`.
//!
//! Images are read through the `image` crate on first use and cached for the process. A
//! missing or unreadable file warns once on stderr and reads as black, as production renderers
//! do. `texture(name, s, t)` samples bilinearly with periodic wrap, box-filtered over the
//! footprint `filterwidth(s) × filterwidth(t)` when the coordinates carry derivatives
//! (up to 4 × 4 bilinear taps). `environment(name, dir)` reads a latitude-longitude map; with
//! the name `"raytrace"` or a missing map it traces a ray instead (what a ray tracer does).
//! `shadow(name, P)` returns 0 (unoccluded): the ray tracers in this project compute shadows
//! with shadow rays inside `illuminance`, so a shadow map would only repeat that.

use anysl_core::prelude::*;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// A decoded image in linear floats.
#[derive(Debug)]
pub struct TexImage {
    w: usize,
    h: usize,
    px: Vec<[f32; 3]>,
}

impl TexImage {
    fn texel(&self, x: i64, y: i64) -> [f32; 3] {
        let x = x.rem_euclid(self.w as i64) as usize;
        let y = y.rem_euclid(self.h as i64) as usize;
        self.px[y * self.w + x]
    }

    /// Bilinear sample at texture coordinates (s, t) in [0, 1), wrapping.
    fn bilinear(&self, s: f64, t: f64) -> [f64; 3] {
        let x = s * self.w as f64 - 0.5;
        let y = t * self.h as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let mut out = [0.0; 3];
        for (dx, dy, wgt) in
            [(0, 0, (1.0 - fx) * (1.0 - fy)), (1, 0, fx * (1.0 - fy)), (0, 1, (1.0 - fx) * fy), (1, 1, fx * fy)]
        {
            let c = self.texel(x0 + dx, y0 + dy);
            for i in 0..3 {
                out[i] += wgt * f64::from(c[i]);
            }
        }
        out
    }
}

type Cache = Mutex<HashMap<String, Option<Arc<TexImage>>>>;

fn cache() -> &'static Cache {
    static CACHE: OnceLock<Cache> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// The image named `name`, loading it on first use (`None` when missing: warned once).
pub fn image(name: &str) -> Option<Arc<TexImage>> {
    if name.is_empty() || name == "raytrace" {
        return None;
    }
    let mut c = cache().lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(v) = c.get(name) {
        return v.clone();
    }
    let loaded = match image::open(name) {
        Ok(img) => {
            let rgb = img.to_rgb32f();
            let (w, h) = (rgb.width() as usize, rgb.height() as usize);
            let px = rgb.pixels().map(|p| [p.0[0], p.0[1], p.0[2]]).collect();
            Some(Arc::new(TexImage { w, h, px }))
        }
        Err(e) => {
            eprintln!("warning[W0003]: texture \"{name}\" cannot be read ({e}); it reads as black");
            None
        }
    };
    c.insert(name.to_string(), loaded.clone());
    loaded
}

/// True when `name` names a readable image.
#[must_use]
pub fn exists(name: &str) -> bool {
    image(name).is_some()
}

/// `environment(name, dir)` on a latitude-longitude map (black when the map is missing).
pub fn sample_environment<F: ShadingFloat>(name: &str, dir: Vec3<F>) -> Color<F> {
    let Some(img) = image(name) else { return Color::zero() };
    let lanes = F::LANES;
    let mut out = [vec![0.0f64; lanes], vec![0.0f64; lanes], vec![0.0f64; lanes]];
    for i in 0..lanes {
        let (x, y, z) = (dir.x.lane(i), dir.y.lane(i), dir.z.lane(i));
        let len = (x * x + y * y + z * z).sqrt().max(1e-30);
        let s = 0.5 + z.atan2(x) / (2.0 * std::f64::consts::PI);
        let t = (y / len).clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
        let c = img.bilinear(s, t);
        for j in 0..3 {
            out[j][i] = c[j];
        }
    }
    Color::new(F::from_lanes(&out[0]), F::from_lanes(&out[1]), F::from_lanes(&out[2]))
}

/// `texture(name, s, t)`, box-filtered over the footprint of `(s, t)` (black when the image
/// is missing).
pub fn sample_st<F: ShadingFloat>(name: &str, s: F, t: F) -> Color<F> {
    let Some(img) = image(name) else { return Color::zero() };
    let lanes = F::LANES;
    let mut out = [vec![0.0f64; lanes], vec![0.0f64; lanes], vec![0.0f64; lanes]];
    let (ws, wt) = (filterwidth(s), filterwidth(t));
    for i in 0..lanes {
        let (sv, tv) = (s.lane(i), t.lane(i));
        let (fw, fh) = (ws.lane(i).abs(), wt.lane(i).abs());
        let taps_s = ((fw * img.w as f64).ceil() as usize).clamp(1, 4);
        let taps_t = ((fh * img.h as f64).ceil() as usize).clamp(1, 4);
        let mut acc = [0.0; 3];
        for a in 0..taps_s {
            for b in 0..taps_t {
                let os = if taps_s > 1 { ((a as f64 + 0.5) / taps_s as f64 - 0.5) * fw } else { 0.0 };
                let ot = if taps_t > 1 { ((b as f64 + 0.5) / taps_t as f64 - 0.5) * fh } else { 0.0 };
                let c = img.bilinear(sv + os, tv + ot);
                for j in 0..3 {
                    acc[j] += c[j];
                }
            }
        }
        let n = (taps_s * taps_t) as f64;
        for j in 0..3 {
            out[j][i] = acc[j] / n;
        }
    }
    Color::new(F::from_lanes(&out[0]), F::from_lanes(&out[1]), F::from_lanes(&out[2]))
}

/// `texture(name[, s, t])` as generated Rust calls it: `st` are the coordinates (`None`: the
/// globals' `s`, `t`).
#[inline]
#[must_use]
pub fn texture<F: ShadingFloat>(name: &str, st: Option<(F, F)>, g: &Globals<F>) -> Color<F> {
    let (s, t) = st.unwrap_or((g.s, g.t));
    sample_st(name, s, t)
}

/// `environment(name, dir)` as generated Rust calls it.
#[inline]
#[must_use]
pub fn environment<F: ShadingFloat>(name: &str, dir: Vec3<F>) -> Color<F> {
    sample_environment(name, dir)
}
