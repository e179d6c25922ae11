//! The RSL built-in function table: every function of the RenderMan Interface Specification
//! 3.2, chapter "Shading and Lighting Functions", with all overloads, plus a few anysl
//! extensions — and RSL overload resolution.
//!
//! Each [`Overload`] has a unique [`Overload::key`] (`<name>_<args>`, see below) that
//! the back ends map to an implementation; [`Overload::imp`] names the generic Rust that
//! implements it (`stdlib::x` is `anysl_core::stdlib::x`, `F::x` a `ShadingFloat` method,
//! `ShadingContext …` a renderer service). An IR call ([`crate::ir::Op::Call`]) stores the
//! index of the overload in [`OVERLOADS`].
//!
//! Keys are `<name>_<args>` (just `<name>` without arguments); the functions whose overloads
//! differ only in their return type (`noise`, `cellnoise`, `snoise`, `pnoise`, `psnoise`,
//! `random`, `texture`, `environment`, `shadow`) put the return type's letter first:
//! `noise_cp` is `color noise(point)`.
//! Key letters: `f` float, `c` color, `p` point, `v` vector, `n` normal, `m` matrix, `s`
//! string, `x` void; an upper-case letter is an `output` argument, `X` an output of any type,
//! a trailing `a` an array. Suffixes: `_fs`/`_cs`/… more arguments of that type (spline knots,
//! `min`/`max`/`concat` operands), `_opt` trailing `"name", value` pairs (texture options),
//! `_etc` any further arguments (`printf`/`format`). Example: `mix_ccf` is
//! `color mix(color, color, float)`, `fresnel_vvfFFVV` the seven-argument `fresnel`.
//!
//! Extensions beyond RSL 3.2 (used by the project's shaders and by common shader libraries;
//! a user function of the same name shadows them): `snoise`/`psnoise` (signed noise,
//! `stdlib::snoise`), `fbm`/`turbulence` (`p, octaves, lacunarity, gain`), `filterwidth`,
//! `filteredpulse`, and the triple forms of `min`/`max`/`clamp`/`mix` and the typed
//! `transform(…, vector|normal)` that PRMan accepts.
//!
//! # Resolution
//! [`resolve`] picks, among the overloads of a name whose arity fits, the one with the least
//! conversion cost per argument: an exact type costs 0, point/vector/normal interchanged 1,
//! float promoted to a triple 2; colour ↔ point-like never converts, nor does anything into
//! an `output` argument except point-like kinds. Ties (overloads differing only in their
//! return type, like `noise`) are broken by the *expected* type — the cast, declaration or
//! assignment target the checker passes down — preferring an exact return type, then a
//! point-like one, then `float`; without an expected type, `float` wins.
//!
//! ```
//! use anysl_rsl::builtins::{resolve_expecting, OVERLOADS};
//! use anysl_rsl::types::{BaseType, Type};
//! let p = Type::varying(BaseType::Point);
//! let i = resolve_expecting("noise", &[p], Some(BaseType::Color)).unwrap();
//! assert_eq!(OVERLOADS[i as usize].key, "noise_cp");
//! ```

use crate::types::BaseType::{self, Color, Float, Matrix, Normal, Point, String, Vector, Void};
use crate::types::Type;
use Builtin as B;

