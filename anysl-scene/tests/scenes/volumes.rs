//! Volume shaders (`Atmosphere`, `Interior`, `Exterior`) and imager shaders in RIB scenes, with
//! known answers: `fog` attenuates by exp(-d/distance), `depthcue` blends linearly between its
//! distances, a ray-marched smoke of uniform density gives the same exponential, an `Interior`
//! acts on the chord a traced ray crosses and an `Exterior` on its way beyond, the `background` imager fills exactly the uncovered
//! part of each pixel and a vignette imager gives its formula.

use anysl_renderers::{render_packet, render_pbrt, render_scalar, Integrator, RenderOptions};
use anysl_scene::build::{BuildOptions, FrameDesc, SceneBuilder};
use anysl_scene::render::{frame_scene, FrameScene, Surfaces};
use anysl_scene::shaders::ShaderLibrary;
use anysl_simd::F32x8;
use std::path::PathBuf;

fn shader_dir() -> PathBuf {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("anysl-scene-volumes-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let files = [
            (
                "vignette.sl",
                "imager vignette(float cx = 8, cy = 8, radius = 10;)\n\
                 {\n    Ci *= max(0, 1 - distance(P, point(cx, cy, 0)) / radius);\n}\n",
            ),
            // Sees straight through: what a traced ray along I meets.
            ("seethrough.sl", "surface seethrough() { Oi = 1; Ci = trace(P, normalize(I)); }\n"),
        ];
        for (name, text) in files {
            std::fs::write(dir.join(name), text).expect("write shader");
        }
        dir
    })
    .clone()
}

fn scenes_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes"))
}

fn frame(rib: &str) -> FrameDesc {
    let mut b = SceneBuilder::new(BuildOptions::default());
    if let Err(e) = anysl_rib::parse_str("v.rib", rib, &mut b, &anysl_rib::Options::new()) {
        panic!("{}", e.render());
    }
    b.finish().remove(0)
}

fn scene(frame: &FrameDesc) -> Result<FrameScene<anysl_rsl::back::interp::InterpShader>, String> {
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(vec![shader_dir(), scenes_dir()], Vec::new()));
    frame_scene(frame, &mut surfaces)
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Renderer {
    Scalar,
    Packet,
    Pbrt,
}

fn render(rib: &str, renderer: Renderer) -> Vec<[f32; 4]> {
    let frame = frame(rib);
    let fs = scene(&frame).unwrap_or_else(|e| panic!("{e}"));
    assert!(fs.warnings.is_empty(), "{:?}", fs.warnings);
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let image = match renderer {
        Renderer::Scalar => render_scalar(&fs.scene, &opts),
        Renderer::Packet => render_packet::<F32x8, _, _>(&fs.scene, &opts),
        Renderer::Pbrt => render_pbrt(&fs.scene, &opts, Integrator::Active),
    };
    fs.finish(&frame.film, &image)
}

const ALL: [Renderer; 3] = [Renderer::Scalar, Renderer::Packet, Renderer::Pbrt];

/// 16×16 pixels, one sample each, an orthographic view along +z of [-2, 2]² from z = 0.
const ORTHO: &str =
    "Format 16 16 1 PixelSamples 1 1 PixelFilter \"box\" 1 1 Projection \"orthographic\" ScreenWindow -2 2 -2 2\n";

/// A constant-coloured plane z = `z` filling the view.
fn plane(z: f32, color: &str) -> String {
    format!(
        "AttributeBegin Color {color} Surface \"constant\" Translate 0 0 {z} \
         Polygon \"P\" [-5 -5 0 5 -5 0 5 5 0 -5 5 0] AttributeEnd\n"
    )
}

fn close(got: [f32; 4], want: [f32; 4], tol: f32) -> bool {
    got.iter().zip(want).all(|(g, w)| (g - w).abs() <= tol)
}

