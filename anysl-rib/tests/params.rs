//! Parameter lists: inline declarations, `Declare`, predeclared names, value checks.

mod util;

use anysl_rib::{codes, predeclared, Class, Decl, DeclOrigin, Param, ParamList, Request, Type, Values};
use util::{error_codes, fail, one, record, record_with_report};

fn params_of(r: Request) -> ParamList {
    match r {
        Request::Surface { params, .. } | Request::Polygon { params, .. } | Request::Attribute { params, .. } => params,
        Request::Option { params, .. } => params,
        other => panic!("no params in {other:?}"),
    }
}

fn param(text: &str, name: &str) -> Param {
    params_of(one(text)).get(name).cloned().unwrap_or_else(|| panic!("no {name} in {text}"))
}

#[test]
fn inline_declarations_all_classes_and_types() {
    let cases: &[(&str, Class, Type, Option<u32>, usize)] = &[
        ("constant float a", Class::Constant, Type::Float, None, 1),
        ("uniform integer a", Class::Uniform, Type::Integer, None, 1),
        ("varying int a", Class::Varying, Type::Integer, None, 1),
        ("vertex point a", Class::Vertex, Type::Point, None, 3),
        ("facevarying vector a", Class::FaceVarying, Type::Vector, None, 3),
        ("facevertex normal a", Class::FaceVertex, Type::Normal, None, 3),
        ("color a", Class::Uniform, Type::Color, None, 3),
        ("uniform hpoint a", Class::Uniform, Type::HPoint, None, 4),
        ("matrix a", Class::Uniform, Type::Matrix, None, 16),
        ("uniform bool a", Class::Uniform, Type::Bool, None, 1),
        ("float[2] a", Class::Uniform, Type::Float, Some(2), 2),
        ("varying color [2] a", Class::Varying, Type::Color, Some(2), 6),
        ("constant string a", Class::Constant, Type::String, None, 1),
    ];
    for &(decl, class, ty, array_len, per) in cases {
        let values = match ty {
            Type::String => "[\"x\" \"y\"]".to_string(),
            _ => format!("[{}]", vec!["1"; per * 2].join(" ")),
        };
        let p = param(&format!("Surface \"s\" \"{decl}\" {values}"), "a");
        assert_eq!(p.decl, Decl { class, ty, array_len }, "{decl}");
        assert_eq!(p.origin, DeclOrigin::Inline);
        assert_eq!(p.decl.values_per_item(), per);
        assert_eq!(p.item_count(), 2, "{decl}");
        match ty.value_kind() {
            anysl_rib::ValueKind::Float => assert!(matches!(p.values, Values::Float(_))),
            anysl_rib::ValueKind::Int => assert_eq!(p.values, Values::Int(vec![1; per * 2])),
            anysl_rib::ValueKind::String => assert_eq!(p.values, Values::String(vec!["x".into(), "y".into()])),
        }
    }
}

#[test]
fn declare_types_later_parameters() {
    let reqs = record(
        "Declare \"Kc\" \"uniform color\"\nDeclare \"count\" \"integer\"\nDeclare \"map\" \"string\"\n\
         Declare \"uv\" \"varying float[2]\"\nDeclare \"Kq\" \"uniform float Kq\"\n\
         Surface \"s\" \"Kc\" [1 0 0] \"count\" 3 \"map\" \"m.tex\" \"uv\" [0 0 1 1] \"Kq\" 1",
    );
    assert_eq!(reqs.len(), 1, "Declare does not reach the builder");
    let params = params_of(reqs.into_iter().next().unwrap());
    let kc = params.get("Kc").unwrap();
    assert_eq!((kc.decl, kc.origin), (Decl::new(Class::Uniform, Type::Color), DeclOrigin::Declare));
    assert_eq!(params.ints("count"), Some(&[3][..]));
    assert_eq!(params.string("map"), Some("m.tex"));
    let uv = params.get("uv").unwrap();
    assert_eq!((uv.decl.class, uv.decl.array_len, uv.item_count()), (Class::Varying, Some(2), 2));
    assert_eq!(params.float("Kq"), Some(1.0));
}

#[test]
fn inline_declaration_overrides_declare() {
    let p = param("Declare \"a\" \"color\"\nSurface \"s\" \"float a\" [1 2]", "a");
    assert_eq!((p.decl.ty, p.origin, p.item_count()), (Type::Float, DeclOrigin::Inline, 2));
}

#[test]
fn predeclared_names() {
    let p = param("Polygon \"P\" [0 0 0 1 0 0 1 1 0] \"N\" [0 0 1 0 0 1 0 0 1] \"st\" [0 0 1 0 1 1] \"Pw\" [0 0 0 1 1 0 0 1 1 1 0 1]", "st");
    assert_eq!((p.decl.class, p.decl.ty, p.decl.array_len, p.item_count()), (Class::Varying, Type::Float, Some(2), 3));
    assert_eq!(p.origin, DeclOrigin::Predeclared);
    for (name, class, ty) in [
        ("P", Class::Vertex, Type::Point),
        ("Pz", Class::Vertex, Type::Float),
        ("Pw", Class::Vertex, Type::HPoint),
        ("N", Class::Varying, Type::Normal),
        ("Np", Class::Uniform, Type::Normal),
        ("Cs", Class::Varying, Type::Color),
        ("Os", Class::Varying, Type::Color),
        ("s", Class::Varying, Type::Float),
        ("t", Class::Varying, Type::Float),
        ("fov", Class::Uniform, Type::Float),
        ("Ka", Class::Uniform, Type::Float),
        ("texturename", Class::Uniform, Type::String),
        ("lightcolor", Class::Uniform, Type::Color),
        ("from", Class::Uniform, Type::Point),
        ("width", Class::Varying, Type::Float),
        ("constantwidth", Class::Constant, Type::Float),
    ] {
        let d = predeclared(name).unwrap();
        assert_eq!((d.class, d.ty), (class, ty), "{name}");
    }
    assert_eq!(predeclared("searchpath:shader").map(|d| d.ty), Some(Type::String));
    assert!(predeclared("nosuchname").is_none());
}

