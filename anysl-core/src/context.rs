//! The renderer's side of the contract: [`ShadingContext`] (globals, `illuminance`,
//! `ambient`, `trace`), its object-safe form [`ErasedContext`], and [`PointContext`], a
//! complete context for shading points that are not part of a scene (tests, benchmarks,
//! `testshade`-style evaluation).

use crate::exec::Exec;
use crate::float::ShadingFloat;
use crate::globals::Globals;
use crate::light::{run_illuminance, sum_ambient, Falloff, LightData, LightKind, LightQuery, LightRecord, LightSource};
use crate::spaces::Spaces;
use crate::vec::{Color, Vec3};

/// Most lights a [`PointContext`] describes as data (with more, it describes none).
pub const MAX_DATA_LIGHTS: usize = 8;

/// The lights of a [`PointContext`] as data, for the slice they were made from.
#[derive(Clone, Copy)]
struct LightTable {
    from: (usize, usize),
    len: usize,
    data: [LightData; MAX_DATA_LIGHTS],
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

    /// The lights as records ([`LightRecord`]: each light's machine code at `F`, or its
    /// data), when this context can describe them so and not as data: then
    /// `illuminance("", p, cone, body)` is [`run_illuminance`] with each light evaluated by
    /// its code (or data) and no shadowing, and `ambient()` is [`sum_ambient`] over them, as
    /// for [`ShadingContext::lights_as_data`]. `None` (the default): no such description.
    #[inline(always)]
    fn light_records(&self) -> Option<&[LightRecord]> {
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

    /// How many `trace` calls deep the ray that reached the shaded points is: 0 for camera
    /// rays (and their continuation through transparent surfaces), 1 for a ray `trace`d from a
    /// point a camera ray reached, … `None` (the default): the points were not reached along a
    /// ray of a rendered image (a material probe, a test point), so volume shaders, which act
    /// on ray segments, do not apply.
    #[inline(always)]
    fn ray_depth(&self) -> Option<u32> {
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
    /// [`ShadingContext::light_records`].
    fn light_records_dyn(&self) -> Option<&[LightRecord]>;
    /// [`ShadingContext::spaces`].
    fn spaces_dyn(&self) -> &Spaces;
    /// [`ShadingContext::ray_depth`].
    fn ray_depth_dyn(&self) -> Option<u32>;
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
    fn light_records_dyn(&self) -> Option<&[LightRecord]> {
        self.light_records()
    }
    fn spaces_dyn(&self) -> &Spaces {
        self.spaces()
    }
    fn ray_depth_dyn(&self) -> Option<u32> {
        self.ray_depth()
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
    fn light_records(&self) -> Option<&[LightRecord]> {
        self.0.light_records_dyn()
    }
    fn spaces(&self) -> &Spaces {
        self.0.spaces_dyn()
    }
    fn ray_depth(&self) -> Option<u32> {
        self.0.ray_depth_dyn()
    }
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
    /// `lights` as records, made on the first [`ShadingContext::light_records`] (for the
    /// slice it was made from, as `data`).
    records: core::cell::OnceCell<Option<RecordTable>>,
}

/// The lights of a [`PointContext`] as records, for the slice they were made from.
struct RecordTable {
    from: (usize, usize),
    records: Vec<LightRecord>,
}

/// `lights` as records at float type `F` ([`LightRecord::of_all`]).
#[cold]
fn record_table<F: ShadingFloat, L: LightSource>(lights: &[L]) -> Option<RecordTable> {
    let from = (lights.as_ptr() as usize, lights.len());
    LightRecord::of_all::<F, L>(lights).map(|records| RecordTable { from, records })
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
            records: core::cell::OnceCell::new(),
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

    /// Lights without shadows: as records when each has code or data, not all of them data.
    #[inline]
    fn light_records(&self) -> Option<&[LightRecord]> {
        if L::as_data(self.lights).is_some() {
            return None;
        }
        let t = self.records.get_or_init(|| record_table::<F, L>(self.lights)).as_ref()?;
        (t.from == (self.lights.as_ptr() as usize, self.lights.len())).then_some(&t.records[..])
    }

    #[inline(always)]
    fn spaces(&self) -> &Spaces {
        self.spaces
    }
}
