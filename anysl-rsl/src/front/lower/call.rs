//! Calls: built-in calls resolved among the overloads (by argument types, then by the
//! expected return type), user function calls matched by arity and types, and the
//! diagnostics of a call that fits no overload.

use super::place::Place;
use super::scope::{Binding, Found, VarInfo};
use super::{an_t, signature_of, suggest, type_name, Lowerer, Val, R};
use crate::builtins::{self, ArgSpec, Builtin, Overload, ResolveError, OVERLOADS};
use crate::diag::{codes, Diagnostic};
use crate::front::ast::{self, Expr, ExprKind};
use crate::ir::{Const, Op, SlotKind};
use crate::span::Span;
use crate::types::{BaseType, Detail, Type};

pub(super) enum CallArg {
    Value(Val),
    Place(Place),
}

impl CallArg {
    fn ty(&self) -> Type {
        match self {
            CallArg::Value(v) => v.ty,
            CallArg::Place(p) => p.ty,
        }
    }
}

impl<'a, 'd> Lowerer<'a, 'd> {
    pub(super) fn call(
        &mut self,
        e: &'a Expr,
        name: &'a ast::Ident,
        args: &'a [Expr],
        expected: Option<BaseType>,
    ) -> R {
        let user = self.lookup_fns(&name.name);
        if !user.is_empty() {
            return self.user_call(e, name, &user, args, expected);
        }
        if name.name == "arraylength" && args.len() == 1 {
            return self.array_length(&args[0]);
        }
        if matches!(name.name.as_str(), "bake3d" | "texture3d") && !builtins::exists(&name.name) {
            return self.point_cloud_call(e, name, args);
        }
        if name.name == "visibility" {
            // Pixie's `visibility (from, to)`: what PRMan calls `transmission`.
            self.report(
                Diagnostic::warning(
                    codes::OTHER_NAME,
                    name.span,
                    "`visibility` (Pixie) is read as `transmission`, its RenderMan name",
                )
                .with_label("transmission (from, to)"),
            );
            return self.builtin_call(e, "transmission", args, expected);
        }
        if !builtins::exists(&name.name) {
            let mut d =
                Diagnostic::error(codes::UNKNOWN_FUNCTION, name.span, format!("unknown function `{}`", name.name))
                    .with_label("not defined");
            let mut names: Vec<&str> = OVERLOADS.iter().map(|o| o.name()).collect();
            names.dedup();
            let user_names: Vec<String> = self.scopes.iter().flat_map(|s| s.funcs.keys().cloned()).collect();
            if let Some(s) = suggest(&name.name, names.into_iter().chain(user_names.iter().map(String::as_str))) {
                d = d.with_note(format!("did you mean `{s}`?"));
            } else {
                d = d.with_note("functions must be defined (or #included) before the shader is compiled");
            }
            self.report(d);
            // Still check the arguments.
            for a in args {
                self.expr(a, None);
            }
            return None;
        }
        self.builtin_call(e, &name.name, args, expected)
    }

    /// Positions that are `output` in every overload of `name` taking `n` arguments.
    fn output_positions(&self, name: &str, n: usize) -> Vec<bool> {
        let mut out = vec![false; n];
        let mut first = true;
        for i in builtins::overloads_of(name) {
            let o = &OVERLOADS[i as usize];
            if !o.accepts_count(n) {
                continue;
            }
            for (k, slot) in out.iter_mut().enumerate() {
                let is_out = o.param(k).is_some_and(|p| p.output);
                *slot = if first { is_out } else { *slot && is_out };
            }
            first = false;
        }
        out
    }

    /// The unique parameter type at position `k` among `name`'s overloads of arity `n`.
    fn unique_param(&self, name: &str, n: usize, k: usize) -> Option<BaseType> {
        let mut t = None;
        for i in builtins::overloads_of(name) {
            let o = &OVERLOADS[i as usize];
            if !o.accepts_count(n) {
                continue;
            }
            let p = o.param(k)?;
            match t {
                None => t = Some(p.ty),
                Some(x) if x != p.ty => return None,
                _ => {}
            }
        }
        t
    }

