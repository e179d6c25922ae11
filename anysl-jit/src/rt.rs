//! The runtime half of the target library: built-ins too large to inline (noise, the
//! transcendental functions, splines, matrices, …), written once and generic over the float
//! type, and the host shims that give compiled code the renderer's `ShadingContext`.
//!
//! Every function here calls the same `anysl-core` standard library as the hand-written
//! generic shaders, the generated Rust and the interpreter, so all back ends compute the same
//! functions. Each has the [`RtFn`] signature; `aux` selects the variant (see the `*_OP`
//! constants used by the code generator).

use crate::abi::{BodyFn, JitFloat, RtFn};
use anysl_core::prelude::*;
use core::ffi::c_void;
use core::marker::PhantomData;
use core::mem::MaybeUninit;

/// Reads consecutive values from a callback's input buffer.
struct In<F> {
    p: *const f32,
    _f: PhantomData<F>,
}

impl<F: JitFloat> In<F> {
    #[inline(always)]
    fn new(p: *const f32) -> Self {
        Self { p, _f: PhantomData }
    }
    #[inline(always)]
    unsafe fn f(&mut self) -> F {
        let v = F::read(self.p);
        self.p = self.p.add(F::STRIDE);
        v
    }
    #[inline(always)]
    unsafe fn v3(&mut self) -> Vec3<F> {
        let x = self.f();
        let y = self.f();
        let z = self.f();
        Vec3::new(x, y, z)
    }
    #[inline(always)]
    unsafe fn c3(&mut self) -> Color<F> {
        let v = self.v3();
        Color::new(v.x, v.y, v.z)
    }
    #[inline(always)]
    unsafe fn m4(&mut self) -> Matrix4<F> {
        let mut m = Matrix4::identity();
        for i in 0..4 {
            for j in 0..4 {
                m.m[i][j] = self.f();
            }
        }
        m
    }
}

/// Writes consecutive values to a callback's output buffer.
struct Out<F> {
    p: *mut f32,
    _f: PhantomData<F>,
}

