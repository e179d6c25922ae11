//! `Pair<F>` against its halves: every operation of a pair is, lane for lane and bit for bit,
//! the operation of `F` on each half — on edge cases and fixed-seed random bit patterns — and
//! the masks and integer lanes keep their lanes in order.

use anysl_core::stdlib::perlin3;
use anysl_core::{LatticeBits, Mask, ShadingFloat, Vec3};
use anysl_simd::{F32x16, F32x4, F32x8, Pair};

/// SplitMix64 bit patterns, with the edge cases first.
fn inputs(n: usize, seed: u64) -> Vec<f32> {
    let mut v = vec![0.0, -0.0, 1.0, -1.0, 0.5, 2.0, f32::INFINITY, f32::NEG_INFINITY, f32::NAN, 1e-45, 1e7, -3.75];
    let mut s = seed;
    while v.len() < n {
        s = s.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = s;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        let bits = ((z ^ (z >> 31)) >> 32) as u32;
        // Half arbitrary bit patterns, half moderate values (where the kernels do the work).
        v.push(if v.len() % 2 == 0 { f32::from_bits(bits) } else { (bits as f32 / u32::MAX as f32 - 0.5) * 20.0 });
    }
    v
}

fn same<F: ShadingFloat>(name: &str, got: Pair<F>, want: [F; 2]) {
    for i in 0..2 * F::LANES {
        let w = want[i / F::LANES].lane(i % F::LANES) as f32;
        let g = got.lane(i) as f32;
        assert!(g.to_bits() == w.to_bits() || (g.is_nan() && w.is_nan()), "{name} lane {i}: {g} against {w}");
    }
}

fn check<F: ShadingFloat>() {
    let n = 2 * F::LANES;
    let (xs, ys) = (inputs(64 * n, 7), inputs(64 * n, 11));
    for (a, b) in xs.chunks(n).zip(ys.chunks(n)) {
        let (x, y) = (Pair::<F>::load(a), Pair::<F>::load(b));
        let (x0, x1) = (F::load(a), F::load(&a[F::LANES..]));
        let (y0, y1) = (F::load(b), F::load(&b[F::LANES..]));
        same("+", x + y, [x0 + y0, x1 + y1]);
        same("*", x * y, [x0 * y0, x1 * y1]);
        same("/", x / y, [x0 / y0, x1 / y1]);
        same("sqrt", x.sqrt(), [x0.sqrt(), x1.sqrt()]);
        same("max", x.max(y), [x0.max(y0), x1.max(y1)]);
        same("pow", x.pow(y), [x0.pow(y0), x1.pow(y1)]);
        // Shininess exponents, the same in every lane (the halves share `pow`'s branches).
        for e in [0.0, 0.5, 1.0, 2.5, 8.0, 12.5, 16.0, 3.3, -2.0] {
            let (ax, ax0, ax1) = (x.abs(), x0.abs(), x1.abs());
            same("pow uniform", ax.pow(Pair::c(e)), [ax0.pow(F::c(e)), ax1.pow(F::c(e))]);
        }
        // Four packets (`Pair<Pair<F>>`, `pow4`): a quarter's lanes are `F`'s, each exponent
        // uniform or not.
        let q = |k: usize| F::load(&a[(k % 2) * F::LANES..]) * F::c(if k < 2 { 1.0 } else { 0.25 });
        let quad = Pair(Pair(q(0), q(1)), Pair(q(2), q(3)));
        for e in [Some(12.5), Some(4.0), None] {
            let ey = |k: usize| e.map_or_else(|| F::load(&b[(k % 2) * F::LANES..]), F::c);
            let got = quad.pow(Pair(Pair(ey(0), ey(1)), Pair(ey(2), ey(3))));
            for k in 0..4 {
                let want = q(k).pow(ey(k));
                let half = if k < 2 { got.0 } else { got.1 };
                let g = if k % 2 == 0 { half.0 } else { half.1 };
                for i in 0..F::LANES {
                    let (g, w) = (g.lane(i) as f32, want.lane(i) as f32);
                    assert!(g.to_bits() == w.to_bits() || (g.is_nan() && w.is_nan()), "pow4 {e:?} packet {k} lane {i}");
                }
            }
        }
        same("exp", x.exp(), [x0.exp(), x1.exp()]);
        same("sin", x.sin(), [x0.sin(), x1.sin()]);
        same("atan2", x.atan2(y), [x0.atan2(y0), x1.atan2(y1)]);
        same("floor", x.floor(), [x0.floor(), x1.floor()]);
        same("select", Pair::select(x.lt(y), x, y), [F::select(x0.lt(y0), x0, y0), F::select(x1.lt(y1), x1, y1)]);
        let p = Vec3::new(x, y, x * y);
        let (p0, p1) = (Vec3::new(x0, y0, x0 * y0), Vec3::new(x1, y1, x1 * y1));
        same("noise", perlin3(p, None, 0), [perlin3(p0, None, 0), perlin3(p1, None, 0)]);
        // Masks and bits keep their lanes in order.
        let m = x.lt(y);
        let bits = m.to_bits();
        assert_eq!(bits, x0.lt(y0).to_bits() | x1.lt(y1).to_bits() << F::LANES);
        assert_eq!(<Pair<F> as ShadingFloat>::Mask::from_bits(bits).to_bits(), bits);
        assert_eq!(m.any(), x0.lt(y0).any() || x1.lt(y1).any());
        assert_eq!(m.all(), x0.lt(y0).all() && x1.lt(y1).all());
        let h = x.floor_bits();
        for i in 0..n {
            let half = if i < F::LANES { x0.floor_bits() } else { x1.floor_bits() };
            assert_eq!(h.lane(i), half.lane(i % F::LANES));
        }
    }
    let mut out = vec![0.0f32; n];
    let v: Vec<f64> = (0..n).map(|i| i as f64 * 0.25).collect();
    Pair::<F>::from_lanes(&v).store(&mut out);
    assert!(out.iter().zip(&v).all(|(&o, &w)| f64::from(o) == w), "from_lanes/store keep the lane order");
}

#[test]
fn pair_of_f32_is_its_halves() {
    check::<f32>();
}

#[test]
fn pair_of_f32x4_is_its_halves() {
    check::<F32x4>();
}

#[test]
fn pair_of_f32x8_is_its_halves() {
    check::<F32x8>();
}

#[test]
fn pair_of_f32x16_is_its_halves() {
    check::<F32x16>();
}
