//! Diagnostics: small structured errors, rendered with `codespan-reporting`.
//!
//! Every stage reports [`Diagnostic`]s into a [`Diagnostics`] list and keeps going where it
//! can, so one run shows several errors. Rendering (`file:line:col`, the source line, a caret
//! under the offending text, notes on how to fix it) happens once, at the end, in
//! [`Diagnostics::render`].

use crate::span::{FileId, SourceMap, Span};
use codespan_reporting::diagnostic::{Diagnostic as CsDiagnostic, Label, Severity as CsSeverity};
use codespan_reporting::files::{Error as FilesError, Files};
use codespan_reporting::term::{self, termcolor::NoColor};
use std::fmt;
use std::ops::Range;

/// How bad a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// Compilation continues and succeeds.
    Warning,
    /// Compilation fails.
    Error,
}

/// One problem found in the source.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// Stable code, e.g. `E0102`; see [`codes`].
    pub code: &'static str,
    /// One-line message.
    pub message: String,
    /// Where (the caret goes here).
    pub span: Span,
    /// Label under the caret.
    pub label: String,
    /// Further places, e.g. the earlier definition.
    pub secondary: Vec<(Span, String)>,
    /// Hints on how to fix it.
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// An error with code, span and message.
    #[must_use]
    pub fn error(code: &'static str, span: Span, message: impl Into<String>) -> Self {
        Self {
            severity: Severity::Error,
            code,
            message: message.into(),
            span,
            label: String::new(),
            secondary: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// A warning with code, span and message.
    #[must_use]
    pub fn warning(code: &'static str, span: Span, message: impl Into<String>) -> Self {
        Self { severity: Severity::Warning, ..Self::error(code, span, message) }
    }

    /// Sets the label under the caret.
    #[must_use]
    pub fn with_label(mut self, label: impl Into<String>) -> Self {
        self.label = label.into();
        self
    }

    /// Adds a secondary location.
    #[must_use]
    pub fn with_secondary(mut self, span: Span, label: impl Into<String>) -> Self {
        self.secondary.push((span, label.into()));
        self
    }

    /// Adds a note.
    #[must_use]
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }
}

/// Diagnostic codes, one per kind of problem. Stable: tests and users match on them.
pub mod codes {
    /// Lexer: a character that starts no token.
    pub const BAD_CHAR: &str = "E0001";
    /// Lexer: string literal without its closing quote.
    pub const UNTERMINATED_STRING: &str = "E0002";
    /// Lexer: `/*` without `*/`.
    pub const UNTERMINATED_COMMENT: &str = "E0003";
    /// Lexer: malformed number.
    pub const BAD_NUMBER: &str = "E0004";
    /// Preprocessor: `#include` file not found.
    pub const INCLUDE_NOT_FOUND: &str = "E0010";
    /// Preprocessor: unknown or malformed directive.
    pub const BAD_DIRECTIVE: &str = "E0011";
    /// Preprocessor: `#if` without `#endif`, or `#else`/`#endif` without `#if`.
    pub const UNBALANCED_CONDITIONAL: &str = "E0012";
    /// Preprocessor: macro called with the wrong number of arguments.
    pub const MACRO_ARGS: &str = "E0013";
    /// Preprocessor: `#include` nesting too deep (recursive include).
    pub const INCLUDE_DEPTH: &str = "E0014";
    /// Preprocessor: explicit `#error`.
    pub const PP_ERROR: &str = "E0015";
    /// Parser: unexpected token.
    pub const SYNTAX: &str = "E0100";
    /// Parser: unexpected end of file.
    pub const UNEXPECTED_EOF: &str = "E0101";
    /// Checker: unknown identifier.
    pub const UNKNOWN_NAME: &str = "E0200";
    /// Checker: unknown function.
    pub const UNKNOWN_FUNCTION: &str = "E0201";
    /// Checker: no overload of a function matches the argument types.
    pub const NO_OVERLOAD: &str = "E0202";
    /// Checker: wrong number of arguments.
    pub const ARG_COUNT: &str = "E0203";
    /// Checker: type mismatch (assignment, initializer, return, operand).
    pub const TYPE_MISMATCH: &str = "E0204";
    /// Checker: operator not defined for these operand types.
    pub const BAD_OPERANDS: &str = "E0205";
    /// Checker: varying value assigned to a uniform variable.
    pub const VARYING_TO_UNIFORM: &str = "E0206";
    /// Checker: assignment to something that is not an lvalue.
    pub const NOT_LVALUE: &str = "E0207";
    /// Checker: `break`/`continue` outside a loop, or level too deep.
    pub const BREAK_OUTSIDE_LOOP: &str = "E0208";
    /// Checker: a name defined twice in one scope.
    pub const REDEFINITION: &str = "E0209";
    /// Checker: `return` value type does not match the function.
    pub const RETURN_TYPE: &str = "E0210";
    /// Checker: statement not allowed in this kind of shader (e.g. `illuminate` in a surface).
    pub const WRONG_CONTEXT: &str = "E0211";
    /// Checker: output parameter passed something that cannot be assigned.
    pub const OUTPUT_ARG: &str = "E0212";
    /// Checker: indexing something that is not an array, or a bad array size.
    pub const BAD_INDEX: &str = "E0213";
    /// Checker: uniform variable assigned under varying control flow.
    pub const UNIFORM_IN_VARYING_FLOW: &str = "E0214";
    /// Checker: wrong number of components in a triple/matrix literal or array initializer.
    pub const BAD_LITERAL: &str = "E0215";
    /// Checker: a shader parameter default that is not a constant expression.
    pub const NON_CONSTANT_DEFAULT: &str = "E0216";
    /// Checker: recursion (RSL functions are inlined and may not recurse).
    pub const RECURSION: &str = "E0217";
    /// Checker: no shader in the file / several shaders where one was expected.
    pub const NO_SHADER: &str = "E0218";
    /// Checker: a function that must return a value may end without `return`.
    pub const MISSING_RETURN: &str = "E0219";
    /// Checker: a read-only global or parameter assigned.
    pub const READ_ONLY: &str = "E0220";
    /// Checker: unsupported feature.
    pub const UNSUPPORTED: &str = "E0221";
    /// Warning: an unknown coordinate or colour space name in a literal.
    pub const UNKNOWN_SPACE: &str = "W0001";
    /// Warning: a variable is used before being assigned.
    pub const UNINITIALIZED: &str = "W0002";
    /// Warning: a missing texture file (reads as black).
    pub const MISSING_TEXTURE: &str = "W0003";
    /// Warning: a `uniform` local of a function is assigned under varying control flow, so it
    /// is made varying (BMRT's noises.h: `uniform float amp` in a loop on a varying width).
    pub const PROMOTED_TO_VARYING: &str = "W0004";
    /// Warning: a C float suffix on a number (`0.5f`), read as the number.
    pub const FLOAT_SUFFIX: &str = "W0005";
    /// Warning: a shader parameter default that is not a constant (`normalize(dPdu)`); it is
    /// computed when the shader runs unless the parameter is given.
    pub const COMPUTED_DEFAULT: &str = "W0006";
    /// Warning: a shader assigns a global the RenderMan spec makes read-only there, which only
    /// that shader reads afterwards (`N` in Pixie's and Aqsis' area lights, `I` in Pixie's
    /// mirror).
    pub const WRITTEN_GLOBAL: &str = "W0007";
    /// Warning: a construct a period compiler took that has no effect here (an `illuminance`
    /// loop in a light shader, which sees no lights).
    pub const NO_EFFECT: &str = "W0008";
    /// Warning: another renderer's or book's name, read as its RenderMan equivalent (Pixie's
    /// `visibility` as `transmission`, `Ps` in a surface shader as `P`).
    pub const OTHER_NAME: &str = "W0009";
    /// Warning: a `#warning` directive (its text).
    pub const PP_WARNING: &str = "W0010";
}

