//! Every request family: positional arguments, arrays versus loose numbers, parameter lists.

mod util;

use anysl_rib::{Basis, Handle, Recorder, Request, Values};
use util::{one, record, show};

/// Checks that `text` reads as requests whose location-free `Debug` is `expected`.
fn check(text: &str, expected: &[&str]) {
    let got: Vec<String> = record(text).iter().map(show).collect();
    assert_eq!(got, expected, "reading {text:?}");
}

#[test]
fn blocks() {
    check(
        "FrameBegin 1 WorldBegin AttributeBegin TransformBegin TransformEnd AttributeEnd \
         SolidBegin \"union\" SolidEnd ObjectBegin 3 ObjectEnd ObjectInstance 3 \
         ObjectBegin \"obj\" ObjectEnd ObjectInstance \"obj\" \
         MotionBegin [0 1] Translate 0 0 0 Translate 1 0 0 MotionEnd WorldEnd FrameEnd",
        &[
            "FrameBegin { frame: 1 }",
            "WorldBegin",
            "AttributeBegin",
            "TransformBegin",
            "TransformEnd",
            "AttributeEnd",
            "SolidBegin { operation: \"union\" }",
            "SolidEnd",
            "ObjectBegin { handle: Int(3) }",
            "ObjectEnd",
            "ObjectInstance { handle: Int(3) }",
            "ObjectBegin { handle: Str(\"obj\") }",
            "ObjectEnd",
            "ObjectInstance { handle: Str(\"obj\") }",
            "MotionBegin { times: [0.0, 1.0] }",
            "Translate { dx: 0.0, dy: 0.0, dz: 0.0 }",
            "Translate { dx: 1.0, dy: 0.0, dz: 0.0 }",
            "MotionEnd",
            "WorldEnd",
            "FrameEnd",
        ],
    );
}

#[test]
fn camera_and_image_options() {
    check(
        "Format 640 480 1\nFrameAspectRatio 1.333\nScreenWindow -1 1 -0.75 0.75\nScreenWindow [-1 1 -1 1]\n\
         CropWindow 0 0.5 0 1\nClipping 0.1 1e4\nClippingPlane 0 0 1 0 0 -1\nDepthOfField 2.8 0.05 10\n\
         DepthOfField\nShutter 0 0.5\nPixelVariance 0.01\nPixelSamples 4 4\nPixelFilter \"gaussian\" 2 2\n\
         Exposure 1 2.2\nQuantize \"rgba\" 255 0 255 0.5\nRelativeDetail 0.5\nErrorHandler \"print\"\n\
         ColorSamples [1 0 0 0 1 0 0 0 1] [1 0 0 0 1 0 0 0 1]\nPerspective 40",
        &[
            "Format { xres: 640, yres: 480, pixel_aspect: 1.0 }",
            "FrameAspectRatio { aspect: 1.333 }",
            "ScreenWindow { window: [-1.0, 1.0, -0.75, 0.75] }",
            "ScreenWindow { window: [-1.0, 1.0, -1.0, 1.0] }",
            "CropWindow { window: [0.0, 0.5, 0.0, 1.0] }",
            "Clipping { near: 0.1, far: 10000.0 }",
            "ClippingPlane { plane: [0.0, 0.0, 1.0, 0.0, 0.0, -1.0] }",
            "DepthOfField { fstop: 2.8, focal_length: 0.05, focal_distance: 10.0 }",
            "DepthOfField { fstop: inf, focal_length: 0.0, focal_distance: 0.0 }",
            "Shutter { open: 0.0, close: 0.5 }",
            "PixelVariance { variance: 0.01 }",
            "PixelSamples { xsamples: 4.0, ysamples: 4.0 }",
            "PixelFilter { name: \"gaussian\", xwidth: 2.0, ywidth: 2.0 }",
            "Exposure { gain: 1.0, gamma: 2.2 }",
            "Quantize { kind: \"rgba\", one: 255, min: 0, max: 255, dither_amplitude: 0.5 }",
            "RelativeDetail { relative_detail: 0.5 }",
            "ErrorHandler { name: \"print\" }",
            "ColorSamples { n_rgb: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], rgb_n: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0] }",
            "Perspective { fov: 40.0 }",
        ],
    );
}

