//! The *packet* renderer (RTfact-like): coherent packets of primary rays over small pixel
//! blocks (4 rays = 2×2, 8 = 4×2, 16 = 4×4), traced together through the BVH (one box test
//! for all rays of the packet, see [`crate::accel::packet`]), then
//! **shaded together**: the hits are gathered into the structure-of-arrays globals of a
//! SIMD [`ShadingFloat`] and each surface shader present in the packet runs once, masked to
//! its lanes ([`crate::shading::shade_lanes_by`]). A shader whose metadata says
//! `uses_derivatives` is shaded with `Dual<F>` seeded from the camera rays' differentials
//! (as the scalar renderer does with `Dual<f32>`), unless [`RenderOptions::derivatives`] is
//! off. The same packets can be split and shaded lane by lane with `f32` (the AnySL paper's
//! "Scalar" column) or `f64` (the accuracy reference): [`render_packet_split`]. A caller can
//! plug its own packet shading kernel in front of the shaders: [`render_packet_kernel`].

use super::{render_bands, sample_offset, RenderOptions};
use crate::accel::{Hit, RayPacket, MAX_PACKET};
use crate::camera::RayDifferential;
use crate::image::Image;
use crate::scene::{Scene, SurfaceHit};
use crate::shading::{
    shade_lanes_by, Depth, FilteredShading, GroupShading, KernelShading, Lanes, LightTables, Tracer, MAX_LANES,
};
use anysl_core::{Globals, LightShader, ShadingFloat, SurfaceOutput, SurfaceShader};
use glam::Vec3A;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// Where a packet render spent its time: the AnySL paper compares *shading* time, which
/// tracing would otherwise hide.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PacketStats {
    /// Wall-clock time of the whole render.
    pub total: Duration,
    /// Time inside shading (summed over threads): gathering globals, running the shaders
    /// and everything they call (shadow and secondary rays included), timed per packet with
    /// the cost of reading the clock taken out (packets that hit nothing under a hidden sky
    /// need no shading and are not timed).
    pub shading: Duration,
    /// Camera-ray hits shaded.
    pub shaded_points: u64,
}

/// The pixel block `(columns, rows)` covered by a packet of `lanes` rays.
#[must_use]
pub fn packet_shape(lanes: usize) -> (u32, u32) {
    match lanes {
        4 => (2, 2),
        8 => (4, 2),
        16 => (4, 4),
        n => (n as u32, 1),
    }
}

/// Renders `scene` with packets of `F::LANES` rays shaded together as `F`.
///
/// # Panics
/// When `F::LANES` exceeds [`MAX_LANES`].
#[must_use]
pub fn render_packet<F, S, L>(scene: &Scene<S, L>, opts: &RenderOptions) -> Image
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    render_packet_split::<F, S, L>(scene, opts, F::LANES)
}

/// [`render_packet_split`] that also measures where the time went.
///
/// # Panics
/// As [`render_packet_split`].
#[must_use]
pub fn render_packet_stats<F, S, L>(
    scene: &Scene<S, L>,
    opts: &RenderOptions,
    packet_lanes: usize,
) -> (Image, PacketStats)
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    let derivs = FilteredShading::flags(&scene.surfaces, opts.derivatives);
    measured(|stats| {
        packet_render::<F, S, L, _>(scene, opts, packet_lanes, stats, FilteredShading { uses_derivatives: &derivs })
    })
}

/// [`render_packet_stats`] with a caller's shading kernel: for every group of lanes that hit
/// the same surface shader, `kernel(shader, globals)` is asked first (`globals`: the
/// packet's [`Globals`] in `F`, seeded with derivatives if `F` carries them) and returns
/// the group's `Ci`/`Oi`, or `None` to let the shader run as in [`render_packet_stats`]. The
/// kernel does its own lighting (it does not see the scene). The AnySL paper's "Native"
/// column plugs hand-written SIMD shaders in here.
///
/// # Panics
/// As [`render_packet_split`].
#[must_use]
pub fn render_packet_kernel<F, S, L, K>(
    scene: &Scene<S, L>,
    opts: &RenderOptions,
    packet_lanes: usize,
    kernel: &K,
) -> (Image, PacketStats)
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
    K: Fn(&S, &Globals<F>) -> Option<SurfaceOutput<F>> + Sync,
{
    let derivs = FilteredShading::flags(&scene.surfaces, opts.derivatives);
    let how = KernelShading { kernel, fallback: FilteredShading { uses_derivatives: &derivs } };
    render_packet_with::<F, S, L, _>(scene, opts, packet_lanes, how)
}

