//! The renderer side of the shading contract, shared by every renderer: [`SceneContext`]
//! implements [`ShadingContext`] over a scene (shadow rays for `illuminance`, secondary rays
//! for `trace`), [`shade_lanes`] gathers hits into the structure-of-arrays [`Globals`] of any
//! [`ShadingFloat`] and runs each surface shader present once, masked, and
//! [`ProbeContext`] evaluates a shader *passively* for the path tracer.
//!
//! Lanes are addressed by bit masks (`u32`, bit `i` = lane `i`), so a packet of up to
//! [`MAX_LANES`] rays needs no allocation anywhere on this path.

use crate::accel::{Hit, RayPacket, MAX_PACKET};
use crate::scene::{Scene, SurfaceHit};
use anysl_ad::Dual;
use anysl_core::{
    in_cone, run_illuminance, sum_ambient, Color, Emission, Exec, GlobalSet, Globals, LightData, LightOutput,
    LightQuery, LightRecord, LightShader, Mask, ShadingContext, ShadingFloat, Spaces, SurfaceOutput, SurfaceShader,
    SurfaceVisitor, Vec3,
};
use glam::Vec3A;

/// The widest packet (and the widest `ShadingFloat`) the renderers handle.
pub const MAX_LANES: usize = 16;
const _: () = assert!(MAX_LANES <= MAX_PACKET, "a packet of shading lanes must fit a ray packet");
/// How many `trace` calls may nest; deeper ones return the sky.
pub const MAX_TRACE_DEPTH: u32 = 4;
/// How many partly transparent surfaces a ray may pass through.
pub const MAX_LAYERS: u32 = 16;

/// Offset of secondary and shadow rays from the surface they leave, relative to the
/// magnitude of the coordinates.
#[inline(always)]
#[must_use]
pub fn ray_epsilon(p: Vec3A) -> f32 {
    1e-4 * (1.0 + p.abs().max_element())
}

/// A scene as seen by shading: the scene plus the switches that change lighting.
pub struct Tracer<'a, S, L> {
    /// The scene.
    pub scene: &'a Scene<S, L>,
    /// Cast shadow rays in `illuminance` (else every light reaches every point).
    pub shadows: bool,
    /// The lights of each surface slot as data, where each has a description.
    pub light_data: &'a LightTables,
}

/// The lights each surface slot sees ([`Scene::lights_for`]) as data ([`LightData::of_all`]),
/// where each light has a description: the light loops then run over plain numbers instead of
/// dispatching to light shaders (for the float types where that is the same bits,
/// [`LightData::exact_for`]). Made once per render.
#[derive(Clone, Debug, Default)]
pub struct LightTables {
    per_surface: Vec<Option<Vec<LightData>>>,
    /// Per surface slot, its lights as records at float type `records_of` where they are not
    /// all data ([`LightRecord::of_all`]: some have code, such as `.sl` lights the JIT compiled).
    records: Vec<Option<Vec<LightRecord>>>,
    records_of: Option<core::any::TypeId>,
}

impl LightTables {
    /// The tables of `scene`'s surface slots, with light records for float type `F` (the
    /// type the renderer shades with).
    #[must_use]
    pub fn of<F: ShadingFloat, S, L: LightShader>(scene: &Scene<S, L>) -> Self {
        let lights_of = |s: u32| match scene.surface_lights.get(s as usize) {
            Some(Some(lights)) => &lights[..],
            _ => &scene.lights[..],
        };
        let all = LightData::of_all(&scene.lights);
        let per_surface: Vec<Option<Vec<LightData>>> = (0..scene.surfaces.len() as u32)
            .map(|s| match scene.surface_lights.get(s as usize) {
                Some(Some(lights)) => LightData::of_all(lights),
                _ => all.clone(),
            })
            .collect();
        let records = (0..scene.surfaces.len() as u32)
            .map(|s| if per_surface[s as usize].is_some() { None } else { LightRecord::of_all::<F, L>(lights_of(s)) })
            .collect();
        Self { per_surface, records, records_of: Some(core::any::TypeId::of::<F>()) }
    }

    /// Surface slot `surface`'s lights as records at float type `F`, if the tables have them.
    #[inline(always)]
    #[must_use]
    pub fn records_for<F: ShadingFloat>(&self, surface: u32) -> Option<&[LightRecord]> {
        if Some(core::any::TypeId::of::<F>()) != self.records_of {
            return None;
        }
        self.records.get(surface as usize).and_then(Option::as_deref)
    }

    /// Surface slot `surface`'s lights as data, if each has a description.
    #[inline(always)]
    #[must_use]
    pub fn for_surface(&self, surface: u32) -> Option<&[LightData]> {
        self.per_surface.get(surface as usize).and_then(Option::as_deref)
    }
}

