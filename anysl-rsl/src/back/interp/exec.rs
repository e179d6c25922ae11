//! Running a [`Program`]: register files, masked control flow, and the shader boundary.

use super::builtins;
use super::frame::{Frame, Loc};
use super::prepare::{Arith, CNode, Cmp, Code, Program};
use crate::ir::{Const, Global, Module, ShaderKind};
use crate::types::BaseType;
use anysl_core::exec::INTERVAL_LOOP_LIMIT;
use anysl_core::prelude::*;
use anysl_core::shader::{ParamError, ParamInfo, ParamType, ParamValue, ShaderMeta, Storage};
use anysl_core::{Erased, ErasedContext, Spaces};
use std::any::Any;
use std::cell::RefCell;
use std::ops::Range;
use std::sync::Arc;

thread_local! {
    static POOL: RefCell<Vec<Box<dyn Any>>> = const { RefCell::new(Vec::new()) };
}

fn take_frame<F: ShadingFloat>(p: &Program, n: usize) -> Frame<F> {
    let cached = POOL.with(|pool| {
        let mut pool = pool.borrow_mut();
        let i = pool.iter().position(|b| b.is::<Frame<F>>())?;
        pool.swap_remove(i).downcast::<Frame<F>>().ok()
    });
    let mut fr = cached.map_or_else(
        || Frame {
            n,
            f: Vec::new(),
            m: Vec::new(),
            s: Vec::new(),
            loops: Vec::new(),
            rets: Vec::new(),
            widening: false,
            light_l: Vec3::zero(),
            light_ps: Vec3::zero(),
        },
        |b| *b,
    );
    fr.n = n;
    fr.f.clear();
    fr.f.resize(p.nregs as usize * n, F::c(0.0));
    fr.m.clear();
    fr.m.resize(p.nmasks as usize * n, F::Mask::splat(false));
    fr.s.clear();
    fr.s.resize(p.nstrs as usize, String::new());
    fr.loops.clear();
    fr.rets.clear();
    fr.widening = false;
    fr.light_l = Vec3::zero();
    fr.light_ps = Vec3::zero();
    for &(r, x) in &p.consts {
        let v = F::c(x);
        for k in 0..n {
            fr.set(r, k, v);
        }
    }
    for &(r, b) in &p.mask_consts {
        for k in 0..n {
            fr.set_mask(r, k, F::Mask::splat(b));
        }
    }
    for (r, s) in &p.str_consts {
        fr.s[*r as usize] = s.clone();
    }
    fr
}

fn give_frame<F: ShadingFloat>(fr: Frame<F>) {
    POOL.with(|pool| {
        let mut pool = pool.borrow_mut();
        if pool.len() < 8 {
            pool.push(Box::new(fr));
        }
    });
}

fn write_const<F: ShadingFloat>(fr: &mut Frame<F>, loc: Loc, c: &Const) {
    let mut nums = Vec::new();
    let mut strs = Vec::new();
    c.flatten(&mut nums, &mut strs);
    match loc {
        Loc::Num { off, width } => {
            if nums.len() == 1 && width > 1 {
                nums = vec![nums[0]; width as usize];
            }
            for (i, x) in nums.iter().enumerate().take(width as usize) {
                let v = F::c(*x);
                for k in 0..fr.n {
                    fr.set(off + i as u32, k, v);
                }
            }
        }
        Loc::Str(off, len) => {
            for (i, s) in strs.into_iter().enumerate().take(len as usize) {
                fr.s[off as usize + i] = s;
            }
        }
        _ => {}
    }
}

fn load_globals<F: ShadingFloat>(p: &Program, fr: &mut Frame<F>, k: usize, g: &Globals<F>) {
    for &(gl, loc) in &p.globals {
        let off = loc.off();
        match gl {
            Global::P => fr.set3(off, k, [g.P.x, g.P.y, g.P.z]),
            Global::N => fr.set3(off, k, [g.N.x, g.N.y, g.N.z]),
            Global::Ng => fr.set3(off, k, [g.Ng.x, g.Ng.y, g.Ng.z]),
            Global::I => fr.set3(off, k, [g.I.x, g.I.y, g.I.z]),
            Global::E => fr.set3(off, k, [g.E.x, g.E.y, g.E.z]),
            Global::DPdu => fr.set3(off, k, [g.dPdu.x, g.dPdu.y, g.dPdu.z]),
            Global::DPdv => fr.set3(off, k, [g.dPdv.x, g.dPdv.y, g.dPdv.z]),
            Global::Cs => fr.set3(off, k, [g.Cs.r, g.Cs.g, g.Cs.b]),
            Global::Os | Global::Oi => fr.set3(off, k, [g.Os.r, g.Os.g, g.Os.b]),
            Global::S => fr.set(off, k, g.s),
            Global::T => fr.set(off, k, g.t),
            Global::U => fr.set(off, k, g.u),
            Global::V => fr.set(off, k, g.v),
            Global::Du => fr.set(off, k, g.du),
            Global::Dv => fr.set(off, k, g.dv),
            Global::Ncomps => fr.set(off, k, F::c(3.0)),
            _ => {}
        }
    }
}

