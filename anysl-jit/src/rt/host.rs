//! The host shims: the built-ins that need the renderer's `ShadingContext` (light loops,
//! rays, derivatives, random numbers, named spaces), called by compiled code through the
//! [`HostTable`] with a [`HostCtx`] as their context.

use super::{In, Out};
use crate::abi::{BodyFn, JitFloat};
use anysl_core::prelude::*;
use anysl_core::{LightRecord, Spaces};
use core::ffi::c_void;
use core::marker::PhantomData;
use core::mem::MaybeUninit;

/// What the compiled code and the host shims receive as `ctx`: the context's lights as data
/// (read by the compiled code, which runs the built-in light loops itself when there are
/// any, at the offsets [`HOST_CTX_LIGHTS`] and [`HOST_CTX_N_LIGHTS`]), the renderer's context,
/// and a memo of the last `specular` light loop, which also summed the diffuse term (the
/// fused loop of [`diffuse_specular`], as the compiled Rust shaders use): a following
/// `diffuse` of the same normal under the same mask reuses it instead of visiting the lights
/// again.
#[repr(C)]
pub struct HostCtx<'a, F: ShadingFloat, C> {
    /// [`ShadingContext::lights_as_data`], or null when the context's loops must be called.
    pub lights: *const LightData,
    /// The number of `lights`.
    pub n_lights: usize,
    /// [`ShadingContext::light_records`] when the context has no lights as data, or null.
    pub records: *const LightRecord,
    /// The number of `records`.
    pub n_records: usize,
    /// The renderer's context.
    pub ctx: &'a mut C,
    /// The diffuse sum of the last fused loop.
    pub lit: Option<KeptDiffuse<F>>,
}

impl<'a, F: ShadingFloat, C: ShadingContext<F>> HostCtx<'a, F, C> {
    /// The host state of one call into compiled code: the context's lights as data when it
    /// has them (read by the compiled code in place, while the host shims hold the context,
    /// which never changes them: a `ShadingContext` hands them out only by shared reference).
    pub fn new(ctx: &'a mut C) -> Self {
        let (lights, n_lights) = match ctx.lights_as_data() {
            Some(l) => (l.as_ptr(), l.len()),
            None => (core::ptr::null(), 0),
        };
        let records = if lights.is_null() { ctx.light_records() } else { None };
        let (records, n_records) = match records {
            Some(r) => (r.as_ptr(), r.len()),
            None => (core::ptr::null(), 0),
        };
        Self { lights, n_lights, records, n_records, ctx, lit: None }
    }
}

/// The diffuse sum a `specular` host call leaves for the `diffuse` call after it: taken when
/// the normal, the mask and `P` are the same (a points entry shades many packets with one
/// [`HostCtx`]).
pub struct KeptDiffuse<F: ShadingFloat> {
    /// The normal.
    pub n: Vec3<F>,
    /// The mask.
    pub mask: F::Mask,
    /// `diffuse(n)`.
    pub diffuse: Color<F>,
    /// The context's `P` at the call.
    pub p: Vec3<F>,
}

/// Byte offset of [`HostCtx::lights`].
pub const HOST_CTX_LIGHTS: u64 = 0;
/// Byte offset of [`HostCtx::n_lights`].
pub const HOST_CTX_N_LIGHTS: u64 = 8;
/// Byte offset of [`HostCtx::records`].
pub const HOST_CTX_RECORDS: u64 = 16;
/// Byte offset of [`HostCtx::n_records`].
pub const HOST_CTX_N_RECORDS: u64 = 24;

fn same<F: ShadingFloat>(a: Vec3<F>, b: Vec3<F>, ma: F::Mask, mb: F::Mask) -> bool {
    let eq = a.x.eq(b.x) & a.y.eq(b.y) & a.z.eq(b.z);
    let dm = (ma & !mb) | (mb & !ma);
    dm.none() && (eq | !ma).all()
}

/// The callbacks that need the renderer: a table per float type and context type, indexed by
/// [`Host`].
pub struct HostTable<F, C, G>(PhantomData<(F, C, G)>);