impl<'a, S, L: LightShader> Tracer<'a, S, L> {
    /// The tracer of `scene`, with `light_data` made by [`LightTables::of`] (kept by the
    /// caller for the render).
    #[must_use]
    pub fn new(scene: &'a Scene<S, L>, shadows: bool, light_data: &'a LightTables) -> Self {
        Self { scene, shadows, light_data }
    }

    /// Surface slot `surface`'s lights as data, where float type `F` computes with them what
    /// the light shaders compute.
    #[inline(always)]
    fn data_for<F: ShadingFloat>(&self, surface: u32) -> Option<&'a [LightData]> {
        if LightData::exact_for::<F>() {
            self.light_data.for_surface(surface)
        } else {
            None
        }
    }
}

impl<S, L> Clone for Tracer<'_, S, L> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S, L> Copy for Tracer<'_, S, L> {}

/// Recursion state of a shading point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Depth {
    /// Nesting of `trace` calls.
    pub trace: u32,
    /// Transparent surfaces passed so far.
    pub layer: u32,
}

/// Up to [`MAX_LANES`] rays and what they hit, as slices starting at lane 0.
#[derive(Clone, Copy, Debug)]
pub struct Lanes<'p> {
    /// Hit records (meaningful where `hit` has the bit; any finite values elsewhere).
    pub hits: &'p [SurfaceHit],
    /// Ray directions (for the sky of lanes that missed).
    pub dirs: &'p [Vec3A],
    /// Lanes in use.
    pub active: u32,
    /// Lanes that hit a surface.
    pub hit: u32,
    /// Camera rays: misses are black unless the sky is visible to the camera.
    pub camera: bool,
}

/// The [`ShadingContext`] of points on a scene's surfaces.
pub struct SceneContext<'a, F: ShadingFloat, S, L> {
    /// The points being shaded.
    pub globals: Globals<F>,
    tracer: Tracer<'a, S, L>,
    depth: Depth,
    /// The surface shader being run (its named spaces are looked up when a shader asks).
    surface: u32,
}

/// The lane mask of `bits`.
#[inline(always)]
#[must_use]
pub fn lane_mask<F: ShadingFloat>(bits: u32) -> F::Mask {
    F::Mask::from_bits(bits)
}

/// The bits of the lanes of `m` that are (possibly) set.
#[inline(always)]
#[must_use]
pub fn mask_bits<F: ShadingFloat>(m: F::Mask) -> u32 {
    m.to_bits()
}

/// Lane `i` of a vector as a glam vector.
#[inline(always)]
fn vec_lane<F: ShadingFloat>(v: &Vec3<F>, i: usize) -> Vec3A {
    Vec3A::new(v.x.lane(i) as f32, v.y.lane(i) as f32, v.z.lane(i) as f32)
}

/// The globals of the hits in `group` (structure of arrays), seeded with screen-space
/// derivatives when `F` carries them. Lanes outside `group` read the hit of lane `first`,
/// so that masked lanes hold finite values.
#[inline(always)]
#[must_use]
pub fn gather_globals<F: ShadingFloat>(hits: &[SurfaceHit], group: u32, first: usize) -> Globals<F> {
    gather_globals_read(hits, group, first, GlobalSet::ALL)
}

/// Floats in a hit record ([`SurfaceHit`] is `repr(C)` and made of 4-byte fields).
const HIT_FLOATS: usize = core::mem::size_of::<SurfaceHit>() / 4;
/// The record read as 8-float chunks (the last one ends in padding, see [`transpose_hits`]).
const HIT_CHUNKS: usize = HIT_FLOATS / 8;
const _: () = assert!(HIT_FLOATS == 8 * HIT_CHUNKS && core::mem::align_of::<SurfaceHit>() == 16);

/// Float offset of a field of [`SurfaceHit`].
macro_rules! at {
    ($field:ident) => {
        core::mem::offset_of!(SurfaceHit, $field) / 4
    };
}
/// Floats of the last chunk that are fields (the rest is the record's tail padding).
const LAST_CHUNK_FIELDS: usize = at!(surface) + 1 - 8 * (HIT_CHUNKS - 1);

