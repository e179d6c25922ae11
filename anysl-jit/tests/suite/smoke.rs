//! Every shader in shaders/rsl: JIT variants against the interpreter at the same float type.

use anysl_ad::Dual;
use anysl_core::points::{shade_points, PointSet, ShadeOut};
use anysl_core::ShadingFloat;
use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_shaders::{table1_lights, Light};
use anysl_simd::F32x8;
use std::path::PathBuf;

fn rsl_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"))
}

fn max_diff(a: &ShadeOut<f32>, b: &ShadeOut<f32>) -> f32 {
    let mut m = 0.0f32;
    for c in 0..6 {
        for (x, y) in a.channels[c].iter().zip(&b.channels[c]) {
            let d = (x - y).abs();
            if d.is_nan() {
                return f32::INFINITY;
            }
            m = m.max(d);
        }
    }
    m
}

fn check<F: ShadingFloat>(name: &str, jit: &JitShader, set: &PointSet) -> f32 {
    let lights = table1_lights();
    let mut a = ShadeOut::new(set.len());
    let mut b = ShadeOut::new(set.len());
    shade_points::<F, JitShader, Light>(jit, &lights, set, &mut a);
    shade_points::<F, _, Light>(jit.interp(), &lights, set, &mut b);
    let d = max_diff(&a, &b);
    eprintln!("{name:12} {:10} max diff {d:e}", F::NAME);
    d
}

#[test]
fn shaders_match_interpreter() {
    let set = PointSet::random(256, 7);
    for name in ["plastic", "checker", "brick", "wood", "granite", "parquet", "screen", "starball", "venus", "glass"] {
        let path = rsl_dir().join(format!("{name}.sl"));
        let jit = JitShader::from_file(&path, &[rsl_dir().join("include")], JitOptions::default()).unwrap();
        for v in [Variant::F32, Variant::X8, Variant::DualF32] {
            if let Err(e) = jit.variant(v) {
                panic!("{name} {v:?}: {e}");
            }
        }
        assert!(check::<f32>(name, &jit, &set) < 1e-4, "{name} f32");
        assert!(check::<F32x8>(name, &jit, &set) < 1e-4, "{name} x8");
        assert!(check::<Dual<f32>>(name, &jit, &set) < 1e-4, "{name} dual");
    }
}

/// The inline-IR noise (`JitOptions::inline_noise`) computes what the library noise computes.
#[test]
fn inline_noise_matches_library_noise() {
    let set = PointSet::random(256, 11);
    let lights = table1_lights();
    for name in ["wood", "granite", "venus", "parquet"] {
        let path = rsl_dir().join(format!("{name}.sl"));
        let inc = [rsl_dir().join("include")];
        let lib = JitShader::from_file(&path, &inc, JitOptions { inline_noise: Some(false), ..JitOptions::default() })
            .unwrap();
        let inline =
            JitShader::from_file(&path, &inc, JitOptions { inline_noise: Some(true), ..JitOptions::default() })
                .unwrap();
        let run = |j: &JitShader, dual: bool, wide: bool| {
            let mut o = ShadeOut::new(set.len());
            match (dual, wide) {
                (true, _) => shade_points::<Dual<f32>, JitShader, Light>(j, &lights, &set, &mut o),
                (false, true) => shade_points::<F32x8, JitShader, Light>(j, &lights, &set, &mut o),
                (false, false) => shade_points::<f32, JitShader, Light>(j, &lights, &set, &mut o),
            }
            o
        };
        for (dual, wide) in [(false, false), (false, true), (true, false)] {
            let d = max_diff(&run(&lib, dual, wide), &run(&inline, dual, wide));
            assert!(d <= 1e-6, "{name} dual={dual} wide={wide}: inline noise differs by {d:e}");
        }
    }
}

