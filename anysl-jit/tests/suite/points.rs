//! The points entry (a loop over a point set compiled with the shader,
//! `JitShader::shade_points`) gives what the shader gives packet by packet, bit for bit:
//! Table-1 and workload shaders, shaders whose host callbacks read the context's globals
//! (`Du`, `calculatenormal`, `random`, the renderer's light loops), every float type with a
//! points entry, lights the compiled code loops over and lights only the context can run.

use anysl_core::points::{field, PointSet, ShadeOut};
use anysl_core::prelude::*;
use anysl_core::PointContext;
use anysl_jit::rsl::ir::Global;
use anysl_jit::{JitOptions, JitShader};
use anysl_shaders::lights::{PointLight, SpotLight};
use anysl_shaders::{table1_lights, Light};
use anysl_simd::{F32x16, F32x4, F32x8, Pair};
use std::path::PathBuf;

fn rsl_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"))
}

fn shaders() -> Vec<(String, JitShader)> {
    let inc = [rsl_dir().join("include")];
    let file = |p: PathBuf| JitShader::from_file(&p, &inc, JitOptions::default()).unwrap();
    let mut v: Vec<(String, JitShader)> = ["plastic", "checker", "wood", "granite", "glass", "venus"]
        .iter()
        .map(|n| (n.to_string(), file(rsl_dir().join(format!("{n}.sl")))))
        .collect();
    for n in ["plastic", "wood"] {
        v.push((format!("workload {n}"), file(rsl_dir().join("workload").join(format!("{n}.sl")))));
    }
    // Host callbacks that read the context's globals, and light calls under a varying mask
    // (the renderer's loops even where the lights are data).
    let src = r#"
surface hostcalls(float Kd = 0.8;)
{
    normal Nf = faceforward(normalize(N), I);
    normal n = calculatenormal(P + 0.1 * noise(P * 3));
    float d = Du(s) + Dv(t) + area(P);
    color c = Kd * diffuse(Nf);
    if (s > 0.5)
        c += diffuse(normalize(n + Nf));
    Ci = c + color(random(), d, u * v) + color(n) * 0.1;
    Oi = color(P);
}
"#;
    v.push(("hostcalls".into(), JitShader::from_source("hostcalls.sl", src, &[], JitOptions::default()).unwrap()));
    v
}

fn bits(x: f32) -> u32 {
    // One NaN for all NaNs: only their presence is compared.
    if x.is_nan() {
        f32::NAN.to_bits()
    } else {
        x.to_bits()
    }
}

/// `Ci` and `Oi` of every point, packet by packet through `SurfaceShader::shade`.
fn by_packet<F: ShadingFloat>(jit: &JitShader, set: &PointSet, lights: &[Light]) -> Vec<Vec<u32>> {
    let mut out = vec![Vec::new(); 6];
    for i in (0..set.len()).step_by(F::LANES) {
        let mut ctx = PointContext::new(set.globals::<F>(i), lights);
        let o = jit.shade(&mut ctx, &mut Exec::new());
        for (k, c) in [o.Ci.r, o.Ci.g, o.Ci.b, o.Oi.r, o.Oi.g, o.Oi.b].into_iter().enumerate() {
            out[k].extend((0..F::LANES).map(|l| bits(c.lane(l) as f32)));
        }
    }
    out
}

/// The same through the points entry: every global the set has, from its arrays.
fn by_points<F: ShadingFloat>(jit: &JitShader, set: &PointSet, lights: &[Light]) -> Vec<Vec<u32>> {
    let mut out = ShadeOut::new(set.len());
    assert!(jit.shade_point_set::<F, _>(lights, set, &mut out).unwrap(), "{} has a points entry", F::NAME);
    out.channels.iter().map(|c| c.iter().map(|&x| bits(x)).collect()).collect()
}

fn check<F: ShadingFloat>(name: &str, jit: &JitShader, set: &PointSet, lights_name: &str, lights: &[Light]) {
    let want = by_packet::<F>(jit, set, lights);
    let got = by_points::<F>(jit, set, lights);
    for (k, (w, g)) in want.iter().zip(&got).enumerate() {
        let differ = w.iter().zip(g).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "{name} {} with {lights_name}: {differ} values of output {k} differ", F::NAME);
    }
}

#[test]
fn points_entry_is_the_packet_path_bit_for_bit() {
    let set = PointSet::random(256, 29);
    let spot = vec![
        Light::Point(PointLight { intensity: 3.0, lightcolor: [0.9, 0.7, 0.4], from: [1.0, 2.0, 3.0], falloff: 2.0 }),
        Light::Spot(SpotLight::default()),
    ];
    let sets = [("table 1", table1_lights()), ("a spotlight (no data)", spot), ("none", Vec::new())];
    for (name, jit) in &shaders() {
        for (ln, lights) in &sets {
            check::<f32>(name, jit, &set, ln, lights);
            check::<F32x4>(name, jit, &set, ln, lights);
            check::<F32x8>(name, jit, &set, ln, lights);
            check::<F32x16>(name, jit, &set, ln, lights);
            check::<Pair<Pair<F32x8>>>(name, jit, &set, ln, lights);
            check::<Pair<F32x16>>(name, jit, &set, ln, lights);
        }
    }
}

#[test]
fn points_entry_declines_what_it_cannot_shade_and_names_bad_input() {
    let inc = [rsl_dir().join("include")];
    let jit = JitShader::from_file(&rsl_dir().join("plastic.sl"), &inc, JitOptions::default()).unwrap();
    let set = PointSet::random(64, 3);
    let lights = table1_lights();
    let p = [set.field(field::P), set.field(field::P + 1), set.field(field::P + 2)];
    // Dual numbers have no points entry: the caller shades packet by packet.
    let mut ctx = PointContext::new(set.globals::<anysl_ad::Dual<f32>>(0), &lights[..]);
    let mut c = vec![vec![0.0f32; 64]; 3];
    let mut outs: Vec<&mut [f32]> = c.iter_mut().map(Vec::as_mut_slice).collect();
    assert!(!jit.shade_points(&mut ctx, &[(Global::P, &p)], &mut outs).unwrap());
    // Wrong lengths and components are errors, not a crash.
    let mut ctx = PointContext::new(set.globals::<F32x8>(0), &lights[..]);
    let mut short = vec![vec![0.0f32; 60]; 3];
    let mut outs: Vec<&mut [f32]> = short.iter_mut().map(Vec::as_mut_slice).collect();
    let e = jit.shade_points(&mut ctx, &[(Global::P, &p)], &mut outs).unwrap_err();
    assert!(e.to_string().contains("multiple of 8"), "{e}");
    let mut outs: Vec<&mut [f32]> = c.iter_mut().map(Vec::as_mut_slice).collect();
    let e = jit.shade_points(&mut ctx, &[(Global::P, &p[..2])], &mut outs).unwrap_err();
    assert!(e.to_string().contains("P needs 3 arrays"), "{e}");
    let e = jit.shade_points(&mut ctx, &[(Global::Ci, &p)], &mut outs).unwrap_err();
    assert!(e.to_string().contains("not a global"), "{e}");
    // No points: nothing to do.
    let mut none: Vec<&mut [f32]> = vec![&mut [], &mut [], &mut []];
    assert!(jit.shade_points(&mut ctx, &[], &mut none).unwrap());
}
