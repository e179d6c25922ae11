//! What the reader hands to a builder: handles, bases, and the builder's error type.
//!
//! The [`RibBuilder`](crate::RibBuilder) trait itself (one method per request) is generated
//! with the [`Request`](crate::Request) enum from one table in `requests.rs`.

use std::fmt;

/// A light or object handle: RIB writes an integer sequence number or a string.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Handle {
    /// `LightSource "pointlight" 1`.
    Int(i32),
    /// `LightSource "pointlight" "key"`.
    Str(String),
}

impl fmt::Display for Handle {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Int(i) => write!(f, "{i}"),
            Self::Str(s) => write!(f, "\"{s}\""),
        }
    }
}

/// A 4×4 matrix, row-major, as written in RIB (points are row vectors: `p' = p · M`).
pub type Matrix = [f32; 16];

/// A patch basis: a standard name or an explicit matrix.
#[derive(Clone, Debug, PartialEq)]
pub enum Basis {
    /// `"bezier"`, `"b-spline"`, `"catmull-rom"`, `"hermite"`, `"power"`, or another name.
    Named(String),
    /// Sixteen numbers.
    Matrix(Matrix),
}

/// How a builder's refusal is reported.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BuildErrorKind {
    /// The builder does not implement the request: one warning per request name, reading goes on.
    Unsupported,
    /// The request is accepted with a warning.
    Warning,
    /// The request is wrong: an error at its location (reading goes on to find more).
    Error,
}

/// A builder's answer to a request it refuses or accepts with a warning.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BuildError {
    /// Unsupported, warning or error.
    pub kind: BuildErrorKind,
    /// One-line message (empty for [`BuildErrorKind::Unsupported`]).
    pub message: String,
    /// Hints on how to fix it.
    pub notes: Vec<String>,
}

impl BuildError {
    /// The request is not supported by this builder (the default of every builder method).
    #[must_use]
    pub fn unsupported() -> Self {
        Self { kind: BuildErrorKind::Unsupported, message: String::new(), notes: Vec::new() }
    }

    /// An error with a message.
    #[must_use]
    pub fn error(message: impl Into<String>) -> Self {
        Self { kind: BuildErrorKind::Error, message: message.into(), notes: Vec::new() }
    }

    /// A warning with a message: the request was taken, maybe only in part.
    #[must_use]
    pub fn warning(message: impl Into<String>) -> Self {
        Self { kind: BuildErrorKind::Warning, message: message.into(), notes: Vec::new() }
    }

    /// Adds a note.
    #[must_use]
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.kind {
            BuildErrorKind::Unsupported => f.write_str("unsupported request"),
            _ => f.write_str(&self.message),
        }
    }
}

impl std::error::Error for BuildError {}

/// Borrowed argument → owned field of a [`Request`](crate::Request).
pub(crate) trait OwnArg {
    type Owned;
    fn own(self) -> Self::Owned;
}

/// Owned field of a [`Request`](crate::Request) → borrowed argument.
pub(crate) trait BorrowArg {
    type Ref<'a>
    where
        Self: 'a;
    fn borrow_arg(&self) -> Self::Ref<'_>;
}

macro_rules! copy_arg {
    ($($t:ty),*) => {$(
        impl OwnArg for $t {
            type Owned = $t;
            fn own(self) -> $t { self }
        }
        impl BorrowArg for $t {
            type Ref<'a> = $t;
            fn borrow_arg(&self) -> $t { *self }
        }
    )*};
}
copy_arg!(f32, i32, bool);

macro_rules! ref_arg {
    ($($t:ty),*) => {$(
        impl OwnArg for &$t {
            type Owned = $t;
            fn own(self) -> $t { self.clone() }
        }
        impl BorrowArg for $t {
            type Ref<'a> = &'a $t;
            fn borrow_arg(&self) -> &$t { self }
        }
    )*};
}
ref_arg!(Handle, Basis, crate::param::ParamList);

impl OwnArg for &str {
    type Owned = String;
    fn own(self) -> String {
        self.to_owned()
    }
}

impl BorrowArg for String {
    type Ref<'a> = &'a str;
    fn borrow_arg(&self) -> &str {
        self
    }
}

impl<T: Clone> OwnArg for &[T] {
    type Owned = Vec<T>;
    fn own(self) -> Vec<T> {
        self.to_vec()
    }
}

impl<T> BorrowArg for Vec<T> {
    type Ref<'a>
        = &'a [T]
    where
        T: 'a;
    fn borrow_arg(&self) -> &[T] {
        self
    }
}

impl<T: Clone, const N: usize> OwnArg for &[T; N] {
    type Owned = [T; N];
    fn own(self) -> [T; N] {
        self.clone()
    }
}

impl<T, const N: usize> BorrowArg for [T; N] {
    type Ref<'a>
        = &'a [T; N]
    where
        T: 'a;
    fn borrow_arg(&self) -> &[T; N] {
        self
    }
}
