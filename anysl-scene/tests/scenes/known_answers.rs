//! Known-answer renders of small RIB scenes (≤ 64×64), shaded by the interpreter: the
//! pinhole formula, exact colours, exposure and quantization, filter widths, one-sided
//! culling, orthographic against perspective, and the three renderers against each other.

use anysl_renderers::{render_packet, render_pbrt, render_scalar, Integrator, RenderOptions};
use anysl_scene::build::{BuildOptions, Film, FrameDesc, SceneBuilder};
use anysl_scene::film::quantized;
use anysl_scene::render::{frame_scene, Surfaces};
use anysl_scene::shaders::ShaderLibrary;
use anysl_simd::F32x8;

#[derive(Clone, Copy, Debug)]
enum Renderer {
    Packet,
    Scalar,
    Pbrt,
}

fn frames(rib: &str) -> Vec<FrameDesc> {
    let mut b = SceneBuilder::new(BuildOptions::default());
    let report = anysl_rib::parse_str("test.rib", rib, &mut b, &anysl_rib::Options::new());
    if let Err(e) = &report {
        panic!("{}", e.render());
    }
    b.finish()
}

fn render_with(rib: &str, renderer: Renderer) -> (Film, Vec<[f32; 4]>) {
    let frame = frames(rib).remove(0);
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(Vec::new(), Vec::new()));
    let fs = frame_scene(&frame, &mut surfaces).expect("the scene builds");
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let image = match renderer {
        Renderer::Packet => render_packet::<F32x8, _, _>(&fs.scene, &opts),
        Renderer::Scalar => render_scalar(&fs.scene, &opts),
        Renderer::Pbrt => render_pbrt(&fs.scene, &opts, Integrator::Active),
    };
    let pixels = fs.finish(&frame.film, &image);
    (frame.film, pixels)
}

fn render(rib: &str) -> (Film, Vec<[f32; 4]>) {
    render_with(rib, Renderer::Scalar)
}

const ONE_SAMPLE: &str = "PixelSamples 1 1 PixelFilter \"box\" 1 1\n";

#[test]
fn a_sphere_covers_the_pixels_the_pinhole_formula_says() {
    let (r, d, fov) = (1.0f32, 6.0f32, 40.0f32);
    let rib = format!(
        "Format 64 64 1 {ONE_SAMPLE} Projection \"perspective\" \"fov\" {fov}\n\
         WorldBegin Surface \"constant\" Translate 0 0 {d} Sphere {r} -{r} {r} 360 WorldEnd"
    );
    let (_, px) = render(&rib);
    // The silhouette's screen radius: tan(asin(r/d)) / tan(fov/2), in units of half the image.
    let screen_r = (r / d).asin().tan() / (fov.to_radians() * 0.5).tan();
    let pixel_r = screen_r * 32.0;
    let mut wrong = 0;
    for y in 0..64 {
        for x in 0..64 {
            let dist = ((x as f32 + 0.5 - 32.0).powi(2) + (y as f32 + 0.5 - 32.0).powi(2)).sqrt();
            let covered = px[y * 64 + x][3] > 0.5;
            if covered != (dist < pixel_r) {
                assert!(
                    (dist - pixel_r).abs() < 1.0,
                    "pixel ({x}, {y}) at {dist} px from the centre, radius {pixel_r}"
                );
                wrong += 1;
            }
        }
    }
    assert!(wrong < 8, "{wrong} pixels differ on the silhouette");
}

#[test]
fn a_constant_disk_has_exactly_its_colour() {
    let rib = format!(
        "Format 32 32 1 {ONE_SAMPLE} Quantize \"rgba\" 255 0 255 0 Projection \"perspective\" \"fov\" 30\n\
         WorldBegin Color 0.2 0.4 0.6 Surface \"constant\" Translate 0 0 5 Disk 0 1 360 WorldEnd"
    );
    let (film, px) = render(&rib);
    assert_eq!(px[16 * 32 + 16], [0.2, 0.4, 0.6, 1.0]);
    let q = quantized(&film, &px, 3);
    assert_eq!(&q[3 * (16 * 32 + 16)..3 * (16 * 32 + 17)], &[51, 102, 153]);
    // Outside the disk: black, no coverage.
    assert_eq!(px[0], [0.0; 4]);
}

