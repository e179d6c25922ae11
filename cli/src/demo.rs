//! `anysl demo`: the gallery rendered by every renderer into `out/`, how far the pictures are
//! apart, and a small Table-1 benchmark.

use crate::render::{build_scene, render_with, RendererName, SceneName};
use crate::table1;
use anysl_renderers::{Image, RenderOptions};
use indicatif::ProgressBar;
use std::path::Path;
use std::time::Instant;

/// Gallery width in pixels (height 9/16 of it).
pub const GALLERY_SIZE: u32 = 640;
/// Samples per pixel of the gallery renders (2×2; also the passive path tracer's indirect
/// samples).
pub const GALLERY_SPP: u32 = 4;

/// Runs the demo, writing pictures into `out`; `bench` = the small Table-1 settings.
pub fn run(out: &Path, bench: &table1::Table1Opts, pb: &ProgressBar) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let scene = build_scene(SceneName::Gallery, None, &[], GALLERY_SIZE)?;
    let opts = RenderOptions { spp: GALLERY_SPP, progress: pb.is_hidden(), ..RenderOptions::default() };
    println!(
        "gallery: ten Table-1 shaders, phong bunny, checker ground, {}×{} pixels, {GALLERY_SPP} spp, shadows",
        scene.camera.width(),
        scene.camera.height()
    );
    let mut images: Vec<(RendererName, Image)> = Vec::new();
    for renderer in RendererName::ALL {
        let start = Instant::now();
        let image = render_with(&scene, renderer, 8, &opts);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let path = out.join(format!("gallery-{}.png", renderer.name()));
        image.save_png(&path)?;
        let label = match renderer {
            RendererName::Packet => "packet f32x8".to_string(),
            r => r.name().to_string(),
        };
        println!("  {label:<13} {ms:>8.0} ms  -> {}", path.display());
        images.push((renderer, image));
    }
    let scalar = &images[1].1;
    println!("PSNR against the scalar renderer (same shaders; pbrt-passive lights the shaders as materials,");
    println!("with one indirect bounce, so it is expected to differ):");
    for (renderer, image) in &images {
        if *renderer != RendererName::Scalar {
            println!(
                "  {:<13} {:>6.1} dB  (max diff {:.3})",
                renderer.name(),
                image.psnr(scalar),
                image.max_abs_diff(scalar)
            );
        }
    }
    println!();
    println!("Table 1 (small run: {0}×{0}, {1} run, {2} thread):", bench.size, bench.runs, bench.threads);
    let rows = table1::run(bench, pb)?;
    pb.finish_and_clear();
    table1::report(&rows, bench);
    println!();
    println!(
        "pictures are in {}/ (gallery-packet.png, gallery-scalar.png, gallery-pbrt.png, gallery-pbrt-passive.png)",
        out.display()
    );
    Ok(())
}
