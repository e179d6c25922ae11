//! Light-call fusion analysis: where calls of the built-in light loops (`ambient()`,
//! `diffuse(N)`, `specular(N, V, roughness)`) meet, so that a back end can visit the lights once
//! for several of them.
//!
//! An analysis of the IR only: it changes nothing, and what to generate for the calls it finds
//! is the back end's. The JIT uses it to fuse a matte-like shader's
//! `Ka·ambient() + Kd·diffuse(Nf)` into one light loop, and its `specular` loop to also sum
//! `ambient()` when the shader calls it.

use crate::builtins::Builtin;
use crate::ir::{Block, Function, Node, Op, SlotId, Value};
use std::collections::HashMap;

/// Where the normal of the `diffuse(N)` that follows an `ambient()` call can be read at the
/// `ambient()` call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalSrc {
    /// A variable (not an array) not written between the two calls: its value at the
    /// `ambient()` call is the normal.
    Slot(SlotId),
    /// A value computed before the `ambient()` call in the same block.
    Value(Value),
}

/// For every `ambient()` call followed, in the same block and with only instructions and
/// stores in between (so under the same mask), by a `diffuse(N)` whose normal can be read at
/// the `ambient()` call: where that normal is, keyed by the `ambient()` call. Only the first
/// `diffuse` after an `ambient()` call is considered.
///
/// ```
/// use anysl_rsl::passes::{lights, optimize, PassOptions};
/// let src = "surface matte(float Ka = 1; float Kd = 1) {
///     normal Nf = faceforward(normalize(N), I);
///     Ci = Cs * (Ka * ambient() + Kd * diffuse(Nf));
/// }";
/// let module = anysl_rsl::compile_source("matte.sl", src, &Default::default()).unwrap().module;
/// let analyzed = optimize(module, &PassOptions::default());
/// assert_eq!(lights::ambient_partners(&analyzed.module().func).len(), 1);
/// ```
#[must_use]
pub fn ambient_partners(func: &Function) -> HashMap<Value, NormalSrc> {
    let mut out = HashMap::new();
    partners_in(func, &func.body, &mut out);
    out
}

/// Does some instruction of `func` call `ambient()`? (A back end whose `specular` loop can
/// also sum the ambient light does so only then.)
#[must_use]
pub fn calls_ambient(func: &Function) -> bool {
    func.insts.iter().any(|i| matches!(&i.op, Op::Call { builtin: Builtin::Ambient, .. }))
}

/// Is `v` a call of `want` with `nargs` arguments?
fn is_call(func: &Function, v: Value, want: Builtin, nargs: usize) -> bool {
    let i = func.inst(v);
    matches!(&i.op, Op::Call { builtin, .. } if *builtin == want) && i.args.len() == nargs
}

