//! Control flow: blocks and statements, stores under the current mask, `if` (native or
//! masked), loops with their break/continue masks, `break`/`continue`/`return`, inlined
//! function frames, and the light loops (`illuminance`, `illuminate`, `solar`).

use super::{key, tri_ty, Gen, GenError, Repr};
use crate::ir::{Global, Node, ShaderKind, SlotId, Value};
use crate::types::BaseType;

/// A native (Rust control flow) or masked construct that exits target.
#[derive(Clone, Debug)]
pub(super) enum LoopCtx {
    Native { brk: String, cont: String },
    Masked { brk: String, cont: String },
    Light { brk: String },
}

#[derive(Clone, Debug)]
pub(super) enum FrameCtx {
    Native(String),
    Masked(String),
    LightBody,
}

impl<'a> Gen<'a> {
    pub(super) fn block(&mut self, block: &'a [Node]) -> Result<(), GenError> {
        for n in block {
            if let Some(sp) = self.node_span(n) {
                if !matches!(n, Node::Inst(v) if self.consts[v.0 as usize].is_some()) {
                    self.source_comment(sp);
                }
            }
            self.node(n)?;
        }
        Ok(())
    }

    fn node(&mut self, n: &'a Node) -> Result<(), GenError> {
        match n {
            Node::Inst(v) => self.inst(*v),
            Node::Store { slot, index, value, .. } => {
                self.store(*slot, *index, *value);
                Ok(())
            }
            Node::If { cond, then, otherwise } => self.if_(*cond, then, otherwise),
            Node::Loop { header, cond, body, step } => self.loop_(n, header, *cond, body, step),
            Node::Break(_) | Node::Continue(_) | Node::Return => {
                self.exit(n);
                Ok(())
            }
            Node::Frame(b) => self.frame(n, b),
            Node::Illuminance { category, position, cone, body } => self.illuminance(*category, *position, *cone, body),
            Node::Illuminate { position, cone, body } => self.light_region(Some(*position), *cone, body),
            Node::Solar { cone, body } => self.light_region(None, *cone, body),
        }
    }

    fn store(&mut self, slot: SlotId, index: Option<Value>, value: Value) {
        let s = slot;
        let var = self.slot_var(s);
        let r = self.sr[s.0 as usize];
        let st = self.f.slot(s).ty;
        if st.base == BaseType::String {
            let v = self.val(value, Repr::Scalar);
            let guard = if self.full { String::new() } else { format!("if {}.any() ", self.mask) };
            match index {
                None if st.array.is_some() => self.line(&format!("{guard}{{ {var} = {v}.clone(); }}")),
                None => self.line(&format!("{guard}{{ {var} = {v}.to_string(); }}")),
                Some(i) => {
                    let n = st.array.unwrap_or(1);
                    let iv = self.val(i, Repr::Scalar);
                    let iv = if self.scalar_value(i) { iv } else { format!("{}.lane(0)", self.val(i, Repr::Lane)) };
                    self.line(&format!(
                        "{guard}{{ {var}[(({iv}).max(0.0) as usize).min({})] = {v}.to_string(); }}",
                        n.saturating_sub(1)
                    ));
                }
            }
            return;
        }
        match index {
            None => {
                let v = self.store_value(value, s, false);
                self.assign(&var, &v, r);
            }
            Some(i) => {
                let n = st.array.unwrap_or(1);
                let v = self.store_value(value, s, true);
                let tmp = self.fresh("x");
                self.line(&format!("let {tmp} = {v};"));
                if self.scalar_value(i) && (r == Repr::Scalar || self.full) {
                    let iv = self.val(i, Repr::Scalar);
                    self.line(&format!(
                        "{{ let i = ({iv}).floor(); if i >= 0.0 && i < {n}.0 {{ {var}[i as usize] = {tmp}; }} }}"
                    ));
                } else if self.scalar_value(i) {
                    let iv = self.val(i, Repr::Scalar);
                    let m = self.mask.clone();
                    self.line(&format!(
                        "{{ let i = ({iv}).floor(); if i >= 0.0 && i < {n}.0 {{ let i = i as usize; {var}[i] = Blend::<F>::blend({m}, {tmp}, {var}[i]); }} }}"
                    ));
                } else {
                    let iv = self.val(i, Repr::Lane);
                    let m = self.mask.clone();
                    self.line(&format!(
                        "{{ let iv = ({iv}).floor(); for k in 0..{n} {{ let hit = {m} & iv.eq(F::c(k as f64)); if hit.any() {{ {var}[k] = Blend::<F>::blend(hit, {tmp}, {var}[k]); }} }} }}"
                    ));
                }
            }
        }
    }

