//! Every shader under every instantiation: SIMD lanes equal scalar, dual derivatives equal
//! finite differences, intervals contain point samples, and extreme inputs behave.

use anysl_ad::{Dual, Interval};
use anysl_core::points::{shade_points_f64, PointSet, SplitMix64};
use anysl_core::{Color, Exec, Globals, PointContext, Shader, ShadingFloat, SurfaceShader, Vec3};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::{F32x16, F32x4, F32x8};

fn surfaces() -> Vec<(&'static str, Surface)> {
    Surface::NAMES.iter().map(|n| (*n, Surface::by_name(n).expect("known shader"))).collect()
}

/// Shades one set of globals and returns (Ci, Oi).
fn shade<F: ShadingFloat>(s: &Surface, lights: &[Light], g: Globals<F>) -> (Color<F>, Color<F>) {
    let mut ctx = PointContext::new(g, lights);
    let mut e = Exec::<F>::new();
    let out = s.shade(&mut ctx, &mut e);
    (out.Ci, out.Oi)
}

/// Every shader runs under every instantiation and gives finite output on ordinary points.
#[test]
fn every_shader_runs_under_every_instantiation() {
    let lights = table1_lights();
    let set = PointSet::random(64, 7);
    for (name, s) in surfaces() {
        let check = |inst: &str, out: anysl_core::points::ShadeOut<f64>| {
            for ch in &out.channels {
                for v in ch {
                    assert!(v.is_finite(), "{name} {inst}: non-finite output {v}");
                }
            }
        };
        check("f32", shade_points_f64::<f32, _, _>(&s, &lights, &set));
        check("f64", shade_points_f64::<f64, _, _>(&s, &lights, &set));
        check("f32x4", shade_points_f64::<F32x4, _, _>(&s, &lights, &set));
        check("f32x8", shade_points_f64::<F32x8, _, _>(&s, &lights, &set));
        check("f32x16", shade_points_f64::<F32x16, _, _>(&s, &lights, &set));
        check("dual-f32", shade_points_f64::<Dual<f32>, _, _>(&s, &lights, &set));
        check("dual-f32x8", shade_points_f64::<Dual<F32x8>, _, _>(&s, &lights, &set));
        check("interval-f32", shade_points_f64::<Interval<f32>, _, _>(&s, &lights, &set));
    }
}

/// `globals_read` is right for every shader: with every other global NaN, f32, F32x8 and
/// Dual<f32> give the same bits as with all globals set (renderers fill only these).
#[test]
fn globals_outside_globals_read_are_not_read() {
    fn bits<F: ShadingFloat, S: SurfaceShader>(s: &S, lights: &[Light], set: &PointSet, poison: bool) -> Vec<u64> {
        let mut out = Vec::new();
        for i in (0..set.len()).step_by(F::LANES) {
            let mut g = set.globals::<F>(i);
            if poison {
                g.poison_except(s.globals_read());
            }
            let mut ctx = PointContext::new(g, lights);
            let o = s.shade(&mut ctx, &mut Exec::<F>::new());
            let (ci, oi) = (o.Ci, o.Oi);
            for c in [ci.r, ci.g, ci.b, oi.r, oi.g, oi.b] {
                out.extend((0..F::LANES).map(|l| c.lane(l).to_bits()));
            }
        }
        out
    }
    let lights = table1_lights();
    let set = PointSet::random(256, 9);
    fn check<S: SurfaceShader>(name: &str, s: &S, lights: &[Light], set: &PointSet) {
        assert!(bits::<f32, S>(s, lights, set, false) == bits::<f32, S>(s, lights, set, true), "{name} f32");
        assert!(bits::<F32x8, S>(s, lights, set, false) == bits::<F32x8, S>(s, lights, set, true), "{name} f32x8");
        let (a, b) = (bits::<Dual<f32>, S>(s, lights, set, false), bits::<Dual<f32>, S>(s, lights, set, true));
        assert!(a == b, "{name} dual-f32");
    }
    for (name, s) in surfaces() {
        check(name, &s, &lights, &set);
    }
    // The `.sl` shaders compiled to Rust publish what the IR analysis found.
    for name in anysl_shaders::rsl::RslSurface::NAMES {
        let s = anysl_shaders::rsl::RslSurface::by_name(name).expect("generated shader");
        if *name == "plastic" {
            assert!(s.globals_read() != anysl_core::GlobalSet::ALL, "plastic: no globals_read");
        }
        check(name, &s, &lights, &set);
    }
}

