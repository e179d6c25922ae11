//! The film: from the renderer's samples to the pixels of a `Display`.
//!
//! The renderer is asked for one sample at the centre of every cell of an `nx × ny` grid in
//! each pixel (`PixelSamples`, stratified), over the crop window grown by the filter's
//! reach ([`SampleWindow`]). The film then *gathers*: each output pixel is the
//! filter-weighted mean of the samples within `±width/2` of its centre, the kernel applied
//! separably in x and then in y. Then the `Imager` shader, if any ([`run_imager`]), then
//! `Exposure` (`(gain · c)^(1/gamma)`) and `Quantize`
//! (`round(one · c + dither)` clamped to `[min, max]`, with a dither that depends only on the
//! pixel, so any subset of frames or a re-run gives identical files).

use crate::build::{DisplayDesc, DisplayFormat, Film, FilterKind, PixelFilter};
use anysl_core::{Color, ImagerPixel, ImagerShader, Vec3};
use anysl_renderers::CameraSpec;
use std::path::Path;

/// The grid of samples the renderer computes for a frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleWindow {
    /// First pixel column covered (may be negative: samples beyond the image edge).
    pub x0: i64,
    /// First pixel row covered.
    pub y0: i64,
    /// Pixels covered across.
    pub width: u32,
    /// Pixels covered down.
    pub height: u32,
    /// Samples per pixel across and down.
    pub samples: [u32; 2],
}

impl SampleWindow {
    /// The samples `film` needs: its crop window grown by the filter's reach.
    #[must_use]
    pub fn of(film: &Film) -> Self {
        let [x0, x1, y0, y1] = film.crop_pixels();
        let reach = |w: f32| (w * 0.5 - 0.5).ceil().max(0.0) as i64;
        let (mx, my) = (reach(film.filter.xwidth), reach(film.filter.ywidth));
        Self {
            x0: i64::from(x0) - mx,
            y0: i64::from(y0) - my,
            width: (i64::from(x1 - x0) + 2 * mx).max(1) as u32,
            height: (i64::from(y1 - y0) + 2 * my).max(1) as u32,
            samples: film.samples,
        }
    }

    /// The size of the sample image: one renderer pixel per sample.
    #[must_use]
    pub fn sample_size(&self) -> (u32, u32) {
        (self.width * self.samples[0], self.height * self.samples[1])
    }

    /// The camera that renders exactly these samples: the screen window of the covered pixels
    /// (one renderer pixel per sample, its centre at the centre of the sample's cell).
    #[must_use]
    pub fn camera(&self, spec: &CameraSpec, film: &Film) -> CameraSpec {
        let [l, r, b, t] = spec.screen_window;
        let (xres, yres) = (film.xres as f32, film.yres as f32);
        let sx = |px: i64| l + (r - l) * px as f32 / xres;
        let sy = |py: i64| t - (t - b) * py as f32 / yres;
        let x1 = self.x0 + i64::from(self.width);
        let y1 = self.y0 + i64::from(self.height);
        CameraSpec { screen_window: [sx(self.x0), sx(x1), sy(y1), sy(self.y0)], ..*spec }
    }
}

/// The filter kernel at offset `x` pixels from the pixel centre.
#[must_use]
pub fn kernel(kind: FilterKind, width: f32, x: f32) -> f32 {
    let half = width * 0.5;
    let ax = x.abs();
    if ax > half {
        return 0.0;
    }
    match kind {
        FilterKind::Box => 1.0,
        FilterKind::Triangle => (1.0 - ax / half).max(0.0),
        FilterKind::CatmullRom => {
            // The Catmull-Rom cubic, its support [-2, 2] stretched over the filter width.
            let t = ax * 4.0 / width;
            if t < 1.0 {
                1.5 * t * t * t - 2.5 * t * t + 1.0
            } else if t < 2.0 {
                -0.5 * t * t * t + 2.5 * t * t - 4.0 * t + 2.0
            } else {
                0.0
            }
        }
        FilterKind::Gaussian => {
            let t = ax / half;
            (-2.0 * t * t).exp()
        }
        FilterKind::Sinc => {
            if ax < 1e-6 {
                1.0
            } else {
                let p = std::f32::consts::PI * ax;
                p.sin() / p
            }
        }
    }
}

