//! `anysl bench table1`: the AnySL paper's Table 1. For each of the ten shaders the
//! `table1` scene (a triangulated sphere, two point lights and an ambient light, **no
//! shadows** as in the paper's workload) is rendered with the packet renderer, every variant
//! shading the same packets:
//!
//! - `f32`: packets of 8 rays split and shaded lane by lane in `f32` (the paper's "Scalar");
//! - `f32x4`, `f32x8`, `f32x16`: packets of 4/8/16 rays shaded together with SIMD floats;
//! - `native-f32x8` (phong and checker only): the hand-written `wide::f32x8` kernels of
//!   `anysl_shaders::native` plugged into the packet renderer's shading step.
//!
//! Every variant shades the plain function (no dual numbers: derivatives off), so all rows
//! compute the same thing. Speedups compare the **shading step** (time inside the renderer's
//! shading calls, measured by `render_packet_stats`), the paper's measure; frame speedups
//! (tracing included) are reported beside them. Errors are against an `f64` render of the
//! same packets.

use anysl_core::{Globals, SurfaceOutput};
use anysl_renderers::{
    render_packet_stats, render_packet_with, scenes, Image, KernelShading, PlainShading, RenderOptions, Scene,
};
use anysl_shaders::native::{native_lights, shade_x8, NativePointLight};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::{F32x16, F32x4, F32x8};
use indicatif::ProgressBar;
use serde::Serialize;
use std::time::Duration;

/// One row of the table (the JSON schema other tools read).
#[derive(Clone, Debug, Serialize)]
pub struct Table1Row {
    /// Shader name (Table-1 spelling: `phong` for RSL `plastic`).
    pub shader: String,
    /// `f32`, `f32x4`, `f32x8`, `f32x16` or `native-f32x8`.
    pub variant: String,
    /// Frames per second, whole frame (median of the runs).
    pub fps: f64,
    /// Shading speedup over the `f32` row of the same shader and run (= `shading_speedup`).
    pub speedup: f64,
    /// PSNR in dB against the `f64` render.
    pub psnr_db: f64,
    /// Milliseconds per frame spent shading (median of the runs, summed over threads).
    pub shading_ms: f64,
    /// `f32` shading time / this row's shading time.
    pub shading_speedup: f64,
    /// `f32` frame time / this row's frame time.
    pub frame_speedup: f64,
    /// Largest per-channel absolute difference to the `f64` render.
    pub max_abs_err: f64,
}

/// Benchmark settings.
#[derive(Clone, Debug)]
pub struct Table1Opts {
    /// Image side in pixels.
    pub size: u32,
    /// Timed runs per row (medians reported).
    pub runs: usize,
    /// Worker threads (0 = all).
    pub threads: usize,
    /// Only these shaders (Table-1 names; empty: all ten).
    pub shaders: Vec<String>,
}

/// The variants in table order.
pub const VARIANTS: [&str; 5] = ["f32", "f32x4", "f32x8", "f32x16", "native-f32x8"];

/// The hand-written kernels as a packet-shading hook: phong (plastic) and checker, `None`
/// (the generic shader runs) for every other shader.
struct Native {
    lights: Vec<NativePointLight>,
    ambient: [f32; 3],
}

impl Native {
    fn shade(&self, surface: &Surface, g: &Globals<F32x8>) -> Option<SurfaceOutput<F32x8>> {
        shade_x8(surface, &self.lights, self.ambient, g)
    }
}

/// Median of durations, in seconds.
fn median(mut v: Vec<Duration>) -> f64 {
    v.sort();
    v[v.len() / 2].as_secs_f64()
}

