//! `anysl jit check` (JIT against the monomorphized build) and `anysl bench jit`.

use anysl_ad::Dual;
use anysl_core::points::{abs_error_stats, shade_points, shade_points_f64, PointSet, ShadeOut};
use anysl_core::prelude::*;
use anysl_core::shader::{ParamError, ParamValue, ShaderMeta};
use anysl_jit::check::{StageAsSurface, ABS_FLOOR, MAX_ULPS};
use anysl_jit::{compile_with, ir_passes, CompileStats, JitOptions, JitShader, Variant};
use anysl_rsl::back::interp::{InterpShader, Program};
use anysl_rsl::ir::ShaderKind;
use anysl_rsl::CompileOptions;
use anysl_scene::surface::{SceneSurface, Volumes};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::{F32x16, F32x4, F32x8};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// The folder of the repository's `.sl` shaders.
pub fn rsl_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"))
}

/// The conformance suite.
pub fn conformance_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/rsl/conformance"))
}

fn include_dirs(file: &Path) -> Vec<PathBuf> {
    let mut v = vec![rsl_dir().join("include")];
    if let Some(p) = file.parent() {
        v.push(p.join("include"));
    }
    v
}

/// The hand-written generic Rust shader for an `.sl` file, when there is one (`plastic` is
/// the Table-1 "phong").
pub fn aot_for(stem: &str) -> Option<Surface> {
    Surface::by_name(if stem == "plastic" { "phong" } else { stem })
}

/// Result of one comparison.
#[derive(Clone, Debug, Serialize)]
pub struct CheckRow {
    /// File stem.
    pub shader: String,
    /// `jit-f32 vs f32`, ….
    pub pair: String,
    /// The monomorphized side: `aot` (hand-written generic Rust) or `interp`.
    pub oracle: String,
    /// Max ulps over all outputs.
    pub max_ulps: u64,
    /// Max abs difference.
    pub max_abs: f64,
    /// Outputs beyond the bound.
    pub mismatches: usize,
    /// Compilation error or note.
    pub note: String,
}

/// Checks one `.sl` file: JIT f32 / x8 / dual-f32 against the monomorphized shader at the
/// same type on `n` random points.
pub fn check_file(file: &Path, n: usize) -> Vec<CheckRow> {
    let stem = file.file_stem().map(|s| s.to_string_lossy().to_string()).unwrap_or_default();
    let row = |pair: &str, oracle: &str, note: String| CheckRow {
        shader: stem.clone(),
        pair: pair.into(),
        oracle: oracle.into(),
        max_ulps: 0,
        max_abs: 0.0,
        mismatches: 0,
        note,
    };
    let compiled =
        match anysl_rsl::compile_file(file, &CompileOptions { include_dirs: include_dirs(file), ..Default::default() })
        {
            Ok(c) => c,
            Err(e) => {
                return vec![row("-", "-", format!("compile error: {}", e.to_string().lines().next().unwrap_or("")))]
            }
        };
    let kind = compiled.module.kind;
    if kind == ShaderKind::Light {
        return vec![row("-", "-", "skipped: light shader".to_string())];
    }
    let jit = match JitShader::new(compiled.module, JitOptions::default()) {
        Ok(j) => j,
        Err(e) => return vec![row("-", "-", e.to_string())],
    };
    // Displacement, volume and imager shaders through their own entries, as surfaces.
    let stage = (kind != ShaderKind::Surface)
        .then(|| (StageAsSurface { shader: jit.clone(), kind }, StageAsSurface { shader: jit.interp().clone(), kind }));
    let set = PointSet::random(n, 0x5eed_0005);
    let lights = table1_lights();
    let aot = if stage.is_none() { aot_for(&stem) } else { None };
    let oracle_name = if aot.is_some() { "aot" } else { "interp" };
    let mut rows = Vec::new();
    macro_rules! pair {
        ($F:ty, $v:expr, $label:expr) => {{
            let compiled = match &stage {
                Some((j, _)) => j.shader.variant($v),
                None => jit.variant($v),
            };
            match compiled {
                Err(e) => rows.push(row($label, oracle_name, e)),
                Ok(_) => {
                    let mut a = ShadeOut::new(set.len());
                    let mut b = ShadeOut::new(set.len());
                    match (&stage, &aot) {
                        (Some((j, i)), _) => {
                            shade_points::<$F, _, Light>(j, &lights, &set, &mut a);
                            shade_points::<$F, _, Light>(i, &lights, &set, &mut b);
                        }
                        (None, Some(s)) => {
                            shade_points::<$F, JitShader, Light>(&jit, &lights, &set, &mut a);
                            shade_points::<$F, Surface, Light>(s, &lights, &set, &mut b);
                        }
                        (None, None) => {
                            shade_points::<$F, JitShader, Light>(&jit, &lights, &set, &mut a);
                            shade_points::<$F, InterpShader, Light>(jit.interp(), &lights, &set, &mut b);
                        }
                    }
                    let anysl_jit::check::Comparison { max_ulps: mu, max_abs: ma, mismatches: bad } =
                        anysl_jit::check::compare(&a, &b);
                    let mut r = row($label, oracle_name, String::new());
                    r.max_ulps = mu;
                    r.max_abs = ma;
                    r.mismatches = bad;
                    rows.push(r);
                }
            }
        }};
    }
    pair!(f32, Variant::F32, "jit-f32 vs f32");
    pair!(F32x8, Variant::X8, "jit-x8 vs f32x8");
    pair!(Dual<f32>, Variant::DualF32, "jit-dual vs dual-f32");
    rows
}

