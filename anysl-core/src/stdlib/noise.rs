//! Branch-free, table-free gradient noise and everything built on it.
//!
//! The core is Perlin's "improved noise" (2002) with the permutation table replaced by an
//! integer hash computed on the fly (Teschner et al. spatial-hash primes, then Wellons'
//! `lowbias32` finaliser), exactly as in `shaders/assets/workload_ref/shading_workload.md` §4, so it
//! vectorizes and needs no memory. Lattice coordinates are the `i32` bit patterns of
//! `floor(x)`: the hash sees exact integers at any magnitude (no float-multiply hash that
//! loses bits at 1e7), and the fractional part is taken before hashing, so detail is kept
//! wherever the input precision has it. Coordinates beyond ±2^31 are first reduced modulo the
//! hash period 2^32 (exactly), so noise is periodic with that period on every axis instead of
//! collapsing where `floor` leaves the i32 range (30-octave fBm reaches 2^31 at |x| ≈ 4).
//!
//! RSL conventions: `noise` is in [0, 1] (0.5 + 0.5·perlin), `snoise` in [-1, 1], `cellnoise`
//! is constant on unit cells with values in [0, 1), `pnoise` repeats with a given period.
//! Non-finite coordinates give the lattice-point value (noise 0.5, snoise 0), never NaN.

use super::math::{clamp, fmod};
use crate::float::{LatticeBits, Mask, PureFn, ShadingFloat};
use crate::vec::{Color, Vec3};

/// The constants of the lattice hash, public so that code generators emitting the same noise
/// (the JIT's inline noise) use these values rather than copies.
pub mod lattice {
    /// Hash multipliers per lattice axis (x, y, z, w) and for the seed.
    pub const PRIMES: [u32; 5] = [73856093, 19349663, 83492791, 2654435761, 0x27d4_eb2d];
    /// The two multipliers of the `lowbias32` finaliser.
    pub const FINALIZE: [u32; 2] = [0x7FEB_352D, 0x846C_A68B];
    /// Seed of `cellnoise`.
    pub const CELL_SEED: u32 = 0x0c31_1ced;
    /// The period of the lattice hash along each axis: it sees lattice coordinates as u32.
    pub const HASH_PERIOD: f64 = 4_294_967_296.0;
    /// Seeds of the components of vector-valued noise (`vnoise`, `vsnoise`, `vcellnoise`).
    pub const VECTOR_SEEDS: [u32; 3] = [0, 0x5bd1_e995, 0x1b87_3593];
}
pub use lattice::VECTOR_SEEDS;
use lattice::{CELL_SEED, FINALIZE, HASH_PERIOD, PRIMES};

/// `lowbias32` finaliser.
#[inline(always)]
fn finalize<B: LatticeBits>(mut h: B) -> B {
    h = h ^ (h >> 16);
    h = h.wrapping_mul(B::splat(FINALIZE[0]));
    h = h ^ (h >> 15);
    h = h.wrapping_mul(B::splat(FINALIZE[1]));
    h ^ (h >> 16)
}

/// Hash of an integer lattice point given as u32 lanes (`hash(i, j, k)` of the workload for
/// 3D and seed 0; unused axes are 0).
#[inline(always)]
#[must_use]
pub fn lattice_hash<B: LatticeBits>(c: &[B], seed: u32) -> B {
    let mut h = B::splat(seed.wrapping_mul(PRIMES[4]));
    for (axis, &ci) in c.iter().enumerate() {
        h = h ^ ci.wrapping_mul(B::splat(PRIMES[axis]));
    }
    finalize(h)
}

/// Perlin's 16 gradients for 3D (12 cube-edge directions, four repeated), by component:
/// `GRAD3[axis][h & 15]`.
const GRAD3: [[f32; 16]; 3] = [
    [1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0],
    [1.0, 1.0, -1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0],
    [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, -1.0, -1.0, 1.0, 1.0, -1.0, -1.0, 0.0, 1.0, 0.0, -1.0],
];

