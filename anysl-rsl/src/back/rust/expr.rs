//! Values: the Rust types of IR types in each representation, constants, lifting scalars to
//! lanes, and the expression of each instruction (operators, conversions, loads, triples and
//! matrices).

use super::{comps, ident, lit, tri_ty, Gen, GenError, Repr};
use crate::ir::{BinOp, Const, Op, SlotId, SlotKind, UnOp, Value};
use crate::types::{BaseType, Type};

impl<'a> Gen<'a> {
    // ---------------------------------------------------------------------------------------
    // Types and values.

    fn base_ty(&self, base: BaseType, r: Repr) -> String {
        let t = if r == Repr::Scalar { "f64" } else { "F" };
        match base {
            BaseType::Float | BaseType::Void => t.to_string(),
            BaseType::Color => format!("Color<{t}>"),
            BaseType::Point | BaseType::Vector | BaseType::Normal => format!("Vec3<{t}>"),
            BaseType::Matrix => format!("Matrix4<{t}>"),
            BaseType::String => "&str".into(),
        }
    }

    fn rust_ty(&self, t: Type, is_bool: bool, r: Repr) -> String {
        let el = if is_bool {
            if r == Repr::Scalar {
                "bool".into()
            } else {
                "F::Mask".into()
            }
        } else {
            self.base_ty(t.base, r)
        };
        match t.array {
            Some(n) => format!("[{el}; {n}]"),
            None => el,
        }
    }

    pub(super) fn slot_ty(&self, s: SlotId) -> String {
        let slot = self.f.slot(s);
        if slot.ty.base == BaseType::String {
            return match slot.ty.array {
                Some(n) => format!("[String; {n}]"),
                None => "String".into(),
            };
        }
        self.rust_ty(slot.ty, false, self.sr[s.0 as usize])
    }

    pub(super) fn slot_var(&self, s: SlotId) -> String {
        format!("s{}_{}", s.0, ident(&self.f.slot(s).name).trim_start_matches("r#"))
    }

    /// A constant in representation `r`.
    fn const_expr(&self, c: &Const, base: BaseType, r: Repr) -> String {
        let f = |x: f64| if r == Repr::Scalar { lit(x) } else { format!("F::c({})", lit(x)) };
        match c {
            Const::Float(x) => match base {
                b if b.is_triple() => format!("{}::splat({})", tri_ty(b), f(*x)),
                BaseType::Matrix => format!("Matrix4::scalar({})", f(*x)),
                _ => f(*x),
            },
            Const::Triple(t) => format!("{}::new({}, {}, {})", tri_ty(base), f(t[0]), f(t[1]), f(t[2])),
            Const::Matrix(m) => {
                let t = if r == Repr::Scalar { "f64" } else { "F" };
                format!(
                    "Matrix4::<{t}>::from_array([{}])",
                    m.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(", ")
                )
            }
            Const::Str(s) => format!("{s:?}"),
            Const::Array(items) => {
                format!("[{}]", items.iter().map(|i| self.const_expr(i, base, r)).collect::<Vec<_>>().join(", "))
            }
        }
    }

    /// Lifts a scalar expression (a variable or field) of type `t` to lanes.
    pub(super) fn lift(&self, e: &str, t: Type, is_bool: bool) -> String {
        if t.array.is_some() {
            let inner = self.lift("x", t.element(), is_bool);
            return format!("{e}.map(|x| {inner})");
        }
        if is_bool {
            return format!("<F::Mask as Mask>::splat({e})");
        }
        match t.base {
            BaseType::Float => format!("F::c({e})"),
            b if b.is_triple() => {
                let [a, bb, c] = comps(b);
                format!("{}::<F>::c({e}.{a}, {e}.{bb}, {e}.{c})", tri_ty(b))
            }
            BaseType::Matrix => format!("Matrix4::<F> {{ m: {e}.m.map(|r| r.map(F::c)) }}"),
            _ => e.to_string(),
        }
    }

    /// The expression of value `v` in representation `want`.
    pub(super) fn val(&self, v: Value, want: Repr) -> String {
        let inst = self.f.inst(v);
        if let Some(c) = &self.consts[v.0 as usize] {
            if inst.ty.base == BaseType::String {
                return self.const_expr(c, inst.ty.base, Repr::Scalar);
            }
            return self.const_expr(c, inst.ty.base, want);
        }
        let name = format!("v{}", v.0);
        if self.vr[v.0 as usize] == want || inst.ty.base == BaseType::String {
            return name;
        }
        if want == Repr::Scalar {
            // Never needed by construction; keep the generated code compiling regardless.
            return format!("/* lane 0 */ {name}.lane(0)");
        }
        self.lift(&name, inst.ty, inst.is_bool)
    }

    // ---------------------------------------------------------------------------------------
    // Instructions.

