//! The abstract number types every shader is written against: [`ShadingFloat`], its
//! [`Mask`] and the integer lanes [`LatticeBits`] behind the noise hash.
//!
//! A type implementing `ShadingFloat` is a *set of shading points* evaluated together:
//! one (`f32`, `f64`), several SIMD lanes (`F32x8`), a value with screen-space derivatives
//! (`Dual<F>`) or a conservative range (`Interval<F>`). Shaders never see which.

use core::fmt::Debug;
use core::ops::{
    Add, AddAssign, BitAnd, BitOr, BitXor, Div, DivAssign, Mul, MulAssign, Neg, Not, Shl, Shr, Sub, SubAssign,
};

/// The result of comparing two [`ShadingFloat`]s: one truth value per lane.
///
/// For intervals the truth value is three-valued ("surely true", "surely false", "maybe"):
/// [`Mask::any`] then means *possibly true in some lane* and [`Mask::all`] *surely true in
/// every lane*, which is what masked control flow needs to stay conservative.
pub trait Mask:
    Copy + Debug + Send + Sync + 'static + BitAnd<Output = Self> + BitOr<Output = Self> + Not<Output = Self>
{
    /// Number of lanes.
    const LANES: usize;
    /// True when the mask can hold "maybe" (interval masks); loops then widen after a bound.
    const THREE_VALUED: bool = false;
    /// Every lane set to `b`.
    fn splat(b: bool) -> Self;
    /// Some lane is (possibly) true.
    fn any(self) -> bool;
    /// Every lane is (surely) true.
    fn all(self) -> bool;
    /// No lane is (possibly) true.
    #[inline(always)]
    fn none(self) -> bool {
        !self.any()
    }
    /// Lane `i` is (possibly) true.
    fn lane(self, i: usize) -> bool;
    /// The mask whose lane `i` is bit `i` of `bits` (higher bits ignored): how renderers turn
    /// the lane sets they track as integers into masks.
    fn from_bits(bits: u32) -> Self;
    /// Bit `i` set where lane `i` is (possibly) true: [`Mask::from_bits`] reversed.
    #[inline(always)]
    fn to_bits(self) -> u32 {
        (0..Self::LANES).filter(|&i| self.lane(i)).fold(0, |b, i| b | 1 << i)
    }
    /// Lane-wise choice between two masks.
    #[inline(always)]
    fn select_mask(m: Self, a: Self, b: Self) -> Self {
        (m & a) | (!m & b)
    }
}

impl Mask for bool {
    const LANES: usize = 1;
    #[inline(always)]
    fn splat(b: bool) -> Self {
        b
    }
    #[inline(always)]
    fn any(self) -> bool {
        self
    }
    #[inline(always)]
    fn all(self) -> bool {
        self
    }
    #[inline(always)]
    fn lane(self, _i: usize) -> bool {
        self
    }
    #[inline(always)]
    fn from_bits(bits: u32) -> Self {
        bits & 1 != 0
    }
    #[inline(always)]
    fn to_bits(self) -> u32 {
        u32::from(self)
    }
    #[inline(always)]
    fn select_mask(m: Self, a: Self, b: Self) -> Self {
        if m {
            a
        } else {
            b
        }
    }
}

/// Unsigned 32-bit integer lanes: the integer side of a [`ShadingFloat`], used by the
/// table-free lattice hash behind noise. `+` and `*` wrap modulo 2^32.
pub trait LatticeBits:
    Copy
    + Debug
    + Send
    + Sync
    + 'static
    + BitAnd<Output = Self>
    + BitOr<Output = Self>
    + BitXor<Output = Self>
    + Shr<u32, Output = Self>
    + Shl<u32, Output = Self>
{
    /// The mask type produced by comparisons.
    type Mask: Mask;
    /// Every lane set to `v`.
    fn splat(v: u32) -> Self;
    /// Lane-wise wrapping addition.
    fn wrapping_add(self, rhs: Self) -> Self;
    /// Lane-wise wrapping multiplication.
    fn wrapping_mul(self, rhs: Self) -> Self;
    /// Lane-wise equality.
    fn eq_mask(self, rhs: Self) -> Self::Mask;
    /// Lane `i` (for tests and debugging; for unknown interval bits, the stored guess).
    fn lane(self, i: usize) -> u32;
}

