//! [`JitShader`]: a JIT-compiled `.sl` surface, displacement or light shader behind the same
//! [`SurfaceShader`] / [`DisplacementShader`] / [`LightShader`] boundary as every other shader.

use crate::abi::JitFloat;
use crate::abi::{GLOBAL_ORDER, GLOBAL_VALUES};
use crate::rt::{cast, HostCtx, HostTable};
use crate::{
    compile, compile_inlining, compile_points_inlining, CompiledPoints, CompiledShader, InlineLight, JitError,
    JitOptions, LightIr, OpCounts, PointsLayout, Variant,
};
use anysl_ad::Dual;
use anysl_core::points::{PointSet, ShadeOut};
use anysl_core::prelude::*;
use anysl_core::shader::{ParamError, ParamValue, ShaderMeta};
use anysl_core::{
    Emission, ImagerPixel, ImagerShader, LightCode, LightOutput, LightRecord, LightShader, LightSource, PointContext,
    Spaces, VolumeShader,
};
use anysl_rsl::back::interp::{InterpShader, LightCtx, Program};
use anysl_rsl::ir::{Const, Global, Module};
use anysl_rsl::CompileOptions;
use anysl_simd::{F32x16, F32x4, F32x8, Pair};
use std::any::TypeId;
use std::path::Path;
use std::sync::{Arc, Mutex, OnceLock};

/// One shading point's results as [`JitShader::eval_point`] reads them back (lane 0).
#[derive(Clone, Debug, PartialEq)]
pub struct PointOutputs {
    /// `Ci`.
    pub ci: [f64; 3],
    /// `Oi`.
    pub oi: [f64; 3],
    /// The numeric output parameters in declaration order: name and components.
    pub params: Vec<(String, Vec<f64>)>,
}

/// The JIT variant that shades with float type `F`, if any.
#[must_use]
pub fn variant_of<F: 'static>() -> Option<Variant> {
    let t = TypeId::of::<F>();
    [
        (TypeId::of::<f32>(), Variant::F32),
        (TypeId::of::<F32x4>(), Variant::X4),
        (TypeId::of::<F32x8>(), Variant::X8),
        (TypeId::of::<F32x16>(), Variant::X16),
        (TypeId::of::<Dual<f32>>(), Variant::DualF32),
        (TypeId::of::<Dual<F32x8>>(), Variant::DualX8),
        (TypeId::of::<Pair<Pair<F32x8>>>(), Variant::X8x4),
        (TypeId::of::<Pair<F32x16>>(), Variant::X16x2),
    ]
    .into_iter()
    .find(|(id, _)| *id == t)
    .map(|(_, v)| v)
}

type Slot = OnceLock<Result<Arc<CompiledShader>, String>>;

/// The points entries compiled so far: (variant, layout) → machine code or the error.
type PointsCache = Mutex<Vec<(Variant, PointsLayout, Result<Arc<CompiledPoints>, String>)>>;

/// A surface, displacement or light shader compiled at run time. Each float type's variant
/// is compiled on first use and cached; float types the JIT has no variant for (f64,
/// intervals) run on the interpreter.
pub struct JitShader {
    /// The lowered IR (before the instance-specific passes).
    pub module: Arc<Module>,
    /// This instance's parameter values.
    pub values: Vec<Const>,
    /// Compiler settings.
    pub opts: JitOptions,
    variants: [Slot; Variant::ALL.len()],
    /// The variants compiled for contexts with light records ([`JitOptions::light_records`]).
    record_variants: [Slot; Variant::ALL.len()],
    /// The same with the light shaders of the first such context compiled in
    /// ([`JitShader::inline_variant`]).
    inline_variants: [Slot; Variant::ALL.len()],
    /// Variants that also write the output parameters ([`JitShader::eval_point`]).
    eval_variants: [Slot; Variant::ALL.len()],
    points: PointsCache,
    interp: InterpShader,
    /// `values` as the run-time parameter block that code compiled without specialization
    /// reads ([`crate::codegen::param_block`]).
    param_block: Vec<f32>,
}

impl Clone for JitShader {
    fn clone(&self) -> Self {
        Self {
            module: self.module.clone(),
            values: self.values.clone(),
            opts: self.opts.clone(),
            variants: Default::default(),
            record_variants: Default::default(),
            inline_variants: Default::default(),
            eval_variants: Default::default(),
            points: PointsCache::default(),
            interp: self.interp.clone(),
            param_block: self.param_block.clone(),
        }
    }
}

impl std::fmt::Debug for JitShader {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("JitShader").field("name", &self.module.name).finish_non_exhaustive()
    }
}

impl JitShader {
    /// A shader from a lowered module, with its default parameter values.
    ///
    /// # Errors
    /// When the interpreter (the fallback for other float types) cannot run the module.
    pub fn new(module: Module, opts: JitOptions) -> Result<Self, JitError> {
        let values: Vec<Const> = module.params.iter().map(|p| p.default.clone()).collect();
        let interp_module = anysl_rsl::passes::optimize(module.clone(), &anysl_rsl::passes::PassOptions::default());
        let program = Program::new(interp_module).map_err(|e| JitError(e.to_string()))?;
        let param_block = crate::codegen::param_block(&module, &values).0;
        Ok(Self {
            param_block,
            module: Arc::new(module),
            values,
            opts,
            variants: Default::default(),
            record_variants: Default::default(),
            inline_variants: Default::default(),
            eval_variants: Default::default(),
            points: PointsCache::default(),
            interp: InterpShader::new(Arc::new(program)),
        })
    }

