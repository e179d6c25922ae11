//! Calls: into the runtime library (per packet when a variant shades several), into the
//! host (the renderer's callbacks), their buffers (spills, outputs, masks as `u32` lanes),
//! and the threaded form of an op — a call of its target-library function
//! `ar_<op>_<types>.<reprs>`, built on first use.

use super::math;
use super::value::{Repr, Shape, Val, M, R, S};
use super::Cg;
use crate::rt::Host;
use crate::rt::{self, RtKind};
use anysl_rsl::builtins::Builtin;
use anysl_rsl::ir::{Op, SlotId, UnOp, Value};
use anysl_rsl::types::{BaseType, Type};
use inkwell::attributes::{Attribute, AttributeLoc};
use inkwell::module::Linkage;
use inkwell::types::{BasicMetadataTypeEnum, BasicType, BasicTypeEnum, VectorType};
use inkwell::values::{BasicMetadataValueEnum, BasicValueEnum, CallableValue, FunctionValue, PointerValue};
use inkwell::AddressSpace;

impl<'c> Cg<'c, '_> {
    /// Calls runtime function `kind` with `aux`; `n_out` output values. Uniform when every
    /// argument is uniform and `force_varying` is false.
    /// Transcendentals of varying vectors are emitted inline instead ([`math`]).
    pub(super) fn rt_call(
        &mut self,
        kind: RtKind,
        aux: u32,
        args: &[S<'c>],
        n_out: usize,
        force_varying: bool,
    ) -> Vec<S<'c>> {
        if let Some(r) = math::MathFn::of(kind, aux).and_then(|f| self.math_inline(f, args)) {
            return vec![r];
        }
        self.rt_call_library(kind, aux, args, n_out, force_varying)
    }

    /// [`Cg::rt_call`] always as a call of the runtime library.
    fn rt_call_library(
        &mut self,
        kind: RtKind,
        aux: u32,
        args: &[S<'c>],
        n_out: usize,
        force_varying: bool,
    ) -> Vec<S<'c>> {
        let uni = !force_varying && args.iter().all(|a| a.r == Repr::U);
        let addr = if uni { (self.rt_u)(kind, aux) } else { (self.rt_v)(kind, aux) };
        let fnp = self.const_fn_ptr(addr);
        // The runtime library reads no mask (its functions compute every lane): none is
        // written for it.
        if !uni && self.t.native < self.t.lanes {
            if let Some(all) = self.rt_packets.and_then(|f| f(kind, aux)) {
                return self.callback_masked(self.const_fn_ptr(all), aux, args, n_out, false, None);
            }
            return self.callback_per_packet(fnp, aux, args, n_out);
        }
        self.callback_masked(fnp, aux, args, n_out, uni, None)
    }

    /// The packets of `native` lanes a vector of the variant's lanes is made of.
    pub(super) fn packets_of(&self, v: inkwell::values::VectorValue<'c>) -> Vec<inkwell::values::VectorValue<'c>> {
        let n = self.t.native;
        (0..v.get_type().get_size() / n)
            .map(|k| {
                let idx: Vec<_> = (k * n..(k + 1) * n).map(|i| self.i32c(u64::from(i))).collect();
                self.b
                    .build_shuffle_vector(v, v.get_type().get_undef(), VectorType::const_vector(&idx), "")
                    .expect("shuffle")
            })
            .collect()
    }

    /// The vector of `parts` one after the other (equal widths, a power of two of them).
    pub(super) fn concat(&self, parts: &[inkwell::values::VectorValue<'c>]) -> inkwell::values::VectorValue<'c> {
        let mut level = parts.to_vec();
        while level.len() > 1 {
            level = level
                .chunks(2)
                .map(|ab| {
                    let w = ab[0].get_type().get_size();
                    let idx: Vec<_> = (0..2 * w).map(|i| self.i32c(u64::from(i))).collect();
                    self.b.build_shuffle_vector(ab[0], ab[1], VectorType::const_vector(&idx), "").expect("shuffle")
                })
                .collect();
        }
        level[0]
    }

    /// A call of a runtime library function compiled for one packet, once per packet of a
    /// variant that shades several: each call gets its packet's lanes of the varying
    /// arguments (uniform arguments as they are), and the results are put back together.
    fn callback_per_packet(&mut self, fnp: PointerValue<'c>, aux: u32, args: &[S<'c>], n_out: usize) -> Vec<S<'c>> {
        assert!(!self.t.dual, "several packets per call of dual numbers");
        let arg_parts: Vec<Option<Vec<_>>> =
            args.iter().map(|a| (a.r != Repr::U).then(|| self.packets_of(a.v.into_vector_value()))).collect();
        let lanes = self.t.lanes;
        let mut outs: Vec<Vec<inkwell::values::VectorValue<'c>>> = vec![Vec::new(); n_out];
        for k in 0..(lanes / self.t.native) as usize {
            let args_k: Vec<S<'c>> = args
                .iter()
                .zip(&arg_parts)
                .map(|(a, p)| match p {
                    Some(p) => S { r: Repr::V, v: p[k].into(), d: None },
                    None => *a,
                })
                .collect();
            // One packet's widths for the buffers of this call.
            self.t.lanes = self.t.native;
            let r = self.callback_masked(fnp, aux, &args_k, n_out, false, None);
            self.t.lanes = lanes;
            for (o, v) in outs.iter_mut().zip(r) {
                o.push(v.v.into_vector_value());
            }
        }
        outs.iter().map(|parts| S { r: Repr::V, v: self.concat(parts).into(), d: None }).collect()
    }

    fn rt_fn_type(&self) -> inkwell::types::FunctionType<'c> {
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let i32p = self.cx.i32_type().ptr_type(AddressSpace::default());
        self.cx
            .void_type()
            .fn_type(&[self.i8p().into(), i32p.into(), f32p.into(), f32p.into(), self.cx.i32_type().into()], false)
    }

    pub(super) fn const_fn_ptr(&self, addr: usize) -> PointerValue<'c> {
        self.cx
            .i64_type()
            .const_int(addr as u64, false)
            .const_to_pointer(self.rt_fn_type().ptr_type(AddressSpace::default()))
    }

    pub(super) fn host_fn_ptr(&self, idx: Host, ty: inkwell::types::FunctionType<'c>) -> PointerValue<'c> {
        self.host_used.set(self.host_used.get() | 1 << idx as u64);
        let host = self.st().host.into_pointer_value();
        let slot =
            unsafe { self.b.build_gep(host, &[self.cx.i64_type().const_int(idx as u64, false)], "") }.expect("gep");
        let addr = self.b.build_load(slot, "").expect("load").into_int_value();
        self.b.build_int_to_ptr(addr, ty.ptr_type(AddressSpace::default()), "").expect("inttoptr")
    }

    /// Spills `vals` (each converted to the full varying representation, or uniform) to a
    /// buffer and returns a `float*` to it.
    pub(super) fn spill(&self, vals: &[S<'c>], uni: bool) -> PointerValue<'c> {
        let (elt, per): (BasicTypeEnum<'c>, usize) =
            if uni { (self.f32t.into(), 1) } else { (self.vt(), if self.t.dual { 3 } else { 1 }) };
        let n = (vals.len() * per).max(1) as u32;
        let buf = self.entry_alloca(elt.array_type(n).into());
        let mut k = 0u64;
        for &v in vals {
            let v = if uni { self.to(v, Repr::U) } else { self.to(v, self.full()) };
            let mut parts = vec![v.v];
            if let Some((x, y)) = v.d {
                parts.push(x);
                parts.push(y);
            }
            for p in parts {
                let ptr = unsafe {
                    self.b.build_gep(
                        buf,
                        &[self.cx.i64_type().const_zero(), self.cx.i64_type().const_int(k, false)],
                        "",
                    )
                }
                .expect("gep");
                self.b.build_store(ptr, p).expect("store");
                k += 1;
            }
        }
        self.b.build_pointer_cast(buf, self.f32t.ptr_type(AddressSpace::default()), "").expect("cast")
    }

    pub(super) fn unspill(&self, buf: PointerValue<'c>, n: usize, uni: bool) -> Vec<S<'c>> {
        let elt = if uni { BasicTypeEnum::from(self.f32t) } else { self.vt() };
        let p = self.b.build_pointer_cast(buf, self.ptr_ty(elt), "").expect("cast");
        let r = if uni { Repr::U } else { self.full() };
        let per = if r == Repr::D { 3 } else { 1 };
        (0..n)
            .map(|i| {
                let ld = |k: usize| {
                    let ptr = unsafe {
                        self.b.build_gep(p, &[self.cx.i64_type().const_int((i * per + k) as u64, false)], "")
                    }
                    .expect("gep");
                    self.b.build_load(ptr, "").expect("load")
                };
                let v = ld(0);
                let d = (per == 3).then(|| (ld(1), ld(2)));
                S { r, v, d }
            })
            .collect()
    }

    pub(super) fn out_buf(&self, n: usize, uni: bool) -> PointerValue<'c> {
        let (elt, per): (BasicTypeEnum<'c>, usize) =
            if uni { (self.f32t.into(), 1) } else { (self.vt(), if self.t.dual { 3 } else { 1 }) };
        let buf = self.entry_alloca(elt.array_type((n * per).max(1) as u32).into());
        self.b.build_pointer_cast(buf, self.f32t.ptr_type(AddressSpace::default()), "").expect("cast")
    }

    /// The current mask as `u32` lanes in memory.
    pub(super) fn mask_buf(&self) -> PointerValue<'c> {
        self.mask_buf_of(self.load_mask(self.st().mask))
    }

    /// Mask `m` as `u32` lanes in memory.
    pub(super) fn mask_buf_of(&self, m: M<'c>) -> PointerValue<'c> {
        let i32t = self.cx.i32_type();
        let (ty, v): (BasicTypeEnum<'c>, BasicValueEnum<'c>) = match m.v {
            BasicValueEnum::IntValue(x) => (i32t.into(), self.b.build_int_s_extend(x, i32t, "").expect("sext").into()),
            BasicValueEnum::VectorValue(x) => {
                let vt = i32t.vec_type(self.t.lanes);
                (vt.into(), self.b.build_int_s_extend(x, vt, "").expect("sext").into())
            }
            _ => panic!("mask"),
        };
        let buf = self.entry_alloca(ty);
        self.b.build_store(buf, v).expect("store");
        self.b.build_pointer_cast(buf, i32t.ptr_type(AddressSpace::default()), "").expect("cast")
    }

    fn callback(&mut self, fnp: PointerValue<'c>, aux: u32, args: &[S<'c>], n_out: usize, uni: bool) -> Vec<S<'c>> {
        let m = self.load_mask(self.st().mask);
        self.callback_masked(fnp, aux, args, n_out, uni, Some(m))
    }

    /// [`Cg::callback`] for the lanes of mask `m`; `None`: for a callee that reads no mask
    /// (a null pointer is passed).
    fn callback_masked(
        &mut self,
        fnp: PointerValue<'c>,
        aux: u32,
        args: &[S<'c>],
        n_out: usize,
        uni: bool,
        m: Option<M<'c>>,
    ) -> Vec<S<'c>> {
        let inp = self.spill(args, uni);
        let out = self.out_buf(n_out, uni);
        let mask = match m {
            Some(m) => self.mask_buf_of(m),
            None => self.cx.i32_type().ptr_type(AddressSpace::default()).const_null(),
        };
        self.call_rt_fn(fnp, mask, inp, out, aux);
        self.unspill(out, n_out, uni)
    }

    /// Calls a function of the runtime ABI (`ctx, mask, inputs, outputs, aux`).
    fn call_rt_fn(
        &self,
        fnp: PointerValue<'c>,
        mask: PointerValue<'c>,
        inp: PointerValue<'c>,
        out: PointerValue<'c>,
        aux: u32,
    ) {
        let ctx = self.st().ctx;
        let callee = CallableValue::try_from(fnp).expect("callable");
        self.b
            .build_call(
                callee,
                &[ctx.into(), mask.into(), inp.into(), out.into(), self.i32c(u64::from(aux)).into()],
                "",
            )
            .expect("call");
    }

    /// Emits call `v`: threaded (a call of its target-library function) or inline.
    pub(super) fn emit_call(&mut self, v: Value, args: Vec<Val<'c>>) -> R<Val<'c>> {
        if self.t.threaded {
            self.threaded(v, args)
        } else {
            let out = self.op_body(v, &args)?;
            self.finish_outputs(v, out)
        }
    }

    /// A matrix of the context's named spaces as 16 uniform values (`kind`: `rt::SPACE_*`,
    /// `names`: the space name, or both names of `rt::SPACE_BETWEEN`).
    pub(super) fn space_matrix(&mut self, kind: u32, names: &str) -> Vec<S<'c>> {
        let gs = self.b.build_global_string_ptr(names, "space").expect("string").as_pointer_value();
        let inp = self.b.build_pointer_cast(gs, self.f32t.ptr_type(AddressSpace::default()), "").expect("cast");
        let out = self.out_buf(16, true);
        let mask = self.mask_buf();
        let fnp = self.host_fn_ptr(Host::Space, self.rt_fn_type());
        self.call_rt_fn(fnp, mask, inp, out, kind | (names.len() as u32) << 2);
        self.unspill(out, 16, true)
    }

    pub(super) fn host_call(&mut self, idx: Host, aux: u32, args: &[S<'c>], n_out: usize) -> Vec<S<'c>> {
        let fnp = self.host_fn_ptr(idx, self.rt_fn_type());
        self.callback(fnp, aux, args, n_out, false)
    }

    /// Handles output arguments of calls: the op body returns `[result, outputs…]`.
    fn finish_outputs(&mut self, v: Value, mut out: Vec<Val<'c>>) -> R<Val<'c>> {
        let inst = self.func.inst(v);
        if let Op::Call { outputs, .. } = &inst.op {
            let outs: Vec<SlotId> = outputs.iter().flatten().copied().collect();
            let rest = out.split_off(1);
            for (s, val) in outs.iter().zip(rest) {
                if let Val::Void = val {
                    continue;
                }
                self.store_val(*s, &val);
            }
        }
        Ok(out.into_iter().next().unwrap_or(Val::Void))
    }

    /// Threaded form: the op's body lives in a target-library function called here.
    fn threaded(&mut self, v: Value, args: Vec<Val<'c>>) -> R<Val<'c>> {
        let inst = self.func.inst(v);
        // setcomp-like calls read the variable they update: inline.
        if let Op::Call { builtin, .. } = &inst.op {
            if matches!(builtin, Builtin::SetComp | Builtin::SetXComp | Builtin::SetYComp | Builtin::SetZComp) {
                let out = self.op_body(v, &args)?;
                return self.finish_outputs(v, out);
            }
        }
        let name = self.threaded_name(v, &args);
        let existing = self.m.get_function(&name);
        // Shapes of arguments → parameter list.
        let mut ptys: Vec<BasicMetadataTypeEnum<'c>> = vec![
            self.i8p().into(),
            self.cx.i64_type().ptr_type(AddressSpace::default()).into(),
            self.mty(false).into(),
            self.f32t.ptr_type(AddressSpace::default()).into(),
        ];
        let mut flat: Vec<BasicMetadataValueEnum<'c>> = Vec::new();
        for a in &args {
            match a {
                Val::Num(c) => {
                    for s in c {
                        ptys.push(s.v.get_type().into());
                        flat.push(s.v.into());
                        if let Some((x, y)) = s.d {
                            ptys.push(x.get_type().into());
                            ptys.push(y.get_type().into());
                            flat.push(x.into());
                            flat.push(y.into());
                        }
                    }
                }
                Val::Mask(m) => {
                    ptys.push(m.v.get_type().into());
                    flat.push(m.v.into());
                }
                _ => {}
            }
        }
        let (f, shape) = match existing {
            Some(f) => {
                let shape = self.shapes.get(&name).cloned().expect("shape");
                (f, shape)
            }
            None => {
                // Build the body in a fresh function.
                let caller_bb = self.b.get_insert_block().expect("bb");
                let saved_st = self.st.clone();
                let tmp_ty = self.cx.void_type().fn_type(&ptys, false);
                let tmp = self.m.add_function(&format!("{name}.tmp"), tmp_ty, Some(Linkage::Internal));
                let entry = self.cx.append_basic_block(tmp, "entry");
                self.b.position_at_end(entry);
                // Parameters back into values.
                let mut k = 4u32;
                let mut pargs = Vec::new();
                for a in &args {
                    pargs.push(match a {
                        Val::Num(c) => Val::Num(
                            c.iter()
                                .map(|s| {
                                    let v = tmp.get_nth_param(k).expect("p");
                                    k += 1;
                                    let d = s.d.map(|_| {
                                        let x = tmp.get_nth_param(k).expect("p");
                                        let y = tmp.get_nth_param(k + 1).expect("p");
                                        k += 2;
                                        (x, y)
                                    });
                                    S { r: s.r, v, d }
                                })
                                .collect(),
                        ),
                        Val::Mask(m) => {
                            let v = tmp.get_nth_param(k).expect("p");
                            k += 1;
                            Val::Mask(M { uni: m.uni, v })
                        }
                        other => other.clone(),
                    });
                }
                let maskp = self.entry_alloca(self.mty(false));
                self.b.build_store(maskp, tmp.get_nth_param(2).expect("mask")).expect("store");
                let mut stn = saved_st.clone().expect("st");
                stn.f = tmp;
                stn.mask = maskp;
                stn.ctx = tmp.get_nth_param(0).expect("ctx");
                stn.host = tmp.get_nth_param(1).expect("host");
                stn.g = tmp.get_nth_param(3).expect("g");
                self.st = Some(stn);
                let out = self.op_body(v, &pargs)?;
                // Return everything as one struct.
                let mut rvals: Vec<BasicValueEnum<'c>> = Vec::new();
                let mut shape = Vec::new();
                for o in &out {
                    match o {
                        Val::Num(c) => {
                            shape.push(Shape::Num(c.iter().map(|s| s.r).collect()));
                            for s in c {
                                rvals.push(s.v);
                                if let Some((x, y)) = s.d {
                                    rvals.push(x);
                                    rvals.push(y);
                                }
                            }
                        }
                        Val::Mask(m) => {
                            shape.push(Shape::Mask(m.uni));
                            rvals.push(m.v);
                        }
                        Val::Str(s) => shape.push(Shape::Str(s.clone())),
                        Val::Void => shape.push(Shape::Void),
                    }
                }
                let rtys: Vec<BasicTypeEnum<'c>> = rvals.iter().map(|v| v.get_type()).collect();
                let sty = self.cx.struct_type(&rtys, false);
                let fty = sty.fn_type(&ptys, false);
                let f = self.m.add_function(&name, fty, Some(Linkage::Internal));
                f.add_attribute(
                    AttributeLoc::Function,
                    self.cx.create_enum_attribute(Attribute::get_named_enum_kind_id("alwaysinline"), 0),
                );
                self.set_fn_attrs(f);
                // Move the blocks of tmp into f: simplest is to rebuild the return in tmp and
                // then replace tmp by f.
                let mut agg = sty.get_undef();
                for (i, v) in rvals.iter().enumerate() {
                    agg = self.b.build_insert_value(agg, *v, i as u32, "").expect("insert").into_struct_value();
                }
                self.b.build_return(Some(&agg)).expect("ret");
                // Transplant every basic block of tmp into f and remap the parameters.
                for (i, p) in tmp.get_param_iter().enumerate() {
                    unsafe { replace_uses(p, f.get_nth_param(i as u32).expect("param")) };
                }
                while let Some(bb) = tmp.get_first_basic_block() {
                    unsafe { transplant(bb, f) };
                }
                unsafe { tmp.delete() };
                self.shapes.insert(name.clone(), shape.clone());
                self.threaded_fns += 1;
                self.st = saved_st;
                self.b.position_at_end(caller_bb);
                (f, shape)
            }
        };
        // The call.
        let st = self.st().clone();
        let m = self.load_mask(st.mask);
        let mut cargs: Vec<BasicMetadataValueEnum<'c>> = vec![st.ctx.into(), st.host.into(), m.v.into(), st.g.into()];
        cargs.extend(flat);
        let ret = self.b.build_call(f, &cargs, "").expect("call").try_as_basic_value().basic();
        let mut k = 0u32;
        let mut take = |cg: &Self| {
            let x = cg.b.build_extract_value(ret.expect("struct").into_struct_value(), k, "").expect("extract");
            k += 1;
            x
        };
        let mut out = Vec::new();
        for sh in &shape {
            out.push(match sh {
                Shape::Num(rs) => Val::Num(
                    rs.iter()
                        .map(|&r| {
                            let v = take(self);
                            let d = (r == Repr::D).then(|| (take(self), take(self)));
                            S { r, v, d }
                        })
                        .collect(),
                ),
                Shape::Mask(uni) => Val::Mask(M { uni: *uni, v: take(self) }),
                Shape::Str(s) => Val::Str(s.clone()),
                Shape::Void => Val::Void,
            });
        }
        self.finish_outputs(v, out)
    }

    fn threaded_name(&self, v: Value, args: &[Val<'c>]) -> String {
        let inst = self.func.inst(v);
        let letter = |t: Type| match t.base {
            BaseType::Float => "f",
            BaseType::Color => "c",
            BaseType::Point => "p",
            BaseType::Vector => "v",
            BaseType::Normal => "n",
            BaseType::Matrix => "m",
            BaseType::String => "s",
            BaseType::Void => "x",
        };
        let op = match &inst.op {
            Op::Unary(UnOp::Neg) => "neg".to_string(),
            Op::Unary(UnOp::Not) => "not".to_string(),
            Op::Binary(b) => b.name().to_string(),
            Op::Select => "select".to_string(),
            Op::Convert => format!("to{}", letter(inst.ty)),
            Op::MakeTriple => format!("make{}", letter(inst.ty)),
            Op::MakeMatrix => "makem".to_string(),
            Op::FromSpace => format!("from{}", letter(inst.ty)),
            Op::Call { builtin, overload, .. } => format!("{builtin}{overload}"),
            _ => "op".to_string(),
        };
        let mut types = String::new();
        let mut reprs = String::new();
        let mut extra = String::new();
        for (a, val) in inst.args.iter().zip(args) {
            let t = self.func.inst(*a).ty;
            types.push_str(if self.func.inst(*a).is_bool { "b" } else { letter(t) });
            if let Some(n) = t.array {
                types.push_str(&n.to_string());
            }
            match val {
                Val::Num(c) => reprs.push(c.first().map_or('u', |s| s.r.letter())),
                Val::Mask(m) => reprs.push(if m.uni { 'u' } else { 'v' }),
                Val::Str(s) => {
                    reprs.push('s');
                    extra.push('.');
                    extra.extend(s.concat().chars().filter(char::is_ascii_alphanumeric));
                }
                Val::Void => reprs.push('x'),
            }
        }
        // A matrix `comp` reads its row and column at compile time: they are part of the body.
        if let Op::Call { builtin: Builtin::Comp, .. } = &inst.op {
            if self.func.inst(inst.args[0]).ty.base == BaseType::Matrix {
                for &a in &inst.args[1..] {
                    extra.push_str(&format!(".{}", self.const_index(a).unwrap_or(usize::MAX)));
                }
            }
        }
        let want = self.inst_repr[v.0 as usize].letter();
        let host = if self.lights_by_renderer { ".host" } else { "" };
        format!("ar_{op}_{types}.{reprs}{want}{extra}.{}{host}", letter(inst.ty))
    }
}

/// Replaces every use of `a` by `b`.
unsafe fn replace_uses<'c>(a: BasicValueEnum<'c>, b: BasicValueEnum<'c>) {
    use inkwell::values::AsValueRef;
    inkwell::llvm_sys::core::LLVMReplaceAllUsesWith(a.as_value_ref(), b.as_value_ref());
}

/// Moves basic block `bb` to the end of function `f`.
unsafe fn transplant<'c>(bb: inkwell::basic_block::BasicBlock<'c>, f: FunctionValue<'c>) {
    use inkwell::llvm_sys::core::{LLVMAppendExistingBasicBlock, LLVMRemoveBasicBlockFromParent};
    use inkwell::values::AsValueRef;
    let bbr = bb.as_mut_ptr();
    LLVMRemoveBasicBlockFromParent(bbr);
    LLVMAppendExistingBasicBlock(f.as_value_ref(), bbr);
}

/// The index in [`rt::COLOR_SPACES`] of colour space `name` (under any of its names).
pub(super) fn space_index(name: &str) -> Option<u32> {
    let cs = anysl_core::stdlib::ColorSpace::from_name(name)?;
    rt::COLOR_SPACES.iter().position(|n| anysl_core::stdlib::ColorSpace::from_name(n) == Some(cs)).map(|i| i as u32)
}
