//! The light shaders (RenderMan Interface 3.2 standard lights), one module each.

pub mod ambientlight;
pub mod distantlight;
pub mod pointlight;
pub mod spotlight;

pub use ambientlight::AmbientLight;
pub use distantlight::DistantLight;
pub use pointlight::PointLight;
pub use spotlight::SpotLight;
