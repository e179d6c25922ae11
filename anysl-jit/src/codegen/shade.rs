//! The shade function: its signature and entry (the lane mask from the caller), the slots and
//! their initial values (globals from the renderer's `Globals` struct, parameters from the
//! instance or the run-time parameter block), the body, and the outputs written to the
//! caller's buffer.

use super::params::{param_block, slot_comps, slot_values};
use super::value::{Repr, Val, M, R, S};
use super::{Cg, FnState, SlotStore, SHADE_NAME};
use crate::abi::{self, GLOBAL_ORDER};
use anysl_rsl::ir::{self, Const, Global, Node, Op, SlotId, SlotKind};
use anysl_rsl::passes::Analyzed;
use anysl_rsl::types::{BaseType, Detail, Type};
use inkwell::attributes::AttributeLoc;
use inkwell::values::{BasicValue, BasicValueEnum, FunctionValue, PointerValue};
use inkwell::{AddressSpace, IntPredicate};

impl<'c> Cg<'c, '_> {
    /// Generates the shade function for `module`.
    ///
    /// # Errors
    /// On ops the JIT does not support.
    pub fn generate(&mut self, analyzed: &Analyzed, param_values: &[Const]) -> R<FunctionValue<'c>> {
        let module = analyzed.module();
        let func = self.func;
        self.inst_repr = func.insts.iter().map(|i| self.repr_of_inst(i)).collect();
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let i32p = self.cx.i32_type().ptr_type(AddressSpace::default());
        let i64p = self.cx.i64_type().ptr_type(AddressSpace::default());
        let fty = self
            .cx
            .void_type()
            .fn_type(&[f32p.into(), f32p.into(), i32p.into(), self.i8p().into(), i64p.into(), f32p.into()], false);
        let f = self.m.add_function(SHADE_NAME, fty, None);
        self.set_fn_attrs(f);
        let entry = self.cx.append_basic_block(f, "entry");
        self.b.position_at_end(entry);
        let g = f.get_nth_param(0).expect("g");
        let out = f.get_nth_param(1).expect("out").into_pointer_value();
        let maskp = f.get_nth_param(2).expect("mask").into_pointer_value();
        let params = f.get_nth_param(5).expect("params").into_pointer_value();
        let param_offsets = param_block(module, param_values).1;
        // Entry mask.
        let m0 = self.read_mask_lanes(maskp);
        let mask = self.new_mask(m0);
        self.st = Some(FnState {
            f,
            mask,
            loops: Vec::new(),
            rets: Vec::new(),
            ctx: f.get_nth_param(3).expect("ctx"),
            host: f.get_nth_param(4).expect("host"),
            g,
        });
        // Slots: a slot holds dual numbers when some load of it needs derivatives.
        let mut slot_dual = vec![false; func.slots.len()];
        ir::walk(&func.body, &mut |n| {
            if let Node::Inst(v) = n {
                let inst = func.inst(*v);
                if let Op::Load(s) | Op::LoadElem(s) = inst.op {
                    if inst.needs_derivs {
                        slot_dual[s.0 as usize] = true;
                    }
                }
            }
        });
        for (i, s) in func.slots.iter().enumerate() {
            let r = if s.ty.detail == Detail::Uniform {
                Repr::U
            } else if self.t.dual && slot_dual[i] {
                Repr::D
            } else {
                Repr::V
            };
            let is_str = s.ty.base == BaseType::String;
            let n = if is_str { 0 } else { slot_comps(s.ty) };
            let ty = self.fty(r);
            let ptrs = (0..n)
                .map(|_| {
                    let p = self.entry_alloca(ty);
                    let d = (r == Repr::D).then(|| (self.entry_alloca(ty), self.entry_alloca(ty)));
                    (p, d)
                })
                .collect();
            self.slots.push(SlotStore { r, ptrs, is_str });
        }
        if module.kind == ir::ShaderKind::Light && func.global_slot(Global::L).is_none() {
            let r = self.full();
            let ty = self.fty(r);
            let ptrs = (0..3)
                .map(|_| {
                    let p = self.entry_alloca(ty);
                    let d = (r == Repr::D).then(|| (self.entry_alloca(ty), self.entry_alloca(ty)));
                    (p, d)
                })
                .collect();
            let sid = SlotId(self.slots.len() as u32);
            self.slots.push(SlotStore { r, ptrs, is_str: false });
            self.slot_stores.push(std::cell::Cell::new(0));
            for k in 0..3 {
                self.store_comp(sid, k, self.fc(0.0), None);
            }
            self.light_l = Some(sid);
        }
        // Volume and imager shaders change what arrives: their `Ci`, `Oi` (and an imager's
        // `alpha`) start as the caller left them in the output buffer, where they also end.
        let incoming = matches!(module.kind, ir::ShaderKind::Volume | ir::ShaderKind::Imager);
        let incoming_at = |gl: Global| -> Option<(usize, usize)> {
            match gl {
                Global::Ci | Global::Oi if incoming => {
                    abi::OUTPUT_ORDER.iter().find(|(g, _)| *g == gl).map(|&(_, o)| (o, 3))
                }
                Global::Alpha if module.kind == ir::ShaderKind::Imager => Some((abi::IMAGER_ALPHA, 1)),
                _ => None,
            }
        };
        // Initial values: globals from the buffer, parameters from the instance, others 0.
        for (i, s) in func.slots.iter().enumerate() {
            let sid = SlotId(i as u32);
            let init: Val<'c> = match &s.kind {
                SlotKind::Global(gl) if incoming_at(*gl).is_some() => {
                    let (off, n) = incoming_at(*gl).expect("matched");
                    Val::Num((off..off + n).map(|k| self.read_out(out, k)).collect())
                }
                SlotKind::Global(gl) => {
                    let from = match gl {
                        Global::Oi => Some(Global::Os),
                        // A light shader runs with `P` = the surface point `Ps`.
                        Global::Ps => Some(Global::P),
                        g => GLOBAL_ORDER.iter().any(|(x, _)| x == g).then_some(*g),
                    };
                    match from {
                        Some(gg) => Val::Num(self.read_global(gg)),
                        None if *gl == Global::Ncomps => Val::Num(vec![self.fc(3.0)]),
                        None => Val::Num(vec![self.fc(0.0); slot_comps(s.ty).max(1)]),
                    }
                }
                SlotKind::Param(k) => match param_offsets.get(*k as usize).copied().flatten() {
                    Some(at) if self.t.runtime_params => self.param_from_block(params, at, slot_comps(s.ty).max(1)),
                    _ => {
                        let c = param_values
                            .get(*k as usize)
                            .cloned()
                            .unwrap_or_else(|| module.params[*k as usize].default.clone());
                        self.const_val(&c, s.ty)
                    }
                },
                SlotKind::Local => {
                    if s.ty.base == BaseType::String {
                        Val::Str(vec![String::new(); s.ty.array.unwrap_or(1) as usize])
                    } else {
                        Val::Num(vec![self.fc(0.0); slot_comps(s.ty).max(1)])
                    }
                }
            };
            // Unmasked initialization.
            match &init {
                Val::Num(c) => {
                    for k in 0..self.slots[i].ptrs.len() {
                        let x = c[k.min(c.len() - 1)];
                        self.store_comp(sid, k, x, None);
                    }
                }
                Val::Str(v) => {
                    self.strs.insert(i as u32, v.clone());
                }
                _ => {}
            }
        }
        // Nothing to do for no lanes.
        let body_bb = self.cx.append_basic_block(f, "body");
        let exit_bb = self.cx.append_basic_block(f, "exit");
        let any = self.any(m0);
        self.b.build_conditional_branch(any, body_bb, exit_bb).expect("br");
        self.b.position_at_end(body_bb);
        let ret = self.new_mask(self.no_lanes());
        self.st.as_mut().expect("st").rets.push(ret);
        self.block(&func.body)?;
        let after = self.b.get_insert_block().expect("bb");
        self.b.build_unconditional_branch(exit_bb).expect("br");
        let _ = after;
        self.b.position_at_end(exit_bb);
        // Outputs: `Ci`, `Oi`, and for displacement shaders `P`, `N` (the only ones read); a
        // light shader's `Cl` and `L` in the places of `Ci` and `Oi`.
        let outputs = if module.kind == ir::ShaderKind::Displacement { 4 } else { 2 };
        let mut order: Vec<(Global, usize)> = if module.kind == ir::ShaderKind::Light {
            vec![(Global::Cl, 0), (Global::L, 3)]
        } else {
            abi::OUTPUT_ORDER.into_iter().take(outputs).collect()
        };
        if module.kind == ir::ShaderKind::Imager {
            order.push((Global::Alpha, abi::IMAGER_ALPHA));
        }
        for (gl, off) in order {
            let gslot = match gl {
                Global::L => func.global_slot(gl).or(self.light_l),
                _ => func.global_slot(gl),
            };
            let vals = match gslot {
                Some(s) => match self.load_slot(s) {
                    Val::Num(c) => c,
                    _ => continue,
                },
                // What arrived stays in the buffer.
                None if incoming_at(gl).is_some() => continue,
                None => match gl {
                    Global::Ci | Global::Cl | Global::L => vec![self.fc(0.0); 3],
                    Global::Oi => self.read_global(Global::Os),
                    _ => self.read_global(gl),
                },
            };
            for (k, v) in vals.iter().enumerate().take(3) {
                self.write_out(out, off + k, *v);
            }
        }
        if self.t.output_params {
            for (k, off, n) in abi::output_params(module) {
                let p = &module.params[k];
                let vals = match self.load_slot(p.slot) {
                    Val::Num(c) => c,
                    _ => continue,
                };
                for (i, v) in vals.iter().enumerate().take(n) {
                    self.write_out(out, off + i, *v);
                }
            }
        }
        self.b.build_return(None).expect("ret");
        Ok(f)
    }

    pub(super) fn set_fn_attrs(&self, f: FunctionValue<'c>) {
        for (k, v) in &self.fn_attrs {
            f.add_attribute(AttributeLoc::Function, self.cx.create_string_attribute(k, v));
        }
    }

    pub(super) fn read_mask_lanes(&self, p: PointerValue<'c>) -> M<'c> {
        let i32t = self.cx.i32_type();
        if self.t.lanes == 1 {
            let x = self.b.build_load(p, "").expect("load").into_int_value();
            let v = self.b.build_int_compare(IntPredicate::NE, x, i32t.const_zero(), "").expect("cmp");
            return M { uni: false, v: v.into() };
        }
        let vt = i32t.vec_type(self.t.lanes);
        let vp = self.b.build_pointer_cast(p, vt.ptr_type(AddressSpace::default()), "").expect("cast");
        let ld = self.b.build_load(vp, "").expect("load");
        ld.as_instruction_value().map(|i| i.set_alignment(4));
        let v = self.b.build_int_compare(IntPredicate::NE, ld.into_vector_value(), vt.const_zero(), "").expect("cmp");
        M { uni: false, v: v.into() }
    }

    /// Reads a global's components from the renderer's `Globals` struct (full representation),
    /// at the offsets of [`Cg::layout`].
    pub(super) fn read_global(&self, g: Global) -> Vec<S<'c>> {
        let Some((_, off)) = GLOBAL_ORDER.iter().find(|(x, _)| *x == g) else {
            return vec![self.fc(0.0); 3];
        };
        let n = g.ty().base.components();
        let gp = self.st().g.into_pointer_value();
        let ld = |fo: u64| self.load_lanes(gp, fo);
        let [dx, dy] = self.layout.dual.map(u64::from);
        (0..n)
            .map(|k| {
                let base = u64::from(self.layout.comp[off + k]);
                let v = ld(base);
                let d = self.t.dual.then(|| (ld(base + dx), ld(base + dy)));
                S { r: self.full(), v, d }
            })
            .collect()
    }

    /// The lanes of one value at float offset `fo` from `base` (4-byte aligned).
    fn load_lanes(&self, base: PointerValue<'c>, fo: u64) -> BasicValueEnum<'c> {
        let p = unsafe { self.b.build_gep(base, &[self.cx.i64_type().const_int(fo, false)], "") }.expect("gep");
        let p = self.b.build_pointer_cast(p, self.ptr_ty(self.vt()), "").expect("cast");
        let v = self.b.build_load(p, "").expect("load");
        v.as_instruction_value().map(|i| i.set_alignment(4));
        v
    }

    /// Value `idx` of the output buffer (as [`Cg::write_out`] writes it), full representation.
    fn read_out(&self, out: PointerValue<'c>, idx: usize) -> S<'c> {
        let ld = |fo: u64| self.load_lanes(out, fo);
        let base = idx as u64 * self.stride() as u64;
        let lanes = u64::from(self.t.lanes);
        let d = self.t.dual.then(|| (ld(base + lanes), ld(base + 2 * lanes)));
        S { r: self.full(), v: ld(base), d }
    }

    fn write_out(&self, out: PointerValue<'c>, idx: usize, v: S<'c>) {
        let v = self.to(v, self.full());
        let vt = self.vt();
        let stride = self.stride() as u64;
        let st = |fo: u64, x: BasicValueEnum<'c>| {
            let p = unsafe { self.b.build_gep(out, &[self.cx.i64_type().const_int(fo, false)], "") }.expect("gep");
            let p = self.b.build_pointer_cast(p, self.ptr_ty(vt), "").expect("cast");
            let s = self.b.build_store(p, x).expect("store");
            let _ = s.set_alignment(4);
        };
        let base = idx as u64 * stride;
        st(base, v.v);
        if let Some((x, y)) = v.d {
            st(base + u64::from(self.t.lanes), x);
            st(base + 2 * u64::from(self.t.lanes), y);
        }
    }

    pub(super) fn const_val(&self, c: &Const, ty: Type) -> Val<'c> {
        if ty.base == BaseType::String {
            let (mut nums, mut strs) = (Vec::new(), Vec::new());
            c.flatten(&mut nums, &mut strs);
            return Val::Str(strs);
        }
        Val::Num(slot_values(c, ty).into_iter().map(|x| self.fc(x)).collect())
    }

    /// Parameter `k`'s value read from the run-time parameter block at `params` (uniform).
    fn param_from_block(&self, params: PointerValue<'c>, offset: usize, comps: usize) -> Val<'c> {
        Val::Num(
            (offset..offset + comps)
                .map(|at| {
                    let p = unsafe { self.b.build_gep(params, &[self.cx.i64_type().const_int(at as u64, false)], "") }
                        .expect("gep");
                    let v = self.b.build_load(p, "param").expect("load");
                    S { r: Repr::U, v, d: None }
                })
                .collect(),
        )
    }
}
