//! Type checking while lowering: AST → [`ir::Module`] for one shader.
//!
//! As in naga's front ends, checking and lowering are one walk: every expression is lowered
//! to IR instructions as soon as its type is known, and a type error yields `None` instead of
//! a value ([`R`]), which silently poisons the expressions built on it (no cascades).
//!
//! * **Scopes.** A stack of scopes maps names to variables (IR slots), read-only values (the
//!   non-`output` parameters of an inlined function) and nested functions. Variables and
//!   functions live in separate namespaces, so a parameter called `scale` does not hide the
//!   built-in. Globals (`P`, `N`, …) and `PI` are found after the scopes.
//! * **Functions are inlined** at each call as a [`Node::Frame`]: input arguments are bound to
//!   their values, `output` arguments copied in to a fresh slot and copied back after the
//!   frame, the result goes through a return slot. A function body sees only its own names
//!   plus the globals (a *barrier* scope); `extern` reaches past the barrier into the
//!   enclosing (calling) scopes. Parameters without `uniform`/`varying` take the caller's
//!   detail, so each call is checked with the actual argument details. Recursion is an error.
//!   Functions that are never called are checked once with their declared types.
//! * **Uniform/varying.** Parameters default to uniform, locals to varying. A varying value
//!   stored into a uniform variable is [`codes::VARYING_TO_UNIFORM`]; storing into a uniform
//!   variable declared outside the innermost varying `if`/loop/light loop (or after a varying
//!   `break`/`return`) is [`codes::UNIFORM_IN_VARYING_FLOW`].
//! * **Return type by context.** Every expression is lowered with an *expected* base type (the
//!   declaration, assignment or cast target, passed down through arithmetic and `?:`); it picks
//!   among built-in overloads that differ only in their return type (`color noise(P)`) and
//!   types a bare triple literal `(a, b, c)`, which is a `point` when nothing says otherwise.
//! * **Parameter defaults** are evaluated to [`Const`]s by [`ConstEval`]: literals, triples,
//!   casts, unary minus, arithmetic, the pure math built-ins and earlier parameters. A
//!   point-like default in a named space keeps the space in [`ParamMeta::space`]; a colour in a
//!   named colour space is converted to RGB at compile time.

use crate::builtins::{self, ArgSpec, Builtin, Overload, ResolveError, OVERLOADS};
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::front::ast::{self, AssignOp, BinaryOp, Expr, ExprKind, ShaderType, Stmt, StmtKind, UnaryOp};
use crate::ir::{
    self, BinOp, Const, Function, Global, Inst, Node, Op, ParamMeta, ShaderKind, Slot, SlotId, SlotKind, UnOp, Value,
};
use crate::span::Span;
use crate::types::{BaseType, Detail, Type};
use std::collections::{HashMap, HashSet};

/// A lowered expression: its SSA value and type.
#[derive(Clone, Copy, Debug)]
struct Val {
    v: Value,
    ty: Type,
    is_bool: bool,
}

/// The result of lowering an expression: `None` when an error was reported.
type R = Option<Val>;

#[derive(Clone, Copy, Debug)]
enum Binding {
    /// A variable.
    Slot(SlotId),
    /// A read-only value (non-output function parameter).
    Value(Val),
}

#[derive(Clone, Copy, Debug)]
struct VarInfo {
    binding: Binding,
    span: Span,
    /// Read-only (non-output parameters, including array ones bound to the caller's slot).
    read_only: bool,
    /// Varying-flow depth at the declaration.
    flow: u32,
}

#[derive(Default)]
struct Scope<'a> {
    vars: HashMap<String, VarInfo>,
    funcs: HashMap<String, Vec<&'a ast::FunctionDef>>,
    /// Names above this scope cannot see names below it (a function body), except via extern.
    barrier: bool,
}

struct LoopCtx {
    /// A varying `break`/`continue` left some lanes behind.
    varying: bool,
}

struct FrameCtx<'a> {
    func: Option<&'a ast::FunctionDef>,
    ret_slot: Option<SlotId>,
    loops: Vec<LoopCtx>,
    /// A varying `return` ended some lanes early.
    varying_exit: bool,
    /// The varying-flow depth at the frame's start.
    flow_at_entry: u32,
}

/// Found by a name look-up.
enum Found {
    Var(VarInfo),
    Global(Global),
    Pi,
}

/// Lowers one shader of `unit` (the one named `shader`, or the only one) to IR. Errors and
/// warnings go to `diags`; the module is returned only when no error was found.
pub fn lower_unit(unit: &ast::Unit, shader: Option<&str>, diags: &mut Diagnostics) -> Option<ir::Module> {
    let shaders: Vec<&ast::ShaderDef> =
        unit.items.iter().filter_map(|i| if let ast::Item::Shader(s) = i { Some(s) } else { None }).collect();
    let chosen = match shader {
        Some(name) => match shaders.iter().find(|s| s.name.name == name) {
            Some(s) => *s,
            None => {
                let mut d = Diagnostic::error(
                    codes::NO_SHADER,
                    shaders.first().map_or(Span::DUMMY, |s| s.name.span),
                    format!("no shader named `{name}` in this file"),
                );
                if !shaders.is_empty() {
                    d = d.with_note(format!(
                        "the file defines: {}",
                        shaders.iter().map(|s| s.name.name.as_str()).collect::<Vec<_>>().join(", ")
                    ));
                }
                diags.push(d);
                return None;
            }
        },
        None => match shaders.as_slice() {
            [s] => *s,
            [] => {
                let span = unit.items.first().map_or(Span::DUMMY, |i| match i {
                    ast::Item::Function(f) => f.name.span,
                    ast::Item::Shader(s) => s.name.span,
                });
                diags.push(
                    Diagnostic::error(codes::NO_SHADER, span, "no shader definition in this file")
                        .with_note("a shader starts with `surface`, `light`, `displacement`, `volume` or `imager`"),
                );
                return None;
            }
            [first, rest @ ..] => {
                let mut d = Diagnostic::error(
                    codes::NO_SHADER,
                    rest[0].name.span,
                    "several shaders in one file: say which one to compile",
                )
                .with_secondary(first.name.span, "first shader");
                d = d.with_note(format!(
                    "the file defines: {}",
                    shaders.iter().map(|s| s.name.name.as_str()).collect::<Vec<_>>().join(", ")
                ));
                diags.push(d);
                return None;
            }
        },
    };
    // `uniform` locals of functions assigned under varying control flow are made varying:
    // lower again with them promoted until no new one turns up.
    let mut promote: HashSet<Span> = HashSet::new();
    loop {
        let mark = diags.items.len();
        let mut l = Lowerer::new(chosen.kind, diags);
        l.promote = promote.clone();
        let module = l.lower_shader(unit, chosen);
        let want = std::mem::take(&mut l.want_promote);
        if want.is_subset(&promote) {
            return module;
        }
        diags.items.truncate(mark);
        promote.extend(want);
    }
}

struct Lowerer<'a, 'd> {
    kind: ShaderType,
    diags: &'d mut Diagnostics,
    seen: HashSet<(&'static str, Span)>,
    func: Function,
    blocks: Vec<ir::Block>,
    scopes: Vec<Scope<'a>>,
    frames: Vec<FrameCtx<'a>>,
    globals: HashMap<Global, SlotId>,
    slot_names: HashMap<String, u32>,
    /// Number of enclosing varying conditions (if/loop/light loop).
    vflow: u32,
    /// Number of enclosing light loops (`illuminance`, `illuminate`, `solar`).
    light_loops: u32,
    /// Functions being inlined (recursion check).
    inlining: Vec<&'a ast::FunctionDef>,
    /// Functions inlined at least once (by span).
    called: HashSet<Span>,
    /// Functions whose `MISSING_RETURN` check ran.
    ret_checked: HashSet<Span>,
    /// Lowering the value stored into a uniform variable: `random()` is then uniform (one
    /// number for the whole grid, as in PRMan).
    uniform_target: bool,
    /// Declarations (name spans) of function-local `uniform` variables lowered as varying.
    promote: HashSet<Span>,
    /// Function-local `uniform` variables found assigned under varying control flow.
    want_promote: HashSet<Span>,
}

fn kind_of(k: ShaderType) -> ShaderKind {
    match k {
        ShaderType::Surface => ShaderKind::Surface,
        ShaderType::Light => ShaderKind::Light,
        ShaderType::Displacement => ShaderKind::Displacement,
        ShaderType::Volume => ShaderKind::Volume,
        ShaderType::Imager => ShaderKind::Imager,
    }
}

/// Levenshtein distance, for "did you mean" notes.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != *cb)).min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The closest of `candidates` to `name`, if close enough to be a likely typo.
fn suggest<'s>(name: &str, candidates: impl Iterator<Item = &'s str>) -> Option<&'s str> {
    let limit = (name.chars().count() / 3).max(1);
    candidates
        .filter(|c| *c != name)
        .map(|c| (edit_distance(&name.to_lowercase(), &c.to_lowercase()), c))
        .filter(|(d, _)| *d <= limit)
        .min()
        .map(|(_, c)| c)
}

/// Whether a statement always ends in `return` (for [`codes::MISSING_RETURN`]).
fn always_returns(s: &Stmt) -> bool {
    match &s.kind {
        StmtKind::Return(_) => true,
        StmtKind::Block(b) => b.stmts.iter().any(always_returns),
        StmtKind::If { then, otherwise: Some(o), .. } => always_returns(then) && always_returns(o),
        StmtKind::While { cond, body } => is_true_literal(cond) && !contains_break(body),
        StmtKind::For { cond, body, .. } => cond.as_ref().is_none_or(is_true_literal) && !contains_break(body),
        _ => false,
    }
}

fn is_true_literal(e: &Expr) -> bool {
    matches!(e.kind, ExprKind::Number(x) if x != 0.0)
}

fn contains_break(s: &Stmt) -> bool {
    match &s.kind {
        StmtKind::Break(_) => true,
        StmtKind::Block(b) => b.stmts.iter().any(contains_break),
        StmtKind::If { then, otherwise, .. } => {
            contains_break(then) || otherwise.as_deref().is_some_and(contains_break)
        }
        _ => false,
    }
}

/// The triple kind of `a op b` for `+ - * /` between triples (module docs of [`ir::BinOp`]).
fn triple_result(op: BinaryOp, a: BaseType, b: BaseType) -> Option<BaseType> {
    use BaseType::*;
    if a == Color || b == Color {
        return if a == b { Some(Color) } else { None };
    }
    Some(match (op, a, b) {
        (BinaryOp::Sub, Point, Point) => Vector,
        (_, x, y) if x == y => x,
        (_, Point, _) | (_, _, Point) => Point,
        _ => Vector,
    })
}

/// Result type of a binary operator on base types (`None`: not defined), and whether it is a
/// boolean.
fn binary_type(op: BinaryOp, a: BaseType, b: BaseType) -> Option<(BaseType, bool)> {
    use BaseType::*;
    match op {
        BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div => match (a, b) {
            (Float, Float) => Some((Float, false)),
            (Float, t) | (t, Float) if t.is_triple() => Some((t, false)),
            (x, y) if x.is_triple() && y.is_triple() => triple_result(op, x, y).map(|t| (t, false)),
            (Matrix, Matrix) | (Matrix, Float) if matches!(op, BinaryOp::Mul | BinaryOp::Div) => Some((Matrix, false)),
            (Float, Matrix) if op == BinaryOp::Mul => Some((Matrix, false)),
            (Matrix, Matrix) | (Matrix, Float) | (Float, Matrix) => Some((Matrix, false)),
            _ => None,
        },
        BinaryOp::Dot => {
            if (a.is_pointlike() && b.is_pointlike()) || (a == Color && b == Color) {
                Some((Float, false))
            } else {
                None
            }
        }
        BinaryOp::Cross => (a.is_pointlike() && b.is_pointlike()).then_some((Vector, false)),
        BinaryOp::Lt | BinaryOp::Le | BinaryOp::Gt | BinaryOp::Ge => {
            (a == Float && b == Float).then_some((Float, true))
        }
        BinaryOp::Eq | BinaryOp::Ne => {
            let ok = a == b
                || (a.is_pointlike() && b.is_pointlike())
                || (a == Float && (b.is_triple() || b == Matrix))
                || (b == Float && (a.is_triple() || a == Matrix));
            ok.then_some((Float, true))
        }
        BinaryOp::And | BinaryOp::Or => Some((Float, true)),
    }
}

