//! Texture look-ups through the store with known answers: images written here, read back
//! through the search path, the `.tex` stem fallback and `Make*` registrations; footprints
//! from dual numbers.

use anysl_ad::Dual;
use anysl_core::prelude::*;
use anysl_rt::texture::{self, env, shadow, store, Filter, Info, MakeSpec, MapKind, St, TexOptions, Wrap};
use std::path::PathBuf;

/// A fresh directory for this test's files.
fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("anysl-rt-texture-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// 2 × 2 RGB8: red, green / blue, white.
fn write_quad(path: &std::path::Path) {
    let px = [255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255];
    image::save_buffer(path, &px, 2, 2, image::ExtendedColorType::Rgb8).expect("image");
}

/// A dual number at `v` changing by `dx` across the pixel in x.
fn d(v: f64, dx: f64) -> Dual<f32> {
    Dual::new(v as f32, dx as f32, 0.0)
}

fn rgb(c: Color<Dual<f32>>) -> [f64; 3] {
    [c.r.lane(0), c.g.lane(0), c.b.lane(0)]
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-5)
}

#[test]
fn the_footprint_of_dual_coordinates_filters_a_two_by_two_image() {
    let p = dir("quad").join("quad.png");
    write_quad(&p);
    let name = p.to_string_lossy().into_owned();
    let o = TexOptions::default();
    // A footprint of the whole image (∂s/∂x = ∂t/∂y = 1): the texel average.
    let whole = St::Point(Dual::new(0.5, 1.0, 0.0), Dual::new(0.5, 0.0, 1.0));
    assert!(close(rgb(texture::lookup(&name, whole, &o)), [0.5; 3]));
    // One texel's footprint around the top-left texel's centre: red.
    let one = St::Point(Dual::new(0.25, 0.5, 0.0), Dual::new(0.25, 0.0, 0.5));
    assert!(close(rgb(texture::lookup(&name, one, &o)), [1.0, 0.0, 0.0]));
    // The same through "width" 2 and through "blur" 0.5: the average again.
    let mut wide = TexOptions::default();
    wide.set_float("width", Dual::c(2.0));
    assert!(close(rgb(texture::lookup(&name, one, &wide)), [0.5; 3]));
    let mut blur = TexOptions::default();
    blur.set_float("blur", Dual::c(0.5));
    assert!(close(rgb(texture::lookup(&name, one, &blur)), [0.5; 3]));
    // Blur widens: a smaller blur lies between the texel and the average.
    blur.set_float("blur", Dual::c(0.25));
    let v = rgb(texture::lookup(&name, one, &blur));
    assert!(v[0] < 1.0 && v[0] > 0.5 && v[1] > 0.0 && v[1] < 0.5, "{v:?}");
    // The four-corner form: the quad over the right column is green and white averaged.
    let q = St::Quad([0.5, 0.0, 1.0, 0.0, 1.0, 1.0, 0.5, 1.0].map(|x| d(x, 0.0)));
    assert!(close(rgb(texture::lookup(&name, q, &o)), [0.5, 1.0, 0.5]));
    // Plain floats read bilinearly: halfway between red and green.
    let c = texture::lookup(&name, St::Point(0.5f32, 0.25f32), &TexOptions::default());
    assert!((c.r - 0.5).abs() < 1e-6 && (c.g - 0.5).abs() < 1e-6 && c.b.abs() < 1e-6);
}

#[test]
fn channels_fill_and_missing_maps() {
    let p = dir("fill").join("quad.png");
    write_quad(&p);
    let name = p.to_string_lossy().into_owned();
    let mut o = TexOptions::default();
    o.set_float("fill", 0.25f32);
    // Channel 1 onwards of white: green, blue, then the missing fourth channel reads fill.
    o.first = 1;
    let c = texture::lookup(&name, St::Point(0.75f32, 0.75f32), &o);
    assert_eq!((c.r, c.g, c.b), (1.0, 1.0, 0.25));
    // A missing map reads fill in every channel.
    let c = texture::lookup("no/such/map.png", St::Point(0.5f32, 0.5f32), &o);
    assert_eq!((c.r, c.g, c.b), (0.25, 0.25, 0.25));
    assert!(!texture::exists("no/such/map.png"));
    // A one-channel image read as a color gives its channel three times.
    let g = dir("fill").join("gray.png");
    image::save_buffer(&g, &[51u8], 1, 1, image::ExtendedColorType::L8).expect("png");
    let c = texture::lookup(&g.to_string_lossy(), St::Point(0.5f32, 0.5f32), &TexOptions::default());
    assert!((c.r - 0.2).abs() < 1e-6 && c.r == c.g && c.g == c.b);
}

#[test]
fn a_missing_tex_is_read_from_the_image_of_the_same_stem_on_the_search_path() {
    let d = dir("stem");
    write_quad(&d.join("brick.tif"));
    texture::add_search_path([d.clone()]);
    let c = texture::lookup("brick.tex", St::Point(0.25f32, 0.75f32), &TexOptions::default());
    assert_eq!((c.r, c.g, c.b), (0.0, 0.0, 1.0));
    assert_eq!(texture::info("brick.tex", "resolution"), Some(Info::Resolution([2.0, 2.0])));
    assert_eq!(texture::info("brick.tex", "channels"), Some(Info::Channels(3.0)));
    assert_eq!(texture::info("brick.tex", "type"), Some(Info::Type("texture")));
    assert_eq!(texture::info("brick.tex", "viewingmatrix"), None);
    assert_eq!(texture::info("brick-missing.tex", "resolution"), None);
    let e = store::resolve("brick-missing.tex", std::slice::from_ref(&d)).unwrap_err();
    assert!(e.contains("brick-missing") && e.contains("tif") && e.contains(&d.display().to_string()), "{e}");
}

