//! The small run-time library generated Rust calls for what `anysl-core` does not offer:
//! texture look-ups (through the interpreter's image cache, so both back ends read the same
//! texels), `format`/`printf`, `match`, and parameter arrays by name.
//!
//! Everything numeric that a shader computes goes through `anysl_core::stdlib`, exactly as in
//! the interpreter; only these services live here.

use crate::back::interp::texture;
use anysl_core::prelude::*;
use anysl_core::shader::{ParamField, ParamValue};

/// `texture(name[, s, t])`: `st` are the coordinates (`None`: the globals' `s`, `t`).
#[inline]
#[must_use]
pub fn texture<F: ShadingFloat>(name: &str, st: Option<(F, F)>, g: &Globals<F>) -> Color<F> {
    let (s, t) = st.unwrap_or((g.s, g.t));
    texture::sample_st(name, s, t)
}

/// `environment(name, dir)`.
#[inline]
#[must_use]
pub fn environment<F: ShadingFloat>(name: &str, dir: Vec3<F>) -> Color<F> {
    texture::sample_environment(name, dir)
}

/// An argument of `format`/`printf`.
#[derive(Clone, Debug)]
pub enum FmtArg {
    /// A number, triple or matrix (lane 0 of each component).
    Num(Vec<f64>),
    /// A string.
    Str(String),
}

/// RSL `format`: `%f %g %d %s %c %p %m %%` (numbers print lane 0; triples as `x y z`), as the
/// interpreter formats them.
#[must_use]
pub fn format_rsl(fmt: &str, args: &[FmtArg]) -> String {
    let mut out = String::new();
    let mut next = 0usize;
    let mut chars = fmt.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        while let Some(&p) = chars.peek() {
            if p.is_ascii_digit() || p == '.' || p == '-' || p == '+' {
                chars.next();
            } else {
                break;
            }
        }
        match chars.next() {
            Some('%') => out.push('%'),
            Some(_) => {
                match args.get(next) {
                    Some(FmtArg::Str(s)) => out.push_str(s),
                    Some(FmtArg::Num(v)) => {
                        let parts: Vec<String> = v.iter().map(|x| format!("{x}")).collect();
                        out.push_str(&parts.join(" "));
                    }
                    None => {}
                }
                next += 1;
            }
            None => out.push('%'),
        }
    }
    out
}

/// RSL `match(pattern, subject)`: substring search with `.`, `*`, `^` and `$`.
#[must_use]
pub fn simple_match(pat: &str, subj: &str) -> bool {
    fn here(p: &[char], s: &[char]) -> bool {
        match p {
            [] => true,
            ['$'] => s.is_empty(),
            [c, '*', rest @ ..] => {
                let mut i = 0;
                loop {
                    if here(rest, &s[i..]) {
                        return true;
                    }
                    if i < s.len() && (*c == '.' || s[i] == *c) {
                        i += 1;
                    } else {
                        return false;
                    }
                }
            }
            [c, rest @ ..] => !s.is_empty() && (*c == '.' || s[0] == *c) && here(rest, &s[1..]),
        }
    }
    let p: Vec<char> = pat.chars().collect();
    let s: Vec<char> = subj.chars().collect();
    if let Some(rest) = p.strip_prefix(&['^']) {
        return here(rest, &s);
    }
    (0..=s.len()).any(|i| here(&p, &s[i..]))
}

/// A parameter array as a [`ParamValue`].
#[must_use]
pub fn array_value<T: ParamField>(a: &[T]) -> ParamValue {
    ParamValue::Array(a.iter().map(ParamField::to_value).collect())
}

/// A parameter array from a [`ParamValue`] of exactly `N` elements.
#[must_use]
pub fn array_from_value<T: ParamField + Clone, const N: usize>(v: &ParamValue, old: &[T; N]) -> Option<[T; N]> {
    match v {
        ParamValue::Array(items) if items.len() == N => {
            let mut out = old.clone();
            for (o, i) in out.iter_mut().zip(items) {
                *o = T::from_value(i)?;
            }
            Some(out)
        }
        _ => None,
    }
}

/// Lane 0 of a number (for `format`, loop bounds read as integers, …).
#[inline(always)]
#[must_use]
pub fn lane0<F: ShadingFloat>(x: F) -> f64 {
    x.lane(0)
}
