//! [`Dual`]: a value with its screen-space derivatives ∂/∂x and ∂/∂y, carried through every
//! operation by the chain rule (forward-mode automatic differentiation).

use crate::name::{as_str, prefixed, NAME_CAP};
use anysl_core::{Blend, PureFn, ShadingFloat};
use core::f64::consts::{LN_2, LOG2_E};
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// A value `val` with derivatives `ddx = ∂val/∂x`, `ddy = ∂val/∂y`, each of the inner type
/// `F` (so `Dual<F32x8>` differentiates eight shading points at once).
///
/// Comparisons and [`ShadingFloat::select`] look at values only; `select` blends value and
/// derivatives with the same lane mask. See the crate docs for the derivative policy at
/// singular points.
#[derive(Clone, Copy, Debug)]
pub struct Dual<F> {
    /// The value.
    pub val: F,
    /// ∂/∂x (screen space).
    pub ddx: F,
    /// ∂/∂y (screen space).
    pub ddy: F,
}

/// `x` where finite, else 0: a chain-rule factor at a singular point (see the crate docs).
#[inline(always)]
fn finite_or_zero<F: ShadingFloat>(x: F) -> F {
    F::select(x.abs().lt(F::c(f64::INFINITY)), x, F::c(0.0))
}

impl<F: ShadingFloat> Dual<F> {
    const NAME_BUF: ([u8; NAME_CAP], usize) = prefixed("dual-", F::NAME);
    const NAME_BYTES: &'static [u8; NAME_CAP] = &Self::NAME_BUF.0;

    /// A value with the given derivatives.
    #[inline(always)]
    #[must_use]
    pub fn new(val: F, ddx: F, ddy: F) -> Self {
        Self { val, ddx, ddy }
    }
    /// A value that does not vary over the screen (zero derivatives).
    #[inline(always)]
    #[must_use]
    pub fn constant(val: F) -> Self {
        let z = F::c(0.0);
        Self { val, ddx: z, ddy: z }
    }
    /// The screen coordinate x itself: derivatives `(1, 0)`.
    #[inline(always)]
    #[must_use]
    pub fn seed_x(val: F) -> Self {
        Self { val, ddx: F::c(1.0), ddy: F::c(0.0) }
    }
    /// The screen coordinate y itself: derivatives `(0, 1)`.
    #[inline(always)]
    #[must_use]
    pub fn seed_y(val: F) -> Self {
        Self { val, ddx: F::c(0.0), ddy: F::c(1.0) }
    }
    /// The chain rule for a unary function: value `f` and derivative factor `k = f'(val)`.
    #[inline(always)]
    fn chain(self, f: F, k: F) -> Self {
        Self { val: f, ddx: self.ddx * k, ddy: self.ddy * k }
    }
    /// The chain rule for a binary function with partial derivatives `ka`, `kb`.
    #[inline(always)]
    fn chain2(self, rhs: Self, f: F, ka: F, kb: F) -> Self {
        Self { val: f, ddx: self.ddx * ka + rhs.ddx * kb, ddy: self.ddy * ka + rhs.ddy * kb }
    }
}

impl<F: ShadingFloat> Add for Dual<F> {
    type Output = Self;
    #[inline(always)]
    fn add(self, r: Self) -> Self {
        Self { val: self.val + r.val, ddx: self.ddx + r.ddx, ddy: self.ddy + r.ddy }
    }
}

impl<F: ShadingFloat> Sub for Dual<F> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, r: Self) -> Self {
        Self { val: self.val - r.val, ddx: self.ddx - r.ddx, ddy: self.ddy - r.ddy }
    }
}

impl<F: ShadingFloat> Mul for Dual<F> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, r: Self) -> Self {
        Self {
            val: self.val * r.val,
            ddx: self.ddx * r.val + self.val * r.ddx,
            ddy: self.ddy * r.val + self.val * r.ddy,
        }
    }
}

