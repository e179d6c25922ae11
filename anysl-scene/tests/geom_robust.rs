//! Random requests never panic, and what they produce is consistent and free of NaN; random
//! RIB snippets through the reader too.

mod geom_util;

use anysl_rib::{Class, Decl, DeclOrigin, Loc, Param, ParamList, Type, Values};
use anysl_scene::geom::{self, Detail, PatchBasis, Tessellation};
use geom_util::{check_consistent, tessellate_all};
use proptest::prelude::*;

/// Numbers that hurt: zero, huge, NaN, infinities, and ordinary ones.
fn number() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -4.0f32..4.0,
        1 => Just(0.0f32),
        1 => Just(1e30f32),
        1 => Just(-3e38f32),
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => (-3i32..4).prop_map(|i| i as f32),
    ]
}

fn angle() -> impl Strategy<Value = f32> {
    prop_oneof![3 => -400.0f32..400.0, 1 => Just(360.0f32), 1 => Just(0.0f32), 1 => number()]
}

fn detail() -> impl Strategy<Value = Detail> {
    (prop_oneof![Just(1e-3f32), Just(0.1), Just(0.0), Just(-1.0), Just(f32::NAN), Just(1e30)], 0u32..6, 0u32..24)
        .prop_map(|(tolerance, min_segments, max_segments)| Detail { tolerance, min_segments, max_segments })
}

fn param() -> impl Strategy<Value = Param> {
    let name = prop::sample::select(vec!["P", "Pw", "Pz", "N", "Cs", "Os", "st", "s", "t", "k"]);
    let class = prop::sample::select(vec![
        Class::Constant,
        Class::Uniform,
        Class::Varying,
        Class::Vertex,
        Class::FaceVarying,
        Class::FaceVertex,
    ]);
    let ty =
        prop::sample::select(vec![Type::Float, Type::Point, Type::Color, Type::Normal, Type::HPoint, Type::Integer]);
    (name, class, ty, prop::option::of(1u32..3), prop::collection::vec(number(), 0..48)).prop_map(
        |(name, class, ty, array_len, vals)| {
            let loc = Loc { file: Default::default(), name: "p".into(), start: 0, end: 0, line: 1, col: 1 };
            let values = match ty {
                Type::Integer => Values::Int(vals.iter().map(|v| *v as i32).collect()),
                _ => Values::Float(vals),
            };
            Param { name: name.into(), decl: Decl { class, ty, array_len }, origin: DeclOrigin::Inline, values, loc }
        },
    )
}

fn params() -> impl Strategy<Value = ParamList> {
    prop::collection::vec(param(), 0..4).prop_map(|params| ParamList { params })
}

/// Every output is consistent and finite.
fn check(r: geom::Result<Tessellation>) {
    if let Ok(t) = r {
        check_consistent(&t);
        assert!(t.dpdu.iter().chain(&t.dpdv).all(|v| v.is_finite()));
        assert!(t.triangles.len() <= geom::MAX_TRIANGLES);
    }
}

