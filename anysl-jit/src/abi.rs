//! The boundary between JIT-compiled code and Rust: how values of each float type lie in
//! memory, and the signatures of the compiled shader and of the callbacks it makes.
//!
//! Every value crosses the boundary as `f32` lanes: a value of a float type with `L` lanes
//! is `L` consecutive `f32`s; a dual number is its value, ∂/∂x and ∂/∂y one after the other
//! (`3 L` floats). Masks are `L` `u32` lanes (0 or `!0`). Triples are three values in a row.

use anysl_ad::Dual;
use anysl_core::ShadingFloat;
use anysl_simd::{F32x16, F32x4, F32x8, Pair, PairMask};
use core::ffi::c_void;

/// A callback of the runtime library or of the host: `(ctx, mask, inputs, outputs, aux)`.
/// `aux` carries compile-time parameters (noise dimensions, knot counts, colour spaces, …).
pub type RtFn = unsafe extern "C" fn(ctx: *mut c_void, mask: *const u32, inp: *const f32, out: *mut f32, aux: u32);

/// The body of an `illuminance` loop, compiled as its own function: `(env, mask, L ++ Cl)`.
pub type BodyFn = unsafe extern "C" fn(env: *mut u8, mask: *const u32, l_cl: *const f32);

/// The host's `illuminance`: `(ctx, mask, P ++ axis ++ angle, has_cone, category, category
/// length, body, env)`.
pub type IllumFn = unsafe extern "C" fn(
    ctx: *mut c_void,
    mask: *const u32,
    inp: *const f32,
    has_cone: u32,
    cat: *const u8,
    cat_len: usize,
    body: BodyFn,
    env: *mut u8,
);

/// A compiled shader: `(globals, outputs, mask, ctx, host table, parameter block)`; the
/// parameter block ([`crate::codegen::param_block`]) is read only by code compiled without
/// specialization. `globals` points at the
/// renderer's `Globals<F>` (read at the offsets of [`GlobalsLayout`]); see [`OUTPUT_ORDER`]
/// for the output buffer.
/// A light shader's direct entry ([`crate::CompiledShader::light`], [`anysl_core::LightCode`]):
/// the surface points (three values of the float type, `STRIDE` floats apart), the output
/// buffer (`Cl`, `L`), the mask, the callbacks' context (the light's `Spaces`), the callback
/// table ([`crate::rt::light_host_table`]) and the parameter block.
pub type LightFn = unsafe extern "C" fn(
    ps: *const f32,
    out: *mut f32,
    mask: *const u32,
    ctx: *mut c_void,
    host: *const usize,
    params: *const f32,
);

pub type ShadeFn = unsafe extern "C" fn(
    globals: *const f32,
    out: *mut f32,
    mask: *const u32,
    ctx: *mut c_void,
    host: *const usize,
    params: *const f32,
);

/// A shader compiled as a loop over a point set ([`crate::compile_points`]): `(packets, src,
/// out, globals, ctx, host table, parameter block)`. For packet `j`, each varying global
/// component `k` (of [`crate::PointsLayout::varying`]) is read from `src[k] + j·lanes` and
/// stored into `globals` (the context's own `Globals<F>`, at the offsets of
/// [`GlobalsLayout`]) before the shader runs on it with every lane active; output component
/// `k` (`Ci` r, g, b, then `Oi`) is written to `out[k] + j·lanes`. Components that do not vary
/// are read from `globals` as the caller left them.
pub type PointsFn = unsafe extern "C" fn(
    packets: u64,
    src: *const *const f32,
    out: *const *mut f32,
    globals: *mut f32,
    ctx: *mut c_void,
    host: *const usize,
    params: *const f32,
);

/// The globals and the number of their first component (see [`GlobalsLayout`]).
pub const GLOBAL_ORDER: [(anysl_rsl::ir::Global, usize); 15] = {
    use anysl_rsl::ir::Global as G;
    [
        (G::P, 0),
        (G::N, 3),
        (G::Ng, 6),
        (G::I, 9),
        (G::E, 12),
        (G::DPdu, 15),
        (G::DPdv, 18),
        (G::Cs, 21),
        (G::Os, 24),
        (G::S, 27),
        (G::T, 28),
        (G::U, 29),
        (G::V, 30),
        (G::Du, 31),
        (G::Dv, 32),
    ]
};
/// Number of global components.
pub const GLOBAL_VALUES: usize = 33;

