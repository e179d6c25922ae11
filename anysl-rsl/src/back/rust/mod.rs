//! Back end A: generated Rust. One shader module in, the Rust source of one shader out — a
//! parameter struct with metadata and set-by-name, and the `SurfaceShader` / `LightShader` /
//! `DisplacementShader` impl, generic over [`ShadingFloat`](anysl_core::ShadingFloat) with
//! masked control flow.
//!
//! ```
//! use anysl_rsl::back::rust::{generate, RustOptions};
//! use anysl_rsl::passes::{optimize, PassOptions};
//! use anysl_rsl::{compile_source, CompileOptions};
//! let src = "surface matte(float Kd = 1;) { Ci = Kd * Cs * diffuse(normalize(N)); }";
//! let c = compile_source("matte.sl", src, &CompileOptions::default()).unwrap();
//! let rust = generate(&optimize(c.module, &PassOptions::default()), &RustOptions::default()).unwrap();
//! assert!(rust.contains("pub struct Matte"));
//! assert!(rust.contains("impl ::anysl_core::SurfaceShader for Matte"));
//! ```
//!
//! # How the IR becomes Rust
//!
//! * **Uniform values are scalars.** A value the uniform analysis proves the same for every
//!   shading point, computed from constants and uniform parameters only, is an `f64` (or
//!   `Vec3<f64>`, `bool`, `&str`, …) — computed once per call, in double precision (as the
//!   hand-written shaders fold their parameter arithmetic) — and enters varying arithmetic
//!   through `F::c`. Every other value is `F`, `Vec3<F>`, `F::Mask`, …. The same generic
//!   `anysl_core::stdlib` functions serve both (f64 is a `ShadingFloat` too).
//! * **SSA values** are `let vN = …;`, **slots** `let mut sN_name`, written with
//!   `Blend::blend` under the current mask, or plainly where the mask is provably full (the
//!   top level of the body before any divergent exit).
//! * **Uniform branches and loops are Rust `if`s and `loop`s**; `break`/`continue`/`return`
//!   reached through uniform control flow only are Rust `break`s to labelled loops and blocks.
//!   Varying branches compute `then`/`else` masks and skip an arm no lane enters (`.any()`);
//!   varying loops carry a live mask and break/continue masks per loop level; `return` under
//!   varying control flow collects the returning lanes in a per-frame mask — the semantics of
//!   the batched interpreter's executor, statement for statement.
//! * `illuminance` is `ctx.illuminance(e, LightQuery::new(category, P, cone), |e, L, Cl| …)`; a `break` stops
//!   visiting lights for those lanes. The closure cannot use the context, so `ambient`,
//!   `diffuse`, `specular`, `phong`, `trace` and nested light loops inside a light-loop body
//!   are generation errors.
//! * Interval loops that keep a "maybe" condition are left after
//!   [`INTERVAL_LOOP_LIMIT`](anysl_core::INTERVAL_LOOP_LIMIT) iterations (without the widened
//!   last pass of `Exec::loop_`).
//!
//! # Files
//!
//! * this module: the options, the entry points, and the generator's state (`Gen`) with its
//!   output helpers;
//! * `analysis.rs`: scalar or lane representation of every value, native or masked exits;
//! * `items.rs`: the parameter struct, the `Shader` and shader-kind impls, the body's prologue;
//! * `flow.rs`: statements and control flow under masks, light loops;
//! * `expr.rs`: Rust types, constants and the expression of each instruction;
//! * `builtin.rs`: the built-in call dispatcher.
//!
//! The generated code calls the run-time library `anysl_rt` (textures, `format`, `match`, …).

mod analysis;
mod builtin;
mod expr;
mod flow;
mod items;

use crate::diag::{Diagnostic, Diagnostics};
use crate::ir::{Const, Function, Module, Node, Op};
use crate::passes::{optimize, Analyzed, PassOptions};
use crate::span::{SourceMap, Span};
use crate::types::BaseType;
use crate::{compile_file, CompileError, CompileOptions};
use flow::{FrameCtx, LoopCtx};
use std::collections::HashMap;
use std::path::Path;

