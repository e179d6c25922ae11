//! The light shaders: values against the classic formulas, f32 against f64, dispatch.

use crate::common;

use anysl_core::prelude::*;
use anysl_core::PointContext;
use anysl_shaders::{table1_lights, AmbientLight, DistantLight, Light, PointLight, SpotLight, TABLE1_AMBIENT};
use common::samples;

fn eval<L: LightShader>(l: &L, p: [f64; 3]) -> LightOutput<f64> {
    l.light(&mut Exec::<f64>::new(), Vec3::from_array(p))
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() <= tol)
}

#[test]
fn pointlight_falls_off_with_the_inverse_square() {
    let l = PointLight { intensity: 4.0, lightcolor: [1.0, 0.5, 0.25], from: [0.0, 0.0, 2.0], falloff: 2.0 };
    let out = eval(&l, [0.0, 0.0, 0.0]);
    assert_eq!(out.emission, Emission::Local);
    assert!(out.lit);
    assert_eq!(out.l.lane(0), [0.0, 0.0, -2.0], "L points from the light to the surface");
    assert!(close(out.cl.lane(0), [1.0, 0.5, 0.25], 1e-15));
    let far = eval(&l, [0.0, 0.0, -2.0]).cl.lane(0);
    assert!(close(far, [0.25, 0.125, 0.0625], 1e-15));
    // falloff 0: no distance law; falloff 1: 1/|L|.
    let none = PointLight { falloff: 0.0, ..l.clone() };
    assert!(close(eval(&none, [0.0, 0.0, -2.0]).cl.lane(0), [4.0, 2.0, 1.0], 1e-15));
    let linear = PointLight { falloff: 1.0, ..l };
    assert!(close(eval(&linear, [0.0, 0.0, -2.0]).cl.lane(0), [1.0, 0.5, 0.25], 1e-12));
}

#[test]
fn distantlight_is_solar() {
    let l = DistantLight { intensity: 2.0, lightcolor: [0.5, 0.5, 1.0], from: [0.0, 1.0, 0.0], to: [0.0, 0.0, 0.0] };
    let out = eval(&l, [5.0, 6.0, 7.0]);
    assert_eq!(out.emission, Emission::Distant);
    assert_eq!(out.l.lane(0), [0.0, -1.0, 0.0]);
    assert_eq!(out.cl.lane(0), [1.0, 1.0, 2.0]);
    assert!(out.lit);
}

#[test]
fn spotlight_cone_and_soft_edge() {
    let l = SpotLight { intensity: 8.0, ..SpotLight::default() };
    let at = |deg: f64, dist: f64| {
        let a = deg.to_radians();
        eval(&l, [dist * a.sin(), 0.0, dist * a.cos()])
    };
    // On the axis: full beam, inverse square.
    let axis = at(0.0, 2.0);
    assert!(axis.lit);
    assert!(close(axis.cl.lane(0), [2.0; 3], 1e-12));
    // Inside the cone, before the soft edge: cos^beamdistribution / d².
    let inner = at(20.0, 2.0);
    let want = 8.0 * 20f64.to_radians().cos().powi(2) / 4.0;
    assert!(close(inner.cl.lane(0), [want; 3], 1e-12));
    // In the soft edge: strictly between 0 and the unattenuated value.
    let edge = at(27.5, 2.0);
    let full = 8.0 * 27.5f64.to_radians().cos().powi(2) / 4.0;
    let c = edge.cl.lane(0)[0];
    assert!(edge.lit && c > 0.0 && c < full, "soft edge {c} vs {full}");
    // Outside the cone: not lit, and no light.
    let out = at(35.0, 2.0);
    assert!(!out.lit);
    assert_eq!(out.cl.lane(0), [0.0; 3]);
    // At the light itself: finite direction terms (cosangle = 1), infinite 1/(L·L) only.
    assert!(!eval(&l, [0.0, 0.0, 0.0]).cl.lane(0)[0].is_nan());
}

