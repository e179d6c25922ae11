//! `anysl render`: one picture of a scene preset with one renderer, shader parameters set by
//! name from the command line.

use anysl_core::{LightShader, ParamValue, Shader, SurfaceShader};
use anysl_renderers::{
    render_packet, render_packet_with, render_pbrt, render_scalar, scenes, Image, Integrator, PlainShading,
    RenderOptions, Scene,
};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::{F32x16, F32x4, F32x8};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use std::time::Instant;

/// The scene presets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SceneName {
    /// The AnySL paper's Table-1 setup: a triangulated sphere, two point lights, ambient.
    Table1,
    /// Ten spheres (one per Table-1 shader), the bunny and a ground plane under a sky.
    Gallery,
    /// The Stanford bunny alone.
    Bunny,
}

/// The renderers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum RendererName {
    /// Packets of `--lanes` rays shaded together with SIMD (RTfact-like).
    Packet,
    /// One ray at a time with ray differentials (Manta-like).
    Scalar,
    /// The pbrt-like renderer running the shader's own lighting ("active").
    Pbrt,
    /// The pbrt-like path tracer with the shader as a passive material.
    PbrtPassive,
}

impl RendererName {
    /// Every renderer, in the order the demo runs them.
    pub const ALL: [Self; 4] = [Self::Packet, Self::Scalar, Self::Pbrt, Self::PbrtPassive];

    /// The command-line spelling.
    pub fn name(self) -> &'static str {
        match self {
            Self::Packet => "packet",
            Self::Scalar => "scalar",
            Self::Pbrt => "pbrt",
            Self::PbrtPassive => "pbrt-passive",
        }
    }
}

/// How a shader is run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Backend {
    /// Compiled at run time by the LLVM JIT.
    Jit,
    /// Run by the batched interpreter.
    Interp,
    /// The compiled (generated or hand-written) Rust shader of that name.
    Aot,
}

/// The shader names `--shader` accepts: the Table-1 names plus `plastic` (= `phong`).
pub fn shader_choices() -> Vec<&'static str> {
    let mut names = Surface::NAMES.to_vec();
    names.push("plastic");
    names
}

/// Options of `anysl render`.
#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    /// A RenderMan scene file (`.rib` or `.rib.gz`) to render instead of a preset: every frame
    /// (or those of `--frame`/`--frames`), each `Display` written into `--out-dir`.
    #[arg(value_name = "SCENE.rib")]
    pub scene_file: Option<PathBuf>,
    /// Where a RIB scene's displays are written (default: the current directory).
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
    /// Render only frame N of a RIB scene (its `FrameBegin` number).
    #[arg(long, value_name = "N", conflicts_with = "frames")]
    pub frame: Option<i32>,
    /// Render only frames A to B of a RIB scene (`FrameBegin` numbers, inclusive).
    #[arg(long, value_name = "A-B")]
    pub frames: Option<String>,
    /// Add a shader search and `#include` directory (repeatable).
    #[arg(short = 'I', value_name = "DIR")]
    pub include: Vec<PathBuf>,
    /// Scene preset.
    #[arg(long, value_enum, default_value_t = SceneName::Table1)]
    pub scene: SceneName,
    /// Surface shader: a Table-1 name or an `.sl` file. For `gallery` it puts this one shader
    /// on every object; without it the gallery shows all ten (default for the other scenes:
    /// phong).
    #[arg(long)]
    pub shader: Option<String>,
    /// Back end: `jit` (the `.sl` compiled at run time; default for `.sl` files when built
    /// with the `jit` feature), `interp` (the batched interpreter), `aot` (the compiled Rust
    /// shader of that name; default for names).
    #[arg(long, value_enum)]
    pub backend: Option<Backend>,
    /// Renderer.
    #[arg(long, value_enum, default_value_t = RendererName::Packet)]
    pub renderer: RendererName,
    /// SIMD width of the packet renderer (rays per packet, shaded together).
    #[arg(long, default_value = "8", value_parser = clap::builder::PossibleValuesParser::new(["4", "8", "16"]))]
    pub lanes: String,
    /// Image width in pixels (table1 and bunny are square, the gallery 16:9; default 512). For
    /// a RIB scene: render at this width with the scene's aspect (default: its `Format`).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub size: Option<u32>,
    /// Samples per pixel (a √spp × √spp stratified grid).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub spp: u32,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,
    /// Set a shader parameter, `NAME=VALUE` (repeatable): `Ks=0.3`, `Cs=1,0.5,0.2`. With the
    /// ten-shader gallery it sets the parameter on every shader that has it.
    #[arg(long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
    /// Output PNG (default: `<shader>.png`, `gallery.png` for the ten-shader gallery).
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// Cast no shadow rays (the paper's Table-1 workload has none).
    #[arg(long)]
    pub no_shadows: bool,
}