fn small_ints(lo: i32, hi: i32, n: usize) -> impl Strategy<Value = Vec<i32>> {
    prop::collection::vec(lo..hi, 0..n)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn quadrics_never_panic(a in number(), b in number(), c in number(), tm in angle(), p in params(), d in detail()) {
        check(geom::sphere(a, b, c, tm, &p, &d));
        check(geom::cone(a, b, tm, &p, &d));
        check(geom::cylinder(a, b, c, tm, &p, &d));
        check(geom::hyperboloid([a, b, c], [c, a, b], tm, &p, &d));
        check(geom::paraboloid(a, b, c, tm, &p, &d));
        check(geom::disk(a, b, tm, &p, &d));
        check(geom::torus(a, b, c, tm, tm, &p, &d));
    }

    #[test]
    fn polygons_never_panic(
        nverts in small_ints(-1, 7, 5),
        nloops in small_ints(-1, 3, 3),
        verts in small_ints(-1, 16, 24),
        p in params(),
        d in detail(),
    ) {
        check(geom::polygon(&p, &d));
        check(geom::general_polygon(&nverts, &p, &d));
        check(geom::points_polygons(&nverts, &verts, &p, &d));
        check(geom::points_general_polygons(&nloops, &nverts, &verts, &p, &d));
    }

    #[test]
    fn patches_never_panic(
        kind in prop::sample::select(vec!["bilinear", "bicubic", "trilinear"]),
        nu in -1i32..9,
        nv in -1i32..9,
        uwrap in prop::sample::select(vec!["periodic", "nonperiodic", "sometimes"]),
        vwrap in prop::sample::select(vec!["periodic", "nonperiodic"]),
        basis in prop::sample::select(vec!["bezier", "b-spline", "catmull-rom", "hermite", "power"]),
        step in 1i32..4,
        p in params(),
        d in detail(),
    ) {
        let b = anysl_rib::Basis::Named(basis.into());
        let basis = PatchBasis::from_rib(&b, step, &b, step).unwrap();
        check(geom::patch(kind, &basis, &p, &d));
        check(geom::patch_mesh(kind, nu, uwrap, nv, vwrap, &basis, &p, &d));
    }

    #[test]
    fn nupatches_never_panic(
        nu in -1i32..6,
        uorder in -1i32..5,
        nv in -1i32..6,
        vorder in -1i32..5,
        uknot in prop::collection::vec(number(), 0..11),
        vknot in prop::collection::vec(-2.0f32..2.0, 0..11),
        sorted in any::<bool>(),
        range in (number(), number()),
        p in params(),
        d in detail(),
    ) {
        let mut uknot = uknot;
        let mut vknot = vknot;
        if sorted {
            uknot.sort_by(f32::total_cmp);
            vknot.sort_by(f32::total_cmp);
        }
        check(geom::nu_patch(nu, uorder, &uknot, range.0, range.1, nv, vorder, &vknot, -1.0, 1.0, &p, &d));
        check(geom::nu_patch(nu, uorder, &uknot, 0.0, 1.0, nv, vorder, &vknot, range.0, range.1, &p, &d));
    }

    /// Well-formed meshes with random points: the output is always finite (the random ParamLists
    /// above mostly fail the count checks; these get through to the tessellators).
    #[test]
    fn valid_meshes_with_random_points(
        pts in prop::collection::vec(number(), 48),
        w in prop::collection::vec(prop_oneof![Just(1.0f32), Just(0.0), Just(-1.0), 0.1f32..2.0], 16),
        d in detail(),
    ) {
        // RIB has no NaN or infinity: those become huge numbers.
        let fin: Vec<f32> = pts.iter().map(|v| if v.is_finite() { *v } else { 1e30 }).collect();
        let nums = |n: usize| fin[..n].iter().map(|v| format!("{v:e}")).collect::<Vec<_>>().join(" ");
        let hp = (0..16)
            .map(|i| format!("{:e} {:e} {:e} {:e}", fin[3 * i], fin[3 * i + 1], fin[3 * i + 2], w[i]))
            .collect::<Vec<_>>()
            .join(" ");
        let rib = |body: &str| {
            body.replace("{P48}", &nums(48)).replace("{P12}", &nums(12)).replace("{P15}", &nums(15)).replace("{PW16}", &hp)
        };
        let text = rib(r#"
            Patch "bicubic" "P" [{P48}]
            Patch "bicubic" "Pw" [{PW16}]
            Patch "bilinear" "P" [{P12}]
            Polygon "P" [{P15}]
            GeneralPolygon [3 2] "P" [{P15}]
            PointsPolygons [3 3] [0 1 2 2 3 4] "P" [{P15}] "Cs" [{P15}]
            NuPatch 4 4 [0 0 0 0 1 1 1 1] 0 1 4 4 [0 0 0 0 1 1 1 1] 0 1 "Pw" [{PW16}]
            Basis "b-spline" 1 "catmull-rom" 1
            PatchMesh "bicubic" 4 "periodic" 4 "periodic" "P" [{P48}]
        "#);
        for r in tessellate_all(&text, &d) {
            check(r);
        }
    }
}

/// A comb: `teeth` teeth of width 1 and height 10 on a base of height 1, gaps of width 1.
fn comb(teeth: usize) -> (Vec<f32>, f64) {
    let mut pts = vec![];
    let w = (2 * teeth - 1) as f32;
    pts.extend([0.0, 0.0, 0.0, w, 0.0, 0.0]);
    for k in (0..teeth).rev() {
        let x0 = (2 * k) as f32;
        let x1 = x0 + 1.0;
        pts.extend([x1, 11.0, 0.0, x0, 11.0, 0.0]);
        if k > 0 {
            pts.extend([x0, 1.0, 0.0, x0 - 1.0, 1.0, 0.0]);
        }
    }
    // The right edge of the last tooth starts at the base's corner (w, 0) → (w, 11).
    let area = w as f64 * 1.0 + teeth as f64 * 10.0;
    (pts, area)
}

#[test]
fn large_concave_polygons_are_exact_and_bounded() {
    let d = Detail::default();
    let loc = Loc { file: Default::default(), name: "p".into(), start: 0, end: 0, line: 1, col: 1 };
    let p = |vals: Vec<f32>| ParamList {
        params: vec![Param {
            name: "P".into(),
            decl: Decl::new(Class::Vertex, Type::Point),
            origin: DeclOrigin::Predeclared,
            values: Values::Float(vals),
            loc: loc.clone(),
        }],
    };
    // 254 teeth: 1018 points, ear clipped.
    let (pts, area) = comb(254);
    let n = pts.len() / 3;
    let t = geom::general_polygon(&[n as i32], &p(pts), &d).unwrap();
    assert!(t.warnings.is_empty(), "{:?}", t.warnings);
    assert!((t.area() - area).abs() < 1e-6 * area, "area {} vs {area}", t.area());
    assert_eq!(t.triangles.len(), n - 2);
    // Beyond the ear-clipping limit: a fan, with a warning, still no panic.
    let (pts, _) = comb(300);
    let n = pts.len() / 3;
    let t = geom::general_polygon(&[n as i32], &p(pts), &d).unwrap();
    assert!(t.warnings[0].contains("cut as a fan"), "{:?}", t.warnings);
    // A big bilinear mesh stays within the triangle budget.
    let (nu, nv) = (300usize, 300usize);
    let grid: Vec<f32> = (0..nu * nv).flat_map(|k| [(k % nu) as f32, (k / nu) as f32, 0.0]).collect();
    let t = geom::patch_mesh(
        "bilinear",
        nu as i32,
        "nonperiodic",
        nv as i32,
        "nonperiodic",
        &PatchBasis::default(),
        &p(grid),
        &d,
    )
    .unwrap();
    assert!(t.triangles.len() <= geom::MAX_TRIANGLES);
    assert!((t.area() - ((nu - 1) * (nv - 1)) as f64).abs() < 1e-3);
}
