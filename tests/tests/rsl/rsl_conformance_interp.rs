//! The RSL conformance suite (`tests/data/rsl/conformance`, see `tests/data/rsl/README.md`) through the
//! batched interpreter: every program compiled at test time, run on the eval harness's 1×1 grid
//! with the table1 lights, at `f32` (or `Dual<f32>` when it uses derivatives), at `F32x8` (all
//! lanes must agree with the scalar run), and as a batch of several chunks; every `// expect:`
//! is checked within its tolerance.

use anysl_ad::Dual;
use anysl_core::prelude::*;
use anysl_core::{ParamValue, PointContext};
use anysl_rsl::back::interp::{release, run_batch, Program};
use anysl_rsl::ir::{Const, Global};
use anysl_rsl::passes::{optimize, PassOptions};
use anysl_rsl::CompileOptions;
use anysl_shaders::{table1_lights, Light};
use anysl_simd::F32x8;
use anysl_tests::rsl_harness::{check, grid_globals, parse_directives, Directives};
use std::path::Path;

pub(crate) fn param_const(v: &ParamValue) -> Option<Const> {
    Some(match v {
        ParamValue::Float(x) => Const::Float(*x),
        ParamValue::Triple(t) => Const::Triple(*t),
        ParamValue::String(s) => Const::Str(s.clone()),
        ParamValue::Matrix(m) => Const::Matrix(*m),
        ParamValue::Array(_) => return None,
    })
}

/// Runs `prog` on `chunks` copies of the 1×1 grid point and returns lane `lane` of chunk
/// `chunk`'s outputs.
pub(crate) fn run<F: ShadingFloat>(
    prog: &Program,
    values: &[Const],
    d: &Directives,
    lights: &[Light],
    chunks: usize,
) -> Vec<Vec<(String, Vec<f64>)>> {
    let mut ctxs: Vec<_> = (0..chunks)
        .map(|_| {
            let mut ctx = PointContext::new(grid_globals::<F>(d, 0, 0, 1, 1), lights);
            ctx.spaces = &d.spaces;
            ctx
        })
        .collect();
    let masks = vec![F::Mask::splat(true); chunks];
    let fr = run_batch::<F, _>(prog, values, &mut ctxs, &masks);
    let mut out = Vec::new();
    for k in 0..chunks {
        for lane in 0..F::LANES {
            let read = |loc| fr.read(loc, k).iter().map(|x: &F| x.lane(lane)).collect::<Vec<f64>>();
            let mut o = Vec::new();
            if let Some(l) = prog.global_loc(Global::Ci) {
                o.push(("Ci".to_string(), read(l)));
            }
            match prog.global_loc(Global::Oi) {
                Some(l) => o.push(("Oi".to_string(), read(l))),
                None => o.push(("Oi".into(), vec![1.0; 3])),
            }
            for (i, p) in prog.module.params.iter().enumerate() {
                if let (true, Some(l)) = (p.output, prog.param_loc(i)) {
                    o.push((p.name.clone(), read(l)));
                }
            }
            out.push(o);
        }
    }
    release(fr);
    out
}

fn as_refs(o: &[(String, Vec<f64>)]) -> Vec<(&str, Vec<f64>)> {
    o.iter().map(|(n, v)| (n.as_str(), v.clone())).collect()
}