/// Lane-major records to component-major rows: `out[f][lane]` = float `f` of `rows[lane]`,
/// for the floats of the 8-float chunks in `chunks` (bit `k` = floats `8k .. 8k + 8`), with
/// 8×8 (and 4×4) register transposes — where writing each float of each lane on its own,
/// then loading a row as a vector, costs as much as a simple shader (and a load that follows
/// narrower stores cannot take its value from them).
///
/// # Safety
/// `out` points at `HIT_FLOATS` writable rows of `MAX_LANES` floats, `rows.len() <= MAX_LANES`.
#[inline(always)]
unsafe fn transpose_hits(rows: &[&SurfaceHit], chunks: u32, out: *mut [f32; MAX_LANES]) {
    use wide::{f32x4, f32x8};
    let n = rows.len();
    // SAFETY (every write below): `f < HIT_FLOATS`, lanes `< n <= MAX_LANES`.
    let put = |f: usize, l: usize, v: &[f32]| unsafe {
        core::ptr::copy_nonoverlapping(v.as_ptr(), out.add(f).cast::<f32>().add(l), v.len());
    };
    let base = |l: usize| (rows[l] as *const SurfaceHit).cast::<f32>();
    for k in 0..HIT_CHUNKS {
        if (chunks >> k) & 1 == 0 {
            continue;
        }
        if k == HIT_CHUNKS - 1 {
            // The last chunk ends in padding, which must not be read: float by float.
            for f in 8 * k..8 * k + LAST_CHUNK_FIELDS {
                for (l, row) in rows.iter().enumerate() {
                    // SAFETY: `f` is a field's float of a `repr(C)` record of 4-byte fields.
                    put(f, l, &[unsafe { *(*row as *const SurfaceHit).cast::<f32>().add(f) }]);
                }
            }
            continue;
        }
        if n.is_multiple_of(8) {
            for half in 0..n / 8 {
                // SAFETY: chunk `k < HIT_CHUNKS - 1` lies inside the record, all of it fields.
                let m: [f32x8; 8] = core::array::from_fn(|j| {
                    f32x8::from(unsafe { base(8 * half + j).add(8 * k).cast::<[f32; 8]>().read_unaligned() })
                });
                for (j, col) in f32x8::transpose(m).iter().enumerate() {
                    put(8 * k + j, 8 * half, &col.to_array());
                }
            }
        } else if n == 4 {
            for q in 0..2 {
                // SAFETY: as above.
                let m: [f32x4; 4] = core::array::from_fn(|j| {
                    f32x4::from(unsafe { base(j).add(8 * k + 4 * q).cast::<[f32; 4]>().read_unaligned() })
                });
                for (j, col) in f32x4::transpose(m).iter().enumerate() {
                    put(8 * k + 4 * q + j, 0, &col.to_array());
                }
            }
        } else {
            for f in 8 * k..8 * k + 8 {
                for l in 0..n {
                    // SAFETY: as above.
                    put(f, l, &[unsafe { *base(l).add(f) }]);
                }
            }
        }
    }
}

