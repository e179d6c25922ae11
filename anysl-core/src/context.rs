//! The renderer's side of the contract: [`ShadingContext`] (globals, `illuminance`,
//! `ambient`, `trace`), the outputs of surface and light shaders, and [`PointContext`], a
//! complete context for shading points that are not part of a scene (tests, benchmarks,
//! `testshade`-style evaluation).

use crate::exec::Exec;
use crate::float::{Blend, Mask, ShadingFloat};
use crate::shader::LightShader;
use crate::spaces::Spaces;
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

/// How a light reaches a surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Emission {
    /// No direction: contributes to `ambient()` only.
    Ambient,
    /// From a point (`illuminate`): shadow rays stop at the light.
    Local,
    /// From a direction (`solar`): shadow rays go to infinity.
    Distant,
}

/// What a light shader computes for a set of surface points.
#[derive(Clone, Copy, Debug)]
pub struct LightOutput<F: ShadingFloat> {
    /// Light colour arriving at the point (RSL `Cl`).
    pub cl: Color<F>,
    /// RSL `L` inside the light shader: from the light towards the surface point (for
    /// distant lights, the direction the light travels).
    pub l: Vec3<F>,
    /// Lanes the light illuminates (inside its cone).
    pub lit: F::Mask,
    /// How the light arrives.
    pub emission: Emission,
}

/// Which light shader a [`LightData`] stands for.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightKind {
    /// `ambientlight`: `Cl = cl`, seen by `ambient()` only.
    Ambient = 0,
    /// `pointlight`: `L = ps - pos`, `Cl = cl` with the distance falloff of [`Falloff`].
    Point = 1,
    /// `distantlight`: `L = pos` (the direction the light travels), `Cl = cl`.
    Distant = 2,
}

/// The distance falloff of a point light described as data.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Falloff {
    /// `Cl = cl`.
    None = 0,
    /// `Cl = cl / (L·L)`.
    InverseSquare = 1,
}

/// A light as plain numbers, for code that runs the built-in light loops (`ambient`,
/// `diffuse`, `specular`) itself instead of calling [`ShadingContext::illuminance`] — the
/// JIT compiles them into the shader. `#[repr(C)]`: compiled code reads it in place. The
/// numbers are what the light shader computes before its first lane-wise operation, rounded
/// to `f32` as the `f32`-based float types round them, so for those types
/// [`LightData::light`] is the shader's `light` bit for bit.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightData {
    /// The light shader.
    pub kind: LightKind,
    /// Point lights: how `Cl` falls off with distance.
    pub falloff: Falloff,
    /// Point lights: the position; distant lights: the direction of travel.
    pub pos: [f32; 3],
    /// The colour times the intensity.
    pub cl: [f32; 3],
}

impl LightData {
    /// What the light shader computes for the points `ps`.
    #[inline(always)]
    #[must_use]
    pub fn light<F: ShadingFloat>(&self, ps: Vec3<F>) -> LightOutput<F> {
        let v = |a: [f32; 3]| Vec3::new(F::c(f64::from(a[0])), F::c(f64::from(a[1])), F::c(f64::from(a[2])));
        let c = v(self.cl).to_color();
        match self.kind {
            LightKind::Ambient => {
                LightOutput { cl: c, l: Vec3::zero(), lit: F::Mask::splat(true), emission: Emission::Ambient }
            }
            LightKind::Distant => {
                let (l, lit) = solar(v(self.pos));
                LightOutput { cl: c, l, lit, emission: Emission::Distant }
            }
            LightKind::Point => {
                let (l, lit) = illuminate(ps, v(self.pos), None);
                let cl = match self.falloff {
                    Falloff::None => c,
                    Falloff::InverseSquare => c / l.dot(l),
                };
                LightOutput { cl, l, lit, emission: Emission::Local }
            }
        }
    }
}

