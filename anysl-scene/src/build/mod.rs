//! The graphics state of a RIB file and the frames it describes: [`SceneBuilder`] implements
//! [`anysl_rib::RibBuilder`] and collects one [`FrameDesc`] per world block.
//!
//! ```
//! use anysl_scene::build::{BuildOptions, SceneBuilder};
//!
//! let rib = "Format 32 24 1 Projection \"perspective\" \"fov\" 40\n\
//!            WorldBegin Translate 0 0 5 Surface \"matte\" Sphere 1 -1 1 360 WorldEnd";
//! let mut b = SceneBuilder::new(BuildOptions::default());
//! anysl_rib::parse_str("t.rib", rib, &mut b, &anysl_rib::Options::new()).unwrap();
//! let frames = b.finish();
//! assert_eq!(frames.len(), 1);
//! assert_eq!((frames[0].film.xres, frames[0].surfaces[0].name.as_str()), (32, "matte"));
//! ```

mod frame;
mod place;
mod textures;

pub use frame::{
    shader_call, DisplayDesc, DisplayFormat, Film, FilterKind, FrameDesc, LightCall, PixelFilter, Quantize, ShaderCall,
    VolumeCalls,
};

use crate::geom::{self, Detail, PatchBasis};
use anysl_renderers::{CameraSpec, Instance, Mesh, Projection};
use anysl_rib::{Basis, BuildError, Handle, Loc, Matrix, ParamList, RibBuilder};
use anysl_rt::texture::MapKind;
use glam::{Mat4, Vec3, Vec4};
use std::collections::{BTreeMap, HashMap};
use std::path::PathBuf;

/// Settings of a build that do not come from the RIB file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildOptions {
    /// Render at this width, keeping the frame's aspect (`--size`).
    pub width: Option<u32>,
    /// Name of the default output when a frame has no `Display` (without extension).
    pub default_output: Option<String>,
}

/// The options state (saved by `FrameBegin`, restored by `FrameEnd`).
#[derive(Clone, Debug)]
struct OptionState {
    xres: u32,
    yres: u32,
    pixel_aspect: f32,
    frame_aspect: Option<f32>,
    screen_window: Option<[f32; 4]>,
    crop: [f32; 4],
    perspective: Option<f32>,
    clipping: [f32; 2],
    samples: [f32; 2],
    filter: PixelFilter,
    gain: f32,
    gamma: f32,
    quantize: Quantize,
    displays: Vec<DisplayDesc>,
    imager: Option<ShaderCall>,
    /// Depth passes: `Display` names of type `"zfile"`/`"shadow"`, mode `"z"`.
    depth_maps: Vec<String>,
    /// The transform current before `WorldBegin` (world-to-camera, built up by the camera
    /// requests).
    camera: Mat4,
}

impl Default for OptionState {
    fn default() -> Self {
        Self {
            xres: 640,
            yres: 480,
            pixel_aspect: 1.0,
            frame_aspect: None,
            screen_window: None,
            crop: [0.0, 1.0, 0.0, 1.0],
            perspective: None,
            clipping: [f32::EPSILON, f32::INFINITY],
            samples: [2.0, 2.0],
            filter: PixelFilter { kind: FilterKind::Gaussian, xwidth: 2.0, ywidth: 2.0 },
            gain: 1.0,
            gamma: 1.0,
            quantize: Quantize::EIGHT_BIT,
            displays: Vec::new(),
            imager: None,
            depth_maps: Vec::new(),
            camera: Mat4::IDENTITY,
        }
    }
}

/// The attribute state (saved by `AttributeBegin`).
#[derive(Clone, Debug)]
struct Attributes {
    color: [f32; 3],
    opacity: [f32; 3],
    two_sided: bool,
    /// Orientation "inside" (after `ReverseOrientation`s), relative to the current transform.
    inside: bool,
    surface: Option<ShaderCall>,
    /// The displacement shader (`Displacement`).
    displacement: Option<ShaderCall>,
    /// The volume shaders (`Atmosphere`, `Interior`, `Exterior`).
    volumes: VolumeCalls,
    /// Shader space: the object-to-world transform current at `Surface`.
    shader_space: Mat4,
    basis: (Basis, i32, Basis, i32),
    /// `TextureCoordinates`: s,t at the four corners of the unit parameter square.
    st: Option<[f32; 8]>,
    /// The light handles switched on, by index into the builder's lights.
    lights_on: Vec<bool>,
}

impl Default for Attributes {
    fn default() -> Self {
        let bezier = Basis::Named("bezier".into());
        Self {
            color: [1.0; 3],
            opacity: [1.0; 3],
            two_sided: true,
            inside: false,
            surface: None,
            displacement: None,
            volumes: VolumeCalls::default(),
            shader_space: Mat4::IDENTITY,
            basis: (bezier.clone(), 3, bezier, 3),
            st: None,
            lights_on: Vec::new(),
        }
    }
}

/// A primitive recorded inside `ObjectBegin`/`ObjectEnd`: its mesh, its transform relative to
/// the object's and the attributes it was defined with.
#[derive(Clone, Debug)]
struct ObjectPart {
    mesh: usize,
    relative: Mat4,
    attrs: Attributes,
    primvars: ParamList,
}

/// Where the reader is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Block {
    Options,
    World,
}

