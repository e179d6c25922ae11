//! Section d: interval bounds. For each shader, boxes of globals around random shading points
//! are shaded once with `Interval<f32>` and sampled with `f32` point samples (corners
//! included); tightness is the bound's width divided by the sampled range over the same box,
//! cost the interval shading time in point-sample equivalents.

use super::{median, table, Section, Sizes};
use anysl_ad::Interval;
use anysl_core::points::{PointSet, SplitMix64};
use anysl_core::prelude::*;
use anysl_core::PointContext;
use anysl_shaders::{table1_lights, Light, Surface};
use std::time::Instant;

fn shade<F: ShadingFloat>(s: &Surface, lights: &[Light], g: Globals<F>) -> [F; 6] {
    let o = s.shade(&mut PointContext::new(g, lights), &mut Exec::new());
    [o.Ci.r, o.Ci.g, o.Ci.b, o.Oi.r, o.Oi.g, o.Oi.b]
}

/// The box `[g − r, g + r]` in P, N, I, s, t, u, v around point `i` of `set`.
fn make_box(set: &PointSet, i: usize, r: f32) -> (Globals<f32>, Globals<f32>) {
    let g = set.globals::<f32>(i);
    let (mut lo, mut hi) = (g, g);
    let d = Vec3::splat(r);
    (lo.P, hi.P, lo.N, hi.N, lo.I, hi.I) = (g.P - d, g.P + d, g.N - d, g.N + d, g.I - d, g.I + d);
    (lo.s, hi.s, lo.t, hi.t) = (g.s - r, g.s + r, g.t - r, g.t + r);
    (lo.u, hi.u, lo.v, hi.v) = (g.u - r, g.u + r, g.v - r, g.v + r);
    (lo, hi)
}

fn sample(lo: &Globals<f32>, hi: &Globals<f32>, rng: &mut SplitMix64) -> Globals<f32> {
    let mut u = |a: f32, b: f32| (rng.uniform(f64::from(a), f64::from(b)) as f32).clamp(a, b);
    let mut g = *lo;
    g.P = Vec3::new(u(lo.P.x, hi.P.x), u(lo.P.y, hi.P.y), u(lo.P.z, hi.P.z));
    g.N = Vec3::new(u(lo.N.x, hi.N.x), u(lo.N.y, hi.N.y), u(lo.N.z, hi.N.z));
    g.Ng = g.N;
    g.I = Vec3::new(u(lo.I.x, hi.I.x), u(lo.I.y, hi.I.y), u(lo.I.z, hi.I.z));
    (g.s, g.t, g.u, g.v) = (u(lo.s, hi.s), u(lo.t, hi.t), u(lo.u, hi.u), u(lo.v, hi.v));
    g
}

/// Box half-widths measured.
const RADII: [f32; 3] = [1e-4, 1e-3, 1e-2];