/// [`gather_globals`] of only the globals in `read` (see
/// [`SurfaceShader::globals_read`]); the others are zero.
///
/// The hit records are transposed chunk by chunk ([`transpose_hits`]) into a scratch block,
/// only the chunks holding what `read` (and the derivatives of a dual `F`) needs; each
/// component is then loaded as one vector.
#[inline(always)]
#[must_use]
pub fn gather_globals_read<F: ShadingFloat>(
    hits: &[SurfaceHit],
    group: u32,
    first: usize,
    read: GlobalSet,
) -> Globals<F> {
    debug_assert!(F::LANES <= MAX_LANES && hits.len() >= F::LANES);
    let derivs = F::HAS_DERIVS;
    let has = |x: GlobalSet| read.contains(x);
    let chunk = |f: usize| 1u32 << (f / 8);
    let mut chunks = 0;
    for (bit, f) in [
        (GlobalSet::P, at!(p)),
        (GlobalSet::N, at!(n)),
        (GlobalSet::NG, at!(ng)),
        (GlobalSet::I, at!(i)),
        (GlobalSet::E, at!(e)),
        (GlobalSet::S, at!(s)),
        (GlobalSet::T, at!(t)),
        (GlobalSet::U, at!(u)),
        (GlobalSet::V, at!(v)),
        (GlobalSet::CS, at!(cs)),
        (GlobalSet::OS, at!(os)),
        (GlobalSet::DU, at!(du)),
        (GlobalSet::DV, at!(dv)),
        (GlobalSet::DPDU, at!(dpdu)),
        (GlobalSet::DPDV, at!(dpdv)),
    ] {
        if bit.0 & read.0 != 0 {
            chunks |= chunk(f) | chunk(f + 2);
        }
    }
    if derivs {
        for f in [at!(dpdx), at!(dpdy), at!(dndx), at!(dndy), at!(dsdx), at!(dtdy)] {
            chunks |= chunk(f) | chunk(f + 2);
        }
    }
    let mut rows = [&hits[first]; MAX_LANES];
    for (i, row) in rows.iter_mut().enumerate().take(F::LANES) {
        if (group >> i) & 1 != 0 {
            *row = &hits[i];
        }
    }
    let mut scratch = core::mem::MaybeUninit::<[[f32; MAX_LANES]; HIT_FLOATS]>::uninit();
    let block = scratch.as_mut_ptr().cast::<[f32; MAX_LANES]>();
    // SAFETY: `block` has `HIT_FLOATS` rows of `MAX_LANES >= F::LANES` floats.
    unsafe { transpose_hits(&rows[..F::LANES], chunks, block) };
    // SAFETY: the first `F::LANES` floats of row `f` were written for every row read below:
    // `chunks` holds the chunk of every float the same conditions read.
    let ld = |f: usize| -> F { F::load(unsafe { core::slice::from_raw_parts(block.add(f).cast::<f32>(), F::LANES) }) };
    let ld3 = |f: usize| Vec3::new(ld(f), ld(f + 1), ld(f + 2));
    let zero3 = Vec3::splat(F::c(0.0));
    let pick3 = |bit: GlobalSet, f: usize| if has(bit) { ld3(f) } else { zero3 };
    let seed = |v: F, dx: usize, dy: usize| if derivs { v.with_derivs(ld(dx), ld(dy)) } else { v };
    let seed3 = |v: Vec3<F>, dx: usize, dy: usize| {
        Vec3::new(seed(v.x, dx, dy), seed(v.y, dx + 1, dy + 1), seed(v.z, dx + 2, dy + 2))
    };
    let (p, n, i) = (pick3(GlobalSet::P, at!(p)), pick3(GlobalSet::N, at!(n)), pick3(GlobalSet::I, at!(i)));
    let st = |bits: GlobalSet, f: usize| if bits.0 & read.0 != 0 { ld(f) } else { F::c(0.0) };
    let s = st(GlobalSet::S, at!(s));
    let t = st(GlobalSet::T, at!(t));
    let (s, t) = (seed(s, at!(dsdx), at!(dsdy)), seed(t, at!(dtdx), at!(dtdy)));
    let white = Color::c(1.0, 1.0, 1.0);
    let color = |bit: GlobalSet, f: usize| if has(bit) { Color::new(ld(f), ld(f + 1), ld(f + 2)) } else { white };
    Globals {
        // The eye is fixed, so I = P − E changes like P.
        P: seed3(p, at!(dpdx), at!(dpdy)),
        N: seed3(n, at!(dndx), at!(dndy)),
        Ng: pick3(GlobalSet::NG, at!(ng)),
        I: seed3(i, at!(dpdx), at!(dpdy)),
        E: pick3(GlobalSet::E, at!(e)),
        s,
        t,
        u: st(GlobalSet::U, at!(u)),
        v: st(GlobalSet::V, at!(v)),
        du: st(GlobalSet::DU, at!(du)),
        dv: st(GlobalSet::DV, at!(dv)),
        dPdu: pick3(GlobalSet::DPDU, at!(dpdu)),
        dPdv: pick3(GlobalSet::DPDV, at!(dpdv)),
        Cs: color(GlobalSet::CS, at!(cs)),
        Os: color(GlobalSet::OS, at!(os)),
    }
}

/// The sky colour seen along `dir`, lane by lane (generic twin of [`crate::Sky::color`]).
#[inline(always)]
fn sky_color<F: ShadingFloat>(sky: &crate::Sky, dir: Vec3<F>) -> Color<F> {
    let d = dir.normalize();
    let t = d.y.abs().min(F::c(1.0));
    let h = Color::<F>::from_array(sky.horizon.map(f64::from));
    let z = Color::<F>::from_array(sky.zenith.map(f64::from));
    h + (z - h) * t
}

/// Shades lanes `0 .. F::LANES` of `lanes` with [`PlainShading`]: misses get the background,
/// hits are grouped by surface shader and each group is shaded in one masked pass; partly
/// transparent results are composited over what lies behind (`Ci + (1 − Oi) · behind`).
#[inline(never)]
pub fn shade_lanes<F, S, L>(tracer: Tracer<'_, S, L>, lanes: &Lanes<'_>, depth: Depth) -> Color<F>
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    shade_lanes_by::<F, S, L, _>(tracer, lanes, depth, PlainShading)
}

/// [`shade_lanes`] with the shading of each group of lanes chosen by `how` (see
/// [`GroupShading`]).
#[inline(never)]
pub fn shade_lanes_by<F, S, L, G>(tracer: Tracer<'_, S, L>, lanes: &Lanes<'_>, depth: Depth, how: G) -> Color<F>
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
    G: GroupShading<F, S, L>,
{
    debug_assert!(F::LANES <= MAX_LANES && lanes.hits.len() >= F::LANES && lanes.dirs.len() >= F::LANES);
    let scene = tracer.scene;
    let all = if F::LANES >= 32 { u32::MAX } else { (1u32 << F::LANES) - 1 };
    let active = lanes.active & all;
    let miss = active & !lanes.hit;
    let mut result = Color::<F>::zero();
    if miss != 0 && (!lanes.camera || scene.sky.visible_to_camera) {
        let mut bg = [[0.0f32; MAX_LANES]; 3];
        for (i, dir) in lanes.dirs.iter().enumerate().take(F::LANES) {
            if (miss >> i) & 1 != 0 {
                let c = scene.sky.color(*dir);
                for (channel, v) in bg.iter_mut().zip(c) {
                    channel[i] = v;
                }
            }
        }
        result = Color::new(F::load(&bg[0]), F::load(&bg[1]), F::load(&bg[2]));
    }
    let mut remaining = active & lanes.hit;
    while remaining != 0 {
        let first = remaining.trailing_zeros() as usize;
        let surface = lanes.hits[first].surface;
        let mut group = 0u32;
        for i in first..F::LANES {
            if (remaining >> i) & 1 != 0 && lanes.hits[i].surface == surface {
                group |= 1 << i;
            }
        }
        remaining &= !group;
        let c = how.shade_group(tracer, lanes, group, first, depth);
        result = if group == active { c } else { Color::select(lane_mask::<F>(group), c, result) };
    }
    result
}

