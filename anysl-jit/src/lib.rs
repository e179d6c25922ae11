//! # anysl-jit
//!
//! The run-time half of AnySL: an `.sl` shader loaded while the program runs is lowered from
//! the portable IR to LLVM IR as *subroutine-threaded code* (every op a call to an
//! `ar_<op>_<types>` function of a target library), specialized for the renderer's concrete
//! types (scalar `f32`, 4/8/16-wide vectors with lane masks, dual numbers), inlined,
//! optimized and compiled to machine code for the host CPU.
//!
//! ```no_run
//! use anysl_jit::{JitShader, JitOptions};
//! use anysl_core::prelude::*;
//! let shader = JitShader::from_file("shaders/rsl/plastic.sl".as_ref(), &[], JitOptions::default()).unwrap();
//! // `shader` is a SurfaceShader: any renderer shades it with f32, F32x8, Dual<f32>, …; the
//! // variant for each float type is compiled on first use.
//! assert_eq!(shader.meta().name, "plastic");
//! ```
//!
//! The pipeline ([`compile`]): IR passes (specialization of the instance's uniform
//! parameters, constant folding, DCE, uniform/varying and derivative analyses) → LLVM IR
//! generation ([`codegen`]) → the new pass manager ([`pass_pipeline`]) → MCJIT with the host's
//! `target-cpu`/`target-features`. [`CompileStats`] reports the time and the instruction
//! counts of each stage; with [`JitOptions::count_ops`] the code counts the operations it
//! executes ([`opcount`]).

pub mod abi;
pub mod check;
pub mod codegen;
pub mod opcount;
pub mod rt;
mod shader;

pub use anysl_rsl as rsl;
pub use opcount::OpCounts;
pub use shader::{variant_of, JitShader, PointOutputs};

use abi::{PointsFn, ShadeFn};
use anysl_ad::Dual;
use anysl_rsl::ir::{Const, Module};
use anysl_simd::{F32x16, F32x4, F32x8, Pair};
use codegen::{Cg, Target};
use inkwell::context::Context;
use inkwell::execution_engine::ExecutionEngine;
use inkwell::passes::PassBuilderOptions;
use inkwell::targets::{CodeModel, InitializationConfig, RelocMode, Target as LlvmTarget, TargetMachine};
use inkwell::OptimizationLevel;
use std::fmt;
use std::sync::{Arc, Once};
use std::time::Instant;

/// The float types the JIT compiles for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Variant {
    /// `f32`
    F32,
    /// `F32x4`
    X4,
    /// `F32x8`
    X8,
    /// `F32x16`
    X16,
    /// `Dual<f32>`
    DualF32,
    /// `Dual<F32x8>`
    DualX8,
    /// `Pair<Pair<F32x8>>`: four 8-lane packets per call, in 8-lane instructions.
    X8x4,
    /// `Pair<F32x16>`: two 16-lane packets per call, in 16-lane instructions.
    X16x2,
}

impl Variant {
    /// Every variant.
    pub const ALL: [Variant; 8] =
        [Self::F32, Self::X4, Self::X8, Self::X16, Self::DualF32, Self::DualX8, Self::X8x4, Self::X16x2];

    /// Lanes shaded per call (the width of the compiled code's vectors).
    #[must_use]
    pub const fn lanes(self) -> u32 {
        match self {
            Self::F32 | Self::DualF32 => 1,
            Self::X4 => 4,
            Self::X8 | Self::DualX8 => 8,
            Self::X16 => 16,
            Self::X8x4 | Self::X16x2 => 32,
        }
    }

    /// Lanes of the machine instructions: [`Variant::lanes`] is this times the packets
    /// shaded per call.
    #[must_use]
    pub const fn native_lanes(self) -> u32 {
        match self {
            Self::X8x4 => 8,
            Self::X16x2 => 16,
            v => v.lanes(),
        }
    }

    /// Whether the noise family is emitted as IR by default ([`JitOptions::inline_noise`]
    /// `None`): at four 8-lane packets per call, where the IR noise, scheduled with the code
    /// around it and without the spills a call costs, shades the noise workload shaders
    /// 1.0–1.1× as fast as the compiled build and the calls 0.9–1.0× (`workload_jit` on a
    /// Zen 3 host, docs/benchmarks.md). Elsewhere the calls (the Table-1 shaders' one-packet variants
    /// shade no faster with IR noise; two 16-lane packets measured within the spread).
    #[must_use]
    pub const fn inline_noise(self) -> bool {
        matches!(self, Self::X8x4)
    }

