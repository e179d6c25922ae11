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
//! * `illuminance` is `ctx.illuminance(e, category, P, cone, |e, L, Cl| …)`; a `break` stops
//!   visiting lights for those lanes. The closure cannot use the context, so `ambient`,
//!   `diffuse`, `specular`, `phong`, `trace` and nested light loops inside a light-loop body
//!   are generation errors.
//! * Interval loops that keep a "maybe" condition are left after
//!   [`INTERVAL_LOOP_LIMIT`](anysl_core::INTERVAL_LOOP_LIMIT) iterations (without the widened
//!   last pass of `Exec::loop_`).

use crate::builtins::Builtin;
use crate::diag::{Diagnostic, Diagnostics};
use crate::ir::{BinOp, Const, Function, Global, Module, Node, Op, ShaderKind, SlotId, SlotKind, UnOp, Value};
use crate::passes::{optimize, Analyzed, PassOptions};
use crate::span::{SourceMap, Span};
use crate::types::{BaseType, Detail, Type};
use crate::{compile_file, CompileError, CompileOptions};
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

/// A native (Rust control flow) or masked construct that exits target.
#[derive(Clone, Debug)]
enum LoopCtx {
    Native { brk: String, cont: String },
    Masked { brk: String, cont: String },
    Light { brk: String },
}

#[derive(Clone, Debug)]
enum FrameCtx {
    Native(String),
    Masked(String),
    LightBody,
}

#[derive(Clone, Copy, Debug)]
enum Enc {
    If(bool),
    Loop(usize),
    Frame(usize),
    Light,
    Region,
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
    // Analyses of the generator.

    fn is_string(&self, t: Type) -> bool {
        t.base == BaseType::String
    }

