//! Closed-set dispatch (pbrt-style tagged enums): [`Surface`] and [`Light`] hold any shader
//! of the collection and forward to it with a `match`, so renderers can pick shaders by name
//! at run time without dynamic dispatch per shading point.

use crate::lights::{AmbientLight, DistantLight, PointLight, SpotLight};
use crate::surfaces::{Brick, Checker, Glass, Granite, Parquet, Plastic, Screen, Starball, Venus, Wood};
use anysl_core::prelude::*;
use anysl_core::{ParamError, ParamValue, ShaderMeta, SurfaceVisitor};

/// Forwards `Shader` and one generic shading method of an enum to its variants.
macro_rules! closed_set {
    (
        $(#[$doc:meta])*
        pub enum $E:ident { $( $(#[$vdoc:meta])* $V:ident($T:ty) ),+ $(,)? }
    ) => {
        $(#[$doc])*
        #[derive(Clone, Debug, PartialEq)]
        pub enum $E { $( $(#[$vdoc])* $V($T), )+ }

        impl Shader for $E {
            fn meta(&self) -> ShaderMeta {
                match self { $( Self::$V(s) => s.meta(), )+ }
            }
            fn param(&self, name: &str) -> Option<ParamValue> {
                match self { $( Self::$V(s) => s.param(name), )+ }
            }
            fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
                match self { $( Self::$V(s) => s.set_param(name, value), )+ }
            }
        }

        $( impl From<$T> for $E {
            #[inline]
            fn from(s: $T) -> Self {
                Self::$V(s)
            }
        } )+
    };
}

/// One concrete shader's `shade` as a function of its own (see [`Surface`]'s `shade`).
#[inline(never)]
fn shade_out_of_line<S: SurfaceShader, F: ShadingFloat, C: ShadingContext<F>>(
    s: &S,
    ctx: &mut C,
    e: &mut Exec<F>,
) -> SurfaceOutput<F> {
    s.shade(ctx, e)
}

closed_set! {
    /// Any surface shader of the collection (the paper's Table 1).
    pub enum Surface {
        /// [`Brick`].
        Brick(Brick),
        /// [`Checker`].
        Checker(Checker),
        /// [`Glass`].
        Glass(Glass),
        /// [`Granite`].
        Granite(Granite),
        /// [`Parquet`].
        Parquet(Parquet),
        /// [`Plastic`] (the paper's "Phong").
        Plastic(Plastic),
        /// [`Screen`].
        Screen(Screen),
        /// [`Starball`].
        Starball(Starball),
        /// [`Venus`].
        Venus(Venus),
        /// [`Wood`].
        Wood(Wood),
    }
}

impl Surface {
    /// The surfaces in the order of the paper's Table 1 (plastic under its paper name
    /// "phong"; [`Surface::by_name`] accepts both).
    pub const NAMES: [&'static str; 10] =
        ["brick", "checker", "glass", "granite", "parquet", "phong", "screen", "starball", "venus", "wood"];

    /// The surface called `name` with default parameters (`"phong"` and `"plastic"` are the
    /// same shader); `None` for an unknown name.
    #[must_use]
    pub fn by_name(name: &str) -> Option<Self> {
        Some(match name {
            "brick" => Brick::default().into(),
            "checker" => Checker::default().into(),
            "glass" => Glass::default().into(),
            "granite" => Granite::default().into(),
            "parquet" => Parquet::default().into(),
            "phong" | "plastic" => Plastic::default().into(),
            "screen" => Screen::default().into(),
            "starball" => Starball::default().into(),
            "venus" => Venus::default().into(),
            "wood" => Wood::default().into(),
            _ => return None,
        })
    }

    /// Every surface with default parameters, in the order of [`Surface::NAMES`].
    #[must_use]
    pub fn all() -> Vec<Self> {
        Self::NAMES.iter().map(|n| Self::by_name(n).expect("every listed name resolves")).collect()
    }

    /// The shader's RSL name (`"plastic"` for the paper's "phong").
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::Brick(_) => "brick",
            Self::Checker(_) => "checker",
            Self::Glass(_) => "glass",
            Self::Granite(_) => "granite",
            Self::Parquet(_) => "parquet",
            Self::Plastic(_) => "plastic",
            Self::Screen(_) => "screen",
            Self::Starball(_) => "starball",
            Self::Venus(_) => "venus",
            Self::Wood(_) => "wood",
        }
    }
}

impl SurfaceShader for Surface {
    /// Dispatches to the variant's shader, compiled as its own function per number type and
    /// context (`shade_out_of_line`): a `match` over ten fully inlined shaders would make one
    /// giant function per instantiation, whose optimization time grows much faster than its
    /// size. Hot loops that want the shader inlined go through [`SurfaceShader::visit`].
    #[inline]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        match self {
            Self::Brick(s) => shade_out_of_line(s, ctx, e),
            Self::Checker(s) => shade_out_of_line(s, ctx, e),
            Self::Glass(s) => shade_out_of_line(s, ctx, e),
            Self::Granite(s) => shade_out_of_line(s, ctx, e),
            Self::Parquet(s) => shade_out_of_line(s, ctx, e),
            Self::Plastic(s) => shade_out_of_line(s, ctx, e),
            Self::Screen(s) => shade_out_of_line(s, ctx, e),
            Self::Starball(s) => shade_out_of_line(s, ctx, e),
            Self::Venus(s) => shade_out_of_line(s, ctx, e),
            Self::Wood(s) => shade_out_of_line(s, ctx, e),
        }
    }

    #[inline]
    fn globals_read(&self) -> anysl_core::GlobalSet {
        match self {
            Self::Brick(s) => s.globals_read(),
            Self::Checker(s) => s.globals_read(),
            Self::Glass(s) => s.globals_read(),
            Self::Granite(s) => s.globals_read(),
            Self::Parquet(s) => s.globals_read(),
            Self::Plastic(s) => s.globals_read(),
            Self::Screen(s) => s.globals_read(),
            Self::Starball(s) => s.globals_read(),
            Self::Venus(s) => s.globals_read(),
            Self::Wood(s) => s.globals_read(),
        }
    }

    #[inline(always)]
    fn visit<V: SurfaceVisitor>(&self, v: V) -> V::Output {
        match self {
            Self::Brick(s) => v.visit(s),
            Self::Checker(s) => v.visit(s),
            Self::Glass(s) => v.visit(s),
            Self::Granite(s) => v.visit(s),
            Self::Parquet(s) => v.visit(s),
            Self::Plastic(s) => v.visit(s),
            Self::Screen(s) => v.visit(s),
            Self::Starball(s) => v.visit(s),
            Self::Venus(s) => v.visit(s),
            Self::Wood(s) => v.visit(s),
        }
    }
}

closed_set! {
    /// Any light shader of the collection.
    pub enum Light {
        /// [`PointLight`].
        Point(PointLight),
        /// [`DistantLight`].
        Distant(DistantLight),
        /// [`SpotLight`].
        Spot(SpotLight),
        /// [`AmbientLight`].
        Ambient(AmbientLight),
    }
}

impl Light {
    /// The light shaders' RSL names.
    pub const NAMES: [&'static str; 4] = ["ambientlight", "distantlight", "pointlight", "spotlight"];

    /// The light called `name` with default parameters; `None` for an unknown name.
    #[must_use]
    pub fn by_name(name: &str) -> Option<Self> {
        Some(match name {
            "ambientlight" => AmbientLight::default().into(),
            "distantlight" => DistantLight::default().into(),
            "pointlight" => PointLight::default().into(),
            "spotlight" => SpotLight::default().into(),
            _ => return None,
        })
    }

    /// The shader's RSL name.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::Point(_) => "pointlight",
            Self::Distant(_) => "distantlight",
            Self::Spot(_) => "spotlight",
            Self::Ambient(_) => "ambientlight",
        }
    }
}

impl LightShader for Light {
    #[inline(always)]
    fn light<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        match self {
            Self::Point(l) => l.light(e, ps),
            Self::Distant(l) => l.light(e, ps),
            Self::Spot(l) => l.light(e, ps),
            Self::Ambient(l) => l.light(e, ps),
        }
    }

    #[inline(always)]
    fn emission(&self) -> Option<Emission> {
        match self {
            Self::Point(l) => l.emission(),
            Self::Distant(l) => l.emission(),
            Self::Spot(l) => l.emission(),
            Self::Ambient(l) => l.emission(),
        }
    }

    fn data(&self) -> Option<LightData> {
        match self {
            Self::Point(l) => l.data(),
            Self::Distant(l) => l.data(),
            Self::Spot(l) => l.data(),
            Self::Ambient(l) => l.data(),
        }
    }
}

/// Ambient colour of the Table 1 scene (`shaders/assets/workload_ref/shading_workload.md` §3).
pub const TABLE1_AMBIENT: [f64; 3] = [0.08, 0.08, 0.10];

/// The lights of the paper's Table 1 scene as the shading workload defines them
/// (`shaders/assets/workload_ref/shading_workload.md` §3): two point lights at (−3, 4, 5) with colour
/// (0.90, 0.85, 0.80) and at (4, −1.5, 3) with colour (0.25, 0.30, 0.45), and an ambient
/// light of (0.08, 0.08, 0.10).
///
/// The workload's lights have no distance falloff, so the point lights here use
/// `falloff = 0` (see [`PointLight`]) instead of being scaled: with them, `plastic`, `wood`
/// and `granite` with the workload's coefficients reproduce the workload's reference images
/// exactly, not just in magnitude.
#[must_use]
pub fn table1_lights() -> Vec<Light> {
    let point = |from: [f64; 3], color: [f64; 3]| {
        Light::Point(PointLight { intensity: 1.0, lightcolor: color, from, falloff: 0.0 })
    };
    vec![
        point([-3.0, 4.0, 5.0], [0.90, 0.85, 0.80]),
        point([4.0, -1.5, 3.0], [0.25, 0.30, 0.45]),
        Light::Ambient(AmbientLight { intensity: 1.0, lightcolor: TABLE1_AMBIENT }),
    ]
}
