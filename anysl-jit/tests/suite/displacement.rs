//! Displacement shaders compiled by the JIT (`DisplacementShader for JitShader`): `P` and `N`
//! as the shader leaves them — values and, in the dual-number variants, their screen
//! derivatives (what a renderer's bump mapping takes the moved surface's normal from) — equal
//! the interpreter's.

use anysl_ad::Dual;
use anysl_core::points::PointSet;
use anysl_core::{DisplacementShader, Exec, PointContext, ShadingFloat};
use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_shaders::Light;
use anysl_simd::F32x8;

/// Moves P along the normal by a sine of x and sets N to the moved surface's normal.
const RIPPLE: &str = "displacement ripple(float amp = 0.1; float freq = 3;)\n\
{\n    P += amp * sin(freq * xcomp(P)) * normalize(N);\n    N = calculatenormal(P);\n}\n";

/// Every lane's value, then (for dual numbers) every lane's x and y derivative, of each
/// component of the displaced `P` and `N` of every packet of `set`.
fn displaced<F: ShadingFloat, D: DisplacementShader>(d: &D, set: &PointSet) -> Vec<f64> {
    let lights: Vec<Light> = Vec::new();
    let mut out = Vec::new();
    let mut i = 0;
    while i + F::LANES <= set.len() {
        let mut ctx = PointContext::new(set.globals::<F>(i), &lights);
        let (p, n) = d.displace(&mut ctx, &mut Exec::<F>::new());
        for c in [p.x, p.y, p.z, n.x, n.y, n.z] {
            let parts = if F::HAS_DERIVS { vec![c.value(), c.dx(), c.dy()] } else { vec![c] };
            for x in parts {
                out.extend((0..F::LANES).map(|l| x.lane(l)));
            }
        }
        i += F::LANES;
    }
    out
}

fn max_diff<F: ShadingFloat>(jit: &JitShader, set: &PointSet) -> f64 {
    let a = displaced::<F, _>(jit, set);
    let b = displaced::<F, _>(jit.interp(), set);
    assert_eq!(a.len(), b.len());
    a.iter().zip(&b).map(|(x, y)| if (x - y).is_nan() { f64::INFINITY } else { (x - y).abs() }).fold(0.0, f64::max)
}

#[test]
fn compiled_displacement_moves_p_and_n_as_the_interpreter_does() {
    let set = PointSet::random(256, 3);
    let jit = JitShader::from_source("ripple.sl", RIPPLE, &[], JitOptions::default()).expect("compiles");
    for v in [Variant::F32, Variant::X8, Variant::DualF32, Variant::DualX8] {
        if let Err(e) = jit.variant(v) {
            panic!("{v:?}: {e}");
        }
    }
    for (name, d) in [
        ("f32", max_diff::<f32>(&jit, &set)),
        ("f32x8", max_diff::<F32x8>(&jit, &set)),
        ("dual-f32", max_diff::<Dual<f32>>(&jit, &set)),
        ("dual-f32x8", max_diff::<Dual<F32x8>>(&jit, &set)),
    ] {
        assert!(d < 1e-4, "{name}: JIT against interpreter {d:e}");
    }
    // The compiled run moved P, and P's derivatives are the moved surface's, not zero.
    let lights: Vec<Light> = Vec::new();
    let g = set.globals::<Dual<f32>>(0);
    let mut ctx = PointContext::new(g, &lights);
    let (p, _) = jit.displace(&mut ctx, &mut Exec::new());
    let d = p - g.P;
    let moved: f64 = [d.x, d.y, d.z].iter().map(|c| c.value().lane(0).powi(2)).sum();
    assert!(moved > 0.0, "P did not move");
    let dpdx: f64 = [p.x, p.y, p.z].iter().map(|c| c.dx().lane(0).powi(2)).sum();
    assert!(dpdx > 0.0, "the moved P has no x derivative");
}