/// Applies the pixel filter along one axis: `src` holds `n_src` samples per line (sample `i`
/// at pixel coordinate `origin + (i + 0.5)/per_pixel`), the result `n_out` pixels per line
/// (pixel `j` centred at `first + j + 0.5`). `stride`/`lines` describe the layout.
#[allow(clippy::too_many_arguments)]
fn filter_axis(
    src: &[[f32; 4]],
    n_src: usize,
    lines: usize,
    along_rows: bool,
    origin: i64,
    per_pixel: u32,
    first: i64,
    n_out: usize,
    kind: FilterKind,
    width: f32,
) -> Vec<[f32; 4]> {
    // Weights per output pixel: (first sample, weights), normalized.
    let inv = 1.0 / per_pixel as f32;
    let taps: Vec<(usize, Vec<f32>)> = (0..n_out)
        .map(|j| {
            let centre = (first + j as i64) as f32 + 0.5;
            let lo = ((centre - width * 0.5 - origin as f32) * per_pixel as f32 - 0.5).floor().max(0.0) as usize;
            let hi = (((centre + width * 0.5 - origin as f32) * per_pixel as f32 - 0.5).ceil().max(0.0) as usize)
                .min(n_src.saturating_sub(1));
            let mut w: Vec<f32> = (lo..=hi.max(lo))
                .map(|i| kernel(kind, width, origin as f32 + (i as f32 + 0.5) * inv - centre))
                .collect();
            let sum: f32 = w.iter().sum();
            if sum.abs() > 1e-8 {
                w.iter_mut().for_each(|x| *x /= sum);
            } else {
                // A kernel narrower than the sample spacing: the nearest sample.
                let nearest =
                    (((centre - origin as f32) * per_pixel as f32 - 0.5).round().max(0.0) as usize).min(n_src - 1);
                return (nearest, vec![1.0]);
            }
            (lo, w)
        })
        .collect();
    let mut out = vec![[0.0f32; 4]; n_out * lines];
    for line in 0..lines {
        for (j, (lo, w)) in taps.iter().enumerate() {
            let mut acc = [0.0f32; 4];
            for (k, wk) in w.iter().enumerate() {
                let i = lo + k;
                let s = if along_rows { src[line * n_src + i] } else { src[i * lines + line] };
                for c in 0..4 {
                    acc[c] += wk * s[c];
                }
            }
            if along_rows {
                out[line * n_out + j] = acc;
            } else {
                out[j * lines + line] = acc;
            }
        }
    }
    out
}

/// Filters the samples of `window` (row-major RGBA, alpha = coverage) into the crop window's
/// pixels (row-major RGBA, before exposure).
#[must_use]
pub fn reconstruct(film: &Film, window: &SampleWindow, samples: &[[f32; 4]]) -> Vec<[f32; 4]> {
    let (sw, sh) = window.sample_size();
    let [x0, x1, y0, y1] = film.crop_pixels();
    let PixelFilter { kind, xwidth, ywidth } = film.filter;
    let rows = filter_axis(
        samples,
        sw as usize,
        sh as usize,
        true,
        window.x0,
        window.samples[0],
        i64::from(x0),
        (x1 - x0) as usize,
        kind,
        xwidth,
    );
    filter_axis(
        &rows,
        sh as usize,
        (x1 - x0) as usize,
        false,
        window.y0,
        window.samples[1],
        i64::from(y0),
        (y1 - y0) as usize,
        kind,
        ywidth,
    )
}

/// Pixels an imager shader runs on at once (the interpreter decodes each op once per batch).
const IMAGER_BATCH: usize = 256;