    /// Dual numbers.
    #[must_use]
    pub const fn dual(self) -> bool {
        matches!(self, Self::DualF32 | Self::DualX8)
    }

    /// Short name (`f32`, `x8`, `dual-x8`, …).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::F32 => "f32",
            Self::X4 => "x4",
            Self::X8 => "x8",
            Self::X16 => "x16",
            Self::DualF32 => "dual-f32",
            Self::DualX8 => "dual-x8",
            Self::X8x4 => "x8x4",
            Self::X16x2 => "x16x2",
        }
    }

    /// Index into [`Variant::ALL`].
    #[must_use]
    pub const fn index(self) -> usize {
        match self {
            Self::F32 => 0,
            Self::X4 => 1,
            Self::X8 => 2,
            Self::X16 => 3,
            Self::DualF32 => 4,
            Self::DualX8 => 5,
            Self::X8x4 => 6,
            Self::X16x2 => 7,
        }
    }

    /// Where the renderer's `Globals` of this variant's float type keeps each global.
    #[must_use]
    pub fn globals_layout(self) -> abi::GlobalsLayout {
        use abi::GlobalsLayout as L;
        match self {
            Self::F32 => L::of::<f32>(),
            Self::X4 => L::of::<F32x4>(),
            Self::X8 => L::of::<F32x8>(),
            Self::X16 => L::of::<F32x16>(),
            Self::DualF32 => L::of::<Dual<f32>>(),
            Self::DualX8 => L::of::<Dual<F32x8>>(),
            Self::X8x4 => L::of::<Pair<Pair<F32x8>>>(),
            Self::X16x2 => L::of::<Pair<F32x16>>(),
        }
    }

    /// The address compiled code of this variant calls for runtime function `kind` with
    /// `aux` ([`rt::rt_addr`] of the variant's float type). Not generic, and never inlined,
    /// so callers in other crates (tests, tools) link to this crate's copies of the runtime
    /// functions instead of compiling their own.
    #[must_use]
    #[inline(never)]
    pub fn rt_addr(self, kind: rt::RtKind, aux: u32) -> usize {
        self.rt_resolver()(kind, aux)
    }

    /// The general runtime function of `kind` for this variant's float type (the entry of
    /// [`rt::rt_table`]: the one that dispatches on `aux` at run time), as an address.
    #[must_use]
    #[inline(never)]
    pub fn rt_general_addr(self, kind: rt::RtKind) -> usize {
        (self.runtime().1)()[kind as usize] as usize
    }

    /// The address compiled code of this multi-packet variant calls for runtime function
    /// `kind` with `aux` when one call takes all its packets ([`rt::rt_addr_packets`]);
    /// `None` where each packet is called on its own ([`Variant::rt_addr`]) and for
    /// variants of one packet. Not generic, like [`Variant::rt_addr`].
    #[must_use]
    #[inline(never)]
    pub fn rt_packets_addr(self, kind: rt::RtKind, aux: u32) -> Option<usize> {
        self.rt_packets_resolver().and_then(|f| f(kind, aux))
    }

    /// Where compiled code of this variant calls a runtime function that takes all its
    /// packets at once ([`rt::rt_addr_packets`]); `None` for variants of one packet.
    fn rt_packets_resolver(self) -> Option<fn(rt::RtKind, u32) -> Option<usize>> {
        match self {
            Self::X8x4 => Some(rt::rt_addr_packets::<Pair<Pair<F32x8>>>),
            _ => None,
        }
    }

    /// Where compiled code of this variant calls for a runtime function ([`rt::rt_addr`]).
    #[inline(never)]
    fn rt_resolver(self) -> fn(rt::RtKind, u32) -> usize {
        self.runtime().0
    }

    /// The runtime of this variant's float type: [`rt::rt_addr`] and [`rt::rt_table`].
    /// Several packets per call use the functions of one packet, called once per packet,
    /// except the few that take all packets at once ([`Variant::rt_packets_addr`]).
    fn runtime(self) -> (fn(rt::RtKind, u32) -> usize, fn() -> [abi::RtFn; 5]) {
        fn of<F: abi::JitFloat>() -> (fn(rt::RtKind, u32) -> usize, fn() -> [abi::RtFn; 5]) {
            (rt::rt_addr::<F>, rt::rt_table::<F>)
        }
        match self {
            Self::F32 => of::<f32>(),
            Self::X4 => of::<F32x4>(),
            Self::X8 | Self::X8x4 => of::<F32x8>(),
            Self::X16 | Self::X16x2 => of::<F32x16>(),
            Self::DualF32 => of::<Dual<f32>>(),
            Self::DualX8 => of::<Dual<F32x8>>(),
        }
    }
}

