//! `anysl rslc …`: the RenderMan Shading Language compiler driver — check, info (like
//! `sloinfo`), ir, rust, and eval (like OSL's `testshade`).

use anysl_ad::Dual;
use anysl_core::prelude::*;
use anysl_core::{ParamValue, PointContext};
use anysl_rsl::back::interp::{run_batch, InterpShader, Program};
use anysl_rsl::ir::{Const, Global, Module};
use anysl_rsl::passes::{optimize, PassOptions};
use anysl_rsl::types::BaseType;
use anysl_rsl::{CompileOptions, Compiled};
use anysl_shaders::{table1_lights, Light};
use clap::{Args, Subcommand, ValueEnum};
use serde_json::{json, Value as Json};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Options every command that reads `.sl` takes.
#[derive(Args, Debug, Clone, Default)]
pub struct SlOptions {
    /// Add a directory to the `#include` search path (repeatable; the file's own directory is
    /// searched first).
    #[arg(short = 'I', value_name = "DIR")]
    pub include: Vec<PathBuf>,
    /// Define a preprocessor macro, `NAME` or `NAME=VALUE` (repeatable).
    #[arg(short = 'D', value_name = "NAME[=VALUE]")]
    pub define: Vec<String>,
}

impl SlOptions {
    /// The compiler options.
    pub fn compile_options(&self) -> CompileOptions {
        CompileOptions {
            include_dirs: self.include.clone(),
            defines: self
                .define
                .iter()
                .map(|d| match d.split_once('=') {
                    Some((n, v)) => (n.to_string(), Some(v.to_string())),
                    None => (d.clone(), None),
                })
                .collect(),
            ..CompileOptions::default()
        }
    }
}

/// The back ends `rslc eval` can run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum EvalBackend {
    /// The batched interpreter.
    Interp,
    /// The compiled (monomorphized) shader of the same name from the shader collection.
    Aot,
    /// The LLVM JIT.
    Jit,
}

/// `anysl rslc` subcommands.
#[derive(Subcommand, Debug)]
pub enum RslcCommand {
    /// Check files for errors; prints diagnostics, exit status 1 when any file has errors.
    Check {
        /// `.sl` files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        #[command(flatten)]
        sl: SlOptions,
    },
    /// The shader's parameters as JSON (like `sloinfo`).
    Info {
        /// A `.sl` file.
        file: PathBuf,
        #[command(flatten)]
        sl: SlOptions,
    },
    /// Print the optimized IR (with `--set`, specialized to those parameter values).
    Ir {
        /// A `.sl` file.
        file: PathBuf,
        /// Specialize a uniform parameter, `NAME=VALUE` (repeatable).
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
        /// Print the IR as lowered, without optimization passes.
        #[arg(long)]
        no_opt: bool,
        #[command(flatten)]
        sl: SlOptions,
    },
    /// Print the generated Rust for the shader.
    Rust {
        /// A `.sl` file.
        file: PathBuf,
        #[command(flatten)]
        sl: SlOptions,
    },
    /// Run the shader on a grid of shading points and print every output as JSON.
    Eval {
        /// A `.sl` file.
        file: PathBuf,
        /// Back end.
        #[arg(long, value_enum, default_value_t = EvalBackend::Interp)]
        backend: EvalBackend,
        /// Set a parameter, `NAME=VALUE` (repeatable; triples as `a,b,c`).
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
        /// Override a global, `NAME=VALUE` (repeatable): P, N, Ng, I, E, s, t, u, v, du, dv,
        /// dPdu, dPdv, Cs, Os.
        #[arg(long = "global", value_name = "NAME=VALUE")]
        global: Vec<String>,
        /// Grid size `WxH` (default 1x1).
        #[arg(long, default_value = "1x1")]
        grid: String,
        /// No scene lights (default: the table1 lights).
        #[arg(long)]
        no_lights: bool,
        #[command(flatten)]
        sl: SlOptions,
    },
}

/// Compiles a file; on errors prints the rendered diagnostics and returns `Err`.
pub fn compile(file: &Path, sl: &SlOptions) -> Result<Compiled, String> {
    match anysl_rsl::compile_file(file, &sl.compile_options()) {
        Ok(c) => {
            if !c.warnings.items.is_empty() {
                eprint!("{}", c.warnings.render(&c.sources));
            }
            Ok(c)
        }
        Err(e) => Err(format!("{e}{} error(s) in {}", e.diags.error_count(), file.display())),
    }
}

fn parse_triple(text: &str) -> Option<Vec<f64>> {
    let v: Result<Vec<f64>, _> = text.split(',').map(|x| x.trim().parse::<f64>()).collect();
    v.ok().filter(|v| v.len() == 1 || v.len() == 3 || v.len() == 16)
}

