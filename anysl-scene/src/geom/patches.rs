//! Patches.
use super::{err, Detail, Result, Tessellation};
use anysl_rib::ParamList;
use glam::Mat4;
/// Basis.
#[derive(Clone, Debug)]
pub struct PatchBasis {
    pub u: Mat4,
    pub ustep: u32,
    pub v: Mat4,
    pub vstep: u32,
}
/// `Patch`.
pub fn patch(_kind: &str, _basis: &PatchBasis, _params: &ParamList, _d: &Detail) -> Result<Tessellation> {
    err("x".into())
}
/// `PatchMesh`.
#[allow(clippy::too_many_arguments)]
pub fn patch_mesh(
    _kind: &str,
    _nu: i32,
    _uwrap: &str,
    _nv: i32,
    _vwrap: &str,
    _basis: &PatchBasis,
    _params: &ParamList,
    _d: &Detail,
) -> Result<Tessellation> {
    err("x".into())
}