#[test]
fn option_parameters_are_declared_per_category() {
    let reqs = record(
        "Declare \"render:quality\" \"integer\"\nOption \"render\" \"quality\" [2]\nOption \"limits\" \"gridsize\" 256",
    );
    let Request::Option { params, .. } = &reqs[0] else { panic!() };
    assert_eq!(params.ints("quality"), Some(&[2][..]));
    let Request::Option { params, .. } = &reqs[1] else { panic!() };
    assert_eq!(params.ints("gridsize"), Some(&[256][..]));
}

#[test]
fn undeclared_parameters_are_inferred_with_one_warning() {
    let (reqs, report) = record_with_report("Surface \"s\" \"foo\" [1 2 3] \"bar\" \"x\"\nSurface \"s\" \"foo\" 4");
    let Request::Surface { params, .. } = &reqs[0] else { panic!() };
    let foo = params.get("foo").unwrap();
    assert_eq!((foo.decl.ty, foo.origin, foo.values.len()), (Type::Float, DeclOrigin::Inferred, 3));
    assert_eq!(params.get("bar").unwrap().decl.ty, Type::String);
    let codes: Vec<_> = report.warnings.iter().map(|d| (d.code, d.message.as_str())).collect();
    assert_eq!(
        codes,
        [
            (codes::UNDECLARED_PARAM, "undeclared parameter \"foo\""),
            (codes::UNDECLARED_PARAM, "undeclared parameter \"bar\"")
        ]
    );
}

#[test]
fn value_count_must_be_a_multiple_of_the_components() {
    assert_eq!(error_codes("Polygon \"P\" [0 0 0 1]"), [codes::VALUE_COUNT]);
    assert_eq!(error_codes("Surface \"s\" \"float[2] a\" [1 2 3]"), [codes::VALUE_COUNT]);
    assert_eq!(error_codes("Surface \"s\" \"matrix m\" [1 2 3]"), [codes::VALUE_COUNT]);
    // Zero values is a multiple of anything.
    let p = param("Polygon \"P\" []", "P");
    assert_eq!(p.values, Values::Float(vec![]));
}

#[test]
fn value_kinds_are_checked() {
    assert_eq!(error_codes("Surface \"s\" \"float a\" [\"x\"]"), [codes::VALUE_TYPE]);
    assert_eq!(error_codes("Surface \"s\" \"string a\" [1]"), [codes::VALUE_TYPE]);
    assert_eq!(error_codes("Surface \"s\" \"integer a\" [1.5]"), [codes::VALUE_TYPE]);
    assert_eq!(error_codes("Surface \"s\" \"integer a\" [\"x\"]"), [codes::VALUE_TYPE]);
    assert_eq!(param("Surface \"s\" \"integer a\" [2.0]", "a").values, Values::Int(vec![2]));
}

#[test]
fn malformed_declarations() {
    assert_eq!(error_codes("Surface \"s\" \"uniform flot a\" 1"), [codes::BAD_DECLARATION]);
    assert_eq!(error_codes("Surface \"s\" \"uniform float\" 1"), [codes::BAD_DECLARATION]);
    assert_eq!(error_codes("Surface \"s\" \"float[0] a\" 1"), [codes::BAD_DECLARATION]);
    assert_eq!(error_codes("Surface \"s\" \"float a b\" 1"), [codes::BAD_DECLARATION]);
    assert_eq!(error_codes("Declare \"a\" \"uniform\""), [codes::BAD_DECLARATION]);
    assert_eq!(error_codes("Declare \"a\" \"float b\""), [codes::BAD_DECLARATION]);
    let e = fail("Declare \"a\" \"colour\"");
    assert!(e.render().contains("unknown type `colour`"), "{}", e.render());
}

#[test]
fn parameter_names_and_values_must_pair() {
    assert_eq!(error_codes("Surface \"s\" \"Ks\""), [codes::MISSING_VALUE]);
    assert_eq!(error_codes("Surface \"s\" 1 2"), [codes::EXPECTED_PARAM_NAME]);
    assert_eq!(error_codes("Surface \"s\" [\"Ks\"] 1"), [codes::EXPECTED_PARAM_NAME]);
}

#[test]
fn parameter_locations() {
    let p = param("Surface \"plastic\"\n  \"Ks\" [0.5]", "Ks");
    assert_eq!((p.loc.line, p.loc.col, p.loc.start, p.loc.end), (2, 3, 20, 24));
}

#[test]
fn later_parameter_of_the_same_name_wins() {
    let params = params_of(one("Surface \"s\" \"Ks\" 0.1 \"Ks\" 0.9"));
    assert_eq!((params.len(), params.float("Ks")), (2, Some(0.9)));
}
