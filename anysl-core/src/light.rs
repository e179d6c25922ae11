//! Lights: what a light shader computes ([`LightOutput`]), a light as plain numbers
//! ([`LightData`]), the light of either kind to the shared loops ([`LightSource`]), the
//! `illuminate`/`solar` geometry and cone tests, the query an `illuminance` statement makes
//! ([`LightQuery`]) and the light loops every context shares ([`run_illuminance`],
//! [`sum_ambient`]).

use crate::exec::Exec;
use crate::float::{Mask, ShadingFloat};
use crate::vec::{Color, Vec3};

/// How a light reaches a surface.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Emission {
    /// No direction: contributes to `ambient()` only.
    Ambient = 0,
    /// From a point (`illuminate`): shadow rays stop at the light.
    Local = 1,
    /// From a direction (`solar`): shadow rays go to infinity.
    Distant = 2,
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
/// `diffuse`, `specular`) itself instead of calling [`ShadingContext::illuminance`](crate::ShadingContext::illuminance) — the
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

/// A light shader's machine code, callable by compiled surface code in its own light loops
/// (the JIT's), so that a light that data cannot describe costs a call, not a trip through
/// the renderer's loop. `#[repr(C)]`: compiled code reads it in place.
///
/// `entry` is `extern "C" fn(ps, out, mask, ctx, host, params)`: `ps` the surface points
/// (three values of the float type, one packet's width apart), `out` where it writes `Cl`
/// then `L` (six values so), `mask` the live lanes (one `u32` per lane), and `ctx`, `host`,
/// `params` passed through as this record holds them. The code is that of the light's
/// [`LightShader::light`](crate::LightShader::light) for one float type: a light gives it
/// ([`LightShader::code`](crate::LightShader::code)) only for the float type it was compiled
/// for, and every pointer stays valid while the light lives unchanged.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightCode {
    /// The entry point (never null).
    pub entry: *const (),
    /// The context the code's callbacks receive (e.g. the light's named spaces).
    pub ctx: *const (),
    /// The code's callback table.
    pub host: *const usize,
    /// The light's parameter block.
    pub params: *const f32,
    /// How the light always emits (`Local` when it may vary).
    pub emission: Emission,
    /// For the code's producer only: what it needs to compile the light into a caller's
    /// code instead of calling `entry` (anysl-jit: the compiled variant the entry belongs
    /// to, recognized by `host`), or null. Others pass it on untouched.
    pub source: *const (),
}

// SAFETY: the pointers are to machine code and to data the light owns and does not change
// while it lives (what `LightCode` promises); sharing them between threads shares nothing
// mutable.
unsafe impl Send for LightCode {}
// SAFETY: as for `Send`.
unsafe impl Sync for LightCode {}

/// One light for compiled light loops ([`ShadingContext::light_records`](crate::ShadingContext::light_records)):
/// its code when it has some, else its data. `#[repr(C)]`: compiled code reads it in place.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct LightRecord {
    /// The light as data (read when `code.entry` is null).
    pub data: LightData,
    /// The light's code (`entry` null: the light is `data`).
    pub code: LightCode,
}

impl LightRecord {
    /// The record of `light` at float type `F`: its code, else its data; `None` when it has
    /// neither.
    #[must_use]
    pub fn of<F: ShadingFloat, L: LightSource>(light: &L) -> Option<Self> {
        let none = LightData { kind: LightKind::Ambient, falloff: Falloff::None, pos: [0.0; 3], cl: [0.0; 3] };
        if let Some(code) = light.source_code::<F>() {
            return Some(Self { data: none, code });
        }
        let data = light.source_data()?;
        let code = LightCode {
            entry: core::ptr::null(),
            ctx: core::ptr::null(),
            host: core::ptr::null(),
            params: core::ptr::null(),
            emission: Emission::Local,
            source: core::ptr::null(),
        };
        Some(Self { data, code })
    }

    /// `lights` as records at float type `F`, when each has code or data and at least one has
    /// code (lights that are all data are described as data).
    #[must_use]
    pub fn of_all<F: ShadingFloat, L: LightSource>(lights: &[L]) -> Option<Vec<Self>> {
        let records = lights.iter().map(Self::of::<F, L>).collect::<Option<Vec<_>>>()?;
        records.iter().any(|r| !r.code.entry.is_null()).then_some(records)
    }
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
/// [`LightShader`](crate::LightShader), and a light described as [`LightData`] — so a context can run its loops
/// over whichever it has. (The names differ from [`LightShader`](crate::LightShader)'s so that both traits can be
/// in scope.)
pub trait LightSource {
    /// [`LightShader::emission`](crate::LightShader::emission).
    fn source_emission(&self) -> Option<Emission>;
    /// [`LightShader::category`](crate::LightShader::category).
    fn source_category(&self) -> &str;
    /// [`LightShader::light`](crate::LightShader::light).
    fn evaluate<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F>;
    /// [`LightShader::data`](crate::LightShader::data): the light as data, when data can describe it.
    fn source_data(&self) -> Option<LightData>;
    /// [`LightShader::code`](crate::LightShader::code): the light's machine code for float type `F`, when it has some.
    #[inline(always)]
    fn source_code<F: ShadingFloat>(&self) -> Option<LightCode> {
        None
    }
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
        if !category.is_empty() && !category_matches(light.source_category(), category) {
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

/// Whether a light with categories `light` (comma-separated) takes part in
/// `illuminance(wanted, …)`: an empty `wanted` takes every light; otherwise `wanted` is a
/// comma-separated list of names, each either `name` (the light must have it) or `-name`
/// (the light must not); a light takes part when it has any of the wanted names (or no
/// positive names were given) and none of the excluded ones.
#[must_use]
pub fn category_matches(light: &str, wanted: &str) -> bool {
    let wanted = wanted.trim();
    if wanted.is_empty() {
        return true;
    }
    let has = |name: &str| light.split(',').any(|c| c.trim() == name);
    let mut any_positive = false;
    let mut positive_hit = false;
    for term in wanted.split(',').map(str::trim).filter(|t| !t.is_empty()) {
        if let Some(excluded) = term.strip_prefix('-') {
            if has(excluded.trim()) {
                return false;
            }
        } else {
            any_positive = true;
            positive_hit |= has(term);
        }
    }
    !any_positive || positive_hit
}
