//! The AnySL claim: the same shader in renderers with very different internals gives the same
//! picture. Silhouettes need no special handling: every renderer traces the same primary
//! rays (same camera, same stratified sample positions) through the same BVH, so the hit
//! masks are identical; and there is no sampling noise to handle, because the packet, scalar
//! and active pbrt renderers are deterministic. What remains is the difference between
//! number types (f32, SIMD lanes, f64), which must stay far below 40 dB.

use crate::common;

use anysl_core::{Blend, ShadingFloat};
use anysl_renderers::{
    render_packet, render_packet_split, render_pbrt, render_scalar, render_scalar_as, scenes, Image, Integrator,
    RenderOptions, Scene,
};
use common::{workload_lights, Mirror, TestLight, TestSurface};

const MIN_PSNR: f64 = 40.0;

fn opts() -> RenderOptions {
    RenderOptions { threads: 1, ..RenderOptions::default() }
}

fn assert_agree(name: &str, reference: &Image, other: &Image) {
    let p = reference.psnr(other);
    assert!(p >= MIN_PSNR, "{name}: PSNR {p:.1} dB < {MIN_PSNR} dB (max diff {})", reference.max_abs_diff(other));
}

/// Every renderer and instantiation that runs the shader's own lighting, against the scalar
/// renderer.
fn check_all_agree(scene: &Scene<TestSurface, TestLight>, opts: &RenderOptions) {
    let reference = render_scalar(scene, opts);
    assert!(reference.mean().iter().any(|c| *c > 0.01), "the reference picture is black");
    assert_agree("packet f32", &reference, &render_packet::<f32, _, _>(scene, opts));
    assert_agree("packet f64", &reference, &render_packet::<f64, _, _>(scene, opts));
    for lanes in [4, 8, 16] {
        assert_agree("packet split f32", &reference, &render_packet_split::<f32, _, _>(scene, opts, lanes));
    }
    assert_agree("scalar f64", &reference, &render_scalar_as::<f64, anysl_ad::Dual<f64>, _, _>(scene, opts));
    assert_agree("pbrt active", &reference, &render_pbrt(scene, opts, Integrator::Active));
    check_simd_agree(scene, opts, &reference);
}

fn check_simd_agree(scene: &Scene<TestSurface, TestLight>, opts: &RenderOptions, reference: &Image) {
    check_width::<anysl_simd::F32x4>(scene, opts, reference);
    check_width::<anysl_simd::F32x8>(scene, opts, reference);
    check_width::<anysl_simd::F32x16>(scene, opts, reference);
}

fn check_width<F: ShadingFloat + Blend<F>>(
    scene: &Scene<TestSurface, TestLight>,
    opts: &RenderOptions,
    reference: &Image,
) {
    let img = render_packet::<F, _, _>(scene, opts);
    assert_agree(F::NAME, reference, &img);
}

#[test]
fn table1_lambert_agrees_across_renderers() {
    let scene = scenes::table1(TestSurface::lambert(0.8, [1.0, 0.9, 0.7]), workload_lights(), 64);
    check_all_agree(&scene, &opts());
}

#[test]
fn supersampled_and_parallel_renders_agree() {
    let scene = scenes::table1(TestSurface::lambert(0.8, [1.0, 0.9, 0.7]), workload_lights(), 48);
    let o = RenderOptions { spp: 4, threads: 2, ..RenderOptions::default() };
    check_all_agree(&scene, &o);
    // Threads change nothing, bit for bit.
    let one = RenderOptions { threads: 1, ..o };
    assert_eq!(render_scalar(&scene, &o), render_scalar(&scene, &one));
    assert_eq!(render_packet::<f32, _, _>(&scene, &o), render_packet::<f32, _, _>(&scene, &one));
}

