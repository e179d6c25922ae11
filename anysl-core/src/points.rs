//! Reproducible sets of shading points outside any scene, and a driver that shades them with
//! any instantiation: the workload of kernel benchmarks and of the cross-instantiation tests.
//!
//! Points lie on the visible half of a unit sphere seen from a camera at (0, 0, 3); `s`, `t`,
//! `u`, `v` are independent uniform values in [0, 1] (so patterns on s/t cross many edges);
//! each point carries screen-space derivative seeds (a pixel footprint of about 1/256 of the
//! sphere) that dual-number instantiations pick up and all others ignore.

use crate::context::PointContext;
use crate::exec::Exec;
use crate::float::ShadingFloat;
use crate::globals::{GlobalSet, Globals};
use crate::shader::{LightShader, SurfaceShader, SurfaceVisitor};
use crate::vec::{Color, Vec3};

/// A small, fast, reproducible generator (SplitMix64).
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Number of f32 arrays in a [`PointSet`] (see [`PointSet::field`]).
const FIELDS: usize = 31;

/// Shading points in structure-of-arrays form (f32: the input precision of every
/// instantiation; the f64 reference reads the same values exactly).
#[derive(Clone, Debug)]
pub struct PointSet {
    n: usize,
    /// The [`FIELDS`] arrays one after the other, field `k` at `data[k * stride ..][.. n]`
    /// (one allocation, so a chunk's loads need one bounds check, not one per field).
    data: Vec<f32>,
    /// Distance between fields: `n` plus one cache line, so that a chunk's loads from the
    /// 31 fields do not all fall into one L1 set (as they would for a power-of-two `n`).
    stride: usize,
}

/// Field indices into [`PointSet`] arrays ([`PointSet::field`]); triples take 3 slots.
#[allow(missing_docs)]
pub mod field {
    pub const P: usize = 0;
    pub const N: usize = 3;
    pub const I: usize = 6;
    pub const S: usize = 9;
    pub const T: usize = 10;
    pub const U: usize = 11;
    pub const V: usize = 12;
    pub const DPDU: usize = 13;
    pub const DPDV: usize = 16;
    pub const DPDX: usize = 19;
    pub const DPDY: usize = 22;
    pub const DSDX: usize = 25;
    pub const DSDY: usize = 26;
    pub const DTDX: usize = 27;
    pub const DTDY: usize = 28;
    pub const DU: usize = 29;
    pub const DV: usize = 30;
}

