//! Shader parameter defaults: compile-time evaluation of the default expressions to
//! [`Const`]s (literals, triples, matrices, casts with a space, unary minus, arithmetic, the
//! pure math built-ins and earlier parameters), and the zero of a type.
//!
//! This is the front end's view of the compiler's one constant evaluator: it types the
//! expression and reports what is not constant, while the arithmetic and the built-ins are
//! computed by the constant folder ([`fold::componentwise`], [`fold::eval_builtin`]) on the
//! component helpers of [`Const`].

use super::an;
use super::typing::{assignable, binary_type, binop};
use crate::builtins::Builtin;
use crate::diag::{codes, Diagnostic};
use crate::front::ast::{BinaryOp, Expr, ExprKind, UnaryOp};
use crate::ir::Const;
use crate::passes::fold;
use crate::types::{BaseType, Type};
use std::collections::HashMap;

/// The zero of a type (used after an error, and for parameters without a default).
pub(super) fn zero_const(ty: Type) -> Const {
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

/// The built-ins a default may call, with their argument counts; every argument is a float.
const DEFAULT_BUILTINS: &[(Builtin, usize)] = &[
    (Builtin::Radians, 1),
    (Builtin::Degrees, 1),
    (Builtin::Sin, 1),
    (Builtin::Cos, 1),
    (Builtin::Tan, 1),
    (Builtin::Asin, 1),
    (Builtin::Acos, 1),
    (Builtin::Atan, 1),
    (Builtin::Atan, 2),
    (Builtin::Sqrt, 1),
    (Builtin::Exp, 1),
    (Builtin::Log, 1),
    (Builtin::Abs, 1),
    (Builtin::Floor, 1),
    (Builtin::Ceil, 1),
    (Builtin::Round, 1),
    (Builtin::Pow, 2),
    (Builtin::Min, 2),
    (Builtin::Max, 2),
    (Builtin::Mod, 2),
];

/// Compile-time evaluation of shader parameter defaults.
pub(super) struct ConstEval<'e> {
    /// Earlier parameters.
    pub(super) env: &'e HashMap<String, (Const, BaseType)>,
    pub(super) diags: Vec<Diagnostic>,
}

impl ConstEval<'_> {
    /// Evaluates `e` as a default for a parameter of type `ty`; a point-like value in a named
    /// space sets `space`.
    pub(super) fn eval_to(&mut self, e: &Expr, ty: Type, space: &mut Option<String>) -> Option<Const> {
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
        Some(c.promote(ty.base))
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
                Some((c.map_components(|x| -x)?, b))
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
                // Both operands promoted to the result type, then component by component (a
                // matrix with a float too: the float on the diagonal).
                let xs = x.promote(t).components()?;
                let ys = y.promote(t).components()?;
                Some((Const::from_components(t, &fold::componentwise(binop(*op), &xs, &ys))?, t))
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
                let c = c.promote(*to);
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
                let builtin = Builtin::from_name(&name.name).filter(|b| DEFAULT_BUILTINS.contains(&(*b, vals.len())));
                let floats: Option<Vec<Const>> =
                    vals.into_iter().map(|(c, _)| matches!(c, Const::Float(_)).then_some(c)).collect();
                let r = builtin.zip(floats).and_then(|(b, consts)| fold::eval_builtin(b, Float, &consts));
                match r {
                    Some(c) => Some((c, Float)),
                    None => self.non_constant(e, &format!("a call of `{}`", name.name)),
                }
            }
            _ => self.non_constant(e, "this expression"),
        }
    }
}
