//! The context-free math of the runtime: unary functions ([`rt_un`], and [`rt_trig_lanes`]
//! for the inline trigonometry's out-of-range lanes), binary and ternary functions
//! ([`rt_bin`]), and geometry, matrices and colour spaces ([`rt_geo`]).

use super::{Bin, Geo, In, Out, Un, COLOR_SPACES};
use crate::abi::JitFloat;
use anysl_core::prelude::*;
use core::ffi::c_void;

rt_family!(
    /// Unary math, component-wise on one value.
    rt_un, rt_un_k, un_op
);

#[inline(always)]
unsafe fn un_op<F: JitFloat>(inp: *const f32, out: *mut f32, aux: u32) {
    let x = In::<F>::new(inp).f();
    let r = match Un::from_aux(aux) {
        Some(Un::Sin) => x.sin(),
        Some(Un::Cos) => x.cos(),
        Some(Un::Tan) => x.tan(),
        Some(Un::Asin) => x.asin(),
        Some(Un::Acos) => x.acos(),
        Some(Un::Atan) => x.atan(),
        Some(Un::Exp) => x.exp(),
        Some(Un::Log) => x.ln(),
        Some(Un::Sign) => sign(x),
        Some(Un::Round) => x.round(),
        Some(Un::Radians) => radians(x),
        Some(Un::Degrees) => degrees(x),
        Some(Un::InvSqrt) => inversesqrt(x),
        Some(Un::Sqrt) => x.sqrt(),
        Some(Un::Floor) => x.floor(),
        Some(Un::Ceil) => x.ceil(),
        Some(Un::Abs) => x.abs(),
        None => F::c(f64::NAN),
    };
    Out::<F>::new(out).f(r);
}

/// std's `f32` sine, cosine or tangent (`aux & 0xff`: [`Un::Sin`], [`Un::Cos`], [`Un::Tan`])
/// of the lanes that `mask` selects, out of `aux >> 8` lanes (the others are copied): the path
/// of the inline trigonometry for arguments beyond the vector reduction's range, as the
/// SIMD types take it.
///
/// # Safety
/// `mask`, `inp` and `out` each hold `aux >> 8` lanes.
pub unsafe extern "C" fn rt_trig_lanes(_: *mut c_void, mask: *const u32, inp: *const f32, out: *mut f32, aux: u32) {
    let f: fn(f32) -> f32 = match Un::from_aux(aux & 0xff) {
        Some(Un::Sin) => f32::sin,
        Some(Un::Cos) => f32::cos,
        Some(Un::Tan) => f32::tan,
        _ => |_| f32::NAN,
    };
    for i in 0..(aux >> 8) as usize {
        let x = *inp.add(i);
        *out.add(i) = if *mask.add(i) != 0 { f(x) } else { x };
    }
}

rt_family!(
    /// Binary and ternary math on floats.
    rt_bin, rt_bin_k, bin_op
);

#[inline(always)]
unsafe fn bin_op<F: JitFloat>(inp: *const f32, out: *mut f32, aux: u32) {
    let mut i = In::<F>::new(inp);
    let a = i.f();
    let b = i.f();
    let r = match Bin::from_aux(aux) {
        Some(Bin::Pow) => a.pow(b),
        Some(Bin::Atan2) => a.atan2(b),
        Some(Bin::LogBase) => log_base(a, b),
        Some(Bin::Mod) => fmod(a, b),
        Some(Bin::Min) => a.min(b),
        Some(Bin::Max) => a.max(b),
        Some(Bin::Step) => step(a, b),
        Some(Bin::SmoothStep) => smoothstep(a, b, i.f()),
        Some(Bin::Clamp) => clamp(a, b, i.f()),
        Some(Bin::Mix) => mix(a, b, i.f()),
        Some(Bin::FilterStep) => filterstep(a, b),
        Some(Bin::FilterStep3) => {
            // filterstep(edge, s0, s1): box over [s0, s1] (as the interpreter).
            let (e, s0, s1) = (a, b, i.f());
            let lo = s0.min(s1);
            let wdt = (s1 - s0).abs();
            let t = clamp((lo + wdt - e) / wdt.max(F::c(1e-30)), F::c(0.0), F::c(1.0));
            F::select(wdt.gt(F::c(0.0)), t, step(e, s0))
        }
        None => F::c(f64::NAN),
    };
    Out::<F>::new(out).f(r);
}

