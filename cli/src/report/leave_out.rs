//! Section e: leaving out what a scene does not need. Per Table-1 `.sl` shader: IR instruction
//! counts with and without constant folding + dead-code elimination and parameter
//! specialization (`anysl_rsl::passes::optimize`), the interpreter's speed for each, and with
//! the JIT the LLVM instruction counts, compile time and speed with and without specialization
//! and for the dual-number variant that derivative-activity analysis avoids. Then a check that
//! a scene compiles only the shaders and variants it uses.

use super::{median, table, Section, Sizes};
use anysl_core::points::{shade_points, PointSet, ShadeOut};
use anysl_core::Shader;
use anysl_rsl::back::interp::{InterpShader, Program};
use anysl_rsl::ir::Module;
use anysl_rsl::passes::{optimize, PassOptions};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::F32x8;
use std::sync::Arc;
use std::time::Instant;

fn lowered(stem: &str) -> Result<Module, String> {
    let dir = crate::interp_bench::rsl_dir();
    let file = dir.join(format!("{stem}.sl"));
    let opts = anysl_rsl::CompileOptions { include_dirs: vec![dir.join("include")], ..Default::default() };
    Ok(anysl_rsl::compile_file(&file, &opts).map_err(|e| e.to_string())?.module)
}

/// Median ns per point of `f` over the set.
fn ns_per_point(set: &PointSet, runs: usize, mut f: impl FnMut(&mut ShadeOut<f32>)) -> f64 {
    let mut out = ShadeOut::new(set.len());
    f(&mut out);
    let times: Vec<f64> = (0..runs.max(1))
        .map(|_| {
            let t = Instant::now();
            f(&mut out);
            t.elapsed().as_secs_f64()
        })
        .collect();
    median(times) * 1e9 / set.len() as f64
}

