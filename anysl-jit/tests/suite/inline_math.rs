//! The transcendentals the JIT emits inline for the SIMD variants compute the library's values
//! (`anysl-simd`'s kernels) bit for bit, edge cases included, and starball's compiled code
//! no longer calls the library for them.

use anysl_core::{Exec, Globals, PointContext, ShadingFloat, SurfaceShader};
use anysl_jit::rt::{RtKind, Un};
use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_shaders::Light;
use anysl_simd::{F32x16, F32x4, F32x8};
use std::path::PathBuf;

/// Arguments around every special case of the kernels: signed zeros, subnormals, the edges of
/// the polynomial ranges (0.6 for asin, 1 for atan), multiples of π/2, the overflow and
/// underflow of exp, the vector trigonometry's limit 2^19, huge values, infinities and NaN.
const EDGES: [f32; 40] = [
    0.0,
    -0.0,
    1.0e-45,
    -3.0e-39,
    1.175_494_4e-38,
    1.0e-20,
    0.25,
    -0.5,
    0.6,
    0.600_000_1,
    -0.75,
    1.0,
    -1.0,
    1.000_000_1,
    core::f32::consts::FRAC_PI_2,
    -core::f32::consts::FRAC_PI_2,
    2.0,
    core::f32::consts::PI,
    3.0 * core::f32::consts::FRAC_PI_2,
    -7.25,
    10.0,
    33.3,
    -88.72,
    88.72,
    89.5,
    -103.9,
    -150.0,
    127.0,
    1000.0,
    524_288.0,
    524_288.06,
    -600_000.0,
    1.0e7,
    -1.0e7,
    1.0e30,
    f32::MAX,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NAN,
    -f32::NAN,
];

/// A surface shader `name` with body `body`, compiled from source.
fn shader(name: &str, body: &str) -> JitShader {
    let src = format!("surface {name}() {{ {body} }}");
    JitShader::from_source(&format!("{name}.sl"), &src, &[], JitOptions::default()).unwrap()
}

/// The six outputs of `jit` at the points whose `s` and `t` lanes are `s` and `t`.
fn shade<F: ShadingFloat>(jit: &JitShader, s: &[f32], t: &[f32]) -> [F; 6] {
    let lanes = |v: &[f32]| F::from_lanes(&v.iter().map(|&x| f64::from(x)).collect::<Vec<_>>());
    let (s, t) = (lanes(s), lanes(t));
    let g = Globals::unit_square(s, t);
    let lights: [Light; 0] = [];
    let mut ctx = PointContext::new(g, &lights);
    let o = jit.shade(&mut ctx, &mut Exec::new());
    [o.Ci.r, o.Ci.g, o.Ci.b, o.Oi.r, o.Oi.g, o.Oi.b]
}

/// Same bits, or NaN on both sides.
fn same<F: ShadingFloat>(a: F, b: F) -> bool {
    (0..F::LANES).all(|l| {
        let (x, y) = (a.lane(l) as f32, b.lane(l) as f32);
        x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan())
    })
}

/// Every function at every width against `F`'s library function, on `EDGES` and on pairs of
/// them (`pow`, `atan2`, `log` with a base).
fn check_width<F: ShadingFloat>(unary: &JitShader, binary: &JitShader) {
    let n = EDGES.len();
    let mut checked = 0;
    for rot in [0, 7, 13, 29] {
        let mut k = 0;
        while k < n {
            let s: Vec<f32> = (0..F::LANES).map(|l| EDGES[(k + l) % n]).collect();
            let t: Vec<f32> = (0..F::LANES).map(|l| EDGES[(k + l + rot) % n]).collect();
            let lanes = |v: &[f32]| F::from_lanes(&v.iter().map(|&x| f64::from(x)).collect::<Vec<_>>());
            let (x, y) = (lanes(&s), lanes(&t));
            let want_u = [x.sin(), x.cos(), x.tan(), x.asin(), x.acos(), x.atan()];
            let want_b = [x.exp(), x.ln(), x.atan2(y), x.pow(y), x.ln() / y.ln(), y.pow(x)];
            let names = [["sin", "cos", "tan", "asin", "acos", "atan"], ["exp", "ln", "atan2", "pow", "log", "pow'"]];
            for (which, (jit, want)) in [(unary, want_u), (binary, want_b)].into_iter().enumerate() {
                let got = shade::<F>(jit, &s, &t);
                for (c, (g, w)) in got.iter().zip(&want).enumerate() {
                    let lane_vals = |v: F| (0..F::LANES).map(|l| v.lane(l) as f32).collect::<Vec<_>>();
                    assert!(
                        same(*g, *w),
                        "{} {}(s = {s:?}, t = {t:?}): jit {:?} library {:?}",
                        F::NAME,
                        names[which][c],
                        lane_vals(*g),
                        lane_vals(*w)
                    );
                    checked += 1;
                }
            }
            k += F::LANES;
        }
    }
    assert!(checked >= 4 * 12 * (n / F::LANES), "{} cases checked", checked);
}

fn kernels() -> (JitShader, JitShader) {
    let unary = shader("mathu", "Ci = color(sin(s), cos(s), tan(s)); Oi = color(asin(s), acos(s), atan(s));");
    let binary =
        shader("mathb", "Ci = color(exp(s), log(s), atan(s, t)); Oi = color(pow(s, t), log(s, t), pow(t, s));");
    (unary, binary)
}

