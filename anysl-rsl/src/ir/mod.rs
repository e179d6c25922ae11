//! The portable IR: threaded code over structured control flow.
//!
//! A shader compiles to one [`Function`] (RSL functions are inlined: the language forbids
//! recursion, and every production compiler inlines them). The function has
//!
//! * **values** — an arena of [`Inst`]s, each defining one SSA value (`Value`), written once and
//!   never reassigned. Every instruction is an *abstract op* keyed by operator and operand
//!   types: `mul(float, vector)` is [`Op::Binary`]`(Mul)` whose arguments have types `float`
//!   and `vector`; built-in calls are [`Op::Call`] with a resolved overload. Back ends implement
//!   each op for their own types — that is what makes type replacement possible at run time;
//! * **slots** — the named variables of the source (locals, parameters, globals, outputs),
//!   read with [`Op::Load`] and written with [`Node::Store`]. They play the part of LLVM's entry
//!   block `alloca`s: a back end that wants pure SSA promotes them (the JIT lets `mem2reg` do it);
//!   the batched interpreter and generated Rust keep them as masked registers;
//! * **a body** — a tree of [`Node`]s: structured control flow (`if`, loops with `break`/
//!   `continue` to any enclosing level, `return` from an inlined function frame, and the
//!   light loops). RSL has only structured control flow, so the control-flow graph is the tree's
//!   reducible CFG (see [`cfg`]); keeping the structure lets every back end execute divergent
//!   control flow with masks (whole-function vectorization) without rediscovering it.
//!
//! An instruction is placed in the body by a [`Node::Inst`]; its value is available to every
//! node after it in the same block and in nested blocks (dominance is lexical).

pub mod cfg;
pub mod print;

use crate::builtins::Builtin;
use crate::span::Span;
use crate::types::{BaseType, Detail, Type};

/// Handle of an SSA value (an instruction) in [`Function::insts`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Value(pub u32);

/// Handle of a variable slot in [`Function::slots`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SlotId(pub u32);

/// A compile-time constant.
#[derive(Clone, Debug, PartialEq)]
pub enum Const {
    /// A float.
    Float(f64),
    /// A colour, point, vector or normal.
    Triple([f64; 3]),
    /// A 4×4 matrix, row-major.
    Matrix([f64; 16]),
    /// A string.
    Str(String),
    /// An array of constants (all of one type).
    Array(Vec<Const>),
}

impl Const {
    /// The const of type `float` holding `x`.
    #[must_use]
    pub fn float(x: f64) -> Self {
        Const::Float(x)
    }

    /// The components of a float (one), a triple (three) or a matrix (sixteen, row-major);
    /// `None` for a string or an array.
    #[must_use]
    pub fn components(&self) -> Option<Vec<f64>> {
        match self {
            Const::Float(x) => Some(vec![*x]),
            Const::Triple(t) => Some(t.to_vec()),
            Const::Matrix(m) => Some(m.to_vec()),
            Const::Str(_) | Const::Array(_) => None,
        }
    }

    /// The constant of base type `base` with components `v` (the inverse of
    /// [`components`](Self::components)): a float from one component, a triple of any kind from
    /// three, a matrix from sixteen; `None` when the count does not fit `base`.
    #[must_use]
    pub fn from_components(base: BaseType, v: &[f64]) -> Option<Const> {
        match (base, v.len()) {
            (BaseType::Float, 1) => Some(Const::Float(v[0])),
            (b, 3) if b.is_triple() => Some(Const::Triple([v[0], v[1], v[2]])),
            (BaseType::Matrix, 16) => {
                let mut m = [0.0; 16];
                m.copy_from_slice(v);
                Some(Const::Matrix(m))
            }
            _ => None,
        }
    }

    /// A float, triple or matrix with `f` applied to each component (keeping its shape);
    /// `None` for a string or an array.
    #[must_use]
    pub fn map_components(&self, f: impl Fn(f64) -> f64) -> Option<Const> {
        match self {
            Const::Float(x) => Some(Const::Float(f(*x))),
            Const::Triple(v) => Some(Const::Triple(v.map(&f))),
            Const::Matrix(m) => Some(Const::Matrix(m.map(&f))),
            Const::Str(_) | Const::Array(_) => None,
        }
    }

