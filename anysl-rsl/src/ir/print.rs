//! The readable IR printer: `impl Display for Module`.
//!
//! ```text
//! surface plastic
//! params:
//!   p0 uniform float Ka = 1
//! slots:
//!   s0 uniform float Ka (param 0)
//!   s1 varying normal N (global)
//! body:
//!   v0: varying normal = load s1 N
//!   v1: varying normal = call normalize_n(v0)
//!   v2: varying vector = mul(float v3, vector v11)
//!   store s2 Nf = v1
//!   if v5 {
//!     …
//!   } else {
//!     …
//!   }
//! ```

use super::{Block, Const, Function, Module, Node, Op, ShaderKind, SlotKind, UnOp, Value};
use crate::builtins::OVERLOADS;
use std::fmt::{self, Display, Formatter, Write};

impl Display for Const {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Const::Float(x) => write!(f, "{x}"),
            Const::Triple([a, b, c]) => write!(f, "({a}, {b}, {c})"),
            Const::Matrix(m) => {
                f.write_str("(")?;
                for (i, x) in m.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{x}")?;
                }
                f.write_str(")")
            }
            Const::Str(s) => write!(f, "{s:?}"),
            Const::Array(v) => {
                f.write_str("{")?;
                for (i, c) in v.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{c}")?;
                }
                f.write_str("}")
            }
        }
    }
}

impl Display for ShaderKind {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ShaderKind::Surface => "surface",
            ShaderKind::Light => "light",
            ShaderKind::Displacement => "displacement",
            ShaderKind::Volume => "volume",
            ShaderKind::Imager => "imager",
        })
    }
}

impl Display for Module {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        writeln!(f, "{} {}", self.kind, self.name)?;
        if !self.params.is_empty() {
            writeln!(f, "params:")?;
            for (i, p) in self.params.iter().enumerate() {
                write!(f, "  p{i} {}{} {} = {}", if p.output { "output " } else { "" }, p.ty, p.name, p.default)?;
                if let Some(s) = &p.space {
                    write!(f, " in {s:?}")?;
                }
                writeln!(f, " -> s{}", p.slot.0)?;
            }
        }
        write!(f, "{}", self.func)
    }
}

impl Display for Function {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        writeln!(f, "slots:")?;
        for (i, s) in self.slots.iter().enumerate() {
            let kind = match &s.kind {
                SlotKind::Local => String::new(),
                SlotKind::Param(p) => format!(" (param {p})"),
                SlotKind::Global(_) => " (global)".to_string(),
            };
            writeln!(f, "  s{i} {} {}{kind}", s.ty, s.name)?;
        }
        writeln!(f, "body:")?;
        let mut out = String::new();
        self.block(&mut out, &self.body, 1)?;
        f.write_str(&out)
    }
}

impl Function {
    fn val(&self, v: Value) -> String {
        format!("v{}", v.0)
    }

    fn typed_val(&self, v: Value) -> String {
        match self.insts.get(v.0 as usize) {
            Some(i) if i.is_bool => format!("bool v{}", v.0),
            Some(i) => format!("{} v{}", crate::types::Type { array: i.ty.array, ..i.ty }.base, v.0),
            None => format!("v{}", v.0),
        }
    }

    fn slot_ref(&self, s: super::SlotId) -> String {
        match self.slots.get(s.0 as usize) {
            Some(slot) => format!("s{} {}", s.0, slot.name),
            None => format!("s{}", s.0),
        }
    }

    fn inst_text(&self, v: Value) -> String {
        let Some(inst) = self.insts.get(v.0 as usize) else { return format!("v{}: <missing>", v.0) };
        let ty = if inst.is_bool { format!("{} bool", inst.ty.detail) } else { inst.ty.to_string() };
        let args = |typed: bool| {
            inst.args
                .iter()
                .map(|a| if typed { self.typed_val(*a) } else { self.val(*a) })
                .collect::<Vec<_>>()
                .join(", ")
        };
        let rhs = match &inst.op {
            Op::Const(c) => format!("const {c}"),
            Op::Load(s) => format!("load {}", self.slot_ref(*s)),
            Op::LoadElem(s) => format!("load {}[{}]", self.slot_ref(*s), args(false)),
            Op::Unary(UnOp::Neg) => format!("neg({})", args(true)),
            Op::Unary(UnOp::Not) => format!("not({})", args(true)),
            Op::Binary(b) => format!("{}({})", b.name(), args(true)),
            Op::Select => format!("select({})", args(false)),
            Op::Convert => format!("convert({})", args(true)),
            Op::MakeTriple => format!("triple({})", args(false)),
            Op::MakeMatrix => format!("matrix({})", args(false)),
            Op::FromSpace => format!("fromspace({})", args(false)),
            Op::Call { builtin, overload, outputs } => {
                let key = OVERLOADS.get(*overload as usize).map_or(builtin.name(), |o| o.key);
                let mut ins = inst.args.iter();
                let mut parts = Vec::new();
                for o in outputs {
                    match o {
                        Some(s) => parts.push(format!("out {}", self.slot_ref(*s))),
                        None => {
                            if let Some(a) = ins.next() {
                                parts.push(self.val(*a));
                            }
                        }
                    }
                }
                parts.extend(ins.map(|a| self.val(*a)));
                format!("call {key}({})", parts.join(", "))
            }
        };
        format!("v{}: {ty} = {rhs}", v.0)
    }

