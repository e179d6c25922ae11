//! The RSL conformance suite (`tests/data/rsl/conformance`, see `tests/data/rsl/README.md`) through
//! generated Rust: `tests/build.rs` generates every program; each runs on the eval harness's
//! 1×1 grid with the table1 lights (at f32, or `Dual<f32>` when it uses derivatives) and every
//! `// expect:` is checked within its tolerance.

use anysl_ad::Dual;
use anysl_core::prelude::*;
use anysl_core::PointContext;
use anysl_shaders::{table1_lights, Light};
use anysl_tests::rsl_harness::{check, grid_globals, parse_directives, Directives};
use std::path::Path;

/// A generated surface with its outputs by name.
pub trait Generated: SurfaceShader + Clone {
    /// Runs the shader; lane 0 of every output (`Ci`, `Oi`, output parameters).
    fn eval<F: ShadingFloat, C: ShadingContext<F>>(
        &self,
        ctx: &mut C,
        e: &mut Exec<F>,
    ) -> Vec<(&'static str, Vec<f64>)>;
}

/// Runs one generated shader.
pub trait Visitor {
    /// What a visit returns.
    type Output;
    /// Runs on `s`; `derivs`: the shader uses derivatives (shade with dual numbers).
    fn visit<S: Generated>(self, s: S, derivs: bool) -> Self::Output;
}

include!(concat!(env!("OUT_DIR"), "/conformance.rs"));

/// Programs that cannot pass through generated Rust, with the reason. Keep it empty when
/// possible; every entry names a bug to fix elsewhere.
const SKIP: &[(&str, &str)] = &[];

struct Eval<'a> {
    d: &'a Directives,
    lights: &'a [Light],
}

#[inline(never)]
fn eval_as<F: ShadingFloat, S: Generated>(s: &S, d: &Directives, lights: &[Light]) -> Vec<(&'static str, Vec<f64>)> {
    let mut ctx = PointContext::new(grid_globals::<F>(d, 0, 0, 1, 1), lights);
    ctx.spaces = &d.spaces;
    s.eval(&mut ctx, &mut Exec::new())
}

impl Visitor for Eval<'_> {
    type Output = Result<Vec<(&'static str, Vec<f64>)>, String>;
    fn visit<S: Generated>(self, mut s: S, derivs: bool) -> Self::Output {
        for (name, v) in &self.d.sets {
            s.set_param(name, v).map_err(|e| format!("set {name}: {e}"))?;
        }
        Ok(if derivs {
            eval_as::<Dual<f32>, S>(&s, self.d, self.lights)
        } else {
            eval_as::<f32, S>(&s, self.d, self.lights)
        })
    }
}

#[test]
fn conformance_suite_through_generated_rust() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data").join("rsl").join("conformance");
    let table1 = table1_lights();
    let mut failures = Vec::new();
    let mut passed = 0;
    for (stem, msg) in GEN_ERRORS {
        if !SKIP.iter().any(|(s, _)| s == stem) {
            failures.push(format!("{stem}.sl: {msg}"));
        }
    }
    for stem in FILES {
        if SKIP.iter().any(|(s, _)| s == stem) {
            continue;
        }
        let text = std::fs::read_to_string(dir.join(format!("{stem}.sl"))).expect("conformance file");
        let d = parse_directives(&text);
        let lights: &[Light] = if d.lights { &table1 } else { &[] };
        match with_shader(stem, Eval { d: &d, lights }).expect("registered") {
            Ok(outputs) => match check(&d, &outputs) {
                Ok(()) => passed += 1,
                Err(e) => failures.push(format!("{stem}.sl: {e}")),
            },
            Err(e) => failures.push(format!("{stem}.sl: {e}")),
        }
    }
    eprintln!("{passed} conformance programs pass through generated Rust, {} skipped", SKIP.len());
    assert!(failures.is_empty(), "{} conformance failures:\n{}", failures.len(), failures.join("\n"));
}
