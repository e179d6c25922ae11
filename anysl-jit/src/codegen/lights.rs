//! The built-in light loops — `ambient()`, `diffuse(N)` and the fused loop of `specular`
//! ([`anysl_core::stdlib::diffuse_specular`], which also sums `diffuse(N)` and, when asked,
//! `ambient()`) — compiled into the shader for contexts that describe their lights as data
//! ([`anysl_core::ShadingContext::lights_as_data`]; the pointer the compiled code finds in
//! [`crate::rt::HostCtx`]). Contexts that do not (renderers with shadow rays) get the
//! renderer call as before: the choice is a branch on that pointer at run time.
//!
//! The loop over the lights is [`anysl_core::run_illuminance`] with each light evaluated as
//! [`anysl_core::LightData::light`] does, and the bodies are those of `anysl-core`'s lighting
//! functions, operation for operation, so the sums are the renderer's bit for bit (tested:
//! `tests/suite/light_loops.rs`). Inline, the loop costs no call into the renderer and no spill of
//! the shader's live registers; `1/roughness` is computed once. The highlight's `pow` is the
//! library's polynomial emitted as IR for the vector variants (bit for bit the library's),
//! with the lanes whose cosine is `+0` taken out ([`Cg::pow_of_cosine`]).

use super::{Cg, Repr, M, S};
use crate::rt::Host;
use crate::rt::{self, RtKind};
use anysl_core::{Emission, Falloff, LightCode, LightData, LightKind, LightRecord};
use anysl_rsl::ir::Global;
use core::mem::{offset_of, size_of};
use inkwell::types::BasicType;
use inkwell::values::{IntValue, PointerValue};
use inkwell::{AddressSpace, FloatPredicate, IntPredicate};

/// A cone prepared for [`Cg::cone_test_contains`]: the axis, `cos²(angle)·|axis|²`, the
/// no-wider-than-a-hemisphere mask and the admits-everything mask.
pub(super) type ConeCode<'c> = (Vec<S<'c>>, S<'c>, M<'c>, M<'c>);

/// The lights a compiled loop visits ([`Cg::light_table`]): `n` records from `base`, each a
/// [`LightData`] or — when `records` — a [`LightRecord`] (its data at the start).
#[derive(Clone, Copy)]
pub(super) struct LightTable<'c> {
    pub(super) base: PointerValue<'c>,
    pub(super) n: IntValue<'c>,
    pub(super) records: bool,
}

const _: () = assert!(offset_of!(LightRecord, data) == 0);

/// The sums one loop computes.
#[derive(Clone, Copy)]
struct Sums {
    /// `specular(N, V, roughness)`, fused with `diffuse(N)` (no cone test).
    specular: bool,
    /// `diffuse(N)`: with the cone test of `diffuse` unless fused into `specular`.
    diffuse: bool,
    /// `ambient()`.
    ambient: bool,
}

