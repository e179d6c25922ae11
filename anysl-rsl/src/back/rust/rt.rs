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

/// RSL `format`: `%f %g %e %d %s %c %p %m %%` with C flags, width and precision (numbers print
/// lane 0; triples as `x y z`; without a precision a number prints in its shortest form).
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
        let mut spec = String::new();
        while let Some(&p) = chars.peek() {
            if p.is_ascii_digit() || p == '.' || p == '-' || p == '+' || p == ' ' || p == '#' {
                spec.push(p);
                chars.next();
            } else {
                break;
            }
        }
        let left = spec.contains('-');
        let (width, prec) = match spec.trim_start_matches(['-', '+', ' ', '#']).split_once('.') {
            Some((w, p)) => (w.parse::<usize>().unwrap_or(0), p.parse::<usize>().ok()),
            None => (spec.trim_start_matches(['-', '+', ' ', '#']).parse::<usize>().unwrap_or(0), None),
        };
        let conv = chars.next();
        let num = |x: f64| -> String {
            match (conv, prec) {
                (Some('d' | 'i'), _) => format!("{}", x.trunc() as i64),
                (Some('e'), Some(p)) => format!("{x:.p$e}"),
                (Some('e'), None) => format!("{x:e}"),
                (_, Some(p)) => format!("{x:.p$}"),
                _ => format!("{x}"),
            }
        };
        let text = match conv {
            Some('%') => {
                out.push('%');
                continue;
            }
            None => {
                out.push('%');
                continue;
            }
            Some(_) => {
                let t = match args.get(next) {
                    Some(FmtArg::Str(s)) => s.clone(),
                    Some(FmtArg::Num(v)) => v.iter().map(|x| num(*x)).collect::<Vec<_>>().join(" "),
                    None => String::new(),
                };
                next += 1;
                t
            }
        };
        let pad = width.saturating_sub(text.chars().count());
        if left {
            out.push_str(&text);
            out.extend(std::iter::repeat_n(' ', pad));
        } else {
            out.extend(std::iter::repeat_n(' ', pad));
            out.push_str(&text);
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_follows_c_precision_and_width() {
        let n = |x: f64| FmtArg::Num(vec![x]);
        assert_eq!(format_rsl("%.2f", &[n(0.5)]), "0.50");
        assert_eq!(format_rsl("%f|%5.1f|%-4d|%d%%", &[n(0.25), n(2.0), n(3.7), n(-2.5)]), "0.25|  2.0|3   |-2%");
        assert_eq!(format_rsl("%s-%s", &[FmtArg::Str("x".into()), FmtArg::Str("y".into())]), "x-y");
        assert_eq!(format_rsl("%p", &[FmtArg::Num(vec![1.0, 0.5, 0.0])]), "1 0.5 0");
    }

    #[test]
    fn match_subset_of_regular_expressions() {
        assert!(simple_match("b.d", "abcde"));
        assert!(!simple_match("^x", "abc"));
        assert!(simple_match("^ab*c$", "abbbc"));
    }
}

/// Lane 0 of a number (for `format`, loop bounds read as integers, …).
#[inline(always)]
#[must_use]
pub fn lane0<F: ShadingFloat>(x: F) -> f64 {
    x.lane(0)
}