    /// Compiles the `.sl` file at `path` (parse and check only; machine code comes lazily).
    ///
    /// # Errors
    /// Compile errors, rendered.
    pub fn from_file(path: &Path, include_dirs: &[std::path::PathBuf], opts: JitOptions) -> Result<Self, JitError> {
        let copts = CompileOptions { include_dirs: include_dirs.to_vec(), ..Default::default() };
        let c = anysl_rsl::compile_file(path, &copts).map_err(|e| JitError(e.to_string()))?;
        Self::new(c.module, opts)
    }

    /// [`JitShader::from_file`] for `.sl` source text; `name` stands for the file in
    /// diagnostics.
    ///
    /// # Errors
    /// Compile errors, rendered.
    pub fn from_source(
        name: &str,
        text: &str,
        include_dirs: &[std::path::PathBuf],
        opts: JitOptions,
    ) -> Result<Self, JitError> {
        let copts = CompileOptions { include_dirs: include_dirs.to_vec(), ..Default::default() };
        let c = anysl_rsl::compile_source(name, text, &copts).map_err(|e| JitError(e.to_string()))?;
        Self::new(c.module, opts)
    }

    /// The compiled variant (compiling it now if needed).
    ///
    /// # Errors
    /// When the shader cannot be compiled for this variant.
    pub fn variant(&self, v: Variant) -> Result<Arc<CompiledShader>, String> {
        self.variant_ref(v).map(Arc::clone).map_err(Clone::clone)
    }

    /// [`JitShader::variant`] without touching the reference count (the per-call path).
    #[inline]
    fn variant_ref(&self, v: Variant) -> Result<&Arc<CompiledShader>, &String> {
        self.variants[v.index()]
            .get_or_init(|| {
                let mut cs = compile(&self.module, &self.values, v, &self.opts).map_err(|e| e.to_string())?;
                if cs.light.is_some() {
                    // A light with a direct entry: surfaces may compile it into their loops.
                    let ir =
                        LightIr { module: self.module.clone(), values: self.values.clone(), opts: self.opts.clone() };
                    cs.source = Some(ir);
                }
                Ok(Arc::new(cs))
            })
            .as_ref()
    }

    /// The variant `v` compiled for contexts with light records ([`JitOptions::light_records`];
    /// compiling it now if needed). Its light loops call the lights' entries.
    fn record_variant(&self, v: Variant) -> Result<&Arc<CompiledShader>, &String> {
        self.record_variants[v.index()]
            .get_or_init(|| {
                let opts = JitOptions { light_records: true, ..self.opts.clone() };
                compile(&self.module, &self.values, v, &opts).map(Arc::new).map_err(|e| e.to_string())
            })
            .as_ref()
    }

    /// [`JitShader::record_variant`] with the light shaders of the first context with records
    /// compiled into its light loops ([`inline_lights`]; compiled when that context first runs
    /// the shader, if they all can be), when it runs `records`: when every record with code is
    /// one of those lights. Scenes keep their lights, so that is every later context of the
    /// render; another light set runs [`JitShader::record_variant`].
    fn inline_variant(&self, v: Variant, records: &[LightRecord]) -> Option<&Arc<CompiledShader>> {
        let cs = self.inline_variants[v.index()]
            .get_or_init(|| {
                let lights = inline_lights(records, v).ok_or("lights that cannot be compiled in")?;
                let opts = JitOptions { light_records: true, ..self.opts.clone() };
                compile_inlining(&self.module, &self.values, v, &opts, false, &lights)
                    .map(Arc::new)
                    .map_err(|e| e.to_string())
            })
            .as_ref()
            .ok()?;
        cs.runs_records(records).then_some(cs)
    }

    /// The variant run for a context with light records: [`JitShader::inline_variant`], else
    /// [`JitShader::record_variant`].
    fn records_variant_for(&self, v: Variant, records: &[LightRecord]) -> Option<&Arc<CompiledShader>> {
        self.inline_variant(v, records).or_else(|| self.record_variant(v).ok())
    }

