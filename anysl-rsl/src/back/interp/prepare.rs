//! IR → register-allocated code tree.

use super::builtins::{self, Bi};
use super::frame::Loc;
use crate::ir::{BinOp, Block, Const, Global, Module, Node, Op, SlotKind, UnOp, Value};
use crate::types::{BaseType, Type};
use std::fmt;

/// Arithmetic operators of [`Code::Arith`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arith {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
}

/// Comparison operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cmp {
    /// `==` (all components)
    Eq,
    /// `!=` (any component)
    Ne,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
}

/// One register-level op.
#[derive(Clone, Debug)]
pub enum Code {
    /// `dst[0..w] = src[0..w]`
    Copy { dst: u32, src: u32, w: u32 },
    /// `dst[0..w] = src[0]`
    Splat { dst: u32, src: u32, w: u32 },
    /// `dst = -a`
    Neg { dst: u32, a: u32, w: u32 },
    /// Component-wise arithmetic with float broadcast (`sa`/`sb`: operand is one float).
    Arith { op: Arith, dst: u32, a: u32, sa: bool, b: u32, sb: bool, w: u32 },
    /// 4×4 matrix product (`div`: by the inverse of `b`).
    MatMul { dst: u32, a: u32, b: u32, div: bool },
    /// Dot product of triples.
    Dot { dst: u32, a: u32, b: u32 },
    /// Cross product.
    Cross { dst: u32, a: u32, b: u32 },
    /// Numeric comparison into a mask.
    Cmp { op: Cmp, dst: u32, a: u32, b: u32, w: u32 },
    /// String (in)equality.
    CmpStr { ne: bool, dst: u32, a: u32, b: u32 },
    /// Mask equality.
    CmpMask { ne: bool, dst: u32, a: u32, b: u32 },
    /// `dst = !a`
    Not { dst: u32, a: u32 },
    /// `dst = a && b` (or `||`)
    Logic { or: bool, dst: u32, a: u32, b: u32 },
    /// Float (any component) `!= 0` → mask.
    ToMask { dst: u32, a: u32, w: u32 },
    /// Mask → 1.0 / 0.0.
    FromMask { dst: u32, a: u32 },
    /// `dst = c ? a : b`
    Select { dst: u32, c: u32, a: u32, b: u32, w: u32 },
    /// Mask select.
    SelectMask { dst: u32, c: u32, a: u32, b: u32 },
    /// String select (uniform condition: lane 0 decides).
    SelectStr { dst: u32, c: u32, a: u32, b: u32 },
    /// String copy.
    CopyStr { dst: u32, src: u32, n: u32 },
    /// `dst = base[idx]` (element width `w`, `len` elements).
    LoadElem { dst: u32, base: u32, len: u32, w: u32, idx: u32 },
    /// String array element (uniform index).
    LoadElemStr { dst: u32, base: u32, len: u32, idx: u32 },
    /// Colour from a named colour space (`color "hsv" (…)`), or a point, vector, normal or
    /// matrix from a named coordinate system to `current` (`point "object" (…)`); `base` is
    /// the result's type.
    FromSpace { dst: u32, space: u32, src: u32, base: BaseType },
    /// A built-in call.
    Call { f: Bi, dst: Loc, args: Vec<Loc>, outs: Vec<Option<Loc>> },
}

/// A node of the compiled tree (mirrors [`crate::ir::Node`]).
#[derive(Clone, Debug)]
pub enum CNode {
    /// A register op.
    Op(Code),
    /// Masked store into a variable; `idx` for array elements.
    Store { dst: Loc, src: Loc, idx: Option<u32>, elem: u32, len: u32 },
    /// Branch.
    If { c: u32, then: Vec<CNode>, otherwise: Vec<CNode> },
    /// Loop.
    Loop { header: Vec<CNode>, cond: Option<u32>, body: Vec<CNode>, step: Vec<CNode> },
    /// `break`
    Break(u32),
    /// `continue`
    Continue(u32),
    /// `return`
    Return,
    /// Inlined function.
    Frame(Vec<CNode>),
    /// Light loop of a surface shader.
    Illuminance {
        cat: Option<u32>,
        p: u32,
        cone: Option<(u32, u32)>,
        body: Vec<CNode>,
        l: Option<u32>,
        cl: Option<u32>,
    },
    /// `illuminate` in a light shader.
    Illuminate { p: u32, cone: Option<(u32, u32)>, body: Vec<CNode> },
    /// `solar` in a light shader.
    Solar { cone: Option<(u32, u32)>, body: Vec<CNode> },
}

