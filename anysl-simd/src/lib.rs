//! # anysl-simd
//!
//! SIMD instantiations of [`ShadingFloat`]: [`F32x4`], [`F32x8`] and [`F32x16`] evaluate 4,
//! 8 or 16 shading points at once over the pinned `wide` crate, with lane masks
//! ([`M32x4`]…) and integer lanes for the noise hash ([`U32x4`]…). Every lane computes what
//! scalar `f32` computes: exact operations are bit-identical, transcendentals agree with
//! std to a few ulp (see *Accuracy*).
//!
//! ```
//! use anysl_core::{ShadingFloat, Vec3};
//! use anysl_simd::{pack_vec3, F32x8};
//!
//! // A shading function written once…
//! fn specular<F: ShadingFloat>(n: Vec3<F>, h: Vec3<F>, roughness: F) -> F {
//!     n.dot(h).max(F::c(0.0)).pow(F::c(1.0) / roughness)
//! }
//!
//! // …run for 8 normals at once,
//! let normals: Vec<Vec3<f32>> = (0..8)
//!     .map(|i| {
//!         let a = i as f32 * 0.15;
//!         Vec3::new(a.sin(), 0.0, a.cos())
//!     })
//!     .collect();
//! let h = Vec3::<F32x8>::c(0.0, 0.0, 1.0);
//! let wide = specular(pack_vec3::<F32x8>(&normals), h, F32x8::splat(0.05));
//!
//! // …and checked lane by lane against scalar f32.
//! for (i, n) in normals.iter().enumerate() {
//!     let scalar = specular(*n, Vec3::c(0.0, 0.0, 1.0), 0.05f32);
//!     let lane = wide.to_array()[i];
//!     assert!((lane - scalar).abs() <= 1e-6 * scalar.abs().max(1e-30));
//! }
//! ```
//!
//! ## Accuracy
//!
//! Measured against std's `f32` functions by `tests/simd_float.rs` (max relative error over
//! the edge cases and 10 000+ random inputs per function, every width; the tests assert
//! 2e-7, and 2e-7 · max(1, \|y·log2 x\|) for `pow`):
//!
//! | function | max rel. error vs std (max ulp) | notes |
//! |---|---|---|
//! | `+ - * / sqrt floor ceil trunc round min max abs` | 0 | bit-identical |
//! | `exp`, `exp2`, `ln`, `log2` | 1.2e-7 (1 ulp) | subnormal results included |
//! | `pow` | 1.2e-7 · max(1, \|y·log2 x\|) (8.4e-6 at \|y·log2 x\| ≈ 114) | f32 `log2 m`, double-f32 product and `exp2` |
//! | `sin`, `cos` | 1.2e-7 (1 ulp) | lanes with \|x\| > 2^19 (and ±inf) go through std |
//! | `tan` | 1.95e-7 (2 ulp) | same fallback |
//! | `asin` | 1.85e-7 (2 ulp) | |
//! | `acos`, `atan`, `atan2` | 1.2e-7 (1 ulp) | |
//!
//! `wide` 1.7.1's own `exp`/`ln` are about as accurate on normal inputs, but its `sin`,
//! `cos`, `tan` (≈5e-7 near multiples of π/2, ≈1e-6 at |x| ≈ 1e3), `asin`, `atan`
//! (≈2.3e-7) and `powf_simd` are not, and `recip`/`recip_sqrt` are 12-bit estimates on AVX;
//! so all transcendentals here are our own kernels (`src/math.rs`), written once over all
//! widths. `pow` is `exp2(y·log2 x)` in f32 lanes: `log2 x = e + log2 m` with `log2 m` from
//! one degree-8 polynomial, `y·log2 x` and the exponential in double-f32, so its only error
//! beyond an ulp is the f32 error of `log2 m` times `|y|` — relative to results of at most 1
//! (every highlight) an absolute error below 5e-8. The kernels need FMA (the workspace builds
//! with `target-cpu=native`).
//!
//! [`Pair<F>`] shades two packets of any of these types together, operation by operation,
//! so that one packet's dependency chains fill the other's latency.
#![warn(missing_docs)]