/// Compares two outputs point by point: |a - b| ≤ tol · max(1, |b|). Returns the number of
/// values out of tolerance and the worst relative error.
fn compare(a: &anysl_core::points::ShadeOut<f64>, b: &anysl_core::points::ShadeOut<f64>, tol: f64) -> (usize, f64) {
    let mut bad = 0;
    let mut worst: f64 = 0.0;
    for (ca, cb) in a.channels.iter().zip(&b.channels) {
        for (x, y) in ca.iter().zip(cb) {
            let rel = (x - y).abs() / y.abs().max(1.0);
            worst = worst.max(rel);
            if !(rel <= tol) {
                bad += 1;
            }
        }
    }
    (bad, worst)
}

/// SIMD lanes equal the scalar result (relative error ≤ 1e-5) on 10 000 random shading
/// points per shader. The points cross pattern edges, branch both ways within a packet
/// (divergent masks) and run the octave/segment loops; a point within rounding distance of
/// a pattern edge may legitimately flip, so up to 0.05% of values may differ beyond 1e-5 —
/// in practice the count is reported and is 0 for most shaders.
#[test]
fn simd_lanes_equal_scalar() {
    let lights = table1_lights();
    let set = PointSet::random(10_000, 11);
    for (name, s) in surfaces() {
        let scalar = shade_points_f64::<f32, _, _>(&s, &lights, &set);
        let total = scalar.channels.iter().map(Vec::len).sum::<usize>();
        for (inst, out) in [
            ("f32x4", shade_points_f64::<F32x4, _, _>(&s, &lights, &set)),
            ("f32x8", shade_points_f64::<F32x8, _, _>(&s, &lights, &set)),
            ("f32x16", shade_points_f64::<F32x16, _, _>(&s, &lights, &set)),
            ("dual-f32x8 vs dual-f32", {
                let d8 = shade_points_f64::<Dual<F32x8>, _, _>(&s, &lights, &set);
                let d1 = shade_points_f64::<Dual<f32>, _, _>(&s, &lights, &set);
                let (bad, worst) = compare(&d8, &d1, 1e-5);
                assert!(bad * 2000 <= total, "{name} dual-f32x8: {bad} of {total} values differ (worst {worst:e})");
                d8
            }),
        ] {
            if inst.starts_with("dual") {
                continue;
            }
            let (bad, worst) = compare(&out, &scalar, 1e-5);
            assert!(bad * 2000 <= total, "{name} {inst}: {bad} of {total} values differ from f32 (worst {worst:e})");
        }
    }
}

/// Offsets globals along their screen-space derivative seeds by `h` pixels in x or y.
fn shifted(g: &Globals<Dual<f64>>, h: f64, along_x: bool) -> Globals<f64> {
    g.map(|d| d.val + h * if along_x { d.ddx } else { d.ddy })
}