/// Parses `NAME=VALUE` parameter settings against the module's parameters.
pub fn parse_sets(m: &Module, sets: &[String]) -> Result<Vec<(String, Const)>, String> {
    let mut out = Vec::new();
    for s in sets {
        let (name, text) =
            s.split_once('=').ok_or_else(|| format!("--set {s:?}: expected NAME=VALUE, e.g. --set Ks=0.5"))?;
        let name = name.trim();
        let p = m.params.iter().find(|p| p.name == name).ok_or_else(|| {
            let known: Vec<&str> = m.params.iter().map(|p| p.name.as_str()).collect();
            format!("--set {name}: shader '{}' has no parameter '{name}' (parameters: {})", m.name, known.join(", "))
        })?;
        let c = match p.ty.base {
            BaseType::String => Const::Str(text.to_string()),
            b => {
                let v = parse_triple(text)
                    .ok_or_else(|| format!("--set {name}={text}: expected a number or a comma-separated triple"))?;
                match (b, v.len()) {
                    (BaseType::Float, 1) => Const::Float(v[0]),
                    (t, 1) if t.is_triple() => Const::Triple([v[0]; 3]),
                    (t, 3) if t.is_triple() => Const::Triple([v[0], v[1], v[2]]),
                    (BaseType::Matrix, 16) => {
                        let mut a = [0.0; 16];
                        a.copy_from_slice(&v);
                        Const::Matrix(a)
                    }
                    _ => return Err(format!("--set {name}={text}: parameter '{name}' is a {}", p.ty.base)),
                }
            }
        };
        out.push((name.to_string(), c));
    }
    Ok(out)
}

fn const_json(c: &Const) -> Json {
    match c {
        Const::Float(x) => json!(x),
        Const::Triple(t) => json!(t),
        Const::Matrix(m) => json!(m.to_vec()),
        Const::Str(s) => json!(s),
        Const::Array(v) => Json::Array(v.iter().map(const_json).collect()),
    }
}

/// The `sloinfo`-like description of a shader.
pub fn info_json(m: &Module, uses_derivatives: bool) -> Json {
    json!({
        "name": m.name,
        "type": format!("{:?}", m.kind).to_lowercase(),
        "uses_derivatives": uses_derivatives,
        "params": m.params.iter().map(|p| json!({
            "name": p.name,
            "type": p.ty.base.name(),
            "detail": p.ty.detail.to_string(),
            "array": p.ty.array,
            "output": p.output,
            "default": const_json(&p.default),
        })).collect::<Vec<_>>(),
    })
}

/// Runs an `rslc` command; returns the process exit code.
pub fn run(cmd: &RslcCommand) -> Result<u8, String> {
    match cmd {
        RslcCommand::Check { files, sl } => {
            let mut failed = 0;
            for f in files {
                // Every shader of the file (PRMan's `shader` compiles them all).
                let mut errors = 0;
                for r in anysl_rsl::compile_file_all(f, &sl.compile_options()) {
                    match r {
                        Ok(c) => {
                            if !c.warnings.items.is_empty() {
                                eprint!("{}", c.warnings.render(&c.sources));
                            }
                            println!(
                                "{}: ok ({} `{}`)",
                                f.display(),
                                format!("{:?}", c.module.kind).to_lowercase(),
                                c.module.name
                            );
                        }
                        Err(e) => {
                            errors += e.diags.error_count();
                            eprint!("{e}");
                        }
                    }
                }
                if errors > 0 {
                    failed += 1;
                    eprintln!("{}: {errors} error(s)", f.display());
                }
            }
            if files.len() > 1 {
                println!("{} of {} files clean", files.len() - failed, files.len());
            }
            Ok(u8::from(failed > 0))
        }
        RslcCommand::Info { file, sl } => {
            let c = compile(file, sl)?;
            let m = optimize(c.module, &PassOptions::default());
            println!(
                "{}",
                serde_json::to_string_pretty(&info_json(m.module(), m.uses_derivatives())).map_err(|e| e.to_string())?
            );
            Ok(0)
        }
        RslcCommand::Ir { file, set, no_opt, sl } => {
            let c = compile(file, sl)?;
            let m = c.module;
            let values = parse_sets(&m, set)?;
            if *no_opt {
                print!("{m}");
                return Ok(0);
            }
            let a = optimize(m, &PassOptions { specialize: values, ..PassOptions::default() });
            let report = a.report();
            print!("{}", a.module());
            let stages: Vec<String> = report.stages.iter().map(|(s, n)| format!("{s} {n}")).collect();
            println!("; instructions by stage: {}", stages.join(" → "));
            println!("; uses derivatives: {}", report.uses_derivatives);
            Ok(0)
        }
        RslcCommand::Rust { file, sl } => {
            let opts = anysl_rsl::back::rust::RustOptions::default();
            let text = anysl_rsl::back::rust::generate_file(file, &sl.compile_options(), &opts)
                .map_err(|e| format!("{e}{} error(s) in {}", e.diags.error_count(), file.display()))?;
            print!("{text}");
            Ok(0)
        }
        RslcCommand::Eval { file, backend, set, global, grid, no_lights, sl } => {
            let c = compile(file, sl)?;
            let out = eval(c.module, *backend, set, global, grid, *no_lights)?;
            println!("{}", serde_json::to_string_pretty(&out).map_err(|e| e.to_string())?);
            Ok(0)
        }
    }
}

