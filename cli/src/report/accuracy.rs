//! Section b: error against run time. For every shader, one point per instantiation and back
//! end (the rows of `anysl bench kernels`, the interpreter, and the JIT when built with it):
//! nanoseconds per shading point against max abs error and PSNR versus the `f64` reference,
//! drawn as a Pareto scatter plot per shader.

use super::plot::{pareto_front, scatter_svg, Point, Scatter, Series};
use super::{db, median, psnr_of_mse, sci, table, Section, Sizes};
use anysl_ad::Dual;
use anysl_core::points::{shade_points, shade_points_f64, PointSet, ShadeOut};
use anysl_core::Shader;
use anysl_rsl::back::interp::InterpShader;
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::F32x8;
use std::sync::Arc;
use std::time::Instant;

/// One measured point.
struct Row {
    shader: String,
    backend: String,
    kind: &'static str,
    ns_per_point: f64,
    max_abs: f64,
    psnr: f64,
    reference: &'static str,
}

fn errors(out: &ShadeOut<f32>, reference: &ShadeOut<f64>) -> (f64, f64) {
    let (mut max, mut sse, mut n) = (0.0f64, 0.0f64, 0usize);
    for (a, b) in out.channels.iter().zip(&reference.channels) {
        for (&x, &y) in a.iter().zip(b) {
            let d = (f64::from(x) - y).abs();
            let d = if d.is_nan() { f64::INFINITY } else { d };
            max = max.max(d);
            let c = (f64::from(x).clamp(0.0, 1.0) - y.clamp(0.0, 1.0)).powi(2);
            sse += if c.is_nan() { 1.0 } else { c };
            n += 1;
        }
    }
    (max, psnr_of_mse(sse / n.max(1) as f64))
}

type Run<'a> = Box<dyn FnMut(&mut ShadeOut<f32>) + 'a>;

