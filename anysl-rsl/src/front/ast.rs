//! The abstract syntax tree produced by the parser.
//!
//! Every node carries a [`Span`]. Expressions also carry an [`ExprId`], dense and unique within
//! one [`Unit`], so that the checker can record each expression's type in a side table
//! (`Vec<Type>` indexed by id) instead of mutating the tree.

use crate::span::Span;
use crate::types::{BaseType, Detail};

/// Dense id of an expression within a [`Unit`] (assigned by the parser in creation order).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ExprId(pub u32);

/// An identifier with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    /// The name.
    pub name: String,
    /// Where.
    pub span: Span,
}

/// A parsed source file (after preprocessing): its top-level definitions in order.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Unit {
    /// Shaders and functions, in source order.
    pub items: Vec<Item>,
    /// Number of expression ids handed out (ids are `0..expr_count`).
    pub expr_count: u32,
}

/// A top-level definition.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// `surface name(params) { body }` and the other shader kinds.
    Shader(ShaderDef),
    /// `type name(params) { body }`.
    Function(FunctionDef),
}

/// The kind of a shader definition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShaderType {
    /// `surface`
    Surface,
    /// `light`
    Light,
    /// `displacement`
    Displacement,
    /// `volume` (atmosphere, interior, exterior)
    Volume,
    /// `imager`
    Imager,
}

impl ShaderType {
    /// The keyword.
    #[must_use]
    pub const fn keyword(self) -> &'static str {
        match self {
            Self::Surface => "surface",
            Self::Light => "light",
            Self::Displacement => "displacement",
            Self::Volume => "volume",
            Self::Imager => "imager",
        }
    }
}

/// A shader definition.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderDef {
    /// Surface, light, ….
    pub kind: ShaderType,
    /// The shader's name.
    pub name: Ident,
    /// Instance parameters, each with a default.
    pub params: Vec<Param>,
    /// The body.
    pub body: Block,
    /// From the kind keyword to the closing brace.
    pub span: Span,
}

/// A function definition (top level or nested in a block).
#[derive(Clone, Debug, PartialEq)]
pub struct FunctionDef {
    /// Return type (`void` for none); `None` detail when the source gave none.
    pub ret: TypeSpec,
    /// The name.
    pub name: Ident,
    /// Formal parameters.
    pub params: Vec<Param>,
    /// The body.
    pub body: Block,
    /// Whole definition.
    pub span: Span,
}

/// A written type: optional detail, base type, and (for declarators) array length elsewhere.
#[derive(Clone, Debug, PartialEq)]
pub struct TypeSpec {
    /// `uniform`/`varying` if written.
    pub detail: Option<Detail>,
    /// The base type.
    pub base: BaseType,
    /// Where the type was written.
    pub span: Span,
}

/// A shader or function parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// `output` was written.
    pub output: bool,
    /// Type (one `TypeSpec` may be shared by several names: `float Ka = 1, Kd = .5`; the parser
    /// repeats it for each).
    pub ty: TypeSpec,
    /// The name.
    pub name: Ident,
    /// `[n]` array length; `Some(None)` for an unsized array parameter `float a[]`.
    pub array: Option<Option<u32>>,
    /// `= expr` default (required for shader parameters, optional for functions).
    pub default: Option<Expr>,
    /// Whole declarator.
    pub span: Span,
}

/// `{ statements }`.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Block {
    /// The statements.
    pub stmts: Vec<Stmt>,
    /// From `{` to `}`.
    pub span: Span,
}

/// One variable declared in a declaration statement.
#[derive(Clone, Debug, PartialEq)]
pub struct Declarator {
    /// The name.
    pub name: Ident,
    /// `[n]` array length.
    pub array: Option<u32>,
    /// `= expr` (for arrays, usually an [`ExprKind::ArrayInit`]).
    pub init: Option<Expr>,
    /// Whole declarator.
    pub span: Span,
}

/// A statement.
#[derive(Clone, Debug, PartialEq)]
pub struct Stmt {
    /// What it is.
    pub kind: StmtKind,
    /// Where.
    pub span: Span,
}

