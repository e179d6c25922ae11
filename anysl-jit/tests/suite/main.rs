//! The JIT's tests, one binary: the modules share the instantiations of the JIT's calling code
//! (host tables, contexts, the interpreter fallback) that separate binaries would each compile.
//!
//! `cargo test -p anysl-jit --test suite points::` runs one module.

mod check;
mod displacement;
mod inline_geometry;
mod inline_math;
mod light_code;
mod light_loops;
mod light_shaders;
mod opcount;
mod points;
mod runtime;
mod smoke;
mod spaces;
