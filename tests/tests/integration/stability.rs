//! Stability under stiff and extreme inputs: the library and the shaders at huge coordinates,
//! grazing angles, refraction at index 1 and under total internal reflection, derivatives at
//! singular points, interval division by zero, long f32 loops, denormals, extreme shader
//! parameters, NaN/Inf inputs and zero-length vectors.
//!
//! Each case is a generic function whose doc comment states the expected outcome; `case!`
//! turns it into one `#[test]` per instantiation (`<case>::f32`, `<case>::f64`,
//! `<case>::f32x8`, `<case>::dual_f32`, … — run one with `cargo test --test stability grazing`).

use anysl_ad::{Dual, Interval};
use anysl_core::prelude::*;
use anysl_core::{PointContext, Shader};
use anysl_shaders::workload::WorkloadShader;
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::{F32x16, F32x8};

/// Declares a generic case `fn name<F>()` and a module `name` (both carrying the case's doc
/// comment) with one `#[test]` per listed instantiation (default: f32, f64, F32x8, Dual<f32>).
macro_rules! case {
    ($(#[$doc:meta])* fn $name:ident<$F:ident>() $body:block) => {
        case!($(#[$doc])* fn $name<$F>() $body for [f32: f32, f64: f64, f32x8: F32x8, dual_f32: Dual<f32>]);
    };
    ($(#[$doc:meta])* fn $name:ident<$F:ident>() $body:block for [$($m:ident: $T:ty),* $(,)?]) => {
        $(#[$doc])*
        fn $name<$F: ShadingFloat>() $body
        $(#[$doc])*
        mod $name {
            #[allow(unused_imports)]
            use super::*;
            $(
                #[test]
                fn $m() {
                    super::$name::<$T>();
                }
            )*
        }
    };
}

// ---------------------------------------------------------------------------------------------
// Helpers

/// Every lane of the value and (for duals) of both derivatives is finite.
fn finite<F: ShadingFloat>(x: F) -> bool {
    (0..F::LANES).all(|i| x.lane(i).is_finite() && x.dx().lane(i).is_finite() && x.dy().lane(i).is_finite())
}

fn finite3<F: ShadingFloat>(v: Vec3<F>) -> bool {
    finite(v.x) && finite(v.y) && finite(v.z)
}

fn finite_color<F: ShadingFloat>(c: Color<F>) -> bool {
    finite(c.r) && finite(c.g) && finite(c.b)
}

/// Smallest lane value of a colour.
fn min_channel<F: ShadingFloat>(c: Color<F>) -> f64 {
    (0..F::LANES).flat_map(|i| c.lane(i)).fold(f64::INFINITY, f64::min)
}

/// A value whose x-derivative is 1 (the seed of differentiation; a plain constant otherwise).
fn seed_x<F: ShadingFloat>(v: f64) -> F {
    F::c(v).with_derivs(F::c(1.0), F::c(0.0))
}

/// A value whose y-derivative is 1.
fn seed_y<F: ShadingFloat>(v: f64) -> F {
    F::c(v).with_derivs(F::c(0.0), F::c(1.0))
}

/// `f64` value of lane 0 (all lanes hold the same value in these cases).
fn v0<F: ShadingFloat>(x: F) -> f64 {
    x.lane(0)
}

/// Globals of one shading point (every lane the same) with the given P, N, I.
fn globals<F: ShadingFloat>(p: [f64; 3], n: [f64; 3], i: [f64; 3]) -> Globals<F> {
    let mut g = Globals::<F>::unit_square(F::c(0.3), F::c(0.7));
    g.P = Vec3::from_array(p);
    g.N = Vec3::from_array(n);
    g.Ng = g.N;
    g.I = Vec3::from_array(i);
    g
}

fn lights() -> Vec<Light> {
    table1_lights()
}

/// Every Table-1 surface and every workload shader, shaded at `g`: `(name, Ci, Oi)`.
fn shade_all<F: ShadingFloat>(g: Globals<F>) -> Vec<(String, Color<F>, Color<F>)> {
    let lights = lights();
    let mut out = Vec::new();
    for s in Surface::all() {
        let o = s.shade(&mut PointContext::new(g, &lights), &mut Exec::new());
        out.push((s.name().to_string(), o.Ci, o.Oi));
    }
    for s in WorkloadShader::all() {
        let o = s.shade(&mut PointContext::new(g, &lights), &mut Exec::new());
        out.push((format!("workload_{}", s.name()), o.Ci, o.Oi));
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Coordinates up to 1e7 and beyond

case! {
    /// Noise keeps its full detail at large coordinates: the lattice coordinate is an exact
    /// integer taken before hashing (reduced modulo the hash period 2^32), so at every
    /// magnitude where the input has fractional bits the values follow the same process as near
    /// the origin — finite, zero on the lattice, continuous, with the same spread — and the
    /// noise is exactly periodic with the hash period.
    fn noise_keeps_detail_at_large_coordinates<F>() {
        let spread = |base: f64| {
            // 128 samples along x over two cells (exact in f32 up to 2^17, in f64 up to 2^46).
            let vals: Vec<f64> = (0..128)
                .map(|k| {
                    let x = base + f64::from(k) / 64.0;
                    v0(snoise3(Vec3::new(F::c(x), F::c(0.3125), F::c(0.6875))))
                })
                .collect();
            let mean = vals.iter().sum::<f64>() / 128.0;
            let sd = (vals.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / 128.0).sqrt();
            let jump = vals.windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0, f64::max);
            (sd, jump, vals)
        };
        let (sd0, _, _) = spread(0.0);
        let bases: &[f64] = if F::UNIT_ROUNDOFF > 1e-12 { &[1e3, 1e5] } else { &[1e3, 1e5, 1e7, 1e9, 1e12] };
        for &base in bases {
            let (sd, jump, vals) = spread(base);
            assert!(vals.iter().all(|v| v.is_finite()), "{}: non-finite noise at {base}", F::NAME);
            assert!(sd > 0.2 * sd0 && sd < 5.0 * sd0, "{}: spread {sd} at {base} vs {sd0} at 0", F::NAME);
            assert!(jump < 0.15, "{}: jump {jump} between neighbours at {base}", F::NAME);
        }
        // Periodic with the hash period 2^32 on every axis, also beyond the i32 range.
        let period = 4_294_967_296.0;
        for (x, y, z) in [(0.375, 0.6, 0.2), (-7.25, 3.5, 1.125), (1234.5, -0.75, 0.375)] {
            let a = v0(snoise3(Vec3::new(F::c(x), F::c(y), F::c(z))));
            for k in [1.0, -1.0, 3.0, 1000.0] {
                let b = v0(snoise3(Vec3::new(F::c(x + k * period), F::c(y), F::c(z))));
                if F::UNIT_ROUNDOFF < 1e-12 {
                    assert!((a - b).abs() < 1e-9, "{}: noise({x} + {k}·2^32) = {b}, noise({x}) = {a}", F::NAME);
                } else {
                    // f32 holds no fraction there: the shifted point is a lattice plane point.
                    assert!(b.is_finite());
                }
            }
        }
    }
}

case! {
    /// At 1e7 (and up to 4e9, beyond the i32 range) f32 noise is the f64 noise of the same
    /// input (the lattice is exact, not collapsed): agreement to 1e-6 at inputs f32 holds
    /// exactly, with values that vary from cell to cell; derivatives stay finite.
    fn noise_at_1e7_agrees_with_f64<F>() {
        let mut distinct = Vec::new();
        for base in [1e7f32, 1.6e7, -1e7, 3.9e9, -3.9e9] {
            for k in 0..16 {
                let x = base + k as f32 * (base.abs() * f32::EPSILON).max(1.0);
                let (y, z) = (0.3125 + k as f32 * 0.25, 0.6875);
                let p = Vec3::new(seed_x::<F>(f64::from(x)), F::c(f64::from(y)), F::c(z));
                let n = snoise3(p);
                let n64 = snoise3(Vec3::new(f64::from(x), f64::from(y), z));
                assert!(finite(n), "{}: noise({x}, {y}, {z}) = {n:?}", F::NAME);
                assert!((v0(n) - n64).abs() <= 1e-6, "{}: noise({x}) = {} vs f64 {n64}", F::NAME, v0(n));
                distinct.push((n64 * 1e6).round() as i64);
            }
        }
        distinct.sort_unstable();
        distinct.dedup();
        assert!(distinct.len() > 40, "only {} distinct values: detail lost", distinct.len());
    }
}

case! {
    /// Shaders at P ≈ ±1e7 (noise-based ones included) give finite, non-negative colours.
    fn shaders_at_1e7_are_finite<F>() {
        for p in [[1e7, 2e7, -3e7], [-1e7, 0.5, 1e7], [3e9, 1.0, 0.25]] {
            let g = globals::<F>(p, [0.0, 0.6, 0.8], [0.0, -0.6, -0.8]);
            for (name, ci, oi) in shade_all(g) {
                assert!(finite_color(ci) && finite_color(oi), "{name} at {p:?}: Ci {ci:?}");
                assert!(min_channel(ci) >= 0.0, "{name} at {p:?}: negative Ci {ci:?}");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Grazing angles

case! {
    /// As N·I → 0 (grazing incidence, down to exactly 0 and just past it) every shader gives a
    /// finite, non-negative colour and opacity (derivatives finite for duals).
    fn grazing_angles_give_finite_nonnegative_colour<F>() {
        for eps in [1e-2, 1e-4, 1e-7, 1e-12, 1e-30, 0.0, -1e-7] {
            let i = [1.0, 0.0, -eps];
            let g = globals::<F>([0.3, 0.2, 0.0], [0.0, 0.0, 1.0], i);
            for (name, ci, oi) in shade_all(g) {
                assert!(finite_color(ci) && finite_color(oi), "{name} at N·I = {eps}: Ci {ci:?} Oi {oi:?}");
                assert!(min_channel(ci) >= 0.0 && min_channel(oi) >= 0.0, "{name} at N·I = {eps}: {ci:?}");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Refraction

case! {
    /// With index ratio 1 `refract` passes the ray straight through (T = I to rounding), and
    /// for ratios 1 ± 1e-7 it stays within 1e-5 of I; `fresnel` reflects nothing (Kr ≤ 1e-6)
    /// away from grazing incidence.
    fn refract_at_index_one_passes_straight<F>() {
        let n = Vec3::<F>::c(0.0, 0.0, 1.0);
        for (x, z) in [(0.0, -1.0), (0.6, -0.8), (0.99, -0.141), (0.3, -0.2)] {
            let i = Vec3::<F>::c(x, 0.0, z).normalize();
            for (eta, tol) in [(1.0, 2e-7), (1.0 + 1e-7, 1e-5), (1.0 - 1e-7, 1e-5)] {
                let t = refract(i, n, F::c(eta));
                assert!(finite3(t));
                for c in 0..3 {
                    let (a, b) = (v0(t.comp(c)), v0(i.comp(c)));
                    assert!((a - b).abs() <= tol, "{}: refract({x}, {z}; {eta})[{c}] = {a}, I = {b}", F::NAME);
                }
            }
            let f = fresnel(i, n, F::c(1.0));
            assert!(v0(f.kr).abs() <= 1e-6 && (v0(f.kt) - 1.0).abs() <= 1e-6, "{}: Kr {:?}", F::NAME, f.kr);
        }
    }
}

case! {
    /// Past the critical angle (ratio 1.5, leaving a dense medium) `refract` returns the zero
    /// vector and `fresnel` gives Kr = 1, Kt = 0, T = 0; exactly at the critical angle and at
    /// grazing incidence everything stays finite with Kr ≤ 1.
    fn total_internal_reflection<F>() {
        let n = Vec3::<F>::c(0.0, 0.0, 1.0);
        let eta = F::c(1.5);
        for deg in [45.0f64, 60.0, 89.9, 90.0] {
            let a = deg.to_radians();
            let i = Vec3::<F>::c(a.sin(), 0.0, -a.cos());
            let t = refract(i, n, eta);
            for c in 0..3 {
                assert_eq!(v0(t.comp(c)), 0.0, "{}: refract at {deg}° = {t:?}", F::NAME);
            }
            assert!(finite3(t));
            let f = fresnel(i, n, eta);
            assert_eq!(v0(f.kr), 1.0, "{}: Kr at {deg}°", F::NAME);
            assert_eq!(v0(f.kt), 0.0, "{}: Kt at {deg}°", F::NAME);
            assert!(finite(f.kr) && finite3(f.t) && finite3(f.r));
        }
        // The critical angle itself: sin θc = 1/1.5.
        let a = (1.0f64 / 1.5).asin();
        let i = Vec3::<F>::c(a.sin(), 0.0, -a.cos());
        let t = refract(i, n, eta);
        let f = fresnel(i, n, eta);
        assert!(finite3(t) && finite(f.kr) && v0(f.kr) <= 1.0 && v0(f.kr) >= 0.0);
    }
}

// ---------------------------------------------------------------------------------------------
// Derivatives at singular points

case! {
    /// No NaN or Inf in derivatives where the value is finite (anysl-ad's policy): sqrt at 0
    /// and at denormals, pow at base 0 / tiny bases for every exponent sign, atan2 at and near
    /// the origin and on the branch cut, normalize of zero, tiny and huge vectors. The
    /// derivative that has no finite limit is 0.
    fn derivatives_at_singular_points<F>() {
        let tiny = if F::UNIT_ROUNDOFF > 1e-12 { f64::from(f32::from_bits(1)) } else { f64::from_bits(1) };
        let check = |what: &str, x: F| {
            if (0..F::LANES).all(|i| x.lane(i).is_finite()) {
                assert!(finite(x), "{}: {what} = {x:?}: value finite, derivative not", F::NAME);
            }
        };
        for x in [0.0, tiny, 1e-30, 1e-10, 1.0] {
            check(&format!("sqrt({x})"), seed_x::<F>(x).sqrt());
            assert_eq!(v0(seed_x::<F>(0.0).sqrt().dx()), 0.0);
            for y in [-2.0, -0.5, 0.0, 0.5, 1.0, 2.0, 12.5] {
                check(&format!("pow({x}, {y})"), seed_x::<F>(x).pow(seed_y(y)));
            }
            check(&format!("ln({x})"), seed_x::<F>(x).ln());
        }
        for (y, x) in [(0.0, 0.0), (tiny, 0.0), (0.0, -tiny), (1e-30, 1e-30), (0.0, -1.0), (-0.0, -1.0), (1e30, 1e-30)] {
            check(&format!("atan2({y}, {x})"), seed_y::<F>(y).atan2(seed_x(x)));
        }
        assert_eq!(v0(seed_y::<F>(0.0).atan2(seed_x(0.0)).dx()), 0.0);
        for s in [0.0, tiny, 1e-30, 1e-20, 1e-10, 1e10, 1e20, 1e30] {
            let v = Vec3::new(seed_x::<F>(s), seed_y::<F>(0.5 * s), F::c(0.0));
            let u = v.normalize();
            assert!(finite3(u), "{}: normalize({s}·(1, ½, 0)) = {u:?}", F::NAME);
            let len = v0(u.dot(u)).sqrt();
            let want = if s == 0.0 { 0.0 } else { 1.0 };
            assert!((len - want).abs() <= 1e-6, "{}: |normalize({s}·(1, ½, 0))| = {len}", F::NAME);
        }
    }
    for [f32: f32, f64: f64, f32x8: F32x8, dual_f32: Dual<f32>, dual_f64: Dual<f64>, dual_f32x8: Dual<F32x8>]
}

case! {
    /// Quotients of tiny (denormal) numbers keep finite derivatives when the value is finite
    /// (`x / x` with x the smallest subnormal is 1 with derivative 0).
    fn derivatives_of_denormal_quotients<F>() {
        let tiny = if F::UNIT_ROUNDOFF > 1e-12 { f64::from(f32::from_bits(1)) } else { f64::from_bits(1) };
        for (a, b) in [(tiny, tiny), (0.0, tiny), (1e-40, 3e-40), (1.0, 1e-30)] {
            let q = F::c(a) / F::c(b);
            assert!(finite(q), "{}: {a} / {b} = {q:?}", F::NAME);
            let q = seed_x::<F>(a) / F::c(b);
            if v0(q).is_finite() && a / b < 1e30 {
                assert!(q.dx().lane(0).is_finite() || v0(q.dx()).abs() > 1e30, "{}: d({a}/{b})", F::NAME);
            }
        }
    }
    for [f32: f32, f64: f64, dual_f32: Dual<f32>, dual_f64: Dual<f64>, dual_f32x8: Dual<F32x8>]
}

// ---------------------------------------------------------------------------------------------
// Interval division by intervals containing zero

case! {
    /// Dividing by an interval that contains 0 gives a conservative result — the entire line
    /// or a hull — never NaN bounds; every sampled quotient of points of the operands (with a
    /// non-zero divisor) lies inside.
    fn interval_division_by_zero_containing<F>() {
        let boxes = [(-1.0, 1.0), (0.0, 1.0), (-1.0, 0.0), (0.0, 0.0), (-0.0, 0.0), (1e-45, 1.0), (-3.0, 2.0)];
        let nums = [(1.0, 2.0), (-2.0, -1.0), (-1.0, 1.0), (0.0, 0.0), (0.0, 5.0)];
        for (a0, a1) in nums {
            for (b0, b1) in boxes {
                let a = Interval::new(F::c(a0), F::c(a1));
                let b = Interval::new(F::c(b0), F::c(b1));
                let q = a / b;
                for l in 0..F::LANES {
                    let (lo, hi) = (q.lo().lane(l), q.hi().lane(l));
                    assert!(!lo.is_nan() && !hi.is_nan() && lo <= hi, "[{a0}, {a1}] / [{b0}, {b1}] = [{lo}, {hi}]");
                    for i in 0..=8 {
                        for j in 0..=8 {
                            let x = a0 + (a1 - a0) * f64::from(i) / 8.0;
                            let y = b0 + (b1 - b0) * f64::from(j) / 8.0;
                            if y != 0.0 {
                                let r = f64::from((x as f32) / (y as f32));
                                let r = if F::UNIT_ROUNDOFF < 1e-12 { x / y } else { r };
                                assert!(lo <= r && r <= hi, "{x}/{y} = {r} outside [{lo}, {hi}]");
                            }
                        }
                    }
                }
                // Other operations on the result stay NaN-free too.
                let z = (q * Interval::<F>::c(0.0) + q.abs()).sqrt();
                for l in 0..F::LANES {
                    assert!(!z.lo().lane(l).is_nan() && !z.hi().lane(l).is_nan());
                }
            }
        }
    }
    for [f32: f32, f64: f64, f32x8: F32x8]
}

// ---------------------------------------------------------------------------------------------
// f32 against f64 over long loops

/// The bound on |fBm_f32 − fBm_f64| over `octaves` octaves at coordinates up to `xmax`: per
/// octave the noise error is ≤ 16·δ (noise is Lipschitz with constant < 16 here) where δ is the
/// f32 error of the octave's coordinates (√3·|x|·lacunarity^o·(o + 2)·2^-24 for a non-power-of-two
/// lacunarity, none for 2), plus 1e-6 of arithmetic, capped at the octave's full range 2·1.04.
fn fbm_drift_bound(octaves: u32, lacunarity: f64, gain: f64, xmax: f64) -> f64 {
    let exact_scaling = lacunarity == 2.0;
    (0..octaves)
        .map(|o| {
            let delta = if exact_scaling {
                0.0
            } else {
                3f64.sqrt() * xmax * lacunarity.powi(o as i32) * f64::from(o + 2) * 2f64.powi(-24)
            };
            gain.powi(o as i32) * (16.0 * delta + 1e-6).min(2.08)
        })
        .sum()
}

case! {
    /// fBm with 30 octaves in f32 (scalar, SIMD, dual) stays within a computed bound of the f64
    /// fBm at the same inputs: ≈ 2e-6 for lacunarity 2 (scaling by 2 is exact, so only rounding
    /// in each octave's noise adds up) and ≈ 2e-5 for lacunarity 1.92 (the high octaves' f32
    /// coordinates drift, but their amplitude 0.5^o bounds what they can add).
    fn fbm_30_octaves_f32_vs_f64<F>() {
        let mut rng = anysl_core::points::SplitMix64(30);
        for (lac, gain) in [(2.0, 0.5), (1.92, 0.5)] {
            let bound = fbm_drift_bound(30, lac, gain, 2.0);
            let mut worst = 0.0f64;
            for _ in 0..64 {
                let p = [0; 3].map(|_| rng.uniform(-2.0, 2.0) as f32 as f64);
                let a = fbm(NoiseDomain::D3(Vec3::<F>::from_array(p)), 30, lac, gain);
                let b = fbm(NoiseDomain::D3(Vec3::<f64>::from_array(p)), 30, lac, gain);
                assert!(finite(a));
                worst = worst.max((v0(a) - b).abs());
            }
            assert!(worst <= bound, "{}: lacunarity {lac}: drift {worst:e} > bound {bound:e}", F::NAME);
        }
    }
    for [f32: f32, f32x8: F32x8, dual_f32: Dual<f32>]
}

// ---------------------------------------------------------------------------------------------
// Denormals and flush-to-zero

case! {
    /// Denormal inputs give finite results everywhere (no flush-to-zero: a denormal times 1 is
    /// itself, ln of a denormal is finite), and the math functions keep their usual meaning.
    fn denormal_inputs_give_finite_results<F>() {
        let (tiny, half_min) = if F::UNIT_ROUNDOFF > 1e-12 {
            (f64::from(f32::from_bits(1)), f64::from(f32::MIN_POSITIVE) / 2.0)
        } else {
            (f64::from_bits(1), f64::MIN_POSITIVE / 2.0)
        };
        for x in [tiny, half_min, -tiny, -half_min] {
            let d = F::c(x);
            assert_eq!(v0(d * F::c(1.0)), x, "{}: {x} flushed", F::NAME);
            assert_eq!(v0(d + F::c(0.0)), x, "{}: {x} flushed", F::NAME);
            let a = d.abs();
            let results = [
                ("sqrt", a.sqrt()),
                ("exp", d.exp()),
                ("exp2", d.exp2()),
                ("ln", a.ln()),
                ("log2", a.log2()),
                ("pow ½", a.pow(F::c(0.5))),
                ("pow 2", a.pow(F::c(2.0))),
                ("sin", d.sin()),
                ("cos", d.cos()),
                ("tan", d.tan()),
                ("atan", d.atan()),
                ("atan2", d.atan2(F::c(1.0))),
                ("asin", d.asin()),
                ("acos", d.acos()),
                ("floor", d.floor()),
                ("smoothstep", smoothstep(F::c(0.0), F::c(1.0), d)),
                ("noise", snoise3(Vec3::splat(d))),
                ("1/x", F::c(1.0) / (d + F::c(1.0))),
            ];
            for (what, r) in results {
                assert!(finite(r), "{}: {what}({x}) = {r:?}", F::NAME);
            }
            let ln = v0(a.ln());
            assert!((ln - x.abs().ln()).abs() <= 1e-5 * x.abs().ln().abs(), "{}: ln({x}) = {ln}", F::NAME);
            assert_eq!(v0(d.sin()), x, "{}: sin of a denormal is itself", F::NAME);
            let u = Vec3::new(d, d, F::c(0.0)).normalize();
            assert!(finite3(u) && (v0(u.dot(u)) - 1.0).abs() <= 1e-6, "{}: normalize({x}, {x}, 0)", F::NAME);
        }
    }
}

/// SIMD lanes holding denormals (and results that underflow into denormals) agree with scalar
/// f32 lane by lane: exact operations bit for bit, transcendentals to 2e-7 relative (or 1e-45
/// absolute in the denormal range) — neither flushes to zero.
#[test]
fn denormals_simd_agrees_with_scalar() {
    let tiny = f32::from_bits(1);
    let xs: [f32; 16] = [
        tiny,
        -tiny,
        f32::MIN_POSITIVE / 2.0,
        f32::MIN_POSITIVE,
        1e-40,
        -1e-40,
        0.0,
        -0.0,
        1e-39,
        3e-44,
        -87.5,
        -103.0,
        -149.0,
        2.5e-38,
        1e-45,
        5e-45,
    ];
    type Op = (&'static str, fn(f32) -> f32, fn(F32x16) -> F32x16);
    let ops: [Op; 11] = [
        ("x*1", |x| x * 1.0, |x| x * F32x16::c(1.0)),
        ("x*0.5", |x| x * 0.5, |x| x * F32x16::c(0.5)),
        ("sqrt|x|", |x| ShadingFloat::sqrt(x.abs()), |x| ShadingFloat::sqrt(ShadingFloat::abs(x))),
        ("exp", |x| ShadingFloat::exp(x), |x| ShadingFloat::exp(x)),
        ("exp2", |x| ShadingFloat::exp2(x), |x| ShadingFloat::exp2(x)),
        ("ln|x|", |x| ShadingFloat::ln(x.abs()), |x| ShadingFloat::ln(ShadingFloat::abs(x))),
        ("log2|x|", |x| ShadingFloat::log2(x.abs()), |x| ShadingFloat::log2(ShadingFloat::abs(x))),
        ("sin", |x| ShadingFloat::sin(x), |x| ShadingFloat::sin(x)),
        ("atan", |x| ShadingFloat::atan(x), |x| ShadingFloat::atan(x)),
        (
            "pow(|x|, 1.5)",
            |x| ShadingFloat::pow(x.abs(), 1.5),
            |x| ShadingFloat::pow(ShadingFloat::abs(x), F32x16::c(1.5)),
        ),
        ("floor", |x| ShadingFloat::floor(x), |x| ShadingFloat::floor(x)),
    ];
    let v = F32x16::from(xs);
    for (what, scalar, simd) in ops {
        let lanes = simd(v).to_array();
        for (x, got) in xs.iter().zip(lanes) {
            let want = scalar(*x);
            let ok = if want.is_nan() {
                got.is_nan()
            } else {
                got == want || (got - want).abs() <= 2e-7 * want.abs().max(1e-45 / 2e-7)
            };
            assert!(ok, "{what}({x:e}): SIMD {got:e}, scalar {want:e}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Extreme shader parameters

case! {
    /// Every float parameter of every Table-1 and workload shader set to 0, 1e-6 or 1e6 (one
    /// at a time) still gives finite colours — roughness 1e-6 (a needle highlight) and 1e6 (a
    /// flat one), frequencies of 1e6, zero sizes; Ks = 1e30 gives a finite, huge highlight.
    fn extreme_parameters_give_finite_colour<F>() {
        let lights = lights();
        let points = [
            globals::<F>([0.3, 0.2, 0.9], [0.3, 0.2, 0.93], [0.3, 0.2, -2.1]),
            globals::<F>([-0.5, 0.4, 0.6], [-0.5, 0.4, 0.77], [-0.5, 0.4, -2.4]),
        ];
        let mut shaders: Vec<(String, Box<dyn Fn(&str, f64) -> Vec<Color<F>>>)> = Vec::new();
        for s in Surface::all() {
            let lights = lights.clone();
            shaders.push((
                s.name().to_string(),
                Box::new(move |param: &str, value: f64| {
                    let mut s = s.clone();
                    s.set_param(param, &anysl_core::ParamValue::Float(value)).expect("a float parameter");
                    points
                        .iter()
                        .map(|g| s.shade(&mut PointContext::new(*g, &lights), &mut Exec::new()).Ci)
                        .collect()
                }),
            ));
        }
        for s in WorkloadShader::all() {
            let lights = lights.clone();
            shaders.push((
                format!("workload_{}", s.name()),
                Box::new(move |param: &str, value: f64| {
                    let mut s = s.clone();
                    s.set_param(param, &anysl_core::ParamValue::Float(value)).expect("a float parameter");
                    points
                        .iter()
                        .map(|g| s.shade(&mut PointContext::new(*g, &lights), &mut Exec::new()).Ci)
                        .collect()
                }),
            ));
        }
        let metas: Vec<anysl_core::ShaderMeta> = Surface::all()
            .iter()
            .map(Shader::meta)
            .chain(WorkloadShader::all().iter().map(Shader::meta))
            .collect();
        for ((name, shade), meta) in shaders.iter().zip(&metas) {
            for p in meta.params.iter().filter(|p| p.ty == anysl_core::ParamType::Float) {
                for value in [0.0, 1e-6, 1e6] {
                    for ci in shade(&p.name, value) {
                        assert!(finite_color(ci), "{}: {name} with {} = {value}: Ci {ci:?}", F::NAME, p.name);
                    }
                }
            }
            if meta.param("Ks").is_some() {
                for ci in shade("Ks", 1e30) {
                    assert!(finite_color(ci), "{}: {name} with Ks = 1e30: Ci {ci:?}", F::NAME);
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// NaN and Inf inputs

/// Shades eight points as one F32x8 packet, with NaN or ±Inf in the inputs of some lanes:
/// nothing panics or hangs, and every clean lane equals the same point shaded alone in f32
/// (to 1e-5) — a bad lane does not poison the others. The scalar f32 and Dual<f32> shading
/// of the bad points also returns.
#[test]
fn nan_and_inf_inputs_do_not_poison_other_lanes() {
    let nan = f64::NAN;
    let inf = f64::INFINITY;
    // (P, N, I) per lane; lanes 1, 3, 4 and 6 are bad.
    let pts: [([f64; 3], [f64; 3], [f64; 3]); 8] = [
        ([0.3, 0.2, 0.9], [0.3, 0.2, 0.93], [0.3, 0.2, -2.1]),
        ([nan, 0.2, 0.9], [0.3, 0.2, 0.93], [0.3, 0.2, -2.1]),
        ([-0.5, 0.4, 0.6], [-0.5, 0.4, 0.77], [-0.5, 0.4, -2.4]),
        ([0.1, inf, 0.9], [0.1, 0.4, 0.9], [0.1, 0.4, -2.1]),
        ([0.1, 0.4, 0.9], [nan, nan, nan], [0.1, 0.4, -2.1]),
        ([0.7, -0.1, 0.7], [0.7, -0.1, 0.7], [0.7, -0.1, -2.3]),
        ([-inf, 0.0, nan], [0.0, 0.0, 1.0], [0.0, 0.0, -inf]),
        ([0.0, -0.6, 0.8], [0.0, -0.6, 0.8], [0.0, -0.6, -2.2]),
    ];
    let bad = [1, 3, 4, 6];
    let lane_globals = |k: usize| {
        let (p, n, i) = pts[k];
        let mut g = globals::<f32>(p, n, i);
        g.s = 0.1 + 0.1 * k as f32;
        g.t = 0.9 - 0.1 * k as f32;
        g
    };
    let pack =
        |f: &dyn Fn(&Globals<f32>) -> f32| F32x8::from(core::array::from_fn::<f32, 8, _>(|k| f(&lane_globals(k))));
    let g8 = Globals::<F32x8> {
        P: Vec3::new(pack(&|g| g.P.x), pack(&|g| g.P.y), pack(&|g| g.P.z)),
        N: Vec3::new(pack(&|g| g.N.x), pack(&|g| g.N.y), pack(&|g| g.N.z)),
        Ng: Vec3::new(pack(&|g| g.Ng.x), pack(&|g| g.Ng.y), pack(&|g| g.Ng.z)),
        I: Vec3::new(pack(&|g| g.I.x), pack(&|g| g.I.y), pack(&|g| g.I.z)),
        s: pack(&|g| g.s),
        t: pack(&|g| g.t),
        u: pack(&|g| g.u),
        v: pack(&|g| g.v),
        ..Globals::<F32x8>::unit_square(F32x8::c(0.0), F32x8::c(0.0))
    };
    let wide = shade_all(g8);
    for k in 0..8 {
        let alone = shade_all(lane_globals(k));
        // Dual<f32> of the same point returns as well.
        let _ = shade_all(lane_globals(k).map(Dual::constant));
        if bad.contains(&k) {
            continue;
        }
        for ((name, ci8, oi8), (_, ci, oi)) in wide.iter().zip(&alone) {
            for (a, b) in ci8.lane(k).iter().chain(&oi8.lane(k)).zip(ci.lane(0).iter().chain(&oi.lane(0))) {
                assert!(a.is_finite(), "{name}: lane {k} poisoned: {a}");
                assert!((a - b).abs() <= 1e-5 * b.abs().max(1.0), "{name}: lane {k} = {a}, alone {b}");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Zero-length vectors

case! {
    /// Zero-length vectors never produce NaN: normalize(0) = 0 (with zero derivatives),
    /// length 0, reflect about a zero normal is the identity, refract and fresnel of a zero
    /// incident direction are finite, and shaders with N = 0 or I = 0 give finite colours.
    fn zero_length_vectors<F>() {
        let z = Vec3::new(seed_x::<F>(0.0), seed_y::<F>(0.0), F::c(0.0));
        let u = z.normalize();
        for c in 0..3 {
            assert_eq!(v0(u.comp(c)), 0.0);
        }
        assert!(finite3(u), "{}: normalize(0) = {u:?}", F::NAME);
        assert!(finite(z.length()) && v0(z.length()) == 0.0);
        let i = Vec3::<F>::c(0.6, 0.0, -0.8);
        let n = Vec3::<F>::c(0.0, 0.0, 1.0);
        let r = reflect(i, Vec3::zero());
        assert!(finite3(r) && (v0(r.x) - 0.6).abs() < 1e-7);
        assert!(finite3(faceforward(Vec3::zero(), i, n)));
        assert!(finite3(faceforward(n, Vec3::zero(), n)));
        assert!(finite3(refract(Vec3::zero(), n, F::c(1.5))));
        assert!(finite3(refract(i, Vec3::zero(), F::c(1.5))));
        let f = fresnel(Vec3::zero(), n, F::c(1.5));
        assert!(finite(f.kr) && finite(f.kt) && finite3(f.r) && finite3(f.t), "{}: fresnel(0)", F::NAME);
        let f = fresnel(i, Vec3::zero(), F::c(1.5));
        assert!(finite(f.kr) && finite(f.kt) && finite3(f.r) && finite3(f.t), "{}: fresnel(N = 0)", F::NAME);
        for (nn, ii) in [([0.0; 3], [0.3, 0.2, -2.1]), ([0.3, 0.2, 0.93], [0.0; 3]), ([0.0; 3], [0.0; 3])] {
            for (name, ci, oi) in shade_all(globals::<F>([0.3, 0.2, 0.9], nn, ii)) {
                assert!(finite_color(ci) && finite_color(oi), "{}: {name} with N = {nn:?}, I = {ii:?}: {ci:?}", F::NAME);
            }
        }
    }
}
