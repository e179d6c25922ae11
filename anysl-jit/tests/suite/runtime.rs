//! Unit tests of the runtime: the host context's layout, the spline bases, and the copies
//! compiled for one selector against the general functions, the inlined noise against the
//! library's.

use anysl_core::prelude::*;
use anysl_jit::abi::{JitFloat, RtFn};
use anysl_jit::rt::{
    Bin, Geo, HostCtx, NoiseOp, NoiseSel, RtKind, Un, HOST_CTX_LIGHTS, HOST_CTX_N_LIGHTS, SPLINE_BASES,
    SPLINE_BASIS_BY_INDEX as BASES,
};
use anysl_jit::Variant;

/// The compiled code reads the lights at fixed offsets of `HostCtx` and each light's
/// fields at the offsets of `LightData` (taken from the type itself).
#[test]
fn host_ctx_lights_are_where_the_compiled_code_reads_them() {
    use core::mem::offset_of;
    type H = HostCtx<'static, anysl_simd::F32x8, ()>;
    assert_eq!(offset_of!(H, lights) as u64, HOST_CTX_LIGHTS);
    assert_eq!(offset_of!(H, n_lights) as u64, HOST_CTX_N_LIGHTS);
    type H1 = HostCtx<'static, f32, ()>;
    assert_eq!(offset_of!(H1, lights) as u64, HOST_CTX_LIGHTS);
    assert_eq!(offset_of!(H1, n_lights) as u64, HOST_CTX_N_LIGHTS);
}

#[test]
fn spline_bases_by_index_are_the_named_ones() {
    for (i, name) in SPLINE_BASES.iter().enumerate() {
        assert_eq!(Some(BASES[i]), SplineBasis::from_name(name), "{name}");
    }
}

#[test]
fn specialized_runtime_functions_compute_what_the_general_ones_do() {
    // Every specialized (kind, aux) against the general function on the same input, for
    // 8 lanes (the copies exist for 8 and 16 lanes without derivatives).
    type X = anysl_simd::F32x8;
    let n = X::STRIDE;
    let inp: Vec<f32> = (0..64 * n).map(|k| 0.37 + 0.61 * (k / n) as f32 + 0.001 * (k % n) as f32).collect();
    let mut cases: Vec<(RtKind, u32)> = Vec::new();
    cases.extend(Un::ALL.iter().map(|&a| (RtKind::Un, a as u32)));
    cases.extend(Bin::ALL.iter().map(|&a| (RtKind::Bin, a as u32)));
    cases.extend(Geo::ALL.iter().filter(|&&a| a != Geo::CTransform).map(|&a| (RtKind::Geo, a as u32)));
    for kind in [NoiseOp::Noise, NoiseOp::SNoise, NoiseOp::Cell, NoiseOp::PNoise, NoiseOp::PSNoise] {
        for dims in 1..=4 {
            for out in [1, 3] {
                cases.push((RtKind::Noise, NoiseSel { kind, dims, out, extra: 0 }.encode()));
            }
        }
    }
    for kind in [NoiseOp::Fbm, NoiseOp::Turbulence] {
        for dims in [1, 3] {
            cases.push((RtKind::Noise, NoiseSel { kind, dims, out: 1, extra: 2 }.encode()));
        }
    }
    for b in 0..6 {
        for w in [1, 3] {
            cases.push((RtKind::Spline, 5 | b << 8 | w << 16));
        }
    }
    let mut specialized = 0;
    for (kind, aux) in cases {
        // Other types have no copies: every call gets the general function.
        assert_eq!(Variant::F32.rt_addr(kind, aux), Variant::F32.rt_general_addr(kind));
        assert_eq!(Variant::DualX8.rt_addr(kind, aux), Variant::DualX8.rt_general_addr(kind));
        // SAFETY: the address of an `RtFn` (`rt_general_addr`).
        let general: RtFn = unsafe { core::mem::transmute::<usize, RtFn>(Variant::X8.rt_general_addr(kind)) };
        let addr = Variant::X8.rt_addr(kind, aux);
        if addr != general as usize {
            specialized += 1;
        }
        // SAFETY: `addr` is an `RtFn` (it comes from `rt_addr`).
        let f: RtFn = unsafe { core::mem::transmute::<usize, RtFn>(addr) };
        let (mut a, mut b) = (vec![0f32; 16 * n], vec![0f32; 16 * n]);
        unsafe {
            general(core::ptr::null_mut(), core::ptr::null(), inp.as_ptr(), a.as_mut_ptr(), aux);
            f(core::ptr::null_mut(), core::ptr::null(), inp.as_ptr(), b.as_mut_ptr(), aux);
        }
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b), "{kind:?} aux {aux:#x}");
    }
    // 99 of the cases: every one but `noise`'s eight, which the code generator compiles as
    // `snoise` (`0.5 + 0.5·snoise`), so they have no copies of their own.
    assert_eq!(specialized, 99, "calls with their own function");
    let noise3 = NoiseSel { kind: NoiseOp::Noise, dims: 3, out: 1, extra: 0 }.encode();
    assert_eq!(Variant::X8.rt_addr(RtKind::Noise, noise3), Variant::X8.rt_general_addr(RtKind::Noise));
    // A call without a specialized copy gets the general function.
    assert_eq!(
        Variant::X8.rt_addr(RtKind::Geo, Geo::CTransform as u32 | 1 << 8),
        Variant::X8.rt_general_addr(RtKind::Geo)
    );
}

