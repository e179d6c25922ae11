//! Built-in calls: the `call` dispatcher matches on [`Builtin`] with no catch-all arm (a
//! built-in this back end lacks does not compile), with the helpers for output arguments and
//! strings.

use super::{comps, tri_ty, Gen, GenError, Repr};
use crate::builtins::Builtin;
use crate::ir::{ShaderKind, SlotId, Value};
use crate::types::{BaseType, Detail, Type};

impl<'a> Gen<'a> {
    #[allow(clippy::too_many_lines)]
    pub(super) fn call(
        &mut self,
        v: Value,
        builtin: Builtin,
        outputs: &[Option<SlotId>],
        r: Repr,
    ) -> Result<String, GenError> {
        use BaseType as B;
        let inst = self.f.inst(v);
        let args = inst.args.clone();
        let n = args.len();
        let ret = inst.ty.base;
        let span = inst.span;
        let tb = |i: usize| args.get(i).map_or(B::Void, |a| self.arg_ty(*a).base);
        let a = |i: usize| self.val(args[i], r);
        let lane0 = |i: usize| -> String {
            if self.scalar_value(args[i]) {
                self.val(args[i], Repr::Scalar)
            } else {
                format!("{}.lane(0)", self.val(args[i], Repr::Lane))
            }
        };
        let g = "g";
        if builtin.calls_renderer() && self.in_closure {
            return Err(self.err(
                span,
                format!(
                    "generated Rust cannot call `{builtin}` inside an `illuminance` body: the light-loop body is a closure and cannot use the shading context; compute it before the loop"
                ),
            ));
        }
        let light = self.m.kind == ShaderKind::Light;
        // Component-wise application for triples.
        let map1 = |f: &dyn Fn(&str) -> String, x: String, base: BaseType| -> String {
            if base.is_triple() {
                format!("({x}).map(|x| {})", f("x"))
            } else {
                f(&x)
            }
        };
        let tri = |base: BaseType, parts: [String; 3]| -> String {
            format!("{}::new({}, {}, {})", tri_ty(base), parts[0], parts[1], parts[2])
        };
        // Component `c` of argument `i` (broadcasting floats).
        let comp_of = |i: usize, c: usize| -> String {
            let b = tb(i);
            if b.is_triple() {
                format!("a{i}.{}", comps(b)[c])
            } else {
                format!("a{i}")
            }
        };
        let bind =
            |k: usize| -> String { (0..k).map(|i| format!("let a{i} = {};", a(i))).collect::<Vec<_>>().join(" ") };
        let un = |f: &str| -> String {
            let f = f.to_string();
            map1(&|x: &str| f.replace('$', x), a(0), tb(0))
        };
        let e = match builtin {
            Builtin::Abs => un("$.abs()"),
            Builtin::Sign => un("sign($)"),
            Builtin::Floor => un("$.floor()"),
            Builtin::Ceil => un("$.ceil()"),
            Builtin::Round => un("$.round()"),
            Builtin::Sqrt => un("$.sqrt()"),
            Builtin::InverseSqrt => un("inversesqrt($)"),
            Builtin::Exp => un("$.exp()"),
            Builtin::Log if n == 1 => un("$.ln()"),
            Builtin::Log => format!("log_base({}, {})", a(0), a(1)),
            Builtin::Sin => un("$.sin()"),
            Builtin::Cos => un("$.cos()"),
            Builtin::Tan => un("$.tan()"),
            Builtin::Asin => un("$.asin()"),
            Builtin::Acos => un("$.acos()"),
            Builtin::Atan if n == 1 => un("$.atan()"),
            Builtin::Atan => format!("{}.atan2({})", a(0), a(1)),
            Builtin::Radians => un("radians($)"),
            Builtin::Degrees => un("degrees($)"),
            Builtin::Pow | Builtin::Mod | Builtin::Step | Builtin::Min | Builtin::Max => {
                let f = match builtin {
                    Builtin::Pow => "$0.pow($1)",
                    Builtin::Mod => "fmod($0, $1)",
                    Builtin::Step => "step($0, $1)",
                    Builtin::Min => "$0.min($1)",
                    _ => "$0.max($1)",
                };
                let fold = |c: Option<usize>| -> String {
                    let get = |i: usize| match c {
                        Some(c) => comp_of(i, c),
                        None => format!("a{i}"),
                    };
                    let mut acc = f.replace("$0", &get(0)).replace("$1", &get(1));
                    for i in 2..n {
                        acc = f.replace("$0", &acc).replace("$1", &get(i));
                    }
                    acc
                };
                if ret.is_triple() {
                    format!("{{ {} {} }}", bind(n), tri(ret, [fold(Some(0)), fold(Some(1)), fold(Some(2))]))
                } else {
                    format!("{{ {} {} }}", bind(n), fold(None))
                }
            }
            Builtin::Clamp | Builtin::Mix | Builtin::SmoothStep => {
                let f = match builtin {
                    Builtin::Clamp => "clamp",
                    Builtin::Mix => "mix",
                    _ => "smoothstep",
                };
                if ret.is_triple() {
                    let parts =
                        [0, 1, 2].map(|c| format!("{f}({}, {}, {})", comp_of(0, c), comp_of(1, c), comp_of(2, c)));
                    format!("{{ {} {} }}", bind(3), tri(ret, parts))
                } else {
                    format!("{f}({}, {}, {})", a(0), a(1), a(2))
                }
            }
            Builtin::Length => format!("{}.length()", a(0)),
            Builtin::Normalize => format!("{}.normalize()", a(0)),
            Builtin::Distance => format!("distance({}, {})", a(0), a(1)),
            Builtin::FaceForward if n == 3 => format!("faceforward({}, {}, {})", a(0), a(1), a(2)),
            Builtin::FaceForward => format!("faceforward({}, {}, {g}.Ng)", a(0), a(1)),
            Builtin::Reflect => format!("reflect({}, {})", a(0), a(1)),
            Builtin::Refract => format!("refract({}, {}, {})", a(0), a(1), a(2)),
            Builtin::Fresnel => {
                let call = format!("fresnel({}, {}, {})", a(0), a(1), a(2));
                let tmp = self.fresh("fr");
                self.line(&format!("let {tmp} = {call};"));
                let fields = [("kr", B::Float), ("kt", B::Float), ("r", B::Vector), ("t", B::Vector)];
                for (i, (f, b)) in fields.iter().enumerate() {
                    if let Some(Some(s)) = outputs.get(3 + i) {
                        let val = self.out_value(&format!("{tmp}.{f}"), r, *s, *b);
                        self.write_out(*s, &val, *b);
                    }
                }
                "()".into()
            }
            Builtin::PtLineD => format!("ptlined({}, {}, {})", a(0), a(1), a(2)),
            Builtin::Rotate if tb(0).is_triple() => format!("rotate({}, {}, {}, {})", a(0), a(1), a(2), a(3)),
            Builtin::Rotate => format!("({} * Matrix4::rotate({}, {}))", a(0), a(1), a(2)),
            Builtin::Translate => format!("({} * Matrix4::translate({}))", a(0), a(1)),
            Builtin::Scale => format!("({} * Matrix4::scale({}))", a(0), a(1)),
            Builtin::XComp | Builtin::YComp | Builtin::ZComp => {
                let c = match builtin {
                    Builtin::XComp => 0,
                    Builtin::YComp => 1,
                    _ => 2,
                };
                format!("{}.{}", a(0), comps(tb(0))[c])
            }
            Builtin::SetXComp | Builtin::SetYComp | Builtin::SetZComp => {
                let c = match builtin {
                    Builtin::SetXComp => 0,
                    Builtin::SetYComp => 1,
                    _ => 2,
                };
                if let Some(Some(s)) = outputs.first() {
                    let var = self.slot_var(*s);
                    let sr = self.sr[s.0 as usize];
                    let field = format!("{var}.{}", comps(self.f.slot(*s).ty.base)[c]);
                    let x = self.val(args[0], sr);
                    self.assign(&field, &x, sr);
                }
                "()".into()
            }
            Builtin::Comp if tb(0) == B::Matrix => {
                format!(
                    "{{ let m = {}; m.m[(({}) as usize).min(3)][(({}) as usize).min(3)] }}",
                    a(0),
                    lane0(1),
                    lane0(2)
                )
            }
            Builtin::Comp => {
                let x = a(0);
                let cs = comps(tb(0));
                if r == Repr::Scalar {
                    format!("{{ let v = {x}; let i = ({}).floor().max(0.0).min(2.0); if i == 0.0 {{ v.{} }} else if i == 1.0 {{ v.{} }} else {{ v.{} }} }}", a(1), cs[0], cs[1], cs[2])
                } else {
                    format!(
                        "{{ let v = {x}; let i = ({}).floor().max(F::c(0.0)).min(F::c(2.0)); F::select(i.eq(F::c(0.0)), v.{}, F::select(i.eq(F::c(1.0)), v.{}, v.{})) }}",
                        a(1),
                        cs[0],
                        cs[1],
                        cs[2]
                    )
                }
            }
            Builtin::SetComp => {
                if let Some(Some(s)) = outputs.first() {
                    let var = self.slot_var(*s);
                    let sr = self.sr[s.0 as usize];
                    let st = self.f.slot(*s).ty;
                    if st.base == B::Matrix {
                        let (i, j, x) = (
                            if self.scalar_value(args[0]) {
                                self.val(args[0], Repr::Scalar)
                            } else {
                                format!("{}.lane(0)", self.val(args[0], Repr::Lane))
                            },
                            if self.scalar_value(args[1]) {
                                self.val(args[1], Repr::Scalar)
                            } else {
                                format!("{}.lane(0)", self.val(args[1], Repr::Lane))
                            },
                            self.val(args[2], sr),
                        );
                        let field = format!("{var}.m[(({i}) as usize).min(3)][(({j}) as usize).min(3)]");
                        self.assign(&field, &x, sr);
                    } else {
                        let cs = comps(st.base);
                        let x = self.val(args[1], sr);
                        if sr == Repr::Scalar {
                            let i = self.val(args[0], Repr::Scalar);
                            self.line(&format!(
                                "{{ let i = ({i}).floor(); let x = {x}; if i == 0.0 {{ {var}.{} = x; }} else if i == 1.0 {{ {var}.{} = x; }} else if i == 2.0 {{ {var}.{} = x; }} }}",
                                cs[0], cs[1], cs[2]
                            ));
                        } else {
                            let i = self.val(args[0], Repr::Lane);
                            let m = if self.full {
                                "<F::Mask as Mask>::splat(true)".to_string()
                            } else {
                                self.mask.clone()
                            };
                            self.line(&format!(
                                "{{ let i = ({i}).floor(); let x = {x}; let m = {m}; {var}.{0} = F::select(m & i.eq(F::c(0.0)), x, {var}.{0}); {var}.{1} = F::select(m & i.eq(F::c(1.0)), x, {var}.{1}); {var}.{2} = F::select(m & i.eq(F::c(2.0)), x, {var}.{2}); }}",
                                cs[0], cs[1], cs[2]
                            ));
                        }
                    }
                }
                "()".into()
            }
            Builtin::Transform | Builtin::VTransform | Builtin::NTransform => {
                let last = a(n - 1);
                match args.iter().position(|x| self.arg_ty(*x).base == B::Matrix) {
                    Some(mi) => {
                        let f = match (builtin, ret) {
                            (Builtin::VTransform, _) | (_, B::Vector) => "transform_vector",
                            (Builtin::NTransform, _) | (_, B::Normal) => "transform_normal",
                            _ => "transform_point",
                        };
                        let strings = args.iter().filter(|x| self.arg_ty(**x).base == B::String).count();
                        if strings == 1 {
                            // transform(fromspace, m, p): from `fromspace` to current, then by `m`.
                            let t = if r == Repr::Scalar { "f64" } else { "F" };
                            let to = format!("{}.to_current::<{t}>({})", self.spaces_table(), a(0));
                            format!("{}.{f}({to}.{f}({last}))", a(mi))
                        } else {
                            format!("{}.{f}({last})", a(mi))
                        }
                    }
                    None => {
                        let f = match (builtin, ret) {
                            (Builtin::VTransform, _) | (_, B::Vector) => "transform_vector",
                            (Builtin::NTransform, _) | (_, B::Normal) => "transform_normal",
                            _ => "transform_point",
                        };
                        let t = if r == Repr::Scalar { "f64" } else { "F" };
                        let m = if n == 3 {
                            format!("{}.between::<{t}>({}, {})", self.spaces_table(), a(0), a(1))
                        } else {
                            format!("{}.from_current::<{t}>({})", self.spaces_table(), a(0))
                        };
                        format!("{m}.{f}({last})")
                    }
                }
            }
            Builtin::CTransform => {
                let spaces = args.iter().filter(|x| self.arg_ty(**x).base == B::String).count();
                let c = a(spaces);
                let from = if spaces == 2 {
                    format!("ColorSpace::from_name({})", a(0))
                } else {
                    "Some(ColorSpace::Rgb)".into()
                };
                let to = format!("ColorSpace::from_name({})", a(spaces - 1));
                format!(
                    "{{ let c = {c}; match ({from}, {to}) {{ (Some(f), Some(t)) => ctransform(f, t, c), _ => c }} }}"
                )
            }
            Builtin::Determinant => format!("{}.determinant()", a(0)),
            Builtin::Du | Builtin::Dv => {
                let f = if builtin == Builtin::Du { "du" } else { "dv" };
                if tb(0).is_triple() {
                    format!("({}).map(|x| {f}(&{g}, x))", a(0))
                } else {
                    format!("{f}(&{g}, {})", a(0))
                }
            }
            Builtin::Deriv => {
                if tb(0).is_triple() {
                    format!("{{ let d = {}; ({}).map(|x| deriv(&{g}, x, d)) }}", a(1), a(0))
                } else {
                    format!("deriv(&{g}, {}, {})", a(0), a(1))
                }
            }
            Builtin::Area => format!("area({})", a(0)),
            Builtin::CalculateNormal => format!("calculatenormal(&{g}, {})", a(0)),
            Builtin::FilterWidth if tb(0).is_triple() => format!("filterwidth_point({})", a(0)),
            Builtin::FilterWidth => format!("filterwidth({})", a(0)),
            Builtin::FilterStep => {
                let nnum = args.iter().take_while(|x| self.arg_ty(**x).base != B::String).count();
                if nnum >= 3 {
                    format!(
                        "{{ let (e, s0, s1) = ({}, {}, {}); let lo = s0.min(s1); let w = (s1 - s0).abs(); let t = clamp((lo + w - e) / w.max(F::c(1e-30)), F::c(0.0), F::c(1.0)); F::select(w.gt(F::c(0.0)), t, step(e, s0)) }}",
                        a(0),
                        a(1),
                        a(2)
                    )
                } else {
                    format!("filterstep({}, {})", a(0), a(1))
                }
            }
            Builtin::Noise | Builtin::SNoise | Builtin::PNoise | Builtin::PSNoise | Builtin::CellNoise => {
                let periodic = matches!(builtin, Builtin::PNoise | Builtin::PSNoise);
                let nd = if periodic { n / 2 } else { n };
                let dom = |off: usize| -> Result<String, GenError> {
                    let t: Vec<B> = (off..off + nd).map(tb).collect();
                    Ok(match t.as_slice() {
                        [B::Float] => format!("NoiseDomain::D1({})", a(off)),
                        [B::Float, B::Float] => format!("NoiseDomain::D2({}, {})", a(off), a(off + 1)),
                        [p] if p.is_triple() => format!("NoiseDomain::D3({})", self.as_vec(args[off], r)),
                        [p, B::Float] if p.is_triple() => {
                            format!("NoiseDomain::D4({}, {})", self.as_vec(args[off], r), a(off + 1))
                        }
                        _ => {
                            return Err(
                                self.err(span, format!("`{builtin}` with these argument types has no implementation"))
                            )
                        }
                    })
                };
                let d = dom(0)?;
                let signed = matches!(builtin, Builtin::SNoise | Builtin::PSNoise);
                let vecr = ret.is_triple();
                let e = if periodic {
                    let p = dom(nd)?;
                    match (vecr, signed) {
                        (false, false) => format!("pnoise({d}, {p})"),
                        (false, true) => format!("psnoise({d}, {p})"),
                        (true, false) => format!("vpnoise({d}, {p})"),
                        (true, true) => {
                            format!("(vpnoise({d}, {p}) * {} - Vec3::splat({}))", self.k(2.0, r), self.k(1.0, r))
                        }
                    }
                } else if builtin == Builtin::CellNoise {
                    if vecr {
                        format!("vcellnoise({d})")
                    } else {
                        format!("cellnoise({d})")
                    }
                } else {
                    match (vecr, signed) {
                        (false, false) => format!("noise({d})"),
                        (false, true) => format!("snoise({d})"),
                        (true, false) => format!("vnoise({d})"),
                        (true, true) => format!("vsnoise({d})"),
                    }
                };
                if ret == B::Color {
                    format!("({e}).to_color()")
                } else {
                    e
                }
            }
            Builtin::Fbm | Builtin::Turbulence => {
                let d = if tb(0).is_triple() {
                    format!("NoiseDomain::D3({})", self.as_vec(args[0], r))
                } else {
                    format!("NoiseDomain::D1({})", a(0))
                };
                let oct = if n > 1 { format!("(({}).max(0.0) as u32)", lane0(1)) } else { "6".into() };
                let lac = if n > 2 { lane0(2) } else { "2.0".into() };
                let gain = if n > 3 { lane0(3) } else { "0.5".into() };
                format!("{builtin}({d}, {oct}, {lac}, {gain})")
            }
            Builtin::Random => {
                let p = format!("{g}.P * F::c(1.0e4)");
                if ret.is_triple() {
                    tri(ret, [0, 1, 2].map(|c| format!("cellnoise(NoiseDomain::D4({p}, F::c({}.5)))", c)))
                } else {
                    format!("cellnoise(NoiseDomain::D4({p}, F::c(0.5)))")
                }
            }
            Builtin::Spline => {
                let basis = tb(0) == B::String;
                let first = usize::from(basis);
                let b = if basis {
                    format!("SplineBasis::from_name({}).unwrap_or(SplineBasis::CATMULL_ROM)", a(0))
                } else {
                    "SplineBasis::CATMULL_ROM".into()
                };
                let x = a(first);
                let rest = &args[first + 1..];
                let knots = if rest.len() == 1 && self.arg_ty(rest[0]).array.is_some() {
                    a(first + 1)
                } else {
                    format!("[{}]", (first + 1..n).map(a).collect::<Vec<_>>().join(", "))
                };
                format!("{{ let b = {b}; let k = {knots}; spline(&b, {x}, &k) }}")
            }
            Builtin::Ambient | Builtin::Diffuse | Builtin::Specular | Builtin::Phong | Builtin::Trace if light => {
                "Color::zero()".to_string()
            }
            Builtin::Ambient => format!(
                "ambient(ctx, {})",
                if self.exec_mut() == "e" { "&*e".to_string() } else { self.exec_mut().replacen("&mut ", "&", 1) }
            ),
            Builtin::Diffuse => format!("diffuse(ctx, {}, {})", self.exec_mut(), a(0)),
            Builtin::Specular => format!("specular(ctx, {}, {}, {}, {})", self.exec_mut(), a(0), a(1), a(2)),
            Builtin::Phong => format!("phong(ctx, {}, {}, {}, {})", self.exec_mut(), a(0), a(1), a(2)),
            Builtin::Trace => {
                let ex =
                    if self.exec_mut() == "e" { "&*e".to_string() } else { self.exec_mut().replacen("&mut ", "&", 1) };
                format!("ctx.trace({ex}, {}, {})", a(0), a(1))
            }
            Builtin::SpecularBrdf => format!("Color::splat(specularbrdf({}, {}, {}, {}))", a(0), a(1), a(2), a(3)),
            Builtin::Texture | Builtin::Environment | Builtin::Shadow => {
                let rt = format!("{}::texture", self.opts.runtime);
                let coords = args.iter().skip(1).take_while(|x| self.arg_ty(**x).base != B::String).count();
                // The `"name", value` pairs after the coordinates (channel selection arrives as
                // `"firstchannel", c`).
                let mut opts = String::new();
                for i in (1 + coords..n.saturating_sub(1)).step_by(2) {
                    let set = if self.arg_ty(args[i + 1]).base == B::String { "set_string" } else { "set_float" };
                    opts.push_str(&format!("o.{set}({}, {}); ", a(i), a(i + 1)));
                }
                let v = |k: usize| a(1 + k);
                let quad = |k: usize| (0..k).map(v).collect::<Vec<_>>().join(", ");
                let c = match builtin {
                    Builtin::Shadow if coords >= 4 => {
                        format!("Color::splat({rt}::shadow::lookup_quad({}, [{}], &o))", a(0), quad(4))
                    }
                    Builtin::Shadow if coords >= 1 => {
                        format!("Color::splat({rt}::shadow::lookup({}, {}, &o))", a(0), v(0))
                    }
                    Builtin::Environment if coords >= 4 => {
                        format!("{rt}::env::lookup({}, {rt}::env::Dir::Quad([{}]), &o)", a(0), quad(4))
                    }
                    Builtin::Environment if coords >= 1 => {
                        format!("{rt}::env::lookup({}, {rt}::env::Dir::Ray({}), &o)", a(0), v(0))
                    }
                    Builtin::Texture if coords >= 8 => {
                        format!("{rt}::lookup({}, {rt}::St::Quad([{}]), &o)", a(0), quad(8))
                    }
                    Builtin::Texture if coords >= 2 => {
                        format!("{rt}::lookup({}, {rt}::St::Point({}, {}), &o)", a(0), v(0), v(1))
                    }
                    Builtin::Texture if coords == 0 => {
                        format!("{rt}::lookup({}, {rt}::St::Point({g}.s, {g}.t), &o)", a(0))
                    }
                    _ => "Color::splat(o.fill)".to_string(),
                };
                let c = format!("{{ let mut o = {rt}::TexOptions::default(); {opts}{c} }}");
                if ret == B::Float {
                    format!("({c}).r")
                } else {
                    c
                }
            }
            Builtin::Concat => format!(
                "&*{}",
                self.leak_string(&format!("[{}].concat()", (0..n).map(a).collect::<Vec<_>>().join(", ")))
            ),
            Builtin::Format | Builtin::Printf => {
                let rt = self.opts.runtime.clone();
                let mut fa = Vec::new();
                for x in args.iter().skip(1) {
                    let t = self.arg_ty(*x);
                    let e = self.val(*x, self.vr[x.0 as usize]);
                    let lane = self.vr[x.0 as usize] == Repr::Lane;
                    let l = |s: String| if lane { format!("{s}.lane(0)") } else { s };
                    fa.push(match t.base {
                        B::String => format!("{rt}::FmtArg::Str({e}.to_string())"),
                        B::Float if self.f.inst(*x).is_bool => {
                            if lane {
                                format!("{rt}::FmtArg::Num(vec![if {e}.lane(0) {{ 1.0 }} else {{ 0.0 }}])")
                            } else {
                                format!("{rt}::FmtArg::Num(vec![if {e} {{ 1.0 }} else {{ 0.0 }}])")
                            }
                        }
                        B::Float => format!("{rt}::FmtArg::Num(vec![{}])", l(e.clone())),
                        B::Matrix => {
                            format!("{rt}::FmtArg::Num({e}.m.iter().flatten().map(|x| {}).collect())", l("x".into()))
                        }
                        b => {
                            let cs = comps(b);
                            format!(
                                "{rt}::FmtArg::Num(vec![{}, {}, {}])",
                                l(format!("{e}.{}", cs[0])),
                                l(format!("{e}.{}", cs[1])),
                                l(format!("{e}.{}", cs[2]))
                            )
                        }
                    });
                }
                let call = format!("{rt}::format_rsl({}, &[{}])", a(0), fa.join(", "));
                if builtin == Builtin::Printf {
                    let guard = if self.full { "true".to_string() } else { format!("{}.any()", self.mask) };
                    format!("if {guard} {{ print!(\"{{}}\", {call}); }}")
                } else {
                    format!("&*{}", self.leak_string(&call))
                }
            }
            Builtin::Match => {
                let rt = self.opts.runtime.clone();
                format!(
                    "if {rt}::simple_match({}, {}) {{ {} }} else {{ {} }}",
                    a(0),
                    a(1),
                    self.k(1.0, r),
                    self.k(0.0, r)
                )
            }
            Builtin::Surface
            | Builtin::LightSource
            | Builtin::Displacement
            | Builtin::Atmosphere
            | Builtin::Incident
            | Builtin::Opposite
            | Builtin::Attribute
            | Builtin::Option
            | Builtin::RendererInfo
            | Builtin::TextureInfo => self.k(0.0, r),
            Builtin::ShaderName => "\"\"".to_string(),
            Builtin::Depth => {
                return Err(self.err(span, "`depth` reached the back end: the front end lowers it to a transform"))
            }
            Builtin::RayInfo => self.k(0.0, r),
            // Outside a scene: camera rays, nothing occludes, no indirect or caustic light,
            // nothing blocks transmission (as the interpreter).
            Builtin::RayLevel | Builtin::IsShadowRay | Builtin::IsIndirectRay | Builtin::Occlusion => self.k(0.0, r),
            Builtin::IndirectDiffuse | Builtin::Caustic => "Color::zero()".to_string(),
            Builtin::Transmission => "Color::splat(F::c(1.0))".to_string(),
            Builtin::FilteredPulse => format!("filteredpulse({}, {}, {})", a(0), a(1), a(2)),
        };
        Ok(e)
    }

