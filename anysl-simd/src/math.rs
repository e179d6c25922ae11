//! Vectorized f32 math kernels, written once over the private [`Wide`] trait and shared by
//! every lane width.
//!
//! All kernels are branch-free (the one exception is the cold scalar fallback of the
//! trigonometric functions for |x| > 2^19, see [`sin`]) and rely on fused multiply-add for
//! their extended-precision steps (`two_prod` via `fma(a, b, -a·b)`), so build with FMA
//! available (`target-cpu=native` or x86-64-v3).
//!
//! Polynomials: Chebyshev interpolants of the reduced functions, converted to monomial
//! form and rounded to f32, generated and checked by `tools/polyfit.py` (method:
//! L. N. Trefethen, *Approximation Theory and Approximation Practice*, ch. 16). Range
//! reductions: Cody & Waite, *Software Manual for the Elementary Functions* (1980), with
//! FMA-exact products. Special values follow C99 Annex F, i.e. the `f32` methods of std.

// Coefficients are printed by tools/polyfit.py with 9 significant digits, which round to
// exactly the intended f32; keeping them verbatim makes them checkable against the script.
#![allow(clippy::excessive_precision)]

use core::ops::{Add, BitAnd, BitOr, BitXor, Div, Mul, Neg, Not, Shl, Shr, Sub};

/// The operations of a `wide` f32 vector the kernels need (implemented by `impl_wide!`).
///
/// Masks are float vectors whose lanes are all-ones or all-zeros, as in `wide`.
pub(crate) trait Wide:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + BitAnd<Output = Self>
    + BitOr<Output = Self>
    + BitXor<Output = Self>
    + Not<Output = Self>
{
    /// Signed 32-bit integer lanes of the same width.
    type I: Copy
        + Add<Output = Self::I>
        + Sub<Output = Self::I>
        + BitAnd<Output = Self::I>
        + BitOr<Output = Self::I>
        + BitXor<Output = Self::I>
        + Shl<u32, Output = Self::I>
        + Shr<u32, Output = Self::I>;
    /// Every lane `v`.
    fn splat(v: f32) -> Self;
    /// Every integer lane `v`.
    fn splat_i(v: i32) -> Self::I;
    /// Bit pattern as integers.
    fn bits(self) -> Self::I;
    /// Float from bit pattern.
    fn from_bits(i: Self::I) -> Self;
    /// `self * m + a` with one rounding.
    fn fma(self, m: Self, a: Self) -> Self;
    /// Correctly rounded square root.
    fn sqrt(self) -> Self;
    /// The hardware estimate of 1/√x, the one `anysl_core::rsqrt_f32` starts from.
    fn rsqrt_estimate(self) -> Self;
    /// Round toward -inf.
    fn floor(self) -> Self;
    /// Round toward zero.
    fn trunc(self) -> Self;
    /// Round to nearest, ties to even.
    fn round_even(self) -> Self;
    /// Truncating conversion; out of range and NaN give `i32::MIN` (the x86 "indefinite").
    fn to_int(self) -> Self::I;
    /// Integer to float, rounding to nearest.
    fn from_int(i: Self::I) -> Self;
    /// x86's `minps(self, r)`: `self < r ? self : r` (`r` where either is NaN).
    fn hw_min(self, r: Self) -> Self;
    /// x86's `maxps(self, r)`: `self > r ? self : r` (`r` where either is NaN).
    fn hw_max(self, r: Self) -> Self;
    /// `self < r` mask.
    fn lt(self, r: Self) -> Self;
    /// `self <= r` mask.
    fn le(self, r: Self) -> Self;
    /// `self == r` mask.
    fn eq(self, r: Self) -> Self;
    /// `m ? a : b`.
    fn select(m: Self, a: Self, b: Self) -> Self;
    /// `a == b` on integer lanes, as a float-lane mask.
    fn eq_i(a: Self::I, b: Self::I) -> Self;
    /// Some lane of the mask is set.
    fn any(self) -> bool;
    /// Every lane of the mask is set.
    fn all(self) -> bool;
    /// Replaces the lanes selected by `m` with `f(lane)` (slow path, not vectorized).
    fn map_where(self, m: Self, f: fn(f32) -> f32) -> Self;
    /// Lane 0.
    fn first(self) -> f32;
}

/// Implements [`Wide`] for a `wide` float type and its integer twin.
macro_rules! impl_wide {
    ($f:ident, $i:ident, $from_int:ident, $rsqrt:ident) => {
        impl Wide for wide::$f {
            type I = wide::$i;
            #[inline(always)]
            fn splat(v: f32) -> Self {
                wide::$f::splat(v)
            }
            #[inline(always)]
            fn splat_i(v: i32) -> Self::I {
                wide::$i::splat(v)
            }
            #[inline(always)]
            fn bits(self) -> Self::I {
                wide::bytemuck::cast(self)
            }
            #[inline(always)]
            fn from_bits(i: Self::I) -> Self {
                wide::bytemuck::cast(i)
            }
            #[inline(always)]
            fn fma(self, m: Self, a: Self) -> Self {
                self.mul_add(m, a)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                wide::$f::sqrt(self)
            }
            #[inline(always)]
            fn rsqrt_estimate(self) -> Self {
                $rsqrt(self)
            }
            #[inline(always)]
            fn floor(self) -> Self {
                wide::$f::floor(self)
            }
            #[inline(always)]
            fn trunc(self) -> Self {
                wide::$f::trunc(self)
            }
            #[inline(always)]
            fn round_even(self) -> Self {
                self.round_ties_even()
            }
            #[inline(always)]
            fn to_int(self) -> Self::I {
                self.fast_trunc_int()
            }
            #[inline(always)]
            fn from_int(i: Self::I) -> Self {
                wide::$f::$from_int(i)
            }
            #[inline(always)]
            fn hw_min(self, r: Self) -> Self {
                self.fast_min(r)
            }
            #[inline(always)]
            fn hw_max(self, r: Self) -> Self {
                self.fast_max(r)
            }
            #[inline(always)]
            fn lt(self, r: Self) -> Self {
                self.simd_lt(r)
            }
            #[inline(always)]
            fn le(self, r: Self) -> Self {
                self.simd_le(r)
            }
            #[inline(always)]
            fn eq(self, r: Self) -> Self {
                self.simd_eq(r)
            }
            #[inline(always)]
            fn select(m: Self, a: Self, b: Self) -> Self {
                m.select(a, b)
            }
            #[inline(always)]
            fn eq_i(a: Self::I, b: Self::I) -> Self {
                wide::bytemuck::cast(a.simd_eq(b))
            }
            #[inline(always)]
            fn any(self) -> bool {
                wide::$f::any(self)
            }
            #[inline(always)]
            fn all(self) -> bool {
                wide::$f::all(self)
            }
            #[inline(always)]
            fn first(self) -> f32 {
                self.as_array()[0]
            }
            #[cold]
            #[inline(never)]
            fn map_where(self, m: Self, f: fn(f32) -> f32) -> Self {
                let mut v = self.to_array();
                let m = m.to_bitmask();
                for (i, x) in v.iter_mut().enumerate() {
                    if m & (1 << i) != 0 {
                        *x = f(*x);
                    }
                }
                wide::$f::from(v)
            }
        }
    };
}

