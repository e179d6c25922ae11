//! The RSL run-time library: the services a shader calls that `anysl-core`'s numeric
//! standard library does not offer — `format`/`printf`, `match`, texture and environment
//! look-ups with their image cache, and parameter arrays by name.
//!
//! It belongs to no back end: generated Rust (`anysl-rsl`'s Rust generator emits calls to
//! `::anysl_rt::…`), the interpreter and the JIT all call these functions, so every back end
//! formats, matches and samples alike, and a crate of generated shaders needs the compiler
//! only at build time.

pub mod format;
pub mod params;
pub mod pattern;
pub mod texture;

pub use format::{format_rsl, FmtArg};
pub use params::{array_from_value, array_value, lane0};
pub use pattern::simple_match;
pub use texture::{environment, texture};
