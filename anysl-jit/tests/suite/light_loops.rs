//! The built-in light loops compiled into the shader (for contexts that describe their lights
//! as data) give the renderer's sums bit for bit: every Table-1 shader and the fused-loop test
//! shaders, at every float type the JIT compiles, under several sets of lights, against the
//! same compiled code calling the context's own loops.

use anysl_core::points::PointSet;
use anysl_core::prelude::*;
use anysl_core::{LightRecord, LightSource, PointContext};
use anysl_jit::{JitOptions, JitShader};
use anysl_shaders::lights::{AmbientLight, DistantLight, PointLight, SpotLight};
use anysl_shaders::{table1_lights, Light};
use anysl_simd::{F32x16, F32x4, F32x8};
use std::cell::Cell;
use std::path::PathBuf;

fn rsl_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"))
}

/// A [`PointContext`] that may hide its lights' data and records (so the compiled code calls
/// its loops) and counts the calls of its loops.
pub(crate) struct Probe<'a, F: ShadingFloat, L> {
    inner: PointContext<'a, F, L>,
    hide: bool,
    loops: &'a Cell<usize>,
}

impl<F: ShadingFloat, L: LightSource> ShadingContext<F> for Probe<'_, F, L> {
    fn globals(&self) -> &Globals<F> {
        self.inner.globals()
    }
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        e: &mut Exec<F>,
        q: LightQuery<'_, F>,
        body: B,
    ) {
        self.loops.set(self.loops.get() + 1);
        self.inner.illuminance(e, q, body);
    }
    fn ambient(&mut self, e: &Exec<F>) -> Color<F> {
        self.loops.set(self.loops.get() + 1);
        self.inner.ambient(e)
    }
    fn trace(&mut self, e: &Exec<F>, p: Vec3<F>, dir: Vec3<F>) -> Color<F> {
        self.inner.trace(e, p, dir)
    }
    fn lights_as_data(&self) -> Option<&[LightData]> {
        if self.hide {
            None
        } else {
            self.inner.lights_as_data()
        }
    }
    fn light_records(&self) -> Option<&[LightRecord]> {
        if self.hide {
            None
        } else {
            self.inner.light_records()
        }
    }
}

/// The outputs of `jit` on `set` as `f32` bits, the context's lights hidden or not, and how
/// often the compiled code called the context's light loops.
pub(crate) fn shade<F: ShadingFloat, L: LightSource>(
    jit: &JitShader,
    set: &PointSet,
    lights: &[L],
    hide: bool,
) -> (Vec<u32>, usize) {
    let loops = Cell::new(0);
    let mut out = Vec::new();
    for i in (0..set.len()).step_by(F::LANES) {
        let mut ctx = Probe { inner: PointContext::new(set.globals::<F>(i), lights), hide, loops: &loops };
        let o = jit.shade(&mut ctx, &mut Exec::new());
        for c in [o.Ci.r, o.Ci.g, o.Ci.b, o.Oi.r, o.Oi.g, o.Oi.b] {
            out.extend((0..F::LANES).map(|l| {
                let x = c.lane(l) as f32;
                // One NaN for all NaNs: only their presence is compared.
                if x.is_nan() {
                    f32::NAN.to_bits()
                } else {
                    x.to_bits()
                }
            }));
        }
    }
    (out, loops.get())
}