/// The host shims: the [`Host`] index of each and [`HostTable::TABLE`], in one list.
macro_rules! host_shims {
    ($($(#[$doc:meta])* $v:ident => $f:expr,)*) => {
        /// Indices into the host table: the callbacks that need the renderer's context.
        #[repr(usize)]
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum Host {
            $($(#[$doc])* $v,)*
        }

        impl Host {
            /// Number of entries.
            pub const LEN: usize = [$(Host::$v,)*].len();
        }

        impl<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat> HostTable<F, C, G> {
            /// The table (indexed by [`Host`]): one static array per instantiation.
            pub const TABLE: [*const (); Host::LEN] = [$($f as *const (),)*];
        }
    };
}

host_shims! {
    /// `illuminance` loops: the body is a compiled function the shim calls per light.
    Illuminance => host_illuminance::<F, C, G>,
    /// `ambient()`.
    Ambient => host_ambient::<F, C, G>,
    /// `diffuse(N)` (with `aux`, also the ambient sum).
    Diffuse => host_diffuse::<F, C, G>,
    /// `specular(N, V, roughness)` (with `aux`, also the diffuse and ambient sums).
    Specular => host_specular::<F, C, G>,
    /// `phong(N, V, size)`.
    Phong => host_phong::<F, C, G>,
    /// `trace(P, R)`.
    Trace => host_trace::<F, C, G>,
    /// `Du(x)`.
    Du => host_du::<F, C, G>,
    /// `Dv(x)`.
    Dv => host_dv::<F, C, G>,
    /// `Deriv(num, den)`.
    Deriv => host_deriv::<F, C, G>,
    /// `calculatenormal(P)`.
    CalcNormal => host_calcnormal::<F, C, G>,
    /// `random()`.
    Random => host_random::<F, C, G>,
    /// A named coordinate system's matrix.
    Space => host_space::<F, C>,
}

impl<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat> HostTable<F, C, G> {
    /// [`HostTable::TABLE`] as the compiled code reads it (addresses as `usize`).
    #[inline(always)]
    #[must_use]
    pub fn table() -> *const usize {
        let t: &'static [*const (); Host::LEN] = &Self::TABLE;
        t.as_ptr().cast()
    }
}

/// Most floats per value of any [`JitFloat`] (`Dual<F32x16>`).
const MAX_STRIDE: usize = 48;

unsafe extern "C" fn host_illuminance<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    mask: *const u32,
    inp: *const f32,
    has_cone: u32,
    cat: *const u8,
    cat_len: usize,
    body: BodyFn,
    env: *mut u8,
) {
    let ctx = &mut *(*ctx.cast::<HostCtx<F, C>>()).ctx;
    let m = cast::<G::Mask, F::Mask>(G::read_mask(mask));
    let mut i = HIn::<F, G>::new(inp);
    let p = i.v3();
    let cone = if has_cone != 0 {
        let a = i.v3();
        Some((a, i.f()))
    } else {
        None
    };
    let category =
        if cat_len == 0 { "" } else { core::str::from_utf8_unchecked(core::slice::from_raw_parts(cat, cat_len)) };
    let mut e = Exec::with_mask(m);
    ctx.illuminance(&mut e, LightQuery::new(category, p, cone), |e, l, cl| {
        let mut buf = MaybeUninit::<[f32; 6 * MAX_STRIDE]>::uninit();
        let buf: *mut f32 = buf.as_mut_ptr().cast();
        let mut o = HOut::<F, G>::new(buf);
        o.v3(l);
        o.c3(cl);
        let mut mb = [0u32; crate::abi::MAX_LANES];
        G::write_mask(cast::<F::Mask, G::Mask>(e.mask()), mb.as_mut_ptr());
        body(env, mb.as_ptr(), buf);
    });
}

unsafe extern "C" fn host_ambient<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    mask: *const u32,
    _: *const f32,
    out: *mut f32,
    _: u32,
) {
    let ctx = &mut *(*ctx.cast::<HostCtx<F, C>>()).ctx;
    let e = Exec::with_mask(cast::<G::Mask, F::Mask>(G::read_mask(mask)));
    HOut::<F, G>::new(out).c3(ctx.ambient(&e));
}

unsafe extern "C" fn host_diffuse<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    mask: *const u32,
    inp: *const f32,
    out: *mut f32,
    aux: u32,
) {
    let hc = &mut *ctx.cast::<HostCtx<F, C>>();
    let m = cast::<G::Mask, F::Mask>(G::read_mask(mask));
    let n = HIn::<F, G>::new(inp).v3();
    let d = match hc.lit.take() {
        Some(k) if same(n, k.n, m, k.mask) && same(hc.ctx.globals().P, k.p, m, k.mask) => k.diffuse,
        _ => diffuse(hc.ctx, &mut Exec::with_mask(m), n),
    };
    let mut o = HOut::<F, G>::new(out);
    o.c3(d);
    // `aux` 1: also `ambient()` (an `ambient()` call the code generator fused with this one).
    if aux >= 1 {
        o.c3(hc.ctx.ambient(&Exec::with_mask(m)));
    }
}

unsafe extern "C" fn host_specular<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    mask: *const u32,
    inp: *const f32,
    out: *mut f32,
    aux: u32,
) {
    let hc = &mut *ctx.cast::<HostCtx<F, C>>();
    let m = cast::<G::Mask, F::Mask>(G::read_mask(mask));
    let mut i = HIn::<F, G>::new(inp);
    let (n, v, r) = (i.v3(), i.v3(), i.f());
    let (d, sp) = diffuse_specular(hc.ctx, &mut Exec::with_mask(m), n, v, r);
    hc.lit = Some(KeptDiffuse { n, mask: m, diffuse: d, p: hc.ctx.globals().P });
    let mut o = HOut::<F, G>::new(out);
    o.c3(sp);
    // `aux` 1: also `diffuse(N)`; 2: and `ambient()` (the code generator keeps them).
    if aux >= 1 {
        o.c3(d);
    }
    if aux >= 2 {
        o.c3(hc.ctx.ambient(&Exec::with_mask(m)));
    }
}