/// The runtime noise, whose kernel is inlined for types without derivatives, gives the
/// library's noise bit for bit (f32 and 8 lanes; 1–3 dimensions; float and vector;
/// fBm and turbulence), including non-finite and huge coordinates.
#[test]
fn inlined_runtime_noise_is_the_library_noise() {
    fn run<F: JitFloat>(aux: u32, args: &[F], outs: usize) -> Vec<F> {
        let variant = anysl_jit::variant_of::<F>().expect("a JIT float type");
        let mut inp = vec![0f32; 8 * F::STRIDE];
        for (k, a) in args.iter().enumerate() {
            unsafe { a.write(inp.as_mut_ptr().add(k * F::STRIDE)) };
        }
        let mut out = vec![0f32; 3 * F::STRIDE];
        let f: RtFn = unsafe { core::mem::transmute::<usize, RtFn>(variant.rt_addr(RtKind::Noise, aux)) };
        unsafe { f(core::ptr::null_mut(), core::ptr::null(), inp.as_ptr(), out.as_mut_ptr(), aux) };
        (0..outs).map(|k| unsafe { F::read(out.as_ptr().add(k * F::STRIDE)) }).collect()
    }
    fn bits<F: ShadingFloat>(v: &[F]) -> Vec<u64> {
        v.iter().flat_map(|x| (0..F::LANES).map(|l| x.lane(l).to_bits())).collect()
    }
    fn check<F: JitFloat>(x: F, y: F, z: F) {
        let p = Vec3::new(x, y, z);
        let doms = [NoiseDomain::D1(x), NoiseDomain::D2(x, y), NoiseDomain::D3(p)];
        for (k, d) in doms.into_iter().enumerate() {
            let dims = k as u32 + 1;
            let args = [x, y, z];
            let a = &args[..k + 1];
            let sel = |kind: NoiseOp, out: u32| NoiseSel { kind, dims, out, extra: 0 }.encode();
            let v3 = |v: Vec3<F>| vec![v.x, v.y, v.z];
            let cases: [(u32, Vec<F>, Vec<F>); 4] = [
                (sel(NoiseOp::SNoise, 1), run(sel(NoiseOp::SNoise, 1), a, 1), vec![snoise(d)]),
                (sel(NoiseOp::Noise, 1), run(sel(NoiseOp::Noise, 1), a, 1), vec![anysl_core::prelude::noise(d)]),
                (sel(NoiseOp::SNoise, 3), run(sel(NoiseOp::SNoise, 3), a, 3), v3(vsnoise(d))),
                (sel(NoiseOp::Noise, 3), run(sel(NoiseOp::Noise, 3), a, 3), v3(vnoise(d))),
            ];
            for (aux, got, want) in cases {
                assert_eq!(bits(&got), bits(&want), "{} aux {aux:#x}", F::NAME);
            }
            let mut with_opts = a.to_vec();
            with_opts.extend([F::c(4.0), F::c(2.5), F::c(0.375)]);
            for (kind, want) in
                [(NoiseOp::Fbm, fbm(d, 4, 2.5, 0.375)), (NoiseOp::Turbulence, turbulence(d, 4, 2.5, 0.375))]
            {
                let aux = NoiseSel { kind, dims, out: 1, extra: 3 }.encode();
                assert_eq!(bits(&run(aux, &with_opts, 1)), bits(&[want]), "{} aux {aux:#x}", F::NAME);
            }
        }
    }
    let vals = [0.37f32, -5.25, 1.0e7, -3.0e-39, 12.5, f32::NAN, f32::INFINITY, 0.0];
    for (i, &x) in vals.iter().enumerate() {
        let (y, z) = (vals[(i + 3) % vals.len()], vals[(i + 5) % vals.len()]);
        check::<f32>(x, y * 0.7 + 0.1, z * 1.3 - 0.2);
    }
    let lanes = |o: usize| {
        let l: Vec<f64> = (0..8).map(|l| f64::from(vals[(l + o) % vals.len()] * (1.0 + 0.1 * o as f32))).collect();
        anysl_simd::F32x8::from_lanes(&l)
    };
    check::<anysl_simd::F32x8>(lanes(0), lanes(3), lanes(5));
}

