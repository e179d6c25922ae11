//! The shading workload (`shaders/assets/workload_ref/shading_workload.md`): the generic plastic, wood and
//! granite with the workload's coefficients and [`table1_lights`] reproduce its float64
//! reference images, instantiated with f32, within the workload's bound of 1e-4.

use anysl_core::prelude::*;
use anysl_core::PointContext;
use anysl_shaders::{table1_lights, Granite, Light, Plastic, Wood};
use std::path::PathBuf;

const W: usize = 512;

/// A hit pixel: its index and (P, N, V) rounded to f32.
type Hit = (usize, [f32; 3], [f32; 3], [f32; 3]);

/// The workload's shading inputs (§2), in pixel order.
fn hits() -> Vec<Hit> {
    let mut out = Vec::new();
    for row in 0..W {
        for col in 0..W {
            let sx = ((col as f64 + 0.5) * (2.0 / 512.0) - 1.0) * 0.375;
            let sy = (1.0 - (row as f64 + 0.5) * (2.0 / 512.0)) * 0.375;
            let l = (sx * sx + sy * sy + 1.0f64).sqrt();
            let d = [sx / l, sy / l, -1.0 / l];
            let o = [0.0, 0.0, 3.0];
            let b = o[2] * d[2];
            let q = [o[0] - b * d[0], o[1] - b * d[1], o[2] - b * d[2]];
            let h = 1.0 - (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
            if h > 0.0 {
                let t = -b - h.sqrt();
                let p = [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];
                let pl = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                let n = p.map(|c| (c / pl) as f32);
                out.push((row * W + col, p.map(|c| c as f32), n, d.map(|c| -c as f32)));
            }
        }
    }
    out
}

/// A reference image (`.npy`, `<f4`, 512×512×3), or `None` when the workload is not checked out.
fn reference(name: &str) -> Option<Vec<f32>> {
    let path: PathBuf =
        [env!("CARGO_MANIFEST_DIR"), "..", "..", "shared", "bench", "ref", &format!("{name}.npy")].iter().collect();
    let bytes = std::fs::read(&path).ok()?;
    assert_eq!(&bytes[..6], b"\x93NUMPY", "{}: not an npy file", path.display());
    let header = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let data = &bytes[10 + header..];
    assert_eq!(data.len(), W * W * 3 * 4);
    Some(data.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect())
}

fn check<S: SurfaceShader>(name: &str, shader: &S, cs: [f64; 3]) {
    let Some(reference) = reference(name) else {
        eprintln!("skipping {name}: shared/bench/ref not found");
        return;
    };
    let lights: Vec<Light> = table1_lights();
    let pts = hits();
    assert_eq!(pts.len(), 183_020, "hit count of the workload");
    let mut max_err = 0.0f64;
    for &(pix, p, n, v) in &pts {
        let mut g = Globals::<f32>::unit_square(0.0, 0.0);
        g.P = Vec3::new(p[0], p[1], p[2]);
        g.N = Vec3::new(n[0], n[1], n[2]);
        g.Ng = g.N;
        g.I = Vec3::new(-v[0], -v[1], -v[2]);
        g.E = Vec3::c(0.0, 0.0, 3.0);
        g.Cs = Color::from_array(cs);
        let mut ctx = PointContext::new(g, &lights);
        let out = shader.shade(&mut ctx, &mut Exec::new());
        let ci = out.Ci.lane(0);
        for c in 0..3 {
            max_err = max_err.max((ci[c] - reference[pix * 3 + c] as f64).abs());
        }
    }
    eprintln!("{name}: max |f32 - reference| = {max_err:.3e}");
    assert!(max_err <= 1e-4, "{name}: max error {max_err:e} exceeds the workload's 1e-4");
}

#[test]
fn plastic_reproduces_the_workload() {
    let plastic = Plastic { Ka: 1.0, Kd: 0.8, Ks: 0.5, roughness: 0.08, ..Plastic::default() };
    check("plastic", &plastic, [0.80, 0.25, 0.15]);
}

#[test]
fn wood_reproduces_the_workload() {
    check("wood", &Wood { roughness: 0.08, ..Wood::default() }, [1.0; 3]);
}

#[test]
fn granite_reproduces_the_workload() {
    check("granite", &Granite { roughness: 0.08, ..Granite::default() }, [1.0; 3]);
}