    /// A float promoted to base type `to` as an implicit conversion does it: a triple of three
    /// equal components, or a matrix with the float on its diagonal. Any other constant (and a
    /// float promoted to `float`) is returned unchanged.
    #[must_use]
    pub fn promote(self, to: BaseType) -> Const {
        match (self, to) {
            (Const::Float(x), t) if t.is_triple() => Const::Triple([x; 3]),
            (Const::Float(x), BaseType::Matrix) => {
                let mut m = [0.0; 16];
                for i in 0..4 {
                    m[i * 5] = x;
                }
                Const::Matrix(m)
            }
            (c, _) => c,
        }
    }

    /// Appends the components to `nums` and the strings to `strs`, the elements of an array
    /// in order: the flat layout of a constant in a back end's registers.
    pub fn flatten(&self, nums: &mut Vec<f64>, strs: &mut Vec<String>) {
        match self {
            Const::Float(x) => nums.push(*x),
            Const::Triple(t) => nums.extend_from_slice(t),
            Const::Matrix(m) => nums.extend_from_slice(m),
            Const::Str(s) => strs.push(s.clone()),
            Const::Array(v) => v.iter().for_each(|e| e.flatten(nums, strs)),
        }
    }
}

/// The RSL global variables a shader can read (and some write).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Global {
    /// Surface position.
    P,
    /// Shading normal.
    N,
    /// Geometric normal.
    Ng,
    /// Incident ray direction (from the eye to P).
    I,
    /// Eye position.
    E,
    /// Surface colour.
    Cs,
    /// Surface opacity.
    Os,
    /// Texture coordinates.
    S,
    /// Texture coordinates.
    T,
    /// Surface parameters.
    U,
    /// Surface parameters.
    V,
    /// Parameter step sizes.
    Du,
    /// Parameter step sizes.
    Dv,
    /// Surface derivatives.
    DPdu,
    /// Surface derivatives.
    DPdv,
    /// Output colour (surface, light: `Cl`).
    Ci,
    /// Output opacity.
    Oi,
    /// Light direction inside `illuminance`/`illuminate`/`solar`.
    L,
    /// Light colour inside `illuminance`; the light shader's output.
    Cl,
    /// Light opacity (unused by the renderers, kept for completeness).
    Ol,
    /// Light position for light shaders (`Ps`).
    Ps,
    /// Ray time.
    Time,
    /// Surface-to-light ambient `alpha` (imager shaders).
    Alpha,
    /// Number of components (`ncomps`, uniform).
    Ncomps,
}

impl Global {
    /// Every global with its RSL name.
    pub const ALL: [(Global, &'static str); 24] = [
        (Global::P, "P"),
        (Global::N, "N"),
        (Global::Ng, "Ng"),
        (Global::I, "I"),
        (Global::E, "E"),
        (Global::Cs, "Cs"),
        (Global::Os, "Os"),
        (Global::S, "s"),
        (Global::T, "t"),
        (Global::U, "u"),
        (Global::V, "v"),
        (Global::Du, "du"),
        (Global::Dv, "dv"),
        (Global::DPdu, "dPdu"),
        (Global::DPdv, "dPdv"),
        (Global::Ci, "Ci"),
        (Global::Oi, "Oi"),
        (Global::L, "L"),
        (Global::Cl, "Cl"),
        (Global::Ol, "Ol"),
        (Global::Ps, "Ps"),
        (Global::Time, "time"),
        (Global::Alpha, "alpha"),
        (Global::Ncomps, "ncomps"),
    ];

    /// The RSL name.
    #[must_use]
    pub fn name(self) -> &'static str {
        Self::ALL.iter().find(|(g, _)| *g == self).map_or("?", |(_, n)| n)
    }

    /// The global with RSL name `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().find(|(_, n)| *n == name).map(|(g, _)| *g)
    }

    /// Its type (detail as declared by the spec).
    #[must_use]
    pub fn ty(self) -> Type {
        use BaseType::*;
        match self {
            Global::P | Global::E | Global::Ps => Type::varying(Point),
            Global::N | Global::Ng => Type::varying(Normal),
            Global::I | Global::DPdu | Global::DPdv | Global::L => Type::varying(Vector),
            Global::Cs | Global::Os | Global::Ci | Global::Oi | Global::Cl | Global::Ol => Type::varying(Color),
            Global::S | Global::T | Global::U | Global::V | Global::Du | Global::Dv | Global::Alpha => {
                Type::varying(Float)
            }
            Global::Time | Global::Ncomps => Type::uniform(Float),
        }
    }
}