/// The builder: graphics state plus the frames made so far.
pub struct SceneBuilder {
    opts: BuildOptions,
    options: OptionState,
    saved_options: Vec<(OptionState, Mat4)>,
    frame_number: Option<i32>,
    block: Block,
    ctm: Mat4,
    attrs: Attributes,
    stack: Vec<(Mat4, Option<Attributes>)>,
    coordinate_systems: BTreeMap<String, Mat4>,
    // World state.
    meshes: Vec<Mesh>,
    instances: Vec<Instance>,
    shader_spaces: Vec<Mat4>,
    surfaces: Vec<ShaderCall>,
    displacements: Vec<Option<ShaderCall>>,
    volumes: Vec<VolumeCalls>,
    lights: Vec<LightCall>,
    light_used: Vec<bool>,
    /// Per instance, its light list (an index into `light_lists`).
    instance_lights: Vec<u32>,
    /// The distinct light lists of the instances (indices into `lights`), interned.
    light_lists: Vec<Vec<u32>>,
    light_list_index: HashMap<Vec<u32>, u32>,
    light_handles: HashMap<Handle, usize>,
    objects: HashMap<Handle, Vec<ObjectPart>>,
    recording: Option<(Handle, Mat4, Vec<ObjectPart>)>,
    world_to_camera: Mat4,
    /// Shader search path set by `Option "searchpath" "shader"`.
    pub shader_paths: Vec<PathBuf>,
    frames: Vec<FrameDesc>,
    warned_options: Vec<String>,
}

fn unit(x: f32) -> Result<f32, BuildError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(BuildError::error(format!("{x} is not a finite number")))
    }
}

/// A RIB matrix (row-major, row vectors) as a glam matrix (column vectors): the same numbers.
fn rib_matrix(m: &Matrix) -> Mat4 {
    Mat4::from_cols_array(m)
}

/// RenderMan's `Skew`: points move parallel to `d2` so that `d1` turns by `angle` degrees
/// towards `d2`.
fn skew_matrix(s: &[f32; 7]) -> Result<Mat4, BuildError> {
    let (angle, d1, d2) = (s[0].to_radians(), Vec3::new(s[1], s[2], s[3]), Vec3::new(s[4], s[5], s[6]));
    let b = d2.try_normalize().ok_or_else(|| BuildError::error("Skew: the second vector is zero"))?;
    let perp = d1 - b * d1.dot(b);
    let a = perp.try_normalize().ok_or_else(|| BuildError::error("Skew: the two vectors are parallel"))?;
    let (alpha, beta) = (d1.dot(a), d1.dot(b));
    let theta = beta.atan2(alpha) + angle;
    if theta.abs() >= std::f32::consts::FRAC_PI_2 {
        return Err(BuildError::error(format!("Skew: an angle of {} degrees is degenerate", s[0])));
    }
    let k = theta.tan() - beta / alpha;
    let col = |j: usize| {
        let mut c = Vec4::ZERO;
        c[j] = 1.0;
        c + (b * k * a[j]).extend(0.0)
    };
    Ok(Mat4::from_cols(col(0), col(1), col(2), Vec4::W))
}

/// RenderMan's `Perspective fov`: the projection onto z = 1 (homogeneous).
fn perspective_matrix(fov: f32) -> Mat4 {
    let inv = 1.0 / (fov.to_radians() * 0.5).tan();
    Mat4::from_cols(
        Vec4::new(inv, 0.0, 0.0, 0.0),
        Vec4::new(0.0, inv, 0.0, 0.0),
        Vec4::new(0.0, 0.0, 1.0, 1.0),
        Vec4::new(0.0, 0.0, -1.0, 0.0),
    )
}

impl SceneBuilder {
    /// A builder at the start of a file.
    #[must_use]
    pub fn new(opts: BuildOptions) -> Self {
        Self {
            opts,
            options: OptionState::default(),
            saved_options: Vec::new(),
            frame_number: None,
            block: Block::Options,
            ctm: Mat4::IDENTITY,
            attrs: Attributes::default(),
            stack: Vec::new(),
            coordinate_systems: BTreeMap::new(),
            meshes: Vec::new(),
            instances: Vec::new(),
            shader_spaces: Vec::new(),
            surfaces: Vec::new(),
            displacements: Vec::new(),
            volumes: Vec::new(),
            lights: Vec::new(),
            light_used: Vec::new(),
            instance_lights: Vec::new(),
            light_lists: Vec::new(),
            light_list_index: HashMap::new(),
            light_handles: HashMap::new(),
            objects: HashMap::new(),
            recording: None,
            world_to_camera: Mat4::IDENTITY,
            shader_paths: Vec::new(),
            frames: Vec::new(),
            warned_options: Vec::new(),
        }
    }

    /// The frames described, in order.
    #[must_use]
    pub fn finish(self) -> Vec<FrameDesc> {
        self.frames
    }

    fn concat(&mut self, m: Mat4) {
        self.ctm *= m;
    }

    /// The resolution after `--size`.
    fn resolution(&self) -> (u32, u32) {
        let (x, y) = (self.options.xres.max(1), self.options.yres.max(1));
        match self.opts.width {
            Some(w) => (w, ((w as f64 * y as f64 / x as f64).round() as u32).max(1)),
            None => (x, y),
        }
    }

    fn frame_aspect(&self) -> f32 {
        let (x, y) = (self.options.xres.max(1) as f32, self.options.yres.max(1) as f32);
        self.options.frame_aspect.unwrap_or(x * self.options.pixel_aspect / y)
    }