/// Measures every back end of every shader.
pub fn section(sz: &Sizes) -> Result<Section, String> {
    let lights = table1_lights();
    let set = PointSet::random(sz.points, 0x5eed_2010);
    let mut rows: Vec<Row> = Vec::new();
    for name in Surface::NAMES {
        let surface = Surface::by_name(name).ok_or("unknown shader")?;
        let stem = if name == "phong" { "plastic" } else { name };
        let reference = shade_points_f64::<f64, _, _>(&surface, &lights, &set);
        let dual_reference =
            surface.meta().uses_derivatives.then(|| shade_points_f64::<Dual<f64>, _, _>(&surface, &lights, &set));
        let interp = InterpShader::new(Arc::new(crate::interp_bench::load_program(stem)?));
        #[cfg(feature = "jit")]
        let jit = {
            let file = crate::jit::rsl_dir().join(format!("{stem}.sl"));
            let include = vec![crate::jit::rsl_dir().join("include")];
            anysl_jit::JitShader::from_file(&file, &include, anysl_jit::JitOptions::default())
                .map_err(|e| e.to_string())?
        };
        let mut runners: Vec<(String, &'static str, Run)> = Vec::new();
        for (inst, f) in crate::kernels::instantiations() {
            let s = &surface;
            let (l, p) = (&lights, &set);
            runners.push((inst.to_string(), "generic Rust", Box::new(move |o| f(s, l, p, o))));
        }
        if let Some(native) = crate::native::runner(&surface) {
            let s = &surface;
            let (l, p) = (&lights, &set);
            runners.push(("native-f32x8".into(), "hand-written", Box::new(move |o| native(s, l, p, o))));
        }
        {
            let (l, p, i) = (&lights, &set, &interp);
            runners.push((
                "interp-f32".into(),
                "interpreter",
                Box::new(move |o| shade_points::<f32, _, Light>(i, l, p, o)),
            ));
            runners.push((
                "interp-f32x8".into(),
                "interpreter",
                Box::new(move |o| shade_points::<F32x8, _, Light>(i, l, p, o)),
            ));
        }
        #[cfg(feature = "jit")]
        {
            use anysl_simd::{F32x16, F32x4};
            let (l, p, j) = (&lights, &set, &jit);
            runners.push(("jit-f32".into(), "LLVM JIT", Box::new(move |o| shade_points::<f32, _, Light>(j, l, p, o))));
            runners.push((
                "jit-f32x4".into(),
                "LLVM JIT",
                Box::new(move |o| shade_points::<F32x4, _, Light>(j, l, p, o)),
            ));
            runners.push((
                "jit-f32x8".into(),
                "LLVM JIT",
                Box::new(move |o| shade_points::<F32x8, _, Light>(j, l, p, o)),
            ));
            runners.push((
                "jit-f32x16".into(),
                "LLVM JIT",
                Box::new(move |o| shade_points::<F32x16, _, Light>(j, l, p, o)),
            ));
        }
        let mut outs: Vec<ShadeOut<f32>> = runners.iter().map(|_| ShadeOut::new(set.len())).collect();
        let mut times: Vec<Vec<f64>> = vec![Vec::new(); runners.len()];
        // Round 0 warms up (and compiles JIT variants); the rest are timed round-robin.
        for round in 0..=sz.runs {
            for (k, (_, _, f)) in runners.iter_mut().enumerate() {
                let t = Instant::now();
                f(&mut outs[k]);
                if round > 0 {
                    times[k].push(t.elapsed().as_secs_f64());
                }
            }
        }
        for (k, (backend, kind, _)) in runners.iter().enumerate() {
            let dual = backend.starts_with("dual");
            let (refname, r) = match (&dual_reference, dual) {
                (Some(d), true) => ("dual-f64", d),
                _ => ("f64", &reference),
            };
            let (max_abs, psnr) = errors(&outs[k], r);
            rows.push(Row {
                shader: name.to_string(),
                backend: backend.clone(),
                kind,
                ns_per_point: median(std::mem::take(&mut times[k])) * 1e9 / set.len() as f64,
                max_abs,
                psnr,
                reference: refname,
            });
        }
    }
    Ok(render(sz, &rows))
}

/// Errors below this are drawn at this value (log axis; the f64 row is exact).
const FLOOR: f64 = 1e-9;

fn render(sz: &Sizes, rows: &[Row]) -> Section {
    let mut html = format!(
        "<p>{} random shading points on the visible half of a unit sphere (two point lights and ambient), one \
         thread, median of {} round-robin runs. Time is nanoseconds per shading point; error is the max \
         absolute difference over Ci and Oi to the <code>f64</code> instantiation of the hand-written generic \
         shader (dual rows of the derivative-using shaders — brick, checker, parquet — against <code>dual-f64</code>, \
         because filtering changes the result by design; interval rows use the midpoint of the bound). PSNR is \
         over the same channels clamped to [0, 1]. Interpreter and JIT rows run the <code>.sl</code> shaders of \
         <code>shaders/rsl</code>. In the plots, errors below {FLOOR:.0e} (the f64 row itself) sit on the floor, \
         and the grey staircase is the Pareto front: no back end is both faster and more accurate than a point \
         on it.</p>\n<div class=\"plots\">",
        sz.points, sz.runs
    );
    let kinds = ["generic Rust", "hand-written", "interpreter", "LLVM JIT"];
    let mut summary = Vec::new();
    let mut front_count: Vec<(String, usize)> = Vec::new();
    for name in Surface::NAMES {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.shader == name).collect();
        let series: Vec<Series> = kinds
            .iter()
            .map(|k| Series {
                name: (*k).to_string(),
                points: mine
                    .iter()
                    .filter(|r| r.kind == *k)
                    .map(|r| Point { x: r.ns_per_point, y: r.max_abs.max(FLOOR), label: r.backend.clone() })
                    .collect(),
            })
            .filter(|s| !s.points.is_empty())
            .collect();
        html.push_str(&scatter_svg(
            &Scatter {
                title: name,
                x_label: "ns per shading point",
                y_label: "max abs error",
                size: (410, 300),
                pareto: true,
                lines: false,
            },
            &series,
        ));
        let pts: Vec<(f64, f64)> = mine.iter().map(|r| (r.ns_per_point, r.max_abs.max(FLOOR))).collect();
        for (x, y) in pareto_front(&pts) {
            if let Some(r) = mine.iter().find(|r| r.ns_per_point == x && r.max_abs.max(FLOOR) == y) {
                match front_count.iter_mut().find(|(b, _)| *b == r.backend) {
                    Some((_, n)) => *n += 1,
                    None => front_count.push((r.backend.clone(), 1)),
                }
            }
        }
    }
    html.push_str("</div>\n");
    let body: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.shader.clone(),
                r.backend.clone(),
                r.kind.to_string(),
                format!("{:.1}", r.ns_per_point),
                sci(r.max_abs),
                db(r.psnr),
                r.reference.to_string(),
            ]
        })
        .collect();
    html.push_str(&table(&["shader", "back end", "kind", "ns/point", "max abs err", "PSNR dB", "reference"], &body));
    front_count.sort_by(|a, b| b.1.cmp(&a.1));
    summary.push(format!(
        "Pareto-optimal (shaders on whose front the back end lies): {}",
        front_count.iter().map(|(b, n)| format!("{b} {n}")).collect::<Vec<_>>().join(", ")
    ));
    let mean_ns = |b: &str| {
        let v: Vec<f64> = rows.iter().filter(|r| r.backend == b).map(|r| r.ns_per_point).collect();
        (!v.is_empty()).then(|| (v.iter().map(|x| x.ln()).sum::<f64>() / v.len() as f64).exp())
    };
    let list: Vec<String> =
        ["f32", "f64", "f32x16", "dual-f32x8", "interval-f32", "interp-f32x8", "jit-f32x8", "jit-f32x16"]
            .iter()
            .filter_map(|b| mean_ns(b).map(|t| format!("{b} {t:.1}")))
            .collect();
    summary.push(format!("geometric-mean ns per point over the ten shaders: {}", list.join(", ")));
    let worst = |b: &str| rows.iter().filter(|r| r.backend == b).map(|r| r.max_abs).fold(0.0, f64::max);
    summary.push(format!(
        "worst max abs error vs f64: f32 {}, f32x16 {}, interp-f32x8 {}{}; interval-f32 midpoints up to {} (hulls of \"maybe\" branches)",
        sci(worst("f32")),
        sci(worst("f32x16")),
        sci(worst("interp-f32x8")),
        if cfg!(feature = "jit") { format!(", jit-f32x8 {}", sci(worst("jit-f32x8"))) } else { String::new() },
        sci(worst("interval-f32"))
    ));
    Section { id: "accuracy", title: "b. Error against run time per shader and back end", html, summary }
}
