//! The type rules of the checker: the result type of each binary operator, implicit
//! assignment conversions, and which globals each shader kind may read and write.

use crate::front::ast::{BinaryOp, ShaderType};
use crate::ir::{BinOp, Global};
use crate::types::BaseType;

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
pub(super) fn binary_type(op: BinaryOp, a: BaseType, b: BaseType) -> Option<(BaseType, bool)> {
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

pub(super) fn binop(op: BinaryOp) -> BinOp {
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

/// Can a value of base `from` be stored in a variable of base `to` (implicitly)?
pub(super) fn assignable(from: BaseType, to: BaseType) -> bool {
    from == to
        || (from == BaseType::Float && (to.is_triple() || to == BaseType::Matrix))
        || (from.is_pointlike() && to.is_pointlike())
}

/// Which globals a shader kind may read and write.
pub(super) fn global_access(kind: ShaderType, g: Global) -> (bool, bool) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::ast::BinaryOp;
    use crate::types::BaseType;

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