    /// Shades one point with compiled code (the variant of `F`; `f32` and `Dual<f32>`, one
    /// lane) and reads back `Ci`, `Oi` and every numeric output parameter: the JIT's answer
    /// to `rslc eval`, compiled with [`JitOptions::output_params`] (and cached apart from
    /// the variants [`SurfaceShader::shade`] runs).
    ///
    /// # Errors
    /// When `F` is not a one-lane type the JIT compiles, or the shader cannot be compiled
    /// (never a silent fallback to the interpreter).
    pub fn eval_point<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C) -> Result<PointOutputs, String> {
        let v = match variant_of::<F>() {
            Some(v @ (Variant::F32 | Variant::DualF32)) => v,
            _ => return Err(format!("eval_point runs f32 or Dual<f32>, not {}", core::any::type_name::<F>())),
        };
        let cs = self.eval_variants[v.index()]
            .get_or_init(|| {
                let opts = JitOptions { output_params: true, ..self.opts.clone() };
                compile(&self.module, &self.values, v, &opts).map(Arc::new).map_err(|e| e.to_string())
            })
            .as_ref()
            .map_err(Clone::clone)?;
        if v == Variant::F32 {
            if const { may_be::<F, f32>() } {
                return Ok(self.run_eval::<F, C, f32>(cs, ctx));
            }
        } else if const { may_be::<F, Dual<f32>>() } {
            return Ok(self.run_eval::<F, C, Dual<f32>>(cs, ctx));
        }
        unreachable!("variant_of::<{}>() named {v:?}, a type of other lanes or size", core::any::type_name::<F>())
    }

    fn run_eval<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
        &self,
        cs: &CompiledShader,
        ctx: &mut C,
    ) -> PointOutputs {
        let layout = crate::abi::output_params(&self.module);
        let values = layout.last().map_or(crate::abi::OUTPUT_VALUES, |&(_, at, n)| at + n);
        let mut out = vec![0f32; values * G::STRIDE];
        let mut mbuf = [0u32; crate::abi::MAX_LANES];
        let gbuf = (ctx.globals() as *const Globals<F>).cast::<f32>();
        unsafe { G::write_mask(G::Mask::splat(true), mbuf.as_mut_ptr()) };
        let host = HostTable::<F, C, G>::table();
        let mut hc = HostCtx::new(ctx);
        // SAFETY: as in `run`; the output buffer has room for every value the code compiled
        // with `output_params` writes (`abi::output_params`).
        unsafe {
            (cs.f)(
                gbuf,
                out.as_mut_ptr(),
                mbuf.as_ptr(),
                (&mut hc as *mut HostCtx<F, C>).cast(),
                host,
                self.param_block.as_ptr(),
            );
        }
        // SAFETY: `out` holds `values` values of `G`, `STRIDE` floats apart.
        let rd = |k: usize| unsafe { G::read(out.as_ptr().add(k * G::STRIDE)) }.lane(0);
        PointOutputs {
            ci: [rd(0), rd(1), rd(2)],
            oi: [rd(3), rd(4), rd(5)],
            params: layout
                .iter()
                .map(|&(k, at, n)| (self.module.params[k].name.clone(), (at..at + n).map(rd).collect()))
                .collect(),
        }
    }

    /// The points entry of variant `v` for `layout` (compiling it now if needed).
    ///
    /// # Errors
    /// When the shader cannot be compiled so ([`compile_points`]).
    pub fn points_variant(&self, v: Variant, layout: PointsLayout) -> Result<Arc<CompiledPoints>, String> {
        self.points_variant_for(v, layout, &[])
    }

    /// [`JitShader::points_variant`] compiling the light shaders of `records` into the light
    /// loops when it compiles ([`JitShader::record_variant`]).
    fn points_variant_for(
        &self,
        v: Variant,
        layout: PointsLayout,
        records: &[LightRecord],
    ) -> Result<Arc<CompiledPoints>, String> {
        let mut cache = self.points.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        // For records: code with their lights compiled in, else code that calls them (and code
        // with lights compiled in is made once, for the first records that allow it).
        let same = |cv: Variant, cl: PointsLayout| cv == v && cl == layout;
        let pick = |r: &Result<Arc<CompiledPoints>, String>| match r {
            Ok(c) if layout.light_records && c.inlines_lights() => c.runs_records(records),
            _ => true,
        };
        if let Some((_, _, r)) = cache.iter().find(|(cv, cl, r)| same(*cv, *cl) && pick(r)) {
            return r.clone();
        }
        let tried = cache.iter().any(|(cv, cl, r)| same(*cv, *cl) && r.as_ref().is_ok_and(|c| c.inlines_lights()));
        let inline = match layout.light_records && !tried {
            true => inline_lights(records, v).unwrap_or_default(),
            false => Vec::new(),
        };
        let r = compile_points_inlining(&self.module, &self.values, v, &self.opts, layout, false, &inline)
            .map(Arc::new)
            .map_err(|e| e.to_string());
        cache.push((v, layout, r.clone()));
        r
    }

    /// Shades a point set with the compiled loop of [`crate::abi::PointsFn`]: the points
    /// `0 .. n` (`n` the length of each output array, a multiple of `F::LANES`) in packets of
    /// `F::LANES`, every lane active. `varying` gives, for each global that differs from point
    /// to point, one array of `n` values per component (`P`: x, y, z; `s`: one); the other
    /// globals are the context's, the same for every packet (and a varying global the shader
    /// does not read, [`SurfaceShader::globals_read`], is not copied). `out` receives `Ci` (r, g, b) and,
    /// with six arrays, `Oi`. The result is what [`SurfaceShader::shade`] gives packet by
    /// packet with the context's globals set to each packet's values, bit for bit.
    ///
    /// Returns `Ok(false)` without shading when this float type has no points entry (dual
    /// numbers, intervals, `f64`) or the context does not lend its globals
    /// ([`ShadingContext::globals_mut`]): the caller shades packet by packet then.
    ///
    /// # Errors
    /// Arrays of the wrong length or number, a global the compiled code does not read from the
    /// renderer's globals, or a shader the points entry cannot be compiled for.
    pub fn shade_points<F: ShadingFloat, C: ShadingContext<F>>(
        &self,
        ctx: &mut C,
        varying: &[(Global, &[&[f32]])],
        out: &mut [&mut [f32]],
    ) -> Result<bool, JitError> {
        let Some(v) = variant_of::<F>().filter(|v| !v.dual()) else { return Ok(false) };
        if ctx.globals_mut().is_none() {
            return Ok(false);
        }
        let n = out.first().map_or(0, |o| o.len());
        if out.is_empty() || out.len() > 6 || out.iter().any(|o| o.len() != n) || !n.is_multiple_of(F::LANES) {
            let lens: Vec<usize> = out.iter().map(|o| o.len()).collect();
            return Err(JitError(format!(
                "points: 1 to 6 output arrays of one length, a multiple of {} lanes (got {lens:?})",
                F::LANES
            )));
        }
        let mut src = [core::ptr::null::<f32>(); GLOBAL_VALUES];
        let mut mask = 0u64;
        // Only the globals the shader reads are copied per packet (the contract of
        // `globals_read`, which a renderer calling `shade` relies on too).
        let read = self.globals_read();
        for (g, comps) in varying {
            let Some(&(_, first)) = GLOBAL_ORDER.iter().find(|(x, _)| x == g) else {
                return Err(JitError(format!("points: {g:?} is not a global the renderer supplies")));
            };
            let nc = g.ty().base.components();
            if comps.len() != nc || comps.iter().any(|a| a.len() != n) {
                return Err(JitError(format!("points: {g:?} needs {nc} arrays of {n} values")));
            }
            if !read.contains(anysl_rsl::passes::analysis::global_set(*g)) {
                continue;
            }
            for (c, a) in comps.iter().enumerate() {
                src[first + c] = a.as_ptr();
                mask |= 1 << (first + c);
            }
        }
        if n == 0 {
            return Ok(true);
        }
        let records = if ctx.lights_as_data().is_none() { ctx.light_records() } else { None };
        let layout = PointsLayout { varying: mask, outputs: out.len(), light_records: records.is_some() };
        let cp = self.points_variant_for(v, layout, records.unwrap_or(&[])).map_err(JitError)?;
        let mut dst = [core::ptr::null_mut::<f32>(); 6];
        for (d, o) in dst.iter_mut().zip(out.iter_mut()) {
            *d = o.as_mut_ptr();
        }
        let packets = n / F::LANES;
        return_as_variant!(v, F, |G| {
            self.run_points::<F, C, G>(&cp, ctx, &src, &dst, packets);
            Ok(true)
        });
        unreachable!("variant_of::<{}>() named {v:?}, a type of other lanes or size", core::any::type_name::<F>())
    }

    /// [`anysl_core::points::shade_points`] through the points entry ([`JitShader::shade_points`]):
    /// every global the set holds (`P`, `N` = `Ng`, `I`, `s`, `t`, `u`, `v`, `du`, `dv`,
    /// `dPdu`, `dPdv`) read from its arrays, `Ci` and `Oi` written to `out`; as there, the
    /// points past the last whole packet are left alone. `Ok(false)` (nothing shaded) where
    /// [`JitShader::shade_points`] declines.
    ///
    /// # Errors
    /// As [`JitShader::shade_points`]; `out` not as long as the set.
    pub fn shade_point_set<F: ShadingFloat, L: LightSource>(
        &self,
        lights: &[L],
        set: &PointSet,
        out: &mut ShadeOut<f32>,
    ) -> Result<bool, JitError> {
        use anysl_core::points::field;
        if out.channels.iter().any(|c| c.len() != set.len()) {
            return Err(JitError(format!("points: outputs for {} points", set.len())));
        }
        let n = set.len() / F::LANES * F::LANES;
        if n == 0 {
            return Ok(true);
        }
        let f = |k: usize| &set.field(k)[..n];
        let t = |k: usize| [f(k), f(k + 1), f(k + 2)];
        let (p, nn, i, dpdu, dpdv) = (t(field::P), t(field::N), t(field::I), t(field::DPDU), t(field::DPDV));
        let [s, tt, u, v, du, dv] = [field::S, field::T, field::U, field::V, field::DU, field::DV].map(|k| [f(k)]);
        let varying: [(Global, &[&[f32]]); 12] = [
            (Global::P, &p),
            (Global::N, &nn),
            (Global::Ng, &nn),
            (Global::I, &i),
            (Global::S, &s),
            (Global::T, &tt),
            (Global::U, &u),
            (Global::V, &v),
            (Global::Du, &du),
            (Global::Dv, &dv),
            (Global::DPdu, &dpdu),
            (Global::DPdv, &dpdv),
        ];
        let mut ctx = PointContext::new(set.globals::<F>(0), lights);
        let mut outs: Vec<&mut [f32]> = out.channels.iter_mut().map(|c| &mut c[..n]).collect();
        self.shade_points(&mut ctx, &varying, &mut outs)
    }

    fn run_points<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
        &self,
        cp: &CompiledPoints,
        ctx: &mut C,
        src: &[*const f32; GLOBAL_VALUES],
        dst: &[*mut f32; 6],
        packets: usize,
    ) {
        // The compiled loop writes each packet's varying globals into the context's own
        // `Globals` (where the host callbacks that read the context find them) and reads them
        // back there; no Rust code reads through this pointer while it runs.
        let g = ctx.globals_mut().expect("checked by shade_points") as *mut Globals<F>;
        let host = HostTable::<F, C, G>::table();
        let mut hc = HostCtx::new(ctx);
        // SAFETY: the arrays hold `packets · F::LANES` values each (`shade_points`), the
        // globals have the layout the code was compiled for, and `ctx` is a `C`, which is what
        // the host table's shims take.
        unsafe {
            (cp.f)(
                packets as u64,
                src.as_ptr(),
                dst.as_ptr(),
                g.cast::<f32>(),
                (&mut hc as *mut HostCtx<F, C>).cast(),
                host,
                self.param_block.as_ptr(),
            );
        }
    }

    /// The operations executed so far by the code compiled for variant `v` — its
    /// per-packet function ([`SurfaceShader::shade`]), its points entries
    /// ([`JitShader::shade_points`]) and [`JitShader::eval_point`]'s, summed — since
    /// compilation or [`JitShader::reset_op_counts`]; `None` unless compiled with
    /// [`JitOptions::count_ops`]. Shade with one variant between resets to attribute the
    /// counts to one run. See [`crate::opcount`] for what is counted.
    #[must_use]
    pub fn op_counts(&self, v: Variant) -> Option<OpCounts> {
        if !self.opts.count_ops {
            return None;
        }
        let mut n = OpCounts::default();
        let slots = [&self.variants, &self.record_variants, &self.inline_variants, &self.eval_variants];
        for slot in slots.map(|s| &s[v.index()]) {
            if let Some(Ok(c)) = slot.get() {
                n += c.op_counts().unwrap_or_default();
            }
        }
        let cache = self.points.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        for (_, _, c) in cache.iter().filter(|(cv, _, _)| *cv == v) {
            if let Ok(c) = c {
                n += c.op_counts().unwrap_or_default();
            }
        }
        Some(n)
    }

    /// Sets the operation counts of every compiled variant to zero ([`JitShader::op_counts`]).
    pub fn reset_op_counts(&self) {
        let slots = [&self.variants, &self.record_variants, &self.inline_variants, &self.eval_variants];
        for slot in slots.into_iter().flatten() {
            if let Some(Ok(c)) = slot.get() {
                c.reset_op_counts();
            }
        }
        let cache = self.points.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        for (_, _, c) in cache.iter() {
            if let Ok(c) = c {
                c.reset_op_counts();
            }
        }
    }

    /// Variant `v` as compiled for contexts with light records ([`JitOptions::light_records`])
    /// with the light shaders of the first such context compiled in, when such a context has
    /// run it and they could be.
    #[must_use]
    pub fn inline_variant_compiled(&self, v: Variant) -> Option<Arc<CompiledShader>> {
        self.inline_variants[v.index()].get().and_then(|r| r.as_ref().ok()).cloned()
    }

    /// The variants compiled so far.
    #[must_use]
    pub fn compiled(&self) -> Vec<Variant> {
        let done = |slots: &[Slot], v: Variant| matches!(slots[v.index()].get(), Some(Ok(_)));
        let slots = [&self.variants, &self.record_variants, &self.inline_variants];
        Variant::ALL.into_iter().filter(|&v| slots.iter().any(|s| done(&s[..], v))).collect()
    }

    /// The interpreter instance used for other float types.
    #[must_use]
    pub fn interp(&self) -> &InterpShader {
        &self.interp
    }

    #[inline]
    fn run<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
        &self,
        cs: &CompiledShader,
        ctx: &mut C,
        e: &Exec<F>,
    ) -> SurfaceOutput<F> {
        // The compiled code writes every output of a surface shader (`Ci`, `Oi`) straight into
        // the return value, which has the layout of its output buffer.
        assert!(crate::abi::output_layout_is_buffer::<G>(), "SurfaceOutput layout differs from the JIT's");
        let mut out = std::mem::MaybeUninit::<SurfaceOutput<G>>::uninit();
        // SAFETY: a surface shader's code writes `Ci` and `Oi`: six values of `G`, `STRIDE`
        // floats apart (`output_layout_is_buffer`), the size and alignment of `SurfaceOutput<G>`.
        unsafe { self.invoke::<F, C, G>(cs, ctx, e, out.as_mut_ptr().cast()) };
        // Read back component by component with `G::read` (one load per packet, the width
        // of the compiled code's stores), not as a whole: a copy of the whole struct moves it
        // with wider loads than the stores that wrote it, and store forwarding fails on each.
        // SAFETY: the compiled code wrote all six components; F and G are the same type.
        let o = out.as_ptr().cast::<f32>();
        let rd = |k: usize| cast::<G, F>(unsafe { G::read(o.add(k * G::STRIDE)) });
        SurfaceOutput { Ci: Color::new(rd(0), rd(1), rd(2)), Oi: Color::new(rd(3), rd(4), rd(5)) }
    }

    /// A displacement shader's run: its `P` and `N` (the third and fourth outputs).
    fn run_displace<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
        &self,
        cs: &CompiledShader,
        ctx: &mut C,
        e: &Exec<F>,
    ) -> (Vec3<F>, Vec3<F>) {
        assert!(crate::abi::output_layout_is_buffer::<G>(), "SurfaceOutput layout differs from the JIT's");
        // Two `SurfaceOutput<G>` are the twelve values `Ci`, `Oi`, `P`, `N` (abi::OUTPUT_ORDER).
        let mut out = std::mem::MaybeUninit::<[SurfaceOutput<G>; 2]>::uninit();
        // SAFETY: a displacement shader's code writes the four outputs: twelve values of `G`,
        // `STRIDE` floats apart, the size and alignment of two `SurfaceOutput<G>`.
        unsafe { self.invoke::<F, C, G>(cs, ctx, e, out.as_mut_ptr().cast()) };
        let o = out.as_ptr().cast::<f32>();
        // SAFETY: the compiled code wrote all twelve values; F and G are the same type.
        let rd = |k: usize| cast::<G, F>(unsafe { G::read(o.add(k * G::STRIDE)) });
        (Vec3::new(rd(6), rd(7), rd(8)), Vec3::new(rd(9), rd(10), rd(11)))
    }

    /// A volume shader's run: `Ci`, `Oi` go into the output buffer, where the code finds them
    /// on entry and leaves what it makes of them.
    fn run_volume<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
        &self,
        cs: &CompiledShader,
        ctx: &mut C,
        e: &Exec<F>,
        entering: SurfaceOutput<F>,
    ) -> SurfaceOutput<F> {
        assert!(crate::abi::output_layout_is_buffer::<G>(), "SurfaceOutput layout differs from the JIT's");
        let mut out = std::mem::MaybeUninit::<SurfaceOutput<G>>::uninit();
        let o = out.as_mut_ptr().cast::<f32>();
        let (ci, oi) = (entering.Ci, entering.Oi);
        for (k, c) in [ci.r, ci.g, ci.b, oi.r, oi.g, oi.b].into_iter().enumerate() {
            // SAFETY: six values of `G`, `STRIDE` floats apart, fill a `SurfaceOutput<G>`; F is G.
            unsafe { cast::<F, G>(c).write(o.add(k * G::STRIDE)) };
        }
        // SAFETY: a volume shader's code reads and writes `Ci` and `Oi`, the six values above.
        unsafe { self.invoke::<F, C, G>(cs, ctx, e, o) };
        // SAFETY: all six values are written (above, and by the code); F and G are the same type.
        let rd = |k: usize| cast::<G, F>(unsafe { G::read(o.add(k * G::STRIDE)) });
        SurfaceOutput { Ci: Color::new(rd(0), rd(1), rd(2)), Oi: Color::new(rd(3), rd(4), rd(5)) }
    }

    /// An imager shader's run on `px`: its `Ci`, `Oi` and `alpha` go into the output buffer
    /// (`alpha` at [`crate::abi::IMAGER_ALPHA`]), where the code finds them and leaves its own.
    fn run_imager<F: ShadingFloat, G: JitFloat>(
        &self,
        cs: &CompiledShader,
        e: &Exec<F>,
        px: ImagerPixel<F>,
    ) -> ImagerPixel<F> {
        assert!(crate::abi::output_layout_is_buffer::<G>(), "SurfaceOutput layout differs from the JIT's");
        // Two `SurfaceOutput<G>`: room for the seven values.
        let mut out = std::mem::MaybeUninit::<[SurfaceOutput<G>; 2]>::uninit();
        let o = out.as_mut_ptr().cast::<f32>();
        let (ci, oi) = (px.Ci, px.Oi);
        let vals = [ci.r, ci.g, ci.b, oi.r, oi.g, oi.b, px.alpha];
        for (k, c) in vals.into_iter().enumerate() {
            // SAFETY: as in `run_volume`, seven values of the twelve the buffer holds.
            unsafe { cast::<F, G>(c).write(o.add(k * G::STRIDE)) };
        }
        let mut ctx = LightCtx::imager(&px);
        // SAFETY: an imager's code reads and writes the seven values above.
        unsafe { self.invoke::<F, LightCtx<'_, F>, G>(cs, &mut ctx, e, o) };
        // SAFETY: the seven values are written; F and G are the same type.
        let rd = |k: usize| cast::<G, F>(unsafe { G::read(o.add(k * G::STRIDE)) });
        ImagerPixel { P: px.P, Ci: Color::new(rd(0), rd(1), rd(2)), Oi: Color::new(rd(3), rd(4), rd(5)), alpha: rd(6) }
    }

    /// A light shader's run for the points `ps`: its `Cl` and `L` (the first two outputs).
    fn run_light<F: ShadingFloat, G: JitFloat>(
        &self,
        cs: &CompiledShader,
        e: &Exec<F>,
        ps: Vec3<F>,
        spaces: &Spaces,
    ) -> LightOutput<F> {
        assert!(crate::abi::output_layout_is_buffer::<G>(), "SurfaceOutput layout differs from the JIT's");
        let mut out = std::mem::MaybeUninit::<SurfaceOutput<G>>::uninit();
        if let Some(entry) = cs.light {
            // The direct entry (what compiled light loops call): the points and the mask in
            // buffers, the light's spaces as its callbacks' context; no globals, no host context.
            let mut psb = [0f32; 3 * crate::abi::MAX_LANES];
            let mut mbuf = [0u32; crate::abi::MAX_LANES];
            // SAFETY: `psb` holds three values of `G` (`STRIDE` = lanes floats each, at most
            // `MAX_LANES`), `mbuf` a mask of `G`; F and G are the same type.
            unsafe {
                for (k, c) in [ps.x, ps.y, ps.z].into_iter().enumerate() {
                    cast::<F, G>(c).write(psb.as_mut_ptr().add(k * G::STRIDE));
                }
                G::write_mask(cast::<F::Mask, G::Mask>(e.mask()), mbuf.as_mut_ptr());
            }
            // SAFETY: the entry was generated with the `LightFn` signature (`CompiledShader::light`).
            let f = unsafe { std::mem::transmute::<usize, crate::abi::LightFn>(entry) };
            // SAFETY: the buffers have the layout the code expects; a light shader's code
            // writes `Cl` and `L`, six values of `G` (`SurfaceOutput<G>`'s size and alignment);
            // its only callback reads `spaces` as the context.
            unsafe {
                f(
                    psb.as_ptr(),
                    out.as_mut_ptr().cast(),
                    mbuf.as_ptr(),
                    (spaces as *const Spaces).cast_mut().cast(),
                    crate::rt::light_host_table(),
                    self.param_block.as_ptr(),
                );
            }
        } else {
            let mut ctx = LightCtx::at(ps, spaces);
            // SAFETY: a light shader's code writes `Cl` and `L`: six values of `G`, `STRIDE`
            // floats apart, the size and alignment of `SurfaceOutput<G>`.
            unsafe { self.invoke::<F, LightCtx<'_, F>, G>(cs, &mut ctx, e, out.as_mut_ptr().cast()) };
        }
        let o = out.as_ptr().cast::<f32>();
        // SAFETY: the compiled code wrote all six values; F and G are the same type.
        let rd = |k: usize| cast::<G, F>(unsafe { G::read(o.add(k * G::STRIDE)) });
        LightOutput {
            cl: Color::new(rd(0), rd(1), rd(2)),
            l: Vec3::new(rd(3), rd(4), rd(5)),
            lit: e.mask(),
            emission: self.interp.emission().unwrap_or(Emission::Local),
        }
    }

    /// Calls the compiled code of `cs` on the packet of `ctx` under `e`'s mask.
    ///
    /// # Safety
    /// `out` has room for every output value `cs` writes, aligned for `G`; `F` is `G`.
    #[inline]
    unsafe fn invoke<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
        &self,
        cs: &CompiledShader,
        ctx: &mut C,
        e: &Exec<F>,
        out: *mut f32,
    ) {
        let mut mbuf = [0u32; crate::abi::MAX_LANES];
        // The compiled code reads the globals in place, at the offsets of `Globals<F>`'s
        // layout (`abi::GlobalsLayout`), while the host callbacks hold the context mutably:
        // they never write the globals (a `ShadingContext` hands them out only by shared
        // reference), and no Rust code reads through this pointer after they ran.
        let gbuf = (ctx.globals() as *const Globals<F>).cast::<f32>();
        unsafe { G::write_mask(cast::<F::Mask, G::Mask>(e.mask()), mbuf.as_mut_ptr()) };
        let host = HostTable::<F, C, G>::table();
        let mut hc = HostCtx::new(ctx);
        // A context with light records runs the flavour compiled for them (where it does not
        // compile, the plain one, whose loops call the context's; the variants with
        // derivatives have one flavour).
        let f = if hc.records.is_null() || cs.variant.dual() {
            cs.f
        } else {
            // SAFETY: `HostCtx::new` took the records from the context, which outlives `hc`.
            let records = unsafe { core::slice::from_raw_parts(hc.records, hc.n_records) };
            self.records_variant_for(cs.variant, records).map_or(cs.f, |r| r.f)
        };
        // SAFETY: the buffers have the layout the compiled code expects (the caller's
        // promise for `out`); `ctx` is a `C`, which is what the host table's shims take.
        unsafe {
            f(gbuf, out, mbuf.as_ptr(), (&mut hc as *mut HostCtx<F, C>).cast(), host, self.param_block.as_ptr());
        }
    }
}

