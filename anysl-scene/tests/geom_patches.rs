//! Patches, patch meshes and NURBS: planes reproduced, periodic meshes closed, Catmull-Rom
//! interpolation, NuPatch against the bilinear patch and the rational quarter circle,
//! varying/vertex counts of periodic meshes, partials against finite differences.

// Tests index parallel per-vertex arrays.
#![allow(clippy::needless_range_loop)]

mod geom_util;

use anysl_rib::{Basis, ParamList};
use anysl_scene::geom::{Detail, PatchBasis, Tessellation};
use geom_util::{check_consistent, one, one_err, tessellate_all};
use glam::{Vec2, Vec3};

/// The vertex nearest to (u, v).
fn at(t: &Tessellation, u: f32, v: f32) -> usize {
    let q = Vec2::new(u, v);
    (0..t.uv.len()).min_by(|&a, &b| t.uv[a].distance(q).total_cmp(&t.uv[b].distance(q))).unwrap()
}

fn points(f: impl Fn(usize, usize) -> [f32; 3], nu: usize, nv: usize) -> String {
    let mut s = String::new();
    for j in 0..nv {
        for i in 0..nu {
            let p = f(i, j);
            s += &format!("{} {} {}  ", p[0], p[1], p[2]);
        }
    }
    s
}

