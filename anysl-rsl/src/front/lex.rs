//! The lexer: source text → [`Token`]s with spans.
//!
//! Lexing never fails: a character that starts no token, an unterminated string or comment
//! and a malformed number each produce a [`Diagnostic`] and lexing goes on. The diagnostics
//! are returned beside the tokens rather than reported directly, so that the preprocessor can
//! drop the ones inside `#if 0` regions (real shaders comment code out that way, apostrophes
//! and all).
//!
//! Every token records whether it is the first on its line (`line_start`, which is how the
//! preprocessor finds directives and their ends; a backslash-newline continues the line) and
//! whether white space precedes it (`space_before`, which tells `#define F(x)` from
//! `#define F (x)`).

use crate::diag::{codes, Diagnostic};
use crate::span::{FileId, Span};
use std::fmt;

/// Reserved words of the shading language.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Keyword {
    /// `float`
    Float,
    /// `color`
    Color,
    /// `point`
    Point,
    /// `vector`
    Vector,
    /// `normal`
    Normal,
    /// `matrix`
    Matrix,
    /// `string`
    String,
    /// `void`
    Void,
    /// `uniform`
    Uniform,
    /// `varying`
    Varying,
    /// `output`
    Output,
    /// `extern`
    Extern,
    /// `surface`
    Surface,
    /// `light`
    Light,
    /// `displacement`
    Displacement,
    /// `volume`
    Volume,
    /// `imager`
    Imager,
    /// `if`
    If,
    /// `else`
    Else,
    /// `while`
    While,
    /// `for`
    For,
    /// `break`
    Break,
    /// `continue`
    Continue,
    /// `return`
    Return,
    /// `illuminance`
    Illuminance,
    /// `illuminate`
    Illuminate,
    /// `solar`
    Solar,
    /// `gather`
    Gather,
}

impl Keyword {
    /// Every keyword, for tables and tests.
    pub const ALL: [Keyword; 28] = [
        Self::Float,
        Self::Color,
        Self::Point,
        Self::Vector,
        Self::Normal,
        Self::Matrix,
        Self::String,
        Self::Void,
        Self::Uniform,
        Self::Varying,
        Self::Output,
        Self::Extern,
        Self::Surface,
        Self::Light,
        Self::Displacement,
        Self::Volume,
        Self::Imager,
        Self::If,
        Self::Else,
        Self::While,
        Self::For,
        Self::Break,
        Self::Continue,
        Self::Return,
        Self::Illuminance,
        Self::Illuminate,
        Self::Solar,
        Self::Gather,
    ];

    /// The keyword as written.
    #[must_use]
    pub const fn as_str(self) -> &'static str {
        match self {
            Self::Float => "float",
            Self::Color => "color",
            Self::Point => "point",
            Self::Vector => "vector",
            Self::Normal => "normal",
            Self::Matrix => "matrix",
            Self::String => "string",
            Self::Void => "void",
            Self::Uniform => "uniform",
            Self::Varying => "varying",
            Self::Output => "output",
            Self::Extern => "extern",
            Self::Surface => "surface",
            Self::Light => "light",
            Self::Displacement => "displacement",
            Self::Volume => "volume",
            Self::Imager => "imager",
            Self::If => "if",
            Self::Else => "else",
            Self::While => "while",
            Self::For => "for",
            Self::Break => "break",
            Self::Continue => "continue",
            Self::Return => "return",
            Self::Illuminance => "illuminance",
            Self::Illuminate => "illuminate",
            Self::Solar => "solar",
            Self::Gather => "gather",
        }
    }

    /// The keyword spelled `s`, if any.
    #[must_use]
    pub fn from_word(s: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|k| k.as_str() == s)
    }
}

/// Operators and punctuation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Punct {
    /// `+`
    Plus,
    /// `-`
    Minus,
    /// `*`
    Star,
    /// `/`
    Slash,
    /// `^`
    Caret,
    /// `.`
    Dot,
    /// `==`
    EqEq,
    /// `!=`
    Ne,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `&&`
    AndAnd,
    /// `||`
    OrOr,
    /// `!`
    Not,
    /// `?`
    Question,
    /// `:`
    Colon,
    /// `=`
    Assign,
    /// `+=`
    PlusAssign,
    /// `-=`
    MinusAssign,
    /// `*=`
    StarAssign,
    /// `/=`
    SlashAssign,
    /// `(`
    LParen,
    /// `)`
    RParen,
    /// `[`
    LBracket,
    /// `]`
    RBracket,
    /// `{`
    LBrace,
    /// `}`
    RBrace,
    /// `,`
    Comma,
    /// `;`
    Semi,
    /// `#` (preprocessor directive or stringification)
    Hash,
    /// `##` (token pasting)
    HashHash,
}