#[test]
fn fog_attenuates_by_the_exponential_of_the_distance() {
    let (d, distance) = (5.0f32, 4.0f32);
    let (c, bg) = ([1.0f32, 0.5, 0.25], [0.0f32, 0.2, 1.0]);
    let rib = format!(
        "{ORTHO}WorldBegin Atmosphere \"fog\" \"distance\" {distance} \"background\" [0 0.2 1]\n{}WorldEnd",
        plane(d, "1 0.5 0.25")
    );
    let t = (-d / distance).exp();
    let want = [c[0] * t + bg[0] * (1.0 - t), c[1] * t + bg[1] * (1.0 - t), c[2] * t + bg[2] * (1.0 - t), 1.0];
    for r in ALL {
        let px = render(&rib, r);
        for (k, p) in px.iter().enumerate() {
            assert!(close(*p, want, 1e-5), "{r:?} pixel {k}: {p:?}, expected {want:?}");
        }
    }
}

#[test]
fn fog_on_each_segment_of_a_ray_through_a_transparent_surface() {
    // A half-transparent white plane at z = 2 in front of an opaque red one at z = 5: the red
    // light crosses 5 units of fog, the white light 2, each segment on its own.
    let distance = 4.0f32;
    let rib = format!(
        "{ORTHO}WorldBegin Atmosphere \"fog\" \"distance\" {distance}\n\
         AttributeBegin Opacity 0.5 0.5 0.5 {}AttributeEnd {}WorldEnd",
        plane(2.0, "1 1 1"),
        plane(5.0, "1 0 0")
    );
    let (t1, t2) = ((-2.0 / distance).exp(), (-3.0 / distance).exp());
    // Front: Ci = 0.5·t1, Oi = 0.5·t1 + (1 − t1); behind it the red plane fogged over 3 units.
    let front = 0.5 * t1;
    let through = 1.0 - (0.5 * t1 + (1.0 - t1));
    let want = [front + through * t2, front, front, 1.0];
    for r in ALL {
        let px = render(&rib, r);
        assert!(close(px[8 * 16 + 8], want, 1e-5), "{r:?}: {:?}, expected {want:?}", px[8 * 16 + 8]);
    }
    // Red seen through the white plane keeps exp(-5/distance) of itself in all: 0.5 · t1 · t2.
    assert!((through * t2 - 0.5 * (-5.0 / distance).exp()).abs() < 1e-6);
}

#[test]
fn depthcue_blends_linearly_between_its_distances() {
    for d in [1.0f32, 3.0, 5.0, 8.0, 9.5] {
        let rib = format!(
            "{ORTHO}WorldBegin Atmosphere \"depthcue\" \"mindistance\" 2 \"maxdistance\" 8 \"background\" [0 0 1]\n{}WorldEnd",
            plane(d, "1 1 0")
        );
        let f = ((d - 2.0) / 6.0).clamp(0.0, 1.0);
        let want = [1.0 - f, 1.0 - f, f, 1.0];
        for r in [Renderer::Scalar, Renderer::Packet] {
            let px = render(&rib, r);
            assert!(px.iter().all(|p| close(*p, want, 1e-5)), "{r:?} depth {d}: {:?}, expected {want:?}", px[0]);
        }
    }
}

#[test]
fn a_ray_marched_smoke_of_uniform_density_is_exponential() {
    let (d, density) = (3.0f32, 0.4f32);
    let rib = format!(
        "{ORTHO}WorldBegin Atmosphere \"smoke\" \"density\" {density} \"noisiness\" 0 \"stepsize\" 0.25 \
         \"smokecolor\" [0.5 0.5 0.5]\n{}WorldEnd",
        plane(d, "1 0 0")
    );
    let t = (-density * d).exp();
    let want = [t + 0.5 * (1.0 - t), 0.5 * (1.0 - t), 0.5 * (1.0 - t), 1.0];
    for r in ALL {
        let px = render(&rib, r);
        assert!(px.iter().all(|p| close(*p, want, 1e-5)), "{r:?}: {:?}, expected {want:?}", px[0]);
    }
    // With its noise the smoke varies across the picture and stays between the two colours.
    let rib = format!("{ORTHO}WorldBegin Atmosphere \"smoke\" \"density\" 1\n{}WorldEnd", plane(d, "0 0 0"));
    let px = render(&rib, Renderer::Scalar);
    let (lo, hi) = px.iter().fold((f32::MAX, f32::MIN), |(lo, hi), p| (lo.min(p[0]), hi.max(p[0])));
    assert!(lo >= 0.0 && hi <= 1.0 && hi - lo > 0.05, "smoke from {lo} to {hi}");
}

