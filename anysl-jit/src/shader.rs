//! [`JitShader`]: a JIT-compiled `.sl` surface shader behind the same [`SurfaceShader`]
//! boundary as every other shader.

use crate::abi::{JitFloat, GLOBAL_ORDER, GLOBAL_VALUES, OUTPUT_VALUES};
use crate::rt::{cast, HostCtx, HostTable};
use crate::{compile, CompiledShader, JitError, JitOptions, Variant};
use anysl_ad::Dual;
use anysl_core::prelude::*;
use anysl_core::shader::{ParamError, ParamValue, ShaderMeta};
use anysl_rsl::back::interp::{InterpShader, Program};
use anysl_rsl::ir::{Const, Global, Module};
use anysl_rsl::CompileOptions;
use anysl_simd::{F32x16, F32x4, F32x8};
use std::any::TypeId;
use std::path::Path;
use std::sync::{Arc, OnceLock};

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
    ]
    .into_iter()
    .find(|(id, _)| *id == t)
    .map(|(_, v)| v)
}

type Slot = OnceLock<Result<Arc<CompiledShader>, String>>;

/// A surface shader compiled at run time. Each float type's variant is compiled on first use
/// and cached; float types the JIT has no variant for (f64, intervals) run on the
/// interpreter.
pub struct JitShader {
    /// The lowered IR (before the instance-specific passes).
    pub module: Arc<Module>,
    /// This instance's parameter values.
    pub values: Vec<Const>,
    /// Compiler settings.
    pub opts: JitOptions,
    variants: [Slot; 6],
    interp: InterpShader,
    /// The globals the shader reads (only these are copied in).
    used_globals: Vec<(Global, usize)>,
}

impl Clone for JitShader {
    fn clone(&self) -> Self {
        Self {
            module: self.module.clone(),
            values: self.values.clone(),
            opts: self.opts.clone(),
            variants: Default::default(),
            interp: self.interp.clone(),
            used_globals: self.used_globals.clone(),
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
        let mut interp_module = module.clone();
        anysl_rsl::passes::optimize(&mut interp_module, &anysl_rsl::passes::PassOptions::default());
        let program = Program::new(interp_module).map_err(|e| JitError(e.to_string()))?;
        let used_globals = GLOBAL_ORDER
            .iter()
            .copied()
            .filter(|(g, _)| matches!(g, Global::P | Global::Ng | Global::Os) || module.func.global_slot(*g).is_some())
            .collect();
        Ok(Self {
            used_globals,
            module: Arc::new(module),
            values,
            opts,
            variants: Default::default(),
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

    /// The compiled variant (compiling it now if needed).
    ///
    /// # Errors
    /// When the shader cannot be compiled for this variant.
    pub fn variant(&self, v: Variant) -> Result<Arc<CompiledShader>, String> {
        self.variants[v.index()]
            .get_or_init(|| compile(&self.module, &self.values, v, &self.opts).map(Arc::new).map_err(|e| e.to_string()))
            .clone()
    }

    /// The variants compiled so far.
    #[must_use]
    pub fn compiled(&self) -> Vec<Variant> {
        Variant::ALL.into_iter().filter(|v| matches!(self.variants[v.index()].get(), Some(Ok(_)))).collect()
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
        // Uninitialized: only the globals the shader reads are written and read; every output
        // is written by the compiled code (zeroing 9 KB per call would cost more than shading).
        let mut gbuf_m = std::mem::MaybeUninit::<[f32; GLOBAL_VALUES * 48]>::uninit();
        let mut obuf_m = std::mem::MaybeUninit::<[f32; OUTPUT_VALUES * 48]>::uninit();
        let gbuf: *mut f32 = gbuf_m.as_mut_ptr().cast();
        let obuf: *mut f32 = obuf_m.as_mut_ptr().cast();
        let mut mbuf = [0u32; 16];
        let g = *ctx.globals();
        let st = G::STRIDE;
        // SAFETY: `k < GLOBAL_VALUES` and the buffer holds `GLOBAL_VALUES * 48 >= GLOBAL_VALUES * st` floats.
        let put = |buf: *mut f32, k: usize, x: F| unsafe { cast::<F, G>(x).write(buf.add(k * st)) };
        for &(gl, off) in &self.used_globals {
            match gl {
                Global::P => put3(gbuf, off, g.P, put),
                Global::N => put3(gbuf, off, g.N, put),
                Global::Ng => put3(gbuf, off, g.Ng, put),
                Global::I => put3(gbuf, off, g.I, put),
                Global::E => put3(gbuf, off, g.E, put),
                Global::DPdu => put3(gbuf, off, g.dPdu, put),
                Global::DPdv => put3(gbuf, off, g.dPdv, put),
                Global::Cs => put3(gbuf, off, Vec3::new(g.Cs.r, g.Cs.g, g.Cs.b), put),
                Global::Os => put3(gbuf, off, Vec3::new(g.Os.r, g.Os.g, g.Os.b), put),
                Global::S => put(gbuf, off, g.s),
                Global::T => put(gbuf, off, g.t),
                Global::U => put(gbuf, off, g.u),
                Global::V => put(gbuf, off, g.v),
                Global::Du => put(gbuf, off, g.du),
                Global::Dv => put(gbuf, off, g.dv),
                _ => {}
            }
        }
        unsafe { G::write_mask(cast::<F::Mask, G::Mask>(e.mask()), mbuf.as_mut_ptr()) };
        let host = HostTable::<F, C, G>::table();
        let mut hc = HostCtx { ctx, lit: None };
        // SAFETY: the buffers have the layout the compiled code expects; `ctx` is a `C`, which
        // is what the host table's shims take.
        unsafe {
            (cs.f)(gbuf, obuf, mbuf.as_ptr(), (&mut hc as *mut HostCtx<F, C>).cast(), host.as_ptr());
        }
        let get = |k: usize| -> F { unsafe { cast::<G, F>(G::read(obuf.add(k * st))) } };
        SurfaceOutput { Ci: Color::new(get(0), get(1), get(2)), Oi: Color::new(get(3), get(4), get(5)) }
    }
}

#[inline(always)]
fn put3<F: Copy>(buf: *mut f32, off: usize, v: Vec3<F>, put: impl Fn(*mut f32, usize, F)) {
    put(buf, off, v.x);
    put(buf, off + 1, v.y);
    put(buf, off + 2, v.z);
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
        // Parameters are compiled in: recompile on next use.
        self.variants = Default::default();
        Ok(())
    }
}

impl SurfaceShader for JitShader {
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        if let Some(v) = variant_of::<F>() {
            if let Ok(cs) = self.variant(v) {
                return match v {
                    Variant::F32 => self.run::<F, C, f32>(&cs, ctx, e),
                    Variant::X4 => self.run::<F, C, F32x4>(&cs, ctx, e),
                    Variant::X8 => self.run::<F, C, F32x8>(&cs, ctx, e),
                    Variant::X16 => self.run::<F, C, F32x16>(&cs, ctx, e),
                    Variant::DualF32 => self.run::<F, C, Dual<f32>>(&cs, ctx, e),
                    Variant::DualX8 => self.run::<F, C, Dual<F32x8>>(&cs, ctx, e),
                };
            }
        }
        self.interp.shade(ctx, e)
    }
}
