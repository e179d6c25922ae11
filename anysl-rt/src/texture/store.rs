//! The maps of a run: what `Make*` requests registered, where image files are searched, and
//! the decoded pyramids, each loaded once on first use and shared by every thread.
//!
//! A name is resolved in this order: a map registered by [`make`] or [`insert`] under that
//! name; else an image file of that name — as given, then in each search directory
//! ([`add_search_path`]); a name ending in `.tex`, `.tx` or `.tdl` that is not found is tried
//! again with the same stem and the image extensions `.tif`, `.tiff`, `.png`, `.exr`, `.jpg`
//! (old scenes ship the `.tif` beside a `.tex` they never made). A name found nowhere warns once
//! and reads as missing.

use super::mip::{Filter, MipMap, Wrap};
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock, PoisonError, RwLock};

/// What a map is for (RenderMan's texture file types).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapKind {
    /// `MakeTexture`, or an image read directly by `texture()`.
    Texture,
    /// `MakeLatLongEnvironment`, or an image read directly by `environment()`.
    LatLong,
    /// `MakeCubeFaceEnvironment`: six faces.
    CubeFace,
    /// `MakeShadow`, or a depth pass rendered in memory.
    Shadow,
}

impl MapKind {
    /// The name `textureinfo(…, "type", …)` reports.
    #[must_use]
    pub fn type_name(self) -> &'static str {
        match self {
            Self::Texture => "texture",
            Self::LatLong | Self::CubeFace => "environment",
            Self::Shadow => "shadow",
        }
    }
}

/// A `Make*` request: the images it reads and how the result is filtered.
#[derive(Clone, Debug, PartialEq)]
pub struct MakeSpec {
    /// What it makes.
    pub kind: MapKind,
    /// The source pictures (one; six for a cube: px nx py ny pz nz).
    pub sources: Vec<String>,
    /// `swrap`, `twrap`.
    pub wrap: (Wrap, Wrap),
    /// The filter look-ups use unless they name one.
    pub filter: Filter,
    /// A cube's full field of view per face, in degrees.
    pub fov: f64,
}

/// A depth map's camera: world to the light's camera space, and camera space to the screen
/// window [-1, 1]² (the RenderMan "screen" space of the pass; x right, y up).
#[derive(Clone, Debug, PartialEq)]
pub struct DepthCamera {
    /// World → camera (column vectors, column-major).
    pub world_to_camera: [f64; 16],
    /// Camera → screen (column vectors, column-major; divide by w).
    pub projection: [f64; 16],
}

/// A loaded map.
#[derive(Clone, Debug)]
pub struct Map {
    /// What it is.
    pub kind: MapKind,
    /// Its images: one, or six cube faces.
    pub faces: Vec<MipMap>,
    /// Wrap modes of `texture()` look-ups.
    pub wrap: (Wrap, Wrap),
    /// The filter of look-ups that name none.
    pub filter: Filter,
    /// A cube's field of view per face, degrees.
    pub fov: f64,
    /// A shadow map's camera.
    pub camera: Option<DepthCamera>,
}

impl Map {
    /// A texture map over one image, periodic, box-filtered.
    #[must_use]
    pub fn texture(image: MipMap) -> Self {
        Self {
            kind: MapKind::Texture,
            faces: vec![image],
            wrap: (Wrap::Periodic, Wrap::Periodic),
            filter: Filter::Box,
            fov: 90.0,
            camera: None,
        }
    }

    /// Channels of its images.
    #[must_use]
    pub fn channels(&self) -> usize {
        self.faces[0].channels()
    }
}

#[derive(Default)]
struct Store {
    made: HashMap<String, MakeSpec>,
    search: Vec<PathBuf>,
    maps: HashMap<String, Option<Arc<Map>>>,
    warned: HashSet<String>,
}

fn store() -> &'static RwLock<Store> {
    static STORE: OnceLock<RwLock<Store>> = OnceLock::new();
    STORE.get_or_init(|| RwLock::new(Store::default()))
}

/// Prints `message` on stderr the first time `key` is seen in this run.
pub fn warn_once(key: &str, message: impl FnOnce() -> String) {
    let mut s = store().write().unwrap_or_else(PoisonError::into_inner);
    if s.warned.insert(key.to_string()) {
        eprintln!("{}", message());
    }
}

/// Appends directories to the image search path (each once, in order).
pub fn add_search_path(dirs: impl IntoIterator<Item = PathBuf>) {
    let mut s = store().write().unwrap_or_else(PoisonError::into_inner);
    for d in dirs {
        if !s.search.contains(&d) {
            s.search.push(d);
        }
    }
}

/// Registers what `name` is made of (a RIB `Make*` request); a map already loaded under that
/// name is dropped so the next look-up reads the new one.
pub fn make(name: &str, spec: MakeSpec) {
    let mut s = store().write().unwrap_or_else(PoisonError::into_inner);
    s.maps.remove(name);
    s.made.insert(name.to_string(), spec);
}

/// Registers a map built in memory (a rendered depth pass) under `name`.
pub fn insert(name: &str, map: Map) {
    let mut s = store().write().unwrap_or_else(PoisonError::into_inner);
    s.made.remove(name);
    // Maps made from the old one are made again on their next look-up.
    let stale: Vec<String> =
        s.made.iter().filter(|(_, sp)| sp.sources.iter().any(|x| x == name)).map(|(k, _)| k.clone()).collect();
    for k in stale {
        s.maps.remove(&k);
    }
    s.maps.insert(name.to_string(), Some(Arc::new(map)));
}

