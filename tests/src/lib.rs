//! Cross-crate integration tests live in `tests/`. This library compiles the README's code
//! examples as doctests, so the documentation cannot drift from the API, and holds the
//! harnesses the tests share.
#![doc = include_str!("../../README.md")]

pub mod rsl_harness;
