//! The noise family of the runtime ([`rt_noise`]): noise, signed, cell and periodic noise
//! over one to four dimensions, fBm and turbulence, selected by a [`NoiseSel`].

use super::{In, NoiseOp, NoiseSel, Out};
use crate::abi::JitFloat;
use anysl_core::prelude::*;
use core::ffi::c_void;

unsafe fn domain<F: JitFloat>(i: &mut In<F>, dims: u32) -> NoiseDomain<F> {
    match dims {
        1 => NoiseDomain::D1(i.f()),
        2 => {
            let x = i.f();
            NoiseDomain::D2(x, i.f())
        }
        3 => NoiseDomain::D3(i.v3()),
        _ => {
            let p = i.v3();
            NoiseDomain::D4(p, i.f())
        }
    }
}

rt_family!(
    /// The noise family, fBm and turbulence.
    rt_noise, rt_noise_k, noise_op
);

#[inline(always)]
unsafe fn noise_op<F: JitFloat>(inp: *const f32, out: *mut f32, aux: u32) {
    let mut i = In::<F>::new(inp);
    let mut o = Out::<F>::new(out);
    let Some(NoiseSel { kind, dims, out: w, extra }) = NoiseSel::decode(aux) else {
        return;
    };
    let d = domain(&mut i, dims);
    // Up to three dimensions the noise is Perlin's 3D noise; for types without derivatives
    // its kernel is inlined here (`snoise_inlined`): this function already is the one
    // compiled copy for its selector, and calling the kernel out of line would add a call
    // and copies of its arguments. Same values as the library functions.
    let inlined = !F::DUAL && dims <= 3;
    match kind {
        NoiseOp::Noise | NoiseOp::SNoise if inlined => {
            let signed = kind == NoiseOp::SNoise;
            // The noise inlined like the kernel: a closure here was left out of line in one
            // build of this crate and x16 noise ran 7x slower.
            #[inline(always)]
            fn one<F: JitFloat>(d: NoiseDomain<F>, seed: u32, signed: bool) -> F {
                let s = snoise_inlined(d, seed);
                if signed {
                    s
                } else {
                    unsigned_noise(s)
                }
            }
            let n = |seed| one(d, seed, signed);
            if w == 1 {
                o.f(n(0));
            } else {
                o.v3(noise_vector(n));
            }
        }
        NoiseOp::Noise | NoiseOp::SNoise => {
            let signed = kind == NoiseOp::SNoise;
            if w == 1 {
                o.f(if signed { snoise(d) } else { anysl_core::prelude::noise(d) });
            } else {
                o.v3(if signed { vsnoise(d) } else { vnoise(d) });
            }
        }
        NoiseOp::Cell => {
            if w == 1 {
                o.f(cellnoise(d));
            } else {
                o.v3(vcellnoise(d));
            }
        }
        NoiseOp::PNoise | NoiseOp::PSNoise => {
            let per = domain(&mut i, dims);
            let signed = kind == NoiseOp::PSNoise;
            if w == 1 {
                o.f(if signed { psnoise(d, per) } else { pnoise(d, per) });
            } else {
                let v = vpnoise(d, per);
                o.v3(if signed { v * F::c(2.0) - Vec3::splat(F::c(1.0)) } else { v });
            }
        }
        NoiseOp::Fbm | NoiseOp::Turbulence => {
            let mut get = |k: u32, dflt: f64| if extra > k { i.f().lane(0) } else { dflt };
            let oct = get(0, 6.0).max(0.0) as u32;
            let lac = get(1, 2.0);
            let gain = get(2, 0.5);
            o.f(match (kind == NoiseOp::Fbm, inlined) {
                (true, true) => octave_sum(
                    d,
                    oct,
                    lac,
                    gain,
                    #[inline(always)]
                    |d| snoise_inlined(d, 0),
                ),
                (false, true) => octave_sum(
                    d,
                    oct,
                    lac,
                    gain,
                    #[inline(always)]
                    |d| snoise_inlined(d, 0).abs(),
                ),
                (true, false) => fbm(d, oct, lac, gain),
                (false, false) => turbulence(d, oct, lac, gain),
            });
        }
    }
}
