//! Structured control flow under masks, as the interpreter runs it: blocks (skipping the rest
//! when no lane is left), varying `if`s run arm by arm under their masks, uniform branches as
//! branches, loops with live, break and continue masks per level, `return` per inlined frame.

use super::value::Val;
use super::value::{err, R};
use super::Cg;
use anysl_rsl::ir::{self, Block, Global, Node, Value};
use inkwell::values::PointerValue;

impl<'c> Cg<'c, '_> {
    /// Does the block contain a break/continue/return (which may narrow the mask)?
    fn narrows(b: &Block) -> bool {
        let mut found = false;
        ir::walk(b, &mut |n| {
            if matches!(n, Node::Break(_) | Node::Continue(_) | Node::Return) {
                found = true;
            }
        });
        found
    }

    pub(super) fn block(&mut self, block: &Block) -> R<()> {
        let mut done: Option<inkwell::basic_block::BasicBlock<'c>> = None;
        for node in block {
            let stop = self.node(node)?;
            if stop {
                break;
            }
            let may_narrow = match node {
                Node::If { then, otherwise, .. } => Self::narrows(then) || Self::narrows(otherwise),
                Node::Loop { header, body, step, .. } => {
                    Self::narrows(header) || Self::narrows(body) || Self::narrows(step)
                }
                _ => false,
            };
            if may_narrow {
                // Skip the rest of the block when no lane is left.
                let d = *done.get_or_insert_with(|| self.cx.append_basic_block(self.st().f, "done"));
                let next = self.cx.append_basic_block(self.st().f, "go");
                let m = self.load_mask(self.st().mask);
                let any = self.any(m);
                self.b.build_conditional_branch(any, next, d).expect("br");
                self.b.position_at_end(next);
            }
        }
        if let Some(d) = done {
            self.b.build_unconditional_branch(d).expect("br");
            self.b.position_at_end(d);
        }
        Ok(())
    }

    /// Generates one node; returns true when the rest of the block is unreachable.
    fn node(&mut self, node: &Node) -> R<bool> {
        match node {
            Node::Inst(v) => self.inst(*v)?,
            Node::Store { slot, index, value, init } => {
                let val = self.val(*value)?;
                match index {
                    // A fresh slot's first value: no lane it leaves inactive is read later, so
                    // every lane is written. A merge would keep the slot's previous value alive
                    // — in a light loop, a loop-carried register per component of every
                    // variable declared in the body.
                    None if *init => self.store_val_under(*slot, &val, None),
                    None => self.store_val(*slot, &val),
                    Some(ix) => self.store_elem(*slot, *ix, &val)?,
                }
            }
            Node::If { cond, then, otherwise } => {
                let c = self.mask_of(*cond)?;
                let f = self.st().f;
                if c.uni {
                    let tb = self.cx.append_basic_block(f, "then");
                    let eb = self.cx.append_basic_block(f, "else");
                    let mb = self.cx.append_basic_block(f, "endif");
                    self.b.build_conditional_branch(c.v.into_int_value(), tb, eb).expect("br");
                    self.b.position_at_end(tb);
                    self.block(then)?;
                    self.b.build_unconditional_branch(mb).expect("br");
                    self.b.position_at_end(eb);
                    self.block(otherwise)?;
                    self.b.build_unconditional_branch(mb).expect("br");
                    self.b.position_at_end(mb);
                } else {
                    let m = self.load_mask(self.st().mask);
                    let mt = self.mand(m, c);
                    let me = self.mand(m, self.mnot(c));
                    let pt = self.new_mask(mt);
                    let pe = self.new_mask(me);
                    let saved = self.st().mask;
                    self.masked_region(pt, |cg| cg.block(then))?;
                    if !otherwise.is_empty() {
                        self.masked_region(pe, |cg| cg.block(otherwise))?;
                    }
                    let a = self.load_mask(pt);
                    let b = self.load_mask(pe);
                    self.st.as_mut().expect("st").mask = saved;
                    self.store_mask(saved, self.mor(a, b));
                }
            }
            Node::Loop { header, cond, body, step } => self.loop_(header, *cond, body, step)?,
            Node::Break(level) | Node::Continue(level) => {
                let is_break = matches!(node, Node::Break(_));
                let st = self.st().clone();
                let depth = st.loops.len();
                let m = self.load_mask(st.mask);
                if let Some(&(brk, cont)) = depth.checked_sub(1 + *level as usize).and_then(|i| st.loops.get(i)) {
                    let target = if is_break { brk } else { cont };
                    let old = self.load_mask(target);
                    self.store_mask(target, self.mor(old, m));
                }
                self.store_mask(st.mask, self.no_lanes());
                return Ok(true);
            }
            Node::Return => {
                let st = self.st().clone();
                let m = self.load_mask(st.mask);
                if let Some(&ret) = st.rets.last() {
                    let old = self.load_mask(ret);
                    self.store_mask(ret, self.mor(old, m));
                }
                self.store_mask(st.mask, self.no_lanes());
                return Ok(true);
            }
            Node::Frame(b) => {
                let ret = self.new_mask(self.no_lanes());
                let saved_loops = std::mem::take(&mut self.st.as_mut().expect("st").loops);
                self.st.as_mut().expect("st").rets.push(ret);
                self.block(b)?;
                let st = self.st.as_mut().expect("st");
                st.rets.pop();
                st.loops = saved_loops;
                let mp = self.st().mask;
                let m = self.load_mask(mp);
                let r = self.load_mask(ret);
                self.store_mask(mp, self.mor(m, r));
            }
            Node::Illuminance { category, position, cone, body } => {
                self.illuminance(*category, *position, *cone, body)?;
            }
            Node::Illuminate { position, cone, body } => self.light_stmt(Some(*position), *cone, body)?,
            Node::Solar { cone, body } => self.light_stmt(None, *cone, body)?,
        }
        Ok(false)
    }

    /// A light shader's `illuminate(from [, axis, angle])` (`from` given) or `solar([axis,
    /// angle])`, as the interpreter runs it: `L = Ps − from` (or the axis; zero without one)
    /// for the live lanes, then the body for the lanes inside the cone (`Cl` stays as it was
    /// for the others). `L` also goes to the hidden slot the light's output reads when the
    /// shader has no `L` variable of its own.
    fn light_stmt(&mut self, from: Option<Value>, cone: Option<(Value, Value)>, body: &Block) -> R<()> {
        let ps = match self.func.global_slot(Global::Ps) {
            Some(s) => match self.load_slot(s) {
                Val::Num(c) => c,
                _ => return err("Ps is not a point"),
            },
            None => self.read_global(Global::P),
        };
        let (l, lit) = match from {
            Some(from) => {
                let from = self.nums(from)?;
                let l: Vec<_> = (0..3).map(|k| self.sub(ps[k], from[k.min(from.len() - 1)])).collect();
                let lit = match cone {
                    Some((axis, angle)) => {
                        let c = self.cone_test(axis, angle)?;
                        Some(self.cone_test_contains(&c, &l))
                    }
                    None => None,
                };
                (l, lit)
            }
            None => {
                let axis = match cone {
                    Some((axis, _)) => self.nums(axis)?,
                    None => vec![self.fc(0.0); 3],
                };
                ((0..3).map(|k| axis[k.min(axis.len() - 1)]).collect(), None)
            }
        };
        let outer = self.st().mask;
        let m = self.load_mask(outer);
        for s in [self.func.global_slot(Global::L), self.light_l].into_iter().flatten() {
            for (c, &v) in l.iter().enumerate() {
                self.store_comp(s, c, v, Some(m));
            }
        }
        let inside = match lit {
            Some(lit) => self.mand(m, lit),
            None => m,
        };
        let p = self.new_mask(inside);
        self.masked_region(p, |cg| cg.block(body))?;
        // Lanes that left the body (`return`, `break`) are gone; those outside the cone stay.
        let after = self.load_mask(p);
        let rest = match lit {
            Some(lit) => self.mor(after, self.mand(m, self.mnot(lit))),
            None => after,
        };
        self.store_mask(outer, rest);
        Ok(())
    }

    /// Runs `f` with mask pointer `p` when some lane of it is set.
    fn masked_region(&mut self, p: PointerValue<'c>, f: impl FnOnce(&mut Self) -> R<()>) -> R<()> {
        let fnv = self.st().f;
        let run = self.cx.append_basic_block(fnv, "run");
        let skip = self.cx.append_basic_block(fnv, "skip");
        let m = self.load_mask(p);
        let any = self.any(m);
        self.b.build_conditional_branch(any, run, skip).expect("br");
        self.b.position_at_end(run);
        let saved = self.st().mask;
        self.st.as_mut().expect("st").mask = p;
        f(self)?;
        self.st.as_mut().expect("st").mask = saved;
        self.b.build_unconditional_branch(skip).expect("br");
        self.b.position_at_end(skip);
        Ok(())
    }

    fn loop_(&mut self, header: &Block, cond: Option<Value>, body: &Block, step: &Block) -> R<()> {
        let fnv = self.st().f;
        let outer = self.st().mask;
        let m = self.load_mask(outer);
        let live = self.new_mask(m);
        let exited = self.new_mask(self.no_lanes());
        let brk = self.new_mask(self.no_lanes());
        let cont = self.new_mask(self.no_lanes());
        let hb = self.cx.append_basic_block(fnv, "loop.header");
        let bb = self.cx.append_basic_block(fnv, "loop.body");
        let xb = self.cx.append_basic_block(fnv, "loop.exit");
        self.b.build_unconditional_branch(hb).expect("br");
        self.b.position_at_end(hb);
        self.st.as_mut().expect("st").mask = live;
        self.st.as_mut().expect("st").loops.push((brk, cont));
        self.block(header)?;
        match cond {
            Some(c) => {
                let c = self.mask_of(c)?;
                if c.uni {
                    // A uniform condition: all live lanes leave together.
                    let leave = self.cx.append_basic_block(fnv, "loop.leave");
                    self.b.build_conditional_branch(c.v.into_int_value(), bb, leave).expect("br");
                    self.b.position_at_end(leave);
                    let l = self.load_mask(live);
                    let e = self.load_mask(exited);
                    self.store_mask(exited, self.mor(e, l));
                    self.b.build_unconditional_branch(xb).expect("br");
                } else {
                    let l = self.load_mask(live);
                    let e = self.load_mask(exited);
                    self.store_mask(exited, self.mor(e, self.mand(l, self.mnot(c))));
                    let nl = self.mand(l, c);
                    self.store_mask(live, nl);
                    let any = self.any(self.splat_mask(nl));
                    self.b.build_conditional_branch(any, bb, xb).expect("br");
                }
            }
            None => {
                let l = self.load_mask(live);
                let any = self.any(l);
                self.b.build_conditional_branch(any, bb, xb).expect("br");
            }
        }
        self.b.position_at_end(bb);
        self.block(body)?;
        let l = self.load_mask(live);
        let c = self.load_mask(cont);
        self.store_mask(live, self.mor(l, c));
        self.store_mask(cont, self.no_lanes());
        // The step runs when some lane is live.
        let sb = self.cx.append_basic_block(fnv, "loop.step");
        let any = self.any(self.load_mask(live));
        self.b.build_conditional_branch(any, sb, xb).expect("br");
        self.b.position_at_end(sb);
        self.block(step)?;
        let any = self.any(self.load_mask(live));
        self.b.build_conditional_branch(any, hb, xb).expect("br");
        self.b.position_at_end(xb);
        let st = self.st.as_mut().expect("st");
        st.loops.pop();
        st.mask = outer;
        let e = self.load_mask(exited);
        let k = self.load_mask(brk);
        self.store_mask(outer, self.mor(e, k));
        Ok(())
    }
}
