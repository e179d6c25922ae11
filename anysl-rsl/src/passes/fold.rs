//! Parameter specialization and constant folding.
//!
//! The evaluation of ops on constants here is the compiler's one constant evaluator: besides
//! folding IR instructions, the front end evaluates shader parameter defaults with its
//! element-wise arithmetic (`componentwise`) and its math built-ins (`eval_builtin`), on
//! the [`Const`] component helpers ([`Const::components`], [`Const::from_components`],
//! [`Const::promote`]).

use crate::builtins::Builtin;
use crate::ir::{BinOp, Block, Const, Function, Inst, Module, Node, Op, SlotKind, UnOp, Value};
use crate::types::{BaseType, Detail};

/// Replaces reads of uniform, non-output parameters that the shader never assigns by constants:
/// the value given in `values`, or the default when `use_defaults` is set.
pub fn specialize(module: &mut Module, values: &[(String, Const)], use_defaults: bool) {
    // A given parameter whose default is computed when the shader runs keeps the given value:
    // its flag is specialized to 0 too.
    let mut values = values.to_vec();
    for (n, _) in values.clone() {
        let flag = crate::ir::default_flag_name(&n);
        if module.params.iter().any(|p| p.name == flag) && !values.iter().any(|(m, _)| *m == flag) {
            values.push((flag, Const::Float(0.0)));
        }
    }
    let values = &values[..];
    let func = &mut module.func;
    let mut stored = vec![false; func.slots.len()];
    crate::ir::walk(&func.body, &mut |n| {
        if let Node::Store { slot, .. } = n {
            stored[slot.0 as usize] = true;
        }
    });
    for p in &module.params {
        if p.output || p.ty.detail != Detail::Uniform || stored[p.slot.0 as usize] {
            continue;
        }
        let value = match values.iter().find(|(n, _)| *n == p.name) {
            Some((_, v)) => v.clone(),
            None if use_defaults => p.default.clone(),
            None => continue,
        };
        for inst in &mut func.insts {
            match &inst.op {
                Op::Load(s) if *s == p.slot => inst.op = Op::Const(value.clone()),
                Op::LoadElem(s) if *s == p.slot => {
                    // Leave indexed reads of a specialized array to folding: make the array a
                    // constant and index it there.
                    let _ = s;
                }
                _ => {}
            }
        }
    }
    let _ = SlotKind::Local;
}

/// Folds instructions whose arguments are constants, forwards selects on constant conditions,
/// and removes branches and loops decided at compile time.
pub fn fold_constants(func: &mut Function) {
    let mut fwd: Vec<Option<Value>> = vec![None; func.insts.len()];
    let body = std::mem::take(&mut func.body);
    func.body = fold_block(func, body, &mut fwd);
    // Rewrite forwarded uses.
    let resolve = |fwd: &[Option<Value>], mut v: Value| {
        while let Some(n) = fwd[v.0 as usize] {
            v = n;
        }
        v
    };
    for i in 0..func.insts.len() {
        let args: Vec<Value> = func.insts[i].args.iter().map(|&a| resolve(&fwd, a)).collect();
        func.insts[i].args = args;
    }
    rewrite_operands(&mut func.body, &|v| resolve(&fwd, v));
}

/// Applies `map` to every value operand of the nodes in `block` (recursively).
pub fn rewrite_operands(block: &mut Block, map: &impl Fn(Value) -> Value) {
    for n in block.iter_mut() {
        match n {
            Node::Store { index, value, .. } => {
                if let Some(i) = index {
                    *i = map(*i);
                }
                *value = map(*value);
            }
            Node::If { cond, .. } => *cond = map(*cond),
            Node::Loop { cond: Some(c), .. } => *c = map(*c),
            Node::Illuminance { category, position, cone, .. } => {
                if let Some(c) = category {
                    *c = map(*c);
                }
                *position = map(*position);
                if let Some((a, b)) = cone {
                    *a = map(*a);
                    *b = map(*b);
                }
            }
            Node::Illuminate { position, cone, .. } => {
                *position = map(*position);
                if let Some((a, b)) = cone {
                    *a = map(*a);
                    *b = map(*b);
                }
            }
            Node::Solar { cone: Some((a, b)), .. } => {
                *a = map(*a);
                *b = map(*b);
            }
            _ => {}
        }
        for b in n.blocks_mut() {
            rewrite_operands(b, map);
        }
    }
}

fn const_of(func: &Function, fwd: &[Option<Value>], v: Value) -> Option<Const> {
    let mut v = v;
    while let Some(n) = fwd[v.0 as usize] {
        v = n;
    }
    match &func.inst(v).op {
        Op::Const(c) => Some(c.clone()),
        _ => None,
    }
}

