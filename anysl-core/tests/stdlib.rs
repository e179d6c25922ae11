//! The shading library on f32/f64, including the extreme inputs whose outcome is documented.

use anysl_core::stdlib::*;
use anysl_core::{Color, Exec, Matrix4, ShadingFloat, Vec3};
use approx::assert_relative_eq;
use proptest::prelude::*;

#[test]
fn smoothstep_basics_and_equal_edges() {
    assert_eq!(smoothstep(0.0f32, 1.0, -1.0), 0.0);
    assert_eq!(smoothstep(0.0f32, 1.0, 2.0), 1.0);
    assert_relative_eq!(smoothstep(0.0f64, 1.0, 0.5), 0.5);
    // Equal edges: a step, never NaN.
    assert_eq!(smoothstep(0.3f32, 0.3, 0.2), 0.0);
    assert_eq!(smoothstep(0.3f32, 0.3, 0.3), 1.0);
    assert_eq!(smoothstep(0.3f32, 0.3, 0.4), 1.0);
}

#[test]
fn pow_of_negative_base_and_zero() {
    assert!(ShadingFloat::pow(-2.0f32, 0.5).is_nan());
    assert_eq!(ShadingFloat::pow(-2.0f32, 3.0), -8.0);
    assert_eq!(ShadingFloat::pow(0.0f32, 12.5), 0.0);
    assert_eq!(ShadingFloat::pow(0.0f32, 0.0), 1.0);
}

#[test]
fn mod_follows_rsl_floor_semantics() {
    assert_relative_eq!(fmod(5.5f64, 2.0), 1.5);
    assert_relative_eq!(fmod(-0.5f64, 2.0), 1.5);
    assert_eq!(fmod(3.0f32, 0.0), 0.0);
    // The rounding corner: a tiny negative a must not return b itself.
    let r = fmod(-1e-9f32, 1.0);
    assert!((0.0..1.0).contains(&r), "{r}");
}

#[test]
fn normalize_zero_vector_is_zero() {
    let z = Vec3::<f32>::zero().normalize();
    assert_eq!(z, Vec3::zero());
    let d = Vec3::<f32>::c(1e-30, 0.0, 0.0).normalize();
    assert!(d.x.is_finite());
    let n = Vec3::<f32>::c(3.0, 4.0, 0.0).normalize();
    assert_relative_eq!(n.length(), 1.0, epsilon = 1e-6);
    // Huge coordinates: no overflow to inf in the squared length for 1e7.
    let h = Vec3::<f32>::c(1e7, 1e7, 0.0).normalize();
    assert_relative_eq!(h.length(), 1.0, epsilon = 1e-6);
}

#[test]
fn faceforward_grazing_keeps_n() {
    let n = Vec3::<f32>::c(0.0, 0.0, 1.0);
    let i = Vec3::<f32>::c(1.0, 0.0, 0.0);
    assert_eq!(faceforward(n, i, n), n);
    assert_eq!(faceforward(n, Vec3::c(0.0, 0.0, 1.0), n), -n);
    assert_eq!(faceforward(n, Vec3::c(0.0, 0.0, -1.0), n), n);
}

#[test]
fn refract_and_fresnel_edge_cases() {
    let n = Vec3::<f64>::c(0.0, 0.0, 1.0);
    // Straight through at eta = 1: no bending, no reflection.
    let i = Vec3::<f64>::c(0.6, 0.0, -0.8);
    let t = refract(i, n, 1.0);
    assert_relative_eq!(t.x, i.x, epsilon = 1e-12);
    assert_relative_eq!(t.z, i.z, epsilon = 1e-12);
    let f = fresnel(i, n, 1.0);
    assert!(f.kr.abs() < 1e-12, "kr at eta=1: {}", f.kr);
    assert_relative_eq!(f.kr + f.kt, 1.0);
    // Normal incidence, glass: ((n-1)/(n+1))² = 0.04.
    let f = fresnel(Vec3::<f64>::c(0.0, 0.0, -1.0), n, 1.0 / 1.5);
    assert_relative_eq!(f.kr, 0.04, epsilon = 1e-12);
    // Total internal reflection from inside glass at a steep angle.
    let i = Vec3::<f64>::c(0.9, 0.0, -(1.0f64 - 0.81).sqrt());
    let f = fresnel(i, n, 1.5);
    assert_eq!(f.kr, 1.0);
    assert_eq!(f.kt, 0.0);
    assert_eq!(f.t, Vec3::zero());
    assert_eq!(refract(i, n, 1.5), Vec3::zero());
    // Exactly grazing (N·I = 0): full reflection, finite.
    let f = fresnel(Vec3::<f32>::c(1.0, 0.0, 0.0), Vec3::c(0.0, 0.0, 1.0), 1.0 / 1.5);
    assert_eq!(f.kr, 1.0);
    assert!(f.r.x.is_finite() && f.t.x.is_finite());
    // Zero-length I: finite.
    let f = fresnel(Vec3::<f32>::zero(), Vec3::c(0.0, 0.0, 1.0), 1.0 / 1.5);
    assert!(f.kr.is_finite() && f.kt.is_finite());
}

