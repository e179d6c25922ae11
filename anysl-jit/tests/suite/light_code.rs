//! Lights with machine code ([`anysl_core::LightCode`]): the compiled surface's own light
//! loops run a compiled `.sl` light's code per light — compiled into the loops for the lights
//! of the first context with records, called at its direct entry for others — and give what the same surface
//! gives calling the context's loops (which run the light through
//! [`LightShader::light_in`]) bit for bit — for every light loop of the Table-1 shaders and the
//! loop test shaders, at every float type the JIT compiles, with `.sl` lights alone, mixed with
//! lights described as data, and in a space of their own.

use super::light_loops::{shade, shaders};
use anysl_core::points::{PointSet, ShadeOut};
use anysl_core::prelude::*;
use anysl_core::shader::{ParamError, ParamValue, ShaderMeta};
use anysl_core::{LightCode, LightRecord, PointContext, Spaces};
use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_shaders::lights::{AmbientLight, PointLight};
use anysl_shaders::Light;
use anysl_simd::{F32x16, F32x4, F32x8};
use std::path::PathBuf;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A light of a test scene: a compiled `.sl` light seeing `spaces`, or a light data describes.
#[derive(Clone, Debug)]
enum Lamp {
    Sl(Box<(JitShader, Spaces)>),
    Rust(Light),
}

impl Shader for Lamp {
    fn meta(&self) -> ShaderMeta {
        match self {
            Self::Sl(b) => b.0.meta(),
            Self::Rust(l) => l.meta(),
        }
    }
    fn param(&self, name: &str) -> Option<ParamValue> {
        match self {
            Self::Sl(b) => b.0.param(name),
            Self::Rust(l) => l.param(name),
        }
    }
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
        match self {
            Self::Sl(b) => b.0.set_param(name, value),
            Self::Rust(l) => l.set_param(name, value),
        }
    }
}

impl LightShader for Lamp {
    fn light<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        match self {
            Self::Sl(b) => b.0.light_in(e, ps, &b.1),
            Self::Rust(l) => l.light(e, ps),
        }
    }
    fn emission(&self) -> Option<Emission> {
        match self {
            Self::Sl(b) => b.0.emission(),
            Self::Rust(l) => l.emission(),
        }
    }
    fn data(&self) -> Option<LightData> {
        match self {
            Self::Sl(_) => None,
            Self::Rust(l) => l.data(),
        }
    }
    fn code<F: ShadingFloat>(&self) -> Option<LightCode> {
        match self {
            Self::Sl(b) => b.0.code_in::<F>(&b.1),
            Self::Rust(_) => None,
        }
    }
}

fn sl(name: &str, params: &[(&str, ParamValue)], spaces: Spaces) -> Lamp {
    let path =
        if name == "gobo" { repo().join("scenes/gobo.sl") } else { repo().join(format!("shaders/rsl/{name}.sl")) };
    let mut j = JitShader::from_file(&path, &[], JitOptions::default()).unwrap();
    for (p, v) in params {
        j.set_param(p, v).unwrap();
    }
    Lamp::Sl(Box::new((j, spaces)))
}

fn light_sets() -> Vec<(&'static str, Vec<Lamp>)> {
    use ParamValue as P;
    let std = || Spaces::standard().clone();
    let turned =
        Spaces::new([("shader", [0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.1, -0.2, -2.0, 1.0])]);
    let point = |from: [f64; 3]| {
        Lamp::Rust(Light::Point(PointLight { intensity: 2.5, lightcolor: [0.9, 0.7, 0.4], from, falloff: 2.0 }))
    };
    vec![
        (
            "sl point, distant, ambient",
            vec![
                sl("pointlight", &[("from", P::Triple([-2.0, 3.0, 4.0])), ("intensity", P::Float(6.0))], std()),
                sl("distantlight", &[("from", P::Triple([1.0, 2.0, 3.0])), ("intensity", P::Float(0.8))], std()),
                sl("ambientlight", &[("intensity", P::Float(0.2))], std()),
            ],
        ),
        (
            "sl spotlight among data",
            vec![
                point([0.5, 0.5, 3.0]),
                sl("spotlight", &[("from", P::Triple([0.0, 0.0, -2.0])), ("coneangle", P::Float(0.6))], std()),
                Lamp::Rust(Light::Ambient(AmbientLight { intensity: 0.3, lightcolor: [0.1, 0.2, 0.3] })),
                sl("pointlight", &[("from", P::Triple([3.0, -1.0, 2.0])), ("falloff", P::Float(1.0))], std()),
            ],
        ),
        (
            "gobo in a turned space",
            vec![
                sl("gobo", &[("frequency", P::Float(3.0)), ("coneangle", P::Float(1.2))], turned),
                point([-1.0, 2.0, 1.0]),
            ],
        ),
    ]
}

