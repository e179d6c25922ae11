//! The front end: preprocessor, lexer, parser, checker and lowering to IR.
//!
//! Parsing never panics and always ends, whatever the input: problems become
//! [`Diagnostic`](crate::diag::Diagnostic)s and the parser recovers, so one run reports several.
//!
//! ```
//! use anysl_rsl::diag::Diagnostics;
//! use anysl_rsl::front::{self, ast, PpOptions};
//! use anysl_rsl::span::SourceMap;
//!
//! let mut sources = SourceMap::new();
//! let mut diags = Diagnostics::new();
//! let src = "surface matte(float Kd = 1;) { Ci = Kd * Cs; }";
//! let unit = front::parse_source(&mut sources, "matte.sl", src, &PpOptions::default(), &mut diags);
//! assert!(!diags.has_errors());
//! assert!(matches!(unit.items[0], ast::Item::Shader(_)));
//! ```

pub mod ast;
pub mod lex;
pub mod parse;
pub mod pp;

pub use pp::{FsLoader, PpOptions, SourceLoader};

use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::span::{SourceMap, Span};
use std::path::Path;

/// Preprocesses and parses `text` (shown as `name` in diagnostics; `#include "…"` is searched
/// first in the directory part of `name`, then in `opts.include_dirs`), reading includes from
/// disk.
pub fn parse_source(
    sources: &mut SourceMap,
    name: &str,
    text: &str,
    opts: &PpOptions,
    diags: &mut Diagnostics,
) -> ast::Unit {
    parse_source_with(sources, name, text, opts, &mut FsLoader, diags)
}

/// [`parse_source`] with includes read through `loader` (e.g. from memory).
pub fn parse_source_with(
    sources: &mut SourceMap,
    name: &str,
    text: &str,
    opts: &PpOptions,
    loader: &mut dyn SourceLoader,
    diags: &mut Diagnostics,
) -> ast::Unit {
    let file = sources.add(name, None, text);
    let tokens = pp::preprocess(sources, file, opts, loader, diags);
    parse::parse_tokens(&tokens, diags)
}

/// Reads, preprocesses and parses the file at `path` from disk. A file that cannot be read is
/// reported as a diagnostic (and gives an empty unit).
pub fn parse_file(sources: &mut SourceMap, path: &Path, opts: &PpOptions, diags: &mut Diagnostics) -> ast::Unit {
    parse_file_with(sources, path, opts, &mut FsLoader, diags)
}

/// [`parse_file`] with the file and its includes read through `loader`.
pub fn parse_file_with(
    sources: &mut SourceMap,
    path: &Path,
    opts: &PpOptions,
    loader: &mut dyn SourceLoader,
    diags: &mut Diagnostics,
) -> ast::Unit {
    let name = path.to_string_lossy().into_owned();
    match loader.load(path) {
        Ok(text) => {
            let file = sources.add(name, Some(path.to_path_buf()), text);
            let tokens = pp::preprocess(sources, file, opts, loader, diags);
            parse::parse_tokens(&tokens, diags)
        }
        Err(why) => {
            // An empty stand-in file so the diagnostic has somewhere to point.
            let file = sources.add(name.clone(), Some(path.to_path_buf()), "");
            diags.push(
                Diagnostic::error(
                    codes::INCLUDE_NOT_FOUND,
                    Span::new(file, 0, 0),
                    format!("cannot read `{name}`: {why}"),
                )
                .with_label("file not read"),
            );
            ast::Unit::default()
        }
    }
}
pub mod lower;