fn binop(op: BinaryOp) -> BinOp {
    match op {
        BinaryOp::Add => BinOp::Add,
        BinaryOp::Sub => BinOp::Sub,
        BinaryOp::Mul => BinOp::Mul,
        BinaryOp::Div => BinOp::Div,
        BinaryOp::Dot => BinOp::Dot,
        BinaryOp::Cross => BinOp::Cross,
        BinaryOp::Eq => BinOp::Eq,
        BinaryOp::Ne => BinOp::Ne,
        BinaryOp::Lt => BinOp::Lt,
        BinaryOp::Le => BinOp::Le,
        BinaryOp::Gt => BinOp::Gt,
        BinaryOp::Ge => BinOp::Ge,
        BinaryOp::And => BinOp::And,
        BinaryOp::Or => BinOp::Or,
    }
}

fn type_name(t: Type) -> String {
    match t.array {
        Some(n) => format!("{}[{n}]", t.base),
        None => t.base.to_string(),
    }
}

fn an(t: BaseType) -> &'static str {
    match t {
        BaseType::Float => "a float",
        BaseType::Color => "a color",
        BaseType::Point => "a point",
        BaseType::Vector => "a vector",
        BaseType::Normal => "a normal",
        BaseType::Matrix => "a matrix",
        BaseType::String => "a string",
        BaseType::Void => "nothing (void)",
    }
}

/// Can a value of base `from` be stored in a variable of base `to` (implicitly)?
fn assignable(from: BaseType, to: BaseType) -> bool {
    from == to
        || (from == BaseType::Float && (to.is_triple() || to == BaseType::Matrix))
        || (from.is_pointlike() && to.is_pointlike())
}

/// Which globals a shader kind may read and write.
fn global_access(kind: ShaderType, g: Global) -> (bool, bool) {
    use Global::*;
    use ShaderType::*;
    match kind {
        Surface => match g {
            Ci | Oi | P | N => (true, true),
            Ps | Alpha => (false, false),
            _ => (true, false),
        },
        Light => match g {
            Cl | Ol | L => (true, true),
            Ci | Oi | Alpha => (false, false),
            _ => (true, false),
        },
        Displacement => match g {
            P | N => (true, true),
            Ci | Oi | Cl | Ol | L | Ps | Alpha => (false, false),
            _ => (true, false),
        },
        Volume => match g {
            Ci | Oi => (true, true),
            Ps | Alpha => (false, false),
            _ => (true, false),
        },
        Imager => match g {
            Ci | Oi | Alpha => (true, true),
            P | Ncomps | Time | S | T | U | V | Du | Dv => (true, false),
            _ => (false, false),
        },
    }
}

impl<'a, 'd> Lowerer<'a, 'd> {
    fn new(kind: ShaderType, diags: &'d mut Diagnostics) -> Self {
        Self {
            kind,
            diags,
            seen: HashSet::new(),
            func: Function::default(),
            blocks: vec![Vec::new()],
            scopes: vec![Scope::default()],
            frames: Vec::new(),
            globals: HashMap::new(),
            slot_names: HashMap::new(),
            vflow: 0,
            light_loops: 0,
            inlining: Vec::new(),
            called: HashSet::new(),
            ret_checked: HashSet::new(),
            uniform_target: false,
            promote: HashSet::new(),
            want_promote: HashSet::new(),
        }
    }

    // ---- diagnostics -------------------------------------------------------------------------

    #[cold]
    fn report(&mut self, d: Diagnostic) {
        if self.seen.insert((d.code, d.span)) {
            self.diags.push(d);
        }
    }

    #[cold]
    fn err(&mut self, code: &'static str, span: Span, msg: impl Into<String>, label: impl Into<String>) {
        self.report(Diagnostic::error(code, span, msg).with_label(label));
    }

    // ---- building ----------------------------------------------------------------------------

    fn emit(&mut self, n: Node) {
        if let Some(b) = self.blocks.last_mut() {
            b.push(n);
        }
    }

    fn inst(&mut self, op: Op, args: Vec<Value>, ty: Type, is_bool: bool, span: Span) -> Val {
        let v = self.func.add_inst(Inst { op, args, ty, is_bool, needs_derivs: false, span });
        self.emit(Node::Inst(v));
        Val { v, ty, is_bool }
    }

    fn constant(&mut self, c: Const, base: BaseType, span: Span) -> Val {
        let ty = match &c {
            Const::Array(v) => Type { base, detail: Detail::Uniform, array: Some(v.len() as u32) },
            _ => Type::uniform(base),
        };
        self.inst(Op::Const(c), Vec::new(), ty, false, span)
    }

    fn new_slot(&mut self, name: &str, ty: Type, kind: SlotKind, span: Span) -> SlotId {
        let n = self.slot_names.entry(name.to_string()).or_insert(0);
        let unique = if *n == 0 { name.to_string() } else { format!("{name}.{n}") };
        *n += 1;
        self.func.slots.push(Slot { name: unique, ty, kind, span });
        SlotId(self.func.slots.len() as u32 - 1)
    }

    fn slot_ty(&self, s: SlotId) -> Type {
        self.func.slots[s.0 as usize].ty
    }

    fn global_slot(&mut self, g: Global) -> SlotId {
        if let Some(&s) = self.globals.get(&g) {
            return s;
        }
        let s = self.new_slot(g.name(), g.ty(), SlotKind::Global(g), Span::DUMMY);
        self.globals.insert(g, s);
        s
    }

    fn push_block(&mut self) {
        self.blocks.push(Vec::new());
    }

    fn pop_block(&mut self) -> ir::Block {
        self.blocks.pop().unwrap_or_default()
    }

    fn push_scope(&mut self, barrier: bool) {
        self.scopes.push(Scope { barrier, ..Scope::default() });
    }

    fn pop_scope(&mut self) {
        self.scopes.pop();
    }

    /// The current varying-flow depth (conditions plus varying early exits).
    fn flow(&self) -> u32 {
        let exits: u32 = self
            .frames
            .iter()
            .map(|f| u32::from(f.varying_exit) + f.loops.iter().filter(|l| l.varying).count() as u32)
            .sum();
        self.vflow + exits
    }

    fn declare(&mut self, name: &str, info: VarInfo) {
        let prev = self.scopes.last().and_then(|s| s.vars.get(name)).map(|v| v.span);
        if let Some(prev) = prev {
            self.report(
                Diagnostic::error(codes::REDEFINITION, info.span, format!("`{name}` is already defined in this scope"))
                    .with_label("redefined here")
                    .with_secondary(prev, "first defined here")
                    .with_note("rename one of them, or assign to the existing variable without a type"),
            );
            return;
        }
        if let Some(s) = self.scopes.last_mut() {
            s.vars.insert(name.to_string(), info);
        }
    }

    fn lookup(&self, name: &str) -> Option<Found> {
        for s in self.scopes.iter().rev() {
            if let Some(v) = s.vars.get(name) {
                return Some(Found::Var(*v));
            }
            if s.barrier {
                break;
            }
        }
        if let Some(g) = Global::from_name(name) {
            return Some(Found::Global(g));
        }
        // Aqsis' light shaders call the surface normal at `Ps` `Ns`.
        if name == "Ns" && self.kind == ShaderType::Light {
            return Some(Found::Global(Global::N));
        }
        if name == "PI" {
            return Some(Found::Pi);
        }
        None
    }

    /// `extern` look-up: past function barriers.
    fn lookup_extern(&self, name: &str) -> Option<Found> {
        let mut crossed = false;
        for s in self.scopes.iter().rev() {
            if crossed {
                if let Some(v) = s.vars.get(name) {
                    return Some(Found::Var(*v));
                }
            }
            if s.barrier {
                crossed = true;
            }
        }
        Global::from_name(name).map(Found::Global)
    }

    fn visible_names(&self) -> Vec<String> {
        let mut out = Vec::new();
        for s in self.scopes.iter().rev() {
            out.extend(s.vars.keys().cloned());
            if s.barrier {
                break;
            }
        }
        out.extend(Global::ALL.iter().filter(|(g, _)| global_access(self.kind, *g).0).map(|(_, n)| n.to_string()));
        out.push("PI".into());
        out
    }

