//! `anysl render`: one picture of a scene preset with one renderer, shader parameters set by
//! name from the command line.

use anysl_core::{ParamValue, Shader};
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

/// The shader names `--shader` accepts: the Table-1 names plus `plastic` (= `phong`).
pub fn shader_choices() -> Vec<&'static str> {
    let mut names = Surface::NAMES.to_vec();
    names.push("plastic");
    names
}

/// Options of `anysl render`.
#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    /// Scene preset.
    #[arg(long, value_enum, default_value_t = SceneName::Table1)]
    pub scene: SceneName,
    /// Surface shader. For `gallery` it puts this one shader on every object; without it the
    /// gallery shows all ten (default for the other scenes: phong).
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(shader_choices()))]
    pub shader: Option<String>,
    /// Renderer.
    #[arg(long, value_enum, default_value_t = RendererName::Packet)]
    pub renderer: RendererName,
    /// SIMD width of the packet renderer (rays per packet, shaded together).
    #[arg(long, default_value = "8", value_parser = clap::builder::PossibleValuesParser::new(["4", "8", "16"]))]
    pub lanes: String,
    /// Image width in pixels (table1 and bunny are square, the gallery 16:9).
    #[arg(long, default_value_t = 512, value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub size: u32,
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

/// Sets `NAME=VALUE` parameters on `surfaces`: each name must exist on at least one of them
/// and its value parse as that parameter's type. Errors name the parameter and list the
/// parameters there are.
pub fn apply_params(surfaces: &mut [Surface], params: &[String]) -> Result<(), String> {
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
            surface
                .set_param(name, &value)
                .map_err(|e| format!("--param {name}={text}: {e}"))?;
        }
        if !found {
            let listing: Vec<String> = unique_shaders(surfaces)
                .iter()
                .map(|s| {
                    let meta = s.meta();
                    let params: Vec<String> = meta
                        .params
                        .iter()
                        .map(|p| format!("{} {} = {}", p.ty.keyword(), p.name, p.default))
                        .collect();
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

fn unique_shaders(surfaces: &[Surface]) -> Vec<&Surface> {
    let mut seen: Vec<&Surface> = Vec::new();
    for s in surfaces {
        if !seen.iter().any(|t| t.name() == s.name()) {
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
        Surface::by_name(name).ok_or_else(|| {
            format!(
                "--shader {name}: unknown shader (choices: {})",
                shader_choices().join(", ")
            )
        })
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

/// Renders `scene` with `renderer` (`lanes` for the packet renderer).
///
/// Dual-number packets are compiled for 8 lanes only (each width of `Dual<F32xN>` is a full
/// copy of every shader; keeping one keeps the build time reasonable): a scene with a shader
/// that uses derivatives is shaded in packets of 8 whatever `lanes` says, and a note is
/// printed. Pictures are identical at every width.
pub fn render_with(scene: &Scene<Surface, Light>, renderer: RendererName, lanes: usize, opts: &RenderOptions) -> Image {
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

/// `anysl render`.
pub fn run(args: &RenderArgs) -> Result<(), String> {
    let lanes: usize = args
        .lanes
        .parse()
        .map_err(|_| format!("--lanes {}: expected 4, 8 or 16", args.lanes))?;
    let scene = build_scene(args.scene, args.shader.as_deref(), &args.params, args.size)?;
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
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{stem}.png")));
    let start = Instant::now();
    let image = render_with(&scene, args.renderer, lanes, &opts);
    let elapsed = start.elapsed();
    image.save_png(&output)?;
    let what = match args.renderer {
        RendererName::Packet => format!("packet f32x{lanes}"),
        r => r.name().to_string(),
    };
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
