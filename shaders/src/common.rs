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
/// `filterstep` nearer to it; without derivatives it is exactly `step(½, mod(x, 1))`.
#[inline(always)]
pub(crate) fn filtered_square<F: ShadingFloat>(x: F) -> F {
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
