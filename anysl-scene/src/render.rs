//! A [`FrameDesc`] made into a renderer [`Scene`] and the renderer's samples made into the
//! frame's pixels, whatever renderer and shader back end run in between.
//!
//! ```
//! use anysl_scene::build::{BuildOptions, SceneBuilder};
//! use anysl_scene::render::{frame_scene, Surfaces};
//! use anysl_scene::shaders::ShaderLibrary;
//!
//! let rib = "Format 16 16 1 PixelSamples 1 1 PixelFilter \"box\" 1 1 Projection \"perspective\" \"fov\" 30\n\
//!            WorldBegin Color 1 0 0 Surface \"constant\" Translate 0 0 4 Sphere 1 -1 1 360 WorldEnd";
//! let mut b = SceneBuilder::new(BuildOptions::default());
//! anysl_rib::parse_str("doc.rib", rib, &mut b, &anysl_rib::Options::new()).unwrap();
//! let frame = &b.finish()[0];
//! let mut surfaces = Surfaces::interpreter(ShaderLibrary::new(vec![], vec![]));
//! let fs = frame_scene(frame, &mut surfaces).unwrap();
//! let opts = anysl_renderers::RenderOptions { threads: 1, ..Default::default() };
//! let pixels = fs.finish(&frame.film, &anysl_renderers::render_scalar(&fs.scene, &opts));
//! assert_eq!(pixels[8 * 16 + 8], [1.0, 0.0, 0.0, 1.0]);
//! ```

use crate::build::{Film, FrameDesc, ShaderCall};
use crate::film::{reconstruct, SampleWindow};
use crate::lights::{scene_light, LightMaker, SceneLight};
use crate::shaders::{apply_params, ShaderLibrary};
use crate::surface::{SceneSurface, Volumes};
use anysl_core::{DisplacementShader, ImagerShader, LightShader, Matrix4, Spaces, SurfaceShader, VolumeShader};
use anysl_renderers::Projection;
use anysl_renderers::{Camera, Image, Scene};
use anysl_rsl::back::interp::{InterpShader, Program};
use glam::DMat4;
use std::collections::HashMap;
use std::sync::Arc;

/// A shader back end's type for every kind of shader a scene names (the interpreter's
/// `InterpShader`, the JIT's `JitShader`): surfaces, displacements, lights, volumes and
/// imagers of a scene are all made by the one back end.
pub trait SceneShader: SurfaceShader + DisplacementShader + LightShader + VolumeShader + ImagerShader + Clone {}

impl<S: SurfaceShader + DisplacementShader + LightShader + VolumeShader + ImagerShader + Clone> SceneShader for S {}

/// Makes the shaders of one back end from compiled modules, each distinct shader once.
pub struct Surfaces<S> {
    /// Where shaders are found.
    pub library: ShaderLibrary,
    make: Box<dyn FnMut(anysl_rsl::ir::Module) -> Result<S, String>>,
    cache: HashMap<String, S>,
    /// Whether each shader made so far names a coordinate system.
    uses_spaces: HashMap<String, bool>,
    /// Shaders of earlier frames with their parameters set (and, for the JIT, compiled),
    /// handed back by [`Surfaces::keep`] for the next frame to reuse.
    kept: Vec<(ShaderCall, S)>,
}

impl<S: SceneShader> Surfaces<S> {
    /// Shaders made by `make` from each shader's compiled module.
    pub fn new(library: ShaderLibrary, make: impl FnMut(anysl_rsl::ir::Module) -> Result<S, String> + 'static) -> Self {
        Self { library, make: Box::new(make), cache: HashMap::new(), uses_spaces: HashMap::new(), kept: Vec::new() }
    }

    /// Hands back the surface shaders of a rendered frame (`frame.surfaces` in order), so a
    /// later frame with the same shader and parameters reuses them as they are (a JIT
    /// shader's compiled code included).
    pub fn keep(&mut self, frame: &FrameDesc, shaders: Vec<S>) {
        for (call, s) in frame.surfaces.iter().zip(shaders) {
            if !self.kept.iter().any(|(c, _)| c.same_as(call)) {
                self.kept.push((call.clone(), s));
            }
        }
    }

    /// The shader for `call`: a kept one with the same parameters, else a fresh instance with
    /// the parameters set (and the warnings that gave).
    fn for_call(&mut self, call: &ShaderCall) -> Result<(S, Vec<String>), String> {
        if let Some(k) = self.kept.iter().position(|(c, _)| c.same_as(call)) {
            return Ok((self.kept.swap_remove(k).1, Vec::new()));
        }
        let mut s = self.instance(&call.name)?;
        let warnings = apply_params(&mut s, call);
        Ok((s, warnings))
    }