/// Measures the passes.
pub fn section(sz: &Sizes) -> Result<Section, String> {
    let lights = table1_lights();
    let set = PointSet::random(sz.points, 0x5eed_2010);
    let configs: [(&str, PassOptions); 3] = [
        ("no passes", PassOptions { fold: false, dce: false, ..PassOptions::default() }),
        ("fold + DCE", PassOptions::default()),
        ("specialized + fold + DCE", PassOptions { specialize_defaults: true, ..PassOptions::default() }),
    ];
    let mut ir_rows = Vec::new();
    let mut deriv_rows = Vec::new();
    let mut summary = Vec::new();
    let mut shrink = Vec::new();
    let mut interp_gain = Vec::new();
    #[cfg(feature = "jit")]
    let mut jit_rows = Vec::new();
    #[cfg(feature = "jit")]
    let (mut spec_gain, mut dual_cost) = (Vec::new(), Vec::new());
    for name in Surface::NAMES {
        let stem = if name == "phong" { "plastic" } else { name };
        let module = lowered(stem)?;
        let mut row = vec![name.to_string(), module.func.inst_count().to_string()];
        let mut speeds = Vec::new();
        let mut uses = false;
        for (_, opts) in &configs {
            let t = Instant::now();
            let m = optimize(module.clone(), opts);
            let ms = t.elapsed().as_secs_f64() * 1e3;
            uses = m.uses_derivatives();
            let n = m.module().func.inst_count();
            let prog = Program::new(m).map_err(|e| format!("{stem}: {e}"))?;
            let interp = InterpShader::new(Arc::new(prog));
            let ns = ns_per_point(&set, sz.runs, |o| shade_points::<F32x8, _, Light>(&interp, &lights, &set, o));
            speeds.push(ns);
            row.push(n.to_string());
            row.push(format!("{ms:.2}"));
            row.push(format!("{ns:.0}"));
        }
        let first = row[1].parse::<f64>().unwrap_or(1.0);
        let last = row[row.len() - 3].parse::<f64>().unwrap_or(1.0);
        shrink.push(last / first);
        interp_gain.push(speeds[0] / speeds[2]);
        ir_rows.push(row);
        let hand = Surface::by_name(name).map(|s| s.meta().uses_derivatives).unwrap_or(false);
        deriv_rows.push(vec![
            name.to_string(),
            uses.to_string(),
            hand.to_string(),
            if uses == hand { "agree".into() } else { "DIFFER".into() },
        ]);
        #[cfg(feature = "jit")]
        {
            use anysl_ad::Dual;
            use anysl_jit::{compile, JitOptions, JitShader, Variant};
            let values: Vec<_> = module.params.iter().map(|p| p.default.clone()).collect();
            let mut r = vec![name.to_string()];
            let mut ns_list = Vec::new();
            for (spec, variant) in [(true, Variant::X8), (false, Variant::X8), (true, Variant::DualX8)] {
                let opts = JitOptions { specialize: spec, ..JitOptions::default() };
                let cs = compile(&module, &values, variant, &opts).map_err(|e| e.to_string())?;
                let insts = cs.stats.insts.iter().find(|(s, _)| s == "llvm-optimized").map_or(0, |(_, n)| *n);
                let shader = JitShader::new(module.clone(), opts).map_err(|e| e.to_string())?;
                let ns = if variant == Variant::X8 {
                    ns_per_point(&set, sz.runs, |o| shade_points::<F32x8, _, Light>(&shader, &lights, &set, o))
                } else {
                    ns_per_point(&set, sz.runs, |o| shade_points::<Dual<F32x8>, _, Light>(&shader, &lights, &set, o))
                };
                ns_list.push(ns);
                r.push(insts.to_string());
                r.push(format!("{:.0}", cs.stats.total_ms()));
                r.push(format!("{ns:.1}"));
            }
            spec_gain.push(ns_list[1] / ns_list[0]);
            dual_cost.push(ns_list[2] / ns_list[0]);
            jit_rows.push(r);
        }
    }
    let gm = |v: &[f64]| (v.iter().map(|x| x.ln()).sum::<f64>() / v.len().max(1) as f64).exp();
    let mut html = String::from(
        "<h3>IR passes and the interpreter</h3><p>Per Table-1 <code>.sl</code> shader: IR instructions after \
         lowering, then with each pass configuration of <code>anysl_rsl::passes::optimize</code> (instruction \
         count, pass time in ms, and the batched interpreter's ns per shading point on <code>F32x8</code> \
         chunks). <i>specialized</i> replaces every uniform parameter by the instance's value (the defaults) \
         before folding.</p>",
    );
    let mut head = vec!["shader", "lowered"];
    for (n, _) in &configs {
        head.extend([*n, "ms", "interp ns/pt"]);
    }
    html.push_str(&table(&head, &ir_rows));
    summary.push(format!(
        "IR: specialization + folding + DCE keeps {:.0}% of the lowered instructions (geometric mean) and speeds the interpreter up {:.2}×",
        gm(&shrink) * 100.0,
        gm(&interp_gain)
    ));
    #[cfg(feature = "jit")]
    {
        html.push_str(
            "<h3>LLVM JIT</h3><p>Per shader, the JIT's <code>F32x8</code> variant with specialization (the \
             default), without it (uniform parameters read at run time), and the <code>Dual&lt;F32x8&gt;</code> \
             variant — what every shader would cost if derivative-activity analysis did not tell the renderer \
             that it can shade on plain floats. LLVM instructions after <code>default&lt;O2&gt;</code>, cold \
             compile time (IR passes to machine code), ns per shading point.</p>",
        );
        html.push_str(&table(
            &[
                "shader",
                "spec insts",
                "spec ms",
                "spec ns/pt",
                "generic insts",
                "generic ms",
                "generic ns/pt",
                "dual insts",
                "dual ms",
                "dual ns/pt",
            ],
            &jit_rows,
        ));
        summary.push(format!(
            "JIT: specialization makes x8 code {:.2}× faster (geometric mean); the dual-x8 variant that the derivative analysis avoids would cost {:.2}× the time",
            gm(&spec_gain),
            gm(&dual_cost)
        ));
    }
    html.push_str(
        "<h3>Derivative activity</h3><p>Whether a shader needs derivatives, from the IR's derivative-activity \
         analysis (the interpreter's and the JIT's <code>uses_derivatives</code>) and from the hand-written \
         generic shader's metadata. Renderers shade a shader with <code>Dual</code> only when it says so.</p>",
    );
    html.push_str(&table(&["shader", "IR analysis", "hand-written metadata", ""], &deriv_rows));
    let disagree = deriv_rows.iter().filter(|r| r[3] != "agree").count();
    summary.push(format!(
        "derivative analysis: {} of 10 shaders need derivatives ({}); IR analysis and hand-written metadata {}",
        deriv_rows.iter().filter(|r| r[1] == "true").count(),
        deriv_rows.iter().filter(|r| r[1] == "true").map(|r| r[0].as_str()).collect::<Vec<_>>().join(", "),
        if disagree == 0 { "agree on all".to_string() } else { format!("disagree on {disagree}") }
    ));
    let (check_html, check_summary) = lazy_check(sz)?;
    html.push_str(&check_html);
    summary.push(check_summary);
    Ok(Section {
        id: "leave-out",
        title: "e. Leaving out: specialization, dead code, derivatives, unused shaders",
        html,
        summary,
    })
}

