//! Uniform/varying analysis and derivative-activity analysis.

use crate::ir::{walk, Block, Function, Node, Op, SlotKind};
use crate::types::Detail;

/// Sets the detail of every instruction and slot: `uniform` when the value is provably the
/// same for every shading point, else `varying`. A local assigned under varying control flow
/// (a branch on a varying condition, a loop some lanes leave early, a light loop) is varying.
///
/// Declared details of parameters and globals are kept; locals start uniform and are raised.
pub fn analyze_uniform(func: &mut Function) {
    let mut slot_var: Vec<bool> = func
        .slots
        .iter()
        .map(|s| match &s.kind {
            SlotKind::Local => false,
            SlotKind::Param(_) | SlotKind::Global(_) => s.ty.detail == Detail::Varying,
        })
        .collect();
    let mut inst_var = vec![false; func.insts.len()];
    loop {
        let mut changed = false;
        visit(func, &func.body, false, &mut slot_var, &mut inst_var, &mut changed);
        if !changed {
            break;
        }
    }
    for (i, inst) in func.insts.iter_mut().enumerate() {
        inst.ty.detail = if inst_var[i] { Detail::Varying } else { Detail::Uniform };
    }
    for (i, slot) in func.slots.iter_mut().enumerate() {
        slot.ty.detail = if slot_var[i] { Detail::Varying } else { Detail::Uniform };
    }
}

/// Does `block` hold a `Break`/`Continue`/`Return` below a varying branch (with `flow` the
/// flow state at its start)?
fn exits_divergently(func: &Function, block: &Block, inst_var: &[bool], varying_flow: bool) -> bool {
    block.iter().any(|n| match n {
        Node::Break(_) | Node::Continue(_) | Node::Return => varying_flow,
        Node::If { cond, then, otherwise } => {
            let vf = varying_flow || inst_var[cond.0 as usize];
            exits_divergently(func, then, inst_var, vf) || exits_divergently(func, otherwise, inst_var, vf)
        }
        Node::Loop { header, body, step, cond } => {
            let vf = varying_flow || cond.is_some_and(|c| inst_var[c.0 as usize]);
            [header, body, step].iter().any(|b| exits_divergently(func, b, inst_var, vf))
        }
        Node::Frame(b) => exits_divergently(func, b, inst_var, varying_flow),
        Node::Illuminance { body, .. } | Node::Illuminate { body, .. } | Node::Solar { body, .. } => {
            exits_divergently(func, body, inst_var, true)
        }
        _ => false,
    })
}

fn raise(flag: &mut bool, to: bool, changed: &mut bool) {
    if to && !*flag {
        *flag = true;
        *changed = true;
    }
}

fn visit(
    func: &Function,
    block: &Block,
    varying_flow: bool,
    slot_var: &mut Vec<bool>,
    inst_var: &mut Vec<bool>,
    changed: &mut bool,
) {
    for n in block {
        match n {
            Node::Inst(v) => {
                let inst = func.inst(*v);
                let mut var = inst.args.iter().any(|a| inst_var[a.0 as usize]);
                match &inst.op {
                    Op::Load(s) | Op::LoadElem(s) => var |= slot_var[s.0 as usize],
                    Op::Call { builtin, outputs, .. } => {
                        var |= builtin.varies_per_point();
                        for s in outputs.iter().flatten() {
                            let mut f = slot_var[s.0 as usize];
                            raise(&mut f, var || varying_flow, changed);
                            slot_var[s.0 as usize] = f;
                        }
                    }
                    _ => {}
                }
                let mut f = inst_var[v.0 as usize];
                raise(&mut f, var, changed);
                inst_var[v.0 as usize] = f;
            }
            Node::Store { slot, index, value, .. } => {
                let var = varying_flow || inst_var[value.0 as usize] || index.is_some_and(|i| inst_var[i.0 as usize]);
                let mut f = slot_var[slot.0 as usize];
                raise(&mut f, var, changed);
                slot_var[slot.0 as usize] = f;
            }
            Node::If { cond, then, otherwise } => {
                let vf = varying_flow || inst_var[cond.0 as usize];
                visit(func, then, vf, slot_var, inst_var, changed);
                visit(func, otherwise, vf, slot_var, inst_var, changed);
            }
            Node::Loop { header, cond, body, step } => {
                // The header runs first with the entry flow; whether the loop diverges depends
                // on its condition and on early exits, which are known after a visit.
                visit(func, header, varying_flow, slot_var, inst_var, changed);
                let divergent = varying_flow
                    || cond.is_some_and(|c| inst_var[c.0 as usize])
                    || exits_divergently(func, body, inst_var, false)
                    || exits_divergently(func, step, inst_var, false);
                visit(func, header, divergent, slot_var, inst_var, changed);
                visit(func, body, divergent, slot_var, inst_var, changed);
                visit(func, step, divergent, slot_var, inst_var, changed);
            }
            Node::Frame(b) => {
                let vf = varying_flow || exits_divergently(func, b, inst_var, false);
                visit(func, b, vf, slot_var, inst_var, changed);
            }
            Node::Illuminance { body, .. } | Node::Illuminate { body, .. } | Node::Solar { body, .. } => {
                visit(func, body, true, slot_var, inst_var, changed);
            }
            Node::Break(_) | Node::Continue(_) | Node::Return => {}
        }
    }
}

