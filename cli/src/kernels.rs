//! `anysl bench kernels`: shading points per second for every shader × instantiation on one
//! fixed random point set, single-threaded, each row with its error against f64.

use anysl_ad::{Dual, Interval};
use anysl_core::points::{abs_error_stats, shade_points, shade_points_f64, PointSet, ShadeOut};
use anysl_core::Shader;
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::{F32x16, F32x4, F32x8};
use serde::Serialize;
use std::time::Instant;

/// One row of the kernel benchmark (the JSON schema other tools read).
#[derive(Clone, Debug, Serialize)]
pub struct KernelRow {
    /// Shader name.
    pub shader: String,
    /// Instantiation: f32, f64, f32x4, f32x8, f32x16, dual-f32, dual-f32x8, interval-f32,
    /// native-f32x8.
    pub instantiation: String,
    /// Median shading points per second.
    pub points_per_s: f64,
    /// Max abs error over all points and channels (Ci, Oi) against the reference.
    pub max_abs_err: f64,
    /// 99.9th percentile of the abs error.
    pub p999_abs_err: f64,
    /// Speedup over the `f32` row of the same shader, same run.
    pub speedup: f64,
    /// What the error is measured against: `f64`, or `dual-f64` for dual rows of shaders that
    /// use derivatives (filtered results differ from point samples by design).
    pub reference: String,
}

/// Benchmark settings.
#[derive(Clone, Debug)]
pub struct KernelOpts {
    /// Shading points per run.
    pub points: usize,
    /// Timed runs per row (median reported).
    pub runs: usize,
    /// Shaders to run (all when empty).
    pub shaders: Vec<String>,
    /// Instantiations to run (all when empty; `f32` always runs as the speedup base).
    pub instantiations: Vec<String>,
}

type Runner = fn(&Surface, &[Light], &PointSet, &mut ShadeOut<f32>);

/// The instantiations measured, in table order.
pub fn instantiations() -> Vec<(&'static str, Runner)> {
    vec![
        ("f32", shade_points::<f32, Surface, Light> as Runner),
        ("f64", shade_points::<f64, Surface, Light>),
        ("f32x4", shade_points::<F32x4, Surface, Light>),
        ("f32x8", shade_points::<F32x8, Surface, Light>),
        ("f32x16", shade_points::<F32x16, Surface, Light>),
        ("dual-f32", shade_points::<Dual<f32>, Surface, Light>),
        ("dual-f32x8", shade_points::<Dual<F32x8>, Surface, Light>),
        ("interval-f32", shade_points::<Interval<f32>, Surface, Light>),
    ]
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).expect("finite times"));
    v[v.len() / 2]
}

