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
use crate::shaders::{apply_params, standard_light, ShaderLibrary};
use anysl_core::SurfaceShader;
use anysl_renderers::{Camera, Image, Scene};
use anysl_rsl::back::interp::{InterpShader, Program};
use anysl_shaders::Light;
use std::collections::HashMap;
use std::sync::Arc;

/// Makes surface shaders of one back end from compiled modules, each distinct shader once.
pub struct Surfaces<S> {
    /// Where shaders are found.
    pub library: ShaderLibrary,
    make: Box<dyn FnMut(anysl_rsl::ir::Module) -> Result<S, String>>,
    cache: HashMap<String, S>,
    /// Shaders of earlier frames with their parameters set (and, for the JIT, compiled),
    /// handed back by [`Surfaces::keep`] for the next frame to reuse.
    kept: Vec<(ShaderCall, S)>,
}

impl<S: SurfaceShader + Clone> Surfaces<S> {
    /// Shaders made by `make` from each shader's compiled module.
    pub fn new(library: ShaderLibrary, make: impl FnMut(anysl_rsl::ir::Module) -> Result<S, String> + 'static) -> Self {
        Self { library, make: Box::new(make), cache: HashMap::new(), kept: Vec::new() }
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

    /// A fresh instance of shader `name` with its defaults.
    ///
    /// # Errors
    /// The shader cannot be found or compiled.
    pub fn instance(&mut self, name: &str) -> Result<S, String> {
        if let Some(s) = self.cache.get(name) {
            return Ok(s.clone());
        }
        let module = self.library.module(name)?;
        let shader = (self.make)(module).map_err(|e| format!("shader \"{name}\": {e}"))?;
        self.cache.insert(name.to_string(), shader.clone());
        Ok(shader)
    }
}

impl Surfaces<InterpShader> {
    /// Shaders run by the batched interpreter (optimized IR).
    #[must_use]
    pub fn interpreter(library: ShaderLibrary) -> Self {
        Self::new(library, |mut m| {
            anysl_rsl::passes::optimize(&mut m, &anysl_rsl::passes::PassOptions::default());
            Program::new(m).map(|p| InterpShader::new(Arc::new(p))).map_err(|e| e.to_string())
        })
    }
}

/// A frame ready to render: the scene of its samples and what it takes to make pixels of
/// them.
pub struct FrameScene<S> {
    /// The renderer scene; its camera renders one pixel per film sample.
    pub scene: Scene<S, Light>,
    /// The samples' window.
    pub window: SampleWindow,
    /// Warnings (parameters that do not fit, unsupported lights).
    pub warnings: Vec<String>,
}

/// Builds the renderer scene of `frame` with surface shaders from `surfaces`.
///
/// # Errors
/// A surface shader that cannot be found or compiled, or inconsistent geometry.
pub fn frame_scene<S: SurfaceShader + Clone>(
    frame: &FrameDesc,
    surfaces: &mut Surfaces<S>,
) -> Result<FrameScene<S>, String> {
    let mut warnings = Vec::new();
    let mut shaders = Vec::with_capacity(frame.surfaces.len());
    for call in &frame.surfaces {
        let (s, w) = surfaces.for_call(call)?;
        warnings.extend(w);
        shaders.push(s);
    }
    let mut lights = Vec::new();
    for call in &frame.lights {
        match standard_light(call) {
            Ok((light, w)) => {
                warnings.extend(w);
                lights.push(light);
            }
            Err(e) => warnings.push(format!("{e}; the light is left out")),
        }
    }
    if shaders.is_empty() {
        // A world without primitives still needs a shader slot.
        shaders.push(surfaces.instance("defaultsurface")?);
    }
    let window = SampleWindow::of(&frame.film);
    let (w, h) = window.sample_size();
    let camera = Camera::from_spec(&window.camera(&frame.camera, &frame.film), w, h);
    let scene =
        Scene::new(camera, &frame.meshes, frame.instances.clone(), shaders, lights).map_err(|e| e.to_string())?;
    Ok(FrameScene { scene, window, warnings })
}

impl<S> FrameScene<S> {
    /// The frame's pixels (crop window, row-major RGBA before exposure, alpha = coverage)
    /// from the renderer's `image` of the samples (rendered at one sample per pixel).
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
        reconstruct(film, &self.window, &samples)
    }
}
