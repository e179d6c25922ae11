//! The items around the shader body: the parameter struct with its defaults, its `Shader`
//! impl (metadata, get and set by name), the output struct, the `SurfaceShader` /
//! `LightShader` / `DisplacementShader` impl, and the prologue of the body (slot
//! declarations, globals and parameters read in their representation).

use super::flow::FrameCtx;
use super::{ident, tri_ty, Gen, GenError, Repr};
use crate::ir::{Const, Global, Node, ShaderKind, SlotId, SlotKind};
use crate::types::{BaseType, Detail, Type};

impl<'a> Gen<'a> {
    pub(super) fn module(&mut self) -> Result<(), GenError> {
        let m = self.m;
        let k = self.k.clone();
        let ty = self.ty.clone();
        let kind_kw = match m.kind {
            ShaderKind::Surface => "surface",
            ShaderKind::Light => "light",
            ShaderKind::Displacement => "displacement",
            ShaderKind::Volume => "volume",
            ShaderKind::Imager => "imager",
        };
        if self.opts.prelude {
            self.line(&format!("use {k}::prelude::*;"));
            self.line("");
        }
        self.line(&format!("/// RSL {kind_kw} `{}` (generated Rust; parameters are the RSL ones).", m.name));
        self.line("#[allow(non_snake_case, non_camel_case_types)]");
        self.line("#[derive(Clone, Debug, PartialEq)]");
        self.line(&format!("pub struct {ty} {{"));
        self.ind += 1;
        for p in &m.params {
            let d = if p.output { "output " } else { "" };
            self.line(&format!(
                "/// `{d}{} {}`{}",
                p.ty.detail,
                p.ty.base,
                p.ty.array.map_or(String::new(), |n| format!("[{n}]"))
            ));
            self.line(&format!("pub {}: {},", ident(&p.name), Self::param_field_ty(p.ty)));
        }
        self.ind -= 1;
        self.line("}");
        self.line("");
        // Default.
        self.line(&format!("impl Default for {ty} {{"));
        self.ind += 1;
        self.line("fn default() -> Self {");
        self.ind += 1;
        self.line("Self {");
        self.ind += 1;
        for p in &m.params {
            self.line(&format!("{}: {},", ident(&p.name), Self::param_default(&p.default, p.ty)));
        }
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        self.line("");
        self.shader_impl();
        self.line("");
        self.outputs_struct();
        self.line("");
        // The shading function.
        self.line("#[allow(non_snake_case, unused_mut, unused_variables, unused_assignments, unused_labels, unused_parens, unused_braces, unreachable_code, clippy::all)]");
        self.line(&format!("impl {ty} {{"));
        self.ind += 1;
        let res = format!("{ty}Result");
        match m.kind {
            ShaderKind::Light => {
                self.line("/// Runs the light shader for surface points `ps`: `Cl`, `L`, the lanes an `illuminate`/`solar` reached, and the output parameters.");
                self.line("#[inline(always)]");
                self.line(&format!("pub fn run<F: ShadingFloat>(&self, e: &mut Exec<F>, ps: Vec3<F>) -> {res}<F> {{"));
                self.ind += 1;
                self.line("let zero = F::c(0.0);");
                self.line("let g = Globals { P: ps, N: Vec3::zero(), Ng: Vec3::zero(), I: Vec3::zero(), E: Vec3::zero(), s: zero, t: zero, u: zero, v: zero, du: zero, dv: zero, dPdu: Vec3::zero(), dPdv: Vec3::zero(), Cs: Color::zero(), Os: Color::zero() };");
            }
            kind => {
                // Volume and imager shaders start from what arrives (`Ci`, `Oi`; an imager's
                // `alpha`) instead of zero.
                let arriving = match kind {
                    ShaderKind::Volume => format!(", arriving: {}::SurfaceOutput<F>", self.k),
                    ShaderKind::Imager => format!(", arriving: {}::ImagerPixel<F>", self.k),
                    _ => String::new(),
                };
                self.line("/// Runs the shader: every output (`Ci`, `Oi`, `P`, `N` and the output parameters).");
                self.line("#[inline(always)]");
                self.line(&format!(
                    "pub fn run<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>{arriving}) -> {res}<F> {{"
                ));
                self.ind += 1;
                self.line("let g = *ctx.globals();");
            }
        }
        if m.uses_spaces() {
            // A copy (a reference count) so that the context stays free for `illuminance`.
            match m.kind {
                ShaderKind::Light => self.line(&format!("let spaces = {}::Spaces::standard();", self.k)),
                _ => self.line("let spaces = ctx.spaces().clone();"),
            }
        }
        self.line("let no: F::Mask = Mask::splat(false);");
        self.line("let mut m0 = e.mask();");
        self.line("let mut lit = no;");
        if m.kind == ShaderKind::Light && self.f.global_slot(Global::L).is_none() {
            // `L` as the light's output even when the body never names it.
            self.line("let mut light_l: Vec3<F> = Vec3::zero();");
        }
        self.slot_decls();
        let body = &m.func.body;
        let native = self.frame_native.get(&0).copied().unwrap_or(true);
        if native {
            self.frames.push((FrameCtx::Native("'body".into()), Vec::new()));
            self.line("'body: {");
            self.ind += 1;
            self.block(body)?;
            self.ind -= 1;
            self.line("}");
        } else {
            self.line("let mut ret0 = no;");
            self.frames.push((FrameCtx::Masked("ret0".into()), Vec::new()));
            self.block(body)?;
        }
        self.frames.pop();
        self.result_expr();
        self.ind -= 1;
        self.line("}");
        self.eval_values_fn();
        self.ind -= 1;
        self.line("}");
        self.line("");
        self.trait_impl();
        let _ = k;
        Ok(())
    }

