//! `anysl bench workload`: the shared shading workload (`shared/bench/shading_workload.md`,
//! copied to `shaders/assets/workload_ref/`) — its four shaders over the 183 020 hit points
//! of the 512×512 sphere image, one row per shader × thread count × system, printed as the
//! document's §9 TSV.
//!
//! Protocol (§6): a *shading call* computes Ci for every hit point into a buffer (inputs
//! already in memory in SoA form; scene setup and the scatter into the image are not timed,
//! thread fork/join is). Per shader and thread count, each system's first call is timed as
//! `first_call_ms` and serves as the warm-up; then every system is called once per round,
//! round-robin, for `runs` rounds, and `Mpts_per_s = n_hit / median / 1e6` — interleaving
//! the systems lets drift on a shared machine hit them alike, so ratios within one run are
//! comparable. `max_abs_err` is taken over the 512×512×3 image (black background) against
//! the reference array of the shader.
//!
//! A new system (interpreter, JIT, …) implements [`System`] and is appended in [`systems`].

use anysl_ad::Dual;
use anysl_core::ShadingFloat;
use anysl_shaders::workload::{self, reference, WorkloadScene, WorkloadShader};
use anysl_shaders::Light;
use anysl_simd::{F32x16, F32x4, F32x8};
use indicatif::ProgressBar;
use rayon::prelude::*;
use rayon::ThreadPool;
use serde::Serialize;
use std::time::Instant;

/// One row of the table (the JSON schema; the TSV has the first six fields).
#[derive(Clone, Debug, Serialize)]
pub struct WorkloadRow {
    /// System and variant, e.g. `anysl-f32x8`.
    pub system: String,
    /// `plastic`, `checker`, `wood` or `granite`.
    pub shader: String,
    /// Worker threads of a shading call.
    pub threads: usize,
    /// Millions of shading points per second (median call).
    pub mpts_per_s: f64,
    /// Wall time of the first call of this system, shader and thread count in the process.
    pub first_call_ms: f64,
    /// Max abs error of the image against the reference.
    pub max_abs_err: f64,
    /// Pixels with an error above 1e-3 (should be 0).
    pub pixels_over_1e3: usize,
    /// Timed calls after the first (the median is over these).
    pub runs: usize,
}

/// Benchmark settings.
#[derive(Clone, Debug)]
pub struct WorkloadOpts {
    /// Thread counts to measure (each its own block of rows).
    pub threads: Vec<usize>,
    /// Timed calls per row after the first.
    pub runs: usize,
    /// Only these shaders (all when empty).
    pub shaders: Vec<String>,
    /// Only these systems (all when empty).
    pub systems: Vec<String>,
}

/// Everything a shading call may use.
pub struct CallEnv<'a> {
    /// The inputs.
    pub scene: &'a WorkloadScene,
    /// The §3 lights.
    pub lights: &'a [Light],
    /// The worker pool (`None`: one thread, the calling one).
    pub pool: Option<&'a ThreadPool>,
}

/// A shading system measured on the workload.
pub trait System {
    /// The `system` column, e.g. `anysl-f32x8`.
    fn name(&self) -> &str;
    /// One shading call: Ci (r, g, b) of every input point into `out` (each
    /// `scene.padded_len()` long). A system that compiles does it lazily inside its first call
    /// for a shader (and caches the result), so that `first_call_ms` includes compilation.
    fn shade(&mut self, env: &CallEnv<'_>, shader: &WorkloadShader, out: &mut [Vec<f32>; 3]) -> Result<(), String>;
}

/// Points per parallel work item (a multiple of every SIMD width).
const CHUNK: usize = 4096;

/// A generic anysl shader instantiated with `F` (ahead-of-time code).
struct Generic<F> {
    name: &'static str,
    _f: core::marker::PhantomData<F>,
}

impl<F: ShadingFloat> System for Generic<F> {
    fn name(&self) -> &str {
        self.name
    }
    fn shade(&mut self, env: &CallEnv<'_>, shader: &WorkloadShader, out: &mut [Vec<f32>; 3]) -> Result<(), String> {
        let [r, g, b] = out;
        let (scene, lights) = (env.scene, env.lights);
        match env.pool {
            None => scene.shade::<F>(shader, lights, 0, [r, g, b]),
            Some(pool) => pool.install(|| {
                r.par_chunks_mut(CHUNK)
                    .zip(g.par_chunks_mut(CHUNK))
                    .zip(b.par_chunks_mut(CHUNK))
                    .enumerate()
                    .for_each(|(k, ((r, g), b))| scene.shade::<F>(shader, lights, k * CHUNK, [r, g, b]));
            }),
        }
        Ok(())
    }
}

fn generic<F: ShadingFloat>(name: &'static str) -> Box<dyn System> {
    Box::new(Generic::<F> { name, _f: core::marker::PhantomData })
}

/// The systems measured, in table order.
pub fn systems() -> Vec<Box<dyn System>> {
    // Other back ends (anysl-interp, anysl-jit-f32, anysl-jit-x8, anysl-jit-x16) append here.
    vec![
        generic::<f32>("anysl-f32"),
        generic::<F32x4>("anysl-f32x4"),
        generic::<F32x8>("anysl-f32x8"),
        generic::<F32x16>("anysl-f32x16"),
        generic::<Dual<F32x8>>("anysl-dual-f32x8"),
    ]
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).expect("finite times"));
    v[v.len() / 2]
}

