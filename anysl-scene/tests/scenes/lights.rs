//! `.sl` light shaders in RIB scenes: found on the shader search path, run by the interpreter,
//! placed in their own "shader" space, and the same picture as the compiled standard light
//! they copy.

use anysl_renderers::{render_packet, render_scalar, RenderOptions};
use anysl_rsl::back::interp::InterpShader;
use anysl_scene::build::{BuildOptions, SceneBuilder};
use anysl_scene::lights::SceneLight;
use anysl_scene::render::{frame_scene, FrameScene, Surfaces};
use anysl_scene::shaders::ShaderLibrary;
use anysl_simd::F32x8;
use std::path::PathBuf;

/// A directory holding the test's light shaders (written once: the tests run in parallel).
fn shader_dir() -> PathBuf {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(write_shaders).clone()
}

fn write_shaders() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("anysl-scene-lights-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let write = |name: &str, text: &str| std::fs::write(dir.join(name), text).expect("write shader");
    // The standard point light, with `from` in shader space as the RI standard writes it.
    write(
        "shaderpoint.sl",
        "light shaderpoint(float intensity = 1; color lightcolor = 1;\n\
                           point from = point \"shader\" (0, 0, 0);)\n\
         {\n    illuminate(from) { Cl = intensity * lightcolor / (L . L); }\n}\n",
    );
    // The same with `from` written without a space: current (world) space.
    write(
        "worldpoint.sl",
        "light worldpoint(float intensity = 1; color lightcolor = 1; point from = (-2, 2, -2);)\n\
         {\n    illuminate(from) { Cl = intensity * lightcolor / (L . L); }\n}\n",
    );
    // A light that reads a named space in its body and a direction parameter.
    write(
        "beam.sl",
        "light beam(float intensity = 1; vector dir = (0, 0, 1);)\n\
         {\n    solar(vector \"shader\" dir, 0) { Cl = intensity; }\n}\n",
    );
    dir
}

fn frame_scene_of(rib: &str) -> (anysl_scene::build::FrameDesc, FrameScene<InterpShader>) {
    let mut b = SceneBuilder::new(BuildOptions::default());
    if let Err(e) = anysl_rib::parse_str("lights.rib", rib, &mut b, &anysl_rib::Options::new()) {
        panic!("{}", e.render());
    }
    let frame = b.finish().remove(0);
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(vec![shader_dir()], Vec::new()));
    let fs = frame_scene(&frame, &mut surfaces).expect("the scene builds");
    (frame, fs)
}

fn render(rib: &str, packet: bool) -> Vec<[f32; 4]> {
    let (frame, fs) = frame_scene_of(rib);
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let image = if packet { render_packet::<F32x8, _, _>(&fs.scene, &opts) } else { render_scalar(&fs.scene, &opts) };
    fs.finish(&frame.film, &image)
}

fn scene(light: &str) -> String {
    format!(
        "Format 32 24 1 PixelSamples 1 1 PixelFilter \"box\" 1 1\n\
         Projection \"perspective\" \"fov\" 35 Translate 0 0 5\n\
         WorldBegin\n{light}\n\
         Surface \"matte\" Sphere 1 -1 1 360\n\
         AttributeBegin Translate 0 -1 0 Rotate -90 1 0 0 Surface \"matte\" Disk 0 3 360 AttributeEnd\n\
         WorldEnd"
    )
}

fn max_diff(a: &[[f32; 4]], b: &[[f32; 4]]) -> f32 {
    a.iter().zip(b).flat_map(|(p, q)| (0..4).map(move |c| (p[c] - q[c]).abs())).fold(0.0, f32::max)
}

fn lit(pixels: &[[f32; 4]]) -> usize {
    pixels.iter().filter(|p| p[0] > 0.05).count()
}

#[test]
fn a_shader_space_point_light_is_the_standard_light_moved_there() {
    let standard = render(&scene("LightSource \"pointlight\" 1 \"from\" [-2 2 -2] \"intensity\" 6"), false);
    let placed = render(
        &scene("TransformBegin Translate -2 2 -2 LightSource \"shaderpoint\" 1 \"intensity\" 6 TransformEnd"),
        false,
    );
    // A `from` given in the RIB is in shader space too.
    let given = render(
        &scene("TransformBegin Translate -1 0 0 LightSource \"shaderpoint\" 1 \"from\" [-1 2 -2] \"intensity\" 6 TransformEnd"),
        false,
    );
    assert!(lit(&standard) > 100, "the picture is dark");
    assert!(max_diff(&standard, &placed) < 1e-5, "{}", max_diff(&standard, &placed));
    assert!(max_diff(&standard, &given) < 1e-5, "{}", max_diff(&standard, &given));
}

#[test]
fn a_default_without_a_space_is_in_world_space() {
    let standard = render(&scene("LightSource \"pointlight\" 1 \"from\" [-2 2 -2] \"intensity\" 6"), false);
    // The translation before LightSource does not move a `from` written without a space.
    let world = render(
        &scene("TransformBegin Translate 5 5 5 LightSource \"worldpoint\" 1 \"intensity\" 6 TransformEnd"),
        false,
    );
    assert!(max_diff(&standard, &world) < 1e-5, "{}", max_diff(&standard, &world));
}

