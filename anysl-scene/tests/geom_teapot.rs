//! The teapot: 32 patches, the classic bounds, outward normals, nothing NaN.

// Tests index parallel per-vertex arrays.
#![allow(clippy::needless_range_loop)]

mod geom_util;

use anysl_scene::geom::{teapot, Detail, TEAPOT_PATCHES, TEAPOT_POINTS};
use geom_util::{check_consistent, one};
use glam::Vec3;

#[test]
fn teapot_has_the_classic_shape() {
    assert_eq!(TEAPOT_PATCHES.len(), 32);
    assert_eq!(TEAPOT_POINTS.len(), 306);
    assert!(TEAPOT_PATCHES.iter().flatten().all(|&i| (i as usize) < TEAPOT_POINTS.len()));
    let d = Detail { tolerance: 1e-3, min_segments: 4, max_segments: 64 };
    let t = teapot(&d);
    check_consistent(&t);
    let (lo, hi) = t.positions.iter().fold((Vec3::MAX, Vec3::MIN), |(a, b), &p| (a.min(p), b.max(p)));
    eprintln!("teapot bounds {lo} {hi}, {} triangles", t.triangles.len());
    // The Utah teapot: spout tip at x ≈ 3.43, handle at x = -3, body radius 2, lid knob at 3.15.
    let expect_lo = Vec3::new(-3.0, -2.0, 0.0);
    let expect_hi = Vec3::new(3.434, 2.0, 3.15);
    assert!((lo - expect_lo).abs().max_element() < 0.01, "low corner {lo}");
    assert!((hi - expect_hi).abs().max_element() < 0.01, "high corner {hi}");
    // Every patch is cut into the same grid: the vertex count is a multiple of 32.
    assert_eq!(t.positions.len() % 32, 0);
    let per_patch = t.positions.len() / 32;
    // Normals point out of the pot: away from the z axis on the body (patches 4-11), up or
    // out (never towards the axis) on the lid and knob (20-27), down or out on the bottom (28-31).
    for k in 0..t.positions.len() {
        let (patch, p, n) = (k / per_patch, t.positions[k], t.normals[k]);
        match patch {
            4..=11 => assert!(n.dot(p.truncate().extend(0.0).normalize()) > 0.3, "body normal {n} at {p}"),
            20..=27 if p.truncate().length() > 0.05 => {
                let radial = p.truncate().extend(0.0).normalize();
                assert!(n.dot(radial) > -0.05 && (n.z > 0.0 || n.dot(radial) > 0.5), "lid normal {n} at {p}")
            }
            28..=31 if p.truncate().length() > 0.05 => {
                let radial = p.truncate().extend(0.0).normalize();
                assert!(n.dot(radial) > -0.05 && (n.z < 0.0 || n.dot(radial) > 0.9), "bottom normal {n} at {p}");
                if p.truncate().length() < 1.0 {
                    assert!(n.z < -0.99, "flat bottom normal {n} at {p}");
                }
            }
            _ => {}
        }
    }
    // The knob's tip and the bottom's centre are degenerate patch corners: their normals are
    // the limits, straight up and straight down.
    for k in 0..t.positions.len() {
        let p = t.positions[k];
        if p.truncate().length() < 1e-6 && p.z == 3.15 {
            assert!((t.normals[k] - Vec3::Z).length() < 1e-2, "{}", t.normals[k]);
        }
        if p.truncate().length() < 1e-6 && p.z == 0.0 {
            assert!((t.normals[k] + Vec3::Z).length() < 1e-2, "{}", t.normals[k]);
        }
    }
    // Through the RIB request too.
    assert_eq!(one(r#"Geometry "teapot""#).positions.len() % 32, 0);
}
