//! The RSL globals of a shading point ([`Globals`], and [`GlobalSet`], the set of them a
//! shader reads) and what a surface shader writes ([`SurfaceOutput`]).

use crate::float::{Blend, ShadingFloat};
use crate::vec::{Color, Vec3};

/// A set of the fields of [`Globals`] — what a shader reads, so that a renderer may leave the
/// others unset (OSL's "globals needed", RenderMan's shader needs). One bit per field;
/// [`SurfaceShader::globals_read`](crate::SurfaceShader::globals_read) publishes it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct GlobalSet(pub u16);

impl GlobalSet {
    /// No global.
    pub const NONE: Self = Self(0);
    /// `P`.
    pub const P: Self = Self(1 << 0);
    /// `N`.
    pub const N: Self = Self(1 << 1);
    /// `Ng`.
    pub const NG: Self = Self(1 << 2);
    /// `I`.
    pub const I: Self = Self(1 << 3);
    /// `E`.
    pub const E: Self = Self(1 << 4);
    /// `s`.
    pub const S: Self = Self(1 << 5);
    /// `t`.
    pub const T: Self = Self(1 << 6);
    /// `u`.
    pub const U: Self = Self(1 << 7);
    /// `v`.
    pub const V: Self = Self(1 << 8);
    /// `du`.
    pub const DU: Self = Self(1 << 9);
    /// `dv`.
    pub const DV: Self = Self(1 << 10);
    /// `dPdu`.
    pub const DPDU: Self = Self(1 << 11);
    /// `dPdv`.
    pub const DPDV: Self = Self(1 << 12);
    /// `Cs`.
    pub const CS: Self = Self(1 << 13);
    /// `Os`.
    pub const OS: Self = Self(1 << 14);
    /// Every global.
    pub const ALL: Self = Self((1 << 15) - 1);

    /// True when every global of `other` is in `self`.
    #[inline(always)]
    #[must_use]
    pub const fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }

    /// The globals in either set.
    #[inline(always)]
    #[must_use]
    pub const fn union(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }
}

impl core::ops::BitOr for GlobalSet {
    type Output = Self;
    #[inline(always)]
    fn bitor(self, rhs: Self) -> Self {
        self.union(rhs)
    }
}

impl core::ops::BitOrAssign for GlobalSet {
    #[inline(always)]
    fn bitor_assign(&mut self, rhs: Self) {
        *self = self.union(rhs);
    }
}

/// The RSL global variables of a surface shading point, named as in RSL.
#[allow(non_snake_case)]
#[derive(Clone, Copy, Debug)]
pub struct Globals<F> {
    /// Surface position.
    pub P: Vec3<F>,
    /// Shading normal.
    pub N: Vec3<F>,
    /// Geometric normal.
    pub Ng: Vec3<F>,
    /// Incident ray direction (from the eye to P, not normalized).
    pub I: Vec3<F>,
    /// Eye position.
    pub E: Vec3<F>,
    /// Texture coordinate s.
    pub s: F,
    /// Texture coordinate t.
    pub t: F,
    /// Surface parameter u.
    pub u: F,
    /// Surface parameter v.
    pub v: F,
    /// Change in u between adjacent samples.
    pub du: F,
    /// Change in v between adjacent samples.
    pub dv: F,
    /// ∂P/∂u.
    pub dPdu: Vec3<F>,
    /// ∂P/∂v.
    pub dPdv: Vec3<F>,
    /// Surface colour.
    pub Cs: Color<F>,
    /// Surface opacity.
    pub Os: Color<F>,
}

impl<F: ShadingFloat> Globals<F> {
    /// Globals with `P` = `p` and every other one zero: what a light shader's run sees (`P`
    /// the surface point).
    #[must_use]
    pub fn at(p: Vec3<F>) -> Self {
        let zero = F::c(0.0);
        Self {
            P: p,
            N: Vec3::zero(),
            Ng: Vec3::zero(),
            I: Vec3::zero(),
            E: Vec3::zero(),
            s: zero,
            t: zero,
            u: zero,
            v: zero,
            du: zero,
            dv: zero,
            dPdu: Vec3::zero(),
            dPdv: Vec3::zero(),
            Cs: Color::zero(),
            Os: Color::zero(),
        }
    }

    /// What an imager shader sees for `px`: `P` its raster position, `Cs` and `Os` its `Ci`
    /// and `Oi`, every other global zero.
    #[must_use]
    pub fn imager(px: &crate::ImagerPixel<F>) -> Self {
        Self { Cs: px.Ci, Os: px.Oi, ..Self::at(px.P) }
    }

    /// Sets every global outside `read` to NaN: shading with the result shows whether a
    /// shader's [`SurfaceShader::globals_read`](crate::SurfaceShader::globals_read) is right
    /// (the tests compare it bit for bit with shading the intact globals).
    pub fn poison_except(&mut self, read: GlobalSet) {
        let nan = F::c(f64::NAN);
        let nan3 = Vec3::new(nan, nan, nan);
        for (bit, v) in [
            (GlobalSet::P, &mut self.P),
            (GlobalSet::N, &mut self.N),
            (GlobalSet::NG, &mut self.Ng),
            (GlobalSet::I, &mut self.I),
            (GlobalSet::E, &mut self.E),
            (GlobalSet::DPDU, &mut self.dPdu),
            (GlobalSet::DPDV, &mut self.dPdv),
        ] {
            if !read.contains(bit) {
                *v = nan3;
            }
        }
        for (bit, v) in [
            (GlobalSet::S, &mut self.s),
            (GlobalSet::T, &mut self.t),
            (GlobalSet::U, &mut self.u),
            (GlobalSet::V, &mut self.v),
            (GlobalSet::DU, &mut self.du),
            (GlobalSet::DV, &mut self.dv),
        ] {
            if !read.contains(bit) {
                *v = nan;
            }
        }
        for (bit, c) in [(GlobalSet::CS, &mut self.Cs), (GlobalSet::OS, &mut self.Os)] {
            if !read.contains(bit) {
                *c = Color::new(nan, nan, nan);
            }
        }
    }
}