/// Perlin's 16-case gradient for 3D: `dot(g[h & 15], (x, y, z))`. The gradient's components
/// come from three register lookups ([`ShadingFloat::lookup16`]: one permute each at 16
/// lanes) in place of the eleven compares and selects of the case analysis. Two of the three
/// components are ±1 and one is 0, so the dot product rounds once, as `±u ± v` does: the
/// same value.
#[inline(always)]
#[must_use]
pub fn grad3<F: ShadingFloat>(h: F::Bits, x: F, y: F, z: F) -> F {
    let gx = F::lookup16(&GRAD3[0], h);
    let gy = F::lookup16(&GRAD3[1], h);
    let gz = F::lookup16(&GRAD3[2], h);
    gz.mul_add(z, gy.mul_add(y, gx * x))
}

/// Gradient for 4D: the 16 corners (±1, ±1, ±1, ±1) of the hypercube.
#[inline(always)]
fn grad4<F: ShadingFloat>(h: F::Bits, x: F, y: F, z: F, w: F) -> F {
    let s = |m: u32, v: F| F::select((h & F::Bits::splat(m)).eq_mask(F::Bits::splat(0)), v, -v);
    s(1, x) + s(2, y) + s(4, z) + s(8, w)
}

/// Perlin's fade curve `6t⁵ - 15t⁴ + 10t³`.
#[inline(always)]
#[must_use]
pub fn fade<F: ShadingFloat>(t: F) -> F {
    t * t * t * (t * (t * F::c(6.0) - F::c(15.0)) + F::c(10.0))
}

#[inline(always)]
fn lerp<F: ShadingFloat>(t: F, a: F, b: F) -> F {
    a + t * (b - a)
}

/// `x` reduced modulo the hash period into [-2^31, 2^31] (`x - 2^32·round(x/2^32)`, exact in
/// binary floating point), so that the bits of its `floor` ([`ShadingFloat::lattice_bits`]) are
/// those of `floor(x)` modulo 2^32 — what the hash would see with unbounded integers — and its fraction
/// is that of `x`. Without it, lattice coordinates beyond ±2^31 saturate and every cell there
/// hashes alike. The identity (bit for bit) where |x| < 2^31.
#[inline(always)]
fn reduce_to_hash_period<F: ShadingFloat>(x: F) -> F {
    let r = x - F::c(HASH_PERIOD) * (x * F::c(1.0 / HASH_PERIOD)).round();
    F::select(is_big(x), r, x)
}

/// Lanes where `x` is beyond the range [`reduce_to_hash_period`] leaves alone.
#[inline(always)]
fn is_big<F: ShadingFloat>(x: F) -> F::Mask {
    x.abs().ge(F::c(HASH_PERIOD * 0.5))
}

/// The coordinates `c`, each reduced to the hash period ([`reduce_to_hash_period`]); one test
/// for all of them, and the reduction only when some lane of some coordinate needs it (a
/// noise call then has one branch, not one per axis).
#[inline(always)]
fn reduce_all<F: ShadingFloat, const N: usize>(c: [F; N]) -> [F; N] {
    let mut big = is_big(c[0]);
    for &x in &c[1..] {
        big = big | is_big(x);
    }
    if big.any() {
        c.map(reduce_to_hash_period)
    } else {
        c
    }
}

/// Lattice cell of one coordinate (reduced to the hash period): `(fraction, bits of floor,
/// bits of floor+1)`, optionally wrapping the lattice with period `p` (`pnoise`).
#[inline(always)]
fn cell<F: ShadingFloat>(x: F, period: Option<F>) -> (F, F::Bits, F::Bits) {
    let xf = x.floor();
    let f = x - xf;
    match period {
        None => {
            let i = xf.lattice_bits();
            (f, i, i.wrapping_add(F::Bits::splat(1)))
        }
        Some(p) => {
            let p = p.round().max(F::c(1.0));
            let i0 = fmod(xf, p);
            let i1 = fmod(xf + F::c(1.0), p);
            (f, i0.floor_bits(), i1.floor_bits())
        }
    }
}

/// Signed Perlin gradient noise in 3D, range ≈ [-1, 1], 0 at lattice points; `period`
/// repeats the lattice (per axis) and `seed` selects an independent noise.
#[inline]
#[must_use]
pub fn perlin3<F: ShadingFloat>(p: Vec3<F>, period: Option<Vec3<F>>, seed: u32) -> F {
    perlin3_at(p, period, seed)
}