/// Where the compiled code finds the globals: the renderer's own [`anysl_core::Globals`]
/// struct, read in place (no copy per call). `comp[k]` is the offset in floats of component
/// `k` (numbered as in [`GLOBAL_ORDER`]) — of its value part for dual numbers, whose ∂/∂x
/// and ∂/∂y lie `dual[0]` and `dual[1]` floats further.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct GlobalsLayout {
    /// Float offset of each component's value.
    pub comp: [u32; GLOBAL_VALUES],
    /// Float offsets of ∂/∂x and ∂/∂y from the value (dual numbers only).
    pub dual: [u32; 2],
}

impl GlobalsLayout {
    /// The layout of `Globals<F>` as the Rust compiler laid it out.
    #[must_use]
    pub fn of<F: JitFloat>() -> Self {
        use anysl_core::{Color, Globals, Vec3};
        use core::mem::offset_of;
        let fl = |bytes: usize| -> u32 {
            debug_assert!(bytes % 4 == 0);
            u32::try_from(bytes / 4).expect("small offsets")
        };
        let v3 = [offset_of!(Vec3<F>, x), offset_of!(Vec3<F>, y), offset_of!(Vec3<F>, z)];
        let c3 = [offset_of!(Color<F>, r), offset_of!(Color<F>, g), offset_of!(Color<F>, b)];
        let triples = [
            offset_of!(Globals<F>, P),
            offset_of!(Globals<F>, N),
            offset_of!(Globals<F>, Ng),
            offset_of!(Globals<F>, I),
            offset_of!(Globals<F>, E),
            offset_of!(Globals<F>, dPdu),
            offset_of!(Globals<F>, dPdv),
        ];
        let singles = [
            offset_of!(Globals<F>, s),
            offset_of!(Globals<F>, t),
            offset_of!(Globals<F>, u),
            offset_of!(Globals<F>, v),
            offset_of!(Globals<F>, du),
            offset_of!(Globals<F>, dv),
        ];
        let mut comp = [0u32; GLOBAL_VALUES];
        let mut k = 0;
        for base in triples {
            for o in v3 {
                comp[k] = fl(base + o);
                k += 1;
            }
        }
        for base in [offset_of!(Globals<F>, Cs), offset_of!(Globals<F>, Os)] {
            for o in c3 {
                comp[k] = fl(base + o);
                k += 1;
            }
        }
        for base in singles {
            comp[k] = fl(base);
            k += 1;
        }
        debug_assert_eq!(k, GLOBAL_VALUES);
        let dual = if F::DUAL { F::dual_offsets().map(fl) } else { [0, 0] };
        Self { comp, dual }
    }
}
/// True when a `SurfaceOutput<G>` lies in memory exactly as the compiled code writes the
/// first [`OUTPUT_ORDER`] entries (`Ci`, then `Oi`; r, g, b; each value `G::STRIDE` floats
/// with dual parts `lanes` and `2·lanes` floats after the value), so the code can write the
/// caller's return value in place. Constant for each `G` (the check folds away).
#[must_use]
pub fn output_layout_is_buffer<G: JitFloat>() -> bool {
    use anysl_core::{Color, SurfaceOutput};
    use core::mem::{offset_of, size_of};
    let v = G::STRIDE * 4;
    let lane_bytes = G::BASE_LANES * 4;
    size_of::<G>() == v
        && offset_of!(SurfaceOutput<G>, Ci) == 0
        && offset_of!(SurfaceOutput<G>, Oi) == 3 * v
        && offset_of!(Color<G>, r) == 0
        && offset_of!(Color<G>, g) == v
        && offset_of!(Color<G>, b) == 2 * v
        && (!G::DUAL || G::dual_offsets() == [lane_bytes, 2 * lane_bytes])
}