/// Why a module cannot be interpreted.
#[derive(Clone, Debug, PartialEq)]
pub struct PrepareError(pub String);

impl fmt::Display for PrepareError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot interpret: {}", self.0)
    }
}

impl std::error::Error for PrepareError {}

/// An IR module compiled for the interpreter.
#[derive(Clone, Debug)]
pub struct Program {
    /// The (optimized) IR it was compiled from.
    pub module: Module,
    pub(crate) code: Vec<CNode>,
    pub(crate) nregs: u32,
    pub(crate) nmasks: u32,
    pub(crate) nstrs: u32,
    pub(crate) consts: Vec<(u32, f64)>,
    pub(crate) mask_consts: Vec<(u32, bool)>,
    pub(crate) str_consts: Vec<(u32, String)>,
    pub(crate) globals: Vec<(Global, Loc)>,
    /// Parameter index → its slot's location.
    pub(crate) params: Vec<Loc>,
    /// True when some value needs derivatives.
    pub uses_derivatives: bool,
    /// The globals the shader reads ([`crate::passes::analysis::globals_read`]).
    pub globals_read: anysl_core::GlobalSet,
    /// As a light shader, how it emits ([`anysl_core::LightShader::emission`]): found once
    /// here, not per light call.
    pub emission: Option<anysl_core::Emission>,
}

struct Alloc {
    nregs: u32,
    nmasks: u32,
    nstrs: u32,
}

impl Alloc {
    fn loc(&mut self, ty: Type, is_bool: bool) -> Loc {
        let len = ty.array.unwrap_or(1).max(1);
        if is_bool {
            self.nmasks += 1;
            return Loc::Mask(self.nmasks - 1);
        }
        match ty.base {
            BaseType::String => {
                self.nstrs += len;
                Loc::Str(self.nstrs - len, len)
            }
            BaseType::Void => Loc::None,
            b => {
                let width = b.components() as u32 * len;
                self.nregs += width;
                Loc::Num { off: self.nregs - width, width }
            }
        }
    }
}

impl Program {
    /// Compiles an analyzed module ([`crate::passes::optimize`]).
    ///
    /// # Errors
    /// When the module uses an op or built-in overload the interpreter does not implement.
    pub fn new(module: crate::passes::Analyzed) -> Result<Self, PrepareError> {
        let module = module.into_module();
        let mut a = Alloc { nregs: 0, nmasks: 0, nstrs: 0 };
        let func = &module.func;
        let slot_locs: Vec<Loc> = func.slots.iter().map(|s| a.loc(s.ty, false)).collect();
        let val_locs: Vec<Loc> = func.insts.iter().map(|i| a.loc(i.ty, i.is_bool)).collect();
        let mut p = Program {
            module: module.clone(),
            code: Vec::new(),
            nregs: 0,
            nmasks: 0,
            nstrs: 0,
            consts: Vec::new(),
            mask_consts: Vec::new(),
            str_consts: Vec::new(),
            globals: Vec::new(),
            params: vec![Loc::None; module.params.len()],
            uses_derivatives: func.insts.iter().any(|i| i.needs_derivs),
            globals_read: crate::passes::analysis::globals_read(&module),
            emission: emission_of(&module.func.body),
        };
        for (i, s) in func.slots.iter().enumerate() {
            match &s.kind {
                SlotKind::Global(g) => p.globals.push((*g, slot_locs[i])),
                SlotKind::Param(k) => {
                    if let Some(l) = p.params.get_mut(*k as usize) {
                        *l = slot_locs[i];
                    }
                }
                SlotKind::Local => {}
            }
        }
        let cx = Cx { m: &module, slots: &slot_locs, vals: &val_locs };
        let mut consts = Consts::default();
        p.code = cx.block(&func.body, &mut consts)?;
        p.consts = consts.num;
        p.mask_consts = consts.mask;
        p.str_consts = consts.strs;
        p.nregs = a.nregs;
        p.nmasks = a.nmasks;
        p.nstrs = a.nstrs;
        Ok(p)
    }
}

#[derive(Default)]
struct Consts {
    num: Vec<(u32, f64)>,
    mask: Vec<(u32, bool)>,
    strs: Vec<(u32, String)>,
}