/// The per-batch state the executor threads through.
struct Run<'p, C> {
    p: &'p Program,
    ctxs: &'p mut [C],
}

/// Executes `code` for the chunks in `range`; `mask[k - range.start]` are the live lanes and
/// are narrowed in place as lanes break, continue or return.
fn exec_block<F: ShadingFloat, C: ShadingContext<F>>(
    fr: &mut Frame<F>,
    run: &mut Run<'_, C>,
    code: &[CNode],
    range: Range<usize>,
    mask: &mut [F::Mask],
) {
    for node in code {
        if mask.iter().all(|m| m.none()) {
            return;
        }
        match node {
            CNode::Op(c) => exec_op(fr, run, c, range.clone(), mask),
            CNode::Store { dst, src, idx, elem, len } => {
                for k in range.clone() {
                    let m = mask[k - range.start];
                    if m.none() {
                        continue;
                    }
                    store(fr, *dst, *src, *idx, *elem, *len, k, m);
                }
            }
            CNode::If { c, then, otherwise } => {
                let mut mt: Vec<F::Mask> = Vec::with_capacity(mask.len());
                let mut me: Vec<F::Mask> = Vec::with_capacity(mask.len());
                for k in range.clone() {
                    let m = mask[k - range.start];
                    let cv = fr.mask(*c, k);
                    mt.push(m & cv);
                    me.push(m & !cv);
                }
                if mt.iter().any(|m| m.any()) {
                    exec_block(fr, run, then, range.clone(), &mut mt);
                }
                if me.iter().any(|m| m.any()) && !otherwise.is_empty() {
                    exec_block(fr, run, otherwise, range.clone(), &mut me);
                }
                for (i, m) in mask.iter_mut().enumerate() {
                    *m = mt[i] | me[i];
                }
            }
            CNode::Loop { header, cond, body, step } => {
                let no = F::Mask::splat(false);
                let mut live = mask.to_vec();
                let mut exited = vec![no; mask.len()];
                fr.loops.push((vec![no; mask.len()], vec![no; mask.len()]));
                let mut iterations = 0usize;
                loop {
                    if <F::Mask as Mask>::THREE_VALUED && iterations >= INTERVAL_LOOP_LIMIT {
                        fr.widening = true;
                    }
                    exec_block(fr, run, header, range.clone(), &mut live);
                    if let Some(c) = cond {
                        for k in range.clone() {
                            let i = k - range.start;
                            let cv = fr.mask(*c, k);
                            exited[i] = exited[i] | (live[i] & !cv);
                            live[i] = live[i] & cv;
                        }
                    }
                    if live.iter().all(|m| m.none()) {
                        break;
                    }
                    exec_block(fr, run, body, range.clone(), &mut live);
                    if let Some((_, cont)) = fr.loops.last_mut() {
                        for (l, c) in live.iter_mut().zip(cont.iter_mut()) {
                            *l = *l | *c;
                            *c = no;
                        }
                    }
                    exec_block(fr, run, step, range.clone(), &mut live);
                    iterations += 1;
                    if fr.widening && <F::Mask as Mask>::THREE_VALUED {
                        // The widened pass covers every further iteration.
                        for (e, l) in exited.iter_mut().zip(&live) {
                            *e = *e | *l;
                        }
                        break;
                    }
                }
                if <F::Mask as Mask>::THREE_VALUED && iterations >= INTERVAL_LOOP_LIMIT {
                    fr.widening = false;
                }
                let (brk, _) = fr.loops.pop().unwrap_or_default();
                for (i, m) in mask.iter_mut().enumerate() {
                    *m = exited[i] | brk.get(i).copied().unwrap_or(no);
                }
            }
            CNode::Break(level) | CNode::Continue(level) => {
                let is_break = matches!(node, CNode::Break(_));
                let depth = fr.loops.len();
                if let Some(frame) = depth.checked_sub(1 + *level as usize).and_then(|i| fr.loops.get_mut(i)) {
                    // `continue n` for n > 1 leaves the inner loops like a break of those, then
                    // continues the outer one.
                    let target = if is_break { &mut frame.0 } else { &mut frame.1 };
                    for (t, m) in target.iter_mut().zip(mask.iter()) {
                        *t = *t | *m;
                    }
                }
                mask.iter_mut().for_each(|m| *m = F::Mask::splat(false));
            }
            CNode::Return => {
                if let Some(ret) = fr.rets.last_mut() {
                    for (t, m) in ret.iter_mut().zip(mask.iter()) {
                        *t = *t | *m;
                    }
                }
                mask.iter_mut().for_each(|m| *m = F::Mask::splat(false));
            }
            CNode::Frame(body) => {
                fr.rets.push(vec![F::Mask::splat(false); mask.len()]);
                let saved_loops = std::mem::take(&mut fr.loops);
                exec_block(fr, run, body, range.clone(), mask);
                fr.loops = saved_loops;
                let ret = fr.rets.pop().unwrap_or_default();
                for (m, r) in mask.iter_mut().zip(ret) {
                    *m = *m | r;
                }
            }
            CNode::Illuminance { cat, p, cone, body, l, cl } => {
                for k in range.clone() {
                    let m = mask[k - range.start];
                    if m.none() || k >= run.ctxs.len() {
                        continue;
                    }
                    let pos = fr.vec3(*p, k);
                    let cone_v = cone.map(|(a, b)| (fr.vec3(a, k), fr.get(b, k)));
                    let category = cat.map(|c| fr.s[c as usize].clone()).unwrap_or_default();
                    let mut e = Exec::with_mask(m);
                    let (l, cl) = (*l, *cl);
                    let prog = run.p;
                    let ctx = &mut run.ctxs[k];
                    // The light loop is a loop: `break` leaves it (no further lights for those
                    // lanes), `continue` goes on with the next light.
                    let saved = std::mem::take(&mut fr.loops);
                    let no = F::Mask::splat(false);
                    fr.loops.push((vec![no], vec![no]));
                    ctx.illuminance(&mut e, LightQuery::new(&category, pos, cone_v), |e, lv, clv| {
                        let broken = fr.loops.last().map_or(no, |l| l.0[0]);
                        let live = e.mask() & !broken;
                        if live.none() {
                            return;
                        }
                        if let Some(l) = l {
                            fr.set3(l, k, [lv.x, lv.y, lv.z]);
                        }
                        if let Some(cl) = cl {
                            fr.set3(cl, k, [clv.r, clv.g, clv.b]);
                        }
                        let mut inner = Run::<C> { p: prog, ctxs: &mut [] };
                        let mut bm = [live];
                        fr.rets.push(vec![F::Mask::splat(false)]);
                        exec_block(fr, &mut inner, body, k..k + 1, &mut bm);
                        fr.rets.pop();
                        if let Some(l) = fr.loops.last_mut() {
                            l.1[0] = no;
                        }
                    });
                    fr.loops = saved;
                }
            }
            CNode::Illuminate { p, cone, body } => {
                light_body(fr, run, Some(*p), *cone, body, range.clone(), mask);
            }
            CNode::Solar { cone, body } => {
                light_body(fr, run, None, *cone, body, range.clone(), mask);
            }
        }
    }
}