/// The default files: every shader in `shaders/rsl` (with the standard volumes and imager),
/// `scenes/`, the conformance suite and the volume and imager programs of
/// `tests/data/rsl/stages`.
pub fn default_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    let scenes = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes"));
    let stages = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/rsl/stages"));
    let standard = rsl_dir().join("standard");
    let dirs = [rsl_dir(), standard.clone(), standard.join("volume"), standard.join("imager"), scenes];
    for dir in dirs.into_iter().chain([conformance_dir(), stages]) {
        if let Ok(rd) = std::fs::read_dir(&dir) {
            let mut v: Vec<PathBuf> =
                rd.flatten().map(|e| e.path()).filter(|p| p.extension().is_some_and(|x| x == "sl")).collect();
            v.sort();
            files.extend(v);
        }
    }
    files
}

/// `anysl jit check`: prints a table; returns false on mismatches or compile failures of
/// surface shaders.
pub fn check(files: &[PathBuf], points: usize, verbose: bool) -> bool {
    let files = if files.is_empty() { default_files() } else { files.to_vec() };
    let mut ok = true;
    let (mut n_pairs, mut n_bad, mut n_fallback, mut worst) = (0usize, 0usize, 0usize, 0u64);
    println!("{:<28} {:<22} {:<7} {:>10} {:>10} {:>6}  note", "shader", "pair", "oracle", "max ulps", "max abs", "bad");
    for f in &files {
        for r in check_file(f, points) {
            // Built-ins the JIT does not compile (`format` with numbers, textures) run on the
            // interpreter, as documented: reported, not a failure (as in the test).
            let fallback = r.pair != "-" && r.note.contains("not supported by the JIT");
            n_fallback += usize::from(fallback);
            let failed = r.mismatches > 0 || (r.pair != "-" && !r.note.is_empty() && !fallback);
            if r.pair != "-" && r.note.is_empty() {
                n_pairs += 1;
                worst = worst.max(r.max_ulps);
            }
            if failed {
                ok = false;
                n_bad += 1;
            }
            if verbose || failed || r.pair == "-" || r.oracle == "aot" {
                println!(
                    "{:<28} {:<22} {:<7} {:>10} {:>10.2e} {:>6}  {}",
                    r.shader,
                    r.pair,
                    r.oracle,
                    if r.max_ulps == u64::MAX { "nan".to_string() } else { r.max_ulps.to_string() },
                    r.max_abs,
                    r.mismatches,
                    r.note
                );
            }
        }
    }
    println!(
        "{} files, {n_pairs} comparisons on {points} points each, {n_bad} failing, {n_fallback} on the interpreter; bound: > {MAX_ULPS} ulps and > {ABS_FLOOR:e}·max(1,|x|)",
        files.len()
    );
    ok
}