#[test]
fn ambientlight_feeds_ambient_only() {
    let l = AmbientLight { intensity: 0.5, lightcolor: [0.2, 0.4, 0.6] };
    let out = eval(&l, [1.0, 2.0, 3.0]);
    assert_eq!(out.emission, Emission::Ambient);
    assert_eq!(out.cl.lane(0), [0.1, 0.2, 0.3]);
    let lights = [Light::Ambient(l)];
    let mut ctx = PointContext::new(Globals::<f64>::unit_square(0.5, 0.5), &lights);
    let mut e = Exec::new();
    assert_eq!(ambient(&mut ctx, &e).lane(0), [0.1, 0.2, 0.3]);
    let n = ctx.globals.N;
    assert_eq!(diffuse(&mut ctx, &mut e, n).lane(0), [0.0; 3], "no directional light");
}

#[test]
fn table1_lights_are_the_workload_lights() {
    let lights = table1_lights();
    assert_eq!(lights.len(), 3);
    // Without falloff, a surface point sees exactly the workload colours, wherever it is.
    for p in [[0.0, 0.0, 1.0], [0.6, -0.8, 0.0], [0.0, 0.0, 0.0]] {
        assert_eq!(eval(&lights[0], p).cl.lane(0), [0.90, 0.85, 0.80]);
        assert_eq!(eval(&lights[1], p).cl.lane(0), [0.25, 0.30, 0.45]);
        assert_eq!(eval(&lights[2], p).cl.lane(0), TABLE1_AMBIENT);
    }
    assert_eq!(eval(&lights[0], [0.0; 3]).l.lane(0), [3.0, -4.0, -5.0]);
    assert_eq!(eval(&lights[1], [0.0; 3]).l.lane(0), [-4.0, 1.5, -3.0]);
    // Lambert through the context: N = +z at the origin.
    let mut ctx = PointContext::new(Globals::<f64>::unit_square(0.5, 0.5), &lights);
    let mut e = Exec::new();
    let d = diffuse(&mut ctx, &mut e, Vec3::c(0.0, 0.0, 1.0)).lane(0);
    let (c1, c2) = (5.0 / 50f64.sqrt(), 3.0 / 27.25f64.sqrt());
    let want = [0.90 * c1 + 0.25 * c2, 0.85 * c1 + 0.30 * c2, 0.80 * c1 + 0.45 * c2];
    assert!(close(d, want, 1e-12), "{d:?} vs {want:?}");
}

#[test]
fn every_light_f32_matches_f64_and_dispatch_is_transparent() {
    let lights = [
        Light::Point(PointLight { intensity: 20.0, from: [1.0, 2.0, 3.0], ..PointLight::default() }),
        Light::Distant(DistantLight { from: [1.0, 1.0, 1.0], ..DistantLight::default() }),
        Light::Spot(SpotLight {
            intensity: 20.0,
            from: [0.0, 0.0, 3.0],
            to: [0.0, 0.0, 0.0],
            coneangle: 0.5,
            conedeltaangle: 0.2,
            beamdistribution: 3.0,
            ..SpotLight::default()
        }),
        Light::Ambient(AmbientLight { intensity: 0.3, ..AmbientLight::default() }),
    ];
    let mut lit_seen = [0usize; 4];
    for x in samples(1000, 7) {
        for (k, light) in lights.iter().enumerate() {
            let a = light.light(&mut Exec::<f32>::new(), Vec3::from_array(x.p));
            let b = light.light(&mut Exec::<f64>::new(), Vec3::from_array(x.p));
            assert_eq!(a.lit, b.lit, "{}: lit differs at {:?}", light.name(), x.p);
            assert_eq!(a.emission, b.emission);
            let (ca, cb) = (a.cl.lane(0), b.cl.lane(0));
            for i in 0..3 {
                assert!(ca[i].is_finite() && cb[i].is_finite(), "{}", light.name());
                assert!((ca[i] - cb[i]).abs() <= 1e-5 * cb[i].abs().max(1.0), "{}: {ca:?} vs {cb:?}", light.name());
            }
            lit_seen[k] += usize::from(b.lit && cb.iter().any(|&c| c > 0.0));
        }
    }
    assert!(lit_seen.iter().all(|&n| n > 50), "every light lights some points: {lit_seen:?}");
    // The enum forwards exactly.
    let direct = SpotLight { intensity: 3.0, ..SpotLight::default() };
    let wrapped = Light::from(direct.clone());
    let p = [0.1, 0.2, 1.5];
    assert_eq!(eval(&direct, p).cl.lane(0), eval(&wrapped, p).cl.lane(0));
}
