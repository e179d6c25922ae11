//! Every surface, instantiated with f32 and with the f64 oracle, on random shading points.

use crate::common;

use anysl_core::{Exec, Globals, PointContext, Shader, SurfaceShader};
use anysl_shaders::{table1_lights, Light, Plastic, PointLight, Screen, SpotLight, Surface};
use common::{quantile, samples, shade_point, Sample};

const N: usize = 2000;

/// Shades every sample with f32 and f64; checks finiteness and Oi ∈ [0, 1] and returns the
/// per-channel |f32 - f64| errors plus the f64 colours.
fn compare(surface: &Surface, lights: &[Light], pts: &[Sample]) -> (Vec<f64>, Vec<[f64; 3]>) {
    let name = surface.name();
    let mut errs = Vec::with_capacity(pts.len() * 6);
    let mut colours = Vec::with_capacity(pts.len());
    for x in pts {
        let (ci32, oi32) = shade_point::<f32, _, _>(surface, lights, x);
        let (ci64, oi64) = shade_point::<f64, _, _>(surface, lights, x);
        for c in 0..3 {
            for v in [ci32[c], ci64[c], oi32[c], oi64[c]] {
                assert!(v.is_finite(), "{name}: non-finite output at {x:?}");
            }
            for v in [oi32[c], oi64[c]] {
                assert!((0.0..=1.0).contains(&v), "{name}: Oi = {v} outside [0, 1] at {x:?}");
            }
            errs.push((ci32[c] - ci64[c]).abs());
            errs.push((oi32[c] - oi64[c]).abs());
        }
        colours.push(ci64);
    }
    (errs, colours)
}

#[test]
fn every_surface_f32_matches_f64() {
    let lights = table1_lights();
    let pts = samples(N, 1);
    for surface in Surface::all() {
        let (mut errs, colours) = compare(&surface, &lights, &pts);
        let p999 = quantile(&mut errs, 0.999);
        let max = errs[errs.len() - 1];
        eprintln!("{:10} p99.9 {p999:.2e}  max {max:.2e}", surface.name());
        assert!(p999 <= 1e-4, "{}: 99.9th percentile |f32 - f64| = {p999:e} (max {max:e})", surface.name());
        // The shader does something: its colours are not all the same.
        let first = colours[0];
        assert!(
            colours.iter().any(|c| (0..3).any(|i| (c[i] - first[i]).abs() > 1e-3)),
            "{}: constant output",
            surface.name()
        );
    }
}

#[test]
fn every_surface_under_classic_lights() {
    // Inverse-square point light, a spot covering the visible hemisphere, a distant light.
    let lights = vec![
        Light::Point(PointLight { intensity: 30.0, lightcolor: [1.0, 0.9, 0.8], from: [-3.0, 4.0, 5.0], falloff: 2.0 }),
        Light::Spot(SpotLight {
            intensity: 20.0,
            from: [0.0, 0.0, 4.0],
            to: [0.0, 0.0, 0.0],
            coneangle: 0.4,
            ..SpotLight::default()
        }),
        Light::by_name("distantlight").expect("distantlight"),
        Light::by_name("ambientlight").expect("ambientlight"),
    ];
    let pts = samples(1000, 2);
    for surface in Surface::all() {
        let (mut errs, _) = compare(&surface, &lights, &pts);
        let p999 = quantile(&mut errs, 0.999);
        assert!(p999 <= 1e-4, "{}: 99.9th percentile |f32 - f64| = {p999:e}", surface.name());
    }
}

#[test]
fn by_name_resolves_every_table1_name() {
    assert_eq!(
        Surface::NAMES,
        ["brick", "checker", "glass", "granite", "parquet", "phong", "screen", "starball", "venus", "wood"]
    );
    for name in Surface::NAMES {
        let s = Surface::by_name(name).unwrap_or_else(|| panic!("{name} not found"));
        let expected = if name == "phong" { "plastic" } else { name };
        assert_eq!(s.name(), expected);
        assert_eq!(s.meta().name, expected);
    }
    assert_eq!(Surface::by_name("phong"), Surface::by_name("plastic"));
    assert_eq!(Surface::by_name("plastic"), Some(Surface::Plastic(Plastic::default())));
    assert!(Surface::by_name("marble").is_none());
    assert!(Surface::by_name("").is_none());
    assert!(Surface::by_name("Phong").is_none(), "names are case-sensitive, as in RSL");
    for name in Light::NAMES {
        assert_eq!(Light::by_name(name).map(|l| l.meta().name), Some(name.to_string()));
    }
    assert!(Light::by_name("arealight").is_none());
}

