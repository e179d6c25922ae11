//! The workload's reference images (§8) — NumPy `.npy` files, read by a small reader — and
//! the error metrics of §6.

use std::path::{Path, PathBuf};

use super::scene::SIZE;
use super::WorkloadScene;

/// Where the reference arrays live in this repository (`shaders/assets/workload_ref/`, copied
/// from `shared/bench/ref/` together with the workload definition).
#[must_use]
pub fn reference_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets").join("workload_ref")
}

/// The element types the reader understands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Dtype {
    /// `<f4`.
    F32,
    /// `|b1`.
    Bool,
}

/// Parses a `.npy` file (version 1.x or 2.x, C order) and returns its dtype, shape and data.
fn parse_npy(bytes: &[u8]) -> Result<(Dtype, Vec<usize>, &[u8]), String> {
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err("not a .npy file (magic \\x93NUMPY missing)".into());
    }
    let (header_len, start) = match bytes[6] {
        1 => (usize::from(u16::from_le_bytes([bytes[8], bytes[9]])), 10),
        2 | 3 if bytes.len() >= 12 => (u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize, 12),
        v => return Err(format!("unsupported .npy version {v}")),
    };
    let header = bytes
        .get(start..start + header_len)
        .and_then(|h| std::str::from_utf8(h).ok())
        .ok_or("truncated or non-ASCII .npy header")?;
    let field = |key: &str| -> Result<&str, String> {
        let at = header.find(&format!("'{key}'")).ok_or_else(|| format!("no '{key}' in .npy header {header:?}"))?;
        let rest = header[at + key.len() + 2..].trim_start();
        Ok(rest.strip_prefix(':').unwrap_or(rest).trim_start())
    };
    let dtype = match field("descr")? {
        d if d.starts_with("'<f4'") => Dtype::F32,
        d if d.starts_with("'|b1'") => Dtype::Bool,
        d => return Err(format!("unsupported dtype {d:?} (expected '<f4' or '|b1')")),
    };
    if !field("fortran_order")?.starts_with("False") {
        return Err("Fortran-ordered arrays are not supported".into());
    }
    let shape_text = field("shape")?;
    let close = shape_text.find(')').ok_or("malformed shape in .npy header")?;
    let shape: Vec<usize> = shape_text[1..close]
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<usize>().map_err(|e| format!("bad shape entry {s:?}: {e}")))
        .collect::<Result<_, _>>()?;
    let count: usize = shape.iter().product();
    let size = count
        * match dtype {
            Dtype::F32 => 4,
            Dtype::Bool => 1,
        };
    let data = bytes
        .get(start + header_len..start + header_len + size)
        .ok_or_else(|| format!("truncated .npy data: expected {size} bytes"))?;
    Ok((dtype, shape, data))
}

fn read(path: &Path) -> Result<Vec<u8>, String> {
    std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))
}