/// The noise copies that take every packet of a multi-packet variant in one call give each
/// packet the bits of the one-packet copy, also when only some packets hold non-finite,
/// huge or denormal coordinates (their kernels take a wider path for the whole call).
#[test]
fn all_packet_noise_is_the_per_packet_noise() {
    fn call(addr: usize, inp: &[f32], out: &mut [f32], aux: u32) {
        // SAFETY: `addr` is an `RtFn` (from `rt_addr`/`rt_packets_addr`) and the buffers hold
        // the selector's arguments and results at the variant's width.
        let f: RtFn = unsafe { core::mem::transmute::<usize, RtFn>(addr) };
        unsafe { f(core::ptr::null_mut(), core::ptr::null(), inp.as_ptr(), out.as_mut_ptr(), aux) };
    }
    let odd = [f32::NAN, f32::INFINITY, -1.0e7, 3.0e-39, 2.5e9];
    let snoise3 = NoiseSel { kind: NoiseOp::SNoise, dims: 3, out: 1, extra: 0 }.encode();
    let mut checked = 0;
    for (many, one) in [(Variant::X8x4, Variant::X8)] {
        let (lanes, native) = (many.lanes() as usize, one.lanes() as usize);
        for kind in NoiseOp::ALL {
            for dims in 1..=4 {
                for out in [1, 3] {
                    let aux = NoiseSel { kind, dims, out, extra: 0 }.encode();
                    let Some(addr) = many.rt_packets_addr(RtKind::Noise, aux) else {
                        continue;
                    };
                    assert!(kind == NoiseOp::SNoise && (dims <= 3 && out == 1 || dims == 3), "{kind:?} {dims}");
                    // Argument k, lane l; the last packet alone gets the odd coordinates.
                    let n_in = dims as usize;
                    let inp: Vec<f32> = (0..n_in * lanes)
                        .map(|i| {
                            let (k, l) = (i / lanes, i % lanes);
                            if l / native == lanes / native - 1 && l % 3 == k % 3 {
                                odd[(l + k) % odd.len()]
                            } else {
                                -3.7 + 0.173 * l as f32 + 1.31 * k as f32
                            }
                        })
                        .collect();
                    let mut all = vec![0f32; out as usize * lanes];
                    call(addr, &inp, &mut all, aux);
                    for p in 0..lanes / native {
                        let part: Vec<f32> = (0..n_in)
                            .flat_map(|k| inp[k * lanes + p * native..k * lanes + (p + 1) * native].iter().copied())
                            .collect();
                        let mut want = vec![0f32; out as usize * native];
                        call(one.rt_addr(RtKind::Noise, aux), &part, &mut want, aux);
                        for c in 0..out as usize {
                            for l in 0..native {
                                let (g, w) = (all[c * lanes + p * native + l], want[c * native + l]);
                                assert_eq!(
                                    g.to_bits(),
                                    w.to_bits(),
                                    "{many:?} {kind:?} {dims}D out {out} packet {p} lane {l}"
                                );
                            }
                        }
                    }
                    checked += 1;
                }
            }
        }
        // A call without an all-packet copy, and a variant of one packet, have none.
        let cell = NoiseSel { kind: NoiseOp::Cell, dims: 3, out: 1, extra: 0 }.encode();
        assert_eq!(many.rt_packets_addr(RtKind::Noise, cell), None);
        assert_eq!(many.rt_packets_addr(RtKind::Un, Un::Sin as u32), None);
        assert_eq!(one.rt_packets_addr(RtKind::Noise, snoise3), None);
    }
    assert_eq!(checked, 4, "snoise of 1–3 dimensions, float, and of 3, triple");
    // Two 16-lane packets call per packet (their copies measured no faster).
    assert_eq!(Variant::X16x2.rt_packets_addr(RtKind::Noise, snoise3), None);
}