/// [`ambient_partners`] of `block` and the blocks nested in it.
fn partners_in(func: &Function, block: &Block, out: &mut HashMap<Value, NormalSrc>) {
    for (i, node) in block.iter().enumerate() {
        match node {
            Node::Inst(v) if is_call(func, *v, Builtin::Ambient, 0) => {
                let mut stored = Vec::new();
                for later in &block[i + 1..] {
                    match later {
                        Node::Inst(w) if is_call(func, *w, Builtin::Diffuse, 1) => {
                            let a = func.inst(*w).args[0];
                            let src = match func.inst(a).op {
                                Op::Load(s) if !stored.contains(&s) && func.slot(s).ty.array.is_none() => {
                                    Some(NormalSrc::Slot(s))
                                }
                                _ if block[..i].contains(&Node::Inst(a)) => Some(NormalSrc::Value(a)),
                                _ => None,
                            };
                            if let Some(src) = src {
                                out.insert(*v, src);
                            }
                            break;
                        }
                        Node::Inst(_) => {}
                        Node::Store { slot, .. } => stored.push(*slot),
                        _ => break,
                    }
                }
            }
            Node::Inst(_) | Node::Store { .. } | Node::Break(_) | Node::Continue(_) | Node::Return => {}
            Node::If { then, otherwise, .. } => {
                partners_in(func, then, out);
                partners_in(func, otherwise, out);
            }
            Node::Loop { header, body, step, .. } => {
                partners_in(func, header, out);
                partners_in(func, body, out);
                partners_in(func, step, out);
            }
            Node::Frame(b)
            | Node::Illuminance { body: b, .. }
            | Node::Illuminate { body: b, .. }
            | Node::Solar { body: b, .. } => partners_in(func, b, out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::{Global, SlotKind};
    use crate::passes::{optimize, Analyzed, PassOptions};

    fn analyzed(body: &str) -> Analyzed {
        let src = format!("surface s(float Ka = 1; float Kd = 1) {{ {body} }}");
        let module = crate::compile_source("s.sl", &src, &crate::CompileOptions::default())
            .unwrap_or_else(|e| panic!("{e}"))
            .module;
        optimize(module, &PassOptions::default())
    }

    /// The `ambient()` calls of `func`.
    fn ambient_calls(func: &Function) -> Vec<Value> {
        (0..func.insts.len() as u32).map(Value).filter(|&v| is_call(func, v, Builtin::Ambient, 0)).collect()
    }

    #[test]
    fn matte_pairs_ambient_with_the_diffuse_of_nf() {
        let a = analyzed("normal Nf = faceforward(normalize(N), I); Ci = Cs * (Ka * ambient() + Kd * diffuse(Nf));");
        let func = &a.module().func;
        let partners = ambient_partners(func);
        let amb = ambient_calls(func);
        assert_eq!(amb.len(), 1);
        match partners.get(&amb[0]) {
            Some(NormalSrc::Slot(s)) => assert_eq!(func.slot(*s).name, "Nf"),
            other => panic!("expected the slot of Nf, found {other:?}"),
        }
        assert_eq!(partners.len(), 1);
        assert!(calls_ambient(func));
    }

    #[test]
    fn a_global_normal_is_its_slot() {
        let a = analyzed("Ci = Ka * ambient() + Kd * diffuse(N);");
        let func = &a.module().func;
        let amb = ambient_calls(func);
        assert_eq!(amb.len(), 1);
        match ambient_partners(func).get(&amb[0]) {
            Some(&NormalSrc::Slot(s)) => assert_eq!(func.slot(s).kind, SlotKind::Global(Global::N)),
            other => panic!("expected the slot of N, found {other:?}"),
        }
    }

    #[test]
    fn a_normal_written_in_between_is_no_partner() {
        let a = analyzed("normal Nf = normalize(N); color c = Ka * ambient(); Nf = -Nf; Ci = c + Kd * diffuse(Nf);");
        let func = &a.module().func;
        assert_eq!(ambient_calls(func).len(), 1);
        assert!(ambient_partners(func).is_empty(), "{:?}", ambient_partners(func));
    }

    #[test]
    fn a_normal_computed_after_ambient_is_no_partner() {
        let a = analyzed("Ci = Ka * ambient() + Kd * diffuse(normalize(N));");
        let func = &a.module().func;
        assert_eq!(ambient_calls(func).len(), 1);
        assert!(ambient_partners(func).is_empty(), "{:?}", ambient_partners(func));
    }

    #[test]
    fn a_diffuse_under_another_mask_is_no_partner() {
        let a = analyzed(
            "normal Nf = normalize(N); color c = Ka * ambient(); \
             if (s > 0.5) { c += Kd * diffuse(Nf); } Ci = c;",
        );
        let func = &a.module().func;
        assert_eq!(ambient_calls(func).len(), 1);
        assert!(ambient_partners(func).is_empty(), "{:?}", ambient_partners(func));
    }

    #[test]
    fn a_branch_in_between_is_no_partner() {
        // The branch may write the normal (and changes the mask in its arms).
        let a = analyzed(
            "normal Nf = normalize(N); color c = Ka * ambient(); \
             if (s > 0.5) { Nf = -Nf; } Ci = c + Kd * diffuse(Nf);",
        );
        let func = &a.module().func;
        assert_eq!(ambient_calls(func).len(), 1);
        assert!(ambient_partners(func).is_empty(), "{:?}", ambient_partners(func));
    }

    #[test]
    fn no_ambient_call_no_partner() {
        let a = analyzed("Ci = Kd * diffuse(normalize(N));");
        let func = &a.module().func;
        assert!(ambient_partners(func).is_empty());
        assert!(!calls_ambient(func));
    }
}
