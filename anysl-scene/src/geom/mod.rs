//! The RenderMan geometric primitives (RenderMan Interface 3.2, §5) cut into triangles.
//!
//! Each function takes a request's positional arguments and parameter list and returns a
//! [`Tessellation`]: triangles in object space whose vertices carry the *exact* surface's
//! shading data — the point, the surface parameters (u, v) of the RI spec, the texture
//! coordinates (s, t), the partials dPdu and dPdv, the unit normal, and every primitive
//! variable interpolated as its storage class says. How fine the triangles are is set by a
//! [`Detail`]: the largest distance allowed between the surface and its triangles.
//!
//! The parametric surfaces (quadrics, patches, NURBS, the teapot) share one engine
//! (`grid.rs`): a surface is a grid of faces, each evaluated exactly (point and both
//! partials) on a regular grid whose size comes from a bound on the second derivatives.
//! Polygons are triangulated by fan (convex) or ear clipping (concave, with holes).
//!
//! ```
//! use anysl_scene::geom::{torus, Detail};
//! use anysl_rib::ParamList;
//!
//! let d = Detail { tolerance: 1e-2, ..Detail::default() };
//! let t = torus(1.0, 0.25, 0.0, 360.0, 360.0, &ParamList::new(), &d).unwrap();
//! assert!(!t.triangles.is_empty());
//! assert!(t.uv.iter().all(|uv| (0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y)));
//! ```

mod grid;
mod nurbs;
mod patches;
mod polygons;
mod primvars;
mod quadrics;
mod teapot;

use glam::{Vec2, Vec3};
use std::fmt;

pub use nurbs::nu_patch;
pub use patches::{patch, patch_mesh, PatchBasis};
pub use polygons::{general_polygon, points_general_polygons, points_polygons, polygon};
pub use quadrics::{cone, cylinder, disk, hyperboloid, paraboloid, sphere, torus};
pub use teapot::{teapot, TEAPOT_PATCHES, TEAPOT_POINTS};

/// The most triangles one primitive may produce, so that hostile input cannot exhaust memory.
pub const MAX_TRIANGLES: usize = 4 << 20;

/// A primitive cut into triangles, in object space, with the exact surface's shading data per
/// vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tessellation {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit normals: `normalize(dPdu × dPdv)` of the exact surface (right-handed cross product
    /// of the object-space vectors), or the user's `"N"`; never NaN (at a degenerate point
    /// such as a sphere's pole, the limit from inside the surface).
    pub normals: Vec<Vec3>,
    /// Surface parameters (u, v) as the RI spec defines them for the primitive.
    pub uv: Vec<Vec2>,
    /// Texture coordinates: `"st"`, `"s"`/`"t"`, else the primitive's default.
    pub st: Vec<Vec2>,
    /// Partial derivative of the position along u.
    pub dpdu: Vec<Vec3>,
    /// Partial derivative of the position along v.
    pub dpdv: Vec<Vec3>,
    /// `"Cs"` interpolated to the vertices, if given.
    pub cs: Option<Vec<[f32; 3]>>,
    /// `"Os"` interpolated to the vertices, if given.
    pub os: Option<Vec<[f32; 3]>>,
    /// Every other float primitive variable, interpolated to the vertices.
    pub primvars: Vec<PrimVar>,
    /// Vertex indices, counter-clockwise seen from the side the normals point to.
    pub triangles: Vec<[u32; 3]>,
    /// Things ignored or repaired, e.g. `"NuPatch: trim curves are ignored"`.
    pub warnings: Vec<String>,
}

impl Tessellation {
    /// Number of vertices.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// True when there are no triangles.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The primitive variable called `name`, if any.
    #[must_use]
    pub fn primvar(&self, name: &str) -> Option<&PrimVar> {
        self.primvars.iter().find(|p| p.name == name)
    }