impl Shader for JitShader {
    fn meta(&self) -> ShaderMeta {
        self.interp.meta()
    }
    fn param(&self, name: &str) -> Option<ParamValue> {
        self.interp.param(name)
    }
    fn set_param(&mut self, name: &str, value: &ParamValue) -> Result<(), ParamError> {
        self.interp.set_param(name, value)?;
        self.values = self.interp.values.clone();
        self.param_block = crate::codegen::param_block(&self.module, &self.values).0;
        if self.opts.specialize {
            // Parameters are compiled in: recompile on next use.
            self.variants = Default::default();
            self.record_variants = Default::default();
            self.inline_variants = Default::default();
            self.eval_variants = Default::default();
            self.points = PointsCache::default();
        }
        Ok(())
    }
}

/// Returns `$body` evaluated with `$G` the [`JitFloat`] of variant `$v`, for the variant whose
/// type may be `$F` ([`may_be`]); falls through otherwise. Each arm is behind an `if const`,
/// so only the matching variant's code (its `run` and host table) is instantiated for `$F`:
/// eight variants would otherwise cost every float type and context eight copies.
macro_rules! return_as_variant {
    ($v:expr, $F:ty, |$G:ident| $body:expr) => {
        match $v {
            Variant::F32 => return_as_variant!(@arm $F, f32, $G, $body),
            Variant::X4 => return_as_variant!(@arm $F, F32x4, $G, $body),
            Variant::X8 => return_as_variant!(@arm $F, F32x8, $G, $body),
            Variant::X16 => return_as_variant!(@arm $F, F32x16, $G, $body),
            Variant::DualF32 => return_as_variant!(@arm $F, Dual<f32>, $G, $body),
            Variant::DualX8 => return_as_variant!(@arm $F, Dual<F32x8>, $G, $body),
            Variant::X8x4 => return_as_variant!(@arm $F, Pair<Pair<F32x8>>, $G, $body),
            Variant::X16x2 => return_as_variant!(@arm $F, Pair<F32x16>, $G, $body),
        }
    };
    (@arm $F:ty, $T:ty, $G:ident, $body:expr) => {{
        type $G = $T;
        if const { may_be::<$F, $G>() } {
            return $body;
        }
    }};
}
use return_as_variant;

