//! `.sl` light shaders compiled by the JIT (`illuminate`, `solar`, the light's `Ps`, `L` and
//! `Cl`, named spaces through the host) against the interpreter, per float type, and their
//! code compiled rather than handed to the interpreter.

use anysl_ad::Dual;
use anysl_core::points::PointSet;
use anysl_core::{Exec, LightOutput, LightShader, Shader, ShadingFloat, Spaces};
use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_rsl::back::interp::InterpShader;
use anysl_simd::{F32x16, F32x4, F32x8};
use std::path::PathBuf;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The light's `Cl` and `L` per lane, for the points of `set` in packets of `F`.
fn run<F: ShadingFloat, L: LightShader>(l: &L, set: &PointSet, spaces: &Spaces) -> Vec<[f64; 6]> {
    let mut out = Vec::new();
    let mut i = 0;
    while i + F::LANES <= set.len() {
        let ps = set.globals::<F>(i).P;
        let o: LightOutput<F> = l.light_in(&mut Exec::<F>::new(), ps, spaces);
        for k in 0..F::LANES {
            out.push([o.cl.r, o.cl.g, o.cl.b, o.l.x, o.l.y, o.l.z].map(|x| x.lane(k)));
        }
        i += F::LANES;
    }
    out
}

fn close(a: &[[f64; 6]], b: &[[f64; 6]], what: &str) {
    assert_eq!(a.len(), b.len());
    let mut lit = 0;
    for (x, y) in a.iter().zip(b) {
        for c in 0..6 {
            let tol = 2e-6 * x[c].abs().max(y[c].abs()).max(1.0);
            assert!((x[c] - y[c]).abs() <= tol, "{what}: JIT {x:?} against the interpreter {y:?}");
        }
        lit += usize::from(x[..3].iter().any(|&c| c != 0.0));
    }
    assert!(lit > 0, "{what}: no point is lit, the comparison says nothing");
}

/// Compares the JIT's light with the interpreter's for every float type the JIT compiles a
/// light for, and checks each variant compiled (no silent fallback).
fn check(jit: &JitShader, spaces: &Spaces, what: &str) {
    let set = PointSet::random(96, 0x11647);
    let interp: &InterpShader = jit.interp();
    for v in [Variant::F32, Variant::X4, Variant::X8, Variant::X16, Variant::DualF32, Variant::DualX8] {
        if let Err(e) = jit.variant(v) {
            panic!("{what}: the {} variant does not compile: {e}", v.name());
        }
    }
    close(&run::<f32, _>(jit, &set, spaces), &run::<f32, _>(interp, &set, spaces), &format!("{what} f32"));
    close(&run::<F32x4, _>(jit, &set, spaces), &run::<F32x4, _>(interp, &set, spaces), &format!("{what} x4"));
    close(&run::<F32x8, _>(jit, &set, spaces), &run::<F32x8, _>(interp, &set, spaces), &format!("{what} x8"));
    close(&run::<F32x16, _>(jit, &set, spaces), &run::<F32x16, _>(interp, &set, spaces), &format!("{what} x16"));
    close(
        &run::<Dual<f32>, _>(jit, &set, spaces),
        &run::<Dual<f32>, _>(interp, &set, spaces),
        &format!("{what} dual-f32"),
    );
    close(
        &run::<Dual<F32x8>, _>(jit, &set, spaces),
        &run::<Dual<F32x8>, _>(interp, &set, spaces),
        &format!("{what} dual-x8"),
    );
    assert_eq!(jit.emission(), interp.emission(), "{what}: emission");
    assert_eq!(jit.category(), interp.category(), "{what}: category");
}

