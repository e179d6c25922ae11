//! Light-call fusion, the code generation side: a `specular` call's light loop also sums
//! `diffuse(N)` (and `ambient()`), kept ([`LitMemo`]) for the `diffuse` and `ambient` calls
//! after it, which take the kept sums when their normal and mask are the same at run time;
//! an `ambient()` call followed by a `diffuse(N)` gets both sums from one renderer call.
//! Which `ambient()` calls have such a partner is an analysis of the IR
//! ([`anysl_rsl::passes::lights`]).

use super::value::{err, Repr, Val, R, S};
use super::{Cg, LitMemo, NormalKey};
use crate::rt::Host;
use anysl_rsl::builtins::Builtin;
use anysl_rsl::ir::{Op, Value};
use anysl_rsl::passes::lights::{calls_ambient, NormalSrc};
use inkwell::types::BasicTypeEnum;
use inkwell::values::{BasicValue, BasicValueEnum, IntValue};
use inkwell::IntPredicate;

impl<'c> Cg<'c, '_> {
    /// How many light sums beyond its own a `specular` call with `args` (N, V, roughness)
    /// returns: 1 (`diffuse(N)`), 2 (and `ambient()`, when the shader calls it), or `None`
    /// (dual numbers: the derivatives of the sums would have to be kept as well).
    pub(super) fn lit_sums(&self, args: &[S<'c>]) -> Option<u32> {
        if self.t.dual || args.len() != 7 {
            return None;
        }
        Some(if calls_ambient(self.func) { 2 } else { 1 })
    }

    /// Call `v`, with the light sums of `specular` kept for the `diffuse(N)` and `ambient()`
    /// calls after it ([`LitMemo`]).
    pub(super) fn lit_call(&mut self, v: Value, args: Vec<Val<'c>>) -> R<Val<'c>> {
        let builtin = match &self.func.inst(v).op {
            Op::Call { builtin, .. } => *builtin,
            _ => return self.emit_call(v, args),
        };
        let triple = |a: Option<&Val<'c>>| a.and_then(Self::plain_triple);
        match builtin {
            Builtin::Specular => {
                let n = triple(args.first());
                let key = self.normal_key(v);
                let r = self.emit_call(v, args)?;
                match (r, n) {
                    (Val::Num(c), Some(n)) if c.len() == 6 || c.len() == 9 => {
                        self.lit_store(&n, &c[3..], key);
                        Ok(Val::Num(c[..3].to_vec()))
                    }
                    (r, _) => Ok(r),
                }
            }
            Builtin::Diffuse | Builtin::Ambient => {
                let f = self.cur_fn();
                let n = if builtin == Builtin::Diffuse { triple(args.first()) } else { None };
                // The kept sums are tried only under the same mask as far as the code generator
                // can tell, and for `diffuse` only for a normal from the same source; the test at
                // run time decides.
                let mask_now = (self.st().mask, self.mask_stores.get());
                let (same_mask, same_normal) = match self.lit_key {
                    Some((key, p, k)) => {
                        ((p, k) == mask_now, n.is_some() && key.is_some() && key == self.normal_key(v))
                    }
                    None => (false, false),
                };
                let memo = match self.lit {
                    Some(m)
                        if m.f == f
                            && same_mask
                            && (same_normal || (builtin == Builtin::Ambient && m.amb.is_some())) =>
                    {
                        m
                    }
                    _ => {
                        return match (builtin == Builtin::Ambient).then(|| self.ambient_with_diffuse(v)).flatten() {
                            Some(r) => Ok(r),
                            None => self.emit_call(v, args),
                        }
                    }
                };
                // Where the kept sums do not apply at run time (another mask), the renderer's
                // loop: a compiled loop there too would add code to every fused call for a case
                // the usual shaders fold away.
                self.lit_guarded(memo, n.as_deref(), |cg| {
                    cg.lights_by_renderer = true;
                    let r = cg.emit_call(v, args);
                    cg.lights_by_renderer = false;
                    r
                })
            }
            _ => self.emit_call(v, args),
        }
    }

    /// The components of a triple without derivatives (a normal the light sums can be kept
    /// for).
    fn plain_triple(v: &Val<'c>) -> Option<Vec<S<'c>>> {
        match v {
            Val::Num(c) if c.len() == 3 && c.iter().all(|s| s.d.is_none()) => Some(c.clone()),
            _ => None,
        }
    }

    /// `ambient()` call `v` when a `diffuse(N)` follows it under the same mask
    /// ([`anysl_rsl::passes::lights::ambient_partners`]): one renderer call returns both sums
    /// (`diffuse` with `aux` 1), the diffuse sum is kept for the `diffuse(N)` call, which checks
    /// its normal and mask as after a `specular` ([`Cg::lit_guarded`]). `None`: emit the plain
    /// call.
    fn ambient_with_diffuse(&mut self, v: Value) -> Option<Val<'c>> {
        if self.t.dual {
            return None;
        }
        let (n, key) = match *self.amb_partner.get(&v)? {
            NormalSrc::Slot(s) => {
                (Self::plain_triple(&self.load_slot(s))?, NormalKey::Slot(s, self.slot_stores[s.0 as usize].get()))
            }
            NormalSrc::Value(a) => (Self::plain_triple(self.vals[a.0 as usize].as_ref()?)?, NormalKey::Value(a)),
        };
        let sums = self.light_call(Host::Diffuse, 1, &n, 6);
        self.lit_store(&n, &sums, Some(key));
        Some(Val::Num(sums[3..].to_vec()))
    }

    /// Where the normal argument of light call `v` comes from.
    fn normal_key(&self, v: Value) -> Option<NormalKey> {
        let a = *self.func.inst(v).args.first()?;
        Some(match self.func.inst(a).op {
            Op::Load(s) => NormalKey::Slot(s, self.slot_stores[s.0 as usize].get()),
            _ => NormalKey::Value(a),
        })
    }

    /// Keeps the sums `extra` (diffuse, then ambient if present) of a `specular(n, …)` call
    /// whose normal came from `key`.
    fn lit_store(&mut self, n: &[S<'c>], extra: &[S<'c>], key: Option<NormalKey>) {
        self.lit_key = Some((key, self.st().mask, self.mask_stores.get()));
        let f = self.cur_fn();
        let amb = extra.len() == 6;
        let memo = match self.lit {
            Some(m) if m.f == f && m.amb.is_some() == amb => m,
            _ => {
                let vt = self.vt();
                let slot = |cg: &Self| cg.entry_alloca(vt);
                let valid = self.entry_alloca(self.cx.bool_type().into());
                // `false` at entry: stored right after the alloca.
                let entry = f.get_first_basic_block().expect("entry");
                let tb = self.cx.create_builder();
                match valid.as_instruction_value().and_then(|i| i.get_next_instruction()) {
                    Some(i) => tb.position_before(&i),
                    None => tb.position_at_end(entry),
                }
                tb.build_store(valid, self.cx.bool_type().const_zero()).expect("store");
                let m = LitMemo {
                    f,
                    valid,
                    n: [slot(self), slot(self), slot(self)],
                    mask: self.entry_alloca(self.mty(false)),
                    diff: [slot(self), slot(self), slot(self)],
                    amb: amb.then(|| [slot(self), slot(self), slot(self)]),
                };
                self.lit = Some(m);
                m
            }
        };
        for c in 0..3 {
            self.b.build_store(memo.n[c], self.to(n[c], Repr::V).v).expect("store");
            self.b.build_store(memo.diff[c], self.to(extra[c], Repr::V).v).expect("store");
            if let Some(a) = memo.amb {
                self.b.build_store(a[c], self.to(extra[3 + c], Repr::V).v).expect("store");
            }
        }
        let m = self.splat_mask(self.load_mask(self.st().mask));
        self.b.build_store(memo.mask, m.v).expect("store");
        self.b.build_store(memo.valid, self.cx.bool_type().const_int(1, false)).expect("store");
    }

    /// `diffuse(n)` (`Some`) or `ambient()` (`None`): the sums `memo` kept when its normal
    /// and mask are this call's (bitwise, every lane), else `call`.
    fn lit_guarded(
        &mut self,
        memo: LitMemo<'c>,
        n: Option<&[S<'c>]>,
        call: impl FnOnce(&mut Self) -> R<Val<'c>>,
    ) -> R<Val<'c>> {
        let f = self.cur_fn();
        let all_eq = |cg: &Self, a: BasicValueEnum<'c>, b: BasicValueEnum<'c>| -> IntValue<'c> {
            let (a, b) = if a.get_type() == cg.vt() {
                let it: BasicTypeEnum<'c> = if cg.t.lanes == 1 {
                    cg.cx.i32_type().into()
                } else {
                    cg.cx.i32_type().vec_type(cg.t.lanes).into()
                };
                (cg.b.build_bit_cast(a, it, "").expect("bitcast"), cg.b.build_bit_cast(b, it, "").expect("bitcast"))
            } else {
                (a, b)
            };
            match (a, b) {
                (BasicValueEnum::IntValue(x), BasicValueEnum::IntValue(y)) => {
                    cg.b.build_int_compare(IntPredicate::EQ, x, y, "").expect("icmp")
                }
                (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => {
                    let e = cg.b.build_int_compare(IntPredicate::EQ, x, y, "").expect("icmp");
                    cg.call_intr("llvm.vector.reduce.and", &[e.get_type().into()], &[e.into()]).into_int_value()
                }
                _ => unreachable!("masks and floats"),
            }
        };
        let mut hit = self.b.build_load(memo.valid, "").expect("load").into_int_value();
        let m = self.splat_mask(self.load_mask(self.st().mask));
        let mm = self.b.build_load(memo.mask, "").expect("load");
        let e = all_eq(self, m.v, mm);
        hit = self.b.build_and(hit, e, "").expect("and");
        if let Some(n) = n {
            for (&nc, &slot) in n.iter().zip(&memo.n) {
                let v = self.to(nc, Repr::V).v;
                let kept = self.b.build_load(slot, "").expect("load");
                let e = all_eq(self, v, kept);
                hit = self.b.build_and(hit, e, "").expect("and");
            }
        }
        let kept = match n {
            Some(_) => memo.diff,
            None => memo.amb.expect("ambient kept"),
        };
        let hb = self.cx.append_basic_block(f, "lit.kept");
        let mb = self.cx.append_basic_block(f, "lit.call");
        let jb = self.cx.append_basic_block(f, "lit.join");
        self.b.build_conditional_branch(hit, hb, mb).expect("br");
        self.b.position_at_end(hb);
        let kv: Vec<BasicValueEnum<'c>> = kept.iter().map(|p| self.b.build_load(*p, "").expect("load")).collect();
        self.b.build_unconditional_branch(jb).expect("br");
        self.b.position_at_end(mb);
        let cv: Vec<BasicValueEnum<'c>> = match call(self)? {
            Val::Num(c) if c.len() == 3 => c.into_iter().map(|s| self.to(s, Repr::V).v).collect(),
            _ => return err("light sum of unexpected shape"),
        };
        let mb_end = self.b.get_insert_block().expect("bb");
        self.b.build_unconditional_branch(jb).expect("br");
        self.b.position_at_end(jb);
        Ok(Val::Num(
            (0..3)
                .map(|c| {
                    let phi = self.b.build_phi(self.vt(), "").expect("phi");
                    phi.add_incoming(&[(&kv[c], hb), (&cv[c], mb_end)]);
                    S { r: Repr::V, v: phi.as_basic_value(), d: None }
                })
                .collect(),
        ))
    }
}
