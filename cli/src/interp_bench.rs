//! `anysl bench interp`: points/s of the batched interpreter at batch sizes 1, 16, 256 and
//! 4096 against compiled Rust (`f32` and `f32x8`), each row with its max abs error against the
//! `f64` reference. Shaders are the Table-1 `.sl` files of `shaders/rsl`.

use crate::rslc::SlOptions;
use anysl_core::points::{abs_error_stats, shade_points, shade_points_f64, PointSet, ShadeOut};
use anysl_core::prelude::*;
use anysl_core::PointContext;
use anysl_rsl::back::interp::{release, run_batch, Program};
use anysl_rsl::ir::{Const, Global};
use anysl_rsl::passes::{optimize, PassOptions};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::F32x8;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// One row (JSON schema).
#[derive(Clone, Debug, Serialize)]
pub struct InterpRow {
    /// Shader name.
    pub shader: String,
    /// `interp` or `rust-f32` / `rust-f32x8` (the compiled shader of the same name).
    pub backend: String,
    /// Shading points per interpreter call (1 for compiled rows).
    pub batch: usize,
    /// Median points per second.
    pub points_per_s: f64,
    /// Max abs error over Ci and Oi against the f64 reference.
    pub max_abs_err: f64,
    /// Speedup over `rust-f32` of the same shader.
    pub speedup_vs_rust_f32: f64,
}

/// Settings.
#[derive(Clone, Debug)]
pub struct InterpOpts {
    /// Points per run.
    pub points: usize,
    /// Timed runs (median).
    pub runs: usize,
    /// Only these shaders.
    pub shaders: Vec<String>,
}

/// The folder of the repository's `.sl` shaders.
pub fn rsl_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"))
}