/// [`perlin3`], always inlined: [`SignedNoise`] must hold its whole computation (a callee
/// compiled separately, perhaps in another codegen unit, would hide from the optimizer that
/// the noise is pure — and with it that a dead derivative call may be deleted).
#[inline(always)]
fn perlin3_at<F: ShadingFloat>(p: Vec3<F>, period: Option<Vec3<F>>, seed: u32) -> F {
    let [x, y, z] = reduce_all([p.x, p.y, p.z]);
    let p = Vec3 { x, y, z };
    let (fx, i0, i1) = cell(p.x, period.map(|q| q.x));
    let (fy, j0, j1) = cell(p.y, period.map(|q| q.y));
    let (fz, k0, k1) = cell(p.z, period.map(|q| q.z));
    let one = F::c(1.0);
    let (gx0, gx1) = (fx, fx - one);
    let (gy0, gy1) = (fy, fy - one);
    let (gz0, gz1) = (fz, fz - one);
    let c = move |i, j, k, x, y, z| grad3::<F>(lattice_hash(&[i, j, k], seed), x, y, z);
    let u = fade(fx);
    let v = fade(fy);
    let w = fade(fz);
    let x00 = lerp(u, c(i0, j0, k0, gx0, gy0, gz0), c(i1, j0, k0, gx1, gy0, gz0));
    let x10 = lerp(u, c(i0, j1, k0, gx0, gy1, gz0), c(i1, j1, k0, gx1, gy1, gz0));
    let x01 = lerp(u, c(i0, j0, k1, gx0, gy0, gz1), c(i1, j0, k1, gx1, gy0, gz1));
    let x11 = lerp(u, c(i0, j1, k1, gx0, gy1, gz1), c(i1, j1, k1, gx1, gy1, gz1));
    lerp(w, lerp(v, x00, x10), lerp(v, x01, x11))
}

/// Signed Perlin gradient noise in 4D (hypercube-corner gradients), range ≈ [-1, 1].
#[inline]
#[must_use]
pub fn perlin4<F: ShadingFloat>(p: Vec3<F>, t: F, period: Option<(Vec3<F>, F)>, seed: u32) -> F {
    perlin4_at(p, t, period, seed)
}

/// [`perlin4`], always inlined (see [`perlin3_at`]).
#[inline(always)]
fn perlin4_at<F: ShadingFloat>(p: Vec3<F>, t: F, period: Option<(Vec3<F>, F)>, seed: u32) -> F {
    let [x, y, z, t] = reduce_all([p.x, p.y, p.z, t]);
    let p = Vec3 { x, y, z };
    let (fx, i0, i1) = cell(p.x, period.map(|q| q.0.x));
    let (fy, j0, j1) = cell(p.y, period.map(|q| q.0.y));
    let (fz, k0, k1) = cell(p.z, period.map(|q| q.0.z));
    let (fw, l0, l1) = cell(t, period.map(|q| q.1));
    let one = F::c(1.0);
    // Closures capture by value, so that one compiled out of line reads only its arguments.
    let c = move |i, j, k, l, x, y, z, w| grad4::<F>(lattice_hash(&[i, j, k, l], seed), x, y, z, w);
    let (u, v, s, r) = (fade(fx), fade(fy), fade(fz), fade(fw));
    let slice = move |l, gw: F| {
        let x00 = lerp(u, c(i0, j0, k0, l, fx, fy, fz, gw), c(i1, j0, k0, l, fx - one, fy, fz, gw));
        let x10 = lerp(u, c(i0, j1, k0, l, fx, fy - one, fz, gw), c(i1, j1, k0, l, fx - one, fy - one, fz, gw));
        let x01 = lerp(u, c(i0, j0, k1, l, fx, fy, fz - one, gw), c(i1, j0, k1, l, fx - one, fy, fz - one, gw));
        let x11 =
            lerp(u, c(i0, j1, k1, l, fx, fy - one, fz - one, gw), c(i1, j1, k1, l, fx - one, fy - one, fz - one, gw));
        lerp(s, lerp(v, x00, x10), lerp(v, x01, x11))
    };
    // The 4D corner gradients have length 2 (vs √2 in 3D); scale to the same range.
    lerp(r, slice(l0, fw), slice(l1, fw - one)) * F::c(0.5)
}

/// Where a noise is evaluated: 1D to 4D, as RSL's overloads of `noise(…)` take it.
#[derive(Clone, Copy, Debug)]
pub enum NoiseDomain<F> {
    /// `noise(float)`.
    D1(F),
    /// `noise(float, float)`.
    D2(F, F),
    /// `noise(point)`.
    D3(Vec3<F>),
    /// `noise(point, float)`.
    D4(Vec3<F>, F),
}