impl_wide!(f32x4, i32x4, from_i32x4, rsqrt_estimate_x4);
impl_wide!(f32x8, i32x8, from_i32x8, rsqrt_estimate_x8);
impl_wide!(f32x16, i32x16, from_i32x16, rsqrt_estimate_x16);

/// `N` packets of one `wide` type computed in lockstep ([`Wide`] for them): each operation is
/// issued for every packet next to the others, and a mask test (`any`, `all`) asks them all,
/// so a kernel's scalar branches (`pow`'s steering by a uniform exponent) are taken once for
/// all packets and their dependency chains overlap inside one basic block. The kernels make a
/// lane's bits depend on its own inputs only, whichever branch the vector takes, so each packet
/// gets the bits it gets alone.
#[derive(Clone, Copy)]
pub(crate) struct Gang<W, const N: usize>(pub(crate) [W; N]);

macro_rules! gang_binop {
    ($($tr:ident $f:ident),*) => {$(
        impl<W: Copy + $tr<Output = W>, const N: usize> $tr for Gang<W, N> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, r: Self) -> Self {
                Gang(core::array::from_fn(|i| $tr::$f(self.0[i], r.0[i])))
            }
        }
    )*};
}
gang_binop!(Add add, Sub sub, Mul mul, Div div, BitAnd bitand, BitOr bitor, BitXor bitxor);

macro_rules! gang_unop {
    ($($tr:ident $f:ident),*) => {$(
        impl<W: Copy + $tr<Output = W>, const N: usize> $tr for Gang<W, N> {
            type Output = Self;
            #[inline(always)]
            fn $f(self) -> Self {
                Gang(self.0.map($tr::$f))
            }
        }
    )*};
}
gang_unop!(Neg neg, Not not);

macro_rules! gang_shift {
    ($($tr:ident $f:ident),*) => {$(
        impl<W: Copy + $tr<u32, Output = W>, const N: usize> $tr<u32> for Gang<W, N> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, r: u32) -> Self {
                Gang(self.0.map(|x| $tr::$f(x, r)))
            }
        }
    )*};
}
gang_shift!(Shl shl, Shr shr);

impl<W: Wide, const N: usize> Gang<W, N> {
    #[inline(always)]
    fn zip(self, r: Self, f: impl Fn(W, W) -> W) -> Self {
        Gang(core::array::from_fn(|i| f(self.0[i], r.0[i])))
    }
}

/// `Wide` methods of a [`Gang`] that apply the packet type's method to each packet:
/// `map:` unary (`fn(self) -> Self`), `zip:` binary (`fn(self, Self) -> Self`).
macro_rules! gang_forward {
    (map: $($f:ident),*) => {$(
        #[inline(always)]
        fn $f(self) -> Self {
            Gang(self.0.map(W::$f))
        }
    )*};
    (zip: $($f:ident),*) => {$(
        #[inline(always)]
        fn $f(self, r: Self) -> Self {
            self.zip(r, W::$f)
        }
    )*};
}

impl<W: Wide, const N: usize> Wide for Gang<W, N> {
    type I = Gang<W::I, N>;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        Gang([W::splat(v); N])
    }
    #[inline(always)]
    fn splat_i(v: i32) -> Self::I {
        Gang([W::splat_i(v); N])
    }
    #[inline(always)]
    fn bits(self) -> Self::I {
        Gang(self.0.map(W::bits))
    }
    #[inline(always)]
    fn from_bits(i: Self::I) -> Self {
        Gang(i.0.map(W::from_bits))
    }
    #[inline(always)]
    fn fma(self, m: Self, a: Self) -> Self {
        Gang(core::array::from_fn(|i| self.0[i].fma(m.0[i], a.0[i])))
    }
    // Each packet's own op: unary ones through `map`, binary ones through `zip`.
    gang_forward!(map: sqrt, rsqrt_estimate, floor, trunc, round_even);
    #[inline(always)]
    fn to_int(self) -> Self::I {
        Gang(self.0.map(W::to_int))
    }
    #[inline(always)]
    fn from_int(i: Self::I) -> Self {
        Gang(i.0.map(W::from_int))
    }
    gang_forward!(zip: hw_min, hw_max, lt, le, eq);
    #[inline(always)]
    fn select(m: Self, a: Self, b: Self) -> Self {
        Gang(core::array::from_fn(|i| W::select(m.0[i], a.0[i], b.0[i])))
    }
    #[inline(always)]
    fn eq_i(a: Self::I, b: Self::I) -> Self {
        Gang(core::array::from_fn(|i| W::eq_i(a.0[i], b.0[i])))
    }
    #[inline(always)]
    fn any(self) -> bool {
        self.0.into_iter().fold(W::splat(0.0), |a, m| a | m).any()
    }
    #[inline(always)]
    fn all(self) -> bool {
        self.0.into_iter().fold(!W::splat(0.0), |a, m| a & m).all()
    }
    #[inline(always)]
    fn map_where(self, m: Self, f: fn(f32) -> f32) -> Self {
        Gang(core::array::from_fn(|i| self.0[i].map_where(m.0[i], f)))
    }
    #[inline(always)]
    fn first(self) -> f32 {
        self.0[0].first()
    }
}

#[cfg(target_arch = "x86_64")]
use core::arch::x86_64 as arch;

/// The estimate of `anysl_core::rsqrt_f32` at 4 lanes (`vrsqrt14ps` or `rsqrtps`).
#[inline(always)]
fn rsqrt_estimate_x4(x: wide::f32x4) -> wide::f32x4 {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx512f", target_feature = "avx512vl"))]
    // SAFETY: `__m128` and `wide::f32x4` are four f32 lanes; AVX-512F/VL are enabled.
    return unsafe { core::mem::transmute(arch::_mm_rsqrt14_ps(core::mem::transmute(x))) };
    #[cfg(all(
        target_arch = "x86_64",
        target_feature = "sse",
        not(all(target_feature = "avx512f", target_feature = "avx512vl"))
    ))]
    // SAFETY: as above, with SSE.
    return unsafe { core::mem::transmute(arch::_mm_rsqrt_ps(core::mem::transmute(x))) };
    #[allow(unreachable_code)]
    wide::f32x4::from(x.to_array().map(|v| 1.0 / v.sqrt()))
}