impl LatticeBits for u32 {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: u32) -> Self {
        v
    }
    #[inline(always)]
    fn wrapping_add(self, rhs: Self) -> Self {
        u32::wrapping_add(self, rhs)
    }
    #[inline(always)]
    fn wrapping_mul(self, rhs: Self) -> Self {
        u32::wrapping_mul(self, rhs)
    }
    #[inline(always)]
    fn eq_mask(self, rhs: Self) -> bool {
        self == rhs
    }
    #[inline(always)]
    fn lane(self, _i: usize) -> u32 {
        self
    }
}

/// Lane-wise choice for anything a masked assignment can write: floats, vectors, colours,
/// matrices, tuples and arrays of them. `widen` forgets everything known about the value
/// (only intervals do anything: they become unbounded); loops over intervals use it once
/// they stop converging.
pub trait Blend<F: ShadingFloat>: Copy {
    /// `m ? a : b`, lane by lane. For a "maybe" interval lane, the hull of both.
    fn blend(m: F::Mask, a: Self, b: Self) -> Self;
    /// The value with nothing known about it (identity except for intervals).
    #[inline(always)]
    fn widen(self) -> Self {
        self
    }
}

/// A pure function of `N` numbers written once for every instantiation: what
/// [`ShadingFloat::apply`] evaluates. `eval` must not depend on anything but `self` and `args`.
pub trait PureFn<const N: usize> {
    /// `f(args)` at instantiation `G`.
    fn eval<G: ShadingFloat>(&self, args: [G; N]) -> G;
}

