//! What the shading interface must do in a scene: shadows, transparency, reflection rays and
//! screen-space derivatives.

use crate::common;

use anysl_renderers::{
    render_packet, render_packet_split, render_pbrt, render_scalar, Camera, Image, Instance, Integrator, Mesh,
    RenderOptions, Scene,
};
use common::{Mirror, SDerivs, TestLight, TestSurface};
use glam::{Mat4, Vec3, Vec3A};

fn opts(shadows: bool) -> RenderOptions {
    RenderOptions { threads: 1, shadows, ..RenderOptions::default() }
}

/// A ground plane (surface 0) and a sphere (surface 1) of radius 0.5 floating at height 1,
/// a light straight above, looked at from the front and above.
fn shadow_scene(ground: TestSurface, ball: TestSurface) -> Scene<TestSurface, TestLight> {
    let camera = Camera::new(Vec3A::new(0.0, 3.0, 4.0), Vec3A::new(0.0, 0.3, 0.0), Vec3A::Y, 0.9, 48, 48);
    let meshes = [Mesh::ground_quad(8.0, 4.0), Mesh::uv_sphere(0.5, 32, 16)];
    let instances = vec![
        Instance::new(0, 0, Mat4::IDENTITY),
        Instance::new(1, 1, Mat4::from_translation(Vec3::new(0.0, 1.0, 0.0))),
    ];
    Scene::new(camera, &meshes, instances, vec![ground, ball], vec![TestLight::at([0.0, 6.0, 0.0], 1.0)]).unwrap()
}

/// The pixel where the camera sees the ground point (0, 0, 0), straight under the sphere.
fn ground_pixel(scene: &Scene<TestSurface, TestLight>, p: Vec3A) -> (u32, u32) {
    let cam = &scene.camera;
    let mut best = (0, 0, f32::INFINITY);
    for y in 0..cam.height() {
        for x in 0..cam.width() {
            let d = cam.ray_dir(x as f32 + 0.5, y as f32 + 0.5);
            let to_p = (p - cam.position()).normalize();
            let err = (d - to_p).length();
            if err < best.2 {
                best = (x, y, err);
            }
        }
    }
    (best.0, best.1)
}

#[test]
fn shadows_darken_what_they_should() {
    let lambert = TestSurface::lambert(0.8, [1.0; 3]);
    let scene = shadow_scene(lambert.clone(), lambert);
    let (ux, uy) = ground_pixel(&scene, Vec3A::ZERO); // under the sphere
    let (fx, fy) = ground_pixel(&scene, Vec3A::new(2.0, 0.0, 1.0)); // in the open
    type R = fn(&Scene<TestSurface, TestLight>, &RenderOptions) -> Image;
    let renderers: [(&str, R); 5] = [
        ("scalar", |s, o| render_scalar(s, o)),
        ("packet f32", |s, o| render_packet::<f32, _, _>(s, o)),
        ("packet x4", |s, o| render_packet::<anysl_simd::F32x4, _, _>(s, o)),
        ("pbrt active", |s, o| render_pbrt(s, o, Integrator::Active)),
        ("pbrt passive", |s, o| render_pbrt(s, o, Integrator::Passive)),
    ];
    for (name, render) in renderers {
        let lit = render(&scene, &opts(false));
        let shadowed = render(&scene, &opts(true));
        let under_lit = lit.pixel(ux, uy)[1];
        let under_shadowed = shadowed.pixel(ux, uy)[1];
        // Straight under the light: Kd · cos 0 = 0.8 without shadows.
        if name != "pbrt passive" {
            assert!((under_lit - 0.8).abs() < 0.02, "{name}: unshadowed ground {under_lit}");
            assert!(under_shadowed.abs() < 1e-6, "{name}: shadowed ground {under_shadowed}");
        } else {
            // The passive integrator adds sky light bounced once; the shadow still removes
            // the direct part.
            assert!(under_lit - under_shadowed > 0.6, "{name}: {under_lit} vs {under_shadowed}");
        }
        // In the open, shadows change nothing.
        let (a, b) = (lit.pixel(fx, fy), shadowed.pixel(fx, fy));
        if name != "pbrt passive" {
            assert_eq!(a, b, "{name}: open ground changed");
        }
        assert!(a[1] > 0.3, "{name}: open ground too dark: {a:?}");
        // The sphere's top faces the light and is never shadowed.
        assert!(shadowed.mean()[1] < lit.mean()[1], "{name}");
    }
}