/// `illuminate`/`solar`: `L = Ps - from` (or the axis), run the body for the lanes in the
/// cone. The light's `L`/`Ps` slots are found through the program's globals.
fn light_body<F: ShadingFloat, C: ShadingContext<F>>(
    fr: &mut Frame<F>,
    run: &mut Run<'_, C>,
    from: Option<u32>,
    cone: Option<(u32, u32)>,
    body: &[CNode],
    range: Range<usize>,
    mask: &mut [F::Mask],
) {
    let l_slot = run.p.globals.iter().find(|(g, _)| *g == Global::L).map(|(_, l)| l.off());
    let ps_slot = run.p.globals.iter().find(|(g, _)| *g == Global::Ps).map(|(_, l)| l.off());
    let mut bm = Vec::with_capacity(mask.len());
    let mut unlit = Vec::with_capacity(mask.len());
    for k in range.clone() {
        let m = mask[k - range.start];
        let ps = ps_slot.map_or(fr.light_ps, |r| fr.vec3(r, k));
        let (l, lit) = match from {
            Some(p) => illuminate(ps, fr.vec3(p, k), cone.map(|(a, b)| (fr.vec3(a, k), fr.get(b, k)))),
            None => {
                let axis = cone.map_or_else(Vec3::zero, |(a, _)| fr.vec3(a, k));
                solar(axis)
            }
        };
        if let Some(r) = l_slot {
            fr.write(r, k, m, &[l.x, l.y, l.z]);
        }
        fr.light_l = Vec3::select(m, l, fr.light_l);
        bm.push(m & lit);
        unlit.push(m & !lit);
    }
    if bm.iter().any(|m| m.any()) {
        exec_block(fr, run, body, range, &mut bm);
        // Lanes that left the body (`return`, `break`) are gone; those outside the cone stay.
        for ((m, b), u) in mask.iter_mut().zip(&bm).zip(&unlit) {
            *m = *b | *u;
        }
    }
}

