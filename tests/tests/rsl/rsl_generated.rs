//! The RSL ports in `shaders/rsl`, compiled to generic Rust by anysl-rsl at build time
//! (`anysl_shaders::rsl`), against the hand-written generic Rust shaders they port:
//!
//! * the same pictures (max abs pixel difference ≤ 1e-4) on the `table1` scene in the packet,
//!   scalar and active pbrt-like renderers with the hand-written lights, and in the scalar
//!   renderer with the generated lights (the renderers share the light loop; each pairing of
//!   shader and light types is a full instantiation of a renderer, so one renderer has it);
//! * the same values on random shading points (`PointSet`) at f32, F32x8 and Dual<f32>, a
//!   tighter comparison;
//! * the same metadata (names, types, defaults, storage, `uses_derivatives`).

use anysl_ad::Dual;
use anysl_core::points::{shade_points, PointSet, ShadeOut};
use anysl_core::{LightShader, ParamValue, Shader, ShadingFloat};
use anysl_renderers::{render_packet, render_pbrt, render_scalar, scenes, Image, Integrator, RenderOptions};
use anysl_shaders::rsl::{self, RslLight, RslSurface};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::F32x8;

const MAX_PIXEL_DIFF: f32 = 1e-4;
const SIZE: u32 = 48;

fn pair(name: &str) -> (Surface, RslSurface) {
    (
        Surface::by_name(name).unwrap_or_else(|| panic!("{name}: hand-written")),
        RslSurface::by_name(name).unwrap_or_else(|| panic!("{name}: no generated RSL surface")),
    )
}

fn max_diff(a: &ShadeOut<f32>, b: &ShadeOut<f32>) -> (f32, usize, usize) {
    let mut worst = (0.0f32, 0, 0);
    for (c, (x, y)) in a.channels.iter().zip(&b.channels).enumerate() {
        for (i, (p, q)) in x.iter().zip(y).enumerate() {
            let d = if p.is_nan() != q.is_nan() {
                f32::INFINITY
            } else if p.is_nan() {
                0.0
            } else {
                (p - q).abs()
            };
            if d > worst.0 {
                worst = (d, c, i);
            }
        }
    }
    worst
}

fn points_agree<F: ShadingFloat>(tol: f32) -> Vec<String> {
    let set = PointSet::random(256, 7);
    let hand_lights = table1_lights();
    let gen_lights = rsl::table1_lights();
    let mut failures = Vec::new();
    for name in Surface::NAMES {
        let (hand, gen) = pair(name);
        let mut a = ShadeOut::new(set.len());
        let mut b = ShadeOut::new(set.len());
        let mut c = ShadeOut::new(set.len());
        shade_points::<F, _, _>(&hand, &hand_lights, &set, &mut a);
        shade_points::<F, _, _>(&gen, &hand_lights, &set, &mut b);
        shade_points::<F, _, _>(&gen, &gen_lights, &set, &mut c);
        for (what, out) in [("hand-written lights", &b), ("generated lights", &c)] {
            let (d, ch, i) = max_diff(&a, out);
            if d > tol {
                failures.push(format!(
                    "{name} ({}, {what}): max diff {d:e} at point {i} channel {ch} (hand {} vs generated {})",
                    F::NAME,
                    a.channels[ch][i],
                    out.channels[ch][i]
                ));
            }
        }
    }
    failures
}

#[test]
fn generated_shaders_match_hand_written_on_points() {
    let mut failures = points_agree::<f32>(2e-5);
    failures.extend(points_agree::<F32x8>(2e-5));
    failures.extend(points_agree::<Dual<f32>>(2e-5));
    assert!(failures.is_empty(), "generated RSL differs:\n{}", failures.join("\n"));
}

#[test]
fn generated_lights_match_hand_written_lights() {
    let set = PointSet::random(64, 3);
    for name in Light::NAMES {
        let mut hand = Light::by_name(name).expect("hand-written light");
        let mut gen = RslLight::by_name(name).expect("generated light");
        // Non-default placement so cones and directions matter.
        for l in [&mut hand as &mut dyn Shader, &mut gen as &mut dyn Shader] {
            let _ = l.set_param("from", &ParamValue::Triple([0.3, 0.5, 2.0]));
            let _ = l.set_param("to", &ParamValue::Triple([0.0, 0.0, 0.0]));
            let _ = l.set_param("coneangle", &ParamValue::Float(0.4));
        }
        assert_eq!(hand.emission(), gen.emission(), "{name}: emission");
        for i in (0..set.len()).step_by(8) {
            let ps = set.globals::<F32x8>(i).P;
            let a = hand.light(&mut anysl_core::Exec::new(), ps);
            let b = gen.light(&mut anysl_core::Exec::new(), ps);
            for lane in 0..8 {
                let (lit_a, lit_b) = (anysl_core::Mask::lane(a.lit, lane), anysl_core::Mask::lane(b.lit, lane));
                let ca = if lit_a { a.cl.lane(lane) } else { [0.0; 3] };
                let cb = if lit_b { b.cl.lane(lane) } else { [0.0; 3] };
                for k in 0..3 {
                    assert!((ca[k] - cb[k]).abs() <= 1e-5 * ca[k].abs().max(1.0), "{name}: Cl {ca:?} vs {cb:?}");
                }
                if lit_a {
                    let (la, lb) = (a.l.lane(lane), b.l.lane(lane));
                    for k in 0..3 {
                        assert!((la[k] - lb[k]).abs() <= 1e-5, "{name}: L {la:?} vs {lb:?}");
                    }
                }
            }
        }
    }
}

