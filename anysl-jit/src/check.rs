//! The cross-check's comparison of two shadings (`anysl jit check` and its test): outputs
//! more than [`MAX_ULPS`] apart *and* more than [`ABS_FLOOR`]`· max(1, |x|)` apart are
//! mismatches (values near zero after cancellation, and the SIMD polynomial
//! transcendentals, differ in ulps without differing in value).

use anysl_core::points::ShadeOut;

/// Ulps two outputs may differ by.
pub const MAX_ULPS: u64 = 4;
/// The absolute floor, relative to `max(1, |x|)`, under which more ulps are still a match.
pub const ABS_FLOOR: f64 = 2e-6;

/// Distance in units in the last place between two f32s (NaN against anything: infinite).
#[must_use]
pub fn ulps(a: f32, b: f32) -> u64 {
    if a == b {
        return 0;
    }
    if a.is_nan() || b.is_nan() {
        return u64::MAX;
    }
    let key = |x: f32| {
        let i = x.to_bits() as i32;
        i64::from(if i < 0 { i32::MIN - i } else { i })
    };
    (key(a) - key(b)).unsigned_abs()
}

/// How two shadings of the same points compare.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Comparison {
    /// Max ulps over all outputs.
    pub max_ulps: u64,
    /// Max finite absolute difference.
    pub max_abs: f64,
    /// Outputs beyond the bound.
    pub mismatches: usize,
}

/// Compares every output (Ci and Oi) of `a` and `b`.
#[must_use]
pub fn compare(a: &ShadeOut<f32>, b: &ShadeOut<f32>) -> Comparison {
    let mut r = Comparison::default();
    for (ca, cb) in a.channels.iter().zip(&b.channels) {
        for (x, y) in ca.iter().zip(cb) {
            let u = ulps(*x, *y);
            let d = f64::from((x - y).abs());
            r.max_ulps = r.max_ulps.max(u);
            if d.is_finite() {
                r.max_abs = r.max_abs.max(d);
            }
            let scale = f64::from(x.abs().max(y.abs())).max(1.0);
            if u > MAX_ULPS && !(d <= ABS_FLOOR * scale) {
                r.mismatches += 1;
            }
        }
    }
    r
}

/// A displacement, volume or imager shader run as a surface shader, so that the point-set
/// loops (`anysl_core::points::shade_points`) compare back ends on it as on a surface:
/// - displacement: `Ci` = the displaced `P`, `Oi` = its `N`;
/// - volume: on the segment the point's globals give (`P`, `I`, `E`), with
///   `Ci` = (`s`, `t`, `u`) and `Oi` = (`v`, `v`, `v`) arriving; its `Ci`, `Oi`;
/// - imager: the pixel at `P` with that `Ci`, `Oi` and `alpha` = `v`; its `Ci`, and
///   `Oi` with `alpha` in the place of its red component;
/// - a surface: itself.
#[derive(Clone, Debug)]
pub struct StageAsSurface<S> {
    /// The shader.
    pub shader: S,
    /// Which of its entries runs.
    pub kind: anysl_rsl::ir::ShaderKind,
}

impl<S: anysl_core::Shader> anysl_core::Shader for StageAsSurface<S> {
    fn meta(&self) -> anysl_core::ShaderMeta {
        self.shader.meta()
    }
    fn param(&self, name: &str) -> Option<anysl_core::ParamValue> {
        self.shader.param(name)
    }
    fn set_param(&mut self, name: &str, value: &anysl_core::ParamValue) -> Result<(), anysl_core::ParamError> {
        self.shader.set_param(name, value)
    }
}

impl<S> anysl_core::SurfaceShader for StageAsSurface<S>
where
    S: anysl_core::SurfaceShader + anysl_core::DisplacementShader + anysl_core::VolumeShader + anysl_core::ImagerShader,
{
    fn shade<F: anysl_core::ShadingFloat, C: anysl_core::ShadingContext<F>>(
        &self,
        ctx: &mut C,
        e: &mut anysl_core::Exec<F>,
    ) -> anysl_core::SurfaceOutput<F> {
        use anysl_core::{Color, SurfaceOutput};
        use anysl_rsl::ir::ShaderKind;
        let g = *ctx.globals();
        let (ci, oi) = (Color::new(g.s, g.t, g.u), Color::new(g.v, g.v, g.v));
        match self.kind {
            ShaderKind::Displacement => {
                let (p, n) = self.shader.displace(ctx, e);
                SurfaceOutput { Ci: Color::new(p.x, p.y, p.z), Oi: Color::new(n.x, n.y, n.z) }
            }
            ShaderKind::Volume => self.shader.volume(ctx, e, SurfaceOutput { Ci: ci, Oi: oi }),
            ShaderKind::Imager => {
                let px = self.shader.image(e, anysl_core::ImagerPixel { P: g.P, Ci: ci, Oi: oi, alpha: g.v });
                SurfaceOutput { Ci: px.Ci, Oi: Color::new(px.alpha, px.Oi.g, px.Oi.b) }
            }
            ShaderKind::Surface | ShaderKind::Light => self.shader.shade(ctx, e),
        }
    }
}
