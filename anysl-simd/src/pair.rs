//! [`Pair<F>`]: two independent packets of any [`ShadingFloat`] shaded together, operation by
//! operation — the "double-pumped" gangs of ISPC's `avx2-i32x16` / `avx512skx-x32` targets.
//!
//! A shading function is a few long dependency chains (square root → divide → the
//! polynomials of `pow`, the lattice hash of noise): one packet at a time, the FMA units wait
//! on their latency most of the time. With `Pair<F>` every operation is issued for both halves
//! next to each other, inside the same basic blocks (a mask test asks both halves at once), so
//! the second chain fills the first one's latency. Each half computes exactly what `F`
//! computes: lane `i` of a `Pair<F>` is bit for bit lane `i mod F::LANES` of the `F` run on
//! its half.

use anysl_core::{Blend, LatticeBits, Mask, PureFn, ShadingFloat};
use core::ops::{
    Add, AddAssign, BitAnd, BitOr, BitXor, Div, DivAssign, Mul, MulAssign, Neg, Not, Shl, Shr, Sub, SubAssign,
};

/// Two packets of `F`, lanes `0..F::LANES` in `.0` and the rest in `.1` — in that order in
/// memory (`repr(C)`), so a `Pair<Pair<F32x8>>` is 32 consecutive lanes, as JIT-compiled code
/// reads it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct Pair<F>(pub F, pub F);

/// The lane mask of a [`Pair`].
#[derive(Clone, Copy, Debug)]
pub struct PairMask<M>(pub M, pub M);

/// The integer lanes of a [`Pair`].
#[derive(Clone, Copy, Debug)]
pub struct PairBits<B>(pub B, pub B);

macro_rules! binop {
    ($T:ident, $tr:ident, $f:ident, $bound:ident) => {
        impl<X: $bound> $tr for $T<X> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, r: Self) -> Self {
                Self($tr::$f(self.0, r.0), $tr::$f(self.1, r.1))
            }
        }
    };
}

binop!(Pair, Add, add, ShadingFloat);
binop!(Pair, Sub, sub, ShadingFloat);
binop!(Pair, Mul, mul, ShadingFloat);
binop!(Pair, Div, div, ShadingFloat);
binop!(PairMask, BitAnd, bitand, Mask);
binop!(PairMask, BitOr, bitor, Mask);
binop!(PairBits, BitAnd, bitand, LatticeBits);
binop!(PairBits, BitOr, bitor, LatticeBits);
binop!(PairBits, BitXor, bitxor, LatticeBits);

impl<F: ShadingFloat> AddAssign for Pair<F> {
    #[inline(always)]
    fn add_assign(&mut self, r: Self) {
        *self = *self + r;
    }
}
impl<F: ShadingFloat> SubAssign for Pair<F> {
    #[inline(always)]
    fn sub_assign(&mut self, r: Self) {
        *self = *self - r;
    }
}
impl<F: ShadingFloat> MulAssign for Pair<F> {
    #[inline(always)]
    fn mul_assign(&mut self, r: Self) {
        *self = *self * r;
    }
}
impl<F: ShadingFloat> DivAssign for Pair<F> {
    #[inline(always)]
    fn div_assign(&mut self, r: Self) {
        *self = *self / r;
    }
}

impl<F: ShadingFloat> Neg for Pair<F> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self(-self.0, -self.1)
    }
}

impl<M: Mask> Not for PairMask<M> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        Self(!self.0, !self.1)
    }
}

impl<B: LatticeBits> Shr<u32> for PairBits<B> {
    type Output = Self;
    #[inline(always)]
    fn shr(self, r: u32) -> Self {
        Self(self.0 >> r, self.1 >> r)
    }
}

impl<B: LatticeBits> Shl<u32> for PairBits<B> {
    type Output = Self;
    #[inline(always)]
    fn shl(self, r: u32) -> Self {
        Self(self.0 << r, self.1 << r)
    }
}

