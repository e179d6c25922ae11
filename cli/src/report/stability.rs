//! Section f: stability. Representative cases of `tests/tests/integration/stability.rs` run through the
//! library directly (the test suite runs each for f32, f64, F32x8 and dual numbers); each case
//! states its expected outcome and whether it held.

use super::{esc, Section, Sizes};
use anysl_ad::{Dual, Interval};
use anysl_core::prelude::*;
use anysl_core::{ParamType, ParamValue, PointContext, Shader};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::F32x8;
use std::fmt::Write as _;

type Case = (&'static str, &'static str, fn() -> Result<String, String>);

fn finite<F: ShadingFloat>(x: F) -> bool {
    (0..F::LANES).all(|i| x.lane(i).is_finite() && x.dx().lane(i).is_finite() && x.dy().lane(i).is_finite())
}

fn finite_color<F: ShadingFloat>(c: Color<F>) -> bool {
    finite(c.r) && finite(c.g) && finite(c.b)
}

fn globals<F: ShadingFloat>(p: [f64; 3], n: [f64; 3], i: [f64; 3]) -> Globals<F> {
    let mut g = PointSet1::globals::<F>();
    g.P = Vec3::from_array(p);
    g.N = Vec3::from_array(n).normalize();
    g.Ng = g.N;
    g.I = Vec3::from_array(i);
    g
}

/// One fixed shading point's globals, for the cases to modify.
struct PointSet1;
impl PointSet1 {
    fn globals<F: ShadingFloat>() -> Globals<F> {
        anysl_core::points::PointSet::random(1, 7).globals::<F>(0)
    }
}

fn shade_all<F: ShadingFloat>(g: Globals<F>, lights: &[Light]) -> Vec<(&'static str, Color<F>, Color<F>)> {
    Surface::all()
        .into_iter()
        .map(|s| {
            let o = s.shade(&mut PointContext::new(g, lights), &mut Exec::new());
            (s.name(), o.Ci, o.Oi)
        })
        .collect()
}

fn v0<F: ShadingFloat>(x: F) -> f64 {
    x.lane(0)
}

fn shaders_finite_at<F: ShadingFloat>(p: [f64; 3], i: [f64; 3]) -> Result<(), String> {
    let lights = table1_lights();
    for (name, ci, oi) in shade_all(globals::<F>(p, [0.0, 0.6, 0.8], i), &lights) {
        if !finite_color(ci) || !finite_color(oi) {
            return Err(format!("{}: {name} at P={p:?}, I={i:?}: Ci {ci:?}", F::NAME));
        }
        if [ci.r, ci.g, ci.b].iter().any(|c| c.lane(0) < 0.0) {
            return Err(format!("{}: {name}: negative Ci {ci:?}", F::NAME));
        }
    }
    Ok(())
}