#[test]
fn projection_display_hider_option_attribute() {
    let reqs = record(
        "Projection \"perspective\" \"fov\" [45]\nDisplay \"out.tif\" \"file\" \"rgba\" \"origin\" [0 0]\n\
         Hider \"hidden\" \"jitter\" [1]\nOption \"limits\" \"bucketsize\" [16 16]\n\
         Attribute \"identifier\" \"name\" [\"ball\"]\nAttribute \"displacementbound\" \"sphere\" [0.5]\n\
         Imager \"background\" \"background\" [0 0 1]",
    );
    let Request::Projection { name, params, .. } = &reqs[0] else { panic!("{:?}", reqs[0]) };
    assert_eq!((name.as_str(), params.float("fov")), ("perspective", Some(45.0)));
    let Request::Display { name, kind, mode, params, .. } = &reqs[1] else { panic!() };
    assert_eq!((name.as_str(), kind.as_str(), mode.as_str()), ("out.tif", "file", "rgba"));
    assert_eq!(params.ints("origin"), Some(&[0, 0][..]));
    let Request::Hider { kind, params, .. } = &reqs[2] else { panic!() };
    assert_eq!((kind.as_str(), params.int("jitter")), ("hidden", Some(1)));
    let Request::Option { name, params, .. } = &reqs[3] else { panic!() };
    assert_eq!((name.as_str(), params.ints("bucketsize")), ("limits", Some(&[16, 16][..])));
    let Request::Attribute { name, params, .. } = &reqs[4] else { panic!() };
    assert_eq!((name.as_str(), params.string("name")), ("identifier", Some("ball")));
    let Request::Attribute { params, .. } = &reqs[5] else { panic!() };
    assert_eq!(params.float("sphere"), Some(0.5));
    let Request::Imager { name, params, .. } = &reqs[6] else { panic!() };
    assert_eq!((name.as_str(), params.floats("background")), ("background", Some(&[0.0, 0.0, 1.0][..])));
}

#[test]
fn shading_attributes() {
    check(
        "Color [1 0 0]\nColor 0 1 0\nOpacity [0.5 0.5 0.5]\nOpacity 1 1 1\nTextureCoordinates 0 0 1 0 0 1 1 1\n\
         Illuminate 1 0\nIlluminate \"key\" 1\nShadingRate 0.5\nShadingRate [2]\nShadingInterpolation \"smooth\"\n\
         Matte 1\nBound [0 1 0 1 0 1]\nBound 0 1 0 1 0 1\nDetail [-1 1 -1 1 -1 1]\nDetailRange 0 0 10 20\n\
         GeometricApproximation \"flatness\" 0.5\nGeometricRepresentation \"points\"\nOrientation \"rh\"\n\
         ReverseOrientation\nSides 2\nSides 1.0\nCoordinateSystem \"lamp\"\nCoordSysTransform \"lamp\"",
        &[
            "Color { rgb: [1.0, 0.0, 0.0] }",
            "Color { rgb: [0.0, 1.0, 0.0] }",
            "Opacity { rgb: [0.5, 0.5, 0.5] }",
            "Opacity { rgb: [1.0, 1.0, 1.0] }",
            "TextureCoordinates { st: [0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0] }",
            "Illuminate { handle: Int(1), on: false }",
            "Illuminate { handle: Str(\"key\"), on: true }",
            "ShadingRate { size: 0.5 }",
            "ShadingRate { size: 2.0 }",
            "ShadingInterpolation { kind: \"smooth\" }",
            "Matte { on: true }",
            "Bound { bound: [0.0, 1.0, 0.0, 1.0, 0.0, 1.0] }",
            "Bound { bound: [0.0, 1.0, 0.0, 1.0, 0.0, 1.0] }",
            "Detail { bound: [-1.0, 1.0, -1.0, 1.0, -1.0, 1.0] }",
            "DetailRange { range: [0.0, 0.0, 10.0, 20.0] }",
            "GeometricApproximation { kind: \"flatness\", value: 0.5 }",
            "GeometricRepresentation { kind: \"points\" }",
            "Orientation { orientation: \"rh\" }",
            "ReverseOrientation",
            "Sides { sides: 2 }",
            "Sides { sides: 1 }",
            "CoordinateSystem { name: \"lamp\" }",
            "CoordSysTransform { name: \"lamp\" }",
        ],
    );
}