/// What the shared light loops ([`run_illuminance`], [`sum_ambient`]) need of a light: every
/// [`LightShader`], and a light described as [`LightData`] — so a context can run its loops
/// over whichever it has. (The names differ from [`LightShader`]'s so that both traits can be
/// in scope.)
pub trait LightSource {
    /// [`LightShader::emission`].
    fn source_emission(&self) -> Option<Emission>;
    /// [`LightShader::category`].
    fn source_category(&self) -> &str;
    /// [`LightShader::light`].
    fn evaluate<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F>;
    /// [`LightShader::data`]: the light as data, when data can describe it.
    fn source_data(&self) -> Option<LightData>;
    /// `lights` as data without a copy, when they already are data.
    #[inline(always)]
    fn as_data(lights: &[Self]) -> Option<&[LightData]>
    where
        Self: Sized,
    {
        let _ = lights;
        None
    }
}

impl<T: LightShader> LightSource for T {
    #[inline(always)]
    fn source_emission(&self) -> Option<Emission> {
        self.emission()
    }
    #[inline(always)]
    fn source_category(&self) -> &str {
        self.category()
    }
    #[inline(always)]
    fn evaluate<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        self.light(e, ps)
    }
    #[inline(always)]
    fn source_data(&self) -> Option<LightData> {
        self.data()
    }
}

impl LightSource for LightData {
    #[inline(always)]
    fn source_emission(&self) -> Option<Emission> {
        Some(match self.kind {
            LightKind::Ambient => Emission::Ambient,
            LightKind::Point => Emission::Local,
            LightKind::Distant => Emission::Distant,
        })
    }
    #[inline(always)]
    fn source_category(&self) -> &str {
        ""
    }
    #[inline(always)]
    fn evaluate<F: ShadingFloat>(&self, _e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        self.light(ps)
    }
    #[inline(always)]
    fn source_data(&self) -> Option<LightData> {
        Some(*self)
    }
    #[inline(always)]
    fn as_data(lights: &[Self]) -> Option<&[LightData]> {
        Some(lights)
    }
}

impl LightData {
    /// Whether [`LightData::light`] is the light shader's `light` bit for bit at float type
    /// `F`: the types whose arithmetic is `f32`'s (scalar, SIMD, dual numbers over them), not
    /// `f64` (which would see the light's numbers rounded to `f32`) nor intervals (which round
    /// outward).
    #[inline(always)]
    #[must_use]
    pub fn exact_for<F: ShadingFloat>() -> bool {
        F::UNIT_ROUNDOFF == f64::from(f32::EPSILON) / 2.0 && !<F::Mask as Mask>::THREE_VALUED
    }

    /// Every light of `lights` as data, when each has a description. Data carries no
    /// category: a loop that selects on one (`illuminance("category", …)`) runs over the light
    /// shaders.
    #[must_use]
    pub fn of_all<L: LightSource>(lights: &[L]) -> Option<Vec<LightData>> {
        lights.iter().map(LightSource::source_data).collect()
    }
}

/// Most lights a [`PointContext`] describes as data (with more, it describes none).
pub const MAX_DATA_LIGHTS: usize = 8;

/// The lights of a [`PointContext`] as data, for the slice they were made from.
#[derive(Clone, Copy)]
struct LightTable {
    from: (usize, usize),
    len: usize,
    data: [LightData; MAX_DATA_LIGHTS],
}

/// RSL `illuminate(from [, axis, angle])`: `L = ps - from`, and the lanes inside the cone
/// of half-angle `angle` around `axis`.
#[inline(always)]
pub fn illuminate<F: ShadingFloat>(ps: Vec3<F>, from: Vec3<F>, cone: Option<(Vec3<F>, F)>) -> (Vec3<F>, F::Mask) {
    let l = ps - from;
    let lit = match cone {
        None => F::Mask::splat(true),
        Some((axis, angle)) => in_cone(l, axis, angle),
    };
    (l, lit)
}