/// Compiler settings.
#[derive(Clone, Debug, PartialEq)]
pub struct JitOptions {
    /// LLVM optimization level 0–3 (the pass pipeline, see [`pass_pipeline`], and the code
    /// generator's level).
    pub opt_level: u32,
    /// Lower ops to threaded target-library calls (inlined away); `false` emits them inline.
    pub threaded: bool,
    /// Generate code for the host CPU (`target-cpu`/`target-features`); else generic x86-64.
    pub host_cpu: bool,
    /// Specialize uniform parameters to the instance's values (recompiles on `set_param`);
    /// off, numeric parameters are read from a run-time parameter block, so one compiled
    /// variant serves every instance and `set_param` costs no compilation.
    pub specialize: bool,
    /// Emit the noise family as inline LLVM IR (vectorized hash, derivatives dropped where
    /// unused) instead of calling the Rust library: `Some(true)` for every variant,
    /// `Some(false)` for none, `None` (the default) where it measured faster than the calls —
    /// the four-packet variant [`Variant::X8x4`] ([`Variant::inline_noise`]). Inline noise
    /// compiles 3–5× slower.
    pub inline_noise: Option<bool>,
    /// LLVM optimization level of a points entry ([`compile_points`]: the loop over a point
    /// set with the shader inlined). 3 by default: LLVM's `default<O3>` loop passes pay around
    /// the inlined shader at two 16-lane packets per step (`workload_jit`, two alternating
    /// pairs of runs: plastic +18 %, checker +12 %, granite +5 % over level 2) and are within
    /// the noise at four 8-lane ones.
    pub points_opt_level: u32,
    /// Also write the numeric output parameters after the standard outputs
    /// ([`abi::output_params`]), for tools that read them ([`JitShader::eval_point`]); the
    /// caller's output buffer must have room for them.
    pub output_params: bool,
    /// Count the operations the optimized code executes ([`opcount`]): each basic block
    /// adds its vector, scalar and call counts to counters the compiled code owns
    /// ([`CompiledShader::op_counts`], [`JitShader::op_counts`]). For measuring, not for
    /// shading fast: every block executed pays an atomic add per kind it counts.
    pub count_ops: bool,
    /// Compile the light loops for contexts that hand their lights over as light records
    /// (`ShadingContext::light_records`: some lights have code, such as `.sl` lights compiled
    /// here) instead of as data. [`JitShader`] compiles this flavour of a variant beside the
    /// other, and only when a context with records first runs it.
    pub light_records: bool,
}

impl JitOptions {
    /// The defaults: O2, threaded, host CPU, specialized, noise inline where the variant
    /// shades faster with it ([`Variant::inline_noise`]), else through the library (inline
    /// noise compiles 3–5× slower and shaded no faster on the Table-1 shaders).
    #[must_use]
    pub const fn new() -> Self {
        Self {
            opt_level: 2,
            threaded: true,
            host_cpu: true,
            specialize: true,
            inline_noise: None,
            points_opt_level: 3,
            output_params: false,
            count_ops: false,
            light_records: false,
        }
    }
}

impl Default for JitOptions {
    fn default() -> Self {
        Self::new()
    }
}

/// Why a shader could not be compiled.
#[derive(Clone, Debug)]
pub struct JitError(pub String);

impl fmt::Display for JitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "jit: {}", self.0)
    }
}

impl std::error::Error for JitError {}

