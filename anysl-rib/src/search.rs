//! Search paths: `Option "searchpath" "shader" ["dir1:@:&"]`.

use std::collections::BTreeMap;
use std::path::PathBuf;

/// Search paths by kind (`"shader"`, `"texture"`, `"archive"`, `"resource"`, …).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SearchPaths {
    paths: BTreeMap<String, Vec<PathBuf>>,
}

impl SearchPaths {
    /// No paths of any kind.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The paths of `kind`, in search order (empty when never set).
    #[must_use]
    pub fn get(&self, kind: &str) -> &[PathBuf] {
        self.paths.get(kind).map_or(&[], Vec::as_slice)
    }

    /// Sets the paths of `kind`.
    pub fn set(&mut self, kind: impl Into<String>, paths: Vec<PathBuf>) {
        self.paths.insert(kind.into(), paths);
    }

    /// Builder-style [`SearchPaths::set`].
    #[must_use]
    pub fn with(mut self, kind: impl Into<String>, paths: Vec<PathBuf>) -> Self {
        self.set(kind, paths);
        self
    }

    /// Every kind that has paths, with its paths.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &[PathBuf])> {
        self.paths.iter().map(|(k, v)| (k.as_str(), v.as_slice()))
    }

    /// Expands a RIB search path value: `:`-separated entries where `@` stands for the default
    /// paths of `kind` (from `defaults`) and `&` for the current paths of `kind`.
    #[must_use]
    pub fn expand(&self, kind: &str, value: &str, defaults: &SearchPaths) -> Vec<PathBuf> {
        let mut out = Vec::new();
        for entry in value.split(':').map(str::trim).filter(|e| !e.is_empty()) {
            match entry {
                "@" => out.extend_from_slice(defaults.get(kind)),
                "&" => out.extend_from_slice(self.get(kind)),
                _ => out.push(PathBuf::from(entry)),
            }
        }
        out
    }
}
