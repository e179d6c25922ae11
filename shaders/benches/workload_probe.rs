//! Timing probe for the shared workload's ahead-of-time rows (`anysl bench workload` runs the
//! full table; this builds in a fraction of the time): every shader × `VARIANTS`
//! (default: all), one thread, round-robin: the median and the best of `ROUNDS` calls
//! (default 31), with each row's max abs error against the reference. On a shared machine the
//! best call is the steadier figure for comparing builds.
//!
//! `cargo bench -p anysl-shaders --bench workload_probe`; `SHADERS=plastic,wood` selects.

use anysl_core::{LightData, ShadingFloat};
use anysl_shaders::workload::reference::{self, ProbeRun};
use anysl_shaders::workload::{self, WorkloadScene, WorkloadShader};
use anysl_simd::{F32x16, F32x8, Pair};

type Run = fn(&WorkloadScene, &WorkloadShader, &[LightData], &mut [Vec<f32>; 3]);

fn run<F: ShadingFloat>(s: &WorkloadScene, sh: &WorkloadShader, l: &[LightData], out: &mut [Vec<f32>; 3]) {
    let [r, g, b] = out;
    s.shade::<F, LightData>(sh, l, 0, [r, g, b]);
}

fn main() {
    let env = |k: &str| std::env::var(k).ok();
    let rounds: usize = env("ROUNDS").and_then(|s| s.parse().ok()).unwrap_or(31);
    let variants: Vec<String> = env("VARIANTS")
        .unwrap_or_else(|| "f32x8,f32x16,f32x8x2,f32x16x2,st-x8,st-x16".into())
        .split(',')
        .map(str::to_string)
        .collect();
    let shaders: Vec<String> = env("SHADERS")
        .map(|s| s.split(',').map(str::to_string).collect())
        .unwrap_or_else(|| WorkloadShader::NAMES.iter().map(|s| s.to_string()).collect());
    let all: [(&str, Run); 19] = [
        ("f32x8", run::<F32x8>),
        ("f32x16", run::<F32x16>),
        ("f32x8x2", run::<Pair<F32x8>>),
        ("f32x16x2", run::<Pair<F32x16>>),
        ("f32x8x4", run::<Pair<Pair<F32x8>>>),
        ("f32x16x4", run::<Pair<Pair<F32x16>>>),
        ("st-x8", straight::<F32x8>),
        ("st-x16", straight::<F32x16>),
        ("pow-x8", micro_pow::<F32x8>),
        ("pow-x16", micro_pow::<F32x16>),
        ("nrm-x8", micro_norm::<F32x8>),
        ("nrm-x16", micro_norm::<F32x16>),
        ("dr-x16", straight_dr::<true, true, false, false>),
        ("dr-x16-div", straight_dr::<false, true, false, false>),
        ("dr-x16-ourpow", straight_dr::<true, false, false, false>),
        ("dr-x16-both", straight_dr::<false, false, false, false>),
        ("dr-x16-both-norm", straight_dr::<false, false, true, false>),
        ("dr-x16-both-max", straight_dr::<false, false, false, true>),
        ("dr-x16-all", straight_dr::<false, false, true, true>),
    ];
    let runs: Vec<(&str, Run)> = all.into_iter().filter(|(n, _)| variants.iter().any(|v| v == n)).collect();
    let scene = WorkloadScene::new();
    let lights = workload::light_data();
    for name in &shaders {
        let sh = WorkloadShader::by_name(name).expect("a workload shader");
        let reference = reference::load_reference(sh.name()).expect("reference");
        let (scene, sh, lights) = (&scene, &sh, &lights);
        let rows: Vec<ProbeRun<'_>> =
            runs.iter().map(|&(v, f)| -> ProbeRun<'_> { (v, Box::new(move |o| f(scene, sh, lights, o))) }).collect();
        reference::probe_rounds(scene, name, &reference, &rows, rounds);
    }
}

/// Straight-line plastic with both lights unrolled (no context, no masks): what the math
/// alone costs.
#[inline(never)]
fn straight<F: ShadingFloat>(s: &WorkloadScene, _sh: &WorkloadShader, l: &[LightData], out: &mut [Vec<f32>; 3]) {
    use anysl_core::{Color, Vec3};
    let [ro, go, bo] = out;
    let inp = s.inputs_f32();
    let lp: [[f32; 3]; 2] = [l[0].pos, l[1].pos];
    let lc: [[f32; 3]; 2] = [l[0].cl, l[1].cl];
    let mut i = 0;
    while i + F::LANES <= ro.len() {
        let ld = |k: usize| F::load(&inp[k][i..]);
        let p = Vec3::new(ld(0), ld(1), ld(2));
        let n = Vec3::new(ld(3), ld(4), ld(5)).normalize();
        let v = -(-Vec3::new(ld(6), ld(7), ld(8))).normalize();
        let zero = F::c(0.0);
        let e = F::c(12.5);
        let mut diff = Color::<F>::zero();
        let mut spec = Color::<F>::zero();
        for j in 0..2 {
            let lpos = Vec3::new(F::c(lp[j][0] as f64), F::c(lp[j][1] as f64), F::c(lp[j][2] as f64));
            let cl = Color::new(F::c(lc[j][0] as f64), F::c(lc[j][1] as f64), F::c(lc[j][2] as f64));
            let lu = (lpos - p).normalize();
            let ndl = lu.dot(n);
            diff = diff + cl * ndl.max(zero);
            let h = lu + v;
            let h2 = h.dot(h);
            let ndh = (n.dot(h) * F::select(h2.gt(zero), F::c(1.0) / h2.sqrt(), zero)).max(zero);
            let sp = ndh.pow(e);
            spec = spec + cl * F::select(ndl.gt(zero), sp, zero);
        }
        let ca = Color::new(F::c(0.08), F::c(0.08), F::c(0.10));
        let cs = Color::new(F::c(0.8), F::c(0.25), F::c(0.15));
        let c = cs * (ca + diff * F::c(0.8)) + spec * F::c(0.5);
        c.r.store(&mut ro[i..]);
        c.g.store(&mut go[i..]);
        c.b.store(&mut bo[i..]);
        i += F::LANES;
    }
}

/// Micro: one `pow` per point (x from the normal's z, y = 12.5).
#[inline(never)]
fn micro_pow<F: ShadingFloat>(s: &WorkloadScene, _sh: &WorkloadShader, _l: &[LightData], out: &mut [Vec<f32>; 3]) {
    let inp = s.inputs_f32();
    let mut i = 0;
    while i + F::LANES <= out[0].len() {
        let x = F::load(&inp[5][i..]).abs();
        x.pow(F::c(12.5)).store(&mut out[0][i..]);
        i += F::LANES;
    }
}

/// Micro: one normalize per point.
#[inline(never)]
fn micro_norm<F: ShadingFloat>(s: &WorkloadScene, _sh: &WorkloadShader, _l: &[LightData], out: &mut [Vec<f32>; 3]) {
    use anysl_core::Vec3;
    let inp = s.inputs_f32();
    let mut i = 0;
    while i + F::LANES <= out[0].len() {
        let v = Vec3::new(F::load(&inp[0][i..]), F::load(&inp[1][i..]), F::load(&inp[2][i..])).normalize();
        (v.x + v.y + v.z).store(&mut out[0][i..]);
        i += F::LANES;
    }
}

mod drlike {
    use wide::{f32x16, i32x16};
    #[inline(always)]
    fn k(v: f32) -> f32x16 {
        f32x16::splat(v)
    }
    #[inline(always)]
    fn fma(a: f32x16, b: f32x16, c: f32x16) -> f32x16 {
        a.mul_add(b, c)
    }
    #[inline(always)]
    pub fn rsqrt(x: f32x16) -> f32x16 {
        use core::arch::x86_64::*;
        let y: f32x16 = unsafe { core::mem::transmute(_mm512_rsqrt14_ps(core::mem::transmute(x))) };
        let h = x * k(0.5);
        let e = fma(-h, y * y, k(0.5));
        fma(y, e, y)
    }
    /// pow for x in [0, 1] normal-or-zero, y > 0: f32 log2 (Estrin), f32 exp2 (Estrin), one-step ldexp.
    #[inline(always)]
    pub fn pow(x: f32x16, y: f32x16) -> f32x16 {
        let zero = x.simd_eq(k(0.0));
        let xb = zero.select(k(1.0), x);
        let u: i32x16 = wide::bytemuck::cast(xb);
        let ei: i32x16 = (u - i32x16::splat(0x3f35_04f3)) >> 23_u32;
        let m: f32x16 = wide::bytemuck::cast(u - (ei << 23_u32));
        let e = ei.round_float();
        let f = m - k(1.0);
        let f2 = f * f;
        let f4 = f2 * f2;
        let c = [
            1.442695022e+00f32,
            -7.213474512e-01,
            4.809107482e-01,
            -3.606932759e-01,
            2.879032493e-01,
            -2.391698807e-01,
            2.160782218e-01,
            -2.058618814e-01,
            1.231096834e-01,
        ];
        let p01 = fma(f, k(c[1]), k(c[0]));
        let p23 = fma(f, k(c[3]), k(c[2]));
        let p45 = fma(f, k(c[5]), k(c[4]));
        let p67 = fma(f, k(c[7]), k(c[6]));
        let p03 = fma(f2, p23, p01);
        let p47 = fma(f2, p67, p45);
        let p48 = fma(f4, k(c[8]), p47);
        let q = fma(f4, p48, p03);
        let l = fma(f, q, e);
        let t = (y * l).max(k(-150.0));
        let n = t.round();
        let r = t - n;
        let q7 = [
            6.931471825e-1f32,
            2.402265072e-1,
            5.550410971e-2,
            9.618056938e-3,
            1.333350199e-3,
            1.546146814e-4,
            1.529734072e-5,
        ];
        let r2 = r * r;
        let a01 = fma(r, k(q7[1]), k(q7[0]));
        let a23 = fma(r, k(q7[3]), k(q7[2]));
        let a45 = fma(r, k(q7[5]), k(q7[4]));
        let a03 = fma(r2, a23, a01);
        let a46 = fma(r2, k(q7[6]), a45);
        let qq = fma(r2 * r2, a46, a03);
        let p = fma(r, qq, k(1.0));
        let ni: i32x16 = n.round_int();
        let sc: f32x16 = wide::bytemuck::cast((ni + i32x16::splat(127)) << 23_u32);
        let res = p * sc;
        zero.select(k(0.0), res)
    }
}

/// Straight-line plastic at 16 lanes with Dr.Jit-like rsqrt and pow.
#[inline(never)]
fn straight_dr<const RSQ: bool, const DRPOW: bool, const LIBNORM: bool, const LIBMAX: bool>(
    s: &WorkloadScene,
    _sh: &WorkloadShader,
    l: &[LightData],
    out: &mut [Vec<f32>; 3],
) {
    use wide::f32x16;
    let [ro, go, bo] = out;
    let inp = s.inputs_f32();
    let ld = |k: usize, i: usize| f32x16::from(<[f32; 16]>::try_from(&inp[k][i..i + 16]).unwrap());
    let k = f32x16::splat;
    let dot = |a: [f32x16; 3], b: [f32x16; 3]| a[0].mul_add(b[0], a[1].mul_add(b[1], a[2] * b[2]));
    let rs = |x: f32x16| if RSQ { drlike::rsqrt(x) } else { f32x16::splat(1.0) / x.sqrt() };
    let norm = |a: [f32x16; 3]| {
        if LIBNORM {
            let v = anysl_core::Vec3::new(F32x16(a[0]), F32x16(a[1]), F32x16(a[2])).normalize();
            return [v.x.0, v.y.0, v.z.0];
        }
        let r = rs(dot(a, a));
        [a[0] * r, a[1] * r, a[2] * r]
    };
    let mx =
        |a: f32x16, b: f32x16| if LIBMAX { anysl_core::ShadingFloat::max(F32x16(a), F32x16(b)).0 } else { a.max(b) };
    let pw = |x: f32x16, y: f32x16| {
        if DRPOW {
            drlike::pow(x, y)
        } else {
            anysl_core::ShadingFloat::pow(F32x16(x), F32x16(y)).0
        }
    };
    let mut i = 0;
    while i + 16 <= ro.len() {
        let p = [ld(0, i), ld(1, i), ld(2, i)];
        let n = norm([ld(3, i), ld(4, i), ld(5, i)]);
        let v = norm([ld(6, i), ld(7, i), ld(8, i)]);
        let mut diff = [k(0.0); 3];
        let mut spec = [k(0.0); 3];
        for lt in &l[..2] {
            let lu = norm([k(lt.pos[0]) - p[0], k(lt.pos[1]) - p[1], k(lt.pos[2]) - p[2]]);
            let ndl = dot(lu, n);
            let w = mx(ndl, k(0.0));
            let h = [lu[0] + v[0], lu[1] + v[1], lu[2] + v[2]];
            let ndh = mx(dot(n, h) * rs(dot(h, h)), k(0.0));
            let s = ndl.simd_gt(k(0.0)).select(pw(ndh, k(12.5)), k(0.0));
            for c in 0..3 {
                diff[c] = k(lt.cl[c]).mul_add(w, diff[c]);
                spec[c] = k(lt.cl[c]).mul_add(s, spec[c]);
            }
        }
        let ca = [0.08f32, 0.08, 0.10];
        let cs = [0.8f32, 0.25, 0.15];
        let o = [&mut *ro, &mut *go, &mut *bo];
        for (c, dst) in o.into_iter().enumerate() {
            let v = k(cs[c]) * diff[c].mul_add(k(0.8), k(ca[c]));
            let v = spec[c].mul_add(k(0.5), v);
            dst[i..i + 16].copy_from_slice(&v.to_array());
        }
        i += 16;
    }
}