/// Forgets every map, registration, search directory and warning (a new run).
pub fn clear() {
    *store().write().unwrap_or_else(PoisonError::into_inner) = Store::default();
}

/// The map `name`, loading it on first use; `kind` says how an image read directly is used.
/// `None` (warned once) when it cannot be found or read.
pub fn map(name: &str, kind: MapKind) -> Option<Arc<Map>> {
    if name.is_empty() || name == "raytrace" {
        return None;
    }
    if let Some(m) = store().read().unwrap_or_else(PoisonError::into_inner).maps.get(name) {
        return m.clone();
    }
    let (spec, search, in_memory) = {
        let s = store().read().unwrap_or_else(PoisonError::into_inner);
        let spec = s.made.get(name).cloned();
        // `MakeShadow "pass.z" "pass.shad"` of a depth pass rendered in memory.
        let in_memory = spec
            .as_ref()
            .filter(|sp| sp.sources.len() == 1)
            .and_then(|sp| s.maps.get(&sp.sources[0]).cloned().flatten().map(|m| (sp.kind, m)));
        (spec, s.search.clone(), in_memory)
    };
    if let Some((kind, m)) = in_memory {
        let mut m = (*m).clone();
        m.kind = kind;
        let mut s = store().write().unwrap_or_else(PoisonError::into_inner);
        return s.maps.entry(name.to_string()).or_insert(Some(Arc::new(m))).clone();
    }
    let spec = spec.unwrap_or_else(|| MakeSpec {
        kind: if kind == MapKind::Texture { MapKind::Texture } else { MapKind::LatLong },
        sources: vec![name.to_string()],
        wrap: match kind {
            MapKind::Texture => (Wrap::Periodic, Wrap::Periodic),
            _ => (Wrap::Periodic, Wrap::Clamp),
        },
        filter: Filter::Box,
        fov: 90.0,
    });
    let loaded = load(name, &spec, &search);
    let mut s = store().write().unwrap_or_else(PoisonError::into_inner);
    let out = match loaded {
        Ok(m) => Some(Arc::new(m)),
        Err(e) => {
            if s.warned.insert(name.to_string()) {
                eprintln!("warning[W0003]: texture \"{name}\": {e}; it reads as missing");
            }
            None
        }
    };
    s.maps.entry(name.to_string()).or_insert(out).clone()
}

/// Image extensions tried for a missing `.tex`/`.tx`/`.tdl`.
const IMAGE_EXTENSIONS: [&str; 5] = ["tif", "tiff", "png", "exr", "jpg"];

/// The file `name` names, through the search path and the stem fallback.
///
/// # Errors
/// A message listing what was tried.
pub fn resolve(name: &str, search: &[PathBuf]) -> Result<PathBuf, String> {
    let given = Path::new(name);
    let mut places = vec![given.to_path_buf()];
    if given.is_relative() {
        places.extend(search.iter().map(|d| d.join(given)));
    }
    if let Some(p) = places.iter().find(|p| p.is_file()) {
        return Ok(p.clone());
    }
    let ext = given.extension().and_then(|e| e.to_str()).unwrap_or("");
    if matches!(ext, "tex" | "tx" | "tdl") {
        for p in &places {
            for e in IMAGE_EXTENSIONS {
                let q = p.with_extension(e);
                if q.is_file() {
                    return Ok(q);
                }
            }
        }
        let stem = given.with_extension("");
        return Err(format!(
            "no such file (nor {} with an image extension: {}){}",
            stem.display(),
            IMAGE_EXTENSIONS.join(", "),
            searched(search)
        ));
    }
    Err(format!("no such file{}", searched(search)))
}

fn searched(search: &[PathBuf]) -> String {
    if search.is_empty() {
        String::new()
    } else {
        let dirs: Vec<String> = search.iter().map(|d| d.display().to_string()).collect();
        format!(" in the working directory or {}", dirs.join(", "))
    }
}

/// Decodes an image file into a pyramid keeping its channels (1 to 4).
///
/// # Errors
/// The decoder's message.
pub fn read_image(path: &Path) -> Result<MipMap, String> {
    let img = image::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let (w, h) = (img.width() as usize, img.height() as usize);
    if w == 0 || h == 0 {
        return Err(format!("{}: the image is empty", path.display()));
    }
    let (channels, data) = match img.color().channel_count() {
        1 => (1, img.to_luma32f().into_raw()),
        2 => (2, img.to_luma_alpha32f().into_raw()),
        3 => (3, img.to_rgb32f().into_raw()),
        _ => (4, img.to_rgba32f().into_raw()),
    };
    Ok(MipMap::new(w, h, channels, data))
}

fn load(name: &str, spec: &MakeSpec, search: &[PathBuf]) -> Result<Map, String> {
    let mut faces = Vec::with_capacity(spec.sources.len());
    for src in &spec.sources {
        let path = resolve(src, search).map_err(|e| if src == name { e } else { format!("{src}: {e}") })?;
        faces.push(read_image(&path)?);
    }
    if faces.is_empty() {
        return Err("no source images".into());
    }
    Ok(Map { kind: spec.kind, faces, wrap: spec.wrap, filter: spec.filter, fov: spec.fov, camera: None })
}