/// Runs the imager shader on the crop window's filtered pixels (row-major RGBA, alpha =
/// coverage): each pixel's `P` is the raster position of its centre (`x + ½`, `y + ½`, 0),
/// `Ci` its colour, `Oi` and `alpha` its alpha; it becomes (`Ci`, `alpha`) as the shader
/// leaves them. Values that are not finite become 0.
pub fn run_imager<I: ImagerShader>(imager: &I, film: &Film, pixels: &mut [[f32; 4]]) {
    let [x0, x1, y0, _] = film.crop_pixels();
    let w = (x1 - x0).max(1) as usize;
    let masks = [true; IMAGER_BATCH];
    for (b, batch) in pixels.chunks_mut(IMAGER_BATCH).enumerate() {
        let mut px: Vec<ImagerPixel<f32>> = batch
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let k = b * IMAGER_BATCH + i;
                let (x, y) = ((x0 as usize + k % w) as f32 + 0.5, (y0 as usize + k / w) as f32 + 0.5);
                ImagerPixel {
                    P: Vec3::new(x, y, 0.0),
                    Ci: Color::new(p[0], p[1], p[2]),
                    Oi: Color::new(p[3], p[3], p[3]),
                    alpha: p[3],
                }
            })
            .collect();
        imager.image_batch(&mut px, &masks[..batch.len()]);
        for (p, out) in batch.iter_mut().zip(&px) {
            let finite = |v: f32| if v.is_finite() { v } else { 0.0 };
            *p = [finite(out.Ci.r), finite(out.Ci.g), finite(out.Ci.b), finite(out.alpha)];
        }
    }
}

/// A deterministic dither in `[-1, 1)` for pixel `(x, y)`, channel `c`.
fn dither(x: u32, y: u32, c: u32) -> f32 {
    let mut h = u64::from(x) << 40 ^ u64::from(y) << 16 ^ u64::from(c);
    h = (h ^ (h >> 33)).wrapping_mul(0xff51_afd7_ed55_8ccd);
    h = (h ^ (h >> 33)).wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    h ^= h >> 33;
    (h >> 40) as f32 / (1u64 << 23) as f32 - 1.0
}

/// Exposure and quantization of one value of pixel `(x, y)`, channel `c`.
#[must_use]
pub fn quantize(film: &Film, v: f32, x: u32, y: u32, c: u32) -> u16 {
    let exposed = (film.gain * v).max(0.0).powf(1.0 / film.gamma);
    let q = film.quantize;
    if q.one == 0 {
        // Quantize 0: floating point output is not written; clamp to the 16-bit range.
        return (exposed.clamp(0.0, 1.0) * 65535.0).round() as u16;
    }
    let value = (q.one as f32 * exposed + q.dither * dither(x, y, c)).round();
    value.clamp(q.min as f32, q.max as f32).clamp(0.0, 65535.0) as u16
}

/// The quantized pixels of the crop window: `channels` (3 or 4) values per pixel.
#[must_use]
pub fn quantized(film: &Film, pixels: &[[f32; 4]], channels: usize) -> Vec<u16> {
    let [x0, x1, y0, _] = film.crop_pixels();
    let w = (x1 - x0) as usize;
    let mut out = Vec::with_capacity(pixels.len() * channels);
    for (k, p) in pixels.iter().enumerate() {
        let (x, y) = (x0 + (k % w) as u32, y0 + (k / w) as u32);
        for c in 0..channels {
            // Alpha is quantized like the colours (gain and gamma apply to colour only).
            let v = if c == 3 {
                let q = film.quantize;
                ((q.one.max(1) as f32 * p[3] + q.dither * dither(x, y, 3)).round()).clamp(q.min as f32, q.max as f32)
                    as u16
            } else {
                quantize(film, p[c], x, y, c as u32)
            };
            out.push(v);
        }
    }
    out
}