#[test]
fn interior_and_exterior_act_on_the_segments_a_traced_ray_crosses() {
    // A sphere of radius 1.5 at z = 5 that shows what lies behind it, filled with fog, before a
    // white plane with fog outside it. A camera ray meeting the sphere traces through it: the
    // chord inside gets the sphere's Interior, the way on to the plane (reached from its front)
    // the plane's Exterior. Outside the sphere's outline the camera sees the plane directly, on
    // a camera ray, where neither applies. (The polygon as written faces away from the camera:
    // `ReverseOrientation` turns its outside, where its normal points, towards the sphere.)
    let (r, inner, outer) = (1.5f32, 2.0f32, 8.0f32);
    let rib = format!(
        "{ORTHO}WorldBegin AttributeBegin Surface \"seethrough\" Interior \"fog\" \"distance\" {inner} \
         Translate 0 0 5 Sphere {r} -{r} {r} 360 AttributeEnd\n\
         AttributeBegin Exterior \"fog\" \"distance\" {outer} ReverseOrientation {}AttributeEnd WorldEnd",
        plane(9.0, "1 1 1")
    );
    for renderer in ALL {
        let px = render(&rib, renderer);
        for j in 0..16 {
            for i in 0..16 {
                let (x, y) = (-2.0 + (i as f32 + 0.5) * 0.25, 2.0 - (j as f32 + 0.5) * 0.25);
                let h2 = r * r - x * x - y * y;
                // Stay off the tessellated outline.
                if h2.abs() < 0.1 {
                    continue;
                }
                let want = if h2 > 0.0 {
                    let h = h2.sqrt();
                    // The chord 2h, then from the sphere's back (z = 5 + h) to the plane.
                    (-2.0 * h / inner).exp() * (-(4.0 - h) / outer).exp()
                } else {
                    1.0
                };
                let got = px[j * 16 + i][0];
                assert!((got - want).abs() < 2e-2, "{renderer:?} pixel ({i}, {j}): {got}, expected {want}");
            }
        }
    }
}

#[test]
fn the_background_imager_fills_exactly_the_uncovered_part_of_each_pixel() {
    let world = "WorldBegin Color 1 0 0 Surface \"constant\" Translate 0 0 5 Sphere 1.2 -1.2 1.2 360 WorldEnd";
    for samples in [1, 3] {
        let head = format!(
            "Format 16 16 1 PixelSamples {samples} {samples} PixelFilter \"box\" 1 1 \
             Projection \"orthographic\" ScreenWindow -2 2 -2 2\n"
        );
        let plain = render(&format!("{head}{world}"), Renderer::Scalar);
        let imaged =
            render(&format!("{head}Imager \"background\" \"color background\" [0 0.5 1]\n{world}"), Renderer::Scalar);
        let (mut empty, mut covered) = (0, 0);
        for (k, (p, q)) in plain.iter().zip(&imaged).enumerate() {
            let a = p[3];
            let want = [p[0], p[1] + (1.0 - a) * 0.5, p[2] + (1.0 - a), 1.0];
            assert!(close(*q, want, 1e-6), "{samples}² samples, pixel {k}: {q:?} from {p:?}, expected {want:?}");
            empty += usize::from(a == 0.0);
            covered += usize::from(a == 1.0);
            if a == 1.0 {
                assert_eq!(*q, *p, "a covered pixel changed");
            }
        }
        assert!(empty > 50 && covered > 20, "{empty} empty, {covered} covered");
    }
}

#[test]
fn a_custom_imager_gives_its_formula() {
    let rib = format!("{ORTHO}Imager \"vignette\" \"radius\" 10\nWorldBegin {}WorldEnd", plane(5.0, "1 1 1"));
    for r in ALL {
        let px = render(&rib, r);
        for j in 0..16 {
            for i in 0..16 {
                let d = ((i as f32 + 0.5 - 8.0).powi(2) + (j as f32 + 0.5 - 8.0).powi(2)).sqrt();
                let want = (1.0 - d / 10.0).max(0.0);
                let p = px[j * 16 + i];
                assert!(close(p, [want, want, want, 1.0], 1e-5), "{r:?} pixel ({i}, {j}): {p:?}, expected {want}");
            }
        }
    }
}