#[test]
fn exposure_and_quantize_apply_to_the_pixels() {
    let scene = |opts: &str| {
        let rib = format!(
            "Format 8 8 1 {ONE_SAMPLE} {opts} Projection \"orthographic\"\n\
             WorldBegin Color 0.25 0.25 0.25 Surface \"constant\" Translate 0 0 5 Disk 0 4 360 WorldEnd"
        );
        let (film, px) = render(&rib);
        quantized(&film, &px, 3)[0]
    };
    assert_eq!(scene("Quantize \"rgba\" 255 0 255 0"), 64);
    assert_eq!(scene("Quantize \"rgba\" 255 0 255 0 Exposure 2 1"), 128);
    assert_eq!(scene("Quantize \"rgba\" 255 0 255 0 Exposure 1 2"), 128);
    assert_eq!(scene("Quantize \"rgba\" 1000 100 200 0"), 200);
    assert_eq!(scene("Quantize \"rgba\" 100 0 20 0"), 20);
}

#[test]
fn a_box_filter_spreads_an_edge_over_its_width() {
    // Orthographic, one screen unit per pixel: the polygon covers x < 0, the left half.
    let scene = |width: f32| {
        let rib = format!(
            "Format 16 4 1 PixelSamples 4 4 PixelFilter \"box\" {width} {width} Quantize \"rgba\" 255 0 255 0\n\
             Projection \"orthographic\" ScreenWindow -8 8 -2 2\n\
             WorldBegin Surface \"constant\" Translate 0 0 1\n\
             Polygon \"P\" [-20 -20 0  0 -20 0  0 20 0  -20 20 0] WorldEnd"
        );
        let (_, px) = render(&rib);
        (0..16).map(|x| px[16 + x][0]).collect::<Vec<f32>>()
    };
    let sharp = scene(1.0);
    assert_eq!(&sharp[6..10], &[1.0, 1.0, 0.0, 0.0]);
    let wide = scene(3.0);
    // A 3-pixel box: the pixels next to the edge see 2/3 and 1/3 of covered samples.
    let want = [1.0, 2.0 / 3.0, 1.0 / 3.0, 0.0];
    for (got, want) in wide[6..10].iter().zip(want) {
        assert!((got - want).abs() < 1e-5, "{:?}", &wide[6..10]);
    }
}

#[test]
fn one_sided_surfaces_are_culled_from_behind() {
    let scene = |attrs: &str| {
        let rib = format!(
            "Format 8 8 1 {ONE_SAMPLE} Projection \"perspective\" \"fov\" 30\n\
             WorldBegin Surface \"constant\" Translate 0 0 5 {attrs} Disk 0 1 360 WorldEnd"
        );
        render(&rib).1[4 * 8 + 4][3]
    };
    // The disk's normal is +z, away from the camera: its back faces the eye.
    assert_eq!(scene("Sides 2"), 1.0);
    assert_eq!(scene("Sides 1"), 0.0);
    assert_eq!(scene("Sides 1 ReverseOrientation"), 1.0);
    assert_eq!(scene("Sides 1 Orientation \"inside\""), 1.0);
    // A mirroring transform flips the orientation too.
    assert_eq!(scene("Sides 1 Scale 1 1 -1"), 1.0);
}

