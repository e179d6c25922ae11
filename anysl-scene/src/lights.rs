//! The lights of a RIB scene: the standard lights compiled ahead of time, and any other `.sl`
//! light shader found on the shader search path, made by the scene's shader back end (the
//! batched interpreter, or the JIT, which compiles it per float type) and run in its own
//! coordinate systems (its "shader" space is the space current at its `LightSource`).

use crate::build::LightCall;
use crate::shaders::{apply_params, standard_light, ShaderLibrary, ShaderSource};
use anysl_core::{
    Emission, Exec, LightCode, LightData, LightOutput, LightShader, ParamError, ParamType, ParamValue, Shader,
    ShaderMeta, ShadingFloat, Spaces, Vec3,
};
use anysl_rsl::back::interp::InterpShader;
use anysl_rsl::ir::ShaderKind;
use anysl_shaders::Light;

/// A light of a RIB scene; `S` is the back end's shader type (the interpreter's by default).
#[derive(Clone, Debug)]
pub enum SceneLight<S = InterpShader> {
    /// One of the standard lights (`ambientlight`, `distantlight`, `pointlight`,
    /// `spotlight`), compiled ahead of time; light loops may read it as [`LightData`].
    Standard(Light),
    /// A `.sl` light shader run by the scene's back end.
    Shader(ShaderLight<S>),
}

/// A `.sl` light shader instance placed in a scene: the shader with its parameters and the
/// named spaces it sees.
#[derive(Clone, Debug)]
pub struct ShaderLight<S = InterpShader> {
    shader: S,
    spaces: Spaces,
}

impl<S> ShaderLight<S> {
    /// The shader instance (its parameters set).
    #[must_use]
    pub fn shader(&self) -> &S {
        &self.shader
    }

    /// The named spaces the shader sees ("shader" and "object": the space current at its
    /// `LightSource`; the frame's "world", "camera", "screen", "NDC", "raster" and named
    /// coordinate systems).
    #[must_use]
    pub fn spaces(&self) -> &Spaces {
        &self.spaces
    }
}

impl<S: Shader> Shader for SceneLight<S> {
    fn meta(&self) -> ShaderMeta {
        match self {
            Self::Standard(l) => l.meta(),
            Self::Shader(s) => s.shader.meta(),
        }
    }
    fn param(&self, name: &str) -> Option<ParamValue> {
        match self {
            Self::Standard(l) => l.param(name),
            Self::Shader(s) => s.shader.param(name),
        }
    }
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
        match self {
            Self::Standard(l) => l.set_param(name, value),
            Self::Shader(s) => s.shader.set_param(name, value),
        }
    }
}

impl<S: LightShader> LightShader for SceneLight<S> {
    #[inline]
    fn light<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        match self {
            Self::Standard(l) => l.light(e, ps),
            Self::Shader(s) => s.shader.light_in(e, ps, &s.spaces),
        }
    }
    fn emission(&self) -> Option<Emission> {
        match self {
            Self::Standard(l) => l.emission(),
            Self::Shader(s) => s.shader.emission(),
        }
    }
    fn category(&self) -> &str {
        match self {
            Self::Standard(l) => l.category(),
            Self::Shader(s) => s.shader.category(),
        }
    }
    fn data(&self) -> Option<LightData> {
        match self {
            Self::Standard(l) => l.data(),
            Self::Shader(_) => None,
        }
    }
    /// A `.sl` light's code in its own spaces (the standard lights are data).
    fn code<F: ShadingFloat>(&self) -> Option<LightCode> {
        match self {
            Self::Standard(_) => None,
            Self::Shader(s) => s.shader.code_in::<F>(&s.spaces),
        }
    }
}

/// Where the shader of a `.sl` light comes from: the library that finds it and the back end
/// that makes an instance (`anysl_scene::render::Surfaces`).
pub trait LightMaker<S> {
    /// The shader library.
    fn library(&mut self) -> &mut ShaderLibrary;
    /// A fresh instance of shader `name` with its defaults.
    ///
    /// # Errors
    /// The shader cannot be found or made.
    fn instance(&mut self, name: &str) -> Result<S, String>;
}

