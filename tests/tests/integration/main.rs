//! The shader-instantiation half of the cross-crate tests, one test binary (generic shader code
//! monomorphized and linked once instead of once per file; the `.sl` half is the `rsl` test binary, `tests/rsl/`).
//! `cargo test -p anysl-tests --test integration <module>::` runs one file's tests.

mod control_flow;
mod docs_links;
mod instantiations;
mod layout;
mod renderers_agree;
mod scenes_jit;
mod stability;
mod workload;
