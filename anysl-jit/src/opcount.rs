//! Dynamic operation counts of compiled code ([`JitOptions::count_ops`](crate::JitOptions)):
//! after LLVM's optimization pipeline and before machine code generation, every basic block
//! gets an increment of per-compilation counters by the number of operations it holds, so
//! after shading the counters hold the operations the optimized code executed — loops over
//! lights and noise octaves included, each iteration counted.
//!
//! What counts ([`classify`]), one per IR instruction:
//!
//! - **vector** (floating point on vectors): `fadd`, `fsub`, `fmul`, `fdiv`, `frem`, `fneg`,
//!   `fcmp`; `select` with a vector float or lane-mask (`<N x i1>`) result; `fptosi`,
//!   `fptoui`, `sitofp`, `uitofp`, `fptrunc`, `fpext`; every LLVM intrinsic on float vectors
//!   (`llvm.fma`/`llvm.fmuladd` — one operation: an FMA issues once —, `sqrt`, `floor`,
//!   `ceil`, `minnum`, `maxnum`, `fabs`, `copysign`, the x86 `rsqrt14`, …).
//! - **vector_int**: integer and lane-mask operations on vectors (`add`, `sub`, `mul`, shifts,
//!   `and`/`or`/`xor` — lane-mask logic is this —, `icmp`, `select` of integer vectors,
//!   integer intrinsics such as `llvm.vector.reduce.or` of a mask): the noise hash and the
//!   masked control flow.
//! - **scalar**: the same floating-point operations on scalar `float`/`double` (uniform
//!   values, loop counters of uniform loops).
//! - **calls**: calls of anything but an LLVM intrinsic — the Rust runtime library (noise,
//!   splines, matrices), the renderer's host callbacks and light loops, the per-lane `sin`/
//!   `cos` fallback. The operations executed *inside* those calls are not counted (they are
//!   Rust code, not code this compiler generated), only that a call was made; JIT code the
//!   renderer calls back (an `illuminance` body run by the renderer's loop) is counted.
//!
//! Not counted: loads, stores, `phi`, `extractelement`/`insertelement`/`shufflevector`,
//! bit casts, scalar integer arithmetic and branches.
//!
//! A vector operation counts once per `unit` lanes (rounded up): `unit` is the variant's
//! native lanes ([`Variant::native_lanes`](crate::Variant::native_lanes)), so an operation
//! on `<32 x float>` in the four-packet `X8x4` variant counts 4, as LLVM splits it into four
//! 8-lane instructions, and a count per 8-lane packet is the same for `X8` and `X8x4`. The
//! one-lane variants take 16 (a vector in their code is narrower than one register).
//!
//! These are counts of the optimized IR's operations, not retired machine instructions: the
//! code generator may still split one (a 16-lane operation on a machine without 512-bit
//! registers, `frem` into a library call) or fold an operation into another (a constant
//! operand into an instruction's memory operand does not change the count; a compare
//! feeding a select does not become fewer operations on x86).

use inkwell::basic_block::BasicBlock;
use inkwell::builder::Builder;
use inkwell::context::Context;
use inkwell::llvm_sys::core::{LLVMGetCalledValue, LLVMGetIntrinsicID, LLVMGetValueName2, LLVMIsAFunction};
use inkwell::module::Module;
use inkwell::types::{AnyTypeEnum, BasicTypeEnum};
use inkwell::values::{AsValueRef, InstructionOpcode, InstructionValue, Operand};
use inkwell::{AddressSpace, AtomicOrdering, AtomicRMWBinOp};
use std::ops::{Add, AddAssign};
use std::sync::atomic::{AtomicU64, Ordering};

/// Operations counted while compiled code ran (see the [module docs](self) for what counts).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCounts {
    /// Floating-point operations on vectors, in units of the variant's native width.
    pub vector: u64,
    /// Integer and lane-mask operations on vectors, in the same units.
    pub vector_int: u64,
    /// Floating-point operations on scalars.
    pub scalar: u64,
    /// Calls out of the generated code (runtime library, host callbacks); their insides are
    /// not counted.
    pub calls: u64,
}

impl OpCounts {
    /// Each count divided by `n` (per point, per packet).
    #[must_use]
    pub fn per(self, n: u64) -> [f64; 4] {
        let n = n.max(1) as f64;
        [self.vector as f64 / n, self.vector_int as f64 / n, self.scalar as f64 / n, self.calls as f64 / n]
    }
}

