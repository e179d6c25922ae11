//! MIP-mapped images and their filters: a pyramid of box-averaged levels built once at load,
//! sampled by integrating a box (or Gaussian-weighted box) footprint over the texels of the two
//! levels whose texel size brackets the footprint's shorter side, blended by the fractional level (trilinear).
//!
//! A footprint is never narrower than one texel of level 0: a box of one texel over
//! piecewise-constant texels is exactly bilinear interpolation, so magnification needs no
//! separate path.

/// How texture coordinates outside [0, 1] read (`MakeTexture`'s `swrap`/`twrap`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrap {
    /// Repeats the image (`"periodic"`).
    Periodic,
    /// Repeats the edge texels (`"clamp"`).
    Clamp,
    /// Reads zero in every channel (`"black"`).
    Black,
}

impl Wrap {
    /// The mode named `name` (`periodic`, `clamp`, `black`), `None` for anything else.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "periodic" => Some(Self::Periodic),
            "clamp" => Some(Self::Clamp),
            "black" => Some(Self::Black),
            _ => None,
        }
    }

    /// The texel index `i` of a row of `n` reads (`None`: black).
    #[inline]
    fn index(self, i: i64, n: usize) -> Option<usize> {
        let n = n as i64;
        match self {
            Self::Periodic => Some(i.rem_euclid(n) as usize),
            Self::Clamp => Some(i.clamp(0, n - 1) as usize),
            Self::Black => (0..n).contains(&i).then_some(i as usize),
        }
    }
}

/// The filter weighting texels inside a footprint (`"filter"` of `texture()`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    /// Every texel weighted by the area it shares with the footprint.
    Box,
    /// The area weights times a Gaussian of the distance from the footprint's centre, falling
    /// to e^-2 at the footprint's edge.
    Gaussian,
}

/// One level of a pyramid: `w × h` texels of `channels` floats, row 0 at t = 0 (the top).
#[derive(Clone, Debug)]
pub struct Level {
    /// Width in texels.
    pub w: usize,
    /// Height in texels.
    pub h: usize,
    data: Vec<f32>,
}

impl Level {
    /// Channel `c` of texel `(x, y)` (`x < w`, `y < h`, `c <` the map's channels).
    #[inline]
    #[must_use]
    pub fn texel(&self, x: usize, y: usize, c: usize) -> f32 {
        let n = self.data.len() / (self.w * self.h);
        self.data[(y * self.w + x) * n + c]
    }
}

/// An image and its MIP levels (level 0 is the image; each next level halves both sizes,
/// rounding down, to 1 × 1).
#[derive(Clone, Debug)]
pub struct MipMap {
    channels: usize,
    levels: Vec<Level>,
}

thread_local! {
    /// [`MipMap::box_at`]'s weights along s and t.
    static AXIS_WEIGHTS: core::cell::RefCell<(Vec<(i64, f64)>, Vec<(i64, f64)>)> =
        const { core::cell::RefCell::new((Vec::new(), Vec::new())) };
}

/// The area weights of the texels a 1-D interval `[a, b)` (in texels) overlaps, each times
/// a Gaussian of its centre's distance from the interval's middle when `gauss`.
fn weights(a: f64, b: f64, gauss: bool, out: &mut Vec<(i64, f64)>) {
    out.clear();
    let (mid, width) = ((a + b) * 0.5, (b - a).max(1e-12));
    let first = a.floor() as i64;
    let last = (b.ceil() as i64 - 1).max(first);
    for i in first..=last {
        let lo = a.max(i as f64);
        let hi = b.min(i as f64 + 1.0);
        let mut wgt = (hi - lo).max(0.0);
        if gauss {
            let r = (i as f64 + 0.5 - mid) / width;
            wgt *= (-8.0 * r * r).exp();
        }
        if wgt > 0.0 {
            out.push((i, wgt));
        }
    }
}

/// Widest footprint taken, in texture-space units: wider ones read the same as this (a
/// periodic map is averaged whole well before; it bounds the work for absurd derivatives).
const MAX_WIDTH: f64 = 4.0;

/// The most texels of its level the longer side of a footprint spans.
pub const MAX_ANISOTROPY: f64 = 8.0;

impl MipMap {
    /// A pyramid over `w × h` texels of `channels` interleaved floats (row 0 at the top).
    ///
    /// # Panics
    /// When `data.len() != w * h * channels` or a size is zero (callers build from decoded
    /// images, which satisfy both).
    #[must_use]
    pub fn new(w: usize, h: usize, channels: usize, data: Vec<f32>) -> Self {
        assert!(w > 0 && h > 0 && channels > 0 && data.len() == w * h * channels);
        let mut levels = vec![Level { w, h, data }];
        while let Some(top) = levels.last().filter(|l| l.w > 1 || l.h > 1) {
            levels.push(Self::half(top, channels));
        }
        Self { channels, levels }
    }