    /// The shader of `call` for `stage` (displacement, volume, imager: made like the
    /// surfaces) with its parameters set, the warnings that gave, and whether it names a
    /// coordinate system.
    ///
    /// # Errors
    /// The shader cannot be found or compiled, or is of another kind than `stage` takes.
    fn stage(&mut self, call: &ShaderCall, stage: Stage) -> Result<(S, Vec<String>, bool), String> {
        let name = &call.name;
        let kind = self.library.module(name).map_err(|e| format!("{}{e}", at(call)))?.kind;
        if kind != stage.kind() {
            return Err(kind_error(call, kind, stage));
        }
        let (shader, warnings) = self.for_call(call).map_err(|e| format!("{}{} {e}", at(call), kind_word(stage)))?;
        Ok((shader, warnings, self.uses_spaces.get(name).copied().unwrap_or(false)))
    }

    /// [`Surfaces::stage`] for a request whose shader may be missing: a shader not found is
    /// left out with a warning naming it (`None`); its parameter warnings join `warnings`.
    ///
    /// # Errors
    /// The shader is found but does not compile or is of another kind.
    fn optional_stage(
        &mut self,
        call: &ShaderCall,
        stage: Stage,
        warnings: &mut Vec<String>,
    ) -> Result<Option<(S, bool)>, String> {
        if let Err(e) = self.library.find(&call.name) {
            warnings.push(format!("{}{} {e}; left out", at(call), stage.request()));
            return Ok(None);
        }
        let (shader, w, names_space) = self.stage(call, stage)?;
        warnings.extend(w);
        Ok(Some((shader, names_space)))
    }

    /// A fresh instance of shader `name` with its defaults.
    ///
    /// # Errors
    /// The shader cannot be found or compiled.
    pub fn instance(&mut self, name: &str) -> Result<S, String> {
        if let Some(s) = self.cache.get(name) {
            return Ok(s.clone());
        }
        let module = self.library.module(name)?;
        self.uses_spaces.insert(name.to_string(), module.uses_spaces());
        let shader = (self.make)(module).map_err(|e| format!("shader \"{name}\": {e}"))?;
        self.cache.insert(name.to_string(), shader.clone());
        Ok(shader)
    }
}

impl<S: SceneShader> LightMaker<S> for Surfaces<S> {
    fn library(&mut self) -> &mut ShaderLibrary {
        &mut self.library
    }
    fn instance(&mut self, name: &str) -> Result<S, String> {
        Surfaces::instance(self, name)
    }
}

impl Surfaces<InterpShader> {
    /// Shaders run by the batched interpreter (optimized IR).
    #[must_use]
    pub fn interpreter(library: ShaderLibrary) -> Self {
        Self::new(library, |m| {
            let m = anysl_rsl::passes::optimize(m, &anysl_rsl::passes::PassOptions::default());
            Program::new(m).map(|p| InterpShader::new(Arc::new(p))).map_err(|e| e.to_string())
        })
    }
}

/// A frame ready to render: the scene of its samples and what it takes to make pixels of
/// them.
pub struct FrameScene<S> {
    /// The renderer scene; its camera renders one pixel per film sample.
    pub scene: Scene<SceneSurface<S>, SceneLight<S>>,
    /// The samples' window.
    pub window: SampleWindow,
    /// Warnings (parameters that do not fit, unsupported lights, shaders left out).
    pub warnings: Vec<String>,
    /// The imager shader, run on the filtered pixels by [`FrameScene::finish`].
    pub imager: Option<S>,
}