/// How a group of lanes that hit the same surface shader is shaded — the step of
/// [`shade_lanes_by`] a renderer (or its caller) may replace. Implementations:
/// [`PlainShading`] (the shader in `F`), [`FilteredShading`] (`Dual<F>` for shaders that
/// use derivatives) and [`KernelShading`] (a caller's own kernel first).
pub trait GroupShading<F: ShadingFloat, S, L>: Copy {
    /// The colour of the lanes of `group`, all of which hit `lanes.hits[first].surface`
    /// (other lanes: any finite value).
    fn shade_group(
        self,
        tracer: Tracer<'_, S, L>,
        lanes: &Lanes<'_>,
        group: u32,
        first: usize,
        depth: Depth,
    ) -> Color<F>;
}

/// Every group shaded by its surface shader instantiated for `F` as is (with `F = Dual<_>`
/// that already carries the hits' derivatives).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PlainShading;

impl<F: ShadingFloat, S: SurfaceShader, L: LightShader> GroupShading<F, S, L> for PlainShading {
    #[inline(always)]
    fn shade_group(
        self,
        tracer: Tracer<'_, S, L>,
        lanes: &Lanes<'_>,
        group: u32,
        first: usize,
        depth: Depth,
    ) -> Color<F> {
        shade_group::<F, S, L>(tracer, lanes, group, first, depth)
    }
}

/// Groups whose surface shader asks for derivatives (`uses_derivatives[surface]`, from
/// [`anysl_core::ShaderMeta::uses_derivatives`]) are shaded with [`Dual<F>`] seeded with the
/// hits' screen-space derivatives (ray differentials, see [`gather_globals`]), the others
/// with plain `F` — what the scalar renderer does one ray at a time, for any width. An
/// all-`false` (or empty) slice shades everything with `F`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FilteredShading<'a> {
    /// Per surface shader of the scene: shade it with dual numbers.
    pub uses_derivatives: &'a [bool],
}

impl FilteredShading<'_> {
    /// The derivative flags of `surfaces` when `enabled`, else none (plain `F` everywhere).
    #[must_use]
    pub fn flags<S: SurfaceShader>(surfaces: &[S], enabled: bool) -> Vec<bool> {
        surfaces.iter().map(|s| enabled && s.meta().uses_derivatives).collect()
    }
}

impl<F: ShadingFloat, S: SurfaceShader, L: LightShader> GroupShading<F, S, L> for FilteredShading<'_> {
    #[inline(always)]
    fn shade_group(
        self,
        tracer: Tracer<'_, S, L>,
        lanes: &Lanes<'_>,
        group: u32,
        first: usize,
        depth: Depth,
    ) -> Color<F> {
        let surface = lanes.hits[first].surface as usize;
        if !F::HAS_DERIVS && self.uses_derivatives.get(surface).copied().unwrap_or(false) {
            let c = shade_group::<Dual<F>, S, L>(tracer, lanes, group, first, depth);
            Color::new(c.r.val, c.g.val, c.b.val)
        } else {
            shade_group::<F, S, L>(tracer, lanes, group, first, depth)
        }
    }
}

/// A caller-supplied shading kernel tried first for every group: `kernel(shader, globals)`
/// returns the group's [`SurfaceOutput`] (`Ci`, `Oi`) or `None` to leave the group to
/// `fallback`. It sees the renderer's gathered globals (lanes outside the group hold copies
/// of a group lane, so any value computed for them is finite and ignored) but not the scene:
/// it does its own lighting. Opacity is composited as for shaders. This is how a
/// hand-written SIMD kernel is plugged into a renderer without the renderer naming it.
pub struct KernelShading<'a, K, G> {
    /// The kernel.
    pub kernel: &'a K,
    /// Shades what the kernel declines.
    pub fallback: G,
}

impl<K, G: Copy> Clone for KernelShading<'_, K, G> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<K, G: Copy> Copy for KernelShading<'_, K, G> {}

