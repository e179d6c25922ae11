//! [`Image`]: linear RGB f32 pixels, PNG output (sRGB-encoded) and the comparisons the tests
//! and benchmarks use (PSNR, maximum absolute difference, mean).

use std::path::Path;

/// A linear-RGB image, row-major from the top-left pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` pixels, row by row from the top.
    pub data: Vec<[f32; 3]>,
}

impl Image {
    /// A black image.
    #[must_use]
    pub fn new(width: u32, height: u32) -> Self {
        Self { width, height, data: vec![[0.0; 3]; width as usize * height as usize] }
    }

    /// The pixel in column `x`, row `y` (row 0 at the top).
    ///
    /// # Panics
    /// When `(x, y)` lies outside the image.
    #[inline]
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> [f32; 3] {
        assert!(x < self.width && y < self.height, "pixel ({x}, {y}) outside {}×{}", self.width, self.height);
        self.data[y as usize * self.width as usize + x as usize]
    }

    /// The 8-bit sRGB encoding of the pixels (clamped to [0, 1] first; NaN becomes 0).
    #[must_use]
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.data.iter().flat_map(|p| p.map(encode_srgb8)).collect()
    }

    /// Writes an 8-bit sRGB PNG.
    ///
    /// # Errors
    /// When the file cannot be written; the message names the path.
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), String> {
        write_rgb8(path.as_ref(), &self.to_srgb8(), self.width, self.height)
    }

    /// Peak signal-to-noise ratio in dB against `other`, on linear values clamped to [0, 1]
    /// with peak 1.0; `f64::INFINITY` for identical images.
    ///
    /// # Panics
    /// When the sizes differ.
    #[must_use]
    pub fn psnr(&self, other: &Image) -> f64 {
        self.assert_same_size(other);
        let n = (self.data.len() * 3).max(1) as f64;
        let sse: f64 = self
            .data
            .iter()
            .zip(&other.data)
            .flat_map(|(a, b)| (0..3).map(move |c| (clamp01(a[c]) - clamp01(b[c])) as f64))
            .map(|d| d * d)
            .sum();
        let mse = sse / n;
        if mse == 0.0 {
            f64::INFINITY
        } else {
            10.0 * (1.0 / mse).log10()
        }
    }

    /// The largest per-channel absolute difference to `other` (unclamped; NaN counts as
    /// infinite).
    ///
    /// # Panics
    /// When the sizes differ.
    #[must_use]
    pub fn max_abs_diff(&self, other: &Image) -> f32 {
        self.assert_same_size(other);
        self.data
            .iter()
            .zip(&other.data)
            .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs()))
            .map(|d| if d.is_nan() { f32::INFINITY } else { d })
            .fold(0.0, f32::max)
    }

    /// The mean of each channel.
    #[must_use]
    pub fn mean(&self) -> [f32; 3] {
        let n = self.data.len().max(1) as f64;
        let mut sum = [0.0f64; 3];
        for p in &self.data {
            for c in 0..3 {
                sum[c] += p[c] as f64;
            }
        }
        sum.map(|s| (s / n) as f32)
    }

    fn assert_same_size(&self, other: &Image) {
        assert!(
            self.width == other.width && self.height == other.height,
            "images differ in size: {}×{} vs {}×{}",
            self.width,
            self.height,
            other.width,
            other.height
        );
    }
}

#[inline]
fn clamp01(v: f32) -> f32 {
    if v.is_nan() {
        0.0
    } else {
        v.clamp(0.0, 1.0)
    }
}

/// sRGB transfer function applied to a clamped linear value, rounded to 8 bits.
#[inline]
fn encode_srgb8(v: f32) -> u8 {
    let v = clamp01(v);
    let s = if v <= 0.003_130_8 { 12.92 * v } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0 + 0.5) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_endpoints_and_midpoint() {
        assert_eq!(encode_srgb8(0.0), 0);
        assert_eq!(encode_srgb8(1.0), 255);
        assert_eq!(encode_srgb8(2.0), 255);
        assert_eq!(encode_srgb8(f32::NAN), 0);
        // Linear 0.2140 is sRGB 0.5 (127.5 of 255); 0.2159 is sRGB 0.502.
        assert_eq!(encode_srgb8(0.2159), 128);
        assert_eq!(encode_srgb8(0.0031308 * 0.5), 5);
    }

    #[test]
    fn psnr_of_known_error() {
        let a = Image::new(4, 4);
        let mut b = Image::new(4, 4);
        assert_eq!(a.psnr(&b), f64::INFINITY);
        for p in &mut b.data {
            *p = [0.1; 3];
        }
        // MSE = 0.01 -> 20 dB.
        assert!((a.psnr(&b) - 20.0).abs() < 1e-4);
        assert!((a.max_abs_diff(&b) - 0.1).abs() < 1e-7);
        assert!((b.mean()[1] - 0.1).abs() < 1e-7);
    }
}

/// Writes 8-bit RGB pixels (row-major, `3 * width * height` bytes) to `path`, in the format its
/// extension names (PNG for `.png`).
///
/// Not generic, and never inlined: the `image` crate's encoders are compiled once, in this
/// crate, instead of in every crate that writes a picture (test binaries, the CLI).
///
/// # Errors
/// When the file cannot be written; the message names the path.
#[inline(never)]
pub fn write_rgb8(path: &Path, rgb: &[u8], width: u32, height: u32) -> Result<(), String> {
    image::save_buffer(path, rgb, width, height, image::ExtendedColorType::Rgb8)
        .map_err(|e| format!("{}: cannot write the image: {e}", path.display()))
}

/// Reads an image file as 8-bit RGB: `(width, height, pixels)` with the pixels row-major,
/// 3 bytes each. Not generic, and never inlined (the decoders are compiled once, here).
///
/// # Errors
/// When the file cannot be read or decoded; the message names the path.
#[inline(never)]
pub fn read_rgb8(path: &Path) -> Result<(u32, u32, Vec<u8>), String> {
    let img = image::open(path).map_err(|e| format!("{}: {e}", path.display()))?.to_rgb8();
    let (w, h) = img.dimensions();
    Ok((w, h, img.into_raw()))
}