impl<F: JitFloat> Out<F> {
    #[inline(always)]
    fn new(p: *mut f32) -> Self {
        Self { p, _f: PhantomData }
    }
    #[inline(always)]
    unsafe fn f(&mut self, v: F) {
        v.write(self.p);
        self.p = self.p.add(F::STRIDE);
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
    #[inline(always)]
    unsafe fn m4(&mut self, m: &Matrix4<F>) {
        for i in 0..4 {
            for j in 0..4 {
                self.f(m.m[i][j]);
            }
        }
    }
}

/// A `#[repr(u32)]` selector: the `aux` values of one runtime family. `from_aux` decodes a
/// selector (the functions `match` on it with no catch-all arm); `special_addr` is the copy
/// of the family's function compiled for one selector ([`rt_addr`]).
macro_rules! selector {
    ($(#[$doc:meta])* $name:ident, $special:ident { $($v:ident = $n:literal,)* }) => {
        $(#[$doc])*
        #[allow(missing_docs)]
        #[repr(u32)]
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum $name {
            $($v = $n,)*
        }

        impl $name {
            /// Every selector of the family.
            pub const ALL: &'static [$name] = &[$($name::$v,)*];

            /// The selector `aux` encodes (`None` for a value no selector has).
            #[must_use]
            pub const fn from_aux(aux: u32) -> Option<Self> {
                match aux {
                    $($n => Some(Self::$v),)*
                    _ => None,
                }
            }

            /// The family's function compiled for selector `aux`, when `aux` is one.
            fn special_addr<F: JitFloat>(aux: u32) -> Option<usize> {
                match aux {
                    $($n => Some($special::<F, $n> as RtFn as usize),)*
                    _ => None,
                }
            }
        }
    };
}

selector!(
    /// Unary functions (`aux` of [`rt_un`]).
    Un, rt_un_k {
        Sin = 0,
        Cos = 1,
        Tan = 2,
        Asin = 3,
        Acos = 4,
        Atan = 5,
        Exp = 6,
        Log = 7,
        Sign = 8,
        Round = 9,
        Radians = 10,
        Degrees = 11,
        InvSqrt = 12,
        Sqrt = 13,
        Floor = 14,
        Ceil = 15,
        Abs = 16,
    }
);

selector!(
    /// Binary and ternary functions (`aux` of [`rt_bin`]).
    Bin, rt_bin_k {
        Pow = 0,
        Atan2 = 1,
        LogBase = 2,
        Mod = 3,
        Min = 4,
        Max = 5,
        Step = 6,
        SmoothStep = 7,
        Clamp = 8,
        Mix = 9,
        FilterStep = 10,
        FilterStep3 = 11,
    }
);

selector!(
    /// Geometric functions (`aux & 0xff` of [`rt_geo`]); `CTransform` takes
    /// `aux = CTransform | from << 8 | to << 16` (indices into [`COLOR_SPACES`]).
    Geo, rt_geo_k {
        Length = 0,
        Normalize = 1,
        Distance = 2,
        FaceForward = 3,
        Reflect = 4,
        Refract = 5,
        Fresnel = 6,
        PtLineD = 7,
        Rotate = 8,
        SpecularBrdf = 9,
        Area = 10,
        FilterWidthP = 11,
        FilterWidth = 12,
        MatMul = 13,
        MatDiv = 14,
        Determinant = 15,
        Translate = 17,
        RotateM = 18,
        ScaleM = 19,
        XformPoint = 20,
        XformVector = 21,
        XformNormal = 22,
        CTransform = 23,
    }
);

/// Noise kinds (the `kind` of a [`NoiseSel`]).
#[allow(missing_docs)]
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoiseOp {
    Noise = 0,
    SNoise = 1,
    Cell = 2,
    PNoise = 3,
    PSNoise = 4,
    Fbm = 5,
    Turbulence = 6,
}

impl NoiseOp {
    /// Every kind.
    pub const ALL: [NoiseOp; 7] =
        [Self::Noise, Self::SNoise, Self::Cell, Self::PNoise, Self::PSNoise, Self::Fbm, Self::Turbulence];
}

/// The selector of a [`rt_noise`] call: `aux = kind | dims << 4 | out << 8 | extra << 12`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NoiseSel {
    /// The function.
    pub kind: NoiseOp,
    /// Dimensions of the domain, 1–4.
    pub dims: u32,
    /// Output components, 1 or 3.
    pub out: u32,
    /// fBm and turbulence: how many of the octaves/lacunarity/gain arguments follow, 0–3.
    pub extra: u32,
}

impl NoiseSel {
    /// The `aux` value.
    #[must_use]
    pub const fn encode(self) -> u32 {
        self.kind as u32 | self.dims << 4 | self.out << 8 | self.extra << 12
    }

    /// The selector `aux` encodes (`None` for an unknown kind).
    #[must_use]
    pub const fn decode(aux: u32) -> Option<Self> {
        let kind = match aux & 0xf {
            0 => NoiseOp::Noise,
            1 => NoiseOp::SNoise,
            2 => NoiseOp::Cell,
            3 => NoiseOp::PNoise,
            4 => NoiseOp::PSNoise,
            5 => NoiseOp::Fbm,
            6 => NoiseOp::Turbulence,
            _ => return None,
        };
        Some(Self { kind, dims: (aux >> 4) & 0xf, out: (aux >> 8) & 0xf, extra: (aux >> 12) & 0xf })
    }
}

/// Colour-space names by index (for `aux`).
pub const COLOR_SPACES: [&str; 6] = ["rgb", "hsv", "hsl", "xyz", "xyY", "YIQ"];
/// Spline basis names by index (for `aux`).
pub const SPLINE_BASES: [&str; 6] = ["catmull-rom", "bezier", "bspline", "hermite", "power", "linear"];

/// A runtime function family: `$general` reads its selector from `aux`; `$special::<F, AUX>`
/// is the copy compiled for one selector ([`rt_addr`]); both run `$op`.
macro_rules! rt_family {
    ($(#[$doc:meta])* $general:ident, $special:ident, $op:ident) => {
        $(#[$doc])*
        ///
        /// # Safety
        /// `inp` holds the arguments and `out` has room for the results that `aux` selects, as
        /// consecutive `F` values (`F::STRIDE` floats each); the context and mask are not read.
        pub unsafe extern "C" fn $general<F: JitFloat>(
            _: *mut c_void,
            _: *const u32,
            inp: *const f32,
            out: *mut f32,
            aux: u32,
        ) {
            $op::<F>(inp, out, aux);
        }

        #[doc = concat!("[`", stringify!($general), "`] for one `aux` known when the shader is compiled.")]
        unsafe extern "C" fn $special<F: JitFloat, const AUX: u32>(
            _: *mut c_void,
            _: *const u32,
            inp: *const f32,
            out: *mut f32,
            _: u32,
        ) {
            $op::<F>(inp, out, AUX);
        }
    };
}

rt_family!(
    /// Unary math, component-wise on one value.
    rt_un, rt_un_k, un_op
);

#[inline(always)]
unsafe fn un_op<F: JitFloat>(inp: *const f32, out: *mut f32, aux: u32) {
    let x = In::<F>::new(inp).f();
    let r = match Un::from_aux(aux) {
        Some(Un::Sin) => x.sin(),
        Some(Un::Cos) => x.cos(),
        Some(Un::Tan) => x.tan(),
        Some(Un::Asin) => x.asin(),
        Some(Un::Acos) => x.acos(),
        Some(Un::Atan) => x.atan(),
        Some(Un::Exp) => x.exp(),
        Some(Un::Log) => x.ln(),
        Some(Un::Sign) => sign(x),
        Some(Un::Round) => x.round(),
        Some(Un::Radians) => radians(x),
        Some(Un::Degrees) => degrees(x),
        Some(Un::InvSqrt) => inversesqrt(x),
        Some(Un::Sqrt) => x.sqrt(),
        Some(Un::Floor) => x.floor(),
        Some(Un::Ceil) => x.ceil(),
        Some(Un::Abs) => x.abs(),
        None => F::c(f64::NAN),
    };
    Out::<F>::new(out).f(r);
}

/// std's `f32` sine, cosine or tangent (`aux & 0xff`: [`Un::Sin`], [`Un::Cos`], [`Un::Tan`])
/// of the lanes that `mask` selects, out of `aux >> 8` lanes (the others are copied): the path
/// of the inline trigonometry for arguments beyond the vector reduction's range, as the
/// SIMD types take it.
///
/// # Safety
/// `mask`, `inp` and `out` each hold `aux >> 8` lanes.
pub unsafe extern "C" fn rt_trig_lanes(_: *mut c_void, mask: *const u32, inp: *const f32, out: *mut f32, aux: u32) {
    let f: fn(f32) -> f32 = match Un::from_aux(aux & 0xff) {
        Some(Un::Sin) => f32::sin,
        Some(Un::Cos) => f32::cos,
        Some(Un::Tan) => f32::tan,
        _ => |_| f32::NAN,
    };
    for i in 0..(aux >> 8) as usize {
        let x = *inp.add(i);
        *out.add(i) = if *mask.add(i) != 0 { f(x) } else { x };
    }
}

rt_family!(
    /// Binary and ternary math on floats.
    rt_bin, rt_bin_k, bin_op
);

#[inline(always)]
unsafe fn bin_op<F: JitFloat>(inp: *const f32, out: *mut f32, aux: u32) {
    let mut i = In::<F>::new(inp);
    let a = i.f();
    let b = i.f();
    let r = match Bin::from_aux(aux) {
        Some(Bin::Pow) => a.pow(b),
        Some(Bin::Atan2) => a.atan2(b),
        Some(Bin::LogBase) => log_base(a, b),
        Some(Bin::Mod) => fmod(a, b),
        Some(Bin::Min) => a.min(b),
        Some(Bin::Max) => a.max(b),
        Some(Bin::Step) => step(a, b),
        Some(Bin::SmoothStep) => smoothstep(a, b, i.f()),
        Some(Bin::Clamp) => clamp(a, b, i.f()),
        Some(Bin::Mix) => mix(a, b, i.f()),
        Some(Bin::FilterStep) => filterstep(a, b),
        Some(Bin::FilterStep3) => {
            // filterstep(edge, s0, s1): box over [s0, s1] (as the interpreter).
            let (e, s0, s1) = (a, b, i.f());
            let lo = s0.min(s1);
            let wdt = (s1 - s0).abs();
            let t = clamp((lo + wdt - e) / wdt.max(F::c(1e-30)), F::c(0.0), F::c(1.0));
            F::select(wdt.gt(F::c(0.0)), t, step(e, s0))
        }
        None => F::c(f64::NAN),
    };
    Out::<F>::new(out).f(r);
}

rt_family!(
    /// Geometry, matrices and colour spaces.
    rt_geo, rt_geo_k, geo_op
);

#[inline(always)]
unsafe fn geo_op<F: JitFloat>(inp: *const f32, out: *mut f32, aux: u32) {
    let mut i = In::<F>::new(inp);
    let mut o = Out::<F>::new(out);
    match Geo::from_aux(aux & 0xff) {
        Some(Geo::Length) => o.f(i.v3().length()),
        Some(Geo::Normalize) => o.v3(i.v3().normalize()),
        Some(Geo::Distance) => {
            let a = i.v3();
            o.f(distance(a, i.v3()));
        }
        Some(Geo::FaceForward) => {
            let (n, ii) = (i.v3(), i.v3());
            o.v3(faceforward(n, ii, i.v3()));
        }
        Some(Geo::Reflect) => {
            let a = i.v3();
            o.v3(reflect(a, i.v3()));
        }
        Some(Geo::Refract) => {
            let (a, n) = (i.v3(), i.v3());
            o.v3(refract(a, n, i.f()));
        }
        Some(Geo::Fresnel) => {
            let (a, n) = (i.v3(), i.v3());
            let r = fresnel(a, n, i.f());
            o.f(r.kr);
            o.f(r.kt);
            o.v3(r.r);
            o.v3(r.t);
        }
        Some(Geo::PtLineD) => {
            let (a, b) = (i.v3(), i.v3());
            o.f(ptlined(a, b, i.v3()));
        }
        Some(Geo::Rotate) => {
            let (q, ang, p0) = (i.v3(), i.f(), i.v3());
            o.v3(rotate(q, ang, p0, i.v3()));
        }
        Some(Geo::SpecularBrdf) => {
            let (l, n, v) = (i.v3(), i.v3(), i.v3());
            let r = specularbrdf(l, n, v, i.f());
            o.v3(Vec3::splat(r));
        }
        Some(Geo::Area) => o.f(area(i.v3())),
        Some(Geo::FilterWidthP) => o.f(filterwidth_point(i.v3())),
        Some(Geo::FilterWidth) => o.f(filterwidth(i.f())),
        Some(Geo::MatMul | Geo::MatDiv) => {
            let a = i.m4();
            let b = i.m4();
            let b = if aux & 0xff == Geo::MatDiv as u32 { b.inverse() } else { b };
            o.m4(&(a * b));
        }
        Some(Geo::Determinant) => o.f(i.m4().determinant()),
        Some(Geo::Translate) => {
            let m = i.m4();
            o.m4(&(m * Matrix4::translate(i.v3())));
        }
        Some(Geo::RotateM) => {
            let m = i.m4();
            let a = i.f();
            o.m4(&(m * Matrix4::rotate(a, i.v3())));
        }
        Some(Geo::ScaleM) => {
            let m = i.m4();
            o.m4(&(m * Matrix4::scale(i.v3())));
        }
        Some(Geo::XformPoint) => {
            let m = i.m4();
            o.v3(m.transform_point(i.v3()));
        }
        Some(Geo::XformVector) => {
            let m = i.m4();
            o.v3(m.transform_vector(i.v3()));
        }
        Some(Geo::XformNormal) => {
            let m = i.m4();
            o.v3(m.transform_normal(i.v3()));
        }
        Some(Geo::CTransform) => {
            let c = i.c3();
            let space = |k: u32| COLOR_SPACES.get(k as usize).and_then(|n| ColorSpace::from_name(n));
            let r = match (space((aux >> 8) & 0xff), space((aux >> 16) & 0xff)) {
                (Some(f), Some(t)) => ctransform(f, t, c),
                _ => c,
            };
            o.c3(r);
        }
        None => {}
    }
}

unsafe fn domain<F: JitFloat>(i: &mut In<F>, dims: u32) -> NoiseDomain<F> {
    match dims {
        1 => NoiseDomain::D1(i.f()),
        2 => {
            let x = i.f();
            NoiseDomain::D2(x, i.f())
        }
        3 => NoiseDomain::D3(i.v3()),
        _ => {
            let p = i.v3();
            NoiseDomain::D4(p, i.f())
        }
    }
}

rt_family!(
    /// The noise family, fBm and turbulence.
    rt_noise, rt_noise_k, noise_op
);

#[inline(always)]
unsafe fn noise_op<F: JitFloat>(inp: *const f32, out: *mut f32, aux: u32) {
    let mut i = In::<F>::new(inp);
    let mut o = Out::<F>::new(out);
    let Some(NoiseSel { kind, dims, out: w, extra }) = NoiseSel::decode(aux) else {
        return;
    };
    let d = domain(&mut i, dims);
    // Up to three dimensions the noise is Perlin's 3D noise; for types without derivatives
    // its kernel is inlined here (`snoise_inlined`): this function already is the one
    // compiled copy for its selector, and calling the kernel out of line would add a call
    // and copies of its arguments. Same values as the library functions.
    let inlined = !F::DUAL && dims <= 3;
    match kind {
        NoiseOp::Noise | NoiseOp::SNoise if inlined => {
            let signed = kind == NoiseOp::SNoise;
            // The noise inlined like the kernel: a closure here was left out of line in one
            // build of this crate and x16 noise ran 7x slower.
            #[inline(always)]
            fn one<F: JitFloat>(d: NoiseDomain<F>, seed: u32, signed: bool) -> F {
                let s = snoise_inlined(d, seed);
                if signed {
                    s
                } else {
                    unsigned_noise(s)
                }
            }
            let n = |seed| one(d, seed, signed);
            if w == 1 {
                o.f(n(0));
            } else {
                o.v3(noise_vector(n));
            }
        }
        NoiseOp::Noise | NoiseOp::SNoise => {
            let signed = kind == NoiseOp::SNoise;
            if w == 1 {
                o.f(if signed { snoise(d) } else { anysl_core::prelude::noise(d) });
            } else {
                o.v3(if signed { vsnoise(d) } else { vnoise(d) });
            }
        }
        NoiseOp::Cell => {
            if w == 1 {
                o.f(cellnoise(d));
            } else {
                o.v3(vcellnoise(d));
            }
        }
        NoiseOp::PNoise | NoiseOp::PSNoise => {
            let per = domain(&mut i, dims);
            let signed = kind == NoiseOp::PSNoise;
            if w == 1 {
                o.f(if signed { psnoise(d, per) } else { pnoise(d, per) });
            } else {
                let v = vpnoise(d, per);
                o.v3(if signed { v * F::c(2.0) - Vec3::splat(F::c(1.0)) } else { v });
            }
        }
        NoiseOp::Fbm | NoiseOp::Turbulence => {
            let mut get = |k: u32, dflt: f64| if extra > k { i.f().lane(0) } else { dflt };
            let oct = get(0, 6.0).max(0.0) as u32;
            let lac = get(1, 2.0);
            let gain = get(2, 0.5);
            o.f(match (kind == NoiseOp::Fbm, inlined) {
                (true, true) => octave_sum(
                    d,
                    oct,
                    lac,
                    gain,
                    #[inline(always)]
                    |d| snoise_inlined(d, 0),
                ),
                (false, true) => octave_sum(
                    d,
                    oct,
                    lac,
                    gain,
                    #[inline(always)]
                    |d| snoise_inlined(d, 0).abs(),
                ),
                (true, false) => fbm(d, oct, lac, gain),
                (false, false) => turbulence(d, oct, lac, gain),
            });
        }
    }
}

/// `spline([basis,] x, knots…)`: `aux = n | basis << 8 | w << 16`.
///
/// # Safety
/// `inp` holds the arguments and `out` has room for the results that `aux` selects, as
/// consecutive `F` values (`F::STRIDE` floats each); the context and mask are not read.
pub unsafe extern "C" fn rt_spline<F: JitFloat>(
    _: *mut c_void,
    _: *const u32,
    inp: *const f32,
    out: *mut f32,
    aux: u32,
) {
    spline_op::<F>(inp, out, aux, aux >> 8);
}

/// [`rt_spline`] with basis and width (`aux >> 8`) known when the shader is compiled; the
/// number of knots still comes from `aux`.
unsafe extern "C" fn rt_spline_k<F: JitFloat, const BW: u32>(
    _: *mut c_void,
    _: *const u32,
    inp: *const f32,
    out: *mut f32,
    aux: u32,
) {
    spline_op::<F>(inp, out, aux, BW);
}

/// The bases of [`SPLINE_BASES`], by index.
const BASES: [SplineBasis; 6] = [
    SplineBasis::CATMULL_ROM,
    SplineBasis::BEZIER,
    SplineBasis::BSPLINE,
    SplineBasis::HERMITE,
    SplineBasis::POWER,
    SplineBasis::LINEAR,
];

#[inline(always)]
unsafe fn spline_op<F: JitFloat>(inp: *const f32, out: *mut f32, aux: u32, bw: u32) {
    let mut i = In::<F>::new(inp);
    let mut o = Out::<F>::new(out);
    let n = (aux & 0xff) as usize;
    let b = BASES.get((bw & 0xff) as usize).copied().unwrap_or(SplineBasis::CATMULL_ROM);
    let w = (bw >> 8) & 0xff;
    let x = i.f();
    // The knots are read into uninitialized stack space: zeroing 64 colour knots (6 KiB at
    // 8 lanes) per call cost more than the spline itself.
    let n = n.min(MAX_KNOTS);
    if w == 1 {
        let mut knots = [const { MaybeUninit::<F>::uninit() }; MAX_KNOTS];
        for k in knots.iter_mut().take(n) {
            k.write(i.f());
        }
        // SAFETY: the first `n` knots were written just above.
        o.f(spline(&b, x, unsafe { assume_init(&knots[..n]) }));
    } else {
        let mut knots = [const { MaybeUninit::<Vec3<F>>::uninit() }; MAX_KNOTS];
        for k in knots.iter_mut().take(n) {
            k.write(i.v3());
        }
        // SAFETY: the first `n` knots were written just above.
        o.v3(spline(&b, x, unsafe { assume_init(&knots[..n]) }));
    }
}

/// Most knots a compiled `spline` call passes (the code generator checks).
pub const MAX_KNOTS: usize = 64;

/// `s` as initialized values.
///
/// # Safety
/// Every element of `s` is initialized.
unsafe fn assume_init<T>(s: &[MaybeUninit<T>]) -> &[T] {
    // SAFETY: `MaybeUninit<T>` has `T`'s layout and the caller vouches for initialization.
    unsafe { &*(s as *const [MaybeUninit<T>] as *const [T]) }
}

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
        Self { lights, n_lights, ctx, lit: None }
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
    let spaces = (*ctx.cast::<HostCtx<F, C>>()).ctx.spaces();
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

/// The context-free runtime functions for float type `F`, in the order of [`RtKind`].
#[must_use]
pub fn rt_table<F: JitFloat>() -> [RtFn; 5] {
    [rt_un::<F>, rt_bin::<F>, rt_geo::<F>, rt_noise::<F>, rt_spline::<F>]
}

/// The runtime function for a call of `kind` with `aux`, as an address: for the `aux`
/// values shaders use, a copy of the function compiled for that one `aux` (no dispatch on
/// it at run time, and only that variant's stack frame); for the rest, the general function
/// of [`rt_table`].
///
/// The copies exist for the 8- and 16-lane float types only (`F32x8`, `F32x16`, and so the
/// multi-packet variants, which call them per packet): those are the variants whose speed is
/// measured against the compiled build. Each copy inlines its whole kernel (noise above all),
/// so every float type with copies adds about a minute to this crate's release build
/// (docs/build.md, "Where the time goes"); the other types get the general functions.
#[must_use]
pub fn rt_addr<F: JitFloat>(kind: RtKind, aux: u32) -> usize {
    // `k!(f, [c…])` returns `f::<F, c>` when `aux == c`.
    macro_rules! k {
        ($f:ident, $a:expr, [$($c:expr),* $(,)?]) => {
            { $( if $a == $c { return $f::<F, { $c }> as RtFn as usize; } )* }
        };
    }
    // Noise of one kind over 1–4 dimensions, float or triple.
    macro_rules! noise {
        ($kind:expr) => {
            k!(
                rt_noise_k,
                aux,
                [
                    NoiseSel { kind: $kind, dims: 1, out: 1, extra: 0 }.encode(),
                    NoiseSel { kind: $kind, dims: 2, out: 1, extra: 0 }.encode(),
                    NoiseSel { kind: $kind, dims: 3, out: 1, extra: 0 }.encode(),
                    NoiseSel { kind: $kind, dims: 4, out: 1, extra: 0 }.encode(),
                    NoiseSel { kind: $kind, dims: 1, out: 3, extra: 0 }.encode(),
                    NoiseSel { kind: $kind, dims: 2, out: 3, extra: 0 }.encode(),
                    NoiseSel { kind: $kind, dims: 3, out: 3, extra: 0 }.encode(),
                    NoiseSel { kind: $kind, dims: 4, out: 3, extra: 0 }.encode(),
                ]
            )
        };
    }
    // fBm or turbulence over 1 or 3 dimensions with 0–3 of its optional arguments.
    macro_rules! fractal {
        ($kind:expr) => {
            k!(
                rt_noise_k,
                aux,
                [
                    NoiseSel { kind: $kind, dims: 1, out: 1, extra: 0 }.encode(),
                    NoiseSel { kind: $kind, dims: 1, out: 1, extra: 1 }.encode(),
                    NoiseSel { kind: $kind, dims: 1, out: 1, extra: 2 }.encode(),
                    NoiseSel { kind: $kind, dims: 1, out: 1, extra: 3 }.encode(),
                    NoiseSel { kind: $kind, dims: 3, out: 1, extra: 0 }.encode(),
                    NoiseSel { kind: $kind, dims: 3, out: 1, extra: 1 }.encode(),
                    NoiseSel { kind: $kind, dims: 3, out: 1, extra: 2 }.encode(),
                    NoiseSel { kind: $kind, dims: 3, out: 1, extra: 3 }.encode(),
                ]
            )
        };
    }
    // `if const`: the copies are not even instantiated for the other types.
    if const { F::LANES >= 8 && !F::DUAL } {
        let special = match kind {
            RtKind::Un => Un::special_addr::<F>(aux),
            RtKind::Bin => Bin::special_addr::<F>(aux),
            // Colour transforms carry their spaces in `aux`: the general function.
            RtKind::Geo if aux & 0xff == Geo::CTransform as u32 => None,
            RtKind::Geo => Geo::special_addr::<F>(aux),
            RtKind::Noise => {
                noise!(NoiseOp::Noise);
                noise!(NoiseOp::SNoise);
                noise!(NoiseOp::Cell);
                noise!(NoiseOp::PNoise);
                noise!(NoiseOp::PSNoise);
                fractal!(NoiseOp::Fbm);
                fractal!(NoiseOp::Turbulence);
                None
            }
            RtKind::Spline => {
                let bw = aux >> 8;
                k!(
                    rt_spline_k,
                    bw,
                    [
                        0 | 1 << 8,
                        1 | 1 << 8,
                        2 | 1 << 8,
                        3 | 1 << 8,
                        4 | 1 << 8,
                        5 | 1 << 8,
                        0 | 3 << 8,
                        1 | 3 << 8,
                        2 | 3 << 8,
                        3 | 3 << 8,
                        4 | 3 << 8,
                        5 | 3 << 8,
                    ]
                );
                None
            }
        };
        if let Some(a) = special {
            return a;
        }
    }
    rt_table::<F>()[kind as usize] as usize
}

/// Which runtime function (index into [`rt_table`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RtKind {
    /// [`rt_un`]
    Un = 0,
    /// [`rt_bin`]
    Bin = 1,
    /// [`rt_geo`]
    Geo = 2,
    /// [`rt_noise`]
    Noise = 3,
    /// [`rt_spline`]
    Spline = 4,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The compiled code reads the lights at fixed offsets of `HostCtx` and each light's
    /// fields at the offsets of `LightData` (taken from the type itself).
    #[test]
    fn host_ctx_lights_are_where_the_compiled_code_reads_them() {
        use core::mem::offset_of;
        type H = HostCtx<'static, anysl_simd::F32x8, ()>;
        assert_eq!(offset_of!(H, lights) as u64, HOST_CTX_LIGHTS);
        assert_eq!(offset_of!(H, n_lights) as u64, HOST_CTX_N_LIGHTS);
        type H1 = HostCtx<'static, f32, ()>;
        assert_eq!(offset_of!(H1, lights) as u64, HOST_CTX_LIGHTS);
        assert_eq!(offset_of!(H1, n_lights) as u64, HOST_CTX_N_LIGHTS);
    }

    #[test]
    fn spline_bases_by_index_are_the_named_ones() {
        for (i, name) in SPLINE_BASES.iter().enumerate() {
            assert_eq!(Some(BASES[i]), SplineBasis::from_name(name), "{name}");
        }
    }

    #[test]
    fn specialized_runtime_functions_compute_what_the_general_ones_do() {
        // Every specialized (kind, aux) against the general function on the same input, for
        // 8 lanes (the copies exist for 8 and 16 lanes without derivatives).
        type X = anysl_simd::F32x8;
        let n = X::STRIDE;
        let inp: Vec<f32> = (0..64 * n).map(|k| 0.37 + 0.61 * (k / n) as f32 + 0.001 * (k % n) as f32).collect();
        let mut cases: Vec<(RtKind, u32)> = Vec::new();
        cases.extend(Un::ALL.iter().map(|&a| (RtKind::Un, a as u32)));
        cases.extend(Bin::ALL.iter().map(|&a| (RtKind::Bin, a as u32)));
        cases.extend(Geo::ALL.iter().filter(|&&a| a != Geo::CTransform).map(|&a| (RtKind::Geo, a as u32)));
        for kind in [NoiseOp::Noise, NoiseOp::SNoise, NoiseOp::Cell, NoiseOp::PNoise, NoiseOp::PSNoise] {
            for dims in 1..=4 {
                for out in [1, 3] {
                    cases.push((RtKind::Noise, NoiseSel { kind, dims, out, extra: 0 }.encode()));
                }
            }
        }
        for kind in [NoiseOp::Fbm, NoiseOp::Turbulence] {
            for dims in [1, 3] {
                cases.push((RtKind::Noise, NoiseSel { kind, dims, out: 1, extra: 2 }.encode()));
            }
        }
        for b in 0..6 {
            for w in [1, 3] {
                cases.push((RtKind::Spline, 5 | b << 8 | w << 16));
            }
        }
        let mut specialized = 0;
        for (kind, aux) in cases {
            // Other types have no copies: every call gets the general function.
            assert_eq!(rt_addr::<f32>(kind, aux), rt_table::<f32>()[kind as usize] as usize);
            assert_eq!(
                rt_addr::<anysl_ad::Dual<X>>(kind, aux),
                rt_table::<anysl_ad::Dual<X>>()[kind as usize] as usize
            );
            let general = rt_table::<X>()[kind as usize];
            let addr = rt_addr::<X>(kind, aux);
            if addr != general as usize {
                specialized += 1;
            }
            // SAFETY: `addr` is an `RtFn` (it comes from `rt_addr`).
            let f: RtFn = unsafe { core::mem::transmute::<usize, RtFn>(addr) };
            let (mut a, mut b) = (vec![0f32; 16 * n], vec![0f32; 16 * n]);
            unsafe {
                general(core::ptr::null_mut(), core::ptr::null(), inp.as_ptr(), a.as_mut_ptr(), aux);
                f(core::ptr::null_mut(), core::ptr::null(), inp.as_ptr(), b.as_mut_ptr(), aux);
            }
            let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&a), bits(&b), "{kind:?} aux {aux:#x}");
        }
        assert!(specialized > 100, "only {specialized} calls have their own function");
        // A call without a specialized copy gets the general function.
        assert_eq!(
            rt_addr::<X>(RtKind::Geo, Geo::CTransform as u32 | 1 << 8),
            rt_table::<X>()[RtKind::Geo as usize] as usize
        );
    }

    /// The runtime noise, whose kernel is inlined for types without derivatives, gives the
    /// library's noise bit for bit (f32 and 8 lanes; 1–3 dimensions; float and vector;
    /// fBm and turbulence), including non-finite and huge coordinates.
    #[test]
    fn inlined_runtime_noise_is_the_library_noise() {
        fn run<F: JitFloat>(aux: u32, args: &[F], outs: usize) -> Vec<F> {
            let mut inp = vec![0f32; 8 * F::STRIDE];
            for (k, a) in args.iter().enumerate() {
                unsafe { a.write(inp.as_mut_ptr().add(k * F::STRIDE)) };
            }
            let mut out = vec![0f32; 3 * F::STRIDE];
            let f: RtFn = unsafe { core::mem::transmute::<usize, RtFn>(rt_addr::<F>(RtKind::Noise, aux)) };
            unsafe { f(core::ptr::null_mut(), core::ptr::null(), inp.as_ptr(), out.as_mut_ptr(), aux) };
            (0..outs).map(|k| unsafe { F::read(out.as_ptr().add(k * F::STRIDE)) }).collect()
        }
        fn bits<F: ShadingFloat>(v: &[F]) -> Vec<u64> {
            v.iter().flat_map(|x| (0..F::LANES).map(|l| x.lane(l).to_bits())).collect()
        }
        fn check<F: JitFloat>(x: F, y: F, z: F) {
            let p = Vec3::new(x, y, z);
            let doms = [NoiseDomain::D1(x), NoiseDomain::D2(x, y), NoiseDomain::D3(p)];
            for (k, d) in doms.into_iter().enumerate() {
                let dims = k as u32 + 1;
                let args = [x, y, z];
                let a = &args[..k + 1];
                let sel = |kind: NoiseOp, out: u32| NoiseSel { kind, dims, out, extra: 0 }.encode();
                let v3 = |v: Vec3<F>| vec![v.x, v.y, v.z];
                let cases: [(u32, Vec<F>, Vec<F>); 4] = [
                    (sel(NoiseOp::SNoise, 1), run(sel(NoiseOp::SNoise, 1), a, 1), vec![snoise(d)]),
                    (sel(NoiseOp::Noise, 1), run(sel(NoiseOp::Noise, 1), a, 1), vec![anysl_core::prelude::noise(d)]),
                    (sel(NoiseOp::SNoise, 3), run(sel(NoiseOp::SNoise, 3), a, 3), v3(vsnoise(d))),
                    (sel(NoiseOp::Noise, 3), run(sel(NoiseOp::Noise, 3), a, 3), v3(vnoise(d))),
                ];
                for (aux, got, want) in cases {
                    assert_eq!(bits(&got), bits(&want), "{} aux {aux:#x}", F::NAME);
                }
                let mut with_opts = a.to_vec();
                with_opts.extend([F::c(4.0), F::c(2.5), F::c(0.375)]);
                for (kind, want) in
                    [(NoiseOp::Fbm, fbm(d, 4, 2.5, 0.375)), (NoiseOp::Turbulence, turbulence(d, 4, 2.5, 0.375))]
                {
                    let aux = NoiseSel { kind, dims, out: 1, extra: 3 }.encode();
                    assert_eq!(bits(&run(aux, &with_opts, 1)), bits(&[want]), "{} aux {aux:#x}", F::NAME);
                }
            }
        }
        let vals = [0.37f32, -5.25, 1.0e7, -3.0e-39, 12.5, f32::NAN, f32::INFINITY, 0.0];
        for (i, &x) in vals.iter().enumerate() {
            let (y, z) = (vals[(i + 3) % vals.len()], vals[(i + 5) % vals.len()]);
            check::<f32>(x, y * 0.7 + 0.1, z * 1.3 - 0.2);
        }
        let lanes = |o: usize| {
            let l: Vec<f64> = (0..8).map(|l| f64::from(vals[(l + o) % vals.len()] * (1.0 + 0.1 * o as f32))).collect();
            anysl_simd::F32x8::from_lanes(&l)
        };
        check::<anysl_simd::F32x8>(lanes(0), lanes(3), lanes(5));
    }
}