/// Dual derivatives agree with central finite differences in smooth regions. A point is
/// "smooth" when the differences at step h and h/2 agree (no pattern edge or branch switch
/// inside the stencil); at least half the points must qualify, and on those the dual
/// derivative must match within 1e-4 relative to the derivative scale. Shaders that
/// filter through their own derivatives (checker, brick) are excluded: their output depends
/// on the derivative itself, whose derivative is not carried (first-order duals).
#[test]
fn dual_derivatives_match_finite_differences() {
    let lights = table1_lights();
    let set = PointSet::random(400, 13);
    for (name, s) in surfaces() {
        if s.meta().uses_derivatives {
            continue;
        }
        let mut smooth = 0;
        let mut checked = 0;
        for i in 0..set.len() {
            let g = set.globals::<Dual<f64>>(i);
            let (ci, _) = shade::<Dual<f64>>(&s, &lights, g);
            for along_x in [true, false] {
                let h = 1e-3;
                let at = |h: f64| shade::<f64>(&s, &lights, shifted(&g, h, along_x)).0;
                let fd = |h: f64| {
                    let (a, b) = (at(h), at(-h));
                    [(a.r - b.r) / (2.0 * h), (a.g - b.g) / (2.0 * h), (a.b - b.b) / (2.0 * h)]
                };
                let (d1, d2) = (fd(h), fd(h / 2.0));
                checked += 1;
                let scale = d1.iter().chain(&d2).fold(1e-3f64, |m, v| m.max(v.abs()));
                if (0..3).any(|k| (d1[k] - d2[k]).abs() > 1e-3 * scale) {
                    continue;
                }
                smooth += 1;
                let ad = if along_x { [ci.r.ddx, ci.g.ddx, ci.b.ddx] } else { [ci.r.ddy, ci.g.ddy, ci.b.ddy] };
                for k in 0..3 {
                    // Richardson-extrapolated difference: O(h^4) error.
                    let rich = (4.0 * d2[k] - d1[k]) / 3.0;
                    assert!(
                        (ad[k] - rich).abs() <= 1e-4 * scale,
                        "{name} point {i} {}: dual {} vs finite difference {}",
                        if along_x { "d/dx" } else { "d/dy" },
                        ad[k],
                        rich
                    );
                }
            }
        }
        assert!(smooth * 2 >= checked, "{name}: only {smooth} of {checked} stencils smooth");
    }
}

/// A box of globals around point `i` of `set` with half-width `r` (in P/N/I and s/t/u/v).
struct GBox {
    lo: Globals<f32>,
    hi: Globals<f32>,
}

fn make_box(set: &PointSet, i: usize, r: f32) -> GBox {
    let g = set.globals::<f32>(i);
    let m = |v: f32, d: f32| (v - d, v + d);
    let v3 = |p: Vec3<f32>, d: f32| (p - Vec3::splat(d), p + Vec3::splat(d));
    let (plo, phi) = v3(g.P, r);
    let (nlo, nhi) = v3(g.N, r);
    let (ilo, ihi) = v3(g.I, r);
    let (slo, shi) = m(g.s, r);
    let (tlo, thi) = m(g.t, r);
    let (ulo, uhi) = m(g.u, r);
    let (vlo, vhi) = m(g.v, r);
    let mut lo = g;
    let mut hi = g;
    (lo.P, hi.P, lo.N, hi.N, lo.I, hi.I) = (plo, phi, nlo, nhi, ilo, ihi);
    (lo.s, hi.s, lo.t, hi.t, lo.u, hi.u, lo.v, hi.v) = (slo, shi, tlo, thi, ulo, uhi, vlo, vhi);
    GBox { lo, hi }
}

fn interval_globals(b: &GBox) -> Globals<Interval<f32>> {
    b.lo.zip(&b.hi, Interval::new)
}

fn sample_box(b: &GBox, rng: &mut SplitMix64) -> Globals<f32> {
    let mut u = |a: f32, c: f32| {
        let x = rng.uniform(a as f64, c as f64) as f32;
        x.clamp(a, c)
    };
    let mut g = b.lo;
    g.P = Vec3::new(u(b.lo.P.x, b.hi.P.x), u(b.lo.P.y, b.hi.P.y), u(b.lo.P.z, b.hi.P.z));
    g.N = Vec3::new(u(b.lo.N.x, b.hi.N.x), u(b.lo.N.y, b.hi.N.y), u(b.lo.N.z, b.hi.N.z));
    g.Ng = g.N;
    g.I = Vec3::new(u(b.lo.I.x, b.hi.I.x), u(b.lo.I.y, b.hi.I.y), u(b.lo.I.z, b.hi.I.z));
    g.s = u(b.lo.s, b.hi.s);
    g.t = u(b.lo.t, b.hi.t);
    g.u = u(b.lo.u, b.hi.u);
    g.v = u(b.lo.v, b.hi.v);
    g
}

