//! A RenderMan RIB reader: `.rib` → tokens with locations → requests → a builder interface.
//!
//! The reader knows no renderer. It lexes ASCII RIB (gzip-compressed files are detected and
//! decompressed), parses each request's positional arguments and parameter list, resolves
//! parameter types from inline declarations, `Declare` and the predeclared names, follows
//! `ReadArchive` through the archive search path, and calls one [`RibBuilder`] method per
//! request with its location. Malformed RIB yields a [`RibError`] that renders as
//! codespan-style diagnostics (`error[R021]: …`, `--> file:line:col`, the line, a caret).
//!
//! ```
//! use anysl_rib::{parse_str, Options, RibBuilder, BuildError, Loc, ParamList};
//!
//! /// Counts spheres and their total radius; every other request is "unsupported".
//! #[derive(Default)]
//! struct Spheres { count: usize, radii: f32 }
//!
//! impl RibBuilder for Spheres {
//!     fn sphere(&mut self, _loc: &Loc, radius: f32, _zmin: f32, _zmax: f32, _thetamax: f32,
//!               _params: &ParamList) -> Result<(), BuildError> {
//!         self.count += 1;
//!         self.radii += radius;
//!         Ok(())
//!     }
//! }
//!
//! let rib = r#"
//! WorldBegin
//!   Surface "plastic" "Ks" [0.5]
//!   Sphere 1 -1 1 360
//!   AttributeBegin Translate 0 0 2 Sphere 0.5 -0.5 0.5 360 AttributeEnd
//! WorldEnd
//! "#;
//! let mut spheres = Spheres::default();
//! let report = parse_str("scene.rib", rib, &mut spheres, &Options::default()).unwrap();
//! assert_eq!((spheres.count, spheres.radii), (2, 1.5));
//! // One warning per request name the builder does not support.
//! assert!(report.render_warnings().contains("unsupported request `Surface`"));
//!
//! // Errors point at the place: file, line, column, the line and a caret.
//! let err = parse_str("bad.rib", "Sphere 1 -1\n", &mut Spheres::default(), &Options::default())
//!     .unwrap_err();
//! assert!(err.render().contains("--> bad.rib:1:1"));
//! ```

#![warn(missing_docs)]

mod args;
mod builder;
mod diag;
mod lex;
mod param;
mod read;
mod requests;
mod search;
mod source;

pub use builder::{Basis, BuildError, BuildErrorKind, Handle, Matrix};
pub use diag::{codes, render, Diagnostic, RibError, Severity};
pub use lex::{LexError, Lexer, Token, TokenKind};
pub use param::{predeclared, Class, Decl, DeclOrigin, Param, ParamList, Type, ValueKind, Values};
pub use requests::{Recorder, Request, RibBuilder};
pub use search::SearchPaths;
pub use source::{FileId, Loc, SourceFile, SourceMap};

use std::path::Path;

/// Settings of one run of the reader.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Options {
    /// The default search paths: the starting value of each kind, and what `@` stands for.
    pub search_paths: SearchPaths,
    /// Reading stops with an error after this many requests (archives replayed many times
    /// count each time), so no input can keep the reader busy forever.
    pub max_requests: u64,
    /// Reading stops after this many errors.
    pub max_errors: usize,
    /// Deepest `ReadArchive` nesting.
    pub max_archive_depth: usize,
}

impl Options {
    /// No default search paths, 100 million requests, 100 errors, archives 64 deep.
    #[must_use]
    pub fn new() -> Self {
        Self { search_paths: SearchPaths::new(), max_requests: 100_000_000, max_errors: 100, max_archive_depth: 64 }
    }

    /// These options with `search_paths` as the default search paths.
    #[must_use]
    pub fn with_search_paths(mut self, search_paths: SearchPaths) -> Self {
        self.search_paths = search_paths;
        self
    }
}

impl Default for Options {
    fn default() -> Self {
        Self::new()
    }
}

/// What a successful read leaves besides the builder's work.
#[derive(Clone, Debug)]
pub struct Report {
    /// Warnings (unknown and unsupported requests, undeclared parameters, builder warnings).
    pub warnings: Vec<Diagnostic>,
    /// The search paths at the end of the input.
    pub search_paths: SearchPaths,
    /// The files read (for rendering the warnings).
    pub sources: SourceMap,
    /// Number of requests read (each replay of an archive counts again).
    pub requests: u64,
}

impl Report {
    /// Renders the warnings as codespan-style text (empty when there are none).
    #[cold]
    #[must_use]
    pub fn render_warnings(&self) -> String {
        render(&self.warnings, &self.sources)
    }
}

fn finish(outcome: read::Outcome) -> Result<Report, RibError> {
    if outcome.errors > 0 {
        return Err(RibError { diagnostics: outcome.diagnostics, sources: outcome.sources });
    }
    Ok(Report {
        warnings: outcome.diagnostics,
        search_paths: outcome.search_paths,
        sources: outcome.sources,
        requests: outcome.requests,
    })
}

/// Reads the RIB file at `path` (plain or gzip-compressed) into `builder`.
///
/// `ReadArchive` names are looked up relative to the reading file's directory, then along the
/// `"archive"` search path.
///
/// The builder is a trait object (as in the three functions here): the reader and its
/// dispatch on request names are compiled once, in this crate, not in every crate that reads
/// RIB (a call per request through a vtable costs nothing next to tokenizing).
pub fn parse_file(path: impl AsRef<Path>, builder: &mut dyn RibBuilder, options: &Options) -> Result<Report, RibError> {
    parse_path(path.as_ref(), builder, options)
}

fn parse_path(path: &Path, builder: &mut dyn RibBuilder, options: &Options) -> Result<Report, RibError> {
    finish(read::Reader::new(builder, options).read_path(path))
}

/// Reads RIB text named `name` (the name is shown in diagnostics) into `builder`.
///
/// `ReadArchive` names are looked up relative to the current directory, then along the
/// `"archive"` search path.
pub fn parse_str(name: &str, text: &str, builder: &mut dyn RibBuilder, options: &Options) -> Result<Report, RibError> {
    parse_bytes(name, text.as_bytes(), builder, options)
}

/// Reads RIB bytes (plain or gzip-compressed) named `name` into `builder`.
pub fn parse_bytes(
    name: &str,
    bytes: &[u8],
    builder: &mut dyn RibBuilder,
    options: &Options,
) -> Result<Report, RibError> {
    finish(read::Reader::new(builder, options).read_bytes(name, bytes))
}
