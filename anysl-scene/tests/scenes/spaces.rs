//! Named coordinate systems reach shaders: `scenes/showspace.sl` colours quads by
//! `transform(space, P)`, and the pixels are checked against positions worked out by hand
//! from the pinhole camera (16×16, fov 90, screen window [-1, 1]², one sample per pixel, box
//! filter of width 1: pixel (i, j) looks along (x, y, 1) with x = (i + ½)/8 − 1,
//! y = 1 − (j + ½)/8).

use anysl_renderers::{render_packet, render_pbrt, render_scalar, Integrator, RenderOptions};
use anysl_scene::build::{BuildOptions, SceneBuilder};
use anysl_scene::render::{frame_scene, Surfaces};
use anysl_scene::shaders::ShaderLibrary;
use anysl_simd::F32x8;
use std::path::PathBuf;

const HEAD: &str = "Format 16 16 1 PixelSamples 1 1 PixelFilter \"box\" 1 1 Projection \"perspective\" \"fov\" 90\n";

fn render(rib: &str, packet: bool) -> Vec<[f32; 4]> {
    let mut b = SceneBuilder::new(BuildOptions::default());
    if let Err(e) = anysl_rib::parse_str("test.rib", rib, &mut b, &anysl_rib::Options::new()) {
        panic!("{}", e.render());
    }
    let frame = b.finish().remove(0);
    let scenes = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes"));
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(vec![scenes], Vec::new()));
    let fs = frame_scene(&frame, &mut surfaces).expect("the scene builds");
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let image = if packet { render_packet::<F32x8, _, _>(&fs.scene, &opts) } else { render_scalar(&fs.scene, &opts) };
    fs.finish(&frame.film, &image)
}

/// Screen coordinates of pixel (i, j)'s centre.
fn screen(i: usize, j: usize) -> (f32, f32) {
    ((i as f32 + 0.5) / 8.0 - 1.0, 1.0 - (j as f32 + 0.5) / 8.0)
}

fn check(pixels: &[[f32; 4]], expect: impl Fn(usize, usize) -> Option<[f32; 3]>) {
    let mut checked = 0;
    for j in 0..16 {
        for i in 0..16 {
            let Some(e) = expect(i, j) else { continue };
            let p = pixels[j * 16 + i];
            for c in 0..3 {
                assert!((p[c] - e[c]).abs() < 1e-3, "pixel ({i}, {j}): {p:?}, expected {e:?}");
            }
            checked += 1;
        }
    }
    assert!(checked > 20, "only {checked} pixels checked");
}

/// Two quads side by side at z = 5 with one shader: object space is each quad's own, also
/// where a packet of rays covers both.
#[test]
fn object_space_is_each_instances_own() {
    let rib = format!(
        "{HEAD}WorldBegin Surface \"showspace\" \"string space\" \"object\"\n\
         AttributeBegin Translate -1 0 5 Polygon \"P\" [-2 -3 0 1 -3 0 1 3 0 -2 3 0] AttributeEnd\n\
         AttributeBegin Translate 1 0 5 Polygon \"P\" [-1 -3 0 2 -3 0 2 3 0 -1 3 0] AttributeEnd\n\
         WorldEnd"
    );
    let expect = |i: usize, j: usize| {
        let (x, y) = screen(i, j);
        // World (5x, 5y, 5); object = world − the instance's translation.
        (x.abs() < 0.55 && y.abs() < 0.55).then_some({
            if x < 0.0 {
                [5.0 * x + 1.0, 5.0 * y, 0.0]
            } else {
                [5.0 * x - 1.0, 5.0 * y, 0.0]
            }
        })
    };
    check(&render(&rib, false), expect);
    check(&render(&rib, true), expect);
}

/// Shader space is the transform at `Surface`; a `CoordinateSystem` is the transform where
/// it is declared.
#[test]
fn shader_space_and_named_spaces() {
    let quad = "Polygon \"P\" [-3 -3 0 3 -3 0 3 3 0 -3 3 0]";
    let rib = format!(
        "{HEAD}WorldBegin AttributeBegin Translate 0 0 4 Surface \"showspace\" \"string space\" \"shader\" \
         Translate 0 0 1 Rotate 20 0 0 1 {quad} AttributeEnd WorldEnd"
    );
    let expect = |i: usize, j: usize| {
        let (x, y) = screen(i, j);
        (x.abs() < 0.5 && y.abs() < 0.5).then_some([5.0 * x, 5.0 * y, 1.0])
    };
    check(&render(&rib, false), expect);
    let rib = format!(
        "{HEAD}WorldBegin TransformBegin Translate 2 0 5 Scale 2 2 2 CoordinateSystem \"mycs\" TransformEnd \
         Surface \"showspace\" \"string space\" \"mycs\" Translate 0 0 5 {quad} WorldEnd"
    );
    let expect = |i: usize, j: usize| {
        let (x, y) = screen(i, j);
        (x.abs() < 0.5 && y.abs() < 0.5).then_some([(5.0 * x - 2.0) / 2.0, 5.0 * y / 2.0, 0.0])
    };
    check(&render(&rib, true), expect);
}

/// Raster space is the pixel grid: the centre of pixel (i, j) is (i + ½, j + ½); NDC is that
/// over the resolution.
#[test]
fn raster_and_ndc_are_the_pixel_grid() {
    let quad = "Polygon \"P\" [-3 -3 0 3 -3 0 3 3 0 -3 3 0]";
    for (space, scale) in [("raster", 1.0), ("NDC", 16.0)] {
        let rib = format!(
            "{HEAD}WorldBegin Surface \"showspace\" \"string space\" \"{space}\" \"float scale\" {scale} \
             Translate 0 0 5 {quad} WorldEnd"
        );
        let px = render(&rib, false);
        check(&px, |i, j| {
            let (x, y) = screen(i, j);
            (x.abs() < 0.5 && y.abs() < 0.5).then(|| [i as f32 + 0.5, j as f32 + 0.5, px[j * 16 + i][2]])
        });
    }
}

/// The pbrt-like renderer's passive integrator evaluates the material with the surface's own
/// spaces too: lit head-on by a unit distant light, an NDC-coloured quad shows its NDC
/// coordinates.
#[test]
fn the_passive_integrator_sees_the_surfaces_spaces() {
    let quad = "Polygon \"P\" [-3 -3 0 3 -3 0 3 3 0 -3 3 0]";
    let rib = format!(
        "{HEAD}WorldBegin LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n\
         Surface \"showspace\" \"string space\" \"NDC\" Translate 0 0 5 {quad} WorldEnd"
    );
    let mut b = SceneBuilder::new(BuildOptions::default());
    anysl_rib::parse_str("test.rib", &rib, &mut b, &anysl_rib::Options::new()).expect("reads");
    let frame = b.finish().remove(0);
    let scenes = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes"));
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(vec![scenes], Vec::new()));
    let fs = frame_scene(&frame, &mut surfaces).expect("the scene builds");
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let px = fs.finish(&frame.film, &render_pbrt(&fs.scene, &opts, Integrator::Passive));
    let mut checked = 0;
    for j in 4..12 {
        for i in 4..12 {
            let p = px[j * 16 + i];
            let e = [(i as f32 + 0.5) / 16.0, (j as f32 + 0.5) / 16.0];
            assert!(
                (p[0] - e[0]).abs() < 2e-3 && (p[1] - e[1]).abs() < 2e-3,
                "pixel ({i}, {j}): {p:?}, expected {e:?}"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 64);
}