#[test]
fn orthographic_size_does_not_depend_on_distance() {
    let covered = |projection: &str, d: f32| {
        let rib = format!(
            "Format 64 64 1 {ONE_SAMPLE} Projection {projection} ScreenWindow -2 2 -2 2\n\
             WorldBegin Surface \"constant\" Translate 0 0 {d} Sphere 1 -1 1 360 WorldEnd"
        );
        render(&rib).1.iter().filter(|p| p[3] > 0.5).count()
    };
    let (near, far) = (covered("\"orthographic\"", 3.0), covered("\"orthographic\"", 30.0));
    assert_eq!(near, far);
    // A circle of radius 16 pixels.
    let area = std::f32::consts::PI * 16.0 * 16.0;
    assert!((near as f32 - area).abs() < 0.05 * area, "{near} vs {area}");
    let (pnear, pfar) = (covered("\"perspective\" \"fov\" 90", 3.0), covered("\"perspective\" \"fov\" 90", 6.0));
    assert!(pnear > 3 * pfar, "{pnear} vs {pfar}");
}

/// Orthographic rays differ in origin, not direction: a plane facing the camera has `area(P)`
/// one pixel's area of the screen window, at any distance, in the scalar and packet
/// renderers (the screen derivatives come from the origin differentials).
#[test]
fn orthographic_derivatives_are_the_pixel_spacing() {
    let dir = std::env::temp_dir().join(format!("anysl-scene-ortho-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("showarea.sl"), "surface showarea(float scale = 1;) { Ci = area(P) * scale; Oi = 1; }")
        .expect("write shader");
    for d in [3.0, 30.0] {
        let rib = format!(
            "Format 16 16 1 {ONE_SAMPLE} Projection \"orthographic\" ScreenWindow -2 2 -2 2\n\
             WorldBegin Surface \"showarea\" \"scale\" 16 Translate 0 0 {d}\n\
             Polygon \"P\" [-5 -5 0 5 -5 0 5 5 0 -5 5 0] WorldEnd"
        );
        let frame = frames(&rib).remove(0);
        let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(vec![dir.clone()], Vec::new()));
        let fs = frame_scene(&frame, &mut surfaces).expect("the scene builds");
        let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
        for image in [render_scalar(&fs.scene, &opts), render_packet::<F32x8, _, _>(&fs.scene, &opts)] {
            let px = fs.finish(&frame.film, &image);
            // Pixels are 0.25 apart: area 1/16, times 16.
            assert!(px.iter().all(|p| (p[0] - 1.0).abs() < 1e-4), "{:?}", &px[..4]);
        }
    }
}

fn psnr(a: &[[f32; 4]], b: &[[f32; 4]]) -> f64 {
    let mse: f64 = a
        .iter()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |c| f64::from(p[c].clamp(0.0, 1.0) - q[c].clamp(0.0, 1.0)).powi(2)))
        .sum::<f64>()
        / (3 * a.len()) as f64;
    if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (1.0 / mse).log10()
    }
}

#[test]
fn packet_scalar_and_pbrt_agree() {
    let rib = "Format 48 36 1 PixelSamples 2 2 PixelFilter \"gaussian\" 2 2\n\
               Projection \"perspective\" \"fov\" 35 Translate 0 -0.3 6\n\
               WorldBegin\n\
               LightSource \"ambientlight\" 1 \"intensity\" 0.1\n\
               LightSource \"distantlight\" 2 \"from\" [1 1 -1] \"to\" [0 0 0] \"intensity\" 0.8\n\
               LightSource \"pointlight\" 3 \"from\" [-2 2 -2] \"intensity\" 8\n\
               AttributeBegin Color 0.9 0.3 0.2 Surface \"plastic\" \"Ks\" 0.6 \"roughness\" 0.1\n\
               Sphere 1 -1 1 360 AttributeEnd\n\
               AttributeBegin Surface \"matte\" Translate 0 -1 0 Rotate -90 1 0 0 Disk 0 4 360 AttributeEnd\n\
               WorldEnd";
    let (_, scalar) = render_with(rib, Renderer::Scalar);
    let (_, packet) = render_with(rib, Renderer::Packet);
    let (_, pbrt) = render_with(rib, Renderer::Pbrt);
    assert!(scalar.iter().any(|p| p[0] > 0.3), "the picture is dark");
    let (a, b) = (psnr(&scalar, &packet), psnr(&scalar, &pbrt));
    assert!(a >= 40.0 && b >= 40.0, "PSNR scalar/packet {a:.1} dB, scalar/pbrt {b:.1} dB");
}

