//! Shared test fixtures: reproducible random shading points and shading helpers.
#![allow(dead_code)]

use anysl_core::{Color, Exec, Globals, LightShader, PointContext, ShadingFloat, SurfaceShader, Vec3};

/// SplitMix64: a small reproducible generator (tests need no `rand`).
pub struct Rng(pub u64);

impl Rng {
    /// Next value uniform in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    /// Next value uniform in [lo, hi), rounded to f32 so f32 and f64 see the same input.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        (lo + (hi - lo) * self.next_f64()) as f32 as f64
    }
}

/// The camera every test point is seen from.
pub const EYE: [f64; 3] = [0.0, 0.0, 3.0];

/// One shading point's inputs (every value exactly representable in f32).
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    pub p: [f64; 3],
    pub s: f64,
    pub t: f64,
    pub u: f64,
    pub v: f64,
    pub cs: [f64; 3],
    pub os: [f64; 3],
}

/// `n` random points on the unit sphere (N = P, I from a camera at (0, 0, 3)), s, t, u, v in
/// [0, 1], Cs in [0, 1], Os in [0.5, 1].
pub fn samples(n: usize, seed: u64) -> Vec<Sample> {
    let mut r = Rng(seed);
    (0..n)
        .map(|_| {
            let z = 2.0 * r.next_f64() - 1.0;
            let phi = 2.0 * std::f64::consts::PI * r.next_f64();
            let rho = (1.0 - z * z).max(0.0).sqrt();
            let p = [rho * phi.cos(), rho * phi.sin(), z].map(|c| c as f32 as f64);
            Sample {
                p,
                s: r.range(0.0, 1.0),
                t: r.range(0.0, 1.0),
                u: r.range(0.0, 1.0),
                v: r.range(0.0, 1.0),
                cs: [r.range(0.0, 1.0), r.range(0.0, 1.0), r.range(0.0, 1.0)],
                os: [r.range(0.5, 1.0), r.range(0.5, 1.0), r.range(0.5, 1.0)],
            }
        })
        .collect()
}

/// The globals of a sample in precision `F`.
pub fn globals<F: ShadingFloat>(x: &Sample) -> Globals<F> {
    let p = Vec3::<F>::from_array(x.p);
    let e = Vec3::<F>::from_array(EYE);
    let n = p;
    // Any tangent frame will do; these tests do not differentiate.
    let dpdu = Vec3::<F>::c(-x.p[1], x.p[0], 0.0);
    let dpdv = n.cross(dpdu);
    Globals {
        P: p,
        N: n,
        Ng: n,
        I: p - e,
        E: e,
        s: F::c(x.s),
        t: F::c(x.t),
        u: F::c(x.u),
        v: F::c(x.v),
        du: F::c(0.0),
        dv: F::c(0.0),
        dPdu: dpdu,
        dPdv: dpdv,
        Cs: Color::from_array(x.cs),
        Os: Color::from_array(x.os),
    }
}

/// Shades one sample with `F` through a [`PointContext`]; returns (Ci, Oi) as f64.
pub fn shade_point<F: ShadingFloat, S: SurfaceShader, L: LightShader>(
    shader: &S,
    lights: &[L],
    x: &Sample,
) -> ([f64; 3], [f64; 3]) {
    let mut ctx = PointContext::new(globals::<F>(x), lights);
    let out = shader.shade(&mut ctx, &mut Exec::new());
    (out.Ci.lane(0), out.Oi.lane(0))
}

/// The `q`-quantile (0..=1) of `v` (sorted in place).
pub fn quantile(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).expect("no NaN"));
    let i = ((v.len() - 1) as f64 * q).round() as usize;
    v[i]
}

/// The globals of `F::LANES` samples, one per lane.
pub fn globals_lanes<F: ShadingFloat>(xs: &[Sample]) -> Globals<F> {
    assert_eq!(xs.len(), F::LANES);
    let g: Vec<Globals<f64>> = xs.iter().map(globals::<f64>).collect();
    let f = |get: &dyn Fn(&Globals<f64>) -> f64| F::from_lanes(&g.iter().map(get).collect::<Vec<_>>());
    let v = |get: &dyn Fn(&Globals<f64>) -> Vec3<f64>| Vec3::new(f(&|x| get(x).x), f(&|x| get(x).y), f(&|x| get(x).z));
    let c =
        |get: &dyn Fn(&Globals<f64>) -> Color<f64>| Color::new(f(&|x| get(x).r), f(&|x| get(x).g), f(&|x| get(x).b));
    Globals {
        P: v(&|x| x.P),
        N: v(&|x| x.N),
        Ng: v(&|x| x.Ng),
        I: v(&|x| x.I),
        E: v(&|x| x.E),
        s: f(&|x| x.s),
        t: f(&|x| x.t),
        u: f(&|x| x.u),
        v: f(&|x| x.v),
        du: f(&|x| x.du),
        dv: f(&|x| x.dv),
        dPdu: v(&|x| x.dPdu),
        dPdv: v(&|x| x.dPdv),
        Cs: c(&|x| x.Cs),
        Os: c(&|x| x.Os),
    }
}