const CASES: &[Case] = &[
    ("noise at 1e7 keeps detail and agrees with f64", "f32 noise at |x| = 1e7…3.9e9 equals f64 noise of the same input to 1e-6, with > 40 distinct values over 80 points", || {
        let mut distinct = Vec::new();
        let mut worst = 0.0f64;
        for base in [1e7f32, 1.6e7, -1e7, 3.9e9, -3.9e9] {
            for k in 0..16 {
                let x = base + k as f32 * (base.abs() * f32::EPSILON).max(1.0);
                let y = 0.3125 + k as f32 * 0.25;
                let a = f64::from(snoise3(Vec3::new(x, y, 0.6875f32)));
                let b = snoise3(Vec3::new(f64::from(x), f64::from(y), 0.6875));
                worst = worst.max((a - b).abs());
                distinct.push((b * 1e6).round() as i64);
            }
        }
        distinct.sort_unstable();
        distinct.dedup();
        if worst <= 1e-6 && distinct.len() > 40 {
            Ok(format!("max |f32 − f64| = {worst:.1e}, {} distinct values", distinct.len()))
        } else {
            Err(format!("max |f32 − f64| = {worst:.1e}, {} distinct values", distinct.len()))
        }
    }),
    ("shaders at P ≈ 1e7", "every Table-1 shader gives finite, non-negative colour at P = (1e7, 2e7, −3e7) and (3e9, 1, 0.25) in f32, F32x8, Dual<f32>", || {
        for p in [[1e7, 2e7, -3e7], [3e9, 1.0, 0.25]] {
            shaders_finite_at::<f32>(p, [0.0, -0.6, -0.8])?;
            shaders_finite_at::<F32x8>(p, [0.0, -0.6, -0.8])?;
            shaders_finite_at::<Dual<f32>>(p, [0.0, -0.6, -0.8])?;
        }
        Ok("finite everywhere".into())
    }),
    ("grazing angles", "as N·I → 0 (1e-2 … 1e-30, 0, −1e-7) every shader gives finite, non-negative colour (f32, Dual<f32>)", || {
        for eps in [1e-2, 1e-7, 1e-30, 0.0, -1e-7] {
            shaders_finite_at::<f32>([0.3, 0.2, 0.0], [1.0, 0.0, -eps])?;
            shaders_finite_at::<Dual<f32>>([0.3, 0.2, 0.0], [1.0, 0.0, -eps])?;
        }
        Ok("finite and non-negative".into())
    }),
    ("refraction at index 1", "refract(I, N, 1) = I to 2e-7; fresnel Kr ≤ 1e-6", || {
        let n = Vec3::<f32>::c(0.0, 0.0, 1.0);
        let mut worst = 0.0f64;
        for (x, z) in [(0.0, -1.0), (0.6, -0.8), (0.99, -0.141)] {
            let i = Vec3::<f32>::c(x, 0.0, z).normalize();
            let t = refract(i, n, 1.0f32);
            for c in 0..3 {
                worst = worst.max(f64::from((t.comp(c) - i.comp(c)).abs()));
            }
            let f = fresnel(i, n, 1.0f32);
            if f.kr.abs() > 1e-6 {
                return Err(format!("Kr = {}", f.kr));
            }
        }
        if worst <= 2e-7 { Ok(format!("max |T − I| = {worst:.1e}")) } else { Err(format!("max |T − I| = {worst:.1e}")) }
    }),
    ("total internal reflection", "leaving glass (ratio 1.5) at 45°–90°: T = 0, Kr = 1, Kt = 0", || {
        let n = Vec3::<f64>::c(0.0, 0.0, 1.0);
        for deg in [45.0f64, 60.0, 89.9, 90.0] {
            let a = deg.to_radians();
            let i = Vec3::<f64>::c(a.sin(), 0.0, -a.cos());
            let t = refract(i, n, 1.5);
            let f = fresnel(i, n, 1.5);
            if t.dot(t) != 0.0 || f.kr != 1.0 || f.kt != 0.0 {
                return Err(format!("{deg}°: T {t:?}, Kr {}, Kt {}", f.kr, f.kt));
            }
        }
        Ok("T = 0, Kr = 1 at every angle".into())
    }),
    ("derivatives at singular points", "Dual<f32>: sqrt(0), pow(0, ½), ln(tiny), atan2(0, 0), normalize(0) have finite derivatives where the value is finite", || {
        let x = |v: f32| Dual::new(v, 1.0f32, 0.0);
        let y = |v: f32| Dual::new(v, 0.0f32, 1.0);
        let checks = [
            ("sqrt(0)", x(0.0).sqrt()),
            ("sqrt(1e-45)", x(1e-45).sqrt()),
            ("pow(0, 0.5)", x(0.0).pow(y(0.5))),
            ("pow(0, -0.5)", x(0.0).pow(y(-0.5))),
            ("atan2(0, 0)", y(0.0).atan2(x(0.0))),
            ("atan2(1e-30, 1e-30)", y(1e-30).atan2(x(1e-30))),
        ];
        for (what, v) in checks {
            if v.lane(0).is_finite() && !finite(v) {
                return Err(format!("{what} = {v:?}"));
            }
        }
        let u = Vec3::new(x(0.0), y(0.0), Dual::c(0.0)).normalize();
        if !(finite(u.x) && finite(u.y) && finite(u.z)) {
            return Err(format!("normalize(0) = {u:?}"));
        }
        Ok("no NaN/Inf derivative with a finite value".into())
    }),
    ("interval division by zero-containing intervals", "[a] / [b ∋ 0] is never NaN and contains every sampled quotient", || {
        for (a0, a1) in [(1.0f32, 2.0), (-1.0, 1.0), (0.0, 0.0)] {
            for (b0, b1) in [(-1.0f32, 1.0), (0.0, 1.0), (-1.0, 0.0), (0.0, 0.0)] {
                let q = Interval::new(a0, a1) / Interval::new(b0, b1);
                let (lo, hi) = (q.lo(), q.hi());
                if lo.is_nan() || hi.is_nan() || lo > hi {
                    return Err(format!("[{a0},{a1}]/[{b0},{b1}] = [{lo},{hi}]"));
                }
                for i in 0..=4 {
                    for j in 0..=4 {
                        let xv = a0 + (a1 - a0) * i as f32 / 4.0;
                        let yv = b0 + (b1 - b0) * j as f32 / 4.0;
                        if yv != 0.0 && !(lo <= xv / yv && xv / yv <= hi) {
                            return Err(format!("{xv}/{yv} outside [{lo}, {hi}]"));
                        }
                    }
                }
            }
        }
        Ok("conservative, NaN-free".into())
    }),
    ("fBm with 30 octaves, f32 vs f64", "lacunarity 2: |fBm_f32 − fBm_f64| ≤ 2e-6 over 64 random points", || {
        let mut rng = anysl_core::points::SplitMix64(30);
        let mut worst = 0.0f64;
        for _ in 0..64 {
            let p = [0; 3].map(|_| rng.uniform(-2.0, 2.0) as f32);
            let a = fbm(NoiseDomain::D3(Vec3::<f32>::from_array(p.map(f64::from))), 30, 2.0, 0.5);
            let b = fbm(NoiseDomain::D3(Vec3::<f64>::from_array(p.map(f64::from))), 30, 2.0, 0.5);
            worst = worst.max((f64::from(a) - b).abs());
        }
        if worst <= 2e-6 { Ok(format!("drift {worst:.1e}")) } else { Err(format!("drift {worst:.1e}")) }
    }),
    ("denormals", "no flush to zero: a denormal × 1 is itself, ln and sqrt of denormals are finite, F32x8 lanes equal f32", || {
        let tiny = f32::from_bits(1);
        let half = f32::MIN_POSITIVE / 2.0;
        for d in [tiny, half, -tiny] {
            if d * 1.0 != d || !d.abs().ln().is_finite() || !d.abs().sqrt().is_finite() {
                return Err(format!("{d:e}"));
            }
            let v = F32x8::splat(d) * F32x8::splat(1.0);
            if v.lane(3) != f64::from(d) {
                return Err(format!("F32x8 flushed {d:e}"));
            }
        }
        Ok("kept".into())
    }),
    ("extreme shader parameters", "every float parameter of every Table-1 shader at 0, 1e-6 and 1e6 gives finite colour (f32)", || {
        let lights = table1_lights();
        let g = PointSet1::globals::<f32>();
        let mut n = 0;
        for base in Surface::all() {
            for p in base.meta().params.iter().filter(|p| p.ty == ParamType::Float) {
                for value in [0.0, 1e-6, 1e6] {
                    let mut s = base.clone();
                    s.set_param(&p.name, &ParamValue::Float(value)).map_err(|e| format!("{e:?}"))?;
                    let o = s.shade(&mut PointContext::new(g, &lights), &mut Exec::new());
                    if !finite_color(o.Ci) || !finite_color(o.Oi) {
                        return Err(format!("{}.{} = {value}: Ci {:?}", base.name(), p.name, o.Ci));
                    }
                    n += 1;
                }
            }
        }
        Ok(format!("{n} shader × parameter × value combinations finite"))
    }),
    ("NaN/Inf lanes do not poison a packet", "an F32x8 packet with NaN and ±Inf in some lanes' P: every clean lane equals the same point shaded alone in f32 (to 1e-5)", || {
        let lights = table1_lights();
        let set = anysl_core::points::PointSet::random(8, 5);
        let mut g = set.globals::<F32x8>(0);
        let bad = [(1usize, f32::NAN), (4, f32::INFINITY), (6, f32::NEG_INFINITY)];
        let mut px = g.P.x.0.to_array();
        for (l, v) in bad {
            px[l] = v;
        }
        g.P.x = F32x8(wide::f32x8::from(px));
        for s in Surface::all() {
            let o = s.shade(&mut PointContext::new(g, &lights), &mut Exec::new());
            for l in (0..8).filter(|l| bad.iter().all(|(b, _)| b != l)) {
                let one = s.shade(&mut PointContext::new(set.globals::<f32>(l), &lights), &mut Exec::new());
                let d = (o.Ci.r.lane(l) - f64::from(one.Ci.r)).abs();
                if d.is_nan() || d > 1e-5 {
                    return Err(format!("{}: lane {l}: {} vs {}", s.name(), o.Ci.r.lane(l), one.Ci.r));
                }
            }
        }
        Ok("clean lanes unaffected".into())
    }),
    ("zero-length vectors", "normalize(0) = 0 (not NaN) in f32, F32x8, Dual<f32>", || {
        let z32 = Vec3::<f32>::splat(0.0).normalize();
        let z8 = Vec3::<F32x8>::splat(F32x8::splat(0.0)).normalize();
        let zd = Vec3::<Dual<f32>>::splat(Dual::c(0.0)).normalize();
        if z32.dot(z32) == 0.0 && v0(z8.dot(z8)) == 0.0 && v0(zd.dot(zd)) == 0.0 && finite(zd.x) {
            Ok("0".into())
        } else {
            Err(format!("{z32:?}"))
        }
    }),
];