/// Runs the benchmark; `pb` counts renders.
pub fn run(opts: &Table1Opts, pb: &ProgressBar) -> Result<Vec<Table1Row>, String> {
    let lights = table1_lights();
    let (points, ambient) = native_lights(&lights).ok_or("the Table-1 lights are not all point and ambient lights")?;
    let native = Native { lights: points, ambient };
    let kernel = |s: &Surface, g: &Globals<F32x8>| native.shade(s, g);
    let ropts = RenderOptions { threads: opts.threads, shadows: false, derivatives: false, ..RenderOptions::default() };
    let runs = opts.runs.max(1);
    let mut rows = Vec::new();
    let names: Vec<&str> = if opts.shaders.is_empty() {
        Surface::NAMES.to_vec()
    } else {
        opts.shaders.iter().map(String::as_str).collect()
    };
    for name in &names {
        if Surface::by_name(name).is_none() {
            return Err(format!("unknown shader '{name}' (choices: {})", Surface::NAMES.join(", ")));
        }
    }
    pb.set_length((names.len() * (5 * runs + 1)) as u64);
    for name in names {
        pb.set_message(name.to_string());
        let surface = Surface::by_name(name).ok_or_else(|| format!("unknown shader {name}"))?;
        let has_native = matches!(surface, Surface::Plastic(_) | Surface::Checker(_));
        let scene: Scene<Surface, Light> = scenes::table1(surface, lights.clone(), opts.size);
        let reference = render_packet_with::<f64, _, _, _>(&scene, &ropts, 8, PlainShading).0;
        pb.inc(1);
        let variants: Vec<&str> = VARIANTS.iter().copied().filter(|v| *v != "native-f32x8" || has_native).collect();
        let render = |variant: &str| match variant {
            "f32" => render_packet_stats::<f32, _, _>(&scene, &ropts, 8),
            "f32x4" => render_packet_stats::<F32x4, _, _>(&scene, &ropts, 4),
            "f32x8" => render_packet_stats::<F32x8, _, _>(&scene, &ropts, 8),
            "f32x16" => render_packet_stats::<F32x16, _, _>(&scene, &ropts, 16),
            _ => render_packet_with::<F32x8, _, _, _>(
                &scene,
                &ropts,
                8,
                KernelShading { kernel: &kernel, fallback: PlainShading },
            ),
        };
        // Round-robin over the variants, so a slow spell of this shared machine lands on every
        // variant of a round instead of on all runs of one variant; medians per variant.
        let mut frames: Vec<Vec<Duration>> = vec![Vec::with_capacity(runs); variants.len()];
        let mut shading: Vec<Vec<Duration>> = vec![Vec::with_capacity(runs); variants.len()];
        let mut images: Vec<Option<Image>> = vec![None; variants.len()];
        for _ in 0..runs {
            for (k, variant) in variants.iter().enumerate() {
                let (img, stats) = render(variant);
                frames[k].push(stats.total);
                shading[k].push(stats.shading);
                images[k] = Some(img);
                pb.inc(1);
            }
        }
        let measured: Vec<(&str, Image, f64, f64)> = variants
            .iter()
            .zip(images)
            .zip(frames.into_iter().zip(shading))
            .map(|((v, img), (f, s))| (*v, img.expect("at least one run"), median(f), median(s)))
            .collect();
        let (base_frame, base_shading) = (measured[0].2, measured[0].3);
        for (variant, img, frame, shading) in measured {
            let shading_speedup = base_shading / shading.max(1e-12);
            rows.push(Table1Row {
                shader: name.to_string(),
                variant: variant.to_string(),
                fps: 1.0 / frame.max(1e-12),
                speedup: shading_speedup,
                psnr_db: img.psnr(&reference),
                shading_ms: shading * 1e3,
                shading_speedup,
                frame_speedup: base_frame / frame.max(1e-12),
                max_abs_err: f64::from(img.max_abs_diff(&reference)),
            });
        }
    }
    Ok(rows)
}

/// Prints the rows as a table.
pub fn print_table(rows: &[Table1Row]) {
    println!(
        "{:<9} {:<13} {:>9} {:>11} {:>10} {:>9} {:>9} {:>8} {:>9}",
        "shader", "variant", "frames/s", "shading ms", "shade spd", "frame spd", "PSNR dB", "max err", ""
    );
    for r in rows {
        let psnr = if r.psnr_db.is_finite() { format!("{:.1}", r.psnr_db) } else { "inf".into() };
        println!(
            "{:<9} {:<13} {:>9.2} {:>11.2} {:>9.2}x {:>8.2}x {:>9} {:>8.1e}",
            r.shader, r.variant, r.fps, r.shading_ms, r.shading_speedup, r.frame_speedup, psnr, r.max_abs_err
        );
    }
}

/// Per variant: (variant, arithmetic mean and geometric mean of the shading speedup, mean
/// frame speedup, number of shaders) over the shaders that have the variant.
pub fn averages(rows: &[Table1Row]) -> Vec<(&'static str, f64, f64, f64, usize)> {
    VARIANTS
        .iter()
        .filter_map(|v| {
            let sel: Vec<&Table1Row> = rows.iter().filter(|r| r.variant == *v).collect();
            if sel.is_empty() {
                return None;
            }
            let n = sel.len() as f64;
            let am = sel.iter().map(|r| r.shading_speedup).sum::<f64>() / n;
            let gm = (sel.iter().map(|r| r.shading_speedup.ln()).sum::<f64>() / n).exp();
            let frame = sel.iter().map(|r| r.frame_speedup).sum::<f64>() / n;
            Some((*v, am, gm, frame, sel.len()))
        })
        .collect()
}

/// Per shader with a native kernel: (shader, generic `f32x8` shading time / native shading
/// time); above 1 means the generic shader is slower.
pub fn generic_vs_native(rows: &[Table1Row]) -> Vec<(String, f64)> {
    rows.iter()
        .filter(|r| r.variant == "native-f32x8")
        .filter_map(|native| {
            let generic = rows.iter().find(|r| r.shader == native.shader && r.variant == "f32x8")?;
            Some((native.shader.clone(), generic.shading_ms / native.shading_ms.max(1e-12)))
        })
        .collect()
}

/// Prints the table, the averages and the generic-vs-native ratios.
pub fn report(rows: &[Table1Row], opts: &Table1Opts) {
    print_table(rows);
    println!();
    println!(
        "mean speedup over f32 shading of the same packets ({0}×{0}, no shadows, {1} thread(s), median of {2} run(s)):",
        opts.size,
        if opts.threads == 0 { "all".to_string() } else { opts.threads.to_string() },
        opts.runs.max(1)
    );
    println!("  {:<13} {:>10} {:>10} {:>12}", "variant", "shading am", "shading gm", "frame am");
    for (v, am, gm, frame, n) in averages(rows) {
        let note = if n == Surface::NAMES.len() { String::new() } else { format!("  ({n} shaders)") };
        println!("  {v:<13} {am:>9.2}x {gm:>9.2}x {frame:>11.2}x{note}");
    }
    let ratios = generic_vs_native(rows);
    if !ratios.is_empty() {
        println!("generic f32x8 vs native f32x8 shading time (1.00 = equal, below 1.10 = within 10%):");
        for (shader, ratio) in ratios {
            println!("  {shader:<9} {ratio:.3}");
        }
    }
}