impl RenderArgs {
    /// The image width of a preset: `--size`, else 512.
    #[must_use]
    pub fn preset_size(&self) -> u32 {
        self.size.unwrap_or(512)
    }
}

/// Sets `NAME=VALUE` parameters on `surfaces`: each name must exist on at least one of them
/// and its value parse as that parameter's type. Errors name the parameter and list the
/// parameters there are.
pub fn apply_params<S: Shader>(surfaces: &mut [S], params: &[String]) -> Result<(), String> {
    for assignment in params {
        let (name, text) = assignment
            .split_once('=')
            .ok_or_else(|| format!("--param {assignment:?}: expected NAME=VALUE, e.g. --param Ks=0.3"))?;
        let (name, text) = (name.trim(), text.trim());
        let mut found = false;
        for surface in surfaces.iter_mut() {
            let meta = surface.meta();
            let Some(info) = meta.param(name) else { continue };
            found = true;
            let value = ParamValue::parse(info.ty, text).map_err(|e| {
                format!(
                    "--param {name}={text}: shader '{}' parameter '{name}' is a {}: {e}",
                    meta.name,
                    info.ty.keyword()
                )
            })?;
            surface.set_param(name, &value).map_err(|e| format!("--param {name}={text}: {e}"))?;
        }
        if !found {
            let listing: Vec<String> = unique_shaders(surfaces)
                .iter()
                .map(|s| {
                    let meta = s.meta();
                    let params: Vec<String> =
                        meta.params.iter().map(|p| format!("{} {} = {}", p.ty.keyword(), p.name, p.default)).collect();
                    format!("  {}: {}", meta.name, params.join(", "))
                })
                .collect();
            return Err(format!(
                "--param {name}: no such shader parameter; the parameters are:\n{}",
                listing.join("\n")
            ));
        }
    }
    Ok(())
}

fn unique_shaders<S: Shader>(surfaces: &[S]) -> Vec<&S> {
    let mut seen: Vec<&S> = Vec::new();
    for s in surfaces {
        if !seen.iter().any(|t| t.meta().name == s.meta().name) {
            seen.push(s);
        }
    }
    seen
}

/// The gallery's surfaces: the ten Table-1 shaders on the spheres, phong on the bunny and a
/// checker ground.
pub fn gallery_surfaces() -> Vec<Surface> {
    let mut surfaces = Surface::all();
    surfaces.push(Surface::by_name("phong").expect("phong is in the collection"));
    surfaces.push(Surface::by_name("checker").expect("checker is in the collection"));
    surfaces
}

/// Builds the scene preset with `shader` (or the gallery's ten) and the Table-1 lights.
pub fn build_scene(
    scene: SceneName,
    shader: Option<&str>,
    params: &[String],
    size: u32,
) -> Result<Scene<Surface, Light>, String> {
    let by_name = |name: &str| {
        Surface::by_name(name)
            .ok_or_else(|| format!("--shader {name}: unknown shader (choices: {})", shader_choices().join(", ")))
    };
    let mut surfaces = match (scene, shader) {
        (SceneName::Gallery, None) => gallery_surfaces(),
        (SceneName::Gallery, Some(name)) => vec![by_name(name)?; 12],
        (_, name) => vec![by_name(name.unwrap_or("phong"))?],
    };
    apply_params(&mut surfaces, params)?;
    let lights = table1_lights();
    Ok(match scene {
        SceneName::Table1 => scenes::table1(surfaces.remove(0), lights, size),
        SceneName::Bunny => scenes::bunny(surfaces.remove(0), lights, size),
        SceneName::Gallery => scenes::gallery(surfaces, lights, size),
    })
}

/// [`render_with`] for any surface shader type (run-time compiled or interpreted shaders).
pub fn render_any<S: SurfaceShader, L: LightShader>(
    scene: &Scene<S, L>,
    renderer: RendererName,
    lanes: usize,
    opts: &RenderOptions,
) -> Image {
    let needs_duals = opts.derivatives && scene.surfaces.iter().any(|s| s.meta().uses_derivatives);
    match renderer {
        RendererName::Packet => match lanes {
            4 | 16 if needs_duals => render_packet::<F32x8, _, _>(scene, opts),
            4 => render_packet_with::<F32x4, _, _, _>(scene, opts, 4, PlainShading).0,
            16 => render_packet_with::<F32x16, _, _, _>(scene, opts, 16, PlainShading).0,
            _ => render_packet::<F32x8, _, _>(scene, opts),
        },
        RendererName::Scalar => render_scalar(scene, opts),
        RendererName::Pbrt => render_pbrt(scene, opts, Integrator::Active),
        RendererName::PbrtPassive => render_pbrt(scene, opts, Integrator::Passive),
    }
}