    /// `arraylength (a)` (PRMan 13): the length of a fixed-size array, a constant. (Arrays here
    /// always have a size known to the compiler: an unsized array parameter of a function
    /// takes the length of the argument it is inlined with.)
    fn array_length(&mut self, a: &'a Expr) -> R {
        let v = self.expr(a, None)?;
        match v.ty.array {
            Some(n) => Some(self.constant(Const::Float(f64::from(n)), BaseType::Float, a.span)),
            None => {
                self.err(
                    codes::NO_OVERLOAD,
                    a.span,
                    format!("`arraylength` takes an array, not {}", an_t(v.ty)),
                    "not an array",
                );
                None
            }
        }
    }

    /// PRMan 13's and Aqsis' point-cloud calls, `bake3d (file, channels, P, N, "name", value,
    /// …)` and `texture3d (file, P, N, "name", output value, …)`: checked, and answered as
    /// outside a renderer that keeps point clouds — nothing is written, nothing is found (0),
    /// the outputs keep their values (W0008).
    fn point_cloud_call(&mut self, e: &'a Expr, name: &'a ast::Ident, args: &'a [Expr]) -> R {
        let bake = name.name == "bake3d";
        let fixed: &[BaseType] = if bake {
            &[BaseType::String, BaseType::String, BaseType::Point, BaseType::Normal]
        } else {
            &[BaseType::String, BaseType::Point, BaseType::Normal]
        };
        if args.len() < fixed.len() || (args.len() - fixed.len()) % 2 != 0 {
            let n = fixed.len();
            self.report(
                Diagnostic::error(
                    codes::ARG_COUNT,
                    e.span,
                    format!("`{}` does not take {} arguments", name.name, args.len()),
                )
                .with_label(format!("{} given", args.len()))
                .with_note(format!("it takes {n} and then \"name\", value pairs")),
            );
            return None;
        }
        let mut ok = true;
        for (k, a) in args.iter().enumerate() {
            let want = fixed.get(k).copied().or_else(|| ((k - fixed.len()) % 2 == 0).then_some(BaseType::String));
            match want {
                Some(t) => ok &= self.typed(a, t, &format!("argument {} of {}", k + 1, name.name)).is_some(),
                None if bake => ok &= self.expr(a, None).is_some(),
                None => ok &= self.place(a, "output").is_some(),
            }
        }
        if !ok {
            return None;
        }
        self.report(
            Diagnostic::warning(
                codes::NO_EFFECT,
                name.span,
                format!(
                    "`{}`: point clouds are not kept here; {}",
                    name.name,
                    if bake {
                        "nothing is written (returns 0)"
                    } else {
                        "nothing is found (returns 0, outputs unchanged)"
                    }
                ),
            )
            .with_label("no point cloud"),
        );
        Some(self.constant(Const::Float(0.0), BaseType::Float, e.span))
    }

