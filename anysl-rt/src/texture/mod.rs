//! Texture look-ups for `texture()`, `environment()`, `shadow()` and `textureinfo()`.
//!
//! Maps live in a per-run store ([`store`]): images are read through the `image` crate (PNG,
//! TIFF of 8/16 bits or floats, JPEG, OpenEXR) on first use, kept with their channels (1–4)
//! and MIP levels ([`mip`]), and shared by every thread. RIB `Make*` requests register a name
//! for a source picture with wrap modes and a filter ([`store::make`]); they build the map in
//! memory and write no file.
//!
//! The filter footprint comes from the derivative parts of the coordinates: with `Dual`
//! numbers, `s` and `t` carry ∂/∂x and ∂/∂y across the pixel, and the footprint's sides are
//! `|∂s/∂x| + |∂s/∂y|` by `|∂t/∂x| + |∂t/∂y|` (times `"swidth"`/`"twidth"`, plus
//! `"sblur"`/`"tblur"`). The four-corner form takes the corners' bounding box instead. Plain
//! floats have no footprint: a look-up reads one texel's worth, i.e. bilinearly.
//!
//! A missing map warns once (naming the file and where it was looked for) and reads `"fill"`
//! in every channel (`texture`, `environment`), or 0 — unoccluded — (`shadow`).

pub mod env;
pub mod mip;
pub mod shadow;
pub mod store;

pub use mip::{Filter, MipMap, Wrap};
pub use store::{add_search_path, make, DepthCamera, MakeSpec, Map, MapKind};

use anysl_core::prelude::*;

/// The most lanes a look-up serves at once (per-lane results live in arrays of this size; the
/// widest instantiation, a pair of 16-lane vectors, has 32).
const MAX_LANES: usize = 64;

/// The optional arguments of a look-up (`"blur"`, `"width"`, `"fill"`, …) and the channel
/// selected by `"name"[c]`.
#[derive(Clone, Copy, Debug)]
pub struct TexOptions<F> {
    /// First channel read (`texture("name"[c], …)`).
    pub first: usize,
    /// Extra filter width added in s and t, in texture-space units (`"blur"`, `"sblur"`,
    /// `"tblur"`).
    pub blur: [F; 2],
    /// Multipliers of the footprint's sides (`"width"`, `"swidth"`, `"twidth"`).
    pub width: [F; 2],
    /// The value of channels the map lacks, and of a missing map (`"fill"`).
    pub fill: F,
    /// The filter (`"filter"`), `None`: the map's own (its `Make*` request's, else box).
    pub filter: Option<Filter>,
    /// Shadow: samples per look-up (`"samples"`).
    pub samples: F,
    /// Shadow: depth bias (`"bias"`).
    pub bias: F,
}

impl<F: ShadingFloat> Default for TexOptions<F> {
    fn default() -> Self {
        Self {
            first: 0,
            blur: [F::c(0.0); 2],
            width: [F::c(1.0); 2],
            fill: F::c(0.0),
            filter: None,
            samples: F::c(16.0),
            bias: F::c(0.0),
        }
    }
}

impl<F: ShadingFloat> TexOptions<F> {
    /// Sets a float option by name; an unknown name warns once and is ignored.
    pub fn set_float(&mut self, name: &str, v: F) {
        match name {
            "blur" => self.blur = [v; 2],
            "sblur" => self.blur[0] = v,
            "tblur" => self.blur[1] = v,
            "width" => self.width = [v; 2],
            "swidth" => self.width[0] = v,
            "twidth" => self.width[1] = v,
            "fill" => self.fill = v,
            "samples" => self.samples = v,
            "bias" => self.bias = v,
            "firstchannel" => self.first = v.lane(0).clamp(0.0, 64.0) as usize,
            other => unknown_option(other),
        }
    }

    /// Sets a string option by name (`"filter"`); others warn once and are ignored.
    pub fn set_string(&mut self, name: &str, v: &str) {
        match (name, v) {
            ("filter", "box") => self.filter = Some(Filter::Box),
            ("filter", "gaussian") => self.filter = Some(Filter::Gaussian),
            ("filter", other) => {
                store::warn_once(&format!("filter:{other}"), || {
                    format!("warning[W0003]: texture filter \"{other}\" is not implemented; box is used")
                });
                self.filter = Some(Filter::Box);
            }
            (other, _) => unknown_option(other),
        }
    }
}

fn unknown_option(name: &str) {
    store::warn_once(&format!("option:{name}"), || {
        format!("warning[W0003]: texture option \"{name}\" is not known to anysl and is ignored")
    });
}

/// Where a texture look-up reads.
#[derive(Clone, Copy, Debug)]
pub enum St<F> {
    /// Around `(s, t)`, the footprint from their derivatives.
    Point(F, F),
    /// The quadrilateral `(s1, t1) … (s4, t4)`: its bounding box.
    Quad([F; 8]),
}