impl Punct {
    /// The punctuation as written.
    #[must_use]
    pub const fn as_str(self) -> &'static str {
        match self {
            Self::Plus => "+",
            Self::Minus => "-",
            Self::Star => "*",
            Self::Slash => "/",
            Self::Caret => "^",
            Self::Dot => ".",
            Self::EqEq => "==",
            Self::Ne => "!=",
            Self::Lt => "<",
            Self::Le => "<=",
            Self::Gt => ">",
            Self::Ge => ">=",
            Self::AndAnd => "&&",
            Self::OrOr => "||",
            Self::Not => "!",
            Self::Question => "?",
            Self::Colon => ":",
            Self::Assign => "=",
            Self::PlusAssign => "+=",
            Self::MinusAssign => "-=",
            Self::StarAssign => "*=",
            Self::SlashAssign => "/=",
            Self::LParen => "(",
            Self::RParen => ")",
            Self::LBracket => "[",
            Self::RBracket => "]",
            Self::LBrace => "{",
            Self::RBrace => "}",
            Self::Comma => ",",
            Self::Semi => ";",
            Self::Hash => "#",
            Self::HashHash => "##",
        }
    }
}

/// What a token is.
#[derive(Clone, Debug, PartialEq)]
pub enum TokenKind {
    /// A name that is not a keyword.
    Ident(String),
    /// A reserved word.
    Keyword(Keyword),
    /// A number (all RSL numbers are floats).
    Number(f64),
    /// A string literal, escapes decoded.
    Str(String),
    /// An operator or punctuation.
    Punct(Punct),
    /// End of input (the parser's token stream ends with exactly one).
    Eof,
}

/// One token.
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    /// What it is.
    pub kind: TokenKind,
    /// Where (for tokens made by macro expansion: the macro use).
    pub span: Span,
    /// First token on its (logical) line.
    pub line_start: bool,
    /// White space or a comment precedes it.
    pub space_before: bool,
}

impl Token {
    /// The spelling of an identifier or keyword (the preprocessor treats both as names).
    #[must_use]
    pub fn word(&self) -> Option<&str> {
        match &self.kind {
            TokenKind::Ident(s) => Some(s),
            TokenKind::Keyword(k) => Some(k.as_str()),
            _ => None,
        }
    }

    /// True for the punctuation `p`.
    #[must_use]
    pub fn is(&self, p: Punct) -> bool {
        self.kind == TokenKind::Punct(p)
    }
}

impl fmt::Display for TokenKind {
    /// How the token is named in diagnostics: `` `;` ``, `identifier `x``, `end of file`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Ident(s) => write!(f, "identifier `{s}`"),
            Self::Keyword(k) => write!(f, "keyword `{}`", k.as_str()),
            Self::Number(n) => write!(f, "number `{n}`"),
            Self::Str(s) => write!(f, "string {s:?}"),
            Self::Punct(p) => write!(f, "`{}`", p.as_str()),
            Self::Eof => f.write_str("end of file"),
        }
    }
}

/// Lexes the whole of `text` (file `file`). Returns the tokens (without an end-of-file token)
/// and the lexical errors, both in source order.
#[must_use]
pub fn lex(text: &str, file: FileId) -> (Vec<Token>, Vec<Diagnostic>) {
    let mut lx = Lexer { text, bytes: text.as_bytes(), pos: 0, file, tokens: Vec::new(), diags: Vec::new() };
    lx.run();
    (lx.tokens, lx.diags)
}

struct Lexer<'a> {
    text: &'a str,
    bytes: &'a [u8],
    pos: usize,
    file: FileId,
    tokens: Vec<Token>,
    diags: Vec<Diagnostic>,
}

fn is_ident_start(b: u8) -> bool {
    b.is_ascii_alphabetic() || b == b'_'
}