/// Shades `n` points of the unit square (s, t on a grid) and returns (Ci, Oi) per point.
fn shade_grid<S: SurfaceShader>(s: &S, n: usize) -> Vec<([f64; 3], [f64; 3])> {
    let lights = table1_lights();
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (u, v) = ((i as f64 + 0.37) / n as f64, (j as f64 + 0.61) / n as f64);
            let mut ctx = PointContext::new(Globals::<f64>::unit_square(u, v), &lights);
            let o = s.shade(&mut ctx, &mut Exec::new());
            out.push((o.Ci.lane(0), o.Oi.lane(0)));
        }
    }
    out
}

#[test]
fn screen_has_holes_and_wire() {
    let screen = Screen::default();
    let out = shade_grid(&screen, 64);
    let holes = out.iter().filter(|(ci, oi)| *oi == [0.0; 3] && *ci == [0.0; 3]).count();
    let wire = out.iter().filter(|(ci, oi)| *oi == [1.0; 3] && ci.iter().any(|&c| c > 0.0)).count();
    assert_eq!(holes + wire, out.len(), "every point is either a hole or wire");
    // density 0.25 in s or t: 1 - 0.75² = 43.75 % wire.
    let frac = wire as f64 / out.len() as f64;
    assert!((frac - 0.4375).abs() < 0.05, "wire fraction {frac}");
    // The mask agrees with the classic condition.
    for (s, t, wire) in [(0.01, 0.5, true), (0.5, 0.01, true), (0.03, 0.03, false), (0.5, 0.5, true)] {
        let m: bool = screen.wire(s, t);
        assert_eq!(m, wire, "s = {s}, t = {t}");
    }
}

#[test]
fn screen_hole_is_black_and_transparent() {
    let screen = Screen::default();
    let lights = table1_lights();
    let mut ctx = PointContext::new(Globals::<f32>::unit_square(0.03, 0.03), &lights);
    let hole = screen.shade(&mut ctx, &mut Exec::new());
    assert_eq!(hole.Oi.lane(0), [0.0; 3]);
    assert_eq!(hole.Ci.lane(0), [0.0; 3]);
}

#[test]
fn patterns_show_all_their_parts() {
    let count =
        |s: &Surface, pred: &dyn Fn(&[f64; 3]) -> bool| shade_grid(s, 48).iter().filter(|(ci, _)| pred(ci)).count();
    // Checker: black checks (with the default black, only the highlight lights them) and
    // bright white checks.
    let checker = Surface::by_name("checker").expect("checker");
    assert!(count(&checker, &|c| c[0] > 0.3) > 500);
    assert!(count(&checker, &|c| c[0] < 0.2) > 500);
    // Brick: red-ish bricks and grey mortar.
    let brick = Surface::by_name("brick").expect("brick");
    assert!(count(&brick, &|c| c[0] > 1.5 * c[2]) > 500);
    assert!(count(&brick, &|c| c[0] < 1.5 * c[2]) > 50);
}

#[test]
fn starball_has_star_band_and_ball() {
    let sb = anysl_shaders::Starball::default();
    let col = |p: [f64; 3]| sb.color(anysl_core::Vec3::<f64>::from_array(p)).lane(0);
    assert_eq!(col([0.0, 0.0, 1.0]), sb.starcolor, "star centre");
    assert_eq!(col([0.0, 0.0, -1.0]), sb.starcolor, "star on the back");
    // The upward tip is inside, the notch direction at the same radius is not.
    let r: f64 = 0.4;
    assert_eq!(col([0.0, r.sin(), r.cos()]), sb.starcolor, "tip");
    let notch = std::f64::consts::PI / 2.0 + std::f64::consts::PI / 5.0;
    assert_eq!(col([r.sin() * notch.cos(), r.sin() * notch.sin(), r.cos()]), sb.ballcolor, "between tips");
    assert_eq!(col([1.0, 0.0, 0.0]), sb.bandcolor, "band at the side");
    assert_eq!(col([0.0, 1.0, 0.0]), sb.ballcolor, "pole");
}

#[test]
fn every_surface_f32x8_lanes_match_scalar_f32() {
    use anysl_simd::F32x8;
    let lights = table1_lights();
    let pts = samples(512, 3);
    for surface in Surface::all() {
        let mut errs = Vec::new();
        for chunk in pts.chunks_exact(8) {
            let mut ctx = PointContext::new(common::globals_lanes::<F32x8>(chunk), &lights);
            let out = surface.shade(&mut ctx, &mut Exec::new());
            for (k, x) in chunk.iter().enumerate() {
                let (ci, oi) = shade_point::<f32, _, _>(&surface, &lights, x);
                for c in 0..3 {
                    errs.push((out.Ci.lane(k)[c] - ci[c]).abs());
                    errs.push((out.Oi.lane(k)[c] - oi[c]).abs());
                }
            }
        }
        let p999 = quantile(&mut errs, 0.999);
        assert!(p999 <= 1e-4, "{}: 99.9th percentile |f32x8 - f32| = {p999:e}", surface.name());
    }
}