/// Where a slot lives.
#[derive(Clone, Debug, PartialEq)]
pub enum SlotKind {
    /// A local variable (also: copies of inlined function parameters, and temporaries).
    Local,
    /// Shader instance parameter number `.0` (index into [`Module::params`]).
    Param(u32),
    /// An RSL global.
    Global(Global),
}

/// A variable.
#[derive(Clone, Debug, PartialEq)]
pub struct Slot {
    /// Source name (made unique by lowering when shadowed, e.g. `x.1`).
    pub name: String,
    /// Type; the detail is the declared one and is refined by the uniform analysis.
    pub ty: Type,
    /// Local, parameter or global.
    pub kind: SlotKind,
    /// Declaration site.
    pub span: Span,
}

/// Unary ops.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnOp {
    /// Negation, per component.
    Neg,
    /// Logical not (of a boolean).
    Not,
}

/// Binary ops; operand types are the argument values' types (`mul(float, vector)`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    /// `+` (component-wise; float operands are promoted).
    Add,
    /// `-`
    Sub,
    /// `*` (component-wise for triples; matrix × matrix is the matrix product)
    Mul,
    /// `/` (matrix / matrix multiplies by the inverse)
    Div,
    /// `.` dot product → float
    Dot,
    /// `^` cross product → vector
    Cross,
    /// `==` → bool
    Eq,
    /// `!=` → bool
    Ne,
    /// `<` → bool (floats only)
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `&&` of booleans (both sides evaluated: RSL relations have no side effects)
    And,
    /// `||`
    Or,
}

impl BinOp {
    /// Short name used in the printer and in target-library function names (`ar_mul_fv`).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Add => "add",
            Self::Sub => "sub",
            Self::Mul => "mul",
            Self::Div => "div",
            Self::Dot => "dot",
            Self::Cross => "cross",
            Self::Eq => "eq",
            Self::Ne => "ne",
            Self::Lt => "lt",
            Self::Le => "le",
            Self::Gt => "gt",
            Self::Ge => "ge",
            Self::And => "and",
            Self::Or => "or",
        }
    }
}

/// An abstract operation.
#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    /// A constant (uniform).
    Const(Const),
    /// Reads a slot (whole value; for arrays the whole array, only as an argument to a call or
    /// store).
    Load(SlotId),
    /// Reads element `args[0]` (a float, truncated and clamped to the bounds) of an array slot.
    LoadElem(SlotId),
    /// Unary op on `args[0]`.
    Unary(UnOp),
    /// Binary op on `args[0]`, `args[1]`.
    Binary(BinOp),
    /// `args[0] ? args[1] : args[2]` per lane (`args[0]` is a bool).
    Select,
    /// Converts `args[0]` to the instruction's type: float → triple (all components), float →
    /// matrix (diagonal), triple → another triple kind (no transformation). Also float → bool
    /// (`!= 0`) for conditions.
    Convert,
    /// Builds a triple of the instruction's type from three floats.
    MakeTriple,
    /// Builds a matrix from 16 floats.
    MakeMatrix,
    /// Transforms `args[1]` (a triple or matrix) *from* the named space `args[0]` (a string) to
    /// `current`, as a point, vector or normal according to the instruction's type, or converts
    /// a colour *from* the named colour space to RGB: the semantics of `point "world" (…)` and
    /// `color "hsv" (…)`.
    FromSpace,
    /// A built-in function: `builtin`, resolved to overload `overload` of
    /// [`crate::builtins::OVERLOADS`]; output arguments are slots in `outputs`, written by the call.
    Call {
        /// The built-in.
        builtin: Builtin,
        /// Index of the overload in the built-in table.
        overload: u32,
        /// One entry per source argument, in argument order: the slot an `output` argument
        /// writes, `None` for an input. [`Inst::args`] holds the input arguments only, in
        /// order, each already converted to the overload's parameter type.
        outputs: Vec<Option<SlotId>>,
    },
}

/// One instruction: an op, its arguments and its result type.
#[derive(Clone, Debug, PartialEq)]
pub struct Inst {
    /// The op.
    pub op: Op,
    /// Argument values.
    pub args: Vec<Value>,
    /// Result type. `detail` is set by the uniform/varying analysis. Booleans (relations) are
    /// typed `float` with [`Inst::is_bool`] set.
    pub ty: Type,
    /// The result is a boolean (a relation or logical op).
    pub is_bool: bool,
    /// Set by the derivative-activity analysis: derivatives of this value are needed.
    pub needs_derivs: bool,
    /// Source.
    pub span: Span,
}