/// Time and size of each compilation stage.
#[derive(Clone, Debug, Default)]
pub struct CompileStats {
    /// `(stage, milliseconds)`: `ir-passes`, `llvm-irgen`, `optimize`, `codegen` (and
    /// `parse+check` when compiled from source).
    pub times_ms: Vec<(&'static str, f64)>,
    /// `(stage, count)`: IR instructions after each IR pass, then LLVM instructions after
    /// generation (`llvm-generated`) and after optimization (`llvm-optimized`).
    pub insts: Vec<(String, usize)>,
    /// Threaded target-library functions created.
    pub threaded_fns: usize,
    /// Light shaders compiled into the light loops over light records ([`InlineLight`]).
    pub inline_lights: usize,
}

impl CompileStats {
    /// Total milliseconds.
    #[must_use]
    pub fn total_ms(&self) -> f64 {
        self.times_ms.iter().map(|(_, t)| t).sum()
    }
}

/// Keeps the LLVM objects behind a compiled function alive.
struct Owned {
    ee: Option<ExecutionEngine<'static>>,
    module: Option<inkwell::module::Module<'static>>,
    ctx: Option<Box<Context>>,
    /// The counters instrumented code increments ([`JitOptions::count_ops`]); their address
    /// is compiled into the code.
    counters: Option<Box<opcount::OpCounters>>,
    /// The light shaders compiled into this code ([`InlineLight`]): kept alive so that their
    /// entries, which the code compares record entries with, name no other code meanwhile.
    inlined: Vec<InlineLight>,
}

impl Drop for Owned {
    fn drop(&mut self) {
        // The engine owns the module; both go before their context.
        self.module.take();
        self.ee.take();
        self.ctx.take();
    }
}

impl Owned {
    /// Whether code with light shaders compiled in runs `records`: every record with code is
    /// one of them (else the light loops, which call no entry, would miss a light).
    fn runs_records(&self, records: &[anysl_core::LightRecord]) -> bool {
        !self.inlined.is_empty()
            && records
                .iter()
                .all(|r| r.code.entry.is_null() || self.inlined.iter().any(|l| l.entry == r.code.entry as usize))
    }

    fn op_counts(&self) -> Option<OpCounts> {
        self.counters.as_ref().map(|c| c.get())
    }

    fn reset_op_counts(&self) {
        if let Some(c) = &self.counters {
            c.reset();
        }
    }
}

// SAFETY: after compilation the LLVM objects are never touched again except to be dropped;
// the machine code is immutable.
unsafe impl Send for Owned {}
unsafe impl Sync for Owned {}

/// A shader compiled for one variant.
pub struct CompiledShader {
    /// The entry point (see [`abi::ShadeFn`]).
    pub f: ShadeFn,
    /// A light shader's direct entry ([`anysl_core::LightCode::entry`]): present for light
    /// shaders of the non-dual variants whose code calls the host for named spaces at most.
    pub light: Option<usize>,
    /// The variant.
    pub variant: Variant,
    /// Stage times and instruction counts.
    pub stats: CompileStats,
    /// The optimized LLVM IR, when requested.
    pub llvm_ir: Option<String>,
    /// A light shader with a direct entry: what compiling it into a surface's light loops
    /// takes ([`InlineLight`]).
    pub(crate) source: Option<LightIr>,
    _owned: Owned,
}

/// A light shader's lowered IR and instance, kept with its compiled variant so that a surface
/// compiled later can compile the light into its own light loops ([`InlineLight`]).
#[derive(Clone)]
pub(crate) struct LightIr {
    pub(crate) module: Arc<Module>,
    pub(crate) values: Vec<Const>,
    pub(crate) opts: JitOptions,
}

/// A light shader compiled into a surface's light loops: the compiled light loops select the
/// light whose `entry` a record's entry is and run its code inline (no call, so the surface's
/// live values stay in registers); such code runs only contexts whose records with code are all
/// compiled in ([`CompiledShader::runs_records`]). The light's variant is the surface's; it
/// stays alive as long as the surface's code.
#[derive(Clone)]
pub(crate) struct InlineLight {
    pub(crate) entry: usize,
    pub(crate) light: Arc<CompiledShader>,
}

/// At most this many distinct light shaders are compiled into one surface's light loops (each
/// adds its code to the surface's compile); a context with more runs the flavour that calls
/// them.
pub const MAX_INLINE_LIGHTS: usize = 8;

impl CompiledShader {
    /// Whether this code, compiled with light shaders in its light loops, runs a context with
    /// `records` ([`InlineLight`]).
    pub(crate) fn runs_records(&self, records: &[anysl_core::LightRecord]) -> bool {
        self._owned.runs_records(records)
    }

    /// The operations counted since compilation or the last reset; `None` unless compiled
    /// with [`JitOptions::count_ops`].
    #[must_use]
    pub fn op_counts(&self) -> Option<OpCounts> {
        self._owned.op_counts()
    }

