//! Places: the assignable targets (a variable or one element of an array variable), the
//! "not assignable" diagnostics, assignments including `+=` and friends, and indexing.

use super::scope::{Binding, Found, VarInfo};
use super::typing::{binary_type, binop, global_access};
use super::{an_t, type_name, Lowerer, Val, R};
use crate::builtins::{self, Builtin, OVERLOADS};
use crate::diag::{codes, Diagnostic};
use crate::front::ast::{AssignOp, BinaryOp, Expr, ExprKind, ShaderType};
use crate::ir::{Global, Node, Op, SlotId};
use crate::span::Span;
use crate::types::{BaseType, Detail, Type};

/// A storage place: a slot, or one element of an array slot.
#[derive(Clone, Copy, Debug)]
pub(super) struct Place {
    pub(super) slot: SlotId,
    pub(super) index: Option<Val>,
    /// The type of the place (the element type for an element).
    pub(super) ty: Type,
}

impl<'a, 'd> Lowerer<'a, 'd> {
    /// The storage place an lvalue expression names (emitting its index computation).
    pub(super) fn place(&mut self, e: &'a Expr, what: &str) -> Option<Place> {
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
                    if ty.detail == Detail::Uniform && self.flow() > decl_flow && !self.promote.contains(&v.span) {
                        // A local or a shader parameter: lowered again as varying (a warning at
                        // its declaration says so).
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
                // Pixie's and Aqsis' area lights set N (the light's own normal) before
                // `illuminate (P, N, PI/2)`; Pixie's mirror normalizes I in place. Only this
                // shader sees the new value (no renderer reads them back).
                let local_write = match g {
                    Global::N => self.kind == ShaderType::Light,
                    Global::I => !matches!(self.kind, ShaderType::Light | ShaderType::Imager),
                    _ => false,
                };
                if !write && local_write {
                    self.report(
                        Diagnostic::warning(
                            codes::WRITTEN_GLOBAL,
                            e.span,
                            format!(
                                "assignment to {}, read-only in a {} shader by the RenderMan spec: accepted as Pixie and Aqsis do",
                                g.name(),
                                self.kind.keyword()
                            ),
                        )
                        .with_label(format!("{} set here", g.name()))
                        .with_note(format!("the new {} is seen by the rest of this shader only", g.name())),
                    );
                } else if !write {
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

    pub(super) fn index_value(&mut self, i: &'a Expr) -> R {
        let v = self.expr(i, Some(BaseType::Float))?;
        if v.ty.base != BaseType::Float || v.is_bool || v.ty.array.is_some() {
            self.err(codes::BAD_INDEX, i.span, format!("an index must be a float, not {}", an_t(v.ty)), "bad index");
            return None;
        }
        Some(v)
    }

    pub(super) fn store(&mut self, p: &Place, v: Val) {
        self.emit(Node::Store { slot: p.slot, index: p.index.map(|i| i.v), value: v.v, init: false });
    }

    pub(super) fn load_place(&mut self, p: &Place, span: Span) -> Val {
        match p.index {
            None => self.inst(Op::Load(p.slot), Vec::new(), p.ty, false, span),
            Some(i) => {
                let ty = Type { detail: p.ty.detail.join(i.ty.detail), ..p.ty };
                self.inst(Op::LoadElem(p.slot), vec![i.v], ty, false, span)
            }
        }
    }

    pub(super) fn slot_name(&self, s: SlotId) -> String {
        self.func.slots[s.0 as usize].name.clone()
    }

    pub(super) fn assign(&mut self, e: &'a Expr, op: AssignOp, lhs: &'a Expr, rhs: &'a Expr) -> R {
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
        if value.ty.detail == Detail::Varying && place.ty.detail == Detail::Uniform && !value.is_bool {
            if let Some(&decl) = self.implicit_uniform.get(&place.slot) {
                // A parameter uniform only by default, assigned a varying value: lowered again
                // as varying (warning W0004 at its declaration).
                self.want_promote.insert(decl);
                return None;
            }
        }
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

    pub(super) fn index(&mut self, e: &'a Expr, base: &'a Expr, idx: &'a Expr) -> R {
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
}