    pub(super) fn inst(&mut self, v: Value) -> Result<(), GenError> {
        if self.consts[v.0 as usize].is_some() {
            return Ok(()); // constants are written where they are used
        }
        let inst = self.f.inst(v);
        let r = self.vr[v.0 as usize];
        let is_str = inst.ty.base == BaseType::String;
        let name = format!("v{}", v.0);
        let e = self.inst_expr(v)?;
        if inst.ty.base == BaseType::Void {
            self.line(&format!("{e};"));
            return Ok(());
        }
        let ty = if is_str {
            if inst.ty.array.is_some() {
                String::new()
            } else {
                ": &str".into()
            }
        } else {
            format!(": {}", self.rust_ty(inst.ty, inst.is_bool, r))
        };
        self.line(&format!("let {name}{ty} = {e};"));
        Ok(())
    }

    pub(super) fn arg_ty(&self, v: Value) -> Type {
        self.f.inst(v).ty
    }

    #[allow(clippy::too_many_lines)]
    fn inst_expr(&mut self, v: Value) -> Result<String, GenError> {
        let inst = self.f.inst(v);
        let r = self.vr[v.0 as usize];
        let args = inst.args.clone();
        let a = |this: &Self, i: usize| this.val(args[i], r);
        let ty = inst.ty;
        Ok(match &inst.op {
            Op::Const(c) => self.const_expr(c, ty.base, r),
            Op::Load(s) => {
                let slot = self.f.slot(*s);
                match slot.kind {
                    SlotKind::Param(pi) if !self.stored[s.0 as usize] && !self.m.params[pi as usize].output => {
                        self.param_read(pi as usize, r, false)
                    }
                    _ => {
                        let var = self.slot_var(*s);
                        if slot.ty.base == BaseType::String {
                            if slot.ty.array.is_some() {
                                format!("{var}.each_ref().map(|x| x.as_str())")
                            } else {
                                format!("{var}.as_str()")
                            }
                        } else if self.sr[s.0 as usize] == r {
                            var
                        } else {
                            self.lift(&var, slot.ty, false)
                        }
                    }
                }
            }
            Op::LoadElem(s) => {
                let slot = self.f.slot(*s);
                let n = slot.ty.array.unwrap_or(1);
                let arr = match slot.kind {
                    SlotKind::Param(pi) if !self.stored[s.0 as usize] && !self.m.params[pi as usize].output => self
                        .param_read(
                            pi as usize,
                            if slot.ty.base == BaseType::String { Repr::Scalar } else { r },
                            false,
                        ),
                    _ => {
                        let var = self.slot_var(*s);
                        if slot.ty.base == BaseType::String {
                            var
                        } else if self.sr[s.0 as usize] == r {
                            var
                        } else {
                            self.lift(&var, slot.ty, false)
                        }
                    }
                };
                let idx = args[0];
                if slot.ty.base == BaseType::String {
                    let iv = if self.scalar_value(idx) {
                        self.val(idx, Repr::Scalar)
                    } else {
                        format!("{}.lane(0)", self.val(idx, Repr::Lane))
                    };
                    format!("{{ let a = &{arr}; &a[(({iv}).max(0.0) as usize).min({})] }}", n.saturating_sub(1))
                } else if self.scalar_value(idx) {
                    let iv = self.val(idx, Repr::Scalar);
                    format!("{{ let a = {arr}; a[(({iv}).floor().max(0.0) as usize).min({})] }}", n.saturating_sub(1))
                } else {
                    let iv = self.val(idx, Repr::Lane);
                    format!(
                        "{{ let a = {arr}; let iv = ({iv}).floor().max(F::c(0.0)).min(F::c({}.0)); let mut r = a[0]; for k in 1..{n} {{ r = Blend::<F>::blend(iv.eq(F::c(k as f64)), a[k], r); }} r }}",
                        n.saturating_sub(1)
                    )
                }
            }
            Op::Unary(UnOp::Neg) => {
                if ty.base == BaseType::Matrix {
                    format!("{{ let a = {}; Matrix4 {{ m: a.m.map(|r| r.map(|x| -x)) }} }}", a(self, 0))
                } else {
                    format!("-{}", a(self, 0))
                }
            }
            Op::Unary(UnOp::Not) => format!("!{}", a(self, 0)),
            Op::Binary(op) => self.binary(*op, &args, r),
            Op::Select => {
                let c = self.val(args[0], if r == Repr::Scalar { Repr::Scalar } else { Repr::Lane });
                let (x, y) = (a(self, 1), a(self, 2));
                if ty.base == BaseType::String {
                    let c = if self.scalar_value(args[0]) { c } else { format!("{c}.lane(0)") };
                    format!("if {c} {{ {x} }} else {{ {y} }}")
                } else if r == Repr::Scalar {
                    format!("if {c} {{ {x} }} else {{ {y} }}")
                } else if inst.is_bool {
                    format!("<F::Mask as Mask>::select_mask({c}, {x}, {y})")
                } else {
                    format!("Blend::<F>::blend({c}, {x}, {y})")
                }
            }
            Op::Convert => {
                let from = self.f.inst(args[0]);
                let x = a(self, 0);
                if inst.is_bool {
                    // float (or triple) → bool: != 0.
                    if from.is_bool {
                        x
                    } else if r == Repr::Scalar {
                        if from.ty.base.is_triple() {
                            let [p, q, s] = comps(from.ty.base);
                            format!("{{ let a = {x}; a.{p} != 0.0 || a.{q} != 0.0 || a.{s} != 0.0 }}")
                        } else {
                            format!("({x} != 0.0)")
                        }
                    } else if from.ty.base.is_triple() {
                        let [p, q, s] = comps(from.ty.base);
                        format!("{{ let a = {x}; a.{p}.ne(F::c(0.0)) | a.{q}.ne(F::c(0.0)) | a.{s}.ne(F::c(0.0)) }}")
                    } else {
                        format!("{x}.ne(F::c(0.0))")
                    }
                } else if from.is_bool {
                    let one = if r == Repr::Scalar { "1.0_f64" } else { "F::c(1.0)" };
                    let zero = if r == Repr::Scalar { "0.0_f64" } else { "F::c(0.0)" };
                    let f = if r == Repr::Scalar {
                        format!("if {x} {{ {one} }} else {{ {zero} }}")
                    } else {
                        format!("F::select({x}, {one}, {zero})")
                    };
                    if ty.base.is_triple() {
                        format!("{}::splat({f})", tri_ty(ty.base))
                    } else {
                        f
                    }
                } else {
                    match (from.ty.base, ty.base) {
                        (BaseType::Float, b) if b.is_triple() => format!("{}::splat({x})", tri_ty(b)),
                        (BaseType::Float, BaseType::Matrix) => format!("Matrix4::scalar({x})"),
                        (BaseType::Color, b) if b.is_pointlike() => format!("({x}).to_vec()"),
                        (b, BaseType::Color) if b.is_pointlike() => format!("({x}).to_color()"),
                        _ => x,
                    }
                }
            }
            Op::MakeTriple => {
                format!("{}::new({}, {}, {})", tri_ty(ty.base), a(self, 0), a(self, 1), a(self, 2))
            }
            Op::MakeMatrix => {
                let e: Vec<String> = (0..16).map(|i| a(self, i)).collect();
                format!(
                    "Matrix4 {{ m: [[{}], [{}], [{}], [{}]] }}",
                    e[0..4].join(", "),
                    e[4..8].join(", "),
                    e[8..12].join(", "),
                    e[12..16].join(", ")
                )
            }
            Op::FromSpace => {
                let space = self.val(args[0], Repr::Scalar);
                let x = a(self, 1);
                if ty.base == BaseType::Color {
                    format!("{{ let c = {x}; match ColorSpace::from_name({space}) {{ Some(cs) => to_rgb(cs, c), None => c }} }}")
                } else {
                    let t = if r == Repr::Scalar { "f64" } else { "F" };
                    let to = format!("{}.to_current::<{t}>({space})", self.spaces_table());
                    match ty.base {
                        BaseType::Matrix => format!("({x} * {to})"),
                        BaseType::Vector => format!("{to}.transform_vector({x})"),
                        BaseType::Normal => format!("{to}.transform_normal({x})"),
                        _ => format!("{to}.transform_point({x})"),
                    }
                }
            }
            Op::Call { builtin, outputs, .. } => {
                let (builtin, outputs) = (*builtin, outputs.clone());
                self.call(v, builtin, &outputs, r)?
            }
        })
    }

