//! Parameter lists: `"name" value-or-[values]` pairs, typed by declarations.
//!
//! A parameter's type comes from an inline declaration (`"uniform float Ks"`), from `Declare`,
//! or from the predeclared names of the RenderMan Interface (`P`, `N`, `Cs`, `st`, …). The
//! reader checks that each value count is a multiple of the type's component count; it does not
//! check counts per primitive (uniform/varying/vertex), which only the builder knows.

use crate::source::Loc;
use std::fmt;

/// Storage class of a parameter: how its values are spread over a primitive.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Class {
    /// One value for the whole primitive.
    Constant,
    /// One value per face (patch, polygon, curve).
    Uniform,
    /// One value per corner of each face, interpolated bilinearly.
    Varying,
    /// One value per control vertex, interpolated like the surface.
    Vertex,
    /// One value per vertex of each face, bilinearly.
    FaceVarying,
    /// One value per vertex of each face, like the surface.
    FaceVertex,
}

impl Class {
    /// Parses a class keyword.
    #[must_use]
    pub fn from_keyword(s: &str) -> Option<Self> {
        Some(match s {
            "constant" => Self::Constant,
            "uniform" => Self::Uniform,
            "varying" => Self::Varying,
            "vertex" => Self::Vertex,
            "facevarying" => Self::FaceVarying,
            "facevertex" => Self::FaceVertex,
            _ => return None,
        })
    }

    /// The keyword, as written in RIB.
    #[must_use]
    pub fn keyword(self) -> &'static str {
        match self {
            Self::Constant => "constant",
            Self::Uniform => "uniform",
            Self::Varying => "varying",
            Self::Vertex => "vertex",
            Self::FaceVarying => "facevarying",
            Self::FaceVertex => "facevertex",
        }
    }
}

/// Type of a parameter's elements.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Type {
    /// One float.
    Float,
    /// One integer (`integer` or `int`).
    Integer,
    /// One string.
    String,
    /// Three floats, a position.
    Point,
    /// Three floats, a direction.
    Vector,
    /// Three floats, a surface normal.
    Normal,
    /// Three floats, an RGB colour.
    Color,
    /// Four floats, a homogeneous position.
    HPoint,
    /// Sixteen floats, a 4×4 matrix in row-major order.
    Matrix,
    /// One integer, 0 or not.
    Bool,
}

impl Type {
    /// Parses a type keyword.
    #[must_use]
    pub fn from_keyword(s: &str) -> Option<Self> {
        Some(match s {
            "float" => Self::Float,
            "integer" | "int" => Self::Integer,
            "string" => Self::String,
            "point" => Self::Point,
            "vector" => Self::Vector,
            "normal" => Self::Normal,
            "color" => Self::Color,
            "hpoint" => Self::HPoint,
            "matrix" => Self::Matrix,
            "bool" => Self::Bool,
            _ => return None,
        })
    }

    /// The keyword, as written in RIB.
    #[must_use]
    pub fn keyword(self) -> &'static str {
        match self {
            Self::Float => "float",
            Self::Integer => "integer",
            Self::String => "string",
            Self::Point => "point",
            Self::Vector => "vector",
            Self::Normal => "normal",
            Self::Color => "color",
            Self::HPoint => "hpoint",
            Self::Matrix => "matrix",
            Self::Bool => "bool",
        }
    }

    /// Number of values one element takes (3 for a colour, 16 for a matrix).
    #[must_use]
    pub fn components(self) -> usize {
        match self {
            Self::Float | Self::Integer | Self::String | Self::Bool => 1,
            Self::Point | Self::Vector | Self::Normal | Self::Color => 3,
            Self::HPoint => 4,
            Self::Matrix => 16,
        }
    }

    /// The kind of values it holds.
    #[must_use]
    pub fn value_kind(self) -> ValueKind {
        match self {
            Self::Integer | Self::Bool => ValueKind::Int,
            Self::String => ValueKind::String,
            _ => ValueKind::Float,
        }
    }
}

/// The kind of values a parameter holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ValueKind {
    /// Floats.
    Float,
    /// Integers.
    Int,
    /// Strings.
    String,
}

/// A declaration: class, type and array length.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Decl {
    /// Storage class.
    pub class: Class,
    /// Element type.
    pub ty: Type,
    /// `Some(n)` for `type[n]`.
    pub array_len: Option<u32>,
}

impl Decl {
    /// A declaration without array length.
    #[must_use]
    pub const fn new(class: Class, ty: Type) -> Self {
        Self { class, ty, array_len: None }
    }

    /// Values per item: the type's components times the array length.
    #[must_use]
    pub fn values_per_item(&self) -> usize {
        self.ty.components().saturating_mul(self.array_len.unwrap_or(1) as usize)
    }