/// Options of the Rust generator.
#[derive(Clone, Debug)]
pub struct RustOptions {
    /// Name of the generated type (default: the shader name in CamelCase, e.g. `PointLight`
    /// for `pointlight` — see [`type_name`]).
    pub type_name: Option<String>,
    /// Path of `anysl_core` in the generated code.
    pub core: String,
    /// Path of the run-time library (`anysl_rt`) in the generated code.
    pub runtime: String,
    /// Emit a `// file:line: source` comment before the code of each source line (when the
    /// sources are known).
    pub line_comments: bool,
    /// Start with `use <core>::prelude::*;` (off when several shaders go into one module that
    /// imports the prelude once).
    pub prelude: bool,
}

impl Default for RustOptions {
    fn default() -> Self {
        Self {
            type_name: None,
            core: "::anysl_core".into(),
            runtime: "::anysl_rt".into(),
            line_comments: true,
            prelude: true,
        }
    }
}

/// Why a module cannot become Rust: a diagnostic pointing at the construct.
#[derive(Clone, Debug)]
pub struct GenError(pub Diagnostic);

impl std::fmt::Display for GenError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "error[{}]: {}", self.0.code, self.0.message)
    }
}

impl std::error::Error for GenError {}

/// Error code of generation errors.
pub const GEN_ERROR: &str = "E0900";

/// The default Rust type name of a shader: known names get their conventional spelling
/// (`pointlight` → `PointLight`), others are CamelCased at `_` and digits (`t_mix_color` →
/// `TMixColor`).
#[must_use]
pub fn type_name(shader: &str) -> String {
    let known = [
        ("pointlight", "PointLight"),
        ("distantlight", "DistantLight"),
        ("spotlight", "SpotLight"),
        ("ambientlight", "AmbientLight"),
        ("shinymetal", "ShinyMetal"),
        ("paintedplastic", "PaintedPlastic"),
    ];
    if let Some((_, t)) = known.iter().find(|(n, _)| *n == shader) {
        return (*t).to_string();
    }
    let mut out = String::new();
    let mut up = true;
    for c in shader.chars() {
        if c.is_ascii_alphanumeric() {
            if up {
                out.extend(c.to_uppercase());
            } else {
                out.push(c);
            }
            up = c.is_ascii_digit();
        } else {
            up = true;
        }
    }
    if out.is_empty() || out.starts_with(|c: char| c.is_ascii_digit()) {
        out.insert(0, 'S');
    }
    out
}

/// Compiles the RSL file at `path` and generates Rust for it (what `anysl rslc rust` prints).
///
/// # Errors
/// The front end's diagnostics, or a generation error rendered the same way.
pub fn generate_file(path: &Path, copts: &CompileOptions, opts: &RustOptions) -> Result<String, CompileError> {
    let c = compile_file(path, copts)?;
    let a = optimize(c.module.clone(), &PassOptions::default());
    generate_with_sources(&a, Some(&c.sources), opts).map_err(|e| {
        let mut diags = Diagnostics::new();
        diags.push(e.0);
        CompileError { sources: c.sources.clone(), diags }
    })
}

/// Rust source for one shader (see the module docs).
///
/// # Errors
/// A construct generated Rust cannot express (a context call inside a light-loop body).
pub fn generate(module: &Analyzed, opts: &RustOptions) -> Result<String, GenError> {
    generate_with_sources(module, None, opts)
}

/// [`generate`] with the source files, for `// file:line` comments.
///
/// # Errors
/// See [`generate`].
pub fn generate_with_sources(
    module: &Analyzed,
    sources: Option<&SourceMap>,
    opts: &RustOptions,
) -> Result<String, GenError> {
    let mut g = Gen::new(module.module(), sources, opts, module.uses_derivatives());
    g.module()?;
    Ok(g.out)
}

// -------------------------------------------------------------------------------------------
// Representation of values: scalar (uniform, f64-based) or lanes (F-based).

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Repr {
    Scalar,
    Lane,
}

fn ident(name: &str) -> String {
    const KW: &[&str] = &[
        "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for", "if", "impl",
        "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return", "static", "struct", "super",
        "trait", "true", "type", "unsafe", "use", "where", "while", "async", "await", "dyn", "abstract", "become",
        "box", "do", "final", "macro", "override", "priv", "typeof", "unsized", "virtual", "yield", "try", "gen",
    ];
    let clean: String = name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
    if KW.contains(&clean.as_str()) {
        format!("r#{clean}")
    } else if clean == "self" || clean == "Self" || clean == "super" || clean == "crate" {
        format!("{clean}_")
    } else {
        clean
    }
}