/// Compiles `shaders/rsl/<name>.sl` for the interpreter.
pub fn load_program(name: &str) -> Result<Program, String> {
    let dir = rsl_dir();
    let file = dir.join(format!("{name}.sl"));
    let sl = SlOptions { include: vec![dir.join("include")], define: Vec::new() };
    let c = crate::rslc::compile(&file, &sl)?;
    Program::new(optimize(c.module, &PassOptions::default())).map_err(|e| format!("{}: {e}", file.display()))
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

fn store_out<F: ShadingFloat>(out: &mut ShadeOut<f32>, i: usize, ci: Color<F>, oi: Color<F>) {
    for l in 0..F::LANES {
        if i + l >= out.channels[0].len() {
            break;
        }
        let (c, o) = (ci.lane(l), oi.lane(l));
        for ch in 0..3 {
            out.channels[ch][i + l] = c[ch] as f32;
            out.channels[3 + ch][i + l] = o[ch] as f32;
        }
    }
}

/// Shades `set` with the interpreter in batches of `batch` points (`f32` for batch 1, chunks
/// of `F32x8` otherwise).
fn interp_points(
    prog: &Program,
    values: &[Const],
    lights: &[Light],
    set: &PointSet,
    batch: usize,
    out: &mut ShadeOut<f32>,
) {
    let ci = prog.global_loc(Global::Ci);
    let oi = prog.global_loc(Global::Oi);
    if batch == 1 {
        for i in 0..set.len() {
            let mut ctx = [PointContext::new(set.globals::<f32>(i), lights)];
            let fr = run_batch::<f32, _>(prog, values, &mut ctx, &[true]);
            let c = ci.map_or(Color::zero(), |l| {
                let v = fr.read(l, 0);
                Color::new(v[0], v[1], v[2])
            });
            let o = oi.map_or(ctx[0].globals.Os, |l| {
                let v = fr.read(l, 0);
                Color::new(v[0], v[1], v[2])
            });
            release(fr);
            store_out(out, i, c, o);
        }
        return;
    }
    let chunks = (batch / F32x8::LANES).max(1);
    let mut i = 0;
    while i < set.len() {
        let n = chunks.min((set.len() - i).div_ceil(8));
        let mut ctxs: Vec<_> = (0..n).map(|k| PointContext::new(set.globals::<F32x8>(i + 8 * k), lights)).collect();
        let masks = vec![<F32x8 as ShadingFloat>::Mask::splat(true); n];
        let fr = run_batch::<F32x8, _>(prog, values, &mut ctxs, &masks);
        for k in 0..n {
            let c = ci.map_or(Color::zero(), |l| {
                let v = fr.read(l, k);
                Color::new(v[0], v[1], v[2])
            });
            let o = oi.map_or(ctxs[k].globals.Os, |l| {
                let v = fr.read(l, k);
                Color::new(v[0], v[1], v[2])
            });
            store_out(out, i + 8 * k, c, o);
        }
        release(fr);
        i += 8 * n;
    }
}

/// Runs the benchmark.
pub fn run(opts: &InterpOpts, progress: &indicatif::ProgressBar) -> Result<Vec<InterpRow>, String> {
    let names: Vec<String> = if opts.shaders.is_empty() {
        Surface::NAMES.iter().map(|s| s.to_string()).collect()
    } else {
        opts.shaders.clone()
    };
    let lights = table1_lights();
    // A multiple of 4096 so every batch size divides it.
    let n = opts.points.div_ceil(4096) * 4096;
    let set = PointSet::random(n, 0x5eed_2010);
    let batches = [1usize, 16, 256, 4096];
    progress.set_length((names.len() * (batches.len() + 2)) as u64);
    let mut rows = Vec::new();
    for name in &names {
        let file = if name == "phong" { "plastic" } else { name.as_str() };
        let surface = Surface::by_name(name)
            .ok_or_else(|| format!("--shader {name}: unknown shader (choices: {})", Surface::NAMES.join(", ")))?;
        let prog = load_program(file)?;
        let values: Vec<Const> = prog.module.params.iter().map(|p| p.default.clone()).collect();
        let reference = shade_points_f64::<f64, Surface, Light>(&surface, &lights, &set);
        let time_row = |backend: &str, batch: usize, f: &mut dyn FnMut(&mut ShadeOut<f32>)| {
            progress.set_message(format!("{name} {backend} {batch}"));
            let mut out = ShadeOut::new(set.len());
            f(&mut out);
            let (err, _) = abs_error_stats(&out, &reference);
            let mut times = Vec::new();
            for _ in 0..opts.runs {
                let t = Instant::now();
                f(&mut out);
                times.push(t.elapsed().as_secs_f64());
            }
            progress.inc(1);
            InterpRow {
                shader: name.clone(),
                backend: backend.to_string(),
                batch,
                points_per_s: set.len() as f64 / median(times),
                max_abs_err: err,
                speedup_vs_rust_f32: 0.0,
            }
        };
        let mut shader_rows = vec![
            time_row("rust-f32", 1, &mut |o| shade_points::<f32, Surface, Light>(&surface, &lights, &set, o)),
            time_row("rust-f32x8", 8, &mut |o| shade_points::<F32x8, Surface, Light>(&surface, &lights, &set, o)),
        ];
        for b in batches {
            shader_rows.push(time_row("interp", b, &mut |o| interp_points(&prog, &values, &lights, &set, b, o)));
        }
        let base = shader_rows[0].points_per_s;
        for r in &mut shader_rows {
            r.speedup_vs_rust_f32 = r.points_per_s / base;
        }
        rows.extend(shader_rows);
    }
    Ok(rows)
}

/// Prints the table.
pub fn print_table(rows: &[InterpRow]) {
    println!(
        "{:<10} {:<11} {:>6} {:>14} {:>10} {:>12}",
        "shader", "backend", "batch", "points/s", "speedup", "max_abs_err"
    );
    for r in rows {
        println!(
            "{:<10} {:<11} {:>6} {:>14.3e} {:>9.3}x {:>12.2e}",
            r.shader, r.backend, r.batch, r.points_per_s, r.speedup_vs_rust_f32, r.max_abs_err
        );
    }
}
