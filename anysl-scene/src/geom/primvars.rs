//! Primitive variables: checking their counts per storage class and interpolating them to
//! the tessellation's vertices.
//!
//! A primitive says how many items each class needs ([`Counts`]) and, for each output vertex,
//! which items it blends with which weights ([`Interp`]); this module does the rest for every
//! primitive alike: `"N"` (or the per-polygon `"Np"`) replaces the normals, `"Cs"`/`"Os"` fill the colour slots,
//! `"st"`, `"s"`, `"t"` the texture coordinates, and every other float variable becomes a
//! [`PrimVar`].

use super::{err, unit, PrimVar, Result, Tessellation};
use anysl_rib::{Class, Param, ParamList, Values};
use glam::Vec3;

/// How many items each storage class needs on a primitive (constant is always 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Counts {
    pub uniform: usize,
    pub varying: usize,
    pub vertex: usize,
    pub facevarying: usize,
    /// Vertex and varying variables may hold more items than used (PointsPolygons: the
    /// count is 1 + the largest vertex index, and more points are tolerated).
    pub vertex_at_least: bool,
}

impl Counts {
    /// The items class `class` needs.
    pub fn of(&self, class: Class) -> usize {
        match class {
            Class::Constant => 1,
            Class::Uniform => self.uniform,
            Class::Varying => self.varying,
            Class::Vertex => self.vertex,
            Class::FaceVarying | Class::FaceVertex => self.facevarying,
        }
    }
}

/// Where each output vertex takes its primitive-variable values from.
pub(crate) trait Interp {
    /// Items per class.
    fn counts(&self) -> Counts;
    /// Number of output vertices.
    fn vertices(&self) -> usize;
    /// The items (index, weight) that vertex `vertex` blends for class `class`; `out` is
    /// cleared first. Indices are below `counts().of(class)`.
    fn weights(&self, class: Class, vertex: usize, out: &mut Vec<(usize, f32)>);
}

/// Checks that `param` has the number of values its class needs on this primitive.
pub(crate) fn check_count(request: &str, param: &Param, counts: &Counts) -> Result<usize> {
    let per = param.decl.values_per_item().max(1);
    let items = counts.of(param.decl.class);
    let expected = items.saturating_mul(per);
    let n = param.values.len();
    let at_least = counts.vertex_at_least && matches!(param.decl.class, Class::Vertex | Class::Varying);
    let ok = if at_least { n >= expected && n.is_multiple_of(per) } else { n == expected };
    if !ok {
        return err(format!(
            "{request}: \"{}\" ({} {}) has {n} values, expected {}{expected} ({items} {} × {per})",
            param.name,
            param.decl.class.keyword(),
            param.decl.ty.keyword(),
            if at_least { "at least " } else { "" },
            if items == 1 { "item" } else { "items" },
        ));
    }
    Ok(per)
}

/// The float values of a numeric parameter (integers converted); `None` for strings.
fn float_values(param: &Param) -> Option<std::borrow::Cow<'_, [f32]>> {
    match &param.values {
        Values::Float(v) => Some(std::borrow::Cow::Borrowed(v)),
        Values::Int(v) => Some(std::borrow::Cow::Owned(v.iter().map(|&i| i as f32).collect())),
        Values::String(_) => None,
    }
}

/// Interpolates `values` (`per` per item) to every vertex.
pub(crate) fn interpolate(interp: &dyn Interp, class: Class, values: &[f32], per: usize) -> Vec<f32> {
    let n = interp.vertices();
    let mut out = vec![0.0f32; n * per];
    let mut w = Vec::with_capacity(16);
    for v in 0..n {
        interp.weights(class, v, &mut w);
        let dst = &mut out[v * per..(v + 1) * per];
        for &(item, weight) in &w {
            if let Some(src) = values.get(item * per..(item + 1) * per) {
                for (d, s) in dst.iter_mut().zip(src) {
                    *d += weight * s;
                }
            }
        }
    }
    out
}

