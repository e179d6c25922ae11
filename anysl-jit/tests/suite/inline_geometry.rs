//! `fresnel` and `refract`, which the JIT emits inline for the scalar and SIMD variants, give
//! anysl-core's values bit for bit on stiff inputs (grazing and normal incidence, total
//! internal reflection, zero-length, huge and subnormal directions, NaN), and glass's compiled
//! code no longer calls the library for them.

use anysl_core::stdlib::{fresnel, refract};
use anysl_core::{Exec, Globals, PointContext, ShadingFloat, SurfaceShader, Vec3};
use anysl_jit::rt::{Geo, RtKind};
use anysl_jit::{JitOptions, JitShader, Variant};
use anysl_shaders::Light;
use anysl_simd::{F32x16, F32x4, F32x8};
use std::path::PathBuf;

fn shader(name: &str, body: &str) -> JitShader {
    let src = format!("surface {name}() {{ {body} }}");
    JitShader::from_source(&format!("{name}.sl"), &src, &[], JitOptions::default()).unwrap()
}

/// Incident directions: ordinary, grazing (I·N = 0), head-on, zero, huge, tiny, subnormal,
/// infinite and NaN components.
const DIRS: [[f32; 3]; 16] = [
    [0.3, -0.4, -1.0],
    [1.0, 0.0, 0.0],
    [0.0, 0.0, -1.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, 0.0],
    [1.0e7, -3.0e6, -2.0e7],
    [1.0e30, 1.0e30, -1.0e30],
    [1.0e-30, 0.0, -1.0e-30],
    [1.0e-40, -2.0e-41, -3.0e-40],
    [0.999_999, 0.0, -1.0e-3],
    [-0.7, 0.7, -0.01],
    [0.2, 0.1, 0.97],
    [f32::INFINITY, 0.0, -1.0],
    [f32::NAN, 0.0, -1.0],
    [0.5, 0.5, -0.5],
    [-1.0e-3, 1.0, 0.0],
];

/// Normals (unit, as RSL's `fresnel` expects, and a few that are not).
const NORMALS: [[f32; 3]; 4] = [[0.0, 0.0, 1.0], [0.0, 0.6, 0.8], [0.0, 0.0, -1.0], [0.0, 0.0, 2.0]];

/// Ratios of indices: through the interface both ways, equal indices, extreme.
const ETAS: [f32; 6] = [1.0 / 1.5, 1.5, 1.0, 2.4, 0.1, 1.0e-20];

fn lanes<F: ShadingFloat>(v: impl Iterator<Item = f32>) -> F {
    F::from_lanes(&v.map(f64::from).collect::<Vec<_>>())
}

fn same<F: ShadingFloat>(a: F, b: F) -> bool {
    (0..F::LANES).all(|l| {
        let (x, y) = (a.lane(l) as f32, b.lane(l) as f32);
        x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan())
    })
}

fn check<F: ShadingFloat>(shaders: &[JitShader; 3]) {
    let cases: Vec<([f32; 3], [f32; 3], f32)> =
        DIRS.iter().flat_map(|i| NORMALS.iter().flat_map(move |n| ETAS.iter().map(move |e| (*i, *n, *e)))).collect();
    let mut checked = 0;
    for chunk in cases.chunks(F::LANES) {
        let at = |l: usize| chunk[l % chunk.len()];
        let v3 = |f: &dyn Fn(usize) -> [f32; 3]| {
            Vec3::new(
                lanes::<F>((0..F::LANES).map(|l| f(l)[0])),
                lanes::<F>((0..F::LANES).map(|l| f(l)[1])),
                lanes::<F>((0..F::LANES).map(|l| f(l)[2])),
            )
        };
        let (i, n) = (v3(&|l| at(l).0), v3(&|l| at(l).1));
        let eta: F = lanes((0..F::LANES).map(|l| at(l).2));
        let mut g = Globals::unit_square(eta, F::c(0.0));
        g.I = i;
        g.N = n;
        let lights: [Light; 0] = [];
        let run = |jit: &JitShader| {
            let mut ctx = PointContext::new(g, &lights);
            let o = jit.shade(&mut ctx, &mut Exec::new());
            [o.Ci.r, o.Ci.g, o.Ci.b, o.Oi.r, o.Oi.g, o.Oi.b]
        };
        let f = fresnel(i, n, eta);
        let t = refract(i, n, eta);
        let want = [
            [f.r.x, f.r.y, f.r.z, f.t.x, f.t.y, f.t.z],
            [f.kr, f.kt, F::c(0.0), t.x, t.y, t.z],
            [f.kr, f.kt, F::c(0.0), F::c(0.0), F::c(0.0), F::c(0.0)],
        ];
        for (k, jit) in shaders.iter().enumerate() {
            for (c, (g, w)) in run(jit).iter().zip(&want[k]).enumerate() {
                let vals = |v: F| (0..F::LANES).map(|l| v.lane(l) as f32).collect::<Vec<_>>();
                assert!(
                    same(*g, *w),
                    "{} shader {k} output {c}: cases {chunk:?}\n jit {:?}\n lib {:?}",
                    F::NAME,
                    vals(*g),
                    vals(*w)
                );
                checked += 1;
            }
        }
    }
    assert!(checked >= 18 * cases.len() / F::LANES);
}

fn shaders() -> [JitShader; 3] {
    [
        shader("fr_dirs", "float kr, kt; vector R, T; fresnel(I, N, s, kr, kt, R, T); Ci = color(R); Oi = color(T);"),
        shader("fr_k", "float kr, kt; vector R, T; fresnel(I, N, s, kr, kt, R, T); Ci = color(kr, kt, 0); Oi = color(refract(I, N, s));"),
        // The four-argument form (no directions).
        shader("fr_4", "float kr, kt; fresnel(I, N, s, kr, kt); Ci = color(kr, kt, 0); Oi = 0;"),
    ]
}

#[test]
fn inline_fresnel_and_refract_are_the_library_bit_for_bit() {
    let s = shaders();
    check::<f32>(&s);
    check::<F32x4>(&s);
    check::<F32x8>(&s);
    check::<F32x16>(&s);
}

/// Glass's `fresnel` is inline at every SIMD width: its optimized IR calls no library
/// function for it.
#[test]
fn glass_calls_no_library_fresnel() {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"));
    let jit = JitShader::from_file(&dir.join("glass.sl"), &[dir.join("include")], JitOptions::default()).unwrap();
    for v in [Variant::X4, Variant::X8, Variant::X16] {
        let a = |aux| v.rt_addr(RtKind::Geo, aux);
        let ir = anysl_jit::compile_with(&jit.module, &jit.values, v, &jit.opts, true).unwrap().llvm_ir.unwrap();
        for (name, aux) in [("fresnel", Geo::Fresnel as u32), ("refract", Geo::Refract as u32)] {
            assert!(!ir.contains(&format!("i64 {} to", a(aux))), "{v:?}: glass calls the library's {name}");
        }
    }
}