#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn store<F: ShadingFloat>(
    fr: &mut Frame<F>,
    dst: Loc,
    src: Loc,
    idx: Option<u32>,
    elem: u32,
    len: u32,
    k: usize,
    m: F::Mask,
) {
    match (dst, src) {
        (Loc::Num { off, width }, Loc::Num { off: so, width: sw }) => match idx {
            None => {
                let mut vals = [F::c(0.0); 16];
                let w = width as usize;
                if w <= 16 {
                    for (c, v) in vals.iter_mut().enumerate().take(w) {
                        *v = fr.get(if sw == 1 { so } else { so + c as u32 }, k);
                    }
                    fr.write(off, k, m, &vals[..w]);
                } else {
                    let vals: Vec<F> = (0..width).map(|c| fr.get(if sw == 1 { so } else { so + c }, k)).collect();
                    fr.write(off, k, m, &vals);
                }
            }
            Some(i) => {
                // Element store: one masked write per element the index may name.
                let iv = fr.get(i, k).floor();
                let vals: Vec<F> = (0..elem).map(|c| fr.get(if sw == 1 { so } else { so + c }, k)).collect();
                for e in 0..len {
                    let hit = m & iv.eq(F::c(f64::from(e)));
                    if hit.any() {
                        fr.write(off + e * elem, k, hit, &vals);
                    }
                }
            }
        },
        (Loc::Str(d, n), Loc::Str(s, _)) => {
            if m.any() {
                match idx {
                    None => {
                        for j in 0..n {
                            fr.s[(d + j) as usize] = fr.s[(s + j) as usize].clone();
                        }
                    }
                    Some(i) => {
                        let e = (fr.get(i, k).lane(0).max(0.0) as u32).min(n.saturating_sub(1));
                        fr.s[(d + e) as usize] = fr.s[s as usize].clone();
                    }
                }
            }
        }
        (Loc::Num { off, .. }, Loc::Mask(b)) => {
            let v = F::select(fr.mask(b, k), F::c(1.0), F::c(0.0));
            fr.write(off, k, m, &[v]);
        }
        _ => {}
    }
}

