//! [`IMask`]: the three-valued truth of a comparison between intervals.

use anysl_core::Mask;
use core::ops::{BitAnd, BitOr, Not};

/// Per lane, whether a condition is *possibly true* and whether it is *possibly false*:
/// both set means "maybe". Combines with Kleene's strong logic (`&`, `|`, `!`).
///
/// As a [`Mask`]: `any` = possibly true in some lane, `all` = surely true in every lane,
/// `lane(i)` = possibly true, and [`Mask::THREE_VALUED`] is set so loops widen.
#[derive(Clone, Copy, Debug)]
pub struct IMask<M> {
    possibly_true: M,
    possibly_false: M,
}

impl<M: Mask> IMask<M> {
    /// A mask from its two halves (a lane with neither set is treated as surely false).
    #[inline(always)]
    #[must_use]
    pub fn new(possibly_true: M, possibly_false: M) -> Self {
        Self { possibly_true, possibly_false }
    }
    /// A two-valued mask: every lane surely `m`.
    #[inline(always)]
    #[must_use]
    pub fn exact(m: M) -> Self {
        Self { possibly_true: m, possibly_false: !m }
    }
    /// "Maybe" in the lanes of `m`, surely false elsewhere.
    #[inline(always)]
    #[must_use]
    pub fn maybe_where(m: M) -> Self {
        Self { possibly_true: m, possibly_false: M::splat(true) }
    }
    /// Lanes where the condition may hold.
    #[inline(always)]
    #[must_use]
    pub fn possibly_true(self) -> M {
        self.possibly_true
    }
    /// Lanes where the condition may fail.
    #[inline(always)]
    #[must_use]
    pub fn possibly_false(self) -> M {
        self.possibly_false
    }
    /// Lanes where the condition certainly holds.
    #[inline(always)]
    #[must_use]
    pub fn surely_true(self) -> M {
        self.possibly_true & !self.possibly_false
    }
    /// Lanes where the condition certainly fails.
    #[inline(always)]
    #[must_use]
    pub fn surely_false(self) -> M {
        !self.possibly_true
    }
    /// Lanes where the condition is undecided.
    #[inline(always)]
    #[must_use]
    pub fn maybe(self) -> M {
        self.possibly_true & self.possibly_false
    }
}

impl<M: Mask> BitAnd for IMask<M> {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, rhs: Self) -> Self {
        Self {
            possibly_true: self.possibly_true & rhs.possibly_true,
            possibly_false: self.possibly_false | rhs.possibly_false,
        }
    }
}

impl<M: Mask> BitOr for IMask<M> {
    type Output = Self;
    #[inline(always)]
    fn bitor(self, rhs: Self) -> Self {
        Self {
            possibly_true: self.possibly_true | rhs.possibly_true,
            possibly_false: self.possibly_false & rhs.possibly_false,
        }
    }
}

impl<M: Mask> Not for IMask<M> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        Self { possibly_true: self.possibly_false, possibly_false: self.possibly_true }
    }
}

impl<M: Mask> Mask for IMask<M> {
    const LANES: usize = M::LANES;
    const THREE_VALUED: bool = true;
    #[inline(always)]
    fn splat(b: bool) -> Self {
        Self::exact(M::splat(b))
    }
    #[inline(always)]
    fn any(self) -> bool {
        self.possibly_true.any()
    }
    #[inline(always)]
    fn all(self) -> bool {
        self.surely_true().all()
    }
    #[inline(always)]
    fn lane(self, i: usize) -> bool {
        self.possibly_true.lane(i)
    }
    #[inline(always)]
    fn from_bits(bits: u32) -> Self {
        Self::exact(M::from_bits(bits))
    }
    #[inline(always)]
    fn to_bits(self) -> u32 {
        self.possibly_true.to_bits()
    }
    /// Surely-true lanes take `a`, surely-false lanes `b`, "maybe" lanes whatever either
    /// could be (the hull of both truth values).
    #[inline(always)]
    fn select_mask(m: Self, a: Self, b: Self) -> Self {
        let (t, f) = (m.possibly_true, m.possibly_false);
        Self {
            possibly_true: (t & a.possibly_true) | (f & b.possibly_true),
            possibly_false: (t & a.possibly_false) | (f & b.possibly_false),
        }
    }
}