/// The estimate at 8 lanes.
#[inline(always)]
fn rsqrt_estimate_x8(x: wide::f32x8) -> wide::f32x8 {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx512f", target_feature = "avx512vl"))]
    // SAFETY: `__m256` and `wide::f32x8` are eight f32 lanes; AVX-512F/VL are enabled.
    return unsafe { core::mem::transmute(arch::_mm256_rsqrt14_ps(core::mem::transmute(x))) };
    #[cfg(all(
        target_arch = "x86_64",
        target_feature = "avx",
        not(all(target_feature = "avx512f", target_feature = "avx512vl"))
    ))]
    // SAFETY: as above, with AVX.
    return unsafe { core::mem::transmute(arch::_mm256_rsqrt_ps(core::mem::transmute(x))) };
    #[allow(unreachable_code)]
    wide::f32x8::from(x.to_array().map(|v| 1.0 / v.sqrt()))
}

/// The estimate at 16 lanes.
#[inline(always)]
fn rsqrt_estimate_x16(x: wide::f32x16) -> wide::f32x16 {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx512f", target_feature = "avx512vl"))]
    // SAFETY: `__m512` and `wide::f32x16` are sixteen f32 lanes; AVX-512F is enabled.
    return unsafe { core::mem::transmute(arch::_mm512_rsqrt14_ps(core::mem::transmute(x))) };
    #[allow(unreachable_code)]
    {
        // SAFETY: without AVX-512, `wide::f32x16` is two `f32x8` halves.
        let h: [wide::f32x8; 2] = unsafe { core::mem::transmute(x) };
        unsafe { core::mem::transmute([rsqrt_estimate_x8(h[0]), rsqrt_estimate_x8(h[1])]) }
    }
}

/// `table[h & 15]` at 4 lanes: two 8-entry permutes (AVX2) and a blend on bit 3.
#[inline(always)]
pub(crate) fn lookup16_x4(table: &[f32; 16], h: wide::u32x4) -> wide::f32x4 {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
    // SAFETY: AVX2 is enabled; `__m128i` and `wide::u32x4` are four 32-bit lanes, the table
    // halves are eight f32 each. `vpermps` reads index bits 2..0; the upper half of the
    // widened index is never looked at (only the low four result lanes are kept).
    unsafe {
        let idx: arch::__m128i = core::mem::transmute(h);
        let wide_idx = arch::_mm256_castsi128_si256(idx);
        let lo = arch::_mm256_loadu_ps(table.as_ptr());
        let hi = arch::_mm256_loadu_ps(table.as_ptr().add(8));
        let a = arch::_mm256_castps256_ps128(arch::_mm256_permutevar8x32_ps(lo, wide_idx));
        let b = arch::_mm256_castps256_ps128(arch::_mm256_permutevar8x32_ps(hi, wide_idx));
        let bit3 = arch::_mm_castsi128_ps(arch::_mm_slli_epi32::<28>(idx));
        return core::mem::transmute(arch::_mm_blendv_ps(a, b, bit3));
    }
    #[allow(unreachable_code)]
    wide::f32x4::from(h.to_array().map(|i| table[(i & 15) as usize]))
}

/// `table[h & 15]` at 8 lanes: one two-table permute (AVX-512VL `vpermt2ps`), or two
/// 8-entry permutes and a blend on bit 3 (AVX2).
#[inline(always)]
pub(crate) fn lookup16_x8(table: &[f32; 16], h: wide::u32x8) -> wide::f32x8 {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx512f", target_feature = "avx512vl"))]
    // SAFETY: AVX-512F/VL are enabled; `__m256i` and `wide::u32x8` are eight 32-bit lanes;
    // `vpermt2ps` reads index bits 3..0 (bit 3 picks the table half).
    unsafe {
        let lo = arch::_mm256_loadu_ps(table.as_ptr());
        let hi = arch::_mm256_loadu_ps(table.as_ptr().add(8));
        return core::mem::transmute(arch::_mm256_permutex2var_ps(lo, core::mem::transmute(h), hi));
    }
    #[cfg(all(
        target_arch = "x86_64",
        target_feature = "avx2",
        not(all(target_feature = "avx512f", target_feature = "avx512vl"))
    ))]
    // SAFETY: AVX2 is enabled; `vpermps` reads index bits 2..0, `vblendvps` the sign bit.
    unsafe {
        let idx: arch::__m256i = core::mem::transmute(h);
        let lo = arch::_mm256_loadu_ps(table.as_ptr());
        let hi = arch::_mm256_loadu_ps(table.as_ptr().add(8));
        let a = arch::_mm256_permutevar8x32_ps(lo, idx);
        let b = arch::_mm256_permutevar8x32_ps(hi, idx);
        let bit3 = arch::_mm256_castsi256_ps(arch::_mm256_slli_epi32::<28>(idx));
        return core::mem::transmute(arch::_mm256_blendv_ps(a, b, bit3));
    }
    #[allow(unreachable_code)]
    wide::f32x8::from(h.to_array().map(|i| table[(i & 15) as usize]))
}

/// `table[h & 15]` at 16 lanes: one permute (AVX-512F `vpermps`, index bits 3..0), or the
/// 8-lane lookup on each half.
#[inline(always)]
pub(crate) fn lookup16_x16(table: &[f32; 16], h: wide::u32x16) -> wide::f32x16 {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
    // SAFETY: AVX-512F is enabled; `__m512i`/`__m512` and the wide types are sixteen 32-bit lanes.
    unsafe {
        let t = arch::_mm512_loadu_ps(table.as_ptr());
        return core::mem::transmute(arch::_mm512_permutexvar_ps(core::mem::transmute(h), t));
    }
    #[allow(unreachable_code)]
    {
        // SAFETY: without AVX-512, the 16-lane wide types are two 8-lane halves.
        let hs: [wide::u32x8; 2] = unsafe { core::mem::transmute(h) };
        unsafe { core::mem::transmute([lookup16_x8(table, hs[0]), lookup16_x8(table, hs[1])]) }
    }
}

/// 1/√x, lane for lane `anysl_core::rsqrt_f32`: the estimate, one Newton step
/// `y + y/2·(1 - (x·y)·y)`, the estimate where the step gives NaN, and (12-bit estimate only)
/// subnormal inputs scaled by 2^24.
#[inline(always)]
pub(crate) fn rsqrt<W: Wide>(x: W) -> W {
    let tiny = if anysl_core::RSQRT_ESTIMATE_14 { k(0.0) } else { abs(x).lt(k(f32::MIN_POSITIVE)) };
    let xs = if anysl_core::RSQRT_ESTIMATE_14 { x } else { W::select(tiny, x * k(16_777_216.0), x) };
    let y = xs.rsqrt_estimate();
    let t = xs * y;
    let e = (-t).fma(y, k(1.0));
    let r = (y * k(0.5)).fma(e, y);
    let r = W::select(is_nan(r), y, r);
    if anysl_core::RSQRT_ESTIMATE_14 {
        r
    } else {
        W::select(tiny, r * k(4096.0), r)
    }
}

