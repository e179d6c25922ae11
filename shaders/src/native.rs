//! Hand-written SIMD shaders on `wide::f32x8` — the paper's "Native" column.
//!
//! [`plastic_x8`] and [`checker_x8`] compute what the generic [`Plastic`] and [`Checker`]
//! compute for eight shading points with point lights and an ambient light through
//! [`anysl_core::PointContext`] (the same formulas in the same order, within 1e-5), but the
//! way a careful engineer writes a SIMD kernel by hand: uniforms splatted once, one fused
//! light loop that normalizes `L` once for diffuse and specular, the `faceforward` sign folded
//! into the normalization, no execution masks (nothing here diverges) and no cone tests
//! (`max(N·L, 0)` and the `N·L > 0` select already give the hemisphere). Comparing them with
//! the generic shaders instantiated for `anysl_simd::F32x8` measures what the abstraction
//! costs.
//!
//! Inputs are assumed well formed: nonzero `N` and `I`, lights not at a shading point.

use crate::dispatch::{Light, Surface};
use crate::lights::PointLight;
use crate::surfaces::{Checker, Plastic};
use anysl_core::{Color, Globals, ShadingFloat, SurfaceOutput};
use anysl_simd::F32x8;
use wide::f32x8;

/// Three lanes-of-eight components: a point, vector, normal or colour for 8 shading points.
pub type V3x8 = [f32x8; 3];

/// The inputs of eight shading points (the RSL globals the native shaders read).
#[derive(Clone, Copy, Debug)]
pub struct PointsX8 {
    /// Surface positions `P`.
    pub p: V3x8,
    /// Shading normals `N`.
    pub n: V3x8,
    /// Incident directions `I` (eye to `P`, any length).
    pub i: V3x8,
    /// Texture coordinate `s`.
    pub s: f32x8,
    /// Texture coordinate `t`.
    pub t: f32x8,
    /// Surface colours `Cs`.
    pub cs: V3x8,
    /// Surface opacities `Os`.
    pub os: V3x8,
}

impl PointsX8 {
    /// The inputs of a packet of eight points from its globals.
    #[inline(always)]
    #[must_use]
    pub fn from_globals(g: &Globals<F32x8>) -> Self {
        let v3 = |x: F32x8, y: F32x8, z: F32x8| [x.0, y.0, z.0];
        Self {
            p: v3(g.P.x, g.P.y, g.P.z),
            n: v3(g.N.x, g.N.y, g.N.z),
            i: v3(g.I.x, g.I.y, g.I.z),
            s: g.s.0,
            t: g.t.0,
            cs: v3(g.Cs.r, g.Cs.g, g.Cs.b),
            os: v3(g.Os.r, g.Os.g, g.Os.b),
        }
    }
}

/// The hand-written kernel of `surface` on a packet of eight points — [`plastic_x8`] for
/// phong (plastic), [`checker_x8`] for checker — as `Ci`, `Oi`; `None` for every other shader.
#[inline]
#[must_use]
pub fn shade_x8(
    surface: &Surface,
    lights: &[NativePointLight],
    ambient: [f32; 3],
    g: &Globals<F32x8>,
) -> Option<SurfaceOutput<F32x8>> {
    let x = PointsX8::from_globals(g);
    let (ci, oi) = match surface {
        Surface::Plastic(p) => plastic_x8(p, lights, ambient, &x),
        Surface::Checker(c) => checker_x8(c, lights, ambient, &x),
        _ => return None,
    };
    let color = |c: V3x8| Color::new(F32x8(c[0]), F32x8(c[1]), F32x8(c[2]));
    Some(SurfaceOutput { Ci: color(ci), Oi: color(oi) })
}

/// A point light for the native kernels: [`PointLight`] with `intensity·lightcolor` folded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NativePointLight {
    /// Position.
    pub from: [f32; 3],
    /// `intensity·lightcolor`.
    pub color: [f32; 3],
    /// Falls off as `1/(L·L)` (`falloff = 2`); otherwise no falloff (`falloff = 0`).
    pub inverse_square: bool,
}