#[test]
fn shaders_and_lights() {
    let reqs = record(
        "LightSource \"spotlight\" 1 \"intensity\" 10 \"from\" [0 5 0] \"to\" [0 0 0]\n\
         LightSource \"ambientlight\" \"amb\" \"lightcolor\" [0.1 0.1 0.1]\n\
         AreaLightSource \"arealight\" 7 \"intensity\" [2]\n\
         Surface \"plastic\" \"Ks\" [0.5] \"Kd\" 0.8\nDisplacement \"bumpy\" \"amplitude\" 0.1\n\
         Atmosphere \"fog\" \"distance\" [5]\nInterior \"water\"\nExterior \"air\"\nDeformation \"twist\"",
    );
    let names: Vec<&str> = reqs.iter().map(Request::name).collect();
    assert_eq!(
        names,
        [
            "LightSource",
            "LightSource",
            "AreaLightSource",
            "Surface",
            "Displacement",
            "Atmosphere",
            "Interior",
            "Exterior",
            "Deformation"
        ]
    );
    let Request::LightSource { name, handle, params, .. } = &reqs[0] else { panic!() };
    assert_eq!((name.as_str(), handle), ("spotlight", &Handle::Int(1)));
    assert_eq!(params.float("intensity"), Some(10.0));
    assert_eq!(params.floats("from"), Some(&[0.0, 5.0, 0.0][..]));
    let Request::LightSource { handle, params, .. } = &reqs[1] else { panic!() };
    assert_eq!(handle, &Handle::Str("amb".into()));
    assert_eq!(params.get("lightcolor").unwrap().item_count(), 1);
    let Request::AreaLightSource { handle, .. } = &reqs[2] else { panic!() };
    assert_eq!(handle, &Handle::Int(7));
    let Request::Surface { name, params, .. } = &reqs[3] else { panic!() };
    assert_eq!((name.as_str(), params.float("Ks"), params.float("Kd")), ("plastic", Some(0.5), Some(0.8)));
    let Request::Interior { name, params, .. } = &reqs[6] else { panic!() };
    assert_eq!((name.as_str(), params.len()), ("water", 0));
}

#[test]
fn transforms() {
    let m = "[1 0 0 0 0 1 0 0 0 0 1 0 1 2 3 1]";
    check(
        &format!(
            "Identity\nTransform {m}\nConcatTransform {m}\nTranslate 1 2 3\nRotate 90 0 0 1\nScale 2 2 2\n\
             Skew 45 0 1 0 1 0 0\nSkew [45 0 1 0 1 0 0]"
        ),
        &[
            "Identity",
            "Transform { matrix: [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 2.0, 3.0, 1.0] }",
            "ConcatTransform { matrix: [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 2.0, 3.0, 1.0] }",
            "Translate { dx: 1.0, dy: 2.0, dz: 3.0 }",
            "Rotate { angle: 90.0, dx: 0.0, dy: 0.0, dz: 1.0 }",
            "Scale { sx: 2.0, sy: 2.0, sz: 2.0 }",
            "Skew { skew: [45.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0] }",
            "Skew { skew: [45.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0] }",
        ],
    );
}

#[test]
fn quadrics() {
    let reqs = record(
        "Sphere 1 -1 1 360\nCone 2 0.5 270\nCylinder 1 -1 1 360\nHyperboloid 1 0 0 0 1 1 360\n\
         Hyperboloid [1 0 0] [0 1 1] 180\nParaboloid 1 0 2 360\nDisk 0 1 360\nTorus 1 0.25 0 360 360",
    );
    let shown: Vec<String> = reqs.iter().map(show).collect();
    let params = "params: ParamList { params: [] }";
    assert_eq!(
        shown,
        [
            format!("Sphere {{ radius: 1.0, zmin: -1.0, zmax: 1.0, thetamax: 360.0, {params} }}"),
            format!("Cone {{ height: 2.0, radius: 0.5, thetamax: 270.0, {params} }}"),
            format!("Cylinder {{ radius: 1.0, zmin: -1.0, zmax: 1.0, thetamax: 360.0, {params} }}"),
            format!("Hyperboloid {{ point1: [1.0, 0.0, 0.0], point2: [0.0, 1.0, 1.0], thetamax: 360.0, {params} }}"),
            format!("Hyperboloid {{ point1: [1.0, 0.0, 0.0], point2: [0.0, 1.0, 1.0], thetamax: 180.0, {params} }}"),
            format!("Paraboloid {{ rmax: 1.0, zmin: 0.0, zmax: 2.0, thetamax: 360.0, {params} }}"),
            format!("Disk {{ height: 0.0, radius: 1.0, thetamax: 360.0, {params} }}"),
            format!("Torus {{ major_radius: 1.0, minor_radius: 0.25, phimin: 0.0, phimax: 360.0, thetamax: 360.0, {params} }}"),
        ]
    );
}

