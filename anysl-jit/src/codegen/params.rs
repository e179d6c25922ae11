//! Constants as the numbers of slots, and the run-time parameter block (the numeric
//! parameters' values, read by code compiled without specialization).

use anysl_rsl::ir::{self, Const};
use anysl_rsl::types::{BaseType, Type};

/// How many floats a slot of type `ty` holds: its components times its array length (0 for
/// strings, which are kept apart).
pub(super) fn slot_comps(ty: Type) -> usize {
    ty.base.components() * ty.array.unwrap_or(1).max(1) as usize
}

/// The numbers a slot of type `ty` holds for the constant `c`: one per component, a float
/// widened to every component of a triple or to the diagonal of a matrix.
pub(super) fn slot_values(c: &Const, ty: Type) -> Vec<f64> {
    let (mut nums, mut strs) = (Vec::new(), Vec::new());
    c.flatten(&mut nums, &mut strs);
    let w = slot_comps(ty).max(1);
    if nums.len() == 1 && w > 1 && ty.base == BaseType::Matrix {
        let x = nums[0];
        nums = (0..16).map(|i| if i % 5 == 0 { x } else { 0.0 }).collect();
    } else if nums.len() == 1 && w > 1 {
        nums = vec![nums[0]; w];
    }
    nums
}

/// The run-time parameter block of `module` with parameter `values` (defaults where missing):
/// every numeric parameter's components in declaration order, as `f32` (strings are always
/// compiled in), and where each parameter starts (`None` for strings).
#[must_use]
pub fn param_block(module: &ir::Module, values: &[Const]) -> (Vec<f32>, Vec<Option<usize>>) {
    let mut block = Vec::new();
    let offsets = module
        .params
        .iter()
        .enumerate()
        .map(|(k, p)| {
            if p.ty.base == BaseType::String {
                return None;
            }
            let at = block.len();
            let c = values.get(k).unwrap_or(&p.default);
            block.extend(slot_values(c, module.func.slots[p.slot.0 as usize].ty).into_iter().map(|x| x as f32));
            Some(at)
        })
        .collect();
    (block, offsets)
}