/// One row of `anysl bench jit` (the JSON schema).
#[derive(Clone, Debug, Serialize)]
pub struct JitBenchRow {
    /// Table-1 shader name.
    pub shader: String,
    /// `jit-f32`, `jit-x4`, `jit-x8`, `jit-x16`, `aot-f32`, `aot-f32x8`, `interp`, `jit-x8-points`
    /// (the points entry, `JitShader::shade_points`); `jit-dual-x8`, `jit-dual-x8-displacement`,
    /// `jit-dual-x8-displaced` (a displacement run before the surface, and each alone);
    /// `jit-x8-sl-lights`, `jit-x8-interp-lights` (the lights as `.sl` light shaders —
    /// `shaders/rsl/<light>.sl` with the same parameters — compiled by the JIT, or run by the
    /// interpreter, instead of the compiled lights; `compile_ms` the lights' compile time, and
    /// for `jit-x8-sl-lights` also that of the surface's flavour with the lights compiled in);
    /// `jit-x8-host-lights` (the compiled lights, called by the renderer's light loop instead
    /// of described as data: the cost of that loop alone).
    pub backend: String,
    /// Median cold compile time, parse → machine code (0 for aot).
    pub compile_ms: f64,
    /// Median points per second.
    pub points_per_s: f64,
    /// Max abs error against the f64 reference.
    pub max_abs_err: f64,
}

/// Settings of `anysl bench jit`.
#[derive(Clone, Debug)]
pub struct JitBenchOpts {
    /// Points per run.
    pub points: usize,
    /// Timed runs (median).
    pub runs: usize,
    /// Cold compiles per variant (median).
    pub compiles: usize,
    /// Only these shaders.
    pub shaders: Vec<String>,
}