/// Parses `WxH`.
fn parse_grid(grid: &str) -> Result<(usize, usize), String> {
    let (w, h) = grid.split_once(['x', 'X']).ok_or_else(|| format!("--grid {grid}: expected WxH, e.g. 4x4"))?;
    let w: usize = w.trim().parse().map_err(|_| format!("--grid {grid}: bad width"))?;
    let h: usize = h.trim().parse().map_err(|_| format!("--grid {grid}: bad height"))?;
    if w == 0 || h == 0 || w * h > 1 << 24 {
        return Err(format!("--grid {grid}: expected 1 ≤ W·H ≤ 16777216"));
    }
    Ok((w, h))
}

/// A global override: name and one or three numbers.
pub type GlobalSet = (String, Vec<f64>);

fn parse_globals(globals: &[String]) -> Result<Vec<GlobalSet>, String> {
    use anysl_rsl::eval::{is_float_global, GLOBAL_NAMES};
    globals
        .iter()
        .map(|g| {
            let (name, text) = g.split_once('=').ok_or_else(|| format!("--global {g:?}: expected NAME=VALUE"))?;
            let name = name.trim();
            if !GLOBAL_NAMES.contains(&name) {
                return Err(format!("--global {name}: unknown global (choices: {})", GLOBAL_NAMES.join(", ")));
            }
            let vals = parse_triple(text)
                .filter(|v| v.len() <= 3)
                .ok_or_else(|| format!("--global {name}={text}: expected a number or a comma-separated triple"))?;
            let float = is_float_global(name);
            if (float && vals.len() != 1) || (!float && vals.len() != 1 && vals.len() != 3) {
                return Err(format!("--global {name}={text}: {name} is a {}", if float { "float" } else { "triple" }));
            }
            Ok((name.to_string(), vals))
        })
        .collect()
}

fn lane_vals<F: ShadingFloat>(v: &[F]) -> Vec<f64> {
    v.iter().map(|x| x.lane(0)).collect()
}

fn json_vals(v: &[f64]) -> Json {
    if v.len() == 1 {
        json!(v[0])
    } else {
        json!(v)
    }
}

/// Runs the interpreter over the grid with float type `F`.
fn eval_interp<F: ShadingFloat>(
    prog: &Program,
    values: &[Const],
    w: usize,
    h: usize,
    sets: &[GlobalSet],
    lights: &[Light],
) -> Vec<Json> {
    let mut points = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let mut ctx = [PointContext::new(anysl_rsl::eval::grid_globals::<F, _>(i, j, w, h, sets), lights)];
            let fr = run_batch::<F, _>(prog, values, &mut ctx, &[F::Mask::splat(true)]);
            let read = |g: Global| prog.global_loc(g).map(|l| lane_vals(&fr.read(l, 0)));
            let ci = read(Global::Ci).unwrap_or_else(|| vec![0.0; 3]);
            let oi = read(Global::Oi).unwrap_or_else(|| {
                let os = ctx[0].globals.Os;
                vec![os.r.lane(0), os.g.lane(0), os.b.lane(0)]
            });
            let mut outputs = serde_json::Map::new();
            for (k, p) in prog.module.params.iter().enumerate() {
                if p.output {
                    if let Some(l) = prog.param_loc(k) {
                        outputs.insert(p.name.clone(), json_vals(&lane_vals(&fr.read(l, 0))));
                    }
                }
            }
            anysl_rsl::back::interp::release(fr);
            points.push(json!({"Ci": ci, "Oi": oi, "outputs": outputs}));
        }
    }
    points
}

/// A `--set` value as a parameter value.
fn param_value(name: &str, c: &Const) -> Result<ParamValue, String> {
    Ok(match c {
        Const::Float(x) => ParamValue::Float(*x),
        Const::Triple(t) => ParamValue::Triple(*t),
        Const::Str(s) => ParamValue::String(s.clone()),
        Const::Matrix(m) => ParamValue::Matrix(*m),
        Const::Array(_) => return Err(format!("--set {name}: arrays cannot be set on the command line")),
    })
}