#[test]
fn generated_metadata_matches_hand_written() {
    for name in Surface::NAMES {
        let (hand, gen) = pair(name);
        let (a, b) = (hand.meta(), gen.meta());
        assert_eq!(a.name, b.name, "{name}");
        assert_eq!(a.kind, b.kind, "{name}");
        assert_eq!(a.uses_derivatives, b.uses_derivatives, "{name}: uses_derivatives");
        for p in &a.params {
            let q = b.param(&p.name).unwrap_or_else(|| panic!("{name}: generated has no parameter {}", p.name));
            assert_eq!(p.ty, q.ty, "{name}.{}", p.name);
            assert_eq!(p.storage, q.storage, "{name}.{}", p.name);
            match (&p.default, &q.default) {
                (ParamValue::Float(x), ParamValue::Float(y)) => assert!((x - y).abs() < 1e-12, "{name}.{}", p.name),
                (ParamValue::Triple(x), ParamValue::Triple(y)) => {
                    assert!(x.iter().zip(y).all(|(x, y)| (x - y).abs() < 1e-12), "{name}.{}", p.name);
                }
                (x, y) => assert_eq!(x, y, "{name}.{}", p.name),
            }
        }
        assert_eq!(a.params.len(), b.params.len(), "{name}: parameter count");
    }
    for name in Light::NAMES {
        let (a, b) = (Light::by_name(name).unwrap().meta(), RslLight::by_name(name).unwrap().meta());
        let names = |m: &anysl_core::ShaderMeta| m.params.iter().map(|p| p.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(&a), names(&b), "{name}");
    }
}

fn opts() -> RenderOptions {
    RenderOptions { threads: 0, ..RenderOptions::default() }
}

fn check(failures: &mut Vec<String>, what: &str, a: &Image, b: &Image) {
    let d = a.max_abs_diff(b);
    eprintln!("{what:<40} max abs diff {d:e}");
    if d.is_nan() || d > MAX_PIXEL_DIFF {
        failures.push(format!("{what}: max abs pixel difference {d:e} > {MAX_PIXEL_DIFF:e}"));
    }
}

#[test]
fn generated_shaders_render_like_hand_written_in_every_renderer() {
    let mut failures = Vec::new();
    for name in Surface::NAMES {
        let (hand, gen) = pair(name);
        let reference = scenes::table1(hand, table1_lights(), SIZE);
        let with_hand_lights = scenes::table1(gen.clone(), table1_lights(), SIZE);
        let with_gen_lights = scenes::table1(gen, rsl::table1_lights(), SIZE);
        let o = opts();
        let r_scalar = render_scalar(&reference, &o);
        check(&mut failures, &format!("{name} scalar"), &r_scalar, &render_scalar(&with_hand_lights, &o));
        check(
            &mut failures,
            &format!("{name} scalar, generated lights"),
            &r_scalar,
            &render_scalar(&with_gen_lights, &o),
        );
        let r_packet = render_packet::<F32x8, _, _>(&reference, &o);
        check(
            &mut failures,
            &format!("{name} packet"),
            &r_packet,
            &render_packet::<F32x8, _, _>(&with_hand_lights, &o),
        );
        let r_pbrt = render_pbrt(&reference, &o, Integrator::Active);
        check(&mut failures, &format!("{name} pbrt"), &r_pbrt, &render_pbrt(&with_hand_lights, &o, Integrator::Active));
    }
    assert!(failures.is_empty(), "generated RSL renders differently:\n{}", failures.join("\n"));
}

/// Points per second of the hand-written and the generated version of every Table-1 shader
/// at f32 and F32x8 (run with `--ignored --nocapture`; numbers from the test profile).
#[test]
#[ignore = "timing, not a check"]
fn generated_speed_vs_hand_written() {
    use std::time::Instant;
    fn rate<F: ShadingFloat, S: anysl_core::SurfaceShader>(s: &S, lights: &[Light], set: &PointSet) -> f64 {
        let mut out = ShadeOut::new(set.len());
        shade_points::<F, _, _>(s, lights, set, &mut out);
        let mut best = f64::MAX;
        for _ in 0..5 {
            let t = Instant::now();
            for _ in 0..4 {
                shade_points::<F, _, _>(s, lights, set, &mut out);
            }
            best = best.min(t.elapsed().as_secs_f64() / 4.0);
        }
        set.len() as f64 / best
    }
    let set = PointSet::random(1 << 14, 11);
    let lights = table1_lights();
    eprintln!(
        "{:<9} {:>12} {:>12} {:>6} {:>12} {:>12} {:>6}",
        "shader", "hand f32", "gen f32", "ratio", "hand f32x8", "gen f32x8", "ratio"
    );
    for name in Surface::NAMES {
        let (hand, gen) = pair(name);
        let (a, b) = (rate::<f32, _>(&hand, &lights, &set), rate::<f32, _>(&gen, &lights, &set));
        let (c, d) = (rate::<F32x8, _>(&hand, &lights, &set), rate::<F32x8, _>(&gen, &lights, &set));
        eprintln!(
            "{name:<9} {:>10.2}M/s {:>10.2}M/s {:>6.2} {:>10.2}M/s {:>10.2}M/s {:>6.2}",
            a / 1e6,
            b / 1e6,
            b / a,
            c / 1e6,
            d / 1e6,
            d / c
        );
    }
}
