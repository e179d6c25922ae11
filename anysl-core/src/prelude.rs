//! Everything a shader needs in scope: `use anysl_core::prelude::*;`.

pub use crate::context::{
    illuminate, solar, Emission, Falloff, Globals, LightData, LightKind, LightOutput, LightQuery, ShadingContext,
    SurfaceOutput,
};
pub use crate::exec::Exec;
pub use crate::float::{Blend, LatticeBits, Mask, PureFn, ShadingFloat};
pub use crate::shader::{DisplacementShader, LightShader, Shader, SurfaceShader};
pub use crate::stdlib::*;
pub use crate::vec::{Color, Matrix4, Vec3};
