//! Every SIMD width against the scalar `f32` oracle, lane by lane: edge cases plus fixed-seed
//! random inputs for every [`ShadingFloat`] operation, masks, bits and SoA packing.
//!
//! `cargo test -p anysl-simd -- --nocapture` prints the measured accuracy per function.

use anysl_core::stdlib::{grad3, lattice_hash};
use anysl_core::{Blend, Color, LatticeBits, Mask, ShadingFloat, Vec3};
use anysl_simd::{
    pack, pack_color, pack_vec3, unpack, unpack_color, unpack_vec3, F32x16, F32x4, F32x8, Lanes, M32x16, M32x4, M32x8,
    U32x16, U32x4, U32x8,
};

/// Bound on the relative error of every transcendental against std.
const TOL: f64 = 2e-7;
/// Random inputs per function and input family.
const RANDOM: usize = 12_000;

// ---------------------------------------------------------------------------------------
// Fixed-seed random numbers (SplitMix64).

struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Rng(seed)
    }
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }
    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f32 {
        let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        (lo + (hi - lo) * u) as f32
    }
    /// Any bit pattern (all exponents, subnormals, infinities and NaNs included).
    fn bits(&mut self) -> f32 {
        f32::from_bits(self.u32())
    }
    /// Finite values with |x| spread over all exponents.
    fn finite(&mut self) -> f32 {
        loop {
            let x = self.bits();
            if x.is_finite() {
                return x;
            }
        }
    }
    fn many(&mut self, n: usize, mut f: impl FnMut(&mut Self) -> f32) -> Vec<f32> {
        (0..n).map(|_| f(self)).collect()
    }
}

/// Values every function is checked on.
fn edge_values() -> Vec<f32> {
    let mut v = vec![
        0.0,
        -0.0,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -f32::NAN,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        1e-40,
        -1e-40,
        f32::from_bits(1),
        -f32::from_bits(1),
        1e-38,
        -1e-38,
        1e7,
        -1e7,
        1e30,
        -1e30,
        f32::MAX,
        f32::MIN,
        1.0,
        -1.0,
        2.0,
        -2.0,
        3.0,
        -3.0,
        0.5,
        -0.5,
        1.0 - f32::EPSILON / 2.0,
        1.0 + f32::EPSILON,
        0.5f32.next_down(),
        -0.5f32.next_down(),
        8_388_607.5,
        -8_388_607.5,
        8_388_608.0,
        16_777_217.0,
        2_147_483_520.0,
        2_147_483_648.0,
        -2_147_483_648.0,
        -2_147_483_904.0,
        core::f32::consts::PI,
        -core::f32::consts::PI,
        core::f32::consts::FRAC_PI_2,
        core::f32::consts::FRAC_PI_4,
        88.72,
        89.0,
        -87.3,
        -103.9,
        -104.0,
        127.9,
        128.0,
        -126.0,
        -149.0,
        -150.0,
        -151.0,
        0.1,
        -0.7,
        10.0,
        100.0,
        524_287.9,
        524_289.0,
    ];
    for i in -6..=6 {
        v.push(i as f32 + 0.5);
        v.push(i as f32);
    }
    v
}

// ---------------------------------------------------------------------------------------
// Comparison against the oracle.

/// Worst case found by a check.
#[derive(Debug, Default, Clone, Copy)]
struct Stats {
    max_rel: f64,
    max_ulp: u32,
    worst: (f32, f32),
    /// Max of error / bound (1 = at the bound); for pow, error / (2e-7·max(1, |y·log2 x|)).
    max_ratio: f64,
    count: usize,
}

impl Stats {
    fn merge(&mut self, o: Stats) {
        if o.max_rel > self.max_rel {
            self.max_rel = o.max_rel;
            self.worst = o.worst;
        }
        self.max_ulp = self.max_ulp.max(o.max_ulp);
        self.max_ratio = self.max_ratio.max(o.max_ratio);
        self.count += o.count;
    }
}

/// Relative error of `got` against `want`, with an absolute floor at the smallest normal
/// (so subnormal results count in units of 2^-126) and exact agreement required for NaN,
/// infinities and the sign of zero.
fn rel_err(got: f32, want: f32, zero_sign_matters: bool) -> f64 {
    if want.is_nan() || got.is_nan() {
        return if want.is_nan() && got.is_nan() { 0.0 } else { f64::INFINITY };
    }
    if want.is_infinite() || got.is_infinite() {
        return if got == want { 0.0 } else { f64::INFINITY };
    }
    if want == 0.0 && got == 0.0 {
        let same = want.is_sign_negative() == got.is_sign_negative();
        return if same || !zero_sign_matters { 0.0 } else { f64::INFINITY };
    }
    (got as f64 - want as f64).abs() / (want.abs() as f64).max(f32::MIN_POSITIVE as f64)
}

fn ulp_diff(got: f32, want: f32) -> u32 {
    if got.is_nan() || want.is_nan() || got.is_sign_negative() != want.is_sign_negative() {
        return if got == want || (got.is_nan() && want.is_nan()) { 0 } else { u32::MAX };
    }
    got.to_bits().abs_diff(want.to_bits())
}