impl Add for OpCounts {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            vector: self.vector + o.vector,
            vector_int: self.vector_int + o.vector_int,
            scalar: self.scalar + o.scalar,
            calls: self.calls + o.calls,
        }
    }
}

impl AddAssign for OpCounts {
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

/// A kind of counted operation: the index of its counter in [`OpCounters`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpClass {
    /// [`OpCounts::vector`].
    Vector = 0,
    /// [`OpCounts::vector_int`].
    VectorInt = 1,
    /// [`OpCounts::scalar`].
    Scalar = 2,
    /// [`OpCounts::calls`].
    Call = 3,
}

/// The counters instrumented code increments, one `u64` per [`OpClass`] at a fixed address
/// (compiled into the code, so they must not move: they live in a `Box` beside the machine
/// code). Atomic increments, so code run on several threads counts exactly.
#[repr(C)]
#[derive(Debug, Default)]
pub struct OpCounters([AtomicU64; 4]);

impl OpCounters {
    /// The counts so far.
    #[must_use]
    pub fn get(&self) -> OpCounts {
        let c = |k: OpClass| self.0[k as usize].load(Ordering::Relaxed);
        OpCounts {
            vector: c(OpClass::Vector),
            vector_int: c(OpClass::VectorInt),
            scalar: c(OpClass::Scalar),
            calls: c(OpClass::Call),
        }
    }

    /// Sets every count to zero.
    pub fn reset(&self) {
        for c in &self.0 {
            c.store(0, Ordering::Relaxed);
        }
    }

    fn addr(&self, k: OpClass) -> u64 {
        (&self.0[k as usize] as *const AtomicU64) as u64
    }
}

/// The shape of a value's type, as far as counting goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shape {
    Float,
    FloatVec(u32),
    /// Integer vector: lanes, lane mask (`i1`).
    IntVec(u32, bool),
    Other,
}

fn shape_of_basic(t: BasicTypeEnum<'_>) -> Shape {
    match t {
        BasicTypeEnum::FloatType(_) => Shape::Float,
        BasicTypeEnum::VectorType(v) => match v.get_element_type() {
            BasicTypeEnum::FloatType(_) => Shape::FloatVec(v.get_size()),
            BasicTypeEnum::IntType(i) => Shape::IntVec(v.get_size(), i.get_bit_width() == 1),
            _ => Shape::Other,
        },
        _ => Shape::Other,
    }
}

fn shape_of(t: AnyTypeEnum<'_>) -> Shape {
    match t {
        AnyTypeEnum::FloatType(f) => shape_of_basic(f.into()),
        AnyTypeEnum::VectorType(v) => shape_of_basic(v.into()),
        _ => Shape::Other,
    }
}

fn operand_shape(inst: InstructionValue<'_>, k: u32) -> Shape {
    match inst.get_operand(k) {
        Some(Operand::Value(v)) => shape_of_basic(v.get_type()),
        _ => Shape::Other,
    }
}

/// The name of the LLVM intrinsic `inst` (a call) calls, `None` for any other callee.
fn intrinsic_name(inst: InstructionValue<'_>) -> Option<String> {
    // SAFETY: `inst` is a call instruction, so it has a called operand; the name is copied
    // out before the module can change.
    unsafe {
        let f = LLVMIsAFunction(LLVMGetCalledValue(inst.as_value_ref()));
        if f.is_null() || LLVMGetIntrinsicID(f) == 0 {
            return None;
        }
        let mut len = 0usize;
        let p = LLVMGetValueName2(f, &mut len);
        Some(String::from_utf8_lossy(std::slice::from_raw_parts(p.cast::<u8>(), len)).into_owned())
    }
}

/// Intrinsics that move memory or tell the optimizer something: never counted.
const NOT_OPERATIONS: [&str; 9] = [
    "llvm.lifetime.",
    "llvm.memcpy",
    "llvm.memmove",
    "llvm.memset",
    "llvm.masked.",
    "llvm.assume",
    "llvm.dbg.",
    "llvm.prefetch",
    "llvm.experimental.noalias",
];

