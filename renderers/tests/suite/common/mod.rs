//! Test shaders defined here (not taken from the shader collection) so that the renderer
//! tests know exactly what each picture must look like.
#![allow(dead_code)]

use anysl_core::prelude::*;
use anysl_core::{ParamError, ParamValue, ShaderMeta};

anysl_core::shader_params! {
    /// `Cs · Kd · Σ Cl · max(0, Nf·L̂)`: no ambient, no specular.
    pub struct Lambert: surface "lambert" {
        uniform float Kd = 0.8;
        uniform color tint = [1.0, 1.0, 1.0];
    }
}

impl SurfaceShader for Lambert {
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let nf = faceforward(g.N.normalize(), g.I, g.Ng);
        let mut sum = Color::zero();
        ctx.illuminance(e, LightQuery::hemisphere(g.P, nf), |e, l, cl| {
            e.update(&mut sum, |s| s + cl * l.normalize().dot(nf));
        });
        let tint = Color::from_array(self.tint);
        SurfaceOutput { Ci: g.Cs * tint * sum * F::c(self.Kd), Oi: g.Os }
    }
}

anysl_core::shader_params! {
    /// A see-through surface: `Oi = opacity`, `Ci = opacity · colour` (premultiplied).
    pub struct Screen: surface "testscreen" {
        uniform float opacity = 0.0;
        uniform color colour = [1.0, 0.0, 0.0];
    }
}

impl SurfaceShader for Screen {
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, _ctx: &mut C, _e: &mut Exec<F>) -> SurfaceOutput<F> {
        let o = F::c(self.opacity);
        SurfaceOutput { Ci: Color::from_array(self.colour) * o, Oi: Color::splat(o) }
    }
}

anysl_core::shader_params! {
    /// A perfect mirror: `Ci = Kr · trace(P, reflect(I, Nf))`.
    pub struct Mirror: surface "testmirror" {
        uniform float Kr = 0.9;
    }
}

impl SurfaceShader for Mirror {
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let nf = faceforward(g.N.normalize(), g.I, g.Ng);
        let i = g.I.normalize();
        let r = i - nf * (F::c(2.0) * i.dot(nf));
        let c = ctx.trace(e, g.P, r);
        SurfaceOutput { Ci: c * F::c(self.Kr), Oi: g.Os }
    }
}

anysl_core::shader_params! {
    /// Writes the screen-space derivatives of s: `Ci = (∂s/∂x, ∂s/∂y, s)`.
    pub struct SDerivs: surface "testderivs" uses_derivatives = true {
        uniform float scale = 1.0;
    }
}

impl SurfaceShader for SDerivs {
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, _e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let k = F::c(self.scale);
        SurfaceOutput { Ci: Color::new(g.s.dx() * k, g.s.dy() * k, g.s.value()), Oi: Color::c(1.0, 1.0, 1.0) }
    }
}

/// The closed set of test surfaces (dispatch by `match`, as the shader collection does).
#[derive(Clone, Debug, PartialEq)]
pub enum TestSurface {
    Lambert(Lambert),
    Screen(Screen),
    Mirror(Mirror),
    SDerivs(SDerivs),
}

macro_rules! each {
    ($self:ident, $s:ident => $e:expr) => {
        match $self {
            TestSurface::Lambert($s) => $e,
            TestSurface::Screen($s) => $e,
            TestSurface::Mirror($s) => $e,
            TestSurface::SDerivs($s) => $e,
        }
    };
}

impl Shader for TestSurface {
    fn meta(&self) -> ShaderMeta {
        each!(self, s => s.meta())
    }
    fn param(&self, name: &str) -> Option<ParamValue> {
        each!(self, s => s.param(name))
    }
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
        each!(self, s => s.set_param(name, value))
    }
}

impl SurfaceShader for TestSurface {
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        each!(self, s => s.shade(ctx, e))
    }
}

impl TestSurface {
    pub fn lambert(kd: f64, tint: [f64; 3]) -> Self {
        Self::Lambert(Lambert { Kd: kd, tint })
    }
    pub fn screen(opacity: f64) -> Self {
        Self::Screen(Screen { opacity, ..Screen::default() })
    }
}

anysl_core::shader_params! {
    /// A point light without falloff.
    pub struct TestLight: light "testlight" {
        uniform point from = [-3.0, 4.0, 5.0];
        uniform color intensity = [0.9, 0.85, 0.8];
    }
}

impl LightShader for TestLight {
    fn light<F: ShadingFloat>(&self, _e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        let (l, lit) = illuminate(ps, Vec3::from_array(self.from), None);
        LightOutput { cl: Color::from_array(self.intensity), l, lit, emission: Emission::Local }
    }
}

impl TestLight {
    pub fn at(from: [f64; 3], intensity: f64) -> Self {
        Self { from, intensity: [intensity; 3] }
    }
}

/// The two point lights of the shading workload (§3), without the ambient term.
pub fn workload_lights() -> Vec<TestLight> {
    vec![
        TestLight { from: [-3.0, 4.0, 5.0], intensity: [0.9, 0.85, 0.8] },
        TestLight { from: [4.0, -1.5, 3.0], intensity: [0.25, 0.3, 0.45] },
    ]
}