/// A list of diagnostics from one compilation.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Diagnostics {
    /// In the order reported.
    pub items: Vec<Diagnostic>,
}

impl Diagnostics {
    /// An empty list.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds one.
    pub fn push(&mut self, d: Diagnostic) {
        self.items.push(d);
    }

    /// True when any error (not only warnings) was reported.
    #[must_use]
    pub fn has_errors(&self) -> bool {
        self.items.iter().any(|d| d.severity == Severity::Error)
    }

    /// Number of errors.
    #[must_use]
    pub fn error_count(&self) -> usize {
        self.items.iter().filter(|d| d.severity == Severity::Error).count()
    }

    /// Renders every diagnostic as plain text (no colour): `error[E0200]: …`, then
    /// `┌─ file:line:col`, the source line and a caret, then the notes.
    #[cold]
    #[must_use]
    pub fn render(&self, sources: &SourceMap) -> String {
        let mut out = NoColor::new(Vec::new());
        let config = term::Config::default();
        for d in &self.items {
            let cs = to_codespan(d);
            // Rendering into a Vec cannot fail for I/O reasons; a span out of range is turned into
            // an empty label by `Files::line_range`, so ignore the (impossible) error.
            let _ = term::emit(&mut out, &config, sources, &cs);
        }
        String::from_utf8_lossy(&out.into_inner()).into_owned()
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}[{}]: {}",
            if self.severity == Severity::Error { "error" } else { "warning" },
            self.code,
            self.message
        )
    }
}

fn to_codespan(d: &Diagnostic) -> CsDiagnostic<FileId> {
    let sev = match d.severity {
        Severity::Error => CsSeverity::Error,
        Severity::Warning => CsSeverity::Warning,
    };
    let mut labels =
        vec![Label::primary(d.span.file, d.span.start as usize..d.span.end as usize).with_message(&d.label)];
    for (s, l) in &d.secondary {
        labels.push(Label::secondary(s.file, s.start as usize..s.end as usize).with_message(l));
    }
    CsDiagnostic::new(sev).with_code(d.code).with_message(&d.message).with_labels(labels).with_notes(d.notes.clone())
}

impl<'a> Files<'a> for SourceMap {
    type FileId = FileId;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: FileId) -> Result<&'a str, FilesError> {
        self.files().get(id.0 as usize).map(|f| f.name.as_str()).ok_or(FilesError::FileMissing)
    }

    fn source(&'a self, id: FileId) -> Result<&'a str, FilesError> {
        self.files().get(id.0 as usize).map(|f| f.text.as_str()).ok_or(FilesError::FileMissing)
    }

    fn line_index(&'a self, id: FileId, byte_index: usize) -> Result<usize, FilesError> {
        let f = self.files().get(id.0 as usize).ok_or(FilesError::FileMissing)?;
        Ok(f.line_col(byte_index.min(f.text.len()) as u32).0)
    }

    fn line_range(&'a self, id: FileId, line_index: usize) -> Result<Range<usize>, FilesError> {
        let f = self.files().get(id.0 as usize).ok_or(FilesError::FileMissing)?;
        let (first, _) = f.line_col(0);
        let _ = first;
        let text = &f.text;
        // Walk to the requested line; files are small, diagnostics rare.
        let mut start = 0usize;
        for _ in 0..line_index {
            match text[start..].find('\n') {
                Some(i) => start += i + 1,
                None => return Ok(text.len()..text.len()),
            }
        }
        let end = text[start..].find('\n').map_or(text.len(), |i| start + i + 1);
        Ok(start..end)
    }
}