#[test]
fn frames_keep_their_own_options() {
    let rib = "Format 16 16 1\n\
               FrameBegin 1 Format 8 4 1 Display \"one.tif\" \"file\" \"rgb\" WorldBegin Sphere 1 -1 1 360 WorldEnd FrameEnd\n\
               FrameBegin 2 Display \"two\" \"framebuffer\" \"rgba\" Display \"+two-copy\" \"png\" \"rgb\"\n\
               WorldBegin WorldEnd FrameEnd";
    let f = frames(rib);
    assert_eq!(f.len(), 2);
    assert_eq!((f[0].number, f[0].film.xres, f[0].film.yres), (Some(1), 8, 4));
    assert_eq!((f[1].number, f[1].film.xres, f[1].film.yres), (Some(2), 16, 16));
    let names: Vec<&str> = f[1].displays.iter().map(|d| d.file.as_str()).collect();
    assert_eq!(names, ["two.png", "two-copy.png"]);
    assert!(f[1].displays[0].alpha && !f[1].displays[1].alpha);
    assert_eq!(f[0].displays[0].file, "one.tif");
}

#[test]
fn a_wrong_parameter_warns_and_the_rest_renders() {
    let rib = format!(
        "Format 8 8 1 {ONE_SAMPLE} Projection \"perspective\" \"fov\" 30\n\
         WorldBegin Surface \"plastic\" \"Kx\" 1 \"string Ks\" \"no\" Translate 0 0 5 Sphere 1 -1 1 360 WorldEnd"
    );
    let frame = frames(&rib).remove(0);
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(Vec::new(), Vec::new()));
    let fs = frame_scene(&frame, &mut surfaces).expect("renders despite the parameters");
    assert_eq!(fs.warnings.len(), 2, "{:?}", fs.warnings);
    assert!(fs.warnings[0].contains("\"Kx\"") && fs.warnings[0].contains("plastic"), "{}", fs.warnings[0]);
    assert!(fs.warnings[1].contains("string Ks") && fs.warnings[1].contains("float Ks"), "{}", fs.warnings[1]);
}

/// A primitive variable of one value named like a shader parameter sets that parameter for
/// the primitive (over the `Surface` list); other primitive variables are no warning.
#[test]
fn a_constant_primitive_variable_binds_to_the_shader_parameter() {
    let scene = |surface: &str, prim: &str| {
        format!(
            "Format 16 16 1 {ONE_SAMPLE} Projection \"perspective\" \"fov\" 30\n\
             WorldBegin LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n\
             Surface {surface} Translate 0 0 5 Sphere 1 -1 1 360 {prim} WorldEnd"
        )
    };
    let bound = scene("\"matte\" \"Kd\" 0.9", "\"constant float Kd\" [0.3] \"constant float notashaderparam\" [7]");
    let given = scene("\"matte\" \"Kd\" 0.3", "");
    let (_, a) = render(&bound);
    let (_, b) = render(&given);
    let (_, c) = render(&scene("\"matte\" \"Kd\" 0.9", ""));
    assert!(a[8 * 16 + 8][0] > 0.2, "{:?}", a[8 * 16 + 8]);
    assert_eq!(a, b);
    assert_ne!(a, c);
    let frame = frames(&bound).remove(0);
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(Vec::new(), Vec::new()));
    let fs = frame_scene(&frame, &mut surfaces).expect("builds");
    assert!(fs.warnings.is_empty(), "{:?}", fs.warnings);
    // A variable with a value per vertex does not bind (it would vary over the surface).
    let (_, d) = render(&scene("\"matte\" \"Kd\" 0.9", "\"varying float Kd\" [0.3 0.3 0.3 0.3]"));
    assert_eq!(d, c);
}