#[test]
fn polygons() {
    let reqs = record(
        "Polygon \"P\" [0 0 0 1 0 0 1 1 0] \"Cs\" [1 0 0 0 1 0 0 0 1]\n\
         GeneralPolygon [4 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0 .2 .2 0 .5 .2 0 .5 .5 0]\n\
         PointsPolygons [3 3] [0 1 2 0 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]\n\
         PointsGeneralPolygons [1 2] [3 4 3] [0 1 2 0 1 2 3 4 5 6] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0 .2 .2 0 .5 .2 0 .5 .5 0]",
    );
    let Request::Polygon { params, .. } = &reqs[0] else { panic!() };
    assert_eq!(params.get("P").unwrap().item_count(), 3);
    assert_eq!(params.get("Cs").unwrap().item_count(), 3);
    let Request::GeneralPolygon { nverts, params, .. } = &reqs[1] else { panic!() };
    assert_eq!((nverts.as_slice(), params.get("P").unwrap().item_count()), (&[4, 3][..], 7));
    let Request::PointsPolygons { nverts, verts, params, .. } = &reqs[2] else { panic!() };
    assert_eq!((nverts.as_slice(), verts.as_slice()), (&[3, 3][..], &[0, 1, 2, 0, 2, 3][..]));
    assert_eq!(params.get("P").unwrap().item_count(), 4);
    let Request::PointsGeneralPolygons { nloops, nverts, verts, .. } = &reqs[3] else { panic!() };
    assert_eq!(nloops, &[1, 2]);
    assert_eq!(nverts, &[3, 4, 3]);
    assert_eq!(verts.len(), 10);
}

#[test]
fn patches_and_nurbs() {
    let reqs = record(
        "Basis \"bezier\" 3 \"bezier\" 3\n\
         Basis [-1 3 -3 1 3 -6 3 0 -3 3 0 0 1 0 0 0] 3 \"catmull-rom\" 1\n\
         Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n\
         PatchMesh \"bicubic\" 4 \"nonperiodic\" 4 \"periodic\" \"Pw\" [0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1 0 0 0 1]\n\
         NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [0 0 0 1 1 0 0 1 0 1 0 1 1 1 0 1]\n\
         TrimCurve [1] [2] [0 0 1 1] [0] [1] [2] [0 1] [0 1] [1 1]",
    );
    let Request::Basis { ubasis, ustep, vbasis, vstep, .. } = &reqs[0] else { panic!() };
    assert_eq!(
        (ubasis, *ustep, vbasis, *vstep),
        (&Basis::Named("bezier".into()), 3, &Basis::Named("bezier".into()), 3)
    );
    let Request::Basis { ubasis: Basis::Matrix(m), vbasis, vstep, .. } = &reqs[1] else { panic!("{:?}", reqs[1]) };
    assert_eq!((m[0], m[15], vbasis, *vstep), (-1.0, 0.0, &Basis::Named("catmull-rom".into()), 1));
    let Request::Patch { kind, params, .. } = &reqs[2] else { panic!() };
    assert_eq!((kind.as_str(), params.get("P").unwrap().item_count()), ("bilinear", 4));
    let Request::PatchMesh { kind, nu, uwrap, nv, vwrap, params, .. } = &reqs[3] else { panic!() };
    assert_eq!((kind.as_str(), *nu, uwrap.as_str(), *nv, vwrap.as_str()), ("bicubic", 4, "nonperiodic", 4, "periodic"));
    assert_eq!(params.get("Pw").unwrap().item_count(), 16);
    let Request::NuPatch { nu, uorder, uknot, umin, umax, nv, vorder, vknot, vmin, vmax, params, .. } = &reqs[4] else {
        panic!()
    };
    assert_eq!((*nu, *uorder, uknot.as_slice(), *umin, *umax), (2, 2, &[0.0, 0.0, 1.0, 1.0][..], 0.0, 1.0));
    assert_eq!((*nv, *vorder, vknot.len(), *vmin, *vmax), (2, 2, 4, 0.0, 1.0));
    assert_eq!(params.get("Pw").unwrap().item_count(), 4);
    assert_eq!(
        show(&reqs[5]),
        "TrimCurve { ncurves: [1], order: [2], knot: [0.0, 0.0, 1.0, 1.0], min: [0.0], max: [1.0], n: [2], \
         u: [0.0, 1.0], v: [0.0, 1.0], w: [1.0, 1.0] }"
    );
}