/// Seconds a timed sample of `anysl bench jit` lasts at least (passes are repeated).
const SAMPLE_S: f64 = 0.01;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Stage medians of cold compiles: `(stage, ms)` and the LLVM instruction counts.
pub fn cold_compile(
    file: &Path,
    variant: Variant,
    runs: usize,
) -> Result<(Vec<(&'static str, f64)>, CompileStats), String> {
    let mut per_stage: Vec<(&'static str, Vec<f64>)> = Vec::new();
    let mut last = None;
    for _ in 0..runs.max(1) {
        let t = Instant::now();
        let c =
            anysl_rsl::compile_file(file, &CompileOptions { include_dirs: include_dirs(file), ..Default::default() })
                .map_err(|e| e.to_string())?;
        let parse = t.elapsed().as_secs_f64() * 1e3;
        let values: Vec<_> = c.module.params.iter().map(|p| p.default.clone()).collect();
        let cs = compile_with(&c.module, &values, variant, &JitOptions::default(), false).map_err(|e| e.to_string())?;
        let mut stages = vec![("parse+check", parse)];
        stages.extend(cs.stats.times_ms.iter().copied());
        for (s, t) in stages {
            match per_stage.iter_mut().find(|(n, _)| *n == s) {
                Some((_, v)) => v.push(t),
                None => per_stage.push((s, vec![t])),
            }
        }
        last = Some(cs.stats.clone());
    }
    Ok((per_stage.into_iter().map(|(s, v)| (s, median(v))).collect(), last.unwrap_or_default()))
}

/// A pass over the point set, writing its outputs.
type Run<'a> = Box<dyn FnMut(&mut ShadeOut<f32>) + 'a>;

/// Times each runner `runs` times, round-robin so drift hits every one alike; returns the
/// median seconds per pass and each runner's outputs.
fn time_runners(runners: &mut [(&str, f64, Run<'_>)], points: usize, runs: usize) -> (Vec<f64>, Vec<ShadeOut<f32>>) {
    let mut outs: Vec<ShadeOut<f32>> = runners.iter().map(|_| ShadeOut::new(points)).collect();
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); runners.len()];
    // Each timed sample repeats the pass until it lasts about `SAMPLE_S` (from the warm-up
    // pass): a single pass over the points takes well under a millisecond for the fast
    // backends, where timer and scheduler jitter on a shared machine would dominate.
    let mut reps = vec![1usize; runners.len()];
    for (k, (_, _, f)) in runners.iter_mut().enumerate() {
        let t = Instant::now();
        f(&mut outs[k]);
        let once = t.elapsed().as_secs_f64().max(1e-7);
        reps[k] = ((SAMPLE_S / once).ceil() as usize).clamp(1, 10_000);
    }
    for _ in 0..runs {
        for (k, (_, _, f)) in runners.iter_mut().enumerate() {
            let t = Instant::now();
            for _ in 0..reps[k] {
                f(&mut outs[k]);
            }
            times[k].push(t.elapsed().as_secs_f64() / reps[k] as f64);
        }
    }
    (times.into_iter().map(median).collect(), outs)
}

/// The displacement shader of the displacement rows: `scenes/dented.sl` (noise dents along
/// the normal, the normal left to the renderer: the moved surface's, from the dual-number
/// derivatives of the moved `P`).
fn dented_file() -> PathBuf {
    rsl_dir().join("../../scenes/dented.sl")
}

/// A displacement shader run as a surface: `Ci` = the displaced `P`, `Oi` = its `N` (the
/// displacement's cost alone, through the point-set loop).
#[derive(Clone)]
struct DisplaceOnly<D>(D);

impl<D: DisplacementShader> Shader for DisplaceOnly<D> {
    fn meta(&self) -> ShaderMeta {
        ShaderMeta { uses_derivatives: true, ..self.0.meta() }
    }
    fn param(&self, name: &str) -> Option<ParamValue> {
        self.0.param(name)
    }
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
        self.0.set_param(name, value)
    }
}

impl<D: DisplacementShader> SurfaceShader for DisplaceOnly<D> {
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let (p, n) = self.0.displace(ctx, e);
        SurfaceOutput { Ci: Color::new(p.x, p.y, p.z), Oi: Color::new(n.x, n.y, n.z) }
    }
}

/// The rows of a displacement run before the surface at 8 lanes with dual numbers (the
/// derivatives give the displaced normal): the surface alone (`jit-dual-x8`), the
/// displacement alone (`jit-dual-x8-displacement`, outputs `P` and `N`) and the two together
/// (`jit-dual-x8-displaced`, `anysl_scene::surface::SceneSurface`), each against the
/// interpreter's f64 answer (the surface alone against the f64 reference).
fn displaced_rows(
    name: &str,
    jit: &JitShader,
    interp: &InterpShader,
    reference: &ShadeOut<f64>,
    lights: &[Light],
    set: &PointSet,
    opts: &JitBenchOpts,
) -> Result<Vec<JitBenchRow>, String> {
    type D8 = Dual<F32x8>;
    let file = dented_file();
    let t = Instant::now();
    let disp = JitShader::from_file(&file, &include_dirs(&file), JitOptions::default()).map_err(|e| e.to_string())?;
    disp.variant(Variant::DualX8)?;
    jit.variant(Variant::DualX8)?;
    let compile_ms = t.elapsed().as_secs_f64() * 1e3;
    let alone = DisplaceOnly(disp.clone());
    let both = SceneSurface { surface: jit.clone(), displacement: Some(disp.clone()), volumes: Volumes::default() };
    let (ref_alone, ref_both) = {
        let d = disp.interp().clone();
        let alone = DisplaceOnly(d.clone());
        let both = SceneSurface { surface: interp.clone(), displacement: Some(d), volumes: Volumes::default() };
        (
            shade_points_f64::<Dual<f64>, _, Light>(&alone, lights, set),
            shade_points_f64::<Dual<f64>, _, Light>(&both, lights, set),
        )
    };
    let mut runners: Vec<(&str, f64, Run)> = vec![
        ("jit-dual-x8", 0.0, Box::new(|o| shade_points::<D8, _, Light>(jit, lights, set, o))),
        ("jit-dual-x8-displacement", compile_ms, Box::new(|o| shade_points::<D8, _, Light>(&alone, lights, set, o))),
        ("jit-dual-x8-displaced", compile_ms, Box::new(|o| shade_points::<D8, _, Light>(&both, lights, set, o))),
    ];
    let (times, outs) = time_runners(&mut runners, set.len(), opts.runs);
    let refs = [reference, &ref_alone, &ref_both];
    Ok(runners
        .iter()
        .enumerate()
        .map(|(k, (b, c, _))| JitBenchRow {
            shader: name.to_string(),
            backend: (*b).to_string(),
            compile_ms: *c,
            points_per_s: set.len() as f64 / times[k],
            max_abs_err: abs_error_stats(&outs[k], refs[k]).0,
        })
        .collect())
}

