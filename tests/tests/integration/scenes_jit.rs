//! RIB scenes with their shaders compiled by the JIT: a displacement shader runs compiled
//! before the compiled surface (the same back end for both), gives the bump normal a finite
//! difference predicts; a `.sl` light shader runs compiled in every renderer; and every
//! `scenes/*.rib` gives the interpreter's picture.

use anysl_jit::{JitOptions, JitShader};
use anysl_renderers::{render_packet, render_scalar, RenderOptions};
use anysl_scene::build::{BuildOptions, FrameDesc, SceneBuilder};
use anysl_scene::render::{frame_scene, Surfaces};
use anysl_scene::shaders::ShaderLibrary;
use anysl_simd::F32x8;
use std::path::PathBuf;

fn repo() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

fn frames(name: &str, rib: &str, size: Option<u32>) -> Vec<FrameDesc> {
    let mut b = SceneBuilder::new(BuildOptions { width: size, ..BuildOptions::default() });
    if let Err(e) = anysl_rib::parse_str(name, rib, &mut b, &anysl_rib::Options::new()) {
        panic!("{}", e.render());
    }
    b.finish()
}

fn jit_surfaces(dirs: Vec<PathBuf>) -> Surfaces<JitShader> {
    Surfaces::new(ShaderLibrary::new(dirs, Vec::new()), |m| {
        JitShader::new(m, JitOptions::default()).map_err(|e| e.to_string())
    })
}