/// Checks a binary operation lane by lane: `tol(x, y)` bounds the relative error (0 means
/// bit-identical up to NaN payloads). Inputs are packed `LANES` at a time; the tail lanes
/// are padded (by repetition) and their results checked too.
fn check2<F: Lanes>(
    name: &str,
    xs: &[(f32, f32)],
    simd: impl Fn(F, F) -> F,
    scalar: impl Fn(f32, f32) -> f32,
    tol: impl Fn(f32, f32) -> f64,
    zero_sign_matters: bool,
) -> Stats {
    let mut st = Stats::default();
    for chunk in xs.chunks(F::LANES) {
        let a = F::gather(chunk, |p| p.0);
        let b = F::gather(chunk, |p| p.1);
        let r = simd(a, b);
        for i in 0..F::LANES {
            let (x, y) = chunk[i.min(chunk.len() - 1)];
            let got = r.lane(i) as f32;
            let want = scalar(x, y);
            let e = rel_err(got, want, zero_sign_matters);
            let bound = tol(x, y);
            assert!(
                e <= bound,
                "{} {name}({x:e}, {y:e}) lane {i}: got {got:e}, std {want:e}, rel. error {e:e} > {bound:e}",
                F::NAME
            );
            if e > st.max_rel {
                st.max_rel = e;
                st.worst = (x, y);
            }
            st.max_ulp = st.max_ulp.max(ulp_diff(got, want));
            if bound > 0.0 {
                st.max_ratio = st.max_ratio.max(e / bound);
            }
            st.count += 1;
        }
    }
    st
}

/// [`check2`] for unary operations.
fn check1<F: Lanes>(name: &str, xs: &[f32], simd: impl Fn(F) -> F, scalar: impl Fn(f32) -> f32, tol: f64) -> Stats {
    let pairs: Vec<(f32, f32)> = xs.iter().map(|&x| (x, 0.0)).collect();
    check2::<F>(name, &pairs, |a, _| simd(a), |x, _| scalar(x), |_, _| tol, true)
}

fn report(width: &str, name: &str, st: Stats) {
    println!(
        "{width:7} {name:6} max rel. error {:.3e} ({:.2} of bound), max {} ulp, worst at ({:e}, {:e}), {} lanes",
        st.max_rel, st.max_ratio, st.max_ulp, st.worst.0, st.worst.1, st.count
    );
}

// ---------------------------------------------------------------------------------------
// The suites, generic over the width.

fn unary_inputs(seed: u64, families: &[(f64, f64)]) -> Vec<f32> {
    let mut rng = Rng::new(seed);
    let mut v = edge_values();
    for &(lo, hi) in families {
        v.extend(rng.many(RANDOM, |r| r.uniform(lo, hi)));
    }
    v.extend(rng.many(RANDOM / 4, Rng::bits));
    v
}

fn pairs(seed: u64, a: &[f32], mut gen: impl FnMut(&mut Rng) -> (f32, f32)) -> Vec<(f32, f32)> {
    let mut rng = Rng::new(seed);
    let mut v: Vec<(f32, f32)> = Vec::new();
    for &x in a {
        for &y in a {
            v.push((x, y));
        }
    }
    v.extend((0..RANDOM).map(|_| gen(&mut rng)));
    v
}

fn exact_unary<F: Lanes>() {
    let mut rng = Rng::new(1);
    let mut xs = edge_values();
    xs.extend(rng.many(RANDOM, Rng::bits));
    xs.extend(rng.many(RANDOM, |r| r.uniform(-100.0, 100.0)));
    xs.extend((0..RANDOM).map(|i| (i as f32 - 6000.0) * 0.5)); // integers and halves
    xs.extend(rng.many(RANDOM, |r| r.uniform(-1e7, 1e7)));
    check1::<F>("abs", &xs, F::abs, f32::abs, 0.0);
    check1::<F>("floor", &xs, F::floor, f32::floor, 0.0);
    check1::<F>("ceil", &xs, F::ceil, f32::ceil, 0.0);
    check1::<F>("round", &xs, F::round, f32::round, 0.0);
    check1::<F>("trunc", &xs, F::trunc, f32::trunc, 0.0);
    check1::<F>("sqrt", &xs, F::sqrt, f32::sqrt, 0.0);
    // rsqrt: every lane is scalar f32's (the same estimate and Newton step), bit for bit.
    check1::<F>("rsqrt", &xs, F::rsqrt, anysl_core::rsqrt_f32, 0.0);
    check1::<F>("neg", &xs, |x| -x, |x| -x, 0.0);
    for &x in &xs {
        let c = F::c(x as f64);
        assert!((0..F::LANES).all(|i| c.lane(i).to_bits() == (x as f64).to_bits() || x.is_nan()));
    }
    let lanes: Vec<f64> = (0..F::LANES).map(|i| xs[i + 7] as f64).collect();
    let v = F::from_lanes(&lanes);
    for (i, &l) in lanes.iter().enumerate() {
        assert!(v.lane(i) == l || (l.is_nan() && v.lane(i).is_nan()));
    }
    // Bits of the lattice coordinate.
    for chunk in xs.chunks(F::LANES) {
        let b = F::gather(chunk, |x| *x).floor_bits();
        for (i, &x) in chunk.iter().enumerate() {
            assert_eq!(b.lane(i), x.floor_bits(), "floor_bits({x:e})");
        }
    }
    // The ends of the i32 range, where the conversion saturates.
    let ends = [2147483648.0f32, 2147483520.0, -2147483648.0, -2147483904.0, 4294967296.0, -0.25, f32::NAN];
    for chunk in ends.chunks(F::LANES) {
        let b = F::gather(chunk, |x| *x).floor_bits();
        for (i, &x) in chunk.iter().enumerate() {
            assert_eq!(b.lane(i), x.floor_bits(), "floor_bits({x:e})");
        }
    }
    // Bits of a cell corner: the integer modulo 2^32 up to |x| = 2^31, as the scalar type.
    let corners = [2147483648.0f32, -2147483648.0, 2147483520.0, -2147483520.0, 0.0, -0.0, -1.0, 7.0, -16777216.0];
    for chunk in corners.chunks(F::LANES) {
        let b = F::gather(chunk, |x| *x).lattice_bits();
        for (i, &x) in chunk.iter().enumerate() {
            assert_eq!(b.lane(i), (x as f64 as i64) as u32, "lattice_bits({x:e})");
            assert_eq!(b.lane(i), x.lattice_bits(), "lattice_bits({x:e})");
        }
    }
}