    /// The named coordinate systems: the variable `run` declares when the shader names a
    /// space (the context's table, or for light shaders, which run without one, the standard
    /// table).
    pub(super) fn spaces_table(&self) -> String {
        "spaces".into()
    }

    fn binary(&self, op: BinOp, args: &[Value], r: Repr) -> String {
        let (ta, tb) = (self.arg_ty(args[0]), self.arg_ty(args[1]));
        let bools = self.f.inst(args[0]).is_bool || self.f.inst(args[1]).is_bool;
        let want = r;
        let (x, y) = (self.val(args[0], want), self.val(args[1], want));
        let scalar = r == Repr::Scalar;
        use BaseType as B;
        match op {
            BinOp::And => format!("({x} & {y})"),
            BinOp::Or => format!("({x} | {y})"),
            BinOp::Eq | BinOp::Ne if ta.base == B::String || tb.base == B::String => {
                let o = if op == BinOp::Eq { "==" } else { "!=" };
                let e = format!("({x} {o} {y})");
                if scalar {
                    e
                } else {
                    format!("<F::Mask as Mask>::splat{e}")
                }
            }
            BinOp::Eq | BinOp::Ne if bools => {
                if scalar {
                    format!("({x} {} {y})", if op == BinOp::Eq { "==" } else { "!=" })
                } else {
                    let d = format!("(({x} & !{y}) | ({y} & !{x}))");
                    if op == BinOp::Eq {
                        format!("!{d}")
                    } else {
                        d
                    }
                }
            }
            BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => {
                let mname = match op {
                    BinOp::Eq => "eq",
                    BinOp::Ne => "ne",
                    BinOp::Lt => "lt",
                    BinOp::Le => "le",
                    BinOp::Gt => "gt",
                    _ => "ge",
                };
                let sop = match op {
                    BinOp::Eq => "==",
                    BinOp::Ne => "!=",
                    BinOp::Lt => "<",
                    BinOp::Le => "<=",
                    BinOp::Gt => ">",
                    _ => ">=",
                };
                if ta.base.is_triple() || ta.base == B::Matrix {
                    // Component-wise: all equal / any different.
                    let cs: Vec<String> = if ta.base == B::Matrix {
                        (0..16).map(|i| format!("m.{}[{}]", i / 4, i % 4)).collect()
                    } else {
                        comps(ta.base).iter().map(|c| (*c).to_string()).collect()
                    };
                    let cs_b: Vec<String> = if tb.base == B::Matrix {
                        (0..16).map(|i| format!("m.{}[{}]", i / 4, i % 4)).collect()
                    } else {
                        comps(tb.base).iter().map(|c| (*c).to_string()).collect()
                    };
                    let fix = |c: &str| c.replace("m.", "m[").replace("][", "][").to_string();
                    let _ = fix;
                    let field = |c: &str| -> String {
                        if let Some(rest) = c.strip_prefix("m.") {
                            let (i, j) = rest.split_once('[').unwrap_or(("0", "0]"));
                            format!("m[{i}][{}", j)
                        } else {
                            c.to_string()
                        }
                    };
                    let parts: Vec<String> = cs
                        .iter()
                        .zip(&cs_b)
                        .map(|(p, q)| {
                            if scalar {
                                format!("(a.{} {sop} b.{})", field(p), field(q))
                            } else {
                                format!("a.{}.{mname}(b.{})", field(p), field(q))
                            }
                        })
                        .collect();
                    let join = if op == BinOp::Ne { " | " } else { " & " };
                    format!("{{ let (a, b) = ({x}, {y}); {} }}", parts.join(join))
                } else if scalar {
                    format!("({x} {sop} {y})")
                } else {
                    format!("{x}.{mname}({y})")
                }
            }
            BinOp::Dot => format!("{x}.dot({y})"),
            BinOp::Cross => format!("{x}.cross({y})"),
            BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div => {
                let o = match op {
                    BinOp::Add => "+",
                    BinOp::Sub => "-",
                    BinOp::Mul => "*",
                    _ => "/",
                };
                match (ta.base, tb.base) {
                    (B::Matrix, B::Matrix) => match op {
                        BinOp::Mul => format!("({x} * {y})"),
                        BinOp::Div => format!("({x} * ({y}).inverse())"),
                        _ => format!(
                            "{{ let (a, b) = ({x}, {y}); Matrix4 {{ m: ::core::array::from_fn(|i| ::core::array::from_fn(|j| a.m[i][j] {o} b.m[i][j])) }} }}"
                        ),
                    },
                    (B::Matrix, B::Float) => format!(
                        "{{ let (a, b) = ({x}, {y}); Matrix4 {{ m: a.m.map(|r| r.map(|x| x {o} b)) }} }}"
                    ),
                    (B::Float, B::Matrix) => format!(
                        "{{ let (a, b) = ({x}, {y}); Matrix4 {{ m: b.m.map(|r| r.map(|x| a {o} x)) }} }}"
                    ),
                    (B::Float, t) if t.is_triple() => match op {
                        BinOp::Add | BinOp::Mul => format!("({y} {o} {x})"),
                        _ => format!("({}::splat({x}) {o} {y})", tri_ty(t)),
                    },
                    (ta_b, tb_b) if ta_b.is_triple() && tb_b.is_triple() && (ta_b == B::Color) != (tb_b == B::Color) => {
                        // Mixed colour and point-like (not produced by the checker; kept total).
                        if ta_b == B::Color {
                            format!("({x} {o} ({y}).to_color())")
                        } else {
                            format!("({x} {o} ({y}).to_vec())")
                        }
                    }
                    _ => format!("({x} {o} {y})"),
                }
            }
        }
    }

    /// A scalar-or-lane constant.
    pub(super) fn k(&self, x: f64, r: Repr) -> String {
        if r == Repr::Scalar {
            lit(x)
        } else {
            format!("F::c({})", lit(x))
        }
    }
}
