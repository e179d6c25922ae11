//! Shaders named by a scene: found as `NAME.sl` on the shader search path or among the
//! built-in RenderMan standard shaders, compiled once per run, with parameters set from the
//! RIB parameter lists by name and type-checked against the shader's own declarations.

use crate::build::{LightCall, ShaderCall};
use anysl_core::{ParamType, ParamValue, Shader};
use anysl_rib::{Param, Values};
use anysl_shaders::Light;
use glam::{Mat4, Vec3};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

const ANYSL_H: &str = include_str!("../../shaders/rsl/include/anysl.h");

/// The RenderMan standard shaders, built in so that a scene naming them needs no files.
pub const STANDARD: &[(&str, &str)] = &[
    ("constant", include_str!("../../shaders/rsl/standard/constant.sl")),
    ("matte", include_str!("../../shaders/rsl/standard/matte.sl")),
    ("metal", include_str!("../../shaders/rsl/standard/metal.sl")),
    ("shinymetal", include_str!("../../shaders/rsl/standard/shinymetal.sl")),
    ("plastic", include_str!("../../shaders/rsl/plastic.sl")),
    ("paintedplastic", include_str!("../../shaders/rsl/standard/paintedplastic.sl")),
    ("null", include_str!("../../shaders/rsl/standard/null.sl")),
    ("defaultsurface", include_str!("../../shaders/rsl/standard/defaultsurface.sl")),
    ("ambientlight", include_str!("../../shaders/rsl/ambientlight.sl")),
    ("distantlight", include_str!("../../shaders/rsl/distantlight.sl")),
    ("pointlight", include_str!("../../shaders/rsl/pointlight.sl")),
    ("spotlight", include_str!("../../shaders/rsl/spotlight.sl")),
    ("fog", include_str!("../../shaders/rsl/standard/volume/fog.sl")),
    ("depthcue", include_str!("../../shaders/rsl/standard/volume/depthcue.sl")),
    ("background", include_str!("../../shaders/rsl/standard/imager/background.sl")),
];

/// Where a shader's source was found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ShaderSource {
    /// A file on the search path.
    File(PathBuf),
    /// A built-in standard shader (its name).
    Builtin(&'static str),
}

/// Finds shaders and compiles each once.
#[derive(Debug, Default)]
pub struct ShaderLibrary {
    /// Directories searched for `NAME.sl`, in order.
    pub search: Vec<PathBuf>,
    /// `#include` directories.
    pub include_dirs: Vec<PathBuf>,
    modules: HashMap<String, Result<anysl_rsl::ir::Module, String>>,
}

impl ShaderLibrary {
    /// A library searching `search` for `NAME.sl`, then the built-in standard shaders.
    #[must_use]
    pub fn new(search: Vec<PathBuf>, include_dirs: Vec<PathBuf>) -> Self {
        Self { search, include_dirs, modules: HashMap::new() }
    }

    /// Where shader `name` comes from.
    ///
    /// # Errors
    /// No such file on the search path and no built-in shader of that name: the message lists
    /// the places looked in.
    pub fn find(&self, name: &str) -> Result<ShaderSource, String> {
        let file = if name.ends_with(".sl") { name.to_string() } else { format!("{name}.sl") };
        if Path::new(&file).is_absolute() && Path::new(&file).is_file() {
            return Ok(ShaderSource::File(PathBuf::from(file)));
        }
        for dir in &self.search {
            let p = dir.join(&file);
            if p.is_file() {
                return Ok(ShaderSource::File(p));
            }
        }
        if let Some((n, _)) = STANDARD.iter().find(|(n, _)| *n == name) {
            return Ok(ShaderSource::Builtin(n));
        }
        let places: Vec<String> = self.search.iter().map(|d| d.display().to_string()).collect();
        Err(format!(
            "shader \"{name}\" not found: no {file} in {} and no built-in shader of that name (built in: {})",
            if places.is_empty() { "(no search path)".to_string() } else { places.join(", ") },
            STANDARD.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
        ))
    }

    /// The compiled module of shader `name` (compiled on first use, then cached; a failure is
    /// cached too).
    ///
    /// # Errors
    /// The shader is not found or does not compile (the rendered diagnostics).
    pub fn module(&mut self, name: &str) -> Result<anysl_rsl::ir::Module, String> {
        if let Some(m) = self.modules.get(name) {
            return m.clone();
        }
        let result = self.compile(name);
        self.modules.insert(name.to_string(), result.clone());
        result
    }

    fn compile(&self, name: &str) -> Result<anysl_rsl::ir::Module, String> {
        let mut include_dirs = self.include_dirs.clone();
        match self.find(name)? {
            ShaderSource::File(path) => {
                if let Some(dir) = path.parent() {
                    include_dirs.push(dir.join("include"));
                }
                let opts = anysl_rsl::CompileOptions { include_dirs, ..Default::default() };
                anysl_rsl::compile_file(&path, &opts).map(|c| c.module).map_err(|e| e.to_string())
            }
            ShaderSource::Builtin(n) => {
                let text = STANDARD.iter().find(|(k, _)| *k == n).map_or("", |(_, t)| t);
                // The header is part of the build: inlined, so no file is needed.
                let text = text.replace("#include \"anysl.h\"", ANYSL_H);
                let opts = anysl_rsl::CompileOptions { include_dirs, ..Default::default() };
                anysl_rsl::compile_source(&format!("<built-in {n}.sl>"), &text, &opts)
                    .map(|c| c.module)
                    .map_err(|e| e.to_string())
            }
        }
    }
}