#[test]
fn a_light_reads_its_shader_space_in_its_body() {
    // The camera looks along +z. `dir` = (0, 0, 1): the light travels away from the camera and
    // lights the side of the sphere it sees; in a shader space rotated 180° about y it
    // travels towards the camera and lights the far side.
    let front = render(&scene("LightSource \"beam\" 1"), false);
    let back = render(&scene("TransformBegin Rotate 180 0 1 0 LightSource \"beam\" 1 TransformEnd"), false);
    let centre = |p: &[[f32; 4]]| p[12 * 32 + 16][0];
    assert!(centre(&front) > 0.5, "front-lit centre {}", centre(&front));
    assert!(centre(&back) < 1e-6, "back-lit centre {}", centre(&back));
}

#[test]
fn interpreted_lights_agree_across_renderers() {
    let rib = scene("TransformBegin Translate -2 2 -2 LightSource \"shaderpoint\" 1 \"intensity\" 6 TransformEnd");
    let (scalar, packet) = (render(&rib, false), render(&rib, true));
    assert!(max_diff(&scalar, &packet) < 1e-4, "{}", max_diff(&scalar, &packet));
}

#[test]
fn the_scene_holds_the_light_kinds_it_names() {
    let (_, fs) = frame_scene_of(&scene(
        "LightSource \"ambientlight\" 1 \"intensity\" 0.1\nLightSource \"shaderpoint\" 2\nLightSource \"nosuchlight\" 3",
    ));
    let kinds: Vec<&str> = fs
        .scene
        .lights
        .iter()
        .map(|l| match l {
            SceneLight::Standard(_) => "standard",
            SceneLight::Shader(_) => "shader",
        })
        .collect();
    assert_eq!(kinds, ["standard", "shader"]);
    assert_eq!(fs.warnings.len(), 1, "{:?}", fs.warnings);
    assert!(fs.warnings[0].contains("nosuchlight") && fs.warnings[0].contains("left out"), "{}", fs.warnings[0]);
}

#[test]
fn a_surface_shader_named_as_a_light_is_an_error() {
    let mut b = SceneBuilder::new(BuildOptions::default());
    anysl_rib::parse_str("l.rib", &scene("LightSource \"matte\" 1"), &mut b, &anysl_rib::Options::new()).unwrap();
    let frame = b.finish().remove(0);
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(Vec::new(), Vec::new()));
    let Err(e) = frame_scene(&frame, &mut surfaces) else { panic!("a surface shader lit the scene") };
    assert!(e.contains("\"matte\"") && e.contains("light shader"), "{e}");
}

/// Two spheres side by side (left at x = -1.2, right at x = 1.2) seen from z = -6, lit from
/// the camera's side by `left_light` (declared with the left sphere) and `right_light`.
fn two_spheres(left: &str, right: &str) -> String {
    format!(
        "Format 48 24 1 PixelSamples 1 1 PixelFilter \"box\" 1 1\n\
         Projection \"perspective\" \"fov\" 30 Translate 0 0 6\n\
         WorldBegin\n\
         LightSource \"ambientlight\" 1 \"intensity\" 0.05\n\
         AttributeBegin {left} Translate -1.2 0 0 Surface \"matte\" Sphere 1 -1 1 360 AttributeEnd\n\
         AttributeBegin {right} Translate 1.2 0 0 Surface \"matte\" Sphere 1 -1 1 360 AttributeEnd\n\
         WorldEnd"
    )
}

/// The red channel at the centres of the left and right spheres.
fn centres(px: &[[f32; 4]]) -> (f32, f32) {
    // The spheres' centres project to x = ±1.2 / 6 / tan(15°) of the half-width (24 px).
    let dx = (1.2 / 6.0 / 15f32.to_radians().tan() * 12.0).round() as usize;
    (px[12 * 48 + 24 - dx][0], px[12 * 48 + 24 + dx][0])
}

#[test]
fn a_light_declared_in_an_attribute_block_lights_only_its_primitives() {
    let light = "LightSource \"distantlight\" 2 \"from\" [0 0 -1] \"to\" [0 0 0]";
    let both = render(&two_spheres("", &format!("{light} Illuminate 2 1")), false);
    let left_only = render(&two_spheres(light, ""), false);
    let (l, r) = centres(&left_only);
    assert!(l > 0.9 && r < 0.06, "left {l}, right {r}");
    // Declared with the right sphere, the left one (shaded before) does not see it either.
    let (l, r) = centres(&both);
    assert!(l < 0.06 && r > 0.9, "left {l}, right {r}");
    // The packet renderer keeps the light lists too.
    let packet = render(&two_spheres(light, ""), true);
    assert!(max_diff(&left_only, &packet) < 1e-4, "{}", max_diff(&left_only, &packet));
}

#[test]
fn illuminate_turns_a_light_off_for_later_primitives() {
    let rib = format!(
        "Format 48 24 1 PixelSamples 1 1 PixelFilter \"box\" 1 1\n\
         Projection \"perspective\" \"fov\" 30 Translate 0 0 6\n\
         WorldBegin\n\
         LightSource \"ambientlight\" 1 \"intensity\" 0.05\n\
         TransformBegin Translate 0 0 -1 LightSource \"shaderpoint\" 2 \"intensity\" 30 TransformEnd\n\
         AttributeBegin Translate -1.2 0 0 Surface \"matte\" Sphere 1 -1 1 360 AttributeEnd\n\
         Illuminate 2 0\n\
         AttributeBegin Translate 1.2 0 0 Surface \"matte\" Sphere 1 -1 1 360 AttributeEnd\n\
         WorldEnd"
    );
    let (l, r) = centres(&render(&rib, false));
    assert!(l > 0.5 && r < 0.06, "left {l}, right {r}");
}