/// A statement of the structured body.
#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    /// Computes instruction `.0` here.
    Inst(Value),
    /// `slot[index] = value` (index for array slots only). Under divergent control flow only
    /// the active lanes are written.
    Store {
        /// The variable.
        slot: SlotId,
        /// Array element index (a float value).
        index: Option<Value>,
        /// The new value.
        value: Value,
        /// The store that gives a fresh slot its first value (a declaration's initializer, a
        /// copied-in output argument). Every later access of the slot is lexically inside the
        /// scope it starts and so runs under these lanes or fewer: the inactive lanes of this
        /// store are never read, and a back end may write every lane instead of merging.
        init: bool,
    },
    /// Two-way branch on a boolean value.
    If {
        /// Condition (a bool).
        cond: Value,
        /// Taken when true.
        then: Block,
        /// Taken when false.
        otherwise: Block,
    },
    /// `while`/`for`: `loop { header; if !cond break; body; step }`.
    Loop {
        /// Computes the condition each iteration.
        header: Block,
        /// The condition (defined in `header`); `None` loops until a `break`.
        cond: Option<Value>,
        /// The body.
        body: Block,
        /// The `for` step (where `continue` goes).
        step: Block,
    },
    /// Leaves the `.0 + 1`-th enclosing loop (0 = innermost) — RSL `break n` is `Break(n - 1)`.
    /// An [`Node::Illuminance`] body counts as a loop (over the lights): `break` inside it
    /// stops visiting lights, `continue` goes on with the next light.
    Break(u32),
    /// Continues the `.0 + 1`-th enclosing loop.
    Continue(u32),
    /// Returns from the innermost [`Node::Frame`] (an inlined function) or the shader.
    Return,
    /// The body of an inlined function call: a `Return` inside ends it for the returning lanes.
    /// Loop levels do not cross frames.
    Frame(Block),
    /// `illuminance([category,] P [, axis, angle]) body`: runs `body` per light with the
    /// `L` and `Cl` global slots set and only the lanes the light reaches active.
    Illuminance {
        /// Category string value.
        category: Option<Value>,
        /// Surface position.
        position: Value,
        /// Cone axis and half-angle.
        cone: Option<(Value, Value)>,
        /// The body.
        body: Block,
    },
    /// `illuminate(P [, axis, angle]) body` in a light shader: sets `L = Ps - P` and runs the
    /// body for the lanes inside the cone; `Cl` stays zero for the others.
    Illuminate {
        /// Light position.
        position: Value,
        /// Cone.
        cone: Option<(Value, Value)>,
        /// Body.
        body: Block,
    },
    /// `solar([axis, angle]) body`: a directional light; sets `L = axis`.
    Solar {
        /// Direction and half-angle.
        cone: Option<(Value, Value)>,
        /// Body.
        body: Block,
    },
}

/// A sequence of nodes.
pub type Block = Vec<Node>;

/// The shader kinds the IR knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShaderKind {
    /// Surface.
    Surface,
    /// Light.
    Light,
    /// Displacement.
    Displacement,
    /// Volume.
    Volume,
    /// Imager.
    Imager,
}

/// A shader parameter with its metadata.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamMeta {
    /// Name.
    pub name: String,
    /// Type (detail as declared: parameters are uniform unless declared varying).
    pub ty: Type,
    /// The default, evaluated to a constant at compile time.
    pub default: Const,
    /// `output` parameter.
    pub output: bool,
    /// The slot holding it in [`Function::slots`].
    pub slot: SlotId,
    /// For a point-like default written in a named space (`point "shader" (0, 0, 0)`): that
    /// space. The default then holds the coordinates *in that space*; the renderer transforms
    /// them to "current" when it binds the instance (as RenderMan does). `None`: current space.
    /// (Colour defaults in a named colour space are converted to RGB at compile time.)
    pub space: Option<String>,
    /// Declaration.
    pub span: Span,
}

/// The name of the hidden uniform float parameter that says whether the parameter `name`,
/// whose default is computed when the shader runs (`vector dir = normalize(dPdu)`), keeps its
/// default: 1 (its default) until the parameter is set, when setters make it 0.
#[must_use]
pub fn default_flag_name(name: &str) -> String {
    format!("__default_{name}")
}

