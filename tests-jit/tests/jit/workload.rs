//! The workload's `.sl` shaders through the JIT, against the reference images
//! (`shaders/assets/workload_ref/shading_workload.md`, acceptance bound 1e-4 max abs error).

use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_shaders::workload::{self, reference, WorkloadShader};
use anysl_simd::{F32x16, F32x8, Pair};
use anysl_tests::workload_harness::{check_subset, reference_image, scene, shade_subset, sl_module};

/// The `.sl` shaders through the JIT: x8 and x16 over full images, f32 on a subset; the
/// multi-packet variants (four 8-lane, two 16-lane packets per call) equal their one-packet
/// variants bit for bit.
#[test]
fn jit_matches_reference() {
    let s = scene();
    let lights = workload::lights();
    for shader in WorkloadShader::all() {
        let jit = JitShader::new(sl_module(&shader), JitOptions::default()).expect("a JIT shader");
        // Compile explicitly: `shade` would fall back to the interpreter on a compile error.
        for v in [Variant::F32, Variant::X8, Variant::X16, Variant::X8x4, Variant::X16x2] {
            if let Err(e) = jit.variant(v) {
                panic!("{} {v:?}: {e}", shader.name());
            }
        }
        let ci = shade_subset::<f32, _>(s, &jit, &lights);
        check_subset(s, &ci, &shader, "jit-f32");
        let n = s.padded_len();
        let shade = |v: Variant| {
            let [mut r, mut g, mut b] = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
            let out = [&mut r[..], &mut g[..], &mut b[..]];
            match v {
                Variant::X8 => s.shade_surface::<F32x8, _, _>(&jit, &lights, 0, out),
                Variant::X16 => s.shade_surface::<F32x16, _, _>(&jit, &lights, 0, out),
                Variant::X8x4 => s.shade_surface::<Pair<Pair<F32x8>>, _, _>(&jit, &lights, 0, out),
                Variant::X16x2 => s.shade_surface::<Pair<F32x16>, _, _>(&jit, &lights, 0, out),
                _ => unreachable!(),
            }
            [r, g, b]
        };
        for (one, many) in [(Variant::X8, Variant::X8x4), (Variant::X16, Variant::X16x2)] {
            let ci = shade(one);
            let err = reference::image_error(&s.to_image(&ci), reference_image(shader.name()));
            assert!(err.max_abs_err <= 1e-4 && err.pixels_over_1e3 == 0, "{} {one:?}: {err:?}", shader.name());
            let cm = shade(many);
            for ch in 0..3 {
                let differ = ci[ch].iter().zip(&cm[ch]).filter(|(a, b)| a.to_bits() != b.to_bits()).count();
                assert_eq!(differ, 0, "{} {many:?} differs from {one:?} in {differ} values", shader.name());
            }
        }
    }
}