/// Runs the cases.
pub fn section(_: &Sizes) -> Result<Section, String> {
    let mut html = String::from(
        "<p>Representative cases of the stability suite (<code>tests/tests/integration/stability.rs</code>, run by \
         <code>cargo test -p anysl-tests --test integration stability::</code> for f32, f64, F32x8 and dual numbers), run here through the \
         library directly. Each states its expected outcome.</p><table><tr><th>case</th><th>expected</th>\
         <th>observed</th><th>result</th></tr>\n",
    );
    let mut passed = 0;
    let mut failed = Vec::new();
    for (name, expected, f) in CASES {
        let r = std::panic::catch_unwind(f).unwrap_or_else(|_| Err("panicked".into()));
        let (obs, ok) = match r {
            Ok(s) => (s, true),
            Err(s) => (s, false),
        };
        if ok {
            passed += 1;
        } else {
            failed.push(*name);
        }
        let _ = writeln!(
            html,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"{}\">{}</td></tr>",
            esc(name),
            esc(expected),
            esc(&obs),
            if ok { "pass" } else { "fail" },
            if ok { "pass" } else { "FAIL" }
        );
    }
    html.push_str("</table>\n");
    let summary = vec![if failed.is_empty() {
        format!("{passed} of {} stability cases pass", CASES.len())
    } else {
        format!("{passed} of {} stability cases pass; failing: {}", CASES.len(), failed.join(", "))
    }];
    Ok(Section { id: "stability", title: "f. Stability under stiff and extreme inputs", html, summary })
}
