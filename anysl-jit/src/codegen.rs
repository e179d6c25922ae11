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

mod lights;
mod math;
mod noise;
mod points;

pub use points::POINTS_NAME;

use crate::abi::{self, Host, GLOBAL_ORDER};
use crate::rt::{self, RtKind};
use anysl_rsl::builtins::Builtin;
use anysl_rsl::ir::{self, BinOp, Block, Const, Function, Global, Node, Op, SlotId, SlotKind, UnOp, Value};
use anysl_rsl::passes::lights::{ambient_partners, calls_ambient, NormalSrc};
use anysl_rsl::passes::Analyzed;
use anysl_rsl::types::{BaseType, Detail, Type};
use inkwell::attributes::{Attribute, AttributeLoc};
use inkwell::builder::Builder;
use inkwell::context::Context;
use inkwell::intrinsics::Intrinsic;
use inkwell::module::{Linkage, Module};
use inkwell::types::{BasicMetadataTypeEnum, BasicType, BasicTypeEnum, FloatType, VectorType};
use inkwell::values::{
    BasicMetadataValueEnum, BasicValue, BasicValueEnum, CallableValue, FunctionValue, IntValue, PointerValue,
};
use inkwell::{AddressSpace, FloatPredicate, IntPredicate};
use std::collections::{HashMap, HashSet};

/// How a number is held: a uniform scalar, a varying vector, or a varying dual number.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Repr {
    /// One `float` for every lane.
    U,
    /// One value per lane.
    V,
    /// Value, ∂/∂x and ∂/∂y per lane.
    D,
}

impl Repr {
    fn letter(self) -> char {
        match self {
            Repr::U => 'u',
            Repr::V => 'v',
            Repr::D => 'd',
        }
    }
}

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
}

/// One float: its value and, for dual numbers, its derivatives.
#[derive(Clone, Copy, Debug)]
pub struct S<'c> {
    r: Repr,
    v: BasicValueEnum<'c>,
    d: Option<(BasicValueEnum<'c>, BasicValueEnum<'c>)>,
}

/// A mask (boolean): uniform `i1` or varying `<N x i1>`.
#[derive(Clone, Copy, Debug)]
pub struct M<'c> {
    uni: bool,
    v: BasicValueEnum<'c>,
}

