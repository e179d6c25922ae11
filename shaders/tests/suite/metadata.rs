//! Parameter metadata: names, types, defaults, storage; setting parameters by name.

use anysl_core::{ParamError, ParamType, ParamValue, Shader, ShaderKind, Storage};
use anysl_shaders::{Light, Surface};

use ParamType::{Color as C, Float as Fl, Point as Pt, Vector as Vc};

fn f(v: f64) -> ParamValue {
    ParamValue::Float(v)
}
fn t(a: f64, b: f64, c: f64) -> ParamValue {
    ParamValue::Triple([a, b, c])
}

/// The classic parameter lists (RSL names, types, defaults), in declaration order.
fn expected(name: &str) -> Vec<(&'static str, ParamType, ParamValue)> {
    let one = t(1.0, 1.0, 1.0);
    match name {
        "plastic" => vec![
            ("Ka", Fl, f(1.0)),
            ("Kd", Fl, f(0.5)),
            ("Ks", Fl, f(0.5)),
            ("roughness", Fl, f(0.1)),
            ("specularcolor", C, one),
        ],
        "checker" => vec![
            ("Kd", Fl, f(0.5)),
            ("Ka", Fl, f(0.1)),
            ("Ks", Fl, f(0.3)),
            ("roughness", Fl, f(0.1)),
            ("frequency", Fl, f(10.0)),
            ("blackcolor", C, t(0.0, 0.0, 0.0)),
            ("whitecolor", C, one.clone()),
            ("specularcolor", C, one),
        ],
        "brick" => vec![
            ("Ka", Fl, f(1.0)),
            ("Kd", Fl, f(1.0)),
            ("brickwidth", Fl, f(0.25)),
            ("brickheight", Fl, f(0.08)),
            ("mortarthickness", Fl, f(0.01)),
            ("rowvary", Fl, f(0.5)),
            ("brickvary", Fl, f(0.2)),
            ("Cbrick", C, t(0.5, 0.15, 0.14)),
            ("Cmortar", C, t(0.5, 0.5, 0.5)),
        ],
        "glass" => vec![
            ("Ka", Fl, f(0.0)),
            ("Kd", Fl, f(0.0)),
            ("Ks", Fl, f(0.5)),
            ("Kr", Fl, f(1.0)),
            ("Kt", Fl, f(1.0)),
            ("roughness", Fl, f(0.05)),
            ("eta", Fl, f(1.5)),
            ("specularcolor", C, one),
        ],
        "granite" => vec![
            ("Ka", Fl, f(1.0)),
            ("Kd", Fl, f(0.8)),
            ("Ks", Fl, f(0.2)),
            ("roughness", Fl, f(0.1)),
            ("specularcolor", C, one),
            ("frequency", Fl, f(4.0)),
            ("offset", Vc, t(1.5, 0.75, 2.25)),
            ("octaves", Fl, f(6.0)),
            ("contrast", Fl, f(1.5)),
            ("darkcolor", C, t(0.20, 0.18, 0.17)),
            ("lightcolor", C, t(0.95, 0.92, 0.88)),
        ],
        "parquet" => vec![
            ("Ka", Fl, f(1.0)),
            ("Kd", Fl, f(0.75)),
            ("Ks", Fl, f(0.15)),
            ("roughness", Fl, f(0.1)),
            ("specularcolor", C, one),
            ("tilesize", Fl, f(0.25)),
            ("planks", Fl, f(3.0)),
            ("groovewidth", Fl, f(0.05)),
            ("ringscale", Fl, f(6.0)),
            ("ringnoise", Fl, f(0.6)),
            ("grainscale", Fl, f(40.0)),
            ("plankvary", Fl, f(0.25)),
            ("lightwood", C, t(0.76, 0.52, 0.29)),
            ("darkwood", C, t(0.45, 0.26, 0.11)),
            ("groovecolor", C, t(0.08, 0.05, 0.03)),
        ],
        "screen" => vec![
            ("Ka", Fl, f(0.1)),
            ("Kd", Fl, f(0.5)),
            ("Ks", Fl, f(0.5)),
            ("roughness", Fl, f(0.1)),
            ("specularcolor", C, one),
            ("density", Fl, f(0.25)),
            ("frequency", Fl, f(20.0)),
        ],
        "starball" => vec![
            ("Ka", Fl, f(1.0)),
            ("Kd", Fl, f(0.5)),
            ("Ks", Fl, f(0.5)),
            ("roughness", Fl, f(0.1)),
            ("specularcolor", C, one),
            ("starcolor", C, t(0.90, 0.10, 0.05)),
            ("bandcolor", C, t(0.05, 0.20, 0.80)),
            ("ballcolor", C, t(1.00, 0.80, 0.05)),
            ("starsize", Fl, f(0.45)),
            ("bandwidth", Fl, f(0.2)),
        ],
        "venus" => vec![
            ("Ka", Fl, f(1.0)),
            ("Kd", Fl, f(1.0)),
            ("offset", Fl, f(1.0)),
            ("scale", Fl, f(0.6)),
            ("twist", Fl, f(0.22)),
            ("distortion", Fl, f(0.3)),
            ("omega", Fl, f(0.65)),
            ("octaves", Fl, f(8.0)),
        ],
        "wood" => vec![
            ("Ka", Fl, f(1.0)),
            ("Kd", Fl, f(0.75)),
            ("Ks", Fl, f(0.4)),
            ("roughness", Fl, f(0.1)),
            ("specularcolor", C, one),
            ("ringscale", Fl, f(8.0)),
            ("grainscale", Fl, f(48.0)),
            ("lightwood", C, t(0.70, 0.45, 0.22)),
            ("darkwood", C, t(0.30, 0.15, 0.06)),
        ],
        "pointlight" => vec![
            ("intensity", Fl, f(1.0)),
            ("lightcolor", C, one),
            ("from", Pt, t(0.0, 0.0, 0.0)),
            ("falloff", Fl, f(2.0)),
        ],
        "distantlight" => vec![
            ("intensity", Fl, f(1.0)),
            ("lightcolor", C, one),
            ("from", Pt, t(0.0, 0.0, 0.0)),
            ("to", Pt, t(0.0, 0.0, 1.0)),
        ],
        "spotlight" => vec![
            ("intensity", Fl, f(1.0)),
            ("lightcolor", C, one),
            ("from", Pt, t(0.0, 0.0, 0.0)),
            ("to", Pt, t(0.0, 0.0, 1.0)),
            ("coneangle", Fl, f(30f64.to_radians())),
            ("conedeltaangle", Fl, f(5f64.to_radians())),
            ("beamdistribution", Fl, f(2.0)),
        ],
        "ambientlight" => vec![("intensity", Fl, f(1.0)), ("lightcolor", C, one)],
        other => panic!("no expectation for {other}"),
    }
}

