//! The number types ray queries are written over: one `f32` ray, or 4, 8 or 16 rays in the
//! lanes of a `wide` vector. The triangle test and the box test are written once over
//! [`RayLanes`], so a packet computes, lane by lane, exactly what a single ray computes.

use core::ops::{Add, BitAnd, BitOr, Div, Mul, Not, Sub};
use wide::{f32x16, f32x4, f32x8};

/// Rays side by side: plain IEEE arithmetic (never fused, so every width rounds alike),
/// comparisons into a lane mask, and the few reductions traversal needs.
pub trait RayLanes: Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> {
    /// Per-lane booleans.
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitOr<Output = Self::Mask> + Not<Output = Self::Mask>;
    /// Number of lanes.
    const N: usize;
    /// Every lane `v`.
    fn splat(v: f32) -> Self;
    /// Lane `i` = `f(i)`.
    fn from_fn(f: impl FnMut(usize) -> f32) -> Self;
    /// Lane `i` of `self`.
    fn lane(self, i: usize) -> f32;
    /// `self < o` per lane (false with a NaN).
    fn lt(self, o: Self) -> Self::Mask;
    /// `self <= o` per lane (false with a NaN).
    fn le(self, o: Self) -> Self::Mask;
    /// `self > o` per lane (false with a NaN).
    fn gt(self, o: Self) -> Self::Mask;
    /// `self >= o` per lane (false with a NaN).
    fn ge(self, o: Self) -> Self::Mask;
    /// `self != o` per lane (true with a NaN).
    fn ne(self, o: Self) -> Self::Mask;
    /// `|self|`.
    fn abs(self) -> Self;
    /// The smaller of the two; `o` when either is NaN (the `minps` rule).
    fn min_or(self, o: Self) -> Self;
    /// The larger of the two; `o` when either is NaN (the `maxps` rule).
    fn max_or(self, o: Self) -> Self;
    /// `a` where `m`, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// Bit `i` set where lane `i` of `m` is.
    fn bits(m: Self::Mask) -> u32;
}

impl RayLanes for f32 {
    type Mask = bool;
    const N: usize = 1;
    #[inline(always)]
    fn splat(v: f32) -> Self {
        v
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f32) -> Self {
        f(0)
    }
    #[inline(always)]
    fn lane(self, _i: usize) -> f32 {
        self
    }
    #[inline(always)]
    fn lt(self, o: Self) -> bool {
        self < o
    }
    #[inline(always)]
    fn le(self, o: Self) -> bool {
        self <= o
    }
    #[inline(always)]
    fn gt(self, o: Self) -> bool {
        self > o
    }
    #[inline(always)]
    fn ge(self, o: Self) -> bool {
        self >= o
    }
    #[inline(always)]
    fn ne(self, o: Self) -> bool {
        self != o
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f32::abs(self)
    }
    #[inline(always)]
    fn min_or(self, o: Self) -> Self {
        if self < o {
            self
        } else {
            o
        }
    }
    #[inline(always)]
    fn max_or(self, o: Self) -> Self {
        if self > o {
            self
        } else {
            o
        }
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
    fn bits(m: bool) -> u32 {
        u32::from(m)
    }
}

/// [`RayLanes`] for a `wide` float vector; masks are all-ones/all-zeros lanes of the same type.
macro_rules! wide_lanes {
    ($($W:ident: $n:literal),+) => {$(
        impl RayLanes for $W {
            type Mask = $W;
            const N: usize = $n;
            #[inline(always)]
            fn splat(v: f32) -> Self {
                $W::splat(v)
            }
            #[inline(always)]
            fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
                $W::new(core::array::from_fn(f))
            }
            #[inline(always)]
            fn lane(self, i: usize) -> f32 {
                self.as_array()[i]
            }
            #[inline(always)]
            fn lt(self, o: Self) -> Self {
                self.simd_lt(o)
            }
            #[inline(always)]
            fn le(self, o: Self) -> Self {
                self.simd_le(o)
            }
            #[inline(always)]
            fn gt(self, o: Self) -> Self {
                self.simd_gt(o)
            }
            #[inline(always)]
            fn ge(self, o: Self) -> Self {
                self.simd_ge(o)
            }
            #[inline(always)]
            fn ne(self, o: Self) -> Self {
                self.simd_ne(o)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                $W::abs(self)
            }
            #[inline(always)]
            fn min_or(self, o: Self) -> Self {
                self.fast_min(o)
            }
            #[inline(always)]
            fn max_or(self, o: Self) -> Self {
                self.fast_max(o)
            }
            #[inline(always)]
            fn select(m: Self, a: Self, b: Self) -> Self {
                m.select(a, b)
            }
            #[inline(always)]
            fn bits(m: Self) -> u32 {
                m.to_bitmask()
            }
        }
    )+};
}
wide_lanes!(f32x4: 4, f32x8: 8, f32x16: 16);