/// A light the context cannot describe as data: light loops call it through the renderer.
#[derive(Clone)]
struct Opaque(Light);

impl Shader for Opaque {
    fn meta(&self) -> ShaderMeta {
        self.0.meta()
    }
    fn param(&self, name: &str) -> Option<ParamValue> {
        self.0.param(name)
    }
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
        self.0.set_param(name, value)
    }
}

impl LightShader for Opaque {
    fn light<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        self.0.light(e, ps)
    }
    fn emission(&self) -> Option<Emission> {
        self.0.emission()
    }
}

/// The lights `lights` as `.sl` light shaders (`shaders/rsl/<light>.sl`, the same
/// parameters) with their 8-lane code compiled, and the milliseconds that took.
fn sl_lights(lights: &[Light]) -> Result<(Vec<JitShader>, f64), String> {
    let t = Instant::now();
    let mut out = Vec::with_capacity(lights.len());
    for l in lights {
        let file = rsl_dir().join(format!("{}.sl", l.name()));
        let mut s =
            JitShader::from_file(&file, &include_dirs(&file), JitOptions::default()).map_err(|e| e.to_string())?;
        for p in l.meta().params {
            let v = l.param(&p.name).ok_or_else(|| format!("{}: no parameter {}", l.name(), p.name))?;
            s.set_param(&p.name, &v).map_err(|e| format!("{}.sl: {e}", l.name()))?;
        }
        s.variant(Variant::X8).map_err(|e| format!("{}.sl: {e}", l.name()))?;
        out.push(s);
    }
    Ok((out, t.elapsed().as_secs_f64() * 1e3))
}

