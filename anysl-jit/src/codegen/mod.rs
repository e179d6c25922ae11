//! IR → LLVM IR: subroutine-threaded code over a target description, with whole-function
//! vectorization of the structured control flow.
//!
//! Every placed instruction becomes a call to a target-library function `ar_<op>_<types>.<reprs>`
//! (created on first use in the same module, `alwaysinline`, internal), whose body is built
//! from the primitives of [`Cg`]: LLVM arithmetic on `float` (uniform values), `<N x float>`
//! (varying values) or triples of those (dual numbers), and calls into the runtime library
//! ([`crate::rt`]) or the host for the rest. The inliner removes every trace of the threading.
//!
//! Control flow follows the interpreter's masked semantics exactly: the current lane mask lives
//! in an entry-block `alloca` (mem2reg makes it SSA); a varying `if` runs each arm under its mask
//! and is skipped when no lane takes it (`llvm.vector.reduce.or`); uniform branches stay
//! branches; loops carry a live mask with break/continue masks per level; `return` collects
//! lanes per inlined frame; stores into varying variables blend with the mask.
//!
//! The generator is one type, [`Cg`], whose methods are spread over files by idea. This file
//! holds [`Cg`], its state and its type and constant helpers. `value` (the values of code
//! generation) and `params` (the parameter block) import no other file; the others import
//! this one, those two, and a few `call` (`space_index`), `math` or `noise`, so the imports
//! between files form no cycle:
//!
//! - `algebra`: float and mask algebra, composite numerics;
//! - `call`: runtime-library and host calls, threaded target-library functions;
//! - `fusion`: light calls that share one visit of the lights (the analysis deciding which is
//!   [`anysl_rsl::passes::lights`]);
//! - `slot`: masks and variables in memory, array elements;
//! - `shade`: the shade function (entry, globals, parameters, outputs);
//! - `flow`: masked control flow; `illuminance`: light loops with a body;
//! - `inst`: instructions and the ops other than built-in calls; `builtin`: the built-ins;
//! - `math`, `noise`, `lights`, `points`: inline transcendentals, inline noise, the built-in
//!   light loops over lights as data, the points entry.

mod algebra;
mod builtin;
mod call;
mod flow;
mod fusion;
mod illuminance;
mod inst;
mod lights;
mod math;
mod noise;
mod params;
mod points;
mod shade;
mod slot;
mod value;

pub use params::param_block;
pub use value::{CgError, Repr, Shape, Val, M, S};

use crate::abi;
use crate::rt::RtKind;
use anysl_rsl::ir::{Function, SlotId, Value};
use anysl_rsl::passes::lights::{ambient_partners, NormalSrc};
use inkwell::builder::Builder;
use inkwell::context::Context;
use inkwell::intrinsics::Intrinsic;
use inkwell::module::Module;
use inkwell::types::{BasicType, BasicTypeEnum, FloatType, VectorType};
use inkwell::values::{BasicMetadataValueEnum, BasicValueEnum, FunctionValue, IntValue, PointerValue};
use inkwell::AddressSpace;
use std::collections::HashMap;

/// The concrete types a shader is compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Target {
    /// Lanes of the varying vectors (1 = scalar).
    pub lanes: u32,
    /// Lanes of one packet: `lanes` is `native` times the packets shaded per call. Runtime
    /// library calls and target intrinsics are issued once per packet.
    pub native: u32,
    /// Varying values whose derivatives are needed are dual numbers.
    pub dual: bool,
    /// Lower each op to a call of a threaded target-library function (else inline).
    pub threaded: bool,
    /// Emit `noise`/`snoise`/`cellnoise` as inline IR (else a call into the Rust library).
    pub inline_noise: bool,
    /// Read numeric parameters from the run-time parameter block (the shade function's
    /// `params` argument, laid out by [`param_block`]) instead of compiling their values in.
    pub runtime_params: bool,
    /// Also write the numeric output parameters to the output buffer, after the
    /// [`abi::OUTPUT_VALUES`] standard outputs ([`abi::output_params`]).
    pub output_params: bool,
    /// The light loops read the context's light records, not its lights as data
    /// ([`crate::JitOptions::light_records`]).
    pub light_records: bool,
}

/// Storage of a variable.
#[derive(Clone, Debug)]
struct SlotStore<'c> {
    r: Repr,
    /// Per component: value pointer and, for dual slots, derivative pointers.
    ptrs: Vec<(PointerValue<'c>, Option<(PointerValue<'c>, PointerValue<'c>)>)>,
    is_str: bool,
}

/// The per-function state (swapped when generating an `illuminance` body).
#[derive(Clone)]
struct FnState<'c> {
    f: FunctionValue<'c>,
    mask: PointerValue<'c>,
    loops: Vec<(PointerValue<'c>, PointerValue<'c>)>,
    rets: Vec<PointerValue<'c>>,
    ctx: BasicValueEnum<'c>,
    host: BasicValueEnum<'c>,
    g: BasicValueEnum<'c>,
}