#[test]
fn transparent_screen_lets_the_background_through() {
    let lambert = TestSurface::lambert(0.8, [1.0, 0.5, 0.25]);
    let with_ball = |ball: TestSurface| shadow_scene(lambert.clone(), ball);
    for sky_visible in [false, true] {
        let mut clear = with_ball(TestSurface::screen(0.0));
        clear.sky.visible_to_camera = sky_visible;
        // Without shadows an invisible sphere must leave no trace at all.
        let mut half = with_ball(TestSurface::screen(0.5));
        half.sky.visible_to_camera = sky_visible;
        type Render = fn(&Scene<TestSurface, TestLight>) -> Image;
        let renders: [(&str, Render); 4] = [
            ("scalar", |s| render_scalar(s, &opts(false))),
            ("packet x8", |s| render_packet::<anysl_simd::F32x8, _, _>(s, &opts(false))),
            ("packet split", |s| render_packet_split::<f32, _, _>(s, &opts(false), 16)),
            ("pbrt active", |s| render_pbrt(s, &opts(false), Integrator::Active)),
        ];
        // The reference: the same scene with the sphere moved out of sight.
        let mut empty = Scene::new(
            clear.camera,
            &[Mesh::ground_quad(8.0, 4.0)],
            vec![Instance::new(0, 0, Mat4::IDENTITY)],
            vec![lambert.clone()],
            vec![TestLight::at([0.0, 6.0, 0.0], 1.0)],
        )
        .unwrap();
        empty.sky.visible_to_camera = sky_visible;
        for (name, render) in renders {
            let reference = render(&empty);
            let through = render(&clear);
            assert!(reference.max_abs_diff(&through) < 1e-5, "{name}: an Oi = 0 screen is visible");
            // Half opacity through the sphere's centre: two layers of (0.5 red, Oi 0.5)
            // over the ground, Ci + (1 − Oi)·behind twice = 0.75 red + 0.25 ground.
            let mixed = render(&half);
            let (cx, cy) = ground_pixel(&half, Vec3A::new(0.0, 1.0, 0.0));
            let (m, r) = (mixed.pixel(cx, cy), reference.pixel(cx, cy));
            assert!(r[1] > 0.1, "{name}: the ground behind is dark: {r:?}");
            let want = [0.75 + 0.25 * r[0], 0.25 * r[1], 0.25 * r[2]];
            for c in 0..3 {
                assert!((m[c] - want[c]).abs() < 1e-3, "{name}: {m:?}, want {want:?}");
            }
        }
    }
}

#[test]
fn mirror_reflects_the_scene_through_trace() {
    let ground = TestSurface::lambert(0.8, [0.2, 1.0, 0.2]);
    let scene = shadow_scene(ground, TestSurface::Mirror(Mirror { Kr: 1.0 }));
    // No shadows: the ground the mirror shows lies in the sphere's shadow.
    let img = render_scalar(&scene, &opts(false));
    let simd = render_packet::<anysl_simd::F32x4, _, _>(&scene, &opts(false));
    assert!(img.psnr(&simd) > 40.0);
    // The lower half of the sphere mirrors the green ground.
    let (x, y) = ground_pixel(&scene, Vec3A::new(0.0, 0.62, 0.3));
    let p = img.pixel(x, y);
    assert!(p[1] > 0.1 && p[1] > 2.0 * p[0], "mirror shows {p:?}, not the green ground");
}

#[test]
fn scalar_renderer_derivatives_match_finite_differences() {
    // s along the sphere's longitude: ∂s/∂x from the ray differentials against the central
    // difference of s between neighbouring pixels.
    let scene = anysl_renderers::scenes::table1(TestSurface::SDerivs(SDerivs::default()), Vec::<TestLight>::new(), 64);
    let img = render_scalar(&scene, &opts(false));
    let mut checked = 0;
    for y in 20..44 {
        for x in 20..44 {
            let s = |x: u32, y: u32| img.pixel(x, y)[2];
            let (dsdx, dsdy) = (img.pixel(x, y)[0], img.pixel(x, y)[1]);
            let (fx, fy) = ((s(x + 1, y) - s(x - 1, y)) / 2.0, (s(x, y + 1) - s(x, y - 1)) / 2.0);
            // Skip the seam where s wraps from 1 to 0.
            if (s(x + 1, y) - s(x - 1, y)).abs() > 0.2 || (s(x, y + 1) - s(x, y - 1)).abs() > 0.2 {
                continue;
            }
            let tol = 0.15 * fx.abs().max(fy.abs()) + 2e-4;
            assert!((dsdx - fx).abs() < tol, "({x}, {y}): ∂s/∂x {dsdx} vs {fx}");
            assert!((dsdy - fy).abs() < tol, "({x}, {y}): ∂s/∂y {dsdy} vs {fy}");
            checked += 1;
        }
    }
    assert!(checked > 400, "{checked}");
    assert!(img.pixel(32, 32)[0].abs() > 1e-3);
    // The packet renderer seeds the same derivatives (as `Dual<F>`) at any width …
    for packet in [
        render_packet::<f32, _, _>(&scene, &opts(false)),
        render_packet::<anysl_simd::F32x8, _, _>(&scene, &opts(false)),
    ] {
        assert!(packet.max_abs_diff(&img) < 1e-5, "packet derivatives differ by {}", packet.max_abs_diff(&img));
    }
    // … and with derivatives switched off every renderer sees zero.
    let plain = RenderOptions { derivatives: false, ..opts(false) };
    assert_eq!(render_packet::<anysl_simd::F32x8, _, _>(&scene, &plain).pixel(32, 32)[0], 0.0);
    assert_eq!(render_scalar(&scene, &plain).pixel(32, 32)[0], 0.0);
}
