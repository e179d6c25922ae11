//! Named coordinate systems: the JIT against the interpreter with a table of spaces, and
//! against values worked out by hand.

use anysl_ad::Dual;
use anysl_core::points::PointSet;
use anysl_core::{Exec, PointContext, ShadingFloat, Spaces, SurfaceShader};
use anysl_jit::{JitOptions, JitShader};
use anysl_shaders::Light;
use anysl_simd::F32x8;

/// object: scale 2, then translate (1, 2, 3); shader: 90° about z; camera: translate
/// (0, 0, -5); NDC, raster, screen: a perspective-like projective matrix; mycs: translate
/// (0, 0, 5).
fn table() -> Spaces {
    Spaces::new([
        ("object", [2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 1.0, 2.0, 3.0, 1.0]),
        ("shader", [0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]),
        ("camera", [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -5.0, 1.0]),
        ("screen", [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, -0.5, 1.0]),
        ("NDC", [0.5, 0.0, 0.0, 0.0, 0.0, -0.5, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.5, 0.5, 0.0, 1.0]),
        ("raster", [64.0, 0.0, 0.0, 0.0, 0.0, 48.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 3.0, 4.0, 0.0, 1.0]),
        ("mycs", [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 5.0, 1.0]),
    ])
}

const EXPRS: &[&str] = &[
    "color(transform(\"object\", P))",
    "color(transform(\"shader\", \"camera\", P))",
    "color(vtransform(\"object\", I))",
    "color(ntransform(\"object\", N))",
    "color(ntransform(\"shader\", \"NDC\", N))",
    "color(transform(\"NDC\", P))",
    "color(transform(\"raster\", P))",
    "color(transform(\"screen\", P))",
    "color(transform(\"world\", \"mycs\", P))",
    "color(point \"object\" (s, t, 1))",
    "color(vector \"shader\" (s, t, 0))",
    "color(normal \"camera\" (s, 1, t))",
    "color(transform(matrix \"object\" 1, P))",
    "color(transform(\"mycs\", matrix \"raster\" (2), P))",
    "color(transform(\"no such space\", P))",
];

fn shade<F: ShadingFloat, S: SurfaceShader>(s: &S, set: &PointSet, spaces: &Spaces) -> Vec<[f64; 3]> {
    let lights: Vec<Light> = Vec::new();
    let mut out = Vec::new();
    let mut i = 0;
    while i + F::LANES <= set.len() {
        let mut ctx = PointContext::new(set.globals::<F>(i), &lights);
        ctx.spaces = spaces;
        let o = s.shade(&mut ctx, &mut Exec::<F>::new());
        for l in 0..F::LANES {
            out.push([o.Ci.r.lane(l), o.Ci.g.lane(l), o.Ci.b.lane(l)]);
        }
        i += F::LANES;
    }
    out
}

fn close(a: &[[f64; 3]], b: &[[f64; 3]], what: &str) {
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        for c in 0..3 {
            let tol = 1e-5 * x[c].abs().max(1.0);
            assert!((x[c] - y[c]).abs() <= tol, "{what}: {x:?} against {y:?}");
        }
    }
}

#[test]
fn named_spaces_match_the_interpreter() {
    let set = PointSet::random(64, 21);
    let spaces = table();
    for e in EXPRS {
        let src = format!("surface t() {{ Ci = {e}; }}");
        let jit = JitShader::from_source("t.sl", &src, &[], JitOptions::default()).unwrap();
        close(&shade::<f32, _>(&jit, &set, &spaces), &shade::<f32, _>(jit.interp(), &set, &spaces), e);
        close(&shade::<F32x8, _>(&jit, &set, &spaces), &shade::<F32x8, _>(jit.interp(), &set, &spaces), e);
        close(&shade::<Dual<f32>, _>(&jit, &set, &spaces), &shade::<Dual<f32>, _>(jit.interp(), &set, &spaces), e);
    }
}

#[test]
fn named_spaces_give_the_hand_worked_values() {
    let set = PointSet::random(8, 5);
    let spaces = table();
    let g = set.globals::<f32>(0);
    let (p, n) = ([g.P.x, g.P.y, g.P.z].map(f64::from), [g.N.x, g.N.y, g.N.z].map(f64::from));
    let run = |e: &str| {
        let src = format!("surface t() {{ Ci = {e}; }}");
        let jit = JitShader::from_source("t.sl", &src, &[], JitOptions::default()).unwrap();
        let (a, b) = (shade::<f32, _>(&jit, &set, &spaces)[0], shade::<f32, _>(jit.interp(), &set, &spaces)[0]);
        close(&[a], &[b], e);
        a
    };
    // Current to object: (P - (1, 2, 3)) / 2.
    close(&[run(EXPRS[0])], &[[(p[0] - 1.0) / 2.0, (p[1] - 2.0) / 2.0, (p[2] - 3.0) / 2.0]], "object");
    // Normals to object: the inverse transpose of that, i.e. times 2.
    close(&[run(EXPRS[3])], &[[2.0 * n[0], 2.0 * n[1], 2.0 * n[2]]], "object normal");
    // Current to mycs: P - (0, 0, 5).
    close(&[run("color(transform(\"mycs\", P))")], &[[p[0], p[1], p[2] - 5.0]], "mycs");
    // Unknown: the identity.
    close(&[run(EXPRS[14])], &[p], "unknown");
}
