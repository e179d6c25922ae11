//! The renderer side of the shading contract, shared by every renderer: [`SceneContext`]
//! implements [`ShadingContext`] over a scene (shadow rays for `illuminance`, secondary rays
//! for `trace`), [`shade_lanes`] gathers hits into the structure-of-arrays [`Globals`] of any
//! [`ShadingFloat`] and runs each surface shader present once, masked, and
//! [`ProbeContext`] evaluates a shader *passively* for the path tracer.
//!
//! Lanes are addressed by bit masks (`u32`, bit `i` = lane `i`), so a packet of up to
//! [`MAX_LANES`] rays needs no allocation anywhere on this path.

use crate::scene::{Scene, SurfaceHit};
use anysl_ad::Dual;
use anysl_core::{
    in_cone, run_illuminance, sum_ambient, Color, Emission, Exec, GlobalSet, Globals, LightOutput, LightShader, Mask,
    ShadingContext, ShadingFloat, SurfaceOutput, SurfaceShader, Vec3,
};
use glam::Vec3A;

/// The widest packet (and the widest `ShadingFloat`) the renderers handle.
pub const MAX_LANES: usize = 16;
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

/// Number of hit components [`gather_globals_read`] transposes.
const COMPONENTS: usize = 43;

/// [`gather_globals`] of only the globals in `read` (see
/// [`SurfaceShader::globals_read`]); the others are zero.
///
/// The hits are transposed in two passes: every lane's components are written to a scratch
/// block first, then each component is loaded as one vector. Loading a vector right after
/// writing its lanes one by one would stall on store forwarding for every component.
#[inline(always)]
#[must_use]
pub fn gather_globals_read<F: ShadingFloat>(
    hits: &[SurfaceHit],
    group: u32,
    first: usize,
    read: GlobalSet,
) -> Globals<F> {
    debug_assert!(F::LANES <= MAX_LANES && hits.len() >= F::LANES);
    let mut scratch = core::mem::MaybeUninit::<[[f32; MAX_LANES]; COMPONENTS]>::uninit();
    let block = scratch.as_mut_ptr().cast::<[f32; MAX_LANES]>();
    let derivs = F::HAS_DERIVS;
    let has = |x: GlobalSet| read.contains(x);
    for i in 0..F::LANES {
        let h = &hits[if (group >> i) & 1 != 0 { i } else { first }];
        // SAFETY: `c < COMPONENTS` and `i < F::LANES <= MAX_LANES`: inside the block.
        let put = |c: usize, v: f32| unsafe { (*block.add(c))[i] = v };
        let put3 = |c: usize, v: Vec3A| {
            put(c, v.x);
            put(c + 1, v.y);
            put(c + 2, v.z);
        };
        if has(GlobalSet::P) {
            put3(0, h.p);
        }
        if has(GlobalSet::N) {
            put3(3, h.n);
        }
        if has(GlobalSet::NG) {
            put3(6, h.ng);
        }
        if has(GlobalSet::I) {
            put3(9, h.i);
        }
        if has(GlobalSet::E) {
            put3(12, h.e);
        }
        if has(GlobalSet::S) || has(GlobalSet::U) {
            put(15, h.s);
        }
        if has(GlobalSet::T) || has(GlobalSet::V) {
            put(16, h.t);
        }
        if has(GlobalSet::DU) {
            put(17, h.du);
        }
        if has(GlobalSet::DV) {
            put(18, h.dv);
        }
        if has(GlobalSet::DPDU) {
            put3(19, h.dpdu);
        }
        if has(GlobalSet::DPDV) {
            put3(22, h.dpdv);
        }
        if derivs {
            put3(25, h.dpdx);
            put3(28, h.dpdy);
            put3(31, h.dndx);
            put3(34, h.dndy);
            put(37, h.dsdx);
            put(38, h.dsdy);
            put(39, h.dtdx);
            put(40, h.dtdy);
        }
    }
    // SAFETY: component `c`'s first `F::LANES` values were all written above (for every
    // component read below: the same conditions guard the writes and the reads).
    let ld = |c: usize| -> F { F::load(unsafe { core::slice::from_raw_parts(block.add(c).cast::<f32>(), F::LANES) }) };
    let ld3 = |c: usize| Vec3::new(ld(c), ld(c + 1), ld(c + 2));
    let zero3 = Vec3::splat(F::c(0.0));
    let pick3 = |bit: GlobalSet, c: usize| if has(bit) { ld3(c) } else { zero3 };
    let seed = |v: F, dx: usize, dy: usize| if derivs { v.with_derivs(ld(dx), ld(dy)) } else { v };
    let seed3 = |v: Vec3<F>, dx: usize, dy: usize| {
        Vec3::new(seed(v.x, dx, dy), seed(v.y, dx + 1, dy + 1), seed(v.z, dx + 2, dy + 2))
    };
    let (p, n, i) = (pick3(GlobalSet::P, 0), pick3(GlobalSet::N, 3), pick3(GlobalSet::I, 9));
    let st = |bits: GlobalSet, c: usize| if bits.0 & read.0 != 0 { ld(c) } else { F::c(0.0) };
    let s = st(GlobalSet::S.union(GlobalSet::U), 15);
    let t = st(GlobalSet::T.union(GlobalSet::V), 16);
    let (s, t) = (seed(s, 37, 38), seed(t, 39, 40));
    Globals {
        // The eye is fixed, so I = P − E changes like P.
        P: seed3(p, 25, 28),
        N: seed3(n, 31, 34),
        Ng: pick3(GlobalSet::NG, 6),
        I: seed3(i, 25, 28),
        E: pick3(GlobalSet::E, 12),
        s,
        t,
        u: s,
        v: t,
        du: st(GlobalSet::DU, 17),
        dv: st(GlobalSet::DV, 18),
        dPdu: pick3(GlobalSet::DPDU, 19),
        dPdv: pick3(GlobalSet::DPDV, 22),
        Cs: Color::c(1.0, 1.0, 1.0),
        Os: Color::c(1.0, 1.0, 1.0),
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
#[inline(always)]
fn shade_group<F, S, L>(tracer: Tracer<'_, S, L>, lanes: &Lanes<'_>, group: u32, first: usize, depth: Depth) -> Color<F>
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    let shader = &tracer.scene.surfaces[lanes.hits[first].surface as usize];
    let mask = lane_mask::<F>(group);
    let read = shader.globals_read();
    let mut ctx = SceneContext { globals: gather_globals_read::<F>(lanes.hits, group, first, read), tracer, depth };
    let mut e = Exec::with_mask(mask);
    let out = shader.shade(&mut ctx, &mut e);
    composite::<F, S, L>(tracer, lanes, group, depth, out)
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
    let mut hit_bits = 0u32;
    for i in 0..F::LANES {
        if (active >> i) & 1 == 0 {
            continue;
        }
        let (o, d) = (origins[i], dirs[i]);
        if let Some(h) = scene.intersect(o, d, ray_epsilon(o), f32::INFINITY) {
            hits[i] = scene.surface_hit(&h, o, d, None);
            hit_bits |= 1 << i;
        }
    }
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
    let mut vis = [1.0f32; MAX_LANES];
    for (i, v) in vis.iter_mut().enumerate().take(F::LANES) {
        if !mask.lane(i) {
            continue;
        }
        let o = vec_lane(&p, i);
        let to_light = -vec_lane(&light.l, i);
        let eps = ray_epsilon(o);
        let blocked = match light.emission {
            Emission::Local => {
                let dist = to_light.length();
                dist > 2.0 * eps && scene.accel().occluded(o, to_light / dist, eps, dist - eps)
            }
            Emission::Distant => match to_light.try_normalize() {
                Some(d) => scene.accel().occluded(o, d, eps, f32::INFINITY),
                None => false,
            },
            Emission::Ambient => false,
        };
        if blocked {
            *v = 0.0;
        }
    }
    F::load(&vis)
}

impl<F: ShadingFloat, S: SurfaceShader, L: LightShader> ShadingContext<F> for SceneContext<'_, F, S, L> {
    #[inline(always)]
    fn globals(&self) -> &Globals<F> {
        &self.globals
    }

    #[inline(always)]
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        e: &mut Exec<F>,
        category: &str,
        p: Vec3<F>,
        cone: Option<(Vec3<F>, F)>,
        body: B,
    ) {
        let tracer = self.tracer;
        run_illuminance(
            &tracer.scene.lights,
            e,
            category,
            p,
            cone,
            |mask, p, out| {
                tracer.shadows.then(|| Color::splat(shadow_visibility::<F, S, L>(tracer.scene, mask, p, out)))
            },
            body,
        );
    }

    #[inline(always)]
    fn ambient(&mut self, e: &Exec<F>) -> Color<F> {
        sum_ambient(&self.tracer.scene.lights, e, self.globals.P)
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
/// light, and `trace` sees black.
pub struct ProbeContext<F: ShadingFloat> {
    /// The points being shaded.
    pub globals: Globals<F>,
}

impl<F: ShadingFloat> ShadingContext<F> for ProbeContext<F> {
    #[inline(always)]
    fn globals(&self) -> &Globals<F> {
        &self.globals
    }

    #[inline(always)]
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        e: &mut Exec<F>,
        _category: &str,
        _p: Vec3<F>,
        cone: Option<(Vec3<F>, F)>,
        mut body: B,
    ) {
        let g = &self.globals;
        let facing = g.N.dot(g.I).lt(F::c(0.0));
        let l = Vec3::select(facing, g.N, -g.N);
        let mut mask = e.mask();
        if let Some((axis, angle)) = cone {
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