    /// Sets the operation counts to zero.
    pub fn reset_op_counts(&self) {
        self._owned.reset_op_counts();
    }
}

impl fmt::Debug for CompiledShader {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("CompiledShader").field("variant", &self.variant).field("stats", &self.stats).finish()
    }
}

fn init_llvm() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        LlvmTarget::initialize_native(&InitializationConfig::default()).expect("native target");
    });
}

fn count_insts(m: &inkwell::module::Module<'_>) -> usize {
    let mut n = 0;
    let mut f = m.get_first_function();
    while let Some(func) = f {
        for bb in func.get_basic_blocks() {
            let mut i = bb.get_first_instruction();
            while let Some(inst) = i {
                n += 1;
                i = inst.get_next_instruction();
            }
        }
        f = func.get_next_function();
    }
    n
}

/// Runs the IR passes on a lowered module for one instance: specialization of uniform
/// parameters to `values` (when `specialize`), folding, DCE and the analyses.
#[must_use]
pub fn ir_passes(module: &Module, values: &[Const], specialize: bool) -> anysl_rsl::passes::Analyzed {
    let m = module.clone();
    let spec: Vec<(String, Const)> = if specialize {
        m.params.iter().zip(values).map(|(p, v)| (p.name.clone(), v.clone())).collect()
    } else {
        Vec::new()
    };
    let opts =
        anysl_rsl::passes::PassOptions { specialize: spec, specialize_defaults: specialize, ..Default::default() };
    anysl_rsl::passes::optimize(m, &opts)
}

/// The LLVM pass pipeline of optimization level `level` (0–3). Every target-library function
/// is `alwaysinline`, so the inliner runs first and the rest optimizes the one shade function
/// (and its `illuminance` bodies). Levels 1 and 2 run the passes threaded code needs — SROA
/// for the slots, CSE, instcombine, CFG simplification, SCCP, jump threading, GVN (the kept
/// light sums fold there), LICM for the light loops, DSE, ADCE — rather than LLVM's
/// `default<O2>`, which gave the same code for the Table-1 shaders in twice the optimization
/// time; level 3 is `default<O3>`.
#[must_use]
pub fn pass_pipeline(level: u32) -> &'static str {
    match level {
        0 => "default<O0>",
        1 => "always-inline,function(sroa,early-cse<memssa>,instcombine,simplifycfg,adce)",
        2 => concat!(
            "always-inline,function(sroa,early-cse<memssa>,instcombine,simplifycfg,sccp,jump-threading,",
            "correlated-propagation,gvn,instcombine,simplifycfg,loop-mssa(licm),dse,adce,simplifycfg)"
        ),
        _ => "always-inline,default<O3>",
    }
}

/// Compiles a lowered (not yet optimized) module for `variant` with the instance's parameter
/// `values`.
///
/// # Errors
/// When the shader uses something the JIT does not support or LLVM
/// fails.
pub fn compile(
    module: &Module,
    values: &[Const],
    variant: Variant,
    opts: &JitOptions,
) -> Result<CompiledShader, JitError> {
    compile_with(module, values, variant, opts, false)
}

/// [`compile`], optionally keeping the optimized LLVM IR text.
///
/// # Errors
/// See [`compile`].
pub fn compile_with(
    module: &Module,
    values: &[Const],
    variant: Variant,
    opts: &JitOptions,
    keep_ir: bool,
) -> Result<CompiledShader, JitError> {
    compile_inlining(module, values, variant, opts, keep_ir, &[])
}

/// [`compile_with`] with the light shaders `inline` compiled into the light loops over light
/// records ([`JitOptions::light_records`]).
pub(crate) fn compile_inlining(
    module: &Module,
    values: &[Const],
    variant: Variant,
    opts: &JitOptions,
    keep_ir: bool,
    inline: &[InlineLight],
) -> Result<CompiledShader, JitError> {
    let (addr, light, stats, llvm_ir, owned) = build(module, values, variant, opts, keep_ir, None, inline)?;
    // SAFETY: the function was generated with the `ShadeFn` signature.
    let f: ShadeFn = unsafe { std::mem::transmute::<usize, ShadeFn>(addr) };
    Ok(CompiledShader { f, light, variant, stats, llvm_ir, source: None, _owned: owned })
}