fn exact_binary<F: Lanes>() {
    let mut rng = Rng::new(2);
    let e = edge_values();
    let xs = pairs(3, &e, |r| (r.bits(), r.bits()));
    let ys = pairs(4, &e, |r| (r.uniform(-10.0, 10.0), r.uniform(-10.0, 10.0)));
    let exact = |_: f32, _: f32| 0.0;
    for v in [&xs, &ys] {
        check2::<F>("add", v, |a, b| a + b, |a, b| a + b, exact, true);
        check2::<F>("sub", v, |a, b| a - b, |a, b| a - b, exact, true);
        check2::<F>("mul", v, |a, b| a * b, |a, b| a * b, exact, true);
        check2::<F>("div", v, |a, b| a / b, |a, b| a / b, exact, true);
        let assign = |a: F, b: F| {
            let mut r = a;
            r += b;
            r *= b;
            r -= a;
            r /= b;
            r
        };
        let assign_s = |a: f32, b: f32| ((a + b) * b - a) / b;
        check2::<F>("assign", v, assign, assign_s, exact, true);
        // f32::min/max may return either zero for (0, -0).
        check2::<F>("min", v, F::min, f32::min, exact, false);
        check2::<F>("max", v, F::max, f32::max, exact, false);
    }
    // Comparisons, lane by lane against the scalar mask.
    let mut v = xs.clone();
    v.extend((0..RANDOM).map(|_| {
        let x = rng.uniform(-2.0, 2.0).round();
        (x, rng.uniform(-2.0, 2.0).round())
    }));
    for chunk in v.chunks(F::LANES) {
        let a = F::gather(chunk, |p| p.0);
        let b = F::gather(chunk, |p| p.1);
        for (i, &(x, y)) in chunk.iter().enumerate() {
            let ctx = format!("{} lane {i} of ({x:e}, {y:e})", F::NAME);
            assert_eq!(a.lt(b).lane(i), x < y, "lt {ctx}");
            assert_eq!(a.le(b).lane(i), x <= y, "le {ctx}");
            assert_eq!(a.gt(b).lane(i), x > y, "gt {ctx}");
            assert_eq!(a.ge(b).lane(i), x >= y, "ge {ctx}");
            assert_eq!(a.eq(b).lane(i), x == y, "eq {ctx}");
            assert_eq!(a.ne(b).lane(i), x != y, "ne {ctx}");
            assert_eq!(a.is_nan().lane(i), x.is_nan(), "is_nan {ctx}");
            let s = F::select(a.lt(b), a, b).lane(i) as f32;
            let want = if x < y { x } else { y };
            assert!(s.to_bits() == want.to_bits() || (s.is_nan() && want.is_nan()), "select {ctx}");
            let s = <F as Blend<F>>::blend(a.le(b), b, a).lane(i) as f32;
            let want = if x <= y { y } else { x };
            assert!(s.to_bits() == want.to_bits() || (s.is_nan() && want.is_nan()), "blend {ctx}");
        }
    }
}