    fn builtin_call(&mut self, e: &'a Expr, name: &str, args: &'a [Expr], expected: Option<BaseType>) -> R {
        let outs = self.output_positions(name, args.len());
        let mut vals: Vec<CallArg> = Vec::new();
        let mut failed = false;
        // Spans of the arguments as lowered (channel selection appends two).
        let mut spans: Vec<Span> = args.iter().map(|a| a.span).collect();
        let mut channel: Option<(Val, Span)> = None;
        // Arguments checked but not passed (PRMan's area-shadow `"source", p0, p1, p2, p3`).
        let mut dropped: Vec<usize> = Vec::new();
        for (k, a) in args.iter().enumerate() {
            if dropped.contains(&k) {
                self.expr(a, Some(BaseType::Point));
                continue;
            }
            if name == "shadow" && k >= 2 && matches!(&a.kind, ExprKind::Str(o) if o == "source") && k + 4 < args.len()
            {
                self.report(
                    Diagnostic::warning(
                        codes::NO_EFFECT,
                        a.span,
                        "the area-shadow option \"source\" (four points, PRMan) is ignored: the map is read as from a point",
                    )
                    .with_label("ignored with its four points"),
                );
                dropped.extend(k..k + 5);
                continue;
            }
            // `texture ("name"[n], …)`, `environment (envname[3], …)`: channel selection on the
            // map name (PRMan, BMRT, Aqsis) — the name, plus a `"firstchannel", n` option.
            if k == 0 && matches!(name, "texture" | "environment" | "shadow") {
                if let ExprKind::Index(base, idx) = &a.kind {
                    if let Some(b) = self.expr(base, Some(BaseType::String)) {
                        if b.ty.base == BaseType::String && b.ty.array.is_none() {
                            let Some(i) = self.index_value(idx) else {
                                failed = true;
                                continue;
                            };
                            vals.push(CallArg::Value(b));
                            channel = Some((i, idx.span));
                            continue;
                        }
                    }
                }
            }
            if outs[k] {
                match self.place(a, "output") {
                    Some(p) => vals.push(CallArg::Place(p)),
                    None => failed = true,
                }
            } else {
                let hint = if matches!(a.kind, ExprKind::Triple(_)) {
                    self.unique_param(name, args.len(), k).or(expected.filter(|t| t.is_triple()))
                } else {
                    None
                };
                match self.expr(a, hint).and_then(|v| self.unbool(v, a.span)) {
                    Some(v) => vals.push(CallArg::Value(v)),
                    None => failed = true,
                }
            }
        }
        if failed {
            return None;
        }
        for &k in dropped.iter().rev() {
            spans.remove(k);
        }
        if let Some((i, span)) = channel {
            let opt = self.constant(Const::Str("firstchannel".into()), BaseType::String, span);
            vals.push(CallArg::Value(opt));
            vals.push(CallArg::Value(i));
            spans.push(span);
            spans.push(span);
        }
        let types: Vec<Type> = vals.iter().map(CallArg::ty).collect();
        let k = match builtins::resolve_expecting(name, &types, expected) {
            Ok(k) => k,
            Err(err) => {
                self.no_overload(e, name, args, &types, err, builtins::overloads_of(name).collect());
                return None;
            }
        };
        let o: &'static Overload = &OVERLOADS[k as usize];
        let mut inputs = Vec::new();
        let mut outputs = Vec::new();
        let uniform_random = o.builtin == Builtin::Random && self.uniform_target;
        let mut detail = if o.always_varying && !uniform_random { Detail::Varying } else { Detail::Uniform };
        let mut copy_out = Vec::new();
        for (i, a) in vals.into_iter().enumerate() {
            let p = o.param(i);
            match a {
                CallArg::Value(v) => {
                    detail = detail.join(v.ty.detail);
                    let v = match p {
                        Some(p) if !p.any && !p.array => self.convert(v, p.ty, spans[i])?,
                        _ => v,
                    };
                    inputs.push(v.v);
                    outputs.push(None);
                }
                CallArg::Place(pl) => {
                    if pl.index.is_some() {
                        // An array element: written through a temporary, copied back below.
                        let t = self.new_slot(&format!("{name}.out"), pl.ty, SlotKind::Local, spans[i]);
                        outputs.push(Some(t));
                        copy_out.push((t, pl, spans[i]));
                    } else {
                        outputs.push(Some(pl.slot));
                        copy_out.push((pl.slot, pl, spans[i]));
                    }
                }
            }
        }
        let ty = Type::new(o.ret, detail);
        let out_detail = detail.join(if self.flow() > 0 { Detail::Varying } else { Detail::Uniform });
        if o.builtin == Builtin::Depth {
            return self.depth(inputs[0], detail, e.span);
        }
        let r = self.inst(Op::Call { builtin: o.builtin, overload: k, outputs }, inputs, ty, false, e.span);
        for (t, pl, span) in copy_out {
            if pl.ty.detail == Detail::Uniform && out_detail == Detail::Varying && detail == Detail::Varying {
                let n = self.slot_name(pl.slot);
                self.report(
                    Diagnostic::error(
                        codes::VARYING_TO_UNIFORM,
                        span,
                        format!("`{name}` writes a varying value into the uniform variable `{n}`"),
                    )
                    .with_label("uniform output")
                    .with_note(format!("declare `{n}` varying")),
                );
            }
            if t != pl.slot {
                let v = self.inst(Op::Load(t), Vec::new(), pl.ty, false, span);
                self.store(&pl, v);
            }
        }
        Some(r)
    }

