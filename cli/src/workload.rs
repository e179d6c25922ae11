//! `anysl bench workload`: the shared shading workload (`shaders/assets/workload_ref/shading_workload.md`)
//! — its four shaders over the 183 020 hit points
//! of the 512×512 sphere image, one row per shader × thread count × system, printed as the
//! document's §9 TSV.
//!
//! Protocol (§6): a *shading call* computes Ci for every hit point into a buffer (inputs
//! already in memory in SoA form; scene setup and the scatter into the image are not timed,
//! thread fork/join is). Per shader and thread count, each system's first call is timed as
//! `first_call_ms` and serves as the warm-up; then the systems take turns in [`BLOCKS`]
//! blocks, each system making a block of consecutive calls (`runs` in all), and
//! `Mpts_per_s = n_hit / median / 1e6`. Consecutive calls find their inputs warm in the
//! caches, as a tight timing loop does (the peers' harness times each system that way); the
//! turns spread drift on a shared machine over every system alike, so ratios within one run
//! are comparable. `max_abs_err` is taken over the 512×512×3 image (black background) against
//! the reference array of the shader.
//!
//! Systems: the generic anysl shaders instantiated ahead of time (`anysl-f32` … `anysl-dual-f32x8`;
//! `anysl-f32x8` shades four packets of that width per loop step and `anysl-f32x16` two, `Pair`),
//! and their `.sl` twins (`shaders/rsl/workload/`, embedded in `anysl-shaders`) through the
//! batched interpreter (`anysl-interp`) and, with the `jit` feature, the LLVM JIT
//! (`anysl-jit-f32`, `-x8`, `-x16`). The `.sl` systems compile from source (parse → check → IR,
//! then for the JIT LLVM IR → machine code) inside their first call of each shader and thread
//! count, so `first_call_ms` includes compilation with empty caches, as §6 asks. A new system
//! implements [`System`] and is appended in [`systems`].

use anysl_ad::Dual;
use anysl_core::{LightData, Mask, Shader, ShadingFloat};
use anysl_rsl::back::interp::{InterpShader, Program};
use anysl_rsl::ir::Module;
use anysl_rsl::passes::{optimize, PassOptions};
use anysl_rsl::{compile_source, CompileOptions};
use anysl_shaders::workload::{self, reference, WorkloadScene, WorkloadShader};
use anysl_simd::{F32x16, F32x4, F32x8, Pair};
use indicatif::ProgressBar;
use rayon::ThreadPool;
use serde::Serialize;
use std::collections::hash_map::{Entry, HashMap};
use std::sync::{Mutex, PoisonError};
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
    /// The §3 lights as data (made once per run; every system measured shades with an
    /// `f32`-based float type, for which the data is the light shaders to the bit).
    pub lights: &'a [LightData],
    /// The worker pool (`None`: one thread, the calling one).
    pub pool: Option<&'a ThreadPool>,
}

/// A shading system measured on the workload.
pub trait System {
    /// The `system` column, e.g. `anysl-f32x8`.
    fn name(&self) -> &str;
    /// One shading call: Ci (r, g, b) of every input point into `out` (each
    /// `scene.padded_len()` long). A system that compiles does it lazily inside its first call
    /// for a shader and thread count (and caches the result), so that every row's
    /// `first_call_ms` includes compilation.
    fn shade(&mut self, env: &CallEnv<'_>, shader: &WorkloadShader, out: &mut [Vec<f32>; 3]) -> Result<(), String>;
}

/// Turns each system takes per shader and thread count (see the module docs).
const BLOCKS: usize = 3;

/// Points per parallel work item (a multiple of every SIMD width and batch): small enough that
/// the two threads finish a call within a few microseconds of each other.
const CHUNK: usize = 1024;

impl CallEnv<'_> {
    /// Threads of a call: the calling one and the pool's workers.
    fn threads(&self) -> usize {
        self.pool.map_or(1, |p| p.current_num_threads() + 1)
    }