/// The statement kinds.
#[derive(Clone, Debug, PartialEq)]
pub enum StmtKind {
    /// `;`
    Empty,
    /// `expr;` (assignments and calls)
    Expr(Expr),
    /// `[extern] [uniform|varying] type a = 1, b[3];`
    Decl {
        /// `extern` was written (access to a variable of an enclosing function/shader).
        is_extern: bool,
        /// The type.
        ty: TypeSpec,
        /// The declared names.
        vars: Vec<Declarator>,
    },
    /// `{ … }`
    Block(Block),
    /// `if (cond) then [else otherwise]`
    If {
        /// Condition (a float or relation).
        cond: Expr,
        /// Then branch.
        then: Box<Stmt>,
        /// Else branch.
        otherwise: Option<Box<Stmt>>,
    },
    /// `while (cond) body`
    While {
        /// Condition.
        cond: Expr,
        /// Body.
        body: Box<Stmt>,
    },
    /// `for (init; cond; step) body`
    For {
        /// Initialization expression (RSL has no declarations here).
        init: Option<Expr>,
        /// Condition (absent = forever).
        cond: Option<Expr>,
        /// Step expression.
        step: Option<Expr>,
        /// Body.
        body: Box<Stmt>,
    },
    /// `break [level];`
    Break(Option<u32>),
    /// `continue [level];`
    Continue(Option<u32>),
    /// `return [expr];`
    Return(Option<Expr>),
    /// `illuminance(["category",] position [, axis, angle]) body` (surface shaders).
    Illuminance {
        /// Optional category string expression.
        category: Option<Expr>,
        /// Position.
        position: Expr,
        /// Optional cone: axis and half-angle.
        cone: Option<(Expr, Expr)>,
        /// Body, run once per light.
        body: Box<Stmt>,
    },
    /// `illuminate(position [, axis, angle]) body` (light shaders).
    Illuminate {
        /// Light position.
        position: Expr,
        /// Optional cone.
        cone: Option<(Expr, Expr)>,
        /// Body.
        body: Box<Stmt>,
    },
    /// `solar([axis, angle]) body` (light shaders).
    Solar {
        /// Optional direction and half-angle.
        cone: Option<(Expr, Expr)>,
        /// Body.
        body: Box<Stmt>,
    },
    /// `gather(category, P, dir, angle, samples, …) body [else body]` (ray-traced gathering).
    Gather {
        /// The arguments as written.
        args: Vec<Expr>,
        /// Body for hits.
        body: Box<Stmt>,
        /// Body for misses.
        otherwise: Option<Box<Stmt>>,
    },
    /// A nested function definition.
    Function(Box<FunctionDef>),
}

/// An expression.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// Id for side tables.
    pub id: ExprId,
    /// What it is.
    pub kind: ExprKind,
    /// Where.
    pub span: Span,
}

/// Unary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnaryOp {
    /// `-x`
    Neg,
    /// `!x`
    Not,
}

/// Binary operators (assignment is separate).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinaryOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `.` (dot product)
    Dot,
    /// `^` (cross product)
    Cross,
    /// `==`
    Eq,
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
    And,
    /// `||`
    Or,
}

impl BinaryOp {
    /// The operator as written.
    #[must_use]
    pub const fn symbol(self) -> &'static str {
        match self {
            Self::Add => "+",
            Self::Sub => "-",
            Self::Mul => "*",
            Self::Div => "/",
            Self::Dot => ".",
            Self::Cross => "^",
            Self::Eq => "==",
            Self::Ne => "!=",
            Self::Lt => "<",
            Self::Le => "<=",
            Self::Gt => ">",
            Self::Ge => ">=",
            Self::And => "&&",
            Self::Or => "||",
        }
    }
}

/// Assignment operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AssignOp {
    /// `=`
    Assign,
    /// `+=`
    Add,
    /// `-=`
    Sub,
    /// `*=`
    Mul,
    /// `/=`
    Div,
}

/// The expression kinds.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// A number literal (RSL numbers are all float).
    Number(f64),
    /// A string literal (escapes already decoded).
    Str(String),
    /// A variable or global.
    Name(String),
    /// `-x`, `!x`
    Unary(UnaryOp, Box<Expr>),
    /// `a op b`
    Binary(BinaryOp, Box<Expr>, Box<Expr>),
    /// `cond ? a : b`
    Ternary(Box<Expr>, Box<Expr>, Box<Expr>),
    /// `lhs op= rhs`; the value of the expression is the new value of `lhs`.
    Assign(AssignOp, Box<Expr>, Box<Expr>),
    /// `name(args)` — a built-in or user function.
    Call(Ident, Vec<Expr>),
    /// `(a, b, c)` — a triple, type from context or the cast around it.
    Triple(Box<[Expr; 3]>),
    /// `(m00, …, m33)` — a matrix literal of 16 components.
    MatrixLit(Vec<Expr>),
    /// `{a, b, c}` — an array initializer.
    ArrayInit(Vec<Expr>),
    /// `base[index]` — array element (or component of a triple).
    Index(Box<Expr>, Box<Expr>),
    /// `type ["space"] expr` — a cast, or a space-qualified constructor such as
    /// `color "hsv" (h, s, v)` or `point "world" (x, y, z)`.
    Cast {
        /// The target type.
        to: BaseType,
        /// The space name if written (usually a string literal).
        space: Option<Box<Expr>>,
        /// The operand.
        expr: Box<Expr>,
    },
}