    fn lookup_fns(&self, name: &str) -> Vec<&'a ast::FunctionDef> {
        let mut out = Vec::new();
        for s in self.scopes.iter().rev() {
            if let Some(f) = s.funcs.get(name) {
                out.extend(f.iter().copied());
            }
        }
        out
    }

    fn declare_fn(&mut self, f: &'a ast::FunctionDef) {
        let sig = |f: &ast::FunctionDef| {
            f.params.iter().map(|p| (p.ty.base, p.array.is_some(), p.output)).collect::<Vec<_>>()
        };
        let mine = sig(f);
        let prev = self
            .scopes
            .last()
            .and_then(|s| s.funcs.get(&f.name.name))
            .and_then(|v| v.iter().find(|g| sig(g) == mine && g.span != f.span))
            .map(|g| g.name.span);
        if let Some(prev) = prev {
            self.report(
                Diagnostic::error(
                    codes::REDEFINITION,
                    f.name.span,
                    format!("function `{}` is already defined with these parameter types", f.name.name),
                )
                .with_label("redefined here")
                .with_secondary(prev, "first defined here")
                .with_note("functions may share a name only when their parameter types differ"),
            );
            return;
        }
        if let Some(s) = self.scopes.last_mut() {
            s.funcs.entry(f.name.name.clone()).or_default().push(f);
        }
    }

    // ---- the shader --------------------------------------------------------------------------

    fn lower_shader(&mut self, unit: &'a ast::Unit, sh: &'a ast::ShaderDef) -> Option<ir::Module> {
        for it in &unit.items {
            if let ast::Item::Function(f) = it {
                self.declare_fn(f);
            }
        }
        // Parameters.
        self.push_scope(false);
        let mut params = Vec::new();
        let mut env: HashMap<String, (Const, BaseType)> = HashMap::new();
        for (i, p) in sh.params.iter().enumerate() {
            let detail = p.ty.detail.unwrap_or(Detail::Uniform);
            let array = match p.array {
                None => None,
                Some(Some(n)) => Some(n),
                Some(None) => {
                    self.err(codes::BAD_INDEX, p.name.span, "a shader parameter array needs a size", "size missing");
                    Some(0)
                }
            };
            let ty = Type { base: p.ty.base, detail, array };
            if p.ty.base == BaseType::Void {
                self.err(codes::TYPE_MISMATCH, p.ty.span, "a parameter cannot be void", "void parameter");
            }
            let slot = self.new_slot(&p.name.name, ty, SlotKind::Param(i as u32), p.span);
            let mut space = None;
            let default = match &p.default {
                Some(e) => {
                    let mut ce = ConstEval { env: &env, diags: Vec::new() };
                    let r = ce.eval_to(e, ty, &mut space);
                    for d in ce.diags {
                        self.report(d);
                    }
                    r.unwrap_or_else(|| zero_const(ty))
                }
                None => {
                    self.err(
                        codes::NON_CONSTANT_DEFAULT,
                        p.name.span,
                        format!("shader parameter `{}` needs a default value", p.name.name),
                        "no default",
                    );
                    zero_const(ty)
                }
            };
            env.insert(p.name.name.clone(), (default.clone(), p.ty.base));
            params.push(ParamMeta {
                name: p.name.name.clone(),
                ty,
                default,
                output: p.output,
                slot,
                span: p.span,
                space,
            });
            self.declare(
                &p.name.name,
                VarInfo { binding: Binding::Slot(slot), span: p.name.span, read_only: false, flow: 0 },
            );
        }
        self.frames.push(FrameCtx {
            func: None,
            ret_slot: None,
            loops: Vec::new(),
            varying_exit: false,
            flow_at_entry: 0,
        });
        self.push_scope(false);
        for s in &sh.body.stmts {
            self.stmt(s);
        }
        self.pop_scope();
        self.frames.pop();
        // Check the functions no call reached, with their declared types.
        for it in &unit.items {
            if let ast::Item::Function(f) = it {
                self.check_uncalled(f);
            }
        }
        let body = self.pop_block();
        self.func.body = body;
        if self.diags.has_errors() {
            return None;
        }
        Some(ir::Module {
            kind: kind_of(sh.kind),
            name: sh.name.name.clone(),
            params,
            func: std::mem::take(&mut self.func),
        })
    }

    /// Lowers a never-called function into a scratch frame (discarded) to report its errors.
    fn check_uncalled(&mut self, f: &'a ast::FunctionDef) {
        if self.called.contains(&f.span) {
            return;
        }
        self.called.insert(f.span);
        let (ni, ns) = (self.func.insts.len(), self.func.slots.len());
        let saved_globals = self.globals.clone();
        self.push_block();
        self.frames.push(FrameCtx {
            func: None,
            ret_slot: None,
            loops: Vec::new(),
            varying_exit: false,
            flow_at_entry: 0,
        });
        let mut args = Vec::new();
        for p in &f.params {
            let ty = Type {
                base: p.ty.base,
                detail: p.ty.detail.unwrap_or(Detail::Varying),
                array: p.array.map(|n| n.unwrap_or(1)),
            };
            if p.output || p.array.is_some() {
                let s = self.new_slot(&p.name.name, ty, SlotKind::Local, p.span);
                args.push(CallArg::Place(Place { slot: s, index: None, ty }));
            } else {
                let v = self.inst(Op::Const(zero_const(ty)), Vec::new(), ty, false, p.span);
                args.push(CallArg::Value(v));
            }
        }
        self.inline(f, args, f.name.span, None);
        self.frames.pop();
        self.pop_block();
        self.func.insts.truncate(ni);
        self.func.slots.truncate(ns);
        self.globals = saved_globals;
    }

    // ---- statements --------------------------------------------------------------------------

    fn block(&mut self, b: &'a ast::Block) {
        self.push_scope(false);
        for s in &b.stmts {
            self.stmt(s);
        }
        self.pop_scope();
    }

    /// A statement as a nested block (its own scope).
    fn sub_block(&mut self, s: &'a Stmt) -> ir::Block {
        self.push_block();
        self.push_scope(false);
        self.stmt(s);
        self.pop_scope();
        self.pop_block()
    }

    fn frame(&mut self) -> Option<&mut FrameCtx<'a>> {
        self.frames.last_mut()
    }

    fn stmt(&mut self, s: &'a Stmt) {
        match &s.kind {
            StmtKind::Empty => {}
            StmtKind::Expr(e) => {
                self.expr(e, None);
            }
            StmtKind::Decl { is_extern, ty, vars } => self.decl(*is_extern, ty, vars),
            StmtKind::Block(b) => self.block(b),
            StmtKind::If { cond, then, otherwise } => {
                let Some(c) = self.cond(cond) else {
                    // Still check the branches.
                    let _ = self.sub_block(then);
                    if let Some(o) = otherwise {
                        let _ = self.sub_block(o);
                    }
                    return;
                };
                let varying = c.ty.detail == Detail::Varying;
                self.vflow += u32::from(varying);
                let then = self.sub_block(then);
                let otherwise = otherwise.as_ref().map(|o| self.sub_block(o)).unwrap_or_default();
                self.vflow -= u32::from(varying);
                self.emit(Node::If { cond: c.v, then, otherwise });
            }
            StmtKind::While { cond, body } => self.lower_loop(None, Some(cond), None, body),
            StmtKind::For { init, cond, step, body } => {
                if let Some(i) = init {
                    self.expr(i, None);
                }
                self.lower_loop(None, cond.as_ref(), step.as_ref(), body);
            }
            StmtKind::Break(n) | StmtKind::Continue(n) => {
                let is_break = matches!(s.kind, StmtKind::Break(_));
                let word = if is_break { "break" } else { "continue" };
                let level = n.unwrap_or(1);
                let flow = self.flow();
                let depth = self.frames.last().map_or(0, |f| f.loops.len());
                if level == 0 || level as usize > depth {
                    let msg = if depth == 0 {
                        format!("`{word}` outside a loop")
                    } else {
                        format!("`{word} {level}` inside only {depth} loop{}", if depth == 1 { "" } else { "s" })
                    };
                    self.report(
                        Diagnostic::error(codes::BREAK_OUTSIDE_LOOP, s.span, msg)
                            .with_label(if depth == 0 { "not in a loop" } else { "level too deep" })
                            .with_note(format!(
                                "`{word} n` leaves n enclosing loops (while, for, illuminance); n must be between 1 and {}",
                                depth.max(1)
                            )),
                    );
                    return;
                }
                if let Some(f) = self.frames.last_mut() {
                    let start = f.loops.len() - level as usize;
                    // Conditions entered inside the loop make this exit divergent.
                    if flow > f.flow_at_entry {
                        for l in &mut f.loops[start..] {
                            l.varying = true;
                        }
                    }
                }
                self.emit(if is_break { Node::Break(level - 1) } else { Node::Continue(level - 1) });
            }
            StmtKind::Return(e) => self.ret(s, e.as_ref()),
            StmtKind::Illuminance { category, position, cone, body } => {
                if !matches!(self.kind, ShaderType::Surface | ShaderType::Volume) {
                    self.report(
                        Diagnostic::error(
                            codes::WRONG_CONTEXT,
                            s.span,
                            format!("`illuminance` is not allowed in a {} shader", self.kind.keyword()),
                        )
                        .with_label("light loop here")
                        .with_note(
                            "illuminance loops belong in surface and volume shaders; lights use illuminate or solar",
                        ),
                    );
                }
                let cat = category.as_ref().and_then(|c| self.typed(c, BaseType::String, "an illuminance category"));
                let pos = self.typed(position, BaseType::Point, "the illuminance position");
                let cone = cone.as_ref().map(|(a, b)| {
                    (
                        self.typed(a, BaseType::Vector, "the illuminance axis"),
                        self.typed(b, BaseType::Float, "the illuminance angle"),
                    )
                });
                self.light_loops += 1;
                self.vflow += 1;
                if let Some(f) = self.frame() {
                    f.loops.push(LoopCtx { varying: false });
                }
                let body = self.sub_block(body);
                if let Some(f) = self.frame() {
                    f.loops.pop();
                }
                self.vflow -= 1;
                self.light_loops -= 1;
                let Some(pos) = pos else { return };
                let cone = match cone {
                    Some((Some(a), Some(b))) => Some((a.v, b.v)),
                    Some(_) => return,
                    None => None,
                };
                if category.is_some() && cat.is_none() {
                    return;
                }
                self.emit(Node::Illuminance { category: cat.map(|c| c.v), position: pos.v, cone, body });
            }
            StmtKind::Illuminate { position, cone, body } => {
                self.light_only(s.span, "illuminate");
                let pos = self.typed(position, BaseType::Point, "the illuminate position");
                let cone = cone.as_ref().map(|(a, b)| {
                    (
                        self.typed(a, BaseType::Vector, "the illuminate axis"),
                        self.typed(b, BaseType::Float, "the illuminate angle"),
                    )
                });
                let body = self.light_body(body, cone.is_none());
                let Some(pos) = pos else { return };
                let cone = match cone {
                    Some((Some(a), Some(b))) => Some((a.v, b.v)),
                    Some(_) => return,
                    None => None,
                };
                self.emit(Node::Illuminate { position: pos.v, cone, body });
            }
            StmtKind::Solar { cone, body } => {
                self.light_only(s.span, "solar");
                let cone = cone.as_ref().map(|(a, b)| {
                    (
                        self.typed(a, BaseType::Vector, "the solar axis"),
                        self.typed(b, BaseType::Float, "the solar angle"),
                    )
                });
                let body = self.light_body(body, true);
                let cone = match cone {
                    Some((Some(a), Some(b))) => Some((a.v, b.v)),
                    Some(_) => return,
                    None => None,
                };
                self.emit(Node::Solar { cone, body });
            }
            StmtKind::Gather { body, otherwise, .. } => {
                self.report(
                    Diagnostic::error(codes::UNSUPPORTED, s.span, "`gather` is not supported")
                        .with_label("ray-traced gathering")
                        .with_note("use trace() for single rays"),
                );
                let _ = self.sub_block(body);
                if let Some(o) = otherwise {
                    let _ = self.sub_block(o);
                }
            }
            StmtKind::Function(f) => self.declare_fn(f),
        }
    }

    fn light_only(&mut self, span: Span, what: &str) {
        if self.kind != ShaderType::Light {
            self.report(
                Diagnostic::error(
                    codes::WRONG_CONTEXT,
                    span,
                    format!("`{what}` is only allowed in a light shader, not in a {} shader", self.kind.keyword()),
                )
                .with_label(format!("{what} here"))
                .with_note("surface shaders gather light with `illuminance`"),
            );
        }
    }

    /// The body of `illuminate` or `solar`. With a cone (`illuminate (P, axis, angle)`) only
    /// the points inside it run the body: varying control flow. Without one — `illuminate (P)`,
    /// and `solar`, whose direction does not depend on the point — every point runs it, so
    /// uniform variables may be assigned there (PRMan's own rectanglelight.sl runs uniform
    /// sample loops inside `illuminate (Ps + Ns)`, Liquid's lights query `textureinfo` inside
    /// `solar`).
    fn light_body(&mut self, body: &'a Stmt, all_points: bool) -> ir::Block {
        let v = u32::from(!all_points);
        self.light_loops += 1;
        self.vflow += v;
        let b = self.sub_block(body);
        self.vflow -= v;
        self.light_loops -= 1;
        b
    }

    fn lower_loop(&mut self, _label: Option<()>, cond: Option<&'a Expr>, step: Option<&'a Expr>, body: &'a Stmt) {
        self.push_block();
        let c = cond.map(|c| self.cond(c));
        let header = self.pop_block();
        let (cv, varying) = match c {
            Some(Some(c)) => (Some(c.v), c.ty.detail == Detail::Varying),
            Some(None) => (None, false),
            None => (None, false),
        };
        let failed = matches!(c, Some(None));
        self.vflow += u32::from(varying);
        if let Some(f) = self.frame() {
            f.loops.push(LoopCtx { varying: false });
        }
        let body = self.sub_block(body);
        self.push_block();
        if let Some(st) = step {
            self.expr(st, None);
        }
        let step = self.pop_block();
        if let Some(f) = self.frame() {
            f.loops.pop();
        }
        self.vflow -= u32::from(varying);
        if !failed {
            self.emit(Node::Loop { header, cond: cv, body, step });
        }
    }

    fn ret(&mut self, s: &Stmt, e: Option<&'a Expr>) {
        let Some(frame) = self.frames.last() else { return };
        let flow = self.flow();
        let entry = frame.flow_at_entry;
        match (frame.func, frame.ret_slot) {
            (None, _) => {
                if let Some(e) = e {
                    self.err(
                        codes::RETURN_TYPE,
                        e.span,
                        "a shader cannot return a value",
                        "value returned from the shader body",
                    );
                    return;
                }
            }
            (Some(f), None) => {
                if let Some(e) = e {
                    self.report(
                        Diagnostic::error(
                            codes::RETURN_TYPE,
                            e.span,
                            format!("void function `{}` cannot return a value", f.name.name),
                        )
                        .with_label("value returned")
                        .with_secondary(f.ret.span, "declared void here"),
                    );
                    return;
                }
            }
            (Some(f), Some(slot)) => {
                let Some(e) = e else {
                    self.report(
                        Diagnostic::error(
                            codes::RETURN_TYPE,
                            s.span,
                            format!("function `{}` must return {}", f.name.name, an(f.ret.base)),
                        )
                        .with_label("return without a value"),
                    );
                    return;
                };
                let Some(v) = self.expr(e, Some(f.ret.base)) else {
                    return;
                };
                if !assignable(v.ty.base, f.ret.base) || v.is_bool || v.ty.array.is_some() {
                    self.report(
                        Diagnostic::error(
                            codes::RETURN_TYPE,
                            e.span,
                            format!("function `{}` returns {}, not {}", f.name.name, an(f.ret.base), an(v.ty.base)),
                        )
                        .with_label(format!("this is {}", an(v.ty.base)))
                        .with_secondary(f.ret.span, "return type declared here"),
                    );
                    return;
                }
                let Some(v) = self.convert(v, f.ret.base, e.span) else {
                    return;
                };
                let varying = v.ty.detail == Detail::Varying || flow > entry;
                if varying {
                    if f.ret.detail == Some(Detail::Uniform) {
                        self.report(
                            Diagnostic::error(
                                codes::VARYING_TO_UNIFORM,
                                e.span,
                                format!("function `{}` is declared uniform but returns a varying value", f.name.name),
                            )
                            .with_label("varying value"),
                        );
                    }
                    self.func.slots[slot.0 as usize].ty.detail = Detail::Varying;
                }
                self.emit(Node::Store { slot, index: None, value: v.v, init: false });
            }
        }
        if flow > entry {
            if let Some(f) = self.frame() {
                f.varying_exit = true;
            }
        }
        self.emit(Node::Return);
    }

    fn decl(&mut self, is_extern: bool, ts: &'a ast::TypeSpec, vars: &'a [ast::Declarator]) {
        for d in vars {
            if is_extern {
                match self.lookup_extern(&d.name.name) {
                    Some(Found::Var(v)) => {
                        let t = match v.binding {
                            Binding::Slot(s) => self.slot_ty(s),
                            Binding::Value(v) => v.ty,
                        };
                        if t.base != ts.base {
                            self.report(
                                Diagnostic::error(
                                    codes::TYPE_MISMATCH,
                                    d.name.span,
                                    format!(
                                        "extern `{}` is declared {} but the variable is {}",
                                        d.name.name, ts.base, t.base
                                    ),
                                )
                                .with_label("declared here")
                                .with_secondary(v.span, "the variable"),
                            );
                        }
                        self.declare(&d.name.name, VarInfo { span: d.name.span, ..v });
                    }
                    Some(Found::Global(_)) | Some(Found::Pi) => {} // globals are visible anyway
                    None => {
                        self.report(
                            Diagnostic::error(
                                codes::UNKNOWN_NAME,
                                d.name.span,
                                format!(
                                    "extern `{}` names no variable of an enclosing function or shader",
                                    d.name.name
                                ),
                            )
                            .with_label("not found"),
                        );
                    }
                }
                continue;
            }
            if ts.base == BaseType::Void {
                self.err(codes::TYPE_MISMATCH, ts.span, "a variable cannot be void", "void variable");
                continue;
            }
            let mut ty = Type { base: ts.base, detail: ts.detail.unwrap_or(Detail::Varying), array: d.array };
            if ty.detail == Detail::Uniform && self.promote.contains(&d.name.span) {
                ty.detail = Detail::Varying;
                self.report(
                    Diagnostic::warning(
                        codes::PROMOTED_TO_VARYING,
                        d.name.span,
                        format!(
                            "the uniform variable `{}` is assigned under varying control flow; it is made varying",
                            d.name.name
                        ),
                    )
                    .with_label("made varying")
                    .with_note("as BMRT and Aqsis do for function locals; declare it varying to silence this"),
                );
            }
            if d.array == Some(0) {
                self.err(codes::BAD_INDEX, d.span, "an array needs at least one element", "size 0");
            }
            // The initializer is evaluated before the name is visible.
            let init = match &d.init {
                None => None,
                Some(e) => match (&e.kind, ty.array) {
                    (ExprKind::ArrayInit(items), Some(n)) => {
                        if items.len() != n as usize {
                            self.err(
                                codes::BAD_LITERAL,
                                e.span,
                                format!("array `{}` has {n} elements but {} initializers", d.name.name, items.len()),
                                format!("{} values", items.len()),
                            );
                        }
                        let vals: Vec<R> = items
                            .iter()
                            .map(|it| self.assign_value(it, ty.element(), &d.name.name, d.name.span))
                            .collect();
                        Some(Init::Elems(vals))
                    }
                    (ExprKind::ArrayInit(_), None) => {
                        self.err(
                            codes::BAD_LITERAL,
                            e.span,
                            format!("`{}` is not an array; `{{…}}` initializes arrays", d.name.name),
                            "array initializer",
                        );
                        None
                    }
                    _ => Some(Init::Whole(self.assign_value(e, ty, &d.name.name, d.name.span))),
                },
            };
            let slot = self.new_slot(&d.name.name, ty, SlotKind::Local, d.span);
            let flow = self.flow();
            self.declare(
                &d.name.name,
                VarInfo { binding: Binding::Slot(slot), span: d.name.span, read_only: false, flow },
            );
            match init {
                Some(Init::Whole(Some(v))) => self.emit(Node::Store { slot, index: None, value: v.v, init: true }),
                Some(Init::Elems(vals)) => {
                    for (i, v) in vals.into_iter().enumerate() {
                        if let Some(v) = v {
                            let idx = self.constant(Const::Float(i as f64), BaseType::Float, d.span);
                            self.emit(Node::Store { slot, index: Some(idx.v), value: v.v, init: false });
                        }
                    }
                }
                _ => {}
            }
        }
    }

    /// Lowers `e` for storing into a variable of type `to` (declaration or assignment),
    /// checking type and detail.
    fn assign_value(&mut self, e: &'a Expr, to: Type, name: &str, target: Span) -> R {
        let saved = self.uniform_target;
        self.uniform_target = to.detail == Detail::Uniform;
        let v = self.expr(e, Some(to.base));
        self.uniform_target = saved;
        let v = v?;
        self.check_store(v, to, e.span, name, target)
    }

    /// Checks storing `v` (at `span`) into `name` of type `to` (written at `target`).
    fn check_store(&mut self, v: Val, to: Type, span: Span, name: &str, target: Span) -> R {
        if v.is_bool {
            self.report(
                Diagnostic::error(codes::TYPE_MISMATCH, span, "a relation cannot be stored in a variable")
                    .with_label("boolean")
                    .with_note("write `cond ? 1 : 0` to turn it into a float"),
            );
            return None;
        }
        let ok = if to.array.is_some() || v.ty.array.is_some() {
            to.base == v.ty.base && to.array == v.ty.array
        } else {
            assignable(v.ty.base, to.base)
        };
        if !ok {
            self.report(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    span,
                    format!("type mismatch: {} cannot be assigned to {} `{}`", an_t(v.ty), an_t(to), name),
                )
                .with_label(format!("this is {}", an_t(v.ty)))
                .with_note(match (v.ty.base, to.base) {
                    (a, b) if a.is_triple() && b.is_triple() => {
                        format!("convert explicitly with a cast: `{} (…)`", to.base)
                    }
                    (a, BaseType::Float) if a.is_triple() => {
                        "take one component with comp(), xcomp()… or a product like `x . y`".to_string()
                    }
                    _ => format!("`{name}` is declared {}", type_name(to)),
                }),
            );
            return None;
        }
        if v.ty.detail == Detail::Varying && to.detail == Detail::Uniform {
            self.report(
                Diagnostic::error(
                    codes::VARYING_TO_UNIFORM,
                    target,
                    format!("a varying value cannot be assigned to the uniform variable `{name}`"),
                )
                .with_label("uniform variable")
                .with_secondary(span, "varying value")
                .with_note(format!("declare `{name}` varying, or compute it from uniform values only")),
            );
            return None;
        }
        if to.array.is_some() {
            return Some(v);
        }
        self.convert(v, to.base, span)
    }

    // ---- expressions -------------------------------------------------------------------------

    /// Converts `v` to base `to` (float → triple/matrix, point-like kinds). Assumes the
    /// conversion is legal (checked by the caller).
    fn convert(&mut self, v: Val, to: BaseType, span: Span) -> R {
        if v.ty.base == to || v.ty.array.is_some() {
            return Some(v);
        }
        let ty = Type { base: to, ..v.ty };
        Some(self.inst(Op::Convert, vec![v.v], ty, false, span))
    }

    /// Lowers `e` expecting type `to` (a typed argument of a statement).
    fn typed(&mut self, e: &'a Expr, to: BaseType, what: &str) -> R {
        let v = self.expr(e, Some(to))?;
        if v.is_bool || v.ty.array.is_some() || !assignable(v.ty.base, to) {
            self.report(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    e.span,
                    format!("{what} must be {}, not {}", an(to), an_t(v.ty)),
                )
                .with_label(format!("this is {}", an_t(v.ty))),
            );
            return None;
        }
        self.convert(v, to, e.span)
    }

    /// A condition: a relation, or a float (`x` means `x != 0`).
    fn cond(&mut self, e: &'a Expr) -> R {
        let v = self.expr(e, Some(BaseType::Float))?;
        self.to_bool(v, e.span)
    }

    fn to_bool(&mut self, v: Val, span: Span) -> R {
        if v.is_bool {
            return Some(v);
        }
        if v.ty.base == BaseType::Float && v.ty.array.is_none() {
            return Some(self.inst(Op::Convert, vec![v.v], Type { base: BaseType::Float, ..v.ty }, true, span));
        }
        self.report(
            Diagnostic::error(
                codes::TYPE_MISMATCH,
                span,
                format!("a condition must be a relation or a float, not {}", an_t(v.ty)),
            )
            .with_label(format!("this is {}", an_t(v.ty)))
            .with_note("compare it explicitly, e.g. `x != 0` or `s == \"\"`"),
        );
        None
    }

    fn expr(&mut self, e: &'a Expr, expected: Option<BaseType>) -> R {
        match &e.kind {
            ExprKind::Number(x) => Some(self.constant(Const::Float(*x), BaseType::Float, e.span)),
            ExprKind::Str(s) => Some(self.constant(Const::Str(s.clone()), BaseType::String, e.span)),
            ExprKind::Name(n) => self.name(n, e.span),
            ExprKind::Unary(UnaryOp::Neg, a) => {
                let v = self.expr(a, expected)?;
                if v.is_bool || v.ty.array.is_some() || !(v.ty.base.components() > 0) {
                    self.report(
                        Diagnostic::error(codes::BAD_OPERANDS, e.span, format!("cannot negate {}", an_t(v.ty)))
                            .with_label(format!("this is {}", an_t(v.ty))),
                    );
                    return None;
                }
                Some(self.inst(Op::Unary(UnOp::Neg), vec![v.v], v.ty, false, e.span))
            }
            ExprKind::Unary(UnaryOp::Not, a) => {
                let v = self.cond(a)?;
                Some(self.inst(Op::Unary(UnOp::Not), vec![v.v], v.ty, true, e.span))
            }
            ExprKind::Binary(op, a, b) => self.binary(e, *op, a, b, expected),
            ExprKind::Ternary(c, a, b) => {
                let c = self.cond(c);
                let x = self.expr(a, expected);
                let y = self.expr(b, expected);
                let (c, x, y) = (c?, x?, y?);
                if x.ty.array.is_some() || y.ty.array.is_some() {
                    self.err(codes::BAD_OPERANDS, e.span, "`?:` cannot choose between arrays", "array operand");
                    return None;
                }
                if x.is_bool && y.is_bool {
                    let d = c.ty.detail.join(x.ty.detail).join(y.ty.detail);
                    return Some(self.inst(
                        Op::Select,
                        vec![c.v, x.v, y.v],
                        Type::new(BaseType::Float, d),
                        true,
                        e.span,
                    ));
                }
                let (x, y) = (self.unbool(x, a.span)?, self.unbool(y, b.span)?);
                let base = if x.ty.base == y.ty.base {
                    x.ty.base
                } else if assignable(y.ty.base, x.ty.base) && y.ty.base == BaseType::Float {
                    x.ty.base
                } else if assignable(x.ty.base, y.ty.base) && x.ty.base == BaseType::Float {
                    y.ty.base
                } else if x.ty.base.is_pointlike() && y.ty.base.is_pointlike() {
                    expected.filter(|t| t.is_pointlike()).unwrap_or(x.ty.base)
                } else {
                    self.report(
                        Diagnostic::error(
                            codes::TYPE_MISMATCH,
                            e.span,
                            format!("the arms of `?:` have different types: {} and {}", an_t(x.ty), an_t(y.ty)),
                        )
                        .with_label("arms differ")
                        .with_note("cast one arm so both have the same type"),
                    );
                    return None;
                };
                let x = self.convert(x, base, a.span)?;
                let y = self.convert(y, base, b.span)?;
                let d = c.ty.detail.join(x.ty.detail).join(y.ty.detail);
                Some(self.inst(Op::Select, vec![c.v, x.v, y.v], Type::new(base, d), false, e.span))
            }
            ExprKind::Assign(op, lhs, rhs) => self.assign(e, *op, lhs, rhs),
            ExprKind::Call(name, args) => self.call(e, name, args, expected),
            ExprKind::Triple(items) => {
                let base = expected.filter(|t| t.is_triple()).unwrap_or(BaseType::Point);
                self.triple(e, base, &items[..])
            }
            ExprKind::MatrixLit(items) => self.matrix_lit(e, items),
            ExprKind::ArrayInit(_) => {
                self.err(
                    codes::BAD_LITERAL,
                    e.span,
                    "an array initializer `{…}` is only allowed in a declaration",
                    "array initializer",
                );
                None
            }
            ExprKind::Index(base, idx) => self.index(e, base, idx),
            ExprKind::Cast { to, space, expr } => self.cast(e, *to, space.as_deref(), expr),
        }
    }

    /// A relation used as a value (`x = a < b`): an error.
    fn unbool(&mut self, v: Val, span: Span) -> R {
        if v.is_bool {
            self.report(
                Diagnostic::error(codes::TYPE_MISMATCH, span, "a relation is not a value")
                    .with_label("boolean")
                    .with_note("write `cond ? 1 : 0` to turn it into a float"),
            );
            return None;
        }
        Some(v)
    }

    fn triple(&mut self, e: &'a Expr, base: BaseType, items: &'a [Expr]) -> R {
        let mut vals = Vec::new();
        let mut ok = true;
        for it in items {
            match self.expr(it, Some(BaseType::Float)) {
                Some(v) if v.ty.base == BaseType::Float && !v.is_bool && v.ty.array.is_none() => vals.push(v),
                Some(v) => {
                    self.report(
                        Diagnostic::error(
                            codes::BAD_LITERAL,
                            it.span,
                            format!("a component of a {base} must be a float, not {}", an_t(v.ty)),
                        )
                        .with_label(format!("this is {}", an_t(v.ty))),
                    );
                    ok = false;
                }
                None => ok = false,
            }
        }
        if !ok {
            return None;
        }
        let d = vals.iter().fold(Detail::Uniform, |d, v| d.join(v.ty.detail));
        Some(self.inst(Op::MakeTriple, vals.iter().map(|v| v.v).collect(), Type::new(base, d), false, e.span))
    }

    fn matrix_lit(&mut self, e: &'a Expr, items: &'a [Expr]) -> R {
        if items.len() != 16 {
            self.report(
                Diagnostic::error(
                    codes::BAD_LITERAL,
                    e.span,
                    format!("a matrix literal needs 16 components, not {}", items.len()),
                )
                .with_label(format!("{} components", items.len()))
                .with_note("write all 16 values row by row, or `matrix 1` for the identity"),
            );
            return None;
        }
        let mut vals = Vec::new();
        let mut ok = true;
        for it in items {
            match self.expr(it, Some(BaseType::Float)) {
                Some(v) if v.ty.base == BaseType::Float && !v.is_bool && v.ty.array.is_none() => vals.push(v),
                Some(v) => {
                    self.err(
                        codes::BAD_LITERAL,
                        it.span,
                        format!("a matrix component must be a float, not {}", an_t(v.ty)),
                        "not a float",
                    );
                    ok = false;
                }
                None => ok = false,
            }
        }
        if !ok {
            return None;
        }
        let d = vals.iter().fold(Detail::Uniform, |d, v| d.join(v.ty.detail));
        Some(self.inst(
            Op::MakeMatrix,
            vals.iter().map(|v| v.v).collect(),
            Type::new(BaseType::Matrix, d),
            false,
            e.span,
        ))
    }

    fn name(&mut self, n: &str, span: Span) -> R {
        match self.lookup(n) {
            Some(Found::Var(v)) => match v.binding {
                Binding::Value(val) => Some(val),
                Binding::Slot(s) => {
                    let ty = self.slot_ty(s);
                    Some(self.inst(Op::Load(s), Vec::new(), ty, false, span))
                }
            },
            Some(Found::Pi) => Some(self.constant(Const::Float(std::f64::consts::PI), BaseType::Float, span)),
            Some(Found::Global(g)) => {
                if !self.global_readable(g, span) {
                    return None;
                }
                let s = self.global_slot(g);
                Some(self.inst(Op::Load(s), Vec::new(), g.ty(), false, span))
            }
            None => {
                let mut d = Diagnostic::error(codes::UNKNOWN_NAME, span, format!("unknown variable `{n}`"))
                    .with_label("not declared");
                let names = self.visible_names();
                if let Some(s) = suggest(n, names.iter().map(String::as_str)) {
                    d = d.with_note(format!("did you mean `{s}`?"));
                } else if !self.lookup_fns(n).is_empty() || builtins::exists(n) {
                    d = d.with_note(format!("`{n}` is a function: call it as `{n}(…)`"));
                } else if self.frames.last().is_some_and(|f| f.func.is_some()) && self.lookup_extern(n).is_some() {
                    d = d.with_note(format!(
                        "`{n}` belongs to an enclosing function or shader: declare it `extern` first"
                    ));
                }
                self.report(d);
                None
            }
        }
    }

    fn global_readable(&mut self, g: Global, span: Span) -> bool {
        let (read, _) = global_access(self.kind, g);
        if !read {
            self.report(
                Diagnostic::error(
                    codes::WRONG_CONTEXT,
                    span,
                    format!("the global `{}` does not exist in a {} shader", g.name(), self.kind.keyword()),
                )
                .with_label("not available here"),
            );
            return false;
        }
        if matches!(g, Global::L | Global::Cl | Global::Ol)
            && matches!(self.kind, ShaderType::Surface | ShaderType::Volume)
            && self.light_loops == 0
        {
            self.report(
                Diagnostic::error(
                    codes::WRONG_CONTEXT,
                    span,
                    format!("`{}` is only defined inside illuminance in a {} shader", g.name(), self.kind.keyword()),
                )
                .with_label("outside any illuminance loop")
                .with_note("read L and Cl in the body of an `illuminance (P, …) { … }` loop"),
            );
            return false;
        }
        true
    }

    fn binary(&mut self, e: &'a Expr, op: BinaryOp, a: &'a Expr, b: &'a Expr, expected: Option<BaseType>) -> R {
        if matches!(op, BinaryOp::And | BinaryOp::Or) {
            let x = self.cond(a);
            let y = self.cond(b);
            let (x, y) = (x?, y?);
            let d = x.ty.detail.join(y.ty.detail);
            return Some(self.inst(Op::Binary(binop(op)), vec![x.v, y.v], Type::new(BaseType::Float, d), true, e.span));
        }
        let arith = matches!(op, BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div);
        let is_triple_lit = |x: &Expr| matches!(x.kind, ExprKind::Triple(_));
        // A bare `(a, b, c)` takes the other operand's type.
        let (x, y) = if is_triple_lit(a) && !is_triple_lit(b) {
            let y = self.expr(b, if arith { expected } else { None });
            let hint = y.map(|y| y.ty.base).filter(|t| t.is_triple()).or(expected);
            (self.expr(a, hint), y)
        } else {
            let x = self.expr(a, if arith { expected } else { None });
            let hint =
                if is_triple_lit(b) { x.map(|x| x.ty.base).filter(|t| t.is_triple()).or(expected) } else { None };
            let y = self.expr(b, if arith { expected } else { hint });
            let y = if y.is_none() && hint.is_some() { None } else { y };
            (x, y)
        };
        let (x, y) = (x?, y?);
        let (x, y) = (self.unbool(x, a.span)?, self.unbool(y, b.span)?);
        let res =
            if x.ty.array.is_some() || y.ty.array.is_some() { None } else { binary_type(op, x.ty.base, y.ty.base) };
        let Some((base, is_bool)) = res else {
            let mut d = Diagnostic::error(
                codes::BAD_OPERANDS,
                e.span,
                format!("binary operation `{}` between {} and {} is illegal", op.symbol(), an_t(x.ty), an_t(y.ty)),
            )
            .with_label(format!("{} {} {}", type_name(x.ty), op.symbol(), type_name(y.ty)));
            if (x.ty.base == BaseType::Color && y.ty.base.is_pointlike())
                || (y.ty.base == BaseType::Color && x.ty.base.is_pointlike())
            {
                d = d.with_note("colors and points do not mix; cast one side, e.g. `color (…)` or `vector (…)`");
            } else if matches!(op, BinaryOp::Lt | BinaryOp::Le | BinaryOp::Gt | BinaryOp::Ge) {
                d = d.with_note("only floats can be ordered; compare lengths or components instead");
            }
            self.report(d);
            return None;
        };
        let d = x.ty.detail.join(y.ty.detail);
        Some(self.inst(Op::Binary(binop(op)), vec![x.v, y.v], Type::new(base, d), is_bool, e.span))
    }

    /// The storage place an lvalue expression names (emitting its index computation).
    fn place(&mut self, e: &'a Expr, what: &str) -> Option<Place> {
        let (name, idx) = match &e.kind {
            ExprKind::Name(n) => (n.as_str(), None),
            ExprKind::Index(b, i) => match &b.kind {
                ExprKind::Name(n) => (n.as_str(), Some(i)),
                _ => {
                    self.not_lvalue(e, what);
                    return None;
                }
            },
            _ => {
                self.not_lvalue(e, what);
                return None;
            }
        };
        let slot = match self.lookup(name) {
            Some(Found::Var(v)) => match v.binding {
                Binding::Slot(s) if !v.read_only => {
                    let decl_flow = v.flow;
                    let ty = self.slot_ty(s);
                    if ty.detail == Detail::Uniform
                        && self.flow() > decl_flow
                        && self.frames.last().is_some_and(|f| f.func.is_some())
                        && !self.promote.contains(&v.span)
                    {
                        // A local of a function (inlined here): lowered again as varying.
                        self.want_promote.insert(v.span);
                    } else if ty.detail == Detail::Uniform && self.flow() > decl_flow {
                        self.report(
                            Diagnostic::error(
                                codes::UNIFORM_IN_VARYING_FLOW,
                                e.span,
                                format!("the uniform variable `{name}` is assigned under varying control flow"),
                            )
                            .with_label("assigned here")
                            .with_secondary(v.span, "declared uniform here")
                            .with_note(
                                "inside a varying `if`, loop or light loop, points would disagree about its value; \
                                 declare it varying",
                            ),
                        );
                    }
                    s
                }
                _ => {
                    self.report(
                        Diagnostic::error(codes::READ_ONLY, e.span, format!("`{name}` is a read-only parameter"))
                            .with_label("assigned here")
                            .with_secondary(v.span, "parameter declared here")
                            .with_note("declare the parameter `output` to let the function assign it"),
                    );
                    return None;
                }
            },
            Some(Found::Global(g)) => {
                let (_, write) = global_access(self.kind, g);
                if !write {
                    let d = Diagnostic::error(
                        codes::READ_ONLY,
                        e.span,
                        format!("assignment to the read-only global {} in a {} shader", g.name(), self.kind.keyword()),
                    )
                    .with_label("read-only here")
                    .with_note(format!(
                        "a {} shader may assign {}",
                        self.kind.keyword(),
                        Global::ALL
                            .iter()
                            .filter(|(g, _)| global_access(self.kind, *g).1)
                            .map(|(_, n)| *n)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ));
                    self.report(d);
                    return None;
                }
                if !self.global_readable(g, e.span) {
                    return None;
                }
                self.global_slot(g)
            }
            Some(Found::Pi) => {
                self.err(codes::READ_ONLY, e.span, "`PI` is a constant", "assigned here");
                return None;
            }
            None => {
                self.name(name, e.span);
                return None;
            }
        };
        let ty = self.slot_ty(slot);
        match idx {
            None => Some(Place { slot, index: None, ty }),
            Some(i) => {
                if ty.array.is_none() {
                    self.report(
                        Diagnostic::error(
                            codes::BAD_INDEX,
                            e.span,
                            format!("`{name}` is not an array and cannot be indexed"),
                        )
                        .with_label(format!("`{name}` is {}", an_t(ty)))
                        .with_note("use setcomp() to set one component of a triple"),
                    );
                    return None;
                }
                let iv = self.index_value(i)?;
                Some(Place { slot, index: Some(iv), ty: ty.element() })
            }
        }
    }

    fn not_lvalue(&mut self, e: &Expr, what: &str) {
        let kind = match &e.kind {
            ExprKind::Call(..) => "a function call",
            ExprKind::Number(_) | ExprKind::Str(_) => "a literal",
            ExprKind::Cast { .. } => "a cast",
            _ => "an expression",
        };
        self.report(
            Diagnostic::error(
                if what == "output" { codes::OUTPUT_ARG } else { codes::NOT_LVALUE },
                e.span,
                if what == "output" {
                    format!("an output parameter is passed {kind}, not a variable")
                } else {
                    format!("assignment to something that is not a variable ({kind})")
                },
            )
            .with_label("not a variable")
            .with_note("only variables and array elements can be assigned"),
        );
    }

    fn index_value(&mut self, i: &'a Expr) -> R {
        let v = self.expr(i, Some(BaseType::Float))?;
        if v.ty.base != BaseType::Float || v.is_bool || v.ty.array.is_some() {
            self.err(codes::BAD_INDEX, i.span, format!("an index must be a float, not {}", an_t(v.ty)), "bad index");
            return None;
        }
        Some(v)
    }

    fn store(&mut self, p: &Place, v: Val) {
        self.emit(Node::Store { slot: p.slot, index: p.index.map(|i| i.v), value: v.v, init: false });
    }

    fn load_place(&mut self, p: &Place, span: Span) -> Val {
        match p.index {
            None => self.inst(Op::Load(p.slot), Vec::new(), p.ty, false, span),
            Some(i) => {
                let ty = Type { detail: p.ty.detail.join(i.ty.detail), ..p.ty };
                self.inst(Op::LoadElem(p.slot), vec![i.v], ty, false, span)
            }
        }
    }

    fn slot_name(&self, s: SlotId) -> String {
        self.func.slots[s.0 as usize].name.clone()
    }

    fn assign(&mut self, e: &'a Expr, op: AssignOp, lhs: &'a Expr, rhs: &'a Expr) -> R {
        let place = self.place(lhs, "assign");
        let target = place.as_ref().map(|p| p.ty.base);
        let saved = self.uniform_target;
        self.uniform_target = place.as_ref().is_some_and(|p| p.ty.detail == Detail::Uniform);
        let r = self.expr(rhs, target);
        self.uniform_target = saved;
        let (place, r) = (place?, r?);
        let name = self.slot_name(place.slot);
        let value = match op {
            AssignOp::Assign => r,
            _ => {
                let bop = match op {
                    AssignOp::Add => BinaryOp::Add,
                    AssignOp::Sub => BinaryOp::Sub,
                    AssignOp::Mul => BinaryOp::Mul,
                    _ => BinaryOp::Div,
                };
                let cur = self.load_place(&place, lhs.span);
                let r = self.unbool(r, rhs.span)?;
                let res = if cur.ty.array.is_some() || r.ty.array.is_some() {
                    None
                } else {
                    binary_type(bop, cur.ty.base, r.ty.base)
                };
                let Some((base, _)) = res else {
                    self.report(
                        Diagnostic::error(
                            codes::BAD_OPERANDS,
                            e.span,
                            format!("`{}=` between {} and {} is illegal", bop.symbol(), an_t(cur.ty), an_t(r.ty)),
                        )
                        .with_label(format!(
                            "{} {}= {}",
                            type_name(cur.ty),
                            bop.symbol(),
                            type_name(r.ty)
                        )),
                    );
                    return None;
                };
                let d = cur.ty.detail.join(r.ty.detail);
                self.inst(Op::Binary(binop(bop)), vec![cur.v, r.v], Type::new(base, d), false, e.span)
            }
        };
        let value = self.check_store(value, place.ty, rhs.span, &name, lhs.span)?;
        if let Some(i) = place.index {
            if i.ty.detail == Detail::Varying && place.ty.detail == Detail::Uniform {
                self.err(
                    codes::VARYING_TO_UNIFORM,
                    e.span,
                    format!("a varying index cannot select an element of the uniform array `{name}`"),
                    "varying index",
                );
                return None;
            }
        }
        self.store(&place, value);
        Some(value)
    }

    fn index(&mut self, e: &'a Expr, base: &'a Expr, idx: &'a Expr) -> R {
        if let ExprKind::Name(n) = &base.kind {
            if let Some(Found::Var(VarInfo { binding: Binding::Slot(s), .. })) = self.lookup(n) {
                let ty = self.slot_ty(s);
                if ty.array.is_some() {
                    let i = self.index_value(idx)?;
                    let ety = Type { detail: ty.detail.join(i.ty.detail), ..ty.element() };
                    return Some(self.inst(Op::LoadElem(s), vec![i.v], ety, false, e.span));
                }
            }
        }
        let b = self.expr(base, None)?;
        if b.ty.array.is_none() && b.ty.base.is_triple() {
            // `P[1]`: a component, as comp(P, 1).
            let i = self.index_value(idx)?;
            let k = builtins::resolve("comp", &[b.ty, i.ty]).ok()?;
            let d = b.ty.detail.join(i.ty.detail);
            let b = self.convert(b, OVERLOADS[k as usize].params[0].ty, base.span)?;
            return Some(self.inst(
                Op::Call { builtin: Builtin::Comp, overload: k, outputs: vec![None, None] },
                vec![b.v, i.v],
                Type::new(BaseType::Float, d),
                false,
                e.span,
            ));
        }
        if b.ty.base == BaseType::String && b.ty.array.is_none() {
            self.report(
                Diagnostic::error(
                    codes::UNSUPPORTED,
                    e.span,
                    "texture channel selection `\"name\"[n]` is not supported",
                )
                .with_label("channel selection"),
            );
            return None;
        }
        let what = match &base.kind {
            ExprKind::Name(n) => format!("`{n}`"),
            _ => "this expression".into(),
        };
        self.report(
            Diagnostic::error(codes::BAD_INDEX, e.span, format!("indexing {what}, which is not an array"))
                .with_label(format!("{what} is {}", an_t(b.ty))),
        );
        None
    }

    fn cast(&mut self, e: &'a Expr, to: BaseType, space: Option<&'a Expr>, inner: &'a Expr) -> R {
        let sp = match space {
            None => None,
            Some(s) => {
                let v = self.expr(s, Some(BaseType::String))?;
                if v.ty.base != BaseType::String || v.ty.array.is_some() {
                    self.err(codes::TYPE_MISMATCH, s.span, "a space name must be a string", "not a string");
                    return None;
                }
                if let ExprKind::Str(name) = &s.kind {
                    self.check_space(to, name, s.span);
                }
                Some(v)
            }
        };
        let v = match &inner.kind {
            ExprKind::Triple(items) if to.is_triple() => self.triple(inner, to, &items[..])?,
            _ => self.expr(inner, Some(to))?,
        };
        let v = self.unbool(v, inner.span)?;
        let ok = v.ty.array.is_none()
            && (v.ty.base == to
                || (v.ty.base == BaseType::Float && (to.is_triple() || to == BaseType::Matrix))
                || (v.ty.base.is_triple() && to.is_triple()));
        if !ok {
            self.report(
                Diagnostic::error(codes::TYPE_MISMATCH, e.span, format!("cannot cast {} to {to}", an_t(v.ty)))
                    .with_label(format!("this is {}", an_t(v.ty))),
            );
            return None;
        }
        let v = if v.ty.base == to {
            v
        } else {
            self.inst(Op::Convert, vec![v.v], Type { base: to, ..v.ty }, false, e.span)
        };
        match sp {
            None => Some(v),
            Some(s) => {
                let d = v.ty.detail.join(s.ty.detail);
                Some(self.inst(Op::FromSpace, vec![s.v, v.v], Type::new(to, d), false, e.span))
            }
        }
    }

    fn check_space(&mut self, to: BaseType, name: &str, span: Span) {
        const SPACES: &[&str] = &["current", "object", "shader", "world", "camera", "screen", "raster", "NDC", "eye"];
        let known = if to == BaseType::Color {
            anysl_core::stdlib::ColorSpace::from_name(name).is_some()
        } else {
            SPACES.contains(&name)
        };
        if !known {
            let mut d = Diagnostic::warning(
                codes::UNKNOWN_SPACE,
                span,
                format!("unknown {} space \"{name}\"", if to == BaseType::Color { "colour" } else { "coordinate" }),
            )
            .with_label("unknown space");
            if to == BaseType::Color {
                d = d.with_note("colour spaces: rgb, hsv, hsl, xyz, xyY, YIQ");
            } else {
                d = d.with_note("named coordinate systems from the scene are looked up at render time");
            }
            if to == BaseType::Color {
                self.report(d);
            }
        }
    }

    // ---- calls -------------------------------------------------------------------------------

    fn call(&mut self, e: &'a Expr, name: &'a ast::Ident, args: &'a [Expr], expected: Option<BaseType>) -> R {
        let user = self.lookup_fns(&name.name);
        if !user.is_empty() {
            return self.user_call(e, name, &user, args, expected);
        }
        if !builtins::exists(&name.name) {
            let mut d =
                Diagnostic::error(codes::UNKNOWN_FUNCTION, name.span, format!("unknown function `{}`", name.name))
                    .with_label("not defined");
            let mut names: Vec<&str> = OVERLOADS.iter().map(|o| o.name()).collect();
            names.dedup();
            let user_names: Vec<String> = self.scopes.iter().flat_map(|s| s.funcs.keys().cloned()).collect();
            if let Some(s) = suggest(&name.name, names.into_iter().chain(user_names.iter().map(String::as_str))) {
                d = d.with_note(format!("did you mean `{s}`?"));
            } else {
                d = d.with_note("functions must be defined (or #included) before the shader is compiled");
            }
            self.report(d);
            // Still check the arguments.
            for a in args {
                self.expr(a, None);
            }
            return None;
        }
        self.builtin_call(e, name, args, expected)
    }

    /// Positions that are `output` in every overload of `name` taking `n` arguments.
    fn output_positions(&self, name: &str, n: usize) -> Vec<bool> {
        let mut out = vec![false; n];
        let mut first = true;
        for i in builtins::overloads_of(name) {
            let o = &OVERLOADS[i as usize];
            if !o.accepts_count(n) {
                continue;
            }
            for (k, slot) in out.iter_mut().enumerate() {
                let is_out = o.param(k).is_some_and(|p| p.output);
                *slot = if first { is_out } else { *slot && is_out };
            }
            first = false;
        }
        out
    }

    /// The unique parameter type at position `k` among `name`'s overloads of arity `n`.
    fn unique_param(&self, name: &str, n: usize, k: usize) -> Option<BaseType> {
        let mut t = None;
        for i in builtins::overloads_of(name) {
            let o = &OVERLOADS[i as usize];
            if !o.accepts_count(n) {
                continue;
            }
            let p = o.param(k)?;
            match t {
                None => t = Some(p.ty),
                Some(x) if x != p.ty => return None,
                _ => {}
            }
        }
        t
    }

    fn builtin_call(&mut self, e: &'a Expr, name: &'a ast::Ident, args: &'a [Expr], expected: Option<BaseType>) -> R {
        let outs = self.output_positions(&name.name, args.len());
        let mut vals: Vec<CallArg> = Vec::new();
        let mut failed = false;
        // Spans of the arguments as lowered (channel selection appends two).
        let mut spans: Vec<Span> = args.iter().map(|a| a.span).collect();
        let mut channel: Option<(Val, Span)> = None;
        for (k, a) in args.iter().enumerate() {
            // `texture ("name"[n], …)`, `environment (envname[3], …)`: channel selection on the
            // map name (PRMan, BMRT, Aqsis) — the name, plus a `"firstchannel", n` option.
            if k == 0 && matches!(name.name.as_str(), "texture" | "environment" | "shadow") {
                if let ExprKind::Index(base, idx) = &a.kind {
                    if let Some(b) = self.expr(base, Some(BaseType::String)) {
                        if b.ty.base == BaseType::String && b.ty.array.is_none() {
                            let Some(i) = self.index_value(idx) else {
                                failed = true;
                                continue;
                            };
                            vals.push(CallArg::Value(b));
                            channel = Some((i, idx.span));
                            continue;
                        }
                    }
                }
            }
            if outs[k] {
                match self.place(a, "output") {
                    Some(p) => vals.push(CallArg::Place(p)),
                    None => failed = true,
                }
            } else {
                let hint = if matches!(a.kind, ExprKind::Triple(_)) {
                    self.unique_param(&name.name, args.len(), k).or(expected.filter(|t| t.is_triple()))
                } else {
                    None
                };
                match self.expr(a, hint).and_then(|v| self.unbool(v, a.span)) {
                    Some(v) => vals.push(CallArg::Value(v)),
                    None => failed = true,
                }
            }
        }
        if failed {
            return None;
        }
        if let Some((i, span)) = channel {
            let opt = self.constant(Const::Str("firstchannel".into()), BaseType::String, span);
            vals.push(CallArg::Value(opt));
            vals.push(CallArg::Value(i));
            spans.push(span);
            spans.push(span);
        }
        let types: Vec<Type> = vals.iter().map(CallArg::ty).collect();
        let k = match builtins::resolve_expecting(&name.name, &types, expected) {
            Ok(k) => k,
            Err(err) => {
                self.no_overload(e, &name.name, args, &types, err, builtins::overloads_of(&name.name).collect());
                return None;
            }
        };
        let o: &'static Overload = &OVERLOADS[k as usize];
        let mut inputs = Vec::new();
        let mut outputs = Vec::new();
        let uniform_random = o.builtin == Builtin::Random && self.uniform_target;
        let mut detail = if o.always_varying && !uniform_random { Detail::Varying } else { Detail::Uniform };
        let mut copy_out = Vec::new();
        for (i, a) in vals.into_iter().enumerate() {
            let p = o.param(i);
            match a {
                CallArg::Value(v) => {
                    detail = detail.join(v.ty.detail);
                    let v = match p {
                        Some(p) if !p.any && !p.array => self.convert(v, p.ty, spans[i])?,
                        _ => v,
                    };
                    inputs.push(v.v);
                    outputs.push(None);
                }
                CallArg::Place(pl) => {
                    if pl.index.is_some() {
                        // An array element: written through a temporary, copied back below.
                        let t = self.new_slot(&format!("{}.out", name.name), pl.ty, SlotKind::Local, spans[i]);
                        outputs.push(Some(t));
                        copy_out.push((t, pl, spans[i]));
                    } else {
                        outputs.push(Some(pl.slot));
                        copy_out.push((pl.slot, pl, spans[i]));
                    }
                }
            }
        }
        let ty = Type::new(o.ret, detail);
        let out_detail = detail.join(if self.flow() > 0 { Detail::Varying } else { Detail::Uniform });
        let r = self.inst(Op::Call { builtin: o.builtin, overload: k, outputs }, inputs, ty, false, e.span);
        for (t, pl, span) in copy_out {
            if pl.ty.detail == Detail::Uniform && out_detail == Detail::Varying && detail == Detail::Varying {
                let n = self.slot_name(pl.slot);
                self.report(
                    Diagnostic::error(
                        codes::VARYING_TO_UNIFORM,
                        span,
                        format!("`{}` writes a varying value into the uniform variable `{n}`", name.name),
                    )
                    .with_label("uniform output")
                    .with_note(format!("declare `{n}` varying")),
                );
            }
            if t != pl.slot {
                let v = self.inst(Op::Load(t), Vec::new(), pl.ty, false, span);
                self.store(&pl, v);
            }
        }
        Some(r)
    }

    #[cold]
    fn no_overload(&mut self, e: &Expr, name: &str, args: &[Expr], types: &[Type], err: ResolveError, cands: Vec<u32>) {
        let given = types.iter().map(|t| type_name(*t)).collect::<Vec<_>>().join(", ");
        let mut d = match err {
            ResolveError::ArgCount(counts) => {
                let list: Vec<String> =
                    counts.iter().map(|&c| if c == usize::MAX { "more".to_string() } else { c.to_string() }).collect();
                Diagnostic::error(
                    codes::ARG_COUNT,
                    e.span,
                    format!("`{name}` does not take {} argument{}", args.len(), if args.len() == 1 { "" } else { "s" }),
                )
                .with_label(format!("{} given", args.len()))
                .with_note(format!("it takes {}", list.join(" or ")))
            }
            _ => {
                let what = if types.len() == 1 { an_t(types[0]).to_string() } else { format!("({given})") };
                Diagnostic::error(codes::NO_OVERLOAD, e.span, format!("no overload of `{name}` takes {what}"))
                    .with_label(format!("called with ({given})"))
            }
        };
        let sigs: Vec<String> = cands.iter().take(8).map(|&i| OVERLOADS[i as usize].signature()).collect();
        if !sigs.is_empty() {
            d = d.with_note(format!("candidates:\n  {}", sigs.join("\n  ")));
        }
        self.report(d);
    }

    fn user_call(
        &mut self,
        e: &'a Expr,
        name: &'a ast::Ident,
        defs: &[&'a ast::FunctionDef],
        args: &'a [Expr],
        expected: Option<BaseType>,
    ) -> R {
        let n = args.len();
        let fitting: Vec<&'a ast::FunctionDef> = defs.iter().copied().filter(|f| f.params.len() == n).collect();
        let mut vals: Vec<CallArg> = Vec::new();
        let mut failed = false;
        for (k, a) in args.iter().enumerate() {
            let all_out = !fitting.is_empty() && fitting.iter().all(|f| f.params[k].output);
            let all_arr = !fitting.is_empty() && fitting.iter().all(|f| f.params[k].array.is_some());
            if all_out || (all_arr && matches!(a.kind, ExprKind::Name(_))) {
                let p = if all_out { self.place(a, "output") } else { self.array_arg(a) };
                match p {
                    Some(p) => vals.push(CallArg::Place(p)),
                    None => failed = true,
                }
            } else {
                let hint = if matches!(a.kind, ExprKind::Triple(_)) {
                    fitting.first().map(|f| f.params[k].ty.base).filter(|t| t.is_triple())
                } else {
                    None
                };
                match self.expr(a, hint).and_then(|v| self.unbool(v, a.span)) {
                    Some(v) => vals.push(CallArg::Value(v)),
                    None => failed = true,
                }
            }
        }
        if failed {
            return None;
        }
        // Pick the cheapest fitting definition.
        let mut best: Option<((u32, u32), &'a ast::FunctionDef)> = None;
        for f in &fitting {
            let mut cost = 0;
            let mut ok = true;
            for (p, a) in f.params.iter().zip(&vals) {
                let spec = ArgSpec { ty: p.ty.base, output: p.output, array: p.array.is_some(), any: false };
                let is_place = matches!(a, CallArg::Place(_));
                match builtins::arg_cost(&spec, &a.ty()) {
                    Some(c) if !p.output || is_place => cost += c,
                    _ => ok = false,
                }
            }
            if ok {
                let rc = match expected {
                    Some(t) if t == f.ret.base => 0,
                    None if f.ret.base == BaseType::Float => 0,
                    _ => 1,
                };
                if best.is_none_or(|(c, _)| (cost, rc) < c) {
                    best = Some(((cost, rc), f));
                }
            }
        }
        let Some((_, def)) = best else {
            let given = vals.iter().map(|a| type_name(a.ty())).collect::<Vec<_>>().join(", ");
            let mut d = if fitting.is_empty() {
                Diagnostic::error(
                    codes::ARG_COUNT,
                    e.span,
                    format!("function `{}` does not take {n} argument{}", name.name, if n == 1 { "" } else { "s" }),
                )
                .with_label(format!("{n} given"))
            } else {
                Diagnostic::error(
                    codes::NO_OVERLOAD,
                    e.span,
                    format!("no definition of `{}` takes ({given})", name.name),
                )
                .with_label(format!("called with ({given})"))
            };
            for f in defs.iter().take(4) {
                d = d.with_secondary(f.name.span, format!("`{}` defined here", signature_of(f)));
            }
            self.report(d);
            return None;
        };
        self.called.insert(def.span);
        if self.inlining.iter().any(|f| std::ptr::eq(*f, def)) {
            self.report(
                Diagnostic::error(codes::RECURSION, e.span, format!("recursive call of `{}`", name.name))
                    .with_label("calls itself")
                    .with_secondary(def.name.span, "function defined here")
                    .with_note("RSL functions are inlined and cannot recurse; rewrite it as a loop"),
            );
            return None;
        }
        self.inline(def, vals, e.span, expected)
    }

    /// An array argument passed by reference: the caller's array variable.
    fn array_arg(&mut self, a: &'a Expr) -> Option<Place> {
        if let ExprKind::Name(n) = &a.kind {
            if let Some(Found::Var(VarInfo { binding: Binding::Slot(s), .. })) = self.lookup(n) {
                let ty = self.slot_ty(s);
                return Some(Place { slot: s, index: None, ty });
            }
        }
        let v = self.expr(a, None)?;
        self.err(
            codes::TYPE_MISMATCH,
            a.span,
            format!("an array parameter needs an array variable, not {}", an_t(v.ty)),
            "not an array variable",
        );
        None
    }

    /// Inlines `def` with the given arguments as a [`Node::Frame`].
    fn inline(&mut self, def: &'a ast::FunctionDef, args: Vec<CallArg>, span: Span, _expected: Option<BaseType>) -> R {
        if !self.ret_checked.contains(&def.span) {
            self.ret_checked.insert(def.span);
            if def.ret.base != BaseType::Void && !def.body.stmts.iter().any(always_returns) {
                let end = Span::new(def.body.span.file, def.body.span.end.saturating_sub(1), def.body.span.end);
                self.report(
                    Diagnostic::error(
                        codes::MISSING_RETURN,
                        def.name.span,
                        format!("function `{}` may end without returning {}", def.name.name, an(def.ret.base)),
                    )
                    .with_label("non-void function")
                    .with_secondary(end, "control can reach the end here")
                    .with_note("add a `return` at the end of the function"),
                );
            }
        }
        let fname = def.name.name.clone();
        // Copy-in, in the caller's scope and flow.
        let mut binds: Vec<(String, VarInfo)> = Vec::new();
        let mut copy_out: Vec<(SlotId, Place, Span)> = Vec::new();
        for (p, a) in def.params.iter().zip(args) {
            let declared = p.ty.detail;
            match a {
                CallArg::Place(pl) if p.output => {
                    if pl.ty.array.is_some() {
                        binds.push((
                            p.name.name.clone(),
                            VarInfo { binding: Binding::Slot(pl.slot), span: p.name.span, read_only: false, flow: 0 },
                        ));
                        continue;
                    }
                    let ty = Type {
                        base: p.ty.base,
                        detail: declared.unwrap_or(pl.ty.detail).join(pl.ty.detail),
                        array: None,
                    };
                    let s = self.new_slot(&format!("{fname}.{}", p.name.name), ty, SlotKind::Local, p.span);
                    let cur = self.load_place(&pl, span);
                    if let Some(cur) = self.convert(cur, p.ty.base, span) {
                        self.emit(Node::Store { slot: s, index: None, value: cur.v, init: true });
                    }
                    binds.push((
                        p.name.name.clone(),
                        VarInfo { binding: Binding::Slot(s), span: p.name.span, read_only: false, flow: 0 },
                    ));
                    copy_out.push((s, pl, span));
                }
                CallArg::Place(pl) => {
                    // Array passed by reference, read-only.
                    binds.push((
                        p.name.name.clone(),
                        VarInfo { binding: Binding::Slot(pl.slot), span: p.name.span, read_only: true, flow: 0 },
                    ));
                }
                CallArg::Value(v) => {
                    if declared == Some(Detail::Uniform) && v.ty.detail == Detail::Varying {
                        self.report(
                            Diagnostic::error(
                                codes::VARYING_TO_UNIFORM,
                                span,
                                format!(
                                    "a varying value is passed to the uniform parameter `{}` of `{fname}`",
                                    p.name.name
                                ),
                            )
                            .with_label("varying argument")
                            .with_secondary(p.name.span, "declared uniform here"),
                        );
                    }
                    let Some(mut v) = self.convert(v, p.ty.base, span) else {
                        continue;
                    };
                    if declared == Some(Detail::Varying) {
                        v.ty.detail = Detail::Varying;
                    }
                    binds.push((
                        p.name.name.clone(),
                        VarInfo { binding: Binding::Value(v), span: p.name.span, read_only: true, flow: 0 },
                    ));
                }
            }
        }
        let ret_slot = (def.ret.base != BaseType::Void).then(|| {
            let ty = Type::new(def.ret.base, def.ret.detail.unwrap_or(Detail::Uniform));
            self.new_slot(&format!("{fname}.ret"), ty, SlotKind::Local, def.name.span)
        });
        // The frame.
        let flow = self.flow();
        self.inlining.push(def);
        self.push_block();
        self.push_scope(true);
        for (n, mut info) in binds {
            info.flow = flow;
            if let Some(s) = self.scopes.last_mut() {
                s.vars.insert(n, info);
            }
        }
        self.frames.push(FrameCtx {
            func: Some(def),
            ret_slot,
            loops: Vec::new(),
            varying_exit: false,
            flow_at_entry: flow,
        });
        self.push_scope(false);
        for s in &def.body.stmts {
            self.stmt(s);
        }
        self.pop_scope();
        self.frames.pop();
        self.pop_scope();
        let body = self.pop_block();
        self.inlining.pop();
        self.emit(Node::Frame(body));
        // Copy-out.
        for (s, pl, span) in copy_out {
            let ty = self.slot_ty(s);
            let v = self.inst(Op::Load(s), Vec::new(), ty, false, span);
            let n = self.slot_name(pl.slot);
            if let Some(v) = self.check_store(v, pl.ty, span, &n, span) {
                self.store(&pl, v);
            }
        }
        match ret_slot {
            Some(s) => {
                let ty = self.slot_ty(s);
                Some(self.inst(Op::Load(s), Vec::new(), ty, false, span))
            }
            None => {
                Some(self.inst(Op::Const(Const::Float(0.0)), Vec::new(), Type::uniform(BaseType::Void), false, span))
            }
        }
    }
}

fn signature_of(f: &ast::FunctionDef) -> String {
    let ps: Vec<String> = f
        .params
        .iter()
        .map(|p| {
            format!(
                "{}{}{}",
                if p.output { "output " } else { "" },
                p.ty.base,
                if p.array.is_some() { "[]" } else { "" }
            )
        })
        .collect();
    format!("{} {}({})", f.ret.base, f.name.name, ps.join(", "))
}

fn an_t(t: Type) -> String {
    match t.array {
        Some(n) => format!("an array of {n} {}s", t.base),
        None => an(t.base).to_string(),
    }
}

/// A storage place: a slot, or one element of an array slot.
#[derive(Clone, Copy, Debug)]
struct Place {
    slot: SlotId,
    index: Option<Val>,
    /// The type of the place (the element type for an element).
    ty: Type,
}

enum CallArg {
    Value(Val),
    Place(Place),
}

impl CallArg {
    fn ty(&self) -> Type {
        match self {
            CallArg::Value(v) => v.ty,
            CallArg::Place(p) => p.ty,
        }
    }
}

enum Init {
    Whole(R),
    Elems(Vec<R>),
}

/// The zero of a type (used after an error, and for parameters without a default).
fn zero_const(ty: Type) -> Const {
    let one = match ty.base {
        BaseType::Float | BaseType::Void => Const::Float(0.0),
        BaseType::Matrix => Const::Matrix([0.0; 16]),
        BaseType::String => Const::Str(String::new()),
        _ => Const::Triple([0.0; 3]),
    };
    match ty.array {
        Some(n) => Const::Array(vec![one; n as usize]),
        None => one,
    }
}

/// Compile-time evaluation of shader parameter defaults.
struct ConstEval<'e> {
    /// Earlier parameters.
    env: &'e HashMap<String, (Const, BaseType)>,
    diags: Vec<Diagnostic>,
}