/// The class of instruction `inst` and how many operations it counts for at `unit` lanes
/// per vector operation; `None` for what is not counted (see the [module docs](self)).
#[must_use]
pub fn classify(inst: InstructionValue<'_>, unit: u32) -> Option<(OpClass, u64)> {
    use InstructionOpcode as O;
    let times = |lanes: u32| u64::from(lanes.div_ceil(unit.max(1)));
    let float = |s: Shape| match s {
        Shape::Float => Some((OpClass::Scalar, 1)),
        Shape::FloatVec(n) => Some((OpClass::Vector, times(n))),
        _ => None,
    };
    let int = |s: Shape| match s {
        Shape::IntVec(n, _) => Some((OpClass::VectorInt, times(n))),
        _ => None,
    };
    let result = shape_of(inst.get_type());
    match inst.get_opcode() {
        O::FAdd | O::FSub | O::FMul | O::FDiv | O::FRem | O::FNeg => float(result),
        O::SIToFP | O::UIToFP | O::FPTrunc | O::FPExt => float(result),
        O::FCmp | O::FPToSI | O::FPToUI => float(operand_shape(inst, 0)),
        O::Select => match result {
            // A blend of lane masks is the masked control flow's select, counted with the
            // float operations it guards.
            Shape::IntVec(n, true) => Some((OpClass::Vector, times(n))),
            s => float(s).or_else(|| int(s)),
        },
        O::Add
        | O::Sub
        | O::Mul
        | O::UDiv
        | O::SDiv
        | O::URem
        | O::SRem
        | O::Shl
        | O::LShr
        | O::AShr
        | O::And
        | O::Or
        | O::Xor => int(result),
        O::ICmp => int(operand_shape(inst, 0)),
        O::Call => match intrinsic_name(inst) {
            None => Some((OpClass::Call, 1)),
            Some(name) if NOT_OPERATIONS.iter().any(|p| name.starts_with(p)) => None,
            Some(_) => {
                // The vector among the result and the first argument (a reduction returns a
                // scalar), else the result.
                let first = operand_shape(inst, 0);
                let s = match (result, first) {
                    (Shape::FloatVec(_) | Shape::IntVec(..), _) => result,
                    (_, Shape::FloatVec(_) | Shape::IntVec(..)) => first,
                    _ => result,
                };
                float(s).or_else(|| int(s))
            }
        },
        _ => None,
    }
}

/// The operations of one execution of block `bb`, by [`OpClass`].
#[must_use]
pub fn block_counts(bb: BasicBlock<'_>, unit: u32) -> [u64; 4] {
    let mut n = [0u64; 4];
    let mut i = bb.get_first_instruction();
    while let Some(inst) = i {
        if let Some((class, k)) = classify(inst, unit) {
            n[class as usize] += k;
        }
        i = inst.get_next_instruction();
    }
    n
}

/// The operations of every block of `m` executed once each (a static count, for reading
/// against the dynamic one).
#[must_use]
pub fn static_counts(m: &Module<'_>, unit: u32) -> OpCounts {
    let mut n = [0u64; 4];
    for f in m.get_functions() {
        for bb in f.get_basic_blocks() {
            for (a, b) in n.iter_mut().zip(block_counts(bb, unit)) {
                *a += b;
            }
        }
    }
    OpCounts { vector: n[0], vector_int: n[1], scalar: n[2], calls: n[3] }
}

/// Adds to each block of every function defined in `m`, at its first insertion point (after
/// its `phi`s), an atomic increment of `counters` by the block's operations
/// ([`block_counts`]). Run after optimization: the increments are opaque to nothing but
/// the counters, yet they would stop the optimizer from merging or deleting blocks.
pub fn instrument(cx: &Context, m: &Module<'_>, counters: &OpCounters, unit: u32) {
    let i64t = cx.i64_type();
    let ptr =
        |k: OpClass| i64t.const_int(counters.addr(k), false).const_to_pointer(i64t.ptr_type(AddressSpace::default()));
    let b: Builder<'_> = cx.create_builder();
    for f in m.get_functions() {
        for bb in f.get_basic_blocks() {
            let n = block_counts(bb, unit);
            if n.iter().all(|&k| k == 0) {
                continue;
            }
            let mut at = bb.get_first_instruction();
            while let Some(i) = at.filter(|i| i.get_opcode() == InstructionOpcode::Phi) {
                at = i.get_next_instruction();
            }
            let Some(at) = at else { continue };
            b.position_before(&at);
            for class in [OpClass::Vector, OpClass::VectorInt, OpClass::Scalar, OpClass::Call] {
                let k = n[class as usize];
                if k != 0 {
                    b.build_atomicrmw(
                        AtomicRMWBinOp::Add,
                        ptr(class),
                        i64t.const_int(k, false),
                        AtomicOrdering::Monotonic,
                    )
                    .expect("atomicrmw");
                }
            }
        }
    }
}