fn lit(x: f64) -> String {
    if x.is_nan() {
        "f64::NAN".into()
    } else if x.is_infinite() {
        if x > 0.0 {
            "f64::INFINITY".into()
        } else {
            "f64::NEG_INFINITY".into()
        }
    } else {
        let s = format!("{x:?}");
        if s.starts_with('-') {
            format!("({s}_f64)")
        } else {
            format!("{s}_f64")
        }
    }
}

fn comps(base: BaseType) -> [&'static str; 3] {
    if base == BaseType::Color {
        ["r", "g", "b"]
    } else {
        ["x", "y", "z"]
    }
}

fn tri_ty(base: BaseType) -> &'static str {
    if base == BaseType::Color {
        "Color"
    } else {
        "Vec3"
    }
}

fn key(n: &Node) -> usize {
    std::ptr::from_ref(n) as usize
}

struct Gen<'a> {
    m: &'a Module,
    f: &'a Function,
    sources: Option<&'a SourceMap>,
    opts: &'a RustOptions,
    uses_derivatives: bool,
    vr: Vec<Repr>,
    sr: Vec<Repr>,
    stored: Vec<bool>,
    consts: Vec<Option<Const>>,
    out: String,
    ind: usize,
    counter: usize,
    mask: String,
    full: bool,
    in_closure: bool,
    frames: Vec<(FrameCtx, Vec<LoopCtx>)>,
    loop_native: HashMap<usize, bool>,
    frame_native: HashMap<usize, bool>,
    exit_native: HashMap<usize, bool>,
    last_line: Option<(u32, usize)>,
    ty: String,
    k: String,
}

impl<'a> Gen<'a> {
    fn new(m: &'a Module, sources: Option<&'a SourceMap>, opts: &'a RustOptions, uses_derivatives: bool) -> Self {
        let f = &m.func;
        let consts = f.insts.iter().map(|i| if let Op::Const(c) = &i.op { Some(c.clone()) } else { None }).collect();
        let mut g = Self {
            m,
            f,
            sources,
            opts,
            uses_derivatives,
            vr: vec![Repr::Scalar; f.insts.len()],
            sr: vec![Repr::Scalar; f.slots.len()],
            stored: vec![false; f.slots.len()],
            consts,
            out: String::new(),
            ind: 0,
            counter: 0,
            mask: "m0".into(),
            full: true,
            in_closure: false,
            frames: Vec::new(),
            loop_native: HashMap::new(),
            frame_native: HashMap::new(),
            exit_native: HashMap::new(),
            last_line: None,
            ty: opts.type_name.clone().unwrap_or_else(|| type_name(&m.name)),
            k: opts.core.clone(),
        };
        g.reprs();
        g.classify();
        g
    }

    // ---------------------------------------------------------------------------------------
    // Output helpers.

    fn line(&mut self, s: &str) {
        for _ in 0..self.ind {
            self.out.push_str("    ");
        }
        self.out.push_str(s);
        self.out.push('\n');
    }

    fn fresh(&mut self, p: &str) -> String {
        self.counter += 1;
        format!("{p}{}", self.counter)
    }

    fn err(&self, span: Span, msg: impl Into<String>) -> GenError {
        GenError(Diagnostic::error(GEN_ERROR, span, msg))
    }

    fn source_comment(&mut self, span: Span) {
        if !self.opts.line_comments {
            return;
        }
        let Some(src) = self.sources else { return };
        if (span.file.0 as usize) >= src.files().len() {
            return;
        }
        let file = src.get(span.file);
        let (l, _) = file.line_col(span.start);
        if self.last_line == Some((span.file.0, l)) {
            return;
        }
        self.last_line = Some((span.file.0, l));
        let name = Path::new(&file.name).file_name().map_or(file.name.clone(), |n| n.to_string_lossy().into_owned());
        let text = file.line_text(l).trim().to_string();
        self.line(&format!("// {name}:{}: {text}", l + 1));
    }

    fn node_span(&self, n: &Node) -> Option<Span> {
        match n {
            Node::Inst(v) => Some(self.f.inst(*v).span),
            Node::Store { value, .. } => Some(self.f.inst(*value).span),
            Node::If { cond, .. } => Some(self.f.inst(*cond).span),
            Node::Loop { cond: Some(c), .. } => Some(self.f.inst(*c).span),
            Node::Illuminance { position, .. } | Node::Illuminate { position, .. } => Some(self.f.inst(*position).span),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests;
