//! Triangle meshes: [`Mesh`] with per-vertex positions, normals and texture coordinates, the
//! triangulated UV sphere of the AnySL paper's scene, a ground quad, and an OBJ reader
//! ([`Mesh::from_obj`]) for `v`/`vn`/`vt`/`f` with polygons and negative indices.

use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::fmt;

/// An indexed triangle mesh; `normals` and `uvs` have one entry per position, and so has each
/// optional per-vertex array that is present.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions (object space).
    pub positions: Vec<Vec3>,
    /// Unit vertex normals (object space).
    pub normals: Vec<Vec3>,
    /// Surface parameters `(u, v)`; also the texture coordinates `(s, t)` unless `st` is given.
    pub uvs: Vec<Vec2>,
    /// Triangles as vertex indices, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// Texture coordinates `(s, t)` when they differ from `(u, v)`.
    pub st: Option<Vec<Vec2>>,
    /// ∂P/∂u and ∂P/∂v of the exact surface (object space); without them they come from each
    /// triangle's `(u, v)`.
    pub dpdu_dpdv: Option<(Vec<Vec3>, Vec<Vec3>)>,
    /// Per-vertex surface colour `Cs` (else the instance's colour).
    pub cs: Option<Vec<[f32; 3]>>,
    /// Per-vertex surface opacity `Os` (else the instance's opacity).
    pub os: Option<Vec<[f32; 3]>>,
}

/// An OBJ file that could not be read: the file, the 1-based line and what was wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjError {
    /// File name as given to the reader.
    pub file: String,
    /// 1-based line number (0 for errors about the whole file).
    pub line: usize,
    /// What was wrong.
    pub message: String,
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.file, self.line, self.message)
    }
}

impl std::error::Error for ObjError {}

