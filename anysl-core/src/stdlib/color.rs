//! Colour-space conversion (RSL `color "space" (a, b, c)` and `ctransform`).

use super::math::{clamp, fmod};
use crate::float::ShadingFloat;
use crate::vec::Color;

/// The colour spaces RSL names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorSpace {
    /// Linear RGB (the shading space).
    Rgb,
    /// Hue, saturation, value; hue in [0, 1).
    Hsv,
    /// Hue, saturation, lightness; hue in [0, 1).
    Hsl,
    /// CIE XYZ (Rec. 709 primaries, D65 white).
    Xyz,
    /// CIE xyY chromaticity and luminance.
    XyY,
    /// NTSC YIQ.
    Yiq,
}

impl ColorSpace {
    /// Parses an RSL colour-space name (`"rgb"`, `"hsv"`, `"hsl"`, `"xyz"`/`"XYZ"`, `"xyY"`,
    /// `"YIQ"`).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "rgb" | "RGB" => Self::Rgb,
            "hsv" | "HSV" => Self::Hsv,
            "hsl" | "HSL" => Self::Hsl,
            "xyz" | "XYZ" => Self::Xyz,
            "xyY" => Self::XyY,
            "YIQ" | "yiq" => Self::Yiq,
            _ => return None,
        })
    }
}

const RGB_TO_XYZ: [[f64; 3]; 3] = [
    [0.412_456_4, 0.357_576_1, 0.180_437_5],
    [0.212_672_9, 0.715_152_2, 0.072_175_0],
    [0.019_333_9, 0.119_192_0, 0.950_304_1],
];
const XYZ_TO_RGB: [[f64; 3]; 3] = [
    [3.240_454_2, -1.537_138_5, -0.498_531_4],
    [-0.969_266_0, 1.876_010_8, 0.041_556_0],
    [0.055_643_4, -0.204_025_9, 1.057_225_2],
];
const RGB_TO_YIQ: [[f64; 3]; 3] = [[0.299, 0.587, 0.114], [0.596, -0.274, -0.322], [0.211, -0.523, 0.312]];
const YIQ_TO_RGB: [[f64; 3]; 3] = [[1.0, 0.956, 0.621], [1.0, -0.272, -0.647], [1.0, -1.106, 1.703]];

#[inline(always)]
fn mat3<F: ShadingFloat>(m: &[[f64; 3]; 3], c: Color<F>) -> Color<F> {
    let row = |r: &[f64; 3]| c.r * F::c(r[0]) + c.g * F::c(r[1]) + c.b * F::c(r[2]);
    Color::new(row(&m[0]), row(&m[1]), row(&m[2]))
}

/// HSV (hue in [0, 1)) to RGB, branch-free.
#[inline(always)]
#[must_use]
pub fn hsv_to_rgb<F: ShadingFloat>(c: Color<F>) -> Color<F> {
    let (h, s, v) = (c.r, c.g, c.b);
    // k(n) = (n + 6h) mod 6; channel = v - v·s·max(0, min(k, 4 - k, 1))
    let ch = |n: f64| {
        let kk = fmod(F::c(n) + h * F::c(6.0), F::c(6.0));
        let w = clamp(kk.min(F::c(4.0) - kk), F::c(0.0), F::c(1.0));
        v - v * s * w
    };
    Color::new(ch(5.0), ch(3.0), ch(1.0))
}

/// RGB to HSV (hue in [0, 1)), branch-free; grey gives hue 0 and saturation 0.
#[inline(always)]
#[must_use]
pub fn rgb_to_hsv<F: ShadingFloat>(c: Color<F>) -> Color<F> {
    let z = F::c(0.0);
    let mx = c.r.max(c.g).max(c.b);
    let mn = c.r.min(c.g).min(c.b);
    let d = mx - mn;
    let grey = d.le(z);
    let dd = F::select(grey, F::c(1.0), d);
    let hr = fmod((c.g - c.b) / dd, F::c(6.0));
    let hg = (c.b - c.r) / dd + F::c(2.0);
    let hb = (c.r - c.g) / dd + F::c(4.0);
    let h = F::select(mx.eq(c.r), hr, F::select(mx.eq(c.g), hg, hb)) / F::c(6.0);
    let h = F::select(grey, z, h);
    let s = F::select(mx.le(z), z, d / F::select(mx.le(z), F::c(1.0), mx));
    Color::new(h, s, mx)
}