    /// The value of `v` converted for a store into slot `s`.
    fn store_value(&self, v: Value, s: SlotId, elem: bool) -> String {
        let r = self.sr[s.0 as usize];
        let inst = self.f.inst(v);
        let st = if elem { self.f.slot(s).ty.element() } else { self.f.slot(s).ty };
        if inst.is_bool && !st.base.is_triple() {
            let b = self.val(v, r);
            return if r == Repr::Scalar {
                format!("if {b} {{ 1.0_f64 }} else {{ 0.0_f64 }}")
            } else {
                format!("F::select({b}, F::c(1.0), F::c(0.0))")
            };
        }
        let e = self.val(v, r);
        if inst.ty.base == BaseType::Float && st.base.is_triple() && inst.ty.array.is_none() {
            return format!("{}::splat({e})", tri_ty(st.base));
        }
        if inst.ty.base.is_triple()
            && st.base.is_triple()
            && (inst.ty.base == BaseType::Color) != (st.base == BaseType::Color)
        {
            return if st.base == BaseType::Color { format!("({e}).to_color()") } else { format!("({e}).to_vec()") };
        }
        e
    }

    /// `slot = value` under the current mask (`value` already in the slot's representation).
    pub(super) fn assign(&mut self, var: &str, value: &str, r: Repr) {
        if r == Repr::Scalar || self.full {
            self.line(&format!("{var} = {value};"));
        } else {
            self.line(&format!("{var} = Blend::<F>::blend({}, {value}, {var});", self.mask));
        }
    }

    pub(super) fn exec_mut(&self) -> String {
        if self.full && self.mask == "m0" && !self.in_closure {
            "e".into()
        } else {
            format!("&mut Exec::with_mask({})", self.mask)
        }
    }

    fn if_(&mut self, cond: Value, then: &'a [Node], otherwise: &'a [Node]) -> Result<(), GenError> {
        if self.scalar_value(cond) {
            let c = self.val(cond, Repr::Scalar);
            self.line(&format!("if {c} {{"));
            self.ind += 1;
            let f0 = self.full;
            self.block(then)?;
            let f1 = self.full;
            self.full = f0;
            self.ind -= 1;
            if otherwise.is_empty() {
                self.line("}");
            } else {
                self.line("} else {");
                self.ind += 1;
                self.block(otherwise)?;
                self.ind -= 1;
                self.line("}");
            }
            self.full = f1 && self.full;
            return Ok(());
        }
        let c = self.val(cond, Repr::Lane);
        let mt = self.fresh("m");
        let me = self.fresh("m");
        let m = self.mask.clone();
        self.line(&format!("let mut {mt} = {m} & {c};"));
        let exits = Self::has_exit(then) || Self::has_exit(otherwise);
        if !otherwise.is_empty() || exits {
            self.line(&format!("let mut {me} = {m} & !{c};"));
        }
        let f0 = self.full;
        self.full = false;
        self.mask = mt.clone();
        self.line(&format!("if {mt}.any() {{"));
        self.ind += 1;
        self.block(then)?;
        self.ind -= 1;
        self.line("}");
        if !otherwise.is_empty() {
            self.mask = me.clone();
            self.line(&format!("if {me}.any() {{"));
            self.ind += 1;
            self.block(otherwise)?;
            self.ind -= 1;
            self.line("}");
        }
        self.mask = m.clone();
        self.full = f0;
        if exits {
            self.line(&format!("{m} = {mt} | {me};"));
            self.full = false;
        }
        Ok(())
    }