impl<F, S, L, K, G> GroupShading<F, S, L> for KernelShading<'_, K, G>
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
    K: Fn(&S, &Globals<F>) -> Option<SurfaceOutput<F>>,
    G: GroupShading<F, S, L>,
{
    #[inline(always)]
    fn shade_group(
        self,
        tracer: Tracer<'_, S, L>,
        lanes: &Lanes<'_>,
        group: u32,
        first: usize,
        depth: Depth,
    ) -> Color<F> {
        let shader = &tracer.scene.surfaces[lanes.hits[first].surface as usize];
        let globals = gather_globals::<F>(lanes.hits, group, first);
        match (self.kernel)(shader, &globals) {
            Some(out) => composite::<F, S, L>(tracer, lanes, group, depth, out),
            None => self.fallback.shade_group(tracer, lanes, group, first, depth),
        }
    }
}

/// One masked pass of the surface shader of lane `first` over the lanes of `group`.
///
/// The pass is one function per concrete shader type ([`SurfaceShader::visit`]): for a closed
/// set of shaders the `match` picks it, and gathering the globals, the shader and the
/// compositing are compiled together — the globals the shader does not read are never
/// gathered, and those it reads stay in registers instead of crossing a call in memory, as in
/// a hand-written packet kernel.
#[inline(always)]
fn shade_group<F, S, L>(tracer: Tracer<'_, S, L>, lanes: &Lanes<'_>, group: u32, first: usize, depth: Depth) -> Color<F>
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    let shader = &tracer.scene.surfaces[lanes.hits[first].surface as usize];
    shader.visit(GroupPass::<F, S, L> { tracer: &tracer, lanes, group, first, depth, _f: core::marker::PhantomData })
}

/// [`shade_group`]'s pass, run on the concrete shader.
///
/// The tracer goes by reference: built by value right before the call, its 32 bytes were
/// stored field by field and then read back by the callee as one 32-byte load, which cannot
/// take its value from those narrower stores (a store-forwarding stall of about a tenth of a
/// short shader's time at four lanes).
struct GroupPass<'a, 'p, F, S, L> {
    tracer: &'a Tracer<'a, S, L>,
    lanes: &'a Lanes<'p>,
    group: u32,
    first: usize,
    depth: Depth,
    _f: core::marker::PhantomData<F>,
}

impl<F: ShadingFloat, S: SurfaceShader, L: LightShader> SurfaceVisitor for GroupPass<'_, '_, F, S, L> {
    type Output = Color<F>;

    #[inline(never)]
    fn visit<T: SurfaceShader>(self, shader: &T) -> Color<F> {
        let Self { tracer, lanes, group, first, depth, .. } = self;
        let tracer = *tracer;
        let mut read = shader.globals_read();
        if tracer.scene.all_white {
            // White is what the gather gives for Cs and Os left unread.
            read = GlobalSet(read.0 & !(GlobalSet::CS.0 | GlobalSet::OS.0));
        }
        let surface = lanes.hits[first].surface;
        let globals = gather_globals_read::<F>(lanes.hits, group, first, read);
        let mut ctx = SceneContext { globals, tracer, depth, surface };
        let mut e = Exec::with_mask(lane_mask::<F>(group));
        let out = shader.shade(&mut ctx, &mut e);
        composite::<F, S, L>(tracer, lanes, group, depth, out)
    }
}

/// `Ci` of the lanes of `group`, with what lies behind composited where `Oi < 1`.
#[inline(always)]
fn composite<F, S, L>(
    tracer: Tracer<'_, S, L>,
    lanes: &Lanes<'_>,
    group: u32,
    depth: Depth,
    out: SurfaceOutput<F>,
) -> Color<F>
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    if depth.layer >= MAX_LAYERS {
        return out.Ci;
    }
    let mask = lane_mask::<F>(group);
    let one = F::c(1.0);
    let see_through = mask & (out.Oi.r.lt(one) | out.Oi.g.lt(one) | out.Oi.b.lt(one));
    if see_through.none() {
        return out.Ci;
    }
    let bits = mask_bits::<F>(see_through) & group;
    let mut origins = [Vec3A::ZERO; MAX_LANES];
    let mut dirs = [Vec3A::Z; MAX_LANES];
    for i in 0..F::LANES {
        if (bits >> i) & 1 != 0 {
            origins[i] = lanes.hits[i].p;
            dirs[i] = lanes.hits[i].i.normalize_or(Vec3A::Z);
        }
    }
    let behind = trace_lanes::<F, S, L>(
        tracer,
        &origins,
        &dirs,
        bits,
        lanes.camera,
        Depth { trace: depth.trace, layer: depth.layer + 1 },
    );
    let composite = out.Ci + (Color::splat(one) - out.Oi) * behind;
    Color::select(see_through, composite, out.Ci)
}