impl NativePointLight {
    /// The native form of a point light; `None` for a falloff other than 0 or 2.
    #[must_use]
    pub fn from_light(l: &PointLight) -> Option<Self> {
        let inverse_square = if l.falloff == 2.0 {
            true
        } else if l.falloff == 0.0 {
            false
        } else {
            return None;
        };
        Some(Self {
            from: l.from.map(|c| c as f32),
            color: l.lightcolor.map(|c| (c * l.intensity) as f32),
            inverse_square,
        })
    }
}

/// Splits a light list into native point lights and the summed ambient colour; `None` if it
/// holds a light the native kernels do not implement (distant, spot, or an unusual falloff).
#[must_use]
pub fn native_lights(lights: &[Light]) -> Option<(Vec<NativePointLight>, [f32; 3])> {
    let mut points = Vec::new();
    let mut ambient = [0.0f32; 3];
    for l in lights {
        match l {
            Light::Point(p) => points.push(NativePointLight::from_light(p)?),
            Light::Ambient(a) => {
                for (c, lc) in ambient.iter_mut().zip(a.lightcolor) {
                    *c += (lc * a.intensity) as f32;
                }
            }
            Light::Distant(_) | Light::Spot(_) => return None,
        }
    }
    Some((points, ambient))
}

/// `x^y` lane by lane, with the same polynomial the generic shaders get from
/// `anysl_simd::F32x8` (so native and generic highlights agree to the last bits).
#[inline(always)]
fn pow8(x: f32x8, y: f32x8) -> f32x8 {
    ShadingFloat::pow(anysl_simd::F32x8(x), anysl_simd::F32x8(y)).0
}

#[inline(always)]
fn dot(a: &V3x8, b: &V3x8) -> f32x8 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn splat3(c: [f64; 3]) -> V3x8 {
    c.map(|v| f32x8::splat(v as f32))
}

/// The plastic illumination of eight points with surface colour `ct`:
/// `Os·(Ct·(Ka·ambient + Kd·diffuse(Nf)) + specularcolor·Ks·specular(Nf, V, roughness))`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn plastic_light_x8(
    ka: f64,
    kd: f64,
    ks: f64,
    roughness: f64,
    specularcolor: [f64; 3],
    lights: &[NativePointLight],
    ambient: [f32; 3],
    x: &PointsX8,
    ct: &V3x8,
) -> V3x8 {
    let zero = f32x8::ZERO;
    let one = f32x8::ONE;
    // Nf = faceforward(normalize(N), I, N): the sign folds into the normalization factor.
    let inv_n = one / dot(&x.n, &x.n).sqrt();
    let flip = dot(&x.i, &x.n).simd_gt(zero);
    let nscale = flip.select(-inv_n, inv_n);
    let nf = x.n.map(|c| c * nscale);
    // V = -normalize(I).
    let vscale = -(one / dot(&x.i, &x.i).sqrt());
    let v = x.i.map(|c| c * vscale);
    let exponent = f32x8::splat((1.0 / roughness) as f32);

    let mut diff = [zero; 3];
    let mut spec = [zero; 3];
    for light in lights {
        let to_light: V3x8 = core::array::from_fn(|k| f32x8::splat(light.from[k]) - x.p[k]);
        let l2 = dot(&to_light, &to_light);
        let lu = to_light.map(|c| c * (one / l2.sqrt()));
        let falloff = if light.inverse_square { one / l2 } else { one };
        let ndl = dot(&nf, &lu);
        let h: V3x8 = core::array::from_fn(|k| lu[k] + v[k]);
        let hscale = one / dot(&h, &h).sqrt();
        let ndh = (dot(&nf, &h) * hscale).max(zero);
        let lit = ndl.simd_gt(zero);
        let s = lit.select(pow8(ndh, exponent), zero);
        let wd = ndl.max(zero) * falloff;
        let ws = s * falloff;
        for k in 0..3 {
            let c = f32x8::splat(light.color[k]);
            diff[k] += c * wd;
            spec[k] += c * ws;
        }
    }
    let ka_amb = ambient.map(|a| f32x8::splat(a * ka as f32));
    let kd = f32x8::splat(kd as f32);
    let sc = specularcolor.map(|c| f32x8::splat((c * ks) as f32));
    core::array::from_fn(|k| x.os[k] * (ct[k] * (ka_amb[k] + diff[k] * kd) + sc[k] * spec[k]))
}