    fn screen_window(&self) -> [f32; 4] {
        self.options.screen_window.unwrap_or_else(|| {
            let a = self.frame_aspect();
            if a >= 1.0 {
                [-a, a, -1.0, 1.0]
            } else {
                [-1.0, 1.0, -1.0 / a, 1.0 / a]
            }
        })
    }

    fn camera_spec(&self) -> CameraSpec {
        CameraSpec {
            camera_to_world: self.options.camera.inverse(),
            projection: match self.options.perspective {
                Some(fov) => Projection::Perspective { fov: fov.to_radians() },
                None => Projection::Orthographic,
            },
            screen_window: self.screen_window(),
            clipping: self.options.clipping,
        }
    }

    /// The object-space chord tolerance that makes about a quarter pixel at the primitive's
    /// distance from the camera.
    fn tess_detail(&self) -> Detail {
        let (w, h) = self.resolution();
        let [l, r, b, t] = self.screen_window();
        let pixel = ((r - l) / w as f32).min((t - b) / h as f32);
        let object_to_camera = self.world_to_camera * self.current_object_to_world();
        let origin = object_to_camera.transform_point3(Vec3::ZERO);
        let scale = object_to_camera
            .x_axis
            .truncate()
            .length()
            .max(object_to_camera.y_axis.truncate().length())
            .max(object_to_camera.z_axis.truncate().length());
        let world_pixel = match self.options.perspective {
            Some(fov) => {
                pixel * (fov.to_radians() * 0.5).tan() * origin.length().max(self.options.clipping[0]).max(1e-3)
            }
            None => pixel,
        };
        let tolerance = (0.25 * world_pixel / scale.max(1e-12)).clamp(1e-6, 1e6);
        // At most about half a segment per pixel of the image's larger side (a singular
        // surface, such as a paraboloid's apex, would otherwise take the most segments).
        let max_segments = (w.max(h) / 2).clamp(64, 1024);
        Detail { tolerance, min_segments: 4, max_segments }
    }

    fn current_object_to_world(&self) -> Mat4 {
        match &self.recording {
            Some((_, base, _)) => *base,
            None => self.ctm,
        }
    }

    fn patch_basis(&self) -> Result<PatchBasis, BuildError> {
        let (u, us, v, vs) = &self.attrs.basis;
        PatchBasis::from_rib(u, *us, v, *vs).map_err(|e| BuildError::error(e.0))
    }

    fn displays(&self) -> Vec<DisplayDesc> {
        if !self.options.displays.is_empty() || !self.options.depth_maps.is_empty() {
            return self.options.displays.clone();
        }
        let stem = self.opts.default_output.clone().unwrap_or_else(|| "ri".into());
        let file = match self.frame_number {
            Some(n) => format!("{stem}.{n:04}.tif"),
            None => format!("{stem}.tif"),
        };
        vec![DisplayDesc { file, format: DisplayFormat::Tiff, alpha: false }]
    }
}

macro_rules! ok {
    () => {
        Ok(())
    };
}

impl RibBuilder for SceneBuilder {
    fn frame_begin(&mut self, _loc: &Loc, frame: i32) -> Result<(), BuildError> {
        self.saved_options.push((self.options.clone(), self.ctm));
        self.frame_number = Some(frame);
        ok!()
    }

    fn frame_end(&mut self, _loc: &Loc) -> Result<(), BuildError> {
        if let Some((o, ctm)) = self.saved_options.pop() {
            self.options = o;
            self.ctm = ctm;
        }
        self.frame_number = None;
        ok!()
    }

    fn world_begin(&mut self, loc: &Loc) -> Result<(), BuildError> {
        // Maps named by the world's shaders are looked for beside the RIB file too.
        textures::add_search_dirs(loc, &[]);
        self.options.camera = self.ctm;
        self.world_to_camera = self.ctm;
        self.coordinate_systems.insert("camera".into(), self.ctm.inverse());
        self.coordinate_systems.insert("world".into(), Mat4::IDENTITY);
        self.ctm = Mat4::IDENTITY;
        self.block = Block::World;
        self.stack.push((self.options.camera, Some(self.attrs.clone())));
        ok!()
    }