// ---------------------------------------------------------------------------------------
// Small helpers.

#[inline(always)]
fn k<W: Wide>(v: f32) -> W {
    W::splat(v)
}

const SIGN: i32 = i32::MIN;

/// Polynomial `c[0] + c[1] x + …` by Horner's rule with FMA.
#[inline(always)]
fn horner<W: Wide, const N: usize>(x: W, c: [f32; N]) -> W {
    let mut acc = k::<W>(c[N - 1]);
    let mut i = N - 1;
    while i > 0 {
        i -= 1;
        acc = acc.fma(x, k(c[i]));
    }
    acc
}

/// Polynomial `c[0] + c[1] x + …` (at most 16 coefficients) by Estrin's scheme: pairs
/// `c[2i] + c[2i+1]·x`, then pairs of those with `x²`, `x⁴`, … — the FMAs of Horner's rule
/// in a tree of depth ⌈log2 N⌉ instead of a chain of N - 1, so its latency overlaps with the
/// rest of a shading chain. Each level rounds once more than Horner's last step; where the
/// constant term dominates, take it out ([`estrin1`]).
#[inline(always)]
fn estrin<W: Wide>(x: W, c: &[f32]) -> W {
    let mut v = [k::<W>(0.0); 16];
    let mut n = c.len().div_ceil(2);
    for i in 0..n {
        v[i] = if 2 * i + 1 < c.len() { x.fma(k(c[2 * i + 1]), k(c[2 * i])) } else { k(c[2 * i]) };
    }
    let mut p = x;
    while n > 1 {
        p = p * p;
        let m = n.div_ceil(2);
        for i in 0..m {
            v[i] = if 2 * i + 1 < n { p.fma(v[2 * i + 1], v[2 * i]) } else { v[2 * i] };
        }
        n = m;
    }
    v[0]
}

/// `c[0] + x·E(x)` with `E` the rest of the polynomial by [`estrin`]: the dominant constant
/// term rounded once, as Horner's rule rounds it.
#[inline(always)]
fn estrin1<W: Wide>(x: W, c: &[f32]) -> W {
    x.fma(estrin(x, &c[1..]), k(c[0]))
}

/// |x| (clears the sign bit; NaN stays NaN).
#[inline(always)]
pub(crate) fn abs<W: Wide>(x: W) -> W {
    W::from_bits(x.bits() & W::splat_i(i32::MAX))
}

/// The sign bit of `x` as an integer mask (`i32::MIN` or 0).
#[inline(always)]
fn sign_bit<W: Wide>(x: W) -> W::I {
    x.bits() & W::splat_i(SIGN)
}

/// `x` with its sign bit flipped where `s` has it set.
#[inline(always)]
fn xor_sign<W: Wide>(x: W, s: W::I) -> W {
    W::from_bits(x.bits() ^ s)
}

/// Lanes holding NaN.
#[inline(always)]
pub(crate) fn is_nan<W: Wide>(x: W) -> W {
    !x.eq(x)
}

/// `2^n` for integer lanes `n` in the normal exponent range [-126, 127].
#[inline(always)]
fn pow2i<W: Wide>(n: W::I) -> W {
    W::from_bits((n + W::splat_i(127)) << 23)
}

// ---------------------------------------------------------------------------------------
// Rounding, min/max, integer conversions.

/// Nearest integer, halves away from zero (`f32::round`).
#[inline(always)]
pub(crate) fn round<W: Wide>(x: W) -> W {
    let t = x.trunc();
    // `x - t` is exact; |x| >= 2^23 (and ±inf, NaN) leave `t = x` and a zero/NaN fraction.
    let frac = abs(x - t);
    let one = W::from_bits(W::splat_i(1.0f32.to_bits() as i32) | sign_bit(x));
    W::select(k::<W>(0.5).le(frac), t + one, t)
}

/// Minimum; a NaN operand yields the other operand (`f32::min`), ties (±0) give `a`.
#[inline(always)]
pub(crate) fn min<W: Wide>(a: W, b: W) -> W {
    // x86's `minps(b, a)` is `b < a ? b : a`: `a` for ties and where either is NaN, so only a
    // NaN `a` needs the select (three operations, where the two-select form took four).
    if cfg!(target_arch = "x86_64") {
        W::select(is_nan(a), b, b.hw_min(a))
    } else {
        W::select(is_nan(a), b, W::select(b.lt(a), b, a))
    }
}

/// Maximum; a NaN operand yields the other operand (`f32::max`), ties (±0) give `a`.
#[inline(always)]
pub(crate) fn max<W: Wide>(a: W, b: W) -> W {
    if cfg!(target_arch = "x86_64") {
        W::select(is_nan(a), b, b.hw_max(a))
    } else {
        W::select(is_nan(a), b, W::select(a.lt(b), b, a))
    }
}

/// Bits of `(floor(x) as i32)`: saturating, NaN → 0 (Rust `as` semantics).
#[inline(always)]
pub(crate) fn floor_to_i32<W: Wide>(x: W) -> W::I {
    // The hardware conversion returns i32::MIN for NaN and for both overflow directions;
    // i32::MIN is already right for x < -2^31, i32::MIN ^ !0 is i32::MAX for x >= 2^31, and
    // NaN lanes are cleared: two bitwise operations under the compares' masks (an integer
    // blend in `wide` at 16 lanes is a byte blend, two instructions more).
    let v = x.floor().to_int();
    (v ^ k::<W>(2147483648.0).le(x).bits()) & x.eq(x).bits()
}

// ---------------------------------------------------------------------------------------
// Exponential and logarithm.

/// 2^r = 1 + r·Q(r) on |r| <= 0.5 (tools/polyfit.py "exp2 Q", max rel. error 2.3e-9).
pub const EXP2_Q: [f32; 7] =
    [6.931471825e-1, 2.402265072e-1, 5.550410971e-2, 9.618056938e-3, 1.333350199e-3, 1.546146814e-4, 1.529734072e-5];

/// 2^(hi + lo) for a double-f32 exponent (|lo| <= ulp(hi)), with overflow to +inf,
/// gradual underflow to the subnormals and 0, and NaN propagation from `hi`.
#[inline(always)]
fn exp2_dd<W: Wide>(hi: W, lo: W) -> W {
    // Beyond 129 and -151 the result is inf or 0 whatever `lo` holds (it may be NaN when hi
    // is infinite), so clamp `hi` and drop `lo` there; NaN passes through the selects.
    let in_range = abs(hi).le(k(152.0));
    let h = W::select(k::<W>(129.0).lt(hi), k(129.0), hi);
    let h = W::select(h.lt(k(-151.0)), k(-151.0), h);
    let l = W::select(in_range, lo, k(0.0));
    let n = h.round_even();
    let r = (h - n) + l;
    let p = r.fma(estrin(r, &EXP2_Q), k(1.0));
    // With n = -151 (the clamp's floor) the result p·2^-151 < 2^-150 rounds to +0. Those
    // lanes are scaled by 1 and replaced by +0 at the end: the same bits, but no multiply
    // underflows — an underflowing vector product takes a microcode assist of ~100+ cycles
    // on x86 (and `pow(0, y)`, the highlight of every surface facing away from a light,
    // lands here).
    let zero = n.le(k(-151.0));
    // Scale in two steps so that 2^n stays representable: n = n1 + n2, both in [-76, 65].
    let ni = W::select(zero, k(0.0), n).to_int();
    let n1 = ni >> 1;
    let n2 = ni - n1;
    W::select(zero, k(0.0), p * pow2i::<W>(n1) * pow2i::<W>(n2))
}

