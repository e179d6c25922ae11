//! Texture maps and shadow maps in RIB scenes, with known answers: a picture seen texel for
//! pixel through `MakeTexture` (the footprint comes from the renderers' derivatives),
//! `textureinfo`, and a depth pass whose shadow darkens exactly the occluded part of a plane.

use anysl_renderers::{render_packet, render_scalar, Camera, RenderOptions};
use anysl_scene::build::{BuildOptions, FrameDesc, SceneBuilder};
use anysl_scene::render::{frame_scene, Surfaces};
use anysl_scene::shaders::ShaderLibrary;
use anysl_simd::F32x8;
use std::path::PathBuf;

/// A directory holding this module's shaders and pictures.
fn dir() -> PathBuf {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("anysl-scene-textures-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let shaders = [
            (
                "showtex.sl",
                "surface showtex(string map = \"\"; float blur = 0;)\n\
                 { Oi = 1; Ci = color texture(map, \"blur\", blur); }\n",
            ),
            (
                "showinfo.sl",
                "surface showinfo(string map = \"\";)\n\
                 { float res[2] = { 0, 0 }; float ch = 0; string ty = \"\";\n\
                   float ok = textureinfo(map, \"resolution\", res) + textureinfo(map, \"channels\", ch)\n\
                            + textureinfo(map, \"type\", ty) + textureinfo(map, \"viewingmatrix\", res);\n\
                   Oi = 1; Ci = color(res[0] / 10, ch / 10, ok / 10 + (ty == \"texture\" ? 0.5 : 0)); }\n",
            ),
            (
                "shadowdistant.sl",
                "light shadowdistant(float intensity = 1; point from = point \"shader\" (0, 0, 0);\n\
                     point to = point \"shader\" (0, 0, 1); string shadowname = \"\"; float bias = 0.01;)\n\
                 { solar(to - from, 0) { Cl = intensity * (1 - shadow(shadowname, Ps, \"bias\", bias)); } }\n",
            ),
        ];
        for (name, text) in shaders {
            std::fs::write(dir.join(name), text).expect("write shader");
        }
        // 4 × 4 RGB: texel (i, j) is (i/3, j/3, 0.5).
        let px: Vec<u8> = (0..16).flat_map(|k| [(k % 4) as u8 * 85, (k / 4) as u8 * 85, 128]).collect();
        anysl_renderers::write_rgb8(&dir.join("ramp.png"), &px, 4, 4).expect("png");
        dir
    })
    .clone()
}

fn frames(rib: &str) -> Vec<FrameDesc> {
    let mut b = SceneBuilder::new(BuildOptions::default());
    // One file per call: the tests of this module run in parallel, and a file rewritten by one
    // while another reads it reads as empty.
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let path = dir().join(format!("scene{n}.rib"));
    std::fs::write(&path, rib).expect("write rib");
    if let Err(e) = anysl_rib::parse_file(&path, &mut b, &anysl_rib::Options::new()) {
        panic!("{}", e.render());
    }
    b.finish()
}

fn render(frame: &FrameDesc, packet: bool) -> Vec<[f32; 4]> {
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(vec![dir()], Vec::new()));
    let fs = frame_scene(frame, &mut surfaces).unwrap_or_else(|e| panic!("{e}"));
    assert!(fs.warnings.is_empty(), "{:?}", fs.warnings);
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let image = if packet { render_packet::<F32x8, _, _>(&fs.scene, &opts) } else { render_scalar(&fs.scene, &opts) };
    fs.finish(&frame.film, &image)
}

/// An orthographic view, one pixel per texel, of a bilinear patch whose (s, t) span the screen:
/// s right, t down, as the picture's texels.
fn texel_view(surface: &str) -> String {
    format!(
        "Format 4 4 1 PixelSamples 1 1 PixelFilter \"box\" 1 1 Projection \"orthographic\" ScreenWindow -2 2 -2 2\n\
         MakeTexture \"ramp.png\" \"ramp.tex\" \"periodic\" \"periodic\" \"box\" 1 1\n\
         WorldBegin {surface} Translate 0 0 5 Patch \"bilinear\" \"P\" [-2 2 0 2 2 0 -2 -2 0 2 -2 0] WorldEnd"
    )
}

