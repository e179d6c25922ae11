//! The interpreter renders every surface shader of `shaders/rsl` (the ten Table-1 shaders and
//! the RenderMan standard ones) like their generated-Rust versions, on the `table1` scene in
//! every renderer — and, for the Table-1 shaders, like the hand-written ones.

use anysl_core::Shader as _;
use anysl_renderers::{render_packet, render_pbrt, render_scalar, scenes, Image, Integrator, RenderOptions};
use anysl_rsl::back::interp::{InterpShader, Program};
use anysl_rsl::passes::{optimize, PassOptions};
use anysl_rsl::CompileOptions;
use anysl_shaders::rsl::RslSurface;
use anysl_shaders::{table1_lights, Surface};
use anysl_simd::{F32x4, F32x8};
use std::path::{Path, PathBuf};
use std::sync::Arc;

const SIZE: u32 = 32;
const MAX_PIXEL_DIFF: f32 = 1e-4;

fn rsl_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join("shaders").join("rsl")
}

fn interp(file: &Path) -> InterpShader {
    let opts = CompileOptions { include_dirs: vec![rsl_dir().join("include")], ..CompileOptions::default() };
    let c = anysl_rsl::compile_file(file, &opts).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let m = optimize(c.module, &PassOptions::default());
    InterpShader::new(Arc::new(Program::new(m).unwrap_or_else(|e| panic!("{}: {e}", file.display()))))
}

fn diff(failures: &mut Vec<String>, what: String, a: &Image, b: &Image) {
    let d = a.max_abs_diff(b);
    if d.is_nan() || d > MAX_PIXEL_DIFF {
        failures.push(format!("{what}: max abs pixel difference {d:e}"));
    }
}

#[test]
fn the_interpreter_renders_every_rsl_surface_like_generated_rust() {
    let mut files: Vec<PathBuf> = Vec::new();
    for dir in [rsl_dir(), rsl_dir().join("standard")] {
        for e in std::fs::read_dir(&dir).expect("shaders/rsl") {
            let p = e.expect("entry").path();
            if p.extension().is_some_and(|x| x == "sl") {
                files.push(p);
            }
        }
    }
    files.sort();
    let opts = RenderOptions { threads: 0, ..RenderOptions::default() };
    let mut failures = Vec::new();
    let mut surfaces = 0;
    for file in &files {
        let shader = interp(file);
        if shader.program.module.kind != anysl_rsl::ir::ShaderKind::Surface {
            continue;
        }
        surfaces += 1;
        let name = shader.program.module.name.clone();
        let generated = RslSurface::by_name(&name).unwrap_or_else(|| panic!("no generated shader `{name}`"));
        let a = scenes::table1(shader, table1_lights(), SIZE);
        let b = scenes::table1(generated, table1_lights(), SIZE);
        let scalar = render_scalar(&a, &opts);
        diff(&mut failures, format!("{name} scalar"), &scalar, &render_scalar(&b, &opts));
        let packet = render_packet::<F32x8, _, _>(&b, &opts);
        diff(&mut failures, format!("{name} packet x8"), &render_packet::<F32x8, _, _>(&a, &opts), &packet);
        // The interpreter at 4 lanes against the generated shader at 8 (the generated shaders'
        // widths agree with each other in `integration::instantiations`; one packet width of
        // them here keeps this binary's build shorter).
        diff(&mut failures, format!("{name} packet x4"), &render_packet::<F32x4, _, _>(&a, &opts), &packet);
        diff(
            &mut failures,
            format!("{name} pbrt"),
            &render_pbrt(&a, &opts, Integrator::Active),
            &render_pbrt(&b, &opts, Integrator::Active),
        );
        let hand_name = if name == "plastic" { "phong" } else { name.as_str() };
        if let Some(hand) = Surface::by_name(hand_name) {
            let h = scenes::table1(hand, table1_lights(), SIZE);
            diff(&mut failures, format!("{name} scalar vs hand-written"), &scalar, &render_scalar(&h, &opts));
        }
    }
    assert!(surfaces >= 15, "only {surfaces} surface shaders found in shaders/rsl");
    assert!(failures.is_empty(), "the interpreter renders differently:\n{}", failures.join("\n"));
}

#[test]
fn texture_and_environment_look_ups_agree_between_the_interpreter_and_generated_rust() {
    // The standard shaders that read maps, given the pictures of scenes/textures: both back
    // ends call anysl-rt with the same coordinates and footprints, so the pictures agree.
    let pictures = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join("scenes").join("textures");
    let opts = RenderOptions { threads: 0, ..RenderOptions::default() };
    let mut failures = Vec::new();
    for (name, map) in [("paintedplastic", "tile.png"), ("shinymetal", "sky.png")] {
        let value = anysl_core::ParamValue::String(pictures.join(map).to_string_lossy().into_owned());
        let mut a = interp(&rsl_dir().join("standard").join(format!("{name}.sl")));
        a.set_param("texturename", &value).expect("interpreter parameter");
        let mut b = RslSurface::by_name(name).unwrap_or_else(|| panic!("no generated shader `{name}`"));
        b.set_param("texturename", &value).expect("generated parameter");
        assert!(a.meta().uses_derivatives && b.meta().uses_derivatives, "{name}: look-ups filter by derivatives");
        let (a, b) = (scenes::table1(a, table1_lights(), SIZE), scenes::table1(b, table1_lights(), SIZE));
        let scalar = render_scalar(&a, &opts);
        diff(&mut failures, format!("{name} scalar"), &scalar, &render_scalar(&b, &opts));
        diff(
            &mut failures,
            format!("{name} packet x8"),
            &render_packet::<F32x8, _, _>(&a, &opts),
            &render_packet::<F32x8, _, _>(&b, &opts),
        );
        // The map is read: the picture differs from the shader without one.
        let plain =
            scenes::table1(interp(&rsl_dir().join("standard").join(format!("{name}.sl"))), table1_lights(), SIZE);
        let d = scalar.max_abs_diff(&render_scalar(&plain, &opts));
        assert!(d > 0.05, "{name}: the texture changes the picture by only {d}");
    }
    assert!(failures.is_empty(), "the back ends read textures differently:\n{}", failures.join("\n"));
}
