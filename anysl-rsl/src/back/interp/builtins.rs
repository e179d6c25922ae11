//! The interpreter's built-in functions: each RSL built-in overload resolved once, at
//! preparation, to a [`Bi`], and executed per chunk through the generic standard library of
//! `anysl-core` (the same code the generic Rust shaders and generated Rust call).

use super::frame::{Frame, Loc};
use super::texture;
use crate::builtins::Builtin;
use crate::ir::Const;
use crate::types::BaseType;
use anysl_core::prelude::*;

/// Component-wise unary math.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Un {
    Abs,
    Sign,
    Floor,
    Ceil,
    Round,
    Sqrt,
    InvSqrt,
    Exp,
    Log,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Radians,
    Degrees,
}

/// Component-wise binary math (second operand may be a broadcast float).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bin {
    Pow,
    Atan2,
    LogBase,
    Mod,
    Min,
    Max,
    Step,
}

/// Coordinate-system transform flavours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Xf {
    Point,
    Vector,
    Normal,
}

/// A resolved built-in overload.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bi {
    Un(Un, u32),
    Bin(Bin, u32, bool),
    Clamp(u32, bool),
    Mix(u32, bool),
    Smoothstep(u32),
    Length,
    Normalize,
    Distance,
    Faceforward(bool),
    Reflect,
    Refract,
    Fresnel,
    Ptlined,
    Rotate,
    Comp(u32),
    SetComp(u32),
    Xcomp(u32),
    SetXcomp(u32),
    MComp,
    MSetComp,
    /// `transform([from,] to, p)` or `transform(m, p)`: `matrix` when the first argument is a
    /// matrix; `spaces` = number of space-name arguments.
    Transform(Xf, bool, u32),
    Ctransform(u32),
    Determinant,
    Translate,
    RotateM,
    ScaleM,
    Du(u32),
    Dv(u32),
    Deriv(u32),
    Area,
    CalcNormal,
    FilterWidth(u32),
    FilterStep(u32),
    Noise {
        dims: u8,
        out: u32,
        signed: bool,
    },
    PNoise {
        dims: u8,
        out: u32,
        signed: bool,
    },
    CellNoise {
        dims: u8,
        out: u32,
    },
    Fbm {
        dims: u8,
    },
    Turbulence {
        dims: u8,
    },
    Random(u32),
    /// `spline([basis,] x, knots…)`: element width, number of knots, knots given as an array,
    /// basis string argument present.
    Spline {
        w: u32,
        n: u32,
        array: bool,
        basis: bool,
    },
    Ambient,
    Diffuse,
    Specular,
    SpecularBrdf,
    Phong,
    Trace,
    Texture {
        kind: texture::Kind,
        out: u32,
        coords: u32,
    },
    /// `textureinfo(name, query, out)`.
    TextureInfo,
    Concat,
    Format,
    Printf,
    Match,
    /// Message passing and queries: reports "not found" (returns 0, leaves the output).
    Query,
    /// A constant result of this width (1 or 3): the answer of a scene query outside a scene.
    Fill(u32, u32),
    ShaderName,
    FilteredPulse,
}

fn w(t: BaseType) -> u32 {
    t.components() as u32
}