/// 2^x.
#[inline(always)]
pub(crate) fn exp2<W: Wide>(x: W) -> W {
    exp2_dd(x, k(0.0))
}

/// log2(e) split as hi + lo (f32 + remainder).
pub const LOG2E_HI: f32 = 1.442_695_02;
/// The remainder log2(e) - LOG2E_HI.
pub const LOG2E_LO: f32 = 1.925_963e-8;

/// e^x = 2^(x·log2 e), with x·log2 e formed exactly as a double-f32 (Cody–Waite in the
/// exponent rather than in the argument).
#[inline(always)]
pub(crate) fn exp<W: Wide>(x: W) -> W {
    let hi = x * k(LOG2E_HI);
    let lo = x.fma(k(LOG2E_LO), x.fma(k(LOG2E_HI), -hi));
    exp2_dd(hi, lo)
}

/// ln(1+f) = f - f²/2 + f³·L(f) for f in [√½-1, √2-1] (tools/polyfit.py "log L", degree 8,
/// max error of the f³·L term relative to ln(1+f): 3.4e-9).
pub const LOG_L: [f32; 9] = [
    3.333333135e-1,
    -2.499999702e-1,
    2.000071555e-1,
    -1.666780263e-1,
    1.424905807e-1,
    -1.242568716e-1,
    1.168541983e-1,
    -1.147973388e-1,
    6.971611828e-2,
];

/// Range reduction shared by the logarithms: x = 2^e·(1+f), (1+f) in [√½, √2), and
/// ln(1+f) as a double-f32 `(hi, lo)`. Valid for finite x > 0 (subnormals included);
/// other inputs give garbage that the callers replace.
#[inline(always)]
fn log_reduce<W: Wide>(x: W) -> (W, W, W) {
    let tiny = x.lt(k(f32::MIN_POSITIVE));
    let xs = W::select(tiny, x * k(16_777_216.0), x);
    // Subtracting the bits of √½ makes the exponent field round m into [√½, √2).
    let u = xs.bits();
    let e = (u - W::splat_i(0x3f35_04f3)) >> 23;
    let m = W::from_bits(u - (e << 23));
    let e = W::from_int(e) - W::select(tiny, k(24.0), k(0.0));
    let f = m - k(1.0); // exact (Sterbenz)
                        // -f²/2 exactly as b_hi + b_lo, then f + b_hi by Fast2Sum (|f| >= f²/2).
    let f2 = f * f;
    let b_hi = f2 * k(-0.5);
    let b_lo = f.fma(f, -f2) * k(-0.5);
    let s_hi = f + b_hi;
    let s_lo = (f - s_hi) + b_hi;
    let lo = (f2 * f).fma(horner(f, LOG_L), s_lo + b_lo);
    (e, s_hi, lo)
}

/// log2(x) as a double-f32 for finite x > 0; relative error about 2^-28.
#[inline(always)]
fn log2_dd<W: Wide>(x: W) -> (W, W) {
    let (e, ln_hi, ln_lo) = log_reduce(x);
    let l_hi = ln_hi * k(LOG2E_HI);
    let l_lo = ln_lo.fma(k(LOG2E_HI), ln_hi.fma(k(LOG2E_LO), ln_hi.fma(k(LOG2E_HI), -l_hi)));
    // Fast2Sum: e is an integer and |l_hi| <= 0.5, so |e| >= |l_hi| unless e = 0.
    let hi = e + l_hi;
    let lo = ((e - hi) + l_hi) + l_lo;
    // Renormalize (Fast2Sum, |hi| > |lo|) so that |lo| <= ulp(hi)/2: pow scales the low part
    // by y and feeds it to `exp2_dd`, whose polynomial only covers |r| <= 0.5.
    let s = hi + lo;
    (s, lo - (s - hi))
}

/// Replaces the logarithm of non-positive-or-non-finite inputs by its C99 value.
#[inline(always)]
fn log_specials<W: Wide>(x: W, v: W) -> W {
    let ok = k::<W>(0.0).lt(x) & x.lt(k(f32::INFINITY));
    let special = W::select(x.eq(k(0.0)), k(f32::NEG_INFINITY), W::select(x.eq(k(f32::INFINITY)), x, k(f32::NAN)));
    W::select(ok, v, special)
}

/// log2(x).
#[inline(always)]
pub(crate) fn log2<W: Wide>(x: W) -> W {
    let (hi, lo) = log2_dd(x);
    log_specials(x, hi + lo)
}

/// ln 2 split as hi (16 significant bits, so e·hi is exact) + lo.
pub const LN2_HI16: f32 = 0.693_145_751_953_125;
/// The remainder ln 2 - LN2_HI16.
pub const LN2_LO16: f32 = 1.428_606_8e-6;

/// ln(x).
#[inline(always)]
pub(crate) fn ln<W: Wide>(x: W) -> W {
    let (e, ln_hi, ln_lo) = log_reduce(x);
    let p_hi = e * k(LN2_HI16);
    // Fast2Sum: |e·ln2| >= 0.69 > |ln_hi| unless e = 0.
    let hi = p_hi + ln_hi;
    let lo = ((p_hi - hi) + ln_hi) + e.fma(k(LN2_LO16), ln_lo);
    log_specials(x, hi + lo)
}

/// `log2(1+f) = f·Q(f)` for f in [√½-1, √2-1]: a degree-8 polynomial interpolating
/// `log2(1+f)/f` at the Chebyshev nodes (`tools/polyfit.py "log2 Q"`), relative error of the
/// f32-rounded polynomial below 4.2e-8 (0.35 ulp; the f32 rounding of `Q(0) = 1/ln 2` alone
/// is 1.3e-8).
pub const LOG2_Q: [f32; 9] = [
    1.442695022e+00,
    -7.213474512e-01,
    4.809107482e-01,
    -3.606932759e-01,
    2.879032493e-01,
    -2.391698807e-01,
    2.160782218e-01,
    -2.058618814e-01,
    1.231096834e-01,
];