fn check<F: ShadingFloat>(name: &str, jit: &JitShader, set: &PointSet, lights_name: &str, lights: &[Lamp]) {
    let (direct, calls) = shade::<F, _>(jit, set, lights, false);
    let (host, _) = shade::<F, _>(jit, set, lights, true);
    let differ = direct.iter().zip(&host).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "{name} {} with {lights_name}: {differ} outputs differ from the context's loops", F::NAME);
    if name != "glass" && name != "bodies" {
        // Glass's `trace` is not a light loop, and `bodies` selects on a category; everything
        // else runs in the compiled loops, calling the lights' code.
        assert_eq!(calls, 0, "{name} {} with {lights_name}: {calls} calls of the context's loops", F::NAME);
    }
}

#[test]
fn compiled_light_loops_call_sl_lights_bit_for_bit() {
    let set = PointSet::random(256, 23);
    let sets = light_sets();
    for (_, lights) in &sets {
        for l in lights {
            if let Lamp::Sl(b) = l {
                let j = &b.0;
                for v in [Variant::F32, Variant::X4, Variant::X8, Variant::X16] {
                    assert!(j.variant(v).unwrap().light.is_some(), "{j:?}: no direct entry for {v:?}");
                }
                for v in [Variant::DualF32, Variant::DualX8] {
                    assert!(j.variant(v).unwrap().light.is_none(), "{j:?}: a direct entry for {v:?}");
                }
            }
        }
        let ctx = PointContext::<F32x8, Lamp>::new(set.globals::<F32x8>(0), lights);
        assert!(ctx.lights_as_data().is_none());
        assert_eq!(ctx.light_records().map(<[LightRecord]>::len), Some(lights.len()));
    }
    for (name, jit) in shaders() {
        for (lights_name, lights) in &sets {
            check::<f32>(&name, &jit, &set, lights_name, lights);
            check::<F32x4>(&name, &jit, &set, lights_name, lights);
            check::<F32x8>(&name, &jit, &set, lights_name, lights);
            check::<F32x16>(&name, &jit, &set, lights_name, lights);
        }
        // The first context with records decided the lights compiled into the loops: the three
        // `.sl` lights of the first set (those of the others were called, and gave the same).
        if name != "glass" && name != "bodies" {
            for v in [Variant::F32, Variant::X4, Variant::X8, Variant::X16] {
                let n = jit.inline_variant_compiled(v).map(|c| c.stats.inline_lights);
                assert_eq!(n, Some(3), "{name} {v:?}: lights compiled into the light loops");
            }
        }
    }
}

/// The points entry (one compiled loop over the packets) finds the records too: a point
/// set shaded so is the packet-by-packet shading through the context's loops.
#[test]
fn points_entry_calls_sl_lights() {
    let set = PointSet::random(256, 5);
    let inc = [repo().join("shaders/rsl/include")];
    let jit = JitShader::from_file(&repo().join("shaders/rsl/plastic.sl"), &inc, JitOptions::default()).unwrap();
    for (lights_name, lights) in light_sets() {
        let mut out = ShadeOut::<f32>::new(set.len());
        assert!(jit.shade_point_set::<F32x8, Lamp>(&lights, &set, &mut out).unwrap());
        let (host, calls) = shade::<F32x8, _>(&jit, &set, &lights, true);
        assert!(calls > 0);
        for (k, ch) in out.channels.iter().enumerate().take(3) {
            for (i, x) in ch.iter().enumerate() {
                let want = host[(i / 8 * 6 + k) * 8 + i % 8];
                assert_eq!(x.to_bits(), want, "{lights_name}: point {i} channel {k}");
            }
        }
    }
}