/// Renders scenes with JIT shaders and lists what got compiled.
#[cfg(feature = "jit")]
fn lazy_check(sz: &Sizes) -> Result<(String, String), String> {
    use anysl_jit::{JitOptions, JitShader, Variant};
    use anysl_renderers::{render_packet, scenes, RenderOptions};
    let load = |stem: &str| -> Result<JitShader, String> {
        let file = crate::jit::rsl_dir().join(format!("{stem}.sl"));
        JitShader::from_file(&file, &[crate::jit::rsl_dir().join("include")], JitOptions::default())
            .map_err(|e| e.to_string())
    };
    let opts = RenderOptions { threads: 1, derivatives: true, ..RenderOptions::default() };
    let size = if sz.quick { 16 } else { 64 };
    let mut rows = Vec::new();
    let mut ok = true;
    // Scene 1: the sphere is plastic; wood and checker are loaded into the scene but no object uses them.
    // Scene 2: the sphere is checker (uses derivatives); plastic and wood unused.
    for (used, others) in [("plastic", ["wood", "checker"]), ("checker", ["plastic", "wood"])] {
        let mut scene = scenes::table1(load(used)?, table1_lights(), size);
        for o in others {
            scene.surfaces.push(load(o)?);
        }
        let _ = render_packet::<F32x8, _, _>(&scene, &opts);
        let names = [used, others[0], others[1]];
        for (k, s) in scene.surfaces.iter().enumerate() {
            let compiled = s.compiled();
            let derivs = s.meta().uses_derivatives;
            let expect: Vec<Variant> = if k > 0 {
                Vec::new()
            } else if derivs {
                vec![Variant::DualX8]
            } else {
                vec![Variant::X8]
            };
            let pass = compiled == expect;
            ok &= pass;
            rows.push(vec![
                format!("sphere: {used}"),
                names[k].to_string(),
                if k == 0 { "yes".into() } else { "no".into() },
                derivs.to_string(),
                format!("{:?}", compiled.iter().map(|v| v.name()).collect::<Vec<_>>()),
                format!("{:?}", expect.iter().map(|v| v.name()).collect::<Vec<_>>()),
                if pass { "pass".into() } else { "FAIL".into() },
            ]);
        }
    }
    let mut html = String::from(
        "<h3>Only what the scene uses is compiled</h3><p>Each <code>.sl</code> shader is loaded as a \
         <code>JitShader</code> (parsed and checked; machine code is compiled per float type on first use). \
         Two scenes each hold three shaders but put only one on the sphere; the packet renderer renders them \
         with 8-wide packets and derivatives enabled, then we list the variants each shader compiled. \
         Expected: the unused shaders compile nothing, a shader without derivatives compiles only \
         <code>x8</code> (no <code>Dual</code> path), the derivative-using checker compiles only \
         <code>dual-x8</code>.</p>",
    );
    html.push_str(&table(&["scene", "shader", "on an object", "uses derivatives", "compiled", "expected", ""], &rows));
    let summary = format!(
        "lazy compilation check ({}): a scene compiles only the shaders on its objects, and no Dual variant unless the shader uses derivatives",
        if ok { "pass" } else { "FAIL" }
    );
    Ok((html, summary))
}

/// Without the JIT nothing is compiled at run time; the renderers' choice is shown instead.
#[cfg(not(feature = "jit"))]
fn lazy_check(_: &Sizes) -> Result<(String, String), String> {
    Ok((
        "<h3>Only what the scene uses is compiled</h3><p>Built without the JIT: there is no run-time \
         compilation to observe. The renderers choose <code>Dual</code> per shader from \
         <code>uses_derivatives</code> (table above).</p>"
            .into(),
        "lazy compilation check: needs the JIT (not built)".into(),
    ))
}
