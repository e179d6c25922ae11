//! One test binary for the files beside this one (one link, and generic shader code
//! monomorphized once instead of once per file). `cargo test -p <crate> --test suite <module>::`
//! runs one file's tests.

mod common;
mod gather;
mod geometry;
mod lighting;
mod renderers;
