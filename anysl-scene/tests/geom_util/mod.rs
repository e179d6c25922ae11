//! Helpers of the geometry tests: RIB snippets → requests → tessellations.
#![allow(dead_code)]

use anysl_rib::{parse_str, Options, Recorder, Request};
use anysl_scene::geom::{self, Detail, PatchBasis, Result, Tessellation};

/// The requests of a RIB snippet; panics with the diagnostics if it does not parse.
pub fn requests(text: &str) -> Vec<Request> {
    let mut r = Recorder::new();
    match parse_str("test.rib", text, &mut r, &Options::default()) {
        Ok(_) => r.requests,
        Err(e) => panic!("bad RIB:\n{}", e.render()),
    }
}

/// Tessellates every geometric request of a snippet (a `Basis` applies to later patches).
pub fn tessellate_all(text: &str, d: &Detail) -> Vec<Result<Tessellation>> {
    let mut basis = PatchBasis::default();
    let mut out = Vec::new();
    for r in requests(text) {
        match &r {
            Request::Basis { ubasis, ustep, vbasis, vstep, .. } => {
                basis = PatchBasis::from_rib(ubasis, *ustep, vbasis, *vstep).expect("basis");
            }
            _ => {
                if let Some(t) = tessellate(&r, &basis, d) {
                    out.push(t);
                }
            }
        }
    }
    out
}

/// The one tessellation of a snippet, unwrapped.
pub fn one(text: &str) -> Tessellation {
    let mut v = tessellate_all(text, &Detail::default());
    assert_eq!(v.len(), 1, "{text}");
    v.remove(0).unwrap_or_else(|e| panic!("{e}"))
}

/// The one error of a snippet.
pub fn one_err(text: &str) -> String {
    let mut v = tessellate_all(text, &Detail::default());
    assert_eq!(v.len(), 1, "{text}");
    v.remove(0).expect_err(text).to_string()
}

/// A geometric request's tessellation, `None` for other requests.
pub fn tessellate(r: &Request, basis: &PatchBasis, d: &Detail) -> Option<Result<Tessellation>> {
    Some(match r {
        Request::Sphere { radius, zmin, zmax, thetamax, params, .. } => {
            geom::sphere(*radius, *zmin, *zmax, *thetamax, params, d)
        }
        Request::Cone { height, radius, thetamax, params, .. } => geom::cone(*height, *radius, *thetamax, params, d),
        Request::Cylinder { radius, zmin, zmax, thetamax, params, .. } => {
            geom::cylinder(*radius, *zmin, *zmax, *thetamax, params, d)
        }
        Request::Hyperboloid { point1, point2, thetamax, params, .. } => {
            geom::hyperboloid(*point1, *point2, *thetamax, params, d)
        }
        Request::Paraboloid { rmax, zmin, zmax, thetamax, params, .. } => {
            geom::paraboloid(*rmax, *zmin, *zmax, *thetamax, params, d)
        }
        Request::Disk { height, radius, thetamax, params, .. } => geom::disk(*height, *radius, *thetamax, params, d),
        Request::Torus { major_radius, minor_radius, phimin, phimax, thetamax, params, .. } => {
            geom::torus(*major_radius, *minor_radius, *phimin, *phimax, *thetamax, params, d)
        }
        Request::Polygon { params, .. } => geom::polygon(params, d),
        Request::GeneralPolygon { nverts, params, .. } => geom::general_polygon(nverts, params, d),
        Request::PointsPolygons { nverts, verts, params, .. } => geom::points_polygons(nverts, verts, params, d),
        Request::PointsGeneralPolygons { nloops, nverts, verts, params, .. } => {
            geom::points_general_polygons(nloops, nverts, verts, params, d)
        }
        Request::Patch { kind, params, .. } => geom::patch(kind, basis, params, d),
        Request::PatchMesh { kind, nu, uwrap, nv, vwrap, params, .. } => {
            geom::patch_mesh(kind, *nu, uwrap, *nv, vwrap, basis, params, d)
        }
        Request::NuPatch { nu, uorder, uknot, umin, umax, nv, vorder, vknot, vmin, vmax, params, .. } => {
            geom::nu_patch(*nu, *uorder, uknot, *umin, *umax, *nv, *vorder, vknot, *vmin, *vmax, params, d)
        }
        Request::Geometry { kind, .. } if kind == "teapot" => Ok(geom::teapot(d)),
        _ => return None,
    })
}

/// Every vertex attribute has one entry per vertex, indices are in range, nothing is NaN.
pub fn check_consistent(t: &Tessellation) {
    let n = t.positions.len();
    assert_eq!(t.normals.len(), n);
    assert_eq!(t.uv.len(), n);
    assert_eq!(t.st.len(), n);
    assert_eq!(t.dpdu.len(), n);
    assert_eq!(t.dpdv.len(), n);
    for c in [&t.cs, &t.os].into_iter().flatten() {
        assert_eq!(c.len(), n);
    }
    for p in &t.primvars {
        assert_eq!(p.values.len(), n * p.components, "{}", p.name);
    }
    assert!(t.triangles.iter().flatten().all(|&i| (i as usize) < n));
    assert!(t.positions.iter().all(|p| p.is_finite()));
    assert!(t.normals.iter().all(|v| v.is_finite() && (v.length() - 1.0).abs() < 1e-3), "normals not unit");
}