/// Sets `NAME=VALUE` parameters on one shader of any type.
fn apply_params_to<S: Shader>(surface: &mut S, params: &[String]) -> Result<(), String> {
    for assignment in params {
        let (name, text) = assignment
            .split_once('=')
            .ok_or_else(|| format!("--param {assignment:?}: expected NAME=VALUE, e.g. --param Ks=0.3"))?;
        let (name, text) = (name.trim(), text.trim());
        let meta = surface.meta();
        let info = meta.param(name).ok_or_else(|| {
            let known: Vec<String> = meta.params.iter().map(|p| format!("{} {}", p.ty.keyword(), p.name)).collect();
            format!("--param {name}: shader '{}' has no such parameter (parameters: {})", meta.name, known.join(", "))
        })?;
        let value = ParamValue::parse(info.ty, text).map_err(|e| format!("--param {name}={text}: {e}"))?;
        surface.set_param(name, &value).map_err(|e| format!("--param {name}={text}: {e}"))?;
    }
    Ok(())
}

/// The `.sl` file for `--shader`: the path itself, or `shaders/rsl/<name>.sl` for a name.
fn sl_file(shader: &str) -> PathBuf {
    if shader.ends_with(".sl") {
        return PathBuf::from(shader);
    }
    let stem = if shader == "phong" { "plastic" } else { shader };
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl")).join(format!("{stem}.sl"))
}

