//! # anysl-core
//!
//! The abstract side of AnySL-style type replacement: shaders are written once against
//! [`ShadingFloat`] and run as `f32`, `f64`, SIMD lanes, dual numbers or intervals.
//!
//! ```
//! use anysl_core::{ShadingFloat, Vec3, stdlib::smoothstep};
//!
//! // A shading function written once…
//! fn rim<F: ShadingFloat>(n: Vec3<F>, v: Vec3<F>) -> F {
//!     let c = F::c(1.0) - n.dot(v).abs();
//!     smoothstep(F::c(0.5), F::c(1.0), c)
//! }
//! // …instantiated for scalar f32 and for the f64 accuracy reference.
//! let n = Vec3::<f32>::c(0.0, 0.0, 1.0);
//! let v = Vec3::<f32>::c(0.8, 0.0, 0.6);
//! let a = rim(n, v);
//! let b = rim(Vec3::<f64>::c(0.0, 0.0, 1.0), Vec3::<f64>::c(0.8, 0.0, 0.6));
//! assert!((a as f64 - b).abs() < 1e-6);
//! ```
#![warn(missing_docs)]

pub mod context;
pub mod exec;
pub mod float;
pub mod globals;
pub mod light;
pub mod points;
pub mod prelude;
pub mod shader;
pub mod spaces;
pub mod stdlib;
pub mod vec;

pub use context::{Erased, ErasedContext, PointContext, ShadingContext, MAX_DATA_LIGHTS};
pub use exec::{Exec, INTERVAL_LOOP_LIMIT};
pub use float::{rsqrt_f32, Blend, LatticeBits, Mask, PureFn, ShadingFloat, RSQRT_ESTIMATE_14};
pub use globals::{GlobalSet, Globals, SurfaceOutput};
pub use light::{
    illuminate, in_cone, run_illuminance, solar, sum_ambient, ConeTest, Emission, Falloff, LightCode, LightData,
    LightKind, LightOutput, LightQuery, LightRecord, LightSource,
};
pub use shader::{
    DisplacementShader, ImagerPixel, ImagerShader, LightShader, ParamError, ParamField, ParamInfo, ParamType,
    ParamValue, Shader, ShaderKind, ShaderMeta, Storage, SurfaceShader, SurfaceVisitor, VolumeShader,
};
pub use spaces::{Spaces, DEPTH_SPACE, STANDARD_SPACES};
pub use vec::{Color, Matrix4, Vec3};