fn exec_op<F: ShadingFloat, C: ShadingContext<F>>(
    fr: &mut Frame<F>,
    run: &mut Run<'_, C>,
    code: &Code,
    range: Range<usize>,
    mask: &[F::Mask],
) {
    for k in range.clone() {
        let m = mask[k - range.start];
        if m.none() {
            continue;
        }
        match *code {
            Code::Copy { dst, src, w } => {
                for c in 0..w {
                    let v = fr.get(src + c, k);
                    fr.set(dst + c, k, v);
                }
            }
            Code::Splat { dst, src, w } => {
                let v = fr.get(src, k);
                for c in 0..w {
                    fr.set(dst + c, k, v);
                }
            }
            Code::Neg { dst, a, w } => {
                for c in 0..w {
                    let v = -fr.get(a + c, k);
                    fr.set(dst + c, k, v);
                }
            }
            Code::Arith { op, dst, a, sa, b, sb, w } => {
                for c in 0..w {
                    let x = fr.get(if sa { a } else { a + c }, k);
                    let y = fr.get(if sb { b } else { b + c }, k);
                    let v = match op {
                        Arith::Add => x + y,
                        Arith::Sub => x - y,
                        Arith::Mul => x * y,
                        Arith::Div => x / y,
                    };
                    fr.set(dst + c, k, v);
                }
            }
            Code::MatMul { dst, a, b, div } => {
                let ma = fr.matrix(a, k);
                let mb = fr.matrix(b, k);
                let mb = if div { mb.inverse() } else { mb };
                let r = ma * mb;
                fr.set_matrix(dst, k, &r);
            }
            Code::Dot { dst, a, b } => {
                let v = fr.vec3(a, k).dot(fr.vec3(b, k));
                fr.set(dst, k, v);
            }
            Code::Cross { dst, a, b } => {
                let v = fr.vec3(a, k).cross(fr.vec3(b, k));
                fr.set3(dst, k, [v.x, v.y, v.z]);
            }
            Code::Cmp { op, dst, a, b, w } => {
                let mut r = F::Mask::splat(op != Cmp::Ne);
                for c in 0..w {
                    let (x, y) = (fr.get(a + c, k), fr.get(b + c, k));
                    r = match op {
                        Cmp::Eq => r & x.eq(y),
                        Cmp::Ne => r | x.ne(y),
                        Cmp::Lt => x.lt(y),
                        Cmp::Le => x.le(y),
                        Cmp::Gt => x.gt(y),
                        Cmp::Ge => x.ge(y),
                    };
                }
                fr.set_mask(dst, k, r);
            }
            Code::CmpStr { ne, dst, a, b } => {
                let eq = fr.s[a as usize] == fr.s[b as usize];
                fr.set_mask(dst, k, F::Mask::splat(eq != ne));
            }
            Code::CmpMask { ne, dst, a, b } => {
                let (x, y) = (fr.mask(a, k), fr.mask(b, k));
                let diff = (x & !y) | (y & !x);
                fr.set_mask(dst, k, if ne { diff } else { !diff });
            }
            Code::Not { dst, a } => {
                let v = !fr.mask(a, k);
                fr.set_mask(dst, k, v);
            }
            Code::Logic { or, dst, a, b } => {
                let (x, y) = (fr.mask(a, k), fr.mask(b, k));
                fr.set_mask(dst, k, if or { x | y } else { x & y });
            }
            Code::ToMask { dst, a, w } => {
                let mut r = F::Mask::splat(false);
                for c in 0..w {
                    r = r | fr.get(a + c, k).ne(F::c(0.0));
                }
                fr.set_mask(dst, k, r);
            }
            Code::FromMask { dst, a } => {
                let v = F::select(fr.mask(a, k), F::c(1.0), F::c(0.0));
                fr.set(dst, k, v);
            }
            Code::Select { dst, c, a, b, w } => {
                let cm = fr.mask(c, k);
                for i in 0..w {
                    let v = F::select(cm, fr.get(a + i, k), fr.get(b + i, k));
                    fr.set(dst + i, k, v);
                }
            }
            Code::SelectMask { dst, c, a, b } => {
                let cm = fr.mask(c, k);
                let v = F::Mask::select_mask(cm, fr.mask(a, k), fr.mask(b, k));
                fr.set_mask(dst, k, v);
            }
            Code::SelectStr { dst, c, a, b } => {
                let pick = if fr.mask(c, k).lane(0) { a } else { b };
                fr.s[dst as usize] = fr.s[pick as usize].clone();
            }
            Code::CopyStr { dst, src, n } => {
                for j in 0..n {
                    fr.s[(dst + j) as usize] = fr.s[(src + j) as usize].clone();
                }
            }
            Code::LoadElem { dst, base, len, w, idx } => {
                let iv = fr.get(idx, k).floor();
                let last = F::c(f64::from(len.saturating_sub(1)));
                let iv = iv.max(F::c(0.0)).min(last);
                for c in 0..w {
                    let mut r = fr.get(base + c, k);
                    for e in 1..len {
                        r = F::select(iv.eq(F::c(f64::from(e))), fr.get(base + e * w + c, k), r);
                    }
                    fr.set(dst + c, k, r);
                }
            }
            Code::LoadElemStr { dst, base, len, idx } => {
                let e = (fr.get(idx, k).lane(0).max(0.0) as u32).min(len.saturating_sub(1));
                fr.s[dst as usize] = fr.s[(base + e) as usize].clone();
            }
            Code::FromSpace { dst, space, src, base: BaseType::Matrix } => {
                // `matrix "name" m`: m in space `name`, then that space to current.
                let table = run.ctxs.get(k).map_or(anysl_core::Spaces::standard(), |c| c.spaces());
                let to = table.to_current::<F>(&fr.s[space as usize]);
                let r = fr.matrix(src, k) * to;
                fr.set_matrix(dst, k, &r);
            }
            Code::FromSpace { dst, space, src, base } => {
                let v = fr.vec3(src, k);
                let out = if base == BaseType::Color {
                    let c = Color::new(v.x, v.y, v.z);
                    let c = match ColorSpace::from_name(&fr.s[space as usize]) {
                        Some(cs) => to_rgb(cs, c),
                        None => c,
                    };
                    [c.r, c.g, c.b]
                } else {
                    let table = run.ctxs.get(k).map_or(anysl_core::Spaces::standard(), |c| c.spaces());
                    let to = table.to_current::<F>(&fr.s[space as usize]);
                    let r = match base {
                        BaseType::Vector => to.transform_vector(v),
                        BaseType::Normal => to.transform_normal(v),
                        _ => to.transform_point(v),
                    };
                    [r.x, r.y, r.z]
                };
                fr.set3(dst, k, out);
            }
            Code::Call { f, dst, ref args, ref outs } => {
                let ctx = run.ctxs.get_mut(k);
                builtins::call(fr, ctx, f, dst, args, outs, k, m);
            }
        }
    }
}

/// Shades a batch: `ctxs[k]` supplies chunk `k`'s globals, lights and `trace`; `params` are
/// the instance's parameter values (in [`Module::params`] order); `masks[k]` the live lanes.
/// Returns the frame so callers can read any output (see [`Frame::read`]); hand it back with
/// [`release`] when done.
pub fn run_batch<F: ShadingFloat, C: ShadingContext<F>>(
    p: &Program,
    params: &[Const],
    ctxs: &mut [C],
    masks: &[F::Mask],
) -> Frame<F> {
    // The executor reaches the contexts through `Erased`, so that it is compiled once per
    // float type and not again for every context type that calls it.
    if let [ctx] = ctxs {
        return run_erased(p, params, &mut [Erased(ctx)], masks);
    }
    let mut erased: Vec<Erased<'_, F>> = ctxs.iter_mut().map(|c| Erased(c as &mut dyn ErasedContext<F>)).collect();
    run_erased(p, params, &mut erased, masks)
}