impl<F: ShadingFloat> NoiseDomain<F> {
    /// The same domain with each coordinate multiplied by `s`.
    #[inline(always)]
    #[must_use]
    pub fn scaled(self, s: F) -> Self {
        match self {
            Self::D1(x) => Self::D1(x * s),
            Self::D2(x, y) => Self::D2(x * s, y * s),
            Self::D3(p) => Self::D3(p * s),
            Self::D4(p, t) => Self::D4(p * s, t * s),
        }
    }
}

impl<F: Copy> NoiseDomain<F> {
    /// `(dimensions, coordinates)`, unused coordinates filled with `fill`.
    #[inline(always)]
    fn to_coords(self, fill: F) -> (u8, [F; 4]) {
        match self {
            Self::D1(x) => (1, [x, fill, fill, fill]),
            Self::D2(x, y) => (2, [x, y, fill, fill]),
            Self::D3(p) => (3, [p.x, p.y, p.z, fill]),
            Self::D4(p, t) => (4, [p.x, p.y, p.z, t]),
        }
    }

    /// The domain of `dims` dimensions with coordinates `c` (inverse of `to_coords`).
    #[inline(always)]
    fn from_coords(dims: u8, c: [F; 4]) -> Self {
        match dims {
            1 => Self::D1(c[0]),
            2 => Self::D2(c[0], c[1]),
            3 => Self::D3(Vec3 { x: c[0], y: c[1], z: c[2] }),
            _ => Self::D4(Vec3 { x: c[0], y: c[1], z: c[2] }, c[3]),
        }
    }
}

/// Signed noise of a domain of `dims` dimensions, optionally periodic (`period_dims > 0`),
/// as a [`PureFn`] of the four coordinates followed by the four period coordinates, so that
/// dual numbers can take its value and its derivatives from separate calls (see
/// [`ShadingFloat::apply`]).
#[derive(Clone, Copy, Debug)]
struct SignedNoise {
    dims: u8,
    period_dims: u8,
    seed: u32,
}

impl PureFn<8> for SignedNoise {
    // Inlined into every caller: out of line, the eight coordinates cross the call in
    // memory, the domain and period dimensions (constants at every call site) become
    // run-time branches, and whether the inliner takes it changes from build to build
    // (it is the bulk of a noise shader's time).
    #[inline(always)]
    fn eval<G: ShadingFloat>(&self, a: [G; 8]) -> G {
        let d = NoiseDomain::from_coords(self.dims, [a[0], a[1], a[2], a[3]]);
        let period =
            (self.period_dims > 0).then(|| NoiseDomain::from_coords(self.period_dims, [a[4], a[5], a[6], a[7]]));
        signed_at(d, period, self.seed)
    }
}

/// Signed noise of a domain, through [`SignedNoise`].
#[inline(always)]
fn signed<F: ShadingFloat>(d: NoiseDomain<F>, period: Option<NoiseDomain<F>>, seed: u32) -> F {
    let zero = F::c(0.0);
    let (dims, c) = d.to_coords(zero);
    let (period_dims, pc) = period.map_or((0, [zero; 4]), |p| p.to_coords(zero));
    let f = SignedNoise { dims, period_dims, seed };
    F::apply(&f, [c[0], c[1], c[2], c[3], pc[0], pc[1], pc[2], pc[3]])
}