    /// The next level: each texel the area-weighted average of the 2 × 2 (up to 3 × 3 for odd
    /// sizes) texels of `l` it covers, so every level keeps the image's mean.
    fn half(l: &Level, c: usize) -> Level {
        let (w, h) = ((l.w / 2).max(1), (l.h / 2).max(1));
        let (rx, ry) = (l.w as f64 / w as f64, l.h as f64 / h as f64);
        let mut data = vec![0.0f32; w * h * c];
        let (mut wx, mut wy) = (Vec::new(), Vec::new());
        let mut acc = vec![0.0f64; c];
        for y in 0..h {
            weights(y as f64 * ry, (y + 1) as f64 * ry, false, &mut wy);
            for x in 0..w {
                weights(x as f64 * rx, (x + 1) as f64 * rx, false, &mut wx);
                acc.fill(0.0);
                let mut total = 0.0;
                for &(j, wj) in &wy {
                    for &(i, wi) in &wx {
                        let (i, j) = ((i as usize).min(l.w - 1), (j as usize).min(l.h - 1));
                        let wgt = wi * wj;
                        total += wgt;
                        for (a, v) in acc.iter_mut().zip(&l.data[(j * l.w + i) * c..][..c]) {
                            *a += wgt * f64::from(*v);
                        }
                    }
                }
                for (d, a) in data[(y * w + x) * c..][..c].iter_mut().zip(&acc) {
                    *d = (a / total) as f32;
                }
            }
        }
        Level { w, h, data }
    }

    /// Channels per texel.
    #[must_use]
    pub fn channels(&self) -> usize {
        self.channels
    }

    /// The levels, finest first.
    #[must_use]
    pub fn levels(&self) -> &[Level] {
        &self.levels
    }

    /// Width and height of level 0.
    #[must_use]
    pub fn resolution(&self) -> (usize, usize) {
        (self.levels[0].w, self.levels[0].h)
    }

    /// The continuous MIP level for a footprint `ws × wt` (texture-space widths): log2 of its
    /// shorter side in texels of level 0, raised so that the longer side spans at most
    /// [`MAX_ANISOTROPY`] texels; at least 0 and at most the coarsest level. (The box is
    /// integrated exactly on the level chosen, so an elongated footprint stays sharp across.)
    #[must_use]
    pub fn lod(&self, ws: f64, wt: f64) -> f64 {
        let (w, h) = self.resolution();
        let (a, b) = (ws * w as f64, wt * h as f64);
        let texels = a.min(b).max(a.max(b) / MAX_ANISOTROPY).max(1.0);
        texels.log2().clamp(0.0, (self.levels.len() - 1) as f64)
    }

    /// The filtered value of channels `first..first + out.len()` over the footprint centred on
    /// `(s, t)` of texture-space size `ws × wt`; channels the image lacks read `fill`.
    /// Non-finite coordinates read `fill` in every channel.
    #[allow(clippy::too_many_arguments)]
    pub fn filter(
        &self,
        s: f64,
        t: f64,
        ws: f64,
        wt: f64,
        wrap: (Wrap, Wrap),
        filter: Filter,
        first: usize,
        fill: f64,
        out: &mut [f64],
    ) {
        let ws = if ws.is_finite() { ws.abs().min(MAX_WIDTH) } else { MAX_WIDTH };
        let wt = if wt.is_finite() { wt.abs().min(MAX_WIDTH) } else { MAX_WIDTH };
        if !(s.is_finite() && t.is_finite()) {
            out.fill(fill);
            return;
        }
        let lod = self.lod(ws, wt);
        let lo = lod.floor() as usize;
        let f = lod - lo as f64;
        let mut a = [0.0f64; 4];
        let mut b = [0.0f64; 4];
        let n = out.len().min(4);
        self.box_at(lo, s, t, ws, wt, wrap, filter, first, &mut a[..n]);
        if f > 0.0 && lo + 1 < self.levels.len() {
            self.box_at(lo + 1, s, t, ws, wt, wrap, filter, first, &mut b[..n]);
        }
        for (k, o) in out.iter_mut().enumerate() {
            *o = if first + k >= self.channels {
                fill
            } else if k < 4 {
                a[k] * (1.0 - f) + b[k] * f
            } else {
                fill
            };
        }
    }