fn run_erased<F: ShadingFloat>(
    p: &Program,
    params: &[Const],
    ctxs: &mut [Erased<'_, F>],
    masks: &[F::Mask],
) -> Frame<F> {
    run_erased_with(p, params, ctxs, masks, &[])
}

/// What `Ci`, `Oi` and `alpha` hold when a volume or imager shader starts (per chunk).
#[derive(Clone, Copy, Debug)]
pub(super) struct Incoming<F> {
    pub(super) ci: Color<F>,
    pub(super) oi: Color<F>,
    pub(super) alpha: F,
}

/// [`run_erased`] with `Ci`, `Oi`, `alpha` of chunk `k` starting as `incoming[k]` (when
/// given).
pub(super) fn run_erased_with<F: ShadingFloat>(
    p: &Program,
    params: &[Const],
    ctxs: &mut [Erased<'_, F>],
    masks: &[F::Mask],
    incoming: &[Incoming<F>],
) -> Frame<F> {
    let n = ctxs.len();
    let mut fr = take_frame::<F>(p, n);
    for (i, loc) in p.params.iter().enumerate() {
        if let Some(c) = params.get(i) {
            write_const(&mut fr, *loc, c);
        }
    }
    for (k, ctx) in ctxs.iter().enumerate() {
        let g = *ctx.globals();
        load_globals(p, &mut fr, k, &g);
        if let Some(inc) = incoming.get(k) {
            for &(gl, loc) in &p.globals {
                match gl {
                    Global::Ci => fr.set3(loc.off(), k, [inc.ci.r, inc.ci.g, inc.ci.b]),
                    Global::Oi => fr.set3(loc.off(), k, [inc.oi.r, inc.oi.g, inc.oi.b]),
                    Global::Alpha => fr.set(loc.off(), k, inc.alpha),
                    _ => {}
                }
            }
        }
    }
    let mut mask: Vec<F::Mask> = masks.to_vec();
    mask.resize(n, F::Mask::splat(false));
    fr.rets.push(vec![F::Mask::splat(false); n]);
    let mut run = Run { p, ctxs };
    exec_block(&mut fr, &mut run, &p.code, 0..n, &mut mask);
    fr
}

/// Returns a frame's buffers to the per-thread pool.
pub fn release<F: ShadingFloat>(fr: Frame<F>) {
    give_frame(fr);
}

impl Program {
    /// Where global `g` lives, if the shader touches it.
    #[must_use]
    pub fn global_loc(&self, g: Global) -> Option<Loc> {
        self.globals.iter().find(|(x, _)| *x == g).map(|(_, l)| *l)
    }

    /// Where parameter `i` lives.
    #[must_use]
    pub fn param_loc(&self, i: usize) -> Option<Loc> {
        self.params.get(i).copied()
    }
}

fn param_type(t: crate::types::Type) -> ParamType {
    use crate::types::BaseType as B;
    match t.base {
        B::Float | B::Void => ParamType::Float,
        B::Color => ParamType::Color,
        B::Point => ParamType::Point,
        B::Vector => ParamType::Vector,
        B::Normal => ParamType::Normal,
        B::String => ParamType::String,
        B::Matrix => ParamType::Matrix,
    }
}

fn to_param_value(c: &Const) -> ParamValue {
    match c {
        Const::Float(x) => ParamValue::Float(*x),
        Const::Triple(t) => ParamValue::Triple(*t),
        Const::Str(s) => ParamValue::String(s.clone()),
        Const::Matrix(m) => ParamValue::Matrix(*m),
        Const::Array(v) => ParamValue::Array(v.iter().map(to_param_value).collect()),
    }
}

fn from_param_value(v: &ParamValue, like: &Const) -> Option<Const> {
    Some(match (v, like) {
        (ParamValue::Float(x), Const::Float(_)) => Const::Float(*x),
        (ParamValue::Float(x), Const::Triple(_)) => Const::Triple([*x; 3]),
        (ParamValue::Triple(t), Const::Triple(_)) => Const::Triple(*t),
        (ParamValue::String(s), Const::Str(_)) => Const::Str(s.clone()),
        (ParamValue::Matrix(m), Const::Matrix(_)) => Const::Matrix(*m),
        (ParamValue::Array(a), Const::Array(old)) if a.len() == old.len() => {
            Const::Array(a.iter().zip(old).map(|(x, o)| from_param_value(x, o)).collect::<Option<Vec<_>>>()?)
        }
        _ => return None,
    })
}

fn meta_of(m: &Module, uses_derivatives: bool) -> ShaderMeta {
    ShaderMeta {
        name: m.name.clone(),
        kind: match m.kind {
            ShaderKind::Surface => anysl_core::shader::ShaderKind::Surface,
            ShaderKind::Light => anysl_core::shader::ShaderKind::Light,
            ShaderKind::Displacement => anysl_core::shader::ShaderKind::Displacement,
            ShaderKind::Volume => anysl_core::shader::ShaderKind::Volume,
            ShaderKind::Imager => anysl_core::shader::ShaderKind::Imager,
        },
        params: m
            .params
            .iter()
            .map(|p| ParamInfo {
                name: p.name.clone(),
                ty: param_type(p.ty),
                array_len: p.ty.array.map(|n| n as usize),
                default: to_param_value(&p.default),
                storage: if p.ty.detail == crate::types::Detail::Uniform { Storage::Uniform } else { Storage::Varying },
                output: p.output,
            })
            .collect(),
        uses_derivatives,
    }
}

fn set_param_of(m: &Module, values: &mut [Const], name: &str, value: &ParamValue) -> Result<(), ParamError> {
    let i = m.params.iter().position(|p| p.name == name).ok_or_else(|| ParamError::Unknown {
        shader: m.name.clone(),
        name: name.to_string(),
        known: m.params.iter().map(|p| p.name.clone()).collect(),
    })?;
    let c = from_param_value(value, &values[i]).ok_or_else(|| ParamError::Type {
        name: name.to_string(),
        expected: param_type(m.params[i].ty),
        got: value.clone(),
    })?;
    m.set_param_value(values, i, c);
    Ok(())
}

/// A shader run by the interpreter — surface, displacement or light ([`InterpLight`]): a
/// shader like any other behind the [`SurfaceShader`], [`DisplacementShader`] and
/// [`LightShader`] boundaries.
#[derive(Clone, Debug)]
pub struct InterpShader {
    /// The compiled program (shared between instances).
    pub program: Arc<Program>,
    /// This instance's parameter values.
    pub values: Vec<Const>,
}

impl InterpShader {
    /// An instance with the default parameter values.
    #[must_use]
    pub fn new(program: Arc<Program>) -> Self {
        let values = program.module.params.iter().map(|p| p.default.clone()).collect();
        Self { program, values }
    }
}

impl Shader for InterpShader {
    fn meta(&self) -> ShaderMeta {
        meta_of(&self.program.module, self.program.uses_derivatives)
    }
    fn param(&self, name: &str) -> Option<ParamValue> {
        let i = self.program.module.params.iter().position(|p| p.name == name)?;
        Some(to_param_value(&self.values[i]))
    }
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
        set_param_of(&self.program.module, &mut self.values, name, value)
    }
}

impl InterpShader {
    /// [`SurfaceShader::shade`] for a batch of chunks at once: chunk `k` has the globals and
    /// lights of `ctxs[k]`, the live lanes `masks[k]`, and its output goes to `out[k]`. The
    /// ops are decoded once per batch instead of once per chunk, which is what makes the
    /// interpreter fast (a few hundred points per batch; see `anysl bench interp`).
    ///
    /// # Panics
    /// When `masks` or `out` is shorter than `ctxs`.
    pub fn shade_batch<F: ShadingFloat, C: ShadingContext<F>>(
        &self,
        ctxs: &mut [C],
        masks: &[F::Mask],
        out: &mut [SurfaceOutput<F>],
    ) {
        let n = ctxs.len();
        assert!(masks.len() >= n && out.len() >= n, "{n} chunks, {} masks, {} outputs", masks.len(), out.len());
        let fr = run_batch::<F, C>(&self.program, &self.values, ctxs, &masks[..n]);
        for (k, o) in out[..n].iter_mut().enumerate() {
            *o = surface_output(&fr, &self.program, k);
        }
        release(fr);
    }
}

impl SurfaceShader for InterpShader {
    fn globals_read(&self) -> anysl_core::GlobalSet {
        self.program.globals_read
    }

    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let p = &*self.program;
        let fr = run_batch::<F, C>(p, &self.values, std::slice::from_mut(ctx), &[e.mask()]);
        let out = surface_output(&fr, p, 0);
        release(fr);
        out
    }
}