impl<M: Mask> Mask for PairMask<M> {
    const LANES: usize = 2 * M::LANES;
    const THREE_VALUED: bool = M::THREE_VALUED;
    #[inline(always)]
    fn splat(b: bool) -> Self {
        Self(M::splat(b), M::splat(b))
    }
    #[inline(always)]
    fn any(self) -> bool {
        // Both halves are tested without a branch between them (`|`, not `||`).
        self.0.any() | self.1.any()
    }
    #[inline(always)]
    fn all(self) -> bool {
        self.0.all() & self.1.all()
    }
    #[inline(always)]
    fn lane(self, i: usize) -> bool {
        if i < M::LANES {
            self.0.lane(i)
        } else {
            self.1.lane(i - M::LANES)
        }
    }
    #[inline(always)]
    fn from_bits(bits: u32) -> Self {
        Self(M::from_bits(bits), M::from_bits(bits >> M::LANES))
    }
    #[inline(always)]
    fn to_bits(self) -> u32 {
        self.0.to_bits() | self.1.to_bits() << M::LANES
    }
    #[inline(always)]
    fn select_mask(m: Self, a: Self, b: Self) -> Self {
        Self(M::select_mask(m.0, a.0, b.0), M::select_mask(m.1, a.1, b.1))
    }
}

impl<B: LatticeBits> LatticeBits for PairBits<B> {
    type Mask = PairMask<B::Mask>;
    #[inline(always)]
    fn splat(v: u32) -> Self {
        Self(B::splat(v), B::splat(v))
    }
    #[inline(always)]
    fn wrapping_add(self, r: Self) -> Self {
        Self(self.0.wrapping_add(r.0), self.1.wrapping_add(r.1))
    }
    #[inline(always)]
    fn wrapping_mul(self, r: Self) -> Self {
        Self(self.0.wrapping_mul(r.0), self.1.wrapping_mul(r.1))
    }
    #[inline(always)]
    fn eq_mask(self, r: Self) -> Self::Mask {
        PairMask(self.0.eq_mask(r.0), self.1.eq_mask(r.1))
    }
    #[inline(always)]
    fn lane(self, i: usize) -> u32 {
        let n = <B::Mask as Mask>::LANES;
        if i < n {
            self.0.lane(i)
        } else {
            self.1.lane(i - n)
        }
    }
}

impl<F: ShadingFloat> Blend<Pair<F>> for Pair<F> {
    #[inline(always)]
    fn blend(m: PairMask<F::Mask>, a: Self, b: Self) -> Self {
        <Self as ShadingFloat>::select(m, a, b)
    }
    #[inline(always)]
    fn widen(self) -> Self {
        Self(self.0.widen(), self.1.widen())
    }
}

macro_rules! unary {
    ($($f:ident),*) => {
        $(
            #[inline(always)]
            fn $f(self) -> Self {
                Self(self.0.$f(), self.1.$f())
            }
        )*
    };
}

macro_rules! binary {
    ($($f:ident),*) => {
        $(
            #[inline(always)]
            fn $f(self, r: Self) -> Self {
                Self(self.0.$f(r.0), self.1.$f(r.1))
            }
        )*
    };
}

macro_rules! compare {
    ($($f:ident),*) => {
        $(
            #[inline(always)]
            fn $f(self, r: Self) -> Self::Mask {
                PairMask(self.0.$f(r.0), self.1.$f(r.1))
            }
        )*
    };
}

impl<F: ShadingFloat> ShadingFloat for Pair<F> {
    type Mask = PairMask<F::Mask>;
    type Bits = PairBits<F::Bits>;
    const LANES: usize = 2 * F::LANES;
    const HAS_DERIVS: bool = F::HAS_DERIVS;
    const UNIT_ROUNDOFF: f64 = F::UNIT_ROUNDOFF;
    const NAME: &'static str = F::NAME;