mod math;
mod pair;
mod soa;

pub use pair::{Pair, PairBits, PairMask};

pub use soa::{pack, pack_color, pack_vec3, unpack, unpack_color, unpack_vec3, Lanes};

/// The constants of the vector math kernels — polynomial coefficients (`c[0] + c[1]·x + …`,
/// evaluated by Horner's rule with FMA), Cody–Waite splits and thresholds — for code
/// generators that emit the same algorithms (the JIT's inline transcendentals): defined
/// once, so both compute the same bits. The algorithms are those of `src/math.rs`.
pub mod kernel_consts {
    pub use crate::math::{
        ASIN_A, ATAN_P, COS_C, EXP2_Q, FRAC_2_PI, LN2_HI16, LN2_LO16, LOG2E_HI, LOG2E_LO, LOG2_Q, LOG_L, PIO2_1,
        PIO2_2, PIO2_3, PIO2_LO, PI_HI, PI_LO, POW_HALVES_MIN, SIN_S, SQRT_HALF_BITS, TAN_T, TRIG_VECTOR_LIMIT,
    };
    /// The kernels' `fma` is one fused operation (a build with FMA); without FMA, `wide`
    /// computes `a·b + c` with two roundings.
    pub const FUSED_MUL_ADD: bool = cfg!(target_feature = "fma");
}

use anysl_core::{Blend, LatticeBits, Mask, ShadingFloat};
use core::fmt;
use core::ops::{
    Add, AddAssign, BitAnd, BitOr, BitXor, Div, DivAssign, Mul, MulAssign, Neg, Not, Shl, Shr, Sub, SubAssign,
};

/// Broadcasts of a run-time `f32` to every lane, one `vbroadcastss` each: `wide`'s `splat`
/// transmutes `[v; N]`, which LLVM does not always recognize as a broadcast (at 16 lanes it
/// assembled the vector from 128-bit pieces, lane by lane, 30 instructions for a light's
/// numbers). Constants fold either way.
#[allow(non_snake_case)]
mod splat {
    #[cfg(target_arch = "x86_64")]
    use core::arch::x86_64 as arch;

    /// 4 lanes.
    #[inline(always)]
    pub fn f32x4(v: f32) -> wide::f32x4 {
        #[cfg(all(target_arch = "x86_64", target_feature = "sse"))]
        // SAFETY: `__m128` and `wide::f32x4` are both four f32 lanes, 16 bytes.
        return unsafe { core::mem::transmute::<arch::__m128, wide::f32x4>(arch::_mm_set1_ps(v)) };
        #[allow(unreachable_code)]
        wide::f32x4::splat(v)
    }

    /// 8 lanes.
    #[inline(always)]
    pub fn f32x8(v: f32) -> wide::f32x8 {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
        // SAFETY: `__m256` and `wide::f32x8` (with AVX) are both eight f32 lanes, 32 bytes.
        return unsafe { core::mem::transmute::<arch::__m256, wide::f32x8>(arch::_mm256_set1_ps(v)) };
        #[allow(unreachable_code)]
        wide::f32x8::splat(v)
    }

    /// 16 lanes.
    #[inline(always)]
    pub fn f32x16(v: f32) -> wide::f32x16 {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        // SAFETY: `__m512` and `wide::f32x16` (with AVX-512F) are both sixteen f32 lanes, 64 bytes.
        return unsafe { core::mem::transmute::<arch::__m512, wide::f32x16>(arch::_mm512_set1_ps(v)) };
        #[allow(unreachable_code)]
        {
            let half = f32x8(v);
            // SAFETY: without AVX-512F, `wide::f32x16` is two `f32x8` halves, 64 bytes.
            unsafe { core::mem::transmute::<[wide::f32x8; 2], wide::f32x16>([half, half]) }
        }
    }
}

