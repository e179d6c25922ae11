//! Geometry: the BVH agrees with the brute-force intersector, the triangulated sphere and
//! the camera give the analytic hit mask, the embedded bunny loads.

use crate::common;

use anysl_core::points::SplitMix64;
use anysl_renderers::{scenes, Camera};
use common::{TestLight, TestSurface};
use glam::Vec3A;

fn random_unit(rng: &mut SplitMix64) -> Vec3A {
    loop {
        let v = Vec3A::new(rng.uniform(-1.0, 1.0) as f32, rng.uniform(-1.0, 1.0) as f32, rng.uniform(-1.0, 1.0) as f32);
        let l = v.length_squared();
        if l > 1e-4 && l <= 1.0 {
            return v / l.sqrt();
        }
    }
}

#[test]
fn bvh_closest_and_any_hit_equal_brute_force_on_the_bunny() {
    let scene = scenes::bunny(TestSurface::lambert(0.8, [1.0; 3]), Vec::<TestLight>::new(), 8);
    let accel = scene.accel();
    assert_eq!(accel.len(), 3674);
    let mut rng = SplitMix64(7);
    let (mut hits, mut ties) = (0, 0);
    for k in 0..10_000 {
        // Origins around the bunny (unit height at the origin) aimed at points inside its box,
        // plus a share of fully random directions.
        let o = random_unit(&mut rng) * rng.uniform(0.8, 2.5) as f32;
        let target =
            Vec3A::new(rng.uniform(-0.5, 0.5) as f32, rng.uniform(-0.5, 0.5) as f32, rng.uniform(-0.4, 0.4) as f32);
        let d = if k % 5 == 0 { random_unit(&mut rng) } else { (target - o).normalize() };
        let tmax = if k % 7 == 0 { rng.uniform(0.1, 3.0) as f32 } else { f32::INFINITY };
        let fast = accel.closest_hit(o, d, 0.0, tmax);
        let slow = accel.closest_hit_brute_force(o, d, 0.0, tmax);
        match (fast, slow) {
            (None, None) => {}
            (Some(a), Some(b)) => {
                hits += 1;
                assert_eq!(a.t, b.t, "ray {k}: t differs ({a:?} vs {b:?})");
                if a.prim != b.prim {
                    // Same distance on a shared edge or vertex: either triangle is right.
                    ties += 1;
                } else {
                    assert_eq!((a.b1, a.b2), (b.b1, b.b2), "ray {k}");
                }
            }
            (a, b) => panic!("ray {k} from {o} along {d}: BVH {a:?} vs brute force {b:?}"),
        }
        assert_eq!(accel.occluded(o, d, 0.0, tmax), accel.occluded_brute_force(o, d, 0.0, tmax), "ray {k}");
    }
    assert!(hits > 4000, "only {hits} of 10000 rays hit the bunny");
    assert!(ties < 10, "{ties} ties");
}

#[test]
fn triangulated_sphere_gives_the_analytic_hit_mask() {
    let size = 64;
    let scene = scenes::table1(TestSurface::lambert(0.8, [1.0; 3]), Vec::<TestLight>::new(), size);
    let cam: &Camera = &scene.camera;
    // The 64×32 sphere is inscribed in the unit sphere: its surface lies within
    // 1 − cos(π/32) of it. Pixels whose ray passes closer than that to the silhouette may
    // differ and are left out; every other pixel must agree, and the hit distance must
    // match the analytic one to within the same tolerance (scaled by the grazing angle).
    let slack = 1.0 - (std::f64::consts::PI / 32.0).cos();
    let (mut compared, mut hits) = (0, 0);
    for y in 0..size {
        for x in 0..size {
            let d = cam.ray_dir(x as f32 + 0.5, y as f32 + 0.5);
            let o = cam.position();
            let (od, dd) = (o.as_dvec3(), d.as_dvec3());
            let b = od.dot(dd);
            let q = od - dd * b;
            let closest = q.length();
            let analytic = 1.0 - q.length_squared() > 0.0;
            if (closest - 1.0).abs() < 2.0 * slack {
                continue;
            }
            compared += 1;
            let hit = scene.intersect(o, d, 0.0, f32::INFINITY);
            assert_eq!(hit.is_some(), analytic, "pixel ({x}, {y})");
            if let Some(h) = hit {
                hits += 1;
                let t = -b - (1.0 - q.length_squared()).sqrt();
                let cos = (1.0 - closest * closest).sqrt();
                assert!((h.t as f64 - t).abs() <= slack / cos.max(0.05) + 1e-5, "pixel ({x}, {y}): t {} vs {t}", h.t);
            }
        }
    }
    assert!(compared > size * size * 95 / 100, "only {compared} pixels away from the silhouette");
    // The workload reports 69.8 % of the pixels covered at 512²; a few silhouette pixels are left out here.
    assert!((hits as f64 / (size * size) as f64 - 0.698).abs() < 0.03, "{hits} hits");
}

#[test]
fn embedded_bunny_loads_with_normals_and_uvs() {
    let m = scenes::bunny_mesh();
    assert_eq!(m.triangle_count(), 3674);
    assert_eq!(m.normals.len(), m.positions.len());
    assert!(m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
    assert!(m.uvs.iter().all(|uv| (0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y)));
}