#[test]
fn points_curves_blobby_subdivision_procedural_geometry() {
    let reqs = record(
        "Points \"P\" [0 0 0 1 1 1] \"constantwidth\" [0.1]\n\
         Curves \"cubic\" [4] \"nonperiodic\" \"P\" [0 0 0 1 1 0 2 1 0 3 0 0] \"width\" [0.1 0.1]\n\
         Blobby 2 [1001 0 1001 16 0 2 0 1] [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 0 0 0 0 1 0 0 0 0 1 0 1 0 0 1] [] \n\
         SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"crease\"] [2 1] [0 1] [5] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]\n\
         SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]\n\
         Procedural \"DelayedReadArchive\" [\"tree.rib\"] [-1 1 -1 1 0 4]\n\
         Geometry \"teapot\"",
    );
    let Request::Points { params, .. } = &reqs[0] else { panic!() };
    assert_eq!((params.get("P").unwrap().item_count(), params.float("constantwidth")), (2, Some(0.1)));
    let Request::Curves { kind, nvertices, wrap, params, .. } = &reqs[1] else { panic!() };
    assert_eq!((kind.as_str(), nvertices.as_slice(), wrap.as_str()), ("cubic", &[4][..], "nonperiodic"));
    assert_eq!(params.floats("width"), Some(&[0.1, 0.1][..]));
    let Request::Blobby { nleaf, code, floats, strings, .. } = &reqs[2] else { panic!() };
    assert_eq!((*nleaf, code.len(), floats.len(), strings.len()), (2, 8, 32, 0));
    let Request::SubdivisionMesh { scheme, nvertices, vertices, tags, nargs, intargs, floatargs, params, .. } =
        &reqs[3]
    else {
        panic!()
    };
    assert_eq!(
        (scheme.as_str(), nvertices.as_slice(), vertices.as_slice()),
        ("catmull-clark", &[4][..], &[0, 1, 2, 3][..])
    );
    assert_eq!((tags.as_slice(), nargs.as_slice()), (&["crease".to_string()][..], &[2, 1][..]));
    assert_eq!((intargs.as_slice(), floatargs.as_slice()), (&[0, 1][..], &[5.0][..]));
    assert_eq!(params.get("P").unwrap().item_count(), 4);
    let Request::SubdivisionMesh { tags, nargs, intargs, floatargs, params, .. } = &reqs[4] else { panic!() };
    assert!(tags.is_empty() && nargs.is_empty() && intargs.is_empty() && floatargs.is_empty());
    assert_eq!(params.len(), 1);
    assert_eq!(
        show(&reqs[5]),
        "Procedural { name: \"DelayedReadArchive\", args: [\"tree.rib\"], bound: [-1.0, 1.0, -1.0, 1.0, 0.0, 4.0] }"
    );
    assert_eq!(show(&reqs[6]), "Geometry { kind: \"teapot\", params: ParamList { params: [] } }");
}

#[test]
fn texture_making() {
    check(
        "MakeTexture \"a.tif\" \"a.tex\" \"periodic\" \"clamp\" \"gaussian\" 2 2\n\
         MakeBump \"b.tif\" \"b.bump\" \"black\" \"black\" \"box\" 1 1\n\
         MakeLatLongEnvironment \"sky.tif\" \"sky.env\" \"gaussian\" 2 2\n\
         MakeCubeFaceEnvironment \"px\" \"nx\" \"py\" \"ny\" \"pz\" \"nz\" \"cube.env\" 95 \"gaussian\" 2 2\n\
         MakeShadow \"z.zfile\" \"z.shd\"",
        &[
            "MakeTexture { picture: \"a.tif\", texture: \"a.tex\", swrap: \"periodic\", twrap: \"clamp\", filter: \"gaussian\", swidth: 2.0, twidth: 2.0, params: ParamList { params: [] } }",
            "MakeBump { picture: \"b.tif\", texture: \"b.bump\", swrap: \"black\", twrap: \"black\", filter: \"box\", swidth: 1.0, twidth: 1.0, params: ParamList { params: [] } }",
            "MakeLatLongEnvironment { picture: \"sky.tif\", texture: \"sky.env\", filter: \"gaussian\", swidth: 2.0, twidth: 2.0, params: ParamList { params: [] } }",
            "MakeCubeFaceEnvironment { faces: [\"px\", \"nx\", \"py\", \"ny\", \"pz\", \"nz\"], texture: \"cube.env\", fov: 95.0, filter: \"gaussian\", swidth: 2.0, twidth: 2.0, params: ParamList { params: [] } }",
            "MakeShadow { picture: \"z.zfile\", texture: \"z.shd\", params: ParamList { params: [] } }",
        ],
    );
}

