//! Diagnostics: small structured errors and warnings, rendered with `codespan-reporting`.
//!
//! The reader reports [`Diagnostic`]s into one list and keeps going where it can (it skips to the
//! next request name), so one run shows several errors. Rendering (`error[R0xx]: message`,
//! `--> file:line:col`, the source line, a caret under the offending text, notes) happens once,
//! at the end, in [`render`].

use crate::source::{FileId, Loc, SourceMap};
use codespan_reporting::diagnostic::{Diagnostic as CsDiagnostic, Label, Severity as CsSeverity};
use codespan_reporting::files::{Error as FilesError, Files};
use codespan_reporting::term::{self, termcolor::NoColor, Chars};
use std::fmt;
use std::ops::Range;

/// How bad a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// Reading goes on and succeeds.
    Warning,
    /// Reading goes on to find more errors, then fails.
    Error,
}

/// One problem found in a RIB file.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// Stable code, e.g. `R021`; see [`codes`].
    pub code: &'static str,
    /// One-line message.
    pub message: String,
    /// Where (the caret goes here).
    pub loc: Loc,
    /// Label under the caret.
    pub label: String,
    /// Further places, e.g. the `AttributeBegin` an `End` does not match.
    pub secondary: Vec<(Loc, String)>,
    /// Hints on how to fix it.
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// An error with code, location and message.
    #[must_use]
    pub fn error(code: &'static str, loc: Loc, message: impl Into<String>) -> Self {
        Self {
            severity: Severity::Error,
            code,
            message: message.into(),
            loc,
            label: String::new(),
            secondary: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// A warning with code, location and message.
    #[must_use]
    pub fn warning(code: &'static str, loc: Loc, message: impl Into<String>) -> Self {
        Self { severity: Severity::Warning, ..Self::error(code, loc, message) }
    }

    /// Sets the label under the caret.
    #[must_use]
    pub fn with_label(mut self, label: impl Into<String>) -> Self {
        self.label = label.into();
        self
    }

    /// Adds a secondary location.
    #[must_use]
    pub fn with_secondary(mut self, loc: Loc, label: impl Into<String>) -> Self {
        self.secondary.push((loc, label.into()));
        self
    }

    /// Adds a note.
    #[must_use]
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }

    /// True for errors (not warnings).
    #[must_use]
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let sev = if self.is_error() { "error" } else { "warning" };
        write!(f, "{}: {sev}[{}]: {}", self.loc, self.code, self.message)
    }
}

/// Diagnostic codes, one per kind of problem. Stable: tests and users match on them.
pub mod codes {
    /// Lexer: a character that starts no token.
    pub const BAD_CHAR: &str = "R001";
    /// Lexer: string without its closing quote.
    pub const UNTERMINATED_STRING: &str = "R002";
    /// Lexer: malformed number.
    pub const BAD_NUMBER: &str = "R003";
    /// Lexer: a byte in `0x80..=0xff` outside a string (binary RIB).
    pub const BINARY_RIB: &str = "R004";
    /// Arrays: `]` without `[`.
    pub const UNMATCHED_BRACKET: &str = "R010";
    /// Arrays: `[` without `]`.
    pub const UNCLOSED_ARRAY: &str = "R011";
    /// Arrays: an array inside an array, or numbers and strings mixed in one array.
    pub const BAD_ARRAY: &str = "R012";
    /// Requests: a value where a request name was expected.
    pub const EXPECTED_REQUEST: &str = "R020";
    /// Requests: too few arguments, or an array of the wrong length.
    pub const ARG_COUNT: &str = "R021";
    /// Requests: an argument of the wrong type (a string for a number, a fraction for an integer).
    pub const ARG_TYPE: &str = "R022";
    /// Requests: more arguments than the request takes.
    pub const EXTRA_ARGS: &str = "R023";
    /// Parameter lists: a value where a parameter name was expected.
    pub const EXPECTED_PARAM_NAME: &str = "R030";
    /// Parameter lists: a malformed inline declaration or `Declare`.
    pub const BAD_DECLARATION: &str = "R031";
    /// Parameter lists: a value count that is not a multiple of the type's component count.
    pub const VALUE_COUNT: &str = "R032";
    /// Parameter lists: values of the wrong kind (strings for a float parameter, fractions for an
    /// integer one).
    pub const VALUE_TYPE: &str = "R033";
    /// Parameter lists: a parameter name without a value.
    pub const MISSING_VALUE: &str = "R034";
    /// Blocks: an `…End` that does not close the innermost open `…Begin`.
    pub const UNBALANCED_END: &str = "R040";
    /// Blocks: a `…Begin` never closed.
    pub const UNCLOSED_BLOCK: &str = "R041";
    /// Archives: `ReadArchive` of a file found nowhere on the search path.
    pub const ARCHIVE_NOT_FOUND: &str = "R050";
    /// Archives: an archive that (indirectly) reads itself.
    pub const INCLUDE_CYCLE: &str = "R051";
    /// Archives: a file that could not be read or decompressed.
    pub const IO: &str = "R052";
    /// Archives: `ArchiveBegin` without `ArchiveEnd`.
    pub const UNCLOSED_ARCHIVE: &str = "R053";
    /// Archives: `ReadArchive` nesting deeper than [`Options::max_archive_depth`](crate::Options).
    pub const ARCHIVE_DEPTH: &str = "R054";
    /// Builder: the builder refused a request.
    pub const BUILD: &str = "R060";
    /// Limits: more requests than [`Options::max_requests`](crate::Options), or too many errors.
    pub const LIMIT: &str = "R070";
    /// Warning: a request name the reader does not know; its arguments are skipped.
    pub const UNKNOWN_REQUEST: &str = "W001";
    /// Warning: a request the builder does not support.
    pub const UNSUPPORTED_REQUEST: &str = "W002";
    /// Warning: a parameter that is not declared; its type is taken from its values.
    pub const UNDECLARED_PARAM: &str = "W003";
    /// Warning: reported by the builder.
    pub const BUILD_WARNING: &str = "W004";
}