/// Signed noise of a domain (3D noise with unused axes at 0, plus 4D).
#[inline(always)]
fn signed_at<F: ShadingFloat>(d: NoiseDomain<F>, period: Option<NoiseDomain<F>>, seed: u32) -> F {
    // Unused axes sit at a non-lattice offset so 1D/2D noise is not identically 0 there; a
    // period of another dimension than the domain's repeats nothing (1e9 cells). 1D to 3D
    // share one (inlined) 3D noise.
    let off = F::c(0.5);
    let far = F::c(1e9);
    let n = if let NoiseDomain::D4(p, t) = d {
        let period = period.map(|q| match q {
            NoiseDomain::D4(pp, pt) => (pp, pt),
            _ => (Vec3::splat(far), far),
        });
        perlin4_at(p, t, period, seed)
    } else {
        let (p, period) = match d {
            NoiseDomain::D1(x) => (
                Vec3::new(x, off, off),
                period.map(|q| match q {
                    NoiseDomain::D1(px) => Vec3::new(px, far, far),
                    _ => Vec3::splat(far),
                }),
            ),
            NoiseDomain::D2(x, y) => (
                Vec3::new(x, y, off),
                period.map(|q| match q {
                    NoiseDomain::D2(px, py) => Vec3::new(px, py, far),
                    _ => Vec3::splat(far),
                }),
            ),
            // (D4 took the branch above; naming it here keeps the match free of panics.)
            NoiseDomain::D3(p) | NoiseDomain::D4(p, _) => (
                p,
                period.map(|q| match q {
                    NoiseDomain::D3(pp) => pp,
                    _ => Vec3::splat(far),
                }),
            ),
        };
        perlin3_at(p, period, seed)
    };
    // Non-finite input (NaN, ±inf: the fraction is NaN) reads as 0, so noise stays finite.
    F::select(n.is_nan(), F::c(0.0), clamp(n, F::c(-1.0), F::c(1.0)))
}

/// Signed noise of `d` with `seed` (0 for the float noises; [`VECTOR_SEEDS`] for the three
/// components of the vector noises), not periodic, with the noise kernel inlined into the
/// caller instead of called out of line. For callers that are themselves one compiled
/// function per noise selector (the JIT's runtime library), where the out-of-line call only
/// adds a second call and the copies of its arguments. The same values as [`snoise`]. Types
/// with derivatives cannot use it: theirs come from [`ShadingFloat::apply`].
///
/// # Panics
/// For a type with derivatives ([`ShadingFloat::HAS_DERIVS`]).
#[inline(always)]
#[must_use]
pub fn snoise_inlined<F: ShadingFloat>(d: NoiseDomain<F>, seed: u32) -> F {
    assert!(!F::HAS_DERIVS, "snoise_inlined would drop derivatives");
    signed_at(d, None, seed)
}

/// RSL `snoise`: signed noise in [-1, 1].
#[inline(always)]
#[must_use]
pub fn snoise<F: ShadingFloat>(d: NoiseDomain<F>) -> F {
    signed(d, None, 0)
}

/// RSL `noise` returning float: in [0, 1], 0.5 on lattice points.
#[inline(always)]
#[must_use]
pub fn noise<F: ShadingFloat>(d: NoiseDomain<F>) -> F {
    unsigned_noise(signed(d, None, 0))
}

/// Noise in [0, 1] from signed noise `s` in [-1, 1] (what `noise` is of `snoise`).
#[inline(always)]
#[must_use]
pub fn unsigned_noise<F: ShadingFloat>(s: F) -> F {
    F::c(0.5) + F::c(0.5) * s
}

/// A vector-valued noise: `component(seed)` for each seed of [`VECTOR_SEEDS`].
#[inline(always)]
#[must_use]
pub fn noise_vector<F: ShadingFloat>(component: impl Fn(u32) -> F) -> Vec3<F> {
    Vec3::new(component(VECTOR_SEEDS[0]), component(VECTOR_SEEDS[1]), component(VECTOR_SEEDS[2]))
}

/// RSL `pnoise`: `noise` that repeats with `period` along each axis (periods are rounded to
/// whole cells, at least 1).
#[inline(always)]
#[must_use]
pub fn pnoise<F: ShadingFloat>(d: NoiseDomain<F>, period: NoiseDomain<F>) -> F {
    unsigned_noise(signed(d, Some(period), 0))
}

/// Signed periodic noise.
#[inline(always)]
#[must_use]
pub fn psnoise<F: ShadingFloat>(d: NoiseDomain<F>, period: NoiseDomain<F>) -> F {
    signed(d, Some(period), 0)
}

/// RSL `noise` returning a point/vector/colour: three independent noises in [0, 1].
#[inline(always)]
#[must_use]
pub fn vnoise<F: ShadingFloat>(d: NoiseDomain<F>) -> Vec3<F> {
    noise_vector(|s| unsigned_noise(signed(d, None, s)))
}

/// Signed vector noise in [-1, 1]³.
#[inline(always)]
#[must_use]
pub fn vsnoise<F: ShadingFloat>(d: NoiseDomain<F>) -> Vec3<F> {
    noise_vector(|s| signed(d, None, s))
}

