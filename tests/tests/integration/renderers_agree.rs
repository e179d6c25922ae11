//! The AnySL claim on the real shader collection: every one of the ten Table-1 shaders gives
//! the same picture in renderers with very different internals, and a few small pictures stay
//! what they were (golden images).
//!
//! **Silhouettes.** The packet, scalar and active pbrt-like renderers trace the *same* primary
//! rays — same camera, same pixel-centre sample (spp = 1), same BVH and triangle test — so the
//! set of pixels that hit the sphere is identical in all of them; nothing is masked out or
//! eroded at the silhouette, and an edge pixel that differed would cost a whole pixel's worth of
//! error and show in the PSNR.
//!
//! **Sampling noise.** There is none to handle: the three renderers compared here are
//! deterministic (the active pbrt-like integrator uses the shader's own lighting, no random
//! numbers). Shaders that use derivatives (checker, brick, parquet) are shaded with dual
//! numbers seeded from the same ray differentials in every renderer (`Dual<F32x8>` in the packet
//! renderer, `Dual<f32>` in the others), so their `filterstep` antialiasing is the same too.
//! What remains is arithmetic: SIMD versus scalar evaluation order and polynomial math, which
//! must stay far below the bounds (40 dB packet, 35 dB pbrt-like active).

use anysl_core::Shader;
use anysl_renderers::{
    read_rgb8, render_packet, render_pbrt, render_scalar, scenes, write_rgb8, Image, Integrator, RenderOptions, Scene,
};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::F32x8;
use std::path::{Path, PathBuf};

const PACKET_MIN_PSNR: f64 = 40.0;
const PBRT_MIN_PSNR: f64 = 35.0;

fn opts() -> RenderOptions {
    RenderOptions { threads: 0, ..RenderOptions::default() }
}

fn table1(name: &str, size: u32) -> Scene<Surface, Light> {
    let surface = Surface::by_name(name).unwrap_or_else(|| panic!("{name} is one of Surface::NAMES"));
    scenes::table1(surface, table1_lights(), size)
}

#[test]
fn every_table1_shader_agrees_across_renderers() {
    let mut failures = Vec::new();
    for name in Surface::NAMES {
        let scene = table1(name, 128);
        let scalar = render_scalar(&scene, &opts());
        assert!(scalar.mean().iter().any(|c| *c > 0.01), "{name}: the scalar picture is black");
        let packet = render_packet::<F32x8, _, _>(&scene, &opts());
        let pbrt = render_pbrt(&scene, &opts(), Integrator::Active);
        let (p_packet, p_pbrt) = (packet.psnr(&scalar), pbrt.psnr(&scalar));
        eprintln!("{name:<9} packet f32x8 vs scalar {p_packet:6.1} dB, pbrt active vs scalar {p_pbrt:6.1} dB");
        if p_packet < PACKET_MIN_PSNR {
            failures.push(format!(
                "{name}: packet f32x8 vs scalar {p_packet:.1} dB < {PACKET_MIN_PSNR} dB (max diff {})",
                packet.max_abs_diff(&scalar)
            ));
        }
        if p_pbrt < PBRT_MIN_PSNR {
            failures.push(format!(
                "{name}: pbrt active vs scalar {p_pbrt:.1} dB < {PBRT_MIN_PSNR} dB (max diff {})",
                pbrt.max_abs_diff(&scalar)
            ));
        }
    }
    assert!(failures.is_empty(), "renderers disagree:\n{}", failures.join("\n"));
}

/// The packet renderer really shades derivative shaders with dual numbers: switching
/// derivatives off changes exactly those shaders' pictures, and with derivatives off in both
/// renderers they agree again (point-sampled `filterstep` = `step`).
#[test]
fn packet_renderer_filters_exactly_the_derivative_shaders() {
    let plain = RenderOptions { derivatives: false, ..opts() };
    for name in ["checker", "brick", "phong"] {
        let scene = table1(name, 64);
        let uses = scene.surfaces[0].meta().uses_derivatives;
        let filtered = render_packet::<F32x8, _, _>(&scene, &opts());
        let point_sampled = render_packet::<F32x8, _, _>(&scene, &plain);
        assert_eq!(filtered != point_sampled, uses, "{name}: uses_derivatives = {uses}");
        let p = point_sampled.psnr(&render_scalar(&scene, &plain));
        assert!(p >= PACKET_MIN_PSNR, "{name}: unfiltered packet vs unfiltered scalar {p:.1} dB");
    }
}