/// `Ci` and `Oi` of chunk `k` after a surface shader ran (`Oi` defaults to `Os`, `Os` to 1).
fn surface_output<F: ShadingFloat>(fr: &Frame<F>, p: &Program, k: usize) -> SurfaceOutput<F> {
    let read3 = |g: Global| match p.global_loc(g) {
        Some(Loc::Num { off, .. }) => Some(fr.color(off, k)),
        _ => None,
    };
    let os = read3(Global::Os).unwrap_or_else(|| Color::splat(F::c(1.0)));
    SurfaceOutput { Ci: read3(Global::Ci).unwrap_or_else(Color::zero), Oi: read3(Global::Oi).unwrap_or(os) }
}

impl DisplacementShader for InterpShader {
    fn displace<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> (Vec3<F>, Vec3<F>) {
        let p = &*self.program;
        let g = *ctx.globals();
        let fr = run_batch::<F, C>(p, &self.values, std::slice::from_mut(ctx), &[e.mask()]);
        let read = |gl: Global, dflt: Vec3<F>| match p.global_loc(gl) {
            Some(Loc::Num { off, .. }) => fr.vec3(off, 0),
            _ => dflt,
        };
        let out = (read(Global::P, g.P), read(Global::N, g.N));
        release(fr);
        out
    }
}