fn fold_block(func: &mut Function, block: Block, fwd: &mut Vec<Option<Value>>) -> Block {
    let mut out = Vec::with_capacity(block.len());
    for node in block {
        match node {
            Node::Inst(v) => {
                fold_inst(func, fwd, v);
                out.push(Node::Inst(v));
            }
            Node::If { cond, then, otherwise } => {
                let then = fold_block(func, then, fwd);
                let otherwise = fold_block(func, otherwise, fwd);
                match const_of(func, fwd, cond) {
                    Some(Const::Float(c)) => out.extend(if c != 0.0 { then } else { otherwise }),
                    _ => out.push(Node::If { cond, then, otherwise }),
                }
            }
            Node::Loop { header, cond, body, step } => {
                let header = fold_block(func, header, fwd);
                let never = matches!(cond.and_then(|c| const_of(func, fwd, c)), Some(Const::Float(c)) if c == 0.0);
                if never {
                    out.extend(header);
                } else {
                    let body = fold_block(func, body, fwd);
                    let step = fold_block(func, step, fwd);
                    out.push(Node::Loop { header, cond, body, step });
                }
            }
            mut other => {
                for b in other.blocks_mut() {
                    let taken = std::mem::take(b);
                    *b = fold_block(func, taken, fwd);
                }
                out.push(other);
            }
        }
    }
    out
}

fn fold_inst(func: &mut Function, fwd: &mut [Option<Value>], v: Value) {
    let inst = func.inst(v).clone();
    if let Op::Select = inst.op {
        if let Some(Const::Float(c)) = const_of(func, fwd, inst.args[0]) {
            let pick = if c != 0.0 { inst.args[1] } else { inst.args[2] };
            // Forward only when the types agree exactly (no implicit conversion hidden in the
            // select).
            if func.inst(pick).ty.base == inst.ty.base && func.inst(pick).is_bool == inst.is_bool {
                fwd[v.0 as usize] = Some(pick);
            }
            return;
        }
    }
    if !inst.op.is_pure() || matches!(inst.op, Op::Const(_)) {
        return;
    }
    let args: Option<Vec<Const>> = inst.args.iter().map(|&a| const_of(func, fwd, a)).collect();
    let Some(args) = args else { return };
    if let Some(c) = eval(&inst, &args) {
        func.insts[v.0 as usize].op = Op::Const(c);
        func.insts[v.0 as usize].args.clear();
    }
}

fn bool_c(b: bool) -> Const {
    Const::Float(if b { 1.0 } else { 0.0 })
}

/// `a op b` component by component for `op` one of `+ - * /`, a one-component operand
/// standing for every component (a float with a triple).
pub(crate) fn componentwise(op: BinOp, a: &[f64], b: &[f64]) -> Vec<f64> {
    let n = a.len().max(b.len());
    let get = |v: &[f64], i: usize| if v.len() == 1 { v[0] } else { v[i] };
    (0..n)
        .map(|i| {
            let (x, y) = (get(a, i), get(b, i));
            match op {
                BinOp::Add => x + y,
                BinOp::Sub => x - y,
                BinOp::Mul => x * y,
                _ => x / y,
            }
        })
        .collect()
}

fn mat_mul(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut r = vec![0.0; 16];
    for i in 0..4 {
        for j in 0..4 {
            r[i * 4 + j] = (0..4).map(|k| a[i * 4 + k] * b[k * 4 + j]).sum();
        }
    }
    r
}

/// Evaluates a pure instruction on constant arguments in f64; `None` when it cannot (the
/// instruction then stays for run time).
fn eval(inst: &Inst, args: &[Const]) -> Option<Const> {
    let base = inst.ty.base;
    match &inst.op {
        Op::Unary(UnOp::Neg) => {
            let a = args[0].components()?;
            Const::from_components(base, &a.iter().map(|x| -x).collect::<Vec<_>>())
        }
        Op::Unary(UnOp::Not) => Some(bool_c(args[0].components()?[0] == 0.0)),
        Op::Binary(op) => {
            if let (Const::Str(a), Const::Str(b)) = (&args[0], &args[1]) {
                return match op {
                    BinOp::Eq => Some(bool_c(a == b)),
                    BinOp::Ne => Some(bool_c(a != b)),
                    _ => None,
                };
            }
            let a = args[0].components()?;
            let b = args[1].components()?;
            match op {
                BinOp::Dot if a.len() == 3 && b.len() == 3 => {
                    Some(Const::Float(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]))
                }
                BinOp::Cross if a.len() == 3 && b.len() == 3 => Some(Const::Triple([
                    a[1] * b[2] - a[2] * b[1],
                    a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0],
                ])),
                BinOp::Mul if a.len() == 16 && b.len() == 16 => Const::from_components(base, &mat_mul(&a, &b)),
                BinOp::And => Some(bool_c(a[0] != 0.0 && b[0] != 0.0)),
                BinOp::Or => Some(bool_c(a[0] != 0.0 || b[0] != 0.0)),
                BinOp::Eq => Some(bool_c(a == b)),
                BinOp::Ne => Some(bool_c(a != b)),
                BinOp::Lt => Some(bool_c(a[0] < b[0])),
                BinOp::Le => Some(bool_c(a[0] <= b[0])),
                BinOp::Gt => Some(bool_c(a[0] > b[0])),
                BinOp::Ge => Some(bool_c(a[0] >= b[0])),
                BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div if a.len() != 16 && b.len() != 16 => {
                    Const::from_components(base, &componentwise(*op, &a, &b))
                }
                _ => None,
            }
        }
        Op::Convert => {
            if inst.is_bool {
                return Some(bool_c(args[0].components()?.iter().any(|&x| x != 0.0)));
            }
            let a = args[0].components()?;
            match a.as_slice() {
                [x] if base.is_triple() || base == BaseType::Matrix => Some(Const::Float(*x).promote(base)),
                _ => Const::from_components(base, &a),
            }
        }
        Op::MakeTriple | Op::MakeMatrix => {
            let v: Option<Vec<f64>> = args.iter().map(|c| c.components().map(|v| v[0])).collect();
            Const::from_components(base, &v?)
        }
        Op::Call { builtin, .. } => eval_builtin(*builtin, base, args),
        _ => None,
    }
}

