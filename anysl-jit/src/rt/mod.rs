//! The runtime half of the target library: built-ins too large to inline (noise, the
//! transcendental functions, splines, matrices, …), written once and generic over the float
//! type, and the host shims that give compiled code the renderer's `ShadingContext`.
//!
//! Every function here calls the same `anysl-core` standard library as the hand-written
//! generic shaders, the generated Rust and the interpreter, so all back ends compute the same
//! functions. Each has the [`RtFn`] signature; `aux` selects the variant (see the `*_OP`
//! constants used by the code generator).
//!
//! The files: this module reads and writes the callbacks' buffers, defines the selectors
//! (`aux` values) of the runtime families and picks the function for a call ([`rt_addr`]);
//! `math.rs` holds the unary, binary and geometric functions, `noise.rs` the noise family,
//! `spline.rs` the splines and `host.rs` the host shims and their [`HostTable`].

use crate::abi::{JitFloat, RtFn};
use anysl_core::prelude::*;
use core::marker::PhantomData;

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
        pub(super) unsafe extern "C" fn $special<F: JitFloat, const AUX: u32>(
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

// Below `rt_family!`: a `macro_rules!` macro is visible only after its definition.
mod host;
mod math;
mod noise;
mod spline;

pub use host::{
    cast, light_host_table, Host, HostCtx, HostTable, KeptDiffuse, HOST_CTX_LIGHTS, HOST_CTX_N_LIGHTS,
    HOST_CTX_N_RECORDS, HOST_CTX_RECORDS, SPACE_BETWEEN, SPACE_FROM_CURRENT, SPACE_SEPARATOR, SPACE_TO_CURRENT,
};
pub use math::{rt_bin, rt_geo, rt_trig_lanes, rt_un};
use math::{rt_bin_k, rt_geo_k, rt_un_k};
pub use noise::rt_noise;
use noise::rt_noise_k;
use spline::rt_spline_k;
pub use spline::{rt_spline, BASES as SPLINE_BASIS_BY_INDEX, MAX_KNOTS};

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
/// multi-packet variants, which call them per packet where [`rt_addr_packets`] has none):
/// those are the variants whose speed is measured against the compiled build. Each copy
/// inlines its whole kernel (noise above all), so every float type with copies adds about a
/// minute to this crate's release build (docs/build.md, "Where the time goes"); the other
/// types get the general functions.
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
            // `noise` is called as `snoise` (the code generator adds `0.5 + 0.5·s`).
            RtKind::Noise => {
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

/// A runtime function that takes every packet of a multi-packet variant in one call, for
/// `F` = the variant's lanes as [`Pair`](anysl_simd::Pair)s of packets: the kernel runs over
/// all packets in lockstep (each operation on every packet before the next), as the compiled
/// build's `Pair` types do, instead of once per packet with the call's buffers in between.
/// For `snoise` (which `noise` calls too) of one to three dimensions as a float and of three
/// as a triple — the kernels noise shaders spend their time in — at four 8-lane packets;
/// `None` for the rest, which is called once per packet. Each copy holds its kernel four
/// times over (a triple: twelve), so each is a large function to compile (docs/build.md);
/// at two 16-lane packets such copies measured no faster than two calls, and there are none.
/// Each packet gets the bits of the one-packet copy. Called where that variant's noise is
/// not emitted as IR (`JitOptions::inline_noise` `Some(false)`; by default it is).
#[must_use]
pub fn rt_addr_packets<F: JitFloat>(kind: RtKind, aux: u32) -> Option<usize> {
    if kind != RtKind::Noise {
        return None;
    }
    macro_rules! k {
        ($($kind:ident $dims:literal $out:literal),* $(,)?) => {$({
            const AUX: u32 = NoiseSel { kind: NoiseOp::$kind, dims: $dims, out: $out, extra: 0 }.encode();
            if aux == AUX {
                return Some(rt_noise_k::<F, AUX> as RtFn as usize);
            }
        })*};
    }
    k!(SNoise 1 1, SNoise 2 1, SNoise 3 1, SNoise 3 3);
    None
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