/// A light shader run by the interpreter: the same type as [`InterpShader`] (a program and
/// its parameter values); the program's kind decides which shader trait it is used through.
pub type InterpLight = InterpShader;

/// The context a light (or imager) shader runs in: its globals and the named spaces. It has
/// no lights, and `trace` sees nothing.
pub struct LightCtx<'s, F: ShadingFloat> {
    pub(super) g: Globals<F>,
    pub(super) spaces: &'s Spaces,
}

impl<'s, F: ShadingFloat> LightCtx<'s, F> {
    /// The context of a light shader's run for the surface points `ps`: `P` (and `Ps`) = `ps`,
    /// every other global zero.
    #[must_use]
    pub fn at(ps: Vec3<F>, spaces: &'s Spaces) -> Self {
        Self { g: Globals::at(ps), spaces }
    }
}

impl<F: ShadingFloat> LightCtx<'static, F> {
    /// The context of an imager shader's run for `px`: `P` its raster position, `Cs` and `Os`
    /// its `Ci` and `Oi`, every other global zero; the standard spaces.
    #[must_use]
    pub fn imager(px: &anysl_core::ImagerPixel<F>) -> Self {
        Self { g: Globals::imager(px), spaces: Spaces::standard() }
    }
}

impl<F: ShadingFloat> ShadingContext<F> for LightCtx<'_, F> {
    fn globals(&self) -> &Globals<F> {
        &self.g
    }
    fn spaces(&self) -> &Spaces {
        self.spaces
    }
    fn illuminance<B: FnMut(&mut Exec<F>, Vec3<F>, Color<F>)>(
        &mut self,
        _e: &mut Exec<F>,
        _q: LightQuery<'_, F>,
        _body: B,
    ) {
    }
    fn ambient(&mut self, _e: &Exec<F>) -> Color<F> {
        Color::zero()
    }
    fn trace(&mut self, _e: &Exec<F>, _p: Vec3<F>, _dir: Vec3<F>) -> Color<F> {
        Color::zero()
    }
}

impl LightShader for InterpShader {
    fn category(&self) -> &str {
        match self.program.module.params.iter().position(|p| p.name == "__category").map(|i| &self.values[i]) {
            Some(Const::Str(s)) => s,
            _ => "",
        }
    }

    fn emission(&self) -> Option<Emission> {
        self.program.emission
    }

    fn light<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        self.light_in(e, ps, Spaces::standard())
    }

    fn light_in<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>, spaces: &Spaces) -> LightOutput<F> {
        let p = &*self.program;
        let mut ctx = LightCtx::at(ps, spaces);
        let mut fr = take_frame::<F>(p, 1);
        for (i, loc) in p.params.iter().enumerate() {
            if let Some(c) = self.values.get(i) {
                write_const(&mut fr, *loc, c);
            }
        }
        fr.light_ps = ps;
        if let Some(Loc::Num { off, .. }) = p.global_loc(Global::Ps) {
            fr.set3(off, 0, [ps.x, ps.y, ps.z]);
        }
        if let Some(Loc::Num { off, .. }) = p.global_loc(Global::P) {
            fr.set3(off, 0, [ps.x, ps.y, ps.z]);
        }
        let mut mask = [e.mask()];
        fr.rets.push(vec![F::Mask::splat(false)]);
        let mut run = Run { p, ctxs: &mut [Erased(&mut ctx)] };
        // `Cl` is zero for lanes outside every illuminate cone.
        exec_block(&mut fr, &mut run, &p.code, 0..1, &mut mask);
        let cl = match p.global_loc(Global::Cl) {
            Some(Loc::Num { off, .. }) => fr.color(off, 0),
            _ => Color::zero(),
        };
        let l = match p.global_loc(Global::L) {
            Some(Loc::Num { off, .. }) => fr.vec3(off, 0),
            _ => fr.light_l,
        };
        release(fr);
        let emission = self.emission().unwrap_or(Emission::Local);
        LightOutput { cl, l, lit: e.mask(), emission }
    }
}