#[test]
fn fresnel_is_reciprocal_enough_and_monotone_in_angle() {
    let n = Vec3::<f64>::c(0.0, 0.0, 1.0);
    let mut last = 0.0;
    for k in 0..=89 {
        let a = (k as f64).to_radians();
        let i = Vec3::<f64>::new(a.sin(), 0.0, -a.cos());
        let f = fresnel(i, n, 1.0 / 1.5);
        assert!(f.kr >= last - 1e-12, "Kr not monotone at {k}°");
        assert!((0.0..=1.0).contains(&f.kr));
        last = f.kr;
    }
}

#[test]
fn spline_interpolates_catmull_rom_knots_and_linear() {
    let knots = [0.0f64, 1.0, 4.0, 2.0, 3.0, 5.0];
    let b = SplineBasis::CATMULL_ROM;
    // 6 knots → 3 segments; x = 0, 1/3, 2/3, 1 hit the inner knots 1, 4, 2, 3.
    for (x, want) in [(0.0, 1.0), (1.0 / 3.0, 4.0), (2.0 / 3.0, 2.0), (1.0, 3.0)] {
        assert_relative_eq!(spline(&b, x, &knots), want, epsilon = 1e-12);
    }
    let lin = SplineBasis::LINEAR;
    assert_relative_eq!(spline(&lin, 1.0 / 6.0, &knots), 2.5, epsilon = 1e-12);
    let colors =
        [Color::<f64>::c(0.0, 0.0, 0.0), Color::c(1.0, 0.0, 0.0), Color::c(0.0, 1.0, 0.0), Color::c(0.0, 0.0, 1.0)];
    let c = spline(&b, 0.0, &colors);
    assert_relative_eq!(c.r, 1.0, epsilon = 1e-12);
    // B-spline of constant knots is that constant (partition of unity).
    let flat = [2.0f64; 7];
    for x in [0.0, 0.3, 0.77, 1.0] {
        assert_relative_eq!(spline(&SplineBasis::BSPLINE, x, &flat), 2.0, epsilon = 1e-12);
        assert_relative_eq!(spline(&SplineBasis::BEZIER, x, &flat), 2.0, epsilon = 1e-12);
    }
    for name in ["catmull-rom", "bezier", "bspline", "hermite", "power", "linear"] {
        assert!(SplineBasis::from_name(name).is_some());
    }
    assert!(SplineBasis::from_name("cubic").is_none());
}

#[test]
fn color_spaces_round_trip() {
    let spaces = [ColorSpace::Hsv, ColorSpace::Hsl, ColorSpace::Xyz, ColorSpace::XyY, ColorSpace::Yiq];
    let samples = [[0.2, 0.5, 0.9], [1.0, 0.0, 0.0], [0.3, 0.3, 0.3], [0.0, 0.0, 0.0], [0.9, 0.8, 0.1]];
    for s in spaces {
        for c in samples {
            let rgb = Color::<f64>::from_array(c);
            let back = to_rgb(s, from_rgb(s, rgb));
            for k in 0..3 {
                assert!((back[k] - rgb[k]).abs() < 2e-3, "{s:?} {c:?} → {back:?}");
            }
        }
    }
    let red = hsv_to_rgb(Color::<f64>::c(0.0, 1.0, 1.0));
    assert_relative_eq!(red.r, 1.0);
    let green = hsv_to_rgb(Color::<f64>::c(1.0 / 3.0, 1.0, 1.0));
    assert_relative_eq!(green.g, 1.0, epsilon = 1e-12);
    assert!(green.r.abs() < 1e-12);
    assert_eq!(ColorSpace::from_name("hsv"), Some(ColorSpace::Hsv));
    assert_eq!(ColorSpace::from_name("cmyk"), None);
}

#[test]
fn matrix_inverse_transform_and_singular() {
    let m = Matrix4::<f64>::rotate(0.7, Vec3::c(1.0, 2.0, 3.0))
        * Matrix4::scale(Vec3::c(2.0, 3.0, 0.5))
        * Matrix4::translate(Vec3::c(1.0, -2.0, 3.0));
    let p = Vec3::<f64>::c(0.3, -1.2, 4.0);
    let q = m.inverse().transform_point(m.transform_point(p));
    for k in 0..3 {
        assert_relative_eq!(q[k], p[k], epsilon = 1e-12);
    }
    let id = m * m.inverse();
    for r in 0..4 {
        for c in 0..4 {
            assert_relative_eq!(id.m[r][c], if r == c { 1.0 } else { 0.0 }, epsilon = 1e-12);
        }
    }
    let singular = Matrix4::<f32>::scale(Vec3::c(1.0, 0.0, 1.0));
    assert_eq!(singular.determinant(), 0.0);
    let inv = singular.inverse();
    assert!(inv.m.iter().flatten().all(|v| v.is_finite()));
    // Normals transform by the inverse transpose: stay perpendicular to tangents.
    let t = Vec3::<f64>::c(1.0, 1.0, 0.0);
    let nrm = Vec3::<f64>::c(1.0, -1.0, 0.0);
    let s = Matrix4::<f64>::scale(Vec3::c(3.0, 1.0, 1.0));
    assert!(s.transform_vector(t).dot(s.transform_normal(nrm)).abs() < 1e-12);
}

