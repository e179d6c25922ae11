//! Displacement shaders in RIB scenes: run before the surface shader, they bend its normal
//! (bump mapping) by what a finite difference of the moved surface predicts.

use anysl_renderers::{render_packet, render_scalar, RenderOptions};
use anysl_scene::build::{BuildOptions, SceneBuilder};
use anysl_scene::render::{frame_scene, Surfaces};
use anysl_scene::shaders::ShaderLibrary;
use anysl_simd::F32x8;
use std::path::PathBuf;

fn shader_dir() -> PathBuf {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("anysl-scene-displacement-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        std::fs::write(
            dir.join("ripple.sl"),
            "displacement ripple(float amp = 0.1; float freq = 3;)\n\
             {\n    P += amp * sin(freq * xcomp(P)) * normalize(N);\n}\n",
        )
        .expect("write shader");
        dir
    })
    .clone()
}

fn render(rib: &str, packet: bool) -> Result<Vec<[f32; 4]>, String> {
    let mut b = SceneBuilder::new(BuildOptions::default());
    if let Err(e) = anysl_rib::parse_str("d.rib", rib, &mut b, &anysl_rib::Options::new()) {
        panic!("{}", e.render());
    }
    let frame = b.finish().remove(0);
    let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(vec![shader_dir()], Vec::new()));
    let fs = frame_scene(&frame, &mut surfaces)?;
    assert!(fs.warnings.is_empty(), "{:?}", fs.warnings);
    let opts = RenderOptions { threads: 1, ..RenderOptions::default() };
    let image = if packet { render_packet::<F32x8, _, _>(&fs.scene, &opts) } else { render_scalar(&fs.scene, &opts) };
    Ok(fs.finish(&frame.film, &image))
}

/// An orthographic view of the plane z = 5 (16×16 pixels over [-2, 2]²), lit head-on by a unit
/// distant light, matte.
fn plane(displacement: &str) -> String {
    format!(
        "Format 16 16 1 PixelSamples 1 1 PixelFilter \"box\" 1 1 Projection \"orthographic\" ScreenWindow -2 2 -2 2\n\
         WorldBegin LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n\
         {displacement} Surface \"matte\" Translate 0 0 5 Polygon \"P\" [-5 -5 0 5 -5 0 5 5 0 -5 5 0] WorldEnd"
    )
}

#[test]
fn a_height_field_bends_the_normal_as_its_slope_says() {
    let (amp, freq) = (0.1f32, 3.0f32);
    for packet in [false, true] {
        let px = render(&plane(&format!("Displacement \"ripple\" \"amp\" {amp} \"freq\" {freq}")), packet).unwrap();
        for j in 0..16 {
            for i in 0..16 {
                // The surface z = 5 ± amp·sin(freq·x): its normal makes cos θ = 1/√(1 + h'²) with
                // the light.
                let x = -2.0 + (i as f32 + 0.5) * 0.25;
                let slope = amp * freq * (freq * x).cos();
                let want = 1.0 / (1.0 + slope * slope).sqrt();
                let got = px[j * 16 + i][0];
                assert!((got - want).abs() < 2e-3, "packet {packet}: pixel ({i}, {j}) {got}, expected {want}");
            }
        }
    }
    // Without the displacement the plane is lit evenly.
    let flat = render(&plane(""), false).unwrap();
    assert!(flat.iter().all(|p| (p[0] - 1.0).abs() < 1e-5));
}

#[test]
fn a_surface_shader_named_as_a_displacement_is_an_error() {
    let e = render(&plane("Displacement \"matte\""), false).unwrap_err();
    assert!(e.contains("\"matte\"") && e.contains("displacement shader"), "{e}");
    // "null" is no displacement.
    assert!(render(&plane("Displacement \"null\""), false).unwrap().iter().all(|p| (p[0] - 1.0).abs() < 1e-5));
}
