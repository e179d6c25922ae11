//! RSL `format` and `printf`: C conversions, flags, width and precision.

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
}