/// Runs the benchmark and returns its rows.
pub fn run(opts: &KernelOpts, progress: &indicatif::ProgressBar) -> Result<Vec<KernelRow>, String> {
    let names: Vec<String> = if opts.shaders.is_empty() {
        Surface::NAMES.iter().map(|s| s.to_string()).collect()
    } else {
        opts.shaders.clone()
    };
    let lights = table1_lights();
    let set = PointSet::random(opts.points, 0x5eed_2010);
    let all = instantiations();
    let known: Vec<&str> = all.iter().map(|(n, _)| *n).chain(["native-f32x8"]).collect();
    for want in &opts.instantiations {
        if !known.contains(&want.as_str()) {
            return Err(format!("unknown instantiation '{want}' (choices: {})", known.join(", ")));
        }
    }
    let wanted = |n: &str| n == "f32" || opts.instantiations.is_empty() || opts.instantiations.iter().any(|w| w == n);
    let insts: Vec<_> = all.into_iter().filter(|(n, _)| wanted(n)).collect();
    progress.set_length((names.len() * (insts.len() + 1)) as u64);
    let mut rows = Vec::new();
    for name in &names {
        let surface = Surface::by_name(name)
            .ok_or_else(|| format!("unknown shader '{name}' (choices: {})", Surface::NAMES.join(", ")))?;
        let derivs = surface.meta().uses_derivatives;
        let reference = shade_points_f64::<f64, _, _>(&surface, &lights, &set);
        let dual_reference =
            if derivs { Some(shade_points_f64::<Dual<f64>, _, _>(&surface, &lights, &set)) } else { None };
        let mut f32_rate = None;
        let mut push = |inst: &str, rate: f64, out: &ShadeOut<f32>, rows: &mut Vec<KernelRow>| {
            let (refname, r) = match (&dual_reference, inst.starts_with("dual")) {
                (Some(d), true) => ("dual-f64", d),
                _ => ("f64", &reference),
            };
            let (max, p999) = abs_error_stats(out, r);
            if inst == "f32" {
                f32_rate = Some(rate);
            }
            rows.push(KernelRow {
                shader: name.clone(),
                instantiation: inst.to_string(),
                points_per_s: rate,
                max_abs_err: max,
                p999_abs_err: p999,
                speedup: rate / f32_rate.unwrap_or(rate),
                reference: refname.to_string(),
            });
        };
        // Every instantiation of this shader is timed round-robin (one call each per round,
        // median over the rounds), so drift of the shared machine hits all rows alike and the
        // speedups of one run stay comparable.
        let mut runners: Vec<(&str, Runner)> = insts.iter().map(|(n, r)| (*n, *r)).collect();
        if let Some(native) = crate::native::runner(&surface).filter(|_| wanted("native-f32x8")) {
            runners.push(("native-f32x8", native));
        }
        let mut outs: Vec<ShadeOut<f32>> = runners.iter().map(|_| ShadeOut::<f32>::new(set.len())).collect();
        let mut times: Vec<Vec<f64>> = vec![Vec::new(); runners.len()];
        progress.set_message(name.to_string());
        for round in 0..=opts.runs.max(1) {
            for (k, (_, runner)) in runners.iter().enumerate() {
                let t = Instant::now();
                runner(&surface, &lights, &set, &mut outs[k]);
                // Round 0 is the warm-up.
                if round > 0 {
                    times[k].push(t.elapsed().as_secs_f64());
                }
            }
        }
        for (k, (inst, _)) in runners.iter().enumerate() {
            let secs = median(std::mem::take(&mut times[k]));
            push(inst, set.len() as f64 / secs, &outs[k], &mut rows);
            progress.inc(1);
        }
        progress.inc(1);
    }
    Ok(rows)
}

/// Prints rows as an aligned table.
pub fn print_table(rows: &[KernelRow]) {
    println!(
        "{:<10} {:<13} {:>12} {:>8} {:>11} {:>11}  {}",
        "shader", "instantiation", "Mpts/s", "speedup", "max_err", "p99.9_err", "reference"
    );
    for r in rows {
        println!(
            "{:<10} {:<13} {:>12.2} {:>7.2}x {:>11.2e} {:>11.2e}  {}",
            r.shader,
            r.instantiation,
            r.points_per_s / 1e6,
            r.speedup,
            r.max_abs_err,
            r.p999_abs_err,
            r.reference
        );
    }
}

/// Mean speedup per instantiation over the shaders in `rows`: `(name, arithmetic, geometric)`.
pub fn summary(rows: &[KernelRow]) -> Vec<(String, f64, f64)> {
    let mut names: Vec<String> = Vec::new();
    for r in rows {
        if !names.contains(&r.instantiation) {
            names.push(r.instantiation.clone());
        }
    }
    names
        .into_iter()
        .map(|inst| {
            let sp: Vec<f64> = rows.iter().filter(|r| r.instantiation == inst).map(|r| r.speedup).collect();
            let am = sp.iter().sum::<f64>() / sp.len() as f64;
            let gm = (sp.iter().map(|s| s.ln()).sum::<f64>() / sp.len() as f64).exp();
            (inst, am, gm)
        })
        .collect()
}
