//! The comparison of two renders' channels (`anysl_jit::check`).

use anysl_core::points::ShadeOut;
use anysl_jit::check::{compare, ulps};

#[test]
fn ulps_across_zero_and_nan() {
    assert_eq!(ulps(1.0, 1.0), 0);
    assert_eq!(ulps(1.0, f32::from_bits(1.0f32.to_bits() + 3)), 3);
    assert_eq!(ulps(-0.0, 0.0), 0);
    assert_eq!(ulps(f32::from_bits(1), -f32::from_bits(1)), 2);
    assert_eq!(ulps(f32::NAN, 1.0), u64::MAX);
}

#[test]
fn mismatch_needs_both_ulps_and_absolute_distance() {
    let mut a = ShadeOut::new(2);
    let mut b = ShadeOut::new(2);
    // Near zero: many ulps, tiny value difference: a match.
    a.channels[0][0] = 1e-9;
    b.channels[0][0] = 2e-9;
    // At 1: 5 ulps (6e-7) is under the floor: a match; 0.5 is not.
    a.channels[1][0] = 1.0;
    b.channels[1][0] = f32::from_bits(1.0f32.to_bits() + 5);
    a.channels[2][1] = 1.0;
    b.channels[2][1] = 1.5;
    let c = compare(&a, &b);
    assert_eq!(c.mismatches, 1);
    assert!((c.max_abs - 0.5).abs() < 1e-12);
}
