//! The front end's entry points: source text or a file in, one checked [`ir::Module`] out.
//!
//! ```
//! use anysl_rsl::{compile_source, CompileOptions};
//! let src = "surface matte(float Kd = 1;) { Ci = Kd * Cs * diffuse(normalize(N)); }";
//! let out = compile_source("matte.sl", src, &CompileOptions::default()).unwrap();
//! assert_eq!(out.module.name, "matte");
//! assert_eq!(out.module.params[0].name, "Kd");
//!
//! let err = compile_source("bad.sl", "surface bad() { Ci = foo; }", &CompileOptions::default()).unwrap_err();
//! assert!(err.to_string().contains("unknown variable `foo`"));
//! ```

use crate::diag::Diagnostics;
use crate::front::{self, lower, PpOptions};
use crate::ir;
use crate::span::SourceMap;
use std::fmt;
use std::path::{Path, PathBuf};

/// Options of one compilation.
#[derive(Clone, Debug, Default)]
pub struct CompileOptions {
    /// `#include` search path (after the directory of the file itself).
    pub include_dirs: Vec<PathBuf>,
    /// `-D NAME[=VALUE]` definitions.
    pub defines: Vec<(String, Option<String>)>,
    /// Which shader to compile when the file defines several.
    pub shader: Option<String>,
}

impl CompileOptions {
    fn pp(&self) -> PpOptions {
        PpOptions { include_dirs: self.include_dirs.clone(), defines: self.defines.clone() }
    }
}

/// A successful compilation.
#[derive(Clone, Debug)]
pub struct Compiled {
    /// The shader.
    pub module: ir::Module,
    /// Every file read (for rendering the warnings).
    pub sources: SourceMap,
    /// Warnings (no errors).
    pub warnings: Diagnostics,
}

/// A failed compilation: the diagnostics and the files they point into.
#[derive(Clone, Debug)]
pub struct CompileError {
    /// Every file read.
    pub sources: SourceMap,
    /// Errors and warnings, in the order found.
    pub diags: Diagnostics,
}

impl fmt::Display for CompileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.diags.render(&self.sources))
    }
}

impl std::error::Error for CompileError {}

/// Compiles RSL source text (`name` is shown in diagnostics and its directory searched for
/// includes).
pub fn compile_source(name: &str, text: &str, opts: &CompileOptions) -> Result<Compiled, CompileError> {
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let unit = front::parse_source(&mut sources, name, text, &opts.pp(), &mut diags);
    finish(unit, sources, diags, opts)
}

/// Compiles the RSL file at `path`.
pub fn compile_file(path: &Path, opts: &CompileOptions) -> Result<Compiled, CompileError> {
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let unit = front::parse_file(&mut sources, path, &opts.pp(), &mut diags);
    finish(unit, sources, diags, opts)
}

/// Compiles every shader the RSL file at `path` defines, in file order, as PRMan's `shader`
/// command does with a file of several shaders (`opts.shader`, when given, picks one). A file
/// with no shader or one, or with syntax errors, gives one result.
pub fn compile_file_all(path: &Path, opts: &CompileOptions) -> Vec<Result<Compiled, CompileError>> {
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let unit = front::parse_file(&mut sources, path, &opts.pp(), &mut diags);
    let names: Vec<String> = unit
        .items
        .iter()
        .filter_map(|i| if let front::ast::Item::Shader(s) = i { Some(s.name.name.clone()) } else { None })
        .collect();
    if opts.shader.is_some() || names.len() < 2 || diags.has_errors() {
        return vec![finish(unit, sources, diags, opts)];
    }
    names
        .into_iter()
        .map(|n| {
            let one = CompileOptions { shader: Some(n), ..opts.clone() };
            finish(unit.clone(), sources.clone(), diags.clone(), &one)
        })
        .collect()
}

fn finish(
    unit: front::ast::Unit,
    sources: SourceMap,
    mut diags: Diagnostics,
    opts: &CompileOptions,
) -> Result<Compiled, CompileError> {
    // Check even after syntax errors (the parser recovers), so one run shows more.
    let module = lower::lower_unit(&unit, opts.shader.as_deref(), &mut diags);
    match module {
        Some(module) if !diags.has_errors() => Ok(Compiled { module, sources, warnings: diags }),
        _ => Err(CompileError { sources, diags }),
    }
}