/// The number type a shader is written against. See the module docs.
///
/// Constants enter through [`ShadingFloat::c`] (converted to the type's precision once,
/// after inlining a constant). Comparisons return [`Self::Mask`]; use [`ShadingFloat::select`]
/// (or the masked control flow of [`crate::exec`]) instead of `if`.
///
/// The math functions are *primitives*: each instantiation supplies them (scalar libm, SIMD
/// polynomials, dual-number chain rule, outward-rounded interval hulls); everything else in
/// the shading library is written once on top of them.
pub trait ShadingFloat:
    Copy
    + Debug
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
    + Blend<Self>
{
    /// Lane truth values produced by comparisons.
    type Mask: Mask;
    /// Integer lanes for the noise hash.
    type Bits: LatticeBits<Mask = Self::Mask>;
    /// Number of lanes (shading points) evaluated at once.
    const LANES: usize;
    /// True for dual numbers: derivatives are carried and `dx`/`dy` are meaningful.
    const HAS_DERIVS: bool = false;
    /// Unit roundoff of the underlying precision (2^-24 for f32, 2^-53 for f64).
    const UNIT_ROUNDOFF: f64;
    /// Short name used in benchmark tables (`f32`, `f32x8`, `dual-f32`, …).
    const NAME: &'static str;

    /// The constant `v` in every lane, rounded to this type's precision.
    fn c(v: f64) -> Self;
    /// Lane `i` as f64 (the value part for duals, the midpoint for intervals).
    fn lane(self, i: usize) -> f64;
    /// Builds a value from per-lane f64 values (`lanes.len() == LANES`).
    fn from_lanes(lanes: &[f64]) -> Self;

    /// Loads `LANES` consecutive values (one SIMD load for vector types; derivatives zero,
    /// intervals degenerate). `src.len() >= LANES`.
    #[inline(always)]
    fn load(src: &[f32]) -> Self {
        let mut buf = [0.0f64; 64];
        for (b, s) in buf.iter_mut().zip(&src[..Self::LANES]) {
            *b = *s as f64;
        }
        Self::from_lanes(&buf[..Self::LANES])
    }
    /// `*self = Self::load(src)`, negated when `neg`, written in place. Several-packet types
    /// ([`Pair`](https://docs.rs/anysl-simd)) write each packet where it lies: a value that is
    /// built in a temporary and then assigned whole is copied with moves wider than the
    /// stores that made it (a 64-byte load of two 32-byte stores at 8 lanes), and every such
    /// load waits for the stores to retire instead of being forwarded from them.
    #[inline(always)]
    fn load_into(&mut self, src: &[f32], neg: bool) {
        let v = Self::load(src);
        *self = if neg { -v } else { v };
    }
    /// Stores lane values (see [`ShadingFloat::lane`]) to `LANES` consecutive slots.
    #[inline(always)]
    fn store(self, dst: &mut [f32]) {
        for (i, d) in dst[..Self::LANES].iter_mut().enumerate() {
            *d = self.lane(i) as f32;
        }
    }

    /// `m ? a : b` lane by lane.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// `self < rhs`.
    fn lt(self, rhs: Self) -> Self::Mask;
    /// `self <= rhs`.
    fn le(self, rhs: Self) -> Self::Mask;
    /// `self > rhs`.
    #[inline(always)]
    fn gt(self, rhs: Self) -> Self::Mask {
        rhs.lt(self)
    }
    /// `self >= rhs`.
    #[inline(always)]
    fn ge(self, rhs: Self) -> Self::Mask {
        rhs.le(self)
    }
    /// `self == rhs`.
    fn eq(self, rhs: Self) -> Self::Mask;
    /// `self != rhs`.
    #[inline(always)]
    fn ne(self, rhs: Self) -> Self::Mask {
        !self.eq(rhs)
    }
    /// Lanes holding NaN.
    fn is_nan(self) -> Self::Mask;

    /// |x|.
    fn abs(self) -> Self;
    /// Largest integer ≤ x.
    fn floor(self) -> Self;
    /// Smallest integer ≥ x.
    fn ceil(self) -> Self;
    /// Nearest integer, halves away from zero (RSL `round`).
    fn round(self) -> Self;
    /// Integer part, toward zero.
    fn trunc(self) -> Self;
    /// Lane-wise minimum (a NaN operand yields the other operand).
    fn min(self, rhs: Self) -> Self;
    /// Lane-wise maximum (a NaN operand yields the other operand).
    fn max(self, rhs: Self) -> Self;
    /// √x (NaN for x < 0).
    fn sqrt(self) -> Self;
    /// 1/√x: `+0 → +inf`, `-0 → -inf`, `+inf → +0`, NaN for x < 0. Correctly rounded for
    /// `f64` (and outward-rounded for intervals); for `f32` and its SIMD types the hardware's
    /// estimate refined by one Newton step ([`rsqrt_f32`]) — within 1 ulp with AVX-512's
    /// 14-bit estimate, 2 ulp with the 12-bit SSE/AVX one, and the same bits in scalar `f32`
    /// and every SIMD lane. It takes the place of a square root and a divide, the two slowest
    /// operations of a shading chain (`normalize`, every highlight).
    #[inline(always)]
    fn rsqrt(self) -> Self {
        Self::c(1.0) / self.sqrt()
    }
    /// `self·m + a`. Fused (one rounding) for the types with a fused multiply-add — `f32`,
    /// `f64` and the SIMD types on FMA hardware, dual numbers in their value — so that every
    /// instantiation of a library function that uses it computes the same bits lane for lane;
    /// intervals evaluate the product and the sum, each rounded outward.
    #[inline(always)]
    fn mul_add(self, m: Self, a: Self) -> Self {
        self * m + a
    }
    /// e^x.
    fn exp(self) -> Self;
    /// 2^x.
    fn exp2(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// Base-2 logarithm.
    fn log2(self) -> Self;
    /// x^y for x ≥ 0 (RSL `pow`); `pow(0, y>0) = 0`; a negative base gives NaN unless y is
    /// an integer (then the sign follows the parity of y), as C `pow` does.
    fn pow(self, y: Self) -> Self;
    /// [`ShadingFloat::pow`] of two packets, `[x[0]^y[0], x[1]^y[1]]`, the same bits: a type
    /// may compute them in one pass (the SIMD types do, so that `Pair`'s halves share one
    /// run of `pow`'s branches and overlap their latencies).
    #[inline(always)]
    fn pow2(x: [Self; 2], y: [Self; 2]) -> [Self; 2] {
        [x[0].pow(y[0]), x[1].pow(y[1])]
    }
    /// [`ShadingFloat::pow2`] of four packets.
    #[inline(always)]
    fn pow4(x: [Self; 4], y: [Self; 4]) -> [Self; 4] {
        let [a, b] = Self::pow2([x[0], x[1]], [y[0], y[1]]);
        let [c, d] = Self::pow2([x[2], x[3]], [y[2], y[3]]);
        [a, b, c, d]
    }
    /// sin x.
    fn sin(self) -> Self;
    /// cos x.
    fn cos(self) -> Self;
    /// tan x.
    fn tan(self) -> Self;
    /// asin x (NaN outside [-1, 1]).
    fn asin(self) -> Self;
    /// acos x (NaN outside [-1, 1]).
    fn acos(self) -> Self;
    /// atan x.
    fn atan(self) -> Self;
    /// atan2(y = self, x).
    fn atan2(self, x: Self) -> Self;

    /// The two's-complement bit pattern of `(i32) floor(self)` (the lattice coordinate of the
    /// noise hash). Values outside the i32 range saturate.
    fn floor_bits(self) -> Self::Bits;
    /// The bits of `self` modulo 2^32 where `self` is an integer with |self| ≤ 2^31 (a noise
    /// cell's corner after `floor` and the reduction to the hash period): `(i64) self as u32`,
    /// one conversion without [`floor_bits`](Self::floor_bits)' range checks. Other inputs
    /// give unspecified bits.
    fn lattice_bits(self) -> Self::Bits;
    /// `(h >> 8) · 2^-24`: the top 24 hash bits as a number in [0, 1), exact in f32.
    fn bits_to_unit(h: Self::Bits) -> Self;
    /// `table[h & 15]` lane by lane: a 16-entry constant table held in registers (one
    /// permute at 16 lanes, one two-table permute at 8 with AVX-512VL) — the noise gradients.
    /// Dual numbers give constants (no derivatives); intervals the hull of the table where the
    /// bits are not known.
    fn lookup16(table: &[f32; 16], h: Self::Bits) -> Self;
    /// Converts integer lanes to floats (`(i32) h` as a float).
    fn bits_to_float_signed(h: Self::Bits) -> Self;

    /// `f(args)`, for library functions whose derivatives are best taken by a separate
    /// evaluation (noise). Every type but dual numbers evaluates `f` directly. Dual numbers
    /// take the value from `f` at their inner type (exactly what that type computes) and the
    /// derivatives from a second, separate evaluation: both are pure, so where a shader never
    /// reads the derivatives (its output derivatives are dropped) the compiler deletes the
    /// second whole, even where it is compiled out of line.
    #[inline(always)]
    fn apply<P: PureFn<N>, const N: usize>(f: &P, args: [Self; N]) -> Self {
        f.eval(args)
    }

    /// Screen-space derivative ∂/∂x (zero unless [`Self::HAS_DERIVS`]).
    #[inline(always)]
    fn dx(self) -> Self {
        Self::c(0.0)
    }
    /// Screen-space derivative ∂/∂y (zero unless [`Self::HAS_DERIVS`]).
    #[inline(always)]
    fn dy(self) -> Self {
        Self::c(0.0)
    }
    /// The value with its derivatives dropped (identity unless [`Self::HAS_DERIVS`]).
    #[inline(always)]
    fn value(self) -> Self {
        self
    }
    /// The value with derivatives set to `(dx, dy)` (ignored unless [`Self::HAS_DERIVS`]).
    #[inline(always)]
    fn with_derivs(self, _dx: Self, _dy: Self) -> Self {
        self
    }
    /// Lower bound in lane `i` (the value itself for point types).
    #[inline(always)]
    fn lower(self, i: usize) -> f64 {
        self.lane(i)
    }
    /// Upper bound in lane `i` (the value itself for point types).
    #[inline(always)]
    fn upper(self, i: usize) -> f64 {
        self.lane(i)
    }
}

/// Whether [`rsqrt_f32`] starts from AVX-512's 14-bit estimate (`vrsqrt14`, which takes
/// subnormal inputs as they are) rather than the 12-bit SSE/AVX one (which takes them as 0).
/// Every SIMD width uses the same estimate as scalar `f32`, so the lanes agree bit for bit.
pub const RSQRT_ESTIMATE_14: bool =
    cfg!(all(target_arch = "x86_64", target_feature = "avx512f", target_feature = "avx512vl"));

/// The hardware estimate of 1/√x; off x86-64, the quotient itself (the Newton step then keeps
/// it).
#[inline(always)]
fn rsqrt_estimate_f32(x: f32) -> f32 {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx512f", target_feature = "avx512vl"))]
    // SAFETY: AVX-512F is enabled for this build.
    return unsafe {
        use core::arch::x86_64::{_mm_cvtss_f32, _mm_rsqrt14_ss, _mm_set_ss};
        let v = _mm_set_ss(x);
        _mm_cvtss_f32(_mm_rsqrt14_ss(v, v))
    };
    #[cfg(all(
        target_arch = "x86_64",
        target_feature = "sse",
        not(all(target_feature = "avx512f", target_feature = "avx512vl"))
    ))]
    // SAFETY: SSE is enabled for this build.
    return unsafe {
        use core::arch::x86_64::{_mm_cvtss_f32, _mm_rsqrt_ss, _mm_set_ss};
        _mm_cvtss_f32(_mm_rsqrt_ss(_mm_set_ss(x)))
    };
    #[allow(unreachable_code)]
    {
        1.0 / x.sqrt()
    }
}