/// Defines one SIMD width: the float type, its mask and its integer lanes, with every
/// trait the instantiation needs. All widths share this text, so an operation cannot be
/// missing from one of them.
macro_rules! simd_width {
    (
        $lanes:literal, $name:literal,
        $F:ident($wf:ident), $M:ident, $U:ident($wu:ident), $wi:ident, $from_int:ident, $lookup:ident
    ) => {
        #[doc = concat!("`", $lanes, "` f32 lanes (shading points) evaluated together; a [`ShadingFloat`].")]
        #[derive(Clone, Copy, Default, PartialEq)]
        #[repr(transparent)]
        pub struct $F(pub wide::$wf);

        #[doc = concat!("Lane truth values of [`", stringify!($F), "`] comparisons (all-ones / all-zeros lanes).")]
        #[derive(Clone, Copy, Default)]
        #[repr(transparent)]
        pub struct $M(pub wide::$wf);

        #[doc = concat!("`", $lanes, "` u32 lanes: the [`LatticeBits`] of [`", stringify!($F), "`].")]
        #[derive(Clone, Copy, Default, PartialEq, Eq)]
        #[repr(transparent)]
        pub struct $U(pub wide::$wu);

        impl $F {
            /// Every lane `v`.
            #[inline(always)]
            #[must_use]
            pub fn splat(v: f32) -> Self {
                Self(splat::$wf(v))
            }
            /// The lanes as an array.
            #[inline(always)]
            #[must_use]
            pub fn to_array(self) -> [f32; $lanes] {
                self.0.to_array()
            }
        }

        impl From<[f32; $lanes]> for $F {
            #[inline(always)]
            fn from(v: [f32; $lanes]) -> Self {
                Self(wide::$wf::from(v))
            }
        }

        impl From<$F> for [f32; $lanes] {
            #[inline(always)]
            fn from(v: $F) -> Self {
                v.to_array()
            }
        }

        impl fmt::Debug for $F {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}{:?}", stringify!($F), self.to_array())
            }
        }

        impl Add for $F {
            type Output = Self;
            #[inline(always)]
            fn add(self, rhs: Self) -> Self {
                Self(self.0 + rhs.0)
            }
        }
        impl Sub for $F {
            type Output = Self;
            #[inline(always)]
            fn sub(self, rhs: Self) -> Self {
                Self(self.0 - rhs.0)
            }
        }
        impl Mul for $F {
            type Output = Self;
            #[inline(always)]
            fn mul(self, rhs: Self) -> Self {
                Self(self.0 * rhs.0)
            }
        }
        impl Div for $F {
            type Output = Self;
            #[inline(always)]
            fn div(self, rhs: Self) -> Self {
                Self(self.0 / rhs.0)
            }
        }
        impl Neg for $F {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                Self(-self.0)
            }
        }
        impl AddAssign for $F {
            #[inline(always)]
            fn add_assign(&mut self, rhs: Self) {
                *self = *self + rhs;
            }
        }
        impl SubAssign for $F {
            #[inline(always)]
            fn sub_assign(&mut self, rhs: Self) {
                *self = *self - rhs;
            }
        }
        impl MulAssign for $F {
            #[inline(always)]
            fn mul_assign(&mut self, rhs: Self) {
                *self = *self * rhs;
            }
        }
        impl DivAssign for $F {
            #[inline(always)]
            fn div_assign(&mut self, rhs: Self) {
                *self = *self / rhs;
            }
        }

        impl Blend<$F> for $F {
            #[inline(always)]
            fn blend(m: $M, a: Self, b: Self) -> Self {
                <$F as ShadingFloat>::select(m, a, b)
            }
        }

        impl ShadingFloat for $F {
            type Mask = $M;
            type Bits = $U;
            const LANES: usize = $lanes;
            const UNIT_ROUNDOFF: f64 = 5.960464477539063e-8;
            const NAME: &'static str = $name;

            #[inline(always)]
            fn c(v: f64) -> Self {
                Self::splat(v as f32)
            }
            #[inline(always)]
            fn lane(self, i: usize) -> f64 {
                self.to_array()[i] as f64
            }
            #[inline]
            fn from_lanes(lanes: &[f64]) -> Self {
                assert_eq!(lanes.len(), $lanes, "from_lanes needs exactly LANES values");
                Self::from(core::array::from_fn::<f32, $lanes, _>(|i| lanes[i] as f32))
            }
            #[inline(always)]
            fn load(src: &[f32]) -> Self {
                let arr: [f32; $lanes] = src[..$lanes].try_into().expect("LANES values");
                Self::from(arr)
            }
            #[inline(always)]
            fn store(self, dst: &mut [f32]) {
                dst[..$lanes].copy_from_slice(&self.to_array());
            }
            #[inline(always)]
            fn select(m: $M, a: Self, b: Self) -> Self {
                Self(m.0.select(a.0, b.0))
            }
            #[inline(always)]
            fn lt(self, rhs: Self) -> $M {
                $M(self.0.simd_lt(rhs.0))
            }
            #[inline(always)]
            fn le(self, rhs: Self) -> $M {
                $M(self.0.simd_le(rhs.0))
            }
            #[inline(always)]
            fn gt(self, rhs: Self) -> $M {
                $M(self.0.simd_gt(rhs.0))
            }
            #[inline(always)]
            fn ge(self, rhs: Self) -> $M {
                $M(self.0.simd_ge(rhs.0))
            }
            #[inline(always)]
            fn eq(self, rhs: Self) -> $M {
                $M(self.0.simd_eq(rhs.0))
            }
            #[inline(always)]
            fn is_nan(self) -> $M {
                $M(math::is_nan(self.0))
            }
            #[inline(always)]
            fn abs(self) -> Self {
                Self(math::abs(self.0))
            }
            #[inline(always)]
            fn floor(self) -> Self {
                Self(self.0.floor())
            }
            #[inline(always)]
            fn ceil(self) -> Self {
                Self(self.0.ceil())
            }
            #[inline(always)]
            fn round(self) -> Self {
                Self(math::round(self.0))
            }
            #[inline(always)]
            fn trunc(self) -> Self {
                Self(self.0.trunc())
            }
            #[inline(always)]
            fn min(self, rhs: Self) -> Self {
                Self(math::min(self.0, rhs.0))
            }
            #[inline(always)]
            fn max(self, rhs: Self) -> Self {
                Self(math::max(self.0, rhs.0))
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                Self(self.0.sqrt())
            }
            #[inline(always)]
            fn mul_add(self, m: Self, a: Self) -> Self {
                Self(self.0.mul_add(m.0, a.0))
            }
            #[inline(always)]
            fn rsqrt(self) -> Self {
                Self(math::rsqrt(self.0))
            }
            #[inline(always)]
            fn exp(self) -> Self {
                Self(math::exp(self.0))
            }
            #[inline(always)]
            fn exp2(self) -> Self {
                Self(math::exp2(self.0))
            }
            #[inline(always)]
            fn ln(self) -> Self {
                Self(math::ln(self.0))
            }
            #[inline(always)]
            fn log2(self) -> Self {
                Self(math::log2(self.0))
            }
            #[inline(always)]
            fn pow(self, y: Self) -> Self {
                Self(math::pow(self.0, y.0))
            }
            #[inline(always)]
            fn pow2(x: [Self; 2], y: [Self; 2]) -> [Self; 2] {
                math::pow(math::Gang(x.map(|v| v.0)), math::Gang(y.map(|v| v.0))).0.map(Self)
            }
            #[inline(always)]
            fn pow4(x: [Self; 4], y: [Self; 4]) -> [Self; 4] {
                math::pow(math::Gang(x.map(|v| v.0)), math::Gang(y.map(|v| v.0))).0.map(Self)
            }
            #[inline(always)]
            fn sin(self) -> Self {
                Self(math::sin(self.0))
            }
            #[inline(always)]
            fn cos(self) -> Self {
                Self(math::cos(self.0))
            }
            #[inline(always)]
            fn tan(self) -> Self {
                Self(math::tan(self.0))
            }
            #[inline(always)]
            fn asin(self) -> Self {
                Self(math::asin(self.0))
            }
            #[inline(always)]
            fn acos(self) -> Self {
                Self(math::acos(self.0))
            }
            #[inline(always)]
            fn atan(self) -> Self {
                Self(math::atan(self.0))
            }
            #[inline(always)]
            fn atan2(self, x: Self) -> Self {
                Self(math::atan2(self.0, x.0))
            }
            #[inline(always)]
            fn floor_bits(self) -> $U {
                $U(wide::bytemuck::cast(math::floor_to_i32(self.0)))
            }
            #[inline(always)]
            fn lattice_bits(self) -> $U {
                // The conversion's out-of-range answer, i32::MIN, is 2^31 modulo 2^32.
                $U(wide::bytemuck::cast(self.0.fast_trunc_int()))
            }
            #[inline(always)]
            fn lookup16(table: &[f32; 16], h: $U) -> Self {
                Self(math::$lookup(table, h.0))
            }
            #[inline(always)]
            fn bits_to_unit(h: $U) -> Self {
                // h >> 8 < 2^24: exact as i32 and as f32.
                let top: wide::$wi = wide::bytemuck::cast(h.0 >> 8);
                Self(wide::$wf::$from_int(top) * wide::$wf::splat(1.0 / 16_777_216.0))
            }
            #[inline(always)]
            fn bits_to_float_signed(h: $U) -> Self {
                Self(wide::$wf::$from_int(wide::bytemuck::cast(h.0)))
            }
        }

        impl Lanes for $F {
            #[inline]
            fn gather<T>(src: &[T], f: impl Fn(&T) -> f32) -> Self {
                let last = src.len().checked_sub(1).expect("gather from an empty slice");
                Self::from(core::array::from_fn::<f32, $lanes, _>(|i| f(&src[i.min(last)])))
            }
            #[inline]
            fn scatter<T>(self, dst: &mut [T], mut f: impl FnMut(&mut T, f32)) {
                for (d, v) in dst.iter_mut().zip(self.to_array()) {
                    f(d, v);
                }
            }
        }

        impl $M {
            /// Bit `i` set when lane `i` is true.
            #[inline(always)]
            #[must_use]
            pub fn to_bitmask(self) -> u32 {
                self.0.to_bitmask()
            }
            /// The lanes as booleans.
            #[inline]
            #[must_use]
            pub fn to_array(self) -> [bool; $lanes] {
                let m = self.to_bitmask();
                core::array::from_fn(|i| m & (1 << i) != 0)
            }
        }

        impl From<[bool; $lanes]> for $M {
            #[inline]
            fn from(v: [bool; $lanes]) -> Self {
                let bits = core::array::from_fn::<u32, $lanes, _>(|i| if v[i] { u32::MAX } else { 0 });
                Self(wide::bytemuck::cast(wide::$wu::from(bits)))
            }
        }

        impl PartialEq for $M {
            #[inline]
            fn eq(&self, rhs: &Self) -> bool {
                self.to_bitmask() == rhs.to_bitmask()
            }
        }

        impl fmt::Debug for $M {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}{:?}", stringify!($M), self.to_array())
            }
        }

        impl BitAnd for $M {
            type Output = Self;
            #[inline(always)]
            fn bitand(self, rhs: Self) -> Self {
                Self(self.0 & rhs.0)
            }
        }
        impl BitOr for $M {
            type Output = Self;
            #[inline(always)]
            fn bitor(self, rhs: Self) -> Self {
                Self(self.0 | rhs.0)
            }
        }
        impl Not for $M {
            type Output = Self;
            #[inline(always)]
            fn not(self) -> Self {
                Self(!self.0)
            }
        }

        impl Mask for $M {
            const LANES: usize = $lanes;
            #[inline(always)]
            fn splat(b: bool) -> Self {
                Self(wide::$wf::from_bits(wide::$wu::splat(if b { u32::MAX } else { 0 })))
            }
            #[inline(always)]
            fn any(self) -> bool {
                self.0.any()
            }
            #[inline(always)]
            fn all(self) -> bool {
                self.0.all()
            }
            #[inline(always)]
            fn lane(self, i: usize) -> bool {
                assert!(i < $lanes, "lane {i} out of range 0..{}", $lanes);
                self.to_bitmask() & (1 << i) != 0
            }
            #[inline(always)]
            fn from_bits(bits: u32) -> Self {
                // Lane i tests bit i: splat, keep one bit per lane, compare (three instructions).
                let lane_bit = wide::$wu::from(core::array::from_fn::<u32, $lanes, _>(|i| 1 << i));
                let hit = (wide::$wu::splat(bits) & lane_bit).simd_eq(lane_bit);
                Self(wide::bytemuck::cast(hit))
            }
            #[inline(always)]
            fn to_bits(self) -> u32 {
                self.to_bitmask()
            }
            #[inline(always)]
            fn select_mask(m: Self, a: Self, b: Self) -> Self {
                Self(m.0.select(a.0, b.0))
            }
        }

        impl $U {
            /// The lanes as an array.
            #[inline(always)]
            #[must_use]
            pub fn to_array(self) -> [u32; $lanes] {
                self.0.to_array()
            }
        }

        impl From<[u32; $lanes]> for $U {
            #[inline(always)]
            fn from(v: [u32; $lanes]) -> Self {
                Self(wide::$wu::from(v))
            }
        }

        impl fmt::Debug for $U {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}{:?}", stringify!($U), self.to_array())
            }
        }

        impl BitAnd for $U {
            type Output = Self;
            #[inline(always)]
            fn bitand(self, rhs: Self) -> Self {
                Self(self.0 & rhs.0)
            }
        }
        impl BitOr for $U {
            type Output = Self;
            #[inline(always)]
            fn bitor(self, rhs: Self) -> Self {
                Self(self.0 | rhs.0)
            }
        }
        impl BitXor for $U {
            type Output = Self;
            #[inline(always)]
            fn bitxor(self, rhs: Self) -> Self {
                Self(self.0 ^ rhs.0)
            }
        }
        impl Shr<u32> for $U {
            type Output = Self;
            /// Logical shift; like `u32::wrapping_shr`, the amount is taken modulo 32.
            #[inline(always)]
            fn shr(self, rhs: u32) -> Self {
                Self(self.0 >> rhs)
            }
        }
        impl Shl<u32> for $U {
            type Output = Self;
            /// Like `u32::wrapping_shl`, the amount is taken modulo 32.
            #[inline(always)]
            fn shl(self, rhs: u32) -> Self {
                Self(self.0 << rhs)
            }
        }

        impl LatticeBits for $U {
            type Mask = $M;
            #[inline(always)]
            fn splat(v: u32) -> Self {
                Self(wide::$wu::splat(v))
            }
            #[inline(always)]
            fn wrapping_add(self, rhs: Self) -> Self {
                Self(self.0 + rhs.0)
            }
            #[inline(always)]
            fn wrapping_mul(self, rhs: Self) -> Self {
                Self(self.0 * rhs.0)
            }
            #[inline(always)]
            fn eq_mask(self, rhs: Self) -> $M {
                $M(wide::bytemuck::cast(self.0.simd_eq(rhs.0)))
            }
            #[inline(always)]
            fn lane(self, i: usize) -> u32 {
                self.to_array()[i]
            }
        }
    };
}

simd_width!(4, "f32x4", F32x4(f32x4), M32x4, U32x4(u32x4), i32x4, from_i32x4, lookup16_x4);
simd_width!(8, "f32x8", F32x8(f32x8), M32x8, U32x8(u32x8), i32x8, from_i32x8, lookup16_x8);
simd_width!(16, "f32x16", F32x16(f32x16), M32x16, U32x16(u32x16), i32x16, from_i32x16, lookup16_x16);
