//! NuPatch.
use super::{err, Detail, Result, Tessellation};
use anysl_rib::ParamList;
/// `NuPatch`.
#[allow(clippy::too_many_arguments)]
pub fn nu_patch(
    _nu: i32,
    _uorder: i32,
    _uknot: &[f32],
    _umin: f32,
    _umax: f32,
    _nv: i32,
    _vorder: i32,
    _vknot: &[f32],
    _vmin: f32,
    _vmax: f32,
    _params: &ParamList,
    _d: &Detail,
) -> Result<Tessellation> {
    err("NuPatch: not yet".into())
}
