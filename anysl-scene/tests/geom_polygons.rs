//! Polygons: exact areas with holes and concave outlines, face normals and winding, the
//! primitive-variable classes and the count errors.

// Tests index parallel per-vertex arrays.
#![allow(clippy::needless_range_loop)]

mod geom_util;

use anysl_rib::{Class, Decl, DeclOrigin, Loc, Param, ParamList, Type, Values};
use anysl_scene::geom::{points_polygons, polygon, Detail, Tessellation};
use geom_util::{check_consistent, one, one_err};
use glam::{Vec2, Vec3};

fn centroids(t: &Tessellation) -> Vec<Vec3> {
    t.triangles.iter().map(|tri| tri.iter().map(|&i| t.positions[i as usize]).sum::<Vec3>() / 3.0).collect()
}

fn assert_ccw_about_normals(t: &Tessellation) {
    for tri in &t.triangles {
        let [a, b, c] = tri.map(|i| t.positions[i as usize]);
        let n = t.normals[tri[0] as usize];
        assert!((b - a).cross(c - a).dot(n) > 0.0, "triangle {tri:?} winds against {n}");
    }
}

#[test]
fn square_with_square_hole() {
    // The hole is given counter-clockwise too: its orientation must not matter.
    for hole in ["1 1 0  3 1 0  3 3 0  1 3 0", "1 1 0  1 3 0  3 3 0  3 1 0"] {
        let t = one(&format!(r#"GeneralPolygon [4 4] "P" [0 0 0  4 0 0  4 4 0  0 4 0  {hole}]"#));
        check_consistent(&t);
        assert!((t.area() - 12.0).abs() < 1e-5, "area {}", t.area());
        for c in centroids(&t) {
            assert!(!(c.x > 1.0 && c.x < 3.0 && c.y > 1.0 && c.y < 3.0), "centroid {c} in the hole");
        }
        assert!(t.normals.iter().all(|n| *n == Vec3::Z));
        assert_ccw_about_normals(&t);
    }
}

#[test]
fn two_holes_and_a_concave_outline() {
    // A U-shaped outline with a hole in each arm.
    let t = one(r#"GeneralPolygon [8 4 4] "P" [0 0 0  5 0 0  5 5 0  4 5 0  4 1 0  1 1 0  1 5 0  0 5 0
            0.25 2 0  0.75 2 0  0.75 3 0  0.25 3 0
            4.25 2 0  4.25 3 0  4.75 3 0  4.75 2 0]"#);
    let expect = 5.0 + 2.0 * 4.0 - 2.0 * 0.5;
    assert!((t.area() - expect).abs() < 1e-5, "area {} vs {expect}", t.area());
    for c in centroids(&t) {
        assert!(!(c.x > 1.0 && c.x < 4.0 && c.y > 1.0), "centroid {c} in the notch");
        assert!(
            !(c.y > 2.0 && c.y < 3.0 && ((c.x > 0.25 && c.x < 0.75) || (c.x > 4.25 && c.x < 4.75))),
            "in a hole: {c}"
        );
    }
    assert_ccw_about_normals(&t);
}

#[test]
fn l_shaped_polygon() {
    for req in ["Polygon", "GeneralPolygon [6]"] {
        let t = one(&format!(r#"{req} "P" [0 0 0  2 0 0  2 1 0  1 1 0  1 2 0  0 2 0]"#));
        assert!((t.area() - 3.0).abs() < 1e-5, "{req}: area {}", t.area());
        for c in centroids(&t) {
            assert!(!(c.x > 1.0 && c.y > 1.0), "{req}: centroid {c} outside the L");
        }
        assert_ccw_about_normals(&t);
    }
}

#[test]
fn winding_gives_the_normal_and_uv_span_the_bounds() {
    // Clockwise seen from +z: the normal is -z.
    let t = one(r#"Polygon "P" [0 0 1  0 2 1  3 2 1  3 0 1]"#);
    assert!(t.normals.iter().all(|n| (*n + Vec3::Z).length() < 1e-6));
    assert_ccw_about_normals(&t);
    assert!((t.area() - 6.0).abs() < 1e-6);
    let (lo, hi) = t.uv.iter().fold((Vec2::MAX, Vec2::MIN), |(a, b), &c| (a.min(c), b.max(c)));
    assert_eq!((lo, hi), (Vec2::ZERO, Vec2::ONE));
    // dPdu × dPdv is along the normal, and P moves by dPdu · du.
    for i in 0..t.positions.len() {
        assert!(t.dpdu[i].cross(t.dpdv[i]).normalize().dot(t.normals[i]) > 0.9999);
        let back = t.positions[0] + t.dpdu[0] * (t.uv[i].x - t.uv[0].x) + t.dpdv[0] * (t.uv[i].y - t.uv[0].y);
        assert!((back - t.positions[i]).length() < 1e-5);
    }
    assert_eq!(t.st, t.uv);
}

#[test]
fn homogeneous_points_are_divided() {
    let t = one(r#"Polygon "Pw" [0 0 0 2  4 0 0 2  4 4 0 2  0 4 0 2]"#);
    assert!((t.area() - 4.0).abs() < 1e-6);
}

#[test]
fn uniform_cs_per_face_and_facevarying_st() {
    let t = one(r#"PointsPolygons [4 3] [0 1 2 3  1 4 2] "P" [0 0 0  1 0 0  1 1 0  0 1 0  2 0.5 0]
            "uniform color Cs" [1 0 0  0 1 0]
            "facevarying float[2] st" [0 0  1 0  1 1  0 1  10 10  11 11  12 12]
            "varying float k" [0 1 2 3 4]
            "constant float c" [7]"#);
    check_consistent(&t);
    assert_eq!(t.vertex_count(), 7);
    let cs = t.cs.as_ref().unwrap();
    assert_eq!(&cs[..4], &[[1.0, 0.0, 0.0]; 4]);
    assert_eq!(&cs[4..], &[[0.0, 1.0, 0.0]; 3]);
    let st: Vec<[f32; 2]> = t.st.iter().map(|v| v.to_array()).collect();
    assert_eq!(st, [[0., 0.], [1., 0.], [1., 1.], [0., 1.], [10., 10.], [11., 11.], [12., 12.]]);
    // The shared point 1 has k = 1 in both faces.
    assert_eq!(t.primvar("k").unwrap().values, [0., 1., 2., 3., 1., 4., 2.]);
    assert_eq!(t.primvar("c").unwrap().values, [7.0; 7]);
    assert_eq!(t.triangles.len(), 3);
}

#[test]
fn wrong_counts_name_the_variable_class_and_counts() {
    let base = r#"PointsPolygons [4 3] [0 1 2 3  1 4 2] "P" [0 0 0  1 0 0  1 1 0  0 1 0  2 0.5 0]"#;
    assert_eq!(
        one_err(&format!(r#"{base} "uniform color Cs" [1 0 0]"#)),
        r#"PointsPolygons: "Cs" (uniform color) has 3 values, expected 6 (2 items × 3)"#
    );
    assert_eq!(
        one_err(&format!(r#"{base} "facevarying float s" [1 2 3]"#)),
        r#"PointsPolygons: "s" (facevarying float) has 3 values, expected 7 (7 items × 1)"#
    );
    assert_eq!(
        one_err(&format!(r#"{base} "Cs" [1 0 0  1 0 0]"#)),
        r#"PointsPolygons: "Cs" (varying color) has 6 values, expected at least 15 (5 items × 3)"#
    );
    assert_eq!(
        one_err(r#"Polygon "P" [0 0 0  1 0 0  1 1 0] "Cs" [1 0 0]"#),
        r#"Polygon: "Cs" (varying color) has 3 values, expected 9 (3 items × 3)"#
    );
    assert_eq!(
        one_err(r#"PointsPolygons [3] [0 1 7] "P" [0 0 0  1 0 0  1 1 0]"#),
        r#"PointsPolygons: the vertex indices need 8 points, but "P" has 3"#
    );
    assert_eq!(
        one_err(r#"PointsPolygons [3 -1] [0 1 2] "P" [0 0 0  1 0 0  1 1 0]"#),
        "PointsPolygons: nverts[1] is -1, not a count (≥ 0)"
    );
    assert_eq!(
        one_err(r#"PointsPolygons [3] [0 1] "P" [0 0 0  1 0 0  1 1 0]"#),
        "PointsPolygons: vertids has 2 entries, but nverts adds up to 3"
    );
    assert_eq!(one_err(r#"Polygon "Cs" [1 0 0]"#), r#"Polygon: no positions; give "P" or "Pw""#);
    // A count that is not a multiple of 3 cannot come through the RIB reader: build it by hand.
    let loc = Loc { file: Default::default(), name: "t".into(), start: 0, end: 0, line: 1, col: 1 };
    let p = Param {
        name: "P".into(),
        decl: Decl::new(Class::Vertex, Type::Point),
        origin: DeclOrigin::Predeclared,
        values: Values::Float(vec![0.0; 10]),
        loc,
    };
    let e = polygon(&ParamList { params: vec![p] }, &Detail::default()).unwrap_err();
    assert_eq!(e.to_string(), r#"Polygon: "P" has 10 values, not a multiple of 3"#);
}

#[test]
fn user_normals_replace_the_face_normal() {
    let t = one(r#"Polygon "P" [0 0 0  1 0 0  1 1 0  0 1 0] "N" [0 0 2  0 0 2  1 0 1  1 0 1]"#);
    assert_eq!(t.normals[0], Vec3::Z);
    assert!((t.normals[2] - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6);
}

#[test]
fn degenerate_and_self_intersecting_polygons_do_not_panic() {
    for rib in [
        r#"Polygon "P" [0 0 0  1 1 1  2 2 2]"#,
        r#"Polygon "P" [0 0 0  0 0 0  0 0 0  0 0 0]"#,
        r#"GeneralPolygon [5] "P" [0 0 0  2 2 0  2 0 0  0 2 0  1 1 0]"#,
        r#"GeneralPolygon [4 3] "P" [0 0 0  1 0 0  1 1 0  0 1 0  5 5 0  6 5 0  5 6 0]"#,
        r#"GeneralPolygon [6] "P" [0 0 0  1 0 0  1 0 0  2 0 0  2 0 0  0 1 0]"#,
        r#"GeneralPolygon [4 4] "P" [0 0 0  4 0 0  4 4 0  0 4 0  0 0 0  4 0 0  4 4 0  0 4 0]"#,
    ] {
        let t = one(rib);
        check_consistent(&t);
    }
    let star = r#"Polygon "P" [0 3 0  1 -1 0  -2 1.5 0  2 1.5 0  -1 -1 0]"#;
    check_consistent(&one(star));
    let _ = points_polygons;
}

#[test]
fn np_is_the_polygon_normal() {
    let t = one(r#"PointsPolygons [3 3] [0 1 2  0 2 3] "P" [0 0 0  1 0 0  1 1 0  0 1 0] "Np" [0 0 1  0 1 1]"#);
    assert_eq!(&t.normals[..3], &[Vec3::Z; 3]);
    assert!(t.normals[3..].iter().all(|n| (*n - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-6));
}