/// Ten different shaders (Lambert tints, a mirror, see-through screens) in one scene, so that
/// packets mix shaders, misses and secondary rays.
#[test]
fn mixed_shader_gallery_agrees_across_renderers() {
    let mut surfaces: Vec<TestSurface> =
        (0..10).map(|k| TestSurface::lambert(0.5 + 0.05 * k as f64, [1.0, 0.4 + 0.06 * k as f64, 0.3])).collect();
    surfaces[2] = TestSurface::Mirror(Mirror::default());
    surfaces[6] = TestSurface::screen(0.3);
    surfaces[8] = TestSurface::screen(0.0);
    let lights = vec![TestLight::at([-3.0, 6.0, 5.0], 0.9), TestLight::at([4.0, 3.0, 2.0], 0.4)];
    let scene = scenes::gallery(surfaces, lights, 96);
    check_all_agree(&scene, &opts());
}

/// With no sky and nothing to bounce off (one convex object), the passive path tracer's
/// Lambertian material under direct light is the active shader's own result.
#[test]
fn passive_material_matches_a_lambertian_shader() {
    let mut scene = scenes::table1(TestSurface::lambert(0.8, [1.0, 0.9, 0.7]), workload_lights(), 64);
    scene.sky.horizon = [0.0; 3];
    scene.sky.zenith = [0.0; 3];
    let active = render_pbrt(&scene, &opts(), Integrator::Active);
    let passive = render_pbrt(&scene, &opts(), Integrator::Passive);
    assert_agree("pbrt passive vs active", &active, &passive);
    // With a sky the indirect bounce brightens the sphere.
    scene.sky.horizon = [0.5; 3];
    scene.sky.zenith = [0.5; 3];
    let lit = render_pbrt(&scene, &opts(), Integrator::Passive);
    for c in 0..3 {
        assert!(lit.mean()[c] > passive.mean()[c] + 0.02, "{:?} vs {:?}", lit.mean(), passive.mean());
    }
}

/// The path tracer's random numbers are fixed per pixel: thread count does not matter.
#[test]
fn passive_path_tracer_is_deterministic() {
    let lights = vec![TestLight::at([-3.0, 6.0, 5.0], 0.9)];
    let scene = scenes::gallery((0..10).map(|_| TestSurface::lambert(0.7, [1.0; 3])).collect(), lights, 64);
    let a = render_pbrt(&scene, &RenderOptions { threads: 1, spp: 4, ..RenderOptions::default() }, Integrator::Passive);
    let b = render_pbrt(&scene, &RenderOptions { threads: 2, spp: 4, ..RenderOptions::default() }, Integrator::Passive);
    assert_eq!(a, b);
    let c = render_pbrt(
        &scene,
        &RenderOptions { threads: 1, spp: 4, seed: 99, ..RenderOptions::default() },
        Integrator::Passive,
    );
    assert_ne!(a, c, "the seed must change the indirect samples");
}

/// The statistics variant renders the same picture and counts every camera hit once per sample.
#[test]
fn packet_stats_count_the_shaded_points() {
    let scene = scenes::table1(TestSurface::lambert(0.8, [1.0; 3]), workload_lights(), 40);
    let o = RenderOptions { spp: 4, ..opts() };
    let cam = &scene.camera;
    let mut hits = 0u64;
    for y in 0..cam.height() {
        for x in 0..cam.width() {
            for k in 0..4 {
                let (ox, oy) = anysl_renderers::render::sample_offset(k, 2);
                let d = cam.ray_dir(x as f32 + ox, y as f32 + oy);
                hits += u64::from(scene.intersect(cam.position(), d, 0.0, f32::INFINITY).is_some());
            }
        }
    }
    let (img, stats) = anysl_renderers::render_packet_stats::<anysl_simd::F32x8, _, _>(&scene, &o, 8);
    assert_eq!(img, render_packet::<anysl_simd::F32x8, _, _>(&scene, &o));
    assert_eq!(stats.shaded_points, hits);
    assert!(stats.shading > std::time::Duration::ZERO && stats.shading <= stats.total);
}
