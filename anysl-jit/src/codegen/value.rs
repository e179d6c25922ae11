//! The values of code generation: how a number is held ([`Repr`]), one float ([`S`]), a mask
//! ([`M`]), a value of the IR ([`Val`]), the result shapes of threaded functions ([`Shape`]),
//! and the generator's error type. Types only: this file imports no other file of the
//! generator.

use inkwell::values::BasicValueEnum;

/// How a number is held: a uniform scalar, a varying vector, or a varying dual number.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Repr {
    /// One `float` for every lane.
    U,
    /// One value per lane.
    V,
    /// Value, ∂/∂x and ∂/∂y per lane.
    D,
}

impl Repr {
    pub(super) fn letter(self) -> char {
        match self {
            Repr::U => 'u',
            Repr::V => 'v',
            Repr::D => 'd',
        }
    }
}

/// One float: its value and, for dual numbers, its derivatives.
#[derive(Clone, Copy, Debug)]
pub struct S<'c> {
    pub(super) r: Repr,
    pub(super) v: BasicValueEnum<'c>,
    pub(super) d: Option<(BasicValueEnum<'c>, BasicValueEnum<'c>)>,
}

/// A mask (boolean): uniform `i1` or varying `<N x i1>`.
#[derive(Clone, Copy, Debug)]
pub struct M<'c> {
    pub(super) uni: bool,
    pub(super) v: BasicValueEnum<'c>,
}

/// A value of the IR during code generation.
#[derive(Clone, Debug)]
pub enum Val<'c> {
    /// Float components (1, 3, 16 or arrays of those).
    Num(Vec<S<'c>>),
    /// A boolean.
    Mask(M<'c>),
    /// A string (compile-time).
    Str(Vec<String>),
    /// Nothing.
    Void,
}

/// Result shapes of threaded functions.
#[derive(Clone, Debug)]
pub enum Shape {
    /// Float components with their representations.
    Num(Vec<Repr>),
    /// A mask (uniform?).
    Mask(bool),
    /// A compile-time string.
    Str(Vec<String>),
    /// Nothing.
    Void,
}

/// A code generation error (an unsupported op or built-in).
#[derive(Clone, Debug)]
pub struct CgError(pub String);

pub(super) type R<T> = Result<T, CgError>;

pub(super) fn err<T>(s: impl Into<String>) -> R<T> {
    Err(CgError(s.into()))
}