    /// Runs `shade(start, out)` over `out` — on the calling thread in one piece, or split into
    /// [`CHUNK`]-point work items. The calling thread claims items from the front and the
    /// pool's workers from the back until they meet: each thread shades about the same points
    /// from call to call, so its part of the inputs and outputs is still in its own caches
    /// from the last call (claimed in one order, the items a thread gets change with every
    /// call, and the data moves between the cores' caches). The caller shades too instead of
    /// sleeping while the pool works: one thread is woken per call, not two, which on a call
    /// of a fraction of a millisecond is a visible part of the two-thread time.
    fn for_chunks(&self, out: &mut [Vec<f32>; 3], shade: impl Fn(usize, [&mut [f32]; 3]) + Sync) {
        let [r, g, b] = out;
        let Some(pool) = self.pool else {
            return shade(0, [r, g, b]);
        };
        type Item<'o> = Mutex<Option<(usize, [&'o mut [f32]; 3])>>;
        let items: Vec<Item<'_>> = r
            .chunks_mut(CHUNK)
            .zip(g.chunks_mut(CHUNK))
            .zip(b.chunks_mut(CHUNK))
            .enumerate()
            .map(|(k, ((r, g), b))| Mutex::new(Some((k * CHUNK, [r, g, b]))))
            .collect();
        // The items not yet claimed: `front .. back`.
        let left = Mutex::new((0, items.len()));
        let work = |from_front: bool| loop {
            let k = {
                let mut l = left.lock().unwrap_or_else(PoisonError::into_inner);
                if l.0 >= l.1 {
                    break;
                }
                if from_front {
                    l.0 += 1;
                    l.0 - 1
                } else {
                    l.1 -= 1;
                    l.1
                }
            };
            if let Some((start, out)) = items[k].lock().unwrap_or_else(PoisonError::into_inner).take() {
                shade(start, out);
            }
        };
        pool.in_place_scope(|s| {
            for _ in 0..pool.current_num_threads() {
                s.spawn(|_| work(false));
            }
            work(true);
        });
    }
}

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
        let (scene, lights) = (env.scene, env.lights);
        env.for_chunks(out, |start, out| scene.shade::<F, LightData>(shader, lights, start, out));
        Ok(())
    }
}

fn generic<F: ShadingFloat>(name: &'static str) -> Box<dyn System> {
    Box::new(Generic::<F> { name, _f: core::marker::PhantomData })
}

/// Parses, checks and lowers the `.sl` twin of `shader` from its embedded source.
fn sl_module(shader: &WorkloadShader) -> Result<Module, String> {
    compile_source(shader.sl_file_name(), shader.sl_source(), &CompileOptions::default())
        .map(|c| c.module)
        .map_err(|e| format!("{}: {e}", shader.sl_file_name()))
}

/// Gives an `.sl` shader the parameter values of the workload shader it stands for (the
/// defaults agree; this keeps them agreeing for any instance).
fn copy_params(from: &WorkloadShader, to: &mut impl Shader) -> Result<(), String> {
    for p in from.meta().params {
        let v = from.param(&p.name).ok_or_else(|| format!("{}: no parameter {}", from.name(), p.name))?;
        to.set_param(&p.name, &v).map_err(|e| format!("{}: {e}", from.sl_file_name()))?;
    }
    Ok(())
}

/// The interpreter's float type: on the workload, `F32x16` chunks run 1.5–1.9× faster than
/// `F32x8` (and 6–8× faster than `f32`), at any batch size from 64 to 1024 points.
type InterpFloat = F32x16;
/// Chunks of [`InterpFloat`] per interpreter call: 16 × 16 = 256 points, where the op dispatch
/// is amortized and the register file still fits the caches (`anysl bench interp`).
const INTERP_CHUNKS: usize = 16;