/// Interval results contain every point sample: 100 boxes × 1 000 samples per shader, zero
/// misses. Box half-widths range from 1e-4 to 0.05 so both tight and pattern-crossing
/// boxes occur; the samples are shaded with plain f32, corners included.
#[test]
fn intervals_contain_point_samples() {
    let lights = table1_lights();
    let set = PointSet::random(100, 17);
    let mut rng = SplitMix64(99);
    for (name, s) in surfaces() {
        for bi in 0..100 {
            let r = [1e-4f32, 1e-3, 1e-2, 5e-2][bi % 4];
            let b = make_box(&set, bi, r);
            let (ci, oi) = shade::<Interval<f32>>(&s, &lights, interval_globals(&b));
            let bounds = [ci.r, ci.g, ci.b, oi.r, oi.g, oi.b];
            for k in 0..1000 {
                let g = if k == 0 {
                    b.lo
                } else if k == 1 {
                    b.hi
                } else {
                    sample_box(&b, &mut rng)
                };
                let (c, o) = shade::<f32>(&s, &lights, g);
                for (ch, v) in [c.r, c.g, c.b, o.r, o.g, o.b].into_iter().enumerate() {
                    let iv = bounds[ch];
                    assert!(
                        v.is_nan() || (iv.lower(0) <= v as f64 && v as f64 <= iv.upper(0)),
                        "{name} box {bi} (r={r}) channel {ch}: sample {v} outside [{}, {}]",
                        iv.lower(0),
                        iv.upper(0)
                    );
                }
            }
        }
    }
}

/// Extreme inputs never panic and give the documented outcome: finite output for finite
/// inputs (huge coordinates, zero-length and grazing vectors, denormals), and no panic for
/// NaN/±inf (whose output may be NaN).
#[test]
fn extreme_inputs() {
    let lights = table1_lights();
    let base = Globals::<f32>::unit_square(0.3, 0.7);
    let tiny = f32::from_bits(1);
    let finite_cases: Vec<(&str, Globals<f32>)> = vec![
        ("P at 1e7", Globals { P: Vec3::c(1e7, -1e7, 1e7), ..base }),
        ("s,t at 1e7", Globals { s: 1e7, t: -1e7, u: 1e7, v: 1e7, ..base }),
        ("zero N", Globals { N: Vec3::zero(), Ng: Vec3::zero(), ..base }),
        ("zero I", Globals { I: Vec3::zero(), ..base }),
        ("grazing N.I = 0", Globals { I: Vec3::c(1.0, 0.0, 0.0), ..base }),
        ("denormal inputs", Globals { P: Vec3::splat(tiny), s: tiny, t: tiny, u: tiny, v: tiny, ..base }),
        ("negative s,t", Globals { s: -3.25, t: -0.5, ..base }),
    ];
    for (name, s) in surfaces() {
        for (case, g) in &finite_cases {
            let (c, o) = shade::<f32>(&s, &lights, *g);
            for v in [c.r, c.g, c.b, o.r, o.g, o.b] {
                assert!(v.is_finite(), "{name} with {case}: non-finite output {v}");
            }
            // The same case through SIMD lanes and duals: no panic, finite too.
            let (c8, _) = shade::<F32x8>(&s, &lights, lift::<F32x8>(g));
            assert!(c8.r.lane(3).is_finite(), "{name} f32x8 with {case}");
            let (cd, _) = shade::<Dual<f32>>(&s, &lights, lift::<Dual<f32>>(g));
            assert!(cd.r.val.is_finite() && cd.r.ddx.is_finite(), "{name} dual with {case}");
        }
        for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            let g = Globals { P: Vec3::splat(bad), s: bad, t: bad, ..base };
            let _ = shade::<f32>(&s, &lights, g);
            let _ = shade::<F32x8>(&s, &lights, lift::<F32x8>(&g));
            let _ = shade::<Interval<f32>>(&s, &lights, lift::<Interval<f32>>(&g));
        }
    }
}

/// The same scalar globals in every lane of another instantiation.
fn lift<F: ShadingFloat>(g: &Globals<f32>) -> Globals<F> {
    g.map(|x| F::c(x as f64))
}