macro_rules! builtin_names {
    ($($(#[$doc:meta])* $v:ident = $n:literal,)*) => {
        /// A built-in function of RSL, chosen once by the checker: IR calls
        /// ([`crate::ir::Op::Call`]) carry it, and every back end `match`es on it with no
        /// catch-all arm, so a built-in one back end lacks does not compile. Its overloads are
        /// the rows of [`OVERLOADS`] whose [`Overload::builtin`] it is.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Builtin {
            $($(#[$doc])* #[doc = concat!("`", $n, "`")] $v,)*
        }

        impl Builtin {
            /// Every built-in, in table order.
            pub const ALL: &'static [Builtin] = &[$(Builtin::$v,)*];

            /// The RSL name.
            #[must_use]
            pub const fn name(self) -> &'static str {
                match self {
                    $(Builtin::$v => $n,)*
                }
            }

            /// The built-in called `name` in RSL.
            #[must_use]
            pub fn from_name(name: &str) -> Option<Builtin> {
                match name {
                    $($n => Some(Builtin::$v),)*
                    _ => None,
                }
            }
        }
    };
}

builtin_names! {
    Radians = "radians",
    Degrees = "degrees",
    Sin = "sin",
    Asin = "asin",
    Cos = "cos",
    Acos = "acos",
    Tan = "tan",
    Exp = "exp",
    Sqrt = "sqrt",
    InverseSqrt = "inversesqrt",
    Abs = "abs",
    Sign = "sign",
    Floor = "floor",
    Ceil = "ceil",
    Round = "round",
    Atan = "atan",
    Pow = "pow",
    Log = "log",
    Mod = "mod",
    Min = "min",
    Max = "max",
    Clamp = "clamp",
    Mix = "mix",
    Step = "step",
    SmoothStep = "smoothstep",
    FilterStep = "filterstep",
    Spline = "spline",
    Du = "Du",
    Dv = "Dv",
    Deriv = "Deriv",
    Noise = "noise",
    CellNoise = "cellnoise",
    SNoise = "snoise",
    PNoise = "pnoise",
    PSNoise = "psnoise",
    Random = "random",
    Fbm = "fbm",
    Turbulence = "turbulence",
    XComp = "xcomp",
    YComp = "ycomp",
    ZComp = "zcomp",
    SetXComp = "setxcomp",
    SetYComp = "setycomp",
    SetZComp = "setzcomp",
    Comp = "comp",
    SetComp = "setcomp",
    Length = "length",
    Normalize = "normalize",
    Distance = "distance",
    PtLineD = "ptlined",
    Rotate = "rotate",
    Area = "area",
    FaceForward = "faceforward",
    Reflect = "reflect",
    Refract = "refract",
    Fresnel = "fresnel",
    Transform = "transform",
    VTransform = "vtransform",
    NTransform = "ntransform",
    Depth = "depth",
    CalculateNormal = "calculatenormal",
    CTransform = "ctransform",
    Determinant = "determinant",
    Translate = "translate",
    Scale = "scale",
    Concat = "concat",
    Printf = "printf",
    Format = "format",
    Match = "match",
    Ambient = "ambient",
    Diffuse = "diffuse",
    Specular = "specular",
    SpecularBrdf = "specularbrdf",
    Phong = "phong",
    Trace = "trace",
    Texture = "texture",
    Environment = "environment",
    Shadow = "shadow",
    TextureInfo = "textureinfo",
    Atmosphere = "atmosphere",
    Displacement = "displacement",
    LightSource = "lightsource",
    Surface = "surface",
    Incident = "incident",
    Opposite = "opposite",
    Attribute = "attribute",
    Option = "option",
    RendererInfo = "rendererinfo",
    RayInfo = "rayinfo",
    RayLevel = "raylevel",
    IsShadowRay = "isshadowray",
    IsIndirectRay = "isindirectray",
    Occlusion = "occlusion",
    IndirectDiffuse = "indirectdiffuse",
    Caustic = "caustic",
    Transmission = "transmission",
    ShaderName = "shadername",
    FilterWidth = "filterwidth",
    FilteredPulse = "filteredpulse",
}

impl std::fmt::Display for Builtin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl Builtin {
    /// Needs the derivatives of (some of) its arguments: the derivative-activity analysis
    /// marks them, and dual-number back ends carry them.
    #[must_use]
    pub const fn uses_derivatives(self) -> bool {
        use Builtin as B;
        matches!(
            self,
            B::Du
                | B::Dv
                | B::Deriv
                | B::Area
                | B::CalculateNormal
                | B::FilterWidth
                | B::FilterStep
                | B::FilteredPulse
                | B::Texture
                | B::Environment
                | B::Shadow
        )
    }

    /// The result depends on more than the arguments (the renderer, the lights, the
    /// derivatives of the arguments, a random stream, the named spaces) or the call has a side
    /// effect: never folded, never computed once for uniform arguments.
    #[must_use]
    pub const fn reads_context(self) -> bool {
        use Builtin as B;
        matches!(
            self,
            B::Printf
                | B::Random
                | B::Trace
                | B::Texture
                | B::Environment
                | B::Shadow
                | B::Ambient
                | B::Diffuse
                | B::Specular
                | B::SpecularBrdf
                | B::Phong
                | B::Atmosphere
                | B::Displacement
                | B::LightSource
                | B::Surface
                | B::Incident
                | B::Opposite
                | B::Attribute
                | B::Option
                | B::RendererInfo
                | B::TextureInfo
                | B::Depth
                | B::Du
                | B::Dv
                | B::Deriv
                | B::Area
                | B::CalculateNormal
                | B::FilterWidth
                | B::FilterStep
                | B::FilteredPulse
                | B::ShaderName
                | B::Transform
                | B::VTransform
                | B::NTransform
                | B::CTransform
        )
    }

    /// Needs the shading context or the globals, so a back end never computes it on scalars
    /// even when every argument is uniform.
    #[must_use]
    pub const fn lane_only(self) -> bool {
        use Builtin as B;
        matches!(
            self,
            B::Du
                | B::Dv
                | B::Deriv
                | B::CalculateNormal
                | B::Random
                | B::Ambient
                | B::Diffuse
                | B::Specular
                | B::Phong
                | B::Trace
                | B::Texture
                | B::Environment
                | B::Shadow
                | B::Depth
                | B::Area
                | B::FilterWidth
                | B::FilterStep
                | B::FilteredPulse
                | B::FaceForward
        )
    }

    /// Calls the renderer through the shading context itself (its lights or its rays), not only
    /// its globals.
    #[must_use]
    pub const fn calls_renderer(self) -> bool {
        use Builtin as B;
        matches!(self, B::Ambient | B::Diffuse | B::Specular | B::Phong | B::Trace)
    }

    /// Has an effect besides its value (output arguments aside): never removed when unused.
    #[must_use]
    pub const fn has_side_effect(self) -> bool {
        matches!(self, Builtin::Printf)
    }

    /// Takes a coordinate-system name among its arguments (`transform("world", P)`).
    #[must_use]
    pub const fn names_space(self) -> bool {
        matches!(self, Builtin::Transform | Builtin::VTransform | Builtin::NTransform)
    }

    /// The result differs between shading points even for uniform arguments (lights, rays,
    /// textures, random numbers, derivatives, named spaces).
    #[must_use]
    pub const fn varies_per_point(self) -> bool {
        use Builtin as B;
        matches!(
            self,
            B::Random
                | B::Ambient
                | B::Diffuse
                | B::Specular
                | B::SpecularBrdf
                | B::Phong
                | B::Trace
                | B::Environment
                | B::Shadow
                | B::Texture
                | B::Depth
                | B::Incident
                | B::Opposite
                | B::LightSource
                | B::Surface
                | B::Displacement
                | B::Atmosphere
                | B::CalculateNormal
                | B::Du
                | B::Dv
                | B::Deriv
                | B::Area
                | B::FilterWidth
                | B::FilterStep
                | B::FilteredPulse
                | B::Transform
                | B::VTransform
                | B::NTransform
        )
    }

    /// The globals a call with `nargs` input arguments reads from the renderer behind its
    /// arguments' backs: `P` for the light loops, `random` and `depth`; every global for the
    /// derivative and texture functions (the differentials are taken from them); `Ng` for the
    /// two-argument `faceforward`.
    #[must_use]
    pub fn globals_read(self, nargs: usize) -> anysl_core::GlobalSet {
        use anysl_core::GlobalSet as S;
        use Builtin as B;
        match self {
            B::Du | B::Dv | B::Deriv | B::CalculateNormal | B::Texture | B::Environment | B::Shadow => S::ALL,
            B::Ambient | B::Diffuse | B::Specular | B::Phong | B::Random | B::Depth => S::P,
            B::FaceForward if nargs == 2 => S::NG,
            _ => S::NONE,
        }
    }

    /// Its overloads, as indices into [`OVERLOADS`].
    pub fn overloads(self) -> impl Iterator<Item = u32> {
        OVERLOADS.iter().enumerate().filter(move |(_, o)| o.builtin == self).map(|(i, _)| i as u32)
    }
}

/// One formal parameter of a built-in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ArgSpec {
    /// Its base type (ignored when [`ArgSpec::any`]).
    pub ty: BaseType,
    /// An `output` argument: the call writes it; the actual argument must be a variable.
    pub output: bool,
    /// An array (of any length).
    pub array: bool,
    /// Any type (the message-passing and query functions' output variable).
    pub any: bool,
}

/// What follows the fixed parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variadic {
    /// Zero or more further arguments of this type (spline knots, `min`/`max` operands).
    Repeat(BaseType),
    /// `"name", value` pairs (texture, environment, shadow and filterstep options).
    NameValue,
    /// Any arguments of any type (`printf`, `format`).
    Any,
}