    fn world_end(&mut self, _loc: &Loc) -> Result<(), BuildError> {
        let (w, h) = self.resolution();
        let [sx, sy] = self.options.samples;
        let film = Film {
            xres: w,
            yres: h,
            pixel_aspect: self.options.pixel_aspect,
            crop: self.options.crop,
            samples: [sx.round().max(1.0) as u32, sy.round().max(1.0) as u32],
            filter: self.options.filter,
            gain: self.options.gain,
            gamma: self.options.gamma,
            quantize: self.options.quantize,
        };
        let lights: Vec<LightCall> =
            self.lights.iter().zip(&self.light_used).filter(|(_, used)| **used).map(|(l, _)| l.clone()).collect();
        // Light lists by the frame's light indices (the lights no primitive uses left out).
        let mut renumber = Vec::with_capacity(self.light_used.len());
        let mut next = 0u32;
        for &used in &self.light_used {
            renumber.push(next);
            next += u32::from(used);
        }
        let light_lists = self.light_lists.iter().map(|l| l.iter().map(|&k| renumber[k as usize]).collect()).collect();
        let frame = FrameDesc {
            number: self.frame_number,
            index: self.frames.len(),
            camera: self.camera_spec(),
            film,
            displays: self.displays(),
            depth_maps: self.options.depth_maps.clone(),
            meshes: std::mem::take(&mut self.meshes),
            instances: std::mem::take(&mut self.instances),
            shader_spaces: std::mem::take(&mut self.shader_spaces),
            surfaces: std::mem::take(&mut self.surfaces),
            displacements: std::mem::take(&mut self.displacements),
            volumes: std::mem::take(&mut self.volumes),
            imager: self.options.imager.clone(),
            lights,
            instance_lights: std::mem::take(&mut self.instance_lights),
            light_lists,
            coordinate_systems: std::mem::take(&mut self.coordinate_systems),
        };
        self.frames.push(frame);
        self.lights.clear();
        self.light_used.clear();
        self.light_lists.clear();
        self.light_list_index.clear();
        self.light_handles.clear();
        self.objects.clear();
        self.recording = None;
        self.block = Block::Options;
        while let Some((m, a)) = self.stack.pop() {
            self.ctm = m;
            if let Some(a) = a {
                self.attrs = a;
            }
        }
        self.ctm = self.options.camera;
        ok!()
    }

    fn attribute_begin(&mut self, _loc: &Loc) -> Result<(), BuildError> {
        self.stack.push((self.ctm, Some(self.attrs.clone())));
        ok!()
    }

    fn attribute_end(&mut self, _loc: &Loc) -> Result<(), BuildError> {
        let Some((m, a)) = self.stack.pop() else {
            return Err(BuildError::error("AttributeEnd without AttributeBegin"));
        };
        self.ctm = m;
        if let Some(a) = a {
            // Lights declared inside the block stay, switched as they were outside it.
            let mut a = a;
            a.lights_on.resize(self.lights.len(), false);
            self.attrs = a;
        }
        ok!()
    }

    fn transform_begin(&mut self, _loc: &Loc) -> Result<(), BuildError> {
        self.stack.push((self.ctm, None));
        ok!()
    }

    fn transform_end(&mut self, _loc: &Loc) -> Result<(), BuildError> {
        let Some((m, _)) = self.stack.pop() else {
            return Err(BuildError::error("TransformEnd without TransformBegin"));
        };
        self.ctm = m;
        ok!()
    }

    fn object_begin(&mut self, _loc: &Loc, handle: &Handle) -> Result<(), BuildError> {
        if self.recording.is_some() {
            return Err(BuildError::error("ObjectBegin inside another object definition"));
        }
        self.stack.push((self.ctm, Some(self.attrs.clone())));
        self.recording = Some((handle.clone(), self.ctm, Vec::new()));
        ok!()
    }

    fn object_end(&mut self, loc: &Loc) -> Result<(), BuildError> {
        let Some((handle, _, parts)) = self.recording.take() else {
            return Err(BuildError::error("ObjectEnd without ObjectBegin"));
        };
        self.objects.insert(handle, parts);
        self.attribute_end(loc)
    }

    fn object_instance(&mut self, _loc: &Loc, handle: &Handle) -> Result<(), BuildError> {
        let Some(parts) = self.objects.get(handle).cloned() else {
            return Err(BuildError::error(format!("ObjectInstance {handle}: no object of that handle")));
        };
        for part in parts {
            self.place(part.mesh, self.ctm * part.relative, &part.attrs, &part.primvars);
        }
        ok!()
    }

    fn format(&mut self, _loc: &Loc, xres: i32, yres: i32, pixel_aspect: f32) -> Result<(), BuildError> {
        if xres <= 0 || yres <= 0 || xres > 65536 || yres > 65536 {
            return Err(BuildError::error(format!("Format {xres} {yres}: resolution must be 1 to 65536")));
        }
        self.options.xres = xres as u32;
        self.options.yres = yres as u32;
        self.options.pixel_aspect = if pixel_aspect > 0.0 { pixel_aspect } else { 1.0 };
        ok!()
    }

    fn frame_aspect_ratio(&mut self, _loc: &Loc, aspect: f32) -> Result<(), BuildError> {
        if !(aspect > 0.0 && aspect.is_finite()) {
            return Err(BuildError::error(format!("FrameAspectRatio {aspect}: must be positive")));
        }
        self.options.frame_aspect = Some(aspect);
        ok!()
    }

    fn screen_window(&mut self, _loc: &Loc, window: &[f32; 4]) -> Result<(), BuildError> {
        if window[0] == window[1] || window[2] == window[3] || window.iter().any(|x| !x.is_finite()) {
            return Err(BuildError::error(format!("ScreenWindow {window:?}: an empty window")));
        }
        self.options.screen_window = Some(*window);
        ok!()
    }

    fn crop_window(&mut self, _loc: &Loc, window: &[f32; 4]) -> Result<(), BuildError> {
        let w = window.map(|x| x.clamp(0.0, 1.0));
        if w[0] >= w[1] || w[2] >= w[3] {
            return Err(BuildError::error(format!("CropWindow {window:?}: an empty window")));
        }
        self.options.crop = w;
        ok!()
    }