/// Native plastic for eight points: returns `(Ci, Oi)`; the same values as the generic
/// [`Plastic`] with `lights` and an ambient light of colour `ambient`.
#[inline]
#[must_use]
pub fn plastic_x8(params: &Plastic, lights: &[NativePointLight], ambient: [f32; 3], x: &PointsX8) -> (V3x8, V3x8) {
    let ci = plastic_light_x8(
        params.Ka,
        params.Kd,
        params.Ks,
        params.roughness,
        params.specularcolor,
        lights,
        ambient,
        x,
        &x.cs,
    );
    (ci, x.os)
}

/// `mod(x, 1) >= 0.5` — the unfiltered check parity of one coordinate.
#[inline(always)]
fn upper_half(x: f32x8) -> f32x8 {
    let one = f32x8::ONE;
    let m = x - x.floor();
    // `x - floor(x)` rounds up to 1 for tiny negative x; fold it back as `mod` does.
    let m = m.simd_ge(one).select(m - one, m);
    m.simd_ge(f32x8::splat(0.5))
}

/// Native checker for eight points (without derivatives, as the generic [`Checker`]
/// instantiated for `F32x8` computes it: `filterstep` is `step`): returns `(Ci, Oi)`.
#[inline]
#[must_use]
pub fn checker_x8(params: &Checker, lights: &[NativePointLight], ambient: [f32; 3], x: &PointsX8) -> (V3x8, V3x8) {
    let f = f32x8::splat(params.frequency as f32);
    let black = upper_half(x.s * f) ^ upper_half(x.t * f);
    let (b, w) = (splat3(params.blackcolor), splat3(params.whitecolor));
    let ct: V3x8 = core::array::from_fn(|k| black.select(b[k], w[k]));
    let ci = plastic_light_x8(
        params.Ka,
        params.Kd,
        params.Ks,
        params.roughness,
        params.specularcolor,
        lights,
        ambient,
        x,
        &ct,
    );
    (ci, x.os)
}

#[inline(always)]
fn load8(set: &anysl_core::points::PointSet, k: usize, i: usize) -> f32x8 {
    let a: [f32; 8] = set.field(k)[i..i + 8].try_into().expect("8 lanes");
    f32x8::from(a)
}

/// A shading loop over a point set: the signature of the kernel benchmark's runners.
pub type PointSetRunner =
    fn(&crate::dispatch::Surface, &[Light], &anysl_core::points::PointSet, &mut anysl_core::points::ShadeOut<f32>);

/// The hand-written kernel of `surface` (plastic or checker; `None` for any other shader) over
/// a point set, 8 points at a time, with the same signature as the generic instantiations'
/// runners — the "native" rows of the kernel benchmark.
pub fn point_set_runner(surface: &crate::dispatch::Surface) -> Option<PointSetRunner> {
    use crate::dispatch::Surface;
    match surface {
        Surface::Plastic(_) | Surface::Checker(_) => Some(shade_point_set),
        _ => None,
    }
}

/// [`point_set_runner`]'s kernel loop. Panics if `surface` has no native kernel or `lights`
/// are not all point and ambient lights.
#[inline(never)]
pub fn shade_point_set(
    surface: &crate::dispatch::Surface,
    lights: &[Light],
    set: &anysl_core::points::PointSet,
    out: &mut anysl_core::points::ShadeOut<f32>,
) {
    use crate::dispatch::Surface;
    use anysl_core::points::field;
    let (points, ambient) = native_lights(lights).expect("native kernels need point and ambient lights");
    let one = [f32x8::splat(1.0); 3];
    let load3 = |k, i| [load8(set, k, i), load8(set, k + 1, i), load8(set, k + 2, i)];
    let mut i = 0;
    while i + 8 <= set.len() {
        let x = PointsX8 {
            p: load3(field::P, i),
            n: load3(field::N, i),
            i: load3(field::I, i),
            s: load8(set, field::S, i),
            t: load8(set, field::T, i),
            cs: one,
            os: one,
        };
        let (ci, oi) = match surface {
            Surface::Plastic(p) => plastic_x8(p, &points, ambient, &x),
            Surface::Checker(c) => checker_x8(c, &points, ambient, &x),
            _ => panic!("native kernels exist for plastic and checker only"),
        };
        for (ch, v) in ci.iter().chain(oi.iter()).enumerate() {
            out.channels[ch][i..i + 8].copy_from_slice(&v.to_array());
        }
        i += 8;
    }
}