    fn param_field_ty(t: Type) -> String {
        let el = match t.base {
            BaseType::Float | BaseType::Void => "f64",
            BaseType::String => "::std::string::String",
            BaseType::Matrix => "[f64; 16]",
            _ => "[f64; 3]",
        };
        match t.array {
            Some(n) => format!("[{el}; {n}]"),
            None => el.to_string(),
        }
    }

    fn param_default(c: &Const, t: Type) -> String {
        match c {
            Const::Float(x) => match t.base {
                b if b.is_triple() => format!("[{x:?}; 3]"),
                _ => format!("{x:?}"),
            },
            Const::Triple(v) => format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2]),
            Const::Matrix(m) => format!("[{}]", m.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(", ")),
            Const::Str(s) => format!("{s:?}.to_string()"),
            Const::Array(items) => {
                format!(
                    "[{}]",
                    items.iter().map(|i| Self::param_default(i, t.element())).collect::<Vec<_>>().join(", ")
                )
            }
        }
    }

    fn shader_impl(&mut self) {
        let m = self.m;
        let k = self.k.clone();
        let rt = self.opts.runtime.clone();
        let ty = self.ty.clone();
        self.line(&format!("impl {k}::Shader for {ty} {{"));
        self.ind += 1;
        self.line(&format!("fn meta(&self) -> {k}::ShaderMeta {{"));
        self.ind += 1;
        self.line(&format!("{k}::ShaderMeta {{"));
        self.ind += 1;
        self.line(&format!("name: {:?}.to_string(),", m.name));
        let kind = match m.kind {
            ShaderKind::Surface => "Surface",
            ShaderKind::Light => "Light",
            ShaderKind::Displacement => "Displacement",
            ShaderKind::Volume => "Volume",
            ShaderKind::Imager => "Imager",
        };
        self.line(&format!("kind: {k}::ShaderKind::{kind},"));
        self.line("params: vec![");
        self.ind += 1;
        for p in &m.params {
            let pt = match p.ty.base {
                BaseType::Float | BaseType::Void => "Float",
                BaseType::Color => "Color",
                BaseType::Point => "Point",
                BaseType::Vector => "Vector",
                BaseType::Normal => "Normal",
                BaseType::String => "String",
                BaseType::Matrix => "Matrix",
            };
            let storage = if p.ty.detail == Detail::Uniform { "Uniform" } else { "Varying" };
            self.line(&format!(
                "{k}::ParamInfo {{ name: {:?}.to_string(), ty: {k}::ParamType::{pt}, array_len: {:?}, default: {}, storage: {k}::Storage::{storage}, output: {} }},",
                p.name,
                p.ty.array.map(|n| n as usize),
                Self::param_value(&k, &p.default),
                p.output
            ));
        }
        self.ind -= 1;
        self.line("],");
        self.line(&format!("uses_derivatives: {},", self.uses_derivatives));
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        self.line(&format!("fn param(&self, name: &str) -> Option<{k}::ParamValue> {{"));
        self.ind += 1;
        self.line("match name {");
        self.ind += 1;
        for p in &m.params {
            let f = ident(&p.name);
            if p.ty.array.is_some() {
                self.line(&format!("{:?} => Some({rt}::array_value(&self.{f})),", p.name));
            } else {
                self.line(&format!("{:?} => Some({k}::ParamField::to_value(&self.{f})),", p.name));
            }
        }
        self.line("_ => None,");
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        self.line("#[allow(unreachable_code, unused_variables)]");
        self.line(&format!(
            "fn set_param(&mut self, name: &str, value: &{k}::ParamValue) -> Result<(), {k}::ParamError> {{"
        ));
        self.ind += 1;
        self.line("match name {");
        self.ind += 1;
        for p in &m.params {
            let f = ident(&p.name);
            let pt = match p.ty.base {
                BaseType::Float | BaseType::Void => "Float",
                BaseType::Color => "Color",
                BaseType::Point => "Point",
                BaseType::Vector => "Vector",
                BaseType::Normal => "Normal",
                BaseType::String => "String",
                BaseType::Matrix => "Matrix",
            };
            let conv = if p.ty.array.is_some() {
                format!("{rt}::array_from_value(value, &self.{f})")
            } else {
                format!("{k}::ParamField::from_value(value)")
            };
            // A parameter with a computed default: setting it clears its flag.
            let flag =
                m.params.iter().find(|q| q.name == crate::ir::default_flag_name(&p.name)).map_or(String::new(), |q| {
                    format!(
                        " self.{} = {k}::ParamField::from_value(&{k}::ParamValue::Float(0.0)).unwrap_or(self.{0});",
                        ident(&q.name)
                    )
                });
            self.line(&format!(
                "{:?} => {{ self.{f} = {conv}.ok_or_else(|| {k}::ParamError::Type {{ name: name.to_string(), expected: {k}::ParamType::{pt}, got: value.clone() }})?;{flag} Ok(()) }}",
                p.name
            ));
        }
        let known: Vec<String> = m.params.iter().map(|p| format!("{:?}.to_string()", p.name)).collect();
        self.line(&format!(
            "_ => Err({k}::ParamError::Unknown {{ shader: {:?}.to_string(), name: name.to_string(), known: vec![{}] }}),",
            m.name,
            known.join(", ")
        ));
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
        self.ind -= 1;
        self.line("}");
    }

    fn param_value(k: &str, c: &Const) -> String {
        match c {
            Const::Float(x) => format!("{k}::ParamValue::Float({x:?})"),
            Const::Triple(t) => format!("{k}::ParamValue::Triple([{:?}, {:?}, {:?}])", t[0], t[1], t[2]),
            Const::Matrix(m) => format!(
                "{k}::ParamValue::Matrix([{}])",
                m.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(", ")
            ),
            Const::Str(s) => format!("{k}::ParamValue::String({s:?}.to_string())"),
            Const::Array(items) => format!(
                "{k}::ParamValue::Array(vec![{}])",
                items.iter().map(|i| Self::param_value(k, i)).collect::<Vec<_>>().join(", ")
            ),
        }
    }

    fn output_params(&self) -> Vec<(String, SlotId, Type)> {
        self.m.params.iter().filter(|p| p.output).map(|p| (p.name.clone(), p.slot, p.ty)).collect()
    }

    fn outputs_struct(&mut self) {
        let ty = self.ty.clone();
        let k = self.k.clone();
        self.line(&format!("/// Everything `{ty}::run` computes."));
        self.line("#[allow(non_snake_case)]");
        self.line("#[derive(Clone, Debug)]");
        self.line(&format!("pub struct {ty}Result<F: {k}::ShadingFloat> {{"));
        self.ind += 1;
        match self.m.kind {
            ShaderKind::Light => {
                self.line("/// `Cl`.");
                self.line(&format!("pub Cl: {k}::Color<F>,"));
                self.line("/// `L` (from the light to the surface point).");
                self.line(&format!("pub L: {k}::Vec3<F>,"));
                self.line("/// The lanes an `illuminate`/`solar` body ran for.");
                self.line("pub lit: F::Mask,");
            }
            _ => {
                self.line("/// `Ci`.");
                self.line(&format!("pub Ci: {k}::Color<F>,"));
                self.line("/// `Oi`.");
                self.line(&format!("pub Oi: {k}::Color<F>,"));
                self.line("/// `P` (displaced).");
                self.line(&format!("pub P: {k}::Vec3<F>,"));
                self.line("/// `N`.");
                self.line(&format!("pub N: {k}::Vec3<F>,"));
                if self.m.kind == ShaderKind::Imager {
                    self.line("/// `alpha`.");
                    self.line("pub alpha: F,");
                }
            }
        }
        for (name, _, t) in self.output_params() {
            let el = match t.base {
                BaseType::String => "::std::string::String".to_string(),
                BaseType::Float => "F".into(),
                BaseType::Color => format!("{k}::Color<F>"),
                BaseType::Matrix => format!("{k}::Matrix4<F>"),
                _ => format!("{k}::Vec3<F>"),
            };
            let full = match t.array {
                Some(n) => format!("[{el}; {n}]"),
                None => el,
            };
            self.line(&format!("/// Output parameter `{name}`."));
            self.line(&format!("pub {}: {full},", ident(&format!("out_{name}"))));
        }
        self.ind -= 1;
        self.line("}");
    }

    fn slot_decls(&mut self) {
        let f = self.f;
        let light = self.m.kind == ShaderKind::Light;
        for (i, slot) in f.slots.iter().enumerate() {
            let s = SlotId(i as u32);
            let r = self.sr[i];
            let var = self.slot_var(s);
            let ty = self.slot_ty(s);
            let init = match &slot.kind {
                SlotKind::Param(pi) => {
                    if !self.stored[i] && !self.m.params[*pi as usize].output {
                        continue; // read straight from `self`
                    }
                    self.param_read(*pi as usize, r, true)
                }
                SlotKind::Global(gl) => self.global_init(*gl, slot.ty, r, light),
                SlotKind::Local => self.zero(slot.ty, r),
            };
            self.line(&format!("let mut {var}: {ty} = {init};"));
        }
    }

    fn zero(&self, t: Type, r: Repr) -> String {
        let el = match t.base {
            BaseType::String => "String::new()".to_string(),
            BaseType::Float | BaseType::Void => {
                if r == Repr::Scalar {
                    "0.0_f64".into()
                } else {
                    "F::c(0.0)".into()
                }
            }
            BaseType::Matrix => format!("Matrix4::scalar({})", if r == Repr::Scalar { "0.0_f64" } else { "F::c(0.0)" }),
            b => format!("{}::zero()", tri_ty(b)),
        };
        match t.array {
            Some(n) if t.base == BaseType::String => {
                format!("::core::array::from_fn::<String, {n}, _>(|_| String::new())")
            }
            Some(n) => format!("[{el}; {n}]"),
            None => el,
        }
    }

    fn global_init(&self, gl: Global, t: Type, r: Repr, light: bool) -> String {
        let lane = r == Repr::Lane;
        let e = match gl {
            Global::P => "g.P",
            Global::N => "g.N",
            Global::Ng => "g.Ng",
            Global::I => "g.I",
            Global::E => "g.E",
            Global::Cs => "g.Cs",
            Global::Os => "g.Os",
            Global::S => "g.s",
            Global::T => "g.t",
            Global::U => "g.u",
            Global::V => "g.v",
            Global::Du => "g.du",
            Global::Dv => "g.dv",
            Global::DPdu => "g.dPdu",
            Global::DPdv => "g.dPdv",
            Global::Ci if matches!(self.m.kind, ShaderKind::Volume | ShaderKind::Imager) => "arriving.Ci",
            Global::Oi if matches!(self.m.kind, ShaderKind::Volume | ShaderKind::Imager) => "arriving.Oi",
            Global::Alpha if self.m.kind == ShaderKind::Imager => "arriving.alpha",
            Global::Oi => {
                if light {
                    "Color::zero()"
                } else {
                    "g.Os"
                }
            }
            Global::Ps => {
                if light {
                    "ps"
                } else {
                    return self.zero(t, r);
                }
            }
            Global::Ncomps => return if lane { "F::c(3.0)".into() } else { "3.0_f64".into() },
            _ => return self.zero(t, r),
        };
        if lane {
            e.to_string()
        } else {
            format!("{e}.lane(0)")
        }
    }

    /// A parameter's value from `self` in representation `r`.
    pub(super) fn param_read(&self, pi: usize, r: Repr, owned: bool) -> String {
        let p = &self.m.params[pi];
        let f = format!("self.{}", ident(&p.name));
        let conv = |e: &str, t: Type| -> String {
            match (t.base, r) {
                (BaseType::String, _) => {
                    if owned {
                        format!("{e}.clone()")
                    } else {
                        format!("{e}.as_str()")
                    }
                }
                (BaseType::Float, Repr::Scalar) => e.to_string(),
                (BaseType::Float, Repr::Lane) => format!("F::c({e})"),
                (BaseType::Matrix, Repr::Scalar) => format!("Matrix4::<f64>::from_array({e})"),
                (BaseType::Matrix, Repr::Lane) => format!("Matrix4::<F>::from_array({e})"),
                (b, Repr::Scalar) => format!("{}::<f64>::from_array({e})", tri_ty(b)),
                (b, Repr::Lane) => format!("{}::<F>::from_array({e})", tri_ty(b)),
            }
        };
        match p.ty.array {
            Some(_) if p.ty.base == BaseType::String => {
                if owned {
                    format!("{f}.clone()")
                } else {
                    format!("{f}.each_ref().map(|x| x.as_str())")
                }
            }
            Some(_) => {
                let inner = conv("x", p.ty.element());
                format!("{f}.map(|x| {inner})")
            }
            None => conv(&f, p.ty),
        }
    }

    fn result_expr(&mut self) {
        let ty = self.ty.clone();
        let slot = |g: Global| self.f.global_slot(g);
        let read = |this: &Self, g: Global, dflt: &str| match slot(g) {
            Some(s) if this.sr[s.0 as usize] == Repr::Lane => this.slot_var(s),
            Some(s) => this.lift(&this.slot_var(s), this.f.slot(s).ty, false),
            None => dflt.to_string(),
        };
        let mut fields = Vec::new();
        if self.m.kind == ShaderKind::Light {
            fields.push(format!("Cl: {}", read(self, Global::Cl, "Color::zero()")));
            fields.push(format!("L: {}", read(self, Global::L, "light_l")));
            let has_light = {
                let mut any = false;
                crate::ir::walk(&self.f.body, &mut |n| {
                    any |= matches!(n, Node::Illuminate { .. } | Node::Solar { .. });
                });
                any
            };
            fields.push(if has_light { "lit".into() } else { "lit: e.mask()".into() });
        } else {
            let arrives = matches!(self.m.kind, ShaderKind::Volume | ShaderKind::Imager);
            let (ci, oi) = if arrives { ("arriving.Ci", "arriving.Oi") } else { ("Color::zero()", "g.Os") };
            fields.push(format!("Ci: {}", read(self, Global::Ci, ci)));
            fields.push(format!("Oi: {}", read(self, Global::Oi, oi)));
            fields.push(format!("P: {}", read(self, Global::P, "g.P")));
            fields.push(format!("N: {}", read(self, Global::N, "g.N")));
            if self.m.kind == ShaderKind::Imager {
                fields.push(format!("alpha: {}", read(self, Global::Alpha, "arriving.alpha")));
            }
        }
        for (name, s, t) in self.output_params() {
            let var = self.slot_var(s);
            let v = if t.base == BaseType::String {
                var
            } else if self.sr[s.0 as usize] == Repr::Lane {
                var
            } else {
                self.lift(&var, t, false)
            };
            fields.push(format!("{}: {v}", ident(&format!("out_{name}"))));
        }
        self.line(&format!("{ty}Result {{ {} }}", fields.join(", ")));
    }

    fn eval_values_fn(&mut self) {
        if self.m.kind == ShaderKind::Light {
            return;
        }
        self.line(
            "/// Lane `lane` of every output, by name (`Ci`, `Oi`, … and the output parameters), for test harnesses.",
        );
        if self.m.kind == ShaderKind::Light {
            return;
        }
        let ty = self.ty.clone();
        self.line(&format!(
            "pub fn values<F: ShadingFloat>(r: &{ty}Result<F>, lane: usize) -> Vec<(&'static str, Vec<f64>)> {{"
        ));
        self.ind += 1;
        self.line("let mut v: Vec<(&'static str, Vec<f64>)> = vec![(\"Ci\", r.Ci.lane(lane).to_vec()), (\"Oi\", r.Oi.lane(lane).to_vec())];");
        for (name, _, t) in self.output_params() {
            let f = ident(&format!("out_{name}"));
            let e = match (t.base, t.array) {
                (BaseType::String, _) => continue,
                (BaseType::Float, None) => format!("vec![r.{f}.lane(lane)]"),
                (BaseType::Float, Some(_)) => format!("r.{f}.iter().map(|x| x.lane(lane)).collect()"),
                (BaseType::Matrix, None) => format!("r.{f}.m.iter().flatten().map(|x| x.lane(lane)).collect()"),
                (BaseType::Matrix, Some(_)) => continue,
                (_, None) => format!("r.{f}.lane(lane).to_vec()"),
                (_, Some(_)) => format!("r.{f}.iter().flat_map(|x| x.lane(lane)).collect()"),
            };
            self.line(&format!("v.push(({name:?}, {e}));"));
        }
        self.line("v");
        self.ind -= 1;
        self.line("}");
    }

    fn trait_impl(&mut self) {
        let k = self.k.clone();
        let ty = self.ty.clone();
        match self.m.kind {
            ShaderKind::Surface => {
                self.line(&format!("impl {k}::SurfaceShader for {ty} {{"));
                self.ind += 1;
                let read = crate::passes::analysis::globals_read(self.m);
                self.line("#[inline(always)]");
                self.line(&format!("fn globals_read(&self) -> {k}::GlobalSet {{"));
                self.line(&format!("    {k}::GlobalSet({:#06x})", read.0));
                self.line("}");
                self.line("#[inline(always)]");
                self.line(&format!(
                    "fn shade<F: {k}::ShadingFloat, C: {k}::ShadingContext<F>>(&self, ctx: &mut C, e: &mut {k}::Exec<F>) -> {k}::SurfaceOutput<F> {{"
                ));
                self.line("    let r = self.run(ctx, e);");
                self.line(&format!("    {k}::SurfaceOutput {{ Ci: r.Ci, Oi: r.Oi }}"));
                self.line("}");
                self.ind -= 1;
                self.line("}");
            }
            ShaderKind::Displacement => {
                self.line(&format!("impl {k}::DisplacementShader for {ty} {{"));
                self.ind += 1;
                self.line("#[inline(always)]");
                self.line(&format!(
                    "fn displace<F: {k}::ShadingFloat, C: {k}::ShadingContext<F>>(&self, ctx: &mut C, e: &mut {k}::Exec<F>) -> ({k}::Vec3<F>, {k}::Vec3<F>) {{"
                ));
                self.line("    let r = self.run(ctx, e);");
                self.line("    (r.P, r.N)");
                self.line("}");
                self.ind -= 1;
                self.line("}");
            }
            ShaderKind::Volume => {
                self.line(&format!("impl {k}::VolumeShader for {ty} {{"));
                self.ind += 1;
                self.line("#[inline(always)]");
                self.line(&format!(
                    "fn volume<F: {k}::ShadingFloat, C: {k}::ShadingContext<F>>(&self, ctx: &mut C, e: &mut {k}::Exec<F>, entering: {k}::SurfaceOutput<F>) -> {k}::SurfaceOutput<F> {{"
                ));
                self.line("    let r = self.run(ctx, e, entering);");
                self.line(&format!("    {k}::SurfaceOutput {{ Ci: r.Ci, Oi: r.Oi }}"));
                self.line("}");
                self.ind -= 1;
                self.line("}");
            }
            ShaderKind::Imager => {
                self.line(&format!("impl {k}::ImagerShader for {ty} {{"));
                self.ind += 1;
                self.line("#[inline(always)]");
                self.line(&format!(
                    "fn image<F: {k}::ShadingFloat>(&self, e: &mut {k}::Exec<F>, pixel: {k}::ImagerPixel<F>) -> {k}::ImagerPixel<F> {{"
                ));
                // The imager's context: `P` the raster position, `Cs`/`Os` the pixel's `Ci`/`Oi`
                // (as the interpreter and the JIT give it), no lights.
                self.line(&format!(
                    "    let mut ctx = {k}::PointContext::new({k}::Globals::imager(&pixel), &[] as &[{k}::LightData]);"
                ));
                self.line("    let r = self.run(&mut ctx, e, pixel);");
                self.line(&format!("    {k}::ImagerPixel {{ P: pixel.P, Ci: r.Ci, Oi: r.Oi, alpha: r.alpha }}"));
                self.line("}");
                self.ind -= 1;
                self.line("}");
            }
            ShaderKind::Light => {
                let mut ill = false;
                let mut sol = false;
                crate::ir::walk(&self.f.body, &mut |n| match n {
                    Node::Illuminate { .. } => ill = true,
                    Node::Solar { .. } => sol = true,
                    _ => {}
                });
                let (em, fixed) = match (ill, sol) {
                    (false, false) => ("Ambient", true),
                    (true, false) => ("Local", true),
                    (false, true) => ("Distant", true),
                    (true, true) => ("Local", false),
                };
                self.line(&format!("impl {k}::LightShader for {ty} {{"));
                self.ind += 1;
                self.line("#[inline(always)]");
                self.line(&format!("fn emission(&self) -> Option<{k}::Emission> {{"));
                self.line(&format!(
                    "    {}",
                    if fixed { format!("Some({k}::Emission::{em})") } else { "None".to_string() }
                ));
                self.line("}");
                if let Some(p) = self.m.params.iter().find(|p| p.name == "__category" && p.ty.base == BaseType::String)
                {
                    // RSL's `__category` parameter: what `illuminance("category", …)` selects on.
                    self.line("#[inline(always)]");
                    self.line(&format!("fn category(&self) -> &str {{ &self.{} }}", ident(&p.name)));
                }
                self.line("#[inline(always)]");
                self.line(&format!(
                    "fn light<F: {k}::ShadingFloat>(&self, e: &mut {k}::Exec<F>, ps: {k}::Vec3<F>) -> {k}::LightOutput<F> {{"
                ));
                self.line("    let r = self.run(e, ps);");
                self.line(&format!(
                    "    {k}::LightOutput {{ cl: r.Cl, l: r.L, lit: r.lit, emission: {k}::Emission::{em} }}"
                ));
                self.line("}");
                self.ind -= 1;
                self.line("}");
            }
        }
    }
}