/// Runs `anysl bench jit`.
pub fn bench(opts: &JitBenchOpts) -> Result<Vec<JitBenchRow>, String> {
    let names: Vec<String> = if opts.shaders.is_empty() {
        Surface::NAMES.iter().map(|s| s.to_string()).collect()
    } else {
        opts.shaders.clone()
    };
    let lights = table1_lights();
    let (jit_lights, jit_lights_ms) = sl_lights(&lights)?;
    let interp_lights: Vec<InterpShader> = jit_lights.iter().map(|l| l.interp().clone()).collect();
    let opaque_lights: Vec<Opaque> = lights.iter().cloned().map(Opaque).collect();
    let set = PointSet::random(opts.points, 0x5eed_2010);
    let mut rows = Vec::new();
    println!(
        "{:<9} {:>10} {:>7} {:>9} {:>9} {:>9} {:>9}  {:>16}",
        "shader", "stage ms:", "parse", "ir", "irgen", "opt", "codegen", "llvm insts"
    );
    for name in &names {
        let file_stem = if name == "phong" { "plastic" } else { name.as_str() };
        let file = rsl_dir().join(format!("{file_stem}.sl"));
        let aot = Surface::by_name(name)
            .ok_or_else(|| format!("unknown shader '{name}' (choices: {})", Surface::NAMES.join(", ")))?;
        let reference = shade_points_f64::<f64, _, _>(&aot, &lights, &set);
        let jit =
            JitShader::from_file(&file, &include_dirs(&file), JitOptions::default()).map_err(|e| e.to_string())?;
        let mut compile_ms = [0.0f64; 6];
        for v in [Variant::F32, Variant::X4, Variant::X8, Variant::X16] {
            let (stages, stats) = cold_compile(&file, v, opts.compiles)?;
            compile_ms[v.index()] = stages.iter().map(|(_, t)| t).sum();
            if v == Variant::X8 {
                let get = |s: &str| stages.iter().find(|(n, _)| *n == s).map_or(0.0, |(_, t)| *t);
                let insts: Vec<String> = stats.insts.iter().map(|(s, n)| format!("{s}={n}")).collect();
                println!(
                    "{name:<9} {:>10} {:>7.2} {:>9.2} {:>9.2} {:>9.2} {:>9.2}  {}",
                    "x8",
                    get("parse+check"),
                    get("ir-passes"),
                    get("llvm-irgen"),
                    get("optimize"),
                    get("codegen"),
                    insts.join(" ")
                );
            }
            jit.variant(v)?;
        }
        let interp_t = Instant::now();
        let program = { Program::new(ir_passes(&jit.module, &jit.values, false)).map_err(|e| e.to_string())? };
        let interp = InterpShader::new(Arc::new(program));
        let interp_ms = interp_t.elapsed().as_secs_f64() * 1e3;
        let mut runners: Vec<(&str, f64, Run)> = vec![
            ("jit-f32", compile_ms[0], Box::new(|o| shade_points::<f32, _, Light>(&jit, &lights, &set, o))),
            ("jit-x4", compile_ms[1], Box::new(|o| shade_points::<F32x4, _, Light>(&jit, &lights, &set, o))),
            ("jit-x8", compile_ms[2], Box::new(|o| shade_points::<F32x8, _, Light>(&jit, &lights, &set, o))),
            ("jit-x16", compile_ms[3], Box::new(|o| shade_points::<F32x16, _, Light>(&jit, &lights, &set, o))),
            ("aot-f32", 0.0, Box::new(|o| shade_points::<f32, _, Light>(&aot, &lights, &set, o))),
            ("aot-f32x8", 0.0, Box::new(|o| shade_points::<F32x8, _, Light>(&aot, &lights, &set, o))),
            ("interp", interp_ms, Box::new(|o| shade_points::<F32x8, _, Light>(&interp, &lights, &set, o))),
            // The same lights as `.sl` light shaders, compiled or interpreted.
            (
                "jit-x8-sl-lights",
                jit_lights_ms,
                Box::new(|o| shade_points::<F32x8, _, JitShader>(&jit, &jit_lights, &set, o)),
            ),
            ("jit-x8-host-lights", 0.0, Box::new(|o| shade_points::<F32x8, _, Opaque>(&jit, &opaque_lights, &set, o))),
            (
                "jit-x8-interp-lights",
                0.0,
                Box::new(|o| shade_points::<F32x8, _, InterpShader>(&jit, &interp_lights, &set, o)),
            ),
            // The loop over the point set compiled with the shader (`JitShader::shade_points`).
            (
                "jit-x8-points",
                compile_ms[2],
                Box::new(|o| {
                    if !matches!(jit.shade_point_set::<F32x8, Light>(&lights, &set, o), Ok(true)) {
                        shade_points::<F32x8, _, Light>(&jit, &lights, &set, o);
                    }
                }),
            ),
        ];
        let (times, outs) = time_runners(&mut runners, set.len(), opts.runs);
        // The surface's x8 flavour with the `.sl` lights compiled in, compiled on first use.
        let inlined_ms = jit.inline_variant_compiled(Variant::X8).map_or(0.0, |c| c.stats.total_ms());
        for (k, (b, c, _)) in runners.iter().enumerate() {
            rows.push(JitBenchRow {
                shader: name.clone(),
                backend: (*b).to_string(),
                compile_ms: if *b == "jit-x8-sl-lights" { c + inlined_ms } else { *c },
                points_per_s: set.len() as f64 / times[k],
                max_abs_err: abs_error_stats(&outs[k], &reference).0,
            });
        }
        drop(runners);
        rows.extend(displaced_rows(name, &jit, &interp, &reference, &lights, &set, opts)?);
    }
    Ok(rows)
}

