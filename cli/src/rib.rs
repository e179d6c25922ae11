//! `anysl render SCENE.rib`: every frame of a RenderMan scene (or the ones asked for), each
//! `Display` written into the output directory.

use crate::render::{render_any, Backend, RenderArgs, RendererName};
use anysl_core::Shader;
use anysl_renderers::{render_packet_stats, Image, RenderOptions};
use anysl_scene::build::{BuildOptions, FrameDesc, SceneBuilder};
use anysl_scene::render::{frame_scene, Surfaces};
use anysl_scene::shaders::ShaderLibrary;
use anysl_simd::{F32x16, F32x4, F32x8};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The frames `--frame`/`--frames` select (1-based positions in the file when a frame has no
/// `FrameBegin` number).
fn selected(frame: &FrameDesc, args: &RenderArgs) -> Result<bool, String> {
    let n = frame.number.unwrap_or(frame.index as i32 + 1);
    if let Some(want) = args.frame {
        return Ok(n == want);
    }
    if let Some(range) = &args.frames {
        let (a, b) = range
            .split_once('-')
            .and_then(|(a, b)| Some((a.trim().parse::<i32>().ok()?, b.trim().parse::<i32>().ok()?)))
            .ok_or_else(|| format!("--frames {range}: expected FIRST-LAST, e.g. --frames 1-10"))?;
        return Ok((a..=b).contains(&n));
    }
    Ok(true)
}

fn repo_shaders() -> [PathBuf; 2] {
    let root = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"));
    [root.join("standard"), root]
}

/// Renders the RIB file `path`.
pub fn run(path: &Path, args: &RenderArgs) -> Result<(), String> {
    let lanes: usize = args.lanes.parse().map_err(|_| format!("--lanes {}: expected 4, 8 or 16", args.lanes))?;
    if !path.is_file() {
        return Err(format!("{}: no such file", path.display()));
    }
    let stem = path
        .file_name()
        .map_or("ri".to_string(), |f| f.to_string_lossy().trim_end_matches(".gz").trim_end_matches(".rib").to_string());
    let mut builder = SceneBuilder::new(BuildOptions { width: args.size, default_output: Some(stem) });
    let report = anysl_rib::parse_file(path, &mut builder, &anysl_rib::Options::new()).map_err(|e| e.render())?;
    let warnings = report.render_warnings();
    if !warnings.is_empty() {
        eprint!("{warnings}");
    }
    let rib_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut search: Vec<PathBuf> =
        builder.shader_paths.iter().map(|p| if p.is_relative() { rib_dir.join(p) } else { p.clone() }).collect();
    search.push(rib_dir.clone());
    search.extend(args.include.iter().cloned());
    search.extend(repo_shaders());
    let mut include_dirs = args.include.clone();
    include_dirs.push(repo_shaders()[1].join("include"));
    let library = ShaderLibrary::new(search, include_dirs);
    let frames = builder.finish();
    let out_dir = args.out_dir.clone().unwrap_or_else(|| PathBuf::from("."));
    std::fs::create_dir_all(&out_dir).map_err(|e| format!("--out-dir {}: {e}", out_dir.display()))?;
    let opts = RenderOptions {
        spp: 1,
        threads: args.threads.map_or(0, |t| t as usize),
        progress: std::io::IsTerminal::is_terminal(&std::io::stderr()),
        shadows: !args.no_shadows,
        ..RenderOptions::default()
    };
    let backend = args.backend.unwrap_or(if cfg!(feature = "jit") { Backend::Jit } else { Backend::Interp });
    let mut rendered = 0;
    match backend {
        #[cfg(feature = "jit")]
        Backend::Jit => {
            let mut surfaces = Surfaces::new(library, |m| {
                anysl_jit::JitShader::new(m, anysl_jit::JitOptions::default()).map_err(|e| e.to_string())
            });
            for frame in &frames {
                if selected(frame, args)? {
                    render_frame(frame, &mut surfaces, args, lanes, &opts, &out_dir)?;
                    rendered += 1;
                }
            }
        }
        _ => {
            let mut surfaces = Surfaces::interpreter(library);
            for frame in &frames {
                if selected(frame, args)? {
                    render_frame(frame, &mut surfaces, args, lanes, &opts, &out_dir)?;
                    rendered += 1;
                }
            }
        }
    }
    if rendered == 0 {
        let numbers: Vec<String> = frames.iter().map(|f| f.number.unwrap_or(f.index as i32 + 1).to_string()).collect();
        return Err(format!(
            "{}: no frame selected (the file has {} frame{}: {})",
            path.display(),
            frames.len(),
            if frames.len() == 1 { "" } else { "s" },
            numbers.join(", ")
        ));
    }
    Ok(())
}

fn render_frame<S: anysl_scene::render::SceneShader>(
    frame: &FrameDesc,
    surfaces: &mut Surfaces<S>,
    args: &RenderArgs,
    lanes: usize,
    opts: &RenderOptions,
    out_dir: &Path,
) -> Result<(), String> {
    let start = Instant::now();
    let fs = frame_scene(frame, surfaces)?;
    for w in &fs.warnings {
        eprintln!("warning: {w}");
    }
    let setup = start.elapsed();
    if frame.displays.is_empty() {
        // A depth pass only: `frame_scene` kept its depth map in memory; nothing to render.
        println!(
            "frame {}: depth pass {} kept in memory in {:.1} ms",
            frame.number.unwrap_or(frame.index as i32 + 1),
            frame.depth_maps.join(", "),
            setup.as_secs_f64() * 1e3
        );
        return Ok(());
    }
    let t0 = Instant::now();
    let (image, shading): (Image, Option<Duration>) = match args.renderer {
        RendererName::Packet if !fs.scene.surfaces.iter().any(|s| s.meta().uses_derivatives) => {
            let (img, stats) = match lanes {
                4 => render_packet_stats::<F32x4, _, _>(&fs.scene, opts, 4),
                16 => render_packet_stats::<F32x16, _, _>(&fs.scene, opts, 16),
                _ => render_packet_stats::<F32x8, _, _>(&fs.scene, opts, 8),
            };
            (img, Some(stats.shading))
        }
        r => (render_any(&fs.scene, r, lanes, opts), None),
    };
    let render = t0.elapsed();
    let pixels = fs.finish(&frame.film, &image);
    let mut scene = fs.scene;
    if frame.surfaces.len() == scene.surfaces.len() {
        surfaces.keep(frame, std::mem::take(&mut scene.surfaces).into_iter().map(|s| s.surface).collect());
    }
    let mut written = Vec::new();
    for d in &frame.displays {
        let file = out_dir.join(&d.file);
        anysl_scene::film::write(&frame.film, d, &pixels, &file)?;
        written.push(file.display().to_string());
    }
    let [x0, x1, y0, y1] = frame.film.crop_pixels();
    let share = match shading {
        Some(s) => {
            let threads = if opts.threads == 0 { rayon::current_num_threads() } else { opts.threads };
            format!("{:.0}% shading", 100.0 * s.as_secs_f64() / (render.as_secs_f64() * threads as f64).max(1e-9))
        }
        None => "shading share not measured by this renderer".to_string(),
    };
    println!(
        "frame {}: {} ({}×{} px, {}×{} samples/px, {} triangles, {} surfaces, {} lights) in {:.1} ms (setup {:.1} ms, {share})",
        frame.number.unwrap_or(frame.index as i32 + 1),
        written.join(", "),
        x1 - x0,
        y1 - y0,
        frame.film.samples[0],
        frame.film.samples[1],
        scene.triangles().len(),
        frame.surfaces.len(),
        scene.lights.len(),
        (setup + render).as_secs_f64() * 1e3,
        setup.as_secs_f64() * 1e3,
    );
    Ok(())
}
