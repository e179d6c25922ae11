//! # anysl-rsl
//!
//! The RenderMan Shading Language front end (preprocessor, parser, checker), the portable
//! threaded IR and its back ends (generated Rust, batched interpreter).
//!
//! This crate is the home of that work; it is being built in a later stage of the project
//! (see `ARCHITECTURE.md`). Today it only re-exports the core contracts the back ends target.
pub use anysl_core as core;