/// Measures tightness and cost.
pub fn section(sz: &Sizes) -> Result<Section, String> {
    let lights = table1_lights();
    let set = PointSet::random(sz.boxes, 17);
    let mut rng = SplitMix64(99);
    let mut rows = Vec::new();
    let mut summary_ratio = Vec::new();
    let mut misses_total = 0usize;
    let mut cost_ratios = Vec::new();
    for name in Surface::NAMES {
        let s = Surface::by_name(name).ok_or("unknown shader")?;
        let mut row = vec![name.to_string()];
        let (mut t_iv, mut t_pt, mut n_iv, mut n_pt) = (0.0f64, 0.0f64, 0usize, 0usize);
        let mut misses = 0usize;
        for r in RADII {
            let mut ratios = Vec::new();
            let mut unbounded = 0usize;
            for b in 0..sz.boxes {
                let (lo, hi) = make_box(&set, b, r);
                let t = Instant::now();
                let iv = shade::<Interval<f32>>(&s, &lights, lo.zip(&hi, Interval::new));
                t_iv += t.elapsed().as_secs_f64();
                n_iv += 1;
                let mut smin = [f64::INFINITY; 6];
                let mut smax = [f64::NEG_INFINITY; 6];
                let t = Instant::now();
                for k in 0..sz.box_samples {
                    let g = match k {
                        0 => lo,
                        1 => hi,
                        _ => sample(&lo, &hi, &mut rng),
                    };
                    let v = shade::<f32>(&s, &lights, g);
                    for c in 0..6 {
                        let x = f64::from(v[c]);
                        if x.is_finite() {
                            smin[c] = smin[c].min(x);
                            smax[c] = smax[c].max(x);
                        }
                    }
                }
                t_pt += t.elapsed().as_secs_f64();
                n_pt += sz.box_samples;
                // Ci channels only: Oi = Os is constant here.
                for c in 0..3 {
                    let (l, h) = (iv[c].lower(0), iv[c].upper(0));
                    if smin[c] < l || smax[c] > h {
                        misses += 1;
                    }
                    let width = h - l;
                    let range = smax[c] - smin[c];
                    if !width.is_finite() {
                        unbounded += 1;
                    } else if range > 1e-7 {
                        ratios.push(width / range);
                    }
                }
            }
            let med = median(ratios.clone());
            if r == 1e-3 {
                summary_ratio.push((name, med));
            }
            row.push(if ratios.is_empty() { "—".into() } else { format!("{med:.2}") });
            row.push(if ratios.is_empty() {
                "—".into()
            } else {
                format!("{:.2}", ratios.iter().copied().fold(0.0, f64::max))
            });
            row.push(format!("{unbounded}"));
        }
        let cost = (t_iv / n_iv.max(1) as f64) / (t_pt / n_pt.max(1) as f64);
        cost_ratios.push(cost);
        row.push(format!("{:.2}", t_iv / n_iv.max(1) as f64 * 1e6));
        row.push(format!("{:.2}", t_pt / n_pt.max(1) as f64 * 1e6));
        row.push(format!("{cost:.1}"));
        row.push(misses.to_string());
        misses_total += misses;
        rows.push(row);
    }
    let mut head = vec!["shader".to_string()];
    for r in RADII {
        head.push(format!("median w/range, r={r:.0e}"));
        head.push(format!("max, r={r:.0e}"));
        head.push(format!("unbounded, r={r:.0e}"));
    }
    head.extend(["µs per interval".into(), "µs per point".into(), "interval ÷ point".into(), "samples outside".into()]);
    let head: Vec<&str> = head.iter().map(String::as_str).collect();
    let mut html = format!(
        "<p>For each shader, {} boxes around random shading points (half-width r in P, N, I, s, t, u, v; \
         the two table-1 point lights and ambient), each shaded once with <code>Interval&lt;f32&gt;</code> and \
         sampled with {} <code>f32</code> point samples (the two corners and random points). Tightness = \
         width of the interval bound ÷ range of the samples, per Ci channel (channels whose samples vary by \
         less than 1e-7 are left out; 1.0 would be perfectly tight, and the sampled range itself underestimates \
         the true range, so ratios are upper bounds on the overestimate). <i>unbounded</i> counts channels \
         whose bound is infinite. Cost: time per interval shading against time per point sample, one thread. \
         <i>samples outside</i> must be 0 (the bound is conservative).</p>",
        sz.boxes, sz.box_samples
    );
    html.push_str(&table(&head, &rows));
    html.push_str(
        "<p>Where bounds are loose: every comparison whose operands overlap is \"maybe\", so both branches run \
         and the hull is taken; noise sums many gradient terms whose dependency on the same input intervals \
         is lost (the classic interval dependency problem), and loops that keep a \"maybe\" condition past \
         <code>INTERVAL_LOOP_LIMIT</code> are widened to unbounded. Even the lighting alone (phong) loses a \
         factor of several: the same normal and view vector enter normalize, dot products and pow more than \
         once, and each use widens independently.</p>",
    );
    let gm = (cost_ratios.iter().map(|c| c.ln()).sum::<f64>() / cost_ratios.len() as f64).exp();
    let summary = vec![
        format!(
            "median bound width ÷ sampled range at r = 1e-3: {}",
            summary_ratio.iter().map(|(n, m)| format!("{n} {m:.2}")).collect::<Vec<_>>().join(", ")
        ),
        format!(
            "one interval shading costs {gm:.0} point samples (geometric mean; {:.0}–{:.0}); samples outside their bound: {misses_total}",
            cost_ratios.iter().copied().fold(f64::INFINITY, f64::min),
            cost_ratios.iter().copied().fold(0.0, f64::max)
        ),
    ];
    Ok(Section { id: "intervals", title: "d. Interval bounds: tightness and cost", html, summary })
}
