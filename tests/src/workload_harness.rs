//! What the workload tests share (`tests/integration/workload.rs` here, the JIT's rows in
//! `anysl-tests-jit`): the scene, the reference images, the `.sl` shaders' modules and a
//! subset of points shaded behind the `SurfaceShader` boundary.

use anysl_core::ShadingFloat;
use anysl_rsl::back::interp::{InterpShader, Program};
use anysl_rsl::passes::{optimize, PassOptions};
use anysl_rsl::{compile_source, CompileOptions};
use anysl_shaders::workload::{reference, WorkloadScene, WorkloadShader};
use std::sync::{Arc, OnceLock};

/// The workload's scene (hit points), built once per test binary.
pub fn scene() -> &'static WorkloadScene {
    static SCENE: OnceLock<WorkloadScene> = OnceLock::new();
    SCENE.get_or_init(WorkloadScene::new)
}

/// The reference image of a workload shader, loaded once.
pub fn reference_image(shader: &str) -> &'static [f32] {
    static REFS: OnceLock<Vec<(String, Vec<f32>)>> = OnceLock::new();
    let refs = REFS.get_or_init(|| {
        WorkloadShader::NAMES
            .iter()
            .map(|n| (n.to_string(), reference::load_reference(n).expect("reference arrays in the repo")))
            .collect()
    });
    &refs.iter().find(|(n, _)| n == shader).expect("a workload shader").1
}

/// Compiles a workload shader's embedded `.sl` source.
pub fn sl_module(shader: &WorkloadShader) -> anysl_rsl::ir::Module {
    compile_source(shader.sl_file_name(), shader.sl_source(), &CompileOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .module
}

/// A workload shader's `.sl` source through the interpreter.
pub fn interp_shader(shader: &WorkloadShader) -> InterpShader {
    let m = optimize(sl_module(shader), &PassOptions::default());
    InterpShader::new(Arc::new(Program::new(m).expect("the interpreter runs the module")))
}

/// Shades every 7th run of 16 points with `shader` (the rest stays NaN).
pub fn shade_subset<F: ShadingFloat, S: anysl_core::SurfaceShader>(
    s: &WorkloadScene,
    shader: &S,
    lights: &[anysl_shaders::Light],
) -> [Vec<f32>; 3] {
    let n = s.padded_len();
    let [mut r, mut g, mut b] = [vec![f32::NAN; n], vec![f32::NAN; n], vec![f32::NAN; n]];
    for start in (0..n).step_by(16 * 7) {
        let at = start..start + 16;
        s.shade_surface::<F, S, _>(shader, lights, start, [&mut r[at.clone()], &mut g[at.clone()], &mut b[at]]);
    }
    [r, g, b]
}

/// The shaded points of a subset against the reference pixels.
pub fn check_subset(s: &WorkloadScene, ci: &[Vec<f32>; 3], shader: &WorkloadShader, label: &str) {
    let reference = reference_image(shader.name());
    let (mut checked, mut worst) = (0, 0.0f32);
    for (k, &p) in s.pixels().iter().enumerate() {
        if ci[0][k].is_nan() {
            continue;
        }
        for ch in 0..3 {
            worst = worst.max((ci[ch][k] - reference[p as usize * 3 + ch]).abs());
        }
        checked += 1;
    }
    assert!(checked > 20_000, "{label}: only {checked} points shaded");
    assert!(worst <= 1e-4, "{} {label}: max abs err {worst:e} over {checked} points", shader.name());
}
