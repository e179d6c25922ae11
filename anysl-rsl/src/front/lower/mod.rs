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
//!   stored into a uniform variable is [`codes::VARYING_TO_UNIFORM`]. A uniform local or
//!   parameter stored into under varying control flow (inside a varying `if`/loop/light loop
//!   declared outside it, or after a varying `break`/`return`) is made varying, with the
//!   warning [`codes::PROMOTED_TO_VARYING`]: the shader is lowered again with it varying, as
//!   PRMan, BMRT and Aqsis compiled such shaders; so is a parameter that is uniform only by
//!   default (no `uniform` written) when it is assigned a varying value. A uniform *output
//!   argument* stored into under varying flow stays [`codes::UNIFORM_IN_VARYING_FLOW`] (the
//!   caller's variable is uniform), and a declared `uniform` assigned a varying value stays
//!   [`codes::VARYING_TO_UNIFORM`].
//! * **Return type by context.** Every expression is lowered with an *expected* base type (the
//!   declaration, assignment or cast target, passed down through arithmetic and `?:`); it picks
//!   among built-in overloads that differ only in their return type (`color noise(P)`) and
//!   types a bare triple literal `(a, b, c)`, which is a `point` when nothing says otherwise.
//! * **Parameter defaults** are evaluated to [`Const`]s by [`ConstEval`]: literals, triples,
//!   casts, unary minus, arithmetic, the pure math built-ins and earlier parameters. A
//!   point-like default in a named space keeps the space in [`ParamMeta::space`]; a colour in a
//!   named colour space is converted to RGB at compile time. The arithmetic and the built-ins
//!   are computed by the constant folder ([`passes::fold`](crate::passes::fold)), the one
//!   constant evaluator of the compiler. A default that is not a constant (`normalize(dPdu)`,
//!   `Cs`) is computed at the start of the body, when the hidden uniform parameter
//!   [`ir::default_flag_name`] (1 by default, cleared by the setters) says the parameter kept
//!   its default ([`codes::COMPUTED_DEFAULT`]); such a parameter is made varying (strings stay
//!   uniform).
//!
//! # Files
//!
//! * this module: the `Lowerer` state, the entry point `lower_unit`, the shader (its
//!   parameters and body), diagnostics and the wording of types in them, and the helpers that
//!   build IR (instructions, constants, slots, blocks);
//! * `scope.rs`: scopes, name look-up, and the loop and frame contexts;
//! * `typing.rs`: the type rules of operators, assignments and globals;
//! * `stmt.rs`: statements and declarations;
//! * `expr.rs`: expressions;
//! * `place.rs`: assignable places, assignments and indexing;
//! * `call.rs`: built-in and user function calls, overload resolution and its diagnostics;
//! * `inline.rs`: inlining of user functions, the missing-`return` check, uncalled functions;
//! * `defaults.rs`: compile-time evaluation of parameter defaults.

mod call;
mod defaults;
mod expr;
mod inline;
mod place;
mod scope;
mod stmt;
mod typing;

use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::front::ast::{self, ShaderType};
use crate::ir::{self, Const, Function, Global, Inst, Node, Op, ParamMeta, ShaderKind, Slot, SlotId, SlotKind, Value};
use crate::span::Span;
use crate::types::{BaseType, Detail, Type};
use defaults::{zero_const, ConstEval};
use scope::{Binding, FrameCtx, Scope, VarInfo};
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
    /// Shader parameters uniform only by default (no `uniform` written): slot → name span.
    /// Assigned a varying value, such a parameter is made varying (Aqsis, BMRT).
    implicit_uniform: HashMap<SlotId, Span>,
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

// ---- wording of diagnostics ------------------------------------------------------------------

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