unsafe extern "C" fn host_phong<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    mask: *const u32,
    inp: *const f32,
    out: *mut f32,
    _: u32,
) {
    let ctx = &mut *(*ctx.cast::<HostCtx<F, C>>()).ctx;
    let m = cast::<G::Mask, F::Mask>(G::read_mask(mask));
    let mut i = HIn::<F, G>::new(inp);
    let (n, v, r) = (i.v3(), i.v3(), i.f());
    HOut::<F, G>::new(out).c3(phong(ctx, &mut Exec::with_mask(m), n, v, r));
}

unsafe extern "C" fn host_trace<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    mask: *const u32,
    inp: *const f32,
    out: *mut f32,
    _: u32,
) {
    let ctx = &mut *(*ctx.cast::<HostCtx<F, C>>()).ctx;
    let e = Exec::with_mask(cast::<G::Mask, F::Mask>(G::read_mask(mask)));
    let mut i = HIn::<F, G>::new(inp);
    let (p, d) = (i.v3(), i.v3());
    HOut::<F, G>::new(out).c3(ctx.trace(&e, p, d));
}

unsafe extern "C" fn host_du<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    _: *const u32,
    inp: *const f32,
    out: *mut f32,
    aux: u32,
) {
    let g = *(*ctx.cast::<HostCtx<F, C>>()).ctx.globals();
    let mut i = HIn::<F, G>::new(inp);
    let mut o = HOut::<F, G>::new(out);
    for _ in 0..aux {
        o.f(du(&g, i.f()));
    }
}

unsafe extern "C" fn host_dv<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    _: *const u32,
    inp: *const f32,
    out: *mut f32,
    aux: u32,
) {
    let g = *(*ctx.cast::<HostCtx<F, C>>()).ctx.globals();
    let mut i = HIn::<F, G>::new(inp);
    let mut o = HOut::<F, G>::new(out);
    for _ in 0..aux {
        o.f(dv(&g, i.f()));
    }
}

unsafe extern "C" fn host_deriv<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    _: *const u32,
    inp: *const f32,
    out: *mut f32,
    aux: u32,
) {
    let g = *(*ctx.cast::<HostCtx<F, C>>()).ctx.globals();
    let mut i = HIn::<F, G>::new(inp);
    let mut num = [F::c(0.0); 3];
    for n in num.iter_mut().take(aux as usize) {
        *n = i.f();
    }
    let den = i.f();
    let mut o = HOut::<F, G>::new(out);
    for n in num.iter().take(aux as usize) {
        o.f(deriv(&g, *n, den));
    }
}

unsafe extern "C" fn host_calcnormal<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    _: *const u32,
    inp: *const f32,
    out: *mut f32,
    _: u32,
) {
    let g = *(*ctx.cast::<HostCtx<F, C>>()).ctx.globals();
    let p = HIn::<F, G>::new(inp).v3();
    HOut::<F, G>::new(out).v3(calculatenormal(&g, p));
}

unsafe extern "C" fn host_random<F: ShadingFloat, C: ShadingContext<F>, G: JitFloat>(
    ctx: *mut c_void,
    _: *const u32,
    _: *const f32,
    out: *mut f32,
    aux: u32,
) {
    let p = (*ctx.cast::<HostCtx<F, C>>()).ctx.globals().P;
    let mut o = HOut::<F, G>::new(out);
    for c in 0..aux {
        o.f(cellnoise(NoiseDomain::D4(p * F::c(1.0e4), F::c(f64::from(c) + 0.5))));
    }
}

/// Separates the two names of [`SPACE_BETWEEN`] in the string [`host_space`] reads.
pub const SPACE_SEPARATOR: char = '\u{1f}';
/// [`host_space`] kind: the matrix from the named space to current.
pub const SPACE_TO_CURRENT: u32 = 0;
/// [`host_space`] kind: the matrix from current to the named space.
pub const SPACE_FROM_CURRENT: u32 = 1;
/// [`host_space`] kind: the matrix between two named spaces (`from`, separator, `to`).
pub const SPACE_BETWEEN: u32 = 2;