/// One overload of a built-in function.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Overload {
    /// The built-in it is an overload of.
    pub builtin: Builtin,
    /// Unique key, `<name>_<args>` (see the module docs); back ends dispatch on it.
    pub key: &'static str,
    /// Return type (`Void` for none).
    pub ret: BaseType,
    /// The fixed parameters.
    pub params: &'static [ArgSpec],
    /// What may follow them.
    pub variadic: Option<Variadic>,
    /// The generic Rust implementing it (`stdlib::x` = `anysl_core::stdlib::x`).
    pub imp: &'static str,
    /// The result is varying whatever the arguments (lights, rays, textures, random numbers).
    pub always_varying: bool,
}

const fn arg(ty: BaseType) -> ArgSpec {
    ArgSpec { ty, output: false, array: false, any: false }
}
const fn out(ty: BaseType) -> ArgSpec {
    ArgSpec { ty, output: true, array: false, any: false }
}
const fn arr(ty: BaseType) -> ArgSpec {
    ArgSpec { ty, output: false, array: true, any: false }
}
const F: ArgSpec = arg(Float);
const C: ArgSpec = arg(Color);
const P: ArgSpec = arg(Point);
const V: ArgSpec = arg(Vector);
const N: ArgSpec = arg(Normal);
const M: ArgSpec = arg(Matrix);
const S: ArgSpec = arg(String);
const OUT_ANY: ArgSpec = ArgSpec { ty: Float, output: true, array: false, any: true };

#[allow(clippy::too_many_arguments)]
const fn ov(
    builtin: Builtin,
    key: &'static str,
    ret: BaseType,
    params: &'static [ArgSpec],
    variadic: Option<Variadic>,
    imp: &'static str,
    always_varying: bool,
) -> Overload {
    Overload { builtin, key, ret, params, variadic, imp, always_varying }
}

/// Functions whose operands and result share one type, for float and each triple
/// (`"letter" Type Param`): `extremum` takes two or more operands (`min_cc_cs`), `triple`
/// three (`clamp_ccc`).
macro_rules! same_type {
    (extremum $b:ident $name:literal $imp:literal) => {
        same_type!(@extremum $b $name $imp; "f" Float F, "c" Color C, "p" Point P, "v" Vector V, "n" Normal N)
    };
    (@extremum $b:ident $name:literal $imp:literal; $($l:literal $t:ident $a:ident),*) => {
        &[$(
            ov(B::$b, concat!($name, "_", $l, $l, "_", $l, "s"), $t, &[$a, $a],
                Some(Variadic::Repeat($t)), $imp, false),
        )*]
    };
    (triple $b:ident $name:literal $imp:literal) => {
        same_type!(@triple $b $name $imp; "f" Float F, "c" Color C, "p" Point P, "v" Vector V, "n" Normal N)
    };
    (@triple $b:ident $name:literal $imp:literal; $($l:literal $t:ident $a:ident),*) => {
        &[$(ov(B::$b, concat!($name, "_", $l, $l, $l), $t, &[$a, $a, $a], None, $imp, false),)*]
    };
}

/// Unary float functions: `name_f`, `float name(float)`; `Builtin name imp` each.
macro_rules! unary_float {
    ($($b:ident $name:literal $imp:literal),* $(,)?) => {
        &[$(ov(B::$b, concat!($name, "_f"), Float, &[F], None, $imp, false),)*]
    };
}

/// `mix` of two triples of one type, by a float (`mix_ccf`) or per component (`mix_ccc`).
macro_rules! mix_triples {
    ($($l:literal $t:ident $a:ident),*) => {
        &[$(
            ov(B::Mix, concat!("mix_", $l, $l, "f"), $t, &[$a, $a, F], None, "stdlib::mix per component", false),
            ov(B::Mix, concat!("mix_", $l, $l, $l), $t, &[$a, $a, $a], None, "stdlib::mix per component", false),
        )*]
    };
}

