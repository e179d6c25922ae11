//! Named coordinate systems as a shader sees them: [`Spaces`], the table a renderer hands to
//! the shaders of one batch (through [`crate::ShadingContext::spaces`]).
//!
//! Matrices follow RSL's row-vector convention ([`Matrix4`]): `p' = p · M`. Each entry holds
//! the matrix from its space to `current` (the space shading happens in) and its inverse,
//! both in f64, so every back end takes the same numbers and only rounds them to its float.
//!
//! ```
//! use anysl_core::{Matrix4, Spaces, Vec3};
//! // "object" is translated by (1, 2, 3) from current space.
//! let mut t = [0.0; 16];
//! for i in 0..4 { t[i * 5] = 1.0; }
//! t[12..15].copy_from_slice(&[1.0, 2.0, 3.0]);
//! let spaces = Spaces::new([("object", t)]);
//! let p = spaces.from_current::<f32>("object").transform_point(Vec3::new(1.0, 2.0, 3.0));
//! assert_eq!(p, Vec3::new(0.0, 0.0, 0.0));
//! // Names every renderer has are the identity when a table does not list them.
//! assert_eq!(Spaces::standard().to_current::<f32>("camera"), Matrix4::identity());
//! ```

use crate::{Matrix4, ShadingFloat};
use std::collections::BTreeSet;
use std::sync::{Arc, Mutex};

/// The names RSL defines for every renderer (`"eye"` is an old name of `"camera"`).
pub const STANDARD_SPACES: &[&str] =
    &["current", "object", "shader", "world", "camera", "screen", "raster", "NDC", "eye"];

/// The space whose `z` is RSL `depth()`: camera-space depth mapped to 0 at the near and 1 at
/// the far clipping plane (0 everywhere for a far plane at infinity). The front end lowers
/// `depth(p)` to `zcomp(transform("__depth", p))`; a renderer that knows its camera puts the
/// space in its table; without it (no camera) `depth(p)` is the `z` of `p` in current space.
pub const DEPTH_SPACE: &str = "__depth";

/// One named space: its matrix to `current` and back.
#[derive(Clone, Debug, PartialEq)]
struct Entry {
    name: String,
    to_current: [f64; 16],
    from_current: [f64; 16],
}

/// A table of named coordinate systems, uniform over the points shaded together.
///
/// A lookup of a name the table does not hold gives the identity: silently for the standard
/// names ([`STANDARD_SPACES`], which are all the shading space when a renderer supplies no
/// table), with a warning on standard error once per name and process for any other name
/// (as prman does).
///
/// Cloning is cheap (the entries are shared).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Spaces {
    entries: Option<Arc<Vec<Entry>>>,
}

static STANDARD: Spaces = Spaces { entries: None };
static WARNED: Mutex<BTreeSet<String>> = Mutex::new(BTreeSet::new());

/// The inverse of a row-by-row matrix (zero when it is singular).
fn inverse_rows(m: [f64; 16]) -> [f64; 16] {
    let inv = Matrix4::<f64>::from_array(m).inverse();
    core::array::from_fn(|i| inv.m[i / 4][i % 4])
}

const IDENTITY: [f64; 16] = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];