/// The value of RIB parameter `p` as a value of shader parameter type `ty` (array length
/// `array_len`), or why it does not fit.
fn convert(p: &Param, ty: ParamType, array_len: Option<usize>) -> Result<ParamValue, String> {
    let per = match ty {
        ParamType::Float => 1,
        ParamType::Color | ParamType::Point | ParamType::Vector | ParamType::Normal => 3,
        ParamType::String => 1,
        ParamType::Matrix => 16,
    };
    let items = array_len.unwrap_or(1);
    let one = |k: usize| -> Result<ParamValue, String> {
        match (&p.values, ty) {
            (Values::String(s), ParamType::String) => Ok(ParamValue::String(s[k].clone())),
            (Values::String(_), _) | (_, ParamType::String) => Err("a string and a number do not mix".into()),
            (Values::Float(v), _) => scalar(&v.iter().map(|&x| f64::from(x)).collect::<Vec<_>>(), k, per, ty),
            (Values::Int(v), _) => scalar(&v.iter().map(|&x| f64::from(x)).collect::<Vec<_>>(), k, per, ty),
        }
    };
    let n = p.values.len();
    if n != per * items && !(per == 3 && n == items) {
        return Err(format!("{} values given, {} expected", n, per * items));
    }
    match array_len {
        None => one(0),
        Some(len) => (0..len).map(one).collect::<Result<Vec<_>, _>>().map(ParamValue::Array),
    }
}

fn scalar(v: &[f64], k: usize, per: usize, ty: ParamType) -> Result<ParamValue, String> {
    Ok(match ty {
        ParamType::Float => ParamValue::Float(v[k]),
        ParamType::Matrix => {
            let mut m = [0.0; 16];
            m.copy_from_slice(&v[16 * k..16 * k + 16]);
            ParamValue::Matrix(m)
        }
        _ if v.len() == per * (v.len() / per) && v.len() >= per * (k + 1) => {
            ParamValue::Triple([v[3 * k], v[3 * k + 1], v[3 * k + 2]])
        }
        // One number for a triple: all three components.
        _ => ParamValue::Triple([v[k]; 3]),
    })
}

/// Whether a RIB declaration type can be given to a shader parameter of type `ty`.
fn compatible(p: &Param, ty: ParamType) -> bool {
    use anysl_rib::Type as R;
    if p.origin == anysl_rib::DeclOrigin::Inferred {
        return true;
    }
    matches!(
        (p.decl.ty, ty),
        (R::Float | R::Integer, _) if ty != ParamType::String && ty != ParamType::Matrix
    ) || matches!(
        (p.decl.ty, ty),
        (R::Color, ParamType::Color)
            | (R::Point | R::Vector | R::Normal, ParamType::Point | ParamType::Vector | ParamType::Normal)
            | (R::String, ParamType::String)
            | (R::Matrix, ParamType::Matrix)
    )
}

/// Sets the parameters of `call` on `shader`; returns one warning per parameter that is not
/// the shader's or does not fit its type (the shader keeps its default for it).
pub fn apply_params<S: Shader>(shader: &mut S, call: &ShaderCall) -> Vec<String> {
    let meta = shader.meta();
    let mut warnings = Vec::new();
    // The primitive's variables after the shader call's own list: they override it. Names the
    // shader does not have are other variables of the primitive, not a mistake.
    let primvars = call.primvars.params.iter().filter(|p| meta.param(&p.name).is_some());
    for p in call.params.params.iter().chain(primvars) {
        let Some(info) = meta.param(&p.name) else {
            let known: Vec<String> = meta.params.iter().map(|q| format!("{} {}", q.ty.keyword(), q.name)).collect();
            warnings.push(format!(
                "shader \"{}\" has no parameter \"{}\" (its parameters: {}); ignored",
                meta.name,
                p.name,
                if known.is_empty() { "none".to_string() } else { known.join(", ") }
            ));
            continue;
        };
        let declared = format!("{} {}", p.decl.ty.keyword(), p.name);
        if !compatible(p, info.ty) {
            warnings.push(format!(
                "parameter \"{declared}\" does not fit shader \"{}\"'s \"{} {}\"; ignored",
                meta.name,
                info.ty.keyword(),
                info.name
            ));
            continue;
        }
        match convert(p, info.ty, info.array_len).and_then(|v| shader.set_param(&p.name, &v).map_err(|e| e.to_string()))
        {
            Ok(()) => {}
            Err(e) => warnings.push(format!(
                "parameter \"{declared}\" for shader \"{}\"'s \"{} {}\": {e}; ignored",
                meta.name,
                info.ty.keyword(),
                info.name
            )),
        }
    }
    warnings
}

/// The compiled standard light for `call`, its parameters set and `from`/`to` taken from
/// shader space (the transform current at the `LightSource` request) to world space.
///
/// # Errors
/// A light shader other than the standard four.
pub fn standard_light(call: &LightCall) -> Result<(Light, Vec<String>), String> {
    let name = call.shader.name.as_str();
    let mut light = Light::by_name(name).ok_or_else(|| {
        format!("light shader \"{name}\" is not supported (the standard lights are: {})", Light::NAMES.join(", "))
    })?;
    let warnings = apply_params(&mut light, &call.shader);
    let m: Mat4 = call.transform;
    for point in ["from", "to"] {
        if let Some(ParamValue::Triple(p)) = light.param(point) {
            let w = m.transform_point3(Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32));
            let _ = light.set_param(point, &ParamValue::Triple([w.x, w.y, w.z].map(f64::from)));
        }
    }
    Ok((light, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_standard_shader_compiles_without_files() {
        let mut lib = ShaderLibrary::new(Vec::new(), Vec::new());
        for (name, _) in STANDARD {
            let m = lib.module(name);
            assert!(m.is_ok(), "{name}: {}", m.err().unwrap_or_default());
        }
        assert!(lib.find("nosuchshader").unwrap_err().contains("nosuchshader.sl"));
    }
}
