//! The ASCII RIB lexer: bytes → tokens with byte spans.
//!
//! Tokens are request names (identifiers), numbers, strings in double quotes, `[` and `]`.
//! `#` starts a comment to the end of the line (this covers `##` structure comments). A byte in
//! `0x80..=0xff` outside a string means binary RIB, which is not supported: the lexer reports it
//! and stops. Problems are reported as [`LexError`]s and the lexer goes on after them.

use crate::diag::codes;

/// What a token is.
#[derive(Clone, Debug, PartialEq)]
pub enum TokenKind {
    /// An identifier: a request name.
    Name,
    /// A number; `int` when written without `.` or exponent.
    Number {
        /// The value.
        value: f64,
        /// Written as an integer.
        int: bool,
    },
    /// A string, escapes decoded.
    Str(String),
    /// `[`.
    Open,
    /// `]`.
    Close,
    /// Something malformed, already reported as a [`LexError`].
    Error,
}

/// One token and its byte range in the file.
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    /// What it is.
    pub kind: TokenKind,
    /// First byte.
    pub start: u32,
    /// One past the last byte.
    pub end: u32,
}

/// A problem found by the lexer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LexError {
    /// Diagnostic code (see [`codes`]).
    pub code: &'static str,
    /// Message.
    pub message: String,
    /// First byte.
    pub start: u32,
    /// One past the last byte.
    pub end: u32,
    /// A hint, if any.
    pub note: Option<&'static str>,
}

/// A lexer over `bytes[start..end]`.
#[derive(Clone, Debug)]
pub struct Lexer<'a> {
    bytes: &'a [u8],
    pos: usize,
    end: usize,
    stopped: bool,
}

#[inline]
fn is_delimiter(b: u8) -> bool {
    b.is_ascii_whitespace() || matches!(b, b'[' | b']' | b'"' | b'#')
}

fn off(i: usize) -> u32 {
    u32::try_from(i).unwrap_or(u32::MAX)
}

impl<'a> Lexer<'a> {
    /// A lexer over all of `bytes`.
    #[must_use]
    pub fn new(bytes: &'a [u8]) -> Self {
        Self::range(bytes, 0, bytes.len())
    }

    /// A lexer over `bytes[start..end]` (clamped to the slice).
    #[must_use]
    pub fn range(bytes: &'a [u8], start: usize, end: usize) -> Self {
        let end = end.min(bytes.len());
        Self { bytes, pos: start.min(end), end, stopped: false }
    }

    /// Byte offset of the next unread byte.
    #[must_use]
    pub fn pos(&self) -> usize {
        self.pos
    }