impl ConstEval<'_> {
    /// Evaluates `e` as a default for a parameter of type `ty`; a point-like value in a named
    /// space sets `space`.
    fn eval_to(&mut self, e: &Expr, ty: Type, space: &mut Option<String>) -> Option<Const> {
        if let Some(n) = ty.array {
            let ExprKind::ArrayInit(items) = &e.kind else {
                let (_, b) = self.eval(e, Some(ty.base), space)?;
                self.diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        e.span,
                        format!("type mismatch in a parameter default: {} for an array", an(b)),
                    )
                    .with_label("not an array"),
                );
                return None;
            };
            if items.len() != n as usize {
                self.diags.push(
                    Diagnostic::error(
                        codes::BAD_LITERAL,
                        e.span,
                        format!("the array has {n} elements but {} initializers", items.len()),
                    )
                    .with_label(format!("{} values", items.len())),
                );
                return None;
            }
            let mut out = Vec::new();
            for it in items {
                out.push(self.eval_to(it, ty.element(), space)?);
            }
            return Some(Const::Array(out));
        }
        let (c, b) = self.eval(e, Some(ty.base), space)?;
        if !assignable(b, ty.base) {
            self.diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    e.span,
                    format!("type mismatch in a parameter default: {} for {}", an(b), an(ty.base)),
                )
                .with_label(format!("this is {}", an(b))),
            );
            return None;
        }
        Some(promote(c, ty.base))
    }

    fn non_constant(&mut self, e: &Expr, what: &str) -> Option<(Const, BaseType)> {
        self.diags.push(
            Diagnostic::error(
                codes::NON_CONSTANT_DEFAULT,
                e.span,
                format!("a parameter default must be a constant, not {what}"),
            )
            .with_label("not constant")
            .with_note(
                "use literals, arithmetic, casts, math functions and earlier parameters; compute the rest in the body",
            ),
        );
        None
    }

    fn eval(&mut self, e: &Expr, expected: Option<BaseType>, space: &mut Option<String>) -> Option<(Const, BaseType)> {
        use BaseType::*;
        match &e.kind {
            ExprKind::Number(x) => Some((Const::Float(*x), Float)),
            ExprKind::Str(s) => Some((Const::Str(s.clone()), String)),
            ExprKind::Name(n) => match self.env.get(n) {
                Some((c, b)) => Some((c.clone(), *b)),
                None if n == "PI" => Some((Const::Float(std::f64::consts::PI), Float)),
                None => self.non_constant(e, &format!("`{n}`")),
            },
            ExprKind::Unary(UnaryOp::Neg, a) => {
                let (c, b) = self.eval(a, expected, space)?;
                Some((map_comps(&c, |x| -x)?, b))
            }
            ExprKind::Binary(op, a, b)
                if matches!(op, BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div) =>
            {
                let (x, tx) = self.eval(a, expected, space)?;
                let (y, ty) = self.eval(b, expected, space)?;
                let Some((t, _)) = binary_type(*op, tx, ty) else {
                    self.diags.push(
                        Diagnostic::error(
                            codes::BAD_OPERANDS,
                            e.span,
                            format!("binary operation `{}` between {} and {} is illegal", op.symbol(), an(tx), an(ty)),
                        )
                        .with_label("bad operands"),
                    );
                    return None;
                };
                if t == Matrix && (tx == Matrix && ty == Matrix) && matches!(op, BinaryOp::Mul | BinaryOp::Div) {
                    return self.non_constant(e, "a matrix product");
                }
                let f = |p: f64, q: f64| match op {
                    BinaryOp::Add => p + q,
                    BinaryOp::Sub => p - q,
                    BinaryOp::Mul => p * q,
                    _ => p / q,
                };
                let xs = comps(&promote(x, t))?;
                let ys = comps(&promote(y, t))?;
                let v: Vec<f64> = xs.iter().zip(&ys).map(|(p, q)| f(*p, *q)).collect();
                Some((from_comps(t, &v)?, t))
            }
            ExprKind::Triple(items) => {
                let base = expected.filter(|t| t.is_triple()).unwrap_or(Point);
                let mut v = [0.0; 3];
                for (i, it) in items.iter().enumerate() {
                    match self.eval(it, Some(Float), space)? {
                        (Const::Float(x), _) => v[i] = x,
                        (_, b) => {
                            self.diags.push(
                                Diagnostic::error(
                                    codes::BAD_LITERAL,
                                    it.span,
                                    format!("a component must be a float, not {}", an(b)),
                                )
                                .with_label("not a float"),
                            );
                            return None;
                        }
                    }
                }
                Some((Const::Triple(v), base))
            }
            ExprKind::MatrixLit(items) if items.len() == 16 => {
                let mut m = [0.0; 16];
                for (i, it) in items.iter().enumerate() {
                    match self.eval(it, Some(Float), space)? {
                        (Const::Float(x), _) => m[i] = x,
                        _ => return self.non_constant(it, "a non-float matrix component"),
                    }
                }
                Some((Const::Matrix(m), Matrix))
            }
            ExprKind::Cast { to, space: sp, expr } => {
                let (c, b) = self.eval(expr, Some(*to), space)?;
                if !(b == *to || (b == Float && (to.is_triple() || *to == Matrix)) || (b.is_triple() && to.is_triple()))
                {
                    self.diags.push(
                        Diagnostic::error(codes::TYPE_MISMATCH, e.span, format!("cannot cast {} to {to}", an(b)))
                            .with_label("bad cast"),
                    );
                    return None;
                }
                let c = promote(c, *to);
                let Some(sp) = sp else { return Some((c, *to)) };
                let ExprKind::Str(name) = &sp.kind else {
                    return self.non_constant(sp, "a computed space name");
                };
                if *to == Color {
                    let Some(cs) = anysl_core::stdlib::ColorSpace::from_name(name) else {
                        self.diags.push(
                            Diagnostic::error(
                                codes::UNKNOWN_SPACE,
                                sp.span,
                                format!("unknown colour space \"{name}\""),
                            )
                            .with_label("unknown colour space")
                            .with_note("colour spaces: rgb, hsv, hsl, xyz, xyY, YIQ"),
                        );
                        return None;
                    };
                    let Const::Triple(v) = c else { return None };
                    let rgb = anysl_core::stdlib::to_rgb(cs, anysl_core::Color::new(v[0], v[1], v[2]));
                    return Some((Const::Triple([rgb.r, rgb.g, rgb.b]), Color));
                }
                if name != "current" {
                    *space = Some(name.clone());
                }
                Some((c, *to))
            }
            ExprKind::Call(name, args) => {
                let mut vals = Vec::new();
                for a in args {
                    vals.push(self.eval(a, None, space)?);
                }
                let f = |v: &[(Const, BaseType)], i: usize| match v.get(i) {
                    Some((Const::Float(x), _)) => Some(*x),
                    _ => None,
                };
                let r = match (name.name.as_str(), vals.len()) {
                    ("radians", 1) => f(&vals, 0).map(f64::to_radians),
                    ("degrees", 1) => f(&vals, 0).map(f64::to_degrees),
                    ("sin", 1) => f(&vals, 0).map(f64::sin),
                    ("cos", 1) => f(&vals, 0).map(f64::cos),
                    ("tan", 1) => f(&vals, 0).map(f64::tan),
                    ("asin", 1) => f(&vals, 0).map(f64::asin),
                    ("acos", 1) => f(&vals, 0).map(f64::acos),
                    ("atan", 1) => f(&vals, 0).map(f64::atan),
                    ("atan", 2) => f(&vals, 0).zip(f(&vals, 1)).map(|(y, x)| y.atan2(x)),
                    ("sqrt", 1) => f(&vals, 0).map(f64::sqrt),
                    ("exp", 1) => f(&vals, 0).map(f64::exp),
                    ("log", 1) => f(&vals, 0).map(f64::ln),
                    ("abs", 1) => f(&vals, 0).map(f64::abs),
                    ("floor", 1) => f(&vals, 0).map(f64::floor),
                    ("ceil", 1) => f(&vals, 0).map(f64::ceil),
                    ("round", 1) => f(&vals, 0).map(f64::round),
                    ("pow", 2) => f(&vals, 0).zip(f(&vals, 1)).map(|(x, y)| x.powf(y)),
                    ("min", 2) => f(&vals, 0).zip(f(&vals, 1)).map(|(x, y)| x.min(y)),
                    ("max", 2) => f(&vals, 0).zip(f(&vals, 1)).map(|(x, y)| x.max(y)),
                    ("mod", 2) => f(&vals, 0).zip(f(&vals, 1)).map(|(x, y)| x - y * (x / y).floor()),
                    _ => None,
                };
                match r {
                    Some(x) => Some((Const::Float(x), Float)),
                    None => self.non_constant(e, &format!("a call of `{}`", name.name)),
                }
            }
            _ => self.non_constant(e, "this expression"),
        }
    }
}