/// Returns `$body` with `$cs` the compiled code of the variant for `$F` and `$G` its
/// [`JitFloat`], when there is such a variant and it compiles; falls through otherwise (to
/// the interpreter, in every caller).
macro_rules! return_compiled {
    ($self:ident, $F:ty, |$cs:ident, $G:ident| $body:expr) => {
        if let Some(v) = variant_of::<$F>() {
            if let Ok($cs) = $self.variant_ref(v) {
                return_as_variant!(v, $F, |$G| $body);
                unreachable!(
                    "variant_of::<{}>() named {v:?}, a type of other lanes or size",
                    core::any::type_name::<$F>()
                );
            }
        }
    };
}

/// Whether `F` may be `G` (`variant_of` decides which it is): the same lanes and size.
const fn may_be<F: ShadingFloat, G: JitFloat>() -> bool {
    F::LANES == G::LANES && core::mem::size_of::<F>() == core::mem::size_of::<G>()
}

impl SurfaceShader for JitShader {
    /// As the interpreter's: the same module (the compiled code loads every global slot at
    /// entry and hands `P` to the light loops, like the interpreter).
    fn globals_read(&self) -> anysl_core::GlobalSet {
        self.interp.globals_read()
    }

    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        return_compiled!(self, F, |cs, G| self.run::<F, C, G>(cs, ctx, e));
        self.interp.shade(ctx, e)
    }
}