/// A light whose code calls the host for more than named spaces has no direct entry (its
/// surfaces' loops call the context's then), and gives its results all the same.
#[test]
fn a_light_that_needs_the_host_has_no_direct_entry() {
    let src = "light t() { illuminate(point (0, 1, 0)) { Cl = color (random(), 1, 1); } }";
    let j = JitShader::from_source("t.sl", src, &[], JitOptions::default()).unwrap();
    assert!(j.variant(Variant::X8).unwrap().light.is_none());
    assert!(j.code::<F32x8>().is_none());
    let lights = [Lamp::Sl(Box::new((j, Spaces::standard().clone())))];
    let set = PointSet::random(16, 9);
    let ctx = PointContext::<F32x8, Lamp>::new(set.globals::<F32x8>(0), &lights);
    assert!(ctx.light_records().is_none());
}

/// A light compiled into a surface's light loops reads its named spaces from its record, as
/// its direct entry does: the gobo in a turned space, compiled into plastic's loops, gives
/// what the context's loops give.
#[test]
fn a_light_compiled_into_the_loops_sees_its_own_spaces() {
    let set = PointSet::random(256, 29);
    let sets = light_sets();
    let (lights_name, lights) = sets.iter().find(|(n, _)| n.starts_with("gobo")).unwrap();
    let inc = [repo().join("shaders/rsl/include")];
    let jit = JitShader::from_file(&repo().join("shaders/rsl/plastic.sl"), &inc, JitOptions::default()).unwrap();
    check::<F32x8>("plastic", &jit, &set, lights_name, lights);
    check::<f32>("plastic", &jit, &set, lights_name, lights);
    for v in [Variant::F32, Variant::X8] {
        assert_eq!(jit.inline_variant_compiled(v).map(|c| c.stats.inline_lights), Some(1), "{v:?}");
    }
}

/// `anysl bench jit`'s `.sl`-light row: the Table-1 lights as `.sl` light shaders, shaded
/// through `anysl_core::points::shade_points` — the surface runs its flavour with the three
/// lights compiled in, and gives the context's loops' results bit for bit.
#[test]
fn the_table1_sl_lights_are_compiled_into_the_surface() {
    let lights: Vec<JitShader> = anysl_shaders::table1_lights()
        .iter()
        .map(|l| {
            let path = repo().join(format!("shaders/rsl/{}.sl", l.name()));
            let mut j = JitShader::from_file(&path, &[], JitOptions::default()).unwrap();
            for p in l.meta().params {
                j.set_param(&p.name, &l.param(&p.name).unwrap()).unwrap();
            }
            j
        })
        .collect();
    let set = PointSet::random(512, 31);
    let inc = [repo().join("shaders/rsl/include")];
    let jit = JitShader::from_file(&repo().join("shaders/rsl/plastic.sl"), &inc, JitOptions::default()).unwrap();
    let mut out = ShadeOut::<f32>::new(set.len());
    anysl_core::points::shade_points::<F32x8, _, JitShader>(&jit, &lights, &set, &mut out);
    let c = jit.inline_variant_compiled(Variant::X8).expect("the flavour with the lights compiled in");
    assert_eq!(c.stats.inline_lights, 3);
    let (host, _) = shade::<F32x8, _>(&jit, &set, &lights, true);
    for (k, ch) in out.channels.iter().enumerate() {
        for (i, x) in ch.iter().enumerate() {
            assert_eq!(x.to_bits(), host[(i / 8 * 6 + k) * 8 + i % 8], "point {i} channel {k}");
        }
    }
}