    fn loop_(
        &mut self,
        n: &'a Node,
        header: &'a [Node],
        cond: Option<Value>,
        body: &'a [Node],
        step: &'a [Node],
    ) -> Result<(), GenError> {
        let native = self.loop_native.get(&key(n)).copied().unwrap_or(false);
        if native {
            let l = self.fresh("'l");
            let c = self.fresh("'c");
            if self.has_masked_exit(header) || self.has_masked_exit(body) || self.has_masked_exit(step) {
                self.full = false;
            }
            self.line(&format!("{l}: loop {{"));
            self.ind += 1;
            self.block(header)?;
            if let Some(cv) = cond {
                let e = self.val(cv, Repr::Scalar);
                self.line(&format!("if !{e} {{ break {l}; }}"));
            }
            self.line(&format!("{c}: {{"));
            self.ind += 1;
            self.frames.last_mut().expect("frame").1.push(LoopCtx::Native { brk: l.clone(), cont: c.clone() });
            self.block(body)?;
            self.frames.last_mut().expect("frame").1.pop();
            self.ind -= 1;
            self.line("}");
            self.block(step)?;
            self.ind -= 1;
            self.line("}");
            return Ok(());
        }
        let m = self.mask.clone();
        let live = self.fresh("m");
        let exited = self.fresh("exited");
        let brk = self.fresh("brk");
        let cont = self.fresh("cont");
        let it = self.fresh("iters");
        self.line("{");
        self.ind += 1;
        self.line(&format!("let mut {live} = {m};"));
        self.line(&format!("let mut {exited} = no;"));
        self.line(&format!("let mut {brk} = no;"));
        self.line(&format!("let mut {cont} = no;"));
        self.line(&format!("let mut {it} = 0usize;"));
        self.line("loop {");
        self.ind += 1;
        let f0 = self.full;
        self.full = false;
        self.mask = live.clone();
        self.block(header)?;
        if let Some(cv) = cond {
            let c = self.val(cv, Repr::Lane);
            self.line(&format!("{exited} = {exited} | ({live} & !{c});"));
            self.line(&format!("{live} = {live} & {c};"));
        }
        self.line(&format!("if {live}.none() {{ break; }}"));
        self.frames.last_mut().expect("frame").1.push(LoopCtx::Masked { brk: brk.clone(), cont: cont.clone() });
        self.block(body)?;
        self.frames.last_mut().expect("frame").1.pop();
        self.mask = live.clone();
        self.line(&format!("{live} = {live} | {cont};"));
        self.line(&format!("{cont} = no;"));
        self.block(step)?;
        self.line(&format!("{it} += 1;"));
        self.line(&format!(
            "if <F::Mask as Mask>::THREE_VALUED && {it} > {}::INTERVAL_LOOP_LIMIT {{ {exited} = {exited} | {live}; break; }}",
            self.k
        ));
        self.ind -= 1;
        self.line("}");
        self.mask = m.clone();
        self.full = f0;
        self.line(&format!("{m} = {exited} | {brk};"));
        if Self::has_exit(header) || Self::has_exit(body) || Self::has_exit(step) {
            // Lanes that returned (or left outer loops) are not back.
            self.full = false;
        }
        self.ind -= 1;
        self.line("}");
        Ok(())
    }

    fn exit(&mut self, n: &Node) {
        let native = self.exit_native.get(&key(n)).copied().unwrap_or(false);
        let m = self.mask.clone();
        let kill = format!("{m} = no;");
        let (frame, loops) = self.frames.last().cloned().expect("frame");
        let target_loop = |level: u32| -> Option<LoopCtx> {
            let l = loops.len().checked_sub(1 + level as usize)?;
            loops.get(l).cloned()
        };
        match n {
            Node::Return => match frame {
                FrameCtx::Native(l) if native => self.line(&format!("break {l};")),
                FrameCtx::LightBody if native => self.line("return;"),
                FrameCtx::Masked(r) => {
                    self.line(&format!("{r} = {r} | {m};"));
                    self.line(&kill);
                    self.full = false;
                }
                _ => {
                    self.line(&kill);
                    self.full = false;
                }
            },
            Node::Break(level) | Node::Continue(level) => {
                let is_break = matches!(n, Node::Break(_));
                match target_loop(*level) {
                    Some(LoopCtx::Native { brk, cont }) if native => {
                        self.line(&format!("break {};", if is_break { brk } else { cont }));
                    }
                    Some(LoopCtx::Light { brk }) => {
                        if is_break {
                            self.line(&format!("{brk} = {brk} | {m};"));
                        }
                        if native {
                            self.line("return;");
                        } else {
                            self.line(&kill);
                            self.full = false;
                        }
                    }
                    Some(LoopCtx::Masked { brk, cont }) => {
                        let t = if is_break { brk } else { cont };
                        self.line(&format!("{t} = {t} | {m};"));
                        self.line(&kill);
                        self.full = false;
                    }
                    _ => {
                        self.line(&kill);
                        self.full = false;
                    }
                }
            }
            _ => {}
        }
    }

    fn frame(&mut self, n: &'a Node, body: &'a [Node]) -> Result<(), GenError> {
        let native = self.frame_native.get(&key(n)).copied().unwrap_or(true);
        let f0 = self.full;
        if native {
            let l = self.fresh("'f");
            self.line(&format!("{l}: {{"));
            self.ind += 1;
            self.frames.push((FrameCtx::Native(l), Vec::new()));
            // A trailing `return` is the end of the block.
            let body = match body.last() {
                Some(Node::Return) => &body[..body.len() - 1],
                _ => body,
            };
            self.block(body)?;
            self.frames.pop();
            self.ind -= 1;
            self.line("}");
        } else {
            let r = self.fresh("ret");
            self.line("{");
            self.ind += 1;
            self.line(&format!("let mut {r} = no;"));
            self.frames.push((FrameCtx::Masked(r.clone()), Vec::new()));
            self.block(body)?;
            self.frames.pop();
            let m = self.mask.clone();
            self.line(&format!("{m} = {m} | {r};"));
            self.ind -= 1;
            self.line("}");
        }
        self.full = f0 && !Self::has_break(body);
        Ok(())
    }

