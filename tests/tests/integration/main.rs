//! One test binary for the files beside this one (one link, and generic shader code
//! monomorphized once instead of once per file). `cargo test -p <crate> --test integration <module>::`
//! runs one file's tests.

mod control_flow;
mod instantiations;
mod jit_check;
mod renderers_agree;
mod rsl_conformance_generated;
mod rsl_conformance_interp;
mod rsl_generated;
mod rsl_interp_render;
mod stability;
mod workload;
