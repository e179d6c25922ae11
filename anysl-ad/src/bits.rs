//! [`IBits`]: lattice-hash bits of an interval, with a per-lane "known" flag.

use crate::mask::IMask;
use anysl_core::{LatticeBits, Mask, ShadingFloat};
use core::ops::{BitAnd, BitOr, BitXor, Shl, Shr};

/// The integer side of [`crate::Interval`]: the inner bits plus, per lane, whether they are
/// known. `floor_bits` is known where the whole interval lies in one unit cell; every
/// operation with an unknown operand is unknown, equality on unknown lanes is "maybe", and
/// `bits_to_unit` of unknown bits is `[0, 1)`.
#[derive(Clone, Copy, Debug)]
pub struct IBits<F: ShadingFloat> {
    bits: F::Bits,
    known: F::Mask,
}

impl<F: ShadingFloat> IBits<F> {
    /// Bits with a known-mask (the bits of unknown lanes are an arbitrary guess).
    #[inline(always)]
    #[must_use]
    pub fn new(bits: F::Bits, known: F::Mask) -> Self {
        Self { bits, known }
    }
    /// The stored bits (meaningful only in known lanes).
    #[inline(always)]
    #[must_use]
    pub fn bits(self) -> F::Bits {
        self.bits
    }
    /// The lanes whose bits are known.
    #[inline(always)]
    #[must_use]
    pub fn known(self) -> F::Mask {
        self.known
    }
    #[inline(always)]
    fn combine(self, rhs: Self, bits: F::Bits) -> Self {
        Self { bits, known: self.known & rhs.known }
    }
}

impl<F: ShadingFloat> BitAnd for IBits<F> {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, rhs: Self) -> Self {
        self.combine(rhs, self.bits & rhs.bits)
    }
}

impl<F: ShadingFloat> BitOr for IBits<F> {
    type Output = Self;
    #[inline(always)]
    fn bitor(self, rhs: Self) -> Self {
        self.combine(rhs, self.bits | rhs.bits)
    }
}

impl<F: ShadingFloat> BitXor for IBits<F> {
    type Output = Self;
    #[inline(always)]
    fn bitxor(self, rhs: Self) -> Self {
        self.combine(rhs, self.bits ^ rhs.bits)
    }
}

impl<F: ShadingFloat> Shr<u32> for IBits<F> {
    type Output = Self;
    #[inline(always)]
    fn shr(self, n: u32) -> Self {
        Self { bits: self.bits >> n, known: self.known }
    }
}

impl<F: ShadingFloat> Shl<u32> for IBits<F> {
    type Output = Self;
    #[inline(always)]
    fn shl(self, n: u32) -> Self {
        Self { bits: self.bits << n, known: self.known }
    }
}

impl<F: ShadingFloat> LatticeBits for IBits<F> {
    type Mask = IMask<F::Mask>;
    #[inline(always)]
    fn splat(v: u32) -> Self {
        Self { bits: F::Bits::splat(v), known: F::Mask::splat(true) }
    }
    #[inline(always)]
    fn wrapping_add(self, rhs: Self) -> Self {
        self.combine(rhs, self.bits.wrapping_add(rhs.bits))
    }
    #[inline(always)]
    fn wrapping_mul(self, rhs: Self) -> Self {
        self.combine(rhs, self.bits.wrapping_mul(rhs.bits))
    }
    #[inline(always)]
    fn eq_mask(self, rhs: Self) -> IMask<F::Mask> {
        let eq = self.bits.eq_mask(rhs.bits);
        let unknown = !(self.known & rhs.known);
        IMask::new(eq | unknown, !eq | unknown)
    }
    #[inline(always)]
    fn lane(self, i: usize) -> u32 {
        self.bits.lane(i)
    }
}
