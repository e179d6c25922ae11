//! Everything a shader needs in scope: `use anysl_core::prelude::*;`.

pub use crate::context::ShadingContext;
pub use crate::exec::Exec;
pub use crate::float::{Blend, LatticeBits, Mask, PureFn, ShadingFloat};
pub use crate::globals::{Globals, SurfaceOutput};
pub use crate::light::{illuminate, solar, Emission, Falloff, LightData, LightKind, LightOutput, LightQuery};
pub use crate::shader::{DisplacementShader, LightShader, Shader, SurfaceShader};
pub use crate::stdlib::*;
pub use crate::vec::{Color, Matrix4, Vec3};