    /// The footprint integrated over the texels of level `li` (the footprint is at least one
    /// texel of that level wide).
    #[allow(clippy::too_many_arguments)]
    fn box_at(
        &self,
        li: usize,
        s: f64,
        t: f64,
        ws: f64,
        wt: f64,
        wrap: (Wrap, Wrap),
        filter: Filter,
        first: usize,
        out: &mut [f64],
    ) {
        let l = &self.levels[li];
        let (fw, fh) = ((ws * l.w as f64).max(1.0), (wt * l.h as f64).max(1.0));
        let (cx, cy) = (s * l.w as f64, t * l.h as f64);
        let gauss = filter == Filter::Gaussian;
        out.fill(0.0);
        let mut total = 0.0;
        let c = self.channels;
        // The two axes' weights in buffers kept per thread: a look-up (per point and lane in
        // a shader's inner loop) allocates nothing.
        AXIS_WEIGHTS.with(|axes| {
            let (wx, wy) = &mut *axes.borrow_mut();
            weights(cx - fw * 0.5, cx + fw * 0.5, gauss, wx);
            weights(cy - fh * 0.5, cy + fh * 0.5, gauss, wy);
            for &(j, wj) in wy.iter() {
                let row = wrap.1.index(j, l.h);
                for &(i, wi) in wx.iter() {
                    let wgt = wi * wj;
                    total += wgt;
                    let (Some(y), Some(x)) = (row, wrap.0.index(i, l.w)) else { continue };
                    let texel = &l.data[(y * l.w + x) * c..][..c];
                    for (k, o) in out.iter_mut().enumerate() {
                        if let Some(v) = texel.get(first + k) {
                            *o += wgt * f64::from(*v);
                        }
                    }
                }
            }
        });
        if total > 0.0 {
            for o in out.iter_mut() {
                *o /= total;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const P: (Wrap, Wrap) = (Wrap::Periodic, Wrap::Periodic);

    /// 2 × 2 RGB: red, green / blue, white.
    fn quad() -> MipMap {
        #[rustfmt::skip]
        let data = vec![1.0, 0.0, 0.0,  0.0, 1.0, 0.0,
                        0.0, 0.0, 1.0,  1.0, 1.0, 1.0];
        MipMap::new(2, 2, 3, data)
    }

    fn look(m: &MipMap, s: f64, t: f64, w: f64, wrap: (Wrap, Wrap), filter: Filter) -> [f64; 3] {
        let mut out = [0.0; 3];
        m.filter(s, t, w, w, wrap, filter, 0, 0.0, &mut out);
        out
    }

    #[test]
    fn a_box_over_the_whole_image_is_the_texel_average() {
        let v = look(&quad(), 0.5, 0.5, 1.0, P, Filter::Box);
        assert_eq!(v, [0.5, 0.5, 0.5]);
        // Off centre, a periodic map averages the same.
        let v = look(&quad(), 0.3, 0.8, 1.0, P, Filter::Box);
        for c in v {
            assert!((c - 0.5).abs() < 1e-12, "{v:?}");
        }
    }

    #[test]
    fn a_box_over_one_texel_is_that_texel() {
        let m = quad();
        assert_eq!(look(&m, 0.25, 0.25, 0.5, P, Filter::Box), [1.0, 0.0, 0.0]);
        assert_eq!(look(&m, 0.75, 0.25, 0.5, P, Filter::Box), [0.0, 1.0, 0.0]);
        assert_eq!(look(&m, 0.25, 0.75, 0.5, P, Filter::Box), [0.0, 0.0, 1.0]);
        assert_eq!(look(&m, 0.75, 0.75, 0.5, P, Filter::Box), [1.0, 1.0, 1.0]);
        // A point (no footprint) at a texel centre reads the texel too.
        assert_eq!(look(&m, 0.75, 0.75, 0.0, P, Filter::Box), [1.0, 1.0, 1.0]);
    }

    #[test]
    fn between_texel_centres_a_point_reads_bilinearly() {
        // Halfway between red (0,0) and green (1,0) on the top row.
        let v = look(&quad(), 0.5, 0.25, 0.0, P, Filter::Box);
        assert_eq!(v, [0.5, 0.5, 0.0]);
    }

    #[test]
    fn wrap_modes_read_outside_the_image_as_stated() {
        let m = quad();
        // One texel left of red: periodic reads green, clamp red, black nothing.
        assert_eq!(look(&m, -0.25, 0.25, 0.5, P, Filter::Box), [0.0, 1.0, 0.0]);
        assert_eq!(look(&m, -0.25, 0.25, 0.5, (Wrap::Clamp, Wrap::Clamp), Filter::Box), [1.0, 0.0, 0.0]);
        assert_eq!(look(&m, -0.25, 0.25, 0.5, (Wrap::Black, Wrap::Black), Filter::Box), [0.0; 3]);
        // Half in, half out: black averages with zero.
        assert_eq!(look(&m, 0.0, 0.25, 0.5, (Wrap::Black, Wrap::Black), Filter::Box), [0.5, 0.0, 0.0]);
    }

    #[test]
    fn the_level_follows_the_footprint() {
        let m = MipMap::new(64, 64, 1, vec![0.5; 64 * 64]);
        assert_eq!(m.levels().len(), 7);
        assert_eq!(m.lod(4.0 / 64.0, 4.0 / 64.0), 2.0);
        // Elongated: the shorter side decides until the longer one passes 8 texels.
        assert_eq!(m.lod(4.0 / 64.0, 1.0 / 64.0), 0.0);
        assert_eq!(m.lod(1.0, 2.0 / 64.0), 3.0);
        assert_eq!(m.lod(1.0 / 128.0, 0.0), 0.0);
        assert!((m.lod(3.0 / 64.0, 3.0 / 64.0) - 3f64.log2()).abs() < 1e-12);
        assert_eq!(m.lod(100.0, 100.0), 6.0);
        // Odd sizes: 5 × 3 → 2 × 1 → 1 × 1, each level keeping the mean.
        let data: Vec<f32> = (0..15).map(|i| i as f32).collect();
        let m = MipMap::new(5, 3, 1, data);
        let sizes: Vec<(usize, usize)> = m.levels().iter().map(|l| (l.w, l.h)).collect();
        assert_eq!(sizes, [(5, 3), (2, 1), (1, 1)]);
        assert!((m.levels()[2].data[0] - 7.0).abs() < 1e-5);
        assert!((m.levels()[1].data.iter().sum::<f32>() / 2.0 - 7.0).abs() < 1e-5);
    }

    #[test]
    fn a_footprint_between_levels_blends_them() {
        // 4 × 1 texels 0, 0, 4, 4: level 1 is 0, 4; level 2 is 2. (Footprints as many texels
        // tall as wide; the one row is clamped.)
        let m = MipMap::new(4, 1, 1, vec![0.0, 0.0, 4.0, 4.0]);
        let mut out = [0.0];
        // At s = 0.25 a footprint of 2 texels (lod 1) reads level 1's texel 0 exactly…
        m.filter(0.25, 0.5, 0.5, 2.0, (Wrap::Clamp, Wrap::Clamp), Filter::Box, 0, 0.0, &mut out);
        assert_eq!(out[0], 0.0);
        // …a footprint of 4 texels (lod 2) reads the mean, 2…
        m.filter(0.25, 0.5, 1.0, 4.0, (Wrap::Clamp, Wrap::Clamp), Filter::Box, 0, 0.0, &mut out);
        assert_eq!(out[0], 2.0);
        // …and one of sqrt(8) texels (lod 1.5) lies halfway: on level 1 it spans sqrt(2)
        // texels centred on texel 0 (value 0), reaching (sqrt(2) - 1) / 2 into texel 1 (4) and
        // as far into the clamped edge (0).
        m.filter(0.25, 0.5, 8f64.sqrt() / 4.0, 8f64.sqrt(), (Wrap::Clamp, Wrap::Clamp), Filter::Box, 0, 0.0, &mut out);
        let r = (2f64.sqrt() - 1.0) / 2.0;
        let level1 = 4.0 * r / 2f64.sqrt();
        assert!((out[0] - (0.5 * level1 + 0.5 * 2.0)).abs() < 1e-12, "{}", out[0]);
    }

    #[test]
    fn a_gaussian_weighs_the_centre_more_than_a_box() {
        // 3 × 1: 0, 3, 0 — a box of three texels centred on the middle reads 1, the Gaussian more.
        let m = MipMap::new(3, 1, 1, vec![0.0, 3.0, 0.0]);
        let mut b = [0.0];
        let mut g = [0.0];
        let c = (Wrap::Black, Wrap::Clamp);
        m.box_at(0, 0.5, 0.5, 1.0, 0.0, c, Filter::Box, 0, &mut b);
        m.box_at(0, 0.5, 0.5, 1.0, 0.0, c, Filter::Gaussian, 0, &mut g);
        assert!((b[0] - 1.0).abs() < 1e-12);
        let e = (-8.0f64 / 9.0).exp();
        assert!((g[0] - 3.0 / (1.0 + 2.0 * e)).abs() < 1e-12, "{}", g[0]);
    }

    #[test]
    fn missing_channels_read_the_fill_and_bad_coordinates_too() {
        let m = quad();
        let mut out = [0.0; 3];
        m.filter(0.25, 0.25, 0.5, 0.5, P, Filter::Box, 2, 0.7, &mut out);
        assert_eq!(out, [0.0, 0.7, 0.7]);
        m.filter(f64::NAN, 0.25, 0.5, 0.5, P, Filter::Box, 0, 0.25, &mut out);
        assert_eq!(out, [0.25; 3]);
        // Huge and NaN widths are bounded: the average.
        m.filter(0.5, 0.5, f64::INFINITY, f64::NAN, P, Filter::Box, 0, 0.0, &mut out);
        assert_eq!(out, [0.5; 3]);
    }
}
