//! Dead-code elimination: unused pure instructions, stores to locals nobody reads, empty
//! branches and loops without effect.

use crate::ir::{walk, Block, Function, Module, Node, Op, SlotKind};

/// Removes dead code until nothing changes.
pub fn eliminate_dead_code(module: &mut Module) {
    let func = &mut module.func;
    loop {
        let before = func.inst_count() + count_nodes(&func.body);
        let live_slots = read_slots(func);
        let uses = func.use_counts();
        let body = std::mem::take(&mut func.body);
        func.body = sweep(func, body, &uses, &live_slots);
        if func.inst_count() + count_nodes(&func.body) == before {
            break;
        }
    }
}

fn count_nodes(b: &Block) -> usize {
    let mut n = 0;
    walk(b, &mut |_| n += 1);
    n
}

/// Slots whose value can be observed: read by a load, or visible outside (parameters,
/// globals — outputs are read by the renderer).
fn read_slots(func: &Function) -> Vec<bool> {
    let mut live: Vec<bool> = func.slots.iter().map(|s| !matches!(s.kind, SlotKind::Local)).collect();
    walk(&func.body, &mut |n| {
        if let Node::Inst(v) = n {
            match &func.inst(*v).op {
                Op::Load(s) | Op::LoadElem(s) => live[s.0 as usize] = true,
                _ => {}
            }
        }
    });
    live
}

fn has_effect(b: &Block) -> bool {
    let mut eff = false;
    walk(b, &mut |n| {
        if !matches!(n, Node::Inst(_)) {
            eff = true;
        }
    });
    eff
}

fn sweep(func: &Function, block: Block, uses: &[u32], live: &[bool]) -> Block {
    let mut out = Vec::with_capacity(block.len());
    for mut node in block {
        match &node {
            Node::Inst(v) => {
                let inst = func.inst(*v);
                if uses[v.0 as usize] == 0 && inst.op.is_removable() {
                    continue;
                }
            }
            Node::Store { slot, .. } if !live[slot.0 as usize] => continue,
            _ => {}
        }
        for b in node.blocks_mut() {
            let taken = std::mem::take(b);
            *b = sweep(func, taken, uses, live);
        }
        match &node {
            Node::If { then, otherwise, .. } if !has_effect(then) && !has_effect(otherwise) => {
                // Only pure instructions left inside: their values are used nowhere outside
                // (lexical scoping), so the branch is dead.
                continue;
            }
            Node::Frame(b) if !has_effect(b) => continue,
            _ => {}
        }
        // Trailing code after an unconditional break/continue/return is unreachable.
        let ends = matches!(node, Node::Break(_) | Node::Continue(_) | Node::Return);
        out.push(node);
        if ends {
            break;
        }
    }
    out
}