    /// Parses the class and type part of a declaration: `"uniform float"`, `"varying color"`,
    /// `"float[2]"`. The class defaults to `uniform`.
    pub fn parse(text: &str) -> Result<Self, String> {
        let words = split_decl(text);
        let (decl, rest) = parse_class_type(&words)?;
        if let Some(extra) = rest.first() {
            return Err(format!("unexpected `{extra}` after the type"));
        }
        Ok(decl)
    }
}

impl fmt::Display for Decl {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.class.keyword(), self.ty.keyword())?;
        if let Some(n) = self.array_len {
            write!(f, "[{n}]")?;
        }
        Ok(())
    }
}

/// Splits a declaration into words, with `[n]` as words of its own.
fn split_decl(text: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut cur = String::new();
    for c in text.chars() {
        if c.is_whitespace() || c == '[' || c == ']' {
            if !cur.is_empty() {
                words.push(std::mem::take(&mut cur));
            }
            if c == '[' || c == ']' {
                words.push(c.to_string());
            }
        } else {
            cur.push(c);
        }
    }
    if !cur.is_empty() {
        words.push(cur);
    }
    words
}

fn parse_class_type(words: &[String]) -> Result<(Decl, &[String]), String> {
    let mut i = 0;
    let class = match words.first().and_then(|w| Class::from_keyword(w)) {
        Some(c) => {
            i += 1;
            c
        }
        None => Class::Uniform,
    };
    let Some(word) = words.get(i) else { return Err("missing type".into()) };
    let ty = Type::from_keyword(word).ok_or_else(|| format!("unknown type `{word}`"))?;
    i += 1;
    let mut array_len = None;
    if words.get(i).map(String::as_str) == Some("[") {
        let n = words.get(i + 1).and_then(|w| w.parse::<u32>().ok()).filter(|&n| n > 0);
        if n.is_none() || words.get(i + 2).map(String::as_str) != Some("]") {
            return Err("bad array length; write `type[n]` with n > 0".into());
        }
        array_len = n;
        i += 3;
    }
    Ok((Decl { class, ty, array_len }, &words[i..]))
}

/// Parses an inline declaration `"[class] type[[n]] name"`; `None` when `text` is a plain name
/// (one word, no brackets).
pub fn parse_inline(text: &str) -> Option<Result<(Decl, String), String>> {
    let trimmed = text.trim();
    if !trimmed.contains(|c: char| c.is_whitespace() || c == '[') {
        return None;
    }
    let words = split_decl(trimmed);
    Some(parse_class_type(&words).and_then(|(decl, rest)| match rest {
        [name] if name != "[" && name != "]" => Ok((decl, name.clone())),
        [] => Err("missing parameter name after the type".into()),
        _ => Err(format!("expected one parameter name after the type, found `{}`", rest.join(" "))),
    }))
}

/// The predeclared parameters of the RenderMan Interface 3.2 (and common qualified option and
/// attribute names, written `category:name`).
#[must_use]
pub fn predeclared(name: &str) -> Option<Decl> {
    use Class::{Constant, Uniform, Varying, Vertex};
    use Type::{Color, Float, HPoint, Integer, Normal, Point, String as Str};
    let d = |class, ty| Some(Decl::new(class, ty));
    match name {
        "P" => d(Vertex, Point),
        "Pz" => d(Vertex, Float),
        "Pw" => d(Vertex, HPoint),
        "N" => d(Varying, Normal),
        "Np" => d(Uniform, Normal),
        "Cs" | "Os" => d(Varying, Color),
        "s" | "t" | "u" | "v" | "width" => d(Varying, Float),
        "st" => Some(Decl { class: Varying, ty: Float, array_len: Some(2) }),
        "constantwidth" => d(Constant, Float),
        "Ka" | "Kd" | "Ks" | "Kr" | "Kt" | "roughness" | "intensity" | "coneangle" | "conedeltaangle"
        | "beamdistribution" | "mindistance" | "maxdistance" | "distance" | "amplitude" | "fov" | "sphere" | "bias"
        | "gain" | "gamma" => d(Uniform, Float),
        "texturename" | "shadowname" | "coordinatesystem" | "name" | "filename" | "mapname" => d(Uniform, Str),
        "specularcolor" | "lightcolor" | "background" => d(Uniform, Color),
        "from" | "to" => d(Uniform, Point),
        "origin" => Some(Decl { class: Uniform, ty: Integer, array_len: Some(2) }),
        "jitter" | "maxdepth" => d(Uniform, Integer),
        _ => predeclared_qualified(name),
    }
}

fn predeclared_qualified(name: &str) -> Option<Decl> {
    use Class::Uniform;
    use Type::{Float, Integer, String as Str};
    let d = |ty| Some(Decl::new(Uniform, ty));
    match name {
        n if n.starts_with("searchpath:") => d(Str),
        "limits:bucketsize" | "limits:extremedisplacement" => {
            Some(Decl { class: Uniform, ty: Integer, array_len: Some(2) })
        }
        "limits:gridsize"
        | "limits:texturememory"
        | "limits:eyesplits"
        | "trace:maxdepth"
        | "visibility:camera"
        | "visibility:trace"
        | "visibility:transmission"
        | "visibility:diffuse"
        | "visibility:specular"
        | "visibility:photon"
        | "dice:binary"
        | "dice:rasterorient"
        | "sides:doubleshaded"
        | "hider:jitter" => d(Integer),
        "displacementbound:sphere" | "trace:bias" | "shadow:bias" | "shadow:bias0" | "shadow:bias1" => d(Float),
        "displacementbound:coordinatesystem" | "identifier:name" | "render:bucketorder" => d(Str),
        _ => None,
    }
}