/// Picks the implementation for `name` with these argument types (base, array length),
/// constant arguments, output-slot types and return type. `None` when unsupported.
#[must_use]
pub fn resolve(
    builtin: Builtin,
    args: &[(BaseType, Option<u32>)],
    consts: &[Option<Const>],
    _outs: &[Option<(BaseType, Option<u32>)>],
    ret: BaseType,
) -> Option<Bi> {
    use BaseType as B;
    let n = args.len();
    let ty = |i: usize| args.get(i).map_or(B::Void, |a| a.0);
    let rw = w(ret);
    let dims = |a: &[(BaseType, Option<u32>)]| -> Option<u8> {
        match a.iter().map(|x| x.0).collect::<Vec<_>>().as_slice() {
            [B::Float] => Some(1),
            [B::Float, B::Float] => Some(2),
            [p] if p.is_triple() => Some(3),
            [p, B::Float] if p.is_triple() => Some(4),
            _ => None,
        }
    };
    let un = |u: Un| (n == 1).then_some(Bi::Un(u, w(ty(0))));
    Some(match builtin {
        Builtin::Abs => un(Un::Abs)?,
        Builtin::Sign => un(Un::Sign)?,
        Builtin::Floor => un(Un::Floor)?,
        Builtin::Ceil => un(Un::Ceil)?,
        Builtin::Round => un(Un::Round)?,
        Builtin::Sqrt => un(Un::Sqrt)?,
        Builtin::InverseSqrt => un(Un::InvSqrt)?,
        Builtin::Exp => un(Un::Exp)?,
        Builtin::Log if n == 1 => un(Un::Log)?,
        Builtin::Log if n == 2 => Bi::Bin(Bin::LogBase, w(ty(0)), true),
        Builtin::Sin => un(Un::Sin)?,
        Builtin::Cos => un(Un::Cos)?,
        Builtin::Tan => un(Un::Tan)?,
        Builtin::Asin => un(Un::Asin)?,
        Builtin::Acos => un(Un::Acos)?,
        Builtin::Atan if n == 1 => un(Un::Atan)?,
        Builtin::Atan if n == 2 => Bi::Bin(Bin::Atan2, 1, true),
        Builtin::Radians => un(Un::Radians)?,
        Builtin::Degrees => un(Un::Degrees)?,
        Builtin::Pow if n == 2 => Bi::Bin(Bin::Pow, w(ty(0)), w(ty(1)) == 1),
        Builtin::Mod if n == 2 => Bi::Bin(Bin::Mod, w(ty(0)), w(ty(1)) == 1),
        Builtin::Min if n >= 2 => Bi::Bin(Bin::Min, rw, false),
        Builtin::Max if n >= 2 => Bi::Bin(Bin::Max, rw, false),
        Builtin::Step if n == 2 => Bi::Bin(Bin::Step, rw, w(ty(0)) == 1),
        Builtin::Clamp if n == 3 => Bi::Clamp(rw, w(ty(1)) == 1),
        Builtin::Mix if n == 3 => Bi::Mix(rw, w(ty(2)) == 1),
        Builtin::SmoothStep if n == 3 => Bi::Smoothstep(rw),
        Builtin::Length => Bi::Length,
        Builtin::Normalize => Bi::Normalize,
        Builtin::Distance => Bi::Distance,
        Builtin::FaceForward => Bi::Faceforward(n == 3),
        Builtin::Reflect => Bi::Reflect,
        Builtin::Refract => Bi::Refract,
        Builtin::Fresnel => Bi::Fresnel,
        Builtin::PtLineD => Bi::Ptlined,
        Builtin::Rotate if ty(0).is_triple() => Bi::Rotate,
        Builtin::Rotate => Bi::RotateM,
        Builtin::Translate => Bi::Translate,
        Builtin::Scale => Bi::ScaleM,
        Builtin::XComp => Bi::Xcomp(0),
        Builtin::YComp => Bi::Xcomp(1),
        Builtin::ZComp => Bi::Xcomp(2),
        Builtin::SetXComp => Bi::SetXcomp(0),
        Builtin::SetYComp => Bi::SetXcomp(1),
        Builtin::SetZComp => Bi::SetXcomp(2),
        Builtin::Comp if ty(0) == B::Matrix => Bi::MComp,
        Builtin::Comp => Bi::Comp(w(ty(0))),
        Builtin::SetComp if _outs.first().copied().flatten().is_some_and(|o| o.0 == B::Matrix) => Bi::MSetComp,
        Builtin::SetComp => Bi::SetComp(3),
        Builtin::Transform | Builtin::VTransform | Builtin::NTransform => {
            let xf = match (builtin, ret) {
                (Builtin::VTransform, _) | (_, B::Vector) => Xf::Vector,
                (Builtin::NTransform, _) | (_, B::Normal) => Xf::Normal,
                _ => Xf::Point,
            };
            let matrix = args.iter().any(|a| a.0 == B::Matrix);
            let spaces = args.iter().filter(|a| a.0 == B::String).count() as u32;
            Bi::Transform(xf, matrix, spaces)
        }
        Builtin::CTransform => Bi::Ctransform(args.iter().filter(|a| a.0 == B::String).count() as u32),
        Builtin::Determinant => Bi::Determinant,
        Builtin::Du => Bi::Du(w(ty(0))),
        Builtin::Dv => Bi::Dv(w(ty(0))),
        Builtin::Deriv => Bi::Deriv(w(ty(0))),
        Builtin::Area => Bi::Area,
        Builtin::CalculateNormal => Bi::CalcNormal,
        Builtin::FilterWidth => Bi::FilterWidth(w(ty(0))),
        Builtin::FilteredPulse => Bi::FilteredPulse,
        Builtin::FilterStep => Bi::FilterStep(args.iter().take_while(|a| a.0 != B::String).count() as u32),
        Builtin::Noise | Builtin::SNoise => {
            Bi::Noise { dims: dims(args)?, out: rw, signed: builtin == Builtin::SNoise }
        }
        Builtin::PNoise | Builtin::PSNoise => {
            let half = n / 2;
            Bi::PNoise { dims: dims(&args[..half])?, out: rw, signed: builtin == Builtin::PSNoise }
        }
        Builtin::CellNoise => Bi::CellNoise { dims: dims(args)?, out: rw },
        Builtin::Fbm => Bi::Fbm { dims: if ty(0).is_triple() { 3 } else { 1 } },
        Builtin::Turbulence => Bi::Turbulence { dims: if ty(0).is_triple() { 3 } else { 1 } },
        Builtin::Random => Bi::Random(rw),
        Builtin::Spline => {
            let basis = ty(0) == B::String;
            let first = usize::from(basis) + 1;
            let rest = args.get(first..)?;
            if rest.len() == 1 && rest[0].1.is_some() {
                Bi::Spline { w: w(rest[0].0), n: rest[0].1?, array: true, basis }
            } else {
                Bi::Spline { w: rw, n: rest.len() as u32, array: false, basis }
            }
        }
        Builtin::Ambient => Bi::Ambient,
        Builtin::Diffuse => Bi::Diffuse,
        Builtin::Specular => Bi::Specular,
        Builtin::SpecularBrdf => Bi::SpecularBrdf,
        Builtin::Phong => Bi::Phong,
        Builtin::Trace => Bi::Trace,
        Builtin::Texture | Builtin::Environment | Builtin::Shadow => {
            let kind = match builtin {
                Builtin::Texture => texture::Kind::Texture,
                Builtin::Environment => texture::Kind::Environment,
                _ => texture::Kind::Shadow,
            };
            // Coordinates: the numeric arguments before the first parameter-list string.
            let coords = args.iter().skip(1).take_while(|a| a.0 != B::String).count() as u32;
            Bi::Texture { kind, out: rw, coords }
        }
        Builtin::Concat => Bi::Concat,
        Builtin::Format => Bi::Format,
        Builtin::Printf => Bi::Printf,
        Builtin::Match => Bi::Match,
        Builtin::Surface
        | Builtin::LightSource
        | Builtin::Displacement
        | Builtin::Atmosphere
        | Builtin::Incident
        | Builtin::Opposite
        | Builtin::Attribute
        | Builtin::Option
        | Builtin::RendererInfo => Bi::Query,
        Builtin::TextureInfo => Bi::TextureInfo,
        Builtin::RayInfo => Bi::Query,
        // Outside a scene: camera rays, nothing occludes, no indirect or caustic light.
        Builtin::RayLevel | Builtin::IsShadowRay | Builtin::IsIndirectRay | Builtin::Occlusion => Bi::Fill(0, 1),
        Builtin::IndirectDiffuse | Builtin::Caustic => Bi::Fill(0, 3),
        Builtin::Transmission => Bi::Fill(1, 3),
        Builtin::ShaderName => Bi::ShaderName,
        // Arities the checker never produces; `depth` the front end lowers to a transform.
        Builtin::Depth
        | Builtin::Log
        | Builtin::Atan
        | Builtin::Pow
        | Builtin::Mod
        | Builtin::Min
        | Builtin::Max
        | Builtin::Step
        | Builtin::Clamp
        | Builtin::Mix
        | Builtin::SmoothStep => {
            let _ = consts;
            return None;
        }
    })
}