/// HSL (hue in [0, 1)) to RGB.
#[inline(always)]
#[must_use]
pub fn hsl_to_rgb<F: ShadingFloat>(c: Color<F>) -> Color<F> {
    let (h, s, l) = (c.r, c.g, c.b);
    let a = s * l.min(F::c(1.0) - l);
    let ch = |n: f64| {
        let kk = fmod(F::c(n) + h * F::c(12.0), F::c(12.0));
        l - a * clamp((kk - F::c(3.0)).min(F::c(9.0) - kk), F::c(-1.0), F::c(1.0))
    };
    Color::new(ch(0.0), ch(8.0), ch(4.0))
}

/// RGB to HSL (hue in [0, 1)).
#[inline(always)]
#[must_use]
pub fn rgb_to_hsl<F: ShadingFloat>(c: Color<F>) -> Color<F> {
    let hsv = rgb_to_hsv(c);
    let z = F::c(0.0);
    let one = F::c(1.0);
    let l = hsv.b * (one - hsv.g * F::c(0.5));
    let den = l.min(one - l);
    let s = F::select(den.le(z), z, (hsv.b - l) / F::select(den.le(z), one, den));
    Color::new(hsv.r, s, l)
}

/// Converts `c` from space `from` to RGB.
#[inline(always)]
#[must_use]
pub fn to_rgb<F: ShadingFloat>(from: ColorSpace, c: Color<F>) -> Color<F> {
    match from {
        ColorSpace::Rgb => c,
        ColorSpace::Hsv => hsv_to_rgb(c),
        ColorSpace::Hsl => hsl_to_rgb(c),
        ColorSpace::Xyz => mat3(&XYZ_TO_RGB, c),
        ColorSpace::XyY => {
            let z = F::c(0.0);
            let yy = c.g;
            let safe = F::select(yy.eq(z), F::c(1.0), yy);
            let x = F::select(yy.eq(z), z, c.r * c.b / safe);
            let zz = F::select(yy.eq(z), z, (F::c(1.0) - c.r - c.g) * c.b / safe);
            mat3(&XYZ_TO_RGB, Color::new(x, c.b, zz))
        }
        ColorSpace::Yiq => mat3(&YIQ_TO_RGB, c),
    }
}

/// Converts RGB `c` to space `to`.
#[inline(always)]
#[must_use]
pub fn from_rgb<F: ShadingFloat>(to: ColorSpace, c: Color<F>) -> Color<F> {
    match to {
        ColorSpace::Rgb => c,
        ColorSpace::Hsv => rgb_to_hsv(c),
        ColorSpace::Hsl => rgb_to_hsl(c),
        ColorSpace::Xyz => mat3(&RGB_TO_XYZ, c),
        ColorSpace::XyY => {
            let xyz = mat3(&RGB_TO_XYZ, c);
            let sum = xyz.r + xyz.g + xyz.b;
            let z = F::c(0.0);
            let safe = F::select(sum.eq(z), F::c(1.0), sum);
            Color::new(F::select(sum.eq(z), z, xyz.r / safe), F::select(sum.eq(z), z, xyz.g / safe), xyz.g)
        }
        ColorSpace::Yiq => mat3(&RGB_TO_YIQ, c),
    }
}

/// RSL `ctransform(from, to, c)`.
#[inline(always)]
#[must_use]
pub fn ctransform<F: ShadingFloat>(from: ColorSpace, to: ColorSpace, c: Color<F>) -> Color<F> {
    from_rgb(to, to_rgb(from, c))
}
