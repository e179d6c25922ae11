//! `illuminance` loops: over lights described as data, a loop compiled here with the body
//! inline; otherwise the body as a function the renderer's light loop calls back, its
//! variables copied in and out of an environment block.

use super::value::{Repr, Val, M, R, S};
use super::{Cg, FnState};
use crate::rt::Host;
use anysl_rsl::ir::{self, Block, Global, Node, Op, SlotId, Value};
use inkwell::module::Linkage;
use inkwell::types::BasicTypeEnum;
use inkwell::values::{BasicValue, BasicValueEnum, CallableValue, PointerValue};
use inkwell::AddressSpace;
use std::collections::HashSet;

impl<'c> Cg<'c, '_> {
    pub(super) fn illuminance(
        &mut self,
        category: Option<Value>,
        position: Value,
        cone: Option<(Value, Value)>,
        body: &Block,
    ) -> R<()> {
        // Lights described as data (no category to select on: data carries none) run in a
        // loop compiled here, the body inline; the renderer's loop otherwise, on the other
        // branch (its environment — the body's variables copied in and out of a block the
        // renderer's callback reads — is built there only, so the shader's own variables stay
        // registers).
        let join_bb = if category.is_none() && !self.lights_by_renderer {
            let table = self.light_table();
            let data_bb = self.cx.append_basic_block(self.cur_fn(), "illuminance.data");
            let host_bb = self.cx.append_basic_block(self.cur_fn(), "illuminance.host");
            let join_bb = self.cx.append_basic_block(self.cur_fn(), "illuminance.join");
            let none = self.b.build_is_null(table.base, "").expect("isnull");
            self.b.build_conditional_branch(none, host_bb, data_bb).expect("br");
            self.b.position_at_end(data_bb);
            let saved_vals = self.vals.clone();
            self.illuminance_over_data(position, cone, body, table)?;
            self.vals = saved_vals;
            self.b.build_unconditional_branch(join_bb).expect("br");
            self.b.position_at_end(host_bb);
            Some(join_bb)
        } else {
            None
        };
        let func = self.func;
        // What the body reads from outside: values defined outside and variables.
        let mut defined = HashSet::new();
        ir::walk(body, &mut |n| {
            if let Node::Inst(v) = n {
                defined.insert(*v);
            }
        });
        let mut free: Vec<Value> = Vec::new();
        let mut used_slots: Vec<SlotId> = Vec::new();
        ir::walk(body, &mut |n| {
            let mut use_v = |v: Value| {
                if !defined.contains(&v) && !free.contains(&v) {
                    free.push(v);
                }
            };
            n.operands(&mut use_v);
            match n {
                Node::Inst(v) => {
                    let inst = func.inst(*v);
                    for &a in &inst.args {
                        use_v(a);
                    }
                    match &inst.op {
                        Op::Load(s) | Op::LoadElem(s) => used_slots.push(*s),
                        Op::Call { outputs, .. } => used_slots.extend(outputs.iter().flatten().copied()),
                        _ => {}
                    }
                }
                Node::Store { slot, .. } => used_slots.push(*slot),
                _ => {}
            }
        });
        for g in [Global::L, Global::Cl] {
            if let Some(s) = func.global_slot(g) {
                used_slots.push(s);
            }
        }
        used_slots.sort();
        used_slots.dedup();
        // Environment: pointers (i8*) to spilled free values, slot storage, the break mask,
        // ctx, host and globals.
        let mut env_ptrs: Vec<PointerValue<'c>> = Vec::new();
        let mut free_layout: Vec<(Value, Val<'c>)> = Vec::new();
        for &v in &free {
            let val = self.val(v)?;
            match &val {
                Val::Num(c) => {
                    for s in c {
                        for part in std::iter::once(s.v).chain(s.d.into_iter().flat_map(|(x, y)| [x, y])) {
                            let p = self.entry_alloca(part.get_type());
                            self.b.build_store(p, part).expect("store");
                            env_ptrs.push(p);
                        }
                    }
                }
                Val::Mask(m) => {
                    let p = self.entry_alloca(m.v.get_type());
                    self.b.build_store(p, m.v).expect("store");
                    env_ptrs.push(p);
                }
                _ => {}
            }
            free_layout.push((v, val));
        }
        // The body's variables: copies the callback reads and writes, copied back after the
        // call (the variables' own storage never escapes, so LLVM keeps them in registers).
        let mut copies: Vec<(PointerValue<'c>, PointerValue<'c>)> = Vec::new();
        for &s in &used_slots {
            for (p, d) in self.slots[s.0 as usize].ptrs.clone() {
                for q in std::iter::once(p).chain(d.into_iter().flat_map(|(x, y)| [x, y])) {
                    let t = self.entry_alloca(q.get_type().get_element_type().try_into().expect("a value type"));
                    let v = self.b.build_load(q, "").expect("load");
                    self.b.build_store(t, v).expect("store");
                    env_ptrs.push(t);
                    copies.push((q, t));
                }
            }
        }
        let brk = self.new_mask(self.no_lanes());
        env_ptrs.push(brk);
        let st = self.st().clone();
        let i8p = self.i8p();
        let env_t = i8p.array_type(env_ptrs.len() as u32 + 3);
        let env = self.entry_alloca(env_t.into());
        let put = |cg: &Self, k: usize, p: BasicValueEnum<'c>| {
            let slot = unsafe {
                cg.b.build_gep(env, &[cg.cx.i64_type().const_zero(), cg.cx.i64_type().const_int(k as u64, false)], "")
            }
            .expect("gep");
            let c = cg.b.build_pointer_cast(p.into_pointer_value(), i8p, "").expect("cast");
            cg.b.build_store(slot, c).expect("store");
        };
        for (k, p) in env_ptrs.iter().enumerate() {
            put(self, k, (*p).into());
        }
        let n = env_ptrs.len();
        put(self, n, st.ctx);
        put(self, n + 1, st.host);
        put(self, n + 2, st.g);
        // The body function.
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let i32p = self.cx.i32_type().ptr_type(AddressSpace::default());
        let body_ty = self
            .cx
            .void_type()
            .fn_type(&[i8p.ptr_type(AddressSpace::default()).into(), i32p.into(), f32p.into()], false);
        self.body_count += 1;
        let bf = self.m.add_function(
            &format!("anysl_illuminance_body.{}", self.body_count),
            body_ty,
            Some(Linkage::Internal),
        );
        self.set_fn_attrs(bf);
        let caller_bb = self.b.get_insert_block().expect("bb");
        let saved_vals = self.vals.clone();
        let saved_slots = self.slots.clone();
        let saved_st = self.st.clone();
        {
            let entry = self.cx.append_basic_block(bf, "entry");
            self.b.position_at_end(entry);
            let envp = bf.get_nth_param(0).expect("env").into_pointer_value();
            let get = |cg: &Self, k: usize, t: BasicTypeEnum<'c>| -> PointerValue<'c> {
                let slot =
                    unsafe { cg.b.build_gep(envp, &[cg.cx.i64_type().const_int(k as u64, false)], "") }.expect("gep");
                let p = cg.b.build_load(slot, "").expect("load").into_pointer_value();
                cg.b.build_pointer_cast(p, cg.ptr_ty(t), "").expect("cast")
            };
            let mut k = 0usize;
            for (v, val) in &free_layout {
                let nv = match val {
                    Val::Num(c) => Val::Num(
                        c.iter()
                            .map(|s| {
                                let mut ld = |t: BasicTypeEnum<'c>| {
                                    let p = get(self, k, t);
                                    k += 1;
                                    self.b.build_load(p, "").expect("load")
                                };
                                let v = ld(s.v.get_type());
                                let d = s.d.map(|(x, y)| (ld(x.get_type()), ld(y.get_type())));
                                S { r: s.r, v, d }
                            })
                            .collect(),
                    ),
                    Val::Mask(m) => {
                        let p = get(self, k, m.v.get_type());
                        k += 1;
                        Val::Mask(M { uni: m.uni, v: self.b.build_load(p, "").expect("load") })
                    }
                    other => other.clone(),
                };
                self.vals[v.0 as usize] = Some(nv);
            }
            for &s in &used_slots {
                let r = self.slots[s.0 as usize].r;
                let t = self.fty(r);
                let np: Vec<_> = (0..self.slots[s.0 as usize].ptrs.len())
                    .map(|_| {
                        let p = get(self, k, t);
                        k += 1;
                        let d = (r == Repr::D).then(|| {
                            let x = get(self, k, t);
                            let y = get(self, k + 1, t);
                            k += 2;
                            (x, y)
                        });
                        (p, d)
                    })
                    .collect();
                self.slots[s.0 as usize].ptrs = np;
            }
            let brk_in = get(self, k, self.mty(false));
            let ctx = get(self, n, self.cx.i8_type().into());
            let hostp = get(self, n + 1, self.cx.i64_type().into());
            let gp = get(self, n + 2, self.f32t.into());
            // live = mask & !broken
            let mp = bf.get_nth_param(1).expect("mask").into_pointer_value();
            let m_in = self.read_mask_lanes(mp);
            let broken = self.load_mask(brk_in);
            let live = self.mand(m_in, self.mnot(broken));
            let mask = self.new_mask(live);
            let cont = self.new_mask(self.no_lanes());
            let ret = self.new_mask(self.no_lanes());
            self.st = Some(FnState {
                f: bf,
                mask,
                loops: vec![(brk_in, cont)],
                rets: vec![ret],
                ctx: ctx.into(),
                host: hostp.into(),
                g: gp.into(),
            });
            let run = self.cx.append_basic_block(bf, "run");
            let exit = self.cx.append_basic_block(bf, "exit");
            let any = self.any(live);
            self.b.build_conditional_branch(any, run, exit).expect("br");
            self.b.position_at_end(run);
            // L and Cl, written for every lane.
            let lcl = bf.get_nth_param(2).expect("lcl").into_pointer_value();
            let lv = self.read_values(lcl, 6);
            for (gi, g) in [Global::L, Global::Cl].into_iter().enumerate() {
                if let Some(s) = func.global_slot(g) {
                    for c in 0..3 {
                        self.store_comp(s, c, lv[gi * 3 + c], None);
                    }
                }
            }
            self.block(body)?;
            self.b.build_unconditional_branch(exit).expect("br");
            self.b.position_at_end(exit);
            self.b.build_return(None).expect("ret");
        }
        self.vals = saved_vals;
        self.slots = saved_slots;
        self.st = saved_st;
        self.b.position_at_end(caller_bb);
        // The host call.
        let pos = self.nums(position)?;
        let mut args = pos.clone();
        if let Some((a, b)) = cone {
            args.extend(self.nums(a)?);
            args.extend(self.nums(b)?);
        }
        let cat = match category {
            Some(c) => self.str_of(c)?,
            None => String::new(),
        };
        let inp = self.spill(&args, false);
        let mask = self.mask_buf();
        let cat_g = if cat.is_empty() {
            i8p.const_null()
        } else {
            let gs = self.b.build_global_string_ptr(&cat, "cat").expect("string");
            gs.as_pointer_value()
        };
        let illum_ty = self.cx.void_type().fn_type(
            &[
                i8p.into(),
                i32p.into(),
                f32p.into(),
                self.cx.i32_type().into(),
                i8p.into(),
                self.cx.i64_type().into(),
                body_ty.ptr_type(AddressSpace::default()).into(),
                i8p.into(),
            ],
            false,
        );
        let fnp = self.host_fn_ptr(Host::Illuminance, illum_ty);
        let env_i8 = self.b.build_pointer_cast(env, i8p, "").expect("cast");
        let ctx = self.st().ctx;
        self.b
            .build_call(
                CallableValue::try_from(fnp).expect("callable"),
                &[
                    ctx.into(),
                    mask.into(),
                    inp.into(),
                    self.i32c(u64::from(cone.is_some())).into(),
                    cat_g.into(),
                    self.cx.i64_type().const_int(cat.len() as u64, false).into(),
                    bf.as_global_value().as_pointer_value().into(),
                    env_i8.into(),
                ],
                "",
            )
            .expect("call");
        for (q, t) in copies {
            let v = self.b.build_load(t, "").expect("load");
            self.b.build_store(q, v).expect("store");
        }
        if let Some(join) = join_bb {
            self.b.build_unconditional_branch(join).expect("br");
            self.b.position_at_end(join);
        }
        Ok(())
    }

    /// Reads `n` values from a buffer the host wrote (4-byte aligned, like every buffer the
    /// host passes: a vector load assuming the vector's alignment faults on AVX-512).
    fn read_values(&self, p: PointerValue<'c>, n: usize) -> Vec<S<'c>> {
        let vals = self.unspill(p, n, false);
        for s in &vals {
            for v in std::iter::once(s.v).chain(s.d.into_iter().flat_map(|(x, y)| [x, y])) {
                if let Some(i) = v.as_instruction_value() {
                    let _ = i.set_alignment(4);
                }
            }
        }
        vals
    }
}
