//! The "native" rows of the kernel benchmark: hand-written `wide::f32x8` Phong and Checker
//! run over the same point set as the generic shaders (`anysl_shaders::native`).

use anysl_shaders::Surface;

/// A native runner: same signature as the generic instantiations.
pub use anysl_shaders::native::PointSetRunner as NativeRunner;

/// The native kernel for `surface`, if one exists.
pub fn runner(surface: &Surface) -> Option<NativeRunner> {
    anysl_shaders::native::point_set_runner(surface)
}
