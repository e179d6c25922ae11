//! Polygons.
use super::{err, Detail, Result, Tessellation};
use anysl_rib::ParamList;
/// `Polygon`.
pub fn polygon(_params: &ParamList, _d: &Detail) -> Result<Tessellation> {
    err("x".into())
}
/// `GeneralPolygon`.
pub fn general_polygon(_nverts: &[i32], _params: &ParamList, _d: &Detail) -> Result<Tessellation> {
    err("x".into())
}
/// `PointsPolygons`.
pub fn points_polygons(_nverts: &[i32], _verts: &[i32], _params: &ParamList, _d: &Detail) -> Result<Tessellation> {
    err("x".into())
}
/// `PointsGeneralPolygons`.
pub fn points_general_polygons(
    _nloops: &[i32],
    _nverts: &[i32],
    _verts: &[i32],
    _params: &ParamList,
    _d: &Detail,
) -> Result<Tessellation> {
    err("x".into())
}