/// Runs the benchmark and returns its rows.
pub fn run(opts: &WorkloadOpts, progress: &ProgressBar) -> Result<Vec<WorkloadRow>, String> {
    let shaders: Vec<WorkloadShader> = if opts.shaders.is_empty() {
        WorkloadShader::all()
    } else {
        opts.shaders
            .iter()
            .map(|n| {
                WorkloadShader::by_name(n).ok_or_else(|| {
                    format!("unknown workload shader '{n}' (choices: {})", WorkloadShader::NAMES.join(", "))
                })
            })
            .collect::<Result<_, _>>()?
    };
    let mut systems = systems();
    let known: Vec<String> = systems.iter().map(|s| s.name().to_string()).collect();
    if let Some(bad) = opts.systems.iter().find(|s| !known.contains(s)) {
        return Err(format!("unknown system '{bad}' (choices: {})", known.join(", ")));
    }
    systems.retain(|s| opts.systems.is_empty() || opts.systems.iter().any(|w| w == s.name()));
    if let Some(&bad) = opts.threads.iter().find(|&&t| t == 0) {
        return Err(format!("--threads {bad}: need at least 1"));
    }

    progress.set_message("scene setup");
    let scene = WorkloadScene::new();
    let lights = workload::lights();
    let references: Vec<Vec<f32>> =
        shaders.iter().map(|s| reference::load_reference(s.name())).collect::<Result<_, _>>()?;
    let n = scene.padded_len();
    progress.set_length((opts.threads.len() * shaders.len() * systems.len() * (opts.runs + 1)) as u64);

    let mut rows = Vec::new();
    for &threads in &opts.threads {
        let pool = if threads > 1 {
            Some(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .map_err(|e| format!("cannot start {threads} threads: {e}"))?,
            )
        } else {
            None
        };
        let env = CallEnv { scene: &scene, lights: &lights, pool: pool.as_ref() };
        for (shader, reference) in shaders.iter().zip(&references) {
            progress.set_message(format!("{} × {threads} thread(s)", shader.name()));
            let mut outs: Vec<[Vec<f32>; 3]> =
                systems.iter().map(|_| [vec![0.0; n], vec![0.0; n], vec![0.0; n]]).collect();
            let mut first = vec![0.0; systems.len()];
            let mut times = vec![Vec::with_capacity(opts.runs); systems.len()];
            // The first call of each system: first_call_ms, and the warm-up.
            for (k, sys) in systems.iter_mut().enumerate() {
                let t = Instant::now();
                sys.shade(&env, shader, &mut outs[k])?;
                first[k] = t.elapsed().as_secs_f64();
                progress.inc(1);
            }
            for _ in 0..opts.runs {
                for (k, sys) in systems.iter_mut().enumerate() {
                    let t = Instant::now();
                    sys.shade(&env, shader, &mut outs[k])?;
                    times[k].push(t.elapsed().as_secs_f64());
                    progress.inc(1);
                }
            }
            for (k, sys) in systems.iter().enumerate() {
                let secs = if times[k].is_empty() { first[k] } else { median(std::mem::take(&mut times[k])) };
                let err = reference::image_error(&scene.to_image(&outs[k]), reference);
                rows.push(WorkloadRow {
                    system: sys.name().to_string(),
                    shader: shader.name().to_string(),
                    threads,
                    mpts_per_s: scene.n_hit() as f64 / secs / 1e6,
                    first_call_ms: first[k] * 1e3,
                    max_abs_err: err.max_abs_err,
                    pixels_over_1e3: err.pixels_over_1e3,
                    runs: opts.runs,
                });
            }
        }
    }
    Ok(rows)
}

/// Prints the §9 TSV: header, then one line per row.
pub fn print_tsv(rows: &[WorkloadRow]) {
    println!("system\tshader\tthreads\tMpts_per_s\tfirst_call_ms\tmax_abs_err");
    for r in rows {
        println!(
            "{}\t{}\t{}\t{:.2}\t{:.1}\t{}",
            r.system,
            r.shader,
            r.threads,
            r.mpts_per_s,
            r.first_call_ms,
            three_significant(r.max_abs_err)
        );
    }
}

/// `x` with three significant digits (`2.38e-6`, `0`, `inf`).
fn three_significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:.2e}")
    }
}
