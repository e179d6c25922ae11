//! The cross-crate tests that need the JIT, one test binary in a package of its own: the other
//! cross-crate tests (`anysl-tests`) do not wait for `anysl-jit` to compile, and this binary
//! instantiates the calling code of the JIT once. `cargo test -p anysl-tests-jit --test jit
//! <module>::` runs one file.
//!
//! - `jit_check`: JIT = monomorphized build on random points, every `.sl` shader of the repository;
//! - `jit_eval`: `rslc eval --backend jit` = `--backend interp` on the conformance programs;
//! - `scenes_jit`: RIB scenes with JIT-compiled surface and displacement shaders;
//! - `workload`: the workload's `.sl` shaders through the JIT against the reference images.

mod jit_check;
mod jit_eval;
mod scenes_jit;
mod workload;