/// The packet renderer with the shading of each group of lanes chosen by `how` (ignoring
/// [`RenderOptions::derivatives`]), measured as in [`render_packet_stats`]. With
/// [`PlainShading`](crate::shading::PlainShading) every shader runs in plain `F` and no
/// dual-number code is instantiated (the Table-1 benchmark's variants);
/// [`KernelShading`] puts a caller's kernel in front of any of them.
///
/// # Panics
/// As [`render_packet_split`].
#[must_use]
pub fn render_packet_with<F, S, L, G>(
    scene: &Scene<S, L>,
    opts: &RenderOptions,
    packet_lanes: usize,
    how: G,
) -> (Image, PacketStats)
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
    G: GroupShading<F, S, L> + Sync,
{
    measured(|stats| packet_render::<F, S, L, G>(scene, opts, packet_lanes, stats, how))
}

/// A cheap clock for timing the shading of single packets: the time-stamp counter where
/// there is one (about 20 cycles to read, where `Instant::now` costs a system-call path of
/// ~25 ns per reading — as much as shading a packet of 8 simple points, which would inflate
/// short shading steps and flatten the speedups they are compared by), else nanoseconds.
#[inline(always)]
fn ticks() -> u64 {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: `rdtsc` exists on every x86-64 processor.
        unsafe { core::arch::x86_64::_rdtsc() }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        use std::sync::OnceLock;
        static T0: OnceLock<Instant> = OnceLock::new();
        T0.get_or_init(Instant::now).elapsed().as_nanos() as u64
    }
}

/// What reading [`ticks`] adds to an interval it measures: the median difference of two
/// readings back to back, measured once per process. Each timed packet's interval has it
/// subtracted — it would otherwise count against small packets (on the virtual machines of
/// these benchmarks a reading costs ~12 ns, a quarter of shading a 4-point packet of a
/// simple shader) and more against narrow widths, which time more packets per pixel.
fn reading_cost() -> u64 {
    use std::sync::OnceLock;
    static COST: OnceLock<u64> = OnceLock::new();
    *COST.get_or_init(|| {
        let mut d: Vec<u64> = (0..2001)
            .map(|_| {
                let t = ticks();
                ticks().wrapping_sub(t)
            })
            .collect();
        d.sort_unstable();
        d[d.len() / 2]
    })
}

/// Runs `render` with counters for shading time (in [`ticks`]) and points; the ticks are
/// converted to time by the ratio of ticks to wall-clock time over the whole render.
fn measured(render: impl FnOnce(Option<(&AtomicU64, &AtomicU64)>) -> Image) -> (Image, PacketStats) {
    let shading_ticks = AtomicU64::new(0);
    let points = AtomicU64::new(0);
    let (start, t0) = (Instant::now(), ticks());
    let image = render(Some((&shading_ticks, &points)));
    let (total, dt) = (start.elapsed(), ticks().wrapping_sub(t0));
    let ns_per_tick = if dt == 0 { 0.0 } else { total.as_nanos() as f64 / dt as f64 };
    let stats = PacketStats {
        total,
        shading: Duration::from_nanos((shading_ticks.into_inner() as f64 * ns_per_tick) as u64),
        shaded_points: points.into_inner(),
    };
    (image, stats)
}

/// Renders `scene` with packets of `packet_lanes` rays, each packet shaded `F::LANES` lanes at
/// a time: `render_packet_split::<f32, _, _>(scene, opts, 4)` is the paper's scalar
/// shading of SSE-traced packets.
///
/// # Panics
/// When `packet_lanes` exceeds [`MAX_LANES`] or is not a multiple of `F::LANES`.
#[must_use]
pub fn render_packet_split<F, S, L>(scene: &Scene<S, L>, opts: &RenderOptions, packet_lanes: usize) -> Image
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
{
    let derivs = FilteredShading::flags(&scene.surfaces, opts.derivatives);
    packet_render::<F, S, L, _>(scene, opts, packet_lanes, None, FilteredShading { uses_derivatives: &derivs })
}