/// Builds the renderer scene of `frame` with surface shaders from `surfaces`.
///
/// # Errors
/// A surface shader that cannot be found or compiled, a light shader that is found but does not
/// compile or is not a light shader, or inconsistent geometry. (A light shader that is not
/// found is left out with a warning.)
pub fn frame_scene<S: SceneShader>(frame: &FrameDesc, surfaces: &mut Surfaces<S>) -> Result<FrameScene<S>, String> {
    let mut warnings = Vec::new();
    let mut shaders = Vec::with_capacity(frame.surfaces.len());
    // Per surface slot: whether its shaders name a coordinate system.
    let mut spacey = Vec::with_capacity(frame.surfaces.len());
    for (k, call) in frame.surfaces.iter().enumerate() {
        let (surface, w) = surfaces.for_call(call)?;
        warnings.extend(w);
        let mut uses = surfaces.uses_spaces.get(&call.name).copied().unwrap_or(false);
        let displacement = match frame.displacements.get(k).and_then(Option::as_ref) {
            Some(d) => {
                let (shader, w, names_space) = surfaces.stage(d, Stage::Displacement)?;
                warnings.extend(w);
                uses |= names_space;
                Some(shader)
            }
            None => None,
        };
        let calls = frame.volumes.get(k).cloned().unwrap_or_default();
        let mut volume = |call: &Option<ShaderCall>, stage: Stage| -> Result<Option<S>, String> {
            let Some(call) = call else { return Ok(None) };
            match surfaces.optional_stage(call, stage, &mut warnings)? {
                Some((shader, names_space)) => {
                    uses |= names_space;
                    Ok(Some(shader))
                }
                None => Ok(None),
            }
        };
        let volumes = Volumes {
            atmosphere: volume(&calls.atmosphere, Stage::Atmosphere)?,
            interior: volume(&calls.interior, Stage::Interior)?,
            exterior: volume(&calls.exterior, Stage::Exterior)?,
        };
        spacey.push(uses);
        shaders.push(SceneSurface { surface, displacement, volumes });
    }
    let mut lights = Vec::new();
    // Frame light k → its index in `lights` (none when it is left out).
    let mut light_of = Vec::with_capacity(frame.lights.len());
    let mut spaces = None;
    for call in &frame.lights {
        if let Err(e) = surfaces.library.find(&call.shader.name) {
            warnings.push(format!("{e}; the light is left out"));
            light_of.push(None);
            continue;
        }
        let spaces = spaces.get_or_insert_with(|| frame_spaces(frame));
        let (light, w) = scene_light(call, surfaces, spaces)?;
        warnings.extend(w);
        light_of.push(Some(lights.len()));
        lights.push(light);
    }
    if shaders.is_empty() {
        // A world without primitives still needs a shader slot.
        shaders.push(SceneSurface {
            surface: surfaces.instance("defaultsurface")?,
            displacement: None,
            volumes: Volumes::default(),
        });
        spacey.push(false);
    }
    let window = SampleWindow::of(&frame.film);
    let (w, h) = window.sample_size();
    let camera = Camera::from_spec(&window.camera(&frame.camera, &frame.film), w, h);
    let mut instances = frame.instances.clone();
    let mut surface_spaces = place_spaces(frame, &spacey, &mut instances, &mut shaders);
    let surface_lights = place_lights(frame, &light_of, &lights, &mut instances, &mut shaders, &mut surface_spaces);
    let mut scene = Scene::new(camera, &frame.meshes, instances, shaders, lights).map_err(|e| e.to_string())?;
    scene.surface_spaces = surface_spaces;
    scene.surface_lights = surface_lights;
    // RenderMan has no sky: a ray that meets nothing (`trace`, a path tracer's bounce) sees black.
    scene.sky = anysl_renderers::Sky { horizon: [0.0; 3], zenith: [0.0; 3], visible_to_camera: false };
    // The frame's depth passes, kept for the frames after it (`MakeShadow`, `shadow()`).
    crate::depth::keep_depth_maps(frame, &scene);
    let imager = match &frame.imager {
        Some(call) => surfaces.optional_stage(call, Stage::Imager, &mut warnings)?.map(|s| s.0),
        None => None,
    };
    Ok(FrameScene { scene, window, warnings, imager })
}

/// The shader requests besides `Surface` and `LightSource` (a displacement is made by the
/// surfaces' back end, [`Surfaces::displacement`]; the others are run by the interpreter).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stage {
    Displacement,
    Atmosphere,
    Interior,
    Exterior,
    Imager,
}

impl Stage {
    fn request(self) -> &'static str {
        match self {
            Stage::Displacement => "Displacement",
            Stage::Atmosphere => "Atmosphere",
            Stage::Interior => "Interior",
            Stage::Exterior => "Exterior",
            Stage::Imager => "Imager",
        }
    }

    fn kind(self) -> anysl_rsl::ir::ShaderKind {
        use anysl_rsl::ir::ShaderKind as K;
        match self {
            Stage::Displacement => K::Displacement,
            Stage::Atmosphere | Stage::Interior | Stage::Exterior => K::Volume,
            Stage::Imager => K::Imager,
        }
    }
}

/// Where a shader request is, for messages (`file:line: `, or nothing).
fn at(call: &ShaderCall) -> String {
    call.loc.as_ref().map_or_else(String::new, |l| format!("{l}: "))
}