fn bits_conversions<F: Lanes, const N: usize>()
where
    F::Bits: From<[u32; N]>,
{
    let mut rng = Rng::new(5);
    let mut hs: Vec<u32> = (0..RANDOM).map(|_| rng.u32()).collect();
    hs.extend([0, 1, 255, 256, u32::MAX, 0x8000_0000, 0x7fff_ffff, 0x8000_0001]);
    for chunk in hs.chunks(N) {
        let bits = F::Bits::from(core::array::from_fn(|i| chunk[i.min(chunk.len() - 1)]));
        for (i, &h) in chunk.iter().enumerate() {
            let u = F::bits_to_unit(bits).lane(i) as f32;
            assert_eq!(u.to_bits(), f32::bits_to_unit(h).to_bits(), "bits_to_unit({h:#x})");
            let s = F::bits_to_float_signed(bits).lane(i) as f32;
            let want = f32::bits_to_float_signed(h);
            assert_eq!(s.to_bits(), want.to_bits(), "bits_to_float_signed({h:#x})");
        }
    }
}

fn masks<F: Lanes, const N: usize>()
where
    F::Mask: From<[bool; N]> + PartialEq,
{
    assert_eq!(N, F::LANES);
    assert_eq!(<F::Mask as Mask>::LANES, N);
    let mut rng = Rng::new(6);
    for round in 0..2000 {
        let a: [bool; N] = core::array::from_fn(|_| rng.u32() & 1 == 1);
        // Every few rounds an all-true or all-false mask so that `all`/`none` are hit.
        let b: [bool; N] = match round % 4 {
            0 => [true; N],
            1 => [false; N],
            _ => core::array::from_fn(|_| rng.u32() & 1 == 1),
        };
        let (ma, mb) = (F::Mask::from(a), F::Mask::from(b));
        let and = ma & mb;
        let or = ma | mb;
        let not = !ma;
        let sel = <F::Mask as Mask>::select_mask(ma, mb, not);
        for i in 0..N {
            assert_eq!(ma.lane(i), a[i]);
            assert_eq!(and.lane(i), a[i] && b[i]);
            assert_eq!(or.lane(i), a[i] || b[i]);
            assert_eq!(not.lane(i), !a[i]);
            assert_eq!(sel.lane(i), if a[i] { b[i] } else { !a[i] });
        }
        // Bit sets: bit i is lane i, both ways (bits above the lanes ignored).
        let bits = a.iter().enumerate().fold(0u32, |m, (i, &x)| m | u32::from(x) << i);
        assert_eq!(ma.to_bits(), bits);
        assert_eq!(<F::Mask as Mask>::from_bits(bits | rng.u32() << N) == ma, true, "from_bits({bits:#x})");
        assert_eq!(mb.any(), b.iter().any(|&x| x));
        assert_eq!(mb.all(), b.iter().all(|&x| x));
        assert_eq!(mb.none(), !b.iter().any(|&x| x));
        assert_eq!(ma.any(), a.iter().any(|&x| x));
        assert_eq!(ma.all(), a.iter().all(|&x| x));
        // Masks drive float selection.
        let x = F::from_lanes(&(0..N).map(|i| i as f64).collect::<Vec<_>>());
        let y = F::c(-1.0);
        let s = F::select(ma, x, y);
        for (i, &ai) in a.iter().enumerate() {
            assert_eq!(s.lane(i), if ai { i as f64 } else { -1.0 });
        }
    }
    for b in [false, true] {
        let m = <F::Mask as Mask>::splat(b);
        assert_eq!(m, F::Mask::from([b; N]));
        assert!((0..N).all(|i| m.lane(i) == b));
    }
}