#[test]
fn make_texture_sets_wrap_modes_and_filter() {
    let d = dir("make");
    write_quad(&d.join("src.png"));
    let spec = |wrap| MakeSpec {
        kind: MapKind::Texture,
        sources: vec![d.join("src.png").to_string_lossy().into_owned()],
        wrap,
        filter: Filter::Box,
        fov: 90.0,
    };
    texture::make("made-clamp.tex", spec((Wrap::Clamp, Wrap::Clamp)));
    texture::make("made-black.tex", spec((Wrap::Black, Wrap::Black)));
    let o = TexOptions::default();
    // Left of the red texel: clamp reads red, black reads nothing, periodic (unmade) green.
    let at = St::Point(-0.25f32, 0.25f32);
    let c = texture::lookup("made-clamp.tex", at, &o);
    assert_eq!((c.r, c.g, c.b), (1.0, 0.0, 0.0));
    let c = texture::lookup("made-black.tex", at, &o);
    assert_eq!((c.r, c.g, c.b), (0.0, 0.0, 0.0));
    let c = texture::lookup(&d.join("src.png").to_string_lossy(), at, &o);
    assert_eq!((c.r, c.g, c.b), (0.0, 1.0, 0.0));
}

#[test]
fn a_constant_environment_reads_its_constant_in_every_direction() {
    let sky = dir("env").join("sky.png");
    let px: Vec<u8> = [64u8, 128, 192].repeat(8 * 4);
    image::save_buffer(&sky, &px, 8, 4, image::ExtendedColorType::Rgb8).expect("png");
    let faces: Vec<String> = (0..6).map(|_| sky.to_string_lossy().into_owned()).collect();
    let latlong = MakeSpec {
        kind: MapKind::LatLong,
        sources: faces[..1].to_vec(),
        wrap: (Wrap::Periodic, Wrap::Clamp),
        filter: Filter::Box,
        fov: 90.0,
    };
    texture::make("sky.env", latlong);
    let cube = MakeSpec {
        kind: MapKind::CubeFace,
        sources: faces,
        wrap: (Wrap::Clamp, Wrap::Clamp),
        filter: Filter::Gaussian,
        fov: 95.0,
    };
    texture::make("cube.env", cube);
    let want = [64.0 / 255.0, 128.0 / 255.0, 192.0 / 255.0];
    let dirs = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0], [-0.3, 0.9, -0.2], [0.5, -0.5, 0.7]];
    for name in ["sky.env", "cube.env"] {
        for v in dirs {
            // With a footprint from derivatives, and with four directions.
            let dir = Vec3::new(d(v[0], 0.1), d(v[1], 0.0), d(v[2], 0.05));
            let c = env::lookup(name, env::Dir::Ray(dir), &TexOptions::default());
            assert!(close(rgb(c), want), "{name} {v:?}: {:?}", rgb(c));
            let q = [0.0, 0.1, 0.2, 0.3].map(|e| Vec3::new(d(v[0] + e, 0.0), d(v[1], 0.0), d(v[2] - e, 0.0)));
            let c = env::lookup(name, env::Dir::Quad(q), &TexOptions::default());
            assert!(close(rgb(c), want), "{name} {v:?}");
        }
    }
    assert_eq!(texture::info("cube.env", "type"), Some(Info::Type("environment")));
    // A zero direction reads fill.
    let zero = Vec3::new(0.0f32, 0.0, 0.0);
    assert_eq!(env::lookup("sky.env", env::Dir::Ray(zero), &TexOptions::default()).r, 0.0);
}

#[test]
fn shadow_of_a_depth_map_compares_depths() {
    // A 4 × 4 depth map from a camera at the origin looking down +z with an orthographic
    // projection of the square [-2, 2]²: depth 1 in the left half, infinity elsewhere.
    let mut depth = vec![f32::INFINITY; 16];
    for y in 0..4 {
        for x in 0..2 {
            depth[y * 4 + x] = 1.0;
        }
    }
    let mut map = store::Map::texture(texture::MipMap::new(4, 4, 1, depth));
    map.kind = MapKind::Shadow;
    #[rustfmt::skip]
    let identity = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];
    let mut ortho = identity;
    ortho[0] = 0.5;
    ortho[5] = 0.5;
    map.camera = Some(texture::DepthCamera { world_to_camera: identity, projection: ortho });
    store::insert("depth.shad", map);
    let o = TexOptions::default();
    let at = |x: f32, z: f32| shadow::lookup("depth.shad", Vec3::new(x, 0.5f32, z), &o);
    assert_eq!(at(-1.0, 3.0), 1.0); // behind the occluder
    assert_eq!(at(-1.0, 0.5), 0.0); // in front of it
    assert_eq!(at(1.0, 3.0), 0.0); // nothing in the way
    assert_eq!(at(5.0, 3.0), 0.0); // outside the map
                                   // A footprint across the edge x = 0 (two texels wide): half the samples are in shadow.
    let p = Vec3::new(Dual::new(0.0f32, 2.0, 0.0), Dual::c(0.5), Dual::c(3.0));
    assert_eq!(shadow::lookup("depth.shad", p, &TexOptions::default()).lane(0), 0.5);
    assert_eq!(texture::info("depth.shad", "viewingmatrix"), Some(Info::Matrix(identity)));
    assert!(matches!(texture::info("depth.shad", "projectionmatrix"), Some(Info::Matrix(m)) if m == ortho));
}