// ---------------------------------------------------------------------------------------------
// Golden images.

/// Smallest PSNR (dB, on 8-bit sRGB values) and largest per-channel difference (8-bit levels)
/// a render may have against its golden image: room for other CPUs' and compilers' last-bit
/// differences, none for a changed shader or renderer.
const GOLDEN_MIN_PSNR: f64 = 45.0;
const GOLDEN_MAX_LEVELS: u8 = 12;
const GOLDEN_SIZE: u32 = 48;

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data").join("golden")
}

/// PSNR in dB of two 8-bit buffers (peak 255) and their largest difference.
fn compare8(a: &[u8], b: &[u8]) -> (f64, u8) {
    let sse: f64 = a.iter().zip(b).map(|(x, y)| (f64::from(*x) - f64::from(*y)).powi(2)).sum();
    let max = a.iter().zip(b).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0);
    let mse = sse / a.len().max(1) as f64;
    let psnr = if mse == 0.0 { f64::INFINITY } else { 10.0 * (255.0 * 255.0 / mse).log10() };
    (psnr, max)
}

/// Compares `img` with `tests/data/golden/<name>.png`. With `ANYSL_BLESS=1` the golden image is
/// (re)written instead. On a mismatch `<name>-actual.png` and `<name>-diff.png` (differences ×8)
/// are written next to it.
fn check_golden(name: &str, img: &Image) -> Result<(), String> {
    let dir = golden_dir();
    let path = dir.join(format!("{name}.png"));
    if std::env::var("ANYSL_BLESS").is_ok_and(|v| v == "1") {
        img.save_png(&path)?;
        eprintln!("blessed {}", path.display());
        return Ok(());
    }
    let (w, h, golden) = read_rgb8(&path).map_err(|e| format!("{e} (run with ANYSL_BLESS=1 to create it)"))?;
    let actual = img.to_srgb8();
    let (psnr, max) = if (w, h) == (img.width, img.height) { compare8(&golden, &actual) } else { (0.0, 255) };
    if psnr >= GOLDEN_MIN_PSNR && max <= GOLDEN_MAX_LEVELS {
        return Ok(());
    }
    img.save_png(dir.join(format!("{name}-actual.png")))?;
    if (w, h) == (img.width, img.height) {
        let diff: Vec<u8> = golden.iter().zip(&actual).map(|(a, b)| a.abs_diff(*b).saturating_mul(8)).collect();
        write_rgb8(&dir.join(format!("{name}-diff.png")), &diff, w, h)?;
    }
    Err(format!(
        "{name}: {psnr:.1} dB (need {GOLDEN_MIN_PSNR}), max difference {max} levels (allowed {GOLDEN_MAX_LEVELS}), \
         size {}×{} vs golden {w}×{h}; see {name}-actual.png and {name}-diff.png in {} \
         (ANYSL_BLESS=1 accepts the new picture)",
        img.width,
        img.height,
        dir.display()
    ))
}

/// Three shaders of different kinds — procedural solid texture (wood), derivative-filtered
/// texture (checker), and a raytracing shader (glass: `trace` and transparency) — rendered
/// with the scalar renderer at 48×48.
#[test]
fn golden_images_match() {
    let errors: Vec<String> = ["wood", "checker", "glass"]
        .into_iter()
        .filter_map(|name| {
            let img = render_scalar(&table1(name, GOLDEN_SIZE), &opts());
            check_golden(&format!("table1-{name}"), &img).err()
        })
        .collect();
    assert!(errors.is_empty(), "golden images differ:\n{}", errors.join("\n"));
}

/// The comparison can fail: a brightened picture is caught.
#[test]
fn golden_comparison_detects_a_change() {
    let img = render_scalar(&table1("wood", 16), &opts());
    let a = img.to_srgb8();
    let mut brighter = img.clone();
    for p in &mut brighter.data {
        *p = p.map(|v| v * 1.1 + 0.01);
    }
    let (psnr, max) = compare8(&a, &brighter.to_srgb8());
    assert!(psnr < GOLDEN_MIN_PSNR || max > GOLDEN_MAX_LEVELS, "{psnr:.1} dB, {max} levels");
    assert_eq!(compare8(&a, &a), (f64::INFINITY, 0));
}