/// A matrix of the context's named spaces ([`ShadingContext::spaces`]) as 16 uniform floats:
/// `inp` points at the name's UTF-8 bytes, `aux` is the kind (low 2 bits, `SPACE_*`) and the
/// name's length in bytes (above).
unsafe extern "C" fn host_space<F: ShadingFloat, C: ShadingContext<F>>(
    ctx: *mut c_void,
    _: *const u32,
    inp: *const f32,
    out: *mut f32,
    aux: u32,
) {
    space_matrix((*ctx.cast::<HostCtx<F, C>>()).ctx.spaces(), inp, out, aux);
}

/// The callback table of a light's direct entry ([`anysl_core::LightCode`]): its `ctx` is
/// the light's [`Spaces`]; named spaces are the only callback such code makes (the entry is
/// generated only then), the other slots answer nothing. A `static`, so that it has one
/// address: the JIT knows the records it made by it (a `const` is copied where it is used).
static LIGHT_HOST_TABLE: LightHostTable = LightHostTable({
    let mut t = [light_no_host as *const (); Host::LEN];
    t[Host::Space as usize] = light_space as *const ();
    t
});

/// The entries of [`LIGHT_HOST_TABLE`].
struct LightHostTable([*const (); Host::LEN]);

// SAFETY: function pointers, never written.
unsafe impl Sync for LightHostTable {}

/// [`LIGHT_HOST_TABLE`] as compiled code reads it.
#[must_use]
pub fn light_host_table() -> *const usize {
    LIGHT_HOST_TABLE.0.as_ptr().cast()
}

unsafe extern "C" fn light_no_host(_: *mut c_void, _: *const u32, _: *const f32, _: *mut f32, _: u32) {}

unsafe extern "C" fn light_space(ctx: *mut c_void, _: *const u32, inp: *const f32, out: *mut f32, aux: u32) {
    space_matrix(&*ctx.cast::<Spaces>(), inp, out, aux);
}

/// The matrix of a named space (`aux`: `rt::SPACE_*` and the name's length; `inp`: the name)
/// into `out` (16 floats).
unsafe fn space_matrix(spaces: &Spaces, inp: *const f32, out: *mut f32, aux: u32) {
    let bytes = core::slice::from_raw_parts(inp.cast::<u8>(), (aux >> 2) as usize);
    let name = core::str::from_utf8(bytes).unwrap_or("");
    let m = match aux & 3 {
        SPACE_TO_CURRENT => spaces.to_current_f64(name),
        SPACE_FROM_CURRENT => spaces.from_current_f64(name),
        _ => {
            let (from, to) = name.split_once(SPACE_SEPARATOR).unwrap_or((name, "current"));
            spaces.between_f64(from, to)
        }
    };
    for (i, x) in m.iter().enumerate() {
        *out.add(i) = *x as f32;
    }
}

/// Reinterprets a value of one type as another type that is the same type (checked by
/// `TypeId`): how code generic in the shading float reaches the layout of its `JitFloat`.
#[inline(always)]
pub fn cast<A: 'static, B: 'static>(a: A) -> B {
    assert!(core::any::TypeId::of::<A>() == core::any::TypeId::of::<B>(), "cast between different types");
    // SAFETY: A and B are the same type.
    unsafe { core::mem::transmute_copy::<A, B>(&core::mem::ManuallyDrop::new(a)) }
}

/// [`In`] for host shims: reads `G` values and hands them out as `F` (the same type).
struct HIn<F, G> {
    i: In<G>,
    _f: PhantomData<F>,
}

impl<F: ShadingFloat, G: JitFloat> HIn<F, G> {
    #[inline(always)]
    fn new(p: *const f32) -> Self {
        Self { i: In::new(p), _f: PhantomData }
    }
    #[inline(always)]
    unsafe fn f(&mut self) -> F {
        cast::<G, F>(self.i.f())
    }
    #[inline(always)]
    unsafe fn v3(&mut self) -> Vec3<F> {
        let x = self.f();
        let y = self.f();
        let z = self.f();
        Vec3::new(x, y, z)
    }
}

/// [`Out`] for host shims.
struct HOut<F, G> {
    o: Out<G>,
    _f: PhantomData<F>,
}

impl<F: ShadingFloat, G: JitFloat> HOut<F, G> {
    #[inline(always)]
    fn new(p: *mut f32) -> Self {
        Self { o: Out::new(p), _f: PhantomData }
    }
    #[inline(always)]
    unsafe fn f(&mut self, v: F) {
        self.o.f(cast::<F, G>(v));
    }
    #[inline(always)]
    unsafe fn v3(&mut self, v: Vec3<F>) {
        self.f(v.x);
        self.f(v.y);
        self.f(v.z);
    }
    #[inline(always)]
    unsafe fn c3(&mut self, c: Color<F>) {
        self.f(c.r);
        self.f(c.g);
        self.f(c.b);
    }
}