impl DisplacementShader for JitShader {
    /// The compiled displacement (`P`, `N` as it leaves them) for the variant of `F`; the
    /// interpreter for other float types.
    fn displace<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> (Vec3<F>, Vec3<F>) {
        return_compiled!(self, F, |cs, G| self.run_displace::<F, C, G>(cs, ctx, e));
        self.interp.displace(ctx, e)
    }
}

impl VolumeShader for JitShader {
    /// The compiled volume for the variant of `F` (`Ci`, `Oi` start as they arrive, as in the
    /// interpreter); the interpreter for other float types.
    fn volume<F: ShadingFloat, C: ShadingContext<F>>(
        &self,
        ctx: &mut C,
        e: &mut Exec<F>,
        entering: SurfaceOutput<F>,
    ) -> SurfaceOutput<F> {
        return_compiled!(self, F, |cs, G| self.run_volume::<F, C, G>(cs, ctx, e, entering));
        self.interp.volume(ctx, e, entering)
    }
}

impl ImagerShader for JitShader {
    /// The compiled imager for the variant of `F` (`Ci`, `Oi`, `alpha` start as the pixel's;
    /// `P` its raster position, `Cs`, `Os` its `Ci`, `Oi`, as in the interpreter); the
    /// interpreter for other float types.
    fn image<F: ShadingFloat>(&self, e: &mut Exec<F>, pixel: ImagerPixel<F>) -> ImagerPixel<F> {
        return_compiled!(self, F, |cs, G| self.run_imager::<F, G>(cs, e, pixel));
        self.interp.image(e, pixel)
    }
}