/// `shader "NAME" is a surface shader; Displacement needs a displacement shader`, with the
/// request's location.
fn kind_error(call: &ShaderCall, found: anysl_rsl::ir::ShaderKind, stage: Stage) -> String {
    // "a surface shader", "an imager shader".
    let kind = |k: anysl_rsl::ir::ShaderKind| {
        let k = format!("{k:?}").to_lowercase();
        let article = if k.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" };
        format!("{article} {k} shader")
    };
    format!("{}shader \"{}\" is {}; {} needs {}", at(call), call.name, kind(found), stage.request(), kind(stage.kind()))
}

fn kind_word(stage: Stage) -> &'static str {
    match stage.kind() {
        anysl_rsl::ir::ShaderKind::Displacement => "displacement",
        anysl_rsl::ir::ShaderKind::Imager => "imager",
        _ => "volume",
    }
}

/// A glam matrix (column vectors) as an RSL one (row vectors, row by row).
fn rsl(m: DMat4) -> Matrix4<f64> {
    Matrix4::from_array(m.to_cols_array())
}

fn rows(m: Matrix4<f64>) -> [f64; 16] {
    core::array::from_fn(|i| m.m[i / 4][i % 4])
}

/// The frame's named coordinate systems, each as its matrix to current (= world): "world",
/// "camera", "screen", "NDC", "raster" and every `CoordinateSystem`.
#[must_use]
pub fn frame_spaces(frame: &FrameDesc) -> Spaces {
    let cam = &frame.camera;
    let c2w = rsl(cam.camera_to_world.as_dmat4());
    let w2c = c2w.inverse();
    // Camera to screen (row vectors): the perspective divide by z, z' = f/(f−n) (1 − n/z)
    // (1 − n/z for an infinite far plane); orthographic: the identity.
    let c2s = match cam.projection {
        Projection::Perspective { fov } => {
            let t = 1.0 / (f64::from(fov) / 2.0).tan();
            let (n, f) = (f64::from(cam.clipping[0]), f64::from(cam.clipping[1]));
            let (a, b) = if f.is_finite() { (f / (f - n), -f * n / (f - n)) } else { (1.0, -n) };
            Matrix4::from_array([t, 0.0, 0.0, 0.0, 0.0, t, 0.0, 0.0, 0.0, 0.0, a, 1.0, 0.0, 0.0, b, 0.0])
        }
        Projection::Orthographic => Matrix4::identity(),
    };
    // Screen window to [0, 1]², y down.
    let [l, r, bo, to] = cam.screen_window.map(f64::from);
    let s2n = Matrix4::from_array([
        1.0 / (r - l),
        0.0,
        0.0,
        0.0,
        0.0,
        -1.0 / (to - bo),
        0.0,
        0.0,
        0.0,
        0.0,
        1.0,
        0.0,
        -l / (r - l),
        to / (to - bo),
        0.0,
        1.0,
    ]);
    let (xres, yres) = (f64::from(frame.film.xres), f64::from(frame.film.yres));
    let n2r = Matrix4::from_array([xres, 0.0, 0.0, 0.0, 0.0, yres, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    let w2s = w2c * c2s;
    let w2n = w2s * s2n;
    let w2r = w2n * n2r;
    let mut t = Spaces::new([
        ("world", rows(Matrix4::identity())),
        ("camera", rows(c2w)),
        ("screen", rows(w2s.inverse())),
        ("NDC", rows(w2n.inverse())),
        ("raster", rows(w2r.inverse())),
    ]);
    // `depth()`: camera z taken to 0 at the near and 1 at the far clipping plane.
    let (n, f) = (f64::from(cam.clipping[0]), f64::from(cam.clipping[1]));
    let k = if f.is_finite() && f > n { 1.0 / (f - n) } else { 0.0 };
    let c2d = Matrix4::from_array([1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, k, 0.0, 0.0, 0.0, -n * k, 1.0]);
    t.insert_from_current(anysl_core::DEPTH_SPACE, rows(w2c * c2d));
    for (name, m) in &frame.coordinate_systems {
        t.insert(name, rows(rsl(m.as_dmat4())));
    }
    t
}

/// Per-primitive light lists: where some instance is not lit by every light of the frame,
/// each distinct (surface slot, light list) gets a slot of its own (a copy of the shader, with
/// the slot's spaces) and the lights of its list; returns each slot's lights (`None`: all).
fn place_lights<S: Clone, L: Clone>(
    frame: &FrameDesc,
    light_of: &[Option<usize>],
    lights: &[L],
    instances: &mut [anysl_renderers::Instance],
    shaders: &mut Vec<S>,
    spaces: &mut Vec<Spaces>,
) -> Vec<Option<Vec<L>>> {
    let mut out: Vec<Option<Vec<L>>> = vec![None; shaders.len()];
    // Each list as indices into `lights` (the frame's lists hold distinct lights, so a list as
    // long as `lights` is all of them).
    let sets: Vec<Vec<usize>> = frame
        .light_lists
        .iter()
        .map(|l| l.iter().filter_map(|&k| light_of.get(k as usize).copied().flatten()).collect())
        .collect();
    let partial = |list: usize| sets.get(list).is_some_and(|s| s.len() < lights.len());
    if !(0..sets.len()).any(partial) {
        return out;
    }
    let mut slots: HashMap<(usize, u32), usize> = HashMap::new();
    let mut first_use = vec![true; shaders.len()];
    for (i, inst) in instances.iter_mut().enumerate() {
        let list = frame.instance_lights.get(i).copied().unwrap_or(0);
        let s = inst.surface;
        if let Some(&k) = slots.get(&(s, list)) {
            inst.surface = k;
            continue;
        }
        let k = if std::mem::take(&mut first_use[s]) {
            s
        } else {
            shaders.push(shaders[s].clone());
            spaces.resize(shaders.len() - 1, Spaces::default());
            spaces.push(spaces.get(s).cloned().unwrap_or_default());
            out.push(None);
            shaders.len() - 1
        };
        out[k] = partial(list as usize).then(|| sets[list as usize].iter().map(|&j| lights[j].clone()).collect());
        inst.surface = k;
        slots.insert((s, list), k);
    }
    out
}

/// The named spaces of every surface: a shader that names a space gets one surface slot per
/// distinct ("object", "shader") pair of the instances using it, each with its table, so the
/// spaces are uniform over the points a renderer shades together; other shaders keep one
/// slot and an empty table (never read).
fn place_spaces<S: Clone>(
    frame: &FrameDesc,
    spacey: &[bool],
    instances: &mut [anysl_renderers::Instance],
    shaders: &mut Vec<S>,
) -> Vec<Spaces> {
    let mut out = vec![Spaces::default(); shaders.len()];
    if !spacey.iter().any(|&b| b) {
        return out;
    }
    let base = frame_spaces(frame);
    // (surface, object matrix bits, shader matrix bits) → the slot made for them.
    type Key = (usize, [u32; 16], [u32; 16]);
    let mut slots: Vec<(Key, usize)> = Vec::new();
    let mut first_use = vec![true; shaders.len()];
    for (i, inst) in instances.iter_mut().enumerate() {
        let s = inst.surface;
        if !spacey.get(s).copied().unwrap_or(false) {
            continue;
        }
        let shader_space = frame.shader_spaces.get(i).copied().unwrap_or(glam::Mat4::IDENTITY);
        let key = (s, inst.transform.to_cols_array().map(f32::to_bits), shader_space.to_cols_array().map(f32::to_bits));
        if let Some((_, k)) = slots.iter().find(|(x, _)| *x == key) {
            inst.surface = *k;
            continue;
        }
        let mut t = base.clone();
        t.insert("object", rows(rsl(inst.transform.as_dmat4())));
        t.insert("shader", rows(rsl(shader_space.as_dmat4())));
        let k = if std::mem::take(&mut first_use[s]) {
            s
        } else {
            shaders.push(shaders[s].clone());
            out.push(Spaces::default());
            shaders.len() - 1
        };
        out[k] = t;
        inst.surface = k;
        slots.push((key, k));
    }
    out
}

impl<S: ImagerShader> FrameScene<S> {
    /// The frame's pixels (crop window, row-major RGBA before exposure, alpha = coverage)
    /// from the renderer's `image` of the samples (rendered at one sample per pixel), after
    /// the imager shader if the frame has one.
    ///
    /// # Panics
    /// When `image` is not the size of the sample grid.
    #[must_use]
    pub fn finish(&self, film: &Film, image: &Image) -> Vec<[f32; 4]> {
        let (w, h) = self.window.sample_size();
        assert_eq!((image.width, image.height), (w, h), "the sample image has the wrong size");
        let cam = &self.scene.camera;
        let samples: Vec<[f32; 4]> = (0..w * h)
            .map(|k| {
                let (x, y) = (k % w, k / w);
                let ray = cam.primary_ray(x as f32 + 0.5, y as f32 + 0.5, 1.0);
                let hit = self.scene.intersect_camera(ray.origin, ray.dir, ray.tmin, ray.tmax);
                let [r, g, b] = image.pixel(x, y);
                [r, g, b, if hit.is_some() { 1.0 } else { 0.0 }]
            })
            .collect();
        let mut pixels = reconstruct(film, &self.window, &samples);
        if let Some(imager) = &self.imager {
            crate::film::run_imager(imager, film, &mut pixels);
        }
        pixels
    }
}