    #[inline(always)]
    fn c(v: f64) -> Self {
        let c = F::c(v);
        Self(c, c)
    }
    #[inline(always)]
    fn lane(self, i: usize) -> f64 {
        if i < F::LANES {
            self.0.lane(i)
        } else {
            self.1.lane(i - F::LANES)
        }
    }
    #[inline]
    fn from_lanes(lanes: &[f64]) -> Self {
        assert_eq!(lanes.len(), Self::LANES, "from_lanes needs exactly LANES values");
        Self(F::from_lanes(&lanes[..F::LANES]), F::from_lanes(&lanes[F::LANES..]))
    }
    #[inline(always)]
    fn load(src: &[f32]) -> Self {
        Self(F::load(src), F::load(&src[F::LANES..]))
    }
    #[inline(always)]
    fn load_into(&mut self, src: &[f32], neg: bool) {
        self.0.load_into(src, neg);
        self.1.load_into(&src[F::LANES..], neg);
    }
    #[inline(always)]
    fn store(self, dst: &mut [f32]) {
        self.0.store(dst);
        self.1.store(&mut dst[F::LANES..]);
    }
    #[inline(always)]
    fn select(m: Self::Mask, a: Self, b: Self) -> Self {
        Self(F::select(m.0, a.0, b.0), F::select(m.1, a.1, b.1))
    }
    compare!(lt, le, gt, ge, eq, ne);
    #[inline(always)]
    fn is_nan(self) -> Self::Mask {
        PairMask(self.0.is_nan(), self.1.is_nan())
    }
    unary!(abs, floor, ceil, round, trunc, sqrt, rsqrt, exp, exp2, ln, log2, sin, cos, tan, asin, acos, atan);
    unary!(dx, dy, value);
    binary!(min, max, atan2);
    /// Both halves through one run of `pow` where `F` computes several packets at once
    /// ([`ShadingFloat::pow2`]), the same bits as each half alone.
    #[inline(always)]
    fn pow(self, y: Self) -> Self {
        let [a, b] = F::pow2([self.0, self.1], [y.0, y.1]);
        Self(a, b)
    }
    #[inline(always)]
    fn pow2(x: [Self; 2], y: [Self; 2]) -> [Self; 2] {
        let [a, b, c, d] = F::pow4([x[0].0, x[0].1, x[1].0, x[1].1], [y[0].0, y[0].1, y[1].0, y[1].1]);
        [Self(a, b), Self(c, d)]
    }
    #[inline(always)]
    fn mul_add(self, m: Self, a: Self) -> Self {
        Self(self.0.mul_add(m.0, a.0), self.1.mul_add(m.1, a.1))
    }

    #[inline(always)]
    fn floor_bits(self) -> Self::Bits {
        PairBits(self.0.floor_bits(), self.1.floor_bits())
    }
    #[inline(always)]
    fn lattice_bits(self) -> Self::Bits {
        PairBits(self.0.lattice_bits(), self.1.lattice_bits())
    }
    #[inline(always)]
    fn lookup16(table: &[f32; 16], h: Self::Bits) -> Self {
        Self(F::lookup16(table, h.0), F::lookup16(table, h.1))
    }
    #[inline(always)]
    fn bits_to_unit(h: Self::Bits) -> Self {
        Self(F::bits_to_unit(h.0), F::bits_to_unit(h.1))
    }
    #[inline(always)]
    fn bits_to_float_signed(h: Self::Bits) -> Self {
        Self(F::bits_to_float_signed(h.0), F::bits_to_float_signed(h.1))
    }
    #[inline(always)]
    fn apply<P: PureFn<N>, const N: usize>(f: &P, args: [Self; N]) -> Self {
        Self(F::apply(f, args.map(|a| a.0)), F::apply(f, args.map(|a| a.1)))
    }
    #[inline(always)]
    fn with_derivs(self, dx: Self, dy: Self) -> Self {
        Self(self.0.with_derivs(dx.0, dy.0), self.1.with_derivs(dx.1, dy.1))
    }
    #[inline(always)]
    fn lower(self, i: usize) -> f64 {
        if i < F::LANES {
            self.0.lower(i)
        } else {
            self.1.lower(i - F::LANES)
        }
    }
    #[inline(always)]
    fn upper(self, i: usize) -> f64 {
        if i < F::LANES {
            self.0.upper(i)
        } else {
            self.1.upper(i - F::LANES)
        }
    }
}
