//! `rslc eval --backend jit` = `--backend interp`: every conformance program through the JIT's
//! eval entry (`JitShader::eval_point`, compiled code at `f32`, or `Dual<f32>` when the
//! program uses derivatives, with its output parameters read back), against its `// expect:`
//! lines and against the interpreter on the same point.

use crate::rsl_conformance_interp::{param_const, run};
use anysl_ad::Dual;
use anysl_core::{PointContext, Shader, ShadingFloat};
use anysl_jit::{JitOptions, JitShader, PointOutputs};
use anysl_rsl::back::interp::Program;
use anysl_rsl::ir::Const;
use anysl_rsl::passes::{optimize, PassOptions};
use anysl_rsl::CompileOptions;
use anysl_shaders::{table1_lights, Light};
use anysl_tests::rsl_harness::{check, grid_globals, parse_directives, Directives};
use std::path::Path;

fn eval<F: ShadingFloat>(jit: &JitShader, d: &Directives, lights: &[Light]) -> Result<PointOutputs, String> {
    let mut ctx = PointContext::new(grid_globals::<F>(d, 0, 0, 1, 1), lights);
    ctx.spaces = &d.spaces;
    jit.eval_point(&mut ctx)
}

#[test]
fn conformance_suite_through_the_jit_eval_entry() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data").join("rsl").join("conformance");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("conformance dir")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "sl"))
        .collect();
    files.sort();
    let table1 = table1_lights();
    let (mut failures, mut unsupported, mut ran) = (Vec::new(), Vec::new(), 0);
    for f in &files {
        let name = f.file_name().unwrap_or_default().to_string_lossy().into_owned();
        let d = parse_directives(&std::fs::read_to_string(f).expect("readable"));
        let lights: &[Light] = if d.lights { &table1 } else { &[] };
        let Ok(compiled) = anysl_rsl::compile_file(f, &CompileOptions::default()) else {
            failures.push(format!("{name}: does not compile"));
            continue;
        };
        let mut jit = JitShader::new(compiled.module.clone(), JitOptions::default()).expect("interpretable");
        for (pname, v) in &d.sets {
            if let Err(e) = jit.set_param(pname, v) {
                failures.push(format!("{name}: set {pname}: {e}"));
            }
        }
        let m = optimize(compiled.module, &PassOptions::default());
        let derivs = m.uses_derivatives();
        let r = if derivs { eval::<Dual<f32>>(&jit, &d, lights) } else { eval::<f32>(&jit, &d, lights) };
        let o = match r {
            Ok(o) => o,
            // Strings are compile-time values in the JIT (`format` of numbers); no textures.
            Err(e) if e.contains("not supported by the JIT") => {
                unsupported.push(format!("{name}: {e}"));
                continue;
            }
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        ran += 1;
        let mut outs: Vec<(&str, Vec<f64>)> = vec![("Ci", o.ci.to_vec()), ("Oi", o.oi.to_vec())];
        outs.extend(o.params.iter().map(|(n, v)| (n.as_str(), v.clone())));
        if let Err(e) = check(&d, &outs) {
            failures.push(format!("{name}: {e}"));
            continue;
        }
        // The interpreter on the same point: every output within 1e-5 relative.
        let prog = Program::new(m).expect("interpretable");
        let mut values: Vec<Const> = prog.module.params.iter().map(|p| p.default.clone()).collect();
        for (pname, v) in &d.sets {
            if let (Some(i), Some(c)) = (prog.module.params.iter().position(|p| &p.name == pname), param_const(v)) {
                let c = match (&values[i], c) {
                    (Const::Triple(_), Const::Float(x)) => Const::Triple([x; 3]),
                    (_, c) => c,
                };
                prog.module.set_param_value(&mut values, i, c);
            }
        }
        let interp = if derivs {
            run::<Dual<f32>>(&prog, &values, &d, lights, 1)
        } else {
            run::<f32>(&prog, &values, &d, lights, 1)
        };
        for (key, want) in &interp[0] {
            let Some((_, got)) = outs.iter().find(|(n, _)| n == key) else {
                failures.push(format!("{name}: the JIT has no output {key}"));
                continue;
            };
            let close = got.len() == want.len()
                && got.iter().zip(want).all(|(a, b)| (a - b).abs() <= 1e-5 * b.abs().max(1.0) || a == b);
            if !close {
                failures.push(format!("{name}: {key}: jit {got:?}, interpreter {want:?}"));
            }
        }
    }
    eprintln!("{ran} programs through the JIT; unsupported:\n{}", unsupported.join("\n"));
    assert!(unsupported.len() <= 8, "too many programs the JIT cannot compile:\n{}", unsupported.join("\n"));
    assert!(ran >= 250, "only {ran} programs ran");
    assert!(failures.is_empty(), "{} failures:\n{}", failures.len(), failures.join("\n"));
}
