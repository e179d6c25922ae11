//! The points entry ([`crate::abi::PointsFn`]): a loop over the packets of a point set around
//! the shade function, which is inlined into it.
//!
//! Called once per packet, the shade function reads the globals from the renderer's
//! `Globals` struct and writes the outputs to a buffer, and the Rust code around each call
//! fills the one and reads the other: stores and loads that the compiled build, whose shader
//! is inlined into the renderer's loop, keeps in registers. Here the loop is compiled with
//! the shader: each packet's varying globals are loaded from the caller's arrays and stored
//! into the context's `Globals` (where host callbacks that read the context find them), the
//! inlined shader's loads of them are forwarded from those stores, and the outputs go
//! straight from registers to the caller's arrays. What does not vary stays in the context's
//! `Globals` as the caller set it.

use super::{Cg, LIGHT_NAME, POINTS_NAME};
use crate::abi::{self, GLOBAL_VALUES};
use crate::JitError;
use inkwell::module::Linkage;
use inkwell::types::BasicType;
use inkwell::values::{BasicValue, FunctionValue, PointerValue};
use inkwell::{AddressSpace, IntPredicate};

impl<'c> Cg<'c, '_> {
    /// Builds the points entry around `shade` (the function [`Cg::generate`] made, which
    /// becomes internal and always inlined): `varying` has bit `k` set for each global
    /// component `k` (numbered as in [`abi::GLOBAL_ORDER`]) read from the caller's arrays;
    /// `outputs` is how many output components (`Ci`, then `Oi`) it writes.
    ///
    /// # Errors
    /// For dual-number variants (their globals carry derivatives the arrays do not).
    pub(crate) fn generate_points(
        &mut self,
        shade: FunctionValue<'c>,
        varying: u64,
        outputs: usize,
    ) -> Result<FunctionValue<'c>, JitError> {
        if self.t.dual {
            return Err(JitError("the points entry has no dual-number variants".into()));
        }
        shade.set_linkage(Linkage::Internal);
        super::always_inline(self.cx, shade);
        let i64t = self.cx.i64_type();
        let i32t = self.cx.i32_type();
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let f32pp = f32p.ptr_type(AddressSpace::default());
        let fty = self.cx.void_type().fn_type(
            &[
                i64t.into(),
                f32pp.into(),
                f32pp.into(),
                f32p.into(),
                self.i8p().into(),
                i64t.ptr_type(AddressSpace::default()).into(),
                f32p.into(),
            ],
            false,
        );
        let f = self.m.add_function(POINTS_NAME, fty, None);
        self.set_fn_attrs(f);
        let param = |k: u32| f.get_nth_param(k).expect("points entry parameter");
        let n = param(0).into_int_value();
        let (srcs, outs, g) =
            (param(1).into_pointer_value(), param(2).into_pointer_value(), param(3).into_pointer_value());
        let (ctx, host, params) = (param(4), param(5), param(6));
        let entry = self.cx.append_basic_block(f, "entry");
        let body = self.cx.append_basic_block(f, "packet");
        let exit = self.cx.append_basic_block(f, "exit");
        self.b.position_at_end(entry);

        // Every lane takes part.
        let lanes = self.t.lanes;
        let mask_t = if lanes == 1 { i32t.into() } else { i32t.vec_type(lanes).as_basic_type_enum() };
        let mbuf = self.b.build_alloca(mask_t, "mask").expect("alloca");
        let ones = if lanes == 1 {
            i32t.const_all_ones().into()
        } else {
            let all: Vec<_> = (0..lanes).map(|_| i32t.const_all_ones()).collect();
            inkwell::types::VectorType::const_vector(&all).as_basic_value_enum()
        };
        self.b.build_store(mbuf, ones).expect("store");
        let mbuf = self.b.build_pointer_cast(mbuf, i32t.ptr_type(AddressSpace::default()), "").expect("cast");
        let out_t = self.f32t.array_type(abi::OUTPUT_VALUES as u32 * self.stride());
        let obuf = self.b.build_alloca(out_t, "out").expect("alloca");
        if let Some(i) = obuf.as_instruction() {
            let _ = i.set_alignment(64);
        }
        let obuf = self.b.build_pointer_cast(obuf, f32p, "").expect("cast");
        let nth = |cg: &Self, base: PointerValue<'c>, k: u64, name: &str| {
            let p = unsafe { cg.b.build_gep(base, &[i64t.const_int(k, false)], "") }.expect("gep");
            cg.b.build_load(p, name).expect("load").into_pointer_value()
        };
        let comps: Vec<(u64, PointerValue<'c>)> = (0..GLOBAL_VALUES as u64)
            .filter(|k| varying >> k & 1 == 1)
            .map(|k| (k, nth(self, srcs, k, "src")))
            .collect();
        let dsts: Vec<PointerValue<'c>> = (0..outputs as u64).map(|k| nth(self, outs, k, "dst")).collect();
        let any = self.b.build_int_compare(IntPredicate::SGT, n, i64t.const_zero(), "").expect("cmp");
        self.b.build_conditional_branch(any, body, exit).expect("br");

        self.b.position_at_end(body);
        let j = self.b.build_phi(i64t, "packet").expect("phi");
        let jv = j.as_basic_value().into_int_value();
        let first = self.b.build_int_mul(jv, i64t.const_int(u64::from(lanes), false), "").expect("mul");
        let vt = self.vt();
        let at = |cg: &Self, base: PointerValue<'c>, off: inkwell::values::IntValue<'c>| {
            let p = unsafe { cg.b.build_gep(base, &[off], "") }.expect("gep");
            cg.b.build_pointer_cast(p, cg.ptr_ty(vt), "").expect("cast")
        };
        for &(k, src) in &comps {
            let v = self.b.build_load(at(self, src, first), "").expect("load");
            v.as_instruction_value().map(|i| i.set_alignment(4));
            let to = i64t.const_int(u64::from(self.layout.comp[k as usize]), false);
            let s = self.b.build_store(at(self, g, to), v).expect("store");
            let _ = s.set_alignment(4);
        }
        self.b
            .build_call(shade, &[g.into(), obuf.into(), mbuf.into(), ctx.into(), host.into(), params.into()], "")
            .expect("call");
        let stride = u64::from(self.stride());
        for (k, &dst) in dsts.iter().enumerate() {
            let v = self.b.build_load(at(self, obuf, i64t.const_int(k as u64 * stride, false)), "").expect("load");
            v.as_instruction_value().map(|i| i.set_alignment(4));
            let s = self.b.build_store(at(self, dst, first), v).expect("store");
            let _ = s.set_alignment(4);
        }
        let next = self.b.build_int_add(jv, i64t.const_int(1, false), "").expect("add");
        let more = self.b.build_int_compare(IntPredicate::SLT, next, n, "").expect("cmp");
        let end = self.b.get_insert_block().expect("block");
        self.b.build_conditional_branch(more, body, exit).expect("br");
        j.add_incoming(&[(&i64t.const_zero(), entry), (&next, end)]);

        self.b.position_at_end(exit);
        self.b.build_return(None).expect("ret");
        Ok(f)
    }

    /// The type of a light shader's direct entry ([`anysl_core::LightCode::entry`]):
    /// `void (float* ps, float* out, i32* mask, i8* ctx, i64* host, float* params)`.
    pub(crate) fn light_entry_type(&self) -> inkwell::types::FunctionType<'c> {
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let i64p = self.cx.i64_type().ptr_type(AddressSpace::default());
        let i32p = self.cx.i32_type().ptr_type(AddressSpace::default());
        self.cx
            .void_type()
            .fn_type(&[f32p.into(), f32p.into(), i32p.into(), self.i8p().into(), i64p.into(), f32p.into()], false)
    }

    /// Gives `f`, a declared light entry ([`Cg::light_entry_type`]), a body that calls the
    /// light entry at address `addr` with its arguments.
    pub(crate) fn define_as_call(&self, f: FunctionValue<'c>, addr: u64) {
        let bb = self.cx.append_basic_block(f, "entry");
        self.b.position_at_end(bb);
        let ptr = self.light_entry_type().ptr_type(AddressSpace::default());
        let p = self.b.build_int_to_ptr(self.cx.i64_type().const_int(addr, false), ptr, "").expect("inttoptr");
        let args: Vec<inkwell::values::BasicMetadataValueEnum<'c>> = f.get_param_iter().map(Into::into).collect();
        let callee = inkwell::values::CallableValue::try_from(p).expect("callable");
        self.b.build_call(callee, &args, "").expect("call");
        self.b.build_return(None).expect("ret");
    }

    /// Builds a light shader's direct entry around `shade` (which is always inlined into it):
    /// `(ps, out, mask, ctx, host, params)` — the surface points `ps` (three values one
    /// packet's width apart) become `P` in a globals block of zeros on the stack, as the
    /// interpreter's light context has it, and the rest goes to `shade` as it is. Compiled
    /// light loops call it per light ([`anysl_core::LightCode`]); LLVM forwards the zeros
    /// and `P` into the inlined code, so no globals block is left.
    pub(crate) fn generate_light_entry(&mut self, shade: FunctionValue<'c>) -> FunctionValue<'c> {
        super::always_inline(self.cx, shade);
        let i64t = self.cx.i64_type();
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let f = self.m.add_function(LIGHT_NAME, self.light_entry_type(), None);
        self.set_fn_attrs(f);
        let param = |k: u32| f.get_nth_param(k).expect("light entry parameter");
        let entry = self.cx.append_basic_block(f, "entry");
        self.b.position_at_end(entry);
        let stride = self.stride();
        let floats = self.layout.comp.iter().max().copied().unwrap_or(0) + stride;
        let gbuf = self.b.build_alloca(self.f32t.array_type(floats), "globals").expect("alloca");
        if let Some(i) = gbuf.as_instruction() {
            let _ = i.set_alignment(64);
        }
        let gbuf = self.b.build_pointer_cast(gbuf, f32p, "").expect("cast");
        let bytes = i64t.const_int(u64::from(floats) * 4, false);
        self.b.build_memset(gbuf, 64, self.cx.i8_type().const_zero(), bytes).expect("memset");
        let vt = self.vt();
        let at = |cg: &Self, base: PointerValue<'c>, off: u64| {
            let p = unsafe { cg.b.build_gep(base, &[i64t.const_int(off, false)], "") }.expect("gep");
            cg.b.build_pointer_cast(p, cg.ptr_ty(vt), "").expect("cast")
        };
        let ps = param(0).into_pointer_value();
        // `P` is the first triple of `abi::GLOBAL_ORDER`.
        for c in 0..3u64 {
            let v = self.b.build_load(at(self, ps, c * u64::from(stride)), "").expect("load");
            v.as_instruction_value().map(|i| i.set_alignment(4));
            let s = self.b.build_store(at(self, gbuf, u64::from(self.layout.comp[c as usize])), v).expect("store");
            let _ = s.set_alignment(4);
        }
        let args = [gbuf.into(), param(1).into(), param(2).into(), param(3).into(), param(4).into(), param(5).into()];
        self.b.build_call(shade, &args, "").expect("call");
        self.b.build_return(None).expect("ret");
        f
    }
}