/// `spline` of one knot type: catmull-rom or a named basis (`s` first), with four or more
/// knots (`spline_fccc_cs`) or an array of knots (`spline_fca`).
macro_rules! spline {
    ($($l:literal $t:ident $a:ident),*) => {
        &[$(
            ov(B::Spline, concat!("spline_f", $l, $l, $l, "_", $l, "s"), $t, &[F, $a, $a, $a],
                Some(Variadic::Repeat($t)), "stdlib::spline (catmull-rom)", false),
            ov(B::Spline, concat!("spline_sf", $l, $l, $l, "_", $l, "s"), $t, &[S, F, $a, $a, $a],
                Some(Variadic::Repeat($t)), "stdlib::spline (SplineBasis::from_name)", false),
            ov(B::Spline, concat!("spline_f", $l, "a"), $t, &[F, arr($t)],
                None, "stdlib::spline (catmull-rom, array knots)", false),
            ov(B::Spline, concat!("spline_sf", $l, "a"), $t, &[S, F, arr($t)],
                None, "stdlib::spline (SplineBasis::from_name, array knots)", false),
        )*]
    };
}

/// `Du`, `Dv` and `Deriv` of a triple, `"letter" Param Return` each.
macro_rules! derivatives {
    ($($l:literal $a:ident $r:ident),*) => {
        &[$(
            ov(B::Du, concat!("Du_", $l), $r, &[$a], None, "stdlib::du / du_vec per component", false),
            ov(B::Dv, concat!("Dv_", $l), $r, &[$a], None, "stdlib::dv / dv_vec per component", false),
            ov(B::Deriv, concat!("Deriv_", $l, "f"), $r, &[$a, F], None, "stdlib::deriv per component", false),
        )*]
    };
}

/// A noise function over its four domains (`NoiseDomain::D1`…`D4`), each returning float,
/// color, point or vector (`noise_cp` is `color noise(point)`): `Builtin name float-imp
/// color-imp triple-imp`. `periodic` takes a period after each domain argument.
macro_rules! noise {
    ($b:ident $name:literal $f:literal $c:literal $v:literal) => {
        noise!(@ $b $name $f $c $v; D1 "f" [F], D2 "ff" [F, F], D3 "p" [P], D4 "pf" [P, F])
    };
    (periodic $b:ident $name:literal $f:literal $c:literal $v:literal) => {
        noise!(@ $b $name $f $c $v; D1 "ff" [F, F], D2 "ffff" [F, F, F, F], D3 "pp" [P, P], D4 "pfpf" [P, F, P, F])
    };
    (@ $b:ident $name:literal $f:literal $c:literal $v:literal; $($d:ident $k:literal [$($a:ident),*]),*) => {
        &[$(
            ov(B::$b, concat!($name, "_f", $k), Float, &[$($a),*], None,
                concat!($f, " (NoiseDomain::", stringify!($d), ")"), false),
            ov(B::$b, concat!($name, "_c", $k), Color, &[$($a),*], None,
                concat!($c, " (NoiseDomain::", stringify!($d), ")"), false),
            ov(B::$b, concat!($name, "_p", $k), Point, &[$($a),*], None,
                concat!($v, " (NoiseDomain::", stringify!($d), ")"), false),
            ov(B::$b, concat!($name, "_v", $k), Vector, &[$($a),*], None,
                concat!($v, " (NoiseDomain::", stringify!($d), ")"), false),
        )*]
    };
}

/// `fbm`/`turbulence` over the domains D1, D3 and D4, then octaves, lacunarity and gain.
macro_rules! fractal {
    ($b:ident $name:literal) => {
        fractal!(@ $b $name; D1 "f" [F], D3 "p" [P], D4 "pf" [P, F])
    };
    (@ $b:ident $name:literal; $($d:ident $k:literal [$($a:ident),*]),*) => {
        &[$(ov(B::$b, concat!($name, "_", $k, "fff"), Float, &[$($a,)* F, F, F], None,
            concat!("stdlib::", $name, " (NoiseDomain::", stringify!($d), "; octaves rounded, uniform)"), false),)*]
    };
}

/// `xcomp`/`ycomp`/`zcomp` and their setters on the point-like types: `"letter" "OUTPUT"
/// Param Type` each.
macro_rules! xyz {
    (get $($l:literal $a:ident),*) => {
        &[$(
            ov(B::XComp, concat!("xcomp_", $l), Float, &[$a], None, "Vec3::x", false),
            ov(B::YComp, concat!("ycomp_", $l), Float, &[$a], None, "Vec3::y", false),
            ov(B::ZComp, concat!("zcomp_", $l), Float, &[$a], None, "Vec3::z", false),
        )*]
    };
    (set $($l:literal $t:ident),*) => {
        &[$(
            ov(B::SetXComp, concat!("setxcomp_", $l, "f"), Void, &[out($t), F], None, "Vec3::x =", false),
            ov(B::SetYComp, concat!("setycomp_", $l, "f"), Void, &[out($t), F], None, "Vec3::y =", false),
            ov(B::SetZComp, concat!("setzcomp_", $l, "f"), Void, &[out($t), F], None, "Vec3::z =", false),
        )*]
    };
}

/// `comp`/`setcomp` of a triple by index: `"letter" "OUTPUT" Param Type` each.
macro_rules! comp {
    ($($l:literal $o:literal $a:ident $t:ident),*) => {
        &[$(
            ov(B::Comp, concat!("comp_", $l, "f"), Float, &[$a, F], None, "component by index (clamped)", false),
            ov(B::SetComp, concat!("setcomp_", $o, "ff"), Void, &[out($t), F, F], None,
                "component by index (clamped) =", false),
        )*]
    };
}

/// A transform of one point-like type: from a named space (`_sp`), between two (`_ssp`), by a
/// matrix (`_mp`) or by a matrix into a named space (`_smp`): `Builtin name "letter" Type
/// Param "point|vector|normal"`.
macro_rules! transform {
    ($b:ident $name:literal $l:literal $t:ident $a:ident $kind:literal) => {
        transform!(@ $b $name $l $t $a $kind;
            "s" [S] "ShadingContext space matrix, ",
            "ss" [S, S] "ShadingContext space matrices, ",
            "m" [M] "",
            "sm" [S, M] "ShadingContext space matrix, ")
    };
    (@ $b:ident $name:literal $l:literal $t:ident $a:ident $kind:literal;
        $($k:literal [$($from:ident),*] $how:literal),*) => {
        &[$(ov(B::$b, concat!($name, "_", $k, $l), $t, &[$($from,)* $a], None,
            concat!($how, "Matrix4::transform_", $kind), false),)*]
    };
}