    fn projection(&mut self, _loc: &Loc, name: &str, params: &ParamList) -> Result<(), BuildError> {
        match name {
            "perspective" => {
                let fov = params.float("fov").unwrap_or(90.0);
                if !(fov > 0.0 && fov < 180.0) {
                    return Err(BuildError::error(format!(
                        "Projection \"perspective\" \"fov\" {fov}: must be in (0, 180)"
                    )));
                }
                self.options.perspective = Some(fov);
            }
            "orthographic" => self.options.perspective = None,
            other => {
                return Err(BuildError::warning(format!(
                    "Projection \"{other}\" is not supported; \"perspective\" and \"orthographic\" are"
                )))
            }
        }
        // The camera transform starts after the projection.
        self.ctm = Mat4::IDENTITY;
        ok!()
    }

    fn clipping(&mut self, _loc: &Loc, near: f32, far: f32) -> Result<(), BuildError> {
        if !(near >= 0.0 && far > near) {
            return Err(BuildError::error(format!("Clipping {near} {far}: need 0 ≤ near < far")));
        }
        self.options.clipping = [near, far];
        ok!()
    }

    fn shutter(&mut self, _loc: &Loc, _open: f32, _close: f32) -> Result<(), BuildError> {
        ok!()
    }

    fn pixel_variance(&mut self, _loc: &Loc, _variance: f32) -> Result<(), BuildError> {
        ok!()
    }

    fn pixel_samples(&mut self, _loc: &Loc, xsamples: f32, ysamples: f32) -> Result<(), BuildError> {
        if !(xsamples >= 1.0 && ysamples >= 1.0 && xsamples <= 64.0 && ysamples <= 64.0) {
            return Err(BuildError::warning(format!(
                "PixelSamples {xsamples} {ysamples}: taken as {} {} (1 to 64 each)",
                xsamples.clamp(1.0, 64.0),
                ysamples.clamp(1.0, 64.0)
            )));
        }
        self.options.samples = [xsamples, ysamples];
        ok!()
    }

    fn pixel_filter(&mut self, _loc: &Loc, name: &str, xwidth: f32, ywidth: f32) -> Result<(), BuildError> {
        let kind = match name.trim_end_matches("filter") {
            "box" => FilterKind::Box,
            "triangle" => FilterKind::Triangle,
            "catmull-rom" | "catmullrom" => FilterKind::CatmullRom,
            "gaussian" => FilterKind::Gaussian,
            "sinc" => FilterKind::Sinc,
            other => {
                return Err(BuildError::warning(format!(
                    "PixelFilter \"{other}\" is not known (box, triangle, catmull-rom, gaussian, sinc); keeping the current filter"
                )))
            }
        };
        if !(xwidth > 0.0 && ywidth > 0.0 && xwidth <= 16.0 && ywidth <= 16.0) {
            return Err(BuildError::warning(format!("PixelFilter widths {xwidth} {ywidth}: must be in (0, 16]")));
        }
        self.options.filter = PixelFilter { kind, xwidth, ywidth };
        ok!()
    }

    fn exposure(&mut self, _loc: &Loc, gain: f32, gamma: f32) -> Result<(), BuildError> {
        if !(gain.is_finite() && gamma > 0.0 && gamma.is_finite()) {
            return Err(BuildError::error(format!("Exposure {gain} {gamma}: gamma must be positive")));
        }
        self.options.gain = gain;
        self.options.gamma = gamma;
        ok!()
    }

    fn quantize(
        &mut self,
        _loc: &Loc,
        kind: &str,
        one: i32,
        min: i32,
        max: i32,
        dither: f32,
    ) -> Result<(), BuildError> {
        if kind != "rgba" {
            return Err(BuildError::warning(format!(
                "Quantize \"{kind}\": only \"rgba\" is used (depth is not written)"
            )));
        }
        if min > max || one < 0 {
            return Err(BuildError::error(format!("Quantize {one} {min} {max}: need one ≥ 0 and min ≤ max")));
        }
        self.options.quantize = Quantize { one, min, max, dither: dither.max(0.0) };
        ok!()
    }

    fn display(
        &mut self,
        _loc: &Loc,
        name: &str,
        kind: &str,
        mode: &str,
        _params: &ParamList,
    ) -> Result<(), BuildError> {
        let (add, name) = match name.strip_prefix('+') {
            Some(n) => (true, n),
            None => (false, name),
        };
        if !add {
            self.options.displays.clear();
            self.options.depth_maps.clear();
        }
        if mode == "z" && matches!(kind, "zfile" | "shadow") {
            // A depth pass, kept in memory under its name for `MakeShadow` and `shadow()`.
            self.options.depth_maps.push(name.to_string());
            return ok!();
        }
        let mut warning = None;
        let format = match kind {
            "file" | "tiff" => DisplayFormat::Tiff,
            "png" | "framebuffer" => DisplayFormat::Png,
            other => {
                warning = Some(format!("Display type \"{other}\" is not supported: written as a TIFF file"));
                DisplayFormat::Tiff
            }
        };
        let alpha = match mode {
            "rgb" => false,
            "rgba" => true,
            m if m.contains("rgb") => {
                warning = Some(format!(
                    "Display mode \"{m}\": only the rgb{} channels are written",
                    if m.contains('a') { "a" } else { "" }
                ));
                m.contains('a')
            }
            m => {
                return Err(BuildError::warning(format!(
                    "Display mode \"{m}\" is not supported (rgb, rgba): display skipped"
                )))
            }
        };
        let has_ext = std::path::Path::new(name).extension().is_some();
        let file = match (format, has_ext) {
            (_, true) => name.to_string(),
            (DisplayFormat::Png, false) => format!("{name}.png"),
            (DisplayFormat::Tiff, false) => format!("{name}.tif"),
        };
        self.options.displays.push(DisplayDesc { file, format, alpha });
        match warning {
            Some(w) => Err(BuildError::warning(w)),
            None => ok!(),
        }
    }

