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
    in_cone, run_illuminance, sum_ambient, Color, Emission, Exec, Globals, LightOutput, LightShader, Mask,
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

/// A [`ShadingFloat`] whose lane `i` is 1 where bit `i` of `bits` is set, else 0.
#[inline(always)]
fn lane_flags<F: ShadingFloat>(bits: u32) -> F {
    let mut buf = [0.0f32; MAX_LANES];
    for (i, b) in buf.iter_mut().enumerate().take(F::LANES) {
        *b = ((bits >> i) & 1) as f32;
    }
    F::load(&buf)
}

/// The lane mask of `bits`.
#[inline(always)]
#[must_use]
pub fn lane_mask<F: ShadingFloat>(bits: u32) -> F::Mask {
    lane_flags::<F>(bits).gt(F::c(0.5))
}

/// The bits of the lanes of `m` that are (possibly) set.
#[inline(always)]
#[must_use]
pub fn mask_bits<F: ShadingFloat>(m: F::Mask) -> u32 {
    let mut bits = 0;
    for i in 0..F::LANES {
        if m.lane(i) {
            bits |= 1 << i;
        }
    }
    bits
}

/// Lane `i` of a vector as a glam vector.
#[inline(always)]
fn vec_lane<F: ShadingFloat>(v: &Vec3<F>, i: usize) -> Vec3A {
    Vec3A::new(v.x.lane(i) as f32, v.y.lane(i) as f32, v.z.lane(i) as f32)
}

/// One field of the hits as lanes; lanes outside `group` read lane `first` (so that masked
/// lanes hold finite values).
#[inline(always)]
fn field<F: ShadingFloat>(hits: &[SurfaceHit], src: &[usize; MAX_LANES], f: impl Fn(&SurfaceHit) -> f32) -> F {
    let mut buf = [0.0f32; MAX_LANES];
    for i in 0..F::LANES {
        buf[i] = f(&hits[src[i]]);
    }
    F::load(&buf)
}

#[inline(always)]
fn field3<F: ShadingFloat>(hits: &[SurfaceHit], src: &[usize; MAX_LANES], f: impl Fn(&SurfaceHit) -> Vec3A) -> Vec3<F> {
    Vec3::new(field(hits, src, |h| f(h).x), field(hits, src, |h| f(h).y), field(hits, src, |h| f(h).z))
}

/// The globals of the hits in `group` (structure of arrays), seeded with screen-space
/// derivatives when `F` carries them.
#[inline(always)]
#[must_use]
pub fn gather_globals<F: ShadingFloat>(hits: &[SurfaceHit], group: u32, first: usize) -> Globals<F> {
    let mut src = [first; MAX_LANES];
    for (i, s) in src.iter_mut().enumerate().take(F::LANES) {
        if (group >> i) & 1 != 0 {
            *s = i;
        }
    }
    let mut p = field3::<F>(hits, &src, |h| h.p);
    let mut n = field3::<F>(hits, &src, |h| h.n);
    let mut i = field3::<F>(hits, &src, |h| h.i);
    let mut s = field::<F>(hits, &src, |h| h.s);
    let mut t = field::<F>(hits, &src, |h| h.t);
    if F::HAS_DERIVS {
        let seed3 = |v: Vec3<F>, dx: Vec3<F>, dy: Vec3<F>| {
            Vec3::new(v.x.with_derivs(dx.x, dy.x), v.y.with_derivs(dx.y, dy.y), v.z.with_derivs(dx.z, dy.z))
        };
        let dpdx = field3::<F>(hits, &src, |h| h.dpdx);
        let dpdy = field3::<F>(hits, &src, |h| h.dpdy);
        p = seed3(p, dpdx, dpdy);
        // The eye is fixed, so I = P − E changes like P.
        i = seed3(i, dpdx, dpdy);
        n = seed3(n, field3(hits, &src, |h| h.dndx), field3(hits, &src, |h| h.dndy));
        s = s.with_derivs(field(hits, &src, |h| h.dsdx), field(hits, &src, |h| h.dsdy));
        t = t.with_derivs(field(hits, &src, |h| h.dtdx), field(hits, &src, |h| h.dtdy));
    }
    Globals {
        P: p,
        N: n,
        Ng: field3(hits, &src, |h| h.ng),
        I: i,
        E: field3(hits, &src, |h| h.e),
        s,
        t,
        u: s,
        v: t,
        du: field(hits, &src, |h| h.du),
        dv: field(hits, &src, |h| h.dv),
        dPdu: field3(hits, &src, |h| h.dpdu),
        dPdv: field3(hits, &src, |h| h.dpdv),
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
    let mut ctx = SceneContext { globals: gather_globals::<F>(lanes.hits, group, first), tracer, depth };
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