    fn illuminance(
        &mut self,
        category: Option<Value>,
        position: Value,
        cone: Option<(Value, Value)>,
        body: &'a [Node],
    ) -> Result<(), GenError> {
        if self.in_closure {
            return Err(self.err(
                self.f.inst(position).span,
                "generated Rust cannot nest `illuminance` inside a light-loop body (the loop body is a closure that cannot use the shading context)",
            ));
        }
        if self.m.kind == ShaderKind::Light {
            return Ok(()); // a light shader has no lights to loop over (as in the interpreter)
        }
        let cat = category.map_or_else(|| "\"\"".to_string(), |c| self.val(c, Repr::Scalar));
        let p = self.val(position, Repr::Lane);
        let cone_e = match cone {
            Some((a, b)) => format!("Some(({}, {}))", self.val(a, Repr::Lane), self.val(b, Repr::Lane)),
            None => "None".into(),
        };
        let ex = self.exec_mut();
        let lbrk = self.fresh("lbrk");
        let lm = self.fresh("m");
        let lslot = self.f.global_slot(Global::L);
        let clslot = self.f.global_slot(Global::Cl);
        self.line("{");
        self.ind += 1;
        self.line(&format!("let mut {lbrk} = no;"));
        self.line(&format!(
            "ctx.illuminance({ex}, LightQuery::new({cat}, {p}, {cone_e}), |le: &mut Exec<F>, l: Vec3<F>, cl: Color<F>| {{"
        ));
        self.ind += 1;
        self.line(&format!("let mut {lm} = le.mask() & !{lbrk};"));
        self.line(&format!("if {lm}.none() {{ return; }}"));
        if let Some(s) = lslot {
            let v = self.slot_var(s);
            if self.sr[s.0 as usize] == Repr::Lane {
                self.line(&format!("{v} = l;"));
            }
        }
        if let Some(s) = clslot {
            let v = self.slot_var(s);
            if self.sr[s.0 as usize] == Repr::Lane {
                self.line(&format!("{v} = cl;"));
            }
        }
        let saved = (self.mask.clone(), self.full, self.in_closure);
        self.mask = lm;
        self.full = false;
        self.in_closure = true;
        self.frames.push((FrameCtx::LightBody, vec![LoopCtx::Light { brk: lbrk }]));
        let r = self.block(body);
        self.frames.pop();
        (self.mask, self.full, self.in_closure) = saved;
        r?;
        self.ind -= 1;
        self.line("});");
        self.ind -= 1;
        self.line("}");
        Ok(())
    }

    fn light_region(
        &mut self,
        position: Option<Value>,
        cone: Option<(Value, Value)>,
        body: &'a [Node],
    ) -> Result<(), GenError> {
        let ps = match self.f.global_slot(Global::Ps) {
            Some(s) if self.sr[s.0 as usize] == Repr::Lane => self.slot_var(s),
            _ => "ps".into(),
        };
        let cone_e = match cone {
            Some((a, b)) => format!("Some(({}, {}))", self.val(a, Repr::Lane), self.val(b, Repr::Lane)),
            None => "None".into(),
        };
        let call = match position {
            Some(p) => format!("illuminate({ps}, {}, {cone_e})", self.val(p, Repr::Lane)),
            None => {
                let axis = cone.map_or_else(|| "Vec3::zero()".to_string(), |(a, _)| self.val(a, Repr::Lane));
                format!("solar({axis})")
            }
        };
        let m = self.mask.clone();
        let bm = self.fresh("m");
        self.line("{");
        self.ind += 1;
        self.line(&format!("let (l, in_cone) = {call};"));
        match self.f.global_slot(Global::L) {
            Some(s) => {
                let v = self.slot_var(s);
                if self.sr[s.0 as usize] == Repr::Lane {
                    self.assign(&v, "l", Repr::Lane);
                }
            }
            None => self.assign("light_l", "l", Repr::Lane),
        }
        self.line(&format!("let mut {bm} = {m} & in_cone;"));
        self.line(&format!("lit = lit | {bm};"));
        self.line(&format!("if {bm}.any() {{"));
        self.ind += 1;
        let f0 = self.full;
        self.full = false;
        self.mask = bm;
        self.block(body)?;
        self.mask = m;
        self.full = f0;
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        Ok(())
    }
}