/// Renders diagnostics as plain text (no colour): `error[R021]: …`, `--> file:line:col`, the
/// source line and a caret, then the notes.
#[cold]
#[must_use]
pub fn render(diagnostics: &[Diagnostic], sources: &SourceMap) -> String {
    let mut out = NoColor::new(Vec::new());
    let config = term::Config { chars: Chars::ascii(), ..term::Config::default() };
    for d in diagnostics {
        let cs = to_codespan(d);
        // Rendering into a Vec cannot fail for I/O reasons, and every location comes from the
        // same map; ignore the (impossible) error rather than panic.
        let _ = term::emit(&mut out, &config, sources, &cs);
    }
    String::from_utf8_lossy(&out.into_inner()).into_owned()
}

fn to_codespan(d: &Diagnostic) -> CsDiagnostic<FileId> {
    let sev = match d.severity {
        Severity::Error => CsSeverity::Error,
        Severity::Warning => CsSeverity::Warning,
    };
    let range = |l: &Loc| l.start as usize..l.end as usize;
    let mut labels = vec![Label::primary(d.loc.file, range(&d.loc)).with_message(&d.label)];
    for (l, m) in &d.secondary {
        labels.push(Label::secondary(l.file, range(l)).with_message(m));
    }
    CsDiagnostic::new(sev).with_code(d.code).with_message(&d.message).with_labels(labels).with_notes(d.notes.clone())
}

impl<'a> Files<'a> for SourceMap {
    type FileId = FileId;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: FileId) -> Result<&'a str, FilesError> {
        self.get(id).map(|f| &*f.name).ok_or(FilesError::FileMissing)
    }

    fn source(&'a self, id: FileId) -> Result<&'a str, FilesError> {
        self.get(id).map(|f| f.text()).ok_or(FilesError::FileMissing)
    }

    fn line_index(&'a self, id: FileId, byte_index: usize) -> Result<usize, FilesError> {
        let f = self.get(id).ok_or(FilesError::FileMissing)?;
        Ok(f.line_col(u32::try_from(byte_index).unwrap_or(u32::MAX)).0)
    }

    fn line_range(&'a self, id: FileId, line_index: usize) -> Result<Range<usize>, FilesError> {
        let f = self.get(id).ok_or(FilesError::FileMissing)?;
        let len = f.bytes.len();
        let starts = f.line_starts();
        let start = starts.get(line_index).map_or(len, |&s| s as usize);
        let end = starts.get(line_index + 1).map_or(len, |&e| e as usize);
        Ok(start..end)
    }
}

/// The reader failed: at least one error. Holds every diagnostic (warnings too) and the sources
/// needed to render them.
#[derive(Clone, Debug)]
pub struct RibError {
    /// Errors and warnings, in the order found.
    pub diagnostics: Vec<Diagnostic>,
    /// The files read, for rendering.
    pub sources: SourceMap,
}

impl RibError {
    /// The errors only.
    pub fn errors(&self) -> impl Iterator<Item = &Diagnostic> {
        self.diagnostics.iter().filter(|d| d.is_error())
    }

    /// Renders every diagnostic (errors and warnings) as codespan-style text.
    #[cold]
    #[must_use]
    pub fn render(&self) -> String {
        render(&self.diagnostics, &self.sources)
    }
}

impl fmt::Display for RibError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render())
    }
}

impl std::error::Error for RibError {}
