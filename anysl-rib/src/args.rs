//! A request's values matched against its argument shape: [`Args`] (positional arguments and
//! the parameter list, with the diagnostics a wrong one gets), the declarations in force
//! (`Declare` and inline declarations) and the diagnostics gathered while reading.

use crate::builder::{Basis, Handle};
use crate::diag::{codes, Diagnostic};
use crate::param::{self, Decl, DeclOrigin, Param, ParamList, Type, ValueKind, Values};
use crate::source::{FileId, Loc, SourceMap};
use std::collections::{HashMap, HashSet};

/// Marker: the request is malformed and already reported.
pub(crate) struct Bad;

/// One argument value of a request, with its byte range.
#[derive(Clone, Debug)]
pub(crate) enum Val {
    Num {
        v: f64,
        start: u32,
        end: u32,
    },
    Str {
        s: String,
        start: u32,
        end: u32,
    },
    /// `[numbers]`; `[]` is an empty `Nums`.
    Nums {
        v: Vec<f64>,
        start: u32,
        end: u32,
    },
    Strs {
        v: Vec<String>,
        start: u32,
        end: u32,
    },
}

impl Val {
    pub(crate) fn span(&self) -> (u32, u32) {
        match self {
            Self::Num { start, end, .. }
            | Self::Str { start, end, .. }
            | Self::Nums { start, end, .. }
            | Self::Strs { start, end, .. } => (*start, *end),
        }
    }

    pub(crate) fn describe(&self) -> String {
        match self {
            Self::Num { .. } => "a number".into(),
            Self::Str { s, .. } => format!("the string \"{s}\""),
            Self::Nums { v, .. } => format!("an array of {} numbers", v.len()),
            Self::Strs { v, .. } => format!("an array of {} strings", v.len()),
        }
    }
}

/// Diagnostics with duplicates (same code and place, e.g. from a replayed inline archive) dropped.
#[derive(Default)]
pub(crate) struct Diags {
    pub(crate) items: Vec<Diagnostic>,
    pub(crate) seen: HashSet<(&'static str, FileId, u32, u32)>,
    pub(crate) errors: usize,
}

impl Diags {
    pub(crate) fn push(&mut self, d: Diagnostic) {
        if self.seen.insert((d.code, d.loc.file, d.loc.start, d.loc.end)) {
            if d.is_error() {
                self.errors += 1;
            }
            self.items.push(d);
        }
    }
}

/// State shared by the reader and the argument parser.
pub(crate) struct Ctx {
    pub(crate) sources: SourceMap,
    pub(crate) diags: Diags,
    pub(crate) decls: HashMap<String, Decl>,
    pub(crate) undeclared: HashSet<String>,
}

impl Ctx {
    pub(crate) fn loc(&self, file: FileId, start: u32, end: u32) -> Loc {
        self.sources.loc(file, start, end)
    }
}

/// The values of one request, matched against its argument shape.
pub(crate) struct Args<'r> {
    /// `Name arg1 arg2 …`, shown in a note when the arguments are wrong.
    pub usage: &'static str,
    pub(crate) request: &'r str,
    pub(crate) file: FileId,
    pub(crate) name_start: u32,
    pub(crate) name_end: u32,
    pub(crate) vals: Vec<Val>,
    pub(crate) pos: usize,
    pub(crate) ctx: &'r mut Ctx,
}

pub(crate) fn to_int(v: f64) -> Option<i32> {
    (v.fract() == 0.0 && v >= f64::from(i32::MIN) && v <= f64::from(i32::MAX)).then_some(v as i32)
}