    /// The text of a token's span.
    #[must_use]
    pub fn text(&self, t: &Token) -> &'a [u8] {
        self.bytes.get(t.start as usize..t.end as usize).unwrap_or(&[])
    }

    fn peek_byte(&self, at: usize) -> Option<u8> {
        if at < self.end {
            self.bytes.get(at).copied()
        } else {
            None
        }
    }

    /// The next token, or `None` at the end. Problems go to `errors`.
    pub fn next_token(&mut self, errors: &mut Vec<LexError>) -> Option<Token> {
        if self.stopped {
            return None;
        }
        // Whitespace and comments.
        loop {
            let b = self.peek_byte(self.pos)?;
            if b.is_ascii_whitespace() {
                self.pos += 1;
            } else if b == b'#' {
                while let Some(c) = self.peek_byte(self.pos) {
                    if c == b'\n' {
                        break;
                    }
                    self.pos += 1;
                }
            } else {
                break;
            }
        }
        let start = self.pos;
        let b = self.peek_byte(start)?;
        let kind = match b {
            b'[' => {
                self.pos += 1;
                TokenKind::Open
            }
            b']' => {
                self.pos += 1;
                TokenKind::Close
            }
            b'"' => self.string(errors),
            b'A'..=b'Z' | b'a'..=b'z' | b'_' => {
                while matches!(self.peek_byte(self.pos), Some(c) if c.is_ascii_alphanumeric() || c == b'_') {
                    self.pos += 1;
                }
                TokenKind::Name
            }
            b'0'..=b'9' | b'.' | b'+' | b'-' => self.number(errors),
            0x80..=0xff => {
                // Cover the whole character when the bytes are UTF-8, so the caret shows.
                let len = match b {
                    0xc0..=0xdf => 2,
                    0xe0..=0xef => 3,
                    0xf0..=0xf7 => 4,
                    _ => 1,
                };
                let len = if std::str::from_utf8(self.bytes.get(start..start + len).unwrap_or(&[])).is_ok() {
                    len
                } else {
                    1
                };
                errors.push(LexError {
                    code: codes::BINARY_RIB,
                    message: "binary RIB is not supported".into(),
                    start: off(start),
                    end: off(start + len),
                    note: Some("convert the file to ASCII RIB (e.g. `catrib` or `prman -catrib`)"),
                });
                self.stopped = true;
                self.pos = self.end;
                return Some(Token { kind: TokenKind::Error, start: off(start), end: off(start + len) });
            }
            _ => {
                self.pos += 1;
                let shown = if b.is_ascii_graphic() { format!("`{}`", b as char) } else { format!("byte 0x{b:02x}") };
                errors.push(LexError {
                    code: codes::BAD_CHAR,
                    message: format!("unexpected character {shown}"),
                    start: off(start),
                    end: off(start + 1),
                    note: None,
                });
                TokenKind::Error
            }
        };
        Some(Token { kind, start: off(start), end: off(self.pos) })
    }

    fn number(&mut self, errors: &mut Vec<LexError>) -> TokenKind {
        let start = self.pos;
        let mut i = start;
        if matches!(self.peek_byte(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let mut digits = 0usize;
        while matches!(self.peek_byte(i), Some(b'0'..=b'9')) {
            i += 1;
            digits += 1;
        }
        let mut int = true;
        if self.peek_byte(i) == Some(b'.') {
            int = false;
            i += 1;
            while matches!(self.peek_byte(i), Some(b'0'..=b'9')) {
                i += 1;
                digits += 1;
            }
        }
        let mut ok = digits > 0;
        if ok && matches!(self.peek_byte(i), Some(b'e' | b'E')) {
            int = false;
            i += 1;
            if matches!(self.peek_byte(i), Some(b'+' | b'-')) {
                i += 1;
            }
            let mut exp_digits = 0;
            while matches!(self.peek_byte(i), Some(b'0'..=b'9')) {
                i += 1;
                exp_digits += 1;
            }
            ok = exp_digits > 0;
        }
        // A number ends at a delimiter; `1.2.3`, `12abc` and `-x` are malformed.
        if self.peek_byte(i).is_some_and(|c| !is_delimiter(c)) {
            ok = false;
        }
        if !ok {
            while let Some(c) = self.peek_byte(i) {
                if is_delimiter(c) || c >= 0x80 {
                    break;
                }
                i += 1;
            }
            self.pos = i.max(start + 1);
            errors.push(LexError {
                code: codes::BAD_NUMBER,
                message: format!("malformed number `{}`", String::from_utf8_lossy(&self.bytes[start..self.pos])),
                start: off(start),
                end: off(self.pos),
                note: None,
            });
            return TokenKind::Error;
        }
        self.pos = i;
        // The lexeme is ASCII and matches Rust's float grammar.
        let text = std::str::from_utf8(&self.bytes[start..i]).unwrap_or("0");
        let value = text.parse::<f64>().unwrap_or(0.0);
        TokenKind::Number { value, int }
    }

    fn string(&mut self, errors: &mut Vec<LexError>) -> TokenKind {
        let start = self.pos;
        let mut i = start + 1;
        let mut out = Vec::new();
        loop {
            let c = match self.peek_byte(i) {
                Some(c) => c,
                None => {
                    // Strings may span lines (RIB writers emit multi-line strings); one that
                    // is still open at the end of the input is reported at its opening quote.
                    let line_end =
                        self.bytes[start..].iter().position(|&b| b == b'\n').map_or(self.bytes.len(), |n| start + n);
                    let text_end = if line_end > start + 1 && self.bytes.get(line_end - 1) == Some(&b'\r') {
                        line_end - 1
                    } else {
                        line_end
                    };
                    errors.push(LexError {
                        code: codes::UNTERMINATED_STRING,
                        message: "unterminated string".into(),
                        start: off(start),
                        end: off(text_end.max(start + 1)),
                        note: Some("the string opened here has no closing `\"` before the end of the file"),
                    });
                    self.pos = self.bytes.len();
                    return TokenKind::Error;
                }
            };
            i += 1;
            match c {
                b'"' => break,
                b'\\' => {
                    let Some(e) = self.peek_byte(i) else { continue };
                    i += 1;
                    match e {
                        b'n' => out.push(b'\n'),
                        b't' => out.push(b'\t'),
                        b'r' => out.push(b'\r'),
                        b'b' => out.push(8),
                        b'f' => out.push(12),
                        b'\n' => {}
                        b'\r' => {
                            if self.peek_byte(i) == Some(b'\n') {
                                i += 1;
                            }
                        }
                        b'0'..=b'7' => {
                            let mut v = u32::from(e - b'0');
                            for _ in 0..2 {
                                match self.peek_byte(i) {
                                    Some(d @ b'0'..=b'7') => {
                                        v = v * 8 + u32::from(d - b'0');
                                        i += 1;
                                    }
                                    _ => break,
                                }
                            }
                            out.push((v & 0xff) as u8);
                        }
                        // `\\`, `\"` and any other escaped character stand for themselves.
                        other => out.push(other),
                    }
                }
                _ => out.push(c),
            }
        }
        self.pos = i;
        TokenKind::Str(String::from_utf8(out).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned()))
    }
}