/// `texture`, `environment` and `shadow` returning one type (`"letter" Type`), with `"name",
/// value` options: texture at (s, t), at given coordinates or four corners; environment and
/// shadow along one direction / at one point or four.
macro_rules! lookups {
    ($l:literal $t:ident) => {
        lookups!(@ $l $t;
            Texture "texture" "s" [S] "ShadingContext texture lookup (s, t)",
            Texture "texture" "sff" [S, F, F] "ShadingContext texture lookup (given coordinates)",
            Texture "texture" "sffffffff" [S, F, F, F, F, F, F, F, F]
                "ShadingContext texture lookup (given coordinates)",
            Environment "environment" "sv" [S, V] "ShadingContext::trace (environment as a ray)",
            Environment "environment" "svvvv" [S, V, V, V, V] "ShadingContext::trace (environment as a ray)",
            Shadow "shadow" "sp" [S, P] "ShadingContext shadow ray",
            Shadow "shadow" "spppp" [S, P, P, P, P] "ShadingContext shadow ray")
    };
    (@ $l:literal $t:ident; $($b:ident $name:literal $k:literal [$($a:ident),*] $imp:literal),*) => {
        &[$(ov(B::$b, concat!($name, "_", $l, $k, "_opt"), $t, &[$($a),*], Some(Variadic::NameValue), $imp, true),)*]
    };
}

/// The message-passing and query functions, `name_sX`: `float name(string, output any)`.
macro_rules! queries {
    ($($b:ident $name:literal),* $(,)?) => {
        &[$(ov(B::$b, concat!($name, "_sX"), Float, &[S, OUT_ANY], None,
            "ShadingContext message passing / query (returns 1 when found)", false),)*]
    };
}