impl PointSet {
    /// `n` random points (rounded up to a multiple of 16 so every SIMD width divides it),
    /// reproducible from `seed`.
    #[must_use]
    pub fn random(n: usize, seed: u64) -> Self {
        let n = n.div_ceil(16) * 16;
        let mut rng = SplitMix64(seed);
        let mut data: Vec<Vec<f32>> = (0..FIELDS).map(|_| Vec::with_capacity(n)).collect();
        let eye = [0.0, 0.0, 3.0];
        for _ in 0..n {
            // Uniform on the visible cap z > 1/3 (points whose normal faces the eye).
            let z = rng.uniform(1.0 / 3.0, 1.0);
            let phi = rng.uniform(0.0, std::f64::consts::TAU);
            let r = (1.0 - z * z).sqrt();
            let p = [r * phi.cos(), r * phi.sin(), z];
            let tangent = [-phi.sin(), phi.cos(), 0.0];
            let bitangent = [
                p[1] * tangent[2] - p[2] * tangent[1],
                p[2] * tangent[0] - p[0] * tangent[2],
                p[0] * tangent[1] - p[1] * tangent[0],
            ];
            let mut push3 = |base: usize, v: [f64; 3]| {
                for k in 0..3 {
                    data[base + k].push(v[k] as f32);
                }
            };
            push3(field::P, p);
            push3(field::N, p);
            push3(field::I, [p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]]);
            push3(field::DPDU, tangent.map(|c| c * std::f64::consts::TAU * r));
            push3(field::DPDV, bitangent.map(|c| c * std::f64::consts::PI));
            let fx = 1.0 / 256.0;
            push3(field::DPDX, [0, 1, 2].map(|k| fx * (tangent[k] + 0.2 * bitangent[k])));
            push3(field::DPDY, [0, 1, 2].map(|k| fx * (bitangent[k] - 0.15 * tangent[k])));
            let (s, t, u, v) =
                (rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0));
            for (i, val) in [
                (field::S, s),
                (field::T, t),
                (field::U, u),
                (field::V, v),
                (field::DSDX, fx * 0.5),
                (field::DSDY, fx * 0.08),
                (field::DTDX, -fx * 0.06),
                (field::DTDY, fx * 0.5),
                (field::DU, fx),
                (field::DV, fx),
            ] {
                data[i].push(val as f32);
            }
        }
        let stride = n + 16;
        let mut flat = vec![0.0; FIELDS * stride];
        for (k, f) in data.iter().enumerate() {
            flat[k * stride..k * stride + n].copy_from_slice(f);
        }
        Self { n, data: flat, stride }
    }

    /// Number of points.
    #[must_use]
    pub fn len(&self) -> usize {
        self.n
    }

    /// True when empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Raw array `k` (indices in [`field`]).
    #[must_use]
    pub fn field(&self, k: usize) -> &[f32] {
        &self.data[k * self.stride..][..self.n]
    }

    /// Points `i .. i + F::LANES` of field `k`; the caller has checked `i + F::LANES <= n`.
    #[inline(always)]
    fn load<F: ShadingFloat>(&self, k: usize, i: usize) -> F {
        debug_assert!(k < FIELDS && i + F::LANES <= self.n);
        let at = k * self.stride + i;
        // SAFETY: `data` holds `FIELDS * stride` values and `i + F::LANES <= n < stride`
        // (checked once in `globals`, the only caller), so `at + F::LANES <= FIELDS * stride`.
        F::load(unsafe { self.data.get_unchecked(at..at + F::LANES) })
    }

    #[inline(always)]
    fn load3<F: ShadingFloat>(&self, k: usize, i: usize) -> Vec3<F> {
        Vec3::new(self.load(k, i), self.load(k + 1, i), self.load(k + 2, i))
    }

    /// The globals of points `i .. i + F::LANES`, with derivative seeds for dual numbers:
    /// P carries dP/dx, dP/dy; s and u carry ds/dx, ds/dy; t and v carry dt/dx, dt/dy;
    /// N and I carry the same footprint scaled (the sphere's normal changes like P).
    ///
    /// # Panics
    /// When `i + F::LANES` exceeds [`PointSet::len`].
    #[inline(always)]
    #[must_use]
    pub fn globals<F: ShadingFloat>(&self, i: usize) -> Globals<F> {
        let mut g = Globals::unit_square(F::c(0.0), F::c(0.0));
        self.load_globals(i, &mut g);
        g
    }

    /// [`PointSet::globals`] written field by field into `g` (a context's globals are filled
    /// in place, not built elsewhere and copied: 1 KiB per chunk at 8 lanes).
    ///
    /// # Panics
    /// When `i + F::LANES` exceeds [`PointSet::len`].
    #[inline(always)]
    pub fn load_globals<F: ShadingFloat>(&self, i: usize, g: &mut Globals<F>) {
        self.load_globals_read(i, g, GlobalSet::ALL);
    }

    /// [`PointSet::load_globals`] of only the globals in `read` (the others keep their values).
    ///
    /// # Panics
    /// When `i + F::LANES` exceeds [`PointSet::len`].
    #[inline(always)]
    pub fn load_globals_read<F: ShadingFloat>(&self, i: usize, g: &mut Globals<F>, read: GlobalSet) {
        assert!(i + F::LANES <= self.n, "points {i}..{} of {}", i + F::LANES, self.n);
        let has = |x: GlobalSet| read.contains(x);
        // Every component is stored in place, one value at a time: a `Vec3` built first and
        // then copied had rustc merge the copies into 64-byte moves that read back two
        // 32-byte stores just made (a store-forwarding stall on every chunk).
        let dpdx = self.load3::<F>(field::DPDX, i);
        let dpdy = self.load3::<F>(field::DPDY, i);
        let seeded = |dst: &mut Vec3<F>, k: usize| {
            dst.x = self.load::<F>(k, i).with_derivs(dpdx.x, dpdy.x);
            dst.y = self.load::<F>(k + 1, i).with_derivs(dpdx.y, dpdy.y);
            dst.z = self.load::<F>(k + 2, i).with_derivs(dpdx.z, dpdy.z);
        };
        let plain = |dst: &mut Vec3<F>, k: usize| {
            dst.x = self.load::<F>(k, i);
            dst.y = self.load::<F>(k + 1, i);
            dst.z = self.load::<F>(k + 2, i);
        };
        let (dsdx, dsdy, dtdx, dtdy) = (
            self.load::<F>(field::DSDX, i),
            self.load(field::DSDY, i),
            self.load(field::DTDX, i),
            self.load(field::DTDY, i),
        );
        if has(GlobalSet::P) {
            seeded(&mut g.P, field::P);
        }
        if has(GlobalSet::N) {
            seeded(&mut g.N, field::N);
        }
        if has(GlobalSet::NG) {
            seeded(&mut g.Ng, field::N);
        }
        if has(GlobalSet::I) {
            seeded(&mut g.I, field::I);
        }
        g.E = Vec3::c(0.0, 0.0, 3.0);
        if has(GlobalSet::S) {
            g.s = self.load::<F>(field::S, i).with_derivs(dsdx, dsdy);
        }
        if has(GlobalSet::T) {
            g.t = self.load::<F>(field::T, i).with_derivs(dtdx, dtdy);
        }
        if has(GlobalSet::U) {
            g.u = self.load::<F>(field::U, i).with_derivs(dsdx, dsdy);
        }
        if has(GlobalSet::V) {
            g.v = self.load::<F>(field::V, i).with_derivs(dtdx, dtdy);
        }
        if has(GlobalSet::DU) {
            g.du = self.load(field::DU, i);
        }
        if has(GlobalSet::DV) {
            g.dv = self.load(field::DV, i);
        }
        if has(GlobalSet::DPDU) {
            plain(&mut g.dPdu, field::DPDU);
        }
        if has(GlobalSet::DPDV) {
            plain(&mut g.dPdv, field::DPDV);
        }
        g.Cs = Color::c(1.0, 1.0, 1.0);
        g.Os = Color::c(1.0, 1.0, 1.0);
    }
}