    fn hider(&mut self, _loc: &Loc, _kind: &str, _params: &ParamList) -> Result<(), BuildError> {
        ok!()
    }

    fn relative_detail(&mut self, _loc: &Loc, _relative_detail: f32) -> Result<(), BuildError> {
        ok!()
    }

    fn option(&mut self, _loc: &Loc, name: &str, _params: &ParamList) -> Result<(), BuildError> {
        match name {
            "searchpath" | "limits" | "render" | "statistics" | "trace" | "shadow" | "hider" | "bucket" => ok!(),
            other if self.warned_options.iter().any(|w| w == other) => ok!(),
            other => {
                self.warned_options.push(other.to_string());
                Err(BuildError::warning(format!("Option \"{other}\" is not known to anysl and is ignored")))
            }
        }
    }

    fn search_path(&mut self, loc: &Loc, kind: &str, paths: &[PathBuf]) -> Result<(), BuildError> {
        match kind {
            "shader" => self.shader_paths = paths.to_vec(),
            "texture" => textures::add_search_dirs(loc, paths),
            _ => {}
        }
        ok!()
    }

    fn make_texture(
        &mut self,
        loc: &Loc,
        picture: &str,
        texture: &str,
        swrap: &str,
        twrap: &str,
        filter: &str,
        swidth: f32,
        twidth: f32,
        _params: &ParamList,
    ) -> Result<(), BuildError> {
        let src = vec![picture.to_string()];
        textures::make(loc, MapKind::Texture, src, texture, (swrap, twrap), filter, swidth, twidth, 90.0)
    }

    fn make_lat_long_environment(
        &mut self,
        loc: &Loc,
        picture: &str,
        texture: &str,
        filter: &str,
        swidth: f32,
        twidth: f32,
        _params: &ParamList,
    ) -> Result<(), BuildError> {
        let src = vec![picture.to_string()];
        textures::make(loc, MapKind::LatLong, src, texture, ("periodic", "clamp"), filter, swidth, twidth, 90.0)
    }

    fn make_shadow(&mut self, loc: &Loc, picture: &str, texture: &str, _params: &ParamList) -> Result<(), BuildError> {
        let src = vec![picture.to_string()];
        textures::make(loc, MapKind::Shadow, src, texture, ("clamp", "clamp"), "box", 1.0, 1.0, 90.0)
    }

    fn make_cube_face_environment(
        &mut self,
        loc: &Loc,
        faces: &[String; 6],
        texture: &str,
        fov: f32,
        filter: &str,
        swidth: f32,
        twidth: f32,
        _params: &ParamList,
    ) -> Result<(), BuildError> {
        let src = faces.to_vec();
        textures::make(loc, MapKind::CubeFace, src, texture, ("clamp", "clamp"), filter, swidth, twidth, fov)
    }

    fn attribute(&mut self, _loc: &Loc, _name: &str, _params: &ParamList) -> Result<(), BuildError> {
        ok!()
    }

    fn color(&mut self, _loc: &Loc, rgb: &[f32; 3]) -> Result<(), BuildError> {
        self.attrs.color = *rgb;
        ok!()
    }

    fn opacity(&mut self, _loc: &Loc, rgb: &[f32; 3]) -> Result<(), BuildError> {
        self.attrs.opacity = *rgb;
        ok!()
    }

    fn texture_coordinates(&mut self, _loc: &Loc, st: &[f32; 8]) -> Result<(), BuildError> {
        self.attrs.st = Some(*st);
        ok!()
    }

    fn light_source(&mut self, loc: &Loc, name: &str, handle: &Handle, params: &ParamList) -> Result<(), BuildError> {
        self.lights.push(LightCall {
            shader: ShaderCall {
                name: name.to_string(),
                params: params.clone(),
                primvars: ParamList::new(),
                loc: Some(loc.clone()),
            },
            transform: self.ctm,
        });
        self.light_used.push(false);
        self.light_handles.insert(handle.clone(), self.lights.len() - 1);
        self.attrs.lights_on.resize(self.lights.len(), false);
        if let Some(on) = self.attrs.lights_on.last_mut() {
            *on = true;
        }
        ok!()
    }

    fn illuminate(&mut self, _loc: &Loc, handle: &Handle, on: bool) -> Result<(), BuildError> {
        let Some(&k) = self.light_handles.get(handle) else {
            return Err(BuildError::warning(format!("Illuminate {handle}: no light source of that handle")));
        };
        self.attrs.lights_on.resize(self.lights.len(), false);
        self.attrs.lights_on[k] = on;
        ok!()
    }

    fn surface(&mut self, loc: &Loc, name: &str, params: &ParamList) -> Result<(), BuildError> {
        self.attrs.surface = Some(ShaderCall {
            name: name.to_string(),
            params: params.clone(),
            primvars: ParamList::new(),
            loc: Some(loc.clone()),
        });
        self.attrs.shader_space = self.current_object_to_world();
        ok!()
    }

    fn displacement(&mut self, loc: &Loc, name: &str, params: &ParamList) -> Result<(), BuildError> {
        self.attrs.displacement = shader_call(loc, name, params);
        ok!()
    }

