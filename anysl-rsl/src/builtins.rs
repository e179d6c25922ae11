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
    /// The RSL name.
    pub name: &'static str,
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
    name: &'static str,
    key: &'static str,
    ret: BaseType,
    params: &'static [ArgSpec],
    variadic: Option<Variadic>,
    imp: &'static str,
    always_varying: bool,
) -> Overload {
    Overload { name, key, ret, params, variadic, imp, always_varying }
}

/// Every overload of every built-in, grouped by function.
pub static OVERLOADS: &[Overload] = &[
    ov("radians", "radians_f", Float, &[F], None, "stdlib::radians", false),
    ov("degrees", "degrees_f", Float, &[F], None, "stdlib::degrees", false),
    ov("sin", "sin_f", Float, &[F], None, "F::sin", false),
    ov("asin", "asin_f", Float, &[F], None, "F::asin", false),
    ov("cos", "cos_f", Float, &[F], None, "F::cos", false),
    ov("acos", "acos_f", Float, &[F], None, "F::acos", false),
    ov("tan", "tan_f", Float, &[F], None, "F::tan", false),
    ov("exp", "exp_f", Float, &[F], None, "F::exp", false),
    ov("sqrt", "sqrt_f", Float, &[F], None, "F::sqrt", false),
    ov("inversesqrt", "inversesqrt_f", Float, &[F], None, "stdlib::inversesqrt", false),
    ov("abs", "abs_f", Float, &[F], None, "F::abs", false),
    ov("sign", "sign_f", Float, &[F], None, "stdlib::sign", false),
    ov("floor", "floor_f", Float, &[F], None, "F::floor", false),
    ov("ceil", "ceil_f", Float, &[F], None, "F::ceil", false),
    ov("round", "round_f", Float, &[F], None, "F::round", false),
    ov("atan", "atan_f", Float, &[F], None, "F::atan", false),
    ov("atan", "atan_ff", Float, &[F, F], None, "F::atan2", false),
    ov("pow", "pow_ff", Float, &[F, F], None, "F::powf", false),
    ov("log", "log_f", Float, &[F], None, "F::ln", false),
    ov("log", "log_ff", Float, &[F, F], None, "stdlib::log_base", false),
    ov("mod", "mod_ff", Float, &[F, F], None, "stdlib::fmod", false),
    ov("min", "min_ff_fs", Float, &[F, F], Some(Variadic::Repeat(Float)), "F::min per component", false),
    ov("min", "min_cc_cs", Color, &[C, C], Some(Variadic::Repeat(Color)), "F::min per component", false),
    ov("min", "min_pp_ps", Point, &[P, P], Some(Variadic::Repeat(Point)), "F::min per component", false),
    ov("min", "min_vv_vs", Vector, &[V, V], Some(Variadic::Repeat(Vector)), "F::min per component", false),
    ov("min", "min_nn_ns", Normal, &[N, N], Some(Variadic::Repeat(Normal)), "F::min per component", false),
    ov("max", "max_ff_fs", Float, &[F, F], Some(Variadic::Repeat(Float)), "F::max per component", false),
    ov("max", "max_cc_cs", Color, &[C, C], Some(Variadic::Repeat(Color)), "F::max per component", false),
    ov("max", "max_pp_ps", Point, &[P, P], Some(Variadic::Repeat(Point)), "F::max per component", false),
    ov("max", "max_vv_vs", Vector, &[V, V], Some(Variadic::Repeat(Vector)), "F::max per component", false),
    ov("max", "max_nn_ns", Normal, &[N, N], Some(Variadic::Repeat(Normal)), "F::max per component", false),
    ov("clamp", "clamp_fff", Float, &[F, F, F], None, "stdlib::clamp per component", false),
    ov("clamp", "clamp_ccc", Color, &[C, C, C], None, "stdlib::clamp per component", false),
    ov("clamp", "clamp_ppp", Point, &[P, P, P], None, "stdlib::clamp per component", false),
    ov("clamp", "clamp_vvv", Vector, &[V, V, V], None, "stdlib::clamp per component", false),
    ov("clamp", "clamp_nnn", Normal, &[N, N, N], None, "stdlib::clamp per component", false),
    ov("mix", "mix_fff", Float, &[F, F, F], None, "stdlib::mix", false),
    ov("mix", "mix_ccf", Color, &[C, C, F], None, "stdlib::mix per component", false),
    ov("mix", "mix_ccc", Color, &[C, C, C], None, "stdlib::mix per component", false),
    ov("mix", "mix_ppf", Point, &[P, P, F], None, "stdlib::mix per component", false),
    ov("mix", "mix_ppp", Point, &[P, P, P], None, "stdlib::mix per component", false),
    ov("mix", "mix_vvf", Vector, &[V, V, F], None, "stdlib::mix per component", false),
    ov("mix", "mix_vvv", Vector, &[V, V, V], None, "stdlib::mix per component", false),
    ov("mix", "mix_nnf", Normal, &[N, N, F], None, "stdlib::mix per component", false),
    ov("mix", "mix_nnn", Normal, &[N, N, N], None, "stdlib::mix per component", false),
    ov("step", "step_ff", Float, &[F, F], None, "stdlib::step", false),
    ov("smoothstep", "smoothstep_fff", Float, &[F, F, F], None, "stdlib::smoothstep", false),
    ov("filterstep", "filterstep_ff_opt", Float, &[F, F], Some(Variadic::NameValue), "stdlib::filterstep", false),
    ov(
        "filterstep",
        "filterstep_fff_opt",
        Float,
        &[F, F, F],
        Some(Variadic::NameValue),
        "stdlib::filterstep (s1, s2 form: width |s2 - s1|)",
        false,
    ),
    ov(
        "spline",
        "spline_ffff_fs",
        Float,
        &[F, F, F, F],
        Some(Variadic::Repeat(Float)),
        "stdlib::spline (catmull-rom)",
        false,
    ),
    ov(
        "spline",
        "spline_sffff_fs",
        Float,
        &[S, F, F, F, F],
        Some(Variadic::Repeat(Float)),
        "stdlib::spline (SplineBasis::from_name)",
        false,
    ),
    ov("spline", "spline_ffa", Float, &[F, arr(Float)], None, "stdlib::spline (catmull-rom, array knots)", false),
    ov(
        "spline",
        "spline_sffa",
        Float,
        &[S, F, arr(Float)],
        None,
        "stdlib::spline (SplineBasis::from_name, array knots)",
        false,
    ),
    ov(
        "spline",
        "spline_fccc_cs",
        Color,
        &[F, C, C, C],
        Some(Variadic::Repeat(Color)),
        "stdlib::spline (catmull-rom)",
        false,
    ),
    ov(
        "spline",
        "spline_sfccc_cs",
        Color,
        &[S, F, C, C, C],
        Some(Variadic::Repeat(Color)),
        "stdlib::spline (SplineBasis::from_name)",
        false,
    ),
    ov("spline", "spline_fca", Color, &[F, arr(Color)], None, "stdlib::spline (catmull-rom, array knots)", false),
    ov(
        "spline",
        "spline_sfca",
        Color,
        &[S, F, arr(Color)],
        None,
        "stdlib::spline (SplineBasis::from_name, array knots)",
        false,
    ),
    ov(
        "spline",
        "spline_fppp_ps",
        Point,
        &[F, P, P, P],
        Some(Variadic::Repeat(Point)),
        "stdlib::spline (catmull-rom)",
        false,
    ),
    ov(
        "spline",
        "spline_sfppp_ps",
        Point,
        &[S, F, P, P, P],
        Some(Variadic::Repeat(Point)),
        "stdlib::spline (SplineBasis::from_name)",
        false,
    ),
    ov("spline", "spline_fpa", Point, &[F, arr(Point)], None, "stdlib::spline (catmull-rom, array knots)", false),
    ov(
        "spline",
        "spline_sfpa",
        Point,
        &[S, F, arr(Point)],
        None,
        "stdlib::spline (SplineBasis::from_name, array knots)",
        false,
    ),
    ov(
        "spline",
        "spline_fvvv_vs",
        Vector,
        &[F, V, V, V],
        Some(Variadic::Repeat(Vector)),
        "stdlib::spline (catmull-rom)",
        false,
    ),
    ov(
        "spline",
        "spline_sfvvv_vs",
        Vector,
        &[S, F, V, V, V],
        Some(Variadic::Repeat(Vector)),
        "stdlib::spline (SplineBasis::from_name)",
        false,
    ),
    ov("spline", "spline_fva", Vector, &[F, arr(Vector)], None, "stdlib::spline (catmull-rom, array knots)", false),
    ov(
        "spline",
        "spline_sfva",
        Vector,
        &[S, F, arr(Vector)],
        None,
        "stdlib::spline (SplineBasis::from_name, array knots)",
        false,
    ),
    ov(
        "spline",
        "spline_fnnn_ns",
        Normal,
        &[F, N, N, N],
        Some(Variadic::Repeat(Normal)),
        "stdlib::spline (catmull-rom)",
        false,
    ),
    ov(
        "spline",
        "spline_sfnnn_ns",
        Normal,
        &[S, F, N, N, N],
        Some(Variadic::Repeat(Normal)),
        "stdlib::spline (SplineBasis::from_name)",
        false,
    ),
    ov("spline", "spline_fna", Normal, &[F, arr(Normal)], None, "stdlib::spline (catmull-rom, array knots)", false),
    ov(
        "spline",
        "spline_sfna",
        Normal,
        &[S, F, arr(Normal)],
        None,
        "stdlib::spline (SplineBasis::from_name, array knots)",
        false,
    ),
    ov("Du", "Du_f", Float, &[F], None, "stdlib::du", false),
    ov("Dv", "Dv_f", Float, &[F], None, "stdlib::dv", false),
    ov("Deriv", "Deriv_ff", Float, &[F, F], None, "stdlib::deriv", false),
    ov("Du", "Du_c", Color, &[C], None, "stdlib::du / du_vec per component", false),
    ov("Dv", "Dv_c", Color, &[C], None, "stdlib::dv / dv_vec per component", false),
    ov("Deriv", "Deriv_cf", Color, &[C, F], None, "stdlib::deriv per component", false),
    ov("Du", "Du_p", Vector, &[P], None, "stdlib::du / du_vec per component", false),
    ov("Dv", "Dv_p", Vector, &[P], None, "stdlib::dv / dv_vec per component", false),
    ov("Deriv", "Deriv_pf", Vector, &[P, F], None, "stdlib::deriv per component", false),
    ov("Du", "Du_v", Vector, &[V], None, "stdlib::du / du_vec per component", false),
    ov("Dv", "Dv_v", Vector, &[V], None, "stdlib::dv / dv_vec per component", false),
    ov("Deriv", "Deriv_vf", Vector, &[V, F], None, "stdlib::deriv per component", false),
    ov("Du", "Du_n", Vector, &[N], None, "stdlib::du / du_vec per component", false),
    ov("Dv", "Dv_n", Vector, &[N], None, "stdlib::dv / dv_vec per component", false),
    ov("Deriv", "Deriv_nf", Vector, &[N, F], None, "stdlib::deriv per component", false),
    ov("noise", "noise_ff", Float, &[F], None, "stdlib::noise (NoiseDomain::D1)", false),
    ov("noise", "noise_cf", Color, &[F], None, "stdlib::cnoise (NoiseDomain::D1)", false),
    ov("noise", "noise_pf", Point, &[F], None, "stdlib::vnoise (NoiseDomain::D1)", false),
    ov("noise", "noise_vf", Vector, &[F], None, "stdlib::vnoise (NoiseDomain::D1)", false),
    ov("noise", "noise_fff", Float, &[F, F], None, "stdlib::noise (NoiseDomain::D2)", false),
    ov("noise", "noise_cff", Color, &[F, F], None, "stdlib::cnoise (NoiseDomain::D2)", false),
    ov("noise", "noise_pff", Point, &[F, F], None, "stdlib::vnoise (NoiseDomain::D2)", false),
    ov("noise", "noise_vff", Vector, &[F, F], None, "stdlib::vnoise (NoiseDomain::D2)", false),
    ov("noise", "noise_fp", Float, &[P], None, "stdlib::noise (NoiseDomain::D3)", false),
    ov("noise", "noise_cp", Color, &[P], None, "stdlib::cnoise (NoiseDomain::D3)", false),
    ov("noise", "noise_pp", Point, &[P], None, "stdlib::vnoise (NoiseDomain::D3)", false),
    ov("noise", "noise_vp", Vector, &[P], None, "stdlib::vnoise (NoiseDomain::D3)", false),
    ov("noise", "noise_fpf", Float, &[P, F], None, "stdlib::noise (NoiseDomain::D4)", false),
    ov("noise", "noise_cpf", Color, &[P, F], None, "stdlib::cnoise (NoiseDomain::D4)", false),
    ov("noise", "noise_ppf", Point, &[P, F], None, "stdlib::vnoise (NoiseDomain::D4)", false),
    ov("noise", "noise_vpf", Vector, &[P, F], None, "stdlib::vnoise (NoiseDomain::D4)", false),
    ov("cellnoise", "cellnoise_ff", Float, &[F], None, "stdlib::cellnoise (NoiseDomain::D1)", false),
    ov("cellnoise", "cellnoise_cf", Color, &[F], None, "stdlib::vcellnoise (NoiseDomain::D1)", false),
    ov("cellnoise", "cellnoise_pf", Point, &[F], None, "stdlib::vcellnoise (NoiseDomain::D1)", false),
    ov("cellnoise", "cellnoise_vf", Vector, &[F], None, "stdlib::vcellnoise (NoiseDomain::D1)", false),
    ov("cellnoise", "cellnoise_fff", Float, &[F, F], None, "stdlib::cellnoise (NoiseDomain::D2)", false),
    ov("cellnoise", "cellnoise_cff", Color, &[F, F], None, "stdlib::vcellnoise (NoiseDomain::D2)", false),
    ov("cellnoise", "cellnoise_pff", Point, &[F, F], None, "stdlib::vcellnoise (NoiseDomain::D2)", false),
    ov("cellnoise", "cellnoise_vff", Vector, &[F, F], None, "stdlib::vcellnoise (NoiseDomain::D2)", false),
    ov("cellnoise", "cellnoise_fp", Float, &[P], None, "stdlib::cellnoise (NoiseDomain::D3)", false),
    ov("cellnoise", "cellnoise_cp", Color, &[P], None, "stdlib::vcellnoise (NoiseDomain::D3)", false),
    ov("cellnoise", "cellnoise_pp", Point, &[P], None, "stdlib::vcellnoise (NoiseDomain::D3)", false),
    ov("cellnoise", "cellnoise_vp", Vector, &[P], None, "stdlib::vcellnoise (NoiseDomain::D3)", false),
    ov("cellnoise", "cellnoise_fpf", Float, &[P, F], None, "stdlib::cellnoise (NoiseDomain::D4)", false),
    ov("cellnoise", "cellnoise_cpf", Color, &[P, F], None, "stdlib::vcellnoise (NoiseDomain::D4)", false),
    ov("cellnoise", "cellnoise_ppf", Point, &[P, F], None, "stdlib::vcellnoise (NoiseDomain::D4)", false),
    ov("cellnoise", "cellnoise_vpf", Vector, &[P, F], None, "stdlib::vcellnoise (NoiseDomain::D4)", false),
    ov("snoise", "snoise_ff", Float, &[F], None, "stdlib::snoise (NoiseDomain::D1)", false),
    ov("snoise", "snoise_cf", Color, &[F], None, "stdlib::vsnoise (NoiseDomain::D1)", false),
    ov("snoise", "snoise_pf", Point, &[F], None, "stdlib::vsnoise (NoiseDomain::D1)", false),
    ov("snoise", "snoise_vf", Vector, &[F], None, "stdlib::vsnoise (NoiseDomain::D1)", false),
    ov("snoise", "snoise_fff", Float, &[F, F], None, "stdlib::snoise (NoiseDomain::D2)", false),
    ov("snoise", "snoise_cff", Color, &[F, F], None, "stdlib::vsnoise (NoiseDomain::D2)", false),
    ov("snoise", "snoise_pff", Point, &[F, F], None, "stdlib::vsnoise (NoiseDomain::D2)", false),
    ov("snoise", "snoise_vff", Vector, &[F, F], None, "stdlib::vsnoise (NoiseDomain::D2)", false),
    ov("snoise", "snoise_fp", Float, &[P], None, "stdlib::snoise (NoiseDomain::D3)", false),
    ov("snoise", "snoise_cp", Color, &[P], None, "stdlib::vsnoise (NoiseDomain::D3)", false),
    ov("snoise", "snoise_pp", Point, &[P], None, "stdlib::vsnoise (NoiseDomain::D3)", false),
    ov("snoise", "snoise_vp", Vector, &[P], None, "stdlib::vsnoise (NoiseDomain::D3)", false),
    ov("snoise", "snoise_fpf", Float, &[P, F], None, "stdlib::snoise (NoiseDomain::D4)", false),
    ov("snoise", "snoise_cpf", Color, &[P, F], None, "stdlib::vsnoise (NoiseDomain::D4)", false),
    ov("snoise", "snoise_ppf", Point, &[P, F], None, "stdlib::vsnoise (NoiseDomain::D4)", false),
    ov("snoise", "snoise_vpf", Vector, &[P, F], None, "stdlib::vsnoise (NoiseDomain::D4)", false),
    ov("pnoise", "pnoise_fff", Float, &[F, F], None, "stdlib::pnoise (NoiseDomain::D1)", false),
    ov("pnoise", "pnoise_cff", Color, &[F, F], None, "stdlib::vpnoise (NoiseDomain::D1)", false),
    ov("pnoise", "pnoise_pff", Point, &[F, F], None, "stdlib::vpnoise (NoiseDomain::D1)", false),
    ov("pnoise", "pnoise_vff", Vector, &[F, F], None, "stdlib::vpnoise (NoiseDomain::D1)", false),
    ov("pnoise", "pnoise_fffff", Float, &[F, F, F, F], None, "stdlib::pnoise (NoiseDomain::D2)", false),
    ov("pnoise", "pnoise_cffff", Color, &[F, F, F, F], None, "stdlib::vpnoise (NoiseDomain::D2)", false),
    ov("pnoise", "pnoise_pffff", Point, &[F, F, F, F], None, "stdlib::vpnoise (NoiseDomain::D2)", false),
    ov("pnoise", "pnoise_vffff", Vector, &[F, F, F, F], None, "stdlib::vpnoise (NoiseDomain::D2)", false),
    ov("pnoise", "pnoise_fpp", Float, &[P, P], None, "stdlib::pnoise (NoiseDomain::D3)", false),
    ov("pnoise", "pnoise_cpp", Color, &[P, P], None, "stdlib::vpnoise (NoiseDomain::D3)", false),
    ov("pnoise", "pnoise_ppp", Point, &[P, P], None, "stdlib::vpnoise (NoiseDomain::D3)", false),
    ov("pnoise", "pnoise_vpp", Vector, &[P, P], None, "stdlib::vpnoise (NoiseDomain::D3)", false),
    ov("pnoise", "pnoise_fpfpf", Float, &[P, F, P, F], None, "stdlib::pnoise (NoiseDomain::D4)", false),
    ov("pnoise", "pnoise_cpfpf", Color, &[P, F, P, F], None, "stdlib::vpnoise (NoiseDomain::D4)", false),
    ov("pnoise", "pnoise_ppfpf", Point, &[P, F, P, F], None, "stdlib::vpnoise (NoiseDomain::D4)", false),
    ov("pnoise", "pnoise_vpfpf", Vector, &[P, F, P, F], None, "stdlib::vpnoise (NoiseDomain::D4)", false),
    ov("psnoise", "psnoise_fff", Float, &[F, F], None, "stdlib::psnoise (NoiseDomain::D1)", false),
    ov("psnoise", "psnoise_cff", Color, &[F, F], None, "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D1)", false),
    ov("psnoise", "psnoise_pff", Point, &[F, F], None, "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D1)", false),
    ov(
        "psnoise",
        "psnoise_vff",
        Vector,
        &[F, F],
        None,
        "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D1)",
        false,
    ),
    ov("psnoise", "psnoise_fffff", Float, &[F, F, F, F], None, "stdlib::psnoise (NoiseDomain::D2)", false),
    ov(
        "psnoise",
        "psnoise_cffff",
        Color,
        &[F, F, F, F],
        None,
        "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D2)",
        false,
    ),
    ov(
        "psnoise",
        "psnoise_pffff",
        Point,
        &[F, F, F, F],
        None,
        "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D2)",
        false,
    ),
    ov(
        "psnoise",
        "psnoise_vffff",
        Vector,
        &[F, F, F, F],
        None,
        "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D2)",
        false,
    ),
    ov("psnoise", "psnoise_fpp", Float, &[P, P], None, "stdlib::psnoise (NoiseDomain::D3)", false),
    ov("psnoise", "psnoise_cpp", Color, &[P, P], None, "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D3)", false),
    ov("psnoise", "psnoise_ppp", Point, &[P, P], None, "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D3)", false),
    ov(
        "psnoise",
        "psnoise_vpp",
        Vector,
        &[P, P],
        None,
        "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D3)",
        false,
    ),
    ov("psnoise", "psnoise_fpfpf", Float, &[P, F, P, F], None, "stdlib::psnoise (NoiseDomain::D4)", false),
    ov(
        "psnoise",
        "psnoise_cpfpf",
        Color,
        &[P, F, P, F],
        None,
        "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D4)",
        false,
    ),
    ov(
        "psnoise",
        "psnoise_ppfpf",
        Point,
        &[P, F, P, F],
        None,
        "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D4)",
        false,
    ),
    ov(
        "psnoise",
        "psnoise_vpfpf",
        Vector,
        &[P, F, P, F],
        None,
        "stdlib::vpnoise, remapped to [-1, 1] (NoiseDomain::D4)",
        false,
    ),
    ov("random", "random_f", Float, &[], None, "ShadingContext random stream", true),
    ov("random", "random_c", Color, &[], None, "ShadingContext random stream", true),
    ov("random", "random_p", Point, &[], None, "ShadingContext random stream", true),
    ov("random", "random_v", Vector, &[], None, "ShadingContext random stream", true),
    ov("fbm", "fbm_ffff", Float, &[F, F, F, F], None, "stdlib::fbm (NoiseDomain::D1; octaves rounded, uniform)", false),
    ov("fbm", "fbm_pfff", Float, &[P, F, F, F], None, "stdlib::fbm (NoiseDomain::D3; octaves rounded, uniform)", false),
    ov(
        "fbm",
        "fbm_pffff",
        Float,
        &[P, F, F, F, F],
        None,
        "stdlib::fbm (NoiseDomain::D4; octaves rounded, uniform)",
        false,
    ),
    ov(
        "turbulence",
        "turbulence_ffff",
        Float,
        &[F, F, F, F],
        None,
        "stdlib::turbulence (NoiseDomain::D1; octaves rounded, uniform)",
        false,
    ),
    ov(
        "turbulence",
        "turbulence_pfff",
        Float,
        &[P, F, F, F],
        None,
        "stdlib::turbulence (NoiseDomain::D3; octaves rounded, uniform)",
        false,
    ),
    ov(
        "turbulence",
        "turbulence_pffff",
        Float,
        &[P, F, F, F, F],
        None,
        "stdlib::turbulence (NoiseDomain::D4; octaves rounded, uniform)",
        false,
    ),
    ov("xcomp", "xcomp_p", Float, &[P], None, "Vec3::x", false),
    ov("ycomp", "ycomp_p", Float, &[P], None, "Vec3::y", false),
    ov("zcomp", "zcomp_p", Float, &[P], None, "Vec3::z", false),
    ov("xcomp", "xcomp_v", Float, &[V], None, "Vec3::x", false),
    ov("ycomp", "ycomp_v", Float, &[V], None, "Vec3::y", false),
    ov("zcomp", "zcomp_v", Float, &[V], None, "Vec3::z", false),
    ov("xcomp", "xcomp_n", Float, &[N], None, "Vec3::x", false),
    ov("ycomp", "ycomp_n", Float, &[N], None, "Vec3::y", false),
    ov("zcomp", "zcomp_n", Float, &[N], None, "Vec3::z", false),
    ov("setxcomp", "setxcomp_Pf", Void, &[out(Point), F], None, "Vec3::x =", false),
    ov("setycomp", "setycomp_Pf", Void, &[out(Point), F], None, "Vec3::y =", false),
    ov("setzcomp", "setzcomp_Pf", Void, &[out(Point), F], None, "Vec3::z =", false),
    ov("setxcomp", "setxcomp_Vf", Void, &[out(Vector), F], None, "Vec3::x =", false),
    ov("setycomp", "setycomp_Vf", Void, &[out(Vector), F], None, "Vec3::y =", false),
    ov("setzcomp", "setzcomp_Vf", Void, &[out(Vector), F], None, "Vec3::z =", false),
    ov("setxcomp", "setxcomp_Nf", Void, &[out(Normal), F], None, "Vec3::x =", false),
    ov("setycomp", "setycomp_Nf", Void, &[out(Normal), F], None, "Vec3::y =", false),
    ov("setzcomp", "setzcomp_Nf", Void, &[out(Normal), F], None, "Vec3::z =", false),
    ov("comp", "comp_cf", Float, &[C, F], None, "component by index (clamped)", false),
    ov("setcomp", "setcomp_Cff", Void, &[out(Color), F, F], None, "component by index (clamped) =", false),
    ov("comp", "comp_pf", Float, &[P, F], None, "component by index (clamped)", false),
    ov("setcomp", "setcomp_Pff", Void, &[out(Point), F, F], None, "component by index (clamped) =", false),
    ov("comp", "comp_vf", Float, &[V, F], None, "component by index (clamped)", false),
    ov("setcomp", "setcomp_Vff", Void, &[out(Vector), F, F], None, "component by index (clamped) =", false),
    ov("comp", "comp_nf", Float, &[N, F], None, "component by index (clamped)", false),
    ov("setcomp", "setcomp_Nff", Void, &[out(Normal), F, F], None, "component by index (clamped) =", false),
    ov("comp", "comp_mff", Float, &[M, F, F], None, "Matrix4 element [row][col]", false),
    ov("setcomp", "setcomp_Mfff", Void, &[out(Matrix), F, F, F], None, "Matrix4 element [row][col] =", false),
    ov("length", "length_p", Float, &[P], None, "Vec3::length", false),
    ov("length", "length_v", Float, &[V], None, "Vec3::length", false),
    ov("length", "length_n", Float, &[N], None, "Vec3::length", false),
    ov("normalize", "normalize_v", Vector, &[V], None, "Vec3::normalize", false),
    ov("normalize", "normalize_p", Vector, &[P], None, "Vec3::normalize", false),
    ov("normalize", "normalize_n", Normal, &[N], None, "Vec3::normalize", false),
    ov("distance", "distance_pp", Float, &[P, P], None, "stdlib::distance", false),
    ov("ptlined", "ptlined_ppp", Float, &[P, P, P], None, "stdlib::ptlined", false),
    ov("rotate", "rotate_pfpp", Point, &[P, F, P, P], None, "stdlib::rotate", false),
    ov("area", "area_p", Float, &[P], None, "stdlib::area", false),
    ov("faceforward", "faceforward_vv", Vector, &[V, V], None, "stdlib::faceforward with Nref = Ng", false),
    ov("faceforward", "faceforward_vvv", Vector, &[V, V, V], None, "stdlib::faceforward", false),
    ov("reflect", "reflect_vv", Vector, &[V, V], None, "stdlib::reflect", false),
    ov("refract", "refract_vvf", Vector, &[V, V, F], None, "stdlib::refract", false),
    ov("fresnel", "fresnel_vvfFF", Void, &[V, V, F, out(Float), out(Float)], None, "stdlib::fresnel (kr, kt)", false),
    ov(
        "fresnel",
        "fresnel_vvfFFVV",
        Void,
        &[V, V, F, out(Float), out(Float), out(Vector), out(Vector)],
        None,
        "stdlib::fresnel (kr, kt, R, T)",
        false,
    ),
    ov(
        "transform",
        "transform_sp",
        Point,
        &[S, P],
        None,
        "ShadingContext space matrix, Matrix4::transform_point",
        false,
    ),
    ov(
        "transform",
        "transform_ssp",
        Point,
        &[S, S, P],
        None,
        "ShadingContext space matrices, Matrix4::transform_point",
        false,
    ),
    ov("transform", "transform_mp", Point, &[M, P], None, "Matrix4::transform_point", false),
    ov(
        "transform",
        "transform_smp",
        Point,
        &[S, M, P],
        None,
        "ShadingContext space matrix, Matrix4::transform_point",
        false,
    ),
    ov(
        "vtransform",
        "vtransform_sv",
        Vector,
        &[S, V],
        None,
        "ShadingContext space matrix, Matrix4::transform_vector",
        false,
    ),
    ov(
        "vtransform",
        "vtransform_ssv",
        Vector,
        &[S, S, V],
        None,
        "ShadingContext space matrices, Matrix4::transform_vector",
        false,
    ),
    ov("vtransform", "vtransform_mv", Vector, &[M, V], None, "Matrix4::transform_vector", false),
    ov(
        "vtransform",
        "vtransform_smv",
        Vector,
        &[S, M, V],
        None,
        "ShadingContext space matrix, Matrix4::transform_vector",
        false,
    ),
    ov(
        "ntransform",
        "ntransform_sn",
        Normal,
        &[S, N],
        None,
        "ShadingContext space matrix, Matrix4::transform_normal",
        false,
    ),
    ov(
        "ntransform",
        "ntransform_ssn",
        Normal,
        &[S, S, N],
        None,
        "ShadingContext space matrices, Matrix4::transform_normal",
        false,
    ),
    ov("ntransform", "ntransform_mn", Normal, &[M, N], None, "Matrix4::transform_normal", false),
    ov(
        "ntransform",
        "ntransform_smn",
        Normal,
        &[S, M, N],
        None,
        "ShadingContext space matrix, Matrix4::transform_normal",
        false,
    ),
    ov(
        "transform",
        "transform_sv",
        Vector,
        &[S, V],
        None,
        "ShadingContext space matrix, Matrix4::transform_vector",
        false,
    ),
    ov(
        "transform",
        "transform_ssv",
        Vector,
        &[S, S, V],
        None,
        "ShadingContext space matrices, Matrix4::transform_vector",
        false,
    ),
    ov("transform", "transform_mv", Vector, &[M, V], None, "Matrix4::transform_vector", false),
    ov(
        "transform",
        "transform_smv",
        Vector,
        &[S, M, V],
        None,
        "ShadingContext space matrix, Matrix4::transform_vector",
        false,
    ),
    ov(
        "transform",
        "transform_sn",
        Normal,
        &[S, N],
        None,
        "ShadingContext space matrix, Matrix4::transform_normal",
        false,
    ),
    ov(
        "transform",
        "transform_ssn",
        Normal,
        &[S, S, N],
        None,
        "ShadingContext space matrices, Matrix4::transform_normal",
        false,
    ),
    ov("transform", "transform_mn", Normal, &[M, N], None, "Matrix4::transform_normal", false),
    ov(
        "transform",
        "transform_smn",
        Normal,
        &[S, M, N],
        None,
        "ShadingContext space matrix, Matrix4::transform_normal",
        false,
    ),
    ov("depth", "depth_p", Float, &[P], None, "ShadingContext camera depth (normalized by the clipping planes)", false),
    ov("calculatenormal", "calculatenormal_p", Normal, &[P], None, "stdlib::calculatenormal", false),
    ov("ctransform", "ctransform_sc", Color, &[S, C], None, "stdlib::from_rgb", false),
    ov("ctransform", "ctransform_ssc", Color, &[S, S, C], None, "stdlib::ctransform", false),
    ov("determinant", "determinant_m", Float, &[M], None, "Matrix4::determinant", false),
    ov("translate", "translate_mv", Matrix, &[M, V], None, "Matrix4::translate", false),
    ov("rotate", "rotate_mfv", Matrix, &[M, F, V], None, "Matrix4::rotate", false),
    ov("scale", "scale_mp", Matrix, &[M, P], None, "Matrix4::scale", false),
    ov("concat", "concat_s_ss", String, &[S], Some(Variadic::Repeat(String)), "String concatenation (uniform)", false),
    ov("printf", "printf_s_etc", Void, &[S], Some(Variadic::Any), "formatted print (side effect)", false),
    ov("format", "format_s_etc", String, &[S], Some(Variadic::Any), "formatted string", false),
    ov("match", "match_ss", Float, &[S, S], None, "regex match", false),
    ov("ambient", "ambient", Color, &[], None, "stdlib::ambient", true),
    ov("diffuse", "diffuse_n", Color, &[N], None, "stdlib::diffuse", true),
    ov("specular", "specular_nvf", Color, &[N, V, F], None, "stdlib::specular", true),
    ov("specularbrdf", "specularbrdf_vnvf", Color, &[V, N, V, F], None, "stdlib::specularbrdf (times Cl)", true),
    ov("phong", "phong_nvf", Color, &[N, V, F], None, "stdlib::phong", true),
    ov("trace", "trace_pv", Color, &[P, V], None, "ShadingContext::trace", true),
    ov(
        "texture",
        "texture_fs_opt",
        Float,
        &[S],
        Some(Variadic::NameValue),
        "ShadingContext texture lookup (s, t)",
        true,
    ),
    ov(
        "texture",
        "texture_fsff_opt",
        Float,
        &[S, F, F],
        Some(Variadic::NameValue),
        "ShadingContext texture lookup (given coordinates)",
        true,
    ),
    ov(
        "texture",
        "texture_fsffffffff_opt",
        Float,
        &[S, F, F, F, F, F, F, F, F],
        Some(Variadic::NameValue),
        "ShadingContext texture lookup (given coordinates)",
        true,
    ),
    ov(
        "environment",
        "environment_fsv_opt",
        Float,
        &[S, V],
        Some(Variadic::NameValue),
        "ShadingContext::trace (environment as a ray)",
        true,
    ),
    ov(
        "environment",
        "environment_fsvvvv_opt",
        Float,
        &[S, V, V, V, V],
        Some(Variadic::NameValue),
        "ShadingContext::trace (environment as a ray)",
        true,
    ),
    ov("shadow", "shadow_fsp_opt", Float, &[S, P], Some(Variadic::NameValue), "ShadingContext shadow ray", true),
    ov(
        "shadow",
        "shadow_fspppp_opt",
        Float,
        &[S, P, P, P, P],
        Some(Variadic::NameValue),
        "ShadingContext shadow ray",
        true,
    ),
    ov(
        "texture",
        "texture_cs_opt",
        Color,
        &[S],
        Some(Variadic::NameValue),
        "ShadingContext texture lookup (s, t)",
        true,
    ),
    ov(
        "texture",
        "texture_csff_opt",
        Color,
        &[S, F, F],
        Some(Variadic::NameValue),
        "ShadingContext texture lookup (given coordinates)",
        true,
    ),
    ov(
        "texture",
        "texture_csffffffff_opt",
        Color,
        &[S, F, F, F, F, F, F, F, F],
        Some(Variadic::NameValue),
        "ShadingContext texture lookup (given coordinates)",
        true,
    ),
    ov(
        "environment",
        "environment_csv_opt",
        Color,
        &[S, V],
        Some(Variadic::NameValue),
        "ShadingContext::trace (environment as a ray)",
        true,
    ),
    ov(
        "environment",
        "environment_csvvvv_opt",
        Color,
        &[S, V, V, V, V],
        Some(Variadic::NameValue),
        "ShadingContext::trace (environment as a ray)",
        true,
    ),
    ov("shadow", "shadow_csp_opt", Color, &[S, P], Some(Variadic::NameValue), "ShadingContext shadow ray", true),
    ov(
        "shadow",
        "shadow_cspppp_opt",
        Color,
        &[S, P, P, P, P],
        Some(Variadic::NameValue),
        "ShadingContext shadow ray",
        true,
    ),
    ov("textureinfo", "textureinfo_ssX", Float, &[S, S, OUT_ANY], None, "texture metadata", false),
    ov(
        "atmosphere",
        "atmosphere_sX",
        Float,
        &[S, OUT_ANY],
        None,
        "ShadingContext message passing / query (returns 1 when found)",
        false,
    ),
    ov(
        "displacement",
        "displacement_sX",
        Float,
        &[S, OUT_ANY],
        None,
        "ShadingContext message passing / query (returns 1 when found)",
        false,
    ),
    ov(
        "lightsource",
        "lightsource_sX",
        Float,
        &[S, OUT_ANY],
        None,
        "ShadingContext message passing / query (returns 1 when found)",
        false,
    ),
    ov(
        "surface",
        "surface_sX",
        Float,
        &[S, OUT_ANY],
        None,
        "ShadingContext message passing / query (returns 1 when found)",
        false,
    ),
    ov(
        "incident",
        "incident_sX",
        Float,
        &[S, OUT_ANY],
        None,
        "ShadingContext message passing / query (returns 1 when found)",
        false,
    ),
    ov(
        "opposite",
        "opposite_sX",
        Float,
        &[S, OUT_ANY],
        None,
        "ShadingContext message passing / query (returns 1 when found)",
        false,
    ),
    ov(
        "attribute",
        "attribute_sX",
        Float,
        &[S, OUT_ANY],
        None,
        "ShadingContext message passing / query (returns 1 when found)",
        false,
    ),
    ov(
        "option",
        "option_sX",
        Float,
        &[S, OUT_ANY],
        None,
        "ShadingContext message passing / query (returns 1 when found)",
        false,
    ),
    ov(
        "rendererinfo",
        "rendererinfo_sX",
        Float,
        &[S, OUT_ANY],
        None,
        "ShadingContext message passing / query (returns 1 when found)",
        false,
    ),
    ov(
        "rayinfo",
        "rayinfo_sX",
        Float,
        &[S, OUT_ANY],
        None,
        "ray query (returns 1 when known; a camera ray at depth 0 outside a ray tracer)",
        false,
    ),
    ov("raylevel", "raylevel", Float, &[], None, "ray depth (BMRT): 0 for camera rays", false),
    ov("isshadowray", "isshadowray", Float, &[], None, "1 for shadow rays (BMRT): 0", false),
    ov("isindirectray", "isindirectray", Float, &[], None, "1 for indirect rays (BMRT): 0", false),
    ov(
        "occlusion",
        "occlusion_pnf_opt",
        Float,
        &[P, N, F],
        Some(Variadic::NameValue),
        "ambient occlusion (PRMan 11+): 0, nothing occludes outside a scene",
        true,
    ),
    ov(
        "occlusion",
        "occlusion_spnf_opt",
        Float,
        &[S, P, N, F],
        Some(Variadic::NameValue),
        "ambient occlusion from an occlusion map (PRMan 11 / Aqsis): 0, nothing occludes outside a scene",
        true,
    ),
    ov(
        "indirectdiffuse",
        "indirectdiffuse_pnf_opt",
        Color,
        &[P, N, F],
        Some(Variadic::NameValue),
        "indirect diffuse light (PRMan 11+): black outside a scene",
        true,
    ),
    ov("caustic", "caustic_pn", Color, &[P, N], None, "caustic light from photon maps (PRMan): black", true),
    ov(
        "transmission",
        "transmission_pp_opt",
        Color,
        &[P, P],
        Some(Variadic::NameValue),
        "transmission between two points (PRMan 11+): white, nothing blocks outside a scene",
        true,
    ),
    ov("shadername", "shadername", String, &[], None, "the shader name", false),
    ov("shadername", "shadername_s", String, &[S], None, "the name of the shader bound to a slot", false),
    ov("filterwidth", "filterwidth_f", Float, &[F], None, "stdlib::filterwidth", false),
    ov("filterwidth", "filterwidth_p", Float, &[P], None, "stdlib::filterwidth_point", false),
    ov("filteredpulse", "filteredpulse_fff", Float, &[F, F, F], None, "stdlib::filteredpulse", false),
];

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
    OVERLOADS.iter().any(|o| o.name == name)
}

/// The overloads of `name`, as indices into [`OVERLOADS`].
pub fn overloads_of(name: &str) -> impl Iterator<Item = u32> + '_ {
    OVERLOADS.iter().enumerate().filter(move |(_, o)| o.name == name).map(|(i, _)| i as u32)
}

/// The overload with key `key`.
#[must_use]
pub fn by_key(key: &str) -> Option<u32> {
    OVERLOADS.iter().position(|o| o.key == key).map(|i| i as u32)
}

impl Overload {
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
        format!("{} {}({})", self.ret, self.name, args.join(", "))
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