/// What a points entry ([`abi::PointsFn`]) reads and writes: the global components read
/// from the caller's arrays (bit `k` for component `k`, numbered as in
/// [`abi::GLOBAL_ORDER`]) and the number of output components written (3: `Ci`; 6: `Ci`
/// and `Oi`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PointsLayout {
    /// The varying global components.
    pub varying: u64,
    /// Output components written (1 to 6).
    pub outputs: usize,
    /// The light loops read light records ([`JitOptions::light_records`]).
    pub light_records: bool,
}

/// A shader compiled as a loop over the packets of a point set ([`abi::PointsFn`]).
pub struct CompiledPoints {
    /// The entry point.
    pub f: PointsFn,
    /// The variant (packet type).
    pub variant: Variant,
    /// What the entry reads and writes.
    pub layout: PointsLayout,
    /// Stage times and instruction counts.
    pub stats: CompileStats,
    /// The optimized LLVM IR, when requested.
    pub llvm_ir: Option<String>,
    _owned: Owned,
}

impl CompiledPoints {
    /// [`CompiledShader::runs_records`].
    pub(crate) fn runs_records(&self, records: &[anysl_core::LightRecord]) -> bool {
        self._owned.runs_records(records)
    }

    /// Whether light shaders are compiled into this code ([`InlineLight`]).
    pub(crate) fn inlines_lights(&self) -> bool {
        !self._owned.inlined.is_empty()
    }

    /// The operations counted since compilation or the last reset; `None` unless compiled
    /// with [`JitOptions::count_ops`].
    #[must_use]
    pub fn op_counts(&self) -> Option<OpCounts> {
        self._owned.op_counts()
    }

    /// Sets the operation counts to zero.
    pub fn reset_op_counts(&self) {
        self._owned.reset_op_counts();
    }
}

impl fmt::Debug for CompiledPoints {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("CompiledPoints")
            .field("variant", &self.variant)
            .field("layout", &self.layout)
            .field("stats", &self.stats)
            .finish()
    }
}

/// Compiles a lowered module as a points entry ([`abi::PointsFn`]) for `variant`.
///
/// # Errors
/// As [`compile`]; dual-number variants have no points entry; `layout` names components
/// past [`abi::GLOBAL_VALUES`] or more than six outputs.
pub fn compile_points(
    module: &Module,
    values: &[Const],
    variant: Variant,
    opts: &JitOptions,
    layout: PointsLayout,
    keep_ir: bool,
) -> Result<CompiledPoints, JitError> {
    compile_points_inlining(module, values, variant, opts, layout, keep_ir, &[])
}

/// [`compile_points`] with the light shaders `inline` compiled into the light loops over light
/// records.
pub(crate) fn compile_points_inlining(
    module: &Module,
    values: &[Const],
    variant: Variant,
    opts: &JitOptions,
    layout: PointsLayout,
    keep_ir: bool,
    inline: &[InlineLight],
) -> Result<CompiledPoints, JitError> {
    if layout.varying >> abi::GLOBAL_VALUES != 0 || !(1..=6).contains(&layout.outputs) {
        return Err(JitError(format!(
            "points layout {layout:?}: components 0..{} and 1..=6 outputs",
            abi::GLOBAL_VALUES
        )));
    }
    if module.kind != anysl_rsl::ir::ShaderKind::Surface {
        return Err(JitError(format!("the points entry shades surface shaders, not {:?}", module.kind)));
    }
    let opts = JitOptions { opt_level: opts.points_opt_level, light_records: layout.light_records, ..opts.clone() };
    let (addr, _, stats, llvm_ir, owned) = build(module, values, variant, &opts, keep_ir, Some(layout), inline)?;
    // SAFETY: the function was generated with the `PointsFn` signature.
    let f: PointsFn = unsafe { std::mem::transmute::<usize, PointsFn>(addr) };
    Ok(CompiledPoints { f, variant, layout, stats, llvm_ir, _owned: owned })
}