impl<'c> Cg<'c, '_> {
    /// The renderer call `idx` ([`Host::Ambient`], [`Host::Diffuse`] or [`Host::Specular`],
    /// with `aux` as the host shims take it), or — when the context describes its lights as
    /// data — the same sums from a loop over them here.
    pub(super) fn light_call(&mut self, idx: Host, aux: u32, args: &[S<'c>], n_out: usize) -> Vec<S<'c>> {
        if self.t.dual || self.lights_by_renderer {
            // Dual numbers: the derivatives of the sums would be needed too.
            return self.host_call(idx, aux, args, n_out);
        }
        let sums = match idx {
            Host::Specular => Sums { specular: true, diffuse: aux >= 1, ambient: aux >= 2 },
            Host::Diffuse => Sums { specular: false, diffuse: true, ambient: aux >= 1 },
            _ => Sums { specular: false, diffuse: false, ambient: true },
        };
        let func = self.cur_fn();
        let table = self.light_table();
        let inline_bb = self.cx.append_basic_block(func, "lights.inline");
        let host_bb = self.cx.append_basic_block(func, "lights.host");
        let join = self.cx.append_basic_block(func, "lights.join");
        let none = self.b.build_is_null(table.base, "").expect("isnull");
        self.b.build_conditional_branch(none, host_bb, inline_bb).expect("br");
        self.b.position_at_end(inline_bb);
        let a = self.light_loop(sums, args, table);
        let a_end = self.b.get_insert_block().expect("positioned");
        self.b.build_unconditional_branch(join).expect("br");
        self.b.position_at_end(host_bb);
        let h = self.host_call(idx, aux, args, n_out);
        let h_end = self.b.get_insert_block().expect("positioned");
        self.b.build_unconditional_branch(join).expect("br");
        self.b.position_at_end(join);
        debug_assert_eq!(a.len(), h.len());
        a.iter()
            .zip(&h)
            .map(|(x, y)| {
                let (x, y) = (self.to(*x, Repr::V).v, self.to(*y, Repr::V).v);
                let phi = self.b.build_phi(self.vt(), "").expect("phi");
                phi.add_incoming(&[(&x, a_end), (&y, h_end)]);
                S { r: Repr::V, v: phi.as_basic_value(), d: None }
            })
            .collect()
    }

    /// The table of lights the compiled code finds in [`crate::rt::HostCtx`]: the context's
    /// lights as data, or — in the flavour compiled for them ([`crate::JitOptions::light_records`],
    /// never for the variants with derivatives) — its light records; a null base: the context
    /// has no such table, and the renderer's loops must be called. The flavours are compiled
    /// apart, when a context needs them: the loop over data has no call in it (a call would
    /// make the loop's live vectors spill) and the shader no second loop to compile.
    pub(super) fn light_table(&self) -> LightTable<'c> {
        let ctx = self.st().ctx.into_pointer_value();
        let word = |cg: &Self, off: u64, t: inkwell::types::BasicTypeEnum<'c>| {
            let p = unsafe { cg.b.build_gep(ctx, &[cg.cx.i64_type().const_int(off, false)], "") }.expect("gep");
            let p = cg.b.build_pointer_cast(p, t.ptr_type(AddressSpace::default()), "").expect("cast");
            cg.b.build_load(p, "").expect("load")
        };
        let records = self.t.light_records && !self.t.dual;
        let (base, n) = if records {
            (rt::HOST_CTX_RECORDS, rt::HOST_CTX_N_RECORDS)
        } else {
            (rt::HOST_CTX_LIGHTS, rt::HOST_CTX_N_LIGHTS)
        };
        let base = word(self, base, self.i8p().into()).into_pointer_value();
        let n = word(self, n, self.cx.i64_type().into()).into_int_value();
        LightTable { base, n, records }
    }

    /// `ConeTest::new(axis, angle)`: the axis, `cos²(angle)·|axis|²`, whether the cone is no
    /// wider than a hemisphere, and whether it admits everything (angle ≥ π).
    pub(super) fn cone_test(
        &mut self,
        axis: anysl_rsl::ir::Value,
        angle: anysl_rsl::ir::Value,
    ) -> super::value::R<ConeCode<'c>> {
        let axis = self.nums(axis)?;
        let angle = self.nums(angle)?[0];
        let pi = self.fc(core::f64::consts::PI);
        let a = self.minmax(angle, pi, false);
        let a = if self.t.lanes > 1 { self.to(a, Repr::V) } else { a };
        let c = self.rt_call(RtKind::Un, rt::Un::Cos as u32, &[a], 1, false)[0];
        let c2a2 = self.mul(self.mul(c, c), self.dot(&axis, &axis));
        let narrow = self.cmp(FloatPredicate::OGE, c, self.fc(0.0));
        let all = self.cmp(FloatPredicate::OGE, angle, pi);
        Ok((axis, c2a2, narrow, all))
    }

    /// `ConeTest::contains(dir)` of a [`Cg::cone_test`]: the lanes whose `dir` lies inside the cone.
    pub(super) fn cone_test_contains(&self, cone: &ConeCode<'c>, dir: &[S<'c>]) -> M<'c> {
        let (axis, c2a2, narrow, all) = cone;
        let d = self.dot(dir, axis);
        let front = self.cmp(FloatPredicate::OGE, d, self.fc(0.0));
        let dd = self.mul(d, d);
        let rhs = self.mul(*c2a2, self.dot(dir, dir));
        let wide = self.mnot(*narrow);
        let inside = self.mor(
            self.mand(front, self.mor(self.cmp(FloatPredicate::OGE, dd, rhs), wide)),
            self.mand(wide, self.cmp(FloatPredicate::OLE, dd, rhs)),
        );
        self.mor(inside, *all)
    }

    /// `illuminance(position [, axis, angle]) { body }` over the lights of `table`, the
    /// body compiled inline: [`anysl_core::run_illuminance`] with each light evaluated by its
    /// code (a record with code: called for `position`) or as [`LightData::light`] does — ambient lights skipped, a point light's `L = position - pos`
    /// with its falloff, a distant light's `L = pos`, `L` reversed to point at the light, the
    /// lanes in the cone (`ConeTest`), nothing for no lane, no shadowing — so the body sees
    /// the `L` and `Cl` the renderer's loop would hand it. `break`/`continue` in the body
    /// end the loop or the light for their lanes, as in the body function the renderer calls.
    pub(super) fn illuminance_over_data(
        &mut self,
        position: anysl_rsl::ir::Value,
        cone: Option<(anysl_rsl::ir::Value, anysl_rsl::ir::Value)>,
        body: &anysl_rsl::ir::Block,
        table: LightTable<'c>,
    ) -> super::value::R<()> {
        let func = self.cur_fn();
        let i64t = self.cx.i64_type();
        let ps = self.nums(position)?;
        // `ConeTest::new(axis, angle)`, once for all lights.
        let cone = match cone {
            Some((axis, angle)) => Some(self.cone_test(axis, angle)?),
            None => None,
        };
        let outer = self.st().mask;
        let m_outer = self.load_mask(outer);
        let brk = self.new_mask(self.no_lanes());
        let cont = self.new_mask(self.no_lanes());
        let ret = self.new_mask(self.no_lanes());
        let lmask = self.new_mask(self.no_lanes());

        let pre = self.b.get_insert_block().expect("positioned");
        let head = self.cx.append_basic_block(func, "illum.head");
        let rec_bb = self.cx.append_basic_block(func, "illum.light");
        let latch = self.cx.append_basic_block(func, "illum.next");
        let exit = self.cx.append_basic_block(func, "illum.exit");
        self.b.build_unconditional_branch(head).expect("br");
        self.b.position_at_end(head);
        let i = self.b.build_phi(i64t, "").expect("phi");
        let iv = i.as_basic_value().into_int_value();
        let more = self.b.build_int_compare(IntPredicate::ULT, iv, table.n, "").expect("icmp");
        self.b.build_conditional_branch(more, rec_bb, exit).expect("br");

        self.b.position_at_end(rec_bb);
        let rec = self.light_record(&table, iv);
        let data_bb = self.cx.append_basic_block(func, "illum.data");
        // Records may have code (the records table; never for the variants with derivatives).
        let with_code = table.records;
        let code_bb = with_code.then(|| self.cx.append_basic_block(func, "illum.code"));
        self.branch_on_code(rec, code_bb, data_bb);
        self.b.position_at_end(data_bb);
        let field = |cg: &Self, off: usize, t: inkwell::types::BasicTypeEnum<'c>| {
            let q = unsafe { cg.b.build_gep(rec, &[i64t.const_int(off as u64, false)], "") }.expect("gep");
            let q = cg.b.build_pointer_cast(q, t.ptr_type(AddressSpace::default()), "").expect("cast");
            cg.b.build_load(q, "").expect("load")
        };
        let triple = |cg: &Self, off: usize| -> Vec<S<'c>> {
            (0..3).map(|k| S { r: Repr::U, v: field(cg, off + 4 * k, cg.f32t.into()), d: None }).collect()
        };
        let kind = field(self, offset_of!(LightData, kind), self.cx.i32_type().into()).into_int_value();
        let kval = |k: LightKind| self.cx.i32_type().const_int(k as u64, false);
        let ambient = self.b.build_int_compare(IntPredicate::EQ, kind, kval(LightKind::Ambient), "").expect("icmp");
        let lit_bb = self.cx.append_basic_block(func, "illum.directed");
        self.b.build_conditional_branch(ambient, latch, lit_bb).expect("br");
        self.b.position_at_end(lit_bb);
        let pos = triple(self, offset_of!(LightData, pos));
        let cl_c = triple(self, offset_of!(LightData, cl));
        let point = self.b.build_int_compare(IntPredicate::EQ, kind, kval(LightKind::Point), "").expect("icmp");
        let point = M { uni: true, v: point.into() };
        let l: Vec<S<'c>> = (0..3).map(|k| self.sel(point, self.sub(ps[k], pos[k]), pos[k])).collect();
        // A point light with the inverse-square law divides by `L·L` (on a branch: three
        // divides a light without falloff should not pay).
        let falloff = field(self, offset_of!(LightData, falloff), self.cx.i32_type().into()).into_int_value();
        let sq = self.cx.i32_type().const_int(Falloff::InverseSquare as u64, false);
        let sq = self.b.build_int_compare(IntPredicate::EQ, falloff, sq, "").expect("icmp");
        let sq = self.b.build_and(point.v.into_int_value(), sq, "").expect("and");
        // `Cl` in the representation of `L` (as the division gives it), made before the branch.
        let rep = l.iter().map(|x| x.r).max().unwrap_or(Repr::V);
        let cl_r: Vec<S<'c>> = cl_c.iter().map(|&c| self.to(c, rep)).collect();
        let sq_bb = self.cx.append_basic_block(func, "illum.inverse_square");
        let in_bb = self.cx.append_basic_block(func, "illum.in");
        let from = self.b.get_insert_block().expect("positioned");
        self.b.build_conditional_branch(sq, sq_bb, in_bb).expect("br");
        self.b.position_at_end(sq_bb);
        let d2 = self.dot(&l, &l);
        let cl_sq: Vec<S<'c>> = cl_r.iter().map(|&c| self.to(self.div(c, d2), rep)).collect();
        let sq_end = self.b.get_insert_block().expect("positioned");
        self.b.build_unconditional_branch(in_bb).expect("br");
        self.b.position_at_end(in_bb);
        let cl: Vec<S<'c>> = cl_r
            .iter()
            .zip(&cl_sq)
            .map(|(&c, &q)| {
                let phi = self.b.build_phi(c.v.get_type(), "").expect("phi");
                phi.add_incoming(&[(&c.v, from), (&q.v, sq_end)]);
                let d = match (c.d, q.d) {
                    (Some((cx, cy)), Some((qx, qy))) => {
                        let px = self.b.build_phi(cx.get_type(), "").expect("phi");
                        px.add_incoming(&[(&cx, from), (&qx, sq_end)]);
                        let py = self.b.build_phi(cy.get_type(), "").expect("phi");
                        py.add_incoming(&[(&cy, from), (&qy, sq_end)]);
                        Some((px.as_basic_value(), py.as_basic_value()))
                    }
                    _ => None,
                };
                S { r: q.r, v: phi.as_basic_value(), d }
            })
            .collect();
        // A light with code: called for `position` under the loop's live lanes, unless it is
        // an ambient light (which `illuminance` does not visit); its `L` and `Cl` join the
        // data lights' (as varying values).
        let (l, cl) = if with_code {
            let lv: Vec<S<'c>> = l.iter().map(|&x| self.to(x, Repr::V)).collect();
            let clv: Vec<S<'c>> = cl.iter().map(|&x| self.to(x, Repr::V)).collect();
            let data_end = self.b.get_insert_block().expect("positioned");
            let sum_bb = self.cx.append_basic_block(func, "illum.lit");
            self.b.build_unconditional_branch(sum_bb).expect("br");
            self.b.position_at_end(code_bb.expect("made with the records"));
            let emission = self.record_code_field(rec, offset_of!(LightCode, emission), self.cx.i32_type().into());
            let amb = Emission::Ambient as u64;
            let is_amb = self
                .b
                .build_int_compare(IntPredicate::EQ, emission.into_int_value(), self.i32c(amb), "")
                .expect("icmp");
            let call_bb = self.cx.append_basic_block(func, "illum.call");
            self.b.build_conditional_branch(is_amb, latch, call_bb).expect("br");
            self.b.position_at_end(call_bb);
            let live = self.mand(m_outer, self.mnot(self.load_mask(brk)));
            let (ccl, cl_l) = self.call_light_code(rec, &ps, self.splat_mask(live));
            let code_end = self.b.get_insert_block().expect("positioned");
            self.b.build_unconditional_branch(sum_bb).expect("br");
            self.b.position_at_end(sum_bb);
            (self.join_varying(&lv, data_end, &cl_l, code_end), self.join_varying(&clv, data_end, &ccl, code_end))
        } else {
            (l, cl)
        };
        let to_light: Vec<S<'c>> = l.iter().map(|&x| self.neg(x)).collect();
        let mut m = self.mand(m_outer, self.mnot(self.load_mask(brk)));
        if let Some(cone) = &cone {
            m = self.mand(m, self.cone_test_contains(cone, &to_light));
        }
        self.store_mask(lmask, m);
        self.store_mask(cont, self.no_lanes());
        self.store_mask(ret, self.no_lanes());
        let run_bb = self.cx.append_basic_block(func, "illum.body");
        self.b.build_conditional_branch(self.any(self.load_mask(lmask)), run_bb, latch).expect("br");
        self.b.position_at_end(run_bb);
        for (gi, g) in [Global::L, Global::Cl].into_iter().enumerate() {
            if let Some(s) = self.func.global_slot(g) {
                let src = if gi == 0 { &to_light } else { &cl };
                for (c, &v) in src.iter().enumerate() {
                    self.store_comp(s, c, v, None);
                }
            }
        }
        let saved = self.st().clone();
        {
            let st = self.st.as_mut().expect("st");
            st.mask = lmask;
            st.loops = vec![(brk, cont)];
            st.rets = vec![ret];
        }
        let saved_vals = self.vals.clone();
        self.block(body)?;
        self.vals = saved_vals;
        self.st = Some(saved);
        self.b.build_unconditional_branch(latch).expect("br");

        self.b.position_at_end(latch);
        let next = self.b.build_int_add(iv, i64t.const_int(1, false), "").expect("add");
        self.b.build_unconditional_branch(head).expect("br");
        i.add_incoming(&[(&i64t.const_zero(), pre), (&next, latch)]);
        self.b.position_at_end(exit);
        Ok(())
    }

    /// The loop over the lights of `table`: the sums `sums` for the call arguments `args`
    /// (`N`, then `V` and `roughness` for `specular`), in the order of the host shims'
    /// outputs (specular, diffuse, ambient).
    fn light_loop(&mut self, sums: Sums, args: &[S<'c>], table: LightTable<'c>) -> Vec<S<'c>> {
        let func = self.cur_fn();
        let i64t = self.cx.i64_type();
        let vt = self.vt();
        let zero = self.fc(0.0);
        let normal: Vec<S<'c>> = args.iter().take(3).map(|&a| self.to(a, Repr::V)).collect();
        let view: Vec<S<'c>> = args.iter().skip(3).take(3).map(|&a| self.to(a, Repr::V)).collect();
        // `F::c(1.0) / roughness`, once for all lights.
        let exponent = args.get(6).map(|&r| self.div(self.fc(1.0), r));
        let p = self.read_global(Global::P);
        let m0 = self.splat_mask(self.load_mask(self.st().mask));
        // `diffuse` alone tests the cone of `illuminance(P, N, π/2)` (`ConeTest::new`).
        let cone = (sums.diffuse && !sums.specular).then(|| self.half_space_cone(&normal));
        let acc = |cg: &Self, on: bool| -> Option<[PointerValue<'c>; 3]> {
            on.then(|| {
                [(); 3].map(|()| {
                    let a = cg.entry_alloca(vt);
                    cg.b.build_store(a, cg.to(zero, Repr::V).v).expect("store");
                    a
                })
            })
        };
        let (spec, diff, amb) = (acc(self, sums.specular), acc(self, sums.diffuse), acc(self, sums.ambient));
        let directed = sums.specular || sums.diffuse;

        let pre = self.b.get_insert_block().expect("positioned");
        let head = self.cx.append_basic_block(func, "lights.head");
        let body = self.cx.append_basic_block(func, "lights.body");
        let latch = self.cx.append_basic_block(func, "lights.next");
        let exit = self.cx.append_basic_block(func, "lights.exit");
        self.b.build_unconditional_branch(head).expect("br");
        self.b.position_at_end(head);
        let i = self.b.build_phi(i64t, "").expect("phi");
        let iv = i.as_basic_value().into_int_value();
        let more = self.b.build_int_compare(IntPredicate::ULT, iv, table.n, "").expect("icmp");
        self.b.build_conditional_branch(more, body, exit).expect("br");

        self.b.position_at_end(body);
        let rec = self.light_record(&table, iv);
        // A record with code: the light's entry called for `P` under the mask.
        let data_bb = self.cx.append_basic_block(func, "light.data");
        let code_bb = table.records.then(|| self.cx.append_basic_block(func, "light.code"));
        self.branch_on_code(rec, code_bb, data_bb);

        self.b.position_at_end(data_bb);
        let field_i32 = |cg: &Self, off: usize| -> IntValue<'c> {
            let q = unsafe { cg.b.build_gep(rec, &[i64t.const_int(off as u64, false)], "") }.expect("gep");
            let t = cg.cx.i32_type().ptr_type(AddressSpace::default());
            let q = cg.b.build_pointer_cast(q, t, "").expect("cast");
            cg.b.build_load(q, "").expect("load").into_int_value()
        };
        let field_f32 = |cg: &Self, off: usize| -> S<'c> {
            let q = unsafe { cg.b.build_gep(rec, &[i64t.const_int(off as u64, false)], "") }.expect("gep");
            let q = cg.b.build_pointer_cast(q, cg.f32t.ptr_type(AddressSpace::default()), "").expect("cast");
            S { r: Repr::U, v: cg.b.build_load(q, "").expect("load"), d: None }
        };
        let triple = |cg: &Self, off: usize| -> [S<'c>; 3] { [0, 1, 2].map(|k| field_f32(cg, off + 4 * k)) };
        let kind = field_i32(self, offset_of!(LightData, kind));
        let cl_u = triple(self, offset_of!(LightData, cl));
        let amb_bb = self.cx.append_basic_block(func, "light.ambient");
        let lit_bb = self.cx.append_basic_block(func, "light.directed");
        let sum_bb = self.cx.append_basic_block(func, "light.sum");
        let kval = |k: LightKind| self.cx.i32_type().const_int(k as u64, false);
        let mut cases = Vec::new();
        if sums.ambient {
            cases.push((kval(LightKind::Ambient), amb_bb));
        }
        if directed {
            cases.push((kval(LightKind::Point), lit_bb));
            cases.push((kval(LightKind::Distant), lit_bb));
        }
        self.b.build_switch(kind, latch, &cases).expect("switch");

        // `sum_ambient`: `sum += select(lit, Cl, 0)` with every lane lit.
        self.b.position_at_end(amb_bb);
        if let Some(amb) = amb {
            for (c, slot) in amb.iter().enumerate() {
                let old = S { r: Repr::V, v: self.b.build_load(*slot, "").expect("load"), d: None };
                let new = self.add(old, cl_u[c]);
                self.b.build_store(*slot, self.to(new, Repr::V).v).expect("store");
            }
        }
        self.b.build_unconditional_branch(latch).expect("br");

        // The lights `illuminance` visits, `L` and `Cl` as `LightData::light` computes them:
        // a point light's `L = P - pos` and its falloff, a distant light's `L = pos`.
        self.b.position_at_end(lit_bb);
        let data_lit = if directed {
            let pos = triple(self, offset_of!(LightData, pos));
            let point = self.b.build_int_compare(IntPredicate::EQ, kind, kval(LightKind::Point), "").expect("icmp");
            let point = M { uni: true, v: point.into() };
            let l: Vec<S<'c>> =
                (0..3).map(|k| self.to(self.sel(point, self.sub(p[k], pos[k]), pos[k]), Repr::V)).collect();
            let cl_v: Vec<S<'c>> = cl_u.iter().map(|&c| self.to(c, Repr::V)).collect();
            // A point light with the inverse-square law divides by `L·L` (a distant light's
            // falloff field is not read).
            let falloff = field_i32(self, offset_of!(LightData, falloff));
            let sq = self.cx.i32_type().const_int(Falloff::InverseSquare as u64, false);
            let sq = self.b.build_int_compare(IntPredicate::EQ, falloff, sq, "").expect("icmp");
            let sq = self.b.build_and(point.v.into_int_value(), sq, "").expect("and");
            let sq_bb = self.cx.append_basic_block(func, "light.inverse_square");
            let in_bb = self.cx.append_basic_block(func, "light.in");
            let from = self.b.get_insert_block().expect("positioned");
            self.b.build_conditional_branch(sq, sq_bb, in_bb).expect("br");
            self.b.position_at_end(sq_bb);
            let d2 = self.dot(&l, &l);
            let cl_sq: Vec<S<'c>> = cl_v.iter().map(|&c| self.to(self.div(c, d2), Repr::V)).collect();
            self.b.build_unconditional_branch(in_bb).expect("br");
            self.b.position_at_end(in_bb);
            let cl: Vec<S<'c>> = (0..3)
                .map(|k| {
                    let phi = self.b.build_phi(vt, "").expect("phi");
                    phi.add_incoming(&[(&cl_v[k].v, from), (&cl_sq[k].v, sq_bb)]);
                    S { r: Repr::V, v: phi.as_basic_value(), d: None }
                })
                .collect();
            let end = self.b.get_insert_block().expect("positioned");
            self.b.build_unconditional_branch(sum_bb).expect("br");
            Some((l, cl, end))
        } else {
            self.b.build_unconditional_branch(latch).expect("br");
            None
        };

        // A light with code: `ambient()` takes an ambient light's `Cl` for the live lanes
        // (`sum_ambient`), `illuminance` a directed light's `Cl` and `L`; a light that does
        // not emit so is not called.
        let code_lit = if let Some(code_bb) = code_bb {
            self.b.position_at_end(code_bb);
            let emission = self.record_code_field(rec, offset_of!(LightCode, emission), self.cx.i32_type().into());
            let is_amb = self
                .b
                .build_int_compare(IntPredicate::EQ, emission.into_int_value(), self.i32c(Emission::Ambient as u64), "")
                .expect("icmp");
            let code_amb_bb = self.cx.append_basic_block(func, "light.code.ambient");
            let code_dir_bb = self.cx.append_basic_block(func, "light.code.directed");
            self.b
                .build_conditional_branch(
                    is_amb,
                    if sums.ambient { code_amb_bb } else { latch },
                    if directed { code_dir_bb } else { latch },
                )
                .expect("br");
            self.b.position_at_end(code_amb_bb);
            if let Some(amb) = amb {
                let (cl, _) = self.call_light_code(rec, &p, m0);
                for (c, slot) in amb.iter().enumerate() {
                    let old = S { r: Repr::V, v: self.b.build_load(*slot, "").expect("load"), d: None };
                    let new = self.add(old, self.sel(m0, cl[c], self.to(zero, Repr::V)));
                    self.b.build_store(*slot, self.to(new, Repr::V).v).expect("store");
                }
            }
            self.b.build_unconditional_branch(latch).expect("br");
            self.b.position_at_end(code_dir_bb);
            let code_lit = if directed {
                let (cl, l) = self.call_light_code(rec, &p, m0);
                let end = self.b.get_insert_block().expect("positioned");
                self.b.build_unconditional_branch(sum_bb).expect("br");
                Some((l, cl, end))
            } else {
                self.b.build_unconditional_branch(latch).expect("br");
                None
            };
            code_lit
        } else {
            None
        };

        self.b.position_at_end(sum_bb);
        let lit = match (data_lit, code_lit) {
            (Some((dl, dcl, dend)), Some((cl_l, ccl, cend))) => {
                Some((self.join_varying(&dl, dend, &cl_l, cend), self.join_varying(&dcl, dend, &ccl, cend)))
            }
            (Some((l, cl, _)), None) => Some((l, cl)),
            _ => None,
        };
        if let Some((l, cl)) = lit {
            // `run_illuminance`: L reversed to point at the light, the lanes in the cone,
            // nothing to do for no lane.
            let to_light: Vec<S<'c>> = l.iter().map(|&x| self.neg(x)).collect();
            let mask = match &cone {
                Some(c) => self.mand(m0, self.cone_contains(c, &to_light, &normal)),
                None => m0,
            };
            let run_bb = self.cx.append_basic_block(func, "light.body");
            self.b.build_conditional_branch(self.any(mask), run_bb, latch).expect("br");
            self.b.position_at_end(run_bb);
            // `sum = Cl·w + sum` per component, fused (`Color::mul_add`), for the lanes in `mask`.
            let update = |cg: &Self, slots: [PointerValue<'c>; 3], cl: &[S<'c>], w: S<'c>| {
                for (slot, &c) in slots.iter().zip(cl) {
                    let old = S { r: Repr::V, v: cg.b.build_load(*slot, "").expect("load"), d: None };
                    let new = cg.sel(mask, cg.fma(c, w, old), old);
                    cg.b.build_store(*slot, cg.to(new, Repr::V).v).expect("store");
                }
            };
            let lu = self.normalize(&to_light);
            let ndl = self.dot(&lu, &normal);
            if let Some(diff) = diff {
                // `cl · max(L̂·N, 0)`, as `diffuse` and `diffuse_specular` add it.
                let w = self.lib_max(ndl, zero);
                update(self, diff, &cl, w);
            }
            if let (Some(spec), Some(exponent)) = (spec, exponent) {
                // `diffuse_specular`'s highlight: `n·normalize(h)` without forming it.
                let h: Vec<S<'c>> = (0..3).map(|k| self.add(lu[k], view[k])).collect();
                let h2 = self.dot(&h, &h);
                let inv = self.rsqrt(h2);
                let k = self.sel(self.cmp(FloatPredicate::OGT, h2, zero), inv, zero);
                let ndh = self.lib_max(self.mul(self.dot(&normal, &h), k), zero);
                let s = self.pow_of_cosine(ndh, exponent);
                let w = self.sel(self.cmp(FloatPredicate::OGT, ndl, zero), s, self.to(zero, s.r));
                update(self, spec, &cl, w);
            }
        }
        self.b.build_unconditional_branch(latch).expect("br");

        self.b.position_at_end(latch);
        let next = self.b.build_int_add(iv, i64t.const_int(1, false), "").expect("add");
        self.b.build_unconditional_branch(head).expect("br");
        i.add_incoming(&[(&i64t.const_zero(), pre), (&next, latch)]);

        self.b.position_at_end(exit);
        let read = |cg: &Self, slots: [PointerValue<'c>; 3]| -> Vec<S<'c>> {
            slots.iter().map(|s| S { r: Repr::V, v: cg.b.build_load(*s, "").expect("load"), d: None }).collect()
        };
        let mut out = Vec::new();
        for slots in [spec, diff, amb].into_iter().flatten() {
            out.extend(read(self, slots));
        }
        out
    }

    /// Phis of the varying values `a` (from block `a_bb`) and `b` (from `b_bb`), pairwise, at
    /// the start of the block the builder is positioned in.
    fn join_varying(
        &self,
        a: &[S<'c>],
        a_bb: inkwell::basic_block::BasicBlock<'c>,
        b: &[S<'c>],
        b_bb: inkwell::basic_block::BasicBlock<'c>,
    ) -> Vec<S<'c>> {
        a.iter()
            .zip(b)
            .map(|(x, y)| {
                let phi = self.b.build_phi(self.vt(), "").expect("phi");
                phi.add_incoming(&[(&x.v, a_bb), (&y.v, b_bb)]);
                S { r: Repr::V, v: phi.as_basic_value(), d: None }
            })
            .collect()
    }

    /// Record `i` of `table`.
    pub(super) fn light_record(&self, table: &LightTable<'c>, i: IntValue<'c>) -> PointerValue<'c> {
        let i64t = self.cx.i64_type();
        let size = if table.records { size_of::<LightRecord>() } else { size_of::<LightData>() };
        let size = i64t.const_int(size as u64, false);
        let at = self.b.build_int_mul(i, size, "").expect("mul");
        unsafe { self.b.build_gep(table.base, &[at], "") }.expect("gep")
    }

    /// Branches to `code_bb` when record `rec` is a light with code, else (and without a
    /// `code_bb`: a table of data) to `data_bb` (a record's data is at its start:
    /// [`LightRecord::data`]).
    pub(super) fn branch_on_code(
        &self,
        rec: PointerValue<'c>,
        code_bb: Option<inkwell::basic_block::BasicBlock<'c>>,
        data_bb: inkwell::basic_block::BasicBlock<'c>,
    ) {
        let Some(code_bb) = code_bb else {
            self.b.build_unconditional_branch(data_bb).expect("br");
            return;
        };
        let entry = self.record_code_field(rec, offset_of!(LightCode, entry), self.cx.i64_type().into());
        let none =
            self.b.build_int_compare(IntPredicate::EQ, entry.into_int_value(), self.cx.i64_type().const_zero(), "");
        self.b.build_conditional_branch(none.expect("icmp"), data_bb, code_bb).expect("br");
    }

    /// The field at `off` of [`LightRecord::code`] of record `rec`, loaded as `t`.
    fn record_code_field(
        &self,
        rec: PointerValue<'c>,
        off: usize,
        t: inkwell::types::BasicTypeEnum<'c>,
    ) -> inkwell::values::BasicValueEnum<'c> {
        let at = self.cx.i64_type().const_int((offset_of!(LightRecord, code) + off) as u64, false);
        let q = unsafe { self.b.build_gep(rec, &[at], "") }.expect("gep");
        let q = self.b.build_pointer_cast(q, t.ptr_type(AddressSpace::default()), "").expect("cast");
        self.b.build_load(q, "").expect("load")
    }

    /// Calls the code of record `rec` ([`LightCode`]) for the points `ps` under `mask`:
    /// the light's `Cl` and `L`. With lights compiled into this code ([`Cg::inline_lights`]),
    /// the record's entry selects one of them, run here (its buffers are its own, so that LLVM
    /// keeps them in registers once it is inlined), and no call is left in the loop — a call
    /// on any path would make the loop's live vectors spill on every path — so the code runs
    /// only records whose code is among them (`JitShader` checks that before it runs it); an
    /// entry that is not gives zeros.
    pub(super) fn call_light_code(&self, rec: PointerValue<'c>, ps: &[S<'c>], mask: M<'c>) -> (Vec<S<'c>>, Vec<S<'c>>) {
        let i64p = self.cx.i64_type().ptr_type(AddressSpace::default());
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let fty = self.light_entry_type();
        let entry = self.record_code_field(rec, offset_of!(LightCode, entry), self.cx.i64_type().into());
        let ctx = self.record_code_field(rec, offset_of!(LightCode, ctx), self.i8p().into());
        let host = self.record_code_field(rec, offset_of!(LightCode, host), i64p.into());
        let params = self.record_code_field(rec, offset_of!(LightCode, params), f32p.into());
        let call = |callee: inkwell::values::CallableValue<'c>| {
            let psb = self.spill(ps, false);
            let out = self.out_buf(6, false);
            let m = self.mask_buf_of(mask);
            self.b
                .build_call(callee, &[psb.into(), out.into(), m.into(), ctx.into(), host.into(), params.into()], "")
                .expect("call");
            self.unspill(out, 6, false)
        };
        let mut v = if self.inline_lights.is_empty() {
            let p = self.b.build_int_to_ptr(entry.into_int_value(), fty.ptr_type(AddressSpace::default()), "");
            call(inkwell::values::CallableValue::try_from(p.expect("inttoptr")).expect("callable"))
        } else {
            self.inline_lights_called.set(true);
            let func = self.cur_fn();
            let join = self.cx.append_basic_block(func, "light.joined");
            let other = self.cx.append_basic_block(func, "light.unknown");
            let cases: Vec<_> = self
                .inline_lights
                .iter()
                .map(|&(addr, _)| {
                    (self.cx.i64_type().const_int(addr, false), self.cx.append_basic_block(func, "light.inline"))
                })
                .collect();
            self.b.build_switch(entry.into_int_value(), other, &cases).expect("switch");
            let mut arms = Vec::new();
            for (&(_, f), &(_, bb)) in self.inline_lights.iter().zip(&cases) {
                self.b.position_at_end(bb);
                let out = call(f.into());
                arms.push((out, self.b.get_insert_block().expect("positioned")));
                self.b.build_unconditional_branch(join).expect("br");
            }
            self.b.position_at_end(other);
            arms.push((vec![self.to(self.fc(0.0), Repr::V); 6], other));
            self.b.build_unconditional_branch(join).expect("br");
            self.b.position_at_end(join);
            (0..6)
                .map(|c| {
                    let phi = self.b.build_phi(self.vt(), "").expect("phi");
                    for (out, bb) in &arms {
                        phi.add_incoming(&[(&out[c].v, *bb)]);
                    }
                    S { r: Repr::V, v: phi.as_basic_value(), d: None }
                })
                .collect()
        };
        let l = v.split_off(3);
        (v, l)
    }

    /// `pow(x, y)` for the highlight's cosine `x`, as the library computes it, without its cost
    /// at `x = +0`: there (every lane facing away from the half vector) `pow` is `+0` for
    /// `y > 0`, and the library reaches that `+0` through a result below the smallest normal
    /// float — a microcode assist on x86 that cost more than the rest of the light loop. Those
    /// lanes take `pow(1, y)` and then `+0`: the same bits, no assist. For the vector variants
    /// `pow` is emitted as IR ([`Cg::rt_call`]): called, it was 46 % of plastic's x8 time on an
    /// AVX-512 AMD machine, where the inlined polynomial lets the out-of-order core overlap the
    /// lights (`perf_probe -- probe`: plastic 0.63 → 0.72× of the ahead-of-time code, ~15 %
    /// more LLVM instructions to compile).
    fn pow_of_cosine(&mut self, x: S<'c>, y: S<'c>) -> S<'c> {
        // A uniform exponent stays uniform: `pow` powers by it under scalar branches.
        let (x, y) = if y.r == Repr::U { (x, y) } else { self.unify(x, y) };
        let it = if self.t.lanes == 1 {
            self.cx.i32_type().into()
        } else {
            inkwell::types::BasicTypeEnum::from(self.cx.i32_type().vec_type(self.t.lanes))
        };
        let bits = self.b.build_bit_cast(x.v, it, "").expect("bitcast");
        let zero_bits = it.const_zero();
        let plus_zero = match (bits, zero_bits) {
            (inkwell::values::BasicValueEnum::IntValue(a), inkwell::values::BasicValueEnum::IntValue(b)) => {
                self.b.build_int_compare(IntPredicate::EQ, a, b, "").expect("icmp").into()
            }
            (inkwell::values::BasicValueEnum::VectorValue(a), inkwell::values::BasicValueEnum::VectorValue(b)) => {
                self.b.build_int_compare(IntPredicate::EQ, a, b, "").expect("icmp").into()
            }
            _ => unreachable!("integer lanes of one shape"),
        };
        let zero = self.fc(0.0);
        let skip = self.mand(M { uni: false, v: plus_zero }, self.cmp(FloatPredicate::OGT, y, zero));
        let base = self.sel(skip, self.fc(1.0), x);
        let p = self.rt_call(RtKind::Bin, rt::Bin::Pow as u32, &[base, y], 1, false)[0];
        self.sel(skip, self.to(zero, p.r), p)
    }

    /// `a.max(b)` as the float type's library computes it ([`Cg::minmax`]).
    fn lib_max(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        self.minmax(a, b, true)
    }

    /// `ConeTest::new(n, π/2)`: `(c²·|n|², narrow, all)` with `c = cos(π/2)` as the float
    /// type computes it.
    fn half_space_cone(&self, n: &[S<'c>]) -> (S<'c>, bool, bool) {
        let angle = core::f64::consts::FRAC_PI_2 as f32;
        let c = if self.t.lanes == 1 {
            angle.cos()
        } else {
            use anysl_core::ShadingFloat;
            anysl_simd::F32x8::splat(angle).cos().to_array()[0]
        };
        let c2a2 = self.mul(self.fc(f64::from(c * c)), self.dot(n, n));
        (c2a2, c >= 0.0, angle >= core::f32::consts::PI)
    }

    /// `ConeTest::contains(dir)` for the cone `(c2a2, narrow, all)` around `axis`.
    fn cone_contains(&self, cone: &(S<'c>, bool, bool), dir: &[S<'c>], axis: &[S<'c>]) -> M<'c> {
        let &(c2a2, narrow, all) = cone;
        if all {
            return self.mconst(true);
        }
        let d = self.dot(dir, axis);
        let front = self.cmp(FloatPredicate::OGE, d, self.fc(0.0));
        let dd = self.mul(d, d);
        let rhs = self.mul(c2a2, self.dot(dir, dir));
        if narrow {
            self.mand(front, self.cmp(FloatPredicate::OGE, dd, rhs))
        } else {
            self.mor(front, self.cmp(FloatPredicate::OLE, dd, rhs))
        }
    }
}
