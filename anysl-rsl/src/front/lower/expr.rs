//! Expressions: literals, names and globals, unary and binary operators, `?:`, casts with a
//! space, implicit conversions and the condition (boolean) form of a value.

use super::scope::{Binding, Found};
use super::typing::{assignable, binary_type, binop, global_access};
use super::{an, an_t, suggest, type_name, Lowerer, Val, R};
use crate::builtins;
use crate::diag::{codes, Diagnostic};
use crate::front::ast::{BinaryOp, Expr, ExprKind, ShaderType, UnaryOp};
use crate::ir::{Const, Global, Op, UnOp};
use crate::span::Span;
use crate::types::{BaseType, Detail, Type};

impl<'a, 'd> Lowerer<'a, 'd> {
    /// Converts `v` to base `to` (float → triple/matrix, point-like kinds). Assumes the
    /// conversion is legal (checked by the caller).
    pub(super) fn convert(&mut self, v: Val, to: BaseType, span: Span) -> R {
        if v.ty.base == to || v.ty.array.is_some() {
            return Some(v);
        }
        let ty = Type { base: to, ..v.ty };
        Some(self.inst(Op::Convert, vec![v.v], ty, false, span))
    }

    /// Lowers `e` expecting type `to` (a typed argument of a statement).
    pub(super) fn typed(&mut self, e: &'a Expr, to: BaseType, what: &str) -> R {
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
    pub(super) fn cond(&mut self, e: &'a Expr) -> R {
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

    pub(super) fn expr(&mut self, e: &'a Expr, expected: Option<BaseType>) -> R {
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
    pub(super) fn unbool(&mut self, v: Val, span: Span) -> R {
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

    pub(super) fn name(&mut self, n: &str, span: Span) -> R {
        match self.lookup(n) {
            Some(Found::Var(v)) => match v.binding {
                Binding::Value(val) => Some(val),
                Binding::Slot(s) => {
                    let ty = self.slot_ty(s);
                    Some(self.inst(Op::Load(s), Vec::new(), ty, false, span))
                }
            },
            Some(Found::Pi) => Some(self.constant(Const::Float(std::f64::consts::PI), BaseType::Float, span)),
            Some(Found::Global(Global::Ps)) if matches!(self.kind, ShaderType::Surface | ShaderType::Volume) => {
                // The RenderMan Companion's windowhighlight reads `Ps` in a surface shader: the
                // point being shaded, which a surface shader calls P.
                self.report(
                    Diagnostic::warning(
                        codes::OTHER_NAME,
                        span,
                        format!("`Ps` does not exist in a {} shader: read as `P`", self.kind.keyword()),
                    )
                    .with_label("read as P")
                    .with_note("Ps is the surface point as a light shader sees it"),
                );
                let s = self.global_slot(Global::P);
                Some(self.inst(Op::Load(s), Vec::new(), Global::P.ty(), false, span))
            }
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

    pub(super) fn global_readable(&mut self, g: Global, span: Span) -> bool {
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
}
