//! Noise: the shared workload's check values, range, continuity and behaviour at 1e7.

use anysl_core::stdlib::{
    cellnoise, fbm, lattice_hash, noise, perlin3, pnoise, snoise, turbulence, vnoise, NoiseDomain,
};
use anysl_core::{ShadingFloat, Vec3};

/// A small fixed-seed generator (SplitMix64) so tests are reproducible without extra crates.
struct Rng(u64);
impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn hash_matches_workload_check_values() {
    let cases: [([i32; 3], u32); 8] = [
        ([0, 0, 0], 0x0000_0000),
        ([1, 0, 0], 0x9D5A_7ACD),
        ([0, 1, 0], 0x2859_CC20),
        ([0, 0, 1], 0x3589_17CF),
        ([1, 2, 3], 0x0BD9_0090),
        ([-1, -1, -1], 0x4982_21C6),
        ([-7, 13, -2], 0x75A4_F030),
        ([100, -200, 300], 0xB4A8_71B0),
    ];
    for (c, want) in cases {
        let got = lattice_hash(&[c[0] as u32, c[1] as u32, c[2] as u32], 0);
        assert_eq!(got, want, "hash{c:?}");
    }
}

#[test]
fn noise_matches_workload_check_values() {
    let cases = [
        ([0.3125, 0.6875, 0.1875], 0.006638754),
        ([1.25, -0.75, 2.5], 0.201884270),
        ([-3.375, 0.125, 7.875], 0.192607176),
        ([10.625, -4.25, 0.375], 0.532987841),
        ([100.5625, -57.125, 3.0625], 0.015444126),
        ([0.0, 0.0, 0.0], 0.0),
    ];
    for (p, want) in cases {
        let n64 = perlin3(Vec3::<f64>::from_array(p), None, 0);
        assert!((n64 - want).abs() < 1e-9, "f64 noise{p:?} = {n64}, want {want}");
        let n32 = perlin3(Vec3::<f32>::from_array(p), None, 0);
        assert!((n32 as f64 - want).abs() < 2e-7, "f32 noise{p:?} = {n32}, want {want}");
    }
}

fn stats(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    (mean, var.sqrt())
}

#[test]
fn noise_range_and_mean() {
    let mut rng = Rng(1);
    let mut vals = Vec::new();
    for _ in 0..20_000 {
        let p = Vec3::<f64>::new(rng.uniform(-50.0, 50.0), rng.uniform(-50.0, 50.0), rng.uniform(-50.0, 50.0));
        let n = noise(NoiseDomain::D3(p));
        let s = snoise(NoiseDomain::D3(p));
        assert!((0.0..=1.0).contains(&n), "noise out of range: {n}");
        assert!((-1.0..=1.0).contains(&s), "snoise out of range: {s}");
        vals.push(n);
        let c = cellnoise(NoiseDomain::D3(p));
        assert!((0.0..1.0).contains(&c), "cellnoise out of range: {c}");
        let v = vnoise(NoiseDomain::D4(p, p.x));
        for k in 0..3 {
            assert!((0.0..=1.0).contains(&v[k]));
        }
    }
    let (mean, sd) = stats(&vals);
    assert!((mean - 0.5).abs() < 0.01, "noise mean {mean}");
    assert!(sd > 0.08 && sd < 0.2, "noise std dev {sd}");
}

#[test]
fn noise_is_continuous_across_cells() {
    // Across a lattice plane the value must not jump: compare points 1e-7 apart.
    let mut rng = Rng(2);
    for _ in 0..2000 {
        let y = rng.uniform(-10.0, 10.0);
        let z = rng.uniform(-10.0, 10.0);
        let x = rng.uniform(-10.0, 10.0).floor();
        let a = noise(NoiseDomain::D3(Vec3::<f64>::new(x - 1e-9, y, z)));
        let b = noise(NoiseDomain::D3(Vec3::<f64>::new(x + 1e-9, y, z)));
        assert!((a - b).abs() < 1e-7, "jump at x={x}: {a} vs {b}");
        // Lipschitz: the gradient of Perlin noise is bounded (|∇| < 4 in these units).
        let h = 1e-3;
        let c = noise(NoiseDomain::D3(Vec3::<f64>::new(x + 0.3 + h, y, z)));
        let d = noise(NoiseDomain::D3(Vec3::<f64>::new(x + 0.3, y, z)));
        assert!((c - d).abs() < 4.0 * h);
    }
}