#[test]
fn a_made_texture_is_seen_texel_for_pixel_and_blur_averages_it() {
    let f = frames(&texel_view("Surface \"showtex\" \"map\" \"ramp.tex\""));
    for packet in [false, true] {
        let px = render(&f[0], packet);
        for j in 0..4 {
            for i in 0..4 {
                let p = px[j * 4 + i];
                let want = [i as f32 / 3.0, j as f32 / 3.0, 128.0 / 255.0];
                for c in 0..3 {
                    assert!((p[c] - want[c]).abs() < 2e-3, "packet {packet}: pixel ({i}, {j}) {p:?}, texel {want:?}");
                }
            }
        }
    }
    // A blur of the whole texture reads the mean of a periodic map everywhere.
    let f = frames(&texel_view("Surface \"showtex\" \"map\" \"ramp.tex\" \"blur\" 1"));
    for p in render(&f[0], false) {
        assert!((p[0] - 0.5).abs() < 2e-3 && (p[1] - 0.5).abs() < 2e-3, "{p:?}");
    }
}

#[test]
fn textureinfo_answers_what_the_map_is() {
    // "ramp.tex" does not exist: it is "ramp.png" by the stem fallback, 4 × 4, 3 channels, a
    // texture without a viewing matrix (3 of 4 queries answered).
    let f = frames(&texel_view("Surface \"showinfo\" \"map\" \"ramp.tex\""));
    let p = render(&f[0], false)[5];
    let want = [0.4, 0.3, 0.3 + 0.5];
    for c in 0..3 {
        assert!((p[c] - want[c]).abs() < 1e-4, "{p:?}");
    }
}

#[test]
fn a_shadow_map_darkens_exactly_the_occluded_part_of_a_plane() {
    // Frame 1, the light's view: orthographic, straight down from y = 5 over [-2, 2]², 64 × 64
    // depth pixels of 1/16. Frame 2: a camera above and to the side sees the unit sphere and the
    // plane y = -2 lit straight down by a distant light whose shadow() reads that depth map.
    let world = "AttributeBegin Surface \"matte\" Sphere 1 -1 1 360 AttributeEnd\n\
                 AttributeBegin Surface \"matte\" Patch \"bilinear\" \"P\" [-4 -2 4 4 -2 4 -4 -2 -4 4 -2 -4] AttributeEnd";
    let rib = format!(
        "FrameBegin 1 Format 64 64 1 Projection \"orthographic\" ScreenWindow -2 2 -2 2\n\
           Display \"plane.z\" \"zfile\" \"z\"\n\
           Rotate -90 1 0 0 Translate 0 -5 0\n\
           WorldBegin {world} WorldEnd FrameEnd\n\
         MakeShadow \"plane.z\" \"plane.shad\"\n\
         FrameBegin 2 Format 96 96 1 PixelSamples 1 1 PixelFilter \"box\" 1 1 Projection \"perspective\" \"fov\" 45\n\
           Display \"view.png\" \"png\" \"rgb\"\n\
           Translate 0 0 9 Rotate -35 1 0 0 Rotate 20 0 1 0\n\
           WorldBegin LightSource \"shadowdistant\" 1 \"from\" [0 5 0] \"to\" [0 0 0] \"shadowname\" \"plane.shad\"\n\
           {world} WorldEnd FrameEnd"
    );
    let f = frames(&rib);
    assert_eq!((f.len(), f[0].depth_maps.as_slice(), f[0].displays.len()), (2, &["plane.z".to_string()][..], 0));
    // The depth pass runs when its frame's scene is built.
    render(&f[0], false);
    let (w, h) = (96usize, 96usize);
    let camera = Camera::from_spec(&f[1].camera, w as u32, h as u32);
    // A plane point's shadow is known to within one depth pixel (1/16) either side of the
    // sphere's outline (with no margin the test fails at r = 1.004).
    let margin = 1.0 / 16.0;
    for packet in [false, true] {
        let px = render(&f[1], packet);
        let (mut dark, mut lit) = (0, 0);
        for j in 0..h {
            for i in 0..w {
                let ray = camera.primary_ray(i as f32 + 0.5, j as f32 + 0.5, 0.0);
                let (o, d) = (ray.origin, ray.dir);
                // Pixels that see the sphere, or no plane, are not the test's.
                let b = o.dot(d);
                if b * b - (o.dot(o) - 1.0) >= 0.0 || d.y >= 0.0 {
                    continue;
                }
                let p = o + d * ((-2.0 - o.y) / d.y);
                if p.x.abs() > 4.0 || p.z.abs() > 4.0 {
                    continue;
                }
                let r = (p.x * p.x + p.z * p.z).sqrt();
                let v = px[j * w + i][0];
                if r < 1.0 - margin {
                    assert!(v < 1e-4, "packet {packet}: ({i}, {j}) at r = {r} is lit: {v}");
                    dark += 1;
                } else if r > 1.0 + margin {
                    assert!(v > 0.5, "packet {packet}: ({i}, {j}) at r = {r} is dark: {v}");
                    lit += 1;
                }
            }
        }
        assert!(dark > 50 && lit > 1000, "{dark} shadowed and {lit} lit plane pixels checked");
    }
}
