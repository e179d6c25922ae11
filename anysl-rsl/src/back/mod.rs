//! Back ends: the batched interpreter (run time, no LLVM) and generated Rust (build time).

pub mod interp;
pub mod rust;