/// The four-packet variant, whose noise is IR by default (`Variant::inline_noise`), gives the
/// library noise's bits — the one-packet variant's and its own with the noise called — at
/// every dimension and width of the family, also where some lanes of one packet of a step are
/// beyond the hash period (±2.5e9: the period reduction runs for that step only), non-finite,
/// huge (1e7) or denormal.
#[test]
fn four_packet_inline_noise_is_the_library_noise_at_extreme_coordinates() {
    use anysl_core::points::field;
    use anysl_core::PointContext;
    use anysl_jit::rsl::ir::Global;
    use anysl_simd::Pair;
    let src = r#"
surface noises(float k = 1.7;)
{
    float x = xcomp(P);
    float y = ycomp(P);
    float z = zcomp(P);
    vector v = vector snoise(P * k);
    Ci = color(snoise(x), noise(x, y) + snoise(P), noise(P, z)) + color(v);
    Oi = color(snoise(P * 1e-3), cellnoise(P), float noise(point(z, y, x)));
}
"#;
    const N: usize = 64;
    let set = PointSet::random(N, 41);
    let mut p: [Vec<f32>; 3] = [0, 1, 2].map(|a| set.field(field::P + a).to_vec());
    // Lanes 40..48: the second packet of the second 32-lane step.
    let odd = [1e7 + 0.25, 2.5e9, -3e9, f32::NAN, f32::INFINITY, -f32::INFINITY, 1e-40, 4.3e9];
    for (k, &x) in odd.iter().enumerate() {
        p[0][40 + k] = x;
        p[1][40 + k] = odd[(k + 3) % 8];
        p[2][40 + k] = -odd[(k + 5) % 8];
    }
    let lights = table1_lights();
    fn run<F: ShadingFloat>(jit: &JitShader, set: &PointSet, p: &[Vec<f32>; 3], lights: &[Light]) -> Vec<u32> {
        let mut out = vec![vec![0.0f32; N]; 6];
        let mut ctx = PointContext::new(set.globals::<F>(0), lights);
        let pv: [&[f32]; 3] = [&p[0], &p[1], &p[2]];
        let mut outs: Vec<&mut [f32]> = out.iter_mut().map(Vec::as_mut_slice).collect();
        assert!(jit.shade_points(&mut ctx, &[(Global::P, &pv)], &mut outs).unwrap(), "{} points entry", F::NAME);
        // One NaN for all NaNs: only their presence is compared.
        out.concat().iter().map(|&x| if x.is_nan() { f32::NAN.to_bits() } else { x.to_bits() }).collect()
    }
    let compile = |inline_noise| {
        JitShader::from_source("noises.sl", src, &[], JitOptions { inline_noise, ..JitOptions::default() }).unwrap()
    };
    let (default, calls) = (compile(None), compile(Some(false)));
    assert!(Variant::X8x4.inline_noise() && !Variant::X8.inline_noise());
    let want = run::<F32x8>(&calls, &set, &p, &lights);
    let four = run::<Pair<Pair<F32x8>>>(&default, &set, &p, &lights);
    let four_calls = run::<Pair<Pair<F32x8>>>(&calls, &set, &p, &lights);
    let x8_inline = run::<F32x8>(&compile(Some(true)), &set, &p, &lights);
    for (name, got) in [("x8x4 inline", &four), ("x8x4 calls", &four_calls), ("x8 inline", &x8_inline)] {
        let differ: Vec<usize> = (0..want.len()).filter(|&i| want[i] != got[i]).collect();
        assert!(
            differ.is_empty(),
            "{name}: {} values differ from the library noise, first at {:?}",
            differ.len(),
            differ.first().map(|i| (i / N, i % N))
        );
    }
}

/// What `globals_read` leaves out is really not read: with every other global set to NaN,
/// the interpreter and the JIT (f32 and x8) give the same results as with all of them.
#[test]
fn globals_outside_globals_read_are_not_read() {
    use anysl_core::{Exec, GlobalSet, PointContext, Shader, SurfaceShader};
    let set = PointSet::random(64, 5);
    let lights = table1_lights();
    let mut files: Vec<PathBuf> = std::fs::read_dir(rsl_dir()).unwrap().map(|e| e.unwrap().path()).collect();
    files.extend(std::fs::read_dir(rsl_dir().join("standard")).unwrap().map(|e| e.unwrap().path()));
    let mut checked = 0;
    for path in files.iter().filter(|p| p.extension().is_some_and(|x| x == "sl")) {
        let Ok(jit) = JitShader::from_file(path, &[rsl_dir().join("include")], JitOptions::default()) else {
            continue;
        };
        if jit.meta().kind != anysl_core::ShaderKind::Surface {
            continue;
        }
        let read = jit.globals_read();
        fn run<F: ShadingFloat, S: SurfaceShader>(
            s: &S,
            set: &PointSet,
            lights: &[Light],
            read: Option<GlobalSet>,
        ) -> Vec<f64> {
            let mut out = Vec::new();
            for i in (0..set.len()).step_by(F::LANES) {
                let mut g = set.globals::<F>(i);
                if let Some(r) = read {
                    g.poison_except(r);
                }
                let mut ctx = PointContext::new(g, lights);
                let o = s.shade(&mut ctx, &mut Exec::new());
                for c in [o.Ci.r, o.Ci.g, o.Ci.b, o.Oi.r, o.Oi.g, o.Oi.b] {
                    out.extend((0..F::LANES).map(|l| c.lane(l)));
                }
            }
            out
        }
        let name = path.display();
        let same = |a: Vec<f64>, b: Vec<f64>| a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits());
        assert!(
            same(
                run::<f32, _>(jit.interp(), &set, &lights, None),
                run::<f32, _>(jit.interp(), &set, &lights, Some(read))
            ),
            "{name}: interpreter reads a global outside {read:?}"
        );
        assert!(
            same(run::<f32, _>(&jit, &set, &lights, None), run::<f32, _>(&jit, &set, &lights, Some(read))),
            "{name}: JIT f32 reads a global outside {read:?}"
        );
        assert!(
            same(run::<F32x8, _>(&jit, &set, &lights, None), run::<F32x8, _>(&jit, &set, &lights, Some(read))),
            "{name}: JIT x8 reads a global outside {read:?}"
        );
        checked += 1;
    }
    assert!(checked >= 15, "only {checked} surface shaders checked");
}