/// The packet renderer; `stats` = (shading [`ticks`], shaded points) to measure into,
/// `how` shades each group of lanes.
fn packet_render<F, S, L, G>(
    scene: &Scene<S, L>,
    opts: &RenderOptions,
    packet_lanes: usize,
    stats: Option<(&AtomicU64, &AtomicU64)>,
    how: G,
) -> Image
where
    F: ShadingFloat,
    S: SurfaceShader,
    L: LightShader,
    G: GroupShading<F, S, L> + Sync,
{
    assert!(
        (1..=MAX_LANES).contains(&packet_lanes) && packet_lanes.is_multiple_of(F::LANES),
        "packets of {packet_lanes} rays cannot be shaded {} lanes at a time (at most {MAX_LANES})",
        F::LANES
    );
    let cam = &scene.camera;
    let (width, height) = (cam.width(), cam.height());
    let (bw, bh) = packet_shape(packet_lanes);
    let n = opts.grid();
    let weight = 1.0 / (n * n) as f32;
    let footprint = 1.0 / n as f32;
    let light_data = LightTables::of::<F, _, _>(scene);
    let tracer = Tracer::new(scene, opts.shadows, &light_data);
    let band_rows = 8u32.max(bh);
    let label = format!("packet {}×{} {}", bw, bh, F::NAME);

    render_bands(width, height, band_rows, opts, &label, |y0, pixels| {
        let rows = (pixels.len() / width as usize) as u32;
        let mut hits = [SurfaceHit::default(); MAX_LANES];
        let mut found = [Hit { t: 0.0, prim: 0, b1: 0.0, b2: 0.0 }; MAX_PACKET];
        let mut dirs = [Vec3A::Z; MAX_LANES];
        let mut origins = [Vec3A::ZERO; MAX_LANES];
        let mut out = [[0.0f32; MAX_LANES]; 3];
        let (mut band_ticks, mut band_points) = (0u64, 0u64);
        let tick_cost = if stats.is_some() { reading_cost() } else { 0 };
        for by in (0..rows).step_by(bh as usize) {
            for bx in (0..width).step_by(bw as usize) {
                let lane_pixel = |lane: usize| (bx + lane as u32 % bw, by + lane as u32 / bw);
                // Lanes past the image edge stay inactive.
                let mut active = 0u32;
                for lane in 0..packet_lanes {
                    let (px, py) = lane_pixel(lane);
                    if px < width && py < rows {
                        active |= 1 << lane;
                    }
                }
                let mut acc = [[0.0f32; 3]; MAX_LANES];
                for k in 0..n * n {
                    let (ox, oy) = sample_offset(k, n);
                    // Trace the packet: all its rays through the BVH together.
                    let mut rays = RayPacket::default();
                    let mut differentials = [RayDifferential::default(); MAX_LANES];
                    for lane in (0..packet_lanes).filter(|lane| (active >> lane) & 1 != 0) {
                        let (px, py) = lane_pixel(lane);
                        let ray = cam.primary_ray(px as f32 + ox, (y0 + py) as f32 + oy, footprint);
                        dirs[lane] = ray.dir;
                        origins[lane] = ray.origin;
                        differentials[lane] = ray.differential();
                        rays.set(lane, ray.origin, ray.dir, ray.tmin, ray.tmax);
                    }
                    let hit = scene.intersect_packet_camera(&rays, &mut found);
                    for lane in (0..packet_lanes).filter(|lane| (hit >> lane) & 1 != 0) {
                        hits[lane] =
                            scene.surface_hit(&found[lane], origins[lane], dirs[lane], Some(differentials[lane]));
                    }
                    // A packet that hit nothing shows black where the sky is hidden from the
                    // camera: nothing to shade.
                    if hit == 0 && !scene.sky.visible_to_camera {
                        continue;
                    }
                    // Shade it, F::LANES lanes at a time.
                    let clock = stats.map(|_| ticks());
                    for base in (0..packet_lanes).step_by(F::LANES) {
                        let sub_active = (active >> base) & ((1u32 << F::LANES) - 1);
                        if sub_active == 0 {
                            continue;
                        }
                        let lanes = Lanes {
                            hits: &hits[base..],
                            dirs: &dirs[base..],
                            active: sub_active,
                            hit: hit >> base,
                            camera: true,
                        };
                        let c = shade_lanes_by::<F, S, L, G>(tracer, &lanes, Depth::default(), how);
                        c.r.store(&mut out[0][base..]);
                        c.g.store(&mut out[1][base..]);
                        c.b.store(&mut out[2][base..]);
                    }
                    if let Some(t) = clock {
                        band_ticks += ticks().wrapping_sub(t).saturating_sub(tick_cost);
                        band_points += u64::from(hit.count_ones());
                    }
                    for lane in 0..packet_lanes {
                        if (active >> lane) & 1 != 0 {
                            for ch in 0..3 {
                                acc[lane][ch] += out[ch][lane];
                            }
                        }
                    }
                }
                for (lane, sum) in acc.iter().enumerate().take(packet_lanes) {
                    if (active >> lane) & 1 != 0 {
                        let (px, py) = lane_pixel(lane);
                        pixels[(py * width + px) as usize] = sum.map(|v| v * weight);
                    }
                }
            }
        }
        if let Some((shading, points)) = stats {
            shading.fetch_add(band_ticks, Ordering::Relaxed);
            points.fetch_add(band_points, Ordering::Relaxed);
        }
    })
}
