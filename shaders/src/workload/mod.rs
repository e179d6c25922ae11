//! The shared shading workload (`shaders/assets/workload_ref/shading_workload.md`, a copy of
//! the shared benchmark document): one 512×512 image of the unit sphere under two point lights,
//! four shaders, reference images computed in f64. Any shading system that follows the document
//! computes the same image up to rounding, so systems can be compared on it.
//!
//! - [`WorkloadScene`]: camera, f64 ray–sphere intersection and the 183 020 shading inputs;
//!   [`WorkloadScene::shade`] is one shading call for any instantiation.
//! - [`WorkloadPlastic`], [`WorkloadChecker`], [`WorkloadWood`], [`WorkloadGranite`]: the §5
//!   shaders as ordinary generic anysl shaders (the Table-1 `plastic`, `checker`, `wood` and
//!   `granite` differ: faceforward, (s, t) checks, clamped `snoise`, roughness 0.1), and
//!   [`WorkloadShader`], their closed set by workload name.
//! - [`WorkloadShader::sl_source`]: the same four shaders as ordinary `.sl` shaders
//!   (`shaders/rsl/workload/`, embedded), for the interpreter and the JIT.
//! - [`lights`]: the §3 lights (the same as [`crate::table1_lights`]), and [`light_data`], the
//!   same as data.
//! - [`reference`]: the reference arrays and the §6 error metrics.
//!
//! ```
//! use anysl_shaders::workload::{self, WorkloadScene, WorkloadShader};
//!
//! let scene = WorkloadScene::new();
//! assert_eq!(scene.n_hit(), 183_020);
//! let shader = WorkloadShader::by_name("plastic").expect("a workload shader");
//! let ci = scene.shade_all::<f32, _>(&shader, &workload::lights());
//! let image = scene.to_image(&ci);
//! let reference = workload::reference::load_reference("plastic").expect("reference in the repo");
//! assert!(workload::reference::image_error(&image, &reference).max_abs_err <= 1e-4);
//! ```

pub mod reference;
mod scene;
mod surfaces;

pub use scene::{WorkloadScene, PAD, SIZE};
pub use surfaces::{WorkloadChecker, WorkloadGranite, WorkloadPlastic, WorkloadWood};

use crate::{table1_lights, Light};
use anysl_core::prelude::*;
use anysl_core::{ParamError, ParamValue, ShaderMeta, SurfaceVisitor};

/// The §3 lights: point lights at (−3, 4, 5) colour (0.90, 0.85, 0.80) and (4, −1.5, 3) colour
/// (0.25, 0.30, 0.45), no falloff, and ambient (0.08, 0.08, 0.10).
#[must_use]
pub fn lights() -> Vec<Light> {
    table1_lights()
}

/// [`lights`] as data ([`LightData`](anysl_core::LightData)): what a shading call over many
/// packets hands its contexts with an `f32`-based float type, so that the light loops read a
/// few numbers per light instead of running the light shaders (the same bits).
#[must_use]
pub fn light_data() -> Vec<anysl_core::LightData> {
    anysl_core::LightData::of_all(&lights()).expect("the workload's lights are point and ambient lights")
}

/// The four workload shaders, dispatched by `match` (see [`crate::Surface`]).
#[derive(Clone, Debug, PartialEq)]
pub enum WorkloadShader {
    /// §5(a).
    Plastic(WorkloadPlastic),
    /// §5(b).
    Checker(WorkloadChecker),
    /// §5(c).
    Wood(WorkloadWood),
    /// §5(d).
    Granite(WorkloadGranite),
}

impl WorkloadShader {
    /// The workload's shader names, in its order.
    pub const NAMES: [&'static str; 4] = ["plastic", "checker", "wood", "granite"];

    /// The shader called `name` in the workload (`plastic`, `checker`, `wood`, `granite`) or
    /// by its RSL name (`workload_plastic`, …), with the workload's parameters.
    #[must_use]
    pub fn by_name(name: &str) -> Option<Self> {
        Some(match name.strip_prefix("workload_").unwrap_or(name) {
            "plastic" => Self::Plastic(WorkloadPlastic::default()),
            "checker" => Self::Checker(WorkloadChecker::default()),
            "wood" => Self::Wood(WorkloadWood::default()),
            "granite" => Self::Granite(WorkloadGranite::default()),
            _ => return None,
        })
    }

    /// Every workload shader, in the order of [`WorkloadShader::NAMES`].
    #[must_use]
    pub fn all() -> Vec<Self> {
        Self::NAMES.iter().map(|n| Self::by_name(n).expect("every listed name resolves")).collect()
    }

    /// The workload's name of the shader (`plastic`, …; also the reference file's stem).
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::Plastic(_) => "plastic",
            Self::Checker(_) => "checker",
            Self::Wood(_) => "wood",
            Self::Granite(_) => "granite",
        }
    }

    /// The shader as an ordinary RenderMan `.sl` surface shader (`shaders/rsl/workload/<name>.sl`,
    /// embedded so that it compiles without the repository; no `#include`), named
    /// `workload_<name>`, with this shader's parameters and defaults and the §3 light loop
    /// written out.
    #[must_use]
    pub fn sl_source(&self) -> &'static str {
        match self {
            Self::Plastic(_) => include_str!("../../rsl/workload/plastic.sl"),
            Self::Checker(_) => include_str!("../../rsl/workload/checker.sl"),
            Self::Wood(_) => include_str!("../../rsl/workload/wood.sl"),
            Self::Granite(_) => include_str!("../../rsl/workload/granite.sl"),
        }
    }

    /// The name [`WorkloadShader::sl_source`] goes by in diagnostics: its path in the
    /// repository, `shaders/rsl/workload/<name>.sl`.
    #[must_use]
    pub fn sl_file_name(&self) -> &'static str {
        match self {
            Self::Plastic(_) => "shaders/rsl/workload/plastic.sl",
            Self::Checker(_) => "shaders/rsl/workload/checker.sl",
            Self::Wood(_) => "shaders/rsl/workload/wood.sl",
            Self::Granite(_) => "shaders/rsl/workload/granite.sl",
        }
    }
}

impl Shader for WorkloadShader {
    fn meta(&self) -> ShaderMeta {
        match self {
            Self::Plastic(s) => s.meta(),
            Self::Checker(s) => s.meta(),
            Self::Wood(s) => s.meta(),
            Self::Granite(s) => s.meta(),
        }
    }
    fn param(&self, name: &str) -> Option<ParamValue> {
        match self {
            Self::Plastic(s) => s.param(name),
            Self::Checker(s) => s.param(name),
            Self::Wood(s) => s.param(name),
            Self::Granite(s) => s.param(name),
        }
    }
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
        match self {
            Self::Plastic(s) => s.set_param(name, value),
            Self::Checker(s) => s.set_param(name, value),
            Self::Wood(s) => s.set_param(name, value),
            Self::Granite(s) => s.set_param(name, value),
        }
    }
}

impl SurfaceShader for WorkloadShader {
    #[inline]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        match self {
            Self::Plastic(s) => s.shade(ctx, e),
            Self::Checker(s) => s.shade(ctx, e),
            Self::Wood(s) => s.shade(ctx, e),
            Self::Granite(s) => s.shade(ctx, e),
        }
    }

    #[inline(always)]
    fn visit<V: SurfaceVisitor>(&self, v: V) -> V::Output {
        match self {
            Self::Plastic(s) => v.visit(s),
            Self::Checker(s) => v.visit(s),
            Self::Wood(s) => v.visit(s),
            Self::Granite(s) => v.visit(s),
        }
    }
}