/// Shading results in SoA form: `Ci` and `Oi`, 6 channels of `n` values.
#[derive(Clone, Debug)]
pub struct ShadeOut<T> {
    /// `channels[0..3]` = Ci r, g, b; `channels[3..6]` = Oi r, g, b.
    pub channels: [Vec<T>; 6],
}

impl<T: Copy + Default> ShadeOut<T> {
    /// Zeroed output for `n` points.
    #[must_use]
    pub fn new(n: usize) -> Self {
        Self { channels: core::array::from_fn(|_| vec![T::default(); n]) }
    }
}

/// Shades points `i .. i + F::LANES` and returns `(Ci, Oi)`.
#[inline(always)]
pub fn shade_chunk<F, S, L>(shader: &S, lights: &[L], set: &PointSet, i: usize) -> (Color<F>, Color<F>)
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    let mut ctx = PointContext::new(set.globals::<F>(i), lights);
    let mut e = Exec::<F>::new();
    let out = shader.shade(&mut ctx, &mut e);
    (out.Ci, out.Oi)
}

/// Shades every point of `set` with instantiation `F`, storing lane values as f32 (the
/// value part for duals, the midpoint for intervals). The loop is monomorphized per concrete
/// shader through [`SurfaceShader::visit`], so a closed set of shaders pays its `match` once.
pub fn shade_points<F, S, L>(shader: &S, lights: &[L], set: &PointSet, out: &mut ShadeOut<f32>)
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    struct Job<'a, F, L> {
        lights: &'a [L],
        set: &'a PointSet,
        out: &'a mut ShadeOut<f32>,
        _f: core::marker::PhantomData<F>,
    }
    impl<F: ShadingFloat, L: LightShader> SurfaceVisitor for Job<'_, F, L> {
        type Output = ();
        #[inline(never)]
        fn visit<S: SurfaceShader>(self, shader: &S) {
            let [cr, cg, cb, or, og, ob] = &mut self.out.channels;
            if self.set.len() < F::LANES {
                return;
            }
            // One context, its globals refilled in place per chunk: those the shader reads
            // (all of them for a shader inlined here, where the unused loads fold away).
            let read = shader.globals_read();
            let mut ctx = PointContext::new(self.set.globals::<F>(0), self.lights);
            let mut i = 0;
            while i + F::LANES <= self.set.len() {
                self.set.load_globals_read(i, &mut ctx.globals, read);
                let out = shader.shade(&mut ctx, &mut Exec::<F>::new());
                let (ci, oi) = (out.Ci, out.Oi);
                ci.r.store(&mut cr[i..]);
                ci.g.store(&mut cg[i..]);
                ci.b.store(&mut cb[i..]);
                oi.r.store(&mut or[i..]);
                oi.g.store(&mut og[i..]);
                oi.b.store(&mut ob[i..]);
                i += F::LANES;
            }
        }
    }
    shader.visit(Job::<F, L> { lights, set, out, _f: core::marker::PhantomData });
}