fn un<F: ShadingFloat>(u: Un, x: F) -> F {
    match u {
        Un::Abs => x.abs(),
        Un::Sign => sign(x),
        Un::Floor => x.floor(),
        Un::Ceil => x.ceil(),
        Un::Round => x.round(),
        Un::Sqrt => x.sqrt(),
        Un::InvSqrt => inversesqrt(x),
        Un::Exp => x.exp(),
        Un::Log => x.ln(),
        Un::Sin => x.sin(),
        Un::Cos => x.cos(),
        Un::Tan => x.tan(),
        Un::Asin => x.asin(),
        Un::Acos => x.acos(),
        Un::Atan => x.atan(),
        Un::Radians => radians(x),
        Un::Degrees => degrees(x),
    }
}

fn bin<F: ShadingFloat>(b: Bin, x: F, y: F) -> F {
    match b {
        Bin::Pow => x.pow(y),
        Bin::Atan2 => x.atan2(y),
        Bin::LogBase => log_base(x, y),
        Bin::Mod => fmod(x, y),
        Bin::Min => x.min(y),
        Bin::Max => x.max(y),
        Bin::Step => step(x, y),
    }
}

fn domain<F: ShadingFloat>(fr: &Frame<F>, args: &[Loc], dims: u8, k: usize) -> NoiseDomain<F> {
    match dims {
        1 => NoiseDomain::D1(fr.get(args[0].off(), k)),
        2 => NoiseDomain::D2(fr.get(args[0].off(), k), fr.get(args[1].off(), k)),
        3 => NoiseDomain::D3(fr.vec3(args[0].off(), k)),
        _ => NoiseDomain::D4(fr.vec3(args[0].off(), k), fr.get(args[1].off(), k)),
    }
}