/// Every shader of the collection, as `Shader` trait objects.
fn all_shaders() -> Vec<Box<dyn Shader>> {
    let mut v: Vec<Box<dyn Shader>> = Surface::all().into_iter().map(|s| Box::new(s) as Box<dyn Shader>).collect();
    v.extend(Light::NAMES.iter().map(|n| Box::new(Light::by_name(n).expect("light")) as Box<dyn Shader>));
    v
}

#[test]
fn parameters_have_classic_names_types_and_defaults() {
    for shader in all_shaders() {
        let meta = shader.meta();
        let want = expected(&meta.name);
        let got: Vec<_> = meta.params.iter().map(|p| p.name.as_str()).collect();
        let want_names: Vec<_> = want.iter().map(|w| w.0).collect();
        assert_eq!(got, want_names, "{}: parameter list", meta.name);
        for (p, (name, ty, default)) in meta.params.iter().zip(&want) {
            assert_eq!(p.ty, *ty, "{}.{name}: type", meta.name);
            match (&p.default, default) {
                (ParamValue::Float(a), ParamValue::Float(b)) => {
                    assert!((a - b).abs() < 1e-12, "{}.{name}: default {a} != {b}", meta.name)
                }
                (a, b) => assert_eq!(a, b, "{}.{name}: default", meta.name),
            }
            assert_eq!(p.storage, Storage::Uniform, "{}.{name}", meta.name);
            assert!(!p.output && p.array_len.is_none(), "{}.{name}", meta.name);
            assert_eq!(shader.param(name).as_ref(), Some(&p.default), "{}.{name}: param()", meta.name);
        }
    }
}

#[test]
fn kinds_and_derivative_flags() {
    for s in Surface::all() {
        let meta = s.meta();
        assert_eq!(meta.kind, ShaderKind::Surface);
        let filtered = matches!(meta.name.as_str(), "brick" | "checker" | "parquet");
        assert_eq!(meta.uses_derivatives, filtered, "{}: uses_derivatives", meta.name);
    }
    for n in Light::NAMES {
        let meta = Light::by_name(n).expect("light").meta();
        assert_eq!(meta.kind, ShaderKind::Light);
        assert!(!meta.uses_derivatives);
    }
}

#[test]
fn set_param_by_name_round_trips() {
    for mut shader in all_shaders() {
        let meta = shader.meta();
        for p in &meta.params {
            let value = match p.ty {
                ParamType::Float => f(0.375),
                _ => t(0.25, 0.5, 0.75),
            };
            shader.set_param(&p.name, &value).unwrap_or_else(|e| panic!("{}.{}: {e}", meta.name, p.name));
            assert_eq!(shader.param(&p.name), Some(value), "{}.{}", meta.name, p.name);
            if p.ty.is_triple() {
                // A float promotes to a triple, as in RSL.
                shader.set_param(&p.name, &f(2.0)).expect("promotion");
                assert_eq!(shader.param(&p.name), Some(t(2.0, 2.0, 2.0)));
            }
        }
    }
}

#[test]
fn set_param_errors_name_the_parameter() {
    let mut s = Surface::by_name("phong").expect("phong");
    s.set_param("Kd", &f(0.9)).expect("Kd exists");
    assert_eq!(s, Surface::Plastic(anysl_shaders::Plastic { Kd: 0.9, ..Default::default() }));

    let err = s.set_param("Kx", &f(1.0)).expect_err("no Kx");
    assert!(matches!(&err, ParamError::Unknown { name, .. } if name == "Kx"));
    let text = err.to_string();
    assert!(text.contains("'Kx'") && text.contains("'plastic'") && text.contains("roughness"), "{text}");

    let err = s.set_param("roughness", &t(1.0, 2.0, 3.0)).expect_err("a float cannot take a triple");
    assert!(matches!(&err, ParamError::Type { name, expected: ParamType::Float, .. } if name == "roughness"));
    assert!(err.to_string().contains("'roughness'"), "{err}");

    let mut light = Light::by_name("spotlight").expect("spotlight");
    let err = light.set_param("lightcolor", &ParamValue::String("red".into())).expect_err("string");
    assert!(err.to_string().contains("'lightcolor'"), "{err}");
    let err = light.set_param("angle", &f(1.0)).expect_err("no angle");
    assert!(err.to_string().contains("'angle'") && err.to_string().contains("coneangle"), "{err}");
}
