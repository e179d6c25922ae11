//! What one RIB frame describes, independent of the shader back end: the camera, the film, the
//! displays, the geometry placed by instances, the surface and light shader calls.

use anysl_renderers::{CameraSpec, Instance, Mesh};
use anysl_rib::{Loc, ParamList};
use glam::Mat4;
use std::collections::BTreeMap;

/// One frame of a RIB file, ready to be turned into a renderer scene.
#[derive(Clone, Debug)]
pub struct FrameDesc {
    /// The `FrameBegin` number, if the world was inside a frame block.
    pub number: Option<i32>,
    /// Position of this frame among the file's frames (0-based).
    pub index: usize,
    /// The camera (the transform current at `WorldBegin` and the projection options).
    pub camera: CameraSpec,
    /// Resolution, sampling, filter, exposure, quantization, crop window.
    pub film: Film,
    /// Where the picture goes.
    pub displays: Vec<DisplayDesc>,
    /// Depth passes to keep in memory by name (`Display name "zfile"|"shadow" "z"`): the
    /// camera-space depth of the nearest surface at each pixel centre, with the frame's camera
    /// (see [`crate::depth`]).
    pub depth_maps: Vec<String>,
    /// The tessellated primitives (object space).
    pub meshes: Vec<Mesh>,
    /// The primitives placed in the world, each with an index into `surfaces`.
    pub instances: Vec<Instance>,
    /// Per instance, its surface shader's "shader" space (the object-to-world transform
    /// current at the `Surface` request).
    pub shader_spaces: Vec<Mat4>,
    /// The distinct surface shader calls (name + parameters).
    pub surfaces: Vec<ShaderCall>,
    /// For each of `surfaces`, the displacement shader run before it (`Displacement`), if any.
    pub displacements: Vec<Option<ShaderCall>>,
    /// For each of `surfaces`, the volume shaders along the rays that reach it.
    pub volumes: Vec<VolumeCalls>,
    /// The imager shader (`Imager`), run on the filtered pixels.
    pub imager: Option<ShaderCall>,
    /// The light sources that illuminate some primitive, in the order declared.
    pub lights: Vec<LightCall>,
    /// Per instance, the lights that illuminate it: an index into `light_lists`.
    pub instance_lights: Vec<u32>,
    /// The distinct light lists of the instances, as indices into `lights` (RenderMan's
    /// per-primitive light lists: the lights on at the primitive, by `LightSource` in an
    /// enclosing attribute block or `Illuminate`).
    pub light_lists: Vec<Vec<u32>>,
    /// Named coordinate systems (`CoordinateSystem`): name → that space's object-to-world.
    pub coordinate_systems: BTreeMap<String, Mat4>,
}

/// A shader named in the scene with its parameter list.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderCall {
    /// The shader's name (`"plastic"`, or a name found as `NAME.sl` on the search path).
    pub name: String,
    /// The parameters as written.
    pub params: ParamList,
    /// The primitive variables of the primitive that can bind to shader parameters: those of
    /// one value for the whole primitive (constant class, or uniform on a one-face primitive)
    /// whose names are not geometry (`P`, `N`, `Cs`, `Os`, `s`, `t`, `st`, …). A shader
    /// parameter of the same name takes the value, overriding `params` (RenderMan's rule);
    /// other names are not the shader's business and are dropped silently.
    pub primvars: ParamList,
    /// Where the request is.
    pub loc: Option<Loc>,
}

impl ShaderCall {
    /// Whether two calls name the same shader with the same parameter values (locations
    /// aside).
    #[must_use]
    pub fn same_as(&self, other: &Self) -> bool {
        let same = |a: &ParamList, b: &ParamList| {
            a.params.len() == b.params.len()
                && a.params
                    .iter()
                    .zip(&b.params)
                    .all(|(a, b)| a.name == b.name && a.decl == b.decl && a.values == b.values)
        };
        self.name == other.name && same(&self.params, &other.params) && same(&self.primvars, &other.primvars)
    }

    /// The primitive variables of `params` (a primitive's parameter list) that may bind to a
    /// shader parameter (see [`ShaderCall::primvars`]).
    #[must_use]
    pub fn binding_primvars(params: &ParamList) -> ParamList {
        const GEOMETRY: &[&str] = &["P", "Pw", "Pz", "N", "Np", "Ng", "Cs", "Os", "s", "t", "st", "u", "v"];
        let mut out = ParamList::new();
        for p in &params.params {
            let one = match p.decl.class {
                anysl_rib::Class::Constant => true,
                anysl_rib::Class::Uniform => p.values.len() == p.decl.values_per_item(),
                _ => false,
            };
            if one && !GEOMETRY.contains(&p.name.as_str()) {
                out.params.push(p.clone());
            }
        }
        out
    }
}