/// The rows of the groups, in order (the table is written as groups, some made by the family
/// macros above; an IR call stores a row's index, so the order is part of the IR).
const OVERLOAD_GROUPS: &[&[Overload]] = &[
    unary_float!(
        Radians "radians" "stdlib::radians",
        Degrees "degrees" "stdlib::degrees",
        Sin "sin" "F::sin",
        Asin "asin" "F::asin",
        Cos "cos" "F::cos",
        Acos "acos" "F::acos",
        Tan "tan" "F::tan",
        Exp "exp" "F::exp",
        Sqrt "sqrt" "F::sqrt",
        InverseSqrt "inversesqrt" "stdlib::inversesqrt",
        Abs "abs" "F::abs",
        Sign "sign" "stdlib::sign",
        Floor "floor" "F::floor",
        Ceil "ceil" "F::ceil",
        Round "round" "F::round",
    ),
    &[
        ov(B::Atan, "atan_f", Float, &[F], None, "F::atan", false),
        ov(B::Atan, "atan_ff", Float, &[F, F], None, "F::atan2", false),
        ov(B::Pow, "pow_ff", Float, &[F, F], None, "F::powf", false),
        ov(B::Log, "log_f", Float, &[F], None, "F::ln", false),
        ov(B::Log, "log_ff", Float, &[F, F], None, "stdlib::log_base", false),
        ov(B::Mod, "mod_ff", Float, &[F, F], None, "stdlib::fmod", false),
    ],
    same_type!(extremum Min "min" "F::min per component"),
    same_type!(extremum Max "max" "F::max per component"),
    same_type!(triple Clamp "clamp" "stdlib::clamp per component"),
    &[ov(B::Mix, "mix_fff", Float, &[F, F, F], None, "stdlib::mix", false)],
    mix_triples!("c" Color C, "p" Point P, "v" Vector V, "n" Normal N),
    &[
        ov(B::Step, "step_ff", Float, &[F, F], None, "stdlib::step", false),
        ov(B::SmoothStep, "smoothstep_fff", Float, &[F, F, F], None, "stdlib::smoothstep", false),
        ov(B::FilterStep, "filterstep_ff_opt", Float, &[F, F], Some(Variadic::NameValue), "stdlib::filterstep", false),
        ov(
            B::FilterStep,
            "filterstep_fff_opt",
            Float,
            &[F, F, F],
            Some(Variadic::NameValue),
            "stdlib::filterstep (s1, s2 form: width |s2 - s1|)",
            false,
        ),
    ],
    spline!("f" Float F, "c" Color C, "p" Point P, "v" Vector V, "n" Normal N),
    &[
        ov(B::Du, "Du_f", Float, &[F], None, "stdlib::du", false),
        ov(B::Dv, "Dv_f", Float, &[F], None, "stdlib::dv", false),
        ov(B::Deriv, "Deriv_ff", Float, &[F, F], None, "stdlib::deriv", false),
    ],
    derivatives!("c" C Color, "p" P Vector, "v" V Vector, "n" N Vector),
    noise!(Noise "noise" "stdlib::noise" "stdlib::cnoise" "stdlib::vnoise"),
    noise!(CellNoise "cellnoise" "stdlib::cellnoise" "stdlib::vcellnoise" "stdlib::vcellnoise"),
    noise!(SNoise "snoise" "stdlib::snoise" "stdlib::vsnoise" "stdlib::vsnoise"),
    noise!(periodic PNoise "pnoise" "stdlib::pnoise" "stdlib::vpnoise" "stdlib::vpnoise"),
    noise!(periodic PSNoise "psnoise" "stdlib::psnoise"
        "stdlib::vpnoise, remapped to [-1, 1]" "stdlib::vpnoise, remapped to [-1, 1]"),
    &[
        ov(B::Random, "random_f", Float, &[], None, "ShadingContext random stream", true),
        ov(B::Random, "random_c", Color, &[], None, "ShadingContext random stream", true),
        ov(B::Random, "random_p", Point, &[], None, "ShadingContext random stream", true),
        ov(B::Random, "random_v", Vector, &[], None, "ShadingContext random stream", true),
    ],
    fractal!(Fbm "fbm"),
    fractal!(Turbulence "turbulence"),
    xyz!(get "p" P, "v" V, "n" N),
    xyz!(set "P" Point, "V" Vector, "N" Normal),
    comp!("c" "C" C Color, "p" "P" P Point, "v" "V" V Vector, "n" "N" N Normal),
    &[
        ov(B::Comp, "comp_mff", Float, &[M, F, F], None, "Matrix4 element [row][col]", false),
        ov(B::SetComp, "setcomp_Mfff", Void, &[out(Matrix), F, F, F], None, "Matrix4 element [row][col] =", false),
        ov(B::Length, "length_p", Float, &[P], None, "Vec3::length", false),
        ov(B::Length, "length_v", Float, &[V], None, "Vec3::length", false),
        ov(B::Length, "length_n", Float, &[N], None, "Vec3::length", false),
        ov(B::Normalize, "normalize_v", Vector, &[V], None, "Vec3::normalize", false),
        ov(B::Normalize, "normalize_p", Vector, &[P], None, "Vec3::normalize", false),
        ov(B::Normalize, "normalize_n", Normal, &[N], None, "Vec3::normalize", false),
        ov(B::Distance, "distance_pp", Float, &[P, P], None, "stdlib::distance", false),
        ov(B::PtLineD, "ptlined_ppp", Float, &[P, P, P], None, "stdlib::ptlined", false),
        ov(B::Rotate, "rotate_pfpp", Point, &[P, F, P, P], None, "stdlib::rotate", false),
        ov(B::Area, "area_p", Float, &[P], None, "stdlib::area", false),
        ov(B::FaceForward, "faceforward_vv", Vector, &[V, V], None, "stdlib::faceforward with Nref = Ng", false),
        ov(B::FaceForward, "faceforward_vvv", Vector, &[V, V, V], None, "stdlib::faceforward", false),
        ov(B::Reflect, "reflect_vv", Vector, &[V, V], None, "stdlib::reflect", false),
        ov(B::Refract, "refract_vvf", Vector, &[V, V, F], None, "stdlib::refract", false),
        ov(
            B::Fresnel,
            "fresnel_vvfFF",
            Void,
            &[V, V, F, out(Float), out(Float)],
            None,
            "stdlib::fresnel (kr, kt)",
            false,
        ),
        ov(
            B::Fresnel,
            "fresnel_vvfFFVV",
            Void,
            &[V, V, F, out(Float), out(Float), out(Vector), out(Vector)],
            None,
            "stdlib::fresnel (kr, kt, R, T)",
            false,
        ),
    ],
    transform!(Transform "transform" "p" Point P "point"),
    transform!(VTransform "vtransform" "v" Vector V "vector"),
    transform!(NTransform "ntransform" "n" Normal N "normal"),
    transform!(Transform "transform" "v" Vector V "vector"),
    transform!(Transform "transform" "n" Normal N "normal"),
    &[
        ov(
            B::Depth,
            "depth_p",
            Float,
            &[P],
            None,
            "ShadingContext camera depth (normalized by the clipping planes)",
            false,
        ),
        ov(B::CalculateNormal, "calculatenormal_p", Normal, &[P], None, "stdlib::calculatenormal", false),
        ov(B::CTransform, "ctransform_sc", Color, &[S, C], None, "stdlib::from_rgb", false),
        ov(B::CTransform, "ctransform_ssc", Color, &[S, S, C], None, "stdlib::ctransform", false),
        ov(B::Determinant, "determinant_m", Float, &[M], None, "Matrix4::determinant", false),
        ov(B::Translate, "translate_mv", Matrix, &[M, V], None, "Matrix4::translate", false),
        ov(B::Rotate, "rotate_mfv", Matrix, &[M, F, V], None, "Matrix4::rotate", false),
        ov(B::Scale, "scale_mp", Matrix, &[M, P], None, "Matrix4::scale", false),
        ov(
            B::Concat,
            "concat_s_ss",
            String,
            &[S],
            Some(Variadic::Repeat(String)),
            "String concatenation (uniform)",
            false,
        ),
        ov(B::Printf, "printf_s_etc", Void, &[S], Some(Variadic::Any), "formatted print (side effect)", false),
        ov(B::Format, "format_s_etc", String, &[S], Some(Variadic::Any), "formatted string", false),
        ov(B::Match, "match_ss", Float, &[S, S], None, "regex match", false),
        ov(B::Ambient, "ambient", Color, &[], None, "stdlib::ambient", true),
        ov(B::Diffuse, "diffuse_n", Color, &[N], None, "stdlib::diffuse", true),
        ov(B::Specular, "specular_nvf", Color, &[N, V, F], None, "stdlib::specular", true),
        ov(B::SpecularBrdf, "specularbrdf_vnvf", Color, &[V, N, V, F], None, "stdlib::specularbrdf (times Cl)", true),
        ov(B::Phong, "phong_nvf", Color, &[N, V, F], None, "stdlib::phong", true),
        ov(B::Trace, "trace_pv", Color, &[P, V], None, "ShadingContext::trace", true),
    ],
    lookups!("f" Float),
    lookups!("c" Color),
    &[ov(B::TextureInfo, "textureinfo_ssX", Float, &[S, S, OUT_ANY], None, "texture metadata", false)],
    queries!(
        Atmosphere "atmosphere",
        Displacement "displacement",
        LightSource "lightsource",
        Surface "surface",
        Incident "incident",
        Opposite "opposite",
        Attribute "attribute",
        Option "option",
        RendererInfo "rendererinfo",
    ),
    &[
        ov(
            B::RayInfo,
            "rayinfo_sX",
            Float,
            &[S, OUT_ANY],
            None,
            "ray query (returns 1 when known; a camera ray at depth 0 outside a ray tracer)",
            false,
        ),
        ov(B::RayLevel, "raylevel", Float, &[], None, "ray depth (BMRT): 0 for camera rays", false),
        ov(B::IsShadowRay, "isshadowray", Float, &[], None, "1 for shadow rays (BMRT): 0", false),
        ov(B::IsIndirectRay, "isindirectray", Float, &[], None, "1 for indirect rays (BMRT): 0", false),
        ov(
            B::Occlusion,
            "occlusion_pnf_opt",
            Float,
            &[P, N, F],
            Some(Variadic::NameValue),
            "ambient occlusion (PRMan 11+): 0, nothing occludes outside a scene",
            true,
        ),
        ov(
            B::Occlusion,
            "occlusion_spnf_opt",
            Float,
            &[S, P, N, F],
            Some(Variadic::NameValue),
            "ambient occlusion from an occlusion map (PRMan 11 / Aqsis): 0, nothing occludes outside a scene",
            true,
        ),
        ov(
            B::IndirectDiffuse,
            "indirectdiffuse_pnf_opt",
            Color,
            &[P, N, F],
            Some(Variadic::NameValue),
            "indirect diffuse light (PRMan 11+): black outside a scene",
            true,
        ),
        ov(B::Caustic, "caustic_pn", Color, &[P, N], None, "caustic light from photon maps (PRMan): black", true),
        ov(
            B::Transmission,
            "transmission_pp_opt",
            Color,
            &[P, P],
            Some(Variadic::NameValue),
            "transmission between two points (PRMan 11+): white, nothing blocks outside a scene",
            true,
        ),
        ov(B::ShaderName, "shadername", String, &[], None, "the shader name", false),
        ov(B::ShaderName, "shadername_s", String, &[S], None, "the name of the shader bound to a slot", false),
        ov(B::FilterWidth, "filterwidth_f", Float, &[F], None, "stdlib::filterwidth", false),
        ov(B::FilterWidth, "filterwidth_p", Float, &[P], None, "stdlib::filterwidth_point", false),
        ov(B::FilteredPulse, "filteredpulse_fff", Float, &[F, F, F], None, "stdlib::filteredpulse", false),
    ],
    // Colour powers, which PRMan's and BMRT's compilers took (gamma: `pow(Ct, 1/2.2)`).
    &[
        ov(B::Pow, "pow_cf", Color, &[C, F], None, "F::powf per component", false),
        ov(B::Pow, "pow_cc", Color, &[C, C], None, "F::powf per component", false),
    ],
];

