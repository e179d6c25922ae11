//! User functions: each call is inlined as a [`Node::Frame`](crate::ir::Node::Frame) with its
//! arguments bound, `output` arguments copied back and the result returned through a slot;
//! the missing-`return` check; functions never called are checked once with their declared
//! types.

use super::call::CallArg;
use super::defaults::zero_const;
use super::place::Place;
use super::scope::{Binding, FrameCtx, VarInfo};
use super::{an, Lowerer, R};
use crate::diag::{codes, Diagnostic};
use crate::front::ast::{self, Expr, ExprKind, Stmt, StmtKind};
use crate::ir::{Const, Node, Op, SlotId, SlotKind};
use crate::span::Span;
use crate::types::{BaseType, Detail, Type};

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

impl<'a, 'd> Lowerer<'a, 'd> {
    /// Inlines `def` with the given arguments as a [`Node::Frame`].
    pub(super) fn inline(
        &mut self,
        def: &'a ast::FunctionDef,
        args: Vec<CallArg>,
        span: Span,
        _expected: Option<BaseType>,
    ) -> R {
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

    /// Lowers a never-called function into a scratch frame (discarded) to report its errors.
    pub(super) fn check_uncalled(&mut self, f: &'a ast::FunctionDef) {
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
}