fn is_ident_continue(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

impl Lexer<'_> {
    fn span(&self, start: usize, end: usize) -> Span {
        // Files larger than 4 GiB are not supported; clamp rather than wrap.
        let s = u32::try_from(start).unwrap_or(u32::MAX);
        let e = u32::try_from(end).unwrap_or(u32::MAX);
        Span::new(self.file, s, e)
    }

    fn peek(&self, ahead: usize) -> u8 {
        self.bytes.get(self.pos + ahead).copied().unwrap_or(0)
    }

    fn error(&mut self, code: &'static str, start: usize, end: usize, msg: impl Into<String>, label: &str) {
        let d = Diagnostic::error(code, self.span(start, end), msg).with_label(label);
        self.diags.push(d);
    }

    fn run(&mut self) {
        let mut line_start = true;
        let mut space_before = false;
        while self.pos < self.bytes.len() {
            let b = self.bytes[self.pos];
            match b {
                b'\n' => {
                    self.pos += 1;
                    line_start = true;
                    space_before = true;
                    continue;
                }
                b' ' | b'\t' | b'\r' | 0x0b | 0x0c => {
                    self.pos += 1;
                    space_before = true;
                    continue;
                }
                b'\\' if self.peek(1) == b'\n' => {
                    self.pos += 2;
                    space_before = true;
                    continue;
                }
                b'\\' if self.peek(1) == b'\r' && self.peek(2) == b'\n' => {
                    self.pos += 3;
                    space_before = true;
                    continue;
                }
                b'/' if self.peek(1) == b'/' => {
                    while self.pos < self.bytes.len() && self.bytes[self.pos] != b'\n' {
                        self.pos += 1;
                    }
                    space_before = true;
                    continue;
                }
                b'/' if self.peek(1) == b'*' => {
                    let start = self.pos;
                    match self.text[self.pos + 2..].find("*/") {
                        Some(i) => {
                            let end = self.pos + 2 + i + 2;
                            if self.text[start..end].contains('\n') {
                                line_start = true;
                            }
                            self.pos = end;
                        }
                        None => {
                            self.error(
                                codes::UNTERMINATED_COMMENT,
                                start,
                                start + 2,
                                "unterminated block comment",
                                "this `/*` has no matching `*/`",
                            );
                            self.pos = self.bytes.len();
                        }
                    }
                    space_before = true;
                    continue;
                }
                _ => {}
            }
            let start = self.pos;
            let kind = self.token();
            if let Some(kind) = kind {
                let span = self.span(start, self.pos);
                self.tokens.push(Token { kind, span, line_start, space_before });
                line_start = false;
                space_before = false;
            } else {
                space_before = true;
            }
        }
    }

    /// Lexes one token at `self.pos` (not white space); `None` after a bad character.
    fn token(&mut self) -> Option<TokenKind> {
        let start = self.pos;
        let b = self.bytes[start];
        if is_ident_start(b) {
            while is_ident_continue(self.peek(0)) {
                self.pos += 1;
            }
            let word = &self.text[start..self.pos];
            return Some(match Keyword::from_word(word) {
                Some(k) => TokenKind::Keyword(k),
                None => TokenKind::Ident(word.to_owned()),
            });
        }
        if b.is_ascii_digit() || (b == b'.' && self.peek(1).is_ascii_digit()) {
            return Some(self.number());
        }
        if b == b'"' {
            return Some(self.string());
        }
        use Punct as P;
        let two = [b, self.peek(1)];
        let (p, len) = match &two {
            b"==" => (P::EqEq, 2),
            b"!=" => (P::Ne, 2),
            b"<=" => (P::Le, 2),
            b">=" => (P::Ge, 2),
            b"&&" => (P::AndAnd, 2),
            b"||" => (P::OrOr, 2),
            b"+=" => (P::PlusAssign, 2),
            b"-=" => (P::MinusAssign, 2),
            b"*=" => (P::StarAssign, 2),
            b"/=" => (P::SlashAssign, 2),
            b"##" => (P::HashHash, 2),
            _ => match b {
                b'+' => (P::Plus, 1),
                b'-' => (P::Minus, 1),
                b'*' => (P::Star, 1),
                b'/' => (P::Slash, 1),
                b'^' => (P::Caret, 1),
                b'.' => (P::Dot, 1),
                b'<' => (P::Lt, 1),
                b'>' => (P::Gt, 1),
                b'!' => (P::Not, 1),
                b'?' => (P::Question, 1),
                b':' => (P::Colon, 1),
                b'=' => (P::Assign, 1),
                b'(' => (P::LParen, 1),
                b')' => (P::RParen, 1),
                b'[' => (P::LBracket, 1),
                b']' => (P::RBracket, 1),
                b'{' => (P::LBrace, 1),
                b'}' => (P::RBrace, 1),
                b',' => (P::Comma, 1),
                b';' => (P::Semi, 1),
                b'#' => (P::Hash, 1),
                _ => {
                    // One whole (possibly multi-byte) character.
                    let ch = self.text[start..].chars().next().unwrap_or('\u{fffd}');
                    self.pos += ch.len_utf8().max(1);
                    let hint = match ch {
                        '&' => "`&` is not an RSL operator (did you mean `&&`?)",
                        '|' => "`|` is not an RSL operator (did you mean `||`?)",
                        '\'' => "RSL strings use double quotes",
                        _ => "this character cannot start a token",
                    };
                    self.error(codes::BAD_CHAR, start, self.pos, format!("unexpected character {ch:?}"), hint);
                    return None;
                }
            },
        };
        self.pos += len;
        Some(TokenKind::Punct(p))
    }

    fn digits(&mut self) -> usize {
        let s = self.pos;
        while self.peek(0).is_ascii_digit() {
            self.pos += 1;
        }
        self.pos - s
    }

    /// `1`, `1.`, `.5`, `1e-3`, `1.5E+2`, and (for `#if`) `0x1F`.
    fn number(&mut self) -> TokenKind {
        let start = self.pos;
        if self.peek(0) == b'0' && matches!(self.peek(1), b'x' | b'X') && self.peek(2).is_ascii_hexdigit() {
            self.pos += 2;
            while self.peek(0).is_ascii_hexdigit() {
                self.pos += 1;
            }
            let v = u64::from_str_radix(&self.text[start + 2..self.pos], 16).map_or(f64::INFINITY, |v| v as f64);
            return self.number_suffix(start, v);
        }
        self.digits();
        if self.peek(0) == b'.' {
            self.pos += 1;
            self.digits();
        }
        let mut bad = false;
        if matches!(self.peek(0), b'e' | b'E') {
            let save = self.pos;
            self.pos += 1;
            if matches!(self.peek(0), b'+' | b'-') {
                self.pos += 1;
            }
            if self.digits() == 0 {
                // `1e` or `1e+`: report it as one malformed number.
                bad = true;
                let _ = save;
            }
        }
        let text = &self.text[start..self.pos];
        if bad {
            self.error(
                codes::BAD_NUMBER,
                start,
                self.pos,
                format!("malformed number `{text}`"),
                "exponent has no digits",
            );
            // Keep going with the mantissa's value.
            let mantissa: String = text.chars().take_while(|c| !matches!(c, 'e' | 'E')).collect();
            return TokenKind::Number(mantissa.parse().unwrap_or(0.0));
        }
        let v = text.parse::<f64>().unwrap_or(0.0);
        self.number_suffix(start, v)
    }

    /// A number immediately followed by letters (`1abc`, `2.5q`) is one malformed token; a C
    /// float suffix (`0.5f`, `1.F`, `2e-3f`), which PRMan's and BMRT's compilers took, is read as
    /// the number with a warning.
    fn number_suffix(&mut self, start: usize, v: f64) -> TokenKind {
        if matches!(self.peek(0), b'f' | b'F') && !is_ident_continue(self.peek(1)) && self.peek(1) != b'.' {
            self.pos += 1;
            let text = &self.text[start..self.pos];
            let d = Diagnostic::warning(
                codes::FLOAT_SUFFIX,
                self.span(start, self.pos),
                format!("C float suffix in `{text}`: read as `{}`", &text[..text.len() - 1]),
            )
            .with_label("suffix ignored")
            .with_note("RSL numbers are all floats; drop the `f`");
            self.diags.push(d);
            return TokenKind::Number(v);
        }
        if is_ident_continue(self.peek(0)) || (self.peek(0) == b'.' && self.peek(1).is_ascii_digit()) {
            while is_ident_continue(self.peek(0)) || self.peek(0) == b'.' {
                self.pos += 1;
            }
            let text = &self.text[start..self.pos];
            self.error(codes::BAD_NUMBER, start, self.pos, format!("malformed number `{text}`"), "not a number");
        }
        TokenKind::Number(v)
    }

    fn string(&mut self) -> TokenKind {
        let start = self.pos;
        self.pos += 1;
        let mut value = String::new();
        loop {
            let rest = &self.text[self.pos..];
            let Some(ch) = rest.chars().next() else {
                self.error(
                    codes::UNTERMINATED_STRING,
                    start,
                    self.pos,
                    "unterminated string literal",
                    "this string has no closing `\"`",
                );
                return TokenKind::Str(value);
            };
            match ch {
                '"' => {
                    self.pos += 1;
                    return TokenKind::Str(value);
                }
                '\n' => {
                    self.error(
                        codes::UNTERMINATED_STRING,
                        start,
                        self.pos,
                        "unterminated string literal",
                        "this string has no closing `\"` on its line",
                    );
                    return TokenKind::Str(value);
                }
                '\\' => {
                    let next = rest[1..].chars().next();
                    self.pos += 1;
                    match next {
                        Some('n') => value.push('\n'),
                        Some('t') => value.push('\t'),
                        Some('r') => value.push('\r'),
                        Some('\\') => value.push('\\'),
                        Some('"') => value.push('"'),
                        Some('\'') => value.push('\''),
                        Some('\n') => {} // line continuation inside a string
                        Some(c) => {
                            // Unknown escape: keep it as written.
                            value.push('\\');
                            value.push(c);
                        }
                        None => continue,
                    }
                    if let Some(c) = next {
                        self.pos += c.len_utf8();
                    }
                }
                c => {
                    value.push(c);
                    self.pos += c.len_utf8();
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<TokenKind> {
        let (t, d) = lex(src, FileId(0));
        assert!(d.is_empty(), "{d:?}");
        t.into_iter().map(|t| t.kind).collect()
    }

    #[test]
    fn numbers() {
        let k = kinds("1 1. .5 1e-3 1.5E+2 0x10 2.e1");
        let v: Vec<f64> = k
            .iter()
            .map(|k| match k {
                TokenKind::Number(v) => *v,
                _ => f64::NAN,
            })
            .collect();
        assert_eq!(v, vec![1.0, 1.0, 0.5, 1e-3, 150.0, 16.0, 20.0]);
    }

    #[test]
    fn dot_between_names_is_an_operator() {
        assert_eq!(
            kinds("L.N"),
            vec![TokenKind::Ident("L".into()), TokenKind::Punct(Punct::Dot), TokenKind::Ident("N".into())]
        );
    }

    #[test]
    fn strings_and_escapes() {
        assert_eq!(kinds(r#""a\n\t\\\"b""#), vec![TokenKind::Str("a\n\t\\\"b".into())]);
    }

    #[test]
    fn operators_and_keywords() {
        let k = kinds("a += b == c && !d || e ? f : g; surface illuminance ## #");
        assert!(k.contains(&TokenKind::Punct(Punct::PlusAssign)));
        assert!(k.contains(&TokenKind::Keyword(Keyword::Surface)));
        assert!(k.contains(&TokenKind::Keyword(Keyword::Illuminance)));
        assert!(k.contains(&TokenKind::Punct(Punct::HashHash)));
        assert_eq!(k.len(), 19);
    }

    #[test]
    fn comments_and_line_starts() {
        let (t, _) = lex("a /* x\n y */ b // c\n  c \\\n d", FileId(0));
        let ls: Vec<bool> = t.iter().map(|t| t.line_start).collect();
        assert_eq!(ls, vec![true, true, true, false]);
    }

    #[test]
    fn errors_continue() {
        let (t, d) = lex("a @ b \"open\n1e+ 'x' /* never", FileId(0));
        let codes: Vec<&str> = d.iter().map(|d| d.code).collect();
        assert_eq!(
            codes,
            vec![
                codes::BAD_CHAR,
                codes::UNTERMINATED_STRING,
                codes::BAD_NUMBER,
                codes::BAD_CHAR,
                codes::BAD_CHAR,
                codes::UNTERMINATED_COMMENT
            ]
        );
        assert_eq!(t.len(), 5);
    }
}
