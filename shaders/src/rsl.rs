//! The RSL shaders of `shaders/rsl` (the Table-1 surfaces, the four lights and the RenderMan
//! standard shaders), compiled to generic Rust at build time by anysl-rsl's generated-Rust back
//! end (`shaders/build.rs`). Each is a type like the hand-written ones — [`Plastic`],
//! [`Wood`], [`PointLight`], … — with parameter metadata and set-by-name, and [`RslSurface`] /
//! [`RslLight`] dispatch over them by name like [`crate::Surface`] and [`crate::Light`].
//!
//! ```
//! use anysl_core::{Exec, Globals, PointContext, SurfaceShader};
//! use anysl_shaders::rsl::{RslLight, RslSurface};
//!
//! let lights = vec![RslLight::by_name("pointlight").unwrap()];
//! let wood = RslSurface::by_name("wood").unwrap();
//! let mut ctx = PointContext::new(Globals::<f32>::unit_square(0.3, 0.7), &lights);
//! let out = wood.shade(&mut ctx, &mut Exec::new());
//! assert!(out.Ci.lane(0).iter().all(|c| c.is_finite()));
//! ```
#![allow(missing_docs, clippy::all, clippy::pedantic)]

use anysl_core::prelude::*;
use anysl_core::{ParamError, ParamValue, ShaderMeta, SurfaceVisitor};

/// One concrete shader's `shade` as a function of its own (see `crate::dispatch`).
#[inline(never)]
fn shade_out_of_line<S: SurfaceShader, F: ShadingFloat, C: ShadingContext<F>>(
    s: &S,
    ctx: &mut C,
    e: &mut Exec<F>,
) -> SurfaceOutput<F> {
    s.shade(ctx, e)
}

/// Declares [`RslSurface`], [`RslLight`] and [`RslDisplacement`] over the generated shaders
/// (the build script lists them).
macro_rules! rsl_closed_sets {
    (
        surfaces: [$($S:ident($ST:ty) $sname:literal),* $(,)?],
        lights: [$($L:ident($LT:ty) $lname:literal),* $(,)?],
        displacements: [$($D:ident($DT:ty) $dname:literal),* $(,)?]
    ) => {
        /// Any generated surface shader.
        #[derive(Clone, Debug, PartialEq)]
        pub enum RslSurface { $( $S($ST), )* }

        impl RslSurface {
            /// RSL names of the surfaces, sorted.
            pub const NAMES: &'static [&'static str] = &[$($sname),*];
            /// The surface called `name` (its RSL name; `"phong"` is `plastic`) with default parameters.
            #[must_use]
            pub fn by_name(name: &str) -> Option<Self> {
                match name {
                    "phong" => Self::by_name("plastic"),
                    $( $sname => Some(Self::$S(<$ST>::default())), )*
                    _ => None,
                }
            }
            /// The shader's RSL name.
            #[must_use]
            pub fn name(&self) -> &'static str {
                match self { $( Self::$S(_) => $sname, )* }
            }
        }

        impl Shader for RslSurface {
            fn meta(&self) -> ShaderMeta { match self { $( Self::$S(s) => s.meta(), )* } }
            fn param(&self, name: &str) -> Option<ParamValue> { match self { $( Self::$S(s) => s.param(name), )* } }
            fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
                match self { $( Self::$S(s) => s.set_param(name, value), )* }
            }
        }

        impl SurfaceShader for RslSurface {
            /// Out-of-line per variant, like [`crate::Surface`].
            #[inline]
            fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
                match self { $( Self::$S(s) => shade_out_of_line(s, ctx, e), )* }
            }
            #[inline]
            fn globals_read(&self) -> anysl_core::GlobalSet {
                match self { $( Self::$S(s) => s.globals_read(), )* }
            }
            #[inline(always)]
            fn visit<V: SurfaceVisitor>(&self, v: V) -> V::Output {
                match self { $( Self::$S(s) => v.visit(s), )* }
            }
        }

        /// Any generated light shader.
        #[derive(Clone, Debug, PartialEq)]
        pub enum RslLight { $( $L($LT), )* }

        impl RslLight {
            /// RSL names of the lights, sorted.
            pub const NAMES: &'static [&'static str] = &[$($lname),*];
            /// The light called `name` with default parameters.
            #[must_use]
            pub fn by_name(name: &str) -> Option<Self> {
                match name { $( $lname => Some(Self::$L(<$LT>::default())), )* _ => None }
            }
            /// The shader's RSL name.
            #[must_use]
            pub fn name(&self) -> &'static str {
                match self { $( Self::$L(_) => $lname, )* }
            }
        }

        impl Shader for RslLight {
            fn meta(&self) -> ShaderMeta { match self { $( Self::$L(s) => s.meta(), )* } }
            fn param(&self, name: &str) -> Option<ParamValue> { match self { $( Self::$L(s) => s.param(name), )* } }
            fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
                match self { $( Self::$L(s) => s.set_param(name, value), )* }
            }
        }

        impl LightShader for RslLight {
            #[inline(always)]
            fn light<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
                match self { $( Self::$L(l) => l.light(e, ps), )* }
            }
            #[inline(always)]
            fn emission(&self) -> Option<Emission> {
                match self { $( Self::$L(l) => l.emission(), )* }
            }
        }

        /// Any generated displacement shader.
        #[derive(Clone, Debug, PartialEq)]
        pub enum RslDisplacement { $( $D($DT), )* }

        impl RslDisplacement {
            /// The displacement called `name` with default parameters.
            #[must_use]
            pub fn by_name(name: &str) -> Option<Self> {
                match name { $( $dname => Some(Self::$D(<$DT>::default())), )* _ => None }
            }
        }
    };
}

include!(concat!(env!("OUT_DIR"), "/rsl.rs"));

/// The Table-1 lights (see [`crate::table1_lights`]) as generated RSL lights with the same
/// parameters.
#[must_use]
pub fn table1_lights() -> Vec<RslLight> {
    crate::table1_lights()
        .iter()
        .map(|l| {
            let mut g = RslLight::by_name(l.name()).expect("every hand-written light has an RSL port");
            for p in l.meta().params {
                let v = l.param(&p.name).expect("listed parameter");
                g.set_param(&p.name, &v).expect("the RSL port has the same parameters");
            }
            g
        })
        .collect()
}