/// A value of the IR during code generation.
#[derive(Clone, Debug)]
pub enum Val<'c> {
    /// Float components (1, 3, 16 or arrays of those).
    Num(Vec<S<'c>>),
    /// A boolean.
    Mask(M<'c>),
    /// A string (compile-time).
    Str(Vec<String>),
    /// Nothing.
    Void,
}

/// Storage of a variable.
#[derive(Clone, Debug)]
struct SlotStore<'c> {
    r: Repr,
    /// Per component: value pointer and, for dual slots, derivative pointers.
    ptrs: Vec<(PointerValue<'c>, Option<(PointerValue<'c>, PointerValue<'c>)>)>,
    is_str: bool,
}

/// A code generation error (an unsupported op or built-in).
#[derive(Clone, Debug)]
pub struct CgError(pub String);

type R<T> = Result<T, CgError>;

fn err<T>(s: impl Into<String>) -> R<T> {
    Err(CgError(s.into()))
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

impl<'c, 'm> Cg<'c, 'm> {
    /// A generator for `func` with target `t`; `rt_v`/`rt_u` resolve runtime calls
    /// ([`rt::rt_addr`]) for the varying float type and for `f32`.
    pub fn new(
        cx: &'c Context,
        func: &'m Function,
        t: Target,
        rt_v: fn(RtKind, u32) -> usize,
        rt_u: fn(RtKind, u32) -> usize,
    ) -> Self {
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
            rt_v,
            rt_u,
            body_count: 0,
            lit: None,
            lit_key: None,
            mask_stores: std::cell::Cell::new(0),
            slot_stores: vec![std::cell::Cell::new(0); func.slots.len()],
            amb_partner: ambient_partners(func),
            lights_by_renderer: false,
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

    // ---------------------------------------------------------------- float algebra

    fn splat(&self, v: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        if self.t.lanes == 1 {
            return v;
        }
        if let BasicValueEnum::FloatValue(f) = v {
            if let Some(c) = f.get_constant() {
                return self.fconst_r(c.0, Repr::V);
            }
        }
        let vty = self.f32t.vec_type(self.t.lanes);
        let undef = vty.get_undef();
        let ins = self.b.build_insert_element(undef, v, self.i32c(0), "").expect("insert");
        let zeros = self.cx.i32_type().vec_type(self.t.lanes).const_zero();
        self.b.build_shuffle_vector(ins, undef, zeros, "").expect("shuffle").into()
    }

    fn splat_mask(&self, m: M<'c>) -> M<'c> {
        if !m.uni || self.t.lanes == 1 {
            return M { uni: false, v: m.v };
        }
        let vty = self.cx.bool_type().vec_type(self.t.lanes);
        let undef = vty.get_undef();
        let ins = self.b.build_insert_element(undef, m.v, self.i32c(0), "").expect("insert");
        let zeros = self.cx.i32_type().vec_type(self.t.lanes).const_zero();
        M { uni: false, v: self.b.build_shuffle_vector(ins, undef, zeros, "").expect("shuffle").into() }
    }

    fn zero_r(&self, r: Repr) -> BasicValueEnum<'c> {
        self.fconst_r(0.0, r)
    }

    /// `s` converted to representation `r`.
    fn to(&self, s: S<'c>, r: Repr) -> S<'c> {
        if s.r == r {
            return s;
        }
        match (s.r, r) {
            (Repr::U, Repr::V) => S { r, v: self.splat(s.v), d: None },
            (Repr::U, Repr::D) => {
                let z = self.zero_r(Repr::V);
                S { r, v: self.splat(s.v), d: Some((z, z)) }
            }
            (Repr::V, Repr::D) => {
                let z = self.zero_r(Repr::V);
                S { r, v: s.v, d: Some((z, z)) }
            }
            (Repr::D, Repr::V) => S { r, v: s.v, d: None },
            (_, Repr::U) => {
                // Only reached for values the analysis proved uniform: lane 0 holds them.
                let v = if self.t.lanes == 1 {
                    s.v
                } else {
                    self.b.build_extract_element(s.v.into_vector_value(), self.i32c(0), "").expect("extract")
                };
                S { r, v, d: None }
            }
            _ => s,
        }
    }

    fn arith(&self, op: char, a: BasicValueEnum<'c>, b: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        macro_rules! go {
            ($x:expr, $y:expr) => {
                match op {
                    '+' => self.b.build_float_add($x, $y, "").expect("op").into(),
                    '-' => self.b.build_float_sub($x, $y, "").expect("op").into(),
                    '*' => self.b.build_float_mul($x, $y, "").expect("op").into(),
                    _ => self.b.build_float_div($x, $y, "").expect("op").into(),
                }
            };
        }
        match (a, b) {
            (BasicValueEnum::FloatValue(x), BasicValueEnum::FloatValue(y)) => go!(x, y),
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => go!(x, y),
            _ => panic!("arith on mixed types {a:?} {b:?}"),
        }
    }
    fn fneg_raw(&self, a: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        match a {
            BasicValueEnum::FloatValue(x) => self.b.build_float_neg(x, "").expect("neg").into(),
            BasicValueEnum::VectorValue(x) => self.b.build_float_neg(x, "").expect("neg").into(),
            _ => panic!("neg"),
        }
    }
    fn fcmp_raw(&self, p: FloatPredicate, a: BasicValueEnum<'c>, b: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        match (a, b) {
            (BasicValueEnum::FloatValue(x), BasicValueEnum::FloatValue(y)) => {
                self.b.build_float_compare(p, x, y, "").expect("cmp").into()
            }
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => {
                self.b.build_float_compare(p, x, y, "").expect("cmp").into()
            }
            _ => panic!("cmp"),
        }
    }
    fn sel_raw(&self, m: BasicValueEnum<'c>, a: BasicValueEnum<'c>, b: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        match m {
            BasicValueEnum::IntValue(c) => self.b.build_select(c, a, b, "").expect("select"),
            BasicValueEnum::VectorValue(c) => self.b.build_select(c, a, b, "").expect("select"),
            _ => panic!("select"),
        }
    }
    fn unary_intr(&self, name: &str, a: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        self.call_intr(name, &[a.get_type()], &[a])
    }

    fn unify(&self, a: S<'c>, b: S<'c>) -> (S<'c>, S<'c>) {
        let r = a.r.max(b.r);
        (self.to(a, r), self.to(b, r))
    }

    fn add(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        let (a, b) = self.unify(a, b);
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => Some((self.arith('+', ax, bx), self.arith('+', ay, by))),
            _ => None,
        };
        S { r: a.r, v: self.arith('+', a.v, b.v), d }
    }
    fn sub(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        let (a, b) = self.unify(a, b);
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => Some((self.arith('-', ax, bx), self.arith('-', ay, by))),
            _ => None,
        };
        S { r: a.r, v: self.arith('-', a.v, b.v), d }
    }
    fn mul(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        let (a, b) = self.unify(a, b);
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => {
                let dx = self.arith('+', self.arith('*', ax, b.v), self.arith('*', a.v, bx));
                let dy = self.arith('+', self.arith('*', ay, b.v), self.arith('*', a.v, by));
                Some((dx, dy))
            }
            _ => None,
        };
        S { r: a.r, v: self.arith('*', a.v, b.v), d }
    }
    /// `a·m + c` as the library's `ShadingFloat::mul_add`: fused (`llvm.fma`) where the
    /// library's is ([`anysl_simd::kernel_consts::FUSED_MUL_ADD`]), dual numbers fused in
    /// their value with `∂a·m + (a·∂m + ∂c)` as derivatives.
    fn fma(&self, a: S<'c>, m: S<'c>, c: S<'c>) -> S<'c> {
        if !anysl_simd::kernel_consts::FUSED_MUL_ADD {
            return self.add(self.mul(a, m), c);
        }
        let r = a.r.max(m.r).max(c.r);
        let (a, m, c) = (self.to(a, r), self.to(m, r), self.to(c, r));
        let f = |x: BasicValueEnum<'c>, y: BasicValueEnum<'c>, z: BasicValueEnum<'c>| {
            self.call_intr("llvm.fma", &[x.get_type()], &[x, y, z])
        };
        let d = match (a.d, m.d, c.d) {
            (Some((ax, ay)), Some((mx, my)), Some((cx, cy))) => {
                Some((f(ax, m.v, f(a.v, mx, cx)), f(ay, m.v, f(a.v, my, cy))))
            }
            _ => None,
        };
        S { r, v: f(a.v, m.v, c.v), d }
    }
    fn finite_or_zero(&self, x: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        let ax = self.unary_intr("llvm.fabs", x);
        let inf = self.fconst_r(f64::INFINITY, Repr::V);
        let ok = self.fcmp_raw(FloatPredicate::OLT, ax, inf);
        self.sel_raw(ok, x, self.zero_r(Repr::V))
    }
    fn div(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        let (a, b) = self.unify(a, b);
        let q = self.arith('/', a.v, b.v);
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => {
                let inv = self.arith('/', self.fconst_r(1.0, Repr::V), b.v);
                let dx = self.arith('*', self.arith('-', ax, self.arith('*', q, bx)), inv);
                let dy = self.arith('*', self.arith('-', ay, self.arith('*', q, by)), inv);
                Some((self.finite_or_zero(dx), self.finite_or_zero(dy)))
            }
            _ => None,
        };
        S { r: a.r, v: q, d }
    }
    fn neg(&self, a: S<'c>) -> S<'c> {
        S { r: a.r, v: self.fneg_raw(a.v), d: a.d.map(|(x, y)| (self.fneg_raw(x), self.fneg_raw(y))) }
    }
    fn constant_part(&self, r: Repr, v: BasicValueEnum<'c>) -> S<'c> {
        let z = self.zero_r(Repr::V);
        S { r, v, d: (r == Repr::D).then_some((z, z)) }
    }
    fn floor(&self, a: S<'c>) -> S<'c> {
        self.constant_part(a.r, self.unary_intr("llvm.floor", a.v))
    }
    fn ceil(&self, a: S<'c>) -> S<'c> {
        self.constant_part(a.r, self.unary_intr("llvm.ceil", a.v))
    }
    fn abs(&self, a: S<'c>) -> S<'c> {
        let v = self.unary_intr("llvm.fabs", a.v);
        let d = a.d.map(|(x, y)| {
            let neg = self.fcmp_raw(FloatPredicate::OLT, a.v, self.zero_r(Repr::V));
            (self.sel_raw(neg, self.fneg_raw(x), x), self.sel_raw(neg, self.fneg_raw(y), y))
        });
        S { r: a.r, v, d }
    }
    fn sqrt(&self, a: S<'c>) -> S<'c> {
        let s = self.unary_intr("llvm.sqrt", a.v);
        let d = a.d.map(|(x, y)| {
            let k = self.finite_or_zero(self.arith('/', self.fconst_r(0.5, Repr::V), s));
            (self.arith('*', x, k), self.arith('*', y, k))
        });
        S { r: a.r, v: s, d }
    }
    /// A constant of `x`'s shape (scalar or vector of the variant's lanes).
    fn const_like(&self, x: BasicValueEnum<'c>, v: f64) -> BasicValueEnum<'c> {
        self.fconst_r(v, if x.is_vector_value() { Repr::V } else { Repr::U })
    }
    /// `a·m + c` fused on raw values ([`Cg::fma`] without derivatives).
    fn fma_raw(&self, a: BasicValueEnum<'c>, m: BasicValueEnum<'c>, c: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        if anysl_simd::kernel_consts::FUSED_MUL_ADD {
            self.call_intr("llvm.fma", &[a.get_type()], &[a, m, c])
        } else {
            self.arith('+', self.arith('*', a, m), c)
        }
    }
    /// The hardware estimate of 1/√x that `anysl_core::rsqrt_f32` and the SIMD kernels start
    /// from — AVX-512's `vrsqrt14` or the SSE/AVX `rsqrt` ([`anysl_core::RSQRT_ESTIMATE_14`])
    /// — for a scalar or a vector of 4, 8 or 16 lanes.
    fn rsqrt_estimate(&self, x: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        if !cfg!(target_arch = "x86_64") {
            return self.arith('/', self.const_like(x, 1.0), self.unary_intr("llvm.sqrt", x));
        }
        if let BasicValueEnum::VectorValue(v) = x {
            if v.get_type().get_size() > self.t.native {
                let parts: Vec<_> =
                    self.packets_of(v).into_iter().map(|p| self.rsqrt_estimate(p.into()).into_vector_value()).collect();
                return self.concat(&parts).into();
            }
        }
        let v4 = self.f32t.vec_type(4);
        let ones8 = self.cx.i8_type().const_all_ones();
        let est14 = anysl_core::RSQRT_ESTIMATE_14;
        match x {
            BasicValueEnum::FloatValue(f) => {
                let zero = self.i32c(0);
                let xv: BasicValueEnum<'c> =
                    self.b.build_insert_element(v4.get_undef(), f, zero, "").expect("insert").into();
                let r = if est14 {
                    self.call_intr("llvm.x86.avx512.rsqrt14.ss", &[], &[xv, xv, v4.const_zero().into(), ones8.into()])
                } else {
                    self.call_intr("llvm.x86.sse.rsqrt.ss", &[], &[xv])
                };
                self.b.build_extract_element(r.into_vector_value(), zero, "").expect("extract")
            }
            BasicValueEnum::VectorValue(v) => {
                let n = v.get_type().get_size();
                let vz: BasicValueEnum<'c> = v.get_type().const_zero().into();
                match (n, est14) {
                    (4, true) => self.call_intr("llvm.x86.avx512.rsqrt14.ps.128", &[], &[x, vz, ones8.into()]),
                    (8, true) => self.call_intr("llvm.x86.avx512.rsqrt14.ps.256", &[], &[x, vz, ones8.into()]),
                    (16, true) => self.call_intr(
                        "llvm.x86.avx512.rsqrt14.ps.512",
                        &[],
                        &[x, vz, self.cx.i16_type().const_all_ones().into()],
                    ),
                    (4, false) => self.call_intr("llvm.x86.sse.rsqrt.ps", &[], &[x]),
                    (8, false) => self.call_intr("llvm.x86.avx.rsqrt.ps.256", &[], &[x]),
                    (16, false) => {
                        // Two 8-lane halves, as the library's 16 lanes without AVX-512.
                        let half = |lo: u32| {
                            let idx: Vec<_> = (lo..lo + 8).map(|i| self.i32c(u64::from(i))).collect();
                            let h = self
                                .b
                                .build_shuffle_vector(v, v.get_type().get_undef(), VectorType::const_vector(&idx), "")
                                .expect("shuffle");
                            self.call_intr("llvm.x86.avx.rsqrt.ps.256", &[], &[h.into()]).into_vector_value()
                        };
                        let (a, b) = (half(0), half(8));
                        let idx: Vec<_> = (0..16).map(|i| self.i32c(i)).collect();
                        self.b.build_shuffle_vector(a, b, VectorType::const_vector(&idx), "").expect("shuffle").into()
                    }
                    _ => panic!("rsqrt estimate of {n} lanes"),
                }
            }
            _ => panic!("rsqrt of a non-float"),
        }
    }
    /// `ShadingFloat::rsqrt` as `f32` and its SIMD types compute it (`anysl_core::rsqrt_f32`):
    /// the estimate, one Newton step `y + y/2·(1 - (x·y)·y)`, the estimate where that gives
    /// NaN, subnormal inputs scaled by 2^24 for the 12-bit estimate; dual numbers with the
    /// derivative `-r³/2` (0 where not finite), as `anysl-ad`.
    fn rsqrt(&self, a: S<'c>) -> S<'c> {
        let x = a.v;
        let c = |v: f64| self.const_like(x, v);
        let legacy = !anysl_core::RSQRT_ESTIMATE_14;
        let tiny = legacy.then(|| {
            self.fcmp_raw(FloatPredicate::OLT, self.unary_intr("llvm.fabs", x), c(f64::from(f32::MIN_POSITIVE)))
        });
        let xs = match tiny {
            Some(t) => self.sel_raw(t, self.arith('*', x, c(16_777_216.0)), x),
            None => x,
        };
        let y = self.rsqrt_estimate(xs);
        let t = self.arith('*', xs, y);
        let e = self.fma_raw(self.fneg_raw(t), y, c(1.0));
        let r = self.fma_raw(self.arith('*', y, c(0.5)), e, y);
        let r = self.sel_raw(self.fcmp_raw(FloatPredicate::UNO, r, r), y, r);
        let r = match tiny {
            Some(t) => self.sel_raw(t, self.arith('*', r, c(4096.0)), r),
            None => r,
        };
        let d = a.d.map(|(dx, dy)| {
            let k = self.arith('*', self.arith('*', self.arith('*', c(-0.5), r), r), r);
            let k = self.finite_or_zero(k);
            (self.arith('*', dx, k), self.arith('*', dy, k))
        });
        S { r: a.r, v: r, d }
    }
    fn minmax(&self, a: S<'c>, b: S<'c>, max: bool) -> S<'c> {
        let (a, b) = self.unify(a, b);
        let v = if self.t.lanes == 1 {
            // `f32::max` / `f32::min`.
            let name = if max { "llvm.maxnum" } else { "llvm.minnum" };
            self.call_intr(name, &[a.v.get_type()], &[a.v, b.v])
        } else {
            // The SIMD library's: `a` NaN → `b`; else x86's `maxps(b, a)` (`b > a ? b : a`,
            // ties to `a`) — uniform operands too, which the library computes as splats.
            let p = if max { FloatPredicate::OGT } else { FloatPredicate::OLT };
            let hw = self.sel_raw(self.fcmp_raw(p, b.v, a.v), b.v, a.v);
            self.sel_raw(self.fcmp_raw(FloatPredicate::UNO, a.v, a.v), b.v, hw)
        };
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => {
                // Derivatives of the operand chosen; ties take `a` (anysl-ad).
                let lt = if max {
                    self.fcmp_raw(FloatPredicate::OLT, a.v, b.v)
                } else {
                    self.fcmp_raw(FloatPredicate::OLT, b.v, a.v)
                };
                let nan = self.fcmp_raw(FloatPredicate::UNO, a.v, a.v);
                let take = self.mor(M { uni: false, v: lt }, M { uni: false, v: nan }).v;
                Some((self.sel_raw(take, bx, ax), self.sel_raw(take, by, ay)))
            }
            _ => None,
        };
        S { r: a.r, v, d }
    }
    fn cmp(&self, p: FloatPredicate, a: S<'c>, b: S<'c>) -> M<'c> {
        let (a, b) = self.unify(a, b);
        M { uni: a.r == Repr::U, v: self.fcmp_raw(p, a.v, b.v) }
    }
    /// `m ? a : b`.
    fn sel(&self, m: M<'c>, a: S<'c>, b: S<'c>) -> S<'c> {
        let (mut a, mut b) = self.unify(a, b);
        let m = if !m.uni && a.r == Repr::U {
            a = self.to(a, Repr::V);
            b = self.to(b, Repr::V);
            m
        } else if m.uni && a.r != Repr::U {
            self.splat_mask(m)
        } else {
            m
        };
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => Some((self.sel_raw(m.v, ax, bx), self.sel_raw(m.v, ay, by))),
            _ => None,
        };
        S { r: a.r, v: self.sel_raw(m.v, a.v, b.v), d }
    }

    fn munify(&self, a: M<'c>, b: M<'c>) -> (M<'c>, M<'c>) {
        if a.uni == b.uni {
            (a, b)
        } else {
            (self.splat_mask(a), self.splat_mask(b))
        }
    }
    fn mand(&self, a: M<'c>, b: M<'c>) -> M<'c> {
        let (a, b) = self.munify(a, b);
        let v = match (a.v, b.v) {
            (BasicValueEnum::IntValue(x), BasicValueEnum::IntValue(y)) => {
                self.b.build_and(x, y, "").expect("and").into()
            }
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => {
                self.b.build_and(x, y, "").expect("and").into()
            }
            _ => panic!("and"),
        };
        M { uni: a.uni, v }
    }
    fn mor(&self, a: M<'c>, b: M<'c>) -> M<'c> {
        let (a, b) = self.munify(a, b);
        let v = match (a.v, b.v) {
            (BasicValueEnum::IntValue(x), BasicValueEnum::IntValue(y)) => self.b.build_or(x, y, "").expect("or").into(),
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => {
                self.b.build_or(x, y, "").expect("or").into()
            }
            _ => panic!("or"),
        };
        M { uni: a.uni, v }
    }
    fn mxor(&self, a: M<'c>, b: M<'c>) -> M<'c> {
        let (a, b) = self.munify(a, b);
        let v = match (a.v, b.v) {
            (BasicValueEnum::IntValue(x), BasicValueEnum::IntValue(y)) => {
                self.b.build_xor(x, y, "").expect("xor").into()
            }
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => {
                self.b.build_xor(x, y, "").expect("xor").into()
            }
            _ => panic!("xor"),
        };
        M { uni: a.uni, v }
    }
    fn mnot(&self, a: M<'c>) -> M<'c> {
        let v = match a.v {
            BasicValueEnum::IntValue(x) => self.b.build_not(x, "").expect("not").into(),
            BasicValueEnum::VectorValue(x) => self.b.build_not(x, "").expect("not").into(),
            _ => panic!("not"),
        };
        M { uni: a.uni, v }
    }
    fn msel(&self, c: M<'c>, a: M<'c>, b: M<'c>) -> M<'c> {
        // (c & a) | (!c & b), as Mask::select_mask.
        self.mor(self.mand(c, a), self.mand(self.mnot(c), b))
    }
    /// Some lane set (an `i1`).
    fn any(&self, m: M<'c>) -> IntValue<'c> {
        match m.v {
            BasicValueEnum::IntValue(x) => x,
            BasicValueEnum::VectorValue(x) => {
                self.call_intr("llvm.vector.reduce.or", &[x.get_type().into()], &[x.into()]).into_int_value()
            }
            _ => panic!("any"),
        }
    }

    // ---------------------------------------------------------------- composite numerics

    /// `Vec3::dot`: `x·x' + (y·y' + z·z')`, fused.
    fn dot(&self, a: &[S<'c>], b: &[S<'c>]) -> S<'c> {
        self.fma(a[0], b[0], self.fma(a[1], b[1], self.mul(a[2], b[2])))
    }
    fn cross(&self, a: &[S<'c>], b: &[S<'c>]) -> Vec<S<'c>> {
        vec![
            self.sub(self.mul(a[1], b[2]), self.mul(a[2], b[1])),
            self.sub(self.mul(a[2], b[0]), self.mul(a[0], b[2])),
            self.sub(self.mul(a[0], b[1]), self.mul(a[1], b[0])),
        ]
    }
    fn clamp(&self, x: S<'c>, lo: S<'c>, hi: S<'c>) -> S<'c> {
        self.minmax(self.minmax(x, lo, true), hi, false)
    }
    fn step(&self, e: S<'c>, x: S<'c>) -> S<'c> {
        let lt = self.cmp(FloatPredicate::OLT, x, e);
        let r = e.r.max(x.r);
        let (z, o) = (self.to(self.fc(0.0), r), self.to(self.fc(1.0), r));
        self.sel(lt, z, o)
    }
    fn smoothstep(&self, e0: S<'c>, e1: S<'c>, x: S<'c>) -> S<'c> {
        let w = self.sub(e1, e0);
        let degenerate = self.cmp(FloatPredicate::OEQ, w, self.fc(0.0));
        let den = self.sel(degenerate, self.fc(1.0), w);
        let t = self.clamp(self.div(self.sub(x, e0), den), self.fc(0.0), self.fc(1.0));
        let s = self.mul(self.mul(t, t), self.sub(self.fc(3.0), self.mul(self.fc(2.0), t)));
        self.sel(degenerate, self.step(e0, x), s)
    }
    /// `fmod` as anysl-core defines it (result in `[0, b)`, 0 for `b = 0`).
    fn fmod(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        let z = self.fc(0.0);
        let bz = self.cmp(FloatPredicate::OEQ, b, z);
        let bb = self.sel(bz, self.fc(1.0), b);
        let r = self.sub(a, self.mul(bb, self.floor(self.div(a, bb))));
        let fold = self.mand(self.cmp(FloatPredicate::OGE, r, bb), self.cmp(FloatPredicate::OGT, bb, z));
        let r = self.sel(fold, self.sub(r, bb), r);
        self.sel(bz, z, r)
    }
    fn mix(&self, a: S<'c>, b: S<'c>, t: S<'c>) -> S<'c> {
        self.add(a, self.mul(t, self.sub(b, a)))
    }
    fn length(&self, a: &[S<'c>]) -> S<'c> {
        self.sqrt(self.dot(a, a))
    }

    // ---------------------------------------------------------------- runtime calls

    /// Calls runtime function `kind` with `aux`; `n_out` output values. Uniform when every
    /// argument is uniform and `force_varying` is false.
    /// Transcendentals of varying vectors are emitted inline instead ([`math`]).
    fn rt_call(&mut self, kind: RtKind, aux: u32, args: &[S<'c>], n_out: usize, force_varying: bool) -> Vec<S<'c>> {
        if let Some(r) = math::MathFn::of(kind, aux).and_then(|f| self.math_inline(f, args)) {
            return vec![r];
        }
        self.rt_call_library(kind, aux, args, n_out, force_varying)
    }

    /// [`Cg::rt_call`] always as a call of the runtime library.
    fn rt_call_library(
        &mut self,
        kind: RtKind,
        aux: u32,
        args: &[S<'c>],
        n_out: usize,
        force_varying: bool,
    ) -> Vec<S<'c>> {
        let uni = !force_varying && args.iter().all(|a| a.r == Repr::U);
        let addr = if uni { (self.rt_u)(kind, aux) } else { (self.rt_v)(kind, aux) };
        let fnp = self.const_fn_ptr(addr);
        if !uni && self.t.native < self.t.lanes {
            return self.callback_per_packet(fnp, aux, args, n_out);
        }
        self.callback(fnp, aux, args, n_out, uni)
    }

    /// The packets of `native` lanes a vector of the variant's lanes is made of.
    fn packets_of(&self, v: inkwell::values::VectorValue<'c>) -> Vec<inkwell::values::VectorValue<'c>> {
        let n = self.t.native;
        (0..v.get_type().get_size() / n)
            .map(|k| {
                let idx: Vec<_> = (k * n..(k + 1) * n).map(|i| self.i32c(u64::from(i))).collect();
                self.b
                    .build_shuffle_vector(v, v.get_type().get_undef(), VectorType::const_vector(&idx), "")
                    .expect("shuffle")
            })
            .collect()
    }

    /// The vector of `parts` one after the other (equal widths, a power of two of them).
    fn concat(&self, parts: &[inkwell::values::VectorValue<'c>]) -> inkwell::values::VectorValue<'c> {
        let mut level = parts.to_vec();
        while level.len() > 1 {
            level = level
                .chunks(2)
                .map(|ab| {
                    let w = ab[0].get_type().get_size();
                    let idx: Vec<_> = (0..2 * w).map(|i| self.i32c(u64::from(i))).collect();
                    self.b.build_shuffle_vector(ab[0], ab[1], VectorType::const_vector(&idx), "").expect("shuffle")
                })
                .collect();
        }
        level[0]
    }

    /// [`Cg::callback`] of a runtime library function compiled for one packet, called once
    /// per packet of a variant that shades several: each call gets its packet's lanes of the
    /// varying arguments and of the mask (uniform arguments as they are), and the results
    /// are put back together.
    fn callback_per_packet(&mut self, fnp: PointerValue<'c>, aux: u32, args: &[S<'c>], n_out: usize) -> Vec<S<'c>> {
        assert!(!self.t.dual, "several packets per call of dual numbers");
        let mask = self.load_mask(self.st().mask).v.into_vector_value();
        let mask_parts = self.packets_of(mask);
        let arg_parts: Vec<Option<Vec<_>>> =
            args.iter().map(|a| (a.r != Repr::U).then(|| self.packets_of(a.v.into_vector_value()))).collect();
        let lanes = self.t.lanes;
        let mut outs: Vec<Vec<inkwell::values::VectorValue<'c>>> = vec![Vec::new(); n_out];
        for (k, m) in mask_parts.into_iter().enumerate() {
            let args_k: Vec<S<'c>> = args
                .iter()
                .zip(&arg_parts)
                .map(|(a, p)| match p {
                    Some(p) => S { r: Repr::V, v: p[k].into(), d: None },
                    None => *a,
                })
                .collect();
            // One packet's widths for the buffers of this call.
            self.t.lanes = self.t.native;
            let r = self.callback_masked(fnp, aux, &args_k, n_out, false, M { uni: false, v: m.into() });
            self.t.lanes = lanes;
            for (o, v) in outs.iter_mut().zip(r) {
                o.push(v.v.into_vector_value());
            }
        }
        outs.iter().map(|parts| S { r: Repr::V, v: self.concat(parts).into(), d: None }).collect()
    }

    fn rt_fn_type(&self) -> inkwell::types::FunctionType<'c> {
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let i32p = self.cx.i32_type().ptr_type(AddressSpace::default());
        self.cx
            .void_type()
            .fn_type(&[self.i8p().into(), i32p.into(), f32p.into(), f32p.into(), self.cx.i32_type().into()], false)
    }

    fn const_fn_ptr(&self, addr: usize) -> PointerValue<'c> {
        self.cx
            .i64_type()
            .const_int(addr as u64, false)
            .const_to_pointer(self.rt_fn_type().ptr_type(AddressSpace::default()))
    }

    fn host_fn_ptr(&self, idx: Host, ty: inkwell::types::FunctionType<'c>) -> PointerValue<'c> {
        let host = self.st().host.into_pointer_value();
        let slot =
            unsafe { self.b.build_gep(host, &[self.cx.i64_type().const_int(idx as u64, false)], "") }.expect("gep");
        let addr = self.b.build_load(slot, "").expect("load").into_int_value();
        self.b.build_int_to_ptr(addr, ty.ptr_type(AddressSpace::default()), "").expect("inttoptr")
    }

    /// Spills `vals` (each converted to the full varying representation, or uniform) to a
    /// buffer and returns a `float*` to it.
    fn spill(&self, vals: &[S<'c>], uni: bool) -> PointerValue<'c> {
        let (elt, per): (BasicTypeEnum<'c>, usize) =
            if uni { (self.f32t.into(), 1) } else { (self.vt(), if self.t.dual { 3 } else { 1 }) };
        let n = (vals.len() * per).max(1) as u32;
        let buf = self.entry_alloca(elt.array_type(n).into());
        let mut k = 0u64;
        for &v in vals {
            let v = if uni { self.to(v, Repr::U) } else { self.to(v, self.full()) };
            let mut parts = vec![v.v];
            if let Some((x, y)) = v.d {
                parts.push(x);
                parts.push(y);
            }
            for p in parts {
                let ptr = unsafe {
                    self.b.build_gep(
                        buf,
                        &[self.cx.i64_type().const_zero(), self.cx.i64_type().const_int(k, false)],
                        "",
                    )
                }
                .expect("gep");
                self.b.build_store(ptr, p).expect("store");
                k += 1;
            }
        }
        self.b.build_pointer_cast(buf, self.f32t.ptr_type(AddressSpace::default()), "").expect("cast")
    }

    fn unspill(&self, buf: PointerValue<'c>, n: usize, uni: bool) -> Vec<S<'c>> {
        let elt = if uni { BasicTypeEnum::from(self.f32t) } else { self.vt() };
        let p = self.b.build_pointer_cast(buf, self.ptr_ty(elt), "").expect("cast");
        let r = if uni { Repr::U } else { self.full() };
        let per = if r == Repr::D { 3 } else { 1 };
        (0..n)
            .map(|i| {
                let ld = |k: usize| {
                    let ptr = unsafe {
                        self.b.build_gep(p, &[self.cx.i64_type().const_int((i * per + k) as u64, false)], "")
                    }
                    .expect("gep");
                    self.b.build_load(ptr, "").expect("load")
                };
                let v = ld(0);
                let d = (per == 3).then(|| (ld(1), ld(2)));
                S { r, v, d }
            })
            .collect()
    }

    fn out_buf(&self, n: usize, uni: bool) -> PointerValue<'c> {
        let (elt, per): (BasicTypeEnum<'c>, usize) =
            if uni { (self.f32t.into(), 1) } else { (self.vt(), if self.t.dual { 3 } else { 1 }) };
        let buf = self.entry_alloca(elt.array_type((n * per).max(1) as u32).into());
        self.b.build_pointer_cast(buf, self.f32t.ptr_type(AddressSpace::default()), "").expect("cast")
    }

    /// The current mask as `u32` lanes in memory.
    fn mask_buf(&self) -> PointerValue<'c> {
        self.mask_buf_of(self.load_mask(self.st().mask))
    }

    /// Mask `m` as `u32` lanes in memory.
    fn mask_buf_of(&self, m: M<'c>) -> PointerValue<'c> {
        let i32t = self.cx.i32_type();
        let (ty, v): (BasicTypeEnum<'c>, BasicValueEnum<'c>) = match m.v {
            BasicValueEnum::IntValue(x) => (i32t.into(), self.b.build_int_s_extend(x, i32t, "").expect("sext").into()),
            BasicValueEnum::VectorValue(x) => {
                let vt = i32t.vec_type(self.t.lanes);
                (vt.into(), self.b.build_int_s_extend(x, vt, "").expect("sext").into())
            }
            _ => panic!("mask"),
        };
        let buf = self.entry_alloca(ty);
        self.b.build_store(buf, v).expect("store");
        self.b.build_pointer_cast(buf, i32t.ptr_type(AddressSpace::default()), "").expect("cast")
    }

    fn callback(&mut self, fnp: PointerValue<'c>, aux: u32, args: &[S<'c>], n_out: usize, uni: bool) -> Vec<S<'c>> {
        let m = self.load_mask(self.st().mask);
        self.callback_masked(fnp, aux, args, n_out, uni, m)
    }

    /// [`Cg::callback`] for the lanes of mask `m`.
    fn callback_masked(
        &mut self,
        fnp: PointerValue<'c>,
        aux: u32,
        args: &[S<'c>],
        n_out: usize,
        uni: bool,
        m: M<'c>,
    ) -> Vec<S<'c>> {
        let inp = self.spill(args, uni);
        let out = self.out_buf(n_out, uni);
        let mask = self.mask_buf_of(m);
        self.call_rt_fn(fnp, mask, inp, out, aux);
        self.unspill(out, n_out, uni)
    }

    /// Calls a function of the runtime ABI (`ctx, mask, inputs, outputs, aux`).
    fn call_rt_fn(
        &self,
        fnp: PointerValue<'c>,
        mask: PointerValue<'c>,
        inp: PointerValue<'c>,
        out: PointerValue<'c>,
        aux: u32,
    ) {
        let ctx = self.st().ctx;
        let callee = CallableValue::try_from(fnp).expect("callable");
        self.b
            .build_call(
                callee,
                &[ctx.into(), mask.into(), inp.into(), out.into(), self.i32c(u64::from(aux)).into()],
                "",
            )
            .expect("call");
    }

    /// Emits call `v`: threaded (a call of its target-library function) or inline.
    fn emit_call(&mut self, v: Value, args: Vec<Val<'c>>) -> R<Val<'c>> {
        if self.t.threaded {
            self.threaded(v, args)
        } else {
            let out = self.op_body(v, &args)?;
            self.finish_outputs(v, out)
        }
    }

    /// How many light sums beyond its own a `specular` call with `args` (N, V, roughness)
    /// returns: 1 (`diffuse(N)`), 2 (and `ambient()`, when the shader calls it), or `None`
    /// (dual numbers: the derivatives of the sums would have to be kept as well).
    fn lit_sums(&self, args: &[S<'c>]) -> Option<u32> {
        if self.t.dual || args.len() != 7 {
            return None;
        }
        Some(if calls_ambient(self.func) { 2 } else { 1 })
    }

    /// Call `v`, with the light sums of `specular` kept for the `diffuse(N)` and `ambient()`
    /// calls after it ([`LitMemo`]).
    fn lit_call(&mut self, v: Value, args: Vec<Val<'c>>) -> R<Val<'c>> {
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
    /// ([`ambient_partners`]): one renderer call returns both sums (`diffuse` with `aux` 1),
    /// the diffuse sum is kept for the `diffuse(N)` call, which checks its normal and mask as
    /// after a `specular` ([`Cg::lit_guarded`]). `None`: emit the plain call.
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

    /// A matrix of the context's named spaces as 16 uniform values (`kind`: `rt::SPACE_*`,
    /// `names`: the space name, or both names of `rt::SPACE_BETWEEN`).
    fn space_matrix(&mut self, kind: u32, names: &str) -> Vec<S<'c>> {
        let gs = self.b.build_global_string_ptr(names, "space").expect("string").as_pointer_value();
        let inp = self.b.build_pointer_cast(gs, self.f32t.ptr_type(AddressSpace::default()), "").expect("cast");
        let out = self.out_buf(16, true);
        let mask = self.mask_buf();
        let fnp = self.host_fn_ptr(Host::Space, self.rt_fn_type());
        self.call_rt_fn(fnp, mask, inp, out, kind | (names.len() as u32) << 2);
        self.unspill(out, 16, true)
    }

    fn host_call(&mut self, idx: Host, aux: u32, args: &[S<'c>], n_out: usize) -> Vec<S<'c>> {
        let fnp = self.host_fn_ptr(idx, self.rt_fn_type());
        self.callback(fnp, aux, args, n_out, false)
    }

    // ---------------------------------------------------------------- masks in memory

    fn load_mask(&self, p: PointerValue<'c>) -> M<'c> {
        M { uni: false, v: self.b.build_load(p, "").expect("load") }
    }
    fn store_mask(&self, p: PointerValue<'c>, m: M<'c>) {
        self.mask_stores.set(self.mask_stores.get() + 1);
        let m = self.splat_mask(m);
        self.b.build_store(p, m.v).expect("store");
    }
    fn new_mask(&self, init: M<'c>) -> PointerValue<'c> {
        let p = self.entry_alloca(self.mty(false));
        self.store_mask(p, init);
        p
    }
    fn no_lanes(&self) -> M<'c> {
        M { uni: false, v: self.mty(false).const_zero() }
    }

    // ---------------------------------------------------------------- slots

    fn slot_comps(ty: Type) -> usize {
        ty.base.components() * ty.array.unwrap_or(1).max(1) as usize
    }

    fn load_slot(&self, s: SlotId) -> Val<'c> {
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
    fn store_comp(&self, s: SlotId, i: usize, v: S<'c>, m: Option<M<'c>>) {
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
    fn store_val(&mut self, s: SlotId, v: &Val<'c>) {
        let m = if self.slots[s.0 as usize].r == Repr::U { None } else { Some(self.load_mask(self.st().mask)) };
        self.store_val_under(s, v, m);
    }

    /// [`Self::store_val`] under mask `m` (`None`: every lane).
    fn store_val_under(&mut self, s: SlotId, v: &Val<'c>, m: Option<M<'c>>) {
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

    // ---------------------------------------------------------------- values

    fn val(&self, v: Value) -> R<Val<'c>> {
        match self.vals.get(v.0 as usize).cloned().flatten() {
            Some(x) => Ok(x),
            None => err(format!("value v{} used before it is defined", v.0)),
        }
    }
    fn nums(&self, v: Value) -> R<Vec<S<'c>>> {
        match self.val(v)? {
            Val::Num(c) => Ok(c),
            Val::Mask(m) => Ok(vec![self.sel(m, self.fc(1.0), self.fc(0.0))]),
            other => err(format!("v{} is not numeric: {other:?}", v.0)),
        }
    }
    fn mask_of(&self, v: Value) -> R<M<'c>> {
        match self.val(v)? {
            Val::Mask(m) => Ok(m),
            Val::Num(c) => {
                let mut r = self.cmp(FloatPredicate::UNE, c[0], self.fc(0.0));
                for &x in &c[1..] {
                    r = self.mor(r, self.cmp(FloatPredicate::UNE, x, self.fc(0.0)));
                }
                Ok(r)
            }
            other => err(format!("v{} is not a condition: {other:?}", v.0)),
        }
    }
    fn str_of(&self, v: Value) -> R<String> {
        match self.val(v)? {
            Val::Str(s) => Ok(s.first().cloned().unwrap_or_default()),
            other => err(format!("v{} is not a string: {other:?}", v.0)),
        }
    }

    fn repr_of_inst(&self, inst: &ir::Inst) -> Repr {
        if inst.ty.detail == Detail::Uniform {
            Repr::U
        } else if self.t.dual && inst.needs_derivs {
            Repr::D
        } else {
            Repr::V
        }
    }

    // ---------------------------------------------------------------- the shade function

    /// Generates the shade function for `module`.
    ///
    /// # Errors
    /// On ops the JIT does not support.
    pub fn generate(&mut self, analyzed: &Analyzed, param_values: &[Const]) -> R<FunctionValue<'c>> {
        let module = analyzed.module();
        let func = self.func;
        self.inst_repr = func.insts.iter().map(|i| self.repr_of_inst(i)).collect();
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let i32p = self.cx.i32_type().ptr_type(AddressSpace::default());
        let i64p = self.cx.i64_type().ptr_type(AddressSpace::default());
        let fty = self
            .cx
            .void_type()
            .fn_type(&[f32p.into(), f32p.into(), i32p.into(), self.i8p().into(), i64p.into(), f32p.into()], false);
        let f = self.m.add_function(SHADE_NAME, fty, None);
        self.set_fn_attrs(f);
        let entry = self.cx.append_basic_block(f, "entry");
        self.b.position_at_end(entry);
        let g = f.get_nth_param(0).expect("g");
        let out = f.get_nth_param(1).expect("out").into_pointer_value();
        let maskp = f.get_nth_param(2).expect("mask").into_pointer_value();
        let params = f.get_nth_param(5).expect("params").into_pointer_value();
        let param_offsets = param_block(module, param_values).1;
        // Entry mask.
        let m0 = self.read_mask_lanes(maskp);
        let mask = self.new_mask(m0);
        self.st = Some(FnState {
            f,
            mask,
            loops: Vec::new(),
            rets: Vec::new(),
            ctx: f.get_nth_param(3).expect("ctx"),
            host: f.get_nth_param(4).expect("host"),
            g,
        });
        // Slots: a slot holds dual numbers when some load of it needs derivatives.
        let mut slot_dual = vec![false; func.slots.len()];
        ir::walk(&func.body, &mut |n| {
            if let Node::Inst(v) = n {
                let inst = func.inst(*v);
                if let Op::Load(s) | Op::LoadElem(s) = inst.op {
                    if inst.needs_derivs {
                        slot_dual[s.0 as usize] = true;
                    }
                }
            }
        });
        for (i, s) in func.slots.iter().enumerate() {
            let r = if s.ty.detail == Detail::Uniform {
                Repr::U
            } else if self.t.dual && slot_dual[i] {
                Repr::D
            } else {
                Repr::V
            };
            let is_str = s.ty.base == BaseType::String;
            let n = if is_str { 0 } else { Self::slot_comps(s.ty) };
            let ty = self.fty(r);
            let ptrs = (0..n)
                .map(|_| {
                    let p = self.entry_alloca(ty);
                    let d = (r == Repr::D).then(|| (self.entry_alloca(ty), self.entry_alloca(ty)));
                    (p, d)
                })
                .collect();
            self.slots.push(SlotStore { r, ptrs, is_str });
        }
        // Initial values: globals from the buffer, parameters from the instance, others 0.
        for (i, s) in func.slots.iter().enumerate() {
            let sid = SlotId(i as u32);
            let init: Val<'c> = match &s.kind {
                SlotKind::Global(gl) => {
                    let from = match gl {
                        Global::Oi => Some(Global::Os),
                        g => GLOBAL_ORDER.iter().any(|(x, _)| x == g).then_some(*g),
                    };
                    match from {
                        Some(gg) => Val::Num(self.read_global(gg)),
                        None if *gl == Global::Ncomps => Val::Num(vec![self.fc(3.0)]),
                        None => Val::Num(vec![self.fc(0.0); Self::slot_comps(s.ty).max(1)]),
                    }
                }
                SlotKind::Param(k) => match param_offsets.get(*k as usize).copied().flatten() {
                    Some(at) if self.t.runtime_params => {
                        self.param_from_block(params, at, Self::slot_comps(s.ty).max(1))
                    }
                    _ => {
                        let c = param_values
                            .get(*k as usize)
                            .cloned()
                            .unwrap_or_else(|| module.params[*k as usize].default.clone());
                        self.const_val(&c, s.ty)
                    }
                },
                SlotKind::Local => {
                    if s.ty.base == BaseType::String {
                        Val::Str(vec![String::new(); s.ty.array.unwrap_or(1) as usize])
                    } else {
                        Val::Num(vec![self.fc(0.0); Self::slot_comps(s.ty).max(1)])
                    }
                }
            };
            // Unmasked initialization.
            match &init {
                Val::Num(c) => {
                    for k in 0..self.slots[i].ptrs.len() {
                        let x = c[k.min(c.len() - 1)];
                        self.store_comp(sid, k, x, None);
                    }
                }
                Val::Str(v) => {
                    self.strs.insert(i as u32, v.clone());
                }
                _ => {}
            }
        }
        // Nothing to do for no lanes.
        let body_bb = self.cx.append_basic_block(f, "body");
        let exit_bb = self.cx.append_basic_block(f, "exit");
        let any = self.any(m0);
        self.b.build_conditional_branch(any, body_bb, exit_bb).expect("br");
        self.b.position_at_end(body_bb);
        let ret = self.new_mask(self.no_lanes());
        self.st.as_mut().expect("st").rets.push(ret);
        self.block(&func.body)?;
        let after = self.b.get_insert_block().expect("bb");
        self.b.build_unconditional_branch(exit_bb).expect("br");
        let _ = after;
        self.b.position_at_end(exit_bb);
        // Outputs: `Ci`, `Oi`, and for displacement shaders `P`, `N` (the only ones read).
        let outputs = if module.kind == ir::ShaderKind::Displacement { 4 } else { 2 };
        for (gl, off) in abi::OUTPUT_ORDER.into_iter().take(outputs) {
            let vals = match func.global_slot(gl) {
                Some(s) => match self.load_slot(s) {
                    Val::Num(c) => c,
                    _ => continue,
                },
                None => match gl {
                    Global::Ci => vec![self.fc(0.0); 3],
                    Global::Oi => self.read_global(Global::Os),
                    _ => self.read_global(gl),
                },
            };
            for (k, v) in vals.iter().enumerate().take(3) {
                self.write_out(out, off + k, *v);
            }
        }
        if self.t.output_params {
            for (k, off, n) in abi::output_params(module) {
                let p = &module.params[k];
                let vals = match self.load_slot(p.slot) {
                    Val::Num(c) => c,
                    _ => continue,
                };
                for (i, v) in vals.iter().enumerate().take(n) {
                    self.write_out(out, off + i, *v);
                }
            }
        }
        self.b.build_return(None).expect("ret");
        Ok(f)
    }

    fn set_fn_attrs(&self, f: FunctionValue<'c>) {
        for (k, v) in &self.fn_attrs {
            f.add_attribute(AttributeLoc::Function, self.cx.create_string_attribute(k, v));
        }
    }

    fn read_mask_lanes(&self, p: PointerValue<'c>) -> M<'c> {
        let i32t = self.cx.i32_type();
        if self.t.lanes == 1 {
            let x = self.b.build_load(p, "").expect("load").into_int_value();
            let v = self.b.build_int_compare(IntPredicate::NE, x, i32t.const_zero(), "").expect("cmp");
            return M { uni: false, v: v.into() };
        }
        let vt = i32t.vec_type(self.t.lanes);
        let vp = self.b.build_pointer_cast(p, vt.ptr_type(AddressSpace::default()), "").expect("cast");
        let ld = self.b.build_load(vp, "").expect("load");
        ld.as_instruction_value().map(|i| i.set_alignment(4));
        let v = self.b.build_int_compare(IntPredicate::NE, ld.into_vector_value(), vt.const_zero(), "").expect("cmp");
        M { uni: false, v: v.into() }
    }

    /// Reads a global's components from the renderer's `Globals` struct (full representation),
    /// at the offsets of [`Cg::layout`].
    fn read_global(&self, g: Global) -> Vec<S<'c>> {
        let Some((_, off)) = GLOBAL_ORDER.iter().find(|(x, _)| *x == g) else {
            return vec![self.fc(0.0); 3];
        };
        let n = g.ty().base.components();
        let gp = self.st().g.into_pointer_value();
        let vt = self.vt();
        let ld = |fo: u64| {
            let p = unsafe { self.b.build_gep(gp, &[self.cx.i64_type().const_int(fo, false)], "") }.expect("gep");
            let p = self.b.build_pointer_cast(p, self.ptr_ty(vt), "").expect("cast");
            let v = self.b.build_load(p, "").expect("load");
            v.as_instruction_value().map(|i| i.set_alignment(4));
            v
        };
        let [dx, dy] = self.layout.dual.map(u64::from);
        (0..n)
            .map(|k| {
                let base = u64::from(self.layout.comp[off + k]);
                let v = ld(base);
                let d = self.t.dual.then(|| (ld(base + dx), ld(base + dy)));
                S { r: self.full(), v, d }
            })
            .collect()
    }

    fn write_out(&self, out: PointerValue<'c>, idx: usize, v: S<'c>) {
        let v = self.to(v, self.full());
        let vt = self.vt();
        let stride = self.stride() as u64;
        let st = |fo: u64, x: BasicValueEnum<'c>| {
            let p = unsafe { self.b.build_gep(out, &[self.cx.i64_type().const_int(fo, false)], "") }.expect("gep");
            let p = self.b.build_pointer_cast(p, self.ptr_ty(vt), "").expect("cast");
            let s = self.b.build_store(p, x).expect("store");
            let _ = s.set_alignment(4);
        };
        let base = idx as u64 * stride;
        st(base, v.v);
        if let Some((x, y)) = v.d {
            st(base + u64::from(self.t.lanes), x);
            st(base + 2 * u64::from(self.t.lanes), y);
        }
    }

    fn const_val(&self, c: &Const, ty: Type) -> Val<'c> {
        if ty.base == BaseType::String {
            let (mut nums, mut strs) = (Vec::new(), Vec::new());
            flatten(c, &mut nums, &mut strs);
            return Val::Str(strs);
        }
        Val::Num(slot_values(c, ty).into_iter().map(|x| self.fc(x)).collect())
    }

    /// Parameter `k`'s value read from the run-time parameter block at `params` (uniform).
    fn param_from_block(&self, params: PointerValue<'c>, offset: usize, comps: usize) -> Val<'c> {
        Val::Num(
            (offset..offset + comps)
                .map(|at| {
                    let p = unsafe { self.b.build_gep(params, &[self.cx.i64_type().const_int(at as u64, false)], "") }
                        .expect("gep");
                    let v = self.b.build_load(p, "param").expect("load");
                    S { r: Repr::U, v, d: None }
                })
                .collect(),
        )
    }

    // ---------------------------------------------------------------- control flow

    /// Does the block contain a break/continue/return (which may narrow the mask)?
    fn narrows(b: &Block) -> bool {
        let mut found = false;
        ir::walk(b, &mut |n| {
            if matches!(n, Node::Break(_) | Node::Continue(_) | Node::Return) {
                found = true;
            }
        });
        found
    }

    fn block(&mut self, block: &Block) -> R<()> {
        let mut done: Option<inkwell::basic_block::BasicBlock<'c>> = None;
        for node in block {
            let stop = self.node(node)?;
            if stop {
                break;
            }
            let may_narrow = match node {
                Node::If { then, otherwise, .. } => Self::narrows(then) || Self::narrows(otherwise),
                Node::Loop { header, body, step, .. } => {
                    Self::narrows(header) || Self::narrows(body) || Self::narrows(step)
                }
                _ => false,
            };
            if may_narrow {
                // Skip the rest of the block when no lane is left.
                let d = *done.get_or_insert_with(|| self.cx.append_basic_block(self.st().f, "done"));
                let next = self.cx.append_basic_block(self.st().f, "go");
                let m = self.load_mask(self.st().mask);
                let any = self.any(m);
                self.b.build_conditional_branch(any, next, d).expect("br");
                self.b.position_at_end(next);
            }
        }
        if let Some(d) = done {
            self.b.build_unconditional_branch(d).expect("br");
            self.b.position_at_end(d);
        }
        Ok(())
    }

    /// Generates one node; returns true when the rest of the block is unreachable.
    fn node(&mut self, node: &Node) -> R<bool> {
        match node {
            Node::Inst(v) => self.inst(*v)?,
            Node::Store { slot, index, value, init } => {
                let val = self.val(*value)?;
                match index {
                    // A fresh slot's first value: no lane it leaves inactive is read later, so
                    // every lane is written. A merge would keep the slot's previous value alive
                    // — in a light loop, a loop-carried register per component of every
                    // variable declared in the body.
                    None if *init => self.store_val_under(*slot, &val, None),
                    None => self.store_val(*slot, &val),
                    Some(ix) => self.store_elem(*slot, *ix, &val)?,
                }
            }
            Node::If { cond, then, otherwise } => {
                let c = self.mask_of(*cond)?;
                let f = self.st().f;
                if c.uni {
                    let tb = self.cx.append_basic_block(f, "then");
                    let eb = self.cx.append_basic_block(f, "else");
                    let mb = self.cx.append_basic_block(f, "endif");
                    self.b.build_conditional_branch(c.v.into_int_value(), tb, eb).expect("br");
                    self.b.position_at_end(tb);
                    self.block(then)?;
                    self.b.build_unconditional_branch(mb).expect("br");
                    self.b.position_at_end(eb);
                    self.block(otherwise)?;
                    self.b.build_unconditional_branch(mb).expect("br");
                    self.b.position_at_end(mb);
                } else {
                    let m = self.load_mask(self.st().mask);
                    let mt = self.mand(m, c);
                    let me = self.mand(m, self.mnot(c));
                    let pt = self.new_mask(mt);
                    let pe = self.new_mask(me);
                    let saved = self.st().mask;
                    self.masked_region(pt, |cg| cg.block(then))?;
                    if !otherwise.is_empty() {
                        self.masked_region(pe, |cg| cg.block(otherwise))?;
                    }
                    let a = self.load_mask(pt);
                    let b = self.load_mask(pe);
                    self.st.as_mut().expect("st").mask = saved;
                    self.store_mask(saved, self.mor(a, b));
                }
            }
            Node::Loop { header, cond, body, step } => self.loop_(header, *cond, body, step)?,
            Node::Break(level) | Node::Continue(level) => {
                let is_break = matches!(node, Node::Break(_));
                let st = self.st().clone();
                let depth = st.loops.len();
                let m = self.load_mask(st.mask);
                if let Some(&(brk, cont)) = depth.checked_sub(1 + *level as usize).and_then(|i| st.loops.get(i)) {
                    let target = if is_break { brk } else { cont };
                    let old = self.load_mask(target);
                    self.store_mask(target, self.mor(old, m));
                }
                self.store_mask(st.mask, self.no_lanes());
                return Ok(true);
            }
            Node::Return => {
                let st = self.st().clone();
                let m = self.load_mask(st.mask);
                if let Some(&ret) = st.rets.last() {
                    let old = self.load_mask(ret);
                    self.store_mask(ret, self.mor(old, m));
                }
                self.store_mask(st.mask, self.no_lanes());
                return Ok(true);
            }
            Node::Frame(b) => {
                let ret = self.new_mask(self.no_lanes());
                let saved_loops = std::mem::take(&mut self.st.as_mut().expect("st").loops);
                self.st.as_mut().expect("st").rets.push(ret);
                self.block(b)?;
                let st = self.st.as_mut().expect("st");
                st.rets.pop();
                st.loops = saved_loops;
                let mp = self.st().mask;
                let m = self.load_mask(mp);
                let r = self.load_mask(ret);
                self.store_mask(mp, self.mor(m, r));
            }
            Node::Illuminance { category, position, cone, body } => {
                self.illuminance(*category, *position, *cone, body)?;
            }
            Node::Illuminate { .. } | Node::Solar { .. } => {
                return err("light shaders (illuminate/solar) are not compiled by the JIT yet");
            }
        }
        Ok(false)
    }

    /// Runs `f` with mask pointer `p` when some lane of it is set.
    fn masked_region(&mut self, p: PointerValue<'c>, f: impl FnOnce(&mut Self) -> R<()>) -> R<()> {
        let fnv = self.st().f;
        let run = self.cx.append_basic_block(fnv, "run");
        let skip = self.cx.append_basic_block(fnv, "skip");
        let m = self.load_mask(p);
        let any = self.any(m);
        self.b.build_conditional_branch(any, run, skip).expect("br");
        self.b.position_at_end(run);
        let saved = self.st().mask;
        self.st.as_mut().expect("st").mask = p;
        f(self)?;
        self.st.as_mut().expect("st").mask = saved;
        self.b.build_unconditional_branch(skip).expect("br");
        self.b.position_at_end(skip);
        Ok(())
    }

    fn loop_(&mut self, header: &Block, cond: Option<Value>, body: &Block, step: &Block) -> R<()> {
        let fnv = self.st().f;
        let outer = self.st().mask;
        let m = self.load_mask(outer);
        let live = self.new_mask(m);
        let exited = self.new_mask(self.no_lanes());
        let brk = self.new_mask(self.no_lanes());
        let cont = self.new_mask(self.no_lanes());
        let hb = self.cx.append_basic_block(fnv, "loop.header");
        let bb = self.cx.append_basic_block(fnv, "loop.body");
        let xb = self.cx.append_basic_block(fnv, "loop.exit");
        self.b.build_unconditional_branch(hb).expect("br");
        self.b.position_at_end(hb);
        self.st.as_mut().expect("st").mask = live;
        self.st.as_mut().expect("st").loops.push((brk, cont));
        self.block(header)?;
        match cond {
            Some(c) => {
                let c = self.mask_of(c)?;
                if c.uni {
                    // A uniform condition: all live lanes leave together.
                    let leave = self.cx.append_basic_block(fnv, "loop.leave");
                    self.b.build_conditional_branch(c.v.into_int_value(), bb, leave).expect("br");
                    self.b.position_at_end(leave);
                    let l = self.load_mask(live);
                    let e = self.load_mask(exited);
                    self.store_mask(exited, self.mor(e, l));
                    self.b.build_unconditional_branch(xb).expect("br");
                } else {
                    let l = self.load_mask(live);
                    let e = self.load_mask(exited);
                    self.store_mask(exited, self.mor(e, self.mand(l, self.mnot(c))));
                    let nl = self.mand(l, c);
                    self.store_mask(live, nl);
                    let any = self.any(self.splat_mask(nl));
                    self.b.build_conditional_branch(any, bb, xb).expect("br");
                }
            }
            None => {
                let l = self.load_mask(live);
                let any = self.any(l);
                self.b.build_conditional_branch(any, bb, xb).expect("br");
            }
        }
        self.b.position_at_end(bb);
        self.block(body)?;
        let l = self.load_mask(live);
        let c = self.load_mask(cont);
        self.store_mask(live, self.mor(l, c));
        self.store_mask(cont, self.no_lanes());
        // The step runs when some lane is live.
        let sb = self.cx.append_basic_block(fnv, "loop.step");
        let any = self.any(self.load_mask(live));
        self.b.build_conditional_branch(any, sb, xb).expect("br");
        self.b.position_at_end(sb);
        self.block(step)?;
        let any = self.any(self.load_mask(live));
        self.b.build_conditional_branch(any, hb, xb).expect("br");
        self.b.position_at_end(xb);
        let st = self.st.as_mut().expect("st");
        st.loops.pop();
        st.mask = outer;
        let e = self.load_mask(exited);
        let k = self.load_mask(brk);
        self.store_mask(outer, self.mor(e, k));
        Ok(())
    }

    // ---------------------------------------------------------------- illuminance

    fn illuminance(
        &mut self,
        category: Option<Value>,
        position: Value,
        cone: Option<(Value, Value)>,
        body: &Block,
    ) -> R<()> {
        // Lights described as data (no category to select on: data carries none) run in a
        // loop compiled here, the body inline; the renderer's loop otherwise, on the other
        // branch (its environment — the body's variables copied in and out of a block the
        // renderer's callback reads — is built there only, so the shader's own variables stay
        // registers).
        let join_bb = if category.is_none() && !self.lights_by_renderer {
            let (lights, n_lights) = self.light_data_ptr();
            let data_bb = self.cx.append_basic_block(self.cur_fn(), "illuminance.data");
            let host_bb = self.cx.append_basic_block(self.cur_fn(), "illuminance.host");
            let join_bb = self.cx.append_basic_block(self.cur_fn(), "illuminance.join");
            let none = self.b.build_is_null(lights, "").expect("isnull");
            self.b.build_conditional_branch(none, host_bb, data_bb).expect("br");
            self.b.position_at_end(data_bb);
            let saved_vals = self.vals.clone();
            self.illuminance_over_data(position, cone, body, lights, n_lights)?;
            self.vals = saved_vals;
            self.b.build_unconditional_branch(join_bb).expect("br");
            self.b.position_at_end(host_bb);
            Some(join_bb)
        } else {
            None
        };
        let func = self.func;
        // What the body reads from outside: values defined outside and variables.
        let mut defined = HashSet::new();
        ir::walk(body, &mut |n| {
            if let Node::Inst(v) = n {
                defined.insert(*v);
            }
        });
        let mut free: Vec<Value> = Vec::new();
        let mut used_slots: Vec<SlotId> = Vec::new();
        ir::walk(body, &mut |n| {
            let mut use_v = |v: Value| {
                if !defined.contains(&v) && !free.contains(&v) {
                    free.push(v);
                }
            };
            n.operands(&mut use_v);
            match n {
                Node::Inst(v) => {
                    let inst = func.inst(*v);
                    for &a in &inst.args {
                        use_v(a);
                    }
                    match &inst.op {
                        Op::Load(s) | Op::LoadElem(s) => used_slots.push(*s),
                        Op::Call { outputs, .. } => used_slots.extend(outputs.iter().flatten().copied()),
                        _ => {}
                    }
                }
                Node::Store { slot, .. } => used_slots.push(*slot),
                _ => {}
            }
        });
        for g in [Global::L, Global::Cl] {
            if let Some(s) = func.global_slot(g) {
                used_slots.push(s);
            }
        }
        used_slots.sort();
        used_slots.dedup();
        // Environment: pointers (i8*) to spilled free values, slot storage, the break mask,
        // ctx, host and globals.
        let mut env_ptrs: Vec<PointerValue<'c>> = Vec::new();
        let mut free_layout: Vec<(Value, Val<'c>)> = Vec::new();
        for &v in &free {
            let val = self.val(v)?;
            match &val {
                Val::Num(c) => {
                    for s in c {
                        for part in std::iter::once(s.v).chain(s.d.into_iter().flat_map(|(x, y)| [x, y])) {
                            let p = self.entry_alloca(part.get_type());
                            self.b.build_store(p, part).expect("store");
                            env_ptrs.push(p);
                        }
                    }
                }
                Val::Mask(m) => {
                    let p = self.entry_alloca(m.v.get_type());
                    self.b.build_store(p, m.v).expect("store");
                    env_ptrs.push(p);
                }
                _ => {}
            }
            free_layout.push((v, val));
        }
        // The body's variables: copies the callback reads and writes, copied back after the
        // call (the variables' own storage never escapes, so LLVM keeps them in registers).
        let mut copies: Vec<(PointerValue<'c>, PointerValue<'c>)> = Vec::new();
        for &s in &used_slots {
            for (p, d) in self.slots[s.0 as usize].ptrs.clone() {
                for q in std::iter::once(p).chain(d.into_iter().flat_map(|(x, y)| [x, y])) {
                    let t = self.entry_alloca(q.get_type().get_element_type().try_into().expect("a value type"));
                    let v = self.b.build_load(q, "").expect("load");
                    self.b.build_store(t, v).expect("store");
                    env_ptrs.push(t);
                    copies.push((q, t));
                }
            }
        }
        let brk = self.new_mask(self.no_lanes());
        env_ptrs.push(brk);
        let st = self.st().clone();
        let i8p = self.i8p();
        let env_t = i8p.array_type(env_ptrs.len() as u32 + 3);
        let env = self.entry_alloca(env_t.into());
        let put = |cg: &Self, k: usize, p: BasicValueEnum<'c>| {
            let slot = unsafe {
                cg.b.build_gep(env, &[cg.cx.i64_type().const_zero(), cg.cx.i64_type().const_int(k as u64, false)], "")
            }
            .expect("gep");
            let c = cg.b.build_pointer_cast(p.into_pointer_value(), i8p, "").expect("cast");
            cg.b.build_store(slot, c).expect("store");
        };
        for (k, p) in env_ptrs.iter().enumerate() {
            put(self, k, (*p).into());
        }
        let n = env_ptrs.len();
        put(self, n, st.ctx);
        put(self, n + 1, st.host);
        put(self, n + 2, st.g);
        // The body function.
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let i32p = self.cx.i32_type().ptr_type(AddressSpace::default());
        let body_ty = self
            .cx
            .void_type()
            .fn_type(&[i8p.ptr_type(AddressSpace::default()).into(), i32p.into(), f32p.into()], false);
        self.body_count += 1;
        let bf = self.m.add_function(
            &format!("anysl_illuminance_body.{}", self.body_count),
            body_ty,
            Some(Linkage::Internal),
        );
        self.set_fn_attrs(bf);
        let caller_bb = self.b.get_insert_block().expect("bb");
        let saved_vals = self.vals.clone();
        let saved_slots = self.slots.clone();
        let saved_st = self.st.clone();
        {
            let entry = self.cx.append_basic_block(bf, "entry");
            self.b.position_at_end(entry);
            let envp = bf.get_nth_param(0).expect("env").into_pointer_value();
            let get = |cg: &Self, k: usize, t: BasicTypeEnum<'c>| -> PointerValue<'c> {
                let slot =
                    unsafe { cg.b.build_gep(envp, &[cg.cx.i64_type().const_int(k as u64, false)], "") }.expect("gep");
                let p = cg.b.build_load(slot, "").expect("load").into_pointer_value();
                cg.b.build_pointer_cast(p, cg.ptr_ty(t), "").expect("cast")
            };
            let mut k = 0usize;
            for (v, val) in &free_layout {
                let nv = match val {
                    Val::Num(c) => Val::Num(
                        c.iter()
                            .map(|s| {
                                let mut ld = |t: BasicTypeEnum<'c>| {
                                    let p = get(self, k, t);
                                    k += 1;
                                    self.b.build_load(p, "").expect("load")
                                };
                                let v = ld(s.v.get_type());
                                let d = s.d.map(|(x, y)| (ld(x.get_type()), ld(y.get_type())));
                                S { r: s.r, v, d }
                            })
                            .collect(),
                    ),
                    Val::Mask(m) => {
                        let p = get(self, k, m.v.get_type());
                        k += 1;
                        Val::Mask(M { uni: m.uni, v: self.b.build_load(p, "").expect("load") })
                    }
                    other => other.clone(),
                };
                self.vals[v.0 as usize] = Some(nv);
            }
            for &s in &used_slots {
                let r = self.slots[s.0 as usize].r;
                let t = self.fty(r);
                let np: Vec<_> = (0..self.slots[s.0 as usize].ptrs.len())
                    .map(|_| {
                        let p = get(self, k, t);
                        k += 1;
                        let d = (r == Repr::D).then(|| {
                            let x = get(self, k, t);
                            let y = get(self, k + 1, t);
                            k += 2;
                            (x, y)
                        });
                        (p, d)
                    })
                    .collect();
                self.slots[s.0 as usize].ptrs = np;
            }
            let brk_in = get(self, k, self.mty(false));
            let ctx = get(self, n, self.cx.i8_type().into());
            let hostp = get(self, n + 1, self.cx.i64_type().into());
            let gp = get(self, n + 2, self.f32t.into());
            // live = mask & !broken
            let mp = bf.get_nth_param(1).expect("mask").into_pointer_value();
            let m_in = self.read_mask_lanes(mp);
            let broken = self.load_mask(brk_in);
            let live = self.mand(m_in, self.mnot(broken));
            let mask = self.new_mask(live);
            let cont = self.new_mask(self.no_lanes());
            let ret = self.new_mask(self.no_lanes());
            self.st = Some(FnState {
                f: bf,
                mask,
                loops: vec![(brk_in, cont)],
                rets: vec![ret],
                ctx: ctx.into(),
                host: hostp.into(),
                g: gp.into(),
            });
            let run = self.cx.append_basic_block(bf, "run");
            let exit = self.cx.append_basic_block(bf, "exit");
            let any = self.any(live);
            self.b.build_conditional_branch(any, run, exit).expect("br");
            self.b.position_at_end(run);
            // L and Cl, written for every lane.
            let lcl = bf.get_nth_param(2).expect("lcl").into_pointer_value();
            let lv = self.read_values(lcl, 6);
            for (gi, g) in [Global::L, Global::Cl].into_iter().enumerate() {
                if let Some(s) = func.global_slot(g) {
                    for c in 0..3 {
                        self.store_comp(s, c, lv[gi * 3 + c], None);
                    }
                }
            }
            self.block(body)?;
            self.b.build_unconditional_branch(exit).expect("br");
            self.b.position_at_end(exit);
            self.b.build_return(None).expect("ret");
        }
        self.vals = saved_vals;
        self.slots = saved_slots;
        self.st = saved_st;
        self.b.position_at_end(caller_bb);
        // The host call.
        let pos = self.nums(position)?;
        let mut args = pos.clone();
        if let Some((a, b)) = cone {
            args.extend(self.nums(a)?);
            args.extend(self.nums(b)?);
        }
        let cat = match category {
            Some(c) => self.str_of(c)?,
            None => String::new(),
        };
        let inp = self.spill(&args, false);
        let mask = self.mask_buf();
        let cat_g = if cat.is_empty() {
            i8p.const_null()
        } else {
            let gs = self.b.build_global_string_ptr(&cat, "cat").expect("string");
            gs.as_pointer_value()
        };
        let illum_ty = self.cx.void_type().fn_type(
            &[
                i8p.into(),
                i32p.into(),
                f32p.into(),
                self.cx.i32_type().into(),
                i8p.into(),
                self.cx.i64_type().into(),
                body_ty.ptr_type(AddressSpace::default()).into(),
                i8p.into(),
            ],
            false,
        );
        let fnp = self.host_fn_ptr(Host::Illuminance, illum_ty);
        let env_i8 = self.b.build_pointer_cast(env, i8p, "").expect("cast");
        let ctx = self.st().ctx;
        self.b
            .build_call(
                CallableValue::try_from(fnp).expect("callable"),
                &[
                    ctx.into(),
                    mask.into(),
                    inp.into(),
                    self.i32c(u64::from(cone.is_some())).into(),
                    cat_g.into(),
                    self.cx.i64_type().const_int(cat.len() as u64, false).into(),
                    bf.as_global_value().as_pointer_value().into(),
                    env_i8.into(),
                ],
                "",
            )
            .expect("call");
        for (q, t) in copies {
            let v = self.b.build_load(t, "").expect("load");
            self.b.build_store(q, v).expect("store");
        }
        if let Some(join) = join_bb {
            self.b.build_unconditional_branch(join).expect("br");
            self.b.position_at_end(join);
        }
        Ok(())
    }

    /// Reads `n` values from a buffer the host wrote (4-byte aligned, like every buffer the
    /// host passes: a vector load assuming the vector's alignment faults on AVX-512).
    fn read_values(&self, p: PointerValue<'c>, n: usize) -> Vec<S<'c>> {
        let vals = self.unspill(p, n, false);
        for s in &vals {
            for v in std::iter::once(s.v).chain(s.d.into_iter().flat_map(|(x, y)| [x, y])) {
                if let Some(i) = v.as_instruction_value() {
                    let _ = i.set_alignment(4);
                }
            }
        }
        vals
    }

    // ---------------------------------------------------------------- instructions

    fn store_elem(&mut self, slot: SlotId, index: Value, val: &Val<'c>) -> R<()> {
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

    fn const_index(&self, v: Value) -> R<usize> {
        match &self.func.inst(v).op {
            Op::Const(Const::Float(x)) => Ok(x.max(0.0) as usize),
            _ => err("string arrays need constant indices in the JIT"),
        }
    }

    fn inst(&mut self, v: Value) -> R<()> {
        let func = self.func;
        let inst = func.inst(v);
        let want = self.inst_repr[v.0 as usize];
        let result = match &inst.op {
            Op::Const(c) => {
                if inst.is_bool {
                    Val::Mask(self.mconst(matches!(c, Const::Float(x) if *x != 0.0)))
                } else {
                    self.const_val(c, inst.ty)
                }
            }
            Op::Load(s) => {
                let val = self.load_slot(*s);
                if inst.is_bool {
                    if let Val::Num(c) = &val {
                        Val::Mask(self.cmp(FloatPredicate::UNE, c[0], self.fc(0.0)))
                    } else {
                        val
                    }
                } else {
                    val
                }
            }
            Op::LoadElem(s) => self.load_elem(*s, inst.args[0], inst.ty)?,
            _ => {
                // Derivative built-ins keep dual arguments; every other op runs in the
                // representation its result needs (so derivative work nobody uses is skipped).
                let keep = matches!(&inst.op, Op::Call { builtin, .. } if builtin.uses_derivatives());
                let mut args: Vec<Val<'c>> = Vec::with_capacity(inst.args.len());
                for &a in &inst.args {
                    let x = self.val(a)?;
                    let x = match x {
                        Val::Num(c) if !keep && want != Repr::D && c.iter().any(|s| s.r == Repr::D) => {
                            Val::Num(c.into_iter().map(|s| self.to(s, Repr::V)).collect())
                        }
                        other => other,
                    };
                    args.push(x);
                }
                self.lit_call(v, args)?
            }
        };
        let result = match result {
            Val::Num(c) if !inst.is_bool => {
                let r = if want == Repr::U { c.first().map_or(Repr::U, |s| s.r) } else { want };
                Val::Num(
                    c.into_iter().map(|s| self.to(s, r.max(if want == Repr::U { Repr::U } else { want }))).collect(),
                )
            }
            other => other,
        };
        self.vals[v.0 as usize] = Some(result);
        Ok(())
    }

    /// Handles output arguments of calls: the op body returns `[result, outputs…]`.
    fn finish_outputs(&mut self, v: Value, mut out: Vec<Val<'c>>) -> R<Val<'c>> {
        let inst = self.func.inst(v);
        if let Op::Call { outputs, .. } = &inst.op {
            let outs: Vec<SlotId> = outputs.iter().flatten().copied().collect();
            let rest = out.split_off(1);
            for (s, val) in outs.iter().zip(rest) {
                if let Val::Void = val {
                    continue;
                }
                self.store_val(*s, &val);
            }
        }
        Ok(out.into_iter().next().unwrap_or(Val::Void))
    }

    /// Threaded form: the op's body lives in a target-library function called here.
    fn threaded(&mut self, v: Value, args: Vec<Val<'c>>) -> R<Val<'c>> {
        let inst = self.func.inst(v);
        // setcomp-like calls read the variable they update: inline.
        if let Op::Call { builtin, .. } = &inst.op {
            if matches!(builtin, Builtin::SetComp | Builtin::SetXComp | Builtin::SetYComp | Builtin::SetZComp) {
                let out = self.op_body(v, &args)?;
                return self.finish_outputs(v, out);
            }
        }
        let name = self.threaded_name(v, &args);
        let existing = self.m.get_function(&name);
        // Shapes of arguments → parameter list.
        let mut ptys: Vec<BasicMetadataTypeEnum<'c>> = vec![
            self.i8p().into(),
            self.cx.i64_type().ptr_type(AddressSpace::default()).into(),
            self.mty(false).into(),
            self.f32t.ptr_type(AddressSpace::default()).into(),
        ];
        let mut flat: Vec<BasicMetadataValueEnum<'c>> = Vec::new();
        for a in &args {
            match a {
                Val::Num(c) => {
                    for s in c {
                        ptys.push(s.v.get_type().into());
                        flat.push(s.v.into());
                        if let Some((x, y)) = s.d {
                            ptys.push(x.get_type().into());
                            ptys.push(y.get_type().into());
                            flat.push(x.into());
                            flat.push(y.into());
                        }
                    }
                }
                Val::Mask(m) => {
                    ptys.push(m.v.get_type().into());
                    flat.push(m.v.into());
                }
                _ => {}
            }
        }
        let (f, shape) = match existing {
            Some(f) => {
                let shape = self.shapes.get(&name).cloned().expect("shape");
                (f, shape)
            }
            None => {
                // Build the body in a fresh function.
                let caller_bb = self.b.get_insert_block().expect("bb");
                let saved_st = self.st.clone();
                let tmp_ty = self.cx.void_type().fn_type(&ptys, false);
                let tmp = self.m.add_function(&format!("{name}.tmp"), tmp_ty, Some(Linkage::Internal));
                let entry = self.cx.append_basic_block(tmp, "entry");
                self.b.position_at_end(entry);
                // Parameters back into values.
                let mut k = 4u32;
                let mut pargs = Vec::new();
                for a in &args {
                    pargs.push(match a {
                        Val::Num(c) => Val::Num(
                            c.iter()
                                .map(|s| {
                                    let v = tmp.get_nth_param(k).expect("p");
                                    k += 1;
                                    let d = s.d.map(|_| {
                                        let x = tmp.get_nth_param(k).expect("p");
                                        let y = tmp.get_nth_param(k + 1).expect("p");
                                        k += 2;
                                        (x, y)
                                    });
                                    S { r: s.r, v, d }
                                })
                                .collect(),
                        ),
                        Val::Mask(m) => {
                            let v = tmp.get_nth_param(k).expect("p");
                            k += 1;
                            Val::Mask(M { uni: m.uni, v })
                        }
                        other => other.clone(),
                    });
                }
                let maskp = self.entry_alloca(self.mty(false));
                self.b.build_store(maskp, tmp.get_nth_param(2).expect("mask")).expect("store");
                let mut stn = saved_st.clone().expect("st");
                stn.f = tmp;
                stn.mask = maskp;
                stn.ctx = tmp.get_nth_param(0).expect("ctx");
                stn.host = tmp.get_nth_param(1).expect("host");
                stn.g = tmp.get_nth_param(3).expect("g");
                self.st = Some(stn);
                let out = self.op_body(v, &pargs)?;
                // Return everything as one struct.
                let mut rvals: Vec<BasicValueEnum<'c>> = Vec::new();
                let mut shape = Vec::new();
                for o in &out {
                    match o {
                        Val::Num(c) => {
                            shape.push(Shape::Num(c.iter().map(|s| s.r).collect()));
                            for s in c {
                                rvals.push(s.v);
                                if let Some((x, y)) = s.d {
                                    rvals.push(x);
                                    rvals.push(y);
                                }
                            }
                        }
                        Val::Mask(m) => {
                            shape.push(Shape::Mask(m.uni));
                            rvals.push(m.v);
                        }
                        Val::Str(s) => shape.push(Shape::Str(s.clone())),
                        Val::Void => shape.push(Shape::Void),
                    }
                }
                let rtys: Vec<BasicTypeEnum<'c>> = rvals.iter().map(|v| v.get_type()).collect();
                let sty = self.cx.struct_type(&rtys, false);
                let fty = sty.fn_type(&ptys, false);
                let f = self.m.add_function(&name, fty, Some(Linkage::Internal));
                f.add_attribute(
                    AttributeLoc::Function,
                    self.cx.create_enum_attribute(Attribute::get_named_enum_kind_id("alwaysinline"), 0),
                );
                self.set_fn_attrs(f);
                // Move the blocks of tmp into f: simplest is to rebuild the return in tmp and
                // then replace tmp by f.
                let mut agg = sty.get_undef();
                for (i, v) in rvals.iter().enumerate() {
                    agg = self.b.build_insert_value(agg, *v, i as u32, "").expect("insert").into_struct_value();
                }
                self.b.build_return(Some(&agg)).expect("ret");
                // Transplant every basic block of tmp into f and remap the parameters.
                for (i, p) in tmp.get_param_iter().enumerate() {
                    unsafe { replace_uses(p, f.get_nth_param(i as u32).expect("param")) };
                }
                while let Some(bb) = tmp.get_first_basic_block() {
                    unsafe { transplant(bb, f) };
                }
                unsafe { tmp.delete() };
                self.shapes.insert(name.clone(), shape.clone());
                self.threaded_fns += 1;
                self.st = saved_st;
                self.b.position_at_end(caller_bb);
                (f, shape)
            }
        };
        // The call.
        let st = self.st().clone();
        let m = self.load_mask(st.mask);
        let mut cargs: Vec<BasicMetadataValueEnum<'c>> = vec![st.ctx.into(), st.host.into(), m.v.into(), st.g.into()];
        cargs.extend(flat);
        let ret = self.b.build_call(f, &cargs, "").expect("call").try_as_basic_value().basic();
        let mut k = 0u32;
        let mut take = |cg: &Self| {
            let x = cg.b.build_extract_value(ret.expect("struct").into_struct_value(), k, "").expect("extract");
            k += 1;
            x
        };
        let mut out = Vec::new();
        for sh in &shape {
            out.push(match sh {
                Shape::Num(rs) => Val::Num(
                    rs.iter()
                        .map(|&r| {
                            let v = take(self);
                            let d = (r == Repr::D).then(|| (take(self), take(self)));
                            S { r, v, d }
                        })
                        .collect(),
                ),
                Shape::Mask(uni) => Val::Mask(M { uni: *uni, v: take(self) }),
                Shape::Str(s) => Val::Str(s.clone()),
                Shape::Void => Val::Void,
            });
        }
        self.finish_outputs(v, out)
    }

    fn threaded_name(&self, v: Value, args: &[Val<'c>]) -> String {
        let inst = self.func.inst(v);
        let letter = |t: Type| match t.base {
            BaseType::Float => "f",
            BaseType::Color => "c",
            BaseType::Point => "p",
            BaseType::Vector => "v",
            BaseType::Normal => "n",
            BaseType::Matrix => "m",
            BaseType::String => "s",
            BaseType::Void => "x",
        };
        let op = match &inst.op {
            Op::Unary(UnOp::Neg) => "neg".to_string(),
            Op::Unary(UnOp::Not) => "not".to_string(),
            Op::Binary(b) => b.name().to_string(),
            Op::Select => "select".to_string(),
            Op::Convert => format!("to{}", letter(inst.ty)),
            Op::MakeTriple => format!("make{}", letter(inst.ty)),
            Op::MakeMatrix => "makem".to_string(),
            Op::FromSpace => format!("from{}", letter(inst.ty)),
            Op::Call { builtin, overload, .. } => format!("{builtin}{overload}"),
            _ => "op".to_string(),
        };
        let mut types = String::new();
        let mut reprs = String::new();
        let mut extra = String::new();
        for (a, val) in inst.args.iter().zip(args) {
            let t = self.func.inst(*a).ty;
            types.push_str(if self.func.inst(*a).is_bool { "b" } else { letter(t) });
            if let Some(n) = t.array {
                types.push_str(&n.to_string());
            }
            match val {
                Val::Num(c) => reprs.push(c.first().map_or('u', |s| s.r.letter())),
                Val::Mask(m) => reprs.push(if m.uni { 'u' } else { 'v' }),
                Val::Str(s) => {
                    reprs.push('s');
                    extra.push('.');
                    extra.extend(s.concat().chars().filter(char::is_ascii_alphanumeric));
                }
                Val::Void => reprs.push('x'),
            }
        }
        let want = self.inst_repr[v.0 as usize].letter();
        let host = if self.lights_by_renderer { ".host" } else { "" };
        format!("ar_{op}_{types}.{reprs}{want}{extra}.{}{host}", letter(inst.ty))
    }

    fn load_elem(&mut self, s: SlotId, index: Value, ty: Type) -> R<Val<'c>> {
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

/// Result shapes of threaded functions.
#[derive(Clone, Debug)]
pub enum Shape {
    /// Float components with their representations.
    Num(Vec<Repr>),
    /// A mask (uniform?).
    Mask(bool),
    /// A compile-time string.
    Str(Vec<String>),
    /// Nothing.
    Void,
}

unsafe fn replace_uses<'c>(a: BasicValueEnum<'c>, b: BasicValueEnum<'c>) {
    use inkwell::values::AsValueRef;
    inkwell::llvm_sys::core::LLVMReplaceAllUsesWith(a.as_value_ref(), b.as_value_ref());
}

unsafe fn transplant<'c>(bb: inkwell::basic_block::BasicBlock<'c>, f: FunctionValue<'c>) {
    use inkwell::llvm_sys::core::{LLVMAppendExistingBasicBlock, LLVMRemoveBasicBlockFromParent};
    use inkwell::values::AsValueRef;
    let bbr = bb.as_mut_ptr();
    LLVMRemoveBasicBlockFromParent(bbr);
    LLVMAppendExistingBasicBlock(f.as_value_ref(), bbr);
}

/// The numbers a slot of type `ty` holds for the constant `c`: one per component, a float
/// widened to every component of a triple or to the diagonal of a matrix.
fn slot_values(c: &Const, ty: Type) -> Vec<f64> {
    let (mut nums, mut strs) = (Vec::new(), Vec::new());
    flatten(c, &mut nums, &mut strs);
    let w = Cg::slot_comps(ty).max(1);
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

fn flatten(c: &Const, out: &mut Vec<f64>, strs: &mut Vec<String>) {
    match c {
        Const::Float(x) => out.push(*x),
        Const::Triple(t) => out.extend_from_slice(t),
        Const::Matrix(m) => out.extend_from_slice(m),
        Const::Str(s) => strs.push(s.clone()),
        Const::Array(v) => v.iter().for_each(|e| flatten(e, out, strs)),
    }
}

fn space_index(name: &str) -> Option<u32> {
    let cs = anysl_core::stdlib::ColorSpace::from_name(name)?;
    rt::COLOR_SPACES.iter().position(|n| anysl_core::stdlib::ColorSpace::from_name(n) == Some(cs)).map(|i| i as u32)
}

impl<'c> Cg<'c, '_> {
    fn as_nums(&self, v: &Val<'c>) -> R<Vec<S<'c>>> {
        match v {
            Val::Num(c) => Ok(c.clone()),
            Val::Mask(m) => Ok(vec![self.sel(*m, self.fc(1.0), self.fc(0.0))]),
            other => err(format!("not numeric: {other:?}")),
        }
    }
    fn as_mask(&self, v: &Val<'c>) -> R<M<'c>> {
        match v {
            Val::Mask(m) => Ok(*m),
            Val::Num(c) => {
                let mut r = self.cmp(FloatPredicate::UNE, c[0], self.fc(0.0));
                for &x in &c[1..] {
                    r = self.mor(r, self.cmp(FloatPredicate::UNE, x, self.fc(0.0)));
                }
                Ok(r)
            }
            other => err(format!("not a condition: {other:?}")),
        }
    }
    fn as_str(v: &Val<'c>) -> String {
        match v {
            Val::Str(s) => s.first().cloned().unwrap_or_default(),
            _ => String::new(),
        }
    }

    /// Component-wise op with broadcast of one-component operands.
    fn cwise(&self, args: &[Vec<S<'c>>], w: usize, f: impl Fn(&Self, &[S<'c>]) -> S<'c>) -> Vec<S<'c>> {
        (0..w)
            .map(|c| {
                let xs: Vec<S<'c>> =
                    args.iter().map(|a| if a.len() == 1 { a[0] } else { a[c.min(a.len() - 1)] }).collect();
                f(self, &xs)
            })
            .collect()
    }

    /// The body of one op: `[result, outputs…]`.
    fn op_body(&mut self, v: Value, args: &[Val<'c>]) -> R<Vec<Val<'c>>> {
        let func = self.func;
        let inst = func.inst(v);
        let aty = |i: usize| func.inst(inst.args[i]).ty;
        let res = match &inst.op {
            Op::Unary(UnOp::Neg) => Val::Num(self.as_nums(&args[0])?.into_iter().map(|s| self.neg(s)).collect()),
            Op::Unary(UnOp::Not) => Val::Mask(self.mnot(self.as_mask(&args[0])?)),
            Op::Binary(op) => self.binary(*op, inst, args)?,
            Op::Select => {
                let c = self.as_mask(&args[0])?;
                match (&args[1], &args[2]) {
                    (Val::Mask(a), Val::Mask(b)) => Val::Mask(self.msel(c, *a, *b)),
                    (Val::Str(a), Val::Str(b)) => {
                        let pick = match &func.inst(inst.args[0]).op {
                            Op::Const(Const::Float(x)) => *x != 0.0,
                            _ => return err("string select on a run-time condition"),
                        };
                        Val::Str(if pick { a.clone() } else { b.clone() })
                    }
                    (a, b) => {
                        let (a, b) = (self.as_nums(a)?, self.as_nums(b)?);
                        let w = a.len().max(b.len());
                        Val::Num(self.cwise(&[a, b], w, |cg, x| cg.sel(c, x[0], x[1])))
                    }
                }
            }
            Op::Convert => {
                if inst.is_bool {
                    Val::Mask(self.as_mask(&args[0])?)
                } else {
                    match &args[0] {
                        Val::Str(s) => Val::Str(s.clone()),
                        a => {
                            let x = self.as_nums(a)?;
                            let w = Self::slot_comps(inst.ty).max(1);
                            if inst.ty.base == BaseType::Matrix && x.len() == 1 {
                                Val::Num((0..16).map(|i| if i % 5 == 0 { x[0] } else { self.fc(0.0) }).collect())
                            } else if x.len() == 1 {
                                Val::Num(vec![x[0]; w])
                            } else {
                                Val::Num(x)
                            }
                        }
                    }
                }
            }
            Op::MakeTriple | Op::MakeMatrix => {
                let mut c = Vec::new();
                for a in args {
                    c.push(self.as_nums(a)?[0]);
                }
                Val::Num(c)
            }
            Op::FromSpace => {
                let x = self.as_nums(&args[1])?;
                if inst.ty.base == BaseType::Color {
                    match space_index(&Self::as_str(&args[0])) {
                        Some(from) => {
                            Val::Num(self.rt_call(RtKind::Geo, rt::Geo::CTransform as u32 | from << 8, &x, 3, false))
                        }
                        None => Val::Num(x),
                    }
                } else {
                    let to = self.space_matrix(rt::SPACE_TO_CURRENT, &Self::as_str(&args[0]));
                    let aux = match inst.ty.base {
                        BaseType::Matrix => rt::Geo::MatMul as u32,
                        BaseType::Vector => rt::Geo::XformVector as u32,
                        BaseType::Normal => rt::Geo::XformNormal as u32,
                        _ => rt::Geo::XformPoint as u32,
                    };
                    // `matrix "name" m` is m · (name → current); a triple is transformed by it.
                    let all: Vec<S<'c>> = if aux == rt::Geo::MatMul as u32 {
                        x.into_iter().chain(to).collect()
                    } else {
                        to.into_iter().chain(x).collect()
                    };
                    let n_out = if aux == rt::Geo::MatMul as u32 { 16 } else { 3 };
                    Val::Num(self.rt_call(RtKind::Geo, aux, &all, n_out, false))
                }
            }
            Op::Call { builtin, outputs, .. } => {
                let _ = aty;
                return self.builtin(v, *builtin, outputs, args);
            }
            Op::Const(_) | Op::Load(_) | Op::LoadElem(_) => return err("memory op in a threaded body"),
        };
        Ok(vec![res])
    }

    fn binary(&mut self, op: BinOp, inst: &ir::Inst, args: &[Val<'c>]) -> R<Val<'c>> {
        let func = self.func;
        let ta = func.inst(inst.args[0]).ty.base;
        let tb = func.inst(inst.args[1]).ty.base;
        Ok(match op {
            BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div => {
                let (a, b) = (self.as_nums(&args[0])?, self.as_nums(&args[1])?);
                if ta == BaseType::Matrix && tb == BaseType::Matrix && matches!(op, BinOp::Mul | BinOp::Div) {
                    let aux = if op == BinOp::Mul { rt::Geo::MatMul as u32 } else { rt::Geo::MatDiv as u32 };
                    let all: Vec<S<'c>> = a.into_iter().chain(b).collect();
                    return Ok(Val::Num(self.rt_call(RtKind::Geo, aux, &all, 16, false)));
                }
                let w = a.len().max(b.len());
                Val::Num(self.cwise(&[a, b], w, |cg, x| match op {
                    BinOp::Add => cg.add(x[0], x[1]),
                    BinOp::Sub => cg.sub(x[0], x[1]),
                    BinOp::Mul => cg.mul(x[0], x[1]),
                    _ => cg.div(x[0], x[1]),
                }))
            }
            BinOp::Dot => {
                let (a, b) = (self.as_nums(&args[0])?, self.as_nums(&args[1])?);
                Val::Num(vec![self.dot(&a, &b)])
            }
            BinOp::Cross => {
                let (a, b) = (self.as_nums(&args[0])?, self.as_nums(&args[1])?);
                Val::Num(self.cross(&a, &b))
            }
            BinOp::And | BinOp::Or => {
                let (a, b) = (self.as_mask(&args[0])?, self.as_mask(&args[1])?);
                Val::Mask(if op == BinOp::And { self.mand(a, b) } else { self.mor(a, b) })
            }
            _ => match (&args[0], &args[1]) {
                (Val::Str(a), Val::Str(b)) => Val::Mask(self.mconst((a == b) != (op == BinOp::Ne))),
                (Val::Mask(a), Val::Mask(b)) => {
                    let diff = self.mxor(*a, *b);
                    Val::Mask(if op == BinOp::Ne { diff } else { self.mnot(diff) })
                }
                (a, b) => {
                    let (a, b) = (self.as_nums(a)?, self.as_nums(b)?);
                    let w = a.len().min(b.len());
                    let mut r = self.mconst(op != BinOp::Ne);
                    for c in 0..w {
                        let (x, y) = (a[c], b[c]);
                        r = match op {
                            BinOp::Eq => self.mand(r, self.cmp(FloatPredicate::OEQ, x, y)),
                            BinOp::Ne => self.mor(r, self.cmp(FloatPredicate::UNE, x, y)),
                            BinOp::Lt => self.cmp(FloatPredicate::OLT, x, y),
                            BinOp::Le => self.cmp(FloatPredicate::OLE, x, y),
                            BinOp::Gt => self.cmp(FloatPredicate::OGT, x, y),
                            _ => self.cmp(FloatPredicate::OGE, x, y),
                        };
                    }
                    Val::Mask(r)
                }
            },
        })
    }

    #[allow(clippy::too_many_lines)]
    fn builtin(&mut self, v: Value, builtin: Builtin, outputs: &[Option<SlotId>], args: &[Val<'c>]) -> R<Vec<Val<'c>>> {
        let func = self.func;
        let inst = func.inst(v);
        let n = args.len();
        let aty = |i: usize| inst.args.get(i).map_or(BaseType::Void, |a| func.inst(*a).ty.base);
        let aarr = |i: usize| inst.args.get(i).and_then(|a| func.inst(*a).ty.array);
        let rw = inst.ty.base.components().max(1);
        let nums = |cg: &Self, i: usize| cg.as_nums(&args[i]);
        let un_rt = |cg: &mut Self, aux: u32| -> R<Val<'c>> {
            let x = cg.as_nums(&args[0])?;
            let mut out = Vec::new();
            for s in x {
                out.extend(cg.rt_call(RtKind::Un, aux, &[s], 1, false));
            }
            Ok(Val::Num(out))
        };
        let bin_rt = |cg: &mut Self, aux: u32, w: usize| -> R<Val<'c>> {
            let all: Vec<Vec<S<'c>>> = (0..args.len()).map(|i| cg.as_nums(&args[i])).collect::<R<_>>()?;
            let mut out = Vec::new();
            for c in 0..w {
                let xs: Vec<S<'c>> =
                    all.iter().map(|a| if a.len() == 1 { a[0] } else { a[c.min(a.len() - 1)] }).collect();
                out.extend(cg.rt_call(RtKind::Bin, aux, &xs, 1, false));
            }
            Ok(Val::Num(out))
        };
        let noise_dims = |i0: usize, i1: usize| -> Option<u32> {
            let tys: Vec<BaseType> = (i0..i1).map(aty).collect();
            match tys.as_slice() {
                [BaseType::Float] => Some(1),
                [BaseType::Float, BaseType::Float] => Some(2),
                [p] if p.is_triple() => Some(3),
                [p, BaseType::Float] if p.is_triple() => Some(4),
                _ => None,
            }
        };
        let flat_args = |cg: &Self, r: std::ops::Range<usize>| -> R<Vec<S<'c>>> {
            let mut all = Vec::new();
            for i in r {
                all.extend(cg.as_nums(&args[i])?);
            }
            Ok(all)
        };
        let res: Val<'c> = match builtin {
            Builtin::Abs => Val::Num(nums(self, 0)?.into_iter().map(|s| self.abs(s)).collect()),
            Builtin::Floor => Val::Num(nums(self, 0)?.into_iter().map(|s| self.floor(s)).collect()),
            Builtin::Ceil => Val::Num(nums(self, 0)?.into_iter().map(|s| self.ceil(s)).collect()),
            Builtin::Sqrt => Val::Num(nums(self, 0)?.into_iter().map(|s| self.sqrt(s)).collect()),
            Builtin::Sign => Val::Num(
                nums(self, 0)?
                    .into_iter()
                    .map(|x| {
                        let r = if x.r == Repr::D { Repr::V } else { x.r };
                        let z = self.to(self.fc(0.0), r);
                        let gt = self.cmp(FloatPredicate::OGT, x, self.fc(0.0));
                        let lt = self.cmp(FloatPredicate::OLT, x, self.fc(0.0));
                        let inner = self.sel(lt, self.to(self.fc(-1.0), r), z);
                        let v = self.sel(gt, self.to(self.fc(1.0), r), inner);
                        self.to(v, x.r)
                    })
                    .collect(),
            ),
            Builtin::Round => Val::Num(
                nums(self, 0)?
                    .into_iter()
                    .map(|x| self.constant_part(x.r, self.unary_intr("llvm.round", x.v)))
                    .collect(),
            ),
            Builtin::InverseSqrt => Val::Num(nums(self, 0)?.into_iter().map(|x| self.rsqrt(x)).collect()),
            Builtin::Exp => un_rt(self, rt::Un::Exp as u32)?,
            Builtin::Log if n == 1 => un_rt(self, rt::Un::Log as u32)?,
            Builtin::Log if n == 2 => bin_rt(self, rt::Bin::LogBase as u32, nums(self, 0)?.len())?,
            Builtin::Sin => un_rt(self, rt::Un::Sin as u32)?,
            Builtin::Cos => un_rt(self, rt::Un::Cos as u32)?,
            Builtin::Tan => un_rt(self, rt::Un::Tan as u32)?,
            Builtin::Asin => un_rt(self, rt::Un::Asin as u32)?,
            Builtin::Acos => un_rt(self, rt::Un::Acos as u32)?,
            Builtin::Atan if n == 1 => un_rt(self, rt::Un::Atan as u32)?,
            Builtin::Atan if n == 2 => bin_rt(self, rt::Bin::Atan2 as u32, 1)?,
            Builtin::Radians => Val::Num(
                nums(self, 0)?.into_iter().map(|s| self.mul(s, self.fc(std::f64::consts::PI / 180.0))).collect(),
            ),
            Builtin::Degrees => Val::Num(
                nums(self, 0)?.into_iter().map(|s| self.mul(s, self.fc(180.0 / std::f64::consts::PI))).collect(),
            ),
            Builtin::Pow if n == 2 => bin_rt(self, rt::Bin::Pow as u32, nums(self, 0)?.len())?,
            Builtin::Mod if n == 2 => {
                let all = vec![nums(self, 0)?, nums(self, 1)?];
                let w = all[0].len();
                Val::Num(self.cwise(&all, w, |cg, x| cg.fmod(x[0], x[1])))
            }
            Builtin::Min | Builtin::Max if n >= 2 => {
                let all: Vec<Vec<S<'c>>> = (0..n).map(|i| nums(self, i)).collect::<R<_>>()?;
                let max = builtin == Builtin::Max;
                Val::Num(self.cwise(&all, rw, |cg, x| {
                    let mut r = cg.minmax(x[0], x[1], max);
                    for &z in &x[2..] {
                        r = cg.minmax(r, z, max);
                    }
                    r
                }))
            }
            Builtin::Step if n == 2 => {
                let all = vec![nums(self, 0)?, nums(self, 1)?];
                Val::Num(self.cwise(&all, rw, |cg, x| cg.step(x[0], x[1])))
            }
            Builtin::Clamp if n == 3 => {
                let all: Vec<Vec<S<'c>>> = (0..3).map(|i| nums(self, i)).collect::<R<_>>()?;
                Val::Num(self.cwise(&all, rw, |cg, x| cg.clamp(x[0], x[1], x[2])))
            }
            Builtin::Mix if n == 3 => {
                let all: Vec<Vec<S<'c>>> = (0..3).map(|i| nums(self, i)).collect::<R<_>>()?;
                Val::Num(self.cwise(&all, rw, |cg, x| cg.mix(x[0], x[1], x[2])))
            }
            Builtin::SmoothStep if n == 3 => {
                let all: Vec<Vec<S<'c>>> = (0..3).map(|i| nums(self, i)).collect::<R<_>>()?;
                Val::Num(self.cwise(&all, rw, |cg, x| cg.smoothstep(x[0], x[1], x[2])))
            }
            Builtin::Length => {
                let a = nums(self, 0)?;
                Val::Num(vec![self.length(&a)])
            }
            Builtin::Distance => {
                let (a, b) = (nums(self, 0)?, nums(self, 1)?);
                let d: Vec<S<'c>> = (0..3).map(|c| self.sub(a[c], b[c])).collect();
                Val::Num(vec![self.length(&d)])
            }
            Builtin::Normalize => {
                let a = nums(self, 0)?;
                if a.iter().any(|s| s.r == Repr::D) {
                    Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Normalize as u32, &a, 3, false))
                } else {
                    Val::Num(self.normalize(&a))
                }
            }
            Builtin::FaceForward => {
                let (nn, i) = (nums(self, 0)?, nums(self, 1)?);
                let nref = if n == 3 { nums(self, 2)? } else { self.read_global(Global::Ng) };
                let flip = self.cmp(FloatPredicate::OGT, self.dot(&i, &nref), self.fc(0.0));
                Val::Num(nn.iter().map(|&c| self.sel(flip, self.neg(c), c)).collect())
            }
            Builtin::Reflect => {
                let (i, nn) = (nums(self, 0)?, nums(self, 1)?);
                Val::Num(self.reflect(&i, &nn))
            }
            Builtin::Refract => {
                let a = flat_args(self, 0..3)?;
                if a.iter().any(|s| s.r == Repr::D) {
                    Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Refract as u32, &a, 3, false))
                } else {
                    Val::Num(self.refract(&a[0..3], &a[3..6], a[6]))
                }
            }
            Builtin::Fresnel => {
                let a = flat_args(self, 0..3)?;
                let r = if a.iter().any(|s| s.r == Repr::D) {
                    self.rt_call(RtKind::Geo, rt::Geo::Fresnel as u32, &a, 8, false)
                } else {
                    self.fresnel(&a[0..3], &a[3..6], a[6])
                };
                // Outputs in argument order: kr, kt[, R, T].
                let mut outs = Vec::new();
                let parts: [Vec<S<'c>>; 4] = [vec![r[0]], vec![r[1]], r[2..5].to_vec(), r[5..8].to_vec()];
                for (k, o) in outputs.iter().enumerate() {
                    if o.is_some() && k >= 3 {
                        outs.push(Val::Num(parts[(k - 3).min(3)].clone()));
                    }
                }
                let mut all = vec![Val::Void];
                all.extend(outs);
                return Ok(all);
            }
            Builtin::PtLineD => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::PtLineD as u32, &flat_args(self, 0..3)?, 1, false))
            }
            Builtin::Rotate if aty(0).is_triple() => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Rotate as u32, &flat_args(self, 0..4)?, 3, false))
            }
            Builtin::Rotate => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::RotateM as u32, &flat_args(self, 0..3)?, 16, false))
            }
            Builtin::Translate => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Translate as u32, &flat_args(self, 0..2)?, 16, false))
            }
            Builtin::Scale => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::ScaleM as u32, &flat_args(self, 0..2)?, 16, false))
            }
            Builtin::SpecularBrdf => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::SpecularBrdf as u32, &flat_args(self, 0..4)?, 3, false))
            }
            Builtin::XComp | Builtin::YComp | Builtin::ZComp => {
                let c = match builtin {
                    Builtin::XComp => 0,
                    Builtin::YComp => 1,
                    _ => 2,
                };
                Val::Num(vec![nums(self, 0)?[c]])
            }
            Builtin::SetXComp | Builtin::SetYComp | Builtin::SetZComp => {
                let c = match builtin {
                    Builtin::SetXComp => 0,
                    Builtin::SetYComp => 1,
                    _ => 2,
                };
                if let Some(Some(s)) = outputs.first() {
                    let x = nums(self, 0)?[0];
                    let m = self.load_mask(self.st().mask);
                    let m = if self.slots[s.0 as usize].r == Repr::U { None } else { Some(m) };
                    self.store_comp(*s, c, x, m);
                }
                Val::Void
            }
            Builtin::Comp if aty(0) == BaseType::Matrix => {
                let m = nums(self, 0)?;
                let (r, c) = (self.const_index(inst.args[1])?, self.const_index(inst.args[2])?);
                Val::Num(vec![m[r.min(3) * 4 + c.min(3)]])
            }
            Builtin::Comp => {
                let vv = nums(self, 0)?;
                let i = self.floor(nums(self, 1)?[0]);
                let i = self.minmax(self.minmax(i, self.fc(0.0), true), self.fc(2.0), false);
                let is0 = self.cmp(FloatPredicate::OEQ, i, self.fc(0.0));
                let is1 = self.cmp(FloatPredicate::OEQ, i, self.fc(1.0));
                let r = self.sel(is1, vv[1], vv[2]);
                Val::Num(vec![self.sel(is0, vv[0], r)])
            }
            Builtin::SetComp => {
                let Some(Some(s)) = outputs.first() else { return Ok(vec![Val::Void]) };
                let is_matrix = func.slot(*s).ty.base == BaseType::Matrix;
                let uni = self.slots[s.0 as usize].r == Repr::U;
                let m = self.load_mask(self.st().mask);
                if is_matrix {
                    let (r, c) = (self.const_index(inst.args[0])?, self.const_index(inst.args[1])?);
                    let x = nums(self, 2)?[0];
                    self.store_comp(*s, r.min(3) * 4 + c.min(3), x, if uni { None } else { Some(m) });
                } else {
                    let i = self.floor(nums(self, 0)?[0]);
                    let x = nums(self, 1)?[0];
                    for c in 0..3 {
                        let hit = self.cmp(FloatPredicate::OEQ, i, self.fc(c as f64));
                        let hm = if uni { hit } else { self.mand(m, hit) };
                        self.store_comp(*s, c, x, Some(hm));
                    }
                }
                Val::Void
            }
            Builtin::Transform | Builtin::VTransform | Builtin::NTransform => {
                let last = n - 1;
                let x = nums(self, last)?;
                match (0..n).find(|&i| aty(i) == BaseType::Matrix) {
                    Some(mi) => {
                        let aux = match (builtin, inst.ty.base) {
                            (Builtin::VTransform, _) | (_, BaseType::Vector) => rt::Geo::XformVector as u32,
                            (Builtin::NTransform, _) | (_, BaseType::Normal) => rt::Geo::XformNormal as u32,
                            _ => rt::Geo::XformPoint as u32,
                        };
                        let mut x = x;
                        if (0..n).any(|i| aty(i) == BaseType::String) {
                            // transform(fromspace, m, p): from `fromspace` to current, then by `m`.
                            let mut all = self.space_matrix(rt::SPACE_TO_CURRENT, &Self::as_str(&args[0]));
                            all.extend(x);
                            x = self.rt_call(RtKind::Geo, aux, &all, 3, false);
                        }
                        let mut all = nums(self, mi)?;
                        all.extend(x);
                        Val::Num(self.rt_call(RtKind::Geo, aux, &all, 3, false))
                    }
                    None => {
                        let aux = match (builtin, inst.ty.base) {
                            (Builtin::VTransform, _) | (_, BaseType::Vector) => rt::Geo::XformVector as u32,
                            (Builtin::NTransform, _) | (_, BaseType::Normal) => rt::Geo::XformNormal as u32,
                            _ => rt::Geo::XformPoint as u32,
                        };
                        let mut all = if n == 3 {
                            let names =
                                format!("{}{}{}", Self::as_str(&args[0]), rt::SPACE_SEPARATOR, Self::as_str(&args[1]));
                            self.space_matrix(rt::SPACE_BETWEEN, &names)
                        } else {
                            self.space_matrix(rt::SPACE_FROM_CURRENT, &Self::as_str(&args[0]))
                        };
                        all.extend(x);
                        Val::Num(self.rt_call(RtKind::Geo, aux, &all, 3, false))
                    }
                }
            }
            Builtin::CTransform => {
                let spaces = (0..n).filter(|&i| aty(i) == BaseType::String).count();
                let c = nums(self, spaces)?;
                let from = if spaces == 2 { space_index(&Self::as_str(&args[0])) } else { Some(0) };
                let to = space_index(&Self::as_str(&args[spaces - 1]));
                match (from, to) {
                    (Some(f), Some(t)) => {
                        Val::Num(self.rt_call(RtKind::Geo, rt::Geo::CTransform as u32 | f << 8 | t << 16, &c, 3, false))
                    }
                    _ => Val::Num(c),
                }
            }
            Builtin::Determinant => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Determinant as u32, &nums(self, 0)?, 1, false))
            }
            Builtin::Du | Builtin::Dv => {
                let x = nums(self, 0)?;
                let w = x.len() as u32;
                let idx = if builtin == Builtin::Du { Host::Du } else { Host::Dv };
                Val::Num(self.host_call(idx, w, &x, w as usize))
            }
            Builtin::Deriv => {
                let x = nums(self, 0)?;
                let w = x.len() as u32;
                let mut all = x;
                all.extend(nums(self, 1)?);
                Val::Num(self.host_call(Host::Deriv, w, &all, w as usize))
            }
            Builtin::Area => Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Area as u32, &nums(self, 0)?, 1, true)),
            Builtin::CalculateNormal => Val::Num(self.host_call(Host::CalcNormal, 0, &nums(self, 0)?, 3)),
            Builtin::FilterWidth => {
                let x = nums(self, 0)?;
                let aux = if x.len() == 3 { rt::Geo::FilterWidthP as u32 } else { rt::Geo::FilterWidth as u32 };
                Val::Num(self.rt_call(RtKind::Geo, aux, &x, 1, true))
            }
            Builtin::FilterStep => {
                let nnum = (0..n).take_while(|&i| aty(i) != BaseType::String).count();
                let any_dual =
                    (0..nnum.min(3)).any(|i| matches!(&args[i], Val::Num(c) if c.iter().any(|s| s.r == Repr::D)));
                if nnum == 2 && !any_dual {
                    // No derivatives: the filter width is 0 and filterstep is step.
                    let (e, x) = (nums(self, 0)?[0], nums(self, 1)?[0]);
                    Val::Num(vec![self.step(e, x)])
                } else if nnum >= 3 {
                    Val::Num(self.rt_call(RtKind::Bin, rt::Bin::FilterStep3 as u32, &flat_args(self, 0..3)?, 1, true))
                } else {
                    Val::Num(self.rt_call(RtKind::Bin, rt::Bin::FilterStep as u32, &flat_args(self, 0..2)?, 1, true))
                }
            }
            Builtin::FilteredPulse => {
                let (e0, e1, x) = (nums(self, 0)?[0], nums(self, 1)?[0], nums(self, 2)?[0]);
                if [e0, e1, x].iter().any(|s| s.r == Repr::D) {
                    let a = self.rt_call(RtKind::Bin, rt::Bin::FilterStep as u32, &[e0, x], 1, true)[0];
                    let b = self.rt_call(RtKind::Bin, rt::Bin::FilterStep as u32, &[e1, x], 1, true)[0];
                    Val::Num(vec![self.sub(a, b)])
                } else {
                    // No derivatives: the filter width is 0 and the pulse is a difference of steps.
                    Val::Num(vec![self.sub(self.step(e0, x), self.step(e1, x))])
                }
            }
            Builtin::Noise | Builtin::SNoise | Builtin::CellNoise => {
                let dims = noise_dims(0, n).ok_or_else(|| CgError(format!("{builtin} arguments")))?;
                let kind = match builtin {
                    Builtin::Noise => noise::NoiseKind::Unsigned,
                    Builtin::SNoise => noise::NoiseKind::Signed,
                    _ => noise::NoiseKind::Cell,
                };
                let coords = flat_args(self, 0..n)?;
                debug_assert_eq!(coords.len(), dims as usize);
                // cellnoise is a hash of the cell: a few integer ops inline, where a call
                // would spill every live vector register; Perlin noise is inline on request.
                if self.t.inline_noise || kind == noise::NoiseKind::Cell {
                    Val::Num(self.noise_inline(kind, &coords, rw))
                } else {
                    let kind = match kind {
                        noise::NoiseKind::Unsigned => rt::NoiseOp::Noise,
                        noise::NoiseKind::Signed => rt::NoiseOp::SNoise,
                        noise::NoiseKind::Cell => rt::NoiseOp::Cell,
                    };
                    let aux = rt::NoiseSel { kind, dims, out: rw as u32, extra: 0 }.encode();
                    Val::Num(self.rt_call(RtKind::Noise, aux, &coords, rw, false))
                }
            }
            Builtin::PNoise | Builtin::PSNoise => {
                let half = n / 2;
                let dims = noise_dims(0, half).ok_or_else(|| CgError(format!("{builtin} arguments")))?;
                let kind = if builtin == Builtin::PNoise { rt::NoiseOp::PNoise } else { rt::NoiseOp::PSNoise };
                let aux = rt::NoiseSel { kind, dims, out: rw as u32, extra: 0 }.encode();
                Val::Num(self.rt_call(RtKind::Noise, aux, &flat_args(self, 0..n)?, rw, false))
            }
            Builtin::Fbm | Builtin::Turbulence => {
                let dims = if aty(0).is_triple() { 3 } else { 1 };
                let used = 1;
                let kind = if builtin == Builtin::Fbm { rt::NoiseOp::Fbm } else { rt::NoiseOp::Turbulence };
                let extra = (n - used) as u32;
                let aux = rt::NoiseSel { kind, dims, out: 1, extra }.encode();
                Val::Num(self.rt_call(RtKind::Noise, aux, &flat_args(self, 0..n)?, 1, false))
            }
            Builtin::Random => Val::Num(self.host_call(Host::Random, rw as u32, &[], rw)),
            Builtin::Spline => {
                let basis = aty(0) == BaseType::String;
                let first = usize::from(basis);
                let bname = if basis { Self::as_str(&args[0]) } else { "catmull-rom".to_string() };
                let bi = anysl_core::stdlib::SplineBasis::from_name(&bname)
                    .and_then(|b| {
                        rt::SPLINE_BASES.iter().position(|n| {
                            anysl_core::stdlib::SplineBasis::from_name(n)
                                .is_some_and(|x| format!("{x:?}") == format!("{b:?}"))
                        })
                    })
                    .unwrap_or(0) as u32;
                let rest = first + 1..n;
                let (w, nk) = if rest.len() == 1 && aarr(first + 1).is_some() {
                    (aty(first + 1).components(), aarr(first + 1).unwrap_or(0) as usize)
                } else {
                    (rw, rest.len())
                };
                if nk > rt::MAX_KNOTS {
                    return err(format!("spline with {nk} knots (the JIT passes at most {})", rt::MAX_KNOTS));
                }
                let mut all = nums(self, first)?;
                all.extend(flat_args(self, rest)?);
                let aux = nk as u32 | bi << 8 | (w as u32) << 16;
                Val::Num(self.rt_call(RtKind::Spline, aux, &all, w, false))
            }
            Builtin::Ambient => Val::Num(self.light_call(Host::Ambient, 0, &[], 3)),
            Builtin::Diffuse => Val::Num(self.light_call(Host::Diffuse, 0, &nums(self, 0)?, 3)),
            Builtin::Specular => {
                let args = flat_args(self, 0..3)?;
                match self.lit_sums(&args) {
                    // specular ++ diffuse [++ ambient]; the call site keeps the sums.
                    Some(k) => Val::Num(self.light_call(Host::Specular, k, &args, 3 + 3 * k as usize)),
                    None => Val::Num(self.host_call(Host::Specular, 0, &args, 3)),
                }
            }
            Builtin::Phong => Val::Num(self.host_call(Host::Phong, 0, &flat_args(self, 0..3)?, 3)),
            Builtin::Trace => Val::Num(self.host_call(Host::Trace, 0, &flat_args(self, 0..2)?, 3)),
            Builtin::Concat => Val::Str(vec![args.iter().map(Self::as_str).collect()]),
            Builtin::Printf => Val::Void,
            Builtin::Match => {
                let (p, s) = (Self::as_str(&args[0]), Self::as_str(&args[1]));
                Val::Num(vec![self.fc(if anysl_rsl::back::rust::rt::simple_match(&p, &s) { 1.0 } else { 0.0 })])
            }
            // Outside a scene: camera rays, nothing occludes, no indirect or caustic light,
            // nothing blocks transmission (as the interpreter).
            Builtin::RayInfo
            | Builtin::RayLevel
            | Builtin::IsShadowRay
            | Builtin::IsIndirectRay
            | Builtin::Occlusion => Val::Num(vec![self.fc(0.0)]),
            Builtin::IndirectDiffuse | Builtin::Caustic => Val::Num(vec![self.fc(0.0); 3]),
            Builtin::Transmission => Val::Num(vec![self.fc(1.0); 3]),
            // Arities the checker never produces.
            Builtin::Log
            | Builtin::Atan
            | Builtin::Pow
            | Builtin::Mod
            | Builtin::Min
            | Builtin::Max
            | Builtin::Step
            | Builtin::Clamp
            | Builtin::Mix
            | Builtin::SmoothStep => return err(format!("`{builtin}` with {n} arguments")),
            // Strings are compile-time values in the JIT, and it has no texture host call.
            Builtin::Format | Builtin::Texture | Builtin::Environment | Builtin::Shadow => {
                return err(format!("built-in `{builtin}` is not supported by the JIT"))
            }
            Builtin::Surface
            | Builtin::LightSource
            | Builtin::Displacement
            | Builtin::Atmosphere
            | Builtin::Incident
            | Builtin::Opposite
            | Builtin::Attribute
            | Builtin::Option
            | Builtin::RendererInfo
            | Builtin::TextureInfo => Val::Num(vec![self.fc(0.0)]),
            Builtin::ShaderName => Val::Str(vec![String::new()]),
            Builtin::Depth => Val::Num(vec![self.read_global(Global::P)[2]]),
        };
        // Outputs not produced above keep their values.
        let mut all = vec![res];
        for o in outputs.iter().flatten() {
            let _ = o;
        }
        all.truncate(1);
        Ok(all)
    }

    /// anysl-core's `refract` for uniform and varying triples, operation for operation (dual
    /// triples use the runtime).
    fn refract(&self, i: &[S<'c>], n: &[S<'c>], eta: S<'c>) -> Vec<S<'c>> {
        let (one, zero) = (self.fc(1.0), self.fc(0.0));
        let idotn = self.dot(i, n);
        let k = self.sub(one, self.mul(self.mul(eta, eta), self.sub(one, self.mul(idotn, idotn))));
        let tir = self.cmp(FloatPredicate::OLT, k, zero);
        let s = self.add(self.mul(eta, idotn), self.sqrt(self.minmax(k, zero, true)));
        (0..3).map(|c| self.sel(tir, zero, self.sub(self.mul(i[c], eta), self.mul(n[c], s)))).collect()
    }

    /// anysl-core's `fresnel` for uniform and varying triples, operation for operation:
    /// `kr, kt, R, T` (dual triples use the runtime).
    fn fresnel(&self, i: &[S<'c>], n: &[S<'c>], eta: S<'c>) -> Vec<S<'c>> {
        let (one, zero) = (self.fc(1.0), self.fc(0.0));
        let iu = self.normalize(i);
        let c = self.minmax(self.abs(self.dot(&iu, n)), one, false);
        let inv_eta = self.div(one, eta);
        let g2 = self.add(self.sub(self.mul(inv_eta, inv_eta), one), self.mul(c, c));
        let tir = self.cmp(FloatPredicate::OLT, g2, zero);
        let g = self.sqrt(self.minmax(g2, zero, true));
        let (gpc, gmc) = (self.add(g, c), self.sub(g, c));
        let degenerate = self.mor(self.cmp(FloatPredicate::OLE, gpc, zero), tir);
        let a = self.div(gmc, self.sel(degenerate, one, gpc));
        let num = self.sub(self.mul(c, gpc), one);
        let den = self.add(self.mul(c, gmc), one);
        let b = self.div(num, self.sel(self.cmp(FloatPredicate::OEQ, den, zero), one, den));
        let half_a2 = self.mul(self.mul(self.mul(self.fc(0.5), a), a), self.add(one, self.mul(b, b)));
        let kr = self.sel(degenerate, one, self.minmax(half_a2, one, false));
        let kt = self.sub(one, kr);
        let mut out = vec![kr, kt];
        out.extend(self.reflect(&iu, n));
        out.extend(self.refract(&iu, n, eta));
        out
    }

    /// anysl-core's `reflect`: `i - n·(2·(i·n))`.
    fn reflect(&self, i: &[S<'c>], n: &[S<'c>]) -> Vec<S<'c>> {
        let k = self.mul(self.fc(2.0), self.dot(i, n));
        (0..3).map(|c| self.sub(i[c], self.mul(n[c], k))).collect()
    }

    /// `Vec3::normalize` for uniform and varying triples (dual triples use the runtime).
    fn normalize(&self, a: &[S<'c>]) -> Vec<S<'c>> {
        let l2 = self.dot(a, a);
        // Zero lengths (1/√0 = inf) are among the lanes the rare path replaces, as in
        // anysl-core.
        let k = self.rsqrt(l2);
        let unit: Vec<S<'c>> = a.iter().map(|&c| self.mul(c, k)).collect();
        let lo = 2f64.powi(-120);
        let hi = 2f64.powi(120);
        let rescale =
            self.mor(self.cmp(FloatPredicate::OLT, l2, self.fc(lo)), self.cmp(FloatPredicate::OGT, l2, self.fc(hi)));
        // The rare path, normalize(v / max|c|), only when some lane needs it (as anysl-core).
        self.when_any(rescale, unit, |cg, unit| {
            let r = cg.normalize_rescaled(a);
            (0..3).map(|c| cg.sel(rescale, r[c], unit[c])).collect()
        })
    }

    /// `normalize(v / max|c|)` for the lanes whose squared length is out of range
    /// (`Vec3::normalize_rescaled`), emitted in place on the rare path. Not a call: x86-64
    /// preserves no vector register across one, so a call inside a light loop made the
    /// register allocator keep the loop's values in stack slots on the common path too.
    fn normalize_rescaled(&self, a: &[S<'c>]) -> Vec<S<'c>> {
        let r = a.iter().map(|s| s.r).max().unwrap_or(Repr::U);
        let a: Vec<S<'c>> = a.iter().map(|&s| S { r, v: self.to(s, r).v, d: None }).collect();
        let zero = self.fc(0.0);
        let m = self.minmax(self.minmax(self.abs(a[0]), self.abs(a[1]), true), self.abs(a[2]), true);
        let usable =
            self.mand(self.cmp(FloatPredicate::OGT, m, zero), self.cmp(FloatPredicate::OLT, m, self.fc(f64::INFINITY)));
        let den = self.sel(usable, m, self.fc(1.0));
        let w: Vec<S<'c>> = a.iter().map(|&c| self.div(c, den)).collect();
        let wl2 = self.dot(&w, &w);
        let wk = self.sel(self.cmp(FloatPredicate::OGT, wl2, zero), self.rsqrt(wl2), zero);
        w.iter().map(|&c| S { r, v: self.to(self.mul(c, wk), r).v, d: None }).collect()
    }

    /// `rare(common)` where some lane of `m` is set, else `common`: a branch around code that
    /// is needed only for unusual lanes (the values are merged with phis).
    fn when_any(&self, m: M<'c>, common: Vec<S<'c>>, rare: impl FnOnce(&Self, &[S<'c>]) -> Vec<S<'c>>) -> Vec<S<'c>> {
        let f = self.cur_fn();
        let from = self.b.get_insert_block().expect("positioned");
        let rare_bb = self.cx.append_basic_block(f, "rare");
        let join = self.cx.append_basic_block(f, "join");
        self.b.build_conditional_branch(self.any(m), rare_bb, join).expect("br");
        self.b.position_at_end(rare_bb);
        let r: Vec<S<'c>> = rare(self, &common).into_iter().zip(&common).map(|(x, c)| self.to(x, c.r)).collect();
        let rare_end = self.b.get_insert_block().expect("positioned");
        self.b.build_unconditional_branch(join).expect("br");
        self.b.position_at_end(join);
        let phi = |a: BasicValueEnum<'c>, b: BasicValueEnum<'c>| -> BasicValueEnum<'c> {
            let p = self.b.build_phi(a.get_type(), "").expect("phi");
            p.add_incoming(&[(&a, from), (&b, rare_end)]);
            p.as_basic_value()
        };
        common
            .iter()
            .zip(&r)
            .map(|(c, x)| S {
                r: c.r,
                v: phi(c.v, x.v),
                d: match (c.d, x.d) {
                    (Some((cx, cy)), Some((xx, xy))) => Some((phi(cx, xx), phi(cy, xy))),
                    _ => None,
                },
            })
            .collect()
    }
}
