//! # anysl-renderers
//!
//! Scenes, a BVH and three renderers of deliberately different design that all run the
//! *same* generic shaders — the claim of AnySL (Karrenberg et al., HPG 2010) that one shader
//! source serves renderers with very different internals and gives the same picture in each:
//!
//! - [`render::packet`] (RTfact-like): packets of 4/8/16 rays shaded together with SIMD
//!   floats, masked per shader, `Dual<F32xN>` when a shader asks for derivatives;
//! - [`render::scalar`] (Manta-like): one ray at a time with ray differentials, `f32` or
//!   `Dual<f32>` when a shader asks for derivatives;
//! - [`render::pbrt`] (pbrt-like): an integrator over a passive material interface, or the
//!   shader's own lighting ("active").
//!
//! Renderer code never names a concrete shader: everything is generic over
//! [`anysl_core::SurfaceShader`] and [`anysl_core::LightShader`], and meets shaders only
//! through [`shading::SceneContext`], the renderer's [`anysl_core::ShadingContext`].
//!
//! ```
//! use anysl_core::prelude::*;
//! use anysl_renderers::{render_packet, render_scalar, scenes, RenderOptions};
//!
//! anysl_core::shader_params! {
//!     /// A matte surface: `Kd · Cs · diffuse(Nf)`.
//!     pub struct Matte: surface "matte" { uniform float Kd = 0.8; }
//! }
//! impl SurfaceShader for Matte {
//!     fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
//!         let g = *ctx.globals();
//!         let nf = faceforward(g.N.normalize(), g.I, g.Ng);
//!         let mut sum = Color::zero();
//!         ctx.illuminance(e, LightQuery::hemisphere(g.P, nf), |e, l, cl| {
//!             e.update(&mut sum, |s| s + cl * l.normalize().dot(nf));
//!         });
//!         SurfaceOutput { Ci: g.Cs * sum * F::c(self.Kd), Oi: g.Os }
//!     }
//! }
//! anysl_core::shader_params! {
//!     /// A point light.
//!     pub struct Lamp: light "lamp" { uniform float intensity = 1.0; }
//! }
//! impl LightShader for Lamp {
//!     fn light<F: ShadingFloat>(&self, _e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
//!         let (l, lit) = illuminate(ps, Vec3::c(-3.0, 4.0, 5.0), None);
//!         LightOutput { cl: Color::splat(F::c(self.intensity)), l, lit, emission: Emission::Local }
//!     }
//! }
//!
//! let scene = scenes::table1(Matte::default(), vec![Lamp::default()], 32);
//! let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
//! let a = render_scalar(&scene, &opts);
//! let b = render_packet::<f64, _, _>(&scene, &opts);
//! assert!(a.psnr(&b) > 60.0);
//! ```
#![warn(missing_docs)]

pub mod accel;
pub mod camera;
pub mod image;
pub mod mesh;
pub mod render;
pub mod scene;
pub mod scenes;
pub mod shading;

pub use accel::{Accel, Hit};
pub use camera::{Camera, CameraSpec, PrimaryRay, Projection, RayDifferential};
pub use image::{read_rgb8, write_rgb8, Image};
pub use mesh::{Mesh, ObjError};
pub use render::packet::{
    packet_shape, render_packet, render_packet_kernel, render_packet_split, render_packet_stats, render_packet_with,
    PacketStats,
};
pub use render::pbrt::{render_pbrt, Integrator};
pub use render::scalar::{render_scalar, render_scalar_as};
pub use render::RenderOptions;
pub use scene::{Instance, Scene, SceneError, Sky, SurfaceHit};
pub use shading::{FilteredShading, GroupShading, KernelShading, LightTables, PlainShading};
