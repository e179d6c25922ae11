//! The interpreter's side of `texture()`, `environment()` and `shadow()`: reading the
//! coordinate arguments from the frame and calling the run-time library's look-ups
//! ([`anysl_rt::texture`]), so the interpreter and generated Rust read the same texels.

use super::frame::{Frame, Loc};
use anysl_core::prelude::*;
use anysl_rt::texture::{sample_environment, sample_st};

/// Which look-up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `texture()`
    Texture,
    /// `environment()`
    Environment,
    /// `shadow()`
    Shadow,
}

/// Looks up `name` for chunk `k`; `coords` are the coordinate arguments as written
/// (texture: none → (s, t) of the globals, 2 → (s, t), 8 → four corners; environment and
/// shadow: a direction or point).
pub fn lookup<F: ShadingFloat>(
    fr: &Frame<F>,
    name: &str,
    kind: Kind,
    coords: &[Loc],
    g: Option<&Globals<F>>,
    k: usize,
) -> Color<F> {
    match kind {
        Kind::Shadow => Color::zero(),
        Kind::Environment => match coords.first() {
            Some(l) => sample_environment(name, fr.vec3(l.off(), k)),
            None => Color::zero(),
        },
        Kind::Texture => match coords.len() {
            0 => g.map_or_else(Color::zero, |g| sample_st(name, g.s, g.t)),
            n if n >= 2 => sample_st(name, fr.get(coords[0].off(), k), fr.get(coords[1].off(), k)),
            _ => Color::zero(),
        },
    }
}