/// Compiles `module` to machine code: the shade function, or with `points` the points entry
/// around it. Returns the entry's address.
fn build(
    module: &Module,
    values: &[Const],
    variant: Variant,
    opts: &JitOptions,
    keep_ir: bool,
    points: Option<PointsLayout>,
    inline: &[InlineLight],
) -> Result<(usize, Option<usize>, CompileStats, Option<String>, Owned), JitError> {
    init_llvm();
    let mut stats = CompileStats::default();
    let t0 = Instant::now();
    let analyzed = ir_passes(module, values, opts.specialize);
    let m = analyzed.module();
    for (s, n) in &analyzed.report().stages {
        stats.insts.push((format!("ir-{s}"), *n));
    }
    stats.times_ms.push(("ir-passes", t0.elapsed().as_secs_f64() * 1e3));

    let t1 = Instant::now();
    let ctx = Box::new(Context::create());
    // SAFETY: the context lives in `Owned` next to everything built from it and is dropped last.
    let cref: &'static Context = unsafe { &*(ctx.as_ref() as *const Context) };
    let mut cg = Cg::new(cref, &m.func, target(variant, opts), variant);
    let (cpu, features) = if opts.host_cpu {
        (TargetMachine::get_host_cpu_name().to_string(), TargetMachine::get_host_cpu_features().to_string())
    } else {
        ("x86-64".to_string(), String::new())
    };
    cg.layout = variant.globals_layout();
    cg.fn_attrs = vec![("target-cpu".into(), cpu.clone()), ("target-features".into(), features.clone())];
    if variant.native_lanes() < variant.lanes() {
        // Several packets per call: keep the instructions at one packet's width (wider
        // vectors are split into independent packets, not into wider registers).
        let bits = (32 * variant.native_lanes()).to_string();
        cg.fn_attrs.push(("prefer-vector-width".into(), bits.clone()));
        cg.fn_attrs.push(("min-legal-vector-width".into(), bits));
    }
    // The light shaders that may be compiled into the light loops: declared here (the light
    // loops call them by name), each compiled in a module of its own (in this context) and
    // linked in once the surface's code is generated and calls it.
    let mut candidates = Vec::new();
    if opts.light_records && !variant.dual() {
        for l in inline.iter().filter(|l| l.light.variant == variant && l.light.source.is_some()) {
            let f = cg.m.add_function(&codegen::inline_light_name(candidates.len()), cg.light_entry_type(), None);
            cg.inline_lights.push((l.entry as u64, f));
            candidates.push(l);
            if candidates.len() == MAX_INLINE_LIGHTS {
                break;
            }
        }
    }
    let shade = cg.generate(&analyzed, values).map_err(|e| JitError(e.0))?;
    let entry = match points {
        Some(p) => {
            cg.generate_points(shade, p.varying, p.outputs)?;
            codegen::POINTS_NAME
        }
        None => Cg::shade_name(),
    };
    // A light's direct entry, when its code needs no host callback but named spaces (which
    // the entry's callback table answers from the light's own spaces).
    let spaces_only = cg.host_used.get() & !(1 << rt::Host::Space as u64) == 0;
    let light = (m.kind == anysl_rsl::ir::ShaderKind::Light && points.is_none() && !variant.dual() && spaces_only)
        .then(|| cg.generate_light_entry(shade));
    stats.threaded_fns = cg.threaded_fns;
    let llmod = std::mem::replace(&mut cg.m, cref.create_module("empty"));
    let pinned: Vec<InlineLight> = candidates.iter().map(|&l| l.clone()).collect();
    if !cg.inline_lights_called.get() {
        // No light loop over records: the code runs any records alike.
        for &(_, f) in &cg.inline_lights {
            // SAFETY: a declaration nothing refers to.
            unsafe { f.delete() };
        }
        candidates.clear();
    }
    for (k, (l, &(_, f))) in candidates.iter().zip(&cg.inline_lights).enumerate() {
        match inline_light_module(cref, variant, l.light.source.as_ref().expect("filtered"), &cg, k) {
            Ok(lm) => {
                llmod
                    .link_in_module(lm)
                    .map_err(|e| JitError(format!("linking a light shader in: {}", e.to_string())))?;
                stats.inline_lights += 1;
            }
            // A light that does not compile so again is called at its entry.
            Err(_) => cg.define_as_call(f, l.entry as u64),
        }
        // Linking replaced the declaration `f` with the light's definition.
        let name = codegen::inline_light_name(k);
        let f = llmod.get_function(&name).ok_or_else(|| JitError(format!("{name} not linked in")))?;
        f.set_linkage(inkwell::module::Linkage::Internal);
        codegen::always_inline(cref, f);
    }
    drop(cg);
    if let Err(e) = llmod.verify() {
        return Err(JitError(format!("invalid LLVM IR: {}", e.to_string())));
    }
    stats.insts.push(("llvm-generated".into(), count_insts(&llmod)));
    stats.times_ms.push(("llvm-irgen", t1.elapsed().as_secs_f64() * 1e3));

    let t2 = Instant::now();
    let level = match opts.opt_level {
        0 => OptimizationLevel::None,
        1 => OptimizationLevel::Less,
        2 => OptimizationLevel::Default,
        _ => OptimizationLevel::Aggressive,
    };
    let triple = TargetMachine::get_default_triple();
    let tgt = LlvmTarget::from_triple(&triple).map_err(|e| JitError(e.to_string()))?;
    let tm = tgt
        .create_target_machine(&triple, &cpu, &features, level, RelocMode::Default, CodeModel::JITDefault)
        .ok_or_else(|| JitError("no target machine".into()))?;
    let pipeline = pass_pipeline(opts.opt_level);
    llmod.run_passes(pipeline, &tm, PassBuilderOptions::create()).map_err(|e| JitError(e.to_string()))?;
    stats.insts.push(("llvm-optimized".into(), count_insts(&llmod)));
    stats.times_ms.push(("optimize", t2.elapsed().as_secs_f64() * 1e3));
    let counters = opts.count_ops.then(|| {
        // After optimization, so the counts are the optimized code's; one vector operation
        // per native register's lanes (16 for the one-lane variants, whose vectors are
        // narrower than a register).
        let c = Box::new(opcount::OpCounters::default());
        let unit = if variant.native_lanes() == 1 { 16 } else { variant.native_lanes() };
        opcount::instrument(cref, &llmod, &c, unit);
        c
    });
    if counters.is_some() {
        if let Err(e) = llmod.verify() {
            return Err(JitError(format!("invalid LLVM IR after counting: {}", e.to_string())));
        }
    }
    let llvm_ir = keep_ir.then(|| llmod.print_to_string().to_string());

    let t3 = Instant::now();
    let ee = llmod.create_jit_execution_engine(level).map_err(|e| JitError(e.to_string()))?;
    let addr = ee.get_function_address(entry).map_err(|e| JitError(e.to_string()))?;
    let light = match light {
        Some(_) => Some(ee.get_function_address(codegen::LIGHT_NAME).map_err(|e| JitError(e.to_string()))?),
        None => None,
    };
    stats.times_ms.push(("codegen", t3.elapsed().as_secs_f64() * 1e3));
    Ok((
        addr,
        light,
        stats,
        llvm_ir,
        Owned { ee: Some(ee), module: Some(llmod), ctx: Some(ctx), counters, inlined: pinned },
    ))
}