impl Spaces {
    /// The table of a context without named spaces: every standard name is `current`.
    #[must_use]
    pub fn standard() -> &'static Self {
        &STANDARD
    }

    /// A table of `(name, matrix from that space to current)` in row-vector convention, row
    /// by row (`"current"` is always the identity and need not be given). A singular matrix
    /// gets the zero matrix as its inverse.
    #[must_use]
    pub fn new<'a>(spaces: impl IntoIterator<Item = (&'a str, [f64; 16])>) -> Self {
        let mut t = Self::default();
        for (name, m) in spaces {
            t.insert(name, m);
        }
        t
    }

    /// Adds (or replaces) space `name` with matrix `to_current` (see [`Spaces::new`]).
    pub fn insert(&mut self, name: &str, to_current: [f64; 16]) {
        let from_current = inverse_rows(to_current);
        self.put(Entry { name: name.to_string(), to_current, from_current });
    }

    fn put(&mut self, e: Entry) {
        let entries = Arc::make_mut(self.entries.get_or_insert_with(Arc::default));
        match entries.iter_mut().find(|x| x.name == e.name) {
            Some(x) => *x = e,
            None => entries.push(e),
        }
    }

    /// Adds (or replaces) space `name` given by its matrix *from* current (row vectors, row by
    /// row); the matrix to current is its inverse (zero when it is singular, as a depth space
    /// with the far plane at infinity is).
    pub fn insert_from_current(&mut self, name: &str, from_current: [f64; 16]) {
        let to_current = inverse_rows(from_current);
        self.put(Entry { name: name.to_string(), to_current, from_current });
    }

    /// Whether the table holds nothing (every standard name is `current`).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.entries().is_empty()
    }

    fn entries(&self) -> &[Entry] {
        self.entries.as_deref().map_or(&[], Vec::as_slice)
    }

    /// The names the table holds.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.entries().iter().map(|e| e.name.as_str())
    }

    fn entry(&self, name: &str) -> Option<&Entry> {
        let name = if name == "eye" { "camera" } else { name };
        if name == "current" {
            return None;
        }
        let e = self.entries().iter().find(|e| e.name == name);
        if e.is_none() && !STANDARD_SPACES.contains(&name) && name != DEPTH_SPACE {
            warn_unknown(name);
        }
        e
    }

    /// The matrix from space `name` to `current`, row by row (f64).
    #[must_use]
    pub fn to_current_f64(&self, name: &str) -> [f64; 16] {
        self.entry(name).map_or(IDENTITY, |e| e.to_current)
    }

    /// The matrix from `current` to space `name`, row by row (f64).
    #[must_use]
    pub fn from_current_f64(&self, name: &str) -> [f64; 16] {
        self.entry(name).map_or(IDENTITY, |e| e.from_current)
    }

    /// The matrix from space `from` to space `to`, row by row (the product taken in f64).
    #[must_use]
    pub fn between_f64(&self, from: &str, to: &str) -> [f64; 16] {
        let m = Matrix4::<f64>::from_array(self.to_current_f64(from)) * Matrix4::from_array(self.from_current_f64(to));
        core::array::from_fn(|i| m.m[i / 4][i % 4])
    }

    /// The matrix from space `name` to `current`: what `point "name" (…)` applies.
    #[must_use]
    pub fn to_current<F: ShadingFloat>(&self, name: &str) -> Matrix4<F> {
        Matrix4::from_array(self.to_current_f64(name))
    }

    /// The matrix from `current` to space `name`: what `transform("name", p)` applies.
    #[must_use]
    pub fn from_current<F: ShadingFloat>(&self, name: &str) -> Matrix4<F> {
        Matrix4::from_array(self.from_current_f64(name))
    }

    /// The matrix from space `from` to space `to`: what `transform("from", "to", p)` applies.
    #[must_use]
    pub fn between<F: ShadingFloat>(&self, from: &str, to: &str) -> Matrix4<F> {
        Matrix4::from_array(self.between_f64(from, to))
    }
}

/// Warns about an unknown space name on standard error, once per name and process.
#[cold]
fn warn_unknown(name: &str) {
    let mut w = WARNED.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if w.insert(name.to_string()) {
        eprintln!("warning: unknown coordinate system \"{name}\" (taken as the current space)");
    }
}

/// Whether a lookup warned that space `name` is unknown (in this process).
#[must_use]
pub fn warned_unknown(name: &str) -> bool {
    WARNED.lock().unwrap_or_else(std::sync::PoisonError::into_inner).contains(name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vec3;

    fn translate(x: f64, y: f64, z: f64) -> [f64; 16] {
        let mut t = IDENTITY;
        t[12..15].copy_from_slice(&[x, y, z]);
        t
    }

    #[test]
    fn to_from_and_between_compose() {
        let s = Spaces::new([("a", translate(1.0, 0.0, 0.0)), ("b", translate(0.0, 2.0, 0.0))]);
        let p = Vec3::new(0.0f64, 0.0, 0.0);
        assert_eq!(s.to_current::<f64>("a").transform_point(p), Vec3::new(1.0, 0.0, 0.0));
        assert_eq!(s.from_current::<f64>("b").transform_point(p), Vec3::new(0.0, -2.0, 0.0));
        // From a to b: (0,0,0) in a is (1,0,0) in current, (1,-2,0) in b.
        assert_eq!(s.between::<f64>("a", "b").transform_point(p), Vec3::new(1.0, -2.0, 0.0));
        // Vectors ignore the translation.
        assert_eq!(s.between::<f64>("a", "b").transform_vector(Vec3::new(0.0, 0.0, 1.0)), Vec3::new(0.0, 0.0, 1.0));
        assert_eq!(s.to_current::<f64>("current"), Matrix4::identity());
    }

    #[test]
    fn unknown_names_warn_once_and_are_the_identity() {
        let s = Spaces::new([("a", translate(1.0, 0.0, 0.0))]);
        assert!(!warned_unknown("no such space"));
        assert_eq!(s.to_current::<f32>("no such space"), Matrix4::identity());
        assert!(warned_unknown("no such space"));
        // Standard names are the identity without a warning.
        assert_eq!(Spaces::standard().from_current::<f32>("raster"), Matrix4::identity());
        assert!(!warned_unknown("raster"));
    }
}
