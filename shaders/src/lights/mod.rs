//! The light shaders (RenderMan Interface 3.2 standard lights), one module each.

pub mod ambientlight;
pub mod distantlight;
pub mod pointlight;
pub mod spotlight;

pub use ambientlight::AmbientLight;
pub use distantlight::DistantLight;
pub use pointlight::PointLight;
pub use spotlight::SpotLight;

/// `Color::from_array(colour) * F::c(intensity)` as the `f32`-based float types compute it
/// (each number rounded to `f32`, then one `f32` product): a light's `Cl` in [`LightData`].
fn colour_times(colour: [f64; 3], intensity: f64) -> [f32; 3] {
    colour.map(|c| c as f32 * intensity as f32)
}