/// Colour noise in [0, 1]³.
#[inline(always)]
#[must_use]
pub fn cnoise<F: ShadingFloat>(d: NoiseDomain<F>) -> Color<F> {
    vnoise(d).to_color()
}

/// Periodic vector noise in [0, 1]³.
#[inline(always)]
#[must_use]
pub fn vpnoise<F: ShadingFloat>(d: NoiseDomain<F>, period: NoiseDomain<F>) -> Vec3<F> {
    noise_vector(|s| unsigned_noise(signed(d, Some(period), s)))
}

/// Lattice bits of a domain's cell.
#[inline(always)]
fn cell_bits<F: ShadingFloat>(d: NoiseDomain<F>) -> ([F::Bits; 4], usize) {
    let (n, c) = d.to_coords(F::c(0.0));
    let n = usize::from(n);
    let c = match n {
        1 => [reduce_all([c[0]])[0], c[1], c[2], c[3]],
        2 => {
            let [x, y] = reduce_all([c[0], c[1]]);
            [x, y, c[2], c[3]]
        }
        3 => {
            let [x, y, z] = reduce_all([c[0], c[1], c[2]]);
            [x, y, z, c[3]]
        }
        _ => reduce_all(c),
    };
    (c.map(ShadingFloat::floor_bits), n)
}

/// RSL `cellnoise` returning float: constant on each unit cell, uniform in [0, 1).
#[inline(always)]
#[must_use]
pub fn cellnoise<F: ShadingFloat>(d: NoiseDomain<F>) -> F {
    let (c, n) = cell_bits(d);
    F::bits_to_unit(lattice_hash(&c[..n], CELL_SEED))
}

/// RSL `cellnoise` returning a point/colour: three independent values in [0, 1).
#[inline(always)]
#[must_use]
pub fn vcellnoise<F: ShadingFloat>(d: NoiseDomain<F>) -> Vec3<F> {
    let (c, n) = cell_bits(d);
    let v = |s: u32| F::bits_to_unit(lattice_hash(&c[..n], CELL_SEED ^ s));
    Vec3::new(v(VECTOR_SEEDS[0]), v(VECTOR_SEEDS[1]), v(VECTOR_SEEDS[2]))
}

/// Fractional Brownian motion: `Σ gain^o · snoise(lacunarity^o · p)` over `octaves` octaves.
/// The octave count is uniform (a loop with a fixed trip count).
#[inline(always)]
#[must_use]
pub fn fbm<F: ShadingFloat>(d: NoiseDomain<F>, octaves: u32, lacunarity: f64, gain: f64) -> F {
    octave_sum(d, octaves, lacunarity, gain, snoise)
}

/// Turbulence: `Σ gain^o · |snoise(lacunarity^o · p)|` (the classic granite/marble sum).
#[inline(always)]
#[must_use]
pub fn turbulence<F: ShadingFloat>(d: NoiseDomain<F>, octaves: u32, lacunarity: f64, gain: f64) -> F {
    octave_sum(d, octaves, lacunarity, gain, |d| snoise(d).abs())
}

/// `Σ gain^o · octave(lacunarity^o · d)` over `octaves` octaves: [`fbm`] and [`turbulence`]
/// with the octave function given (e.g. built on [`snoise_inlined`]).
#[inline(always)]
#[must_use]
pub fn octave_sum<F: ShadingFloat>(
    d: NoiseDomain<F>,
    octaves: u32,
    lacunarity: f64,
    gain: f64,
    octave: impl Fn(NoiseDomain<F>) -> F,
) -> F {
    let mut sum = F::c(0.0);
    let mut amp = 1.0;
    let mut freq = 1.0;
    for _ in 0..octaves {
        sum += F::c(amp) * octave(d.scaled(F::c(freq)));
        amp *= gain;
        freq *= lacunarity;
    }
    sum
}

/// Shorthand: `noise(point)` in [0, 1].
#[inline(always)]
#[must_use]
pub fn noise3<F: ShadingFloat>(p: Vec3<F>) -> F {
    noise(NoiseDomain::D3(p))
}

/// Shorthand: `snoise(point)` in [-1, 1].
#[inline(always)]
#[must_use]
pub fn snoise3<F: ShadingFloat>(p: Vec3<F>) -> F {
    snoise(NoiseDomain::D3(p))
}
