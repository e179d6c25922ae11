//! Section a: the AnySL paper's Table 1 (`anysl bench table1` through `crate::table1::run`),
//! plus, with the JIT, the same scene shaded by the JIT-compiled `.sl` shaders.

use super::{db, sci, table, Section, Sizes};
use crate::table1::{averages, generic_vs_native, Table1Opts, Table1Row};

/// Runs the Table-1 benchmark single-threaded and formats it.
pub fn section(sz: &Sizes) -> Result<Section, String> {
    let opts = Table1Opts { size: sz.table1_size, runs: sz.table1_runs, threads: 1, shaders: Vec::new() };
    #[cfg_attr(not(feature = "jit"), allow(unused_mut))]
    let mut rows = crate::table1::run(&opts, &indicatif::ProgressBar::hidden())?;
    #[cfg(feature = "jit")]
    rows.extend(jit_rows(&opts, &rows)?);
    let mut html = format!(
        "<p>The <code>table1</code> scene (a triangulated sphere, two point lights and an ambient light, no \
         shadows) at {0}×{0} pixels, packet renderer, one thread, median of {1} run(s). <i>shade spd</i> is the \
         shading-time speedup over <code>f32</code> shading of the same packets (the paper's measure), <i>frame \
         spd</i> includes tracing. PSNR and max error are against an <code>f64</code> render. All variants shade \
         the plain function (derivatives off).",
        sz.table1_size, sz.table1_runs
    );
    if cfg!(feature = "jit") {
        html.push_str(
            " <code>jit-f32x8</code>/<code>jit-f32x16</code> render the same scene with the <code>.sl</code> \
             shader compiled by the LLVM JIT (compiled on first use, before the timed runs); their speedups \
             are over this table's generic <code>f32</code> row, measured separately.",
        );
    }
    html.push_str("</p>\n");
    let body: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.shader.clone(),
                r.variant.clone(),
                format!("{:.2}", r.fps),
                format!("{:.2}", r.shading_ms),
                format!("{:.2}×", r.shading_speedup),
                format!("{:.2}×", r.frame_speedup),
                db(r.psnr_db),
                sci(r.max_abs_err),
            ]
        })
        .collect();
    html.push_str(&table(
        &["shader", "variant", "frames/s", "shading ms", "shade spd", "frame spd", "PSNR dB", "max err"],
        &body,
    ));
    let mut summary = Vec::new();
    let avg = averages(&rows);
    let mut avg_rows: Vec<Vec<String>> = avg
        .iter()
        .map(|(v, am, gm, fr, n)| {
            vec![(*v).to_string(), format!("{am:.2}×"), format!("{gm:.2}×"), format!("{fr:.2}×"), n.to_string()]
        })
        .collect();
    for jv in ["jit-f32x8", "jit-f32x16"] {
        let sel: Vec<&Table1Row> = rows.iter().filter(|r| r.variant == jv).collect();
        if !sel.is_empty() {
            let n = sel.len() as f64;
            let am = sel.iter().map(|r| r.shading_speedup).sum::<f64>() / n;
            let gm = (sel.iter().map(|r| r.shading_speedup.ln()).sum::<f64>() / n).exp();
            let fr = sel.iter().map(|r| r.frame_speedup).sum::<f64>() / n;
            avg_rows.push(vec![
                jv.to_string(),
                format!("{am:.2}×"),
                format!("{gm:.2}×"),
                format!("{fr:.2}×"),
                sel.len().to_string(),
            ]);
        }
    }
    html.push_str("<p>Mean speedups over the shaders:</p>");
    html.push_str(&table(&["variant", "shading (arith.)", "shading (geom.)", "frame (arith.)", "shaders"], &avg_rows));
    summary.push(format!(
        "{0}×{0}, 1 thread: mean shading speedup over f32 — {1}",
        sz.table1_size,
        avg_rows.iter().map(|r| format!("{} {}", r[0], r[1])).collect::<Vec<_>>().join(", ")
    ));
    let gn = generic_vs_native(&rows);
    if !gn.is_empty() {
        summary.push(format!(
            "generic f32x8 / hand-written native f32x8 shading time: {}",
            gn.iter().map(|(s, r)| format!("{s} {r:.2}")).collect::<Vec<_>>().join(", ")
        ));
    }
    Ok(Section { id: "table1", title: "a. Table 1: frames/s and speedups per shader and variant", html, summary })
}

/// The table1 scene shaded by the JIT-compiled `.sl` shader at 8 and 16 lanes.
#[cfg(feature = "jit")]
fn jit_rows(opts: &Table1Opts, base: &[Table1Row]) -> Result<Vec<Table1Row>, String> {
    use anysl_jit::{JitOptions, JitShader};
    use anysl_renderers::{render_packet_stats, render_packet_with, scenes, PlainShading, RenderOptions};
    use anysl_shaders::{table1_lights, Surface};
    use anysl_simd::{F32x16, F32x8};
    let lights = table1_lights();
    let ropts = RenderOptions { threads: opts.threads, shadows: false, derivatives: false, ..RenderOptions::default() };
    let mut rows = Vec::new();
    for name in Surface::NAMES {
        let stem = if name == "phong" { "plastic" } else { name };
        let file = crate::jit::rsl_dir().join(format!("{stem}.sl"));
        let include = vec![crate::jit::rsl_dir().join("include")];
        let shader = JitShader::from_file(&file, &include, JitOptions::default()).map_err(|e| e.to_string())?;
        let scene = scenes::table1(shader, lights.clone(), opts.size);
        let reference = render_packet_with::<f64, _, _, _>(&scene, &ropts, 8, PlainShading).0;
        let Some(f32_row) = base.iter().find(|r| r.shader == name && r.variant == "f32") else { continue };
        let base_frame = 1.0 / f32_row.fps;
        for (variant, lanes) in [("jit-f32x8", 8usize), ("jit-f32x16", 16)] {
            let render = || match lanes {
                8 => render_packet_stats::<F32x8, _, _>(&scene, &ropts, 8),
                _ => render_packet_stats::<F32x16, _, _>(&scene, &ropts, 16),
            };
            let _ = render(); // compiles the variant
            let mut frames = Vec::new();
            let mut shading = Vec::new();
            let mut img = None;
            for _ in 0..opts.runs.max(1) {
                let (i, st) = render();
                frames.push(st.total.as_secs_f64());
                shading.push(st.shading.as_secs_f64());
                img = Some(i);
            }
            let img = img.expect("one run");
            let (frame, shade) = (super::median(frames), super::median(shading));
            rows.push(Table1Row {
                shader: name.to_string(),
                variant: variant.to_string(),
                fps: 1.0 / frame.max(1e-12),
                speedup: f32_row.shading_ms / 1e3 / shade.max(1e-12),
                psnr_db: img.psnr(&reference),
                shading_ms: shade * 1e3,
                shading_speedup: f32_row.shading_ms / 1e3 / shade.max(1e-12),
                frame_speedup: base_frame / frame.max(1e-12),
                max_abs_err: f64::from(img.max_abs_diff(&reference)),
            });
        }
    }
    Ok(rows)
}