/// Runs the JIT's compiled code over the grid (`f32`, or `Dual<f32>` when the shader uses
/// derivatives, as the interpreter) and reads back `Ci`, `Oi` and the output parameters.
#[cfg(feature = "jit")]
fn eval_jit(
    module: Module,
    values: &[(String, Const)],
    w: usize,
    h: usize,
    sets: &[GlobalSet],
    lights: &[Light],
    derivs: bool,
) -> Result<Vec<Json>, String> {
    use anysl_jit::{JitOptions, JitShader, PointOutputs};
    let mut shader = JitShader::new(module, JitOptions::default()).map_err(|e| e.to_string())?;
    for (name, c) in values {
        shader.set_param(name, &param_value(name, c)?).map_err(|e| format!("--set {name}: {e}"))?;
    }
    let mut points = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let o: PointOutputs = if derivs {
                let mut ctx =
                    PointContext::new(anysl_rsl::eval::grid_globals::<Dual<f32>, _>(i, j, w, h, sets), lights);
                shader.eval_point(&mut ctx)
            } else {
                let mut ctx = PointContext::new(anysl_rsl::eval::grid_globals::<f32, _>(i, j, w, h, sets), lights);
                shader.eval_point(&mut ctx)
            }
            .map_err(|e| format!("--backend jit: {e}"))?;
            let outputs: serde_json::Map<String, Json> =
                o.params.iter().map(|(name, v)| (name.clone(), json_vals(v))).collect();
            points.push(json!({"Ci": o.ci, "Oi": o.oi, "outputs": outputs}));
        }
    }
    Ok(points)
}

#[cfg(not(feature = "jit"))]
fn eval_jit(
    _: Module,
    _: &[(String, Const)],
    _: usize,
    _: usize,
    _: &[GlobalSet],
    _: &[Light],
    _: bool,
) -> Result<Vec<Json>, String> {
    Err("--backend jit: this build has no JIT (build with the `jit` feature)".into())
}

/// `rslc eval`: the points as JSON.
pub fn eval(
    module: Module,
    backend: EvalBackend,
    set: &[String],
    global: &[String],
    grid: &str,
    no_lights: bool,
) -> Result<Json, String> {
    let (w, h) = parse_grid(grid)?;
    let sets = parse_globals(global)?;
    let values = parse_sets(&module, set)?;
    // The JIT runs its own passes per instance, on the lowered module.
    let lowered = (backend == EvalBackend::Jit).then(|| module.clone());
    let m = optimize(module, &PassOptions::default());
    let uses_derivatives = m.uses_derivatives();
    let lights: Vec<Light> = if no_lights { Vec::new() } else { table1_lights() };
    let points = match backend {
        EvalBackend::Interp => {
            let prog = Arc::new(Program::new(m).map_err(|e| e.to_string())?);
            let mut shader = InterpShader::new(prog.clone());
            for (name, c) in &values {
                if let Some(i) = prog.module.params.iter().position(|p| &p.name == name) {
                    prog.module.set_param_value(&mut shader.values, i, c.clone());
                }
            }
            if uses_derivatives {
                eval_interp::<Dual<f32>>(&prog, &shader.values, w, h, &sets, &lights)
            } else {
                eval_interp::<f32>(&prog, &shader.values, w, h, &sets, &lights)
            }
        }
        EvalBackend::Aot => {
            let mut s = anysl_shaders::Surface::by_name(&m.module().name).ok_or_else(|| {
                format!(
                    "--backend aot: no compiled shader named '{}' (compiled shaders: {})",
                    m.module().name,
                    anysl_shaders::Surface::NAMES.join(", ")
                )
            })?;
            for (name, c) in &values {
                s.set_param(name, &param_value(name, c)?).map_err(|e| format!("--set {name}: {e}"))?;
            }
            let mut points = Vec::new();
            for j in 0..h {
                for i in 0..w {
                    let o = if s.meta().uses_derivatives {
                        let mut ctx = PointContext::new(
                            anysl_rsl::eval::grid_globals::<Dual<f32>, _>(i, j, w, h, &sets),
                            &lights,
                        );
                        let o = s.shade(&mut ctx, &mut Exec::new());
                        (o.Ci.lane(0), o.Oi.lane(0))
                    } else {
                        let mut ctx =
                            PointContext::new(anysl_rsl::eval::grid_globals::<f32, _>(i, j, w, h, &sets), &lights);
                        let o = s.shade(&mut ctx, &mut Exec::new());
                        (o.Ci.lane(0), o.Oi.lane(0))
                    };
                    points.push(json!({"Ci": o.0, "Oi": o.1, "outputs": {}}));
                }
            }
            points
        }
        EvalBackend::Jit => {
            let lowered = lowered.expect("kept for the JIT");
            eval_jit(lowered, &values, w, h, &sets, &lights, uses_derivatives)?
        }
    };
    Ok(json!({ "points": points }))
}