fn space_str<F: ShadingFloat>(fr: &Frame<F>, l: Loc) -> &str {
    match l {
        Loc::Str(i, _) => fr.s[i as usize].as_str(),
        _ => "",
    }
}

/// Runs built-in `f` for chunk `k` with live lanes `m`.
#[allow(clippy::too_many_arguments, clippy::too_many_lines)]
pub fn call<F: ShadingFloat, C: ShadingContext<F>>(
    fr: &mut Frame<F>,
    ctx: Option<&mut C>,
    f: Bi,
    dst: Loc,
    args: &[Loc],
    outs: &[Option<Loc>],
    k: usize,
    m: F::Mask,
) {
    let d = dst.off();
    let a = |i: usize| args.get(i).map_or(0, |l| l.off());
    let aw = |i: usize| args.get(i).map_or(1, |l| l.width());
    macro_rules! set3 {
        ($v:expr) => {{
            let v = $v;
            fr.set3(d, k, [v.x, v.y, v.z]);
        }};
    }
    macro_rules! setc {
        ($v:expr) => {{
            let v = $v;
            fr.set3(d, k, [v.r, v.g, v.b]);
        }};
    }
    let out_write = |fr: &mut Frame<F>, i: usize, vals: &[F]| {
        if let Some(Some(l)) = outs.get(i) {
            fr.write(l.off(), k, m, vals);
        }
    };
    match f {
        Bi::Un(u, w) => {
            for c in 0..w {
                let v = un(u, fr.get(a(0) + c, k));
                fr.set(d + c, k, v);
            }
        }
        Bi::Bin(b, w, sb) => {
            let sa = aw(0) == 1;
            let sb = sb || aw(1) == 1;
            for c in 0..w {
                let x = fr.get(if sa { a(0) } else { a(0) + c }, k);
                let y = fr.get(if sb { a(1) } else { a(1) + c }, k);
                let mut v = bin(b, x, y);
                // min/max with more than two arguments fold left.
                for j in 2..args.len() {
                    let z = fr.get(if aw(j) == 1 { a(j) } else { a(j) + c }, k);
                    v = bin(b, v, z);
                }
                fr.set(d + c, k, v);
            }
        }
        Bi::Clamp(w, _) => {
            for c in 0..w {
                let g = |i: usize| fr.get(if aw(i) == 1 { a(i) } else { a(i) + c }, k);
                // `min(x, hi)` first, then `max(·, lo)`: the same as `clamp` when lo ≤ hi, and lo
                // when the bounds cross — so loops that step by `clamp (ss, minstep, end - d)`
                // (ARMan's smoke.sl, cellclouds.sl) still advance at the end, as in PRMan.
                let v = g(0).min(g(2)).max(g(1));
                fr.set(d + c, k, v);
            }
        }
        Bi::Mix(w, _) => {
            for c in 0..w {
                let g = |i: usize| fr.get(if aw(i) == 1 { a(i) } else { a(i) + c }, k);
                let v = mix(g(0), g(1), g(2));
                fr.set(d + c, k, v);
            }
        }
        Bi::Smoothstep(w) => {
            for c in 0..w {
                let g = |i: usize| fr.get(if aw(i) == 1 { a(i) } else { a(i) + c }, k);
                let v = smoothstep(g(0), g(1), g(2));
                fr.set(d + c, k, v);
            }
        }
        Bi::Length => {
            let v = fr.vec3(a(0), k).length();
            fr.set(d, k, v);
        }
        Bi::Normalize => set3!(fr.vec3(a(0), k).normalize()),
        Bi::Distance => {
            let v = distance(fr.vec3(a(0), k), fr.vec3(a(1), k));
            fr.set(d, k, v);
        }
        Bi::Faceforward(three) => {
            let nref = if three { fr.vec3(a(2), k) } else { ctx.map_or_else(|| fr.vec3(a(0), k), |c| c.globals().Ng) };
            set3!(faceforward(fr.vec3(a(0), k), fr.vec3(a(1), k), nref));
        }
        Bi::Reflect => set3!(reflect(fr.vec3(a(0), k), fr.vec3(a(1), k))),
        Bi::Refract => set3!(refract(fr.vec3(a(0), k), fr.vec3(a(1), k), fr.get(a(2), k))),
        Bi::Fresnel => {
            let r = fresnel(fr.vec3(a(0), k), fr.vec3(a(1), k), fr.get(a(2), k));
            out_write(fr, 3, &[r.kr]);
            out_write(fr, 4, &[r.kt]);
            out_write(fr, 5, &[r.r.x, r.r.y, r.r.z]);
            out_write(fr, 6, &[r.t.x, r.t.y, r.t.z]);
        }
        Bi::Ptlined => {
            let v = ptlined(fr.vec3(a(0), k), fr.vec3(a(1), k), fr.vec3(a(2), k));
            fr.set(d, k, v);
        }
        Bi::Rotate => set3!(rotate(fr.vec3(a(0), k), fr.get(a(1), k), fr.vec3(a(2), k), fr.vec3(a(3), k))),
        Bi::Comp(_) => {
            let i = fr.get(a(1), k).floor().max(F::c(0.0)).min(F::c(2.0));
            let v = fr.vec3(a(0), k);
            let r = F::select(i.eq(F::c(0.0)), v.x, F::select(i.eq(F::c(1.0)), v.y, v.z));
            fr.set(d, k, r);
        }
        Bi::SetComp(_) => {
            // setcomp(output c, i, x): the first argument is the output slot.
            // setcomp(output c, i, x): the inputs are (i, x).
            if let Some(Some(l)) = outs.first() {
                let i = fr.get(a(0), k).floor();
                let x = fr.get(a(1), k);
                for c in 0..3u32 {
                    let hit = m & i.eq(F::c(f64::from(c)));
                    if hit.any() {
                        fr.write(l.off() + c, k, hit, &[x]);
                    }
                }
            }
        }
        Bi::Xcomp(c) => {
            let v = fr.get(a(0) + c, k);
            fr.set(d, k, v);
        }
        Bi::SetXcomp(c) => {
            if let Some(Some(l)) = outs.first() {
                let x = fr.get(a(0), k);
                fr.write(l.off() + c, k, m, &[x]);
            }
        }
        Bi::MComp => {
            let (r, c) = (fr.get(a(1), k).lane(0) as u32, fr.get(a(2), k).lane(0) as u32);
            let v = fr.get(a(0) + (r.min(3) * 4 + c.min(3)), k);
            fr.set(d, k, v);
        }
        Bi::MSetComp => {
            if let Some(Some(l)) = outs.first() {
                let (r, c) = (fr.get(a(0), k).lane(0) as u32, fr.get(a(1), k).lane(0) as u32);
                let x = fr.get(a(2), k);
                fr.write(l.off() + r.min(3) * 4 + c.min(3), k, m, &[x]);
            }
        }
        Bi::Transform(xf, matrix, spaces) => {
            let last = args.len() - 1;
            let v = fr.vec3(a(last), k);
            let table = ctx.as_deref().map_or(anysl_core::Spaces::standard(), |c| c.spaces());
            let apply = |mx: &Matrix4<F>, v: Vec3<F>| match xf {
                Xf::Point => mx.transform_point(v),
                Xf::Vector => mx.transform_vector(v),
                Xf::Normal => mx.transform_normal(v),
            };
            let r = if matrix {
                // transform([fromspace,] m, p): from `fromspace` to current, then by `m`.
                let mi = args.iter().position(|l| l.width() == 16).unwrap_or(0);
                let v = if spaces == 1 { apply(&table.to_current(space_str(fr, args[0])), v) } else { v };
                apply(&fr.matrix(a(mi), k), v)
            } else if spaces == 2 {
                apply(&table.between(space_str(fr, args[0]), space_str(fr, args[1])), v)
            } else {
                apply(&table.from_current(space_str(fr, args[0])), v)
            };
            set3!(r);
        }
        Bi::Ctransform(spaces) => {
            let c = fr.color(a(spaces as usize), k);
            let from = if spaces == 2 { ColorSpace::from_name(space_str(fr, args[0])) } else { Some(ColorSpace::Rgb) };
            let to = ColorSpace::from_name(space_str(fr, args[spaces as usize - 1]));
            let r = match (from, to) {
                (Some(f), Some(t)) => ctransform(f, t, c),
                _ => c,
            };
            setc!(r);
        }
        Bi::Determinant => {
            let v = fr.matrix(a(0), k).determinant();
            fr.set(d, k, v);
        }
        Bi::Translate => {
            let r = fr.matrix(a(0), k) * Matrix4::translate(fr.vec3(a(1), k));
            fr.set_matrix(d, k, &r);
        }
        Bi::RotateM => {
            let r = fr.matrix(a(0), k) * Matrix4::rotate(fr.get(a(1), k), fr.vec3(a(2), k));
            fr.set_matrix(d, k, &r);
        }
        Bi::ScaleM => {
            let r = fr.matrix(a(0), k) * Matrix4::scale(fr.vec3(a(1), k));
            fr.set_matrix(d, k, &r);
        }
        Bi::Du(w) | Bi::Dv(w) => {
            let is_u = matches!(f, Bi::Du(_));
            let Some(ctx) = ctx else {
                for c in 0..w {
                    fr.set(d + c, k, F::c(0.0));
                }
                return;
            };
            let g = *ctx.globals();
            for c in 0..w {
                let x = fr.get(a(0) + c, k);
                let v = if is_u { du(&g, x) } else { dv(&g, x) };
                fr.set(d + c, k, v);
            }
        }
        Bi::Deriv(w) => {
            let Some(ctx) = ctx else { return };
            let g = *ctx.globals();
            let den = fr.get(a(1), k);
            for c in 0..w {
                let v = deriv(&g, fr.get(a(0) + c, k), den);
                fr.set(d + c, k, v);
            }
        }
        Bi::Area => {
            let v = area(fr.vec3(a(0), k));
            fr.set(d, k, v);
        }
        Bi::CalcNormal => {
            let Some(ctx) = ctx else { return };
            let g = *ctx.globals();
            set3!(calculatenormal(&g, fr.vec3(a(0), k)));
        }
        Bi::FilterWidth(w) => {
            let v = if w == 3 { filterwidth_point(fr.vec3(a(0), k)) } else { filterwidth(fr.get(a(0), k)) };
            fr.set(d, k, v);
        }
        Bi::FilterStep(nnum) => {
            let v = if nnum >= 3 {
                // filterstep(edge, s0, s1): box over [s0, s1].
                let (e, s0, s1) = (fr.get(a(0), k), fr.get(a(1), k), fr.get(a(2), k));
                let lo = s0.min(s1);
                let wdt = (s1 - s0).abs();
                let t = clamp((lo + wdt - e) / wdt.max(F::c(1e-30)), F::c(0.0), F::c(1.0));
                F::select(wdt.gt(F::c(0.0)), t, step(e, s0))
            } else {
                filterstep(fr.get(a(0), k), fr.get(a(1), k))
            };
            fr.set(d, k, v);
        }
        Bi::FilteredPulse => fr.set(d, k, filteredpulse(fr.get(a(0), k), fr.get(a(1), k), fr.get(a(2), k))),
        Bi::Noise { dims, out, signed } => {
            let dm = domain(fr, args, dims, k);
            if out == 1 {
                let v = if signed { snoise(dm) } else { noise(dm) };
                fr.set(d, k, v);
            } else {
                set3!(if signed { vsnoise(dm) } else { vnoise(dm) });
            }
        }
        Bi::PNoise { dims, out, signed } => {
            let half = args.len() / 2;
            let dm = domain(fr, &args[..half], dims, k);
            let per = domain(fr, &args[half..], dims, k);
            if out == 1 {
                let v = if signed { psnoise(dm, per) } else { pnoise(dm, per) };
                fr.set(d, k, v);
            } else {
                let v = vpnoise(dm, per);
                let v = if signed { v * F::c(2.0) - Vec3::splat(F::c(1.0)) } else { v };
                set3!(v);
            }
        }
        Bi::CellNoise { dims, out } => {
            let dm = domain(fr, args, dims, k);
            if out == 1 {
                let v = cellnoise(dm);
                fr.set(d, k, v);
            } else {
                set3!(vcellnoise(dm));
            }
        }
        Bi::Fbm { dims } | Bi::Turbulence { dims } => {
            let dm = domain(fr, args, dims, k);
            let used = match dims {
                1 | 3 => 1,
                _ => 2,
            };
            let oct = args.get(used).map_or(6.0, |l| fr.get(l.off(), k).lane(0)).max(0.0) as u32;
            let lac = args.get(used + 1).map_or(2.0, |l| fr.get(l.off(), k).lane(0));
            let gain = args.get(used + 2).map_or(0.5, |l| fr.get(l.off(), k).lane(0));
            let v = if matches!(f, Bi::Fbm { .. }) { fbm(dm, oct, lac, gain) } else { turbulence(dm, oct, lac, gain) };
            fr.set(d, k, v);
        }
        Bi::Random(w) => {
            // A per-point hash of the position (deterministic, so renders are repeatable).
            let p = ctx.map_or_else(Vec3::zero, |c| c.globals().P);
            for c in 0..w {
                let v = cellnoise(NoiseDomain::D4(p * F::c(1.0e4), F::c(f64::from(c) + 0.5)));
                fr.set(d + c, k, v);
            }
        }
        Bi::Spline { w, n, array, basis } => {
            let bname = if basis { space_str(fr, args[0]).to_string() } else { "catmullrom".to_string() };
            let b = SplineBasis::from_name(&bname).unwrap_or(SplineBasis::CATMULL_ROM);
            let first = usize::from(basis);
            let x = fr.get(a(first), k);
            let knot = |i: u32| -> u32 {
                if array {
                    a(first + 1) + i * w
                } else {
                    a(first + 1 + i as usize)
                }
            };
            if w == 1 {
                let knots: Vec<F> = (0..n).map(|i| fr.get(knot(i), k)).collect();
                let v = spline(&b, x, &knots);
                fr.set(d, k, v);
            } else {
                let knots: Vec<Vec3<F>> = (0..n).map(|i| fr.vec3(knot(i), k)).collect();
                set3!(spline(&b, x, &knots));
            }
        }
        Bi::Ambient => {
            let v = match ctx {
                Some(c) => c.ambient(&Exec::with_mask(m)),
                None => Color::zero(),
            };
            setc!(v);
        }
        Bi::Diffuse => {
            let v = match ctx {
                Some(c) => diffuse(c, &mut Exec::with_mask(m), fr.vec3(a(0), k)),
                None => Color::zero(),
            };
            setc!(v);
        }
        Bi::Specular => {
            let v = match ctx {
                Some(c) => specular(c, &mut Exec::with_mask(m), fr.vec3(a(0), k), fr.vec3(a(1), k), fr.get(a(2), k)),
                None => Color::zero(),
            };
            setc!(v);
        }
        Bi::Phong => {
            let v = match ctx {
                Some(c) => phong(c, &mut Exec::with_mask(m), fr.vec3(a(0), k), fr.vec3(a(1), k), fr.get(a(2), k)),
                None => Color::zero(),
            };
            setc!(v);
        }
        Bi::SpecularBrdf => {
            let v = specularbrdf(fr.vec3(a(0), k), fr.vec3(a(1), k), fr.vec3(a(2), k), fr.get(a(3), k));
            fr.set3(d, k, [v, v, v]);
        }
        Bi::Trace => {
            let v = match ctx {
                Some(c) => c.trace(&Exec::with_mask(m), fr.vec3(a(0), k), fr.vec3(a(1), k)),
                None => Color::zero(),
            };
            setc!(v);
        }
        Bi::Texture { kind, out, coords } => {
            let name = space_str(fr, args[0]).to_string();
            let g = ctx.map(|c| *c.globals());
            let n = 1 + coords as usize;
            let v = texture::lookup(fr, &name, kind, &args[1..n], args.get(n..).unwrap_or(&[]), g.as_ref(), k);
            if out == 1 {
                fr.set(d, k, v.r);
            } else {
                setc!(v);
            }
        }
        Bi::TextureInfo => {
            let (name, query) = (space_str(fr, args[0]).to_string(), space_str(fr, args[1]).to_string());
            let ok = match outs.get(2).copied().flatten() {
                Some(l) => texture::info(fr, &name, &query, l, k, m),
                None => F::c(0.0),
            };
            fr.set(d, k, ok);
        }
        Bi::Concat => {
            let s: String = args.iter().map(|l| space_str(fr, *l).to_string()).collect();
            if let Loc::Str(i, _) = dst {
                fr.s[i as usize] = s;
            }
        }
        Bi::Format | Bi::Printf => {
            let s = format_rsl(fr, args, k);
            if matches!(f, Bi::Printf) {
                if m.any() {
                    // stderr: stdout stays machine-readable (`rslc eval` prints JSON there).
                    eprint!("{s}");
                }
            } else if let Loc::Str(i, _) = dst {
                fr.s[i as usize] = s;
            }
        }
        Bi::Match => {
            let pat = space_str(fr, args[0]).to_string();
            let subj = space_str(fr, args[1]).to_string();
            let v = F::c(if simple_match(&pat, &subj) { 1.0 } else { 0.0 });
            fr.set(d, k, v);
        }
        Bi::Query => {
            fr.set(d, k, F::c(0.0));
        }
        Bi::Fill(x, width) => {
            if width == 1 {
                fr.set(d, k, F::c(f64::from(x)));
            } else {
                fr.set3(d, k, [F::c(f64::from(x)); 3]);
            }
        }
        Bi::ShaderName => {}
    }
}

/// `format`/`printf` through the one formatter generated Rust uses too.
fn format_rsl<F: ShadingFloat>(fr: &Frame<F>, args: &[Loc], k: usize) -> String {
    use anysl_rt::FmtArg;
    let fmt = space_str(fr, args[0]).to_string();
    let rest: Vec<FmtArg> = args[1..]
        .iter()
        .map(|l| match *l {
            Loc::Str(i, _) => FmtArg::Str(fr.s[i as usize].clone()),
            Loc::Num { off, width } => FmtArg::Num((0..width).map(|c| fr.get(off + c, k).lane(0)).collect()),
            Loc::Mask(m) => FmtArg::Num(vec![if fr.mask(m, k).lane(0) { 1.0 } else { 0.0 }]),
            Loc::None => FmtArg::Str(String::new()),
        })
        .collect();
    anysl_rt::format_rsl(&fmt, &rest)
}

fn simple_match(pat: &str, subj: &str) -> bool {
    anysl_rt::simple_match(pat, subj)
}
