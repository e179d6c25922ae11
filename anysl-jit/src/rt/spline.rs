//! Splines in the runtime ([`rt_spline`]): float or triple knots, passed by value, under one
//! of the named bases.

use super::{In, Out};
use crate::abi::JitFloat;
use anysl_core::prelude::*;
use core::ffi::c_void;
use core::mem::MaybeUninit;

/// `spline([basis,] x, knots…)`: `aux = n | basis << 8 | w << 16`.
///
/// # Safety
/// `inp` holds the arguments and `out` has room for the results that `aux` selects, as
/// consecutive `F` values (`F::STRIDE` floats each); the context and mask are not read.
pub unsafe extern "C" fn rt_spline<F: JitFloat>(
    _: *mut c_void,
    _: *const u32,
    inp: *const f32,
    out: *mut f32,
    aux: u32,
) {
    spline_op::<F>(inp, out, aux, aux >> 8);
}

/// [`rt_spline`] with basis and width (`aux >> 8`) known when the shader is compiled; the
/// number of knots still comes from `aux`.
pub(super) unsafe extern "C" fn rt_spline_k<F: JitFloat, const BW: u32>(
    _: *mut c_void,
    _: *const u32,
    inp: *const f32,
    out: *mut f32,
    aux: u32,
) {
    spline_op::<F>(inp, out, aux, BW);
}

/// The bases of [`SPLINE_BASES`](super::SPLINE_BASES), by index.
pub const BASES: [SplineBasis; 6] = [
    SplineBasis::CATMULL_ROM,
    SplineBasis::BEZIER,
    SplineBasis::BSPLINE,
    SplineBasis::HERMITE,
    SplineBasis::POWER,
    SplineBasis::LINEAR,
];

#[inline(always)]
unsafe fn spline_op<F: JitFloat>(inp: *const f32, out: *mut f32, aux: u32, bw: u32) {
    let mut i = In::<F>::new(inp);
    let mut o = Out::<F>::new(out);
    let n = (aux & 0xff) as usize;
    let b = BASES.get((bw & 0xff) as usize).copied().unwrap_or(SplineBasis::CATMULL_ROM);
    let w = (bw >> 8) & 0xff;
    let x = i.f();
    // The knots are read into uninitialized stack space: zeroing 64 colour knots (6 KiB at
    // 8 lanes) per call cost more than the spline itself.
    let n = n.min(MAX_KNOTS);
    if w == 1 {
        let mut knots = [const { MaybeUninit::<F>::uninit() }; MAX_KNOTS];
        for k in knots.iter_mut().take(n) {
            k.write(i.f());
        }
        // SAFETY: the first `n` knots were written just above.
        o.f(spline(&b, x, unsafe { assume_init(&knots[..n]) }));
    } else {
        let mut knots = [const { MaybeUninit::<Vec3<F>>::uninit() }; MAX_KNOTS];
        for k in knots.iter_mut().take(n) {
            k.write(i.v3());
        }
        // SAFETY: the first `n` knots were written just above.
        o.v3(spline(&b, x, unsafe { assume_init(&knots[..n]) }));
    }
}

/// Most knots a compiled `spline` call passes (the code generator checks).
pub const MAX_KNOTS: usize = 64;

/// `s` as initialized values.
///
/// # Safety
/// Every element of `s` is initialized.
unsafe fn assume_init<T>(s: &[MaybeUninit<T>]) -> &[T] {
    // SAFETY: `MaybeUninit<T>` has `T`'s layout and the caller vouches for initialization.
    unsafe { &*(s as *const [MaybeUninit<T>] as *const [T]) }
}