/// `1/√x` in `f32` as every `f32`-based type computes it: the hardware estimate `y`, one
/// Newton step `y + y/2·(1 - (x·y)·y)` (written so that no intermediate overflows for
/// subnormal `x`), and the estimate itself where the step gives NaN (`x` = ±0, +inf, NaN or
/// negative: the estimate is already the answer). The 12-bit estimate takes subnormal inputs
/// as 0, so those are scaled by 2^24 first. The SIMD kernels of `anysl-simd` compute the same
/// operations lane by lane (tested bit for bit).
#[inline(always)]
#[must_use]
pub fn rsqrt_f32(x: f32) -> f32 {
    let tiny = !RSQRT_ESTIMATE_14 && x.abs() < f32::MIN_POSITIVE;
    let xs = if tiny { x * 16_777_216.0 } else { x };
    let y = rsqrt_estimate_f32(xs);
    let t = xs * y;
    let e = (-t).mul_add(y, 1.0);
    let r = (y * 0.5).mul_add(e, y);
    let r = if r.is_nan() { y } else { r };
    if tiny {
        r * 4096.0
    } else {
        r
    }
}

macro_rules! impl_scalar_float {
    ($t:ident, $name:literal, $roundoff:expr, $rsqrt:expr) => {
        impl Blend<$t> for $t {
            #[inline(always)]
            fn blend(m: bool, a: Self, b: Self) -> Self {
                if m {
                    a
                } else {
                    b
                }
            }
        }

        impl ShadingFloat for $t {
            type Mask = bool;
            type Bits = u32;
            const LANES: usize = 1;
            const UNIT_ROUNDOFF: f64 = $roundoff;
            const NAME: &'static str = $name;

            #[inline(always)]
            fn c(v: f64) -> Self {
                v as $t
            }
            #[inline(always)]
            fn lookup16(table: &[f32; 16], h: u32) -> Self {
                table[(h & 15) as usize] as $t
            }
            #[inline(always)]
            fn lane(self, _i: usize) -> f64 {
                self as f64
            }
            #[inline(always)]
            fn from_lanes(lanes: &[f64]) -> Self {
                lanes[0] as $t
            }
            #[inline(always)]
            fn load(src: &[f32]) -> Self {
                src[0] as $t
            }
            #[inline(always)]
            fn store(self, dst: &mut [f32]) {
                dst[0] = self as f32;
            }
            #[inline(always)]
            fn select(m: bool, a: Self, b: Self) -> Self {
                if m {
                    a
                } else {
                    b
                }
            }
            #[inline(always)]
            fn lt(self, rhs: Self) -> bool {
                self < rhs
            }
            #[inline(always)]
            fn le(self, rhs: Self) -> bool {
                self <= rhs
            }
            #[inline(always)]
            fn eq(self, rhs: Self) -> bool {
                self == rhs
            }
            #[inline(always)]
            fn is_nan(self) -> bool {
                <$t>::is_nan(self)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            #[inline(always)]
            fn floor(self) -> Self {
                <$t>::floor(self)
            }
            #[inline(always)]
            fn ceil(self) -> Self {
                <$t>::ceil(self)
            }
            #[inline(always)]
            fn round(self) -> Self {
                <$t>::round(self)
            }
            #[inline(always)]
            fn trunc(self) -> Self {
                <$t>::trunc(self)
            }
            #[inline(always)]
            fn min(self, rhs: Self) -> Self {
                <$t>::min(self, rhs)
            }
            #[inline(always)]
            fn max(self, rhs: Self) -> Self {
                <$t>::max(self, rhs)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            #[inline(always)]
            fn mul_add(self, m: Self, a: Self) -> Self {
                <$t>::mul_add(self, m, a)
            }
            #[inline(always)]
            fn rsqrt(self) -> Self {
                $rsqrt(self)
            }
            #[inline(always)]
            fn exp(self) -> Self {
                <$t>::exp(self)
            }
            #[inline(always)]
            fn exp2(self) -> Self {
                <$t>::exp2(self)
            }
            #[inline(always)]
            fn ln(self) -> Self {
                <$t>::ln(self)
            }
            #[inline(always)]
            fn log2(self) -> Self {
                <$t>::log2(self)
            }
            #[inline(always)]
            fn pow(self, y: Self) -> Self {
                <$t>::powf(self, y)
            }
            #[inline(always)]
            fn sin(self) -> Self {
                <$t>::sin(self)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                <$t>::cos(self)
            }
            #[inline(always)]
            fn tan(self) -> Self {
                <$t>::tan(self)
            }
            #[inline(always)]
            fn asin(self) -> Self {
                <$t>::asin(self)
            }
            #[inline(always)]
            fn acos(self) -> Self {
                <$t>::acos(self)
            }
            #[inline(always)]
            fn atan(self) -> Self {
                <$t>::atan(self)
            }
            #[inline(always)]
            fn atan2(self, x: Self) -> Self {
                <$t>::atan2(self, x)
            }
            #[inline(always)]
            fn floor_bits(self) -> u32 {
                // `as` saturates out-of-range values and maps NaN to 0.
                (<$t>::floor(self) as i32) as u32
            }
            #[inline(always)]
            fn lattice_bits(self) -> u32 {
                // Wrapping: 2^31 gives the bits of -2^31, as the vector conversion does.
                (self as i64) as u32
            }
            #[inline(always)]
            fn bits_to_unit(h: u32) -> Self {
                // The top 24 bits, so that every precision gives the same exact value.
                ((h >> 8) as f64 * (1.0 / 16777216.0)) as $t
            }
            #[inline(always)]
            fn bits_to_float_signed(h: u32) -> Self {
                (h as i32) as $t
            }
        }
    };
}

impl_scalar_float!(f32, "f32", 5.960464477539063e-8, rsqrt_f32);
impl_scalar_float!(f64, "f64", 1.1102230246251565e-16, |x: f64| 1.0 / x.sqrt());