fn light_sets() -> Vec<(&'static str, Vec<Light>)> {
    let point = |from: [f64; 3], falloff: f64| {
        Light::Point(PointLight { intensity: 3.5, lightcolor: [0.9, 0.7, 0.4], from, falloff })
    };
    let distant = Light::Distant(DistantLight {
        intensity: 0.8,
        lightcolor: [0.3, 0.5, 1.0],
        from: [1.0, 2.0, 3.0],
        to: [0.0, 0.0, 0.25],
    });
    let ambient = |k: f64| Light::Ambient(AmbientLight { intensity: k, lightcolor: [0.1, 0.2, 0.3] });
    vec![
        ("table 1", table1_lights()),
        (
            "inverse square",
            vec![point([-2.0, 3.0, 4.0], 2.0), point([0.5, 0.5, 3.0], 0.0), point([3.0, -1.0, 2.0], 2.0)],
        ),
        ("distant and two ambient", vec![ambient(0.5), distant, point([1.0, 1.0, 1.0], 2.0), ambient(1.5)]),
        ("none", Vec::new()),
        // A spotlight and a falloff other than 0 and 2 have no data: the context describes
        // no light and its loops run.
        ("with a spotlight", vec![point([1.0, 2.0, 3.0], 2.0), Light::Spot(SpotLight::default()), ambient(1.0)]),
        ("another falloff", vec![point([1.0, 2.0, 3.0], 0.0), point([3.0, -1.0, 2.0], 1.5)]),
    ]
}

pub(crate) fn shaders() -> Vec<(String, JitShader)> {
    let inc = [rsl_dir().join("include")];
    let mut v: Vec<(String, JitShader)> =
        ["plastic", "checker", "brick", "wood", "granite", "parquet", "screen", "starball", "venus", "glass"]
            .iter()
            .map(|n| {
                let j = JitShader::from_file(&rsl_dir().join(format!("{n}.sl")), &inc, JitOptions::default()).unwrap();
                (n.to_string(), j)
            })
            .collect();
    // Every light call on its own and fused: `specular` under a varying condition, `diffuse`
    // of another normal, `ambient()` + `diffuse` (one loop), a lone `diffuse` and `ambient`,
    // `specular` of a normal facing away from the viewer.
    let src = r#"
surface loops(float Ks = 0.5; float roughness = 0.2;)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color early = diffuse(Nf);
    color a = 0;
    if (s < 0.5)
        a = specular(Nf, V, roughness);
    normal Nt = normalize(Nf + vector(0.3, -0.2, t));
    color amb = ambient();
    color d2 = diffuse(Nt);
    color sp = specular(Nt, V, roughness * 0.5);
    /* A normal facing away from the viewer: lights in front of it with a half vector behind
       it (the highlight's cosine clamped to 0 where N.L > 0). */
    color back = specular(-Nf, V, roughness);
    Ci = early + 2 * a + 3 * amb + 5 * d2 + 7 * sp + 11 * back;
    Oi = ambient() + diffuse(N);
}
"#;
    v.push(("loops".into(), JitShader::from_source("loops.sl", src, &[], JitOptions::default()).unwrap()));
    // `illuminance` with bodies of their own, compiled inline over the lights as data: the
    // shared workload's shaders, and a cone, `break`, `continue`, a light count and a loop
    // that selects on a category (that one always asks the context).
    for n in ["plastic", "checker", "wood", "granite"] {
        let path = rsl_dir().join("workload").join(format!("{n}.sl"));
        v.push((format!("workload {n}"), JitShader::from_file(&path, &[], JitOptions::default()).unwrap()));
    }
    let src = r#"
surface bodies(float cutoff = 0.4;)
{
    normal Nf = faceforward(normalize(N), I);
    color c = 0;
    float count = 0;
    illuminance (P, Nf, PI / 3) {
        float k = normalize(L) . Nf;
        if (k < cutoff * s)
            continue;
        c += Cl * k;
        count += 1;
        if (count > 1 + 2 * t)
            break;
    }
    color wide = 0;
    illuminance (P, -Nf, 0.75 * PI) {
        wide += Cl * length(L);
    }
    color cat = 0;
    illuminance ("-nothing", P) {
        cat += Cl;
    }
    Ci = c + 0.5 * wide + count * color(0.01, 0.02, 0.03) + 0.25 * cat;
    Oi = 1;
}
"#;
    v.push(("bodies".into(), JitShader::from_source("bodies.sl", src, &[], JitOptions::default()).unwrap()));
    v
}

