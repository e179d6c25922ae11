//! A surface of a RIB scene: its surface shader and, when the attributes name one, the
//! displacement shader run before it at every shaded point.
//!
//! A ray tracer that does not re-tessellate displaces by **bump mapping**: the displacement
//! shader runs on the true hit point; the surface shader then sees the normal it computed (`N`
//! as the shader sets it, or — when it moves `P` and leaves `N` — the normal of the moved
//! surface, from the dual-number screen derivatives of the moved `P`) and the undisplaced `P`, so
//! shadow and secondary rays start on the geometry that was traced.

use anysl_core::{
    Color, DisplacementShader, Exec, GlobalSet, Globals, LightData, LightQuery, ParamError, ParamValue, Shader,
    ShaderMeta, ShadingContext, ShadingFloat, Spaces, SurfaceOutput, SurfaceShader, Vec3,
};
use anysl_rsl::back::interp::InterpShader;

/// A surface shader with an optional displacement shader (run by the interpreter).
#[derive(Clone, Debug)]
pub struct SceneSurface<S> {
    /// The surface shader.
    pub surface: S,
    /// The displacement shader, if the attributes name one.
    pub displacement: Option<InterpShader>,
}

impl<S: Shader> Shader for SceneSurface<S> {
    fn meta(&self) -> ShaderMeta {
        let mut m = self.surface.meta();
        // A displacement's normal comes from the derivatives of the moved P.
        m.uses_derivatives |= self.displacement.is_some();
        m
    }
    fn param(&self, name: &str) -> Option<ParamValue> {
        self.surface.param(name)
    }
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
        self.surface.set_param(name, value)
    }
}

impl<S: SurfaceShader> SurfaceShader for SceneSurface<S> {
    fn globals_read(&self) -> GlobalSet {
        match &self.displacement {
            Some(d) => self.surface.globals_read() | d.globals_read(),
            None => self.surface.globals_read(),
        }
    }

    #[inline]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let Some(d) = &self.displacement else {
            return self.surface.shade(ctx, e);
        };
        let g = *ctx.globals();
        let (p, n) = d.displace(ctx, e);
        let moved = (p - g.P).dot(p - g.P).gt(F::c(0.0));
        let kept_n = (n - g.N).dot(n - g.N).le(F::c(0.0));
        // P moved and N left as it was: the normal of the moved surface (its screen
        // derivatives' cross product, `calculatenormal` without the parametrization, which a
        // polygon may not have), on N's side.
        let mut bent =
            if F::HAS_DERIVS { p.map(|c| c.dx().value()).cross(p.map(|c| c.dy().value())) } else { Vec3::zero() };
        bent = Vec3::select(bent.dot(g.N).lt(F::c(0.0)), -bent, bent);
        let usable = bent.dot(bent).gt(F::c(0.0));
        let n = Vec3::select(moved & kept_n & usable, bent.normalize(), n);
        let mut bumped = Bumped { inner: ctx, g: Globals { N: n, ..g } };
        self.surface.shade(&mut bumped, e)
    }
}

/// The renderer's context with the displaced normal in its globals.
struct Bumped<'c, F: ShadingFloat, C> {
    inner: &'c mut C,
    g: Globals<F>,
}

impl<F: ShadingFloat, C: ShadingContext<F>> ShadingContext<F> for Bumped<'_, F, C> {
    fn globals(&self) -> &Globals<F> {
        &self.g
    }
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        e: &mut Exec<F>,
        q: LightQuery<'_, F>,
        body: B,
    ) {
        self.inner.illuminance(e, q, body);
    }
    fn ambient(&mut self, e: &Exec<F>) -> Color<F> {
        self.inner.ambient(e)
    }
    fn trace(&mut self, e: &Exec<F>, p: Vec3<F>, dir: Vec3<F>) -> Color<F> {
        self.inner.trace(e, p, dir)
    }
    fn lights_as_data(&self) -> Option<&[LightData]> {
        self.inner.lights_as_data()
    }
    fn spaces(&self) -> &Spaces {
        self.inner.spaces()
    }
}