/// What code generation compiles for `variant` with `opts`.
fn target(variant: Variant, opts: &JitOptions) -> Target {
    Target {
        lanes: variant.lanes(),
        native: variant.native_lanes(),
        dual: variant.dual(),
        threaded: opts.threaded,
        inline_noise: opts.inline_noise.unwrap_or(variant.inline_noise()),
        runtime_params: !opts.specialize,
        output_params: opts.output_params,
        light_records: opts.light_records,
    }
}

/// The LLVM module of light `src` compiled for `variant` as the `k`-th light compiled into the
/// surface that `surface` generates: its direct entry named [`codegen::inline_light_name`]
/// (external until linked in), its other functions internal.
fn inline_light_module(
    cx: &'static Context,
    variant: Variant,
    src: &LightIr,
    surface: &Cg<'static, '_>,
    k: usize,
) -> Result<inkwell::module::Module<'static>, JitError> {
    let analyzed = ir_passes(&src.module, &src.values, src.opts.specialize);
    let m = analyzed.module();
    let target = Target { output_params: false, light_records: false, ..target(variant, &src.opts) };
    let mut cg = Cg::new(cx, &m.func, target, variant);
    cg.layout = surface.layout;
    cg.fn_attrs = surface.fn_attrs.clone();
    let shade = cg.generate(&analyzed, &src.values).map_err(|e| JitError(e.0))?;
    if cg.host_used.get() & !(1 << rt::Host::Space as u64) != 0 {
        return Err(JitError("the light calls the host".into()));
    }
    let entry = cg.generate_light_entry(shade);
    shade.as_global_value().set_name(&format!("{}.shade", codegen::inline_light_name(k)));
    shade.set_linkage(inkwell::module::Linkage::Internal);
    entry.as_global_value().set_name(&codegen::inline_light_name(k));
    Ok(std::mem::replace(&mut cg.m, cx.create_module("empty")))
}