    /// Writes `value` (an expression in `Lane`/`Scalar` matching the slot) to output slot `s`.
    fn write_out(&mut self, s: SlotId, value: &str, vbase: BaseType) {
        let var = self.slot_var(s);
        let st = self.f.slot(s).ty;
        let r = self.sr[s.0 as usize];
        let v =
            if vbase.is_triple() && st.base.is_triple() && (vbase == BaseType::Color) != (st.base == BaseType::Color) {
                if st.base == BaseType::Color {
                    format!("({value}).to_color()")
                } else {
                    format!("({value}).to_vec()")
                }
            } else if vbase == BaseType::Float && st.base.is_triple() {
                format!("{}::splat({value})", tri_ty(st.base))
            } else {
                value.to_string()
            };
        self.assign(&var, &v, r);
    }

    /// A call's output value (computed in representation `r`) for slot `s`.
    fn out_value(&self, e: &str, r: Repr, s: SlotId, base: BaseType) -> String {
        if r == self.sr[s.0 as usize] || r == Repr::Lane {
            e.to_string()
        } else {
            let t = Type::new(base, Detail::Uniform);
            self.lift(e, t, false)
        }
    }

    /// An owned string computed once: bound to a fresh variable, returns its name.
    fn leak_string(&mut self, e: &str) -> String {
        let t = self.fresh("string");
        self.line(&format!("let {t}: String = {e};"));
        t
    }

    /// A triple argument as a `Vec3` (colours converted).
    fn as_vec(&self, v: Value, r: Repr) -> String {
        let e = self.val(v, r);
        if self.arg_ty(v).base == BaseType::Color {
            format!("({e}).to_vec()")
        } else {
            e
        }
    }
}