fn comps(c: &Const) -> Option<Vec<f64>> {
    match c {
        Const::Float(x) => Some(vec![*x]),
        Const::Triple(v) => Some(v.to_vec()),
        Const::Matrix(m) => Some(m.to_vec()),
        _ => None,
    }
}

fn from_comps(t: BaseType, v: &[f64]) -> Option<Const> {
    match (t, v.len()) {
        (BaseType::Float, 1) => Some(Const::Float(v[0])),
        (t, 3) if t.is_triple() => Some(Const::Triple([v[0], v[1], v[2]])),
        (BaseType::Matrix, 16) => {
            let mut m = [0.0; 16];
            m.copy_from_slice(v);
            Some(Const::Matrix(m))
        }
        _ => None,
    }
}

fn map_comps(c: &Const, f: impl Fn(f64) -> f64) -> Option<Const> {
    match c {
        Const::Float(x) => Some(Const::Float(f(*x))),
        Const::Triple(v) => Some(Const::Triple(v.map(&f))),
        Const::Matrix(m) => Some(Const::Matrix(m.map(&f))),
        _ => None,
    }
}

/// Promotes a float constant to a triple or matrix (diagonal).
fn promote(c: Const, to: BaseType) -> Const {
    match (c, to) {
        (Const::Float(x), t) if t.is_triple() => Const::Triple([x; 3]),
        (Const::Float(x), BaseType::Matrix) => {
            let mut m = [0.0; 16];
            for i in 0..4 {
                m[i * 5] = x;
            }
            Const::Matrix(m)
        }
        (c, _) => c,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_and_suggest() {
        assert_eq!(edit_distance("normalise", "normalize"), 1);
        assert_eq!(suggest("normalise", ["normalize", "noise"].into_iter()), Some("normalize"));
        assert_eq!(suggest("xyz", ["normalize"].into_iter()), None);
    }

    #[test]
    fn binary_rules() {
        use BaseType::*;
        assert_eq!(binary_type(BinaryOp::Sub, Point, Point), Some((Vector, false)));
        assert_eq!(binary_type(BinaryOp::Add, Point, Vector), Some((Point, false)));
        assert_eq!(binary_type(BinaryOp::Mul, Float, Color), Some((Color, false)));
        assert_eq!(binary_type(BinaryOp::Add, Point, Color), None);
        assert_eq!(binary_type(BinaryOp::Dot, Vector, Normal), Some((Float, false)));
        assert_eq!(binary_type(BinaryOp::Lt, Point, Point), None);
        assert_eq!(binary_type(BinaryOp::Eq, Point, Point), Some((Float, true)));
    }
}
