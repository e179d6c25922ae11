//! The RSL standard library, written once over [`crate::ShadingFloat`].
//!
//! Only the primitives of `ShadingFloat` differ between instantiations; every function here
//! is shared by f32, f64, SIMD, dual and interval shading (and is the oracle the RSL back
//! ends are checked against).

mod color;
mod deriv;
mod lighting;
mod math;
mod noise;
mod spline;

pub use color::*;
pub use deriv::*;
pub use lighting::*;
pub use math::*;
pub use noise::*;
pub use spline::*;