    fn atmosphere(&mut self, loc: &Loc, name: &str, params: &ParamList) -> Result<(), BuildError> {
        self.attrs.volumes.atmosphere = shader_call(loc, name, params);
        ok!()
    }

    fn interior(&mut self, loc: &Loc, name: &str, params: &ParamList) -> Result<(), BuildError> {
        self.attrs.volumes.interior = shader_call(loc, name, params);
        ok!()
    }

    fn exterior(&mut self, loc: &Loc, name: &str, params: &ParamList) -> Result<(), BuildError> {
        self.attrs.volumes.exterior = shader_call(loc, name, params);
        ok!()
    }

    fn imager(&mut self, loc: &Loc, name: &str, params: &ParamList) -> Result<(), BuildError> {
        self.options.imager = shader_call(loc, name, params);
        ok!()
    }

    fn shading_rate(&mut self, _loc: &Loc, _size: f32) -> Result<(), BuildError> {
        ok!()
    }

    fn shading_interpolation(&mut self, _loc: &Loc, _kind: &str) -> Result<(), BuildError> {
        ok!()
    }

    fn geometric_representation(&mut self, _loc: &Loc, _kind: &str) -> Result<(), BuildError> {
        ok!()
    }

    fn geometric_approximation(&mut self, _loc: &Loc, _kind: &str, _value: f32) -> Result<(), BuildError> {
        ok!()
    }

    fn bound(&mut self, _loc: &Loc, _bound: &[f32; 6]) -> Result<(), BuildError> {
        ok!()
    }

    fn orientation(&mut self, _loc: &Loc, orientation: &str) -> Result<(), BuildError> {
        let lefthanded = (self.world_to_camera * self.ctm).determinant() > 0.0;
        self.attrs.inside = match orientation {
            "outside" => false,
            "inside" => true,
            "lh" => !lefthanded,
            "rh" => lefthanded,
            other => {
                return Err(BuildError::error(format!(
                    "Orientation \"{other}\": expected \"outside\", \"inside\", \"lh\" or \"rh\""
                )))
            }
        };
        ok!()
    }

    fn reverse_orientation(&mut self, _loc: &Loc) -> Result<(), BuildError> {
        self.attrs.inside = !self.attrs.inside;
        ok!()
    }

    fn sides(&mut self, _loc: &Loc, sides: i32) -> Result<(), BuildError> {
        match sides {
            1 => self.attrs.two_sided = false,
            2 => self.attrs.two_sided = true,
            n => return Err(BuildError::error(format!("Sides {n}: expected 1 or 2"))),
        }
        ok!()
    }

    fn basis(&mut self, _loc: &Loc, ubasis: &Basis, ustep: i32, vbasis: &Basis, vstep: i32) -> Result<(), BuildError> {
        PatchBasis::from_rib(ubasis, ustep, vbasis, vstep).map_err(|e| BuildError::error(e.0))?;
        self.attrs.basis = (ubasis.clone(), ustep, vbasis.clone(), vstep);
        ok!()
    }

    fn identity(&mut self, _loc: &Loc) -> Result<(), BuildError> {
        self.ctm = Mat4::IDENTITY;
        ok!()
    }

    fn transform(&mut self, _loc: &Loc, matrix: &Matrix) -> Result<(), BuildError> {
        self.ctm = rib_matrix(matrix);
        ok!()
    }

    fn concat_transform(&mut self, _loc: &Loc, matrix: &Matrix) -> Result<(), BuildError> {
        self.concat(rib_matrix(matrix));
        ok!()
    }

    fn perspective(&mut self, _loc: &Loc, fov: f32) -> Result<(), BuildError> {
        if !(fov > 0.0 && fov < 180.0) {
            return Err(BuildError::error(format!("Perspective {fov}: the angle must be in (0, 180)")));
        }
        self.concat(perspective_matrix(fov));
        ok!()
    }

    fn translate(&mut self, _loc: &Loc, dx: f32, dy: f32, dz: f32) -> Result<(), BuildError> {
        self.concat(Mat4::from_translation(Vec3::new(unit(dx)?, unit(dy)?, unit(dz)?)));
        ok!()
    }

    fn rotate(&mut self, _loc: &Loc, angle: f32, dx: f32, dy: f32, dz: f32) -> Result<(), BuildError> {
        let axis = Vec3::new(dx, dy, dz)
            .try_normalize()
            .ok_or_else(|| BuildError::error(format!("Rotate {angle} {dx} {dy} {dz}: the axis is zero")))?;
        self.concat(Mat4::from_axis_angle(axis, unit(angle)?.to_radians()));
        ok!()
    }

    fn scale(&mut self, _loc: &Loc, sx: f32, sy: f32, sz: f32) -> Result<(), BuildError> {
        self.concat(Mat4::from_scale(Vec3::new(unit(sx)?, unit(sy)?, unit(sz)?)));
        ok!()
    }

    fn skew(&mut self, _loc: &Loc, skew: &[f32; 7]) -> Result<(), BuildError> {
        let m = skew_matrix(skew)?;
        self.concat(m);
        ok!()
    }

    fn coordinate_system(&mut self, _loc: &Loc, name: &str) -> Result<(), BuildError> {
        let to_world = if self.block == Block::World { self.ctm } else { self.ctm.inverse() };
        self.coordinate_systems.insert(name.to_string(), to_world);
        ok!()
    }