struct Cx<'a> {
    m: &'a Module,
    slots: &'a [Loc],
    vals: &'a [Loc],
}

impl Cx<'_> {
    fn v(&self, v: Value) -> Loc {
        self.vals[v.0 as usize]
    }

    fn block(&self, b: &Block, k: &mut Consts) -> Result<Vec<CNode>, PrepareError> {
        let mut out = Vec::with_capacity(b.len());
        for n in b {
            match n {
                Node::Inst(v) => self.inst(*v, &mut out, k)?,
                Node::Store { slot, index, value, .. } => {
                    let dst = self.slots[slot.0 as usize];
                    let sty = self.m.func.slot(*slot).ty;
                    let src = self.v(*value);
                    let elem = sty.base.components() as u32;
                    let len = sty.array.unwrap_or(1);
                    out.push(CNode::Store { dst, src, idx: index.map(|i| self.v(i).off()), elem, len });
                }
                Node::If { cond, then, otherwise } => out.push(CNode::If {
                    c: self.mask_of(*cond)?,
                    then: self.block(then, k)?,
                    otherwise: self.block(otherwise, k)?,
                }),
                Node::Loop { header, cond, body, step } => out.push(CNode::Loop {
                    header: self.block(header, k)?,
                    cond: cond.map(|c| self.mask_of(c)).transpose()?,
                    body: self.block(body, k)?,
                    step: self.block(step, k)?,
                }),
                Node::Break(l) => out.push(CNode::Break(*l)),
                Node::Continue(l) => out.push(CNode::Continue(*l)),
                Node::Return => out.push(CNode::Return),
                Node::Frame(b) => out.push(CNode::Frame(self.block(b, k)?)),
                Node::Illuminance { category, position, cone, body } => {
                    let slot_of = |g| self.m.func.global_slot(g).map(|s| self.slots[s.0 as usize].off());
                    out.push(CNode::Illuminance {
                        cat: category.map(|c| self.v(c).off()),
                        p: self.v(*position).off(),
                        cone: cone.map(|(a, b)| (self.v(a).off(), self.v(b).off())),
                        body: self.block(body, k)?,
                        l: slot_of(Global::L),
                        cl: slot_of(Global::Cl),
                    });
                }
                Node::Illuminate { position, cone, body } => out.push(CNode::Illuminate {
                    p: self.v(*position).off(),
                    cone: cone.map(|(a, b)| (self.v(a).off(), self.v(b).off())),
                    body: self.block(body, k)?,
                }),
                Node::Solar { cone, body } => out.push(CNode::Solar {
                    cone: cone.map(|(a, b)| (self.v(a).off(), self.v(b).off())),
                    body: self.block(body, k)?,
                }),
            }
        }
        Ok(out)
    }

    fn mask_of(&self, v: Value) -> Result<u32, PrepareError> {
        match self.v(v) {
            Loc::Mask(m) => Ok(m),
            other => Err(PrepareError(format!("condition v{} is not a boolean ({other:?})", v.0))),
        }
    }

    fn inst(&self, v: Value, out: &mut Vec<CNode>, k: &mut Consts) -> Result<(), PrepareError> {
        let inst = self.m.func.inst(v);
        let dst = self.v(v);
        let arg = |i: usize| self.v(inst.args[i]);
        let unsupported = || {
            PrepareError(format!(
                "{:?} on {:?}",
                inst.op,
                inst.args.iter().map(|a| self.m.func.inst(*a).ty.base).collect::<Vec<_>>()
            ))
        };
        let code = match &inst.op {
            Op::Const(c) => {
                match dst {
                    Loc::Mask(m) => k.mask.push((m, matches!(c, Const::Float(x) if *x != 0.0))),
                    Loc::Num { off, width } => {
                        let mut vals = Vec::new();
                        c.flatten(&mut vals, &mut Vec::new());
                        if vals.len() == 1 && width > 1 {
                            vals = vec![vals[0]; width as usize];
                        }
                        for (i, x) in vals.into_iter().enumerate().take(width as usize) {
                            k.num.push((off + i as u32, x));
                        }
                    }
                    Loc::Str(off, _) => {
                        let mut strs = Vec::new();
                        c.flatten(&mut Vec::new(), &mut strs);
                        for (i, s) in strs.into_iter().enumerate() {
                            k.strs.push((off + i as u32, s));
                        }
                    }
                    Loc::None => {}
                }
                return Ok(());
            }
            Op::Load(s) => {
                let src = self.slots[s.0 as usize];
                match (dst, src) {
                    (Loc::Num { off, width }, Loc::Num { off: so, .. }) => Code::Copy { dst: off, src: so, w: width },
                    (Loc::Str(d, n), Loc::Str(s, _)) => Code::CopyStr { dst: d, src: s, n },
                    (Loc::Mask(d), Loc::Num { off, .. }) => Code::ToMask { dst: d, a: off, w: 1 },
                    _ => return Err(unsupported()),
                }
            }
            Op::LoadElem(s) => {
                let sty = self.m.func.slot(*s).ty;
                let idx = arg(0).off();
                match (dst, self.slots[s.0 as usize]) {
                    (Loc::Num { off, width }, Loc::Num { off: base, .. }) => {
                        Code::LoadElem { dst: off, base, len: sty.array.unwrap_or(1), w: width, idx }
                    }
                    (Loc::Str(d, _), Loc::Str(base, len)) => Code::LoadElemStr { dst: d, base, len, idx },
                    _ => return Err(unsupported()),
                }
            }
            Op::Unary(UnOp::Neg) => Code::Neg { dst: dst.off(), a: arg(0).off(), w: dst.width() },
            Op::Unary(UnOp::Not) => match arg(0) {
                Loc::Mask(a) => Code::Not { dst: dst.off(), a },
                _ => return Err(unsupported()),
            },
            Op::Binary(op) => {
                let (a, b) = (arg(0), arg(1));
                match op {
                    BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div => {
                        let ta = self.m.func.inst(inst.args[0]).ty.base;
                        let tb = self.m.func.inst(inst.args[1]).ty.base;
                        if ta == BaseType::Matrix && tb == BaseType::Matrix && matches!(op, BinOp::Mul | BinOp::Div) {
                            Code::MatMul { dst: dst.off(), a: a.off(), b: b.off(), div: *op == BinOp::Div }
                        } else {
                            let aop = match op {
                                BinOp::Add => Arith::Add,
                                BinOp::Sub => Arith::Sub,
                                BinOp::Mul => Arith::Mul,
                                _ => Arith::Div,
                            };
                            Code::Arith {
                                op: aop,
                                dst: dst.off(),
                                a: a.off(),
                                sa: a.width() == 1,
                                b: b.off(),
                                sb: b.width() == 1,
                                w: dst.width(),
                            }
                        }
                    }
                    BinOp::Dot => Code::Dot { dst: dst.off(), a: a.off(), b: b.off() },
                    BinOp::Cross => Code::Cross { dst: dst.off(), a: a.off(), b: b.off() },
                    BinOp::And | BinOp::Or => match (a, b) {
                        (Loc::Mask(a), Loc::Mask(b)) => Code::Logic { or: *op == BinOp::Or, dst: dst.off(), a, b },
                        _ => return Err(unsupported()),
                    },
                    _ => {
                        let cmp = match op {
                            BinOp::Eq => Cmp::Eq,
                            BinOp::Ne => Cmp::Ne,
                            BinOp::Lt => Cmp::Lt,
                            BinOp::Le => Cmp::Le,
                            BinOp::Gt => Cmp::Gt,
                            _ => Cmp::Ge,
                        };
                        match (a, b) {
                            (Loc::Str(a, _), Loc::Str(b, _)) => {
                                Code::CmpStr { ne: cmp == Cmp::Ne, dst: dst.off(), a, b }
                            }
                            (Loc::Mask(a), Loc::Mask(b)) => Code::CmpMask { ne: cmp == Cmp::Ne, dst: dst.off(), a, b },
                            (Loc::Num { .. }, Loc::Num { .. }) if a.width() == b.width() => {
                                Code::Cmp { op: cmp, dst: dst.off(), a: a.off(), b: b.off(), w: a.width() }
                            }
                            _ => return Err(unsupported()),
                        }
                    }
                }
            }
            Op::Select => match (arg(0), dst) {
                (Loc::Mask(c), Loc::Num { off, width }) => {
                    Code::Select { dst: off, c, a: arg(1).off(), b: arg(2).off(), w: width }
                }
                (Loc::Mask(c), Loc::Mask(d)) => Code::SelectMask { dst: d, c, a: arg(1).off(), b: arg(2).off() },
                (Loc::Mask(c), Loc::Str(d, _)) => Code::SelectStr { dst: d, c, a: arg(1).off(), b: arg(2).off() },
                _ => return Err(unsupported()),
            },
            Op::Convert => match (arg(0), dst) {
                (Loc::Num { off, width: 1 }, Loc::Num { off: d, width }) if width == 16 => {
                    // float → matrix: s on the diagonal.
                    for i in 0..16u32 {
                        if i % 5 != 0 {
                            k.num.push((d + i, 0.0));
                        }
                    }
                    for i in 0..4u32 {
                        out.push(CNode::Op(Code::Copy { dst: d + i * 5, src: off, w: 1 }));
                    }
                    return Ok(());
                }
                (Loc::Num { off, width: 1 }, Loc::Num { off: d, width }) => Code::Splat { dst: d, src: off, w: width },
                (Loc::Num { off, width: sw }, Loc::Num { off: d, width }) if sw == width => {
                    Code::Copy { dst: d, src: off, w: width }
                }
                (Loc::Num { off, width }, Loc::Mask(d)) => Code::ToMask { dst: d, a: off, w: width },
                (Loc::Mask(m), Loc::Num { off, width: 1 }) => Code::FromMask { dst: off, a: m },
                (Loc::Mask(m), Loc::Mask(d)) => Code::SelectMask { dst: d, c: m, a: m, b: m },
                (Loc::Str(s, n), Loc::Str(d, _)) => Code::CopyStr { dst: d, src: s, n },
                _ => return Err(unsupported()),
            },
            Op::MakeTriple | Op::MakeMatrix => {
                for (i, &a) in inst.args.iter().enumerate() {
                    out.push(CNode::Op(Code::Copy { dst: dst.off() + i as u32, src: self.v(a).off(), w: 1 }));
                }
                return Ok(());
            }
            Op::FromSpace => {
                let Loc::Str(space, _) = arg(0) else {
                    return Err(unsupported());
                };
                Code::FromSpace { dst: dst.off(), space, src: arg(1).off(), base: inst.ty.base }
            }
            Op::Call { builtin, outputs, .. } => {
                let arg_tys: Vec<(BaseType, Option<u32>)> = inst
                    .args
                    .iter()
                    .map(|a| {
                        let t = self.m.func.inst(*a).ty;
                        (t.base, t.array)
                    })
                    .collect();
                let consts: Vec<Option<Const>> = inst
                    .args
                    .iter()
                    .map(|a| match &self.m.func.inst(*a).op {
                        Op::Const(c) => Some(c.clone()),
                        _ => None,
                    })
                    .collect();
                let out_tys: Vec<Option<(BaseType, Option<u32>)>> = outputs
                    .iter()
                    .map(|o| o.map(|s| (self.m.func.slot(s).ty.base, self.m.func.slot(s).ty.array)))
                    .collect();
                let f = builtins::resolve(*builtin, &arg_tys, &consts, &out_tys, inst.ty.base).ok_or_else(|| {
                    PrepareError(format!("built-in `{builtin}` with arguments {arg_tys:?} returning {}", inst.ty.base))
                })?;
                Code::Call {
                    f,
                    dst,
                    args: inst.args.iter().map(|&a| self.v(a)).collect(),
                    outs: outputs.iter().map(|o| o.map(|s| self.slots[s.0 as usize])).collect(),
                }
            }
        };
        out.push(CNode::Op(code));
        Ok(())
    }
}

/// How a light shader with body `body` emits: ambient without `illuminate`/`solar`, local with
/// `illuminate` only, distant with `solar` only, unknown (`None`) with both.
fn emission_of(body: &crate::ir::Block) -> Option<anysl_core::Emission> {
    use anysl_core::Emission;
    let (mut has_illuminate, mut has_solar) = (false, false);
    crate::ir::walk(body, &mut |n| match n {
        crate::ir::Node::Illuminate { .. } => has_illuminate = true,
        crate::ir::Node::Solar { .. } => has_solar = true,
        _ => {}
    });
    match (has_illuminate, has_solar) {
        (false, false) => Some(Emission::Ambient),
        (true, false) => Some(Emission::Local),
        (false, true) => Some(Emission::Distant),
        (true, true) => None,
    }
}