impl LightShader for JitShader {
    fn light<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        self.light_in(e, ps, Spaces::standard())
    }

    /// The compiled light for the variant of `F` (`Cl` stays zero outside every `illuminate`
    /// cone, as in the interpreter); the interpreter for other float types.
    fn light_in<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>, spaces: &Spaces) -> LightOutput<F> {
        return_compiled!(self, F, |cs, G| self.run_light::<F, G>(cs, e, ps, spaces));
        self.interp.light_in(e, ps, spaces)
    }

    fn emission(&self) -> Option<Emission> {
        self.interp.emission()
    }

    fn category(&self) -> &str {
        self.interp.category()
    }

    /// The direct entry of the variant of `F` (compiling it now if needed), when the light
    /// compiles for it and needs no callback but named spaces, which it finds in `spaces`.
    fn code_in<F: ShadingFloat>(&self, spaces: &Spaces) -> Option<LightCode> {
        let v = variant_of::<F>()?;
        let cs = self.variant_ref(v).ok()?;
        Some(LightCode {
            entry: cs.light? as *const (),
            ctx: (spaces as *const Spaces).cast(),
            host: crate::rt::light_host_table(),
            params: self.param_block.as_ptr(),
            emission: self.interp.emission().unwrap_or(Emission::Local),
            // What `inline_lights` reads back.
            source: Arc::as_ptr(cs).cast(),
        })
    }
}