/// RSL `solar([axis, angle])`: light travelling along `axis`; lanes always lit.
#[inline(always)]
pub fn solar<F: ShadingFloat>(axis: Vec3<F>) -> (Vec3<F>, F::Mask) {
    (axis, F::Mask::splat(true))
}

/// Lanes where the angle between `dir` and `axis` is at most `angle` (an angle ≥ π admits
/// everything, including zero-length `dir`).
#[inline(always)]
pub fn in_cone<F: ShadingFloat>(dir: Vec3<F>, axis: Vec3<F>, angle: F) -> F::Mask {
    ConeTest::new(axis, angle).contains(dir)
}

/// A cone test prepared once (the cosine of the half-angle) and applied to many directions
/// without a square root: `dir·axis ≥ cos(angle)·|dir|·|axis|` is decided on squares.
#[derive(Clone, Copy, Debug)]
pub struct ConeTest<F: ShadingFloat> {
    axis: Vec3<F>,
    /// `cos²(angle)·|axis|²`.
    c2a2: F,
    /// `cos(angle) >= 0` (a cone no wider than a hemisphere).
    narrow: F::Mask,
    /// `angle >= π`: everything.
    all: F::Mask,
}

impl<F: ShadingFloat> ConeTest<F> {
    /// The cone of half-angle `angle` around `axis`.
    #[inline(always)]
    #[must_use]
    pub fn new(axis: Vec3<F>, angle: F) -> Self {
        let pi = F::c(core::f64::consts::PI);
        let c = angle.min(pi).cos();
        Self { axis, c2a2: c * c * axis.length_squared(), narrow: c.ge(F::c(0.0)), all: angle.ge(pi) }
    }
    /// Lanes whose `dir` lies inside the cone.
    #[inline(always)]
    #[must_use]
    pub fn contains(&self, dir: Vec3<F>) -> F::Mask {
        let d = dir.dot(self.axis);
        let front = d.ge(F::c(0.0));
        let dd = d * d;
        let rhs = self.c2a2 * dir.length_squared();
        // c ≥ 0: front and d² ≥ c²|dir|²|axis|²; c < 0: front or d² ≤ c²|dir|²|axis|². Written
        // so a surely-front, surely-outside-the-band direction is surely inside for intervals.
        let inside = (front & (dd.ge(rhs) | !self.narrow)) | (!self.narrow & dd.le(rhs));
        inside | self.all
    }
}

/// What an `illuminance` statement asks of the renderer: the lights of `category` as seen from
/// `p`, only within `cone` (axis, half-angle) when it is given.
#[derive(Clone, Copy, Debug)]
pub struct LightQuery<'a, F> {
    /// The light category: `""` for every light, else as RSL's `illuminance("name", …)`.
    pub category: &'a str,
    /// The point the lights are seen from.
    pub p: Vec3<F>,
    /// `(axis, angle)`: only lights within `angle` of `axis`; `None` for every direction.
    pub cone: Option<(Vec3<F>, F)>,
}

impl<'a, F: ShadingFloat> LightQuery<'a, F> {
    /// The query of `illuminance(category, p[, axis, angle])`.
    #[inline(always)]
    #[must_use]
    pub fn new(category: &'a str, p: Vec3<F>, cone: Option<(Vec3<F>, F)>) -> Self {
        Self { category, p, cone }
    }

    /// Every light in the hemisphere of `n` seen from `p`: what `diffuse(N)` and `specular`
    /// ask (`illuminance(p, n, PI/2)`).
    #[inline(always)]
    #[must_use]
    pub fn hemisphere(p: Vec3<F>, n: Vec3<F>) -> Self {
        Self { category: "", p, cone: Some((n, F::c(core::f64::consts::FRAC_PI_2))) }
    }
}

/// The renderer's side of shading: globals and the constructs that need the scene.
pub trait ShadingContext<F: ShadingFloat> {
    /// The RSL globals of the points being shaded.
    fn globals(&self) -> &Globals<F>;

