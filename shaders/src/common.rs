//! Pieces the classic surfaces share: the view frame, the plastic illumination model and a
//! filtered square wave.

use anysl_core::prelude::*;
use anysl_core::GlobalSet;

/// The globals every classic surface reads: `N` and `I` for the view frame, `P` for the light
/// loops, `Os` for the opacity.
pub(crate) const VIEW_GLOBALS: GlobalSet = GlobalSet::P.union(GlobalSet::N).union(GlobalSet::I).union(GlobalSet::OS);

/// The shading frame every classic surface starts from: `Nf = faceforward(normalize(N), I, N)`
/// and `V = -normalize(I)`.
#[inline(always)]
pub(crate) fn view_frame<F: ShadingFloat>(g: &Globals<F>) -> (Vec3<F>, Vec3<F>) {
    (faceforward_normalize(g.N, g.I), g.I.normalize_signed(F::Mask::splat(true)))
}

/// The coefficients of the plastic illumination model (uniform shader parameters).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Finish {
    /// Ambient coefficient.
    pub ka: f64,
    /// Diffuse coefficient.
    pub kd: f64,
    /// Specular coefficient; 0 skips the specular light loop.
    pub ks: f64,
    /// Blinn roughness (exponent `1/roughness`).
    pub roughness: f64,
    /// Colour of the highlight.
    pub specularcolor: [f64; 3],
}

/// The three light sums of the plastic model, before the coefficients are applied.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LightSums<F> {
    /// `ambient()`.
    pub amb: Color<F>,
    /// `diffuse(Nf)`.
    pub diff: Color<F>,
    /// `specular(Nf, V, roughness)` (zero when `Ks == 0`).
    pub spec: Color<F>,
}

impl Finish {
    /// Evaluates `ambient()`, `diffuse(Nf)` and (when `Ks != 0`) `specular(Nf, V, roughness)`.
    #[inline(always)]
    pub(crate) fn light_sums<F: ShadingFloat, C: ShadingContext<F>>(
        &self,
        ctx: &mut C,
        e: &mut Exec<F>,
        nf: Vec3<F>,
        v: Vec3<F>,
    ) -> LightSums<F> {
        let amb = ambient(ctx, e);
        // `Ks` is uniform: choosing the loop is a branch on a parameter, not on a lane.
        let (diff, spec) = if self.ks != 0.0 {
            diffuse_specular(ctx, e, nf, v, F::c(self.roughness))
        } else {
            (diffuse(ctx, e, nf), Color::zero())
        };
        LightSums { amb, diff, spec }
    }

    /// Only `specular(Nf, V, roughness)` (for surfaces without a matte part).
    #[inline(always)]
    pub(crate) fn light_sums_specular_only<F: ShadingFloat, C: ShadingContext<F>>(
        &self,
        ctx: &mut C,
        e: &mut Exec<F>,
        nf: Vec3<F>,
        v: Vec3<F>,
    ) -> LightSums<F> {
        let spec = specular(ctx, e, nf, v, F::c(self.roughness));
        LightSums { amb: Color::zero(), diff: Color::zero(), spec }
    }

    /// `Ct·(Ka·amb + Kd·diff)`: the matte part.
    #[inline(always)]
    pub(crate) fn matte_part<F: ShadingFloat>(&self, ct: Color<F>, l: &LightSums<F>) -> Color<F> {
        ct * (l.amb * F::c(self.ka) + l.diff * F::c(self.kd))
    }

    /// `specularcolor·Ks·spec`: the highlight.
    #[inline(always)]
    pub(crate) fn specular_part<F: ShadingFloat>(&self, l: &LightSums<F>) -> Color<F> {
        Color::from_array(self.specularcolor) * F::c(self.ks) * l.spec
    }