    fn block(&self, out: &mut String, b: &Block, depth: usize) -> fmt::Result {
        let pad = "  ".repeat(depth);
        for n in b {
            match n {
                Node::Inst(v) => writeln!(out, "{pad}{}", self.inst_text(*v))?,
                Node::Store { slot, index, value, .. } => match index {
                    None => writeln!(out, "{pad}store {} = {}", self.slot_ref(*slot), self.val(*value))?,
                    Some(i) => {
                        writeln!(out, "{pad}store {}[{}] = {}", self.slot_ref(*slot), self.val(*i), self.val(*value))?
                    }
                },
                Node::If { cond, then, otherwise } => {
                    writeln!(out, "{pad}if {} {{", self.val(*cond))?;
                    self.block(out, then, depth + 1)?;
                    if !otherwise.is_empty() {
                        writeln!(out, "{pad}}} else {{")?;
                        self.block(out, otherwise, depth + 1)?;
                    }
                    writeln!(out, "{pad}}}")?;
                }
                Node::Loop { header, cond, body, step } => {
                    writeln!(out, "{pad}loop {{")?;
                    if !header.is_empty() || cond.is_some() {
                        writeln!(out, "{pad}  header {{")?;
                        self.block(out, header, depth + 2)?;
                        writeln!(out, "{pad}  }} while {}", cond.map_or("forever".into(), |c| self.val(c)))?;
                    }
                    writeln!(out, "{pad}  body {{")?;
                    self.block(out, body, depth + 2)?;
                    writeln!(out, "{pad}  }}")?;
                    if !step.is_empty() {
                        writeln!(out, "{pad}  step {{")?;
                        self.block(out, step, depth + 2)?;
                        writeln!(out, "{pad}  }}")?;
                    }
                    writeln!(out, "{pad}}}")?;
                }
                Node::Break(n) => writeln!(out, "{pad}break {n}")?,
                Node::Continue(n) => writeln!(out, "{pad}continue {n}")?,
                Node::Return => writeln!(out, "{pad}return")?,
                Node::Frame(body) => {
                    writeln!(out, "{pad}frame {{")?;
                    self.block(out, body, depth + 1)?;
                    writeln!(out, "{pad}}}")?;
                }
                Node::Illuminance { category, position, cone, body } => {
                    let mut args = Vec::new();
                    if let Some(c) = category {
                        args.push(format!("category {}", self.val(*c)));
                    }
                    args.push(self.val(*position));
                    if let Some((a, b)) = cone {
                        args.push(format!("axis {}", self.val(*a)));
                        args.push(format!("angle {}", self.val(*b)));
                    }
                    writeln!(out, "{pad}illuminance({}) {{", args.join(", "))?;
                    self.block(out, body, depth + 1)?;
                    writeln!(out, "{pad}}}")?;
                }
                Node::Illuminate { position, cone, body } => {
                    let mut args = vec![self.val(*position)];
                    if let Some((a, b)) = cone {
                        args.push(format!("axis {}", self.val(*a)));
                        args.push(format!("angle {}", self.val(*b)));
                    }
                    writeln!(out, "{pad}illuminate({}) {{", args.join(", "))?;
                    self.block(out, body, depth + 1)?;
                    writeln!(out, "{pad}}}")?;
                }
                Node::Solar { cone, body } => {
                    let args = match cone {
                        Some((a, b)) => format!("axis {}, angle {}", self.val(*a), self.val(*b)),
                        None => String::new(),
                    };
                    writeln!(out, "{pad}solar({args}) {{")?;
                    self.block(out, body, depth + 1)?;
                    writeln!(out, "{pad}}}")?;
                }
            }
        }
        Ok(())
    }
}