    /// RSL `illuminance([category,] p [, axis, angle]) { body }`: runs `body(e, L, Cl)` once per
    /// non-ambient light of `q.category` with the mask narrowed to the lanes the light reaches
    /// from `q.p` (inside `q.cone`, not in shadow). `L` points from `q.p` to the light,
    /// unnormalized.
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        e: &mut Exec<F>,
        q: LightQuery<'_, F>,
        body: B,
    );

    /// RSL `ambient()`: the sum of the ambient lights.
    fn ambient(&mut self, e: &Exec<F>) -> Color<F>;

    /// RSL `trace(p, dir)`: the colour seen along a ray, for the live lanes.
    fn trace(&mut self, e: &Exec<F>, p: Vec3<F>, dir: Vec3<F>) -> Color<F>;

    /// The lights as data, when this context can describe them so: then
    /// `illuminance("", p, cone, body)` is [`run_illuminance`] with each light evaluated by
    /// [`LightData::light`] and no shadowing, and `ambient()` is [`sum_ambient`] over them — so code that
    /// runs those loops itself (the JIT) computes what the context would. `None` (the
    /// default): the context's own light loops must be called.
    #[inline(always)]
    fn lights_as_data(&self) -> Option<&[LightData]> {
        None
    }

    /// The named coordinate systems of the points being shaded (uniform over them): looked up
    /// only by shaders that name a space. The default, [`Spaces::standard`], makes every
    /// standard space the shading space.
    #[inline(always)]
    fn spaces(&self) -> &Spaces {
        Spaces::standard()
    }

    /// The globals, writable, when the context lets a shading loop outside the renderer set
    /// them packet by packet (a JIT-compiled loop over a point set, which then finds the
    /// values the context's own methods read where they look). `None` (the default): the
    /// context sets them itself.
    #[inline(always)]
    fn globals_mut(&mut self) -> Option<&mut Globals<F>> {
        None
    }
}

/// [`ShadingContext`] without generic methods, so that it can be a trait object: code that
/// calls the context rarely (an interpreter, once per op and chunk) takes [`Erased`] and is
/// compiled once per float type instead of once per float type and context. Every
/// `ShadingContext` is one.
pub trait ErasedContext<F: ShadingFloat> {
    /// [`ShadingContext::globals`].
    fn globals_dyn(&self) -> &Globals<F>;
    /// [`ShadingContext::illuminance`] with the body behind a reference.
    fn illuminance_dyn(
        &mut self,
        e: &mut Exec<F>,
        q: LightQuery<'_, F>,
        body: &mut dyn FnMut(&mut Exec<F>, Vec3<F>, Color<F>),
    );
    /// [`ShadingContext::ambient`].
    fn ambient_dyn(&mut self, e: &Exec<F>) -> Color<F>;
    /// [`ShadingContext::trace`].
    fn trace_dyn(&mut self, e: &Exec<F>, p: Vec3<F>, dir: Vec3<F>) -> Color<F>;
    /// [`ShadingContext::lights_as_data`].
    fn lights_as_data_dyn(&self) -> Option<&[LightData]>;
    /// [`ShadingContext::spaces`].
    fn spaces_dyn(&self) -> &Spaces;
}

impl<F: ShadingFloat, C: ShadingContext<F>> ErasedContext<F> for C {
    fn globals_dyn(&self) -> &Globals<F> {
        self.globals()
    }
    fn illuminance_dyn(
        &mut self,
        e: &mut Exec<F>,
        q: LightQuery<'_, F>,
        body: &mut dyn FnMut(&mut Exec<F>, Vec3<F>, Color<F>),
    ) {
        self.illuminance(e, q, body);
    }
    fn ambient_dyn(&mut self, e: &Exec<F>) -> Color<F> {
        self.ambient(e)
    }
    fn trace_dyn(&mut self, e: &Exec<F>, p: Vec3<F>, dir: Vec3<F>) -> Color<F> {
        self.trace(e, p, dir)
    }
    fn lights_as_data_dyn(&self) -> Option<&[LightData]> {
        self.lights_as_data()
    }
    fn spaces_dyn(&self) -> &Spaces {
        self.spaces()
    }
}