#[test]
fn conformance_suite_through_the_interpreter() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data").join("rsl").join("conformance");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("conformance dir")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "sl"))
        .collect();
    files.sort();
    assert!(files.len() >= 150, "the conformance suite has {} programs", files.len());
    let table1 = table1_lights();
    let mut failures = Vec::new();
    for f in &files {
        let name = f.file_name().unwrap_or_default().to_string_lossy().into_owned();
        let text = std::fs::read_to_string(f).expect("readable");
        let d = parse_directives(&text);
        let lights: &[Light] = if d.lights { &table1 } else { &[] };
        let compiled = match anysl_rsl::compile_file(f, &CompileOptions::default()) {
            Ok(c) => c,
            Err(e) => {
                failures.push(format!("{name}: does not compile:\n{e}"));
                continue;
            }
        };
        let m = optimize(compiled.module, &PassOptions::default());
        let derivs = m.uses_derivatives();
        let prog = match Program::new(m) {
            Ok(p) => p,
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        let mut values: Vec<Const> = prog.module.params.iter().map(|p| p.default.clone()).collect();
        for (pname, v) in &d.sets {
            match (prog.module.params.iter().position(|p| &p.name == pname), param_const(v)) {
                (Some(i), Some(c)) => {
                    let c = match (&values[i], c) {
                        (Const::Triple(_), Const::Float(x)) => Const::Triple([x; 3]),
                        (_, c) => c,
                    };
                    prog.module.set_param_value(&mut values, i, c);
                }
                _ => failures.push(format!("{name}: cannot set {pname}")),
            }
        }
        let scalar = if derivs {
            run::<Dual<f32>>(&prog, &values, &d, lights, 1)
        } else {
            run::<f32>(&prog, &values, &d, lights, 1)
        };
        if let Err(e) = check(&d, &as_refs(&scalar[0])) {
            failures.push(format!("{name} (scalar): {e}"));
            continue;
        }
        // SIMD and batches: every lane of every chunk agrees with its expectation (printf
        // output is not part of the check).
        let wide = if derivs {
            run::<Dual<F32x8>>(&prog, &values, &d, lights, 3)
        } else {
            run::<F32x8>(&prog, &values, &d, lights, 3)
        };
        if let Some(bad) = wide.iter().map(|o| check(&d, &as_refs(o))).find_map(Result::err) {
            failures.push(format!("{name} (8-wide batch of 3): {bad}"));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} conformance programs fail:\n{}",
        failures.len(),
        files.len(),
        failures.join("\n")
    );
}

/// The four `.sl` lights run by the interpreter (`InterpLight`) give the hand-written lights'
/// `Cl`, `L` and emission at random points, with default and with changed parameters.
#[test]
fn interpreted_lights_match_the_hand_written_ones() {
    use anysl_rsl::back::interp::InterpLight;
    use std::sync::Arc;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join("shaders").join("rsl");
    let opts = CompileOptions { include_dirs: vec![dir.join("include")], ..CompileOptions::default() };
    let mut rng = anysl_core::points::SplitMix64(7);
    for name in ["pointlight", "distantlight", "spotlight", "ambientlight"] {
        let m = anysl_rsl::compile_file(&dir.join(format!("{name}.sl")), &opts).expect("compiles").module;
        let prog = Arc::new(Program::new(optimize(m, &PassOptions::default())).expect("interpretable"));
        for setting in [None, Some(("intensity", ParamValue::Float(2.5)))] {
            let mut interp = InterpLight::new(prog.clone());
            let mut hand = Light::by_name(name).expect("hand-written light");
            if let Some((p, v)) = &setting {
                interp.set_param(p, v).expect("set");
                hand.set_param(p, v).expect("set");
            }
            assert_eq!(interp.emission(), hand.emission(), "{name}: emission");
            for _ in 0..200 {
                let ps = Vec3::c(rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0));
                let a = interp.light::<f32>(&mut Exec::new(), ps);
                let b = hand.light::<f32>(&mut Exec::new(), ps);
                let (ca, cb) = (a.cl.lane(0), b.cl.lane(0));
                let (la, lb) = (a.l.lane(0), b.l.lane(0));
                for i in 0..3 {
                    assert!(
                        (ca[i] - cb[i]).abs() <= 1e-5 * (1.0 + cb[i].abs()),
                        "{name} {setting:?}: Cl {ca:?} vs {cb:?}"
                    );
                    assert!(
                        (la[i] - lb[i]).abs() <= 1e-5 * (1.0 + lb[i].abs()),
                        "{name} {setting:?}: L {la:?} vs {lb:?}"
                    );
                }
            }
        }
    }
}