/// The volume shaders of a surface (attributes `Atmosphere`, `Interior`, `Exterior`; each
/// absent when not given or given as `"null"`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VolumeCalls {
    /// Along camera rays (and traced rays outside an object without an exterior).
    pub atmosphere: Option<ShaderCall>,
    /// Along traced rays that reach the surface from its inside (its back).
    pub interior: Option<ShaderCall>,
    /// Along traced rays that reach the surface from its outside (its front).
    pub exterior: Option<ShaderCall>,
}

impl VolumeCalls {
    /// Whether the two name the same shaders with the same parameters.
    #[must_use]
    pub fn same_as(&self, other: &Self) -> bool {
        let same = |a: &Option<ShaderCall>, b: &Option<ShaderCall>| match (a, b) {
            (None, None) => true,
            (Some(a), Some(b)) => a.same_as(b),
            _ => false,
        };
        same(&self.atmosphere, &other.atmosphere)
            && same(&self.interior, &other.interior)
            && same(&self.exterior, &other.exterior)
    }
}

/// The shader call of a shader request (`Displacement`, `Atmosphere`, `Imager`, …): none for
/// `"null"`.
#[must_use]
pub fn shader_call(loc: &Loc, name: &str, params: &ParamList) -> Option<ShaderCall> {
    (name != "null").then(|| ShaderCall {
        name: name.to_string(),
        params: params.clone(),
        primvars: ParamList::new(),
        loc: Some(loc.clone()),
    })
}

/// A light source: its shader call and the transform current at the `LightSource` request
/// (shader space to world), which places `from` and `to`.
#[derive(Clone, Debug, PartialEq)]
pub struct LightCall {
    /// The shader call.
    pub shader: ShaderCall,
    /// Shader space to world.
    pub transform: Mat4,
}

/// A `PixelFilter` kernel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FilterKind {
    /// Constant over the support.
    Box,
    /// Linear falloff to zero at the support's edge.
    Triangle,
    /// The Catmull-Rom cubic over the support (negative lobes).
    CatmullRom,
    /// `exp(-2 (2x/w)²)`, RenderMan's `RiGaussianFilter`.
    Gaussian,
    /// Windowed `sinc`.
    Sinc,
}

/// Pixel filter with its total widths (the support is `±width/2` pixels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelFilter {
    /// The kernel.
    pub kind: FilterKind,
    /// Total width in x, pixels.
    pub xwidth: f32,
    /// Total width in y, pixels.
    pub ywidth: f32,
}

/// `Quantize "rgba" one min max dither`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quantize {
    /// The value 1.0 maps to.
    pub one: i32,
    /// Smallest output value.
    pub min: i32,
    /// Largest output value.
    pub max: i32,
    /// Amplitude of the random dither added before rounding.
    pub dither: f32,
}

impl Quantize {
    /// RenderMan's default for 8-bit output: `255 0 255 0.5`.
    pub const EIGHT_BIT: Self = Self { one: 255, min: 0, max: 255, dither: 0.5 };
}

/// Everything the film does with the samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Film {
    /// Image width (after `--size`).
    pub xres: u32,
    /// Image height.
    pub yres: u32,
    /// `Format`'s pixel aspect ratio.
    pub pixel_aspect: f32,
    /// `CropWindow [xmin xmax ymin ymax]` in fractions of the image.
    pub crop: [f32; 4],
    /// Stratified samples per pixel in x and y.
    pub samples: [u32; 2],
    /// The reconstruction filter.
    pub filter: PixelFilter,
    /// `Exposure` gain.
    pub gain: f32,
    /// `Exposure` gamma.
    pub gamma: f32,
    /// Colour quantization.
    pub quantize: Quantize,
}

impl Film {
    /// The pixel rectangle the crop window selects: `[x0, x1) × [y0, y1)` (RenderMan rounds
    /// `ceil(xres·xmin)` … `ceil(xres·xmax) − 1`).
    #[must_use]
    pub fn crop_pixels(&self) -> [u32; 4] {
        let [x0, x1, y0, y1] = self.crop;
        let px = |f: f32, n: u32| ((f * n as f32).ceil().max(0.0) as u32).min(n);
        [px(x0, self.xres), px(x1, self.xres), px(y0, self.yres), px(y1, self.yres)]
    }
}

/// Output file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DisplayFormat {
    /// TIFF (`"file"`, `"tiff"`).
    Tiff,
    /// PNG (`"png"`, and `"framebuffer"` written as a PNG).
    Png,
}

/// One `Display` target.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplayDesc {
    /// The file name (without the `+`), with an extension added when it had none.
    pub file: String,
    /// The format written.
    pub format: DisplayFormat,
    /// With an alpha channel (coverage).
    pub alpha: bool,
}
