//! Masked control flow: the same generic program gives, in every SIMD lane, exactly what the
//! scalar `f32` instantiation gives for that lane's inputs — with divergent if/else, loops
//! whose trip counts differ per lane, `break`, `continue` and early `return`.

use anysl_ad::Dual;
use anysl_core::stdlib::fmod;
use anysl_core::{Exec, ShadingFloat};
use anysl_simd::{F32x16, F32x4, F32x8};
use proptest::prelude::*;

/// A program with every kind of control flow; all writes go through the execution mask.
fn program<F: ShadingFloat>(a: F, b: F, n: F) -> (F, F) {
    let mut e = Exec::<F>::new();
    let mut x = a;
    let mut acc = F::c(0.0);
    let mut i = F::c(0.0);
    e.loop_(|e| {
        if e.break_if(!i.lt(n)) {
            return;
        }
        e.if_else(x.gt(b), |e, then| {
            if then {
                e.update(&mut x, |x| x - b * F::c(0.5));
            } else {
                e.update(&mut x, |x| x + F::c(1.25));
            }
        });
        e.continue_if(fmod(i, F::c(3.0)).eq(F::c(1.0)));
        // A nested loop with its own break.
        let mut j = F::c(0.0);
        e.loop_(|e| {
            e.break_if(j.ge(F::c(2.0)) | (x * j).gt(F::c(30.0)));
            e.update(&mut acc, |acc| acc + x * F::c(0.125));
            e.update(&mut j, |j| j + F::c(1.0));
        });
        e.update(&mut acc, |acc| acc + x);
        e.break_if(acc.gt(F::c(40.0)));
        e.end_continue();
        e.update(&mut i, |i| i + F::c(1.0));
    });
    e.return_if(acc.lt(F::c(0.0)));
    e.update(&mut acc, |acc| acc * F::c(2.0));
    (x, acc)
}

fn check_lanes<F: ShadingFloat>(a: &[f32], b: &[f32], n: &[f32]) -> Result<(), TestCaseError> {
    let to = |v: &[f32]| F::from_lanes(&v[..F::LANES].iter().map(|x| *x as f64).collect::<Vec<_>>());
    let (x, acc) = program::<F>(to(a), to(b), to(n));
    for l in 0..F::LANES {
        let (sx, sacc) = program::<f32>(a[l], b[l], n[l]);
        prop_assert_eq!(x.lane(l) as f32, sx, "lane {} x ({})", l, F::NAME);
        prop_assert_eq!(acc.lane(l) as f32, sacc, "lane {} acc ({})", l, F::NAME);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn simd_lanes_follow_scalar_control_flow(
        a in prop::collection::vec(-20.0f32..20.0, 16),
        b in prop::collection::vec(-5.0f32..5.0, 16),
        n in prop::collection::vec(0u32..25, 16),
    ) {
        let n: Vec<f32> = n.into_iter().map(|v| v as f32).collect();
        check_lanes::<F32x4>(&a, &b, &n)?;
        check_lanes::<F32x8>(&a, &b, &n)?;
        check_lanes::<F32x16>(&a, &b, &n)?;
        check_lanes::<Dual<F32x8>>(&a, &b, &n)?;
    }
}

/// A region no lane needs is not executed.
#[test]
fn idle_regions_are_skipped() {
    let mut e = Exec::<F32x8>::new();
    let mut ran = false;
    let x = F32x8::from_lanes(&[1.0; 8]);
    e.if_(x.gt(F32x8::c(5.0)), |_| ran = true);
    assert!(!ran);
    let mut iterations = 0;
    let mut i = F32x8::from_lanes(&[0.0, 1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 0.0]);
    e.loop_(|e| {
        if e.break_if(i.ge(F32x8::c(4.0))) {
            return;
        }
        iterations += 1;
        e.update(&mut i, |i| i + F32x8::c(1.0));
    });
    // The lane starting at 0 needs 4 iterations; the loop runs exactly that many.
    assert_eq!(iterations, 4);
    assert_eq!(i.lane(3), 4.0);
}