/// Casts one ray per lane of `active` (unit `dirs`) and shades what they hit.
#[inline(never)]
pub fn trace_lanes<F, S, L>(
    tracer: Tracer<'_, S, L>,
    origins: &[Vec3A; MAX_LANES],
    dirs: &[Vec3A; MAX_LANES],
    active: u32,
    camera: bool,
    depth: Depth,
) -> Color<F>
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    let scene = tracer.scene;
    let mut hits = [SurfaceHit::default(); MAX_LANES];
    let hit_bits = if F::LANES == 1 {
        // One ray: straight to the single-ray traversal.
        let (o, d) = (origins[0], dirs[0]);
        match scene.intersect(o, d, ray_epsilon(o), f32::INFINITY) {
            Some(h) if active & 1 != 0 => {
                hits[0] = scene.surface_hit(&h, o, d, None);
                1
            }
            _ => 0,
        }
    } else {
        // The lanes' rays as one packet (RTfact's secondary packets).
        let mut rays = RayPacket::default();
        for i in (0..F::LANES).filter(|i| (active >> i) & 1 != 0) {
            rays.set(i, origins[i], dirs[i], ray_epsilon(origins[i]), f32::INFINITY);
        }
        let mut found = [Hit { t: 0.0, prim: 0, b1: 0.0, b2: 0.0 }; MAX_PACKET];
        let bits = scene.intersect_packet(&rays, &mut found);
        for i in (0..F::LANES).filter(|i| (bits >> i) & 1 != 0) {
            hits[i] = scene.surface_hit(&found[i], origins[i], dirs[i], None);
        }
        bits
    };
    let lanes = Lanes { hits: &hits, dirs, active, hit: hit_bits, camera };
    shade_lanes::<F, S, L>(tracer, &lanes, depth)
}

/// Visibility (0 or 1 per lane) of a light from the points `p` in the lanes of `mask`.
#[inline(never)]
fn shadow_visibility<F: ShadingFloat, S, L>(
    scene: &Scene<S, L>,
    mask: F::Mask,
    p: Vec3<F>,
    light: &LightOutput<F>,
) -> F {
    // The shadow ray of lane `i` as (origin, unit direction, tmin, tmax), if it has one.
    let shadow_ray = |i: usize| {
        let o = vec_lane(&p, i);
        let to_light = -vec_lane(&light.l, i);
        let eps = ray_epsilon(o);
        match light.emission {
            Emission::Local => {
                let dist = to_light.length();
                (dist > 2.0 * eps).then(|| (o, to_light / dist, eps, dist - eps))
            }
            Emission::Distant => to_light.try_normalize().map(|d| (o, d, eps, f32::INFINITY)),
            Emission::Ambient => None,
        }
    };
    let lanes = mask_bits::<F>(mask) & if F::LANES >= 32 { u32::MAX } else { (1u32 << F::LANES) - 1 };
    let blocked = if F::LANES == 1 {
        let ray = if lanes & 1 != 0 { shadow_ray(0) } else { None };
        u32::from(ray.is_some_and(|(o, d, tmin, tmax)| scene.accel().occluded(o, d, tmin, tmax)))
    } else {
        // All lanes' shadow rays towards this light as one packet.
        let mut rays = RayPacket::default();
        for i in (0..F::LANES).filter(|i| (lanes >> i) & 1 != 0) {
            if let Some((o, d, tmin, tmax)) = shadow_ray(i) {
                rays.set(i, o, d, tmin, tmax);
            }
        }
        scene.accel().occluded_packet(&rays)
    };
    let mut vis = [1.0f32; MAX_LANES];
    for (i, v) in vis.iter_mut().enumerate().take(F::LANES) {
        if (blocked >> i) & 1 != 0 {
            *v = 0.0;
        }
    }
    F::load(&vis)
}

/// [`run_illuminance`] not inlined (see [`SceneContext`]'s `illuminance`).
#[inline(never)]
fn run_illuminance_out_of_line<F, L, V, B>(lights: &[L], e: &mut Exec<F>, q: LightQuery<'_, F>, visibility: V, body: B)
where
    F: ShadingFloat,
    L: anysl_core::LightSource,
    V: FnMut(F::Mask, Vec3<F>, &LightOutput<F>) -> Option<Color<F>>,
    B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>),
{
    run_illuminance(lights, e, q, visibility, body);
}