#[test]
fn bezier_patch_with_planar_grid_is_the_plane() {
    let pts = points(|i, j| [i as f32 / 3.0, j as f32 / 3.0, 0.0], 4, 4);
    let t = one(&format!(r#"Patch "bicubic" "P" [{pts}]"#));
    check_consistent(&t);
    for i in 0..t.positions.len() {
        let (p, uv) = (t.positions[i], t.uv[i]);
        assert!((p - Vec3::new(uv.x, uv.y, 0.0)).length() < 1e-6, "P({uv}) = {p}");
        assert!((t.normals[i] - Vec3::Z).length() < 1e-6);
        assert!((t.dpdu[i] - Vec3::X).length() < 1e-5 && (t.dpdv[i] - Vec3::Y).length() < 1e-5);
    }
    assert!((t.area() - 1.0).abs() < 1e-5);
    // A tilted plane with uneven spacing of the inner rows stays in the plane.
    let pts = points(
        |i, j| {
            let (x, y) = (i as f32 + 0.3 * (j == 1) as u8 as f32, (j * j) as f32);
            [x, y, x + y]
        },
        4,
        4,
    );
    let t = one(&format!(r#"Patch "bicubic" "P" [{pts}]"#));
    for p in &t.positions {
        assert!((p.x + p.y - p.z).abs() < 1e-4, "{p} off the plane z = x + y");
    }
}

#[test]
fn bilinear_patch_corners_and_uniform_varying_classes() {
    let t = one(
        r#"Patch "bilinear" "P" [0 0 0  1 0 0  0 1 1  1 1 0] "Cs" [1 0 0  0 1 0  0 0 1  1 1 1] "uniform float k" [3]"#,
    );
    check_consistent(&t);
    for (u, v, p, c) in [
        (0.0, 0.0, Vec3::ZERO, [1.0, 0.0, 0.0]),
        (1.0, 0.0, Vec3::X, [0.0, 1.0, 0.0]),
        (0.0, 1.0, Vec3::new(0.0, 1.0, 1.0), [0.0, 0.0, 1.0]),
        (1.0, 1.0, Vec3::new(1.0, 1.0, 0.0), [1.0, 1.0, 1.0]),
    ] {
        let i = at(&t, u, v);
        assert_eq!(t.positions[i], p);
        assert_eq!(t.cs.as_ref().unwrap()[i], c);
    }
    let i = at(&t, 0.5, 0.5);
    assert_eq!(t.cs.as_ref().unwrap()[i], [0.5, 0.5, 0.5]);
    assert!(t.primvar("k").unwrap().values.iter().all(|&k| k == 3.0));
}

#[test]
fn catmull_rom_patch_interpolates_its_inner_points() {
    let z = |i: usize, j: usize| ((i * 7 + j * 3) % 5) as f32 * 0.25;
    let pts = points(|i, j| [i as f32, j as f32, z(i, j)], 4, 4);
    let t = one(&format!(r#"Basis "catmull-rom" 1 "catmull-rom" 1 Patch "bicubic" "P" [{pts}]"#));
    for (u, v, i, j) in [(0.0, 0.0, 1, 1), (1.0, 0.0, 2, 1), (0.0, 1.0, 1, 2), (1.0, 1.0, 2, 2)] {
        let p = t.positions[at(&t, u, v)];
        assert!((p - Vec3::new(i as f32, j as f32, z(i, j))).length() < 1e-5, "P({u}, {v}) = {p}");
    }
}

#[test]
fn periodic_bspline_mesh_closes() {
    // 8 control points around a circle in u (periodic), 4 rows up in z (nonperiodic).
    let pts = points(
        |i, j| {
            let a = i as f32 * std::f32::consts::TAU / 8.0;
            [a.cos(), a.sin(), j as f32]
        },
        8,
        4,
    );
    let rib =
        format!(r#"Basis "b-spline" 1 "b-spline" 1 PatchMesh "bicubic" 8 "periodic" 4 "nonperiodic" "P" [{pts}]"#);
    let t = one(&rib);
    check_consistent(&t);
    for v in [0.0, 0.3, 0.7, 1.0] {
        let (a, b) = (t.positions[at(&t, 0.0, v)], t.positions[at(&t, 1.0, v)]);
        assert!((a - b).length() < 1e-5, "u = 0 and u = 1 differ at v = {v}: {a} {b}");
        let (na, nb) = (t.normals[at(&t, 0.0, v)], t.normals[at(&t, 1.0, v)]);
        assert!((na - nb).length() < 1e-4);
    }
    // Outward normals (u runs counter-clockwise, v up).
    for i in 0..t.positions.len() {
        let radial = t.positions[i].truncate().extend(0.0).normalize();
        assert!(t.normals[i].dot(radial) > 0.99);
    }
    // Periodic in u: 8 patches, 8 varying columns; nonperiodic in v: 1 patch, 2 varying rows.
    let good = format!("{rib} \"varying float k\" [{}]", vec!["1"; 16].join(" "));
    assert_eq!(tessellate_all(&good, &Detail::default()).len(), 1);
    assert!(tessellate_all(&good, &Detail::default())[0].is_ok());
    assert_eq!(
        one_err(&format!("{rib} \"varying float k\" [{}]", vec!["1"; 18].join(" "))),
        r#"PatchMesh: "k" (varying float) has 18 values, expected 16 (16 items × 1)"#
    );
    assert_eq!(
        one_err(&format!("{rib} \"uniform float k\" [1 2]")),
        r#"PatchMesh: "k" (uniform float) has 2 values, expected 8 (8 items × 1)"#
    );
    let vertex = format!("{rib} \"vertex float k\" [{}]", vec!["2"; 32].join(" "));
    let t = one(&vertex);
    assert!(t.primvar("k").unwrap().values.iter().all(|k| (k - 2.0).abs() < 1e-5), "vertex class reproduces constants");
}

#[test]
fn mesh_uv_spans_the_whole_mesh_and_uniform_per_patch() {
    // A 7 × 4 bezier mesh: 2 patches along u.
    let pts = points(|i, j| [i as f32, j as f32, 0.0], 7, 4);
    let t = one(&format!(r#"PatchMesh "bicubic" 7 "nonperiodic" 4 "nonperiodic" "P" [{pts}] "uniform float k" [1 2]"#));
    let (lo, hi) = t.uv.iter().fold((Vec2::MAX, Vec2::MIN), |(a, b), &c| (a.min(c), b.max(c)));
    assert_eq!((lo, hi), (Vec2::ZERO, Vec2::ONE));
    let k = &t.primvar("k").unwrap().values;
    for i in 0..t.positions.len() {
        let expect = if t.uv[i].x < 0.5 {
            1.0
        } else if t.uv[i].x > 0.5 {
            2.0
        } else {
            k[i]
        };
        assert_eq!(k[i], expect);
        // x runs 0..6 over u in 0..1: dPdu is along x with length 6.
        assert!((t.dpdu[i] - Vec3::new(6.0, 0.0, 0.0)).length() < 1e-4, "{}", t.dpdu[i]);
    }
    assert_eq!(
        one_err(&format!(r#"PatchMesh "bicubic" 6 "nonperiodic" 4 "nonperiodic" "P" [{}]"#, points(|_, _| [0.0; 3], 6, 4))),
        "PatchMesh: nu = 6 control points do not make whole bicubic patches (nonperiodic wants 4 + a multiple of the step 3)"
    );
    assert_eq!(
        one_err(r#"PatchMesh "bilinear" 2 "nonperiodic" 2 "nonperiodic" "P" [0 0 0  1 0 0  0 1 0]"#),
        r#"PatchMesh: "P" has 3 points, expected nu × nv = 2 × 2 = 4"#
    );
    assert_eq!(one_err(r#"Patch "bicubix" "P" [0 0 0]"#), r#"Patch: unknown type "bicubix" (bilinear or bicubic)"#);
}

#[test]
fn height_field_and_rational_patches() {
    let t = one(r#"Patch "bilinear" "Pz" [0 1 2 3]"#);
    for i in 0..t.positions.len() {
        let uv = t.uv[i];
        let expect = Vec3::new(uv.x, uv.y, uv.x + 2.0 * uv.y);
        assert!((t.positions[i] - expect).length() < 1e-5);
    }
    // Equal weights change nothing.
    let a = one(r#"Patch "bilinear" "P" [0 0 0  1 0 0  0 1 1  1 1 0]"#);
    let b = one(r#"Patch "bilinear" "Pw" [0 0 0 2  2 0 0 2  0 2 2 2  2 2 0 2]"#);
    for (p, q) in a.positions.iter().zip(&b.positions) {
        assert!((*p - *q).length() < 1e-6);
    }
}

#[test]
fn partials_match_finite_differences_of_the_evaluated_surface() {
    // A wavy bicubic patch, tessellated finely; compare dPdu with neighbouring vertices.
    let pts = points(|i, j| [i as f32, j as f32, ((i * 3 + j * 5) % 4) as f32 * 0.3], 4, 4);
    let d = Detail { tolerance: 1e-5, min_segments: 64, max_segments: 64 };
    let t = tessellate_all(&format!(r#"Patch "bicubic" "P" [{pts}]"#), &d).remove(0).unwrap();
    let row = 65;
    for j in 1..64 {
        for i in 1..64 {
            let k = j * row + i;
            let h = 1.0 / 64.0;
            let fd_u = (t.positions[k + 1] - t.positions[k - 1]) / (2.0 * h);
            let fd_v = (t.positions[k + row] - t.positions[k - row]) / (2.0 * h);
            assert!((fd_u - t.dpdu[k]).length() < 2e-2 * (1.0 + fd_u.length()), "{fd_u} vs {}", t.dpdu[k]);
            assert!((fd_v - t.dpdv[k]).length() < 2e-2 * (1.0 + fd_v.length()), "{fd_v} vs {}", t.dpdv[k]);
        }
    }
}

#[test]
fn nupatch_of_order_2_is_the_bilinear_patch() {
    let p = "0 0 0  1 0 0.5  0 1 1  1 1 0";
    let a = one(&format!(r#"Patch "bilinear" "P" [{p}] "Cs" [1 0 0  0 1 0  0 0 1  1 1 1]"#));
    let b = one(&format!(r#"NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 "P" [{p}] "Cs" [1 0 0  0 1 0  0 0 1  1 1 1]"#));
    check_consistent(&b);
    assert_eq!(a.positions.len(), b.positions.len());
    for i in 0..a.positions.len() {
        assert!((a.positions[i] - b.positions[i]).length() < 1e-6);
        assert!((a.normals[i] - b.normals[i]).length() < 1e-5);
        assert!((a.dpdu[i] - b.dpdu[i]).length() < 1e-5 && (a.dpdv[i] - b.dpdv[i]).length() < 1e-5);
        assert_eq!(a.uv[i], b.uv[i]);
        let (ca, cb) = (a.cs.as_ref().unwrap()[i], b.cs.as_ref().unwrap()[i]);
        assert!((Vec3::from(ca) - Vec3::from(cb)).length() < 1e-6);
    }
}

#[test]
fn rational_nupatch_quarter_circle() {
    // A quadratic rational curve in u (weights 1, 1/√2, 1) extruded linearly in v.
    let w = std::f32::consts::FRAC_1_SQRT_2;
    let rib = format!(
        r#"NuPatch 3 3 [0 0 0 1 1 1] 0 1 2 2 [0 0 1 1] 0 1
           "Pw" [1 0 0 1  {w} {w} 0 {w}  0 1 0 1   1 0 1 1  {w} {w} {w} {w}  0 1 1 1]"#
    );
    let t = one(&rib);
    check_consistent(&t);
    for i in 0..t.positions.len() {
        let p = t.positions[i];
        assert!((p.truncate().length() - 1.0).abs() < 1e-5, "{p} off the unit circle");
        assert!((p.z - t.uv[i].y).abs() < 1e-6);
        // The normal of the cylinder: radial (u counter-clockwise, v up → outward).
        assert!((t.normals[i] - p.truncate().extend(0.0).normalize()).length() < 1e-4);
        // dPdu is tangent to the circle.
        assert!(t.dpdu[i].dot(p.truncate().extend(0.0)).abs() < 1e-4);
    }
    // Chord error: triangle edge midpoints stay within the tolerance of the circle.
    for tri in &t.triangles {
        for (a, b) in [(0, 1), (1, 2), (2, 0)] {
            let m = (t.positions[tri[a] as usize] + t.positions[tri[b] as usize]) / 2.0;
            assert!(1.0 - m.truncate().length() <= 1e-3 + 1e-6);
        }
    }
}

#[test]
fn nupatch_ranges_and_errors() {
    // umin..umax inside the knot range: u spans exactly that.
    let t = one(r#"NuPatch 2 2 [0 0 2 2] 0.5 1.5 2 2 [0 0 1 1] 0 1 "P" [0 0 0  2 0 0  0 1 0  2 1 0]"#);
    let (lo, hi) = t.uv.iter().fold((Vec2::MAX, Vec2::MIN), |(a, b), &c| (a.min(c), b.max(c)));
    assert_eq!((lo, hi), (Vec2::new(0.5, 0.0), Vec2::new(1.5, 1.0)));
    assert!(t.positions.iter().all(|p| p.x >= 0.5 - 1e-6 && p.x <= 1.5 + 1e-6));
    assert_eq!(
        one_err(r#"NuPatch 2 2 [0 0 1] 0 1 2 2 [0 0 1 1] 0 1 "P" [0 0 0  2 0 0  0 1 0  2 1 0]"#),
        "NuPatch: uknot has 3 values, expected nu + uorder = 4"
    );
    assert_eq!(
        one_err(r#"NuPatch 2 2 [0 1 0 1] 0 1 2 2 [0 0 1 1] 0 1 "P" [0 0 0  2 0 0  0 1 0  2 1 0]"#),
        "NuPatch: uknot decreases at index 2 (1 > 0)"
    );
    assert_eq!(
        one_err(r#"NuPatch 2 3 [0 0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 "P" [0 0 0  2 0 0  0 1 0  2 1 0]"#),
        "NuPatch: nu = 2 control points are fewer than the order 3"
    );
    // Multiple knots (a crease) and several spans: uniform per segment.
    let t = one(
        r#"NuPatch 4 2 [0 0 1 2 3 3] 0 3 2 2 [0 0 1 1] 0 1 "P" [0 0 0  1 0 1  2 0 0  3 0 1  0 1 0  1 1 1  2 1 0  3 1 1]
           "uniform float seg" [0 1 2]"#,
    );
    let seg = &t.primvar("seg").unwrap().values;
    for i in 0..t.positions.len() {
        let u = t.uv[i].x;
        if u.fract() != 0.0 {
            assert_eq!(seg[i], u.floor());
        }
    }
}

#[test]
fn basis_names_and_matrices() {
    let bez = PatchBasis::from_rib(&Basis::Named("bezier".into()), 3, &Basis::Named("bezier".into()), 3).unwrap();
    assert_eq!(bez, PatchBasis::default());
    let m: [f32; 16] = [-1., 3., -3., 1., 3., -6., 3., 0., -3., 3., 0., 0., 1., 0., 0., 0.];
    let explicit = PatchBasis::from_rib(&Basis::Matrix(m), 3, &Basis::Matrix(m), 3).unwrap();
    assert_eq!(explicit, bez);
    let e = PatchBasis::from_rib(&Basis::Named("bezzier".into()), 3, &Basis::Named("bezier".into()), 3).unwrap_err();
    assert!(e.to_string().starts_with(r#"Basis: unknown u basis "bezzier""#), "{e}");
    let e = PatchBasis::from_rib(&Basis::Named("bezier".into()), 0, &Basis::Named("bezier".into()), 3).unwrap_err();
    assert_eq!(e.to_string(), "Basis: ustep is 0, not a positive step");
    // Every named basis: weights sum to one (partition of unity) except hermite and power.
    for name in ["bezier", "b-spline", "catmull-rom"] {
        let (m, _) = PatchBasis::named(name).unwrap();
        for k in 0..4 {
            let s: f32 = m.row(k).to_array().iter().sum();
            assert!((s - if k == 3 { 1.0 } else { 0.0 }).abs() < 1e-6, "{name} row {k}");
        }
    }
    let _ = ParamList::new();
}

/// De Casteljau on a 4 × 4 grid (u fastest), in f64: an evaluation independent of the crate's
/// basis matrices.
fn de_casteljau(ctrl: &[[f64; 3]], u: f64, v: f64) -> glam::DVec3 {
    let curve = |p: [glam::DVec3; 4], t: f64| {
        let l = |a: glam::DVec3, b: glam::DVec3| a + (b - a) * t;
        let (a, b, c) = (l(p[0], p[1]), l(p[1], p[2]), l(p[2], p[3]));
        let (d, e) = (l(a, b), l(b, c));
        l(d, e)
    };
    let rows: Vec<glam::DVec3> =
        (0..4).map(|j| curve([0, 1, 2, 3].map(|i| glam::DVec3::from(ctrl[j * 4 + i])), u)).collect();
    curve([rows[0], rows[1], rows[2], rows[3]], v)
}

#[test]
fn bicubic_chord_error_within_tolerance() {
    let ctrl: Vec<[f64; 3]> =
        (0..16).map(|k| [(k % 4) as f64, (k / 4) as f64, [0.0, 1.5, -1.0, 0.5][(k * 7 + k / 4) % 4]]).collect();
    let pts: String = ctrl.iter().map(|p| format!("{} {} {}  ", p[0], p[1], p[2])).collect();
    for tol in [1e-2f32, 1e-3] {
        let d = Detail { tolerance: tol, min_segments: 1, max_segments: 512 };
        let t = tessellate_all(&format!(r#"Patch "bicubic" "P" [{pts}]"#), &d).remove(0).unwrap();
        let mut worst: f64 = 0.0;
        for tri in &t.triangles {
            let [a, b, c] = tri.map(|i| i as usize);
            for w in [[0.5, 0.5, 0.0], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5], [1.0 / 3.0; 3]] {
                let uv = t.uv[a].as_dvec2() * w[0] + t.uv[b].as_dvec2() * w[1] + t.uv[c].as_dvec2() * w[2];
                let on_tri = t.positions[a].as_dvec3() * w[0]
                    + t.positions[b].as_dvec3() * w[1]
                    + t.positions[c].as_dvec3() * w[2];
                worst = worst.max((de_casteljau(&ctrl, uv.x, uv.y) - on_tri).length());
            }
        }
        for i in 0..t.positions.len() {
            let exact = de_casteljau(&ctrl, t.uv[i].x as f64, t.uv[i].y as f64);
            assert!((exact - t.positions[i].as_dvec3()).length() < 1e-5);
        }
        assert!(worst <= tol as f64, "tolerance {tol}: chord error {worst}");
        assert!(worst > tol as f64 / 20.0, "tolerance {tol}: chord error {worst} far below it (too fine)");
    }
}