/// Bits of √½ as f32: subtracting them makes the exponent field round the mantissa into
/// [√½, √2).
pub const SQRT_HALF_BITS: u32 = 0x3f35_04f3;

/// `log2 x = e + log2 m` for finite x > 0 as an unevaluated sum `(s, sl)`, `s = e + l` and
/// `sl` its rounding error, with `l = log2 m` in one f32 (about one ulp of `l`). With
/// `SUBNORMAL` the lanes below the normal range are scaled by 2^24 first; without, they give
/// garbage (the caller keeps them off this path).
#[inline(always)]
fn log2_split<W: Wide, const SUBNORMAL: bool>(x: W) -> (W, W) {
    let (xs, bias) = if SUBNORMAL {
        let tiny = x.lt(k(f32::MIN_POSITIVE));
        (W::select(tiny, x * k(16_777_216.0), x), W::select(tiny, k(24.0), k(0.0)))
    } else {
        (x, k(0.0))
    };
    let u = xs.bits();
    let ei = (u - W::splat_i(SQRT_HALF_BITS as i32)) >> 23;
    let m = W::from_bits(u - (ei << 23));
    let e = if SUBNORMAL { W::from_int(ei) - bias } else { W::from_int(ei) };
    let f = m - k(1.0); // exact (Sterbenz)
    let l = f * estrin1(f, &LOG2_Q);
    // Fast2Sum: |e| >= 1 > |l| unless e = 0 (then s = l exactly and sl = 0).
    let s = e + l;
    (s, (e - s) + l)
}

/// `ax^y` for `ax >= 0` (or NaN) in f32 lanes: `2^(y·log2 ax)` with `log2 ax` as
/// [`log2_split`] and `y·log2 ax` as a double-f32 (the product's rounding error by FMA), so
/// the only error the exponent carries is that of `l = log2 m`: relative to the result about
/// `ln 2·|y·l|·2^-23` plus an ulp of the exponential. `+0 → 0` for y > 0 and `+inf` for y < 0,
/// `+inf` as C99; NaN propagates; the caller handles the sign, y = 0 and x = 1.
#[inline(always)]
fn pow_mag<W: Wide>(ax: W, y: W) -> W {
    let (lh, ll) = log2_split::<W, true>(ax);
    // log2 of 0 and inf (NaN stays NaN through the arithmetic below).
    let zero = ax.eq(k(0.0));
    let finite = ax.lt(k(f32::INFINITY));
    let lh = W::select(zero, k(f32::NEG_INFINITY), W::select(finite, lh, ax));
    let ll = W::select(finite & !zero, ll, k(0.0));
    let th = y * lh;
    let tl = y.fma(ll, y.fma(lh, -th));
    exp2_dd(th, tl)
}

/// x^y (C99 `pow`, as `f32::powf`) = 2^(y·log2|x|) ([`pow_mag`]), with the sign from the
/// parity of integer y for negative x.
#[inline(always)]
pub(crate) fn pow<W: Wide>(x: W, y: W) -> W {
    // Shininess exponents: a base in [+0, inf) under an exponent in {0, 1/2, 1, …, 16} is
    // computed by binary powering (and a square root for the half) where that result is in
    // [2^-100, inf) or the base is 0; the other lanes (and vectors without such a lane) take
    // the exponential of the logarithm. Each lane's path depends on its own (x, y) only; an
    // exponent the same in every lane (a uniform shader parameter) steers the powering by
    // scalar branches, with the same operations per lane.
    let y0 = y.first();
    let n0 = y0 + y0;
    let (r, halves) = if (0.0..=32.0).contains(&n0) && n0.round_ties_even() == n0 && y.eq(W::splat(y0)).all() {
        (pow_halves_uniform(x, n0 as u32), k::<W>(0.0).le(k(0.0)))
    } else {
        let n2 = y + y;
        let halves = k::<W>(0.0).le(n2) & n2.le(k(32.0)) & n2.round_even().eq(n2);
        if !halves.any() {
            return pow_exp_log(x, y);
        }
        (pow_halves(x, n2), halves)
    };
    let sign_clear = W::eq_i(x.bits() >> 31, W::splat_i(0));
    let in_range = k::<W>(POW_HALVES_MIN).le(r) & r.lt(k(f32::INFINITY));
    let fast = halves & sign_clear & x.lt(k(f32::INFINITY)) & (in_range | x.eq(k(0.0)));
    if fast.all() {
        return r;
    }
    W::select(fast, r, pow_exp_log(x, y))
}

/// The smallest result [`pow_halves`] gives: below it the low parts of its double-f32
/// products would fall into the subnormals.
pub const POW_HALVES_MIN: f32 = 7.888_609_1e-31; // 2^-100

/// `(rh, rl)·(bh, bl)` as an unnormalized double-f32: the rounded product and its error
/// (by FMA) plus the cross terms.
#[inline(always)]
fn dd_mul<W: Wide>(rh: W, rl: W, bh: W, bl: W) -> (W, W) {
    let p = rh * bh;
    (p, rl.fma(bh, rh.fma(bl, rh.fma(bh, -p))))
}

/// `(bh, bl)²` as [`dd_mul`] of the value by itself.
#[inline(always)]
fn dd_sq<W: Wide>(bh: W, bl: W) -> (W, W) {
    let p = bh * bh;
    (p, (bh + bh).fma(bl, bh.fma(bh, -p)))
}

/// `x^(n2/2)` for `x` in [+0, inf) and integer `n2` in [0, 32], as a double-f32 `x^m`
/// (m = ⌊n2/2⌋) by right-to-left binary powering — the error-free product of each step
/// carried, so the result is the exact power rounded once, 0.5 ulp — times `√x` for odd
/// `n2` (the square root's rounding added: ≤ 1.5 ulp). Every lane runs the same steps (a
/// lane whose bit is clear keeps its value), so a lane's bits do not depend on its
/// neighbours'; steps no lane needs are skipped. Overflow gives inf or NaN, which the caller
/// sends to the general path.
#[inline(always)]
fn pow_halves<W: Wide>(x: W, n2: W) -> W {
    let n = n2.to_int();
    let (one, zero) = (W::splat_i(1), W::splat_i(0));
    let (mut rh, mut rl) = (k::<W>(1.0), k::<W>(0.0));
    let (mut bh, mut bl) = (x, k::<W>(0.0));
    let mut rest = n >> 1;
    for step in 0..5 {
        let bit = !W::eq_i(rest & one, zero);
        if bit.any() {
            let (p, e) = dd_mul(rh, rl, bh, bl);
            rh = W::select(bit, p, rh);
            rl = W::select(bit, e, rl);
        }
        rest = rest >> 1;
        if step == 4 || W::eq_i(rest, zero).all() {
            break;
        }
        (bh, bl) = dd_sq(bh, bl);
    }
    let half = !W::eq_i(n & one, zero);
    if half.any() {
        let (p, e) = dd_mul(rh, rl, x.sqrt(), k(0.0));
        rh = W::select(half, p, rh);
        rl = W::select(half, e, rl);
    }
    rh + rl
}