/// The `.sl` shaders through the batched interpreter, compiled on the first call of each
/// shader and thread count.
#[derive(Default)]
struct Interp {
    shaders: HashMap<(&'static str, usize), InterpShader>,
}

impl Interp {
    fn compile(shader: &WorkloadShader) -> Result<InterpShader, String> {
        let m = optimize(sl_module(shader)?, &PassOptions::default());
        let program = Program::new(m).map_err(|e| format!("{}: {e}", shader.sl_file_name()))?;
        let mut interp = InterpShader::new(std::sync::Arc::new(program));
        copy_params(shader, &mut interp)?;
        Ok(interp)
    }
}

impl System for Interp {
    fn name(&self) -> &str {
        "anysl-interp"
    }
    fn shade(&mut self, env: &CallEnv<'_>, shader: &WorkloadShader, out: &mut [Vec<f32>; 3]) -> Result<(), String> {
        let interp: &InterpShader = match self.shaders.entry((shader.name(), env.threads())) {
            Entry::Occupied(e) => e.into_mut(),
            Entry::Vacant(e) => e.insert(Self::compile(shader)?),
        };
        let (scene, lights) = (env.scene, env.lights);
        let masks = [<InterpFloat as ShadingFloat>::Mask::splat(true); INTERP_CHUNKS];
        env.for_chunks(out, |start, out| {
            scene.shade_batched::<InterpFloat, _>(lights, start, out, INTERP_CHUNKS, |ctxs, outs| {
                interp.shade_batch(ctxs, &masks, outs)
            });
        });
        Ok(())
    }
}

/// The `.sl` shaders through the LLVM JIT for one variant, compiled from source on the first
/// call of each shader and thread count.
#[cfg(feature = "jit")]
struct Jit {
    name: &'static str,
    variant: anysl_jit::Variant,
    shaders: HashMap<(&'static str, usize), anysl_jit::JitShader>,
}

#[cfg(feature = "jit")]
impl Jit {
    fn boxed(name: &'static str, variant: anysl_jit::Variant) -> Box<dyn System> {
        Box::new(Self { name, variant, shaders: HashMap::new() })
    }

