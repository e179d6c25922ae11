//! The generator's analyses, run once before any code is written: which values and slots are
//! scalars (uniform, `f64`-based) and which are lanes (`F`-based), and which `break`,
//! `continue` and `return` can be native Rust control flow instead of masks.

use super::{key, Gen, Repr};
use crate::ir::{Node, Op, Value};
use crate::types::{BaseType, Detail, Type};

#[derive(Clone, Copy, Debug)]
enum Enc {
    If(bool),
    Loop(usize),
    Frame(usize),
    Light,
    Region,
}

impl<'a> Gen<'a> {
    fn is_string(&self, t: Type) -> bool {
        t.base == BaseType::String
    }

    /// Scalar or lanes for every value and slot (optimistic scalar, lowered to a fixed point).
    pub(super) fn reprs(&mut self) {
        let f = self.f;
        for (i, s) in f.slots.iter().enumerate() {
            let varying = s.ty.detail == Detail::Varying && !self.is_string(s.ty);
            self.sr[i] = if varying { Repr::Lane } else { Repr::Scalar };
        }
        let mut stores: Vec<Vec<Value>> = vec![Vec::new(); f.slots.len()];
        let mut out_calls: Vec<Vec<Value>> = vec![Vec::new(); f.slots.len()];
        crate::ir::walk(&f.body, &mut |n| match n {
            Node::Store { slot, value, .. } => stores[slot.0 as usize].push(*value),
            Node::Inst(v) => {
                if let Op::Call { outputs, .. } = &f.inst(*v).op {
                    for s in outputs.iter().flatten() {
                        out_calls[s.0 as usize].push(*v);
                    }
                }
            }
            _ => {}
        });
        for (i, s) in stores.iter().enumerate() {
            self.stored[i] = !s.is_empty() || !out_calls[i].is_empty();
        }
        loop {
            let mut changed = false;
            for (i, inst) in f.insts.iter().enumerate() {
                if self.vr[i] == Repr::Lane {
                    continue;
                }
                let lane = if self.is_string(inst.ty) {
                    false
                } else {
                    inst.ty.detail == Detail::Varying
                        || inst
                            .args
                            .iter()
                            .any(|a| self.vr[a.0 as usize] == Repr::Lane && !self.is_string(f.inst(*a).ty))
                        || match &inst.op {
                            Op::Load(s) | Op::LoadElem(s) => self.sr[s.0 as usize] == Repr::Lane,
                            Op::Call { builtin, .. } => builtin.lane_only(),
                            _ => false,
                        }
                };
                if lane {
                    self.vr[i] = Repr::Lane;
                    changed = true;
                }
            }
            for s in 0..f.slots.len() {
                if self.sr[s] == Repr::Lane || self.is_string(f.slots[s].ty) {
                    continue;
                }
                if stores[s].iter().chain(&out_calls[s]).any(|v| self.vr[v.0 as usize] == Repr::Lane) {
                    self.sr[s] = Repr::Lane;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
    }

    pub(super) fn scalar_value(&self, v: Value) -> bool {
        self.vr[v.0 as usize] == Repr::Scalar
    }

    /// Which loops and frames run as Rust control flow, and which exits are Rust `break`s.
    pub(super) fn classify(&mut self) {
        let f = self.f;
        crate::ir::walk(&f.body, &mut |n| {
            if let Node::Loop { cond, .. } = n {
                let native = cond.is_none_or(|c| self.vr[c.0 as usize] == Repr::Scalar);
                self.loop_native.insert(key(n), native);
            }
            if let Node::Frame(_) = n {
                self.frame_native.insert(key(n), true);
            }
        });
        self.frame_native.insert(0, true);
        loop {
            let mut changed = false;
            let mut enc = vec![Enc::Frame(0)];
            let body = &f.body;
            self.classify_block(body, &mut enc, &mut changed);
            if !changed {
                break;
            }
        }
    }

    fn classify_block(&mut self, block: &'a [Node], enc: &mut Vec<Enc>, changed: &mut bool) {
        for n in block {
            match n {
                Node::If { cond, then, otherwise } => {
                    enc.push(Enc::If(self.scalar_value(*cond)));
                    self.classify_block(then, enc, changed);
                    self.classify_block(otherwise, enc, changed);
                    enc.pop();
                }
                Node::Loop { header, body, step, .. } => {
                    enc.push(Enc::Loop(key(n)));
                    self.classify_block(header, enc, changed);
                    self.classify_block(body, enc, changed);
                    self.classify_block(step, enc, changed);
                    enc.pop();
                }
                Node::Frame(b) => {
                    enc.push(Enc::Frame(key(n)));
                    self.classify_block(b, enc, changed);
                    enc.pop();
                }
                Node::Illuminance { body, .. } => {
                    enc.push(Enc::Light);
                    self.classify_block(body, enc, changed);
                    enc.pop();
                }
                Node::Illuminate { body, .. } | Node::Solar { body, .. } => {
                    enc.push(Enc::Region);
                    self.classify_block(body, enc, changed);
                    enc.pop();
                }
                Node::Break(_) | Node::Continue(_) | Node::Return => {
                    let (target, path) = Self::target(n, enc);
                    let path_native = path.iter().all(|e| match e {
                        Enc::If(s) => *s,
                        Enc::Loop(k) => self.loop_native.get(k).copied().unwrap_or(false),
                        _ => false,
                    });
                    let target_native = match target {
                        Some(Enc::Loop(k)) => {
                            if !path_native && self.loop_native.get(&k) == Some(&true) {
                                self.loop_native.insert(k, false);
                                *changed = true;
                            }
                            self.loop_native.get(&k).copied().unwrap_or(false)
                        }
                        Some(Enc::Frame(k)) => {
                            if !path_native && self.frame_native.get(&k) == Some(&true) {
                                self.frame_native.insert(k, false);
                                *changed = true;
                            }
                            self.frame_native.get(&k).copied().unwrap_or(false)
                        }
                        Some(Enc::Light) => true,
                        _ => false,
                    };
                    self.exit_native.insert(key(n), path_native && target_native);
                }
                Node::Inst(_) | Node::Store { .. } => {}
            }
        }
    }

    /// The construct an exit leaves and the constructs between it and the exit (innermost
    /// first). `None`: no target (the lanes just stop, as in the interpreter).
    fn target(n: &Node, enc: &[Enc]) -> (Option<Enc>, Vec<Enc>) {
        let mut path = Vec::new();
        match n {
            Node::Return => {
                for e in enc.iter().rev() {
                    match e {
                        Enc::Frame(_) | Enc::Light => return (Some(*e), path),
                        _ => path.push(*e),
                    }
                }
                (None, path)
            }
            Node::Break(level) | Node::Continue(level) => {
                let mut left = *level;
                for e in enc.iter().rev() {
                    match e {
                        Enc::Loop(_) | Enc::Light => {
                            if left == 0 {
                                return (Some(*e), path);
                            }
                            if matches!(e, Enc::Light) {
                                return (None, path);
                            }
                            left -= 1;
                            path.push(*e);
                        }
                        Enc::Frame(_) => return (None, path),
                        _ => path.push(*e),
                    }
                }
                (None, path)
            }
            _ => (None, path),
        }
    }

    /// True when the block (not counting nested frames' returns) holds an exit.
    pub(super) fn has_exit(block: &[Node]) -> bool {
        block.iter().any(|n| match n {
            Node::Break(_) | Node::Continue(_) | Node::Return => true,
            Node::Frame(b) => Self::has_break(b),
            Node::Illuminance { .. } => false,
            _ => n.blocks().iter().any(|b| Self::has_exit(b)),
        })
    }

    /// Breaks/continues anywhere (they may leave a frame as "no target").
    pub(super) fn has_break(block: &[Node]) -> bool {
        block.iter().any(|n| match n {
            Node::Break(_) | Node::Continue(_) => true,
            Node::Illuminance { .. } => false,
            _ => n.blocks().iter().any(|b| Self::has_break(b)),
        })
    }

    /// True when some exit in the block is a mask operation.
    pub(super) fn has_masked_exit(&self, block: &[Node]) -> bool {
        block.iter().any(|n| match n {
            Node::Break(_) | Node::Continue(_) | Node::Return => {
                !self.exit_native.get(&key(n)).copied().unwrap_or(false)
            }
            Node::Illuminance { .. } => false,
            _ => n.blocks().iter().any(|b| self.has_masked_exit(b)),
        })
    }
}