/// The shader's code.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Function {
    /// Instructions (SSA values).
    pub insts: Vec<Inst>,
    /// Variables.
    pub slots: Vec<Slot>,
    /// The body.
    pub body: Block,
}

impl Function {
    /// The instruction defining `v`.
    #[must_use]
    pub fn inst(&self, v: Value) -> &Inst {
        &self.insts[v.0 as usize]
    }

    /// The slot `s`.
    #[must_use]
    pub fn slot(&self, s: SlotId) -> &Slot {
        &self.slots[s.0 as usize]
    }

    /// The slot holding global `g`, if the shader touches it.
    #[must_use]
    pub fn global_slot(&self, g: Global) -> Option<SlotId> {
        self.slots.iter().position(|s| s.kind == SlotKind::Global(g)).map(|i| SlotId(i as u32))
    }
}

/// One compiled shader.
#[derive(Clone, Debug, PartialEq)]
pub struct Module {
    /// Surface, light, ….
    pub kind: ShaderKind,
    /// The shader's name.
    pub name: String,
    /// Instance parameters in declaration order.
    pub params: Vec<ParamMeta>,
    /// The code.
    pub func: Function,
}

impl Module {
    /// Whether the shader names a coordinate system (`point "object" (…)`, `transform("shader",
    /// P)`, `matrix "world" 1`, …), so that its results depend on the
    /// [`anysl_core::ShadingContext::spaces`] it runs with.
    #[must_use]
    pub fn uses_spaces(&self) -> bool {
        let f = &self.func;
        f.insts.iter().any(|i| match &i.op {
            Op::FromSpace => i.ty.base != BaseType::Color,
            Op::Call { builtin, .. } => {
                builtin.names_space() && i.args.iter().any(|a| f.inst(*a).ty.base == BaseType::String)
            }
            _ => false,
        })
    }

    /// Stores `value` as parameter `i` of an instance's `values` (one per [`Module::params`]).
    /// A parameter whose default is computed when the shader runs also gets its flag
    /// ([`default_flag_name`]) cleared, so the given value is kept: every setter goes through
    /// here.
    pub fn set_param_value(&self, values: &mut [Const], i: usize, value: Const) {
        let flag = default_flag_name(&self.params[i].name);
        values[i] = value;
        if let Some(j) = self.params.iter().position(|p| p.name == flag) {
            values[j] = Const::Float(0.0);
        }
    }
}

impl Detail {
    /// `varying` if either is.
    #[must_use]
    pub fn join(self, other: Detail) -> Detail {
        self.max(other)
    }
}

impl Node {
    /// The values this node reads directly (not those of nested blocks).
    pub fn operands(&self, mut f: impl FnMut(Value)) {
        match self {
            Node::Inst(_) | Node::Break(_) | Node::Continue(_) | Node::Return | Node::Frame(_) => {}
            Node::Store { index, value, .. } => {
                if let Some(i) = index {
                    f(*i);
                }
                f(*value);
            }
            Node::If { cond, .. } => f(*cond),
            Node::Loop { cond, .. } => {
                if let Some(c) = cond {
                    f(*c);
                }
            }
            Node::Illuminance { category, position, cone, .. } => {
                if let Some(c) = category {
                    f(*c);
                }
                f(*position);
                if let Some((a, b)) = cone {
                    f(*a);
                    f(*b);
                }
            }
            Node::Illuminate { position, cone, .. } => {
                f(*position);
                if let Some((a, b)) = cone {
                    f(*a);
                    f(*b);
                }
            }
            Node::Solar { cone, .. } => {
                if let Some((a, b)) = cone {
                    f(*a);
                    f(*b);
                }
            }
        }
    }

    /// The nested blocks of this node, in execution order.
    #[must_use]
    pub fn blocks(&self) -> Vec<&Block> {
        match self {
            Node::If { then, otherwise, .. } => vec![then, otherwise],
            Node::Loop { header, body, step, .. } => vec![header, body, step],
            Node::Frame(b) => vec![b],
            Node::Illuminance { body, .. } | Node::Illuminate { body, .. } | Node::Solar { body, .. } => vec![body],
            _ => Vec::new(),
        }
    }