    fn coord_sys_transform(&mut self, _loc: &Loc, name: &str) -> Result<(), BuildError> {
        let m = match name {
            "world" => Mat4::IDENTITY,
            "camera" => self.world_to_camera.inverse(),
            "object" => return ok!(),
            _ => *self.coordinate_systems.get(name).ok_or_else(|| {
                BuildError::error(format!("CoordSysTransform \"{name}\": no coordinate system of that name"))
            })?,
        };
        self.ctm = if self.block == Block::World { m } else { m.inverse() };
        ok!()
    }

    fn polygon(&mut self, _loc: &Loc, params: &ParamList) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::polygon(params, &d), "Polygon", params)
    }

    fn general_polygon(&mut self, _loc: &Loc, nverts: &[i32], params: &ParamList) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::general_polygon(nverts, params, &d), "GeneralPolygon", params)
    }

    fn points_polygons(
        &mut self,
        _loc: &Loc,
        nverts: &[i32],
        verts: &[i32],
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::points_polygons(nverts, verts, params, &d), "PointsPolygons", params)
    }

    fn points_general_polygons(
        &mut self,
        _loc: &Loc,
        nloops: &[i32],
        nverts: &[i32],
        verts: &[i32],
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::points_general_polygons(nloops, nverts, verts, params, &d), "PointsGeneralPolygons", params)
    }

    fn patch(&mut self, _loc: &Loc, kind: &str, params: &ParamList) -> Result<(), BuildError> {
        let (d, basis) = (self.tess_detail(), self.patch_basis()?);
        self.add(geom::patch(kind, &basis, params, &d), "Patch", params)
    }

    fn patch_mesh(
        &mut self,
        _loc: &Loc,
        kind: &str,
        nu: i32,
        uwrap: &str,
        nv: i32,
        vwrap: &str,
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let (d, basis) = (self.tess_detail(), self.patch_basis()?);
        self.add(geom::patch_mesh(kind, nu, uwrap, nv, vwrap, &basis, params, &d), "PatchMesh", params)
    }

    fn nu_patch(
        &mut self,
        _loc: &Loc,
        nu: i32,
        uorder: i32,
        uknot: &[f32],
        umin: f32,
        umax: f32,
        nv: i32,
        vorder: i32,
        vknot: &[f32],
        vmin: f32,
        vmax: f32,
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let d = self.tess_detail();
        let t = geom::nu_patch(nu, uorder, uknot, umin, umax, nv, vorder, vknot, vmin, vmax, params, &d);
        self.add(t, "NuPatch", params)
    }

    fn trim_curve(
        &mut self,
        _loc: &Loc,
        _ncurves: &[i32],
        _order: &[i32],
        _knot: &[f32],
        _min: &[f32],
        _max: &[f32],
        _n: &[i32],
        _u: &[f32],
        _v: &[f32],
        _w: &[f32],
    ) -> Result<(), BuildError> {
        Err(BuildError::warning("TrimCurve is ignored: NuPatches are rendered untrimmed"))
    }

    fn sphere(
        &mut self,
        _loc: &Loc,
        radius: f32,
        zmin: f32,
        zmax: f32,
        thetamax: f32,
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::sphere(radius, zmin, zmax, thetamax, params, &d), "Sphere", params)
    }

    fn cone(
        &mut self,
        _loc: &Loc,
        height: f32,
        radius: f32,
        thetamax: f32,
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::cone(height, radius, thetamax, params, &d), "Cone", params)
    }

    fn cylinder(
        &mut self,
        _loc: &Loc,
        radius: f32,
        zmin: f32,
        zmax: f32,
        thetamax: f32,
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::cylinder(radius, zmin, zmax, thetamax, params, &d), "Cylinder", params)
    }

    fn hyperboloid(
        &mut self,
        _loc: &Loc,
        point1: &[f32; 3],
        point2: &[f32; 3],
        thetamax: f32,
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::hyperboloid(*point1, *point2, thetamax, params, &d), "Hyperboloid", params)
    }

    fn paraboloid(
        &mut self,
        _loc: &Loc,
        rmax: f32,
        zmin: f32,
        zmax: f32,
        thetamax: f32,
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::paraboloid(rmax, zmin, zmax, thetamax, params, &d), "Paraboloid", params)
    }

    fn disk(
        &mut self,
        _loc: &Loc,
        height: f32,
        radius: f32,
        thetamax: f32,
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::disk(height, radius, thetamax, params, &d), "Disk", params)
    }

    fn torus(
        &mut self,
        _loc: &Loc,
        major_radius: f32,
        minor_radius: f32,
        phimin: f32,
        phimax: f32,
        thetamax: f32,
        params: &ParamList,
    ) -> Result<(), BuildError> {
        let d = self.tess_detail();
        self.add(geom::torus(major_radius, minor_radius, phimin, phimax, thetamax, params, &d), "Torus", params)
    }

    fn geometry(&mut self, _loc: &Loc, kind: &str, params: &ParamList) -> Result<(), BuildError> {
        match kind {
            "teapot" => {
                let d = self.tess_detail();
                self.add(Ok(geom::teapot(&d)), "Geometry \"teapot\"", params)
            }
            other => Err(BuildError::warning(format!("Geometry \"{other}\" is not known (\"teapot\" is)"))),
        }
    }
}
