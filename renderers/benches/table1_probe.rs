//! Shading-time probe of the Table-1 workload (`anysl bench table1` is the benchmark; this is for
//! iterating without building the CLI): `cargo bench -p anysl-renderers --bench table1_probe`.
//! `SHADERS=phong,checker` picks shaders, `VARIANTS=f32,f32x4,f32x4@8` the variants (first: the
//! base of the speedups; `@n`: packets of n rays; `native`: the hand-written f32x8 kernels), `SIZE=256` the image, `RUNS=3` the runs (median);
//! `SPIN=phong:f32x8` renders one variant for 5 s for `perf record`.

use anysl_core::Globals;
use anysl_renderers::{
    render_packet_stats, render_packet_with, scenes, KernelShading, PacketStats, PlainShading, RenderOptions, Scene,
};
use anysl_shaders::native::{native_lights, shade_x8};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::{F32x16, F32x4, F32x8};
use std::time::{Duration, Instant};

fn env(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_string())
}

fn render(scene: &Scene<Surface, Light>, opts: &RenderOptions, variant: &str) -> PacketStats {
    match variant {
        "f32" => render_packet_stats::<f32, _, _>(scene, opts, 8).1,
        "f32x4" => render_packet_stats::<F32x4, _, _>(scene, opts, 4).1,
        "f32x8" => render_packet_stats::<F32x8, _, _>(scene, opts, 8).1,
        "f32@4" => render_packet_stats::<f32, _, _>(scene, opts, 4).1,
        "f32@16" => render_packet_stats::<f32, _, _>(scene, opts, 16).1,
        "f32x4@8" => render_packet_stats::<F32x4, _, _>(scene, opts, 8).1,
        "f32x4@16" => render_packet_stats::<F32x4, _, _>(scene, opts, 16).1,
        "native" => {
            // The hand-written f32x8 kernels (phong, checker), as `anysl bench table1` runs them.
            let (lights, ambient) = native_lights(&table1_lights()).unwrap();
            let kernel = |s: &Surface, g: &Globals<F32x8>| shade_x8(s, &lights, ambient, g);
            render_packet_with::<F32x8, _, _, _>(
                scene,
                opts,
                8,
                KernelShading { kernel: &kernel, fallback: PlainShading },
            )
            .1
        }
        _ => render_packet_stats::<F32x16, _, _>(scene, opts, 16).1,
    }
}

fn table1_shading() {
    let size: u32 = env("SIZE", "256").parse().unwrap();
    let runs: usize = env("RUNS", "3").parse().unwrap();
    let opts = RenderOptions { threads: 1, shadows: false, derivatives: false, ..RenderOptions::default() };
    if let Ok(spin) = std::env::var("SPIN") {
        let (name, variant) = spin.split_once(':').unwrap();
        let scene = scenes::table1(Surface::by_name(name).unwrap(), table1_lights(), size);
        let (t, mut frames, mut shading) = (Instant::now(), 0u32, Duration::ZERO);
        while t.elapsed() < Duration::from_secs(5) {
            shading += render(&scene, &opts, variant).shading;
            frames += 1;
        }
        eprintln!("{frames} frames, shading {:.3} ms/frame", shading.as_secs_f64() * 1e3 / f64::from(frames));
        return;
    }
    let names = env("SHADERS", &Surface::NAMES.join(","));
    let variants_env = env("VARIANTS", "f32,f32x4,f32x8,f32x16");
    let variants: Vec<&str> = variants_env.split(',').collect();
    let mut sums = vec![0.0f64; variants.len()];
    let mut n = 0;
    for name in names.split(',') {
        let scene = scenes::table1(Surface::by_name(name).unwrap(), table1_lights(), size);
        let mut times = vec![Vec::new(); variants.len()];
        let mut points = 0;
        for _ in 0..runs {
            for (k, v) in variants.iter().enumerate() {
                let stats = render(&scene, &opts, v);
                times[k].push(stats.shading);
                points = stats.shaded_points;
            }
        }
        let med: Vec<f64> = times
            .iter_mut()
            .map(|t| {
                t.sort();
                t[t.len() / 2].as_secs_f64() * 1e3
            })
            .collect();
        let mut line = format!("{name:9} {} {:7.2} ms", variants[0], med[0]);
        for (k, v) in variants.iter().enumerate().skip(1) {
            sums[k] += med[0] / med[k];
            line += &format!("  {v} {:5.2}x", med[0] / med[k]);
        }
        line += "   ns/point";
        for m in &med {
            line += &format!(" {:6.2}", m * 1e6 / points.max(1) as f64);
        }
        n += 1;
        eprintln!("{line} ({points} points)");
    }
    let mut line = "mean     ".to_string();
    for (k, v) in variants.iter().enumerate().skip(1) {
        line += &format!("  {v} {:5.2}x", sums[k] / n as f64);
    }
    eprintln!("{line}");
}

fn main() {
    table1_shading();
}