fn check<F: ShadingFloat>(name: &str, jit: &JitShader, set: &PointSet, lights_name: &str, lights: &[Light]) {
    let (inline, calls) = shade::<F, _>(jit, set, lights, false);
    let (host, _) = shade::<F, _>(jit, set, lights, true);
    let differ = inline.iter().zip(&host).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "{name} {} with {lights_name}: {differ} outputs differ from the context's loops", F::NAME);
    let described = PointContext::<F, Light>::new(set.globals::<F>(0), lights).lights_as_data().is_some();
    if described && name != "glass" && name != "bodies" {
        // Glass's `trace` is not a light loop, and `bodies` selects on a category; everything
        // else runs inline.
        assert_eq!(calls, 0, "{name} {} with {lights_name}: {calls} calls of the context's loops", F::NAME);
    }
}

#[test]
fn compiled_light_loops_are_the_contexts_bit_for_bit() {
    let set = PointSet::random(512, 17);
    let mut all = shaders();
    // The highlight's `pow` skips lanes whose cosine is +0 only for exponents > 0: roughness
    // 0 (exponent inf), negative and huge exponents take every lane through the library.
    for roughness in [0.0, -0.25, 1.0e-30, 3.0] {
        let mut jit = all.iter().find(|(n, _)| n == "loops").expect("loops").1.clone();
        jit.set_param("roughness", &anysl_core::shader::ParamValue::Float(roughness)).unwrap();
        all.push((format!("loops(roughness {roughness})"), jit));
    }
    for (name, jit) in all {
        for (lights_name, lights) in light_sets() {
            check::<f32>(&name, &jit, &set, lights_name, &lights);
            check::<F32x4>(&name, &jit, &set, lights_name, &lights);
            check::<F32x8>(&name, &jit, &set, lights_name, &lights);
            check::<F32x16>(&name, &jit, &set, lights_name, &lights);
        }
    }
}

/// Each light's data evaluates to what the light shader computes, bit for bit, at `f32` and
/// 8 lanes; lights that data cannot describe have none, and a context describes its lights
/// only when it can describe all of them.
#[test]
fn light_data_is_the_light_shader() {
    fn same<F: ShadingFloat>(a: &LightOutput<F>, b: &LightOutput<F>) -> bool {
        let bits = |x: F| (0..F::LANES).map(|l| x.lane(l).to_bits()).collect::<Vec<_>>();
        let v = |x: Vec3<F>| [bits(x.x), bits(x.y), bits(x.z)];
        v(a.l) == v(b.l)
            && [bits(a.cl.r), bits(a.cl.g), bits(a.cl.b)] == [bits(b.cl.r), bits(b.cl.g), bits(b.cl.b)]
            && a.emission == b.emission
    }
    fn at<F: ShadingFloat>(light: &Light, set: &PointSet) {
        let data = light.data().expect("described");
        for i in (0..set.len()).step_by(F::LANES) {
            let ps = set.globals::<F>(i).P;
            let mut e = Exec::new();
            assert!(same(&data.light(ps), &light.light(&mut e, ps)), "{light:?} {}", F::NAME);
        }
    }
    let set = PointSet::random(64, 3);
    let mut described = 0;
    for (_, lights) in light_sets() {
        for l in &lights {
            if matches!(l, Light::Spot(_)) || matches!(l, Light::Point(p) if p.falloff != 0.0 && p.falloff != 2.0) {
                assert!(l.data().is_none(), "{l:?}");
                continue;
            }
            at::<f32>(l, &set);
            at::<F32x8>(l, &set);
            described += 1;
        }
        let ctx = PointContext::<f32, Light>::new(set.globals::<f32>(0), &lights);
        let all = lights.iter().all(|l| l.data().is_some());
        assert_eq!(ctx.lights_as_data().map(<[LightData]>::len), all.then_some(lights.len()));
    }
    assert!(described >= 10);
}