#[test]
fn standard_light_shaders_match_the_interpreter() {
    use anysl_core::ParamValue as P;
    let cases: &[(&str, &[(&str, P)])] = &[
        ("ambientlight", &[("intensity", P::Float(0.3))]),
        ("distantlight", &[("from", P::Triple([1.0, 2.0, -1.0])), ("intensity", P::Float(0.8))]),
        ("pointlight", &[("from", P::Triple([0.5, 1.5, 2.0])), ("intensity", P::Float(3.0))]),
        ("pointlight", &[("from", P::Triple([0.5, 1.5, 2.0])), ("falloff", P::Float(0.0))]),
        ("pointlight", &[("from", P::Triple([-1.0, 0.2, 0.4])), ("falloff", P::Float(1.0))]),
        ("spotlight", &[("from", P::Triple([0.0, 0.0, -2.0])), ("coneangle", P::Float(0.4))]),
        ("spotlight", &[("to", P::Triple([0.3, 0.2, 1.0])), ("beamdistribution", P::Float(5.0))]),
    ];
    for (name, params) in cases {
        let file = repo().join(format!("shaders/rsl/{name}.sl"));
        let mut jit = JitShader::from_file(&file, &[], JitOptions::default()).unwrap();
        for (p, v) in *params {
            jit.set_param(p, v).unwrap();
        }
        if *name == "ambientlight" {
            // No `illuminate`: `Cl` everywhere, `L` zero.
            let set = PointSet::random(16, 3);
            let a = run::<F32x8, _>(&jit, &set, Spaces::standard());
            assert!(a.iter().all(|x| (x[0] - 0.3).abs() < 1e-6 && x[3..] == [0.0; 3]), "{a:?}");
        }
        check(&jit, Spaces::standard(), &format!("{name} {params:?}"));
    }
}

#[test]
fn a_light_in_its_own_shader_space_matches_the_interpreter() {
    // gobo: `transform("shader", Ps)` goes through the host's spaces; the "shader" space is
    // turned 90° about z and moved (the light's placement in a scene).
    let file = repo().join("scenes/gobo.sl");
    let mut jit = JitShader::from_file(&file, &[], JitOptions::default()).unwrap();
    jit.set_param("frequency", &anysl_core::ParamValue::Float(3.0)).unwrap();
    jit.set_param("coneangle", &anysl_core::ParamValue::Float(1.2)).unwrap();
    let spaces =
        Spaces::new([("shader", [0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.1, -0.2, -2.0, 1.0])]);
    check(&jit, &spaces, "gobo");
}

#[test]
fn illuminate_and_solar_statements_match_the_interpreter() {
    let sources = [
        // No `L` variable: the light's `L` is the statement's.
        "light t() { illuminate(point (0, 1, 0)) { Cl = 1; } }",
        // Two statements, the first in a cone; `Cl` summed.
        "light t(float k = 2) { illuminate(point (0, 2, 0), vector (0, -1, 0), 0.6) { Cl = color (k, 0, 0); }
           illuminate(point (1, 0, 0)) { Cl += color (0, L . L, 0); } }",
        // `return` inside the body: those lanes skip the rest of the shader.
        "light t() { illuminate(point (0, 0, 0)) { if (xcomp(Ps) > 0) return; Cl = color (Ps); } Cl += 0.5; }",
        // A cone wider than a hemisphere.
        "light t() { illuminate(point (0, 0, -1), vector (0, 0, 1), 2.5) { Cl = color (1, ycomp(L), 0); } }",
        // `solar` without and with an axis.
        "light t() { solar() { Cl = 2; } }",
        "light t() { solar(vector (1, 1, 0), 0.1) { Cl = color (L); } }",
        // `P` and `Ps` are the surface point.
        "light t() { illuminate(point (0, 0, 3)) { Cl = color (P - Ps) + color (Ps) + 0.25; } }",
        // Varying work before the statement, and a loop in the body.
        "light t() { float d = length(Ps); illuminate(point (0, 0, 0)) { float s = 0; float i;
           for (i = 0; i < 3; i += 1) { s += d * i; if (s > 1) break; } Cl = color (s, d, 1); } }",
    ];
    for src in sources {
        let jit =
            JitShader::from_source("t.sl", src, &[], JitOptions::default()).unwrap_or_else(|e| panic!("{src}: {e}"));
        check(&jit, Spaces::standard(), src);
    }
}