/// Marks the values whose derivatives some output needs (`Inst::needs_derivs`): the
/// arguments of `Du`, `Dv`, `Deriv`, `area`, `calculatenormal`, `filterwidth`, `filterstep`
/// and the texture look-ups, and everything varying they are computed from. Returns true when
/// any value needs derivatives — only then must a back end run the shader on dual numbers.
///
/// `outputs` are globals whose final values leave the shader with their derivatives (a
/// displacement shader's `P` and `N`: the renderer takes the moved surface's normal from the
/// screen derivatives of the moved `P`); what they are computed from is marked too.
///
/// Run after [`analyze_uniform`]: uniform values have zero derivatives and are never marked.
pub fn analyze_derivatives(func: &mut Function, outputs: &[crate::ir::Global]) -> bool {
    let n = func.insts.len();
    let mut need = vec![false; n];
    let mut slot_need = vec![false; func.slots.len()];
    // Seeds.
    walk(&func.body, &mut |node| {
        if let Node::Inst(v) = node {
            if let Op::Call { builtin, .. } = &func.inst(*v).op {
                if builtin.uses_derivatives() {
                    for &a in &func.inst(*v).args {
                        need[a.0 as usize] = true;
                    }
                }
                // `texture(name)` reads the globals s, t: their derivatives are its footprint.
                if *builtin == crate::builtins::Builtin::Texture {
                    need[v.0 as usize] = true;
                }
            }
        }
    });
    // Stores per slot, to propagate from loads to stored values.
    let mut stores: Vec<Vec<crate::ir::Value>> = vec![Vec::new(); func.slots.len()];
    walk(&func.body, &mut |node| {
        if let Node::Store { slot, value, .. } = node {
            stores[slot.0 as usize].push(*value);
        }
    });
    for &g in outputs {
        if let Some(s) = func.global_slot(g) {
            slot_need[s.0 as usize] = true;
            for v in &stores[s.0 as usize] {
                need[v.0 as usize] = true;
            }
        }
    }
    // Backward propagation to a fixed point (values only flow forward, so iterate in reverse).
    loop {
        let mut changed = false;
        for i in (0..n).rev() {
            let inst = &func.insts[i];
            if !need[i] || inst.ty.detail == Detail::Uniform {
                continue;
            }
            match &inst.op {
                Op::Load(s) | Op::LoadElem(s) => {
                    if !slot_need[s.0 as usize] {
                        slot_need[s.0 as usize] = true;
                        changed = true;
                        for v in &stores[s.0 as usize] {
                            need[v.0 as usize] = true;
                        }
                    }
                }
                Op::Select => {
                    for &a in &inst.args[1..] {
                        if !need[a.0 as usize] {
                            need[a.0 as usize] = true;
                            changed = true;
                        }
                    }
                }
                _ => {
                    for &a in &inst.args {
                        if !need[a.0 as usize] && !func.insts[a.0 as usize].is_bool {
                            need[a.0 as usize] = true;
                            changed = true;
                        }
                    }
                }
            }
        }
        // Output slots of calls: if an output slot is needed, the call's inputs are too.
        for (i, inst) in func.insts.iter().enumerate() {
            if let Op::Call { outputs, .. } = &inst.op {
                if outputs.iter().flatten().any(|s| slot_need[s.0 as usize]) && !need[i] {
                    need[i] = true;
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    let mut any = false;
    for (i, inst) in func.insts.iter_mut().enumerate() {
        inst.needs_derivs = need[i] && inst.ty.detail == Detail::Varying;
        any |= inst.needs_derivs;
    }
    any
}

/// Built-ins that read the shading context's globals themselves (not only their arguments):
/// the light loops use `P`, two-argument `faceforward` uses `Ng`, `depth` and `random` use
/// `P`; the derivative and texture built-ins use the parametric frame and footprint, so they
/// count as reading every global.

/// The member of [`anysl_core::GlobalSet`] a global is read through (`Oi` starts as `Os`);
/// empty for the outputs and the light-loop globals, which the renderer does not supply.
#[must_use]
pub fn global_set(g: crate::ir::Global) -> anysl_core::GlobalSet {
    use crate::ir::Global as G;
    use anysl_core::GlobalSet as S;
    match g {
        G::P => S::P,
        G::N => S::N,
        G::Ng => S::NG,
        G::I => S::I,
        G::E => S::E,
        G::Cs => S::CS,
        G::Os | G::Oi => S::OS,
        G::S => S::S,
        G::T => S::T,
        G::U => S::U,
        G::V => S::V,
        G::Du => S::DU,
        G::Dv => S::DV,
        G::DPdu => S::DPDU,
        G::DPdv => S::DPDV,
        _ => S::NONE,
    }
}

/// The globals a compiled shader reads — what a renderer must fill in before running it (see
/// `anysl_core::SurfaceShader::globals_read`): every global variable the code touches (back
/// ends load each one at entry), `Os` (the default `Oi`), `P` and `N` for displacement
/// shaders (their outputs default to them), and what the context-reading built-ins use.
#[must_use]
pub fn globals_read(module: &crate::ir::Module) -> anysl_core::GlobalSet {
    use anysl_core::GlobalSet as S;
    let func = &module.func;
    let mut read = S::OS;
    if module.kind == crate::ir::ShaderKind::Displacement {
        read |= S::P | S::N;
    }
    for s in &func.slots {
        if let SlotKind::Global(g) = s.kind {
            read |= global_set(g);
        }
    }
    walk(&func.body, &mut |node| {
        if let Node::Inst(v) = node {
            if let Op::Call { builtin, .. } = &func.inst(*v).op {
                read |= builtin.globals_read(func.inst(*v).args.len());
            }
        }
    });
    read
}