    fn compile(shader: &WorkloadShader) -> Result<anysl_jit::JitShader, String> {
        let mut jit = anysl_jit::JitShader::new(sl_module(shader)?, anysl_jit::JitOptions::default())
            .map_err(|e| format!("{}: {e}", shader.sl_file_name()))?;
        copy_params(shader, &mut jit)?;
        // The machine code is the points entry's, compiled on the first call (`jit_points`),
        // whose errors are the row's; the per-packet variant is compiled only where a float
        // type has no points entry.
        Ok(jit)
    }
}

#[cfg(feature = "jit")]
impl System for Jit {
    fn name(&self) -> &str {
        self.name
    }
    fn shade(&mut self, env: &CallEnv<'_>, shader: &WorkloadShader, out: &mut [Vec<f32>; 3]) -> Result<(), String> {
        use anysl_jit::Variant;
        let jit: &anysl_jit::JitShader = match self.shaders.entry((shader.name(), env.threads())) {
            Entry::Occupied(e) => e.into_mut(),
            Entry::Vacant(e) => e.insert(Self::compile(shader)?),
        };
        let (scene, lights) = (env.scene, env.lights);
        // The points entry is compiled on the first chunk; an error is the row's.
        let fail = Mutex::new(None);
        let run = |r: Result<(), String>| {
            if let Err(e) = r {
                *fail.lock().unwrap_or_else(PoisonError::into_inner) = Some(e);
            }
        };
        macro_rules! points {
            ($F:ty) => {
                env.for_chunks(out, |s, [r, g, b]| run(jit_points::<$F>(scene, jit, lights, s, &mut [r, g, b])))
            };
        }
        match self.variant {
            Variant::F32 => points!(f32),
            Variant::X8 => points!(F32x8),
            Variant::X16 => points!(F32x16),
            Variant::X8x4 => points!(Pair<Pair<F32x8>>),
            Variant::X16x2 => points!(Pair<F32x16>),
            v => return Err(format!("{}: variant {v:?} is not measured", self.name)),
        }
        fail.into_inner().unwrap_or_else(PoisonError::into_inner).map_or(Ok(()), Err)
    }
}

/// Shades points `start .. start + out[0].len()` of the workload with the JIT's compiled loop
/// over the point set ([`anysl_jit::JitShader::shade_points`]: `P`, `N` = `Ng` and `I` read
/// from the scene's arrays, the shader inlined into the loop), or packet by packet where the
/// float type has no such loop.
#[cfg(feature = "jit")]
fn jit_points<F: ShadingFloat>(
    scene: &WorkloadScene,
    jit: &anysl_jit::JitShader,
    lights: &[LightData],
    start: usize,
    out: &mut [&mut [f32]; 3],
) -> Result<(), String> {
    use anysl_rsl::ir::Global;
    let len = out[0].len();
    let mut ctx = anysl_core::PointContext::new(scene.globals::<F>(start), lights);
    let [p, n, i] = scene.varying_f32(start, len);
    let varying: [(Global, &[&[f32]]); 4] = [(Global::P, &p), (Global::N, &n), (Global::Ng, &n), (Global::I, &i)];
    if !jit.shade_points::<F, _>(&mut ctx, &varying, out).map_err(|e| e.to_string())? {
        let [r, g, b] = out;
        scene.shade_surface::<F, _, _>(jit, lights, start, [&mut **r, &mut **g, &mut **b]);
    }
    Ok(())
}

/// The systems measured, in table order.
pub fn systems() -> Vec<Box<dyn System>> {
    #[allow(unused_mut)]
    let mut v: Vec<Box<dyn System>> = vec![
        generic::<f32>("anysl-f32"),
        generic::<F32x4>("anysl-f32x4"),
        // Several packets per step of the loop (`Pair`): 8- and 16-lane instructions with
        // independent dependency chains in flight, so the long rsqrt → pow chains of the light
        // loop overlap. Four 8-lane packets, two 16-lane ones: the counts that measured
        // fastest on the mean of the four shaders (docs/benchmarks.md).
        generic::<Pair<Pair<F32x8>>>("anysl-f32x8"),
        generic::<Pair<F32x16>>("anysl-f32x16"),
        generic::<Dual<F32x8>>("anysl-dual-f32x8"),
        Box::new(Interp::default()),
    ];
    #[cfg(feature = "jit")]
    v.extend([
        Jit::boxed("anysl-jit-f32", anysl_jit::Variant::F32),
        // The same packet shapes as the compiled rows above: the JIT code shades four 8-lane
        // (two 16-lane) packets per call, so it is compared with `anysl-f32x8`/`-x16` like for like.
        Jit::boxed("anysl-jit-x8", anysl_jit::Variant::X8x4),
        Jit::boxed("anysl-jit-x16", anysl_jit::Variant::X16x2),
    ]);
    v
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
    let lights = workload::light_data();
    let references: Vec<Vec<f32>> =
        shaders.iter().map(|s| reference::load_reference(s.name())).collect::<Result<_, _>>()?;
    let n = scene.padded_len();
    progress.set_length((opts.threads.len() * shaders.len() * systems.len() * (opts.runs + 1)) as u64);

    let mut rows = Vec::new();
    for &threads in &opts.threads {
        let pool = if threads > 1 {
            Some(
                // The calling thread is the other one (`CallEnv::for_chunks`).
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads - 1)
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
            for block in 0..BLOCKS {
                let calls = opts.runs / BLOCKS + usize::from(block < opts.runs % BLOCKS);
                for (k, sys) in systems.iter_mut().enumerate() {
                    // One call more than timed: the first of a block reloads the caches
                    // another system's turn has filled.
                    for call in 0..=calls {
                        let t = Instant::now();
                        sys.shade(&env, shader, &mut outs[k])?;
                        if call > 0 {
                            times[k].push(t.elapsed().as_secs_f64());
                            progress.inc(1);
                        }
                    }
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