/// A temporary shader directory of this test run (`tag` names it) holding `file` with `source`.
fn shader_dir(tag: &str, file: &str, source: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("anysl-tests-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join(file), source).expect("write shader");
    dir
}

/// Renders `frame` with `surfaces` in the packet (8 lanes) or scalar renderer.
fn render<S>(frame: &FrameDesc, surfaces: &mut Surfaces<S>, packet: bool) -> Vec<[f32; 4]>
where
    S: anysl_scene::render::SceneShader,
{
    let fs = frame_scene(frame, surfaces).unwrap_or_else(|e| panic!("{e}"));
    assert!(fs.warnings.is_empty(), "{:?}", fs.warnings);
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let image = if packet { render_packet::<F32x8, _, _>(&fs.scene, &opts) } else { render_scalar(&fs.scene, &opts) };
    fs.finish(&frame.film, &image)
}

fn max_diff(a: &[[f32; 4]], b: &[[f32; 4]]) -> f32 {
    a.iter().zip(b).flat_map(|(p, q)| p.iter().zip(q).map(|(x, y)| (x - y).abs())).fold(0.0, f32::max)
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
fn a_compiled_displacement_bends_the_normal_as_its_slope_says() {
    let dir = shader_dir(
        "jit-displacement",
        "ripple.sl",
        "displacement ripple(float amp = 0.1; float freq = 3;)\n{\n    P += amp * sin(freq * xcomp(P)) * normalize(N);\n}\n",
    );
    let (amp, freq) = (0.1f32, 3.0f32);
    // An orthographic view of the plane z = 5 (16×16 pixels over [-2, 2]²), lit head-on.
    let rib = format!(
        "Format 16 16 1 PixelSamples 1 1 PixelFilter \"box\" 1 1 Projection \"orthographic\" ScreenWindow -2 2 -2 2\n\
         WorldBegin LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n\
         Displacement \"ripple\" \"amp\" {amp} \"freq\" {freq} Surface \"matte\"\n\
         Translate 0 0 5 Polygon \"P\" [-5 -5 0 5 -5 0 5 5 0 -5 5 0] WorldEnd"
    );
    let frame = &frames("ripple.rib", &rib, None)[0];
    let mut jit = jit_surfaces(vec![dir.clone()]);
    let mut interp = Surfaces::interpreter(ShaderLibrary::new(vec![dir], Vec::new()));
    for packet in [false, true] {
        let px = render(frame, &mut jit, packet);
        for j in 0..16 {
            for i in 0..16 {
                // z = 5 ± amp·sin(freq·x): the normal makes cos θ = 1/√(1 + h'²) with the light.
                let x = -2.0 + (i as f32 + 0.5) * 0.25;
                let slope = amp * freq * (freq * x).cos();
                let want = 1.0 / (1.0 + slope * slope).sqrt();
                let got = px[j * 16 + i][0];
                assert!((got - want).abs() < 2e-3, "packet {packet}: pixel ({i}, {j}) {got}, expected {want}");
            }
        }
        let d = max_diff(&px, &render(frame, &mut interp, packet));
        assert!(d < 1e-4, "packet {packet}: JIT and interpreter differ by {d}");
    }
    // The compiled displacement ran: the shader the scene holds is a JIT shader with compiled
    // code for the dual-number variants the two renderers shade in.
    let fs = frame_scene(frame, &mut jit).expect("scene");
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let _ = render_scalar(&fs.scene, &opts);
    let _ = render_packet::<F32x8, _, _>(&fs.scene, &opts);
    let d = fs.scene.surfaces[0].displacement.as_ref().expect("a displacement");
    let compiled = d.compiled();
    assert!(
        compiled.contains(&anysl_jit::Variant::DualF32) && compiled.contains(&anysl_jit::Variant::DualX8),
        "{compiled:?}"
    );
}

#[test]
fn every_scene_renders_through_the_jit_as_through_the_interpreter() {
    let scenes = repo().join("scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&scenes)
        .expect("scenes/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "rib"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    for path in &files {
        let text = std::fs::read_to_string(path).expect("read");
        let name = path.file_name().expect("name").to_string_lossy().to_string();
        let mut jit = jit_surfaces(vec![scenes.clone()]);
        let mut interp = Surfaces::interpreter(ShaderLibrary::new(vec![scenes.clone()], Vec::new()));
        for frame in &frames(&name, &text, Some(48)) {
            let a = render(frame, &mut jit, true);
            let b = render(frame, &mut interp, true);
            let p = psnr(&a, &b);
            assert!(p >= 40.0, "{name}: JIT against interpreter {p:.1} dB");
        }
    }
}

#[test]
fn a_sl_light_shader_runs_compiled_in_the_scene() {
    // gobo.sl: a light in its own "shader" space (`transform("shader", Ps)` through the host).
    let scenes = repo().join("scenes");
    let text = std::fs::read_to_string(scenes.join("gobo.rib")).expect("gobo.rib");
    let frame = &frames("gobo.rib", &text, Some(40))[0];
    let mut jit = jit_surfaces(vec![scenes.clone()]);
    let mut interp = Surfaces::interpreter(ShaderLibrary::new(vec![scenes], Vec::new()));
    for packet in [false, true] {
        let a = render(frame, &mut jit, packet);
        let b = render(frame, &mut interp, packet);
        let p = psnr(&a, &b);
        assert!(p >= 50.0, "packet {packet}: JIT against interpreter {p:.1} dB");
        assert!(a.iter().any(|px| px[0] > 0.05), "packet {packet}: the gobo lights nothing");
    }
    let fs = frame_scene(frame, &mut jit).expect("scene");
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let _ = render_scalar(&fs.scene, &opts);
    let _ = render_packet::<F32x8, _, _>(&fs.scene, &opts);
    let compiled: Vec<_> = fs
        .scene
        .lights
        .iter()
        .filter_map(|l| match l {
            anysl_scene::lights::SceneLight::Shader(s) => Some(s.shader().compiled()),
            anysl_scene::lights::SceneLight::Standard(_) => None,
        })
        .collect();
    assert_eq!(compiled.len(), 1, "one .sl light in gobo.rib");
    assert!(
        compiled[0].contains(&anysl_jit::Variant::F32) && compiled[0].contains(&anysl_jit::Variant::X8),
        "{compiled:?}"
    );
}

#[test]
fn compiled_surfaces_call_sl_lights_directly_without_shadows() {
    // `.sl` surface and lights (pointlight, gobo in its turned "shader" space) and a standard
    // light described as data: without shadow rays the renderers hand the lights to the
    // compiled surface as records, whose loops call the lights' code; the picture is the
    // interpreter's.
    let rib = "Format 48 36 1 PixelSamples 1 1 PixelFilter \"box\" 1 1\n\
               Projection \"perspective\" \"fov\" 40 Translate 0 -0.2 7 Rotate -20 1 0 0\n\
               WorldBegin LightSource \"ambientlight\" 1 \"intensity\" 0.06\n\
               LightSource \"pointlight\" 2 \"from\" [2 3 -2] \"intensity\" 12\n\
               TransformBegin Translate 0 5 0 Rotate 90 1 0 0\n\
               LightSource \"gobo\" 3 \"intensity\" 30 \"frequency\" 5 TransformEnd\n\
               Surface \"plastic\" \"roughness\" 0.15 Sphere 1 -1 1 360\n\
               Translate 0 -1 0 Rotate -90 1 0 0 Disk 0 5 360 WorldEnd";
    let frame = &frames("direct.rib", rib, None)[0];
    let dirs = vec![repo().join("scenes"), repo().join("shaders/rsl")];
    let inc = vec![repo().join("shaders/rsl/include")];
    let mut jit = Surfaces::new(ShaderLibrary::new(dirs.clone(), inc.clone()), |m| {
        JitShader::new(m, JitOptions::default()).map_err(|e| e.to_string())
    });
    let mut interp = Surfaces::interpreter(ShaderLibrary::new(dirs, inc));
    let opts = RenderOptions { threads: 1, shadows: false, ..RenderOptions::default() };
    let fs = frame_scene(frame, &mut jit).unwrap_or_else(|e| panic!("{e}"));
    let fi = frame_scene(frame, &mut interp).unwrap_or_else(|e| panic!("{e}"));
    let tables = anysl_renderers::shading::LightTables::of::<F32x8, _, _>(&fs.scene);
    assert_eq!(tables.records_for::<F32x8>(0).map(<[_]>::len), Some(3), "the lights as records");
    for packet in [false, true] {
        let (a, b) = if packet {
            (render_packet::<F32x8, _, _>(&fs.scene, &opts), render_packet::<F32x8, _, _>(&fi.scene, &opts))
        } else {
            (render_scalar(&fs.scene, &opts), render_scalar(&fi.scene, &opts))
        };
        let (a, b) = (fs.finish(&frame.film, &a), fi.finish(&frame.film, &b));
        let p = psnr(&a, &b);
        assert!(p >= 50.0, "packet {packet}: JIT against interpreter {p:.1} dB");
        assert!(a.iter().any(|px| px[0] > 0.05), "packet {packet}: nothing is lit");
    }
}

#[test]
fn depth_is_zero_at_the_near_and_one_at_the_far_clipping_plane() {
    let dir = shader_dir(
        "depth",
        "showdepth.sl",
        "surface showdepth() { Ci = color (depth(P), depth(P + vector (0, 0, 2.5)), depth(point \"camera\" (0, 0, 2))); Oi = 1; }\n",
    );
    // The camera looks down +z; the plane lies at camera z = 7, moved by a world transform
    // (so "current" is not camera space); clipping 2 … 12: depth (7 − 2) / 10 = 0.5.
    let rib = "Format 8 8 1 PixelSamples 1 1 PixelFilter \"box\" 1 1 Clipping 2 12\n\
               Projection \"perspective\" \"fov\" 40 Translate 0 0 3\n\
               WorldBegin Surface \"showdepth\" Translate 0 0 4\n\
               Polygon \"P\" [-20 -20 0 20 -20 0 20 20 0 -20 20 0] WorldEnd";
    let frame = &frames("depth.rib", rib, None)[0];
    let mut jit = jit_surfaces(vec![dir.clone()]);
    let mut interp = Surfaces::interpreter(ShaderLibrary::new(vec![dir], Vec::new()));
    for packet in [false, true] {
        for (what, px) in [("jit", render(frame, &mut jit, packet)), ("interp", render(frame, &mut interp, packet))] {
            for p in &px {
                let want = [0.5, 0.75, 0.0];
                for c in 0..3 {
                    assert!((p[c] - want[c]).abs() < 1e-5, "{what}, packet {packet}: {p:?}, expected {want:?}");
                }
            }
        }
    }
}

#[test]
fn compiled_volume_and_imager_shaders_give_the_known_answers() {
    // A volume shader of our own (fog written out, with a tint so that a wrong `Ci` on entry
    // shows) and an imager that paints the empty pixels, both compiled by the JIT like the
    // surface; the left half of the view is a constant red plane 5 units from the window.
    let dir = shader_dir(
        "jit-volumes",
        "tintfog.sl",
        "volume tintfog(float distance = 1; color background = 0; float tint = 1;)\n{\n    \
         float d = 1 - exp(-length(I) / distance);\n    Ci = tint * mix(Ci, background, d);\n    \
         Oi = mix(Oi, color (1, 1, 1), d);\n}\n",
    );
    std::fs::write(
        dir.join("paint.sl"),
        "imager paint(color bg = color (0, 1, 0);)\n{\n    Ci += (1 - alpha) * bg;\n    alpha = 1;\n}\n",
    )
    .expect("write imager");
    let rib =
        "Format 16 16 1 PixelSamples 1 1 PixelFilter \"box\" 1 1 Projection \"orthographic\" ScreenWindow -2 2 -2 2\n\
               Imager \"paint\" \"bg\" [0.25 0.5 0.75]\n\
               WorldBegin Atmosphere \"tintfog\" \"distance\" 5 \"background\" [0 0 1] \"tint\" 0.5\n\
               Color 1 0 0 Surface \"constant\" Translate 0 0 5\n\
               Polygon \"P\" [-5 -5 0 0 -5 0 0 5 0 -5 5 0] WorldEnd";
    let frame = &frames("volumes.rib", rib, None)[0];
    let mut jit = jit_surfaces(vec![dir.clone()]);
    let mut interp = Surfaces::interpreter(ShaderLibrary::new(vec![dir], Vec::new()));
    let f = (-1.0f32).exp();
    for packet in [false, true] {
        let px = render(frame, &mut jit, packet);
        for j in 0..16 {
            for i in 0..16 {
                // Covered: 0.5 · (red · e^-1 + blue · (1 − e^-1)); empty: the imager's colour.
                let want = if i < 8 { [0.5 * f, 0.0, 0.5 * (1.0 - f), 1.0] } else { [0.25, 0.5, 0.75, 1.0] };
                let got = px[j * 16 + i];
                for c in 0..4 {
                    assert!(
                        (got[c] - want[c]).abs() < 1e-5,
                        "packet {packet}: pixel ({i}, {j}) {got:?}, expected {want:?}"
                    );
                }
            }
        }
        let d = max_diff(&px, &render(frame, &mut interp, packet));
        assert!(d < 1e-6, "packet {packet}: JIT and interpreter differ by {d}");
    }
    // Both ran compiled: the volume at the float types the renderers shade with, the imager at f32.
    let fs = frame_scene(frame, &mut jit).expect("scene");
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let image = render_packet::<F32x8, _, _>(&fs.scene, &opts);
    let _ = fs.finish(&frame.film, &image);
    let _ = render_scalar(&fs.scene, &opts);
    let fog = fs.scene.surfaces[0].volumes.atmosphere.as_ref().expect("an atmosphere");
    let compiled = fog.compiled();
    assert!(compiled.contains(&anysl_jit::Variant::X8) && compiled.contains(&anysl_jit::Variant::F32), "{compiled:?}");
    let imager = fs.imager.as_ref().expect("an imager");
    assert!(imager.compiled().contains(&anysl_jit::Variant::F32), "{:?}", imager.compiled());
}