/// Prints the throughput table and the jit-x8 / aot-f32x8 ratio.
pub fn print_table(rows: &[JitBenchRow]) {
    println!();
    println!(
        "{:<9} {:<24} {:>11} {:>13} {:>9} {:>12}",
        "shader", "backend", "compile ms", "points/s", "vs aot-x8", "max_abs_err"
    );
    let mut ratios = Vec::new();
    for r in rows {
        let base =
            rows.iter().find(|x| x.shader == r.shader && x.backend == "aot-f32x8").map_or(f64::NAN, |x| x.points_per_s);
        if r.backend == "jit-x8" {
            ratios.push(r.points_per_s / base);
        }
        println!(
            "{:<9} {:<24} {:>11.1} {:>13.3e} {:>8.2}x {:>12.2e}",
            r.shader,
            r.backend,
            r.compile_ms,
            r.points_per_s,
            r.points_per_s / base,
            r.max_abs_err
        );
    }
    if !ratios.is_empty() {
        let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
        println!("jit-x8 / aot-f32x8 over {} shaders: mean {mean:.2}x", ratios.len());
    }
    for b in ["jit-x8-sl-lights", "jit-x8-host-lights", "jit-x8-interp-lights"] {
        let r = backend_ratios(rows, b, "aot-f32x8");
        if !r.is_empty() {
            let mean = r.iter().sum::<f64>() / r.len() as f64;
            println!("{b} / aot-f32x8 over {} shaders: mean {mean:.2}x", r.len());
        }
    }
    let displaced = displaced_ratios(rows);
    if !displaced.is_empty() {
        let list: Vec<String> = displaced.iter().map(|(s, r)| format!("{s} {r:.2}x")).collect();
        let mean = displaced.iter().map(|(_, r)| r).sum::<f64>() / displaced.len() as f64;
        println!(
            "displacement + surface / (displacement alone + surface alone), jit dual-x8: mean {mean:.2}x ({})",
            list.join(", ")
        );
    }
}

/// Per shader that has both rows: the throughput of backend `b` over that of `base`.
#[must_use]
pub fn backend_ratios(rows: &[JitBenchRow], b: &str, base: &str) -> Vec<f64> {
    rows.iter()
        .filter(|r| r.backend == b)
        .filter_map(|r| {
            let x = rows.iter().find(|x| x.shader == r.shader && x.backend == base)?;
            Some(r.points_per_s / x.points_per_s)
        })
        .collect()
}

/// Per shader: the time of the displacement and the surface shaded together over the sum of
/// their times alone (`jit-dual-x8-displaced` against `jit-dual-x8` + `jit-dual-x8-displacement`).
#[must_use]
pub fn displaced_ratios(rows: &[JitBenchRow]) -> Vec<(String, f64)> {
    let mut out = Vec::new();
    for r in rows.iter().filter(|r| r.backend == "jit-dual-x8-displaced") {
        let t = |b: &str| rows.iter().find(|x| x.shader == r.shader && x.backend == b).map(|x| 1.0 / x.points_per_s);
        if let (Some(s), Some(d)) = (t("jit-dual-x8"), t("jit-dual-x8-displacement")) {
            out.push((r.shader.clone(), (1.0 / r.points_per_s) / (s + d)));
        }
    }
    out
}