/// The light shaders of `records`, each once, in the records' order, for a surface's variant
/// `v` to compile into its light loops — when each record with code can be: its direct entry
/// was handed out by [`JitShader::code_in`] for `v` (known by this crate's callback table),
/// and there are at most [`crate::MAX_INLINE_LIGHTS`] of them.
fn inline_lights(records: &[LightRecord], v: Variant) -> Option<Vec<InlineLight>> {
    let ours = crate::rt::light_host_table();
    let mut out: Vec<InlineLight> = Vec::new();
    for c in records.iter().map(|r| &r.code) {
        let entry = c.entry as usize;
        if entry == 0 || out.iter().any(|l| l.entry == entry) {
            continue;
        }
        if c.source.is_null() || c.host != ours || out.len() == crate::MAX_INLINE_LIGHTS {
            return None;
        }
        // SAFETY: a record with this crate's callback table comes from `JitShader::code_in`,
        // whose `source` is the compiled variant the entry belongs to, alive as long as the
        // light (which outlives the records: `LightCode`'s promise); the count taken here
        // keeps it alive with the code compiled from it.
        let light = unsafe {
            let p = c.source.cast::<CompiledShader>();
            Arc::increment_strong_count(p);
            Arc::from_raw(p)
        };
        if light.variant != v || light.light != Some(entry) || light.source.is_none() {
            return None;
        }
        out.push(InlineLight { entry, light });
    }
    Some(out)
}