#[test]
fn comments_version_and_structure_lines_are_ignored() {
    let reqs = record(
        "##RenderMan RIB-Structure 1.1\n##Scene test\nversion 3.03\n# a comment\nSphere 1 -1 1 360 # trailing\n",
    );
    assert_eq!(reqs.len(), 1);
    assert_eq!(reqs[0].name(), "Sphere");
}

#[test]
fn locations_point_at_request_names() {
    let reqs = record("WorldBegin\n  Translate 1 2 3\n\tSphere 1 -1 1 360\nWorldEnd\n");
    let locs: Vec<(u32, u32)> = reqs.iter().map(|r| (r.loc().line, r.loc().col)).collect();
    assert_eq!(locs, [(1, 1), (2, 3), (3, 2), (4, 1)]);
    assert_eq!(reqs[1].loc().to_string(), "test.rib:2:3");
    assert_eq!((reqs[2].loc().start, reqs[2].loc().end), (30, 36));
}

#[test]
fn requests_need_no_line_breaks_and_may_span_lines() {
    let reqs = record("Translate 1\n 2\n 3 Rotate 90 0 0 1 Sphere\n1 -1 1 360");
    let names: Vec<&str> = reqs.iter().map(Request::name).collect();
    assert_eq!(names, ["Translate", "Rotate", "Sphere"]);
}

#[test]
fn replay_reproduces_the_requests() {
    let reqs = record(
        "Option \"searchpath\" \"shader\" [\"/s\"]\nWorldBegin\nLightSource \"pointlight\" 1 \"from\" [0 1 0]\n\
         Basis \"bezier\" 3 [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] 1\nSphere 1 -1 1 360 \"Cs\" [1 0 0]\n\
         MakeCubeFaceEnvironment \"px\" \"nx\" \"py\" \"ny\" \"pz\" \"nz\" \"cube.env\" 95 \"gaussian\" 2 2\nWorldEnd",
    );
    let mut again = Recorder::new();
    for r in &reqs {
        r.replay(&mut again).unwrap();
    }
    assert_eq!(again.requests, reqs);
}

#[test]
fn search_path_reaches_the_builder() {
    let reqs = record("Option \"searchpath\" \"shader\" [\"/a:/b\"] \"texture\" \"/t\"");
    assert_eq!(
        reqs.iter().map(show).collect::<Vec<_>>(),
        [
            "SearchPath { kind: \"shader\", paths: [\"/a\", \"/b\"] }",
            "SearchPath { kind: \"texture\", paths: [\"/t\"] }"
        ]
    );
    assert_eq!(reqs[0].name(), "Option");
}

#[test]
fn numbers_in_all_spellings() {
    let r = one("Torus 1. .5 -0 +90 2.5e2");
    assert_eq!(
        show(&r),
        "Torus { major_radius: 1.0, minor_radius: 0.5, phimin: -0.0, phimax: 90.0, thetamax: 250.0, params: ParamList { params: [] } }"
    );
    let r = one("Translate 1e-2 -1.5E+1 3E0");
    assert_eq!(show(&r), "Translate { dx: 0.01, dy: -15.0, dz: 3.0 }");
}

#[test]
fn string_escapes() {
    let r = one(r#"CoordinateSystem "a\tb\nc\\d\"e\101\60f\
g""#);
    let Request::CoordinateSystem { name, .. } = r else { panic!() };
    assert_eq!(name, "a\tb\nc\\d\"eA0fg");
}

#[test]
fn parameter_values_may_be_loose() {
    let r = one("Surface \"plastic\" \"Ks\" 0.5 \"texturename\" \"wood.tex\"");
    let Request::Surface { params, .. } = r else { panic!() };
    assert_eq!(params.get("Ks").unwrap().values, Values::Float(vec![0.5]));
    assert_eq!(params.string("texturename"), Some("wood.tex"));
}
