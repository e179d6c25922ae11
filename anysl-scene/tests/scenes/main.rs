//! Scenes rendered end to end, one binary: the modules share the renderers' instantiations
//! that separate binaries would each compile.
//!
//! `cargo test -p anysl-scene --test scenes spaces::` runs one module.

mod displacement;
mod examples;
mod known_answers;
mod lights;
mod spaces;
mod textures;
mod volumes;
