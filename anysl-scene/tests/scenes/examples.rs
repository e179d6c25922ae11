//! Every RIB file in `scenes/` reads without error, builds, and renders at a small size in the
//! scalar, packet and pbrt-like renderers: the pictures are not empty, the renderers agree, and
//! the scalar picture is what it was (golden images `tests/data/golden/scene-*.png`;
//! `ANYSL_BLESS=1` rewrites them, a mismatch writes `-actual.png` beside them).

use anysl_renderers::{read_rgb8, render_packet, render_pbrt, render_scalar, write_rgb8, Integrator, RenderOptions};
use anysl_scene::build::{BuildOptions, Film, SceneBuilder};
use anysl_scene::film::quantized;
use anysl_scene::render::{frame_scene, Surfaces};
use anysl_scene::shaders::ShaderLibrary;
use anysl_simd::F32x8;
use std::path::PathBuf;

fn scenes_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes"))
}

/// What a render may differ from its golden image by: room for other CPUs' last bits, none for
/// a changed shader, reader or renderer.
const GOLDEN_MIN_PSNR: f64 = 45.0;
const GOLDEN_MAX_LEVELS: u16 = 12;

/// Compares the frame's 8-bit RGB output with `tests/data/golden/<name>.png` (or writes it
/// with `ANYSL_BLESS=1`).
fn check_golden(name: &str, film: &Film, pixels: &[[f32; 4]]) -> Result<(), String> {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/golden"));
    let path = dir.join(format!("{name}.png"));
    let [x0, x1, y0, y1] = film.crop_pixels();
    let (w, h) = (x1 - x0, y1 - y0);
    // 8-bit output as is; deeper `Quantize` scaled to 8 bits.
    let one = f32::from(u16::try_from(film.quantize.one.max(1)).unwrap_or(u16::MAX));
    let rgb: Vec<u8> =
        quantized(film, pixels, 3).into_iter().map(|v| (f32::from(v) * 255.0 / one).round().min(255.0) as u8).collect();
    if std::env::var("ANYSL_BLESS").is_ok_and(|v| v == "1") {
        write_rgb8(&path, &rgb, w, h)?;
        eprintln!("blessed {}", path.display());
        return Ok(());
    }
    let (gw, gh, golden) = read_rgb8(&path).map_err(|e| format!("{e} (run with ANYSL_BLESS=1 to create it)"))?;
    let same_size = (gw, gh) == (w, h);
    let max = if same_size {
        golden.iter().zip(&rgb).map(|(a, b)| u16::from(a.abs_diff(*b))).max().unwrap_or(0)
    } else {
        255
    };
    let mse: f64 = if same_size {
        golden.iter().zip(&rgb).map(|(a, b)| (f64::from(*a) - f64::from(*b)).powi(2)).sum::<f64>() / rgb.len() as f64
    } else {
        f64::INFINITY
    };
    let p = if mse == 0.0 { f64::INFINITY } else { 10.0 * (255.0 * 255.0 / mse).log10() };
    if p >= GOLDEN_MIN_PSNR && max <= GOLDEN_MAX_LEVELS {
        return Ok(());
    }
    let actual = dir.join(format!("{name}-actual.png"));
    let _ = write_rgb8(&actual, &rgb, w, h);
    Err(format!(
        "{name}: PSNR {p:.1} dB, max difference {max} levels against {} (see {})",
        path.display(),
        actual.display()
    ))
}

fn psnr(a: &[[f32; 4]], b: &[[f32; 4]]) -> f64 {
    let mse: f64 = a
        .iter()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |c| f64::from(p[c].clamp(0.0, 1.0) - q[c].clamp(0.0, 1.0)).powi(2)))
        .sum::<f64>()
        / (3 * a.len()) as f64;
    if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (1.0 / mse).log10()
    }
}

#[test]
fn every_example_scene_renders_in_every_renderer() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(scenes_dir())
        .expect("scenes/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "rib"))
        .collect();
    files.sort();
    assert!(files.len() >= 6, "{files:?}");
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let mut golden_errors = Vec::new();
    for file in &files {
        let mut b = SceneBuilder::new(BuildOptions { width: Some(40), ..BuildOptions::default() });
        if let Err(e) = anysl_rib::parse_file(file, &mut b, &anysl_rib::Options::new()) {
            panic!("{}: {}", file.display(), e.render());
        }
        for frame in b.finish() {
            let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(vec![scenes_dir()], Vec::new()));
            let fs = frame_scene(&frame, &mut surfaces).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            assert!(fs.warnings.is_empty(), "{}: {:?}", file.display(), fs.warnings);
            let scalar = fs.finish(&frame.film, &render_scalar(&fs.scene, &opts));
            let packet = fs.finish(&frame.film, &render_packet::<F32x8, _, _>(&fs.scene, &opts));
            let pbrt = fs.finish(&frame.film, &render_pbrt(&fs.scene, &opts, Integrator::Active));
            let name = format!("{} frame {:?}", file.display(), frame.number);
            let bright = scalar.iter().filter(|p| p[0].max(p[1]).max(p[2]) > 0.1).count();
            assert!(bright * 20 >= scalar.len(), "{name}: {bright} of {} pixels lit", scalar.len());
            let (a, b) = (psnr(&scalar, &packet), psnr(&scalar, &pbrt));
            assert!(a >= 40.0 && b >= 40.0, "{name}: PSNR scalar/packet {a:.1} dB, scalar/pbrt {b:.1} dB");
            let stem = file.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
            let golden = format!("scene-{stem}-{}", frame.index);
            if let Err(e) = check_golden(&golden, &frame.film, &scalar) {
                golden_errors.push(e);
            }
        }
    }
    assert!(golden_errors.is_empty(), "golden images differ:\n{}", golden_errors.join("\n"));
}

#[test]
fn the_gobo_projects_its_slide() {
    // The light shines straight down from (0, 5, 0): the floor below shows the checkerboard,
    // so a row of floor pixels crosses light and dark squares.
    let mut b = SceneBuilder::new(BuildOptions { width: Some(96), ..BuildOptions::default() });
    anysl_rib::parse_file(scenes_dir().join("gobo.rib"), &mut b, &anysl_rib::Options::new()).expect("gobo.rib");
    let frame = b.finish().remove(0);
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(vec![scenes_dir()], Vec::new()));
    let fs = frame_scene(&frame, &mut surfaces).expect("builds");
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let px = fs.finish(&frame.film, &render_scalar(&fs.scene, &opts));
    let (w, h) = (frame.film.xres as usize, frame.film.yres as usize);
    // A row near the bottom of the picture (floor in front of the sphere).
    let row = &px[(h * 7 / 8) * w..(h * 7 / 8 + 1) * w];
    let mut switches = 0;
    let mut bright = row[0][0] > 0.3;
    for p in row {
        if (p[0] > 0.3) != bright && (p[0] > 0.45 || p[0] < 0.15) {
            bright = !bright;
            switches += 1;
        }
    }
    assert!(
        switches >= 3,
        "{switches} light/dark changes along the row: {:?}",
        row.iter().map(|p| p[0]).collect::<Vec<_>>()
    );
}