/// Any [`ShadingContext`] behind one type: a `ShadingContext` that forwards to an
/// [`ErasedContext`] object.
pub struct Erased<'a, F: ShadingFloat>(pub &'a mut dyn ErasedContext<F>);

impl<F: ShadingFloat> ShadingContext<F> for Erased<'_, F> {
    fn globals(&self) -> &Globals<F> {
        self.0.globals_dyn()
    }
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        e: &mut Exec<F>,
        q: LightQuery<'_, F>,
        mut body: B,
    ) {
        self.0.illuminance_dyn(e, q, &mut body);
    }
    fn ambient(&mut self, e: &Exec<F>) -> Color<F> {
        self.0.ambient_dyn(e)
    }
    fn trace(&mut self, e: &Exec<F>, p: Vec3<F>, dir: Vec3<F>) -> Color<F> {
        self.0.trace_dyn(e, p, dir)
    }
    fn lights_as_data(&self) -> Option<&[LightData]> {
        self.0.lights_as_data_dyn()
    }
    fn spaces(&self) -> &Spaces {
        self.0.spaces_dyn()
    }
}

/// The light loop every context shares: evaluates each light shader at `p`, keeps the lanes
/// inside the illuminance cone, asks `visibility` for shadowing (`None` = unshadowed) and runs
/// `body` with `L` reversed to point from the surface to the light.
#[inline(always)]
pub fn run_illuminance<F, L, V, B>(lights: &[L], e: &mut Exec<F>, q: LightQuery<'_, F>, mut visibility: V, mut body: B)
where
    F: ShadingFloat,
    L: LightSource,
    V: FnMut(F::Mask, Vec3<F>, &LightOutput<F>) -> Option<Color<F>>,
    B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>),
{
    let LightQuery { category, p, cone } = q;
    let cone = cone.map(|(axis, angle)| ConeTest::new(axis, angle));
    for light in lights {
        if light.source_emission() == Some(Emission::Ambient) {
            continue;
        }
        if !category.is_empty() && !crate::shader::category_matches(light.source_category(), category) {
            continue;
        }
        let out = light.evaluate(e, p);
        if out.emission == Emission::Ambient {
            continue;
        }
        let to_light = -out.l;
        let mut mask = e.mask() & out.lit;
        if let Some(c) = &cone {
            mask = mask & c.contains(to_light);
        }
        if mask.none() {
            continue;
        }
        let cl = match visibility(mask, p, &out) {
            Some(v) => out.cl * v,
            None => out.cl,
        };
        if mask.all() {
            // Every lane is live (the common case): the body runs under a mask the compiler
            // sees to be full, so its masked writes are plain writes (no blends), as in a
            // hand-written kernel. It is inlined twice, once per case.
            e.masked_full(
                #[inline(always)]
                |e| body(e, to_light, cl),
            );
        } else {
            e.masked(
                mask,
                #[inline(always)]
                |e| body(e, to_light, cl),
            );
        }
    }
}

/// The sum of the ambient lights' `Cl` at `p`.
#[inline(always)]
pub fn sum_ambient<F: ShadingFloat, L: LightSource>(lights: &[L], e: &Exec<F>, p: Vec3<F>) -> Color<F> {
    let mut sum = Color::zero();
    for light in lights {
        if matches!(light.source_emission(), Some(Emission::Local | Emission::Distant)) {
            continue;
        }
        let mut le = *e;
        let out = light.evaluate(&mut le, p);
        if out.emission == Emission::Ambient {
            sum += Color::select(out.lit, out.cl, Color::zero());
        }
    }
    sum
}

