//! The request table: one line per RIB request generates the [`RibBuilder`] method, the
//! [`Request`] variant, the [`Recorder`] body, the replay and the reader's argument parsing, so
//! the four cannot drift apart.

// The RIB requests have as many arguments as the RenderMan Interface gives them.
#![allow(clippy::too_many_arguments)]

use crate::args::{Args, Bad};
use crate::builder::{Basis, BorrowArg, BuildError, Handle, Matrix, OwnArg};
use crate::param::ParamList;
use crate::source::Loc;
use std::path::PathBuf;

/// What the reader's generated dispatch did with a request.
pub(crate) enum Dispatch {
    /// Not a request in the table.
    Unknown,
    /// Bad arguments, already reported.
    Bad,
    /// Arguments parsed; the builder's answer.
    Built(Result<(), BuildError>),
}

macro_rules! requests {
    ($(
        $(#[doc = $doc:literal])*
        $Variant:ident = $rib:literal, $method:ident { $($arg:ident : $bty:ty => $oty:ty as $shape:ident),* $(,)? }
    )*) => {
        /// Receives requests from the reader, one method per RIB request, each with its location
        /// (the request name in the file).
        ///
        /// Every method has a default body that returns [`BuildError::unsupported`], so a builder
        /// implements only what it supports; the reader turns the rest into one warning per
        /// request name. `Declare`, `ReadArchive`, `ArchiveBegin`/`ArchiveEnd` and `version` are
        /// handled by the reader and never reach the builder; `Option "searchpath"` reaches it
        /// as [`RibBuilder::search_path`].
        pub trait RibBuilder {
            $(
                $(#[doc = $doc])*
                #[allow(unused_variables)]
                fn $method(&mut self, loc: &Loc, $($arg: $bty),*) -> Result<(), BuildError> {
                    Err(BuildError::unsupported())
                }
            )*
        }

        /// One recorded request with owned arguments (see [`Recorder`]).
        #[derive(Clone, Debug, PartialEq)]
        pub enum Request {
            $(
                $(#[doc = $doc])*
                $Variant {
                    /// Where the request is.
                    loc: Loc,
                    $(
                        #[doc = concat!("The `", stringify!($arg), "` argument.")]
                        $arg: $oty,
                    )*
                },
            )*
        }

        impl Request {
            /// The request's location.
            #[must_use]
            pub fn loc(&self) -> &Loc {
                match self {
                    $(Self::$Variant { loc, .. } => loc,)*
                }
            }

            /// The RIB request name (`Option` for a search path).
            #[must_use]
            pub fn name(&self) -> &'static str {
                match self {
                    $(Self::$Variant { .. } => if $rib.is_empty() { "Option" } else { $rib },)*
                }
            }

            /// Calls the matching builder method with this request's arguments.
            pub fn replay<B: RibBuilder + ?Sized>(&self, builder: &mut B) -> Result<(), BuildError> {
                match self {
                    $(Self::$Variant { loc, $($arg),* } => builder.$method(loc, $(BorrowArg::borrow_arg($arg)),*),)*
                }
            }
        }

        impl RibBuilder for Recorder {
            $(
                fn $method(&mut self, loc: &Loc, $($arg: $bty),*) -> Result<(), BuildError> {
                    self.requests.push(Request::$Variant { loc: loc.clone(), $($arg: OwnArg::own($arg)),* });
                    Ok(())
                }
            )*
        }

        /// Parses the arguments of request `name` and calls the builder.
        pub(crate) fn dispatch<B: RibBuilder + ?Sized>(
            builder: &mut B,
            name: &str,
            loc: &Loc,
            args: &mut Args<'_>,
        ) -> Dispatch {
            match name {
                $(
                    $rib if !$rib.is_empty() => {
                        args.usage = concat!($rib $(, " ", stringify!($arg))*);
                        let parsed: Result<_, Bad> = (|| {
                            $(let $arg: $oty = args.$shape(stringify!($arg))?;)*
                            args.finish()?;
                            Ok(($($arg,)*))
                        })();
                        match parsed {
                            Ok(($($arg,)*)) => Dispatch::Built(builder.$method(loc, $(BorrowArg::borrow_arg(&$arg)),*)),
                            Err(Bad) => Dispatch::Bad,
                        }
                    }
                )*
                _ => Dispatch::Unknown,
            }
        }
    };
}

/// A builder that records every request (for tests, and for builders that want the whole
/// scene before building it). Replay with [`Request::replay`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Recorder {
    /// The requests, in the order read.
    pub requests: Vec<Request>,
}

impl Recorder {
    /// An empty recorder.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

requests! {
    // ---- Blocks ----
    /// `FrameBegin frame`: starts frame number `frame`.
    FrameBegin = "FrameBegin", frame_begin { frame: i32 => i32 as int }
    /// `FrameEnd`: ends the frame.
    FrameEnd = "FrameEnd", frame_end {}
    /// `WorldBegin`: ends the options, starts the scene description.
    WorldBegin = "WorldBegin", world_begin {}
    /// `WorldEnd`: ends the scene description (render now).
    WorldEnd = "WorldEnd", world_end {}
    /// `AttributeBegin`: pushes the attributes and the transform.
    AttributeBegin = "AttributeBegin", attribute_begin {}
    /// `AttributeEnd`: pops the attributes and the transform.
    AttributeEnd = "AttributeEnd", attribute_end {}
    /// `TransformBegin`: pushes the transform.
    TransformBegin = "TransformBegin", transform_begin {}
    /// `TransformEnd`: pops the transform.
    TransformEnd = "TransformEnd", transform_end {}
    /// `SolidBegin operation`: starts a CSG solid (`primitive`, `union`, `intersection`, `difference`).
    SolidBegin = "SolidBegin", solid_begin { operation: &str => String as string }
    /// `SolidEnd`: ends a CSG solid.
    SolidEnd = "SolidEnd", solid_end {}
    /// `ObjectBegin handle`: starts recording a retained object.
    ObjectBegin = "ObjectBegin", object_begin { handle: &Handle => Handle as handle }
    /// `ObjectEnd`: ends a retained object.
    ObjectEnd = "ObjectEnd", object_end {}
    /// `ObjectInstance handle`: places a retained object.
    ObjectInstance = "ObjectInstance", object_instance { handle: &Handle => Handle as handle }
    /// `MotionBegin [times]`: the next requests are motion samples at `times`.
    MotionBegin = "MotionBegin", motion_begin { times: &[f32] => Vec<f32> as floats }
    /// `MotionEnd`: ends the motion samples.
    MotionEnd = "MotionEnd", motion_end {}

    // ---- Options ----
    /// `Format xres yres pixelaspect`: image size in pixels and pixel aspect ratio.
    Format = "Format", format { xres: i32 => i32 as int, yres: i32 => i32 as int, pixel_aspect: f32 => f32 as float }
    /// `FrameAspectRatio aspect`: width / height of the image.
    FrameAspectRatio = "FrameAspectRatio", frame_aspect_ratio { aspect: f32 => f32 as float }
    /// `ScreenWindow left right bottom top`: the screen-space window.
    ScreenWindow = "ScreenWindow", screen_window { window: &[f32; 4] => [f32; 4] as fixed }
    /// `CropWindow xmin xmax ymin ymax`: the part of the image to render, in NDC.
    CropWindow = "CropWindow", crop_window { window: &[f32; 4] => [f32; 4] as fixed }
    /// `Projection name params`: `"perspective"` (with `"fov"`), `"orthographic"`, ….
    Projection = "Projection", projection { name: &str => String as string, params: &ParamList => ParamList as params }
    /// `Clipping near far`: the clipping planes.
    Clipping = "Clipping", clipping { near: f32 => f32 as float, far: f32 => f32 as float }
    /// `ClippingPlane x y z nx ny nz`: an extra clipping plane (point and normal).
    ClippingPlane = "ClippingPlane", clipping_plane { plane: &[f32; 6] => [f32; 6] as fixed }
    /// `DepthOfField fstop focallength focaldistance`; without arguments, a pinhole (`fstop` infinite).
    DepthOfField = "DepthOfField", depth_of_field { fstop: f32 => f32 as dof, focal_length: f32 => f32 as dof, focal_distance: f32 => f32 as dof }
    /// `Shutter open close`: shutter times.
    Shutter = "Shutter", shutter { open: f32 => f32 as float, close: f32 => f32 as float }
    /// `PixelVariance variance`: the allowed pixel variance.
    PixelVariance = "PixelVariance", pixel_variance { variance: f32 => f32 as float }
    /// `PixelSamples xsamples ysamples`: samples per pixel in x and y.
    PixelSamples = "PixelSamples", pixel_samples { xsamples: f32 => f32 as float, ysamples: f32 => f32 as float }
    /// `PixelFilter name xwidth ywidth`: the reconstruction filter.
    PixelFilter = "PixelFilter", pixel_filter { name: &str => String as string, xwidth: f32 => f32 as float, ywidth: f32 => f32 as float }
    /// `Exposure gain gamma`: exposure of the output.
    Exposure = "Exposure", exposure { gain: f32 => f32 as float, gamma: f32 => f32 as float }
    /// `Imager name params`: the imager shader.
    Imager = "Imager", imager { name: &str => String as string, params: &ParamList => ParamList as params }
    /// `Quantize type one min max ditheramplitude`: quantization of `"rgba"` or `"z"`.
    Quantize = "Quantize", quantize { kind: &str => String as string, one: i32 => i32 as int, min: i32 => i32 as int, max: i32 => i32 as int, dither_amplitude: f32 => f32 as float }
    /// `Display name type mode params`: where the image goes (`"file"`, `"framebuffer"`, …).
    Display = "Display", display { name: &str => String as string, kind: &str => String as string, mode: &str => String as string, params: &ParamList => ParamList as params }
    /// `Hider type params`: the hidden-surface algorithm.
    Hider = "Hider", hider { kind: &str => String as string, params: &ParamList => ParamList as params }
    /// `ColorSamples [nRGB] [RGBn]`: colour sample conversion matrices.
    ColorSamples = "ColorSamples", color_samples { n_rgb: &[f32] => Vec<f32> as floats, rgb_n: &[f32] => Vec<f32> as floats }
    /// `RelativeDetail relativedetail`: scales level-of-detail ranges.
    RelativeDetail = "RelativeDetail", relative_detail { relative_detail: f32 => f32 as float }
    /// `Option name params`: an implementation-specific option (not `"searchpath"`, see `search_path`).
    Option = "Option", option { name: &str => String as string, params: &ParamList => ParamList as params }
    /// `Option "searchpath" kind [paths]`: the search path of `kind` (`"shader"`, `"texture"`, …)
    /// is now `paths`, with `@` and `&` already expanded. The default body ignores it.
    SearchPath = "", search_path { kind: &str => String as string, paths: &[PathBuf] => Vec<PathBuf> as none }
    /// `ErrorHandler name`: `"ignore"`, `"print"` or `"abort"`.
    ErrorHandler = "ErrorHandler", error_handler { name: &str => String as string }

    // ---- Attributes ----
    /// `Attribute name params`: an implementation-specific attribute.
    Attribute = "Attribute", attribute { name: &str => String as string, params: &ParamList => ParamList as params }
    /// `Color [r g b]` or `Color r g b`: the surface colour.
    Color = "Color", color { rgb: &[f32; 3] => [f32; 3] as fixed }
    /// `Opacity [r g b]` or `Opacity r g b`: the surface opacity.
    Opacity = "Opacity", opacity { rgb: &[f32; 3] => [f32; 3] as fixed }
    /// `TextureCoordinates s1 t1 s2 t2 s3 t3 s4 t4`: texture coordinates at the corners of a patch.
    TextureCoordinates = "TextureCoordinates", texture_coordinates { st: &[f32; 8] => [f32; 8] as fixed }
    /// `LightSource name handle params`: a light shader instance, switched on.
    LightSource = "LightSource", light_source { name: &str => String as string, handle: &Handle => Handle as handle, params: &ParamList => ParamList as params }
    /// `AreaLightSource name handle params`: an area light; the following geometry emits.
    AreaLightSource = "AreaLightSource", area_light_source { name: &str => String as string, handle: &Handle => Handle as handle, params: &ParamList => ParamList as params }
    /// `Illuminate handle onoff`: switches a light on or off for the following geometry.
    Illuminate = "Illuminate", illuminate { handle: &Handle => Handle as handle, on: bool => bool as boolean }
    /// `Surface name params`: the surface shader.
    Surface = "Surface", surface { name: &str => String as string, params: &ParamList => ParamList as params }
    /// `Displacement name params`: the displacement shader.
    Displacement = "Displacement", displacement { name: &str => String as string, params: &ParamList => ParamList as params }
    /// `Atmosphere name params`: the atmosphere (volume) shader.
    Atmosphere = "Atmosphere", atmosphere { name: &str => String as string, params: &ParamList => ParamList as params }
    /// `Interior name params`: the interior volume shader.
    Interior = "Interior", interior { name: &str => String as string, params: &ParamList => ParamList as params }
    /// `Exterior name params`: the exterior volume shader.
    Exterior = "Exterior", exterior { name: &str => String as string, params: &ParamList => ParamList as params }
    /// `Deformation name params`: the deformation shader.
    Deformation = "Deformation", deformation { name: &str => String as string, params: &ParamList => ParamList as params }
    /// `ShadingRate size`: shading rate in pixels.
    ShadingRate = "ShadingRate", shading_rate { size: f32 => f32 as float }
    /// `ShadingInterpolation type`: `"constant"` or `"smooth"`.
    ShadingInterpolation = "ShadingInterpolation", shading_interpolation { kind: &str => String as string }
    /// `Matte onoff`: the following geometry is a matte (holdout).
    Matte = "Matte", matte { on: bool => bool as boolean }
    /// `Bound [xmin xmax ymin ymax zmin zmax]`: a bound on the following geometry.
    Bound = "Bound", bound { bound: &[f32; 6] => [f32; 6] as fixed }
    /// `Detail [xmin xmax ymin ymax zmin zmax]`: the bound used for level of detail.
    Detail = "Detail", detail { bound: &[f32; 6] => [f32; 6] as fixed }
    /// `DetailRange minvisible lowertransition uppertransition maxvisible`: level-of-detail range.
    DetailRange = "DetailRange", detail_range { range: &[f32; 4] => [f32; 4] as fixed }
    /// `GeometricApproximation type value`: e.g. `"flatness" 0.5`.
    GeometricApproximation = "GeometricApproximation", geometric_approximation { kind: &str => String as string, value: f32 => f32 as float }
    /// `GeometricRepresentation type`: `"primitive"`, `"points"`, `"lines"`, ….
    GeometricRepresentation = "GeometricRepresentation", geometric_representation { kind: &str => String as string }
    /// `Orientation orientation`: `"outside"`, `"inside"`, `"lh"` or `"rh"`.
    Orientation = "Orientation", orientation { orientation: &str => String as string }
    /// `ReverseOrientation`: flips the orientation.
    ReverseOrientation = "ReverseOrientation", reverse_orientation {}
    /// `Sides sides`: 1 or 2 sided.
    Sides = "Sides", sides { sides: i32 => i32 as int }
    /// `Basis ubasis ustep vbasis vstep`: patch bases, by name or 16 numbers.
    Basis = "Basis", basis { ubasis: &Basis => Basis as basis, ustep: i32 => i32 as int, vbasis: &Basis => Basis as basis, vstep: i32 => i32 as int }
    /// `TrimCurve [ncurves] [order] [knot] [min] [max] [n] [u] [v] [w]`: trim loops for NURBS.
    TrimCurve = "TrimCurve", trim_curve {
        ncurves: &[i32] => Vec<i32> as ints, order: &[i32] => Vec<i32> as ints, knot: &[f32] => Vec<f32> as floats,
        min: &[f32] => Vec<f32> as floats, max: &[f32] => Vec<f32> as floats, n: &[i32] => Vec<i32> as ints,
        u: &[f32] => Vec<f32> as floats, v: &[f32] => Vec<f32> as floats, w: &[f32] => Vec<f32> as floats,
    }

    // ---- Transforms ----
    /// `Identity`: the current transform becomes the identity.
    Identity = "Identity", identity {}
    /// `Transform [16 numbers]`: the current transform becomes `matrix`.
    Transform = "Transform", transform { matrix: &Matrix => Matrix as fixed }
    /// `ConcatTransform [16 numbers]`: premultiplies the current transform by `matrix`.
    ConcatTransform = "ConcatTransform", concat_transform { matrix: &Matrix => Matrix as fixed }
    /// `Perspective fov`: concatenates a perspective projection.
    Perspective = "Perspective", perspective { fov: f32 => f32 as float }
    /// `Translate dx dy dz`.
    Translate = "Translate", translate { dx: f32 => f32 as float, dy: f32 => f32 as float, dz: f32 => f32 as float }
    /// `Rotate angle dx dy dz`: rotation by `angle` degrees about an axis.
    Rotate = "Rotate", rotate { angle: f32 => f32 as float, dx: f32 => f32 as float, dy: f32 => f32 as float, dz: f32 => f32 as float }
    /// `Scale sx sy sz`.
    Scale = "Scale", scale { sx: f32 => f32 as float, sy: f32 => f32 as float, sz: f32 => f32 as float }
    /// `Skew angle dx1 dy1 dz1 dx2 dy2 dz2` (loose or as one array of 7).
    Skew = "Skew", skew { skew: &[f32; 7] => [f32; 7] as fixed }
    /// `CoordinateSystem name`: names the current transform.
    CoordinateSystem = "CoordinateSystem", coordinate_system { name: &str => String as string }
    /// `CoordSysTransform name`: the current transform becomes the named one.
    CoordSysTransform = "CoordSysTransform", coord_sys_transform { name: &str => String as string }

    // ---- Geometry ----
    /// `Polygon params`: a convex polygon.
    Polygon = "Polygon", polygon { params: &ParamList => ParamList as params }
    /// `GeneralPolygon [nverts] params`: a polygon with holes, `nverts` per loop.
    GeneralPolygon = "GeneralPolygon", general_polygon { nverts: &[i32] => Vec<i32> as ints, params: &ParamList => ParamList as params }
    /// `PointsPolygons [nverts] [verts] params`: a polygon mesh.
    PointsPolygons = "PointsPolygons", points_polygons { nverts: &[i32] => Vec<i32> as ints, verts: &[i32] => Vec<i32> as ints, params: &ParamList => ParamList as params }
    /// `PointsGeneralPolygons [nloops] [nverts] [verts] params`: a mesh of polygons with holes.
    PointsGeneralPolygons = "PointsGeneralPolygons", points_general_polygons { nloops: &[i32] => Vec<i32> as ints, nverts: &[i32] => Vec<i32> as ints, verts: &[i32] => Vec<i32> as ints, params: &ParamList => ParamList as params }
    /// `Patch type params`: one `"bilinear"` or `"bicubic"` patch.
    Patch = "Patch", patch { kind: &str => String as string, params: &ParamList => ParamList as params }
    /// `PatchMesh type nu uwrap nv vwrap params`: a mesh of patches (wrap `"periodic"`/`"nonperiodic"`).
    PatchMesh = "PatchMesh", patch_mesh { kind: &str => String as string, nu: i32 => i32 as int, uwrap: &str => String as string, nv: i32 => i32 as int, vwrap: &str => String as string, params: &ParamList => ParamList as params }
    /// `NuPatch nu uorder [uknot] umin umax nv vorder [vknot] vmin vmax params`: a NURBS patch.
    NuPatch = "NuPatch", nu_patch {
        nu: i32 => i32 as int, uorder: i32 => i32 as int, uknot: &[f32] => Vec<f32> as floats, umin: f32 => f32 as float, umax: f32 => f32 as float,
        nv: i32 => i32 as int, vorder: i32 => i32 as int, vknot: &[f32] => Vec<f32> as floats, vmin: f32 => f32 as float, vmax: f32 => f32 as float,
        params: &ParamList => ParamList as params,
    }
    /// `Sphere radius zmin zmax thetamax params`.
    Sphere = "Sphere", sphere { radius: f32 => f32 as float, zmin: f32 => f32 as float, zmax: f32 => f32 as float, thetamax: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `Cone height radius thetamax params`.
    Cone = "Cone", cone { height: f32 => f32 as float, radius: f32 => f32 as float, thetamax: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `Cylinder radius zmin zmax thetamax params`.
    Cylinder = "Cylinder", cylinder { radius: f32 => f32 as float, zmin: f32 => f32 as float, zmax: f32 => f32 as float, thetamax: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `Hyperboloid x1 y1 z1 x2 y2 z2 thetamax params`: the line from `point1` to `point2` swept about z.
    Hyperboloid = "Hyperboloid", hyperboloid { point1: &[f32; 3] => [f32; 3] as fixed, point2: &[f32; 3] => [f32; 3] as fixed, thetamax: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `Paraboloid rmax zmin zmax thetamax params`.
    Paraboloid = "Paraboloid", paraboloid { rmax: f32 => f32 as float, zmin: f32 => f32 as float, zmax: f32 => f32 as float, thetamax: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `Disk height radius thetamax params`.
    Disk = "Disk", disk { height: f32 => f32 as float, radius: f32 => f32 as float, thetamax: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `Torus majorradius minorradius phimin phimax thetamax params`.
    Torus = "Torus", torus { major_radius: f32 => f32 as float, minor_radius: f32 => f32 as float, phimin: f32 => f32 as float, phimax: f32 => f32 as float, thetamax: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `Points params`: a point cloud (`"P"`, `"width"`/`"constantwidth"`).
    Points = "Points", points { params: &ParamList => ParamList as params }
    /// `Curves type [nvertices] wrap params`: `"linear"` or `"cubic"` curves.
    Curves = "Curves", curves { kind: &str => String as string, nvertices: &[i32] => Vec<i32> as ints, wrap: &str => String as string, params: &ParamList => ParamList as params }
    /// `Blobby nleaf [code] [floats] [strings] params`: an implicit surface.
    Blobby = "Blobby", blobby { nleaf: i32 => i32 as int, code: &[i32] => Vec<i32> as ints, floats: &[f32] => Vec<f32> as floats, strings: &[String] => Vec<String> as strings, params: &ParamList => ParamList as params }
    /// `SubdivisionMesh scheme [nvertices] [vertices] [tags] [nargs] [intargs] [floatargs] params`
    /// (the tag arrays may be left out together).
    SubdivisionMesh = "SubdivisionMesh", subdivision_mesh {
        scheme: &str => String as string, nvertices: &[i32] => Vec<i32> as ints, vertices: &[i32] => Vec<i32> as ints,
        tags: &[String] => Vec<String> as opt_strings, nargs: &[i32] => Vec<i32> as opt_ints, intargs: &[i32] => Vec<i32> as opt_ints,
        floatargs: &[f32] => Vec<f32> as opt_floats, params: &ParamList => ParamList as params,
    }
    /// `Procedural name [args] [bound]`: `"DelayedReadArchive"`, `"RunProgram"`, `"DynamicLoad"`.
    Procedural = "Procedural", procedural { name: &str => String as string, args: &[String] => Vec<String> as strings, bound: &[f32; 6] => [f32; 6] as fixed }
    /// `Geometry type params`: implementation-specific geometry, e.g. `"teapot"`.
    Geometry = "Geometry", geometry { kind: &str => String as string, params: &ParamList => ParamList as params }

    // ---- Textures ----
    /// `MakeTexture picture texture swrap twrap filter swidth twidth params`.
    MakeTexture = "MakeTexture", make_texture { picture: &str => String as string, texture: &str => String as string, swrap: &str => String as string, twrap: &str => String as string, filter: &str => String as string, swidth: f32 => f32 as float, twidth: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `MakeBump picture texture swrap twrap filter swidth twidth params`.
    MakeBump = "MakeBump", make_bump { picture: &str => String as string, texture: &str => String as string, swrap: &str => String as string, twrap: &str => String as string, filter: &str => String as string, swidth: f32 => f32 as float, twidth: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `MakeLatLongEnvironment picture texture filter swidth twidth params`.
    MakeLatLongEnvironment = "MakeLatLongEnvironment", make_lat_long_environment { picture: &str => String as string, texture: &str => String as string, filter: &str => String as string, swidth: f32 => f32 as float, twidth: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `MakeCubeFaceEnvironment px nx py ny pz nz texture fov filter swidth twidth params`.
    MakeCubeFaceEnvironment = "MakeCubeFaceEnvironment", make_cube_face_environment { faces: &[String; 6] => [String; 6] as fixed_strings, texture: &str => String as string, fov: f32 => f32 as float, filter: &str => String as string, swidth: f32 => f32 as float, twidth: f32 => f32 as float, params: &ParamList => ParamList as params }
    /// `MakeShadow picture texture params`.
    MakeShadow = "MakeShadow", make_shadow { picture: &str => String as string, texture: &str => String as string, params: &ParamList => ParamList as params }
}