    /// `depth(p)` as `zcomp(transform("__depth", p))`: the renderer's depth space
    /// ([`anysl_core::DEPTH_SPACE`]) maps camera depth to 0 at the near and 1 at the far
    /// clipping plane, so every back end computes it with its space transforms.
    fn depth(&mut self, p: crate::ir::Value, detail: Detail, span: Span) -> R {
        let name = self.constant(Const::Str(anysl_core::DEPTH_SPACE.into()), BaseType::String, span);
        let point = Type::new(BaseType::Point, detail);
        let kt = builtins::resolve("transform", &[name.ty, point]).expect("transform(string, point)");
        let t = self.inst(
            Op::Call { builtin: Builtin::Transform, overload: kt, outputs: vec![None, None] },
            vec![name.v, p],
            point,
            false,
            span,
        );
        let kz = builtins::resolve("zcomp", &[point]).expect("zcomp(point)");
        let z = Type::new(BaseType::Float, detail);
        Some(self.inst(
            Op::Call { builtin: Builtin::ZComp, overload: kz, outputs: vec![None] },
            vec![t.v],
            z,
            false,
            span,
        ))
    }

    #[cold]
    fn no_overload(&mut self, e: &Expr, name: &str, args: &[Expr], types: &[Type], err: ResolveError, cands: Vec<u32>) {
        let given = types.iter().map(|t| type_name(*t)).collect::<Vec<_>>().join(", ");
        let mut d = match err {
            ResolveError::ArgCount(counts) => {
                let list: Vec<String> =
                    counts.iter().map(|&c| if c == usize::MAX { "more".to_string() } else { c.to_string() }).collect();
                Diagnostic::error(
                    codes::ARG_COUNT,
                    e.span,
                    format!("`{name}` does not take {} argument{}", args.len(), if args.len() == 1 { "" } else { "s" }),
                )
                .with_label(format!("{} given", args.len()))
                .with_note(format!("it takes {}", list.join(" or ")))
            }
            _ => {
                let what = if types.len() == 1 { an_t(types[0]).to_string() } else { format!("({given})") };
                Diagnostic::error(codes::NO_OVERLOAD, e.span, format!("no overload of `{name}` takes {what}"))
                    .with_label(format!("called with ({given})"))
            }
        };
        let sigs: Vec<String> = cands.iter().take(8).map(|&i| OVERLOADS[i as usize].signature()).collect();
        if !sigs.is_empty() {
            d = d.with_note(format!("candidates:\n  {}", sigs.join("\n  ")));
        }
        self.report(d);
    }