/// Without specialization the compiled code reads its parameters at run time: it agrees with
/// the interpreter, and `set_param` takes effect without compiling again.
#[test]
fn unspecialized_code_reads_parameters_at_run_time() {
    use anysl_core::shader::{ParamValue, Shader};
    let set = PointSet::random(256, 3);
    let opts = JitOptions { specialize: false, ..JitOptions::default() };
    for name in ["plastic", "checker", "brick", "wood", "granite", "parquet", "screen", "starball", "venus", "glass"] {
        let path = rsl_dir().join(format!("{name}.sl"));
        let mut jit = JitShader::from_file(&path, &[rsl_dir().join("include")], opts.clone()).unwrap();
        assert!(check::<f32>(name, &jit, &set) < 1e-4, "{name} f32");
        assert!(check::<F32x8>(name, &jit, &set) < 1e-4, "{name} x8");
        assert!(check::<Dual<f32>>(name, &jit, &set) < 1e-4, "{name} dual");
        let compiled = jit.compiled();
        // Every float parameter doubled (a changed picture), no recompilation.
        let floats: Vec<(String, f64)> = jit
            .meta()
            .params
            .iter()
            .filter_map(|p| match jit.param(&p.name) {
                Some(ParamValue::Float(x)) => Some((p.name.clone(), x)),
                _ => None,
            })
            .collect();
        assert!(!floats.is_empty(), "{name} has float parameters");
        let before = {
            let mut o = ShadeOut::new(set.len());
            shade_points::<F32x8, JitShader, Light>(&jit, &table1_lights(), &set, &mut o);
            o
        };
        for (p, x) in &floats {
            jit.set_param(p, &ParamValue::Float(x * 2.0 + 0.125)).unwrap();
        }
        assert_eq!(jit.compiled(), compiled, "{name}: set_param recompiled unspecialized code");
        assert!(check::<F32x8>(name, &jit, &set) < 1e-4, "{name} x8 after set_param");
        assert!(check::<f32>(name, &jit, &set) < 1e-4, "{name} f32 after set_param");
        let after = {
            let mut o = ShadeOut::new(set.len());
            shade_points::<F32x8, JitShader, Light>(&jit, &table1_lights(), &set, &mut o);
            o
        };
        assert!(max_diff(&before, &after) > 1e-3, "{name}: new parameters changed nothing");
    }
}

/// `specular` keeps its light loop's `diffuse(N)` and `ambient()` sums for the calls after it
/// (`LitMemo` in the code generator); they are taken only for the same normal and mask. Cases
/// where they must not be: another normal, a normal reassigned in between, a `specular`
/// under a varying condition, and a `diffuse` before any `specular`.
#[test]
fn kept_light_sums_are_used_only_where_they_apply() {
    let src = r#"
surface litmemo(float Ks = 0.5; float roughness = 0.2;)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color early = diffuse(Nf);
    color a = 0, b = 0;
    if (s < 0.5)
        a = specular(Nf, V, roughness);
    color d1 = diffuse(Nf);
    color amb = ambient();
    normal Nt = normalize(Nf + vector(0.3, -0.2, 0.1));
    color sp2 = specular(Nt, V, roughness);
    color d2 = diffuse(Nf);
    color d3 = diffuse(Nt);
    Nt = normalize(Nt + vector(t, 0, 0));
    color d4 = diffuse(Nt);
    Ci = early + a + 2 * d1 + 3 * amb + 5 * sp2 + 7 * d2 + 11 * d3 + 13 * d4;
    Oi = 1;
}
"#;
    matches_interpreter_at_f32_x8_dual("litmemo", src, 3);
}