/// The number of rows in `groups`.
const fn row_count(groups: &[&[Overload]]) -> usize {
    let (mut n, mut g) = (0, 0);
    while g < groups.len() {
        n += groups[g].len();
        g += 1;
    }
    n
}

/// The rows of `groups` in order, as one array of their `N` rows.
const fn concat_rows<const N: usize>(groups: &[&[Overload]]) -> [Overload; N] {
    let mut rows = [groups[0][0]; N];
    let (mut n, mut g) = (0, 0);
    while g < groups.len() {
        let mut i = 0;
        while i < groups[g].len() {
            rows[n] = groups[g][i];
            n += 1;
            i += 1;
        }
        g += 1;
    }
    rows
}

static OVERLOAD_ROWS: [Overload; row_count(OVERLOAD_GROUPS)] = concat_rows(OVERLOAD_GROUPS);

/// Every overload of every built-in, grouped by function.
pub static OVERLOADS: &[Overload] = &OVERLOAD_ROWS;

/// Why [`resolve`] found no overload.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ResolveError {
    /// No built-in has this name.
    Unknown,
    /// The name exists but no overload takes this many arguments; the accepted counts
    /// (`usize::MAX` marks "or more" after the previous count).
    ArgCount(Vec<usize>),
    /// Overloads of this arity exist but none accepts these argument types; their indices.
    NoMatch(Vec<u32>),
}

/// True when some built-in is called `name`.
#[must_use]
pub fn exists(name: &str) -> bool {
    Builtin::from_name(name).is_some()
}

/// The overloads of `name`, as indices into [`OVERLOADS`].
pub fn overloads_of(name: &str) -> impl Iterator<Item = u32> + '_ {
    let b = Builtin::from_name(name);
    OVERLOADS.iter().enumerate().filter(move |(_, o)| Some(o.builtin) == b).map(|(i, _)| i as u32)
}

/// The overload with key `key`.
#[must_use]
pub fn by_key(key: &str) -> Option<u32> {
    OVERLOADS.iter().position(|o| o.key == key).map(|i| i as u32)
}