    /// RSL plastic: `Ct·(Ka·ambient() + Kd·diffuse(Nf)) + specularcolor·Ks·specular(Nf, V,
    /// roughness)` (not yet multiplied by `Os`).
    #[inline(always)]
    pub(crate) fn plastic<F: ShadingFloat, C: ShadingContext<F>>(
        &self,
        ctx: &mut C,
        e: &mut Exec<F>,
        nf: Vec3<F>,
        v: Vec3<F>,
        ct: Color<F>,
    ) -> Color<F> {
        let l = self.light_sums(ctx, e, nf, v);
        self.matte_part(ct, &l) + self.specular_part(&l)
    }
}

/// A square wave of period 1 — 0 on `[0, ½)`, 1 on `[½, 1)` — box-filtered with `filterstep`
/// over the pixel footprint of `x`. Each of the two edges of a period is filtered by the
/// `filterstep` nearer to it; without derivatives it is exactly `step(½, mod(x, 1))`, which
/// point types without derivatives compute directly ([`unfiltered_square`]).
#[inline(always)]
pub(crate) fn filtered_square<F: ShadingFloat>(x: F) -> F {
    if !F::HAS_DERIVS && !<F::Mask as Mask>::THREE_VALUED {
        return unfiltered_square(x);
    }
    footprint_square(x)
}

/// [`filtered_square`] without a footprint: 1 where `mod(x, 1) ≥ ½`, else 0 (NaN gives 0).
/// Equal to [`footprint_square`] of a value without derivatives: both `filterstep`s there are
/// `step`, and either branch of its select is 1 exactly where `mod(x, 1) ≥ ½` (the falling
/// edge's `1 - step(0, mod(x, 1) - 1)` too).
#[inline(always)]
pub(crate) fn unfiltered_square<F: ShadingFloat>(x: F) -> F {
    F::select(fmod(x, F::c(1.0)).ge(F::c(0.5)), F::c(1.0), F::c(0.0))
}

/// The general form of [`filtered_square`] (dual numbers, intervals).
#[inline(always)]
pub(crate) fn footprint_square<F: ShadingFloat>(x: F) -> F {
    let half = F::c(0.5);
    let xm = fmod(x, F::c(1.0));
    let near_half = (xm - half).abs().lt(F::c(0.25));
    // The falling edge sits at the integers: measure from there, negative just below.
    let upper = xm.ge(half);
    let from_int = F::select(upper, xm - F::c(1.0), xm);
    let rising = filterstep(half, xm);
    let falling = F::c(1.0) - filterstep(F::c(0.0), from_int);
    F::select(near_half, rising, falling)
}

#[cfg(test)]
mod tests {
    use super::*;
    use anysl_simd::F32x8;

    /// The shortcut equals the general form bit for bit, at and around every edge of the
    /// period, for negative, huge, subnormal, infinite and NaN arguments.
    #[test]
    fn unfiltered_square_is_the_footprint_form_without_derivatives() {
        let mut xs: Vec<f32> = vec![
            0.0,
            -0.0,
            1.0e-45,
            -1.0e-45,
            1.0e-38,
            0.25,
            0.5,
            0.75,
            1.0,
            -0.5,
            -0.25,
            -1.0,
            3.5,
            1.0e7,
            1.0e7 + 1.0,
            -1.0e7,
            1.0e30,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        for e in [0.0f32, 0.25, 0.5, 0.75, 1.0, 2.5, -3.5] {
            xs.extend([e.next_down(), e.next_up(), e + 1.0e-7, e - 1.0e-7]);
        }
        for k in 0..2000 {
            xs.push((k as f32 - 1000.0) * 0.0137);
        }
        for &x in &xs {
            let (a, b) = (unfiltered_square(x), footprint_square(x));
            assert_eq!(a.to_bits(), b.to_bits(), "f32 x = {x:e}: {a} against {b}");
        }
        for c in xs.chunks(8) {
            let x = F32x8::from_lanes(&(0..8).map(|l| f64::from(c[l % c.len()])).collect::<Vec<_>>());
            let (a, b) = (unfiltered_square(x), footprint_square(x));
            for l in 0..8 {
                assert_eq!((a.lane(l) as f32).to_bits(), (b.lane(l) as f32).to_bits(), "F32x8 x = {:e}", x.lane(l));
            }
        }
    }
}