/// Compiles `src` and checks it against the interpreter at f32, x8 and dual-f32 on 512
/// random points (`seed`).
fn matches_interpreter_at_f32_x8_dual(name: &str, src: &str, seed: u64) {
    let jit = JitShader::from_source(&format!("{name}.sl"), src, &[], JitOptions::default()).unwrap();
    let set = PointSet::random(512, seed);
    assert!(check::<f32>(name, &jit, &set) < 1e-4, "f32");
    assert!(check::<F32x8>(name, &jit, &set) < 1e-4, "x8");
    assert!(check::<Dual<f32>>(name, &jit, &set) < 1e-4, "dual");
}

/// Calls into the renderer (indirect calls whose first argument is the context; the calls of
/// lights' code in the loops over light records take the points first) left in the optimized
/// IR of `name` at f32 and x8.
fn renderer_calls(name: &str) -> Vec<(Variant, usize, String)> {
    let path = rsl_dir().join(format!("{name}.sl"));
    let jit = JitShader::from_file(&path, &[rsl_dir().join("include")], JitOptions::default()).unwrap();
    [Variant::F32, Variant::X8]
        .into_iter()
        .map(|v| {
            let ir = anysl_jit::compile_with(&jit.module, &jit.values, v, &jit.opts, true).unwrap().llvm_ir.unwrap();
            let calls = ir.lines().filter(|l| l.trim_start().starts_with("call void %") && l.contains("(i8* ")).count();
            (v, calls, ir)
        })
        .collect()
}

/// In the plastic illumination model (`ambient() + diffuse(Nf) + specular(Nf, V, r)`) the
/// kept sums fold: one call into the renderer remains, the fused light loop.
#[test]
fn plastic_calls_the_renderer_once() {
    for (v, calls, ir) in renderer_calls("plastic") {
        assert_eq!(calls, 1, "{v:?}: {calls} indirect calls in\n{ir}");
    }
}

/// An `ambient()` followed by a `diffuse(N)` under the same mask makes one renderer call for
/// both, and only where that is right: a normal written between the two calls, a `diffuse`
/// of another normal, one under a varying condition and a normal computed before the
/// `ambient()` call, against the interpreter at f32, x8 and dual-f32.
#[test]
fn ambient_then_diffuse_is_one_light_loop_only_where_it_applies() {
    let src = r#"
surface ambdiff(float Ka = 1; float Kd = 0.8;)
{
    normal Nf = faceforward(normalize(N), I);
    color a1 = Ka * ambient();
    color d1 = Kd * diffuse(Nf);
    normal Nt = normalize(Nf + vector(0.3, -0.2, 0.1));
    color a2 = ambient();
    Nt = normalize(Nt + vector(t, 0, 0));
    color d2 = diffuse(Nt);
    color a3 = 0, d3 = 0;
    if (s < 0.5) {
        a3 = ambient();
        d3 = diffuse(normalize(N));
    }
    normal Nu = normalize(N + vector(0, s, 0));
    color a4 = ambient();
    color d4 = diffuse(Nu);
    color a5 = ambient();
    color d5 = diffuse(Nf + Nu);
    Ci = a1 + d1 + 2 * a2 + 3 * d2 + 5 * a3 + 7 * d3 + 11 * a4 + 13 * d4 + 17 * a5 + 19 * d5;
    Oi = 1;
}
"#;
    matches_interpreter_at_f32_x8_dual("ambdiff", src, 5);
}

/// In the matte illumination model (`Ka·ambient() + Kd·diffuse(Nf)`, brick and venus) the
/// `ambient()` call also sums the diffuse term: one call into the renderer remains.
#[test]
fn matte_calls_the_renderer_once() {
    for name in ["brick", "venus"] {
        for (v, calls, ir) in renderer_calls(name) {
            assert_eq!(calls, 1, "{name} {v:?}: {calls} indirect calls in\n{ir}");
        }
    }
}