/// A complete [`ShadingContext`] for points outside a scene: lights without shadows and a
/// constant environment colour seen by `trace`. Used by tests, kernel benchmarks and
/// `rslc eval`.
///
/// The lights are light shaders or lights already described as [`LightData`]. Code that
/// shades many packets under the same lights with an `f32`-based float type gives the data
/// (made once, [`LightData::of_all`]): the light loops then read a few numbers per light
/// instead of running the shaders, with the same bits ([`LightData::exact_for`]), and compiled
/// code finds them in place.
pub struct PointContext<'a, F: ShadingFloat, L> {
    /// The points being shaded.
    pub globals: Globals<F>,
    /// The lights.
    pub lights: &'a [L],
    /// What `trace` returns: a vertical gradient from `horizon` (dir.y = 0) to `zenith`.
    pub horizon: Color<F>,
    /// See `horizon`.
    pub zenith: Color<F>,
    /// The named coordinate systems (default: [`Spaces::standard`]).
    pub spaces: &'a Spaces,
    /// `lights` as data, made on the first [`ShadingContext::lights_as_data`] (and for the
    /// slice it was made from: after `lights` is replaced, the context describes none).
    data: core::cell::OnceCell<Option<LightTable>>,
}

impl<'a, F: ShadingFloat, L: LightSource> PointContext<'a, F, L> {
    /// A context with the default sky (horizon 0.6, zenith (0.2, 0.3, 0.8)).
    #[inline(always)]
    #[must_use]
    pub fn new(globals: Globals<F>, lights: &'a [L]) -> Self {
        Self {
            globals,
            lights,
            horizon: Color::c(0.6, 0.6, 0.6),
            zenith: Color::c(0.2, 0.3, 0.8),
            spaces: Spaces::standard(),
            data: core::cell::OnceCell::new(),
        }
    }
}

/// `lights` as data, when every one of them (at most [`MAX_DATA_LIGHTS`]) has a description.
#[cold]
fn light_table<L: LightSource>(lights: &[L]) -> Option<LightTable> {
    if lights.len() > MAX_DATA_LIGHTS {
        return None;
    }
    let none = LightData { kind: LightKind::Ambient, falloff: Falloff::None, pos: [0.0; 3], cl: [0.0; 3] };
    let mut t =
        LightTable { from: (lights.as_ptr() as usize, lights.len()), len: lights.len(), data: [none; MAX_DATA_LIGHTS] };
    for (d, l) in t.data.iter_mut().zip(lights) {
        *d = l.source_data()?;
    }
    Some(t)
}

impl<F: ShadingFloat, L: LightSource> ShadingContext<F> for PointContext<'_, F, L> {
    #[inline(always)]
    fn globals(&self) -> &Globals<F> {
        &self.globals
    }

    #[inline(always)]
    fn globals_mut(&mut self) -> Option<&mut Globals<F>> {
        Some(&mut self.globals)
    }

    #[inline(always)]
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        e: &mut Exec<F>,
        q: LightQuery<'_, F>,
        body: B,
    ) {
        run_illuminance(self.lights, e, q, |_, _, _| None, body);
    }

    #[inline(always)]
    fn ambient(&mut self, e: &Exec<F>) -> Color<F> {
        sum_ambient(self.lights, e, self.globals.P)
    }

    #[inline(always)]
    fn trace(&mut self, _e: &Exec<F>, _p: Vec3<F>, dir: Vec3<F>) -> Color<F> {
        let d = dir.normalize();
        let t = d.y.abs().min(F::c(1.0));
        self.horizon + (self.zenith - self.horizon) * t
    }

    /// Lights without shadows: described as data when each of them is.
    #[inline]
    fn lights_as_data(&self) -> Option<&[LightData]> {
        if let Some(data) = L::as_data(self.lights) {
            return Some(data);
        }
        let t = self.data.get_or_init(|| light_table(self.lights)).as_ref()?;
        (t.from == (self.lights.as_ptr() as usize, self.lights.len())).then(|| &t.data[..t.len])
    }

    #[inline(always)]
    fn spaces(&self) -> &Spaces {
        self.spaces
    }
}