#[test]
fn missing_volume_and_imager_shaders_are_warnings_and_a_surface_shader_is_an_error() {
    let f = frame(&format!(
        "{ORTHO}Imager \"nosuchimager\"\nWorldBegin Atmosphere \"nosuchfog\" Exterior \"nosuchexterior\"\n{}WorldEnd",
        plane(5.0, "1 1 1")
    ));
    let fs = scene(&f).unwrap();
    for name in ["nosuchfog", "nosuchexterior", "nosuchimager"] {
        assert!(fs.warnings.iter().any(|w| w.contains(&format!("\"{name}\""))), "{name}: {:?}", fs.warnings);
    }
    assert!(fs.warnings.iter().all(|w| w.starts_with("v.rib:")), "{:?}", fs.warnings);
    for request in ["Atmosphere", "Interior", "Exterior", "Imager"] {
        let rib = if request == "Imager" {
            format!("{ORTHO}Imager \"matte\"\nWorldBegin {}WorldEnd", plane(5.0, "1 1 1"))
        } else {
            format!("{ORTHO}WorldBegin {request} \"matte\"\n{}WorldEnd", plane(5.0, "1 1 1"))
        };
        let e = scene(&frame(&rib)).err().unwrap_or_else(|| panic!("{request} \"matte\" accepted"));
        assert!(e.contains("\"matte\" is a surface shader") && e.contains(request) && e.starts_with("v.rib:"), "{e}");
    }
    // "null" is no volume.
    let rib = format!("{ORTHO}WorldBegin Atmosphere \"fog\" Atmosphere \"null\"\n{}WorldEnd", plane(5.0, "1 1 1"));
    assert!(render(&rib, Renderer::Scalar).iter().all(|p| close(*p, [1.0; 4], 0.0)));
}

#[test]
fn the_renderers_agree_on_a_fog_scene() {
    let rib = "Format 48 36 1 PixelSamples 2 2 Projection \"perspective\" \"fov\" 40 Translate 0 -0.3 6\n\
               Imager \"background\" \"background\" [0.6 0.65 0.7]\n\
               WorldBegin Atmosphere \"fog\" \"distance\" 6 \"background\" [0.6 0.65 0.7]\n\
               LightSource \"ambientlight\" 1 \"intensity\" 0.1\n\
               LightSource \"distantlight\" 2 \"from\" [1 2 -2] \"to\" [0 0 0]\n\
               Color 0.9 0.4 0.2 Surface \"matte\" AttributeBegin Translate -1 0 0 Sphere 0.8 -0.8 0.8 360 AttributeEnd\n\
               Color 0.2 0.5 0.9 Surface \"plastic\" AttributeBegin Translate 1.2 0 3 Sphere 0.8 -0.8 0.8 360 AttributeEnd\n\
               Color 0.8 0.8 0.8 Surface \"matte\" AttributeBegin Translate 0 -0.8 0 Rotate 90 1 0 0 \
               Disk 0 6 360 AttributeEnd\nWorldEnd";
    let scalar = render(rib, Renderer::Scalar);
    for r in [Renderer::Packet, Renderer::Pbrt] {
        let other = render(rib, r);
        let mse: f64 = scalar
            .iter()
            .zip(&other)
            .flat_map(|(p, q)| (0..3).map(move |c| f64::from(p[c].clamp(0.0, 1.0) - q[c].clamp(0.0, 1.0)).powi(2)))
            .sum::<f64>()
            / (3 * scalar.len()) as f64;
        let psnr = if mse == 0.0 { f64::INFINITY } else { 10.0 * (1.0 / mse).log10() };
        assert!(psnr >= 40.0, "scalar/{r:?}: {psnr:.1} dB");
    }
    assert!(scalar.iter().all(|p| p[3] == 1.0), "the imager made every pixel opaque");
}
