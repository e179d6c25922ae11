//! The hand-written SIMD shaders compute what the generic ones compute for `F32x8`.

use crate::common;

use anysl_core::prelude::*;
use anysl_core::PointContext;
use anysl_shaders::native::{checker_x8, native_lights, plastic_x8, NativePointLight, PointsX8, V3x8};
use anysl_shaders::{table1_lights, Checker, Light, Plastic, PointLight, SpotLight};
use anysl_simd::F32x8;
use common::{globals_lanes, samples, Sample};
use wide::f32x8;

/// The native inputs of eight samples (the same f32 values the generic globals hold).
fn points_x8(xs: &[Sample]) -> PointsX8 {
    let g = globals_lanes::<F32x8>(xs);
    let s = |v: F32x8| f32x8::from(core::array::from_fn::<f32, 8, _>(|k| v.lane(k) as f32));
    let v3 = |v: Vec3<F32x8>| [s(v.x), s(v.y), s(v.z)];
    let c3 = |c: Color<F32x8>| [s(c.r), s(c.g), s(c.b)];
    PointsX8 { p: v3(g.P), n: v3(g.N), i: v3(g.I), s: s(g.s), t: s(g.t), cs: c3(g.Cs), os: c3(g.Os) }
}

/// Runs generic (through `PointContext<F32x8>`) and native on `n` samples and returns the
/// largest |difference| of Ci and Oi.
fn max_diff<S: SurfaceShader>(
    shader: &S,
    lights: &[Light],
    native: impl Fn(&[NativePointLight], [f32; 3], &PointsX8) -> (V3x8, V3x8),
    n: usize,
) -> f64 {
    let (nl, amb) = native_lights(lights).expect("point and ambient lights only");
    let pts = samples(n, 11);
    let mut worst = 0.0f64;
    for chunk in pts.chunks_exact(8) {
        let mut ctx = PointContext::new(globals_lanes::<F32x8>(chunk), lights);
        let generic = shader.shade(&mut ctx, &mut Exec::new());
        let (ci, oi) = native(&nl, amb, &points_x8(chunk));
        for (k, x) in chunk.iter().enumerate() {
            let (gc, go) = (generic.Ci.lane(k), generic.Oi.lane(k));
            for c in 0..3 {
                let (nc, no) = (ci[c].to_array()[k] as f64, oi[c].to_array()[k] as f64);
                assert!(nc.is_finite(), "native Ci not finite at {x:?}");
                worst = worst.max((nc - gc[c]).abs()).max((no - go[c]).abs());
            }
        }
    }
    worst
}

/// Inverse-square point lights bright enough to matter at the unit sphere, plus ambient.
fn classic_lights() -> Vec<Light> {
    vec![
        Light::Point(PointLight {
            intensity: 40.0,
            lightcolor: [0.9, 0.85, 0.8],
            from: [-3.0, 4.0, 5.0],
            falloff: 2.0,
        }),
        Light::Point(PointLight {
            intensity: 20.0,
            lightcolor: [0.25, 0.3, 0.45],
            from: [4.0, -1.5, 3.0],
            falloff: 2.0,
        }),
        Light::by_name("ambientlight").expect("ambientlight"),
    ]
}

#[test]
fn native_plastic_matches_generic_f32x8() {
    for (lights, plastic) in [
        (table1_lights(), Plastic::default()),
        (table1_lights(), Plastic { Kd: 0.8, roughness: 0.08, specularcolor: [1.0, 0.8, 0.6], ..Plastic::default() }),
        (classic_lights(), Plastic::default()),
    ] {
        let d = max_diff(&plastic, &lights, |l, a, x| plastic_x8(&plastic, l, a, x), 4000);
        eprintln!("plastic: max |native - generic| = {d:.2e}");
        assert!(d <= 1e-5, "plastic: native vs generic differ by {d:e}");
    }
}

#[test]
fn native_checker_matches_generic_f32x8() {
    for (lights, checker) in [
        (table1_lights(), Checker::default()),
        (
            classic_lights(),
            Checker {
                frequency: 3.5,
                blackcolor: [0.1, 0.2, 0.45],
                whitecolor: [0.9, 0.85, 0.7],
                ..Checker::default()
            },
        ),
    ] {
        let d = max_diff(&checker, &lights, |l, a, x| checker_x8(&checker, l, a, x), 4000);
        eprintln!("checker: max |native - generic| = {d:.2e}");
        assert!(d <= 1e-5, "checker: native vs generic differ by {d:e}");
    }
}

#[test]
fn native_lights_accepts_only_what_the_kernels_implement() {
    let (points, ambient) = native_lights(&table1_lights()).expect("table 1 lights are native");
    assert_eq!(points.len(), 2);
    assert_eq!(points[0], NativePointLight { from: [-3.0, 4.0, 5.0], color: [0.9, 0.85, 0.8], inverse_square: false });
    assert_eq!(ambient, [0.08, 0.08, 0.10]);
    assert!(native_lights(&[Light::Spot(SpotLight::default())]).is_none());
    let odd = PointLight { falloff: 1.0, ..PointLight::default() };
    assert!(NativePointLight::from_light(&odd).is_none());
    assert!(native_lights(&[Light::Point(odd)]).is_none());
}