/// Reads a little-endian f32 `.npy` array: `(shape, values in C order)`.
pub fn read_npy_f32(path: &Path) -> Result<(Vec<usize>, Vec<f32>), String> {
    let bytes = read(path)?;
    let (dtype, shape, data) = parse_npy(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    if dtype != Dtype::F32 {
        return Err(format!("{}: expected a float32 array", path.display()));
    }
    let values = data.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
    Ok((shape, values))
}

/// Reads a bool `.npy` array: `(shape, values in C order)`.
pub fn read_npy_bool(path: &Path) -> Result<(Vec<usize>, Vec<bool>), String> {
    let bytes = read(path)?;
    let (dtype, shape, data) = parse_npy(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    if dtype != Dtype::Bool {
        return Err(format!("{}: expected a bool array", path.display()));
    }
    Ok((shape, data.iter().map(|&b| b != 0).collect()))
}

/// The reference image of `shader` (`plastic`, `checker`, `wood`, `granite`) from `dir`:
/// 512·512·3 values, `[row][col][channel]`.
pub fn load_reference_in(dir: &Path, shader: &str) -> Result<Vec<f32>, String> {
    let path = dir.join(format!("{shader}.npy"));
    let (shape, values) = read_npy_f32(&path)?;
    if shape != [SIZE, SIZE, 3] {
        return Err(format!("{}: shape {shape:?}, expected [512, 512, 3]", path.display()));
    }
    Ok(values)
}

/// The reference image of `shader` from [`reference_dir`].
pub fn load_reference(shader: &str) -> Result<Vec<f32>, String> {
    load_reference_in(&reference_dir(), shader)
}

/// The reference hit mask (`mask.npy`), row-major.
pub fn load_reference_mask() -> Result<Vec<bool>, String> {
    let path = reference_dir().join("mask.npy");
    let (shape, values) = read_npy_bool(&path)?;
    if shape != [SIZE, SIZE] {
        return Err(format!("{}: shape {shape:?}, expected [512, 512]", path.display()));
    }
    Ok(values)
}

/// Errors of an image against a reference (§6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageError {
    /// Max over all values of `|image - reference|` (NaN counts as infinite).
    pub max_abs_err: f64,
    /// Pixels with some channel off by more than 1e-3 (should be 0).
    pub pixels_over_1e3: usize,
}

/// Compares two `[row][col][channel]` images of the same size.
#[must_use]
pub fn image_error(image: &[f32], reference: &[f32]) -> ImageError {
    assert_eq!(image.len(), reference.len(), "images of different sizes");
    let mut max = 0.0f64;
    let mut over = 0;
    for (a, b) in image.chunks_exact(3).zip(reference.chunks_exact(3)) {
        let mut worst = 0.0f64;
        for (x, y) in a.iter().zip(b) {
            let e = (f64::from(*x) - f64::from(*y)).abs();
            worst = worst.max(if e.is_nan() { f64::INFINITY } else { e });
        }
        max = max.max(worst);
        over += usize::from(worst > 1e-3);
    }
    ImageError { max_abs_err: max, pixels_over_1e3: over }
}

/// A timed row of a workload probe: its label and one shading call of every point into the
/// output arrays (each [`WorkloadScene::padded_len`] long).
pub type ProbeRun<'a> = (&'a str, Box<dyn Fn(&mut [Vec<f32>; 3]) + 'a>);

/// The timing loop of the workload probes (`cargo bench --bench workload_probe`, `workload_jit`):
/// one warm-up round, then `rounds` rounds in which every run makes one call in turn (so that
/// drift on a shared machine reaches every row alike); prints, per run, the median and the best
/// call as Mpts/s with the max abs error of its image against `reference`.
///
/// # Panics
/// When `rounds` is 0.
pub fn probe_rounds(scene: &WorkloadScene, shader: &str, reference: &[f32], runs: &[ProbeRun<'_>], rounds: usize) {
    assert!(rounds > 0, "a probe times at least one round");
    let n = scene.padded_len();
    let mut outs: Vec<[Vec<f32>; 3]> = runs.iter().map(|_| [vec![0.0; n], vec![0.0; n], vec![0.0; n]]).collect();
    let mut times = vec![Vec::new(); runs.len()];
    for round in 0..=rounds {
        for (k, (_, f)) in runs.iter().enumerate() {
            let t = std::time::Instant::now();
            f(&mut outs[k]);
            if round > 0 {
                times[k].push(t.elapsed().as_secs_f64());
            }
        }
    }
    let mpts = |secs: f64| scene.n_hit() as f64 / secs / 1e6;
    for (k, (label, _)) in runs.iter().enumerate() {
        let t = &mut times[k];
        t.sort_by(f64::total_cmp);
        let err = image_error(&scene.to_image(&outs[k]), reference);
        println!(
            "{shader:<8} {label:<8} {:8.2} Mpts/s  best {:8.2}  max_abs_err {:.3e}",
            mpts(t[t.len() / 2]),
            mpts(t[0]),
            err.max_abs_err
        );
    }
}