/// Where an imager shader's `alpha` is in the output buffer (after `Ci`, `Oi`): one value.
pub const IMAGER_ALPHA: usize = 6;

/// Order of the outputs: `Ci`, `Oi` (surface), `P`, `N` (displacement). Volume and imager
/// shaders find `Ci`, `Oi` (and an imager its `alpha` at [`IMAGER_ALPHA`]) there on entry.
pub const OUTPUT_ORDER: [(anysl_rsl::ir::Global, usize); 4] = {
    use anysl_rsl::ir::Global as G;
    [(G::Ci, 0), (G::Oi, 3), (G::P, 6), (G::N, 9)]
};
/// Number of values in the output buffer.
pub const OUTPUT_VALUES: usize = 12;

/// Where code compiled with [`crate::JitOptions::output_params`] writes the numeric output
/// parameters of `module`: `(parameter index, first value, values)`, in declaration order,
/// after the [`OUTPUT_VALUES`] standard outputs (arrays element by element, triples
/// component by component).
#[must_use]
pub fn output_params(module: &anysl_rsl::ir::Module) -> Vec<(usize, usize, usize)> {
    let mut at = OUTPUT_VALUES;
    let mut out = Vec::new();
    for (k, p) in module.params.iter().enumerate() {
        if !p.output || p.ty.base == anysl_rsl::types::BaseType::String {
            continue;
        }
        let n = p.ty.base.components().max(1) * p.ty.array.unwrap_or(1) as usize;
        out.push((k, at, n));
        at += n;
    }
    out
}

/// Most lanes of any [`JitFloat`] (`Pair<Pair<F32x8>>`, `Pair<F32x16>`): the size of the mask
/// buffers the host passes.
pub const MAX_LANES: usize = 32;

/// A float type compiled code can be specialized for: how its values and masks lie in memory.
///
/// # Safety
/// `read`/`write` access `STRIDE` floats (masks: `BASE_LANES` u32s) at the pointer.
pub unsafe trait JitFloat: ShadingFloat {
    /// Floats per value.
    const STRIDE: usize;
    /// Lanes of the underlying float vector.
    const BASE_LANES: usize;
    /// A dual number.
    const DUAL: bool;
    /// Byte offsets of ∂/∂x and ∂/∂y inside a value (dual numbers; `[0, 0]` otherwise).
    #[must_use]
    fn dual_offsets() -> [usize; 2] {
        [0, 0]
    }
    /// Reads a value.
    ///
    /// # Safety
    /// `p` points at `STRIDE` readable floats.
    unsafe fn read(p: *const f32) -> Self;
    /// Writes a value.
    ///
    /// # Safety
    /// `p` points at `STRIDE` writable floats.
    unsafe fn write(self, p: *mut f32);
    /// Reads a mask.
    ///
    /// # Safety
    /// `p` points at `BASE_LANES` readable u32s.
    unsafe fn read_mask(p: *const u32) -> Self::Mask;
    /// Writes a mask.
    ///
    /// # Safety
    /// `p` points at `BASE_LANES` writable u32s.
    unsafe fn write_mask(m: Self::Mask, p: *mut u32);
}

unsafe impl JitFloat for f32 {
    const STRIDE: usize = 1;
    const BASE_LANES: usize = 1;
    const DUAL: bool = false;
    #[inline(always)]
    unsafe fn read(p: *const f32) -> Self {
        *p
    }
    #[inline(always)]
    unsafe fn write(self, p: *mut f32) {
        *p = self;
    }
    #[inline(always)]
    unsafe fn read_mask(p: *const u32) -> bool {
        *p != 0
    }
    #[inline(always)]
    unsafe fn write_mask(m: bool, p: *mut u32) {
        *p = if m { !0 } else { 0 };
    }
}