impl<F: ShadingFloat> Div for Dual<F> {
    type Output = Self;
    /// `(∂a - q·∂b) / b`; a derivative that is not finite (a divisor at or near 0, e.g. a
    /// denormal whose reciprocal overflows) is 0.
    #[inline(always)]
    fn div(self, r: Self) -> Self {
        let q = self.val / r.val;
        let inv = F::c(1.0) / r.val;
        Self {
            val: q,
            ddx: finite_or_zero((self.ddx - q * r.ddx) * inv),
            ddy: finite_or_zero((self.ddy - q * r.ddy) * inv),
        }
    }
}

impl<F: ShadingFloat> Neg for Dual<F> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self { val: -self.val, ddx: -self.ddx, ddy: -self.ddy }
    }
}

macro_rules! assign_ops {
    ($($Tr:ident $m:ident $op:tt),*) => {$(
        impl<F: ShadingFloat> $Tr for Dual<F> {
            #[inline(always)]
            fn $m(&mut self, r: Self) {
                *self = *self $op r;
            }
        }
    )*};
}
assign_ops!(AddAssign add_assign +, SubAssign sub_assign -, MulAssign mul_assign *, DivAssign div_assign /);

impl<F: ShadingFloat> Blend<Dual<F>> for Dual<F> {
    #[inline(always)]
    fn blend(m: F::Mask, a: Self, b: Self) -> Self {
        <Self as ShadingFloat>::select(m, a, b)
    }
    #[inline(always)]
    fn widen(self) -> Self {
        Self { val: self.val.widen(), ddx: self.ddx.widen(), ddy: self.ddy.widen() }
    }
}

impl<F: ShadingFloat> ShadingFloat for Dual<F> {
    type Mask = F::Mask;
    type Bits = F::Bits;
    const LANES: usize = F::LANES;
    const HAS_DERIVS: bool = true;
    const UNIT_ROUNDOFF: f64 = F::UNIT_ROUNDOFF;
    const NAME: &'static str = as_str(Self::NAME_BYTES, Self::NAME_BUF.1);

    #[inline(always)]
    fn c(v: f64) -> Self {
        Self::constant(F::c(v))
    }
    #[inline(always)]
    fn lane(self, i: usize) -> f64 {
        self.val.lane(i)
    }
    #[inline(always)]
    fn from_lanes(lanes: &[f64]) -> Self {
        Self::constant(F::from_lanes(lanes))
    }

    #[inline(always)]
    fn load(src: &[f32]) -> Self {
        Self::constant(F::load(src))
    }

    #[inline(always)]
    fn store(self, dst: &mut [f32]) {
        self.val.store(dst);
    }

    #[inline(always)]
    fn select(m: F::Mask, a: Self, b: Self) -> Self {
        Self { val: F::select(m, a.val, b.val), ddx: F::select(m, a.ddx, b.ddx), ddy: F::select(m, a.ddy, b.ddy) }
    }
    #[inline(always)]
    fn lt(self, rhs: Self) -> F::Mask {
        self.val.lt(rhs.val)
    }
    #[inline(always)]
    fn le(self, rhs: Self) -> F::Mask {
        self.val.le(rhs.val)
    }
    #[inline(always)]
    fn eq(self, rhs: Self) -> F::Mask {
        self.val.eq(rhs.val)
    }
    #[inline(always)]
    fn is_nan(self) -> F::Mask {
        self.val.is_nan()
    }