/// Shades every point with instantiation `F`, keeping full lane values as f64 (used for
/// the f64 reference and for exact comparisons).
pub fn shade_points_f64<F, S, L>(shader: &S, lights: &[L], set: &PointSet) -> ShadeOut<f64>
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    struct Job<'a, F, L> {
        lights: &'a [L],
        set: &'a PointSet,
        _f: core::marker::PhantomData<F>,
    }
    impl<F: ShadingFloat, L: LightShader> SurfaceVisitor for Job<'_, F, L> {
        type Output = ShadeOut<f64>;
        fn visit<S: SurfaceShader>(self, shader: &S) -> ShadeOut<f64> {
            let mut out = ShadeOut::<f64>::new(self.set.len());
            let mut i = 0;
            while i + F::LANES <= self.set.len() {
                let (ci, oi) = shade_chunk::<F, S, L>(shader, self.lights, self.set, i);
                let vals = [ci.r, ci.g, ci.b, oi.r, oi.g, oi.b];
                for (ch, v) in vals.iter().enumerate() {
                    for l in 0..F::LANES {
                        out.channels[ch][i + l] = v.lane(l);
                    }
                }
                i += F::LANES;
            }
            out
        }
    }
    shader.visit(Job::<F, L> { lights, set, _f: core::marker::PhantomData })
}

/// Absolute-error statistics of `got` against `reference` over all points and channels:
/// `(max, 99.9th percentile)`. NaN anywhere counts as infinite error.
#[must_use]
pub fn abs_error_stats(got: &ShadeOut<f32>, reference: &ShadeOut<f64>) -> (f64, f64) {
    let mut errs: Vec<f64> = got
        .channels
        .iter()
        .zip(&reference.channels)
        .flat_map(|(g, r)| {
            g.iter().zip(r).map(|(a, b)| {
                let e = (*a as f64 - b).abs();
                if e.is_nan() {
                    f64::INFINITY
                } else {
                    e
                }
            })
        })
        .collect();
    if errs.is_empty() {
        return (0.0, 0.0);
    }
    errs.sort_by(|a, b| a.partial_cmp(b).expect("NaN mapped to inf"));
    let max = *errs.last().expect("non-empty");
    let idx = ((errs.len() as f64 * 0.999).ceil() as usize).saturating_sub(1).min(errs.len() - 1);
    (max, errs[idx])
}