impl<F: ShadingFloat, S: SurfaceShader, L: LightShader> ShadingContext<F> for SceneContext<'_, F, S, L> {
    #[inline(always)]
    fn globals(&self) -> &Globals<F> {
        &self.globals
    }

    fn spaces(&self) -> &Spaces {
        self.tracer.scene.surface_spaces.get(self.surface as usize).unwrap_or(Spaces::standard())
    }

    #[inline(always)]
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        e: &mut Exec<F>,
        q: LightQuery<'_, F>,
        body: B,
    ) {
        let tracer = self.tracer;
        let surface = self.surface;
        let visibility = |mask, p, out: &LightOutput<F>| {
            tracer.shadows.then(|| Color::splat(shadow_visibility::<F, S, L>(tracer.scene, mask, p, out)))
        };
        // Data carries no category to select on.
        match tracer.data_for::<F>(surface).filter(|_| q.category.is_empty()) {
            Some(data) => run_illuminance(data, e, q, visibility, body),
            // Where the lights can run as data, the light-shader loop is the rare path
            // (lights without a description, a category): out of line, so that its copy of
            // the body and the light shaders' code (a spotlight's cosines) do not crowd the
            // shading pass's registers and frame. Elsewhere it is the path, inlined.
            None if LightData::exact_for::<F>() => {
                run_illuminance_out_of_line(tracer.scene.lights_for(surface), e, q, visibility, body);
            }
            None => run_illuminance(tracer.scene.lights_for(surface), e, q, visibility, body),
        }
    }

    #[inline(always)]
    fn ambient(&mut self, e: &Exec<F>) -> Color<F> {
        match self.tracer.data_for::<F>(self.surface) {
            Some(data) => sum_ambient(data, e, self.globals.P),
            None => sum_ambient(self.tracer.scene.lights_for(self.surface), e, self.globals.P),
        }
    }

    /// Without shadow rays the scene's light loops are the shared ones over the lights as
    /// data, so code that runs them itself (JIT-compiled shaders) may.
    #[inline(always)]
    fn lights_as_data(&self) -> Option<&[LightData]> {
        if self.tracer.shadows {
            None
        } else {
            self.tracer.data_for::<F>(self.surface)
        }
    }

    /// Without shadow rays, the lights as records where some have code (compiled `.sl`
    /// lights): code that runs the light loops itself calls them.
    #[inline(always)]
    fn light_records(&self) -> Option<&[LightRecord]> {
        if self.tracer.shadows {
            None
        } else {
            self.tracer.light_data.records_for::<F>(self.surface)
        }
    }

    /// Camera rays and their continuations through transparent surfaces are at depth 0,
    /// each `trace` one deeper.
    #[inline(always)]
    fn ray_depth(&self) -> Option<u32> {
        Some(self.depth.trace)
    }

    #[inline(always)]
    fn trace(&mut self, e: &Exec<F>, p: Vec3<F>, dir: Vec3<F>) -> Color<F> {
        if self.depth.trace >= MAX_TRACE_DEPTH {
            return sky_color(&self.tracer.scene.sky, dir);
        }
        let bits = mask_bits::<F>(e.mask());
        let mut origins = [Vec3A::ZERO; MAX_LANES];
        let mut dirs = [Vec3A::Z; MAX_LANES];
        for i in 0..F::LANES {
            if (bits >> i) & 1 != 0 {
                origins[i] = vec_lane(&p, i);
                dirs[i] = vec_lane(&dir, i).normalize_or(Vec3A::Z);
            }
        }
        trace_lanes::<F, S, L>(
            self.tracer,
            &origins,
            &dirs,
            bits,
            false,
            Depth { trace: self.depth.trace + 1, layer: self.depth.layer },
        )
    }
}

/// A context that evaluates a surface shader *passively* (the path tracer's material
/// interface): one unit white light from the viewer-facing normal direction, no ambient
/// light, and `trace` sees black. Named spaces are the surface's own.
pub struct ProbeContext<'s, F: ShadingFloat> {
    /// The points being shaded.
    pub globals: Globals<F>,
    /// The named spaces the shader sees ([`Scene::surface_spaces`]).
    pub spaces: &'s Spaces,
}

impl<F: ShadingFloat> ShadingContext<F> for ProbeContext<'_, F> {
    #[inline(always)]
    fn globals(&self) -> &Globals<F> {
        &self.globals
    }

    fn spaces(&self) -> &Spaces {
        self.spaces
    }

    #[inline(always)]
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        e: &mut Exec<F>,
        q: LightQuery<'_, F>,
        mut body: B,
    ) {
        let g = &self.globals;
        let facing = g.N.dot(g.I).lt(F::c(0.0));
        let l = Vec3::select(facing, g.N, -g.N);
        let mut mask = e.mask();
        if let Some((axis, angle)) = q.cone {
            mask = mask & in_cone(l, axis, angle);
        }
        e.masked(mask, |e| body(e, l, Color::splat(F::c(1.0))));
    }

    #[inline(always)]
    fn ambient(&mut self, _e: &Exec<F>) -> Color<F> {
        Color::zero()
    }

    #[inline(always)]
    fn trace(&mut self, _e: &Exec<F>, _p: Vec3<F>, _dir: Vec3<F>) -> Color<F> {
        Color::zero()
    }
}