/// Writes the crop window's pixels to `path` as the display says (8-bit when the quantized
/// maximum fits, else 16-bit).
///
/// # Errors
/// The file cannot be written.
pub fn write(film: &Film, display: &DisplayDesc, pixels: &[[f32; 4]], path: &Path) -> Result<(), String> {
    let [x0, x1, y0, y1] = film.crop_pixels();
    let (w, h) = (x1 - x0, y1 - y0);
    let channels = if display.alpha { 4 } else { 3 };
    let values = quantized(film, pixels, channels);
    let eight = film.quantize.max <= 255 && film.quantize.one != 0;
    let format = match display.format {
        DisplayFormat::Tiff => image::ImageFormat::Tiff,
        DisplayFormat::Png => image::ImageFormat::Png,
    };
    let err = |e: image::ImageError| format!("{}: {e}", path.display());
    let buffer: image::DynamicImage = match (eight, display.alpha) {
        (true, false) => image::RgbImage::from_raw(w, h, values.iter().map(|&v| v as u8).collect()).map(Into::into),
        (true, true) => image::RgbaImage::from_raw(w, h, values.iter().map(|&v| v as u8).collect()).map(Into::into),
        (false, false) => image::ImageBuffer::<image::Rgb<u16>, _>::from_raw(w, h, values).map(Into::into),
        (false, true) => image::ImageBuffer::<image::Rgba<u16>, _>::from_raw(w, h, values).map(Into::into),
    }
    .ok_or_else(|| format!("{}: {w}×{h} pixels but {} values", path.display(), pixels.len()))?;
    buffer.save_with_format(path, format).map_err(err)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::Quantize;

    fn film(kind: FilterKind, width: f32) -> Film {
        Film {
            xres: 8,
            yres: 4,
            pixel_aspect: 1.0,
            crop: [0.0, 1.0, 0.0, 1.0],
            samples: [2, 2],
            filter: PixelFilter { kind, xwidth: width, ywidth: width },
            gain: 1.0,
            gamma: 1.0,
            quantize: Quantize::EIGHT_BIT,
        }
    }

    #[test]
    fn kernels_are_one_at_the_centre_and_zero_outside() {
        for kind in
            [FilterKind::Box, FilterKind::Triangle, FilterKind::CatmullRom, FilterKind::Gaussian, FilterKind::Sinc]
        {
            assert_eq!(kernel(kind, 2.0, 0.0), 1.0, "{kind:?}");
            assert_eq!(kernel(kind, 2.0, 1.01), 0.0, "{kind:?}");
        }
        assert!((kernel(FilterKind::Gaussian, 2.0, 1.0) - (-2.0f32).exp()).abs() < 1e-6);
        assert!((kernel(FilterKind::Triangle, 4.0, 1.0) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn constant_samples_stay_constant_under_every_filter() {
        for kind in
            [FilterKind::Box, FilterKind::Triangle, FilterKind::CatmullRom, FilterKind::Gaussian, FilterKind::Sinc]
        {
            for width in [1.0, 2.0, 3.0, 4.0] {
                let f = film(kind, width);
                let win = SampleWindow::of(&f);
                let (sw, sh) = win.sample_size();
                let samples = vec![[0.25, 0.5, 0.75, 1.0]; (sw * sh) as usize];
                for p in reconstruct(&f, &win, &samples) {
                    for (c, want) in [0.25, 0.5, 0.75, 1.0].iter().enumerate() {
                        assert!((p[c] - want).abs() < 1e-5, "{kind:?} {width}: {p:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn box_of_one_pixel_averages_the_pixels_own_samples() {
        let f = film(FilterKind::Box, 1.0);
        let win = SampleWindow::of(&f);
        assert_eq!((win.x0, win.y0, win.width, win.height), (0, 0, 8, 4));
        let (sw, sh) = win.sample_size();
        let samples: Vec<[f32; 4]> = (0..sw * sh).map(|k| [(k % sw) as f32, 0.0, 0.0, 1.0]).collect();
        let out = reconstruct(&f, &win, &samples);
        // Pixel 3 holds sample columns 6 and 7.
        assert!((out[3][0] - 6.5).abs() < 1e-5, "{:?}", out[3]);
    }

    #[test]
    fn exposure_and_quantize() {
        let mut f = film(FilterKind::Box, 1.0);
        f.quantize.dither = 0.0;
        assert_eq!(quantize(&f, 0.5, 0, 0, 0), 128);
        f.gain = 2.0;
        assert_eq!(quantize(&f, 0.25, 0, 0, 0), 128);
        f.gain = 1.0;
        f.gamma = 2.0;
        assert_eq!(quantize(&f, 0.25, 0, 0, 0), 128);
        f.quantize = Quantize { one: 100, min: 10, max: 90, dither: 0.0 };
        f.gamma = 1.0;
        assert_eq!((quantize(&f, 0.0, 0, 0, 0), quantize(&f, 0.5, 0, 0, 0), quantize(&f, 2.0, 0, 0, 0)), (10, 50, 90));
        // The dither moves a value by at most its amplitude.
        f.quantize = Quantize { one: 255, min: 0, max: 255, dither: 0.5 };
        for x in 0..64 {
            let v = quantize(&f, 0.5, x, 3, 1);
            assert!((127..=128).contains(&v), "{v}");
        }
    }
}
