//! Instructions: the values already generated, one instruction of the IR in the
//! representation its result needs, and the bodies of the ops other than built-in calls
//! (unary and binary operators, select, conversions, constructors, space transforms).

use super::call::space_index;
use super::params::slot_comps;
use super::value::{err, Repr, Val, M, R, S};
use super::Cg;
use crate::rt::{self, RtKind};
use anysl_rsl::ir::{self, BinOp, Const, Op, UnOp, Value};
use anysl_rsl::types::{BaseType, Detail};
use inkwell::FloatPredicate;

impl<'c> Cg<'c, '_> {
    pub(super) fn val(&self, v: Value) -> R<Val<'c>> {
        match self.vals.get(v.0 as usize).cloned().flatten() {
            Some(x) => Ok(x),
            None => err(format!("value v{} used before it is defined", v.0)),
        }
    }
    pub(super) fn nums(&self, v: Value) -> R<Vec<S<'c>>> {
        match self.val(v)? {
            Val::Num(c) => Ok(c),
            Val::Mask(m) => Ok(vec![self.sel(m, self.fc(1.0), self.fc(0.0))]),
            other => err(format!("v{} is not numeric: {other:?}", v.0)),
        }
    }
    pub(super) fn mask_of(&self, v: Value) -> R<M<'c>> {
        match self.val(v)? {
            Val::Mask(m) => Ok(m),
            Val::Num(c) => {
                let mut r = self.cmp(FloatPredicate::UNE, c[0], self.fc(0.0));
                for &x in &c[1..] {
                    r = self.mor(r, self.cmp(FloatPredicate::UNE, x, self.fc(0.0)));
                }
                Ok(r)
            }
            other => err(format!("v{} is not a condition: {other:?}", v.0)),
        }
    }
    pub(super) fn str_of(&self, v: Value) -> R<String> {
        match self.val(v)? {
            Val::Str(s) => Ok(s.first().cloned().unwrap_or_default()),
            other => err(format!("v{} is not a string: {other:?}", v.0)),
        }
    }

    pub(super) fn repr_of_inst(&self, inst: &ir::Inst) -> Repr {
        if inst.ty.detail == Detail::Uniform {
            Repr::U
        } else if self.t.dual && inst.needs_derivs {
            Repr::D
        } else {
            Repr::V
        }
    }

    pub(super) fn inst(&mut self, v: Value) -> R<()> {
        let func = self.func;
        let inst = func.inst(v);
        let want = self.inst_repr[v.0 as usize];
        let result = match &inst.op {
            Op::Const(c) => {
                if inst.is_bool {
                    Val::Mask(self.mconst(matches!(c, Const::Float(x) if *x != 0.0)))
                } else {
                    self.const_val(c, inst.ty)
                }
            }
            Op::Load(s) => {
                let val = self.load_slot(*s);
                if inst.is_bool {
                    if let Val::Num(c) = &val {
                        Val::Mask(self.cmp(FloatPredicate::UNE, c[0], self.fc(0.0)))
                    } else {
                        val
                    }
                } else {
                    val
                }
            }
            Op::LoadElem(s) => self.load_elem(*s, inst.args[0], inst.ty)?,
            _ => {
                // Derivative built-ins keep dual arguments; every other op runs in the
                // representation its result needs (so derivative work nobody uses is skipped).
                let keep = matches!(&inst.op, Op::Call { builtin, .. } if builtin.uses_derivatives());
                let mut args: Vec<Val<'c>> = Vec::with_capacity(inst.args.len());
                for &a in &inst.args {
                    let x = self.val(a)?;
                    let x = match x {
                        Val::Num(c) if !keep && want != Repr::D && c.iter().any(|s| s.r == Repr::D) => {
                            Val::Num(c.into_iter().map(|s| self.to(s, Repr::V)).collect())
                        }
                        other => other,
                    };
                    args.push(x);
                }
                self.lit_call(v, args)?
            }
        };
        let result = match result {
            Val::Num(c) if !inst.is_bool => {
                let r = if want == Repr::U { c.first().map_or(Repr::U, |s| s.r) } else { want };
                Val::Num(
                    c.into_iter().map(|s| self.to(s, r.max(if want == Repr::U { Repr::U } else { want }))).collect(),
                )
            }
            other => other,
        };
        self.vals[v.0 as usize] = Some(result);
        Ok(())
    }

    pub(super) fn as_nums(&self, v: &Val<'c>) -> R<Vec<S<'c>>> {
        match v {
            Val::Num(c) => Ok(c.clone()),
            Val::Mask(m) => Ok(vec![self.sel(*m, self.fc(1.0), self.fc(0.0))]),
            other => err(format!("not numeric: {other:?}")),
        }
    }
    fn as_mask(&self, v: &Val<'c>) -> R<M<'c>> {
        match v {
            Val::Mask(m) => Ok(*m),
            Val::Num(c) => {
                let mut r = self.cmp(FloatPredicate::UNE, c[0], self.fc(0.0));
                for &x in &c[1..] {
                    r = self.mor(r, self.cmp(FloatPredicate::UNE, x, self.fc(0.0)));
                }
                Ok(r)
            }
            other => err(format!("not a condition: {other:?}")),
        }
    }
    pub(super) fn as_str(v: &Val<'c>) -> String {
        match v {
            Val::Str(s) => s.first().cloned().unwrap_or_default(),
            _ => String::new(),
        }
    }

    /// Component-wise op with broadcast of one-component operands.
    pub(super) fn cwise(&self, args: &[Vec<S<'c>>], w: usize, f: impl Fn(&Self, &[S<'c>]) -> S<'c>) -> Vec<S<'c>> {
        (0..w)
            .map(|c| {
                let xs: Vec<S<'c>> =
                    args.iter().map(|a| if a.len() == 1 { a[0] } else { a[c.min(a.len() - 1)] }).collect();
                f(self, &xs)
            })
            .collect()
    }

    /// The body of one op: `[result, outputs…]`.
    pub(super) fn op_body(&mut self, v: Value, args: &[Val<'c>]) -> R<Vec<Val<'c>>> {
        let func = self.func;
        let inst = func.inst(v);
        let aty = |i: usize| func.inst(inst.args[i]).ty;
        let res = match &inst.op {
            Op::Unary(UnOp::Neg) => Val::Num(self.as_nums(&args[0])?.into_iter().map(|s| self.neg(s)).collect()),
            Op::Unary(UnOp::Not) => Val::Mask(self.mnot(self.as_mask(&args[0])?)),
            Op::Binary(op) => self.binary(*op, inst, args)?,
            Op::Select => {
                let c = self.as_mask(&args[0])?;
                match (&args[1], &args[2]) {
                    (Val::Mask(a), Val::Mask(b)) => Val::Mask(self.msel(c, *a, *b)),
                    (Val::Str(a), Val::Str(b)) => {
                        let pick = match &func.inst(inst.args[0]).op {
                            Op::Const(Const::Float(x)) => *x != 0.0,
                            _ => return err("string select on a run-time condition"),
                        };
                        Val::Str(if pick { a.clone() } else { b.clone() })
                    }
                    (a, b) => {
                        let (a, b) = (self.as_nums(a)?, self.as_nums(b)?);
                        let w = a.len().max(b.len());
                        Val::Num(self.cwise(&[a, b], w, |cg, x| cg.sel(c, x[0], x[1])))
                    }
                }
            }
            Op::Convert => {
                if inst.is_bool {
                    Val::Mask(self.as_mask(&args[0])?)
                } else {
                    match &args[0] {
                        Val::Str(s) => Val::Str(s.clone()),
                        a => {
                            let x = self.as_nums(a)?;
                            let w = slot_comps(inst.ty).max(1);
                            if inst.ty.base == BaseType::Matrix && x.len() == 1 {
                                Val::Num((0..16).map(|i| if i % 5 == 0 { x[0] } else { self.fc(0.0) }).collect())
                            } else if x.len() == 1 {
                                Val::Num(vec![x[0]; w])
                            } else {
                                Val::Num(x)
                            }
                        }
                    }
                }
            }
            Op::MakeTriple | Op::MakeMatrix => {
                let mut c = Vec::new();
                for a in args {
                    c.push(self.as_nums(a)?[0]);
                }
                Val::Num(c)
            }
            Op::FromSpace => {
                let x = self.as_nums(&args[1])?;
                if inst.ty.base == BaseType::Color {
                    match space_index(&Self::as_str(&args[0])) {
                        Some(from) => {
                            Val::Num(self.rt_call(RtKind::Geo, rt::Geo::CTransform as u32 | from << 8, &x, 3, false))
                        }
                        None => Val::Num(x),
                    }
                } else {
                    let to = self.space_matrix(rt::SPACE_TO_CURRENT, &Self::as_str(&args[0]));
                    let aux = match inst.ty.base {
                        BaseType::Matrix => rt::Geo::MatMul as u32,
                        BaseType::Vector => rt::Geo::XformVector as u32,
                        BaseType::Normal => rt::Geo::XformNormal as u32,
                        _ => rt::Geo::XformPoint as u32,
                    };
                    // `matrix "name" m` is m · (name → current); a triple is transformed by it.
                    let all: Vec<S<'c>> = if aux == rt::Geo::MatMul as u32 {
                        x.into_iter().chain(to).collect()
                    } else {
                        to.into_iter().chain(x).collect()
                    };
                    let n_out = if aux == rt::Geo::MatMul as u32 { 16 } else { 3 };
                    Val::Num(self.rt_call(RtKind::Geo, aux, &all, n_out, false))
                }
            }
            Op::Call { builtin, outputs, .. } => {
                let _ = aty;
                return self.builtin(v, *builtin, outputs, args);
            }
            Op::Const(_) | Op::Load(_) | Op::LoadElem(_) => return err("memory op in a threaded body"),
        };
        Ok(vec![res])
    }

    pub(super) fn binary(&mut self, op: BinOp, inst: &ir::Inst, args: &[Val<'c>]) -> R<Val<'c>> {
        let func = self.func;
        let ta = func.inst(inst.args[0]).ty.base;
        let tb = func.inst(inst.args[1]).ty.base;
        Ok(match op {
            BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div => {
                let (a, b) = (self.as_nums(&args[0])?, self.as_nums(&args[1])?);
                if ta == BaseType::Matrix && tb == BaseType::Matrix && matches!(op, BinOp::Mul | BinOp::Div) {
                    let aux = if op == BinOp::Mul { rt::Geo::MatMul as u32 } else { rt::Geo::MatDiv as u32 };
                    let all: Vec<S<'c>> = a.into_iter().chain(b).collect();
                    return Ok(Val::Num(self.rt_call(RtKind::Geo, aux, &all, 16, false)));
                }
                let w = a.len().max(b.len());
                Val::Num(self.cwise(&[a, b], w, |cg, x| match op {
                    BinOp::Add => cg.add(x[0], x[1]),
                    BinOp::Sub => cg.sub(x[0], x[1]),
                    BinOp::Mul => cg.mul(x[0], x[1]),
                    _ => cg.div(x[0], x[1]),
                }))
            }
            BinOp::Dot => {
                let (a, b) = (self.as_nums(&args[0])?, self.as_nums(&args[1])?);
                Val::Num(vec![self.dot(&a, &b)])
            }
            BinOp::Cross => {
                let (a, b) = (self.as_nums(&args[0])?, self.as_nums(&args[1])?);
                Val::Num(self.cross(&a, &b))
            }
            BinOp::And | BinOp::Or => {
                let (a, b) = (self.as_mask(&args[0])?, self.as_mask(&args[1])?);
                Val::Mask(if op == BinOp::And { self.mand(a, b) } else { self.mor(a, b) })
            }
            _ => match (&args[0], &args[1]) {
                (Val::Str(a), Val::Str(b)) => Val::Mask(self.mconst((a == b) != (op == BinOp::Ne))),
                (Val::Mask(a), Val::Mask(b)) => {
                    let diff = self.mxor(*a, *b);
                    Val::Mask(if op == BinOp::Ne { diff } else { self.mnot(diff) })
                }
                (a, b) => {
                    let (a, b) = (self.as_nums(a)?, self.as_nums(b)?);
                    let w = a.len().min(b.len());
                    let mut r = self.mconst(op != BinOp::Ne);
                    for c in 0..w {
                        let (x, y) = (a[c], b[c]);
                        r = match op {
                            BinOp::Eq => self.mand(r, self.cmp(FloatPredicate::OEQ, x, y)),
                            BinOp::Ne => self.mor(r, self.cmp(FloatPredicate::UNE, x, y)),
                            BinOp::Lt => self.cmp(FloatPredicate::OLT, x, y),
                            BinOp::Le => self.cmp(FloatPredicate::OLE, x, y),
                            BinOp::Gt => self.cmp(FloatPredicate::OGT, x, y),
                            _ => self.cmp(FloatPredicate::OGE, x, y),
                        };
                    }
                    Val::Mask(r)
                }
            },
        })
    }
}