    /// Sum of the triangles' areas.
    #[must_use]
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.positions[i as usize].as_dvec3());
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    /// Appends `other`, renumbering its triangles.
    pub fn append(&mut self, other: Tessellation) {
        let base = self.positions.len();
        let Ok(base32) = u32::try_from(base) else { return };
        let n_other = other.positions.len();
        fn merge_colors(a: &mut Option<Vec<[f32; 3]>>, b: Option<Vec<[f32; 3]>>, base: usize, n: usize) {
            if a.is_none() && b.is_none() {
                return;
            }
            let av = a.get_or_insert_with(|| vec![[1.0; 3]; base]);
            match b {
                Some(bv) => av.extend(bv),
                None => av.extend(std::iter::repeat_n([1.0; 3], n)),
            }
        }
        merge_colors(&mut self.cs, other.cs, base, n_other);
        merge_colors(&mut self.os, other.os, base, n_other);
        for pv in other.primvars {
            match self.primvars.iter_mut().find(|p| p.name == pv.name && p.components == pv.components) {
                Some(mine) => mine.values.extend(pv.values),
                None => {
                    let mut values = vec![0.0; base * pv.components];
                    values.extend(pv.values);
                    self.primvars.push(PrimVar { values, ..pv });
                }
            }
        }
        let total = base + n_other;
        for pv in &mut self.primvars {
            pv.values.resize(total * pv.components, 0.0);
        }
        self.positions.extend(other.positions);
        self.normals.extend(other.normals);
        self.uv.extend(other.uv);
        self.st.extend(other.st);
        self.dpdu.extend(other.dpdu);
        self.dpdv.extend(other.dpdv);
        self.triangles.extend(other.triangles.into_iter().map(|t| t.map(|i| i + base32)));
        self.warnings.extend(other.warnings);
    }

    /// Checks that positions, normals and derivatives are finite and every index is in range.
    pub(crate) fn check(self, request: &str) -> Result<Self> {
        let finite = |v: &Vec3| v.is_finite();
        if !self.positions.iter().all(finite) || !self.dpdu.iter().all(finite) || !self.dpdv.iter().all(finite) {
            return Err(GeomError(format!(
                "{request}: the surface has non-finite points or derivatives (values too large, or a weight of 0)"
            )));
        }
        debug_assert!(self.normals.iter().all(|n| n.is_finite()));
        let n = self.positions.len();
        debug_assert!(self.triangles.iter().all(|t| t.iter().all(|&i| (i as usize) < n)));
        Ok(self)
    }
}

/// A primitive variable interpolated to the vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimVar {
    /// Its name (`"Kd"`, `"uv2"`, …), without the declaration.
    pub name: String,
    /// Floats per vertex (1 for a float, 3 for a colour or point, n × that for arrays).
    pub components: usize,
    /// `components` values per vertex.
    pub values: Vec<f32>,
}

/// How finely to cut: the largest allowed distance between the true surface and its
/// triangles, in object-space units. Segment counts per parametric direction are chosen from
/// it (a bound on the second derivatives of the surface, which for an arc is its chord error)
/// and clamped to `[min_segments, max_segments]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Detail {
    /// Largest distance between surface and triangles, in object space.
    pub tolerance: f32,
    /// Fewest segments per parametric direction (of each patch).
    pub min_segments: u32,
    /// Most segments per parametric direction (of each patch).
    pub max_segments: u32,
}

impl Default for Detail {
    /// Tolerance 1e-3, 4 to 512 segments.
    fn default() -> Self {
        Self { tolerance: 1e-3, min_segments: 4, max_segments: 512 }
    }
}

impl Detail {
    /// A coarse preset for previews: tolerance 1e-2, 2 to 64 segments.
    pub const PREVIEW: Self = Self { tolerance: 1e-2, min_segments: 2, max_segments: 64 };
}

/// A request that cannot be tessellated: the message names the request and what is wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GeomError(pub String);

impl fmt::Display for GeomError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for GeomError {}

/// Result of the tessellators.
pub type Result<T> = std::result::Result<T, GeomError>;

/// Shorthand for an error.
#[cold]
pub(crate) fn err<T>(msg: String) -> Result<T> {
    Err(GeomError(msg))
}

/// The unit vector of `v`, or `None` when it is zero, tiny or not finite.
#[inline]
pub(crate) fn unit(v: Vec3) -> Option<Vec3> {
    let l = v.length();
    (l.is_finite() && l > 1e-30).then(|| v / l).filter(|u| u.is_finite())
}
