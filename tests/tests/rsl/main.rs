//! The `.sl` half of the cross-crate tests, one test binary (the shader-instantiation half is
//! `tests/integration/`; two binaries so both cores compile at once, each monomorphizing the
//! generic code it needs once). `cargo test -p anysl-tests --test rsl <module>::` runs one file.

mod jit_check;
mod jit_eval;
mod rsl_conformance_generated;
mod rsl_conformance_interp;
mod rsl_generated;
mod rsl_interp_render;
mod stages_generated;