impl Mesh {
    /// Number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// A UV sphere of `radius` at the origin with `segments` steps of longitude and `rings`
    /// steps of latitude, smooth (analytic) normals and `s` = longitude / 2π (0 at +x,
    /// increasing towards −z, i.e. counter-clockwise seen from +y), `t` = polar angle / π
    /// (0 at the north pole +y, 1 at the south pole). Both poles are fans of triangles.
    ///
    /// # Panics
    /// When `segments < 3` or `rings < 2`.
    #[must_use]
    pub fn uv_sphere(radius: f32, segments: u32, rings: u32) -> Self {
        assert!(segments >= 3 && rings >= 2, "a UV sphere needs ≥ 3 segments and ≥ 2 rings");
        let mut m = Mesh::default();
        // One seam column is duplicated so that s runs continuously from 0 to 1.
        for r in 0..=rings {
            let t = r as f32 / rings as f32;
            let theta = t * std::f32::consts::PI;
            for sgm in 0..=segments {
                let s = sgm as f32 / segments as f32;
                let phi = s * std::f32::consts::TAU;
                let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin());
                m.positions.push(n * radius);
                m.normals.push(n);
                m.uvs.push(Vec2::new(s, t));
            }
        }
        let row = segments + 1;
        for r in 0..rings {
            for sgm in 0..segments {
                let a = r * row + sgm;
                let b = a + row;
                // a — a+1 on the upper ring, b — b+1 on the lower; CCW seen from outside.
                if r != 0 {
                    m.triangles.push([a, b, a + 1]);
                }
                if r != rings - 1 {
                    m.triangles.push([a + 1, b, b + 1]);
                }
            }
        }
        m
    }

    /// A square in the y = 0 plane facing +y, `size` on a side, centred at the origin;
    /// `s` along +x and `t` along +z, each spanning `[0, tiles]`.
    #[must_use]
    pub fn ground_quad(size: f32, tiles: f32) -> Self {
        let h = size * 0.5;
        Mesh {
            positions: vec![Vec3::new(-h, 0.0, -h), Vec3::new(h, 0.0, -h), Vec3::new(h, 0.0, h), Vec3::new(-h, 0.0, h)],
            normals: vec![Vec3::Y; 4],
            uvs: vec![Vec2::new(0.0, 0.0), Vec2::new(tiles, 0.0), Vec2::new(tiles, tiles), Vec2::new(0.0, tiles)],
            triangles: vec![[0, 2, 1], [0, 3, 2]],
            ..Mesh::default()
        }
    }

    /// Reads a Wavefront OBJ from text. `file` names the source in error messages.
    ///
    /// Supported: `v x y z [w]`, `vn`, `vt u [v [w]]`, `f` with `i`, `i/t`, `i//n`, `i/t/n`
    /// references (1-based; negative = relative to the end so far), polygons of any size
    /// (fan-triangulated). Other statements (`o`, `g`, `s`, `usemtl`, `mtllib`, …) are
    /// ignored. Missing normals are computed (area-weighted, smooth); missing texture
    /// coordinates are a planar projection of the bounding box onto its two largest axes.
    ///
    /// # Errors
    /// A malformed number, an index out of range or a face with fewer than three vertices;
    /// the error names the file and line.
    pub fn from_obj(text: &str, file: &str) -> Result<Self, ObjError> {
        let err = |line: usize, message: String| ObjError { file: file.to_string(), line, message };
        let mut pos: Vec<Vec3> = Vec::new();
        let mut nrm: Vec<Vec3> = Vec::new();
        let mut tex: Vec<Vec2> = Vec::new();
        // Unique (position, texcoord, normal) triples become vertices.
        let mut verts: HashMap<(u32, u32, u32), u32> = HashMap::new();
        let mut keys: Vec<(u32, u32, u32)> = Vec::new();
        let mut triangles: Vec<[u32; 3]> = Vec::new();
        let mut poly: Vec<u32> = Vec::new();
        const NONE: u32 = u32::MAX;

        for (lineno, raw) in text.lines().enumerate() {
            let lineno = lineno + 1;
            let line = raw.split('#').next().unwrap_or("").trim();
            let mut it = line.split_whitespace();
            let Some(tag) = it.next() else { continue };
            let mut floats = |n_min: usize, n_max: usize| -> Result<Vec<f32>, ObjError> {
                let vals: Vec<&str> = it.by_ref().collect();
                if vals.len() < n_min || vals.len() > n_max {
                    return Err(err(lineno, format!("'{tag}' needs {n_min} to {n_max} numbers, found {}", vals.len())));
                }
                vals.iter()
                    .map(|v| {
                        v.parse::<f32>()
                            .ok()
                            .filter(|x| x.is_finite())
                            .ok_or_else(|| err(lineno, format!("'{v}' is not a finite number")))
                    })
                    .collect()
            };
            match tag {
                "v" => {
                    let v = floats(3, 4)?;
                    pos.push(Vec3::new(v[0], v[1], v[2]));
                }
                "vn" => {
                    let v = floats(3, 3)?;
                    nrm.push(Vec3::new(v[0], v[1], v[2]).normalize_or_zero());
                }
                "vt" => {
                    let v = floats(1, 3)?;
                    tex.push(Vec2::new(v[0], v.get(1).copied().unwrap_or(0.0)));
                }
                "f" => {
                    poly.clear();
                    for r in it {
                        let mut parts = r.split('/');
                        let resolve = |s: Option<&str>, len: usize, what: &str| -> Result<u32, ObjError> {
                            match s {
                                None | Some("") => Ok(NONE),
                                Some(s) => {
                                    let i: i64 =
                                        s.parse().map_err(|_| err(lineno, format!("'{s}' is not a {what} index")))?;
                                    let idx = if i > 0 { i - 1 } else { len as i64 + i };
                                    if i == 0 || idx < 0 || idx >= len as i64 {
                                        Err(err(lineno, format!("{what} index {i} out of range (have {len})")))
                                    } else {
                                        Ok(idx as u32)
                                    }
                                }
                            }
                        };
                        let p = resolve(parts.next(), pos.len(), "vertex")?;
                        if p == NONE {
                            return Err(err(lineno, format!("face vertex '{r}' has no position index")));
                        }
                        let t = resolve(parts.next(), tex.len(), "texture coordinate")?;
                        let n = resolve(parts.next(), nrm.len(), "normal")?;
                        let key = (p, t, n);
                        let id = *verts.entry(key).or_insert_with(|| {
                            keys.push(key);
                            keys.len() as u32 - 1
                        });
                        poly.push(id);
                    }
                    if poly.len() < 3 {
                        return Err(err(lineno, format!("a face needs at least 3 vertices, found {}", poly.len())));
                    }
                    for k in 1..poly.len() - 1 {
                        triangles.push([poly[0], poly[k], poly[k + 1]]);
                    }
                }
                _ => {}
            }
        }
        if triangles.is_empty() {
            return Err(err(0, "no faces".to_string()));
        }

        let positions: Vec<Vec3> = keys.iter().map(|k| pos[k.0 as usize]).collect();
        let have_normals = keys.iter().all(|k| k.2 != NONE);
        let have_uvs = keys.iter().all(|k| k.1 != NONE);
        let mut mesh = Mesh {
            normals: if have_normals { keys.iter().map(|k| nrm[k.2 as usize]).collect() } else { Vec::new() },
            uvs: if have_uvs { keys.iter().map(|k| tex[k.1 as usize]).collect() } else { Vec::new() },
            positions,
            triangles,
            ..Mesh::default()
        };
        if !have_normals {
            mesh.compute_smooth_normals(&keys.iter().map(|k| k.0).collect::<Vec<_>>());
        }
        if !have_uvs {
            mesh.planar_uvs();
        }
        Ok(mesh)
    }

    /// Area-weighted vertex normals, shared by all vertices with the same position index
    /// (`position_of[v]`), so that splitting a vertex for its texture coordinate does not
    /// crease the surface.
    fn compute_smooth_normals(&mut self, position_of: &[u32]) {
        let n_pos = position_of.iter().map(|&p| p as usize + 1).max().unwrap_or(0);
        let mut acc = vec![Vec3::ZERO; n_pos];
        for tri in &self.triangles {
            let [a, b, c] = tri.map(|i| self.positions[i as usize]);
            let n = (b - a).cross(c - a); // length = 2 × area
            for &i in tri {
                acc[position_of[i as usize] as usize] += n;
            }
        }
        self.normals = position_of.iter().map(|&p| acc[p as usize].normalize_or(Vec3::Y)).collect();
    }

    /// `(s, t)` from the bounding box: the largest extent maps to s, the second to t.
    fn planar_uvs(&mut self) {
        let (lo, hi) = self.bounds();
        let ext = hi - lo;
        let mut axes = [0usize, 1, 2];
        axes.sort_by(|&a, &b| ext[b].total_cmp(&ext[a]));
        let (a, b) = (axes[0], axes[1]);
        let inv = |k: usize| if ext[k] > 0.0 { 1.0 / ext[k] } else { 0.0 };
        self.uvs = self.positions.iter().map(|p| Vec2::new((p[a] - lo[a]) * inv(a), (p[b] - lo[b]) * inv(b))).collect();
    }

    /// Axis-aligned bounds `(min, max)` of the positions.
    #[must_use]
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.positions
            .iter()
            .fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(lo, hi), p| (lo.min(*p), hi.max(*p)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_and_negative_indices() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf -4//1 -3//1 -2//1 -1//1\n";
        let m = Mesh::from_obj(text, "quad.obj").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.normals, vec![Vec3::Z; 4]);
        assert_eq!(m.uvs.len(), 4);
    }

    #[test]
    fn errors_name_file_and_line() {
        let e = Mesh::from_obj("v 0 0 0\nv 1 0 0\n\nf 1 2 5\n", "bad.obj").unwrap_err();
        assert_eq!((e.file.as_str(), e.line), ("bad.obj", 4));
        assert!(e.to_string().starts_with("bad.obj:4: vertex index 5 out of range"), "{e}");
        let e = Mesh::from_obj("v 0 zero 0\n", "n.obj").unwrap_err();
        assert_eq!(e.to_string(), "n.obj:1: 'zero' is not a finite number");
        let e = Mesh::from_obj("v 0 0 0\nv 1 0 0\nf 1 2\n", "f.obj").unwrap_err();
        assert_eq!(e.line, 3);
    }

    #[test]
    fn computed_normals_face_outward() {
        // A tetrahedron-like fan: the normal of CCW triangle (0,1,2) in z = 0 is +z.
        let m = Mesh::from_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj").unwrap();
        for n in &m.normals {
            assert!((*n - Vec3::Z).length() < 1e-6);
        }
    }

    #[test]
    fn sphere_is_closed_and_outward() {
        let m = Mesh::uv_sphere(1.0, 16, 8);
        assert_eq!(m.triangle_count(), 2 * 16 * 8 - 2 * 16);
        for tri in &m.triangles {
            let [a, b, c] = tri.map(|i| m.positions[i as usize]);
            let n = (b - a).cross(c - a);
            assert!(n.dot(a + b + c) > 0.0, "triangle {tri:?} faces inward");
        }
        for (p, n) in m.positions.iter().zip(&m.normals) {
            assert!((p.length() - 1.0).abs() < 1e-5 && (*p - *n).length() < 1e-5);
        }
    }
}