/// Per lane: the centre and sides of the footprint in texture space.
fn footprint<F: ShadingFloat>(st: &St<F>, o: &TexOptions<F>, i: usize) -> [f64; 4] {
    let (sw, tw) = (o.width[0].lane(i), o.width[1].lane(i));
    let (sb, tb) = (o.blur[0].lane(i).abs(), o.blur[1].lane(i).abs());
    match st {
        St::Point(s, t) => {
            let d = |x: F| x.dx().lane(i).abs() + x.dy().lane(i).abs();
            [s.lane(i), t.lane(i), d(*s) * sw + sb, d(*t) * tw + tb]
        }
        St::Quad(c) => {
            let ss = [c[0], c[2], c[4], c[6]].map(|x| x.lane(i));
            let ts = [c[1], c[3], c[5], c[7]].map(|x| x.lane(i));
            let span = |v: [f64; 4]| {
                let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(*x), b.max(*x)));
                ((lo + hi) * 0.5, hi - lo)
            };
            let ((s, ws), (t, wt)) = (span(ss), span(ts));
            [s, t, ws * sw + sb, wt * tw + tb]
        }
    }
}

/// Channels `o.first..o.first + 3` of map `name` filtered over the footprint of `st`: a color
/// look-up reads all three, a float look-up the first. A one-channel map read as a color gives
/// its channel in all three; other missing channels read `"fill"`.
#[must_use]
pub fn lookup<F: ShadingFloat>(name: &str, st: St<F>, o: &TexOptions<F>) -> Color<F> {
    let Some(map) = store::map(name, MapKind::Texture) else { return Color::splat(o.fill) };
    let img = &map.faces[0];
    let filter = o.filter.unwrap_or(map.filter);
    let gray = img.channels() == 1 && o.first == 0;
    let mut out = [[0.0f64; MAX_LANES]; 3];
    for i in 0..F::LANES {
        let [s, t, ws, wt] = footprint(&st, o, i);
        let mut v = [0.0; 3];
        let n = if gray { 1 } else { 3 };
        img.filter(s, t, ws, wt, map.wrap, filter, o.first, o.fill.lane(i), &mut v[..n]);
        if gray {
            v = [v[0]; 3];
        }
        for (o, x) in out.iter_mut().zip(v) {
            o[i] = x;
        }
    }
    let lanes = |c: usize| F::from_lanes(&out[c][..F::LANES]);
    Color::new(lanes(0), lanes(1), lanes(2))
}

/// True when `name` names a map that can be read.
#[must_use]
pub fn exists(name: &str) -> bool {
    store::map(name, MapKind::Texture).is_some()
}

/// `texture(name[, s, t])` as generated Rust calls it: `st` are the coordinates (`None`: the
/// globals' `s`, `t`), default options.
#[inline]
#[must_use]
pub fn texture<F: ShadingFloat>(name: &str, st: Option<(F, F)>, g: &Globals<F>) -> Color<F> {
    let (s, t) = st.unwrap_or((g.s, g.t));
    lookup(name, St::Point(s, t), &TexOptions::default())
}

/// `environment(name, dir)` as generated Rust calls it, default options.
#[inline]
#[must_use]
pub fn environment<F: ShadingFloat>(name: &str, dir: Vec3<F>) -> Color<F> {
    env::lookup(name, env::Dir::Ray(dir), &TexOptions::default())
}

/// What `textureinfo(name, query, var)` answers.
#[derive(Clone, Debug, PartialEq)]
pub enum Info {
    /// `"resolution"`: width, height (of level 0, of one face for a cube).
    Resolution([f64; 2]),
    /// `"type"`: `texture`, `environment` or `shadow`.
    Type(&'static str),
    /// `"channels"`.
    Channels(f64),
    /// `"viewingmatrix"` (world → the depth pass's camera) or `"projectionmatrix"` (world →
    /// its screen), row-major with row vectors as RSL matrices are.
    Matrix([f64; 16]),
}

/// `textureinfo(name, query)`: `None` when the map is missing or does not have that datum
/// (matrices exist for shadow maps only; unknown queries).
#[must_use]
pub fn info(name: &str, query: &str) -> Option<Info> {
    let map = store::map(name, MapKind::Texture)?;
    let (w, h) = map.faces[0].resolution();
    match query {
        "resolution" => Some(Info::Resolution([w as f64, h as f64])),
        "type" => Some(Info::Type(map.kind.type_name())),
        "channels" => Some(Info::Channels(map.channels() as f64)),
        "viewingmatrix" => map.camera.as_ref().map(|c| Info::Matrix(c.world_to_camera)),
        "projectionmatrix" => {
            map.camera.as_ref().map(|c| Info::Matrix(shadow::mat_mul(&c.projection, &c.world_to_camera)))
        }
        _ => None,
    }
}