#[test]
fn inline_transcendentals_are_the_library_bit_for_bit() {
    let (u, b) = kernels();
    check_width::<F32x4>(&u, &b);
    check_width::<F32x8>(&u, &b);
    check_width::<F32x16>(&u, &b);
    // f32 calls std's functions, as before.
    check_width::<f32>(&u, &b);
}

/// Random arguments over the ranges shaders use: the same bits as the library.
#[test]
fn inline_transcendentals_agree_on_random_arguments() {
    let (u, b) = kernels();
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for scale in [1.0f32, 4.0, 100.0, 1.0e4, 1.0e6] {
        for _ in 0..64 {
            let s: Vec<f32> = (0..8).map(|_| ((next() >> 40) as f32 / 8_388_608.0 - 1.0) * scale).collect();
            let t: Vec<f32> = (0..8).map(|_| ((next() >> 40) as f32 / 8_388_608.0 - 1.0) * 4.0).collect();
            let x = F32x8::from_lanes(&s.iter().map(|&v| f64::from(v)).collect::<Vec<_>>());
            let y = F32x8::from_lanes(&t.iter().map(|&v| f64::from(v)).collect::<Vec<_>>());
            let want = [
                [x.sin(), x.cos(), x.tan(), x.asin(), x.acos(), x.atan()],
                [x.exp(), x.ln(), x.atan2(y), x.pow(y), x.ln() / y.ln(), y.pow(x)],
            ];
            for (jit, want) in [(&u, want[0]), (&b, want[1])] {
                for (g, w) in shade::<F32x8>(jit, &s, &t).iter().zip(&want) {
                    assert!(same(*g, *w), "s = {s:?}, t = {t:?}");
                }
            }
        }
    }
}

/// Starball's `acos`, `atan2`, `sin` and `cos` are inline at every SIMD width: its optimized
/// IR calls none of the library functions for them; what remains for them is std's function
/// for arguments beyond the vector reduction, on a cold branch.
#[test]
fn starball_calls_no_library_transcendentals() {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"));
    let jit = JitShader::from_file(&dir.join("starball.sl"), &[dir.join("include")], JitOptions::default()).unwrap();
    let addrs = |v: Variant| -> Vec<(&str, usize)> {
        let a = |k, aux| v.rt_addr(k, aux);
        vec![
            ("sin", a(RtKind::Un, Un::Sin as u32)),
            ("cos", a(RtKind::Un, Un::Cos as u32)),
            ("acos", a(RtKind::Un, Un::Acos as u32)),
            ("atan2", a(RtKind::Bin, anysl_jit::rt::Bin::Atan2 as u32)),
        ]
    };
    for v in [Variant::X4, Variant::X8, Variant::X16] {
        let ir = anysl_jit::compile_with(&jit.module, &jit.values, v, &jit.opts, true).unwrap().llvm_ir.unwrap();
        for (name, addr) in addrs(v) {
            assert!(!ir.contains(&format!("i64 {addr} to")), "{v:?}: starball calls the library's {name}");
        }
        let lanes = anysl_jit::rt::rt_trig_lanes as anysl_jit::abi::RtFn as usize;
        assert!(ir.contains(&format!("i64 {lanes} to")), "{v:?}: no std fallback for large arguments");
    }
}

/// `pow` at exponents `n/2` (binary powering in the library): constant exponents (uniform in
/// the compiled code, powered under scalar branches) and varying ones mixed with other
/// exponents, against the library's bits at every width.
#[test]
fn pow_at_half_integer_exponents_is_the_library_bit_for_bit() {
    let jit = shader(
        "powh",
        "Ci = color(pow(s, 0.5), pow(s, 10), pow(s, 16.5)); Oi = color(pow(s, t), pow(s, 3), pow(s, 17));",
    );
    fn check<F: ShadingFloat>(jit: &JitShader) {
        let exps = [0.0f32, 0.5, 1.0, 2.5, 10.0, 16.0, 16.5, 17.0, -2.0, 0.25, f32::NAN, 7.5];
        let bases: Vec<f32> =
            EDGES.iter().copied().chain((0..40).map(|i| i as f32 / 39.0)).chain([1e-3, 1e-12, 200.0]).collect();
        for (k, chunk) in bases.chunks(F::LANES).enumerate() {
            let mut s = vec![0.5f32; F::LANES];
            s[..chunk.len()].copy_from_slice(chunk);
            let t: Vec<f32> = (0..F::LANES).map(|l| exps[(k + l) % exps.len()]).collect();
            let lanes = |v: &[f32]| F::from_lanes(&v.iter().map(|&x| f64::from(x)).collect::<Vec<_>>());
            let (x, y) = (lanes(&s), lanes(&t));
            let want =
                [x.pow(F::c(0.5)), x.pow(F::c(10.0)), x.pow(F::c(16.5)), x.pow(y), x.pow(F::c(3.0)), x.pow(F::c(17.0))];
            for (c, (g, w)) in shade::<F>(jit, &s, &t).iter().zip(&want).enumerate() {
                assert!(same(*g, *w), "{} output {c}: s = {s:?}, t = {t:?}", F::NAME);
            }
        }
    }
    check::<F32x4>(&jit);
    check::<F32x8>(&jit);
    check::<F32x16>(&jit);
}
