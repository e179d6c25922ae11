//! Variables in memory: the lane masks kept in entry-block `alloca`s (mem2reg makes them SSA),
//! the slots of the IR's variables (a pointer per component, and per derivative for dual
//! slots), masked stores that blend with the current mask, and array elements read and
//! written at run-time indices.

use super::value::{err, Repr, Val, M, R, S};
use super::Cg;
use anysl_rsl::ir::{Const, Op, SlotId, Value};
use anysl_rsl::types::Type;
use inkwell::values::{BasicValueEnum, PointerValue};
use inkwell::FloatPredicate;

impl<'c> Cg<'c, '_> {
    pub(super) fn load_mask(&self, p: PointerValue<'c>) -> M<'c> {
        M { uni: false, v: self.b.build_load(p, "").expect("load") }
    }
    pub(super) fn store_mask(&self, p: PointerValue<'c>, m: M<'c>) {
        self.mask_stores.set(self.mask_stores.get() + 1);
        let m = self.splat_mask(m);
        self.b.build_store(p, m.v).expect("store");
    }
    pub(super) fn new_mask(&self, init: M<'c>) -> PointerValue<'c> {
        let p = self.entry_alloca(self.mty(false));
        self.store_mask(p, init);
        p
    }
    pub(super) fn no_lanes(&self) -> M<'c> {
        M { uni: false, v: self.mty(false).const_zero() }
    }

    pub(super) fn load_slot(&self, s: SlotId) -> Val<'c> {
        let st = &self.slots[s.0 as usize];
        if st.is_str {
            return Val::Str(self.strs.get(&s.0).cloned().unwrap_or_default());
        }
        let comps = st
            .ptrs
            .iter()
            .map(|(p, d)| S {
                r: st.r,
                v: self.b.build_load(*p, "").expect("load"),
                d: d.map(|(x, y)| (self.b.build_load(x, "").expect("load"), self.b.build_load(y, "").expect("load"))),
            })
            .collect();
        Val::Num(comps)
    }

    /// Writes component `i` of slot `s` with `v` for the lanes in `m` (`None`: all lanes).
    pub(super) fn store_comp(&self, s: SlotId, i: usize, v: S<'c>, m: Option<M<'c>>) {
        let count = &self.slot_stores[s.0 as usize];
        count.set(count.get() + 1);
        let st = &self.slots[s.0 as usize];
        let (p, d) = st.ptrs[i];
        let v = self.to(v, st.r);
        let blend = |ptr: PointerValue<'c>, new: BasicValueEnum<'c>| {
            let nv = match m {
                Some(m) if st.r != Repr::U || m.uni => {
                    let m = if st.r == Repr::U { m } else { self.splat_mask(m) };
                    let old = self.b.build_load(ptr, "").expect("load");
                    self.sel_raw(m.v, new, old)
                }
                _ => new,
            };
            self.b.build_store(ptr, nv).expect("store");
        };
        blend(p, v.v);
        if let (Some((px, py)), Some((vx, vy))) = (d, v.d) {
            blend(px, vx);
            blend(py, vy);
        }
    }

    /// Masked store of a whole value.
    pub(super) fn store_val(&mut self, s: SlotId, v: &Val<'c>) {
        let m = if self.slots[s.0 as usize].r == Repr::U { None } else { Some(self.load_mask(self.st().mask)) };
        self.store_val_under(s, v, m);
    }

    /// [`Self::store_val`] under mask `m` (`None`: every lane).
    pub(super) fn store_val_under(&mut self, s: SlotId, v: &Val<'c>, m: Option<M<'c>>) {
        match v {
            Val::Num(c) => {
                let n = self.slots[s.0 as usize].ptrs.len();
                for i in 0..n {
                    let x = if c.len() == 1 { c[0] } else { c[i.min(c.len() - 1)] };
                    self.store_comp(s, i, x, m);
                }
            }
            Val::Mask(b) => {
                let x = self.sel(*b, self.fc(1.0), self.fc(0.0));
                self.store_comp(s, 0, x, m);
            }
            Val::Str(st) => {
                self.strs.insert(s.0, st.clone());
            }
            Val::Void => {}
        }
    }

    pub(super) fn store_elem(&mut self, slot: SlotId, index: Value, val: &Val<'c>) -> R<()> {
        let sty = self.func.slot(slot).ty;
        let len = sty.array.unwrap_or(1) as usize;
        let w = sty.base.components();
        if self.slots[slot.0 as usize].is_str {
            let i = self.const_index(index)?;
            if let Val::Str(s) = val {
                let e = self.strs.entry(slot.0).or_default();
                if e.len() <= i {
                    e.resize(i + 1, String::new());
                }
                e[i.min(len.saturating_sub(1))] = s.first().cloned().unwrap_or_default();
            }
            return Ok(());
        }
        let idx = self.floor(self.nums(index)?[0]);
        let vals = match val {
            Val::Num(c) => c.clone(),
            Val::Mask(m) => vec![self.sel(*m, self.fc(1.0), self.fc(0.0))],
            _ => return Ok(()),
        };
        let uni_slot = self.slots[slot.0 as usize].r == Repr::U;
        let m = self.load_mask(self.st().mask);
        for e in 0..len {
            let hit = self.cmp(FloatPredicate::OEQ, idx, self.fc(e as f64));
            let hm = if uni_slot { hit } else { self.mand(m, hit) };
            for c in 0..w {
                let x = vals[if vals.len() == 1 { 0 } else { c }];
                self.store_comp(slot, e * w + c, x, Some(hm));
            }
        }
        Ok(())
    }

    pub(super) fn const_index(&self, v: Value) -> R<usize> {
        match &self.func.inst(v).op {
            Op::Const(Const::Float(x)) => Ok(x.max(0.0) as usize),
            _ => err("string arrays need constant indices in the JIT"),
        }
    }

    pub(super) fn load_elem(&mut self, s: SlotId, index: Value, ty: Type) -> R<Val<'c>> {
        let sty = self.func.slot(s).ty;
        let len = sty.array.unwrap_or(1) as usize;
        if self.slots[s.0 as usize].is_str {
            let i = self.const_index(index)?;
            let v = self.strs.get(&s.0).and_then(|v| v.get(i.min(len.saturating_sub(1))).cloned()).unwrap_or_default();
            return Ok(Val::Str(vec![v]));
        }
        let w = ty.base.components();
        let Val::Num(all) = self.load_slot(s) else { return err("array load") };
        if let Op::Const(Const::Float(x)) = &self.func.inst(index).op {
            let e = (x.floor().max(0.0) as usize).min(len.saturating_sub(1));
            return Ok(Val::Num(all[e * w..(e + 1) * w].to_vec()));
        }
        let iv = self.floor(self.nums(index)?[0]);
        let iv = self.minmax(self.minmax(iv, self.fc(0.0), true), self.fc(len.saturating_sub(1) as f64), false);
        let mut out = Vec::with_capacity(w);
        for c in 0..w {
            let mut r = all[c];
            for e in 1..len {
                let hit = self.cmp(FloatPredicate::OEQ, iv, self.fc(e as f64));
                r = self.sel(hit, all[e * w + c], r);
            }
            out.push(r);
        }
        Ok(Val::Num(out))
    }
}
