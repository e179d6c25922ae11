//! RSL `match(pattern, subject)`.

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn match_subset_of_regular_expressions() {
        assert!(simple_match("b.d", "abcde"));
        assert!(!simple_match("^x", "abc"));
        assert!(simple_match("^ab*c$", "abbbc"));
    }
}
