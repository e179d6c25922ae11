//! # anysl-shaders
//!
//! The shaders of the AnySL paper's Table 1 (Karrenberg et al., HPG 2010) — brick, checker,
//! glass, granite, parquet, phong (RSL `plastic`), screen, starball, venus, wood — and the
//! standard lights, each written once as generic Rust over [`anysl_core::ShadingFloat`] and
//! instantiated by type replacement: `f32`, `f64`, SIMD lanes, dual numbers, intervals.
//! Shaders read only [`anysl_core::Globals`] and call the RSL standard library; they never
//! name a renderer. [`Surface`] and [`Light`] dispatch over the closed set by name, and
//! [`native`] holds hand-written SIMD versions of plastic and checker that measure what the
//! generic layer costs. [`workload`] is the shared shading workload (its scene, its four
//! shaders and reference images) that shading systems are compared on.
//!
//! ```
//! use anysl_core::{Exec, Globals, PointContext, SurfaceShader};
//! use anysl_shaders::{table1_lights, Light, Surface};
//!
//! let lights: Vec<Light> = table1_lights();
//! let wood = Surface::by_name("wood").expect("wood is in Table 1");
//!
//! // The same shader, instantiated for f32 and for the f64 reference.
//! let mut ctx32 = PointContext::new(Globals::<f32>::unit_square(0.3, 0.7), &lights);
//! let out32 = wood.shade(&mut ctx32, &mut Exec::new());
//! let mut ctx64 = PointContext::new(Globals::<f64>::unit_square(0.3, 0.7), &lights);
//! let out64 = wood.shade(&mut ctx64, &mut Exec::new());
//!
//! for (a, b) in out32.Ci.lane(0).iter().zip(out64.Ci.lane(0)) {
//!     assert!(a.is_finite() && (a - b).abs() < 1e-4, "f32 {a} vs f64 {b}");
//! }
//! assert_eq!(out64.Oi.lane(0), [1.0, 1.0, 1.0]);
//! ```
#![warn(missing_docs)]

mod common;
pub mod dispatch;
pub mod lights;
pub mod native;
pub mod rsl;
pub mod surfaces;
pub mod workload;

pub use dispatch::{table1_lights, Light, Surface, TABLE1_AMBIENT};
pub use lights::{AmbientLight, DistantLight, PointLight, SpotLight};
pub use surfaces::{Brick, Checker, Glass, Granite, Parquet, Plastic, Screen, Starball, Venus, Wood};