impl Overload {
    /// The RSL name.
    #[must_use]
    pub const fn name(&self) -> &'static str {
        self.builtin.name()
    }

    /// True when `n` arguments fit the fixed parameters and the variadic tail.
    #[must_use]
    pub fn accepts_count(&self, n: usize) -> bool {
        let k = self.params.len();
        match self.variadic {
            None => n == k,
            Some(Variadic::Repeat(_)) | Some(Variadic::Any) => n >= k,
            Some(Variadic::NameValue) => n >= k && (n - k) % 2 == 0,
        }
    }

    /// The formal parameter for argument `i` (variadic positions included; `None` past the
    /// end, or for the "value" of a name/value pair and `Any` positions, which take anything).
    #[must_use]
    pub fn param(&self, i: usize) -> Option<ArgSpec> {
        if let Some(p) = self.params.get(i) {
            return Some(*p);
        }
        let k = i - self.params.len();
        match self.variadic {
            Some(Variadic::Repeat(t)) => Some(arg(t)),
            Some(Variadic::NameValue) if k % 2 == 0 => Some(S),
            _ => None,
        }
    }

    /// The signature as RSL would write it, e.g. `color mix(color, color, float)`.
    #[must_use]
    pub fn signature(&self) -> std::string::String {
        let mut args: Vec<std::string::String> = self
            .params
            .iter()
            .map(|p| {
                let t = if p.any { "any" } else { p.ty.name() };
                format!("{}{}{}", if p.output { "output " } else { "" }, t, if p.array { "[]" } else { "" })
            })
            .collect();
        match self.variadic {
            Some(Variadic::Repeat(t)) => args.push(format!("{t}…")),
            Some(Variadic::NameValue) => args.push("\"name\", value…".into()),
            Some(Variadic::Any) => args.push("…".into()),
            None => {}
        }
        format!("{} {}({})", self.ret, self.builtin.name(), args.join(", "))
    }
}

/// Conversion cost of passing an argument of type `a` for parameter `p` (`None`: impossible).
#[must_use]
pub fn arg_cost(p: &ArgSpec, a: &Type) -> Option<u32> {
    if p.any {
        return Some(0);
    }
    if p.array != a.array.is_some() {
        return None;
    }
    if p.ty == a.base {
        return Some(0);
    }
    if p.ty.is_pointlike() && a.base.is_pointlike() {
        return Some(1);
    }
    if !p.output && !p.array && a.base == Float && p.ty.is_triple() {
        return Some(2);
    }
    None
}

fn ret_cost(ret: BaseType, expected: Option<BaseType>) -> u32 {
    match expected {
        None | Some(Void) => u32::from(ret != Float && ret != Void),
        Some(e) if e == ret => 0,
        Some(e) if e.is_pointlike() && ret.is_pointlike() => 1,
        Some(_) if ret == Float => 2,
        Some(_) => 3,
    }
}

/// Resolves a call with no expected result type (see [`resolve_expecting`]).
pub fn resolve(name: &str, args: &[Type]) -> Result<u32, ResolveError> {
    resolve_expecting(name, args, None)
}

/// RSL overload resolution: the overload of `name` with the cheapest argument conversions,
/// ties broken by how well its return type fits `expected` (module docs). Returns the index
/// into [`OVERLOADS`].
pub fn resolve_expecting(name: &str, args: &[Type], expected: Option<BaseType>) -> Result<u32, ResolveError> {
    let mut any = false;
    let mut counts = Vec::new();
    let mut fitting = Vec::new();
    let mut best: Option<(u32, u32, u32)> = None;
    for i in overloads_of(name) {
        any = true;
        let o = &OVERLOADS[i as usize];
        if !o.accepts_count(args.len()) {
            let c = if matches!(o.variadic, Some(Variadic::Repeat(_) | Variadic::Any | Variadic::NameValue)) {
                vec![o.params.len(), usize::MAX]
            } else {
                vec![o.params.len()]
            };
            for c in c {
                if !counts.contains(&c) {
                    counts.push(c);
                }
            }
            continue;
        }
        fitting.push(i);
        let mut cost = 0;
        let mut ok = true;
        for (k, a) in args.iter().enumerate() {
            match o.param(k) {
                Some(p) => match arg_cost(&p, a) {
                    Some(c) => cost += c,
                    None => {
                        ok = false;
                        break;
                    }
                },
                None => {}
            }
        }
        if !ok {
            continue;
        }
        let rc = ret_cost(o.ret, expected);
        if best.is_none_or(|(c, r, _)| (cost, rc) < (c, r)) {
            best = Some((cost, rc, i));
        }
    }
    match best {
        Some((_, _, i)) => Ok(i),
        None if !any => Err(ResolveError::Unknown),
        None if fitting.is_empty() => {
            counts.sort_unstable();
            Err(ResolveError::ArgCount(counts))
        }
        None => Err(ResolveError::NoMatch(fitting)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_has_overloads_and_its_name() {
        for &b in Builtin::ALL {
            assert!(b.overloads().next().is_some(), "{b} has no overload");
            assert_eq!(Builtin::from_name(b.name()), Some(b));
        }
        assert!(OVERLOADS.iter().all(|o| Builtin::ALL.contains(&o.builtin)));
        assert_eq!(Builtin::from_name("nosuch"), None);
    }

    #[test]
    fn keys_are_unique() {
        let mut keys: Vec<_> = OVERLOADS.iter().map(|o| o.key).collect();
        keys.sort_unstable();
        let n = keys.len();
        keys.dedup();
        assert_eq!(n, keys.len());
    }

    #[test]
    fn promotion_and_context() {
        let f = Type::uniform(Float);
        let c = Type::varying(Color);
        let p = Type::varying(Point);
        let key = |n, a: &[Type], e| OVERLOADS[resolve_expecting(n, a, e).unwrap() as usize].key;
        assert_eq!(key("mix", &[f, f, f], None), "mix_fff");
        assert_eq!(key("mix", &[c, f, f], None), "mix_ccf");
        assert_eq!(key("noise", &[p], None), "noise_fp");
        assert_eq!(key("noise", &[p], Some(Color)), "noise_cp");
        assert_eq!(key("noise", &[p], Some(Normal)), "noise_pp");
        assert!(matches!(resolve("normalize", &[c]), Err(ResolveError::NoMatch(_))));
        assert!(matches!(resolve("sin", &[f, f]), Err(ResolveError::ArgCount(_))));
        assert_eq!(resolve("nosuch", &[]), Err(ResolveError::Unknown));
    }
}
