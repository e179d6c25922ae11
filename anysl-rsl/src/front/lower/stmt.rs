//! Statements: blocks, declarations (with initializers), stores with their type and
//! uniform/varying checks, `if`, loops, `break`/`continue`/`return`, and the light loops
//! (`illuminance`, `illuminate`, `solar`).

use super::scope::{Binding, Found, LoopCtx, VarInfo};
use super::typing::assignable;
use super::{an, an_t, type_name, Lowerer, Val, R};
use crate::diag::{codes, Diagnostic};
use crate::front::ast::{self, Expr, ExprKind, ShaderType, Stmt, StmtKind};
use crate::ir::{self, Const, Node, SlotKind};
use crate::span::Span;
use crate::types::{BaseType, Detail, Type};

enum Init {
    Whole(R),
    Elems(Vec<R>),
}

impl<'a, 'd> Lowerer<'a, 'd> {
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

    pub(super) fn stmt(&mut self, s: &'a Stmt) {
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
                if self.kind == ShaderType::Light {
                    self.report(
                        Diagnostic::warning(
                            codes::NO_EFFECT,
                            s.span,
                            "`illuminance` in a light shader: accepted, but its body never runs",
                        )
                        .with_label("light loop here")
                        .with_note("a light shader runs inside another shader's light loop and sees no lights itself"),
                    );
                } else if !matches!(self.kind, ShaderType::Surface | ShaderType::Volume) {
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
                // The body runs once per light for the points it reaches. As in PRMan, uniform
                // variables may be assigned there (a uniform statement runs once per light): the
                // Advanced RenderMan lensflare counts its random draws in a uniform inside it.
                self.light_loops += 1;
                if let Some(f) = self.frame() {
                    f.loops.push(LoopCtx { varying: false });
                }
                let body = self.sub_block(body);
                if let Some(f) = self.frame() {
                    f.loops.pop();
                }
                self.light_loops -= 1;
                let Some(pos) = pos else { return };
                let cone = match cone {
                    Some((Some(a), Some(b))) => Some((a.v, b.v)),
                    Some(_) => return,
                    None => None,
                };
                if (category.is_some() && cat.is_none()) || self.kind == ShaderType::Light {
                    // (In a light shader the loop was checked but is not emitted: no lights.)
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
                self.warn_promoted(d.name.span, &d.name.name, "variable");
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
    pub(super) fn check_store(&mut self, v: Val, to: Type, span: Span, name: &str, target: Span) -> R {
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
}

impl Lowerer<'_, '_> {
    /// W0004: the uniform `what` `name` (declared at `span`) is assigned under varying control
    /// flow (or, for a parameter uniform only by default, a varying value), so it is lowered as
    /// varying — what PRMan, BMRT and Aqsis did with such shaders.
    pub(super) fn warn_promoted(&mut self, span: Span, name: &str, what: &str) {
        self.report(
            Diagnostic::warning(
                codes::PROMOTED_TO_VARYING,
                span,
                format!(
                    "the uniform {what} `{name}` is assigned a varying value or under varying control flow; it is made varying"
                ),
            )
            .with_label("made varying")
            .with_note("points may now hold different values, as the shader meant; declare it varying to silence this"),
        );
    }
}