/// The code generator.
pub struct Cg<'c, 'm> {
    cx: &'c Context,
    /// The module being built.
    pub m: Module<'c>,
    b: Builder<'c>,
    t: Target,
    func: &'m Function,
    f32t: FloatType<'c>,
    vals: Vec<Option<Val<'c>>>,
    inst_repr: Vec<Repr>,
    slots: Vec<SlotStore<'c>>,
    strs: HashMap<u32, Vec<String>>,
    st: Option<FnState<'c>>,
    rt_v: fn(RtKind, u32) -> usize,
    rt_u: fn(RtKind, u32) -> usize,
    /// Resolves runtime calls that take every packet of a multi-packet variant at once
    /// ([`crate::rt::rt_addr_packets`]); `None`: each packet is called on its own.
    rt_packets: Option<fn(RtKind, u32) -> Option<usize>>,
    body_count: u32,
    shapes: HashMap<String, Vec<Shape>>,
    /// Extra function attributes (`target-cpu`, `target-features`).
    pub fn_attrs: Vec<(String, String)>,
    /// Threaded functions created (name → count of calls).
    pub threaded_fns: usize,
    /// Where the globals lie in the renderer's `Globals` struct.
    pub layout: abi::GlobalsLayout,
    /// The light sums of the last `specular` call ([`Cg::lit_call`]).
    lit: Option<LitMemo<'c>>,
    /// Where the normal of the kept sums came from ([`Cg::normal_key`]), and the mask slot
    /// and [`Cg::mask_stores`] count they were computed under.
    lit_key: Option<(Option<NormalKey>, PointerValue<'c>, u32)>,
    /// Mask stores generated so far.
    mask_stores: std::cell::Cell<u32>,
    /// Stores generated into each slot so far (a load of a slot between two calls with the
    /// same count reads the same value).
    slot_stores: Vec<std::cell::Cell<u32>>,
    /// `ambient()` calls followed by a `diffuse(N)` under the same mask whose normal is
    /// known at the `ambient()` call ([`ambient_partners`]).
    amb_partner: HashMap<Value, NormalSrc>,
    /// Light calls made now call the renderer even when the context describes its lights
    /// as data ([`Cg::light_call`]).
    lights_by_renderer: bool,
    /// A light shader without an `L` variable: the slot (after the IR's) that keeps the `L`
    /// of its `illuminate`/`solar` statements for the light's output.
    light_l: Option<SlotId>,
    /// The host callbacks the generated code calls (bit `k` for [`crate::rt::Host`] `k`).
    pub host_used: std::cell::Cell<u64>,
    /// Light shaders compiled into the light loops over records: a record whose entry is the
    /// address here runs the function (the light's direct entry, linked in and inlined)
    /// instead of calling the entry ([`Cg::call_light_code`]).
    pub inline_lights: Vec<(u64, FunctionValue<'c>)>,
    /// Whether the generated code calls [`Cg::inline_lights`] (it has a light loop over
    /// records with code).
    pub inline_lights_called: std::cell::Cell<bool>,
}

/// Where a light call's normal comes from, as far as the code generator can tell: the same
/// key at two calls means the same normal (the kept sums are tried only then).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum NormalKey {
    /// An IR value.
    Value(Value),
    /// A slot, with the number of stores into it generated before the load.
    Slot(SlotId, u32),
}

/// What a `specular` call left for the `diffuse` and `ambient` calls after it: its light loop
/// also summed `diffuse(N)` and, when the shader calls `ambient()`, the ambient light, under
/// the same mask. Kept in stack slots of the function that made the call; a later call
/// compares its normal and mask with the stored ones and takes the stored sums when they
/// are equal, else calls the renderer. When the values are the same SSA values — the usual
/// `ambient() + diffuse(Nf) + specular(Nf, V, roughness)` — LLVM folds the comparison and
/// the later calls disappear.
#[derive(Clone, Copy)]
struct LitMemo<'c> {
    f: FunctionValue<'c>,
    valid: PointerValue<'c>,
    n: [PointerValue<'c>; 3],
    mask: PointerValue<'c>,
    diff: [PointerValue<'c>; 3],
    amb: Option<[PointerValue<'c>; 3]>,
}

const SHADE_NAME: &str = "anysl_shade";

/// Name of the generated points entry.
pub const POINTS_NAME: &str = "anysl_shade_points";

/// Name of a light shader's direct entry ([`anysl_core::LightCode`]).
pub const LIGHT_NAME: &str = "anysl_light";

/// Name of the direct entry of the `k`-th light shader compiled into a surface's light loops.
#[must_use]
pub fn inline_light_name(k: usize) -> String {
    format!("anysl_inline_light_{k}")
}

/// Marks `f` `alwaysinline`.
pub fn always_inline(cx: &Context, f: FunctionValue<'_>) {
    f.add_attribute(
        inkwell::attributes::AttributeLoc::Function,
        cx.create_enum_attribute(inkwell::attributes::Attribute::get_named_enum_kind_id("alwaysinline"), 0),
    );
}

impl<'c, 'm> Cg<'c, 'm> {
    /// A generator for `func` with target `t`, calling the runtime of `variant`'s float type
    /// for varying values ([`crate::rt::rt_addr`], and [`crate::rt::rt_addr_packets`] for its
    /// multi-packet calls) and of `f32` for uniform ones.
    pub fn new(cx: &'c Context, func: &'m Function, t: Target, variant: crate::Variant) -> Self {
        let m = cx.create_module("shader");
        Self {
            cx,
            m,
            b: cx.create_builder(),
            t,
            func,
            f32t: cx.f32_type(),
            vals: vec![None; func.insts.len()],
            inst_repr: Vec::new(),
            slots: Vec::new(),
            strs: HashMap::new(),
            st: None,
            rt_v: variant.rt_resolver(),
            rt_u: crate::Variant::F32.rt_resolver(),
            rt_packets: variant.rt_packets_resolver(),
            body_count: 0,
            lit: None,
            lit_key: None,
            mask_stores: std::cell::Cell::new(0),
            slot_stores: vec![std::cell::Cell::new(0); func.slots.len()],
            amb_partner: ambient_partners(func),
            lights_by_renderer: false,
            light_l: None,
            host_used: std::cell::Cell::new(0),
            inline_lights: Vec::new(),
            inline_lights_called: std::cell::Cell::new(false),
            shapes: HashMap::new(),
            fn_attrs: Vec::new(),
            threaded_fns: 0,
            layout: abi::GlobalsLayout { comp: [0; abi::GLOBAL_VALUES], dual: [0, 0] },
        }
    }

    /// The name of the generated shade function.
    #[must_use]
    pub fn shade_name() -> &'static str {
        SHADE_NAME
    }

    // ---------------------------------------------------------------- types and constants

    fn vt(&self) -> BasicTypeEnum<'c> {
        if self.t.lanes == 1 {
            self.f32t.into()
        } else {
            self.f32t.vec_type(self.t.lanes).into()
        }
    }
    fn fty(&self, r: Repr) -> BasicTypeEnum<'c> {
        match r {
            Repr::U => self.f32t.into(),
            _ => self.vt(),
        }
    }
    fn mty(&self, uni: bool) -> BasicTypeEnum<'c> {
        let i1 = self.cx.bool_type();
        if uni || self.t.lanes == 1 {
            i1.into()
        } else {
            i1.vec_type(self.t.lanes).into()
        }
    }
    fn full(&self) -> Repr {
        if self.t.dual {
            Repr::D
        } else {
            Repr::V
        }
    }
    fn stride(&self) -> u32 {
        self.t.lanes * if self.t.dual { 3 } else { 1 }
    }
    fn i32c(&self, v: u64) -> IntValue<'c> {
        self.cx.i32_type().const_int(v, false)
    }
    fn fc(&self, x: f64) -> S<'c> {
        S { r: Repr::U, v: self.f32t.const_float(x as f32 as f64).into(), d: None }
    }
    fn fconst_r(&self, x: f64, r: Repr) -> BasicValueEnum<'c> {
        let f = self.f32t.const_float(x as f32 as f64);
        match r {
            Repr::U => f.into(),
            _ if self.t.lanes == 1 => f.into(),
            _ => VectorType::const_vector(&vec![f; self.t.lanes as usize]).into(),
        }
    }
    fn mconst(&self, b: bool) -> M<'c> {
        M { uni: true, v: self.cx.bool_type().const_int(u64::from(b), false).into() }
    }
    fn ptr_ty(&self, t: BasicTypeEnum<'c>) -> inkwell::types::PointerType<'c> {
        t.ptr_type(AddressSpace::default())
    }
    fn i8p(&self) -> inkwell::types::PointerType<'c> {
        self.cx.i8_type().ptr_type(AddressSpace::default())
    }

    fn st(&self) -> &FnState<'c> {
        self.st.as_ref().expect("inside a function")
    }

    fn cur_fn(&self) -> FunctionValue<'c> {
        self.b.get_insert_block().and_then(|b| b.get_parent()).expect("positioned")
    }

    fn entry_alloca(&self, t: BasicTypeEnum<'c>) -> PointerValue<'c> {
        let f = self.cur_fn();
        let entry = f.get_first_basic_block().expect("entry");
        let tb = self.cx.create_builder();
        match entry.get_first_instruction() {
            Some(i) => tb.position_before(&i),
            None => tb.position_at_end(entry),
        }
        tb.build_alloca(t, "").expect("alloca")
    }

    fn call_intr(&self, name: &str, tys: &[BasicTypeEnum<'c>], args: &[BasicValueEnum<'c>]) -> BasicValueEnum<'c> {
        let i = Intrinsic::find(name).unwrap_or_else(|| panic!("intrinsic {name}"));
        let f = i.get_declaration(&self.m, tys).unwrap_or_else(|| panic!("declaration of {name}"));
        let a: Vec<BasicMetadataValueEnum> = args.iter().map(|&v| v.into()).collect();
        self.b.build_call(f, &a, "").expect("call").try_as_basic_value().basic().expect("value")
    }
}