/// The values of a parameter.
#[derive(Clone, Debug, PartialEq)]
pub enum Values {
    /// For float, point, vector, normal, color, hpoint and matrix parameters.
    Float(Vec<f32>),
    /// For integer and bool parameters.
    Int(Vec<i32>),
    /// For string parameters.
    String(Vec<String>),
}

impl Values {
    /// Number of values.
    #[must_use]
    pub fn len(&self) -> usize {
        match self {
            Self::Float(v) => v.len(),
            Self::Int(v) => v.len(),
            Self::String(v) => v.len(),
        }
    }

    /// True when there are no values.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Where a parameter's declaration came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DeclOrigin {
    /// Written in the parameter name: `"uniform float Ks"`.
    Inline,
    /// From an earlier `Declare`.
    Declare,
    /// One of the predeclared names (`P`, `Cs`, …).
    Predeclared,
    /// Not declared: `uniform float` for numbers, `uniform string` for strings (with a warning).
    /// A builder that knows better (e.g. a shader's own parameter types) may reinterpret it.
    Inferred,
}

/// One parameter of a parameter list.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// The bare name (`Ks`, not `uniform float Ks`).
    pub name: String,
    /// Class, type and array length.
    pub decl: Decl,
    /// Where `decl` came from.
    pub origin: DeclOrigin,
    /// The values; the count is a multiple of [`Decl::values_per_item`].
    pub values: Values,
    /// Where the parameter's name string is.
    pub loc: Loc,
}

impl Param {
    /// The values as floats, if float-typed.
    #[must_use]
    pub fn floats(&self) -> Option<&[f32]> {
        match &self.values {
            Values::Float(v) => Some(v),
            _ => None,
        }
    }

    /// The values as integers, if integer- or bool-typed.
    #[must_use]
    pub fn ints(&self) -> Option<&[i32]> {
        match &self.values {
            Values::Int(v) => Some(v),
            _ => None,
        }
    }

    /// The values as strings, if string-typed.
    #[must_use]
    pub fn strings(&self) -> Option<&[String]> {
        match &self.values {
            Values::String(v) => Some(v),
            _ => None,
        }
    }

    /// Number of items: values divided by values per item.
    #[must_use]
    pub fn item_count(&self) -> usize {
        self.values.len() / self.decl.values_per_item().max(1)
    }
}

/// A request's parameter list, in the order written.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ParamList {
    /// The parameters.
    pub params: Vec<Param>,
}

impl ParamList {
    /// An empty list.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of parameters.
    #[must_use]
    pub fn len(&self) -> usize {
        self.params.len()
    }

    /// True when empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.params.is_empty()
    }

    /// The parameters in order.
    pub fn iter(&self) -> std::slice::Iter<'_, Param> {
        self.params.iter()
    }

    /// The last parameter named `name` (a later one overrides an earlier one).
    #[must_use]
    pub fn get(&self, name: &str) -> Option<&Param> {
        self.params.iter().rev().find(|p| p.name == name)
    }

    /// The float values of `name`, if present and float-typed.
    #[must_use]
    pub fn floats(&self, name: &str) -> Option<&[f32]> {
        self.get(name).and_then(Param::floats)
    }

    /// The first float value of `name`.
    #[must_use]
    pub fn float(&self, name: &str) -> Option<f32> {
        self.floats(name).and_then(|v| v.first().copied())
    }

    /// The integer values of `name`, if present and integer-typed.
    #[must_use]
    pub fn ints(&self, name: &str) -> Option<&[i32]> {
        self.get(name).and_then(Param::ints)
    }

    /// The first integer value of `name`.
    #[must_use]
    pub fn int(&self, name: &str) -> Option<i32> {
        self.ints(name).and_then(|v| v.first().copied())
    }

    /// The string values of `name`, if present and string-typed.
    #[must_use]
    pub fn strings(&self, name: &str) -> Option<&[String]> {
        self.get(name).and_then(Param::strings)
    }

    /// The first string value of `name`.
    #[must_use]
    pub fn string(&self, name: &str) -> Option<&str> {
        self.strings(name).and_then(|v| v.first()).map(String::as_str)
    }
}

impl<'a> IntoIterator for &'a ParamList {
    type Item = &'a Param;
    type IntoIter = std::slice::Iter<'a, Param>;
    fn into_iter(self) -> Self::IntoIter {
        self.params.iter()
    }
}
