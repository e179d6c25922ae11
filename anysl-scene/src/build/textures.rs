//! RIB texture requests: `MakeTexture`, `MakeLatLongEnvironment`, `MakeCubeFaceEnvironment`
//! register their output name with the run-time texture store ([`anysl_rt::texture`]), so a
//! shader's later look-up of that name reads the source picture with the request's wrap modes
//! and filter. The map is built in memory on first use; no texture file is written.
//!
//! Where pictures and textures are found: as named (relative to the working directory), then
//! in the directories of `Option "searchpath" "texture"` (relative entries taken relative to
//! the RIB file), then in the RIB file's directory. The store's search list is per process:
//! directories are added, in that order, as files are read.

use anysl_rib::{BuildError, Loc};
use anysl_rt::texture::{self, Filter, MakeSpec, MapKind, Wrap};
use std::path::{Path, PathBuf};

/// The directory of the RIB file `loc` is in (`None` for a name without one).
fn rib_dir(loc: &Loc) -> Option<PathBuf> {
    Path::new(&*loc.name).parent().filter(|p| !p.as_os_str().is_empty()).map(Path::to_path_buf)
}

/// Adds the texture search directories `paths` (relative ones taken relative to the RIB
/// file of `loc`), then that file's directory.
pub(super) fn add_search_dirs(loc: &Loc, paths: &[PathBuf]) {
    let base = rib_dir(loc);
    let mut dirs: Vec<PathBuf> = paths
        .iter()
        .map(|p| match &base {
            Some(b) if p.is_relative() => b.join(p),
            _ => p.clone(),
        })
        .collect();
    dirs.extend(base);
    texture::add_search_path(dirs);
}

fn wrap(name: &str, which: &str) -> Result<Wrap, BuildError> {
    Wrap::from_name(name).ok_or_else(|| {
        BuildError::error(format!("{which} \"{name}\" is not a wrap mode"))
            .with_note("use \"periodic\", \"clamp\" or \"black\"")
    })
}

/// The look-up filter of a `Make*` request's `filter` (RenderMan's pixel filter names): box
/// and Gaussian as named; the others are read as box, with a warning.
fn filter(name: &str) -> (Filter, Option<String>) {
    match name {
        "box" => (Filter::Box, None),
        "gaussian" => (Filter::Gaussian, None),
        other => (Filter::Box, Some(format!("filter \"{other}\" is not implemented for textures: box is used"))),
    }
}

fn widths(swidth: f32, twidth: f32) -> Result<(), BuildError> {
    if swidth.is_finite() && twidth.is_finite() && swidth >= 0.0 && twidth >= 0.0 {
        Ok(())
    } else {
        Err(BuildError::error(format!("filter widths {swidth} {twidth}: expected two finite numbers ≥ 0")))
    }
}

/// Registers `texture` as made from `sources`; the outcome of the request.
#[allow(clippy::too_many_arguments)]
pub(super) fn make(
    loc: &Loc,
    kind: MapKind,
    sources: Vec<String>,
    name: &str,
    wrap_modes: (&str, &str),
    filter_name: &str,
    swidth: f32,
    twidth: f32,
    fov: f32,
) -> Result<(), BuildError> {
    widths(swidth, twidth)?;
    if !(fov.is_finite() && fov > 0.0 && fov < 180.0) {
        return Err(BuildError::error(format!("field of view {fov}: expected degrees in (0, 180)")));
    }
    let wrap = (wrap(wrap_modes.0, "swrap")?, wrap(wrap_modes.1, "twrap")?);
    add_search_dirs(loc, &[]);
    let (filter, warning) = filter(filter_name);
    texture::make(name, MakeSpec { kind, sources, wrap, filter, fov: f64::from(fov) });
    match warning {
        Some(w) => Err(BuildError::warning(w)),
        None => Ok(()),
    }
}