impl Args<'_> {
    pub(crate) fn request_end(&self) -> u32 {
        self.vals.last().map_or(self.name_end, |v| v.span().1)
    }

    pub(crate) fn usage_note(&self) -> String {
        format!("usage: {}", self.usage)
    }

    pub(crate) fn missing(&mut self, what: &str) -> Bad {
        let loc = self.ctx.loc(self.file, self.name_start, self.request_end());
        let found = self.vals.len();
        let d = Diagnostic::error(codes::ARG_COUNT, loc, format!("not enough arguments for `{}`", self.request))
            .with_label(format!("`{what}` is missing ({found} value{} given)", if found == 1 { "" } else { "s" }))
            .with_note(self.usage_note());
        self.ctx.diags.push(d);
        Bad
    }

    pub(crate) fn wrong(&mut self, code: &'static str, at: (u32, u32), message: String, label: String) -> Bad {
        let loc = self.ctx.loc(self.file, at.0, at.1);
        let d = Diagnostic::error(code, loc, message).with_label(label).with_note(self.usage_note());
        self.ctx.diags.push(d);
        Bad
    }

    pub(crate) fn wrong_type(&mut self, expected: &str, what: &str) -> Bad {
        let Some(v) = self.vals.get(self.pos) else { return self.missing(what) };
        let (span, found) = (v.span(), v.describe());
        self.wrong(
            codes::ARG_TYPE,
            span,
            format!("`{}` expects {expected} for `{what}`, found {found}", self.request),
            format!("expected {expected}"),
        )
    }

    pub(crate) fn int_of(&mut self, v: f64, span: (u32, u32), what: &str) -> Result<i32, Bad> {
        to_int(v).ok_or_else(|| {
            self.wrong(
                codes::ARG_TYPE,
                span,
                format!("`{}` expects an integer for `{what}`, found {v}", self.request),
                "expected an integer".into(),
            )
        })
    }

    pub(crate) fn float(&mut self, what: &str) -> Result<f32, Bad> {
        let v = match self.vals.get(self.pos) {
            None => return Err(self.missing(what)),
            Some(Val::Num { v, .. }) => *v,
            Some(Val::Nums { v, .. }) if v.len() == 1 => v[0],
            Some(_) => return Err(self.wrong_type("a number", what)),
        };
        self.pos += 1;
        Ok(v as f32)
    }

    /// `DepthOfField` without arguments is a pinhole camera.
    pub(crate) fn dof(&mut self, what: &str) -> Result<f32, Bad> {
        if self.vals.is_empty() {
            return Ok(if what == "fstop" { f32::INFINITY } else { 0.0 });
        }
        self.float(what)
    }

    pub(crate) fn int(&mut self, what: &str) -> Result<i32, Bad> {
        let (v, span) = match self.vals.get(self.pos) {
            None => return Err(self.missing(what)),
            Some(val @ Val::Num { v, .. }) => (*v, val.span()),
            Some(val @ Val::Nums { v, .. }) if v.len() == 1 => (v[0], val.span()),
            Some(_) => return Err(self.wrong_type("an integer", what)),
        };
        let i = self.int_of(v, span, what)?;
        self.pos += 1;
        Ok(i)
    }

    pub(crate) fn boolean(&mut self, what: &str) -> Result<bool, Bad> {
        self.int(what).map(|i| i != 0)
    }

    pub(crate) fn string(&mut self, what: &str) -> Result<String, Bad> {
        let s = match self.vals.get(self.pos) {
            None => return Err(self.missing(what)),
            Some(Val::Str { s, .. }) => s.clone(),
            Some(Val::Strs { v, .. }) if v.len() == 1 => v[0].clone(),
            Some(_) => return Err(self.wrong_type("a string", what)),
        };
        self.pos += 1;
        Ok(s)
    }

    pub(crate) fn handle(&mut self, what: &str) -> Result<Handle, Bad> {
        match self.vals.get(self.pos) {
            Some(Val::Str { .. } | Val::Strs { .. }) => self.string(what).map(Handle::Str),
            _ => self.int(what).map(Handle::Int),
        }
    }

    pub(crate) fn basis(&mut self, what: &str) -> Result<Basis, Bad> {
        match self.vals.get(self.pos) {
            Some(Val::Str { .. }) => self.string(what).map(Basis::Named),
            Some(Val::Nums { .. }) => self.fixed::<16>(what).map(Basis::Matrix),
            None => Err(self.missing(what)),
            Some(_) => Err(self.wrong_type("a basis name or an array of 16 numbers", what)),
        }
    }

    pub(crate) fn floats(&mut self, what: &str) -> Result<Vec<f32>, Bad> {
        let v = match self.vals.get(self.pos) {
            None => return Err(self.missing(what)),
            Some(Val::Nums { v, .. }) => v.iter().map(|&x| x as f32).collect(),
            Some(Val::Num { v, .. }) => vec![*v as f32],
            Some(_) => return Err(self.wrong_type("an array of numbers", what)),
        };
        self.pos += 1;
        Ok(v)
    }

    pub(crate) fn ints(&mut self, what: &str) -> Result<Vec<i32>, Bad> {
        let (nums, span) = match self.vals.get(self.pos) {
            None => return Err(self.missing(what)),
            Some(val @ Val::Nums { v, .. }) => (v.clone(), val.span()),
            Some(val @ Val::Num { v, .. }) => (vec![*v], val.span()),
            Some(_) => return Err(self.wrong_type("an array of integers", what)),
        };
        let mut out = Vec::with_capacity(nums.len());
        for v in nums {
            out.push(self.int_of(v, span, what)?);
        }
        self.pos += 1;
        Ok(out)
    }

    pub(crate) fn strings(&mut self, what: &str) -> Result<Vec<String>, Bad> {
        let v = match self.vals.get(self.pos) {
            None => return Err(self.missing(what)),
            Some(Val::Strs { v, .. }) => v.clone(),
            Some(Val::Str { s, .. }) => vec![s.clone()],
            Some(Val::Nums { v, .. }) if v.is_empty() => Vec::new(),
            Some(_) => return Err(self.wrong_type("an array of strings", what)),
        };
        self.pos += 1;
        Ok(v)
    }

    /// Optional trailing array: absent when the values end or a parameter name follows.
    pub(crate) fn absent(&self) -> bool {
        matches!(self.vals.get(self.pos), None | Some(Val::Str { .. }))
    }

    pub(crate) fn opt_strings(&mut self, what: &str) -> Result<Vec<String>, Bad> {
        if self.absent() {
            return Ok(Vec::new());
        }
        self.strings(what)
    }

    pub(crate) fn opt_ints(&mut self, what: &str) -> Result<Vec<i32>, Bad> {
        if self.absent() {
            return Ok(Vec::new());
        }
        self.ints(what)
    }

    pub(crate) fn opt_floats(&mut self, what: &str) -> Result<Vec<f32>, Bad> {
        if self.absent() {
            return Ok(Vec::new());
        }
        self.floats(what)
    }

    /// Exactly `N` numbers: one array of `N`, or `N` loose numbers.
    pub(crate) fn fixed<const N: usize>(&mut self, what: &str) -> Result<[f32; N], Bad> {
        let mut out = [0.0f32; N];
        match self.vals.get(self.pos) {
            None => return Err(self.missing(what)),
            Some(val @ Val::Nums { v, .. }) => {
                if v.len() != N {
                    let (span, len) = (val.span(), v.len());
                    return Err(self.wrong(
                        codes::ARG_COUNT,
                        span,
                        format!("`{}` expects {N} numbers for `{what}`, the array has {len}", self.request),
                        format!("expected {N} numbers"),
                    ));
                }
                for (o, x) in out.iter_mut().zip(v) {
                    *o = *x as f32;
                }
                self.pos += 1;
            }
            Some(Val::Num { .. }) => {
                for o in &mut out {
                    *o = self.float(what)?;
                }
            }
            Some(_) => return Err(self.wrong_type(&format!("{N} numbers"), what)),
        }
        Ok(out)
    }

    /// Exactly `N` strings: loose or as one array.
    pub(crate) fn fixed_strings<const N: usize>(&mut self, what: &str) -> Result<[String; N], Bad> {
        if let Some(Val::Strs { v, .. }) = self.vals.get(self.pos) {
            if let Ok(arr) = <[String; N]>::try_from(v.clone()) {
                self.pos += 1;
                return Ok(arr);
            }
        }
        let mut out: [String; N] = std::array::from_fn(|_| String::new());
        for o in &mut out {
            *o = self.string(what)?;
        }
        Ok(out)
    }

    /// Fields the reader fills itself (never parsed from RIB).
    pub(crate) fn none<T: Default>(&mut self, _what: &str) -> Result<T, Bad> {
        Ok(T::default())
    }

    /// Every value left, as a parameter list.
    pub(crate) fn params(&mut self, _what: &str) -> Result<ParamList, Bad> {
        // `Option`/`Attribute` parameters are declared per category: `"limits:bucketsize"`.
        let category = match (self.request, self.vals.first()) {
            ("Option" | "Attribute", Some(Val::Str { s, .. })) => Some(s.clone()),
            _ => None,
        };
        let mut list = ParamList::new();
        while self.pos < self.vals.len() {
            let (name_text, ns, ne) = match &self.vals[self.pos] {
                Val::Str { s, start, end } => (s.clone(), *start, *end),
                other => {
                    let (span, found) = (other.span(), other.describe());
                    return Err(self.wrong(
                        codes::EXPECTED_PARAM_NAME,
                        span,
                        format!("expected a parameter name (a string), found {found}"),
                        "expected a parameter name".into(),
                    ));
                }
            };
            self.pos += 1;
            let Some(value) = self.vals.get(self.pos).cloned() else {
                return Err(self.wrong(
                    codes::MISSING_VALUE,
                    (ns, ne),
                    format!("parameter \"{name_text}\" has no value"),
                    "no value follows".into(),
                ));
            };
            self.pos += 1;
            let (decl, name, origin) = self.resolve(&name_text, category.as_deref(), &value, (ns, ne))?;
            let values = self.convert(&name, &decl, &value)?;
            let per = decl.values_per_item().max(1);
            if values.len() % per != 0 {
                let n = values.len();
                let loc = self.ctx.loc(self.file, value.span().0, value.span().1);
                let d = Diagnostic::error(
                    codes::VALUE_COUNT,
                    loc,
                    format!("parameter \"{name}\" ({decl}) has {n} values, not a multiple of {per}"),
                )
                .with_label(format!("{n} values"))
                .with_note(format!("each {} takes {per} values", decl_item(&decl)));
                self.ctx.diags.push(d);
                return Err(Bad);
            }
            let loc = self.ctx.loc(self.file, ns, ne);
            list.params.push(Param { name, decl, origin, values, loc });
        }
        Ok(list)
    }

    pub(crate) fn resolve(
        &mut self,
        text: &str,
        category: Option<&str>,
        value: &Val,
        span: (u32, u32),
    ) -> Result<(Decl, String, DeclOrigin), Bad> {
        if let Some(parsed) = param::parse_inline(text) {
            return match parsed {
                Ok((decl, name)) => Ok((decl, name, DeclOrigin::Inline)),
                Err(e) => Err(self.wrong(
                    codes::BAD_DECLARATION,
                    span,
                    format!("bad inline declaration \"{text}\": {e}"),
                    "expected `[class] type[[n]] name`".into(),
                )),
            };
        }
        let name = text.trim().to_owned();
        let qualified = category.map(|c| format!("{c}:{name}"));
        if let Some(q) = &qualified {
            if let Some(d) = self.ctx.decls.get(q) {
                return Ok((*d, name, DeclOrigin::Declare));
            }
        }
        if let Some(d) = self.ctx.decls.get(&name) {
            return Ok((*d, name, DeclOrigin::Declare));
        }
        if let Some(d) = qualified.as_deref().and_then(param::predeclared).or_else(|| param::predeclared(&name)) {
            return Ok((d, name, DeclOrigin::Predeclared));
        }
        let ty = match value {
            Val::Str { .. } | Val::Strs { .. } => Type::String,
            _ => Type::Float,
        };
        let decl = Decl::new(param::Class::Uniform, ty);
        let shown = qualified.unwrap_or_else(|| name.clone());
        if self.ctx.undeclared.insert(shown.clone()) {
            let loc = self.ctx.loc(self.file, span.0, span.1);
            let d = Diagnostic::warning(codes::UNDECLARED_PARAM, loc, format!("undeclared parameter \"{shown}\""))
                .with_label(format!("taken as `{decl}`"))
                .with_note(format!("declare it inline (\"uniform color {name}\") or with `Declare \"{name}\" \"…\"`"));
            self.ctx.diags.push(d);
        }
        Ok((decl, name, DeclOrigin::Inferred))
    }

    pub(crate) fn convert(&mut self, name: &str, decl: &Decl, value: &Val) -> Result<Values, Bad> {
        let span = value.span();
        let kind = decl.ty.value_kind();
        let mismatch = |this: &mut Self, needs: &str| {
            let found = value.describe();
            let loc = this.ctx.loc(this.file, span.0, span.1);
            this.ctx.diags.push(
                Diagnostic::error(
                    codes::VALUE_TYPE,
                    loc,
                    format!("parameter \"{name}\" ({decl}) needs {needs}, found {found}"),
                )
                .with_label(format!("expected {needs}")),
            );
            Bad
        };
        let nums: &[f64] = match value {
            Val::Num { v, .. } => std::slice::from_ref(v),
            Val::Nums { v, .. } => v,
            Val::Str { s, .. } if kind == ValueKind::String => return Ok(Values::String(vec![s.clone()])),
            Val::Strs { v, .. } if kind == ValueKind::String => return Ok(Values::String(v.clone())),
            _ => {
                return Err(mismatch(
                    self,
                    match kind {
                        ValueKind::Float => "numbers",
                        ValueKind::Int => "integers",
                        ValueKind::String => "strings",
                    },
                ))
            }
        };
        match kind {
            ValueKind::Float => Ok(Values::Float(nums.iter().map(|&x| x as f32).collect())),
            ValueKind::Int => match nums.iter().map(|&x| to_int(x)).collect::<Option<Vec<i32>>>() {
                Some(v) => Ok(Values::Int(v)),
                None => Err(mismatch(self, "integers")),
            },
            ValueKind::String if nums.is_empty() => Ok(Values::String(Vec::new())),
            ValueKind::String => Err(mismatch(self, "strings")),
        }
    }

    /// Reports values left over after the last argument.
    pub(crate) fn finish(&mut self) -> Result<(), Bad> {
        match self.vals.get(self.pos) {
            None => Ok(()),
            Some(v) => {
                let span = v.span();
                Err(self.wrong(
                    codes::EXTRA_ARGS,
                    span,
                    format!("too many arguments for `{}`", self.request),
                    "unexpected argument".into(),
                ))
            }
        }
    }
}