/// The pure math built-ins folded at compile time, on floats and component-wise on triples,
/// with `base` the type of the result; `None` when `builtin` is not folded or the arguments
/// do not fit.
pub(crate) fn eval_builtin(builtin: Builtin, base: BaseType, args: &[Const]) -> Option<Const> {
    let a: Option<Vec<Vec<f64>>> = args.iter().map(Const::components).collect();
    let a = a?;
    let f1 = |f: fn(f64) -> f64| -> Option<Const> {
        if a.len() != 1 {
            return None;
        }
        Const::from_components(base, &a[0].iter().map(|&x| f(x)).collect::<Vec<_>>())
    };
    let scalar = |i: usize| a.get(i).and_then(|v| if v.len() == 1 { Some(v[0]) } else { None });
    match builtin {
        Builtin::Radians => f1(f64::to_radians),
        Builtin::Degrees => f1(f64::to_degrees),
        Builtin::Sin => f1(f64::sin),
        Builtin::Cos => f1(f64::cos),
        Builtin::Tan => f1(f64::tan),
        Builtin::Asin => f1(f64::asin),
        Builtin::Acos => f1(f64::acos),
        Builtin::Atan if a.len() == 1 => f1(f64::atan),
        Builtin::Atan if a.len() == 2 => Some(Const::Float(scalar(0)?.atan2(scalar(1)?))),
        Builtin::Exp => f1(f64::exp),
        Builtin::Sqrt => f1(f64::sqrt),
        Builtin::InverseSqrt => f1(|x| 1.0 / x.sqrt()),
        Builtin::Log if a.len() == 1 => f1(f64::ln),
        Builtin::Log if a.len() == 2 => Some(Const::Float(scalar(0)?.ln() / scalar(1)?.ln())),
        Builtin::Abs => f1(f64::abs),
        Builtin::Floor => f1(f64::floor),
        Builtin::Ceil => f1(f64::ceil),
        Builtin::Round => f1(f64::round),
        Builtin::Sign => f1(|x| {
            if x > 0.0 {
                1.0
            } else if x < 0.0 {
                -1.0
            } else {
                0.0
            }
        }),
        Builtin::Pow => Some(Const::Float(scalar(0)?.powf(scalar(1)?))),
        Builtin::Mod => {
            let (x, y) = (scalar(0)?, scalar(1)?);
            Some(Const::Float(x - y * (x / y).floor()))
        }
        Builtin::Min if a.len() == 2 && a[0].len() == a[1].len() => {
            Const::from_components(base, &a[0].iter().zip(&a[1]).map(|(x, y)| x.min(*y)).collect::<Vec<_>>())
        }
        Builtin::Max if a.len() == 2 && a[0].len() == a[1].len() => {
            Const::from_components(base, &a[0].iter().zip(&a[1]).map(|(x, y)| x.max(*y)).collect::<Vec<_>>())
        }
        Builtin::Clamp => {
            let (x, lo, hi) = (scalar(0)?, scalar(1)?, scalar(2)?);
            // As the interpreter: the lower bound wins when the bounds cross.
            Some(Const::Float(x.min(hi).max(lo)))
        }
        Builtin::Step => Some(Const::Float(if scalar(1)? < scalar(0)? { 0.0 } else { 1.0 })),
        Builtin::Length if a.len() == 1 && a[0].len() == 3 => {
            Some(Const::Float(a[0].iter().map(|x| x * x).sum::<f64>().sqrt()))
        }
        _ => None,
    }
}
