//! Teapot.
use super::{Detail, Tessellation};
/// Points.
pub const TEAPOT_POINTS: [[f32; 3]; 0] = [];
/// Patches.
pub const TEAPOT_PATCHES: [[u16; 16]; 0] = [];
/// `Geometry "teapot"`.
pub fn teapot(_d: &Detail) -> Tessellation {
    Tessellation::default()
}
