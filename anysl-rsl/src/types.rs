//! RSL types: the base types, the uniform/varying detail, and fixed-size arrays.

use std::fmt;

/// The base types of the shading language.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum BaseType {
    /// `float`
    Float,
    /// `color` (three components; RGB in the current colour space)
    Color,
    /// `point` (position; transforms with translation)
    Point,
    /// `vector` (direction; transforms without translation)
    Vector,
    /// `normal` (transforms with the inverse transpose)
    Normal,
    /// `matrix` (4×4, row-major, row vectors as in RenderMan)
    Matrix,
    /// `string`
    String,
    /// `void` (functions only)
    Void,
}

impl BaseType {
    /// The keyword.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Float => "float",
            Self::Color => "color",
            Self::Point => "point",
            Self::Vector => "vector",
            Self::Normal => "normal",
            Self::Matrix => "matrix",
            Self::String => "string",
            Self::Void => "void",
        }
    }

    /// `point`, `vector` or `normal`.
    #[must_use]
    pub const fn is_pointlike(self) -> bool {
        matches!(self, Self::Point | Self::Vector | Self::Normal)
    }

    /// A three-component type (`color` or point-like).
    #[must_use]
    pub const fn is_triple(self) -> bool {
        matches!(self, Self::Color | Self::Point | Self::Vector | Self::Normal)
    }

    /// Number of float components (float 1, triples 3, matrix 16, others 0).
    #[must_use]
    pub const fn components(self) -> usize {
        match self {
            Self::Float => 1,
            Self::Color | Self::Point | Self::Vector | Self::Normal => 3,
            Self::Matrix => 16,
            Self::String | Self::Void => 0,
        }
    }

    /// Parses a type keyword.
    #[must_use]
    pub fn from_keyword(s: &str) -> Option<Self> {
        Some(match s {
            "float" => Self::Float,
            "color" => Self::Color,
            "point" => Self::Point,
            "vector" => Self::Vector,
            "normal" => Self::Normal,
            "matrix" => Self::Matrix,
            "string" => Self::String,
            "void" => Self::Void,
            _ => return None,
        })
    }
}

impl fmt::Display for BaseType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Whether a value may differ between shading points.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub enum Detail {
    /// The same for every point of a grid (and so held as a scalar).
    Uniform,
    /// Per shading point.
    #[default]
    Varying,
}

impl fmt::Display for Detail {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Uniform => "uniform",
            Self::Varying => "varying",
        })
    }
}

/// A full type: base, detail and an optional array length.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Type {
    /// The base type.
    pub base: BaseType,
    /// Uniform or varying.
    pub detail: Detail,
    /// `Some(n)` for a fixed-size array of `n` elements.
    pub array: Option<u32>,
}

impl Type {
    /// A scalar (non-array) type.
    #[must_use]
    pub const fn new(base: BaseType, detail: Detail) -> Self {
        Self { base, detail, array: None }
    }

    /// `uniform float` etc.
    #[must_use]
    pub const fn uniform(base: BaseType) -> Self {
        Self::new(base, Detail::Uniform)
    }

    /// `varying float` etc.
    #[must_use]
    pub const fn varying(base: BaseType) -> Self {
        Self::new(base, Detail::Varying)
    }

    /// The same type with another detail.
    #[must_use]
    pub const fn with_detail(self, detail: Detail) -> Self {
        Self { detail, ..self }
    }

    /// The element type of an array (the type itself otherwise).
    #[must_use]
    pub const fn element(self) -> Self {
        Self { array: None, ..self }
    }
}

impl fmt::Display for Type {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.detail, self.base)?;
        if let Some(n) = self.array {
            write!(f, "[{n}]")?;
        }
        Ok(())
    }
}
