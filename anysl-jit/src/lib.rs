//! # anysl-jit
//!
//! The run-time LLVM back end for RSL shaders (cargo feature `jit` of the CLI).
//!
//! This crate is the home of that work; it is being built in a later stage of the project
//! (see `ARCHITECTURE.md`). Today it only re-exports the front end it will consume.
pub use anysl_rsl as rsl;