fn an_t(t: Type) -> String {
    match t.array {
        Some(n) => format!("an array of {n} {}s", t.base),
        None => an(t.base).to_string(),
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
            implicit_uniform: HashMap::new(),
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
        // Parameters whose default is computed at run time: (parameter, its slot).
        let mut computed: Vec<(&'a ast::Param, SlotId)> = Vec::new();
        for (i, p) in sh.params.iter().enumerate() {
            let array = match p.array {
                None => None,
                Some(Some(n)) => Some(n),
                Some(None) => {
                    self.err(codes::BAD_INDEX, p.name.span, "a shader parameter array needs a size", "size missing");
                    Some(0)
                }
            };
            let declared = p.ty.detail.unwrap_or(Detail::Uniform);
            let mut space = None;
            let evaluated = p.default.as_ref().map(|e| {
                let mut ce = ConstEval { env: &env, diags: Vec::new() };
                let r = ce.eval_to(e, Type { base: p.ty.base, detail: declared, array }, &mut space);
                (r, ce.diags)
            });
            // A default that is an expression of the shading point or a call the compiler
            // cannot fold (`normalize(dPdu)`, `Cs`): PRMan and BMRT evaluate it when the shader
            // runs, so it is computed at the start of the body unless the parameter is given.
            let runtime = array.is_none()
                && p.ty.base != BaseType::Void
                && matches!(&evaluated, Some((None, ds)) if !ds.is_empty() && ds.iter().all(|d| d.code == codes::NON_CONSTANT_DEFAULT));
            let mut detail = declared;
            if runtime && detail == Detail::Uniform && p.ty.base != BaseType::String {
                detail = Detail::Varying;
            }
            if detail == Detail::Uniform && self.promote.contains(&p.name.span) {
                detail = Detail::Varying;
                self.warn_promoted(p.name.span, &p.name.name, "parameter");
            }
            let ty = Type { base: p.ty.base, detail, array };
            if p.ty.base == BaseType::Void {
                self.err(codes::TYPE_MISMATCH, p.ty.span, "a parameter cannot be void", "void parameter");
            }
            let slot = self.new_slot(&p.name.name, ty, SlotKind::Param(i as u32), p.span);
            if p.ty.detail.is_none() && detail == Detail::Uniform {
                self.implicit_uniform.insert(slot, p.name.span);
            }
            let default = match evaluated {
                Some(_) if runtime => {
                    self.warn_computed_default(p, declared != detail);
                    computed.push((p, slot));
                    space = None;
                    zero_const(ty)
                }
                Some((r, ds)) => {
                    for d in ds {
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
            if !runtime {
                env.insert(p.name.name.clone(), (default.clone(), p.ty.base));
            }
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
        // One hidden uniform flag per computed default, after the declared parameters: 1 while
        // the parameter keeps its default (setting the parameter clears it).
        let mut flags = Vec::new();
        for (p, _) in &computed {
            let ty = Type::uniform(BaseType::Float);
            let name = ir::default_flag_name(&p.name.name);
            let slot = self.new_slot(&name, ty, SlotKind::Param(params.len() as u32), p.span);
            params.push(ParamMeta {
                name,
                ty,
                default: Const::Float(1.0),
                output: false,
                slot,
                span: p.span,
                space: None,
            });
            flags.push(slot);
        }
        self.frames.push(FrameCtx {
            func: None,
            ret_slot: None,
            loops: Vec::new(),
            varying_exit: false,
            flow_at_entry: 0,
        });
        // The computed defaults, in parameter order (a default may read earlier parameters).
        for ((p, slot), flag) in computed.iter().zip(flags) {
            let Some(e) = &p.default else { continue };
            let f = self.inst(Op::Load(flag), Vec::new(), Type::uniform(BaseType::Float), false, e.span);
            let cond = self.inst(Op::Convert, vec![f.v], Type::uniform(BaseType::Float), true, e.span);
            self.push_block();
            let ty = self.slot_ty(*slot);
            if let Some(v) = self.expr(e, Some(ty.base)) {
                if let Some(v) = self.check_store(v, ty, e.span, &p.name.name, p.name.span) {
                    self.store(&place::Place { slot: *slot, index: None, ty }, v);
                }
            }
            let then = self.pop_block();
            self.emit(Node::If { cond: cond.v, then, otherwise: Vec::new() });
        }
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
}

impl Lowerer<'_, '_> {
    /// W0006: the default of `p` is computed when the shader runs; `made_varying` when the
    /// parameter, uniform as declared, is made varying to hold it.
    fn warn_computed_default(&mut self, p: &ast::Param, made_varying: bool) {
        let Some(e) = &p.default else { return };
        let mut d = Diagnostic::warning(
            codes::COMPUTED_DEFAULT,
            e.span,
            format!("the default of `{}` is not a constant: it is computed when the shader runs", p.name.name),
        )
        .with_label("computed at each shading point")
        .with_note("as PRMan and BMRT do: a value given for the parameter replaces it");
        if made_varying {
            d = d.with_note(format!("`{}` is made varying to hold it", p.name.name));
        }
        self.report(d);
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
}