    /// Derivative sign taken from the value; at 0 the derivative passes through unchanged.
    #[inline(always)]
    fn abs(self) -> Self {
        let neg = self.val.lt(F::c(0.0));
        Self { val: self.val.abs(), ddx: F::select(neg, -self.ddx, self.ddx), ddy: F::select(neg, -self.ddy, self.ddy) }
    }
    #[inline(always)]
    fn floor(self) -> Self {
        Self::constant(self.val.floor())
    }
    #[inline(always)]
    fn ceil(self) -> Self {
        Self::constant(self.val.ceil())
    }
    #[inline(always)]
    fn round(self) -> Self {
        Self::constant(self.val.round())
    }
    #[inline(always)]
    fn trunc(self) -> Self {
        Self::constant(self.val.trunc())
    }
    /// Derivatives of the operand chosen; ties take `self`.
    #[inline(always)]
    fn min(self, rhs: Self) -> Self {
        let take_rhs = rhs.val.lt(self.val) | self.val.is_nan();
        let pick = <Self as ShadingFloat>::select(take_rhs, rhs, self);
        Self { val: self.val.min(rhs.val), ..pick }
    }
    /// Derivatives of the operand chosen; ties take `self`.
    #[inline(always)]
    fn max(self, rhs: Self) -> Self {
        let take_rhs = self.val.lt(rhs.val) | self.val.is_nan();
        let pick = <Self as ShadingFloat>::select(take_rhs, rhs, self);
        Self { val: self.val.max(rhs.val), ..pick }
    }
    /// The value fused; `∂(a·m + c) = ∂a·m + a·∂m + ∂c`.
    #[inline(always)]
    fn mul_add(self, m: Self, a: Self) -> Self {
        Self {
            val: self.val.mul_add(m.val, a.val),
            ddx: self.ddx.mul_add(m.val, self.val.mul_add(m.ddx, a.ddx)),
            ddy: self.ddy.mul_add(m.val, self.val.mul_add(m.ddy, a.ddy)),
        }
    }
    /// `-1/(2x√x) = -r³/2`; 0 where not finite (at x = 0).
    #[inline(always)]
    fn rsqrt(self) -> Self {
        let r = self.val.rsqrt();
        self.chain(r, finite_or_zero(F::c(-0.5) * r * r * r))
    }
    /// `1/(2√x)`; 0 at x = 0.
    #[inline(always)]
    fn sqrt(self) -> Self {
        let s = self.val.sqrt();
        self.chain(s, finite_or_zero(F::c(0.5) / s))
    }
    #[inline(always)]
    fn exp(self) -> Self {
        let e = self.val.exp();
        self.chain(e, e)
    }
    #[inline(always)]
    fn exp2(self) -> Self {
        let e = self.val.exp2();
        self.chain(e, e * F::c(LN_2))
    }
    /// `1/x`; 0 at x = 0.
    #[inline(always)]
    fn ln(self) -> Self {
        self.chain(self.val.ln(), finite_or_zero(F::c(1.0) / self.val))
    }
    /// `1/(x ln 2)`; 0 at x = 0.
    #[inline(always)]
    fn log2(self) -> Self {
        self.chain(self.val.log2(), finite_or_zero(F::c(LOG2_E) / self.val))
    }
    /// `∂/∂x = y·x^(y-1)` (at x = 0: 1 for y = 1, else 0), `∂/∂y = x^y·ln x` (0 where
    /// `ln x` is not finite).
    #[inline(always)]
    fn pow(self, y: Self) -> Self {
        let (z, one) = (F::c(0.0), F::c(1.0));
        let (x, e) = (self.val, y.val);
        let p = x.pow(e);
        let at0 = x.eq(z);
        let kx = F::select(at0, F::select(e.eq(one), one, z), e * p / F::select(at0, one, x));
        let ky = p * x.ln();
        self.chain2(y, p, finite_or_zero(kx), finite_or_zero(ky))
    }
    #[inline(always)]
    fn sin(self) -> Self {
        self.chain(self.val.sin(), self.val.cos())
    }
    #[inline(always)]
    fn cos(self) -> Self {
        self.chain(self.val.cos(), -self.val.sin())
    }
    /// `1 + tan²x`.
    #[inline(always)]
    fn tan(self) -> Self {
        let t = self.val.tan();
        self.chain(t, finite_or_zero(F::c(1.0) + t * t))
    }
    /// `1/√(1-x²)`; 0 at x = ±1.
    #[inline(always)]
    fn asin(self) -> Self {
        let one = F::c(1.0);
        let k = one / ((one - self.val) * (one + self.val)).sqrt();
        self.chain(self.val.asin(), finite_or_zero(k))
    }
    /// `-1/√(1-x²)`; 0 at x = ±1.
    #[inline(always)]
    fn acos(self) -> Self {
        let one = F::c(1.0);
        let k = one / ((one - self.val) * (one + self.val)).sqrt();
        self.chain(self.val.acos(), -finite_or_zero(k))
    }
    #[inline(always)]
    fn atan(self) -> Self {
        let one = F::c(1.0);
        self.chain(self.val.atan(), one / (one + self.val * self.val))
    }
    /// `∂/∂y = x/(x²+y²)`, `∂/∂x = -y/(x²+y²)`, scaled against overflow; 0 at the origin.
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        let y = self;
        let s = x.val.abs().max(y.val.abs());
        let s1 = F::select(s.gt(F::c(0.0)), s, F::c(1.0));
        let (xs, ys) = (x.val / s1, y.val / s1);
        let k = F::c(1.0) / ((xs * xs + ys * ys) * s1);
        y.chain2(x, y.val.atan2(x.val), finite_or_zero(xs * k), finite_or_zero(-ys * k))
    }

    #[inline(always)]
    fn floor_bits(self) -> F::Bits {
        self.val.floor_bits()
    }
    #[inline(always)]
    fn lattice_bits(self) -> F::Bits {
        self.val.lattice_bits()
    }
    #[inline(always)]
    fn lookup16(table: &[f32; 16], h: F::Bits) -> Self {
        Self::constant(F::lookup16(table, h))
    }
    #[inline(always)]
    fn bits_to_unit(h: F::Bits) -> Self {
        Self::constant(F::bits_to_unit(h))
    }
    #[inline(always)]
    fn bits_to_float_signed(h: F::Bits) -> Self {
        Self::constant(F::bits_to_float_signed(h))
    }

    /// The value is `f` at `F` (what the `F` instantiation computes, so values match it bit
    /// for bit); the derivatives come from `f` at `Dual<F>` in a call of its own
    /// ([`dual_eval`], left to the compiler to inline or not), which is dead, and deleted,
    /// wherever the derivatives are.
    #[inline(always)]
    fn apply<P: PureFn<N>, const N: usize>(f: &P, args: [Self; N]) -> Self {
        let val = f.eval::<F>(args.map(|a| a.val));
        let d = dual_eval(f, args);
        Self { val, ddx: d.ddx, ddy: d.ddy }
    }

    #[inline(always)]
    fn dx(self) -> Self {
        Self::constant(self.ddx)
    }
    #[inline(always)]
    fn dy(self) -> Self {
        Self::constant(self.ddy)
    }
    #[inline(always)]
    fn value(self) -> Self {
        Self::constant(self.val)
    }
    #[inline(always)]
    fn with_derivs(self, dx: Self, dy: Self) -> Self {
        Self { val: self.val, ddx: dx.val, ddy: dy.val }
    }
    #[inline(always)]
    fn lower(self, i: usize) -> f64 {
        self.val.lower(i)
    }
    #[inline(always)]
    fn upper(self, i: usize) -> f64 {
        self.val.upper(i)
    }
}

/// `f` at dual numbers: the derivative half of [`Dual::apply`]. A `PureFn` is inlined into
/// the plain instantiations that call it; its dual form, several times larger, is left to
/// the inliner's judgement here.
#[inline]
fn dual_eval<F: ShadingFloat, P: PureFn<N>, const N: usize>(f: &P, args: [Dual<F>; N]) -> Dual<F> {
    f.eval::<Dual<F>>(args)
}