pub(crate) fn decl_item(decl: &Decl) -> String {
    match decl.array_len {
        Some(n) => format!("{}[{n}]", decl.ty.keyword()),
        None => decl.ty.keyword().to_owned(),
    }
}

pub(crate) fn declare(args: &mut Args<'_>) {
    args.usage = "Declare name declaration";
    let (Ok(name), Ok(text), Ok(())) = (args.string("name"), args.string("declaration"), args.finish()) else {
        return;
    };
    // A declaration may repeat the name: `Declare "Kd" "uniform float Kd"`.
    let parsed = match param::parse_inline(&text) {
        Some(Ok((decl, n))) if n == name => Ok(decl),
        Some(Ok((_, n))) => Err(format!("the declaration names `{n}`, not `{name}`")),
        Some(Err(_)) | None => Decl::parse(&text),
    };
    match parsed {
        Ok(decl) => {
            args.ctx.decls.insert(name, decl);
        }
        Err(e) => {
            let at = args.vals.get(1).map_or((args.name_start, args.name_end), Val::span);
            let loc = args.ctx.loc(args.file, at.0, at.1);
            args.ctx.diags.push(
                Diagnostic::error(codes::BAD_DECLARATION, loc, format!("bad declaration \"{text}\": {e}"))
                    .with_label("expected `[class] type[[n]]`")
                    .with_note("classes: constant uniform varying vertex facevarying facevertex; types: float integer string point vector normal color hpoint matrix bool"),
            );
        }
    }
}
