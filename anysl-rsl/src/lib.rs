//! # anysl-rsl
//!
//! The RenderMan Shading Language front end (preprocessor, parser, checker), the portable
//! threaded IR and its back ends (generated Rust, batched interpreter).
//!
//! The pipeline: [`front`] (source → tokens → AST → checked and lowered) → [`ir`] (threaded
//! code over structured control flow) → passes → back ends.
pub use anysl_core as core;

pub mod back;
pub mod builtins;
pub mod compile;
pub mod diag;
pub mod eval;
pub mod front;
pub mod ir;
pub mod passes;
pub mod span;
pub mod types;

pub use compile::{compile_file, compile_file_all, compile_source, CompileError, CompileOptions, Compiled};
