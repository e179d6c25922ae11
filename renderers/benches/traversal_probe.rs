//! Traversal probe: the see-through rays of the Table-1 sphere (from each camera hit,
//! onwards along the view ray, starting just off the surface) traced as packets of 4, 8 and
//! 16 rays (2×2, 4×2, 4×4 pixel blocks) and one by one through obvhs's compressed BVH.
//! `cargo bench -p anysl-renderers --bench traversal_probe`; `SIZE=512 RUNS=5` (median),
//! `PRIM=1` traces the camera rays instead.
//!
//! Each row reports time per ray and, as its error, the rays whose packet hit differs in
//! distance from the single-ray hit (0 expected: both use the same triangle test).

use anysl_renderers::accel::{RayPacket, MAX_PACKET};
use anysl_renderers::shading::ray_epsilon;
use anysl_renderers::{render::packet::packet_shape, scenes, Hit};
use anysl_shaders::{table1_lights, Surface};
use glam::Vec3A;
use std::time::Instant;

fn env(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_string())
}

fn main() {
    let size: u32 = env("SIZE", "512").parse().expect("SIZE: a number");
    let runs: usize = env("RUNS", "5").parse().expect("RUNS: a number");
    let primary = std::env::var("PRIM").is_ok();
    let scene = scenes::table1(Surface::by_name("screen").expect("screen"), table1_lights(), size);
    let (cam, o) = (&scene.camera, scene.camera.position());
    println!("rays: {}", if primary { "camera" } else { "see-through, from the sphere's front" });
    println!("{:<8} {:>10} {:>8} {:>12}", "lanes", "ns/ray", "rays", "mismatches");
    for lanes in [1usize, 4, 8, 16] {
        // Single rays trace the rays of the 2×2 blocks.
        let (bw, bh) = packet_shape(lanes.max(4));
        // Blocks whose rays all hit the sphere: (origin, unit direction) per ray.
        let mut packets: Vec<Vec<(Vec3A, Vec3A)>> = Vec::new();
        for by in (0..size).step_by(bh as usize) {
            for bx in (0..size).step_by(bw as usize) {
                let block: Option<Vec<_>> = (0..bw * bh)
                    .map(|l| {
                        let d = cam.ray_dir((bx + l % bw) as f32 + 0.5, (by + l / bw) as f32 + 0.5).normalize();
                        let h = scene.intersect(o, d, 0.0, f32::INFINITY)?;
                        Some(if primary { (o, d) } else { (o + d * h.t, d) })
                    })
                    .collect();
                packets.extend(block);
            }
        }
        let rays = packets.len() * (bw * bh) as usize;
        let tmin = |p: Vec3A| if primary { 0.0 } else { ray_epsilon(p) };
        // The packet hit distances (`None`: a miss), ray by ray in block order.
        let trace = |p: &[(Vec3A, Vec3A)], out: &mut [Option<f32>]| {
            if lanes == 1 {
                for (&(o, d), t) in p.iter().zip(out) {
                    *t = scene.intersect(o, d, tmin(o), f32::INFINITY).map(|h| h.t);
                }
            } else {
                let mut r = RayPacket::default();
                for (i, &(o, d)) in p.iter().enumerate() {
                    r.set(i, o, d, tmin(o), f32::INFINITY);
                }
                let mut found = [Hit { t: 0.0, prim: 0, b1: 0.0, b2: 0.0 }; MAX_PACKET];
                let bits = scene.intersect_packet(&r, &mut found);
                for (i, t) in out.iter_mut().enumerate() {
                    *t = ((bits >> i) & 1 != 0).then_some(found[i].t);
                }
            }
        };
        let mut out = [None; MAX_PACKET];
        let mismatches: usize = packets
            .iter()
            .map(|p| {
                trace(p, &mut out);
                p.iter()
                    .zip(&out)
                    .filter(|(&(o, d), t)| scene.intersect(o, d, tmin(o), f32::INFINITY).map(|h| h.t) != **t)
                    .count()
            })
            .sum();
        let mut times: Vec<f64> = (0..runs)
            .map(|_| {
                let t0 = Instant::now();
                for p in &packets {
                    trace(p, &mut out);
                    std::hint::black_box(&out);
                }
                t0.elapsed().as_nanos() as f64 / rays as f64
            })
            .collect();
        times.sort_by(f64::total_cmp);
        println!("{:<8} {:>10.1} {:>8} {:>12}", lanes, times[times.len() / 2], rays, mismatches);
    }
}
