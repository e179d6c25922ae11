//! The renderers and what they share: [`RenderOptions`], the stratified pixel samples and
//! the parallel band driver (rayon; `threads = 1` stays on the calling thread) with an
//! optional progress bar that appears only once a render has run for a while.
//!
//! | renderer | rays | shading | design |
//! |---|---|---|---|
//! | [`packet`] | packets of `F::LANES` (2×2, 4×2, 4×4 pixels) | `F32x4/8/16` together, masked per shader; `Dual<F>` when the shader asks | RTfact-like |
//! | [`scalar`] | one at a time, ray differentials | `f32`, or `Dual<f32>` when the shader asks | Manta-like |
//! | [`pbrt`] | one at a time, integrator, RNG | passive material or the shader's own lighting | pbrt-like |

pub mod packet;
pub mod pbrt;
pub mod scalar;

use crate::image::Image;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Settings every renderer understands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderOptions {
    /// Samples per pixel, on an `n × n` stratified grid at cell centres with
    /// `n = round(√spp)` (so 1 = the pixel centre, 4 = 2×2, 5 rounds to 2×2).
    pub spp: u32,
    /// Worker threads: 0 = rayon's default, 1 = the calling thread only.
    pub threads: usize,
    /// Show a progress bar (only renders that run longer than [`PROGRESS_DELAY`] show it).
    pub progress: bool,
    /// Cast shadow rays (off reproduces the shadow-free AnySL workload).
    pub shadows: bool,
    /// Seed of the path tracer's random numbers.
    pub seed: u64,
    /// Shade surface shaders whose metadata says `uses_derivatives` with dual numbers
    /// seeded from the camera rays' differentials (`Dual<F>` in the packet renderer,
    /// `Dual<f32>` in the scalar and pbrt-like ones), so `filterstep` and friends
    /// antialias. Off: every shader in plain `F` (what the Table-1 benchmark times).
    pub derivatives: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self { spp: 1, threads: 0, progress: false, shadows: true, seed: 0x5EED, derivatives: true }
    }
}

impl RenderOptions {
    /// Side of the stratified sample grid: `round(√spp)`, at least 1.
    #[must_use]
    pub fn grid(&self) -> u32 {
        ((self.spp.max(1) as f64).sqrt().round() as u32).max(1)
    }
}

/// How long a render runs before its progress bar (if asked for) appears.
pub const PROGRESS_DELAY: Duration = Duration::from_millis(750);

/// The offset inside the pixel of sample `k` of an `n × n` grid.
#[inline(always)]
#[must_use]
pub fn sample_offset(k: u32, n: u32) -> (f32, f32) {
    let inv = 1.0 / n as f32;
    (((k % n) as f32 + 0.5) * inv, ((k / n) as f32 + 0.5) * inv)
}

/// A progress bar that stays hidden until the render has taken [`PROGRESS_DELAY`].
struct Progress {
    bar: Option<ProgressBar>,
    start: Instant,
    shown: AtomicBool,
}

impl Progress {
    fn new(enabled: bool, len: u64, label: &str) -> Self {
        let bar = enabled.then(|| {
            let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::hidden());
            if let Ok(style) = ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} bands, {eta} left") {
                bar.set_style(style.progress_chars("=> "));
            }
            bar.set_message(label.to_string());
            bar
        });
        Self { bar, start: Instant::now(), shown: AtomicBool::new(false) }
    }

    fn tick(&self) {
        if let Some(bar) = &self.bar {
            bar.inc(1);
            if self.start.elapsed() >= PROGRESS_DELAY
                && self.shown.compare_exchange(false, true, Ordering::Relaxed, Ordering::Relaxed).is_ok()
            {
                bar.set_draw_target(ProgressDrawTarget::stderr());
            }
        }
    }

    fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// Renders a `width × height` image in bands of `band_rows` rows: `band(y0, pixels)` fills
/// the rows starting at `y0` (`pixels` holds whole rows). Bands run in parallel unless
/// `opts.threads == 1`.
pub(crate) fn render_bands(
    width: u32,
    height: u32,
    band_rows: u32,
    opts: &RenderOptions,
    label: &str,
    band: impl Fn(u32, &mut [[f32; 3]]) + Sync,
) -> Image {
    let mut image = Image::new(width, height);
    let chunk = width as usize * band_rows as usize;
    let progress = Progress::new(opts.progress, height.div_ceil(band_rows) as u64, label);
    let work = |(k, pixels): (usize, &mut [[f32; 3]])| {
        band(k as u32 * band_rows, pixels);
        progress.tick();
    };
    match opts.threads {
        1 => image.data.chunks_mut(chunk).enumerate().for_each(work),
        0 => image.data.par_chunks_mut(chunk).enumerate().for_each(work),
        n => match rayon::ThreadPoolBuilder::new().num_threads(n).build() {
            Ok(pool) => pool.install(|| image.data.par_chunks_mut(chunk).enumerate().for_each(work)),
            // No threads to be had: render here rather than fail.
            Err(_) => image.data.chunks_mut(chunk).enumerate().for_each(work),
        },
    }
    progress.finish();
    image
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_grid() {
        let o = |spp| RenderOptions { spp, ..RenderOptions::default() }.grid();
        assert_eq!((o(0), o(1), o(2), o(4), o(5), o(9), o(16)), (1, 1, 1, 2, 2, 3, 4));
        assert_eq!(sample_offset(0, 1), (0.5, 0.5));
        assert_eq!(sample_offset(3, 2), (0.75, 0.75));
        assert_eq!(sample_offset(1, 2), (0.75, 0.25));
    }

    #[test]
    fn single_thread_stays_on_the_calling_thread() {
        let me = std::thread::current().id();
        let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
        let img = render_bands(8, 8, 2, &opts, "t", |y0, px| {
            assert_eq!(std::thread::current().id(), me);
            for (k, p) in px.iter_mut().enumerate() {
                *p = [y0 as f32 + (k / 8) as f32, 0.0, 0.0];
            }
        });
        for y in 0..8 {
            assert_eq!(img.pixel(3, y)[0], y as f32);
        }
    }
}