    /// The nested blocks, mutably.
    pub fn blocks_mut(&mut self) -> Vec<&mut Block> {
        match self {
            Node::If { then, otherwise, .. } => vec![then, otherwise],
            Node::Loop { header, body, step, .. } => vec![header, body, step],
            Node::Frame(b) => vec![b],
            Node::Illuminance { body, .. } | Node::Illuminate { body, .. } | Node::Solar { body, .. } => vec![body],
            _ => Vec::new(),
        }
    }
}

/// Calls `f` on every node of `block` and its nested blocks, parents before children.
pub fn walk(block: &Block, f: &mut impl FnMut(&Node)) {
    for n in block {
        f(n);
        for b in n.blocks() {
            walk(b, f);
        }
    }
}

impl Function {
    /// How many times each value is used (by instructions placed in the body and by nodes).
    #[must_use]
    pub fn use_counts(&self) -> Vec<u32> {
        let mut uses = vec![0u32; self.insts.len()];
        walk(&self.body, &mut |n| {
            if let Node::Inst(v) = n {
                for a in &self.inst(*v).args {
                    uses[a.0 as usize] += 1;
                }
            }
            n.operands(|v| uses[v.0 as usize] += 1);
        });
        uses
    }

    /// Number of instructions placed in the body (the figure passes report).
    #[must_use]
    pub fn inst_count(&self) -> usize {
        let mut n = 0;
        walk(&self.body, &mut |node| {
            if matches!(node, Node::Inst(_)) {
                n += 1;
            }
        });
        n
    }

    /// Adds an instruction to the arena (not yet placed in the body).
    pub fn add_inst(&mut self, inst: Inst) -> Value {
        self.insts.push(inst);
        Value(self.insts.len() as u32 - 1)
    }
}

impl Op {
    /// True when the op has no effect besides its value, so it may be removed when unused.
    #[must_use]
    pub fn is_removable(&self) -> bool {
        match self {
            Op::Call { builtin, outputs, .. } => outputs.iter().all(Option::is_none) && !builtin.has_side_effect(),
            _ => true,
        }
    }

    /// True when the value depends on its arguments only, so it may be folded when they are
    /// constant (and computed once for uniform arguments).
    #[must_use]
    pub fn is_pure(&self) -> bool {
        match self {
            Op::Call { builtin, outputs, .. } => outputs.iter().all(Option::is_none) && !builtin.reads_context(),
            Op::Load(_) | Op::LoadElem(_) => false,
            _ => true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Const;
    use crate::types::BaseType;

    #[test]
    fn const_components() {
        let m: [f64; 16] = std::array::from_fn(|i| i as f64);
        for (c, base) in [
            (Const::Float(2.0), BaseType::Float),
            (Const::Triple([1.0, 2.0, 3.0]), BaseType::Normal),
            (Const::Matrix(m), BaseType::Matrix),
        ] {
            let v = c.components().unwrap();
            assert_eq!(Const::from_components(base, &v), Some(c));
        }
        assert_eq!(Const::Str("a".into()).components(), None);
        assert_eq!(Const::Array(vec![Const::Float(1.0)]).components(), None);
        assert_eq!(Const::from_components(BaseType::Color, &[1.0]), None);
        assert_eq!(Const::from_components(BaseType::Void, &[1.0]), None);
        assert_eq!(Const::Triple([1.0, 2.0, 3.0]).map_components(|x| -x), Some(Const::Triple([-1.0, -2.0, -3.0])));
        assert_eq!(Const::Str("a".into()).map_components(|x| -x), None);
    }

    #[test]
    fn const_promote_and_flatten() {
        assert_eq!(Const::Float(2.0).promote(BaseType::Color), Const::Triple([2.0; 3]));
        let Const::Matrix(d) = Const::Float(2.0).promote(BaseType::Matrix) else { panic!() };
        assert_eq!((d[0], d[1], d[5], d[15]), (2.0, 0.0, 2.0, 2.0));
        assert_eq!(Const::Triple([1.0; 3]).promote(BaseType::Float), Const::Triple([1.0; 3]));
        let c = Const::Array(vec![Const::Triple([1.0, 2.0, 3.0]), Const::Float(4.0)]);
        let (mut nums, mut strs) = (Vec::new(), Vec::new());
        c.flatten(&mut nums, &mut strs);
        Const::Array(vec![Const::Str("x".into())]).flatten(&mut nums, &mut strs);
        assert_eq!((nums, strs), (vec![1.0, 2.0, 3.0, 4.0], vec!["x".to_string()]));
    }
}