/// [`pow_halves`] for the same `n2` in every lane: the same operations per lane, steered by
/// the bits of `n2` without masks, less those whose result is known: the power is 1 until the
/// first set bit (so that bit's power is taken as it is, not multiplied by 1), and a factor
/// whose low part is 0 (`x` before the first square, `√x`) has no cross term. Bit for bit
/// [`pow_halves`]' result wherever that is finite (the terms left out are exact zeros).
#[inline(always)]
fn pow_halves_uniform<W: Wide>(x: W, n2: u32) -> W {
    let mut r: Option<(W, W)> = None;
    let (mut bh, mut bl) = (x, k::<W>(0.0));
    let mut squared = false;
    let mut rest = n2 >> 1;
    while rest != 0 {
        if rest & 1 != 0 {
            r = Some(match r {
                None => (bh, bl),
                Some((rh, rl)) => dd_mul(rh, rl, bh, bl),
            });
        }
        rest >>= 1;
        if rest != 0 {
            (bh, bl) = if squared {
                dd_sq(bh, bl)
            } else {
                let p = bh * bh;
                (p, bh.fma(bh, -p))
            };
            squared = true;
        }
    }
    let (mut rh, mut rl) = r.unwrap_or((k(1.0), k(0.0)));
    if n2 & 1 != 0 {
        let s = x.sqrt();
        let p = rh * s;
        (rh, rl) = (p, rl.fma(s, rh.fma(s, -p)));
    }
    rh + rl
}

/// [`pow`] through `2^(y·log2|x|)`.
#[inline(always)]
fn pow_exp_log<W: Wide>(x: W, y: W) -> W {
    // The common case — every lane a positive normal base (or +0 under a positive exponent)
    // with a normal result, every highlight — without the sign and special-value fix-ups and
    // with the exponential scaled in one step: for those lanes `pow_general` computes the
    // same operations (`2^n` times a normal `p` is exact in one step or two), so a lane's bits
    // never depend on its neighbours. +0 goes through the logarithm as 1 (`log2_split` would
    // give a finite garbage exponent) and is put back at the end.
    let zero: W = k(0.0);
    // +0 under a positive exponent; +0 under another stays 0 and fails `base_ok`.
    let plus_zero = W::eq_i(x.bits(), W::splat_i(0)) & zero.lt(y);
    let xb = W::select(plus_zero, k(1.0), x);
    let (lh, ll) = log2_split::<W, false>(xb);
    let th = y * lh;
    let tl = y.fma(ll, y.fma(lh, -th));
    let base_ok = k::<W>(f32::MIN_POSITIVE).le(xb) & xb.lt(k(f32::INFINITY));
    // |th| <= 125: a normal 2^n for n = round(th) (and y finite: an infinite y gives an
    // infinite or NaN th).
    if (base_ok & abs(th).le(k(125.0))).all() {
        let n = th.round_even();
        let r = (th - n) + tl;
        let p = r.fma(estrin(r, &EXP2_Q), k(1.0));
        return W::select(plus_zero, zero, p * pow2i::<W>(n.to_int()));
    }
    let sign = W::from_bits(x.bits() >> 31);
    pow_general(x, y, sign)
}

/// [`pow`] for vectors with a negative, infinite or NaN base or exponent in some lane, out of
/// line: inlined, this second copy of the polynomials doubled the code of every light loop
/// (twice over where the loop body is instantiated for full and partial masks) for a path
/// that ordinary highlights never take.
#[cold]
#[inline(never)]
fn pow_general<W: Wide>(x: W, y: W, sign: W) -> W {
    let ax = abs(x);
    let a = pow_mag(ax, y);
    let finite = ax.lt(k(f32::INFINITY));
    let y_int = y.floor().eq(y); // true for ±inf, false for NaN
    let half = y * k(0.5);
    let y_odd = y_int & !half.floor().eq(half);
    let x_neg = sign & !is_nan(x);
    let a = xor_sign(a, (x_neg & y_odd).bits() & W::splat_i(SIGN));
    let domain_error = x.lt(k(0.0)) & finite & !y_int;
    let a = W::select(domain_error, k(f32::NAN), a);
    let one = y.eq(k(0.0)) | x.eq(k(1.0)) | (ax.eq(k(1.0)) & abs(y).eq(k(f32::INFINITY)));
    W::select(one, k(1.0), a)
}

// ---------------------------------------------------------------------------------------
// Trigonometry.

/// sin r = r + r³·S(r²), |r| <= 0.82 (tools/polyfit.py "sin S", degree 3, error 3.1e-9).
pub const SIN_S: [f32; 4] = [-1.666666716e-1, 8.333331905e-3, -1.983986440e-4, 2.722240652e-6];
/// cos r = 1 - r²/2 + r⁴·C(r²), |r| <= 0.82 ("cos C", degree 3, error 8.4e-10).
pub const COS_C: [f32; 4] = [4.166666791e-2, -1.388888690e-3, 2.480041439e-5, -2.727799142e-7];
/// tan r = r + r³·T(r²), |r| <= 0.82 ("tan T", degree 8, error 4.8e-9).
pub const TAN_T: [f32; 9] = [
    3.333333433e-1,
    1.333333105e-1,
    5.396902934e-2,
    2.185781859e-2,
    8.950174786e-3,
    3.233517287e-3,
    2.304464579e-3,
    -5.280334735e-4,
    9.456218686e-4,
];

/// π/2 in three f32 parts (Cody–Waite); with FMA, `x - n·P1` is exact for |x| <= 2^19.
pub const PIO2_1: f32 = 1.570_796_4;
/// The second part of π/2.
pub const PIO2_2: f32 = -4.371_139e-8;
/// The third part of π/2.
pub const PIO2_3: f32 = -1.715_124_5e-15;
/// The remainder π/2 - PIO2_1 (as f32).
pub const PIO2_LO: f32 = PIO2_2;
/// π rounded to f32.
pub const PI_HI: f32 = core::f32::consts::PI;
/// The remainder π - PI_HI.
pub const PI_LO: f32 = -8.742_278e-8;
/// 2/π rounded to f32.
pub const FRAC_2_PI: f32 = core::f32::consts::FRAC_2_PI;

/// Largest |x| reduced in vector code; beyond it the lanes go through std (Payne–Hanek).
pub const TRIG_VECTOR_LIMIT: f32 = 524_288.0;

/// Reduces |x| = n·π/2 + r, |r| <= 0.82, returning `(r, n)`.
#[inline(always)]
fn reduce_pio2<W: Wide>(ax: W) -> (W, W::I) {
    let n = (ax * k(FRAC_2_PI)).round_even();
    let r = n.fma(k(-PIO2_1), ax);
    let r = n.fma(k(-PIO2_2), r);
    let r = n.fma(k(-PIO2_3), r);
    (r, n.to_int())
}