/// At 1e7 the noise keeps its full statistics: the integer lattice coordinates are hashed
/// exactly and the fractional part is taken before hashing. The statistic: mean and
/// standard deviation of `noise` over 20 000 random points in a unit-scale box at 1e7 match
/// those near the origin within 10%, and adjacent samples 0.1 apart stay correlated the
/// same way (no collapse to a constant, no lattice-aligned artefacts). f64 is used because
/// f32 cannot represent sub-integer offsets at 1e7 (its spacing there is 1.0).
#[test]
fn noise_keeps_detail_at_1e7() {
    let sample = |origin: f64, seed: u64| {
        let mut rng = Rng(seed);
        let mut vals = Vec::new();
        let mut diffs = Vec::new();
        for _ in 0..20_000 {
            let p = Vec3::<f64>::new(
                origin + rng.uniform(0.0, 64.0),
                -origin + rng.uniform(0.0, 64.0),
                origin + rng.uniform(0.0, 64.0),
            );
            let a = noise(NoiseDomain::D3(p));
            let b = noise(NoiseDomain::D3(p + Vec3::c(0.1, 0.0, 0.0)));
            vals.push(a);
            diffs.push((a - b).abs());
        }
        let (m, s) = stats(&vals);
        let (dm, _) = stats(&diffs);
        (m, s, dm)
    };
    let (m0, s0, d0) = sample(0.0, 3);
    let (m1, s1, d1) = sample(1.0e7, 4);
    assert!((m0 - m1).abs() < 0.02, "mean {m0} vs {m1}");
    assert!((s1 / s0 - 1.0).abs() < 0.1, "std dev {s0} vs {s1}");
    assert!((d1 / d0 - 1.0).abs() < 0.1, "local variation {d0} vs {d1}");
    // In f32, at 1e7 every representable point is a lattice point, but the hash must still
    // vary (cellnoise is not constant): no precision collapse in the integer path.
    let mut distinct = std::collections::BTreeSet::new();
    for k in 0..64 {
        let p = Vec3::<f32>::new(1.0e7 + k as f32, 2.0e7 - k as f32, 1.0e7);
        distinct.insert(cellnoise(NoiseDomain::D3(p)).to_bits());
    }
    assert!(distinct.len() > 60, "cellnoise collapsed at 1e7: {} distinct", distinct.len());
}

#[test]
fn pnoise_repeats_with_its_period() {
    let mut rng = Rng(5);
    for _ in 0..2000 {
        let p = Vec3::<f64>::new(rng.uniform(-20.0, 20.0), rng.uniform(-20.0, 20.0), rng.uniform(-20.0, 20.0));
        let per = Vec3::<f64>::c(4.0, 5.0, 3.0);
        let a = pnoise(NoiseDomain::D3(p), NoiseDomain::D3(per));
        let b = pnoise(NoiseDomain::D3(p + Vec3::c(4.0, -10.0, 6.0)), NoiseDomain::D3(per));
        assert!((a - b).abs() < 1e-9, "pnoise not periodic at {p:?}: {a} vs {b}");
    }
}

#[test]
fn fbm_and_turbulence_are_bounded_and_f32_tracks_f64_over_30_octaves() {
    let mut rng = Rng(6);
    let mut worst: f64 = 0.0;
    for _ in 0..500 {
        let p = [rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0)];
        let t64 = turbulence(NoiseDomain::D3(Vec3::<f64>::from_array(p)), 6, 2.0, 0.5);
        assert!((0.0..2.0).contains(&t64));
        let f64v = fbm(NoiseDomain::D3(Vec3::<f64>::from_array(p)), 30, 2.0, 0.5);
        let f32v = fbm(NoiseDomain::D3(Vec3::<f32>::from_array(p)), 30, 2.0, 0.5);
        assert!(f64v.abs() <= 2.0);
        worst = worst.max((f64v - f32v as f64).abs());
    }
    // High octaves see f32 coordinates with few fractional bits; their amplitude is 2^-o, so
    // the drift stays small in total.
    assert!(worst < 1e-3, "fbm f32 drift {worst}");
}

#[test]
fn noise_of_nan_inf_and_huge_inputs_is_the_lattice_value() {
    for v in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 1e30, -1e30] {
        let p = Vec3::<f32>::new(v, 0.5, 0.25);
        let n = noise(NoiseDomain::D3(p));
        if v.is_finite() {
            // Huge coordinates saturate the lattice: a finite value in range.
            assert!((0.0..=1.0).contains(&n), "noise({v}) = {n}");
        } else {
            assert_eq!(n, 0.5, "noise({v})");
            assert_eq!(snoise(NoiseDomain::D3(p)), 0.0, "snoise({v})");
        }
        let c = cellnoise(NoiseDomain::D3(p));
        assert!((0.0..1.0).contains(&c), "cellnoise({v}) = {c}");
    }
    let _ = <f32 as ShadingFloat>::c(0.0);
}