#[test]
fn ptlined_and_rotate() {
    let d = ptlined(Vec3::<f64>::c(0.0, 0.0, 0.0), Vec3::c(2.0, 0.0, 0.0), Vec3::c(1.0, 3.0, 0.0));
    assert_relative_eq!(d, 3.0);
    let d = ptlined(Vec3::<f64>::c(0.0, 0.0, 0.0), Vec3::c(0.0, 0.0, 0.0), Vec3::c(0.0, 4.0, 0.0));
    assert_relative_eq!(d, 4.0);
    let r = rotate(Vec3::<f64>::c(1.0, 0.0, 0.0), PI / 2.0, Vec3::zero(), Vec3::c(0.0, 0.0, 1.0));
    assert!((r.y.abs() - 1.0).abs() < 1e-12 && r.x.abs() < 1e-12);
}

#[test]
fn derivative_functions_without_derivatives_fall_back() {
    let g = anysl_core::Globals::<f32>::unit_square(0.3, 0.6);
    assert_eq!(du(&g, 2.0f32), 0.0);
    assert_eq!(dv(&g, 2.0f32), 0.0);
    assert_eq!(area(g.P), 0.0);
    assert_eq!(filterwidth(0.4f32), 0.0);
    assert_eq!(filterstep(0.5f32, 0.4), 0.0);
    assert_eq!(filterstep(0.5f32, 0.6), 1.0);
    assert_eq!(calculatenormal(&g, g.P), Vec3::zero());
    assert_eq!(deriv(&g, 1.0f32, 2.0), 0.0);
}

#[test]
fn denormals_are_not_flushed_by_the_library() {
    let tiny = f32::from_bits(1); // smallest denormal
    assert!(tiny > 0.0);
    assert_eq!(clamp(tiny, 0.0, 1.0), tiny);
    assert_eq!(mix(0.0f32, tiny, 1.0), tiny);
    assert_eq!(step(tiny, 0.0f32), 0.0);
    assert_eq!(smoothstep(0.0f32, tiny, tiny), 1.0);
}

/// A small program with every kind of control flow, written twice: with plain Rust control
/// flow and with `Exec`. For `f32` the two must agree exactly.
fn program_exec(a: f32, b: f32, n: u32) -> (f32, f32) {
    let mut e = Exec::<f32>::new();
    let mut x = a;
    let mut acc = 0.0f32;
    let mut i = 0.0f32;
    let limit = n as f32;
    e.loop_(|e| {
        e.break_if(!i.lt(limit));
        e.if_else(
            x.gt(b),
            |e, then| {
                if then {
                    e.update(&mut x, |x| x - b * 0.5)
                } else {
                    e.update(&mut x, |x| x + 1.25)
                }
            },
        );
        e.continue_if(fmod(i, 3.0).eq(1.0));
        e.update(&mut acc, |acc| acc + x);
        e.break_if(acc.gt(40.0));
        e.end_continue();
        e.update(&mut i, |i| i + 1.0);
    });
    e.return_if(acc.lt(0.0));
    e.update(&mut acc, |acc| acc * 2.0);
    (x, acc)
}

fn program_plain(a: f32, b: f32, n: u32) -> (f32, f32) {
    let mut x = a;
    let mut acc = 0.0f32;
    let mut i = 0.0f32;
    let limit = n as f32;
    loop {
        if !(i < limit) {
            break;
        }
        if x > b {
            x -= b * 0.5;
        } else {
            x += 1.25;
        }
        if fmod(i, 3.0) != 1.0 {
            acc += x;
            if acc > 40.0 {
                break;
            }
        }
        i += 1.0;
    }
    if acc < 0.0 {
        return (x, acc);
    }
    acc *= 2.0;
    (x, acc)
}

proptest! {
    #[test]
    fn exec_scalar_matches_plain_control_flow(a in -20.0f32..20.0, b in -5.0f32..5.0, n in 0u32..30) {
        prop_assert_eq!(program_exec(a, b, n), program_plain(a, b, n));
    }
}

#[test]
fn choose_evaluates_only_needed_arms_for_scalars() {
    let mut e = Exec::<f32>::new();
    let mut calls = 0;
    let v = e.choose(true, |_, then| {
        if then {
            1.0f32
        } else {
            calls += 1;
            2.0
        }
    });
    assert_eq!(v, 1.0);
    assert_eq!(calls, 0);
}