    fn user_call(
        &mut self,
        e: &'a Expr,
        name: &'a ast::Ident,
        defs: &[&'a ast::FunctionDef],
        args: &'a [Expr],
        expected: Option<BaseType>,
    ) -> R {
        let n = args.len();
        let fitting: Vec<&'a ast::FunctionDef> = defs.iter().copied().filter(|f| f.params.len() == n).collect();
        let mut vals: Vec<CallArg> = Vec::new();
        let mut failed = false;
        for (k, a) in args.iter().enumerate() {
            let all_out = !fitting.is_empty() && fitting.iter().all(|f| f.params[k].output);
            let all_arr = !fitting.is_empty() && fitting.iter().all(|f| f.params[k].array.is_some());
            if all_out || (all_arr && matches!(a.kind, ExprKind::Name(_))) {
                let p = if all_out { self.place(a, "output") } else { self.array_arg(a) };
                match p {
                    Some(p) => vals.push(CallArg::Place(p)),
                    None => failed = true,
                }
            } else {
                let hint = if matches!(a.kind, ExprKind::Triple(_)) {
                    fitting.first().map(|f| f.params[k].ty.base).filter(|t| t.is_triple())
                } else {
                    None
                };
                match self.expr(a, hint).and_then(|v| self.unbool(v, a.span)) {
                    Some(v) => vals.push(CallArg::Value(v)),
                    None => failed = true,
                }
            }
        }
        if failed {
            return None;
        }
        // Pick the cheapest fitting definition.
        let mut best: Option<((u32, u32), &'a ast::FunctionDef)> = None;
        for f in &fitting {
            let mut cost = 0;
            let mut ok = true;
            for (p, a) in f.params.iter().zip(&vals) {
                let spec = ArgSpec { ty: p.ty.base, output: p.output, array: p.array.is_some(), any: false };
                let is_place = matches!(a, CallArg::Place(_));
                match builtins::arg_cost(&spec, &a.ty()) {
                    Some(c) if !p.output || is_place => cost += c,
                    _ => ok = false,
                }
            }
            if ok {
                let rc = match expected {
                    Some(t) if t == f.ret.base => 0,
                    None if f.ret.base == BaseType::Float => 0,
                    _ => 1,
                };
                if best.is_none_or(|(c, _)| (cost, rc) < c) {
                    best = Some(((cost, rc), f));
                }
            }
        }
        let Some((_, def)) = best else {
            let given = vals.iter().map(|a| type_name(a.ty())).collect::<Vec<_>>().join(", ");
            let mut d = if fitting.is_empty() {
                Diagnostic::error(
                    codes::ARG_COUNT,
                    e.span,
                    format!("function `{}` does not take {n} argument{}", name.name, if n == 1 { "" } else { "s" }),
                )
                .with_label(format!("{n} given"))
            } else {
                Diagnostic::error(
                    codes::NO_OVERLOAD,
                    e.span,
                    format!("no definition of `{}` takes ({given})", name.name),
                )
                .with_label(format!("called with ({given})"))
            };
            for f in defs.iter().take(4) {
                d = d.with_secondary(f.name.span, format!("`{}` defined here", signature_of(f)));
            }
            self.report(d);
            return None;
        };
        self.called.insert(def.span);
        if self.inlining.iter().any(|f| std::ptr::eq(*f, def)) {
            self.report(
                Diagnostic::error(codes::RECURSION, e.span, format!("recursive call of `{}`", name.name))
                    .with_label("calls itself")
                    .with_secondary(def.name.span, "function defined here")
                    .with_note("RSL functions are inlined and cannot recurse; rewrite it as a loop"),
            );
            return None;
        }
        self.inline(def, vals, e.span, expected)
    }

    /// An array argument passed by reference: the caller's array variable.
    fn array_arg(&mut self, a: &'a Expr) -> Option<Place> {
        if let ExprKind::Name(n) = &a.kind {
            if let Some(Found::Var(VarInfo { binding: Binding::Slot(s), .. })) = self.lookup(n) {
                let ty = self.slot_ty(s);
                return Some(Place { slot: s, index: None, ty });
            }
        }
        let v = self.expr(a, None)?;
        self.err(
            codes::TYPE_MISMATCH,
            a.span,
            format!("an array parameter needs an array variable, not {}", an_t(v.ty)),
            "not an array variable",
        );
        None
    }
}