    /// Scalar or lanes for every value and slot (optimistic scalar, lowered to a fixed point).
    fn reprs(&mut self) {
        let f = self.f;
        for (i, s) in f.slots.iter().enumerate() {
            let varying = s.ty.detail == Detail::Varying && !self.is_string(s.ty);
            self.sr[i] = if varying { Repr::Lane } else { Repr::Scalar };
        }
        let mut stores: Vec<Vec<Value>> = vec![Vec::new(); f.slots.len()];
        let mut out_calls: Vec<Vec<Value>> = vec![Vec::new(); f.slots.len()];
        crate::ir::walk(&f.body, &mut |n| match n {
            Node::Store { slot, value, .. } => stores[slot.0 as usize].push(*value),
            Node::Inst(v) => {
                if let Op::Call { outputs, .. } = &f.inst(*v).op {
                    for s in outputs.iter().flatten() {
                        out_calls[s.0 as usize].push(*v);
                    }
                }
            }
            _ => {}
        });
        for (i, s) in stores.iter().enumerate() {
            self.stored[i] = !s.is_empty() || !out_calls[i].is_empty();
        }
        loop {
            let mut changed = false;
            for (i, inst) in f.insts.iter().enumerate() {
                if self.vr[i] == Repr::Lane {
                    continue;
                }
                let lane = if self.is_string(inst.ty) {
                    false
                } else {
                    inst.ty.detail == Detail::Varying
                        || inst
                            .args
                            .iter()
                            .any(|a| self.vr[a.0 as usize] == Repr::Lane && !self.is_string(f.inst(*a).ty))
                        || match &inst.op {
                            Op::Load(s) | Op::LoadElem(s) => self.sr[s.0 as usize] == Repr::Lane,
                            Op::Call { builtin, .. } => builtin.lane_only(),
                            _ => false,
                        }
                };
                if lane {
                    self.vr[i] = Repr::Lane;
                    changed = true;
                }
            }
            for s in 0..f.slots.len() {
                if self.sr[s] == Repr::Lane || self.is_string(f.slots[s].ty) {
                    continue;
                }
                if stores[s].iter().chain(&out_calls[s]).any(|v| self.vr[v.0 as usize] == Repr::Lane) {
                    self.sr[s] = Repr::Lane;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
    }

    fn scalar_value(&self, v: Value) -> bool {
        self.vr[v.0 as usize] == Repr::Scalar
    }

    /// Which loops and frames run as Rust control flow, and which exits are Rust `break`s.
    fn classify(&mut self) {
        let f = self.f;
        crate::ir::walk(&f.body, &mut |n| {
            if let Node::Loop { cond, .. } = n {
                let native = cond.is_none_or(|c| self.vr[c.0 as usize] == Repr::Scalar);
                self.loop_native.insert(key(n), native);
            }
            if let Node::Frame(_) = n {
                self.frame_native.insert(key(n), true);
            }
        });
        self.frame_native.insert(0, true);
        loop {
            let mut changed = false;
            let mut enc = vec![Enc::Frame(0)];
            let body = &f.body;
            self.classify_block(body, &mut enc, &mut changed);
            if !changed {
                break;
            }
        }
    }

    fn classify_block(&mut self, block: &'a [Node], enc: &mut Vec<Enc>, changed: &mut bool) {
        for n in block {
            match n {
                Node::If { cond, then, otherwise } => {
                    enc.push(Enc::If(self.scalar_value(*cond)));
                    self.classify_block(then, enc, changed);
                    self.classify_block(otherwise, enc, changed);
                    enc.pop();
                }
                Node::Loop { header, body, step, .. } => {
                    enc.push(Enc::Loop(key(n)));
                    self.classify_block(header, enc, changed);
                    self.classify_block(body, enc, changed);
                    self.classify_block(step, enc, changed);
                    enc.pop();
                }
                Node::Frame(b) => {
                    enc.push(Enc::Frame(key(n)));
                    self.classify_block(b, enc, changed);
                    enc.pop();
                }
                Node::Illuminance { body, .. } => {
                    enc.push(Enc::Light);
                    self.classify_block(body, enc, changed);
                    enc.pop();
                }
                Node::Illuminate { body, .. } | Node::Solar { body, .. } => {
                    enc.push(Enc::Region);
                    self.classify_block(body, enc, changed);
                    enc.pop();
                }
                Node::Break(_) | Node::Continue(_) | Node::Return => {
                    let (target, path) = Self::target(n, enc);
                    let path_native = path.iter().all(|e| match e {
                        Enc::If(s) => *s,
                        Enc::Loop(k) => self.loop_native.get(k).copied().unwrap_or(false),
                        _ => false,
                    });
                    let target_native = match target {
                        Some(Enc::Loop(k)) => {
                            if !path_native && self.loop_native.get(&k) == Some(&true) {
                                self.loop_native.insert(k, false);
                                *changed = true;
                            }
                            self.loop_native.get(&k).copied().unwrap_or(false)
                        }
                        Some(Enc::Frame(k)) => {
                            if !path_native && self.frame_native.get(&k) == Some(&true) {
                                self.frame_native.insert(k, false);
                                *changed = true;
                            }
                            self.frame_native.get(&k).copied().unwrap_or(false)
                        }
                        Some(Enc::Light) => true,
                        _ => false,
                    };
                    self.exit_native.insert(key(n), path_native && target_native);
                }
                Node::Inst(_) | Node::Store { .. } => {}
            }
        }
    }

    /// The construct an exit leaves and the constructs between it and the exit (innermost
    /// first). `None`: no target (the lanes just stop, as in the interpreter).
    fn target(n: &Node, enc: &[Enc]) -> (Option<Enc>, Vec<Enc>) {
        let mut path = Vec::new();
        match n {
            Node::Return => {
                for e in enc.iter().rev() {
                    match e {
                        Enc::Frame(_) | Enc::Light => return (Some(*e), path),
                        _ => path.push(*e),
                    }
                }
                (None, path)
            }
            Node::Break(level) | Node::Continue(level) => {
                let mut left = *level;
                for e in enc.iter().rev() {
                    match e {
                        Enc::Loop(_) | Enc::Light => {
                            if left == 0 {
                                return (Some(*e), path);
                            }
                            if matches!(e, Enc::Light) {
                                return (None, path);
                            }
                            left -= 1;
                            path.push(*e);
                        }
                        Enc::Frame(_) => return (None, path),
                        _ => path.push(*e),
                    }
                }
                (None, path)
            }
            _ => (None, path),
        }
    }

    /// True when the block (not counting nested frames' returns) holds an exit.
    fn has_exit(block: &[Node]) -> bool {
        block.iter().any(|n| match n {
            Node::Break(_) | Node::Continue(_) | Node::Return => true,
            Node::Frame(b) => Self::has_break(b),
            Node::Illuminance { .. } => false,
            _ => n.blocks().iter().any(|b| Self::has_exit(b)),
        })
    }

    /// Breaks/continues anywhere (they may leave a frame as "no target").
    fn has_break(block: &[Node]) -> bool {
        block.iter().any(|n| match n {
            Node::Break(_) | Node::Continue(_) => true,
            Node::Illuminance { .. } => false,
            _ => n.blocks().iter().any(|b| Self::has_break(b)),
        })
    }

    /// True when some exit in the block is a mask operation.
    fn has_masked_exit(&self, block: &[Node]) -> bool {
        block.iter().any(|n| match n {
            Node::Break(_) | Node::Continue(_) | Node::Return => {
                !self.exit_native.get(&key(n)).copied().unwrap_or(false)
            }
            Node::Illuminance { .. } => false,
            _ => n.blocks().iter().any(|b| self.has_masked_exit(b)),
        })
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

    // ---------------------------------------------------------------------------------------
    // Types and values.

    fn base_ty(&self, base: BaseType, r: Repr) -> String {
        let t = if r == Repr::Scalar { "f64" } else { "F" };
        match base {
            BaseType::Float | BaseType::Void => t.to_string(),
            BaseType::Color => format!("Color<{t}>"),
            BaseType::Point | BaseType::Vector | BaseType::Normal => format!("Vec3<{t}>"),
            BaseType::Matrix => format!("Matrix4<{t}>"),
            BaseType::String => "&str".into(),
        }
    }

    fn rust_ty(&self, t: Type, is_bool: bool, r: Repr) -> String {
        let el = if is_bool {
            if r == Repr::Scalar {
                "bool".into()
            } else {
                "F::Mask".into()
            }
        } else {
            self.base_ty(t.base, r)
        };
        match t.array {
            Some(n) => format!("[{el}; {n}]"),
            None => el,
        }
    }

    fn slot_ty(&self, s: SlotId) -> String {
        let slot = self.f.slot(s);
        if slot.ty.base == BaseType::String {
            return match slot.ty.array {
                Some(n) => format!("[String; {n}]"),
                None => "String".into(),
            };
        }
        self.rust_ty(slot.ty, false, self.sr[s.0 as usize])
    }

    fn slot_var(&self, s: SlotId) -> String {
        format!("s{}_{}", s.0, ident(&self.f.slot(s).name).trim_start_matches("r#"))
    }

    /// A constant in representation `r`.
    fn const_expr(&self, c: &Const, base: BaseType, r: Repr) -> String {
        let f = |x: f64| if r == Repr::Scalar { lit(x) } else { format!("F::c({})", lit(x)) };
        match c {
            Const::Float(x) => match base {
                b if b.is_triple() => format!("{}::splat({})", tri_ty(b), f(*x)),
                BaseType::Matrix => format!("Matrix4::scalar({})", f(*x)),
                _ => f(*x),
            },
            Const::Triple(t) => format!("{}::new({}, {}, {})", tri_ty(base), f(t[0]), f(t[1]), f(t[2])),
            Const::Matrix(m) => {
                let t = if r == Repr::Scalar { "f64" } else { "F" };
                format!(
                    "Matrix4::<{t}>::from_array([{}])",
                    m.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(", ")
                )
            }
            Const::Str(s) => format!("{s:?}"),
            Const::Array(items) => {
                format!("[{}]", items.iter().map(|i| self.const_expr(i, base, r)).collect::<Vec<_>>().join(", "))
            }
        }
    }

    /// Lifts a scalar expression (a variable or field) of type `t` to lanes.
    fn lift(&self, e: &str, t: Type, is_bool: bool) -> String {
        if t.array.is_some() {
            let inner = self.lift("x", t.element(), is_bool);
            return format!("{e}.map(|x| {inner})");
        }
        if is_bool {
            return format!("<F::Mask as Mask>::splat({e})");
        }
        match t.base {
            BaseType::Float => format!("F::c({e})"),
            b if b.is_triple() => {
                let [a, bb, c] = comps(b);
                format!("{}::<F>::c({e}.{a}, {e}.{bb}, {e}.{c})", tri_ty(b))
            }
            BaseType::Matrix => format!("Matrix4::<F> {{ m: {e}.m.map(|r| r.map(F::c)) }}"),
            _ => e.to_string(),
        }
    }

    /// The expression of value `v` in representation `want`.
    fn val(&self, v: Value, want: Repr) -> String {
        let inst = self.f.inst(v);
        if let Some(c) = &self.consts[v.0 as usize] {
            if inst.ty.base == BaseType::String {
                return self.const_expr(c, inst.ty.base, Repr::Scalar);
            }
            return self.const_expr(c, inst.ty.base, want);
        }
        let name = format!("v{}", v.0);
        if self.vr[v.0 as usize] == want || inst.ty.base == BaseType::String {
            return name;
        }
        if want == Repr::Scalar {
            // Never needed by construction; keep the generated code compiling regardless.
            return format!("/* lane 0 */ {name}.lane(0)");
        }
        self.lift(&name, inst.ty, inst.is_bool)
    }

    fn exec_mut(&self) -> String {
        if self.full && self.mask == "m0" && !self.in_closure {
            "e".into()
        } else {
            format!("&mut Exec::with_mask({})", self.mask)
        }
    }

    /// `slot = value` under the current mask (`value` already in the slot's representation).
    fn assign(&mut self, var: &str, value: &str, r: Repr) {
        if r == Repr::Scalar || self.full {
            self.line(&format!("{var} = {value};"));
        } else {
            self.line(&format!("{var} = Blend::<F>::blend({}, {value}, {var});", self.mask));
        }
    }

    /// The value of `v` converted for a store into slot `s`.
    fn store_value(&self, v: Value, s: SlotId, elem: bool) -> String {
        let r = self.sr[s.0 as usize];
        let inst = self.f.inst(v);
        let st = if elem { self.f.slot(s).ty.element() } else { self.f.slot(s).ty };
        if inst.is_bool && !st.base.is_triple() {
            let b = self.val(v, r);
            return if r == Repr::Scalar {
                format!("if {b} {{ 1.0_f64 }} else {{ 0.0_f64 }}")
            } else {
                format!("F::select({b}, F::c(1.0), F::c(0.0))")
            };
        }
        let e = self.val(v, r);
        if inst.ty.base == BaseType::Float && st.base.is_triple() && inst.ty.array.is_none() {
            return format!("{}::splat({e})", tri_ty(st.base));
        }
        if inst.ty.base.is_triple()
            && st.base.is_triple()
            && (inst.ty.base == BaseType::Color) != (st.base == BaseType::Color)
        {
            return if st.base == BaseType::Color { format!("({e}).to_color()") } else { format!("({e}).to_vec()") };
        }
        e
    }

    // ---------------------------------------------------------------------------------------
    // The module.

    fn module(&mut self) -> Result<(), GenError> {
        let m = self.m;
        let k = self.k.clone();
        let ty = self.ty.clone();
        let kind_kw = match m.kind {
            ShaderKind::Surface => "surface",
            ShaderKind::Light => "light",
            ShaderKind::Displacement => "displacement",
            ShaderKind::Volume => "volume",
            ShaderKind::Imager => "imager",
        };
        if !matches!(m.kind, ShaderKind::Surface | ShaderKind::Light | ShaderKind::Displacement) {
            return Err(self.err(
                m.params.first().map_or_else(Span::default, |p| p.span),
                format!("generated Rust supports surface, light and displacement shaders, not {kind_kw} shaders"),
            ));
        }
        if self.opts.prelude {
            self.line(&format!("use {k}::prelude::*;"));
            self.line("");
        }
        self.line(&format!("/// RSL {kind_kw} `{}` (generated Rust; parameters are the RSL ones).", m.name));
        self.line("#[allow(non_snake_case, non_camel_case_types)]");
        self.line("#[derive(Clone, Debug, PartialEq)]");
        self.line(&format!("pub struct {ty} {{"));
        self.ind += 1;
        for p in &m.params {
            let d = if p.output { "output " } else { "" };
            self.line(&format!(
                "/// `{d}{} {}`{}",
                p.ty.detail,
                p.ty.base,
                p.ty.array.map_or(String::new(), |n| format!("[{n}]"))
            ));
            self.line(&format!("pub {}: {},", ident(&p.name), Self::param_field_ty(p.ty)));
        }
        self.ind -= 1;
        self.line("}");
        self.line("");
        // Default.
        self.line(&format!("impl Default for {ty} {{"));
        self.ind += 1;
        self.line("fn default() -> Self {");
        self.ind += 1;
        self.line("Self {");
        self.ind += 1;
        for p in &m.params {
            self.line(&format!("{}: {},", ident(&p.name), Self::param_default(&p.default, p.ty)));
        }
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        self.line("");
        self.shader_impl();
        self.line("");
        self.outputs_struct();
        self.line("");
        // The shading function.
        self.line("#[allow(non_snake_case, unused_mut, unused_variables, unused_assignments, unused_labels, unused_parens, unused_braces, unreachable_code, clippy::all)]");
        self.line(&format!("impl {ty} {{"));
        self.ind += 1;
        let res = format!("{ty}Result");
        match m.kind {
            ShaderKind::Light => {
                self.line("/// Runs the light shader for surface points `ps`: `Cl`, `L`, the lanes an `illuminate`/`solar` reached, and the output parameters.");
                self.line("#[inline(always)]");
                self.line(&format!("pub fn run<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> {res}<F> {{"));
                self.ind += 1;
                self.line("let zero = F::c(0.0);");
                self.line("let g = Globals { P: ps, N: Vec3::zero(), Ng: Vec3::zero(), I: Vec3::zero(), E: Vec3::zero(), s: zero, t: zero, u: zero, v: zero, du: zero, dv: zero, dPdu: Vec3::zero(), dPdv: Vec3::zero(), Cs: Color::zero(), Os: Color::zero() };");
            }
            _ => {
                self.line("/// Runs the shader: every output (`Ci`, `Oi`, `P`, `N` and the output parameters).");
                self.line("#[inline(always)]");
                self.line(&format!(
                    "pub fn run<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> {res}<F> {{"
                ));
                self.ind += 1;
                self.line("let g = *ctx.globals();");
            }
        }
        if m.uses_spaces() {
            // A copy (a reference count) so that the context stays free for `illuminance`.
            match m.kind {
                ShaderKind::Light => self.line(&format!("let spaces = {}::Spaces::standard();", self.k)),
                _ => self.line("let spaces = ctx.spaces().clone();"),
            }
        }
        self.line("let no: F::Mask = Mask::splat(false);");
        self.line("let mut m0 = e.mask();");
        self.line("let mut lit = no;");
        if m.kind == ShaderKind::Light && self.f.global_slot(Global::L).is_none() {
            // `L` as the light's output even when the body never names it.
            self.line("let mut light_l: Vec3<F> = Vec3::zero();");
        }
        self.slot_decls();
        let body = &m.func.body;
        let native = self.frame_native.get(&0).copied().unwrap_or(true);
        if native {
            self.frames.push((FrameCtx::Native("'body".into()), Vec::new()));
            self.line("'body: {");
            self.ind += 1;
            self.block(body)?;
            self.ind -= 1;
            self.line("}");
        } else {
            self.line("let mut ret0 = no;");
            self.frames.push((FrameCtx::Masked("ret0".into()), Vec::new()));
            self.block(body)?;
        }
        self.frames.pop();
        self.result_expr();
        self.ind -= 1;
        self.line("}");
        self.eval_values_fn();
        self.ind -= 1;
        self.line("}");
        self.line("");
        self.trait_impl();
        let _ = k;
        Ok(())
    }

    fn param_field_ty(t: Type) -> String {
        let el = match t.base {
            BaseType::Float | BaseType::Void => "f64",
            BaseType::String => "::std::string::String",
            BaseType::Matrix => "[f64; 16]",
            _ => "[f64; 3]",
        };
        match t.array {
            Some(n) => format!("[{el}; {n}]"),
            None => el.to_string(),
        }
    }

    fn param_default(c: &Const, t: Type) -> String {
        match c {
            Const::Float(x) => match t.base {
                b if b.is_triple() => format!("[{x:?}; 3]"),
                _ => format!("{x:?}"),
            },
            Const::Triple(v) => format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2]),
            Const::Matrix(m) => format!("[{}]", m.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(", ")),
            Const::Str(s) => format!("{s:?}.to_string()"),
            Const::Array(items) => {
                format!(
                    "[{}]",
                    items.iter().map(|i| Self::param_default(i, t.element())).collect::<Vec<_>>().join(", ")
                )
            }
        }
    }

    fn shader_impl(&mut self) {
        let m = self.m;
        let k = self.k.clone();
        let rt = self.opts.runtime.clone();
        let ty = self.ty.clone();
        self.line(&format!("impl {k}::Shader for {ty} {{"));
        self.ind += 1;
        self.line(&format!("fn meta(&self) -> {k}::ShaderMeta {{"));
        self.ind += 1;
        self.line(&format!("{k}::ShaderMeta {{"));
        self.ind += 1;
        self.line(&format!("name: {:?}.to_string(),", m.name));
        let kind = match m.kind {
            ShaderKind::Surface => "Surface",
            ShaderKind::Light => "Light",
            ShaderKind::Displacement => "Displacement",
            ShaderKind::Volume => "Volume",
            ShaderKind::Imager => "Imager",
        };
        self.line(&format!("kind: {k}::ShaderKind::{kind},"));
        self.line("params: vec![");
        self.ind += 1;
        for p in &m.params {
            let pt = match p.ty.base {
                BaseType::Float | BaseType::Void => "Float",
                BaseType::Color => "Color",
                BaseType::Point => "Point",
                BaseType::Vector => "Vector",
                BaseType::Normal => "Normal",
                BaseType::String => "String",
                BaseType::Matrix => "Matrix",
            };
            let storage = if p.ty.detail == Detail::Uniform { "Uniform" } else { "Varying" };
            self.line(&format!(
                "{k}::ParamInfo {{ name: {:?}.to_string(), ty: {k}::ParamType::{pt}, array_len: {:?}, default: {}, storage: {k}::Storage::{storage}, output: {} }},",
                p.name,
                p.ty.array.map(|n| n as usize),
                Self::param_value(&k, &p.default),
                p.output
            ));
        }
        self.ind -= 1;
        self.line("],");
        self.line(&format!("uses_derivatives: {},", self.uses_derivatives));
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        self.line(&format!("fn param(&self, name: &str) -> Option<{k}::ParamValue> {{"));
        self.ind += 1;
        self.line("match name {");
        self.ind += 1;
        for p in &m.params {
            let f = ident(&p.name);
            if p.ty.array.is_some() {
                self.line(&format!("{:?} => Some({rt}::array_value(&self.{f})),", p.name));
            } else {
                self.line(&format!("{:?} => Some({k}::ParamField::to_value(&self.{f})),", p.name));
            }
        }
        self.line("_ => None,");
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        self.line("#[allow(unreachable_code, unused_variables)]");
        self.line(&format!(
            "fn set_param(&mut self, name: &str, value: &{k}::ParamValue) -> Result<(), {k}::ParamError> {{"
        ));
        self.ind += 1;
        self.line("match name {");
        self.ind += 1;
        for p in &m.params {
            let f = ident(&p.name);
            let pt = match p.ty.base {
                BaseType::Float | BaseType::Void => "Float",
                BaseType::Color => "Color",
                BaseType::Point => "Point",
                BaseType::Vector => "Vector",
                BaseType::Normal => "Normal",
                BaseType::String => "String",
                BaseType::Matrix => "Matrix",
            };
            let conv = if p.ty.array.is_some() {
                format!("{rt}::array_from_value(value, &self.{f})")
            } else {
                format!("{k}::ParamField::from_value(value)")
            };
            self.line(&format!(
                "{:?} => {{ self.{f} = {conv}.ok_or_else(|| {k}::ParamError::Type {{ name: name.to_string(), expected: {k}::ParamType::{pt}, got: value.clone() }})?; Ok(()) }}",
                p.name
            ));
        }
        let known: Vec<String> = m.params.iter().map(|p| format!("{:?}.to_string()", p.name)).collect();
        self.line(&format!(
            "_ => Err({k}::ParamError::Unknown {{ shader: {:?}.to_string(), name: name.to_string(), known: vec![{}] }}),",
            m.name,
            known.join(", ")
        ));
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
    }

    fn param_value(k: &str, c: &Const) -> String {
        match c {
            Const::Float(x) => format!("{k}::ParamValue::Float({x:?})"),
            Const::Triple(t) => format!("{k}::ParamValue::Triple([{:?}, {:?}, {:?}])", t[0], t[1], t[2]),
            Const::Matrix(m) => format!(
                "{k}::ParamValue::Matrix([{}])",
                m.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(", ")
            ),
            Const::Str(s) => format!("{k}::ParamValue::String({s:?}.to_string())"),
            Const::Array(items) => format!(
                "{k}::ParamValue::Array(vec![{}])",
                items.iter().map(|i| Self::param_value(k, i)).collect::<Vec<_>>().join(", ")
            ),
        }
    }

    fn output_params(&self) -> Vec<(String, SlotId, Type)> {
        self.m.params.iter().filter(|p| p.output).map(|p| (p.name.clone(), p.slot, p.ty)).collect()
    }

    fn outputs_struct(&mut self) {
        let ty = self.ty.clone();
        let k = self.k.clone();
        self.line(&format!("/// Everything `{ty}::run` computes."));
        self.line("#[allow(non_snake_case)]");
        self.line("#[derive(Clone, Debug)]");
        self.line(&format!("pub struct {ty}Result<F: {k}::ShadingFloat> {{"));
        self.ind += 1;
        match self.m.kind {
            ShaderKind::Light => {
                self.line("/// `Cl`.");
                self.line(&format!("pub Cl: {k}::Color<F>,"));
                self.line("/// `L` (from the light to the surface point).");
                self.line(&format!("pub L: {k}::Vec3<F>,"));
                self.line("/// The lanes an `illuminate`/`solar` body ran for.");
                self.line("pub lit: F::Mask,");
            }
            _ => {
                self.line("/// `Ci`.");
                self.line(&format!("pub Ci: {k}::Color<F>,"));
                self.line("/// `Oi`.");
                self.line(&format!("pub Oi: {k}::Color<F>,"));
                self.line("/// `P` (displaced).");
                self.line(&format!("pub P: {k}::Vec3<F>,"));
                self.line("/// `N`.");
                self.line(&format!("pub N: {k}::Vec3<F>,"));
            }
        }
        for (name, _, t) in self.output_params() {
            let el = match t.base {
                BaseType::String => "::std::string::String".to_string(),
                BaseType::Float => "F".into(),
                BaseType::Color => format!("{k}::Color<F>"),
                BaseType::Matrix => format!("{k}::Matrix4<F>"),
                _ => format!("{k}::Vec3<F>"),
            };
            let full = match t.array {
                Some(n) => format!("[{el}; {n}]"),
                None => el,
            };
            self.line(&format!("/// Output parameter `{name}`."));
            self.line(&format!("pub {}: {full},", ident(&format!("out_{name}"))));
        }
        self.ind -= 1;
        self.line("}");
    }

    fn slot_decls(&mut self) {
        let f = self.f;
        let light = self.m.kind == ShaderKind::Light;
        for (i, slot) in f.slots.iter().enumerate() {
            let s = SlotId(i as u32);
            let r = self.sr[i];
            let var = self.slot_var(s);
            let ty = self.slot_ty(s);
            let init = match &slot.kind {
                SlotKind::Param(pi) => {
                    if !self.stored[i] && !self.m.params[*pi as usize].output {
                        continue; // read straight from `self`
                    }
                    self.param_read(*pi as usize, r, true)
                }
                SlotKind::Global(gl) => self.global_init(*gl, slot.ty, r, light),
                SlotKind::Local => self.zero(slot.ty, r),
            };
            self.line(&format!("let mut {var}: {ty} = {init};"));
        }
    }

    fn zero(&self, t: Type, r: Repr) -> String {
        let el = match t.base {
            BaseType::String => "String::new()".to_string(),
            BaseType::Float | BaseType::Void => {
                if r == Repr::Scalar {
                    "0.0_f64".into()
                } else {
                    "F::c(0.0)".into()
                }
            }
            BaseType::Matrix => format!("Matrix4::scalar({})", if r == Repr::Scalar { "0.0_f64" } else { "F::c(0.0)" }),
            b => format!("{}::zero()", tri_ty(b)),
        };
        match t.array {
            Some(n) if t.base == BaseType::String => {
                format!("::core::array::from_fn::<String, {n}, _>(|_| String::new())")
            }
            Some(n) => format!("[{el}; {n}]"),
            None => el,
        }
    }

    fn global_init(&self, gl: Global, t: Type, r: Repr, light: bool) -> String {
        let lane = r == Repr::Lane;
        let e = match gl {
            Global::P => "g.P",
            Global::N => "g.N",
            Global::Ng => "g.Ng",
            Global::I => "g.I",
            Global::E => "g.E",
            Global::Cs => "g.Cs",
            Global::Os => "g.Os",
            Global::S => "g.s",
            Global::T => "g.t",
            Global::U => "g.u",
            Global::V => "g.v",
            Global::Du => "g.du",
            Global::Dv => "g.dv",
            Global::DPdu => "g.dPdu",
            Global::DPdv => "g.dPdv",
            Global::Oi => {
                if light {
                    "Color::zero()"
                } else {
                    "g.Os"
                }
            }
            Global::Ps => {
                if light {
                    "ps"
                } else {
                    return self.zero(t, r);
                }
            }
            Global::Ncomps => return if lane { "F::c(3.0)".into() } else { "3.0_f64".into() },
            _ => return self.zero(t, r),
        };
        if lane {
            e.to_string()
        } else {
            format!("{e}.lane(0)")
        }
    }

    /// A parameter's value from `self` in representation `r`.
    fn param_read(&self, pi: usize, r: Repr, owned: bool) -> String {
        let p = &self.m.params[pi];
        let f = format!("self.{}", ident(&p.name));
        let conv = |e: &str, t: Type| -> String {
            match (t.base, r) {
                (BaseType::String, _) => {
                    if owned {
                        format!("{e}.clone()")
                    } else {
                        format!("{e}.as_str()")
                    }
                }
                (BaseType::Float, Repr::Scalar) => e.to_string(),
                (BaseType::Float, Repr::Lane) => format!("F::c({e})"),
                (BaseType::Matrix, Repr::Scalar) => format!("Matrix4::<f64>::from_array({e})"),
                (BaseType::Matrix, Repr::Lane) => format!("Matrix4::<F>::from_array({e})"),
                (b, Repr::Scalar) => format!("{}::<f64>::from_array({e})", tri_ty(b)),
                (b, Repr::Lane) => format!("{}::<F>::from_array({e})", tri_ty(b)),
            }
        };
        match p.ty.array {
            Some(_) if p.ty.base == BaseType::String => {
                if owned {
                    format!("{f}.clone()")
                } else {
                    format!("{f}.each_ref().map(|x| x.as_str())")
                }
            }
            Some(_) => {
                let inner = conv("x", p.ty.element());
                format!("{f}.map(|x| {inner})")
            }
            None => conv(&f, p.ty),
        }
    }

    fn result_expr(&mut self) {
        let ty = self.ty.clone();
        let slot = |g: Global| self.f.global_slot(g);
        let read = |this: &Self, g: Global, dflt: &str| match slot(g) {
            Some(s) if this.sr[s.0 as usize] == Repr::Lane => this.slot_var(s),
            Some(s) => this.lift(&this.slot_var(s), this.f.slot(s).ty, false),
            None => dflt.to_string(),
        };
        let mut fields = Vec::new();
        if self.m.kind == ShaderKind::Light {
            fields.push(format!("Cl: {}", read(self, Global::Cl, "Color::zero()")));
            fields.push(format!("L: {}", read(self, Global::L, "light_l")));
            let has_light = {
                let mut any = false;
                crate::ir::walk(&self.f.body, &mut |n| {
                    any |= matches!(n, Node::Illuminate { .. } | Node::Solar { .. });
                });
                any
            };
            fields.push(if has_light { "lit".into() } else { "lit: e.mask()".into() });
        } else {
            fields.push(format!("Ci: {}", read(self, Global::Ci, "Color::zero()")));
            fields.push(format!("Oi: {}", read(self, Global::Oi, "g.Os")));
            fields.push(format!("P: {}", read(self, Global::P, "g.P")));
            fields.push(format!("N: {}", read(self, Global::N, "g.N")));
        }
        for (name, s, t) in self.output_params() {
            let var = self.slot_var(s);
            let v = if t.base == BaseType::String {
                var
            } else if self.sr[s.0 as usize] == Repr::Lane {
                var
            } else {
                self.lift(&var, t, false)
            };
            fields.push(format!("{}: {v}", ident(&format!("out_{name}"))));
        }
        self.line(&format!("{ty}Result {{ {} }}", fields.join(", ")));
    }

    fn eval_values_fn(&mut self) {
        if self.m.kind == ShaderKind::Light {
            return;
        }
        self.line(
            "/// Lane `lane` of every output, by name (`Ci`, `Oi`, … and the output parameters), for test harnesses.",
        );
        if self.m.kind == ShaderKind::Light {
            return;
        }
        let ty = self.ty.clone();
        self.line(&format!(
            "pub fn values<F: ShadingFloat>(r: &{ty}Result<F>, lane: usize) -> Vec<(&'static str, Vec<f64>)> {{"
        ));
        self.ind += 1;
        self.line("let mut v: Vec<(&'static str, Vec<f64>)> = vec![(\"Ci\", r.Ci.lane(lane).to_vec()), (\"Oi\", r.Oi.lane(lane).to_vec())];");
        for (name, _, t) in self.output_params() {
            let f = ident(&format!("out_{name}"));
            let e = match (t.base, t.array) {
                (BaseType::String, _) => continue,
                (BaseType::Float, None) => format!("vec![r.{f}.lane(lane)]"),
                (BaseType::Float, Some(_)) => format!("r.{f}.iter().map(|x| x.lane(lane)).collect()"),
                (BaseType::Matrix, None) => format!("r.{f}.m.iter().flatten().map(|x| x.lane(lane)).collect()"),
                (BaseType::Matrix, Some(_)) => continue,
                (_, None) => format!("r.{f}.lane(lane).to_vec()"),
                (_, Some(_)) => format!("r.{f}.iter().flat_map(|x| x.lane(lane)).collect()"),
            };
            self.line(&format!("v.push(({name:?}, {e}));"));
        }
        self.line("v");
        self.ind -= 1;
        self.line("}");
    }

    fn trait_impl(&mut self) {
        let k = self.k.clone();
        let ty = self.ty.clone();
        match self.m.kind {
            ShaderKind::Surface => {
                self.line(&format!("impl {k}::SurfaceShader for {ty} {{"));
                self.ind += 1;
                let read = crate::passes::analysis::globals_read(self.m);
                self.line("#[inline(always)]");
                self.line(&format!("fn globals_read(&self) -> {k}::GlobalSet {{"));
                self.line(&format!("    {k}::GlobalSet({:#06x})", read.0));
                self.line("}");
                self.line("#[inline(always)]");
                self.line(&format!(
                    "fn shade<F: {k}::ShadingFloat, C: {k}::ShadingContext<F>>(&self, ctx: &mut C, e: &mut {k}::Exec<F>) -> {k}::SurfaceOutput<F> {{"
                ));
                self.line("    let r = self.run(ctx, e);");
                self.line(&format!("    {k}::SurfaceOutput {{ Ci: r.Ci, Oi: r.Oi }}"));
                self.line("}");
                self.ind -= 1;
                self.line("}");
            }
            ShaderKind::Displacement => {
                self.line(&format!("impl {k}::DisplacementShader for {ty} {{"));
                self.ind += 1;
                self.line("#[inline(always)]");
                self.line(&format!(
                    "fn displace<F: {k}::ShadingFloat, C: {k}::ShadingContext<F>>(&self, ctx: &mut C, e: &mut {k}::Exec<F>) -> ({k}::Vec3<F>, {k}::Vec3<F>) {{"
                ));
                self.line("    let r = self.run(ctx, e);");
                self.line("    (r.P, r.N)");
                self.line("}");
                self.ind -= 1;
                self.line("}");
            }
            ShaderKind::Light => {
                let mut ill = false;
                let mut sol = false;
                crate::ir::walk(&self.f.body, &mut |n| match n {
                    Node::Illuminate { .. } => ill = true,
                    Node::Solar { .. } => sol = true,
                    _ => {}
                });
                let (em, fixed) = match (ill, sol) {
                    (false, false) => ("Ambient", true),
                    (true, false) => ("Local", true),
                    (false, true) => ("Distant", true),
                    (true, true) => ("Local", false),
                };
                self.line(&format!("impl {k}::LightShader for {ty} {{"));
                self.ind += 1;
                self.line("#[inline(always)]");
                self.line(&format!("fn emission(&self) -> Option<{k}::Emission> {{"));
                self.line(&format!(
                    "    {}",
                    if fixed { format!("Some({k}::Emission::{em})") } else { "None".to_string() }
                ));
                self.line("}");
                if let Some(p) = self.m.params.iter().find(|p| p.name == "__category" && p.ty.base == BaseType::String)
                {
                    // RSL's `__category` parameter: what `illuminance("category", …)` selects on.
                    self.line("#[inline(always)]");
                    self.line(&format!("fn category(&self) -> &str {{ &self.{} }}", ident(&p.name)));
                }
                self.line("#[inline(always)]");
                self.line(&format!(
                    "fn light<F: {k}::ShadingFloat>(&self, e: &mut {k}::Exec<F>, ps: {k}::Vec3<F>) -> {k}::LightOutput<F> {{"
                ));
                self.line("    let r = self.run(e, ps);");
                self.line(&format!(
                    "    {k}::LightOutput {{ cl: r.Cl, l: r.L, lit: r.lit, emission: {k}::Emission::{em} }}"
                ));
                self.line("}");
                self.ind -= 1;
                self.line("}");
            }
            _ => {}
        }
    }

    // ---------------------------------------------------------------------------------------
    // Statements.

    fn block(&mut self, block: &'a [Node]) -> Result<(), GenError> {
        for n in block {
            if let Some(sp) = self.node_span(n) {
                if !matches!(n, Node::Inst(v) if self.consts[v.0 as usize].is_some()) {
                    self.source_comment(sp);
                }
            }
            self.node(n)?;
        }
        Ok(())
    }

    fn node(&mut self, n: &'a Node) -> Result<(), GenError> {
        match n {
            Node::Inst(v) => self.inst(*v),
            Node::Store { slot, index, value, .. } => {
                self.store(*slot, *index, *value);
                Ok(())
            }
            Node::If { cond, then, otherwise } => self.if_(*cond, then, otherwise),
            Node::Loop { header, cond, body, step } => self.loop_(n, header, *cond, body, step),
            Node::Break(_) | Node::Continue(_) | Node::Return => {
                self.exit(n);
                Ok(())
            }
            Node::Frame(b) => self.frame(n, b),
            Node::Illuminance { category, position, cone, body } => self.illuminance(*category, *position, *cone, body),
            Node::Illuminate { position, cone, body } => self.light_region(Some(*position), *cone, body),
            Node::Solar { cone, body } => self.light_region(None, *cone, body),
        }
    }

    fn store(&mut self, slot: SlotId, index: Option<Value>, value: Value) {
        let s = slot;
        let var = self.slot_var(s);
        let r = self.sr[s.0 as usize];
        let st = self.f.slot(s).ty;
        if st.base == BaseType::String {
            let v = self.val(value, Repr::Scalar);
            let guard = if self.full { String::new() } else { format!("if {}.any() ", self.mask) };
            match index {
                None if st.array.is_some() => self.line(&format!("{guard}{{ {var} = {v}.clone(); }}")),
                None => self.line(&format!("{guard}{{ {var} = {v}.to_string(); }}")),
                Some(i) => {
                    let n = st.array.unwrap_or(1);
                    let iv = self.val(i, Repr::Scalar);
                    let iv = if self.scalar_value(i) { iv } else { format!("{}.lane(0)", self.val(i, Repr::Lane)) };
                    self.line(&format!(
                        "{guard}{{ {var}[(({iv}).max(0.0) as usize).min({})] = {v}.to_string(); }}",
                        n.saturating_sub(1)
                    ));
                }
            }
            return;
        }
        match index {
            None => {
                let v = self.store_value(value, s, false);
                self.assign(&var, &v, r);
            }
            Some(i) => {
                let n = st.array.unwrap_or(1);
                let v = self.store_value(value, s, true);
                let tmp = self.fresh("x");
                self.line(&format!("let {tmp} = {v};"));
                if self.scalar_value(i) && (r == Repr::Scalar || self.full) {
                    let iv = self.val(i, Repr::Scalar);
                    self.line(&format!(
                        "{{ let i = ({iv}).floor(); if i >= 0.0 && i < {n}.0 {{ {var}[i as usize] = {tmp}; }} }}"
                    ));
                } else if self.scalar_value(i) {
                    let iv = self.val(i, Repr::Scalar);
                    let m = self.mask.clone();
                    self.line(&format!(
                        "{{ let i = ({iv}).floor(); if i >= 0.0 && i < {n}.0 {{ let i = i as usize; {var}[i] = Blend::<F>::blend({m}, {tmp}, {var}[i]); }} }}"
                    ));
                } else {
                    let iv = self.val(i, Repr::Lane);
                    let m = self.mask.clone();
                    self.line(&format!(
                        "{{ let iv = ({iv}).floor(); for k in 0..{n} {{ let hit = {m} & iv.eq(F::c(k as f64)); if hit.any() {{ {var}[k] = Blend::<F>::blend(hit, {tmp}, {var}[k]); }} }} }}"
                    ));
                }
            }
        }
    }

    fn if_(&mut self, cond: Value, then: &'a [Node], otherwise: &'a [Node]) -> Result<(), GenError> {
        if self.scalar_value(cond) {
            let c = self.val(cond, Repr::Scalar);
            self.line(&format!("if {c} {{"));
            self.ind += 1;
            let f0 = self.full;
            self.block(then)?;
            let f1 = self.full;
            self.full = f0;
            self.ind -= 1;
            if otherwise.is_empty() {
                self.line("}");
            } else {
                self.line("} else {");
                self.ind += 1;
                self.block(otherwise)?;
                self.ind -= 1;
                self.line("}");
            }
            self.full = f1 && self.full;
            return Ok(());
        }
        let c = self.val(cond, Repr::Lane);
        let mt = self.fresh("m");
        let me = self.fresh("m");
        let m = self.mask.clone();
        self.line(&format!("let mut {mt} = {m} & {c};"));
        let exits = Self::has_exit(then) || Self::has_exit(otherwise);
        if !otherwise.is_empty() || exits {
            self.line(&format!("let mut {me} = {m} & !{c};"));
        }
        let f0 = self.full;
        self.full = false;
        self.mask = mt.clone();
        self.line(&format!("if {mt}.any() {{"));
        self.ind += 1;
        self.block(then)?;
        self.ind -= 1;
        self.line("}");
        if !otherwise.is_empty() {
            self.mask = me.clone();
            self.line(&format!("if {me}.any() {{"));
            self.ind += 1;
            self.block(otherwise)?;
            self.ind -= 1;
            self.line("}");
        }
        self.mask = m.clone();
        self.full = f0;
        if exits {
            self.line(&format!("{m} = {mt} | {me};"));
            self.full = false;
        }
        Ok(())
    }

    fn loop_(
        &mut self,
        n: &'a Node,
        header: &'a [Node],
        cond: Option<Value>,
        body: &'a [Node],
        step: &'a [Node],
    ) -> Result<(), GenError> {
        let native = self.loop_native.get(&key(n)).copied().unwrap_or(false);
        if native {
            let l = self.fresh("'l");
            let c = self.fresh("'c");
            if self.has_masked_exit(header) || self.has_masked_exit(body) || self.has_masked_exit(step) {
                self.full = false;
            }
            self.line(&format!("{l}: loop {{"));
            self.ind += 1;
            self.block(header)?;
            if let Some(cv) = cond {
                let e = self.val(cv, Repr::Scalar);
                self.line(&format!("if !{e} {{ break {l}; }}"));
            }
            self.line(&format!("{c}: {{"));
            self.ind += 1;
            self.frames.last_mut().expect("frame").1.push(LoopCtx::Native { brk: l.clone(), cont: c.clone() });
            self.block(body)?;
            self.frames.last_mut().expect("frame").1.pop();
            self.ind -= 1;
            self.line("}");
            self.block(step)?;
            self.ind -= 1;
            self.line("}");
            return Ok(());
        }
        let m = self.mask.clone();
        let live = self.fresh("m");
        let exited = self.fresh("exited");
        let brk = self.fresh("brk");
        let cont = self.fresh("cont");
        let it = self.fresh("iters");
        self.line("{");
        self.ind += 1;
        self.line(&format!("let mut {live} = {m};"));
        self.line(&format!("let mut {exited} = no;"));
        self.line(&format!("let mut {brk} = no;"));
        self.line(&format!("let mut {cont} = no;"));
        self.line(&format!("let mut {it} = 0usize;"));
        self.line("loop {");
        self.ind += 1;
        let f0 = self.full;
        self.full = false;
        self.mask = live.clone();
        self.block(header)?;
        if let Some(cv) = cond {
            let c = self.val(cv, Repr::Lane);
            self.line(&format!("{exited} = {exited} | ({live} & !{c});"));
            self.line(&format!("{live} = {live} & {c};"));
        }
        self.line(&format!("if {live}.none() {{ break; }}"));
        self.frames.last_mut().expect("frame").1.push(LoopCtx::Masked { brk: brk.clone(), cont: cont.clone() });
        self.block(body)?;
        self.frames.last_mut().expect("frame").1.pop();
        self.mask = live.clone();
        self.line(&format!("{live} = {live} | {cont};"));
        self.line(&format!("{cont} = no;"));
        self.block(step)?;
        self.line(&format!("{it} += 1;"));
        self.line(&format!(
            "if <F::Mask as Mask>::THREE_VALUED && {it} > {}::INTERVAL_LOOP_LIMIT {{ {exited} = {exited} | {live}; break; }}",
            self.k
        ));
        self.ind -= 1;
        self.line("}");
        self.mask = m.clone();
        self.full = f0;
        self.line(&format!("{m} = {exited} | {brk};"));
        if Self::has_exit(header) || Self::has_exit(body) || Self::has_exit(step) {
            // Lanes that returned (or left outer loops) are not back.
            self.full = false;
        }
        self.ind -= 1;
        self.line("}");
        Ok(())
    }

    fn exit(&mut self, n: &Node) {
        let native = self.exit_native.get(&key(n)).copied().unwrap_or(false);
        let m = self.mask.clone();
        let kill = format!("{m} = no;");
        let (frame, loops) = self.frames.last().cloned().expect("frame");
        let target_loop = |level: u32| -> Option<LoopCtx> {
            let l = loops.len().checked_sub(1 + level as usize)?;
            loops.get(l).cloned()
        };
        match n {
            Node::Return => match frame {
                FrameCtx::Native(l) if native => self.line(&format!("break {l};")),
                FrameCtx::LightBody if native => self.line("return;"),
                FrameCtx::Masked(r) => {
                    self.line(&format!("{r} = {r} | {m};"));
                    self.line(&kill);
                    self.full = false;
                }
                _ => {
                    self.line(&kill);
                    self.full = false;
                }
            },
            Node::Break(level) | Node::Continue(level) => {
                let is_break = matches!(n, Node::Break(_));
                match target_loop(*level) {
                    Some(LoopCtx::Native { brk, cont }) if native => {
                        self.line(&format!("break {};", if is_break { brk } else { cont }));
                    }
                    Some(LoopCtx::Light { brk }) => {
                        if is_break {
                            self.line(&format!("{brk} = {brk} | {m};"));
                        }
                        if native {
                            self.line("return;");
                        } else {
                            self.line(&kill);
                            self.full = false;
                        }
                    }
                    Some(LoopCtx::Masked { brk, cont }) => {
                        let t = if is_break { brk } else { cont };
                        self.line(&format!("{t} = {t} | {m};"));
                        self.line(&kill);
                        self.full = false;
                    }
                    _ => {
                        self.line(&kill);
                        self.full = false;
                    }
                }
            }
            _ => {}
        }
    }

    fn frame(&mut self, n: &'a Node, body: &'a [Node]) -> Result<(), GenError> {
        let native = self.frame_native.get(&key(n)).copied().unwrap_or(true);
        let f0 = self.full;
        if native {
            let l = self.fresh("'f");
            self.line(&format!("{l}: {{"));
            self.ind += 1;
            self.frames.push((FrameCtx::Native(l), Vec::new()));
            // A trailing `return` is the end of the block.
            let body = match body.last() {
                Some(Node::Return) => &body[..body.len() - 1],
                _ => body,
            };
            self.block(body)?;
            self.frames.pop();
            self.ind -= 1;
            self.line("}");
        } else {
            let r = self.fresh("ret");
            self.line("{");
            self.ind += 1;
            self.line(&format!("let mut {r} = no;"));
            self.frames.push((FrameCtx::Masked(r.clone()), Vec::new()));
            self.block(body)?;
            self.frames.pop();
            let m = self.mask.clone();
            self.line(&format!("{m} = {m} | {r};"));
            self.ind -= 1;
            self.line("}");
        }
        self.full = f0 && !Self::has_break(body);
        Ok(())
    }

    fn illuminance(
        &mut self,
        category: Option<Value>,
        position: Value,
        cone: Option<(Value, Value)>,
        body: &'a [Node],
    ) -> Result<(), GenError> {
        if self.in_closure {
            return Err(self.err(
                self.f.inst(position).span,
                "generated Rust cannot nest `illuminance` inside a light-loop body (the loop body is a closure that cannot use the shading context)",
            ));
        }
        if self.m.kind == ShaderKind::Light {
            return Ok(()); // a light shader has no lights to loop over (as in the interpreter)
        }
        let cat = category.map_or_else(|| "\"\"".to_string(), |c| self.val(c, Repr::Scalar));
        let p = self.val(position, Repr::Lane);
        let cone_e = match cone {
            Some((a, b)) => format!("Some(({}, {}))", self.val(a, Repr::Lane), self.val(b, Repr::Lane)),
            None => "None".into(),
        };
        let ex = self.exec_mut();
        let lbrk = self.fresh("lbrk");
        let lm = self.fresh("m");
        let lslot = self.f.global_slot(Global::L);
        let clslot = self.f.global_slot(Global::Cl);
        self.line("{");
        self.ind += 1;
        self.line(&format!("let mut {lbrk} = no;"));
        self.line(&format!(
            "ctx.illuminance({ex}, {cat}, {p}, {cone_e}, |le: &mut Exec<F>, l: Vec3<F>, cl: Color<F>| {{"
        ));
        self.ind += 1;
        self.line(&format!("let mut {lm} = le.mask() & !{lbrk};"));
        self.line(&format!("if {lm}.none() {{ return; }}"));
        if let Some(s) = lslot {
            let v = self.slot_var(s);
            if self.sr[s.0 as usize] == Repr::Lane {
                self.line(&format!("{v} = l;"));
            }
        }
        if let Some(s) = clslot {
            let v = self.slot_var(s);
            if self.sr[s.0 as usize] == Repr::Lane {
                self.line(&format!("{v} = cl;"));
            }
        }
        let saved = (self.mask.clone(), self.full, self.in_closure);
        self.mask = lm;
        self.full = false;
        self.in_closure = true;
        self.frames.push((FrameCtx::LightBody, vec![LoopCtx::Light { brk: lbrk }]));
        let r = self.block(body);
        self.frames.pop();
        (self.mask, self.full, self.in_closure) = saved;
        r?;
        self.ind -= 1;
        self.line("});");
        self.ind -= 1;
        self.line("}");
        Ok(())
    }

    fn light_region(
        &mut self,
        position: Option<Value>,
        cone: Option<(Value, Value)>,
        body: &'a [Node],
    ) -> Result<(), GenError> {
        let ps = match self.f.global_slot(Global::Ps) {
            Some(s) if self.sr[s.0 as usize] == Repr::Lane => self.slot_var(s),
            _ => "ps".into(),
        };
        let cone_e = match cone {
            Some((a, b)) => format!("Some(({}, {}))", self.val(a, Repr::Lane), self.val(b, Repr::Lane)),
            None => "None".into(),
        };
        let call = match position {
            Some(p) => format!("illuminate({ps}, {}, {cone_e})", self.val(p, Repr::Lane)),
            None => {
                let axis = cone.map_or_else(|| "Vec3::zero()".to_string(), |(a, _)| self.val(a, Repr::Lane));
                format!("solar({axis})")
            }
        };
        let m = self.mask.clone();
        let bm = self.fresh("m");
        self.line("{");
        self.ind += 1;
        self.line(&format!("let (l, in_cone) = {call};"));
        match self.f.global_slot(Global::L) {
            Some(s) => {
                let v = self.slot_var(s);
                if self.sr[s.0 as usize] == Repr::Lane {
                    self.assign(&v, "l", Repr::Lane);
                }
            }
            None => self.assign("light_l", "l", Repr::Lane),
        }
        self.line(&format!("let mut {bm} = {m} & in_cone;"));
        self.line(&format!("lit = lit | {bm};"));
        self.line(&format!("if {bm}.any() {{"));
        self.ind += 1;
        let f0 = self.full;
        self.full = false;
        self.mask = bm;
        self.block(body)?;
        self.mask = m;
        self.full = f0;
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        Ok(())
    }

    // ---------------------------------------------------------------------------------------
    // Instructions.

    fn inst(&mut self, v: Value) -> Result<(), GenError> {
        if self.consts[v.0 as usize].is_some() {
            return Ok(()); // constants are written where they are used
        }
        let inst = self.f.inst(v);
        let r = self.vr[v.0 as usize];
        let is_str = inst.ty.base == BaseType::String;
        let name = format!("v{}", v.0);
        let e = self.inst_expr(v)?;
        if inst.ty.base == BaseType::Void {
            self.line(&format!("{e};"));
            return Ok(());
        }
        let ty = if is_str {
            if inst.ty.array.is_some() {
                String::new()
            } else {
                ": &str".into()
            }
        } else {
            format!(": {}", self.rust_ty(inst.ty, inst.is_bool, r))
        };
        self.line(&format!("let {name}{ty} = {e};"));
        Ok(())
    }

    fn arg_ty(&self, v: Value) -> Type {
        self.f.inst(v).ty
    }

    #[allow(clippy::too_many_lines)]
    fn inst_expr(&mut self, v: Value) -> Result<String, GenError> {
        let inst = self.f.inst(v);
        let r = self.vr[v.0 as usize];
        let args = inst.args.clone();
        let a = |this: &Self, i: usize| this.val(args[i], r);
        let ty = inst.ty;
        Ok(match &inst.op {
            Op::Const(c) => self.const_expr(c, ty.base, r),
            Op::Load(s) => {
                let slot = self.f.slot(*s);
                match slot.kind {
                    SlotKind::Param(pi) if !self.stored[s.0 as usize] && !self.m.params[pi as usize].output => {
                        self.param_read(pi as usize, r, false)
                    }
                    _ => {
                        let var = self.slot_var(*s);
                        if slot.ty.base == BaseType::String {
                            if slot.ty.array.is_some() {
                                format!("{var}.each_ref().map(|x| x.as_str())")
                            } else {
                                format!("{var}.as_str()")
                            }
                        } else if self.sr[s.0 as usize] == r {
                            var
                        } else {
                            self.lift(&var, slot.ty, false)
                        }
                    }
                }
            }
            Op::LoadElem(s) => {
                let slot = self.f.slot(*s);
                let n = slot.ty.array.unwrap_or(1);
                let arr = match slot.kind {
                    SlotKind::Param(pi) if !self.stored[s.0 as usize] && !self.m.params[pi as usize].output => self
                        .param_read(
                            pi as usize,
                            if slot.ty.base == BaseType::String { Repr::Scalar } else { r },
                            false,
                        ),
                    _ => {
                        let var = self.slot_var(*s);
                        if slot.ty.base == BaseType::String {
                            var
                        } else if self.sr[s.0 as usize] == r {
                            var
                        } else {
                            self.lift(&var, slot.ty, false)
                        }
                    }
                };
                let idx = args[0];
                if slot.ty.base == BaseType::String {
                    let iv = if self.scalar_value(idx) {
                        self.val(idx, Repr::Scalar)
                    } else {
                        format!("{}.lane(0)", self.val(idx, Repr::Lane))
                    };
                    format!("{{ let a = &{arr}; &a[(({iv}).max(0.0) as usize).min({})] }}", n.saturating_sub(1))
                } else if self.scalar_value(idx) {
                    let iv = self.val(idx, Repr::Scalar);
                    format!("{{ let a = {arr}; a[(({iv}).floor().max(0.0) as usize).min({})] }}", n.saturating_sub(1))
                } else {
                    let iv = self.val(idx, Repr::Lane);
                    format!(
                        "{{ let a = {arr}; let iv = ({iv}).floor().max(F::c(0.0)).min(F::c({}.0)); let mut r = a[0]; for k in 1..{n} {{ r = Blend::<F>::blend(iv.eq(F::c(k as f64)), a[k], r); }} r }}",
                        n.saturating_sub(1)
                    )
                }
            }
            Op::Unary(UnOp::Neg) => {
                if ty.base == BaseType::Matrix {
                    format!("{{ let a = {}; Matrix4 {{ m: a.m.map(|r| r.map(|x| -x)) }} }}", a(self, 0))
                } else {
                    format!("-{}", a(self, 0))
                }
            }
            Op::Unary(UnOp::Not) => format!("!{}", a(self, 0)),
            Op::Binary(op) => self.binary(*op, &args, r),
            Op::Select => {
                let c = self.val(args[0], if r == Repr::Scalar { Repr::Scalar } else { Repr::Lane });
                let (x, y) = (a(self, 1), a(self, 2));
                if ty.base == BaseType::String {
                    let c = if self.scalar_value(args[0]) { c } else { format!("{c}.lane(0)") };
                    format!("if {c} {{ {x} }} else {{ {y} }}")
                } else if r == Repr::Scalar {
                    format!("if {c} {{ {x} }} else {{ {y} }}")
                } else if inst.is_bool {
                    format!("<F::Mask as Mask>::select_mask({c}, {x}, {y})")
                } else {
                    format!("Blend::<F>::blend({c}, {x}, {y})")
                }
            }
            Op::Convert => {
                let from = self.f.inst(args[0]);
                let x = a(self, 0);
                if inst.is_bool {
                    // float (or triple) → bool: != 0.
                    if from.is_bool {
                        x
                    } else if r == Repr::Scalar {
                        if from.ty.base.is_triple() {
                            let [p, q, s] = comps(from.ty.base);
                            format!("{{ let a = {x}; a.{p} != 0.0 || a.{q} != 0.0 || a.{s} != 0.0 }}")
                        } else {
                            format!("({x} != 0.0)")
                        }
                    } else if from.ty.base.is_triple() {
                        let [p, q, s] = comps(from.ty.base);
                        format!("{{ let a = {x}; a.{p}.ne(F::c(0.0)) | a.{q}.ne(F::c(0.0)) | a.{s}.ne(F::c(0.0)) }}")
                    } else {
                        format!("{x}.ne(F::c(0.0))")
                    }
                } else if from.is_bool {
                    let one = if r == Repr::Scalar { "1.0_f64" } else { "F::c(1.0)" };
                    let zero = if r == Repr::Scalar { "0.0_f64" } else { "F::c(0.0)" };
                    let f = if r == Repr::Scalar {
                        format!("if {x} {{ {one} }} else {{ {zero} }}")
                    } else {
                        format!("F::select({x}, {one}, {zero})")
                    };
                    if ty.base.is_triple() {
                        format!("{}::splat({f})", tri_ty(ty.base))
                    } else {
                        f
                    }
                } else {
                    match (from.ty.base, ty.base) {
                        (BaseType::Float, b) if b.is_triple() => format!("{}::splat({x})", tri_ty(b)),
                        (BaseType::Float, BaseType::Matrix) => format!("Matrix4::scalar({x})"),
                        (BaseType::Color, b) if b.is_pointlike() => format!("({x}).to_vec()"),
                        (b, BaseType::Color) if b.is_pointlike() => format!("({x}).to_color()"),
                        _ => x,
                    }
                }
            }
            Op::MakeTriple => {
                format!("{}::new({}, {}, {})", tri_ty(ty.base), a(self, 0), a(self, 1), a(self, 2))
            }
            Op::MakeMatrix => {
                let e: Vec<String> = (0..16).map(|i| a(self, i)).collect();
                format!(
                    "Matrix4 {{ m: [[{}], [{}], [{}], [{}]] }}",
                    e[0..4].join(", "),
                    e[4..8].join(", "),
                    e[8..12].join(", "),
                    e[12..16].join(", ")
                )
            }
            Op::FromSpace => {
                let space = self.val(args[0], Repr::Scalar);
                let x = a(self, 1);
                if ty.base == BaseType::Color {
                    format!("{{ let c = {x}; match ColorSpace::from_name({space}) {{ Some(cs) => to_rgb(cs, c), None => c }} }}")
                } else {
                    let t = if r == Repr::Scalar { "f64" } else { "F" };
                    let to = format!("{}.to_current::<{t}>({space})", self.spaces_table());
                    match ty.base {
                        BaseType::Matrix => format!("({x} * {to})"),
                        BaseType::Vector => format!("{to}.transform_vector({x})"),
                        BaseType::Normal => format!("{to}.transform_normal({x})"),
                        _ => format!("{to}.transform_point({x})"),
                    }
                }
            }
            Op::Call { builtin, outputs, .. } => {
                let (builtin, outputs) = (*builtin, outputs.clone());
                self.call(v, builtin, &outputs, r)?
            }
        })
    }

    /// The named coordinate systems: the variable `run` declares when the shader names a
    /// space (the context's table, or for light shaders, which run without one, the standard
    /// table).
    fn spaces_table(&self) -> String {
        "spaces".into()
    }

    fn binary(&self, op: BinOp, args: &[Value], r: Repr) -> String {
        let (ta, tb) = (self.arg_ty(args[0]), self.arg_ty(args[1]));
        let bools = self.f.inst(args[0]).is_bool || self.f.inst(args[1]).is_bool;
        let want = r;
        let (x, y) = (self.val(args[0], want), self.val(args[1], want));
        let scalar = r == Repr::Scalar;
        use BaseType as B;
        match op {
            BinOp::And => format!("({x} & {y})"),
            BinOp::Or => format!("({x} | {y})"),
            BinOp::Eq | BinOp::Ne if ta.base == B::String || tb.base == B::String => {
                let o = if op == BinOp::Eq { "==" } else { "!=" };
                let e = format!("({x} {o} {y})");
                if scalar {
                    e
                } else {
                    format!("<F::Mask as Mask>::splat{e}")
                }
            }
            BinOp::Eq | BinOp::Ne if bools => {
                if scalar {
                    format!("({x} {} {y})", if op == BinOp::Eq { "==" } else { "!=" })
                } else {
                    let d = format!("(({x} & !{y}) | ({y} & !{x}))");
                    if op == BinOp::Eq {
                        format!("!{d}")
                    } else {
                        d
                    }
                }
            }
            BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => {
                let mname = match op {
                    BinOp::Eq => "eq",
                    BinOp::Ne => "ne",
                    BinOp::Lt => "lt",
                    BinOp::Le => "le",
                    BinOp::Gt => "gt",
                    _ => "ge",
                };
                let sop = match op {
                    BinOp::Eq => "==",
                    BinOp::Ne => "!=",
                    BinOp::Lt => "<",
                    BinOp::Le => "<=",
                    BinOp::Gt => ">",
                    _ => ">=",
                };
                if ta.base.is_triple() || ta.base == B::Matrix {
                    // Component-wise: all equal / any different.
                    let cs: Vec<String> = if ta.base == B::Matrix {
                        (0..16).map(|i| format!("m.{}[{}]", i / 4, i % 4)).collect()
                    } else {
                        comps(ta.base).iter().map(|c| (*c).to_string()).collect()
                    };
                    let cs_b: Vec<String> = if tb.base == B::Matrix {
                        (0..16).map(|i| format!("m.{}[{}]", i / 4, i % 4)).collect()
                    } else {
                        comps(tb.base).iter().map(|c| (*c).to_string()).collect()
                    };
                    let fix = |c: &str| c.replace("m.", "m[").replace("][", "][").to_string();
                    let _ = fix;
                    let field = |c: &str| -> String {
                        if let Some(rest) = c.strip_prefix("m.") {
                            let (i, j) = rest.split_once('[').unwrap_or(("0", "0]"));
                            format!("m[{i}][{}", j)
                        } else {
                            c.to_string()
                        }
                    };
                    let parts: Vec<String> = cs
                        .iter()
                        .zip(&cs_b)
                        .map(|(p, q)| {
                            if scalar {
                                format!("(a.{} {sop} b.{})", field(p), field(q))
                            } else {
                                format!("a.{}.{mname}(b.{})", field(p), field(q))
                            }
                        })
                        .collect();
                    let join = if op == BinOp::Ne { " | " } else { " & " };
                    format!("{{ let (a, b) = ({x}, {y}); {} }}", parts.join(join))
                } else if scalar {
                    format!("({x} {sop} {y})")
                } else {
                    format!("{x}.{mname}({y})")
                }
            }
            BinOp::Dot => format!("{x}.dot({y})"),
            BinOp::Cross => format!("{x}.cross({y})"),
            BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div => {
                let o = match op {
                    BinOp::Add => "+",
                    BinOp::Sub => "-",
                    BinOp::Mul => "*",
                    _ => "/",
                };
                match (ta.base, tb.base) {
                    (B::Matrix, B::Matrix) => match op {
                        BinOp::Mul => format!("({x} * {y})"),
                        BinOp::Div => format!("({x} * ({y}).inverse())"),
                        _ => format!(
                            "{{ let (a, b) = ({x}, {y}); Matrix4 {{ m: ::core::array::from_fn(|i| ::core::array::from_fn(|j| a.m[i][j] {o} b.m[i][j])) }} }}"
                        ),
                    },
                    (B::Matrix, B::Float) => format!(
                        "{{ let (a, b) = ({x}, {y}); Matrix4 {{ m: a.m.map(|r| r.map(|x| x {o} b)) }} }}"
                    ),
                    (B::Float, B::Matrix) => format!(
                        "{{ let (a, b) = ({x}, {y}); Matrix4 {{ m: b.m.map(|r| r.map(|x| a {o} x)) }} }}"
                    ),
                    (B::Float, t) if t.is_triple() => match op {
                        BinOp::Add | BinOp::Mul => format!("({y} {o} {x})"),
                        _ => format!("({}::splat({x}) {o} {y})", tri_ty(t)),
                    },
                    (ta_b, tb_b) if ta_b.is_triple() && tb_b.is_triple() && (ta_b == B::Color) != (tb_b == B::Color) => {
                        // Mixed colour and point-like (not produced by the checker; kept total).
                        if ta_b == B::Color {
                            format!("({x} {o} ({y}).to_color())")
                        } else {
                            format!("({x} {o} ({y}).to_vec())")
                        }
                    }
                    _ => format!("({x} {o} {y})"),
                }
            }
        }
    }

    /// A scalar-or-lane constant.
    fn k(&self, x: f64, r: Repr) -> String {
        if r == Repr::Scalar {
            lit(x)
        } else {
            format!("F::c({})", lit(x))
        }
    }

    /// Writes `value` (an expression in `Lane`/`Scalar` matching the slot) to output slot `s`.
    fn write_out(&mut self, s: SlotId, value: &str, vbase: BaseType) {
        let var = self.slot_var(s);
        let st = self.f.slot(s).ty;
        let r = self.sr[s.0 as usize];
        let v =
            if vbase.is_triple() && st.base.is_triple() && (vbase == BaseType::Color) != (st.base == BaseType::Color) {
                if st.base == BaseType::Color {
                    format!("({value}).to_color()")
                } else {
                    format!("({value}).to_vec()")
                }
            } else if vbase == BaseType::Float && st.base.is_triple() {
                format!("{}::splat({value})", tri_ty(st.base))
            } else {
                value.to_string()
            };
        self.assign(&var, &v, r);
    }

    #[allow(clippy::too_many_lines)]
    fn call(&mut self, v: Value, builtin: Builtin, outputs: &[Option<SlotId>], r: Repr) -> Result<String, GenError> {
        use BaseType as B;
        let inst = self.f.inst(v);
        let args = inst.args.clone();
        let n = args.len();
        let ret = inst.ty.base;
        let span = inst.span;
        let tb = |i: usize| args.get(i).map_or(B::Void, |a| self.arg_ty(*a).base);
        let a = |i: usize| self.val(args[i], r);
        let lane0 = |i: usize| -> String {
            if self.scalar_value(args[i]) {
                self.val(args[i], Repr::Scalar)
            } else {
                format!("{}.lane(0)", self.val(args[i], Repr::Lane))
            }
        };
        let g = "g";
        if builtin.calls_renderer() && self.in_closure {
            return Err(self.err(
                span,
                format!(
                    "generated Rust cannot call `{builtin}` inside an `illuminance` body: the light-loop body is a closure and cannot use the shading context; compute it before the loop"
                ),
            ));
        }
        let light = self.m.kind == ShaderKind::Light;
        // Component-wise application for triples.
        let map1 = |f: &dyn Fn(&str) -> String, x: String, base: BaseType| -> String {
            if base.is_triple() {
                format!("({x}).map(|x| {})", f("x"))
            } else {
                f(&x)
            }
        };
        let tri = |base: BaseType, parts: [String; 3]| -> String {
            format!("{}::new({}, {}, {})", tri_ty(base), parts[0], parts[1], parts[2])
        };
        // Component `c` of argument `i` (broadcasting floats).
        let comp_of = |i: usize, c: usize| -> String {
            let b = tb(i);
            if b.is_triple() {
                format!("a{i}.{}", comps(b)[c])
            } else {
                format!("a{i}")
            }
        };
        let bind =
            |k: usize| -> String { (0..k).map(|i| format!("let a{i} = {};", a(i))).collect::<Vec<_>>().join(" ") };
        let un = |f: &str| -> String {
            let f = f.to_string();
            map1(&|x: &str| f.replace('$', x), a(0), tb(0))
        };
        let e = match builtin {
            Builtin::Abs => un("$.abs()"),
            Builtin::Sign => un("sign($)"),
            Builtin::Floor => un("$.floor()"),
            Builtin::Ceil => un("$.ceil()"),
            Builtin::Round => un("$.round()"),
            Builtin::Sqrt => un("$.sqrt()"),
            Builtin::InverseSqrt => un("inversesqrt($)"),
            Builtin::Exp => un("$.exp()"),
            Builtin::Log if n == 1 => un("$.ln()"),
            Builtin::Log => format!("log_base({}, {})", a(0), a(1)),
            Builtin::Sin => un("$.sin()"),
            Builtin::Cos => un("$.cos()"),
            Builtin::Tan => un("$.tan()"),
            Builtin::Asin => un("$.asin()"),
            Builtin::Acos => un("$.acos()"),
            Builtin::Atan if n == 1 => un("$.atan()"),
            Builtin::Atan => format!("{}.atan2({})", a(0), a(1)),
            Builtin::Radians => un("radians($)"),
            Builtin::Degrees => un("degrees($)"),
            Builtin::Pow | Builtin::Mod | Builtin::Step | Builtin::Min | Builtin::Max => {
                let f = match builtin {
                    Builtin::Pow => "$0.pow($1)",
                    Builtin::Mod => "fmod($0, $1)",
                    Builtin::Step => "step($0, $1)",
                    Builtin::Min => "$0.min($1)",
                    _ => "$0.max($1)",
                };
                let fold = |c: Option<usize>| -> String {
                    let get = |i: usize| match c {
                        Some(c) => comp_of(i, c),
                        None => format!("a{i}"),
                    };
                    let mut acc = f.replace("$0", &get(0)).replace("$1", &get(1));
                    for i in 2..n {
                        acc = f.replace("$0", &acc).replace("$1", &get(i));
                    }
                    acc
                };
                if ret.is_triple() {
                    format!("{{ {} {} }}", bind(n), tri(ret, [fold(Some(0)), fold(Some(1)), fold(Some(2))]))
                } else {
                    format!("{{ {} {} }}", bind(n), fold(None))
                }
            }
            Builtin::Clamp | Builtin::Mix | Builtin::SmoothStep => {
                let f = match builtin {
                    Builtin::Clamp => "clamp",
                    Builtin::Mix => "mix",
                    _ => "smoothstep",
                };
                if ret.is_triple() {
                    let parts =
                        [0, 1, 2].map(|c| format!("{f}({}, {}, {})", comp_of(0, c), comp_of(1, c), comp_of(2, c)));
                    format!("{{ {} {} }}", bind(3), tri(ret, parts))
                } else {
                    format!("{f}({}, {}, {})", a(0), a(1), a(2))
                }
            }
            Builtin::Length => format!("{}.length()", a(0)),
            Builtin::Normalize => format!("{}.normalize()", a(0)),
            Builtin::Distance => format!("distance({}, {})", a(0), a(1)),
            Builtin::FaceForward if n == 3 => format!("faceforward({}, {}, {})", a(0), a(1), a(2)),
            Builtin::FaceForward => format!("faceforward({}, {}, {g}.Ng)", a(0), a(1)),
            Builtin::Reflect => format!("reflect({}, {})", a(0), a(1)),
            Builtin::Refract => format!("refract({}, {}, {})", a(0), a(1), a(2)),
            Builtin::Fresnel => {
                let call = format!("fresnel({}, {}, {})", a(0), a(1), a(2));
                let tmp = self.fresh("fr");
                self.line(&format!("let {tmp} = {call};"));
                let fields = [("kr", B::Float), ("kt", B::Float), ("r", B::Vector), ("t", B::Vector)];
                for (i, (f, b)) in fields.iter().enumerate() {
                    if let Some(Some(s)) = outputs.get(3 + i) {
                        let val = self.out_value(&format!("{tmp}.{f}"), r, *s, *b);
                        self.write_out(*s, &val, *b);
                    }
                }
                "()".into()
            }
            Builtin::PtLineD => format!("ptlined({}, {}, {})", a(0), a(1), a(2)),
            Builtin::Rotate if tb(0).is_triple() => format!("rotate({}, {}, {}, {})", a(0), a(1), a(2), a(3)),
            Builtin::Rotate => format!("({} * Matrix4::rotate({}, {}))", a(0), a(1), a(2)),
            Builtin::Translate => format!("({} * Matrix4::translate({}))", a(0), a(1)),
            Builtin::Scale => format!("({} * Matrix4::scale({}))", a(0), a(1)),
            Builtin::XComp | Builtin::YComp | Builtin::ZComp => {
                let c = match builtin {
                    Builtin::XComp => 0,
                    Builtin::YComp => 1,
                    _ => 2,
                };
                format!("{}.{}", a(0), comps(tb(0))[c])
            }
            Builtin::SetXComp | Builtin::SetYComp | Builtin::SetZComp => {
                let c = match builtin {
                    Builtin::SetXComp => 0,
                    Builtin::SetYComp => 1,
                    _ => 2,
                };
                if let Some(Some(s)) = outputs.first() {
                    let var = self.slot_var(*s);
                    let sr = self.sr[s.0 as usize];
                    let field = format!("{var}.{}", comps(self.f.slot(*s).ty.base)[c]);
                    let x = self.val(args[0], sr);
                    self.assign(&field, &x, sr);
                }
                "()".into()
            }
            Builtin::Comp if tb(0) == B::Matrix => {
                format!(
                    "{{ let m = {}; m.m[(({}) as usize).min(3)][(({}) as usize).min(3)] }}",
                    a(0),
                    lane0(1),
                    lane0(2)
                )
            }
            Builtin::Comp => {
                let x = a(0);
                let cs = comps(tb(0));
                if r == Repr::Scalar {
                    format!("{{ let v = {x}; let i = ({}).floor().max(0.0).min(2.0); if i == 0.0 {{ v.{} }} else if i == 1.0 {{ v.{} }} else {{ v.{} }} }}", a(1), cs[0], cs[1], cs[2])
                } else {
                    format!(
                        "{{ let v = {x}; let i = ({}).floor().max(F::c(0.0)).min(F::c(2.0)); F::select(i.eq(F::c(0.0)), v.{}, F::select(i.eq(F::c(1.0)), v.{}, v.{})) }}",
                        a(1),
                        cs[0],
                        cs[1],
                        cs[2]
                    )
                }
            }
            Builtin::SetComp => {
                if let Some(Some(s)) = outputs.first() {
                    let var = self.slot_var(*s);
                    let sr = self.sr[s.0 as usize];
                    let st = self.f.slot(*s).ty;
                    if st.base == B::Matrix {
                        let (i, j, x) = (
                            if self.scalar_value(args[0]) {
                                self.val(args[0], Repr::Scalar)
                            } else {
                                format!("{}.lane(0)", self.val(args[0], Repr::Lane))
                            },
                            if self.scalar_value(args[1]) {
                                self.val(args[1], Repr::Scalar)
                            } else {
                                format!("{}.lane(0)", self.val(args[1], Repr::Lane))
                            },
                            self.val(args[2], sr),
                        );
                        let field = format!("{var}.m[(({i}) as usize).min(3)][(({j}) as usize).min(3)]");
                        self.assign(&field, &x, sr);
                    } else {
                        let cs = comps(st.base);
                        let x = self.val(args[1], sr);
                        if sr == Repr::Scalar {
                            let i = self.val(args[0], Repr::Scalar);
                            self.line(&format!(
                                "{{ let i = ({i}).floor(); let x = {x}; if i == 0.0 {{ {var}.{} = x; }} else if i == 1.0 {{ {var}.{} = x; }} else if i == 2.0 {{ {var}.{} = x; }} }}",
                                cs[0], cs[1], cs[2]
                            ));
                        } else {
                            let i = self.val(args[0], Repr::Lane);
                            let m = if self.full {
                                "<F::Mask as Mask>::splat(true)".to_string()
                            } else {
                                self.mask.clone()
                            };
                            self.line(&format!(
                                "{{ let i = ({i}).floor(); let x = {x}; let m = {m}; {var}.{0} = F::select(m & i.eq(F::c(0.0)), x, {var}.{0}); {var}.{1} = F::select(m & i.eq(F::c(1.0)), x, {var}.{1}); {var}.{2} = F::select(m & i.eq(F::c(2.0)), x, {var}.{2}); }}",
                                cs[0], cs[1], cs[2]
                            ));
                        }
                    }
                }
                "()".into()
            }
            Builtin::Transform | Builtin::VTransform | Builtin::NTransform => {
                let last = a(n - 1);
                match args.iter().position(|x| self.arg_ty(*x).base == B::Matrix) {
                    Some(mi) => {
                        let f = match (builtin, ret) {
                            (Builtin::VTransform, _) | (_, B::Vector) => "transform_vector",
                            (Builtin::NTransform, _) | (_, B::Normal) => "transform_normal",
                            _ => "transform_point",
                        };
                        let strings = args.iter().filter(|x| self.arg_ty(**x).base == B::String).count();
                        if strings == 1 {
                            // transform(fromspace, m, p): from `fromspace` to current, then by `m`.
                            let t = if r == Repr::Scalar { "f64" } else { "F" };
                            let to = format!("{}.to_current::<{t}>({})", self.spaces_table(), a(0));
                            format!("{}.{f}({to}.{f}({last}))", a(mi))
                        } else {
                            format!("{}.{f}({last})", a(mi))
                        }
                    }
                    None => {
                        let f = match (builtin, ret) {
                            (Builtin::VTransform, _) | (_, B::Vector) => "transform_vector",
                            (Builtin::NTransform, _) | (_, B::Normal) => "transform_normal",
                            _ => "transform_point",
                        };
                        let t = if r == Repr::Scalar { "f64" } else { "F" };
                        let m = if n == 3 {
                            format!("{}.between::<{t}>({}, {})", self.spaces_table(), a(0), a(1))
                        } else {
                            format!("{}.from_current::<{t}>({})", self.spaces_table(), a(0))
                        };
                        format!("{m}.{f}({last})")
                    }
                }
            }
            Builtin::CTransform => {
                let spaces = args.iter().filter(|x| self.arg_ty(**x).base == B::String).count();
                let c = a(spaces);
                let from = if spaces == 2 {
                    format!("ColorSpace::from_name({})", a(0))
                } else {
                    "Some(ColorSpace::Rgb)".into()
                };
                let to = format!("ColorSpace::from_name({})", a(spaces - 1));
                format!(
                    "{{ let c = {c}; match ({from}, {to}) {{ (Some(f), Some(t)) => ctransform(f, t, c), _ => c }} }}"
                )
            }
            Builtin::Determinant => format!("{}.determinant()", a(0)),
            Builtin::Du | Builtin::Dv => {
                let f = if builtin == Builtin::Du { "du" } else { "dv" };
                if tb(0).is_triple() {
                    format!("({}).map(|x| {f}(&{g}, x))", a(0))
                } else {
                    format!("{f}(&{g}, {})", a(0))
                }
            }
            Builtin::Deriv => {
                if tb(0).is_triple() {
                    format!("{{ let d = {}; ({}).map(|x| deriv(&{g}, x, d)) }}", a(1), a(0))
                } else {
                    format!("deriv(&{g}, {}, {})", a(0), a(1))
                }
            }
            Builtin::Area => format!("area({})", a(0)),
            Builtin::CalculateNormal => format!("calculatenormal(&{g}, {})", a(0)),
            Builtin::FilterWidth if tb(0).is_triple() => format!("filterwidth_point({})", a(0)),
            Builtin::FilterWidth => format!("filterwidth({})", a(0)),
            Builtin::FilterStep => {
                let nnum = args.iter().take_while(|x| self.arg_ty(**x).base != B::String).count();
                if nnum >= 3 {
                    format!(
                        "{{ let (e, s0, s1) = ({}, {}, {}); let lo = s0.min(s1); let w = (s1 - s0).abs(); let t = clamp((lo + w - e) / w.max(F::c(1e-30)), F::c(0.0), F::c(1.0)); F::select(w.gt(F::c(0.0)), t, step(e, s0)) }}",
                        a(0),
                        a(1),
                        a(2)
                    )
                } else {
                    format!("filterstep({}, {})", a(0), a(1))
                }
            }
            Builtin::Noise | Builtin::SNoise | Builtin::PNoise | Builtin::PSNoise | Builtin::CellNoise => {
                let periodic = matches!(builtin, Builtin::PNoise | Builtin::PSNoise);
                let nd = if periodic { n / 2 } else { n };
                let dom = |off: usize| -> Result<String, GenError> {
                    let t: Vec<B> = (off..off + nd).map(tb).collect();
                    Ok(match t.as_slice() {
                        [B::Float] => format!("NoiseDomain::D1({})", a(off)),
                        [B::Float, B::Float] => format!("NoiseDomain::D2({}, {})", a(off), a(off + 1)),
                        [p] if p.is_triple() => format!("NoiseDomain::D3({})", self.as_vec(args[off], r)),
                        [p, B::Float] if p.is_triple() => {
                            format!("NoiseDomain::D4({}, {})", self.as_vec(args[off], r), a(off + 1))
                        }
                        _ => {
                            return Err(
                                self.err(span, format!("`{builtin}` with these argument types has no implementation"))
                            )
                        }
                    })
                };
                let d = dom(0)?;
                let signed = matches!(builtin, Builtin::SNoise | Builtin::PSNoise);
                let vecr = ret.is_triple();
                let e = if periodic {
                    let p = dom(nd)?;
                    match (vecr, signed) {
                        (false, false) => format!("pnoise({d}, {p})"),
                        (false, true) => format!("psnoise({d}, {p})"),
                        (true, false) => format!("vpnoise({d}, {p})"),
                        (true, true) => {
                            format!("(vpnoise({d}, {p}) * {} - Vec3::splat({}))", self.k(2.0, r), self.k(1.0, r))
                        }
                    }
                } else if builtin == Builtin::CellNoise {
                    if vecr {
                        format!("vcellnoise({d})")
                    } else {
                        format!("cellnoise({d})")
                    }
                } else {
                    match (vecr, signed) {
                        (false, false) => format!("noise({d})"),
                        (false, true) => format!("snoise({d})"),
                        (true, false) => format!("vnoise({d})"),
                        (true, true) => format!("vsnoise({d})"),
                    }
                };
                if ret == B::Color {
                    format!("({e}).to_color()")
                } else {
                    e
                }
            }
            Builtin::Fbm | Builtin::Turbulence => {
                let d = if tb(0).is_triple() {
                    format!("NoiseDomain::D3({})", self.as_vec(args[0], r))
                } else {
                    format!("NoiseDomain::D1({})", a(0))
                };
                let oct = if n > 1 { format!("(({}).max(0.0) as u32)", lane0(1)) } else { "6".into() };
                let lac = if n > 2 { lane0(2) } else { "2.0".into() };
                let gain = if n > 3 { lane0(3) } else { "0.5".into() };
                format!("{builtin}({d}, {oct}, {lac}, {gain})")
            }
            Builtin::Random => {
                let p = format!("{g}.P * F::c(1.0e4)");
                if ret.is_triple() {
                    tri(ret, [0, 1, 2].map(|c| format!("cellnoise(NoiseDomain::D4({p}, F::c({}.5)))", c)))
                } else {
                    format!("cellnoise(NoiseDomain::D4({p}, F::c(0.5)))")
                }
            }
            Builtin::Spline => {
                let basis = tb(0) == B::String;
                let first = usize::from(basis);
                let b = if basis {
                    format!("SplineBasis::from_name({}).unwrap_or(SplineBasis::CATMULL_ROM)", a(0))
                } else {
                    "SplineBasis::CATMULL_ROM".into()
                };
                let x = a(first);
                let rest = &args[first + 1..];
                let knots = if rest.len() == 1 && self.arg_ty(rest[0]).array.is_some() {
                    a(first + 1)
                } else {
                    format!("[{}]", (first + 1..n).map(a).collect::<Vec<_>>().join(", "))
                };
                format!("{{ let b = {b}; let k = {knots}; spline(&b, {x}, &k) }}")
            }
            Builtin::Ambient | Builtin::Diffuse | Builtin::Specular | Builtin::Phong | Builtin::Trace if light => {
                "Color::zero()".to_string()
            }
            Builtin::Ambient => format!(
                "ambient(ctx, {})",
                if self.exec_mut() == "e" { "&*e".to_string() } else { self.exec_mut().replacen("&mut ", "&", 1) }
            ),
            Builtin::Diffuse => format!("diffuse(ctx, {}, {})", self.exec_mut(), a(0)),
            Builtin::Specular => format!("specular(ctx, {}, {}, {}, {})", self.exec_mut(), a(0), a(1), a(2)),
            Builtin::Phong => format!("phong(ctx, {}, {}, {}, {})", self.exec_mut(), a(0), a(1), a(2)),
            Builtin::Trace => {
                let ex =
                    if self.exec_mut() == "e" { "&*e".to_string() } else { self.exec_mut().replacen("&mut ", "&", 1) };
                format!("ctx.trace({ex}, {}, {})", a(0), a(1))
            }
            Builtin::SpecularBrdf => format!("Color::splat(specularbrdf({}, {}, {}, {}))", a(0), a(1), a(2), a(3)),
            Builtin::Texture | Builtin::Environment | Builtin::Shadow => {
                let rt = self.opts.runtime.clone();
                let coords = args.iter().skip(1).take_while(|x| self.arg_ty(**x).base != B::String).count();
                let c = match builtin {
                    Builtin::Shadow => "Color::zero()".to_string(),
                    Builtin::Environment if coords >= 1 => format!("{rt}::environment({}, {})", a(0), a(1)),
                    Builtin::Environment => "Color::zero()".to_string(),
                    _ if coords >= 2 => format!("{rt}::texture({}, Some(({}, {})), &{g})", a(0), a(1), a(2)),
                    _ if coords == 0 => format!("{rt}::texture({}, None, &{g})", a(0)),
                    _ => "Color::zero()".to_string(),
                };
                if ret == B::Float {
                    format!("({c}).r")
                } else {
                    c
                }
            }
            Builtin::Concat => format!(
                "&*{}",
                self.leak_string(&format!("[{}].concat()", (0..n).map(a).collect::<Vec<_>>().join(", ")))
            ),
            Builtin::Format | Builtin::Printf => {
                let rt = self.opts.runtime.clone();
                let mut fa = Vec::new();
                for x in args.iter().skip(1) {
                    let t = self.arg_ty(*x);
                    let e = self.val(*x, self.vr[x.0 as usize]);
                    let lane = self.vr[x.0 as usize] == Repr::Lane;
                    let l = |s: String| if lane { format!("{s}.lane(0)") } else { s };
                    fa.push(match t.base {
                        B::String => format!("{rt}::FmtArg::Str({e}.to_string())"),
                        B::Float if self.f.inst(*x).is_bool => {
                            if lane {
                                format!("{rt}::FmtArg::Num(vec![if {e}.lane(0) {{ 1.0 }} else {{ 0.0 }}])")
                            } else {
                                format!("{rt}::FmtArg::Num(vec![if {e} {{ 1.0 }} else {{ 0.0 }}])")
                            }
                        }
                        B::Float => format!("{rt}::FmtArg::Num(vec![{}])", l(e.clone())),
                        B::Matrix => {
                            format!("{rt}::FmtArg::Num({e}.m.iter().flatten().map(|x| {}).collect())", l("x".into()))
                        }
                        b => {
                            let cs = comps(b);
                            format!(
                                "{rt}::FmtArg::Num(vec![{}, {}, {}])",
                                l(format!("{e}.{}", cs[0])),
                                l(format!("{e}.{}", cs[1])),
                                l(format!("{e}.{}", cs[2]))
                            )
                        }
                    });
                }
                let call = format!("{rt}::format_rsl({}, &[{}])", a(0), fa.join(", "));
                if builtin == Builtin::Printf {
                    let guard = if self.full { "true".to_string() } else { format!("{}.any()", self.mask) };
                    format!("if {guard} {{ print!(\"{{}}\", {call}); }}")
                } else {
                    format!("&*{}", self.leak_string(&call))
                }
            }
            Builtin::Match => {
                let rt = self.opts.runtime.clone();
                format!(
                    "if {rt}::simple_match({}, {}) {{ {} }} else {{ {} }}",
                    a(0),
                    a(1),
                    self.k(1.0, r),
                    self.k(0.0, r)
                )
            }
            Builtin::Surface
            | Builtin::LightSource
            | Builtin::Displacement
            | Builtin::Atmosphere
            | Builtin::Incident
            | Builtin::Opposite
            | Builtin::Attribute
            | Builtin::Option
            | Builtin::RendererInfo
            | Builtin::TextureInfo => self.k(0.0, r),
            Builtin::ShaderName => "\"\"".to_string(),
            Builtin::Depth => format!("{g}.P.z"),
            Builtin::RayInfo => self.k(0.0, r),
            // Outside a scene: camera rays, nothing occludes, no indirect or caustic light,
            // nothing blocks transmission (as the interpreter).
            Builtin::RayLevel | Builtin::IsShadowRay | Builtin::IsIndirectRay | Builtin::Occlusion => self.k(0.0, r),
            Builtin::IndirectDiffuse | Builtin::Caustic => "Color::zero()".to_string(),
            Builtin::Transmission => "Color::splat(F::c(1.0))".to_string(),
            Builtin::FilteredPulse => format!("filteredpulse({}, {}, {})", a(0), a(1), a(2)),
        };
        Ok(e)
    }

    /// An owned string computed once: bound to a fresh variable, returns its name.
    fn leak_string(&mut self, e: &str) -> String {
        let t = self.fresh("string");
        self.line(&format!("let {t}: String = {e};"));
        t
    }

    /// A triple argument as a `Vec3` (colours converted).
    fn as_vec(&self, v: Value, r: Repr) -> String {
        let e = self.val(v, r);
        if self.arg_ty(v).base == BaseType::Color {
            format!("({e}).to_vec()")
        } else {
            e
        }
    }

    /// A call's output value (computed in representation `r`) for slot `s`.
    fn out_value(&self, e: &str, r: Repr, s: SlotId, base: BaseType) -> String {
        if r == self.sr[s.0 as usize] || r == Repr::Lane {
            e.to_string()
        } else {
            let t = Type::new(base, Detail::Uniform);
            self.lift(e, t, false)
        }
    }
}

#[cfg(test)]
mod tests;