fn lattice_bits<F: Lanes, const N: usize>()
where
    F::Bits: From<[u32; N]>,
{
    let mut rng = Rng::new(7);
    for _ in 0..4000 {
        let a: [u32; N] = core::array::from_fn(|_| rng.u32());
        let mut b: [u32; N] = core::array::from_fn(|_| rng.u32());
        b[0] = a[0]; // some equal lanes for eq_mask
        let s = rng.u32() % 32;
        let (ua, ub) = (F::Bits::from(a), F::Bits::from(b));
        let add = ua.wrapping_add(ub);
        let mul = ua.wrapping_mul(ub);
        let (xor, and, or) = (ua ^ ub, ua & ub, ua | ub);
        let (shr, shl) = (ua >> s, ua << s);
        let eq = ua.eq_mask(ub);
        for i in 0..N {
            assert_eq!(ua.lane(i), a[i]);
            assert_eq!(add.lane(i), a[i].wrapping_add(b[i]));
            assert_eq!(mul.lane(i), a[i].wrapping_mul(b[i]));
            assert_eq!(xor.lane(i), a[i] ^ b[i]);
            assert_eq!(and.lane(i), a[i] & b[i]);
            assert_eq!(or.lane(i), a[i] | b[i]);
            assert_eq!(shr.lane(i), a[i] >> s);
            assert_eq!(shl.lane(i), a[i] << s);
            assert_eq!(eq.lane(i), a[i] == b[i]);
        }
        assert_eq!(F::Bits::splat(a[1]).lane(N - 1), a[1]);
        // The noise hash is the same per lane as in scalar code.
        let h = lattice_hash(&[ua, ub], 0x1234);
        for i in 0..N {
            assert_eq!(h.lane(i), lattice_hash(&[a[i], b[i]], 0x1234));
        }
        // Table lookups by the low four bits (the high bits ignored), and the noise gradient
        // against the workload's case analysis (§4.2) on every lane.
        let table: [f32; 16] = core::array::from_fn(|i| i as f32 * 0.5 - 3.0);
        let t = F::lookup16(&table, ua);
        let (x, y, z) = (rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        let g = grad3::<F>(ua, F::c(f64::from(x)), F::c(f64::from(y)), F::c(f64::from(z)));
        for i in 0..N {
            assert_eq!(t.lane(i) as f32, table[(a[i] & 15) as usize]);
            assert_eq!(g.lane(i) as f32, grad_cases(a[i], x, y, z), "grad3({:#x}) lane {i}", a[i]);
            assert_eq!(grad3::<f32>(a[i], x, y, z), grad_cases(a[i], x, y, z));
        }
    }
}

/// The workload's gradient (§4.2) as its case analysis.
fn grad_cases(h: u32, x: f32, y: f32, z: f32) -> f32 {
    let h = h & 15;
    let u = if h < 8 { x } else { y };
    let v = if h < 4 {
        y
    } else if h == 12 || h == 14 {
        x
    } else {
        z
    };
    (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
}

fn pack_roundtrip<F: Lanes>() {
    let n = F::LANES;
    for len in 1..=2 * n + 1 {
        let pts: Vec<Vec3<f32>> = (0..len).map(|i| Vec3::new(i as f32, -(i as f32) * 0.5, 1e7 + i as f32)).collect();
        let cols: Vec<Color<f32>> = (0..len).map(|i| Color::new(0.1 * i as f32, 2.0, -(i as f32))).collect();
        let vals: Vec<f32> = (0..len).map(|i| i as f32 * 3.25 - 1.0).collect();
        let mut out_p = vec![Vec3::<f32>::splat(f32::NAN); len];
        let mut out_c = vec![Color::<f32>::splat(f32::NAN); len];
        let mut out_v = vec![f32::NAN; len];
        for start in (0..len).step_by(n) {
            let end = (start + n).min(len);
            let p: Vec3<F> = pack_vec3(&pts[start..end]);
            let c: Color<F> = pack_color(&cols[start..end]);
            let v: F = pack(&vals[start..end]);
            // Padding lanes repeat the last point of the tail.
            for i in 0..n {
                let src = (start + i).min(end - 1);
                assert_eq!(p.lane(i), pts[src].lane(0));
                assert_eq!(c.lane(i), cols[src].lane(0));
                assert_eq!(v.lane(i), vals[src] as f64);
            }
            unpack_vec3(p, &mut out_p[start..end]);
            unpack_color(c, &mut out_c[start..end]);
            unpack(v, &mut out_v[start..end]);
        }
        assert_eq!(out_p, pts);
        assert_eq!(out_c, cols);
        assert_eq!(out_v, vals);
    }
}

// ---------------------------------------------------------------------------------------
// Transcendentals.

/// `rsqrt` against the exact `1/√x` over every exponent (subnormals included): within 1 ulp
/// with the 14-bit estimate, 2 with the 12-bit one; the special values exact.
fn rsqrt_accuracy<F: Lanes>() {
    let mut rng = Rng::new(40);
    let mut xs = vec![0.0f32, -0.0, f32::INFINITY, 1.0, 4.0, 0.25, f32::MIN_POSITIVE, 1e-45, 3.4e38];
    xs.extend(rng.many(RANDOM * 4, |r| r.finite().abs()));
    xs.extend(rng.many(RANDOM, |r| r.uniform(0.0, 4.0)));
    let bound = if anysl_core::RSQRT_ESTIMATE_14 { 1.0 } else { 2.0 };
    let mut worst = 0.0f64;
    for chunk in xs.chunks(F::LANES) {
        let mut buf = vec![1.0f32; F::LANES];
        buf[..chunk.len()].copy_from_slice(chunk);
        let got = F::load(&buf).rsqrt();
        for (i, &x) in chunk.iter().enumerate() {
            let want = 1.0 / f64::from(x).sqrt();
            let e = ulps(got.lane(i) as f32, if x == 0.0 && x.is_sign_negative() { f64::NEG_INFINITY } else { want });
            assert!(e <= bound, "rsqrt({x:e}) in {}: {} against {want:e}: {e} ulp", F::NAME, got.lane(i));
            worst = worst.max(e);
        }
    }
    for x in [-1.0f32, -1e-45, f32::NAN, f32::NEG_INFINITY] {
        assert!(F::c(f64::from(x)).rsqrt().lane(0).is_nan(), "rsqrt({x}) is NaN");
    }
    println!("{}: rsqrt within {worst:.3} ulp", F::NAME);
}

fn exp_family<F: Lanes>() -> [(&'static str, Stats); 4] {
    let exp_in = unary_inputs(10, &[(-104.0, 89.0), (-1.0, 1.0)]);
    let exp2_in = unary_inputs(11, &[(-151.0, 129.0), (-1.0, 1.0)]);
    let mut rng = Rng::new(12);
    let mut log_in = unary_inputs(13, &[(0.5, 2.0), (0.0, 1e3)]);
    log_in.extend(rng.many(RANDOM, |r| r.finite().abs()));
    [
        ("exp", check1::<F>("exp", &exp_in, F::exp, f32::exp, TOL)),
        ("exp2", check1::<F>("exp2", &exp2_in, F::exp2, f32::exp2, TOL)),
        ("ln", check1::<F>("ln", &log_in, F::ln, f32::ln, TOL)),
        ("log2", check1::<F>("log2", &log_in, F::log2, f32::log2, TOL)),
    ]
}

/// pow's bound: the error of y·log2 x is amplified by |y·log2 x| in the result.
fn pow_tol(x: f32, y: f32) -> f64 {
    TOL * (y as f64 * (x.abs() as f64).log2()).abs().max(1.0)
}

/// A generator of random (x, y) inputs.
type PairGen = dyn Fn(&mut Rng) -> (f32, f32);

fn pow_family<F: Lanes>() -> [(&'static str, Stats); 1] {
    let e = edge_values();
    let mut st = check2::<F>(
        "pow",
        &pairs(20, &e, |r| (r.uniform(0.0, 10.0), r.uniform(-10.0, 10.0))),
        F::pow,
        f32::powf,
        pow_tol,
        true,
    );
    let mut rng = Rng::new(21);
    let families: [&PairGen; 5] = [
        // Lighting: cosines to the power of a shininess.
        &|r| (r.uniform(0.0, 1.0), r.uniform(1.0, 1000.0)),
        // Wide range of bases, exponents keeping the result finite-ish.
        &|r| {
            let x = r.uniform(-30.0, 30.0).exp2();
            (x, r.uniform(-4.0, 4.0))
        },
        // Near 1 with large exponents.
        &|r| (r.uniform(0.99, 1.01), r.uniform(-5000.0, 5000.0)),
        // Negative bases with integer exponents (sign by parity) and non-integers (NaN).
        &|r| (r.uniform(-4.0, 0.0), r.uniform(-40.0, 40.0).round()),
        &|r| (r.uniform(-4.0, 0.0), r.uniform(-4.0, 4.0)),
    ];
    for f in families {
        let v: Vec<(f32, f32)> = (0..RANDOM).map(|_| f(&mut rng)).collect();
        st.merge(check2::<F>("pow", &v, F::pow, f32::powf, pow_tol, true));
    }
    [("pow", st)]
}

/// Results at the bottom of the subnormal range, bit for bit: `exp2` across the point
/// where its result rounds to +0 (each lane alone and beside normal lanes) and `pow` of ±0.
fn underflow_bits<F: Lanes>() {
    let xs: Vec<f32> = (-152 * 256..=-147 * 256).map(|i| i as f32 / 256.0).collect();
    for chunk in xs.chunks(F::LANES) {
        let mut lanes = vec![1.0f32; F::LANES];
        lanes[..chunk.len()].copy_from_slice(chunk);
        let got = F::load(&lanes).exp2();
        for (i, x) in chunk.iter().enumerate() {
            assert_eq!((got.lane(i) as f32).to_bits(), x.exp2().to_bits(), "exp2({x}) in {}", F::NAME);
        }
        // The same argument in every lane but the first, beside a normal one.
        for x in chunk {
            let mut mixed = vec![*x; F::LANES];
            mixed[0] = 0.5;
            let got = F::load(&mixed).exp2();
            assert_eq!((got.lane(F::LANES - 1) as f32).to_bits(), x.exp2().to_bits(), "exp2({x}) beside 0.5");
            assert_eq!((got.lane(0) as f32).to_bits(), 0.5f32.exp2().to_bits());
        }
    }
    for (x, y) in [(0.0f32, 12.5f32), (0.0, 1000.0), (0.0, 0.5), (-0.0, 3.0), (-0.0, 12.5), (1e-30, 6.0), (0.3, 100.0)]
    {
        let got = F::pow(F::c(f64::from(x)), F::c(f64::from(y)));
        for i in 0..F::LANES {
            assert_eq!((got.lane(i) as f32).to_bits(), x.powf(y).to_bits(), "pow({x}, {y}) in {}", F::NAME);
        }
    }
}

/// Error in ulps of `got` against the exact `want` (an f64 close to the true value), with the
/// ulp of the f32 nearest `want`; inf and 0 must match exactly.
fn ulps(got: f32, want: f64) -> f64 {
    let w = want as f32;
    if !w.is_finite() || w == 0.0 || !got.is_finite() || got == 0.0 {
        return if got.to_bits() == w.to_bits() || (got == 0.0 && w == 0.0) { 0.0 } else { f64::INFINITY };
    }
    let a = w.abs();
    let ulp = f64::from(f32::from_bits(a.to_bits() + 1)) - f64::from(a);
    ((f64::from(got) - want) / ulp).abs()
}

/// `pow` within `2 + 1.5·|y·log2 x|` ulps of `f64::powf`, on lighting exponents, wide
/// ranges, bases near 1 with large exponents, results in the subnormals and at the overflow
/// edge. `pow` carries the f32 error of `log2 m` (about an ulp of it) into the exponent, where
/// it is multiplied by `|y|`: ~1.3 ulp per unit of `|y·log2 x|` at worst, the rest exact
/// (a double-f32 product and exponential); prints the worst case.
fn pow_ulps<F: Lanes>() {
    let mut rng = Rng::new(22);
    let families: [&PairGen; 5] = [
        &|r| (r.uniform(0.0, 1.0), r.uniform(1.0, 1000.0)),
        &|r| (r.uniform(-30.0, 30.0).exp2(), r.uniform(-4.0, 4.0)),
        &|r| (r.uniform(0.99, 1.01), r.uniform(-5000.0, 5000.0)),
        // Results from the subnormals (2^-149) to beyond the largest float (2^128).
        &|r| (r.uniform(0.5, 2.0), r.uniform(-1.0, 1.0) * 160.0 / r.uniform(0.5, 2.0).log2().abs().max(0.01)),
        &|r| (r.uniform(-4.0, -0.0), r.uniform(-40.0, 40.0).round()),
    ];
    let mut worst = 0.0f64;
    for f in families {
        let v: Vec<(f32, f32)> = (0..RANDOM).map(|_| f(&mut rng)).collect();
        for chunk in v.chunks(F::LANES) {
            let mut xs = vec![1.0f32; F::LANES];
            let mut ys = vec![1.0f32; F::LANES];
            for (i, &(x, y)) in chunk.iter().enumerate() {
                xs[i] = x;
                ys[i] = y;
            }
            let got = F::load(&xs).pow(F::load(&ys));
            for (i, &(x, y)) in chunk.iter().enumerate() {
                let want = f64::from(x).powf(f64::from(y));
                let e = ulps(got.lane(i) as f32, want);
                let t = (f64::from(y) * f64::from(x).abs().log2()).abs();
                let bound = 2.0 + 1.5 * if t.is_finite() { t } else { 0.0 };
                assert!(e <= bound, "pow({x:e}, {y:e}) in {}: {} against {want:e}: {e} ulp", F::NAME, got.lane(i));
                worst = worst.max(e / bound);
            }
        }
    }
    println!("{}: pow error at most {worst:.3} of its bound (2 + 1.5·|y·log2 x| ulp)", F::NAME);
}

/// Shininess exponents `y = n/2`, n in 0..=32 (binary powering): within 0.5 ulp of
/// `f64::powf`, 1.5 ulp with the square root of odd n (results down to 2^-100; below, the
/// exponential path's bound), and each lane's bits the same alone (every lane equal) as beside
/// lanes with other exponents, negative bases, NaN, infinities and exponents off the halves.
fn pow_halves_exact<F: Lanes>() {
    let mut rng = Rng::new(23);
    let others =
        [(-2.0f32, 3.0f32), (0.5, 17.0), (f32::NAN, 2.0), (f32::INFINITY, 4.0), (0.7, 2.25), (3.0, -2.0), (1e-30, 6.0)];
    let mut worst = [0.0f64; 2];
    for i in 0..RANDOM {
        let n = i % 33;
        let y = n as f32 / 2.0;
        let x = match i % 4 {
            0 => rng.uniform(0.0, 1.0),
            1 => rng.uniform(0.0, 4.0),
            2 => rng.uniform(-20.0, 5.0).exp2(),
            _ => [0.0, 1.0, 2.0, f32::MIN_POSITIVE, 1e-40][i % 5],
        };
        let want = f64::from(x).powf(f64::from(y));
        let alone = F::c(f64::from(x)).pow(F::c(f64::from(y))).lane(0) as f32;
        let bound = if want != 0.0 && want < 7.9e-31 {
            2.0 + 1.5 * (f64::from(y) * f64::from(x).log2()).abs()
        } else if n % 2 == 1 {
            1.501
        } else {
            0.501
        };
        let e = ulps(alone, want);
        assert!(e <= bound, "pow({x:e}, {y}) in {}: {alone:e} against {want:e}: {e} ulp", F::NAME);
        if bound < 1.6 {
            worst[n % 2] = worst[n % 2].max(e);
        }
        let (ox, oy) = others[i % others.len()];
        let mut xs = vec![ox; F::LANES];
        let mut ys = vec![oy; F::LANES];
        let at = i % F::LANES;
        xs[at] = x;
        ys[at] = y;
        let mixed = F::load(&xs).pow(F::load(&ys));
        assert_eq!(
            (mixed.lane(at) as f32).to_bits(),
            alone.to_bits(),
            "pow({x:e}, {y}) beside pow({ox}, {oy}) in {}",
            F::NAME
        );
        let other = (mixed.lane((at + 1) % F::LANES) as f32).to_bits();
        let other_alone = (F::c(f64::from(ox)).pow(F::c(f64::from(oy))).lane(0) as f32).to_bits();
        assert_eq!(other, other_alone, "pow({ox}, {oy}) beside pow({x:e}, {y}) in {}", F::NAME);
    }
    println!(
        "{}: pow at half-integer exponents at most {:.3} ulp (integer) / {:.3} ulp (half)",
        F::NAME,
        worst[0],
        worst[1]
    );
}

fn trig_family<F: Lanes>() -> [(&'static str, Stats); 7] {
    let mut rng = Rng::new(30);
    let mut trig_in = unary_inputs(31, &[(-10.0, 10.0), (-1e4, 1e4), (-6e5, 6e5)]);
    trig_in.extend(rng.many(RANDOM, |r| r.uniform(-19.0, 19.0).exp2()));
    trig_in.extend(rng.many(RANDOM, |r| r.finite()));
    let inv_in = unary_inputs(32, &[(-1.0, 1.0), (-1.01, 1.01), (0.49, 0.51), (0.59, 0.61)]);
    let atan_in = unary_inputs(33, &[(-10.0, 10.0), (-1e6, 1e6)]);
    let e = edge_values();
    let atan2_in = pairs(34, &e, |r| (r.uniform(-10.0, 10.0), r.uniform(-10.0, 10.0)));
    let mut atan2_st = check2::<F>("atan2", &atan2_in, F::atan2, f32::atan2, |_, _| TOL, true);
    let wild: Vec<(f32, f32)> = (0..RANDOM).map(|_| (rng.bits(), rng.bits())).collect();
    atan2_st.merge(check2::<F>("atan2", &wild, F::atan2, f32::atan2, |_, _| TOL, true));
    [
        ("sin", check1::<F>("sin", &trig_in, F::sin, f32::sin, TOL)),
        ("cos", check1::<F>("cos", &trig_in, F::cos, f32::cos, TOL)),
        ("tan", check1::<F>("tan", &trig_in, F::tan, f32::tan, TOL)),
        ("asin", check1::<F>("asin", &inv_in, F::asin, f32::asin, TOL)),
        ("acos", check1::<F>("acos", &inv_in, F::acos, f32::acos, TOL)),
        ("atan", check1::<F>("atan", &atan_in, F::atan, f32::atan, TOL)),
        ("atan2", atan2_st),
    ]
}

// ---------------------------------------------------------------------------------------
// One instantiation per width.

macro_rules! width_tests {
    ($m:ident, $F:ty, $N:literal) => {
        mod $m {
            use super::*;
            type F = $F;

            #[test]
            fn exact_unary_ops() {
                exact_unary::<F>();
            }
            #[test]
            fn rsqrt_within_its_bound() {
                rsqrt_accuracy::<F>();
            }
            #[test]
            fn exact_binary_ops_and_comparisons() {
                exact_binary::<F>();
            }
            #[test]
            fn bits_conversions_match_scalar() {
                bits_conversions::<F, $N>();
            }
            #[test]
            fn masks_match_bools() {
                masks::<F, $N>();
            }
            #[test]
            fn lattice_bits_match_u32() {
                lattice_bits::<F, $N>();
            }
            #[test]
            fn pack_unpack_round_trip() {
                pack_roundtrip::<F>();
            }
            #[test]
            fn exp_log_accuracy() {
                for (name, st) in exp_family::<F>() {
                    report(F::NAME, name, st);
                }
            }
            #[test]
            fn pow_accuracy() {
                for (name, st) in pow_family::<F>() {
                    report(F::NAME, name, st);
                }
            }
            #[test]
            fn pow_within_ulps_of_exact() {
                pow_ulps::<F>();
            }
            #[test]
            fn pow_half_integer_exponents() {
                pow_halves_exact::<F>();
            }
            #[test]
            fn underflow_to_zero_bit_for_bit() {
                underflow_bits::<F>();
            }
            #[test]
            fn trig_accuracy() {
                for (name, st) in trig_family::<F>() {
                    report(F::NAME, name, st);
                }
            }
            #[test]
            fn constants() {
                assert_eq!(F::LANES, $N);
                assert_eq!(F::NAME, concat!("f32x", stringify!($N)));
                assert_eq!(F::UNIT_ROUNDOFF, 2f64.powi(-24));
                assert_eq!(<F as Default>::default().to_array(), [0.0; $N]);
                let a: [f32; $N] = core::array::from_fn(|i| i as f32);
                assert_eq!(F::from(a).to_array(), a);
                assert_eq!(<[f32; $N]>::from(F::splat(2.5)), [2.5; $N]);
                assert!(format!("{:?}", F::splat(1.0)).starts_with("F32x"));
            }
        }
    };
}

width_tests!(f32x4, F32x4, 4);
width_tests!(f32x8, F32x8, 8);
width_tests!(f32x16, F32x16, 16);

// The mask and bits types are the ones the float types name.
const _: () = {
    let _: fn(F32x4) -> M32x4 = |x| x.lt(x);
    let _: fn(F32x8) -> M32x8 = |x| x.lt(x);
    let _: fn(F32x16) -> M32x16 = |x| x.lt(x);
    let _: fn(F32x4) -> U32x4 = |x| x.floor_bits();
    let _: fn(F32x8) -> U32x8 = |x| x.floor_bits();
    let _: fn(F32x16) -> U32x16 = |x| x.floor_bits();
};