fn include_dirs(file: &std::path::Path) -> Vec<PathBuf> {
    let mut v = vec![PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl/include"))];
    if let Some(p) = file.parent() {
        v.push(p.join("include"));
    }
    v
}

/// Renders a run-time loaded shader (JIT or interpreter) and returns the image.
fn render_loaded<S: SurfaceShader + Clone>(
    mut surface: S,
    args: &RenderArgs,
    lanes: usize,
    opts: &RenderOptions,
) -> Result<Image, String> {
    apply_params_to(&mut surface, &args.params)?;
    let lights = table1_lights();
    let scene = match args.scene {
        SceneName::Table1 => scenes::table1(surface, lights, args.preset_size()),
        SceneName::Bunny => scenes::bunny(surface, lights, args.preset_size()),
        SceneName::Gallery => scenes::gallery(vec![surface; 12], lights, args.preset_size()),
    };
    Ok(render_any(&scene, args.renderer, lanes, opts))
}

fn load_module(file: &std::path::Path) -> Result<anysl_rsl::ir::Module, String> {
    let copts = anysl_rsl::CompileOptions { include_dirs: include_dirs(file), ..Default::default() };
    anysl_rsl::compile_file(file, &copts).map(|c| c.module).map_err(|e| e.to_string())
}

fn render_backend(
    backend: Backend,
    shader: &str,
    args: &RenderArgs,
    lanes: usize,
    opts: &RenderOptions,
) -> Result<Image, String> {
    let file = sl_file(shader);
    match backend {
        Backend::Interp => {
            let m = anysl_rsl::passes::optimize(load_module(&file)?, &anysl_rsl::passes::PassOptions::default());
            let p = anysl_rsl::back::interp::Program::new(m).map_err(|e| format!("{}: {e}", file.display()))?;
            render_loaded(anysl_rsl::back::interp::InterpShader::new(std::sync::Arc::new(p)), args, lanes, opts)
        }
        #[cfg(feature = "jit")]
        Backend::Jit => {
            let m = load_module(&file)?;
            let jit = anysl_jit::JitShader::new(m, anysl_jit::JitOptions::default()).map_err(|e| e.to_string())?;
            // Compile the variants this render shades with up front, so errors show here.
            if let Err(e) = jit.variant(anysl_jit::Variant::F32) {
                eprintln!("note: {e}; shading with the interpreter");
            }
            render_loaded(jit, args, lanes, opts)
        }
        #[cfg(not(feature = "jit"))]
        Backend::Jit => Err("--backend jit: this anysl was built without the `jit` feature".into()),
        Backend::Aot => unreachable!("handled by the caller"),
    }
}

/// Renders `scene` with `renderer` (`lanes` for the packet renderer).
///
/// Dual-number packets are compiled for 8 lanes only (each width of `Dual<F32xN>` is a full
/// copy of every shader; keeping one keeps the build time reasonable): a scene with a shader
/// that uses derivatives is shaded in packets of 8 whatever `lanes` says, and a note is
/// printed. Pictures are identical at every width.
pub fn render_with<S: SurfaceShader>(
    scene: &Scene<S, Light>,
    renderer: RendererName,
    lanes: usize,
    opts: &RenderOptions,
) -> Image {
    let needs_duals = opts.derivatives && scene.surfaces.iter().any(|s| s.meta().uses_derivatives);
    match renderer {
        RendererName::Packet => match lanes {
            4 | 16 if needs_duals => {
                eprintln!("note: shaders with derivatives are shaded in dual-number packets of 8 lanes");
                render_packet::<F32x8, _, _>(scene, opts)
            }
            4 => render_packet_with::<F32x4, _, _, _>(scene, opts, 4, PlainShading).0,
            16 => render_packet_with::<F32x16, _, _, _>(scene, opts, 16, PlainShading).0,
            _ => render_packet::<F32x8, _, _>(scene, opts),
        },
        RendererName::Scalar => render_scalar(scene, opts),
        RendererName::Pbrt => render_pbrt(scene, opts, Integrator::Active),
        RendererName::PbrtPassive => render_pbrt(scene, opts, Integrator::Passive),
    }
}

/// `anysl render` of a built-in scene preset (a RIB file is [`crate::rib::run`]'s).
pub fn run(args: &RenderArgs) -> Result<(), String> {
    let lanes: usize = args.lanes.parse().map_err(|_| format!("--lanes {}: expected 4, 8 or 16", args.lanes))?;
    let is_sl = args.shader.as_deref().is_some_and(|s| s.ends_with(".sl"));
    let default_backend = if is_sl && cfg!(feature = "jit") {
        Backend::Jit
    } else if is_sl {
        Backend::Interp
    } else {
        Backend::Aot
    };
    let backend = args.backend.unwrap_or(default_backend);
    // `--backend aot` with an `.sl` file: the compiled shader of the same name.
    let aot_name = match (backend, args.shader.as_deref()) {
        (Backend::Aot, Some(s)) if is_sl => {
            let stem = std::path::Path::new(s).file_stem().map(|x| x.to_string_lossy().to_string()).unwrap_or_default();
            let stem = if stem == "plastic" { "phong".to_string() } else { stem };
            if Surface::by_name(&stem).is_none() {
                return Err(format!(
                    "--backend aot: no compiled shader named '{stem}' (choices: {}); use --backend jit or interp",
                    shader_choices().join(", ")
                ));
            }
            Some(stem)
        }
        (_, s) => s.map(str::to_string),
    };
    let opts = RenderOptions {
        spp: args.spp,
        threads: args.threads.map_or(0, |t| t as usize),
        progress: std::io::IsTerminal::is_terminal(&std::io::stderr()),
        shadows: !args.no_shadows,
        ..RenderOptions::default()
    };
    let stem = match (args.scene, &args.shader) {
        (SceneName::Gallery, None) => "gallery".to_string(),
        (_, Some(name)) => name.clone(),
        (_, None) => "phong".to_string(),
    };
    let stem = match (&args.shader, is_sl) {
        (Some(s), true) => std::path::Path::new(s).file_stem().map_or(stem, |x| x.to_string_lossy().to_string()),
        _ => stem,
    };
    let output = args.output.clone().unwrap_or_else(|| PathBuf::from(format!("{stem}.png")));
    let start = Instant::now();
    let image = match (backend, args.shader.as_deref()) {
        (Backend::Aot, _) => {
            let scene = build_scene(args.scene, aot_name.as_deref(), &args.params, args.preset_size())?;
            render_with(&scene, args.renderer, lanes, &opts)
        }
        (b, shader) => render_backend(b, shader.unwrap_or("phong"), args, lanes, &opts)?,
    };
    let elapsed = start.elapsed();
    image.save_png(&output)?;
    let what = match args.renderer {
        RendererName::Packet => format!("packet f32x{lanes}"),
        r => r.name().to_string(),
    };
    let what = format!("{what} ({})", format!("{backend:?}").to_lowercase());
    println!(
        "{}: {}×{} {} with {stem}, {what} renderer, {} spp, rendered in {:.1} ms",
        output.display(),
        image.width,
        image.height,
        format!("{:?}", args.scene).to_lowercase(),
        args.spp,
        elapsed.as_secs_f64() * 1e3
    );
    Ok(())
}