/// Applies every parameter except those in `skip` (the positions, which the primitive
/// handles) to `t`, checking counts first.
pub(crate) fn apply(
    t: &mut Tessellation,
    request: &str,
    params: &ParamList,
    interp: &dyn Interp,
    skip: &[&str],
) -> Result<()> {
    let counts = interp.counts();
    // The last of several parameters of one name wins (as `ParamList::get`).
    for (i, param) in params.iter().enumerate() {
        if skip.contains(&param.name.as_str()) || params.params[i + 1..].iter().any(|p| p.name == param.name) {
            continue;
        }
        let per = check_count(request, param, &counts)?;
        let Some(values) = float_values(param) else {
            if param.decl.class != Class::Constant && param.decl.class != Class::Uniform {
                t.warnings.push(format!("{request}: string variable \"{}\" is not interpolated", param.name));
            }
            continue;
        };
        let vals = interpolate(interp, param.decl.class, &values, per);
        match (param.name.as_str(), per) {
            // "Np" is the uniform (per-polygon) normal of RI polygons.
            ("N" | "Np", 3) => {
                for (n, v) in t.normals.iter_mut().zip(vals.chunks_exact(3)) {
                    if let Some(u) = unit(Vec3::new(v[0], v[1], v[2])) {
                        *n = u;
                    }
                }
            }
            ("Cs", 3) => t.cs = Some(vals.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()),
            ("Os", 3) => t.os = Some(vals.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()),
            ("st", 2) => {
                for (st, v) in t.st.iter_mut().zip(vals.chunks_exact(2)) {
                    *st = glam::Vec2::new(v[0], v[1]);
                }
            }
            ("s", 1) => t.st.iter_mut().zip(&vals).for_each(|(st, &s)| st.x = s),
            ("t", 1) => t.st.iter_mut().zip(&vals).for_each(|(st, &v)| st.y = v),
            _ => t.primvars.push(PrimVar { name: param.name.clone(), components: per, values: vals }),
        }
    }
    Ok(())
}

/// The positions of a primitive from `"P"` (points), `"Pw"` (homogeneous, divided by w later)
/// or, when `allow_pz`, `"Pz"` (heights; x and y are filled in by the caller): homogeneous
/// (x, y, z, w) per control point, and the name used.
pub(crate) fn positions(request: &str, params: &ParamList, allow_pz: bool) -> Result<(Vec<glam::Vec4>, &'static str)> {
    let pick = |name: &'static str| params.get(name).map(|p| (name, p));
    let found = pick("P").or_else(|| pick("Pw")).or_else(|| if allow_pz { pick("Pz") } else { None });
    let Some((name, p)) = found else {
        let also = if allow_pz { ", \"Pw\" or \"Pz\"" } else { " or \"Pw\"" };
        return err(format!("{request}: no positions; give \"P\"{also}"));
    };
    let Some(vals) = p.floats() else {
        return err(format!("{request}: \"{name}\" must hold numbers"));
    };
    let per = match name {
        "P" => 3,
        "Pw" => 4,
        _ => 1,
    };
    if vals.len() % per != 0 {
        return err(format!("{request}: \"{name}\" has {} values, not a multiple of {per}", vals.len()));
    }
    if p.decl.class != Class::Vertex && p.decl.class != Class::Varying {
        return err(format!("{request}: \"{name}\" must be of class vertex, not {}", p.decl.class.keyword()));
    }
    Ok((
        vals.chunks_exact(per)
            .map(|c| match per {
                3 => glam::Vec4::new(c[0], c[1], c[2], 1.0),
                4 => glam::Vec4::new(c[0], c[1], c[2], c[3]),
                _ => glam::Vec4::new(0.0, 0.0, c[0], 1.0),
            })
            .collect(),
        name,
    ))
}

/// The names the position handling consumes.
pub(crate) const POSITION_NAMES: &[&str] = &["P", "Pw", "Pz"];