macro_rules! jit_simd {
    ($F:ident, $M:ident, $n:literal, $wf:ident, $wu:ident) => {
        unsafe impl JitFloat for $F {
            const STRIDE: usize = $n;
            const BASE_LANES: usize = $n;
            const DUAL: bool = false;
            #[inline(always)]
            unsafe fn read(p: *const f32) -> Self {
                $F::from(core::ptr::read_unaligned(p.cast::<[f32; $n]>()))
            }
            #[inline(always)]
            unsafe fn write(self, p: *mut f32) {
                core::ptr::write_unaligned(p.cast::<[f32; $n]>(), self.to_array());
            }
            #[inline(always)]
            unsafe fn read_mask(p: *const u32) -> Self::Mask {
                let bits: [u32; $n] = core::ptr::read_unaligned(p.cast::<[u32; $n]>());
                anysl_simd::$M(wide::$wf::from_bits(wide::$wu::from(bits)))
            }
            #[inline(always)]
            unsafe fn write_mask(m: Self::Mask, p: *mut u32) {
                core::ptr::write_unaligned(p.cast::<[u32; $n]>(), m.0.to_array().map(f32::to_bits));
            }
        }
    };
}

jit_simd!(F32x4, M32x4, 4, f32x4, u32x4);
jit_simd!(F32x8, M32x8, 8, f32x8, u32x8);
jit_simd!(F32x16, M32x16, 16, f32x16, u32x16);

unsafe impl<B: JitFloat> JitFloat for Dual<B>
where
    Dual<B>: ShadingFloat<Mask = B::Mask>,
{
    const STRIDE: usize = 3 * B::STRIDE;
    const BASE_LANES: usize = B::BASE_LANES;
    const DUAL: bool = true;
    fn dual_offsets() -> [usize; 2] {
        [
            core::mem::offset_of!(Dual<B>, ddx) - core::mem::offset_of!(Dual<B>, val),
            core::mem::offset_of!(Dual<B>, ddy) - core::mem::offset_of!(Dual<B>, val),
        ]
    }
    #[inline(always)]
    unsafe fn read(p: *const f32) -> Self {
        Dual::new(B::read(p), B::read(p.add(B::STRIDE)), B::read(p.add(2 * B::STRIDE)))
    }
    #[inline(always)]
    unsafe fn write(self, p: *mut f32) {
        self.val.write(p);
        self.ddx.write(p.add(B::STRIDE));
        self.ddy.write(p.add(2 * B::STRIDE));
    }
    #[inline(always)]
    unsafe fn read_mask(p: *const u32) -> Self::Mask {
        B::read_mask(p)
    }
    #[inline(always)]
    unsafe fn write_mask(m: Self::Mask, p: *mut u32) {
        B::write_mask(m, p);
    }
}

/// Several packets shaded together ([`Pair`]): lanes of `.0`, then of `.1`, in one run of
/// `2 · G::STRIDE` floats — the layout of a vector of all lanes. Dual numbers, whose halves
/// would each interleave value and derivatives, are not laid out so and are refused when the
/// impl is instantiated.
unsafe impl<G: JitFloat> JitFloat for Pair<G> {
    const STRIDE: usize = {
        assert!(!G::DUAL, "Pair of dual numbers has no JIT layout");
        2 * G::STRIDE
    };
    const BASE_LANES: usize = {
        assert!(2 * G::BASE_LANES <= MAX_LANES, "more lanes than the host's mask buffers hold");
        2 * G::BASE_LANES
    };
    const DUAL: bool = false;
    #[inline(always)]
    unsafe fn read(p: *const f32) -> Self {
        Pair(G::read(p), G::read(p.add(G::STRIDE)))
    }
    #[inline(always)]
    unsafe fn write(self, p: *mut f32) {
        self.0.write(p);
        self.1.write(p.add(G::STRIDE));
    }
    #[inline(always)]
    unsafe fn read_mask(p: *const u32) -> Self::Mask {
        PairMask(G::read_mask(p), G::read_mask(p.add(G::BASE_LANES)))
    }
    #[inline(always)]
    unsafe fn write_mask(m: Self::Mask, p: *mut u32) {
        G::write_mask(m.0, p);
        G::write_mask(m.1, p.add(G::BASE_LANES));
    }
}

/// Opaque pointer type used by callbacks.
pub type Ctx = *mut c_void;
