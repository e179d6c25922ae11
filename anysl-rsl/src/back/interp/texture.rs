//! The interpreter's side of `texture()`, `environment()`, `shadow()` and `textureinfo()`:
//! reading the coordinate arguments and the optional `"name", value` pairs from the frame and
//! calling the run-time library's look-ups ([`anysl_rt::texture`]), so the interpreter and
//! generated Rust read the same texels.

use super::frame::{Frame, Loc};
use anysl_core::prelude::*;
use anysl_rt::texture::{self as rt, env, shadow, Info, St, TexOptions};

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

fn string<F: ShadingFloat>(fr: &Frame<F>, l: Loc) -> &str {
    match l {
        Loc::Str(i, _) => fr.s[i as usize].as_str(),
        _ => "",
    }
}

/// The options given as `"name", value` pairs after the coordinates (a `"name"[c]` channel
/// selection arrives as the pair `"firstchannel", c`).
fn options<F: ShadingFloat>(fr: &Frame<F>, pairs: &[Loc], k: usize) -> TexOptions<F> {
    let mut o = TexOptions::default();
    for pair in pairs.chunks(2) {
        if let [n, v] = pair {
            let name = string(fr, *n);
            match v {
                Loc::Str(..) => o.set_string(name, string(fr, *v)),
                Loc::Num { off, .. } => o.set_float(name, fr.get(*off, k)),
                _ => {}
            }
        }
    }
    o
}

/// Looks up `name` for chunk `k`; `coords` are the coordinate arguments as written
/// (texture: none → (s, t) of the globals, 2 → (s, t), 8 → four corners; environment and
/// shadow: one direction or point, or four), `opts` the option pairs. A shadow's answer is
/// in all three channels.
pub fn lookup<F: ShadingFloat>(
    fr: &Frame<F>,
    name: &str,
    kind: Kind,
    coords: &[Loc],
    opts: &[Loc],
    g: Option<&Globals<F>>,
    k: usize,
) -> Color<F> {
    let o = options(fr, opts, k);
    let v = |i: usize| fr.vec3(coords[i].off(), k);
    let f = |i: usize| fr.get(coords[i].off(), k);
    match kind {
        Kind::Shadow => match coords.len() {
            0 => Color::zero(),
            n if n >= 4 => Color::splat(shadow::lookup_quad(name, [v(0), v(1), v(2), v(3)], &o)),
            _ => Color::splat(shadow::lookup(name, v(0), &o)),
        },
        Kind::Environment => match coords.len() {
            0 => Color::splat(o.fill),
            n if n >= 4 => env::lookup(name, env::Dir::Quad([v(0), v(1), v(2), v(3)]), &o),
            _ => env::lookup(name, env::Dir::Ray(v(0)), &o),
        },
        Kind::Texture => match coords.len() {
            0 => g.map_or_else(|| Color::splat(o.fill), |g| rt::lookup(name, St::Point(g.s, g.t), &o)),
            n if n >= 8 => rt::lookup(name, St::Quad([f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7)]), &o),
            n if n >= 2 => rt::lookup(name, St::Point(f(0), f(1)), &o),
            _ => Color::splat(o.fill),
        },
    }
}

/// `textureinfo(name, query, out)`: writes the answer to `out` and returns 1, or 0 (`out`
/// untouched) when the map is missing, the query unknown or `out` of another type.
pub fn info<F: ShadingFloat>(fr: &mut Frame<F>, name: &str, query: &str, out: Loc, k: usize, m: F::Mask) -> F {
    let Some(answer) = rt::info(name, query) else { return F::c(0.0) };
    let nums: Vec<f64> = match (&answer, out) {
        (Info::Type(t), Loc::Str(i, _)) => {
            fr.s[i as usize] = (*t).to_string();
            return F::c(1.0);
        }
        (Info::Resolution(r), _) => r.to_vec(),
        (Info::Channels(c), _) => vec![*c],
        (Info::Matrix(mm), _) => mm.to_vec(),
        (Info::Type(_), _) => return F::c(0.0),
    };
    match out {
        Loc::Num { off, width } if width as usize == nums.len() => {
            let vals: Vec<F> = nums.iter().map(|x| F::c(*x)).collect();
            fr.write(off, k, m, &vals);
            F::c(1.0)
        }
        _ => F::c(0.0),
    }
}