impl<F: Copy> Globals<F> {
    /// The same globals with every number transformed by `f` (e.g. to change the number type,
    /// or to step along derivative seeds).
    #[must_use]
    pub fn map<G>(&self, f: impl Fn(F) -> G) -> Globals<G> {
        self.zip(self, |a, _| f(a))
    }

    /// Combines two sets of globals number by number (e.g. lower and upper bounds into
    /// intervals).
    #[must_use]
    pub fn zip<G: Copy, H>(&self, o: &Globals<G>, f: impl Fn(F, G) -> H) -> Globals<H> {
        let v = |a: Vec3<F>, b: Vec3<G>| Vec3 { x: f(a.x, b.x), y: f(a.y, b.y), z: f(a.z, b.z) };
        let c = |a: Color<F>, b: Color<G>| Color { r: f(a.r, b.r), g: f(a.g, b.g), b: f(a.b, b.b) };
        Globals {
            P: v(self.P, o.P),
            N: v(self.N, o.N),
            Ng: v(self.Ng, o.Ng),
            I: v(self.I, o.I),
            E: v(self.E, o.E),
            s: f(self.s, o.s),
            t: f(self.t, o.t),
            u: f(self.u, o.u),
            v: f(self.v, o.v),
            du: f(self.du, o.du),
            dv: f(self.dv, o.dv),
            dPdu: v(self.dPdu, o.dPdu),
            dPdv: v(self.dPdv, o.dPdv),
            Cs: c(self.Cs, o.Cs),
            Os: c(self.Os, o.Os),
        }
    }
}

impl<F: ShadingFloat> Globals<F> {
    /// A unit square in the z = 0 plane facing a camera at (0, 0, 1): the default point set of
    /// `testshade`-style evaluation. `s`, `t`, `u`, `v` are taken from `(u, v)`.
    #[inline]
    #[must_use]
    pub fn unit_square(u: F, v: F) -> Self {
        let zero = F::c(0.0);
        let one = F::c(1.0);
        let p = Vec3::new(u - F::c(0.5), v - F::c(0.5), zero);
        let e = Vec3::c(0.0, 0.0, 1.0);
        Self {
            P: p,
            N: Vec3::c(0.0, 0.0, 1.0),
            Ng: Vec3::c(0.0, 0.0, 1.0),
            I: p - e,
            E: e,
            s: u,
            t: v,
            u,
            v,
            du: F::c(0.0),
            dv: F::c(0.0),
            dPdu: Vec3::new(one, zero, zero),
            dPdv: Vec3::new(zero, one, zero),
            Cs: Color::c(1.0, 1.0, 1.0),
            Os: Color::c(1.0, 1.0, 1.0),
        }
    }
}

impl<F: ShadingFloat> Blend<F> for Globals<F> {
    #[inline(always)]
    fn blend(m: F::Mask, a: Self, b: Self) -> Self {
        Self {
            P: Blend::blend(m, a.P, b.P),
            N: Blend::blend(m, a.N, b.N),
            Ng: Blend::blend(m, a.Ng, b.Ng),
            I: Blend::blend(m, a.I, b.I),
            E: Blend::blend(m, a.E, b.E),
            s: F::select(m, a.s, b.s),
            t: F::select(m, a.t, b.t),
            u: F::select(m, a.u, b.u),
            v: F::select(m, a.v, b.v),
            du: F::select(m, a.du, b.du),
            dv: F::select(m, a.dv, b.dv),
            dPdu: Blend::blend(m, a.dPdu, b.dPdu),
            dPdv: Blend::blend(m, a.dPdv, b.dPdv),
            Cs: Blend::blend(m, a.Cs, b.Cs),
            Os: Blend::blend(m, a.Os, b.Os),
        }
    }
}

/// What a surface shader writes: RSL `Ci` and `Oi`.
#[allow(non_snake_case)]
#[derive(Clone, Copy, Debug)]
pub struct SurfaceOutput<F> {
    /// Outgoing colour (premultiplied by opacity, as RSL shaders write it).
    pub Ci: Color<F>,
    /// Opacity.
    pub Oi: Color<F>,
}

impl<F: ShadingFloat> Blend<F> for SurfaceOutput<F> {
    #[inline(always)]
    fn blend(m: F::Mask, a: Self, b: Self) -> Self {
        Self { Ci: Blend::blend(m, a.Ci, b.Ci), Oi: Blend::blend(m, a.Oi, b.Oi) }
    }
    #[inline(always)]
    fn widen(self) -> Self {
        Self { Ci: self.Ci.widen(), Oi: self.Oi.widen() }
    }
}
