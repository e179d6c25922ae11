//! A surface of a RIB scene: its surface shader and, when the attributes name them, the
//! displacement shader run before it at every shaded point (from the surfaces' back end: the
//! JIT's compiled code, or the interpreter) and the volume shaders (of the same back end) run
//! after it on the ray segment that reached the point.
//!
//! A ray tracer that does not re-tessellate displaces by **bump mapping**: the displacement
//! shader runs on the true hit point; the surface shader then sees the normal it computed (`N`
//! as the shader sets it, or — when it moves `P` and leaves `N` — the normal of the moved
//! surface, from the dual-number screen derivatives of the moved `P`) and the undisplaced `P`, so
//! shadow and secondary rays start on the geometry that was traced.
//!
//! **Volumes** act on the segment from the ray's origin `E` to the hit `P` (`I = P − E`): the
//! surface's `Ci`/`Oi` go in, the attenuated ones come out, and the renderer composites them as
//! it would the surface's own. On a camera ray (and its continuation through transparent
//! surfaces, each segment from the previous hit) that is the `Atmosphere`; on a ray that
//! `trace` cast, the `Interior` when the ray reaches the surface from its inside (`N·I > 0`,
//! the back of a closed object whose normals point out), else the `Exterior`, else the
//! `Atmosphere`. Rays that hit nothing get no volume (as in RenderMan, where volume shaders run
//! only where a surface is shaded); neither do shadow rays. A context that is no ray's (the
//! path tracer's material probe, [`ShadingContext::ray_depth`] `None`) runs no volume.

use anysl_core::{
    Color, DisplacementShader, Exec, GlobalSet, Globals, LightData, LightQuery, LightRecord, Mask, ParamError,
    ParamValue, Shader, ShaderMeta, ShadingContext, ShadingFloat, Spaces, SurfaceOutput, SurfaceShader, Vec3,
    VolumeShader,
};

/// A surface shader with an optional displacement shader and volume shaders, all of one back
/// end.
#[derive(Clone, Debug)]
pub struct SceneSurface<S> {
    /// The surface shader.
    pub surface: S,
    /// The displacement shader, if the attributes name one.
    pub displacement: Option<S>,
    /// The volume shaders the attributes name.
    pub volumes: Volumes<S>,
}

/// The volume shaders of a surface (see the module docs for which runs where).
#[derive(Clone, Debug)]
pub struct Volumes<S> {
    /// `Atmosphere`.
    pub atmosphere: Option<S>,
    /// `Interior`.
    pub interior: Option<S>,
    /// `Exterior`.
    pub exterior: Option<S>,
}

impl<S> Default for Volumes<S> {
    fn default() -> Self {
        Self { atmosphere: None, interior: None, exterior: None }
    }
}

impl<S: SurfaceShader + VolumeShader> Volumes<S> {
    fn all(&self) -> impl Iterator<Item = &S> {
        [&self.atmosphere, &self.interior, &self.exterior].into_iter().flatten()
    }

    /// The globals the volume shaders read, and those the choice between them reads.
    fn globals_read(&self) -> GlobalSet {
        let mut read = GlobalSet::NONE;
        for v in self.all() {
            read |= v.globals_read() | GlobalSet::P | GlobalSet::I | GlobalSet::E;
        }
        if self.interior.is_some() || self.exterior.is_some() {
            read |= GlobalSet::N;
        }
        read
    }

    /// `out` after the volume of the segment that reached the points of `ctx`.
    fn apply<F: ShadingFloat, C: ShadingContext<F>>(
        &self,
        ctx: &mut C,
        e: &mut Exec<F>,
        out: SurfaceOutput<F>,
    ) -> SurfaceOutput<F> {
        let Some(depth) = ctx.ray_depth() else {
            return out;
        };
        if depth == 0 || (self.interior.is_none() && self.exterior.is_none()) {
            return match &self.atmosphere {
                Some(a) => a.volume(ctx, e, out),
                None => out,
            };
        }
        let g = ctx.globals();
        let inside = g.N.dot(g.I).gt(F::c(0.0));
        let outside_volume = self.exterior.as_ref().or(self.atmosphere.as_ref());
        let mut result = out;
        for (volume, lanes) in [(self.interior.as_ref(), inside), (outside_volume, !inside)] {
            let (Some(volume), mask) = (volume, e.mask() & lanes) else {
                continue;
            };
            if mask.none() {
                continue;
            }
            let v = volume.volume(ctx, &mut Exec::with_mask(mask), out);
            result =
                SurfaceOutput { Ci: Color::select(mask, v.Ci, result.Ci), Oi: Color::select(mask, v.Oi, result.Oi) };
        }
        result
    }
}

impl<S: SurfaceShader + VolumeShader> Shader for SceneSurface<S> {
    fn meta(&self) -> ShaderMeta {
        let mut m = self.surface.meta();
        // A displacement's normal comes from the derivatives of the moved P.
        m.uses_derivatives |= self.displacement.is_some();
        m.uses_derivatives |= self.volumes.all().any(|v| v.meta().uses_derivatives);
        m
    }
    fn param(&self, name: &str) -> Option<ParamValue> {
        self.surface.param(name)
    }
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
        self.surface.set_param(name, value)
    }
}

impl<S: SurfaceShader + DisplacementShader + VolumeShader> SurfaceShader for SceneSurface<S> {
    fn globals_read(&self) -> GlobalSet {
        let read = self.surface.globals_read() | self.volumes.globals_read();
        match &self.displacement {
            Some(d) => read | d.globals_read(),
            None => read,
        }
    }

    #[inline]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let out = self.shade_surface(ctx, e);
        if self.volumes.atmosphere.is_none() && self.volumes.interior.is_none() && self.volumes.exterior.is_none() {
            return out;
        }
        self.volumes.apply(ctx, e, out)
    }
}

impl<S: SurfaceShader + DisplacementShader> SceneSurface<S> {
    /// The displacement (if any) and the surface shader.
    #[inline]
    fn shade_surface<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
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
    fn light_records(&self) -> Option<&[LightRecord]> {
        self.inner.light_records()
    }
    fn spaces(&self) -> &Spaces {
        self.inner.spaces()
    }
    fn ray_depth(&self) -> Option<u32> {
        self.inner.ray_depth()
    }
}