rt_family!(
    /// Geometry, matrices and colour spaces.
    rt_geo, rt_geo_k, geo_op
);

#[inline(always)]
unsafe fn geo_op<F: JitFloat>(inp: *const f32, out: *mut f32, aux: u32) {
    let mut i = In::<F>::new(inp);
    let mut o = Out::<F>::new(out);
    match Geo::from_aux(aux & 0xff) {
        Some(Geo::Length) => o.f(i.v3().length()),
        Some(Geo::Normalize) => o.v3(i.v3().normalize()),
        Some(Geo::Distance) => {
            let a = i.v3();
            o.f(distance(a, i.v3()));
        }
        Some(Geo::FaceForward) => {
            let (n, ii) = (i.v3(), i.v3());
            o.v3(faceforward(n, ii, i.v3()));
        }
        Some(Geo::Reflect) => {
            let a = i.v3();
            o.v3(reflect(a, i.v3()));
        }
        Some(Geo::Refract) => {
            let (a, n) = (i.v3(), i.v3());
            o.v3(refract(a, n, i.f()));
        }
        Some(Geo::Fresnel) => {
            let (a, n) = (i.v3(), i.v3());
            let r = fresnel(a, n, i.f());
            o.f(r.kr);
            o.f(r.kt);
            o.v3(r.r);
            o.v3(r.t);
        }
        Some(Geo::PtLineD) => {
            let (a, b) = (i.v3(), i.v3());
            o.f(ptlined(a, b, i.v3()));
        }
        Some(Geo::Rotate) => {
            let (q, ang, p0) = (i.v3(), i.f(), i.v3());
            o.v3(rotate(q, ang, p0, i.v3()));
        }
        Some(Geo::SpecularBrdf) => {
            let (l, n, v) = (i.v3(), i.v3(), i.v3());
            let r = specularbrdf(l, n, v, i.f());
            o.v3(Vec3::splat(r));
        }
        Some(Geo::Area) => o.f(area(i.v3())),
        Some(Geo::FilterWidthP) => o.f(filterwidth_point(i.v3())),
        Some(Geo::FilterWidth) => o.f(filterwidth(i.f())),
        Some(Geo::MatMul | Geo::MatDiv) => {
            let a = i.m4();
            let b = i.m4();
            let b = if aux & 0xff == Geo::MatDiv as u32 { b.inverse() } else { b };
            o.m4(&(a * b));
        }
        Some(Geo::Determinant) => o.f(i.m4().determinant()),
        Some(Geo::Translate) => {
            let m = i.m4();
            o.m4(&(m * Matrix4::translate(i.v3())));
        }
        Some(Geo::RotateM) => {
            let m = i.m4();
            let a = i.f();
            o.m4(&(m * Matrix4::rotate(a, i.v3())));
        }
        Some(Geo::ScaleM) => {
            let m = i.m4();
            o.m4(&(m * Matrix4::scale(i.v3())));
        }
        Some(Geo::XformPoint) => {
            let m = i.m4();
            o.v3(m.transform_point(i.v3()));
        }
        Some(Geo::XformVector) => {
            let m = i.m4();
            o.v3(m.transform_vector(i.v3()));
        }
        Some(Geo::XformNormal) => {
            let m = i.m4();
            o.v3(m.transform_normal(i.v3()));
        }
        Some(Geo::CTransform) => {
            let c = i.c3();
            let space = |k: u32| COLOR_SPACES.get(k as usize).and_then(|n| ColorSpace::from_name(n));
            let r = match (space((aux >> 8) & 0xff), space((aux >> 16) & 0xff)) {
                (Some(f), Some(t)) => ctransform(f, t, c),
                _ => c,
            };
            o.c3(r);
        }
        None => {}
    }
}
