//! The batched interpreter: executes the IR over SoA batches of shading points with masks —
//! the classic RenderMan SIMD-interpreter model.
//!
//! A [`Program`] is the IR compiled once into a tree of register-allocated ops ([`Code`]).
//! Every value and variable owns `width × chunks` registers of the float type `F`: a batch is
//! `chunks` values of `F`, each holding `F::LANES` shading points, so the same program runs
//! on `f32` (one point per chunk), `F32x8` (eight), `Dual<F32x8>` (eight with derivatives)
//! or intervals. Each op is decoded once per batch and applied to every chunk whose mask has
//! an active lane, which amortizes the dispatch over the batch; divergent control flow runs
//! with per-chunk lane masks (see [`exec`]), skipping blocks no lane enters.
//!
//! Strings are uniform and live in a separate register file.

mod builtins;
pub mod exec;
mod frame;
mod prepare;
pub mod texture;
mod volume;

pub use exec::{release, run_batch, InterpLight, InterpShader, LightCtx};
pub use frame::{Frame, Loc};
pub use prepare::{PrepareError, Program};
