//! Structure-of-arrays packing: N shading points stored as `Vec3<f32>`/`Color<f32>`/`f32`
//! (array of structures) to and from one `Vec3<F>`/`Color<F>`/`F` whose lanes are the points.

use anysl_core::{Color, ShadingFloat, Vec3};

/// Float types that gather and scatter their lanes from plain `f32` data: every SIMD width
/// and `f32` itself (one lane), so renderers can stay generic over the packet width.
pub trait Lanes: ShadingFloat {
    /// Lane `i` is `f(&src[i])`; a slice shorter than [`ShadingFloat::LANES`] repeats its
    /// last element into the remaining lanes, extra elements are ignored.
    ///
    /// # Panics
    /// If `src` is empty.
    fn gather<T>(src: &[T], f: impl Fn(&T) -> f32) -> Self;
    /// Calls `f(&mut dst[i], lane i)` for `i < min(dst.len(), LANES)` (a short tail
    /// receives only its own lanes).
    fn scatter<T>(self, dst: &mut [T], f: impl FnMut(&mut T, f32));
}

impl Lanes for f32 {
    #[inline(always)]
    fn gather<T>(src: &[T], f: impl Fn(&T) -> f32) -> Self {
        f(src.first().expect("gather from an empty slice"))
    }
    #[inline(always)]
    fn scatter<T>(self, dst: &mut [T], mut f: impl FnMut(&mut T, f32)) {
        if let Some(d) = dst.first_mut() {
            f(d, self);
        }
    }
}

/// Packs up to `LANES` scalars into one value (short tails repeat the last scalar).
///
/// # Panics
/// If `src` is empty.
#[inline]
#[must_use]
pub fn pack<F: Lanes>(src: &[f32]) -> F {
    F::gather(src, |v| *v)
}

/// Unpacks the first `min(dst.len(), LANES)` lanes into `dst`.
#[inline]
pub fn unpack<F: Lanes>(v: F, dst: &mut [f32]) {
    v.scatter(dst, |d, x| *d = x);
}

/// Packs up to `LANES` points into one SoA vector (short tails repeat the last point).
///
/// # Panics
/// If `src` is empty.
#[inline]
#[must_use]
pub fn pack_vec3<F: Lanes>(src: &[Vec3<f32>]) -> Vec3<F> {
    Vec3::new(F::gather(src, |p| p.x), F::gather(src, |p| p.y), F::gather(src, |p| p.z))
}

/// Unpacks the first `min(dst.len(), LANES)` points into `dst`.
#[inline]
pub fn unpack_vec3<F: Lanes>(v: Vec3<F>, dst: &mut [Vec3<f32>]) {
    v.x.scatter(dst, |d, x| d.x = x);
    v.y.scatter(dst, |d, y| d.y = y);
    v.z.scatter(dst, |d, z| d.z = z);
}

/// Packs up to `LANES` colours into one SoA colour (short tails repeat the last colour).
///
/// # Panics
/// If `src` is empty.
#[inline]
#[must_use]
pub fn pack_color<F: Lanes>(src: &[Color<f32>]) -> Color<F> {
    Color::new(F::gather(src, |c| c.r), F::gather(src, |c| c.g), F::gather(src, |c| c.b))
}

/// Unpacks the first `min(dst.len(), LANES)` colours into `dst`.
#[inline]
pub fn unpack_color<F: Lanes>(v: Color<F>, dst: &mut [Color<f32>]) {
    v.r.scatter(dst, |d, r| d.r = r);
    v.g.scatter(dst, |d, g| d.g = g);
    v.b.scatter(dst, |d, b| d.b = b);
}