/// The light of `call`, its parameters set (with one warning per parameter that does not fit).
///
/// A standard light name that no `.sl` file on the search path overrides is the compiled
/// standard light ([`standard_light`]). Any other name is a `.sl` light shader found by
/// `maker`'s library and made by its back end, seeing `frame_spaces` plus "shader" and
/// "object" = the transform at the `LightSource`. Point, vector and normal parameters are taken to current
/// (world) space as RenderMan does when it binds a shader instance: values from the RIB
/// parameter list from "shader" space, defaults written in a named space
/// (`point "shader" (0, 0, 0)`) from that space; defaults without a space are in current space.
///
/// # Errors
/// The shader is not found, does not compile, or is not a light shader.
pub fn scene_light<S: LightShader>(
    call: &LightCall,
    maker: &mut impl LightMaker<S>,
    frame_spaces: &Spaces,
) -> Result<(SceneLight<S>, Vec<String>), String> {
    let name = call.shader.name.as_str();
    if Light::by_name(name).is_some() && matches!(maker.library().find(name), Ok(ShaderSource::Builtin(_))) {
        let (light, warnings) = standard_light(call)?;
        return Ok((SceneLight::Standard(light), warnings));
    }
    let module = maker.library().module(name)?;
    if module.kind != ShaderKind::Light {
        return Err(format!(
            "shader \"{name}\" is a {} shader; LightSource needs a light shader",
            format!("{:?}", module.kind).to_lowercase()
        ));
    }
    // The parameters' declared spaces (`point "shader" (0, 0, 0)`).
    let decl_spaces: Vec<Option<String>> = module.params.iter().map(|p| p.space.clone()).collect();
    let mut shader = maker.instance(name).map_err(|e| format!("light {e}"))?;
    let warnings = apply_params(&mut shader, &call.shader);

    let mut spaces = frame_spaces.clone();
    let shader_to_world = row_major(call.transform);
    spaces.insert("shader", shader_to_world);
    spaces.insert("object", shader_to_world);

    let given = |n: &str| call.shader.params.params.iter().any(|p| p.name == n);
    let meta = shader.meta();
    for (info, decl_space) in meta.params.iter().zip(&decl_spaces) {
        let kind = match info.ty {
            ParamType::Point => Kind::Point,
            ParamType::Vector => Kind::Vector,
            ParamType::Normal => Kind::Normal,
            _ => continue,
        };
        let space = if given(&info.name) { Some("shader") } else { decl_space.as_deref() };
        let Some(space) = space.filter(|s| *s != "current") else { continue };
        let (to, from) = (spaces.to_current_f64(space), spaces.from_current_f64(space));
        if let Some(v) = shader.param(&info.name) {
            let moved = map_triples(&v, &|p| kind.apply(&to, &from, p));
            let _ = shader.set_param(&info.name, &moved);
        }
    }
    Ok((SceneLight::Shader(ShaderLight { shader, spaces }), warnings))
}

/// A glam matrix (column vectors) as the row-vector matrix [`Spaces`] holds, row by row.
fn row_major(m: glam::Mat4) -> [f64; 16] {
    m.as_dmat4().to_cols_array()
}

/// How a triple moves between spaces.
#[derive(Clone, Copy)]
enum Kind {
    Point,
    Vector,
    Normal,
}

impl Kind {
    /// `p` (in the space `to` maps to current) in current space; `from` is `to`'s inverse.
    /// Row vectors: a point is `p·M`, a vector `p·M` without the translation, a normal
    /// `n·(M⁻¹)ᵀ`.
    fn apply(self, to: &[f64; 16], from: &[f64; 16], p: [f64; 3]) -> [f64; 3] {
        let row = |m: &[f64; 16], j: usize, w: f64| p[0] * m[j] + p[1] * m[4 + j] + p[2] * m[8 + j] + w * m[12 + j];
        match self {
            Self::Point => {
                let w = row(to, 3, 1.0);
                let w = if w == 0.0 { 1.0 } else { w };
                [row(to, 0, 1.0) / w, row(to, 1, 1.0) / w, row(to, 2, 1.0) / w]
            }
            Self::Vector => [row(to, 0, 0.0), row(to, 1, 0.0), row(to, 2, 0.0)],
            Self::Normal => {
                let col = |j: usize| p[0] * from[4 * j] + p[1] * from[4 * j + 1] + p[2] * from[4 * j + 2];
                [col(0), col(1), col(2)]
            }
        }
    }
}

fn map_triples(v: &ParamValue, f: &dyn Fn([f64; 3]) -> [f64; 3]) -> ParamValue {
    match v {
        ParamValue::Triple(p) => ParamValue::Triple(f(*p)),
        ParamValue::Array(items) => ParamValue::Array(items.iter().map(|x| map_triples(x, f)).collect()),
        other => other.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triples_move_as_points_vectors_and_normals() {
        // Translate by (1, 2, 3), then scale x by 2 (row vectors: p·S·T).
        let to = [2.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 2.0, 3.0, 1.0];
        let from = [0.5, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -0.5, -2.0, -3.0, 1.0];
        assert_eq!(Kind::Point.apply(&to, &from, [1.0, 1.0, 1.0]), [3.0, 3.0, 4.0]);
        assert_eq!(Kind::Vector.apply(&to, &from, [1.0, 1.0, 1.0]), [2.0, 1.0, 1.0]);
        // A normal of the plane x = y stays perpendicular to it after the scale.
        let n = Kind::Normal.apply(&to, &from, [1.0, -1.0, 0.0]);
        let tangent = Kind::Vector.apply(&to, &from, [1.0, 1.0, 0.0]);
        assert!((n[0] * tangent[0] + n[1] * tangent[1] + n[2] * tangent[2]).abs() < 1e-12);
    }
}