/// sin or cos: `quadrant_shift` 0 gives sin |x|, 1 gives cos |x|.
#[inline(always)]
fn sin_cos_abs<W: Wide>(ax: W, quadrant_shift: i32) -> W {
    let (r, n) = reduce_pio2(ax);
    let q = n + W::splat_i(quadrant_shift);
    let z = r * r;
    let s = (r * z).fma(horner(z, SIN_S), r);
    let c = z.fma(z.fma(horner(z, COS_C), k(-0.5)), k(1.0));
    let odd = W::from_bits((q << 31) >> 31);
    let v = W::select(odd, c, s);
    xor_sign(v, (q << 30) & W::splat_i(SIGN))
}

/// Runs the std function on lanes too large for the vector reduction (and on ±inf).
#[inline(always)]
fn trig_fallback<W: Wide>(x: W, ax: W, v: W, f: fn(f32) -> f32) -> W {
    let big = k::<W>(TRIG_VECTOR_LIMIT).lt(ax);
    if big.any() {
        W::select(big, x.map_where(big, f), v)
    } else {
        v
    }
}

/// sin x.
#[inline(always)]
pub(crate) fn sin<W: Wide>(x: W) -> W {
    let ax = abs(x);
    let v = xor_sign(sin_cos_abs(ax, 0), sign_bit(x));
    trig_fallback(x, ax, v, f32::sin)
}

/// cos x.
#[inline(always)]
pub(crate) fn cos<W: Wide>(x: W) -> W {
    let ax = abs(x);
    let v = sin_cos_abs(ax, 1);
    trig_fallback(x, ax, v, f32::cos)
}

/// tan x: the odd quadrants use tan(r + π/2) = -1/tan r.
#[inline(always)]
pub(crate) fn tan<W: Wide>(x: W) -> W {
    let ax = abs(x);
    let (r, n) = reduce_pio2(ax);
    let z = r * r;
    let t = (r * z).fma(horner(z, TAN_T), r);
    let odd = W::from_bits((n << 31) >> 31);
    let v = W::select(odd, k::<W>(-1.0) / t, t);
    let v = xor_sign(v, sign_bit(x));
    trig_fallback(x, ax, v, f32::tan)
}

/// asin t = t + t³·A(t²), t in [0, 0.6] ("asin A", degree 7, error 1.6e-9).
pub const ASIN_A: [f32; 8] = [
    1.666666716e-1,
    7.500012219e-2,
    4.463566095e-2,
    3.053795733e-2,
    2.073754929e-2,
    2.641756274e-2,
    -1.255851798e-2,
    4.726486281e-2,
];

/// For a = |x| <= 1: `(p, big)` with p = asin(a) when `big` is clear, and
/// p = asin(√((1-a)/2)) (so that asin a = π/2 - 2p) when `big` (a > 0.6) is set. The switch
/// sits at 0.6 rather than 0.5 so that π/2 - 2p cancels at most 1.44× (2× at 0.5).
#[inline(always)]
fn asin_core<W: Wide>(a: W) -> (W, W) {
    let big = k::<W>(0.6).lt(a);
    let z = W::select(big, (k::<W>(1.0) - a) * k(0.5), a * a);
    let t = W::select(big, z.sqrt(), a);
    let p = (t * z).fma(horner(z, ASIN_A), t);
    (p, big)
}

/// asin x (NaN outside [-1, 1]).
#[inline(always)]
pub(crate) fn asin<W: Wide>(x: W) -> W {
    let ax = abs(x);
    let (p, big) = asin_core(ax);
    // π/2 - 2p with π/2 as hi + lo.
    let v = W::select(big, k::<W>(PIO2_1) - p.fma(k(2.0), k(-PIO2_LO)), p);
    let v = W::select(k::<W>(1.0).lt(ax), k(f32::NAN), v);
    xor_sign(v, sign_bit(x))
}

/// acos x (NaN outside [-1, 1]).
#[inline(always)]
pub(crate) fn acos<W: Wide>(x: W) -> W {
    let ax = abs(x);
    let (p, big) = asin_core(ax);
    let neg = x.lt(k(0.0));
    // |x| <= 0.6: π/2 - asin x; x > 0.6: 2p; x < -0.6: π - 2p.
    let small = k::<W>(PIO2_1) - (xor_sign(p, sign_bit(x)) - k(PIO2_LO));
    let big_pos = p * k(2.0);
    let big_neg = k::<W>(PI_HI) - p.fma(k(2.0), k(-PI_LO));
    let v = W::select(big, W::select(neg, big_neg, big_pos), small);
    W::select(k::<W>(1.0).lt(ax), k(f32::NAN), v)
}

/// atan t = t + t³·P(t²), t in [0, 1] ("atan P", degree 9, error 1.7e-8).
pub const ATAN_P: [f32; 10] = [
    -3.333333433e-1,
    1.999994963e-1,
    -1.428400427e-1,
    1.108826175e-1,
    -8.931826800e-2,
    7.031913847e-2,
    -4.896051437e-2,
    2.630500123e-2,
    -9.144629352e-3,
    1.488691894e-3,
];

/// atan(ay / ax) in [0, π/2] for ay, ax >= 0, from the ratio min/max <= 1 (one division).
/// 0/0 and inf/inf give NaN (callers fix them); other infinities work out.
#[inline(always)]
fn atan_ratio<W: Wide>(ay: W, ax: W) -> W {
    let swap = ax.lt(ay);
    let w = W::select(swap, ax, ay) / W::select(swap, ay, ax);
    let z = w * w;
    let p = (w * z).fma(horner(z, ATAN_P), w);
    W::select(swap, k::<W>(PIO2_1) - (p - k(PIO2_LO)), p)
}

/// atan x.
#[inline(always)]
pub(crate) fn atan<W: Wide>(x: W) -> W {
    xor_sign(atan_ratio(abs(x), k(1.0)), sign_bit(x))
}

/// atan2(y, x) with the C99 special cases.
#[inline(always)]
pub(crate) fn atan2<W: Wide>(y: W, x: W) -> W {
    let ax = abs(x);
    let ay = abs(y);
    let t = atan_ratio(ay, ax);
    let inf = k::<W>(f32::INFINITY);
    let t = W::select(ay.eq(k(0.0)) & ax.eq(k(0.0)), k(0.0), t);
    let t = W::select(ay.eq(inf) & ax.eq(inf), k(core::f32::consts::FRAC_PI_4), t);
    // x negative (including -0): reflect into the left half plane, π - t.
    let x_neg = W::from_bits(x.bits() >> 31);
    let t = W::select(x_neg, k::<W>(PI_HI) - (t - k(PI_LO)), t);
    xor_sign(t, sign_bit(y))
}
