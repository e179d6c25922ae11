//! The built-in functions: [`Cg::builtin`] matches on [`anysl_rsl::builtins::Builtin`] with
//! no catch-all arm (a built-in added to the enum does not compile here until it is handled),
//! and the geometric helpers (refract, fresnel, reflect, normalize) of its arms.

use super::call::space_index;
use super::noise;
use super::value::{err, CgError, Repr, Val, M, R, S};
use super::Cg;
use crate::rt::Host;
use crate::rt::{self, RtKind};
use anysl_rsl::builtins::Builtin;
use anysl_rsl::ir::{Global, SlotId, Value};
use anysl_rsl::types::BaseType;
use inkwell::values::BasicValueEnum;
use inkwell::FloatPredicate;

impl<'c> Cg<'c, '_> {
    #[allow(clippy::too_many_lines)]
    pub(super) fn builtin(
        &mut self,
        v: Value,
        builtin: Builtin,
        outputs: &[Option<SlotId>],
        args: &[Val<'c>],
    ) -> R<Vec<Val<'c>>> {
        let func = self.func;
        let inst = func.inst(v);
        let n = args.len();
        let aty = |i: usize| inst.args.get(i).map_or(BaseType::Void, |a| func.inst(*a).ty.base);
        let aarr = |i: usize| inst.args.get(i).and_then(|a| func.inst(*a).ty.array);
        let rw = inst.ty.base.components().max(1);
        let nums = |cg: &Self, i: usize| cg.as_nums(&args[i]);
        let un_rt = |cg: &mut Self, aux: u32| -> R<Val<'c>> {
            let x = cg.as_nums(&args[0])?;
            let mut out = Vec::new();
            for s in x {
                out.extend(cg.rt_call(RtKind::Un, aux, &[s], 1, false));
            }
            Ok(Val::Num(out))
        };
        let bin_rt = |cg: &mut Self, aux: u32, w: usize| -> R<Val<'c>> {
            let all: Vec<Vec<S<'c>>> = (0..args.len()).map(|i| cg.as_nums(&args[i])).collect::<R<_>>()?;
            let mut out = Vec::new();
            for c in 0..w {
                let xs: Vec<S<'c>> =
                    all.iter().map(|a| if a.len() == 1 { a[0] } else { a[c.min(a.len() - 1)] }).collect();
                out.extend(cg.rt_call(RtKind::Bin, aux, &xs, 1, false));
            }
            Ok(Val::Num(out))
        };
        let noise_dims = |i0: usize, i1: usize| -> Option<u32> {
            let tys: Vec<BaseType> = (i0..i1).map(aty).collect();
            match tys.as_slice() {
                [BaseType::Float] => Some(1),
                [BaseType::Float, BaseType::Float] => Some(2),
                [p] if p.is_triple() => Some(3),
                [p, BaseType::Float] if p.is_triple() => Some(4),
                _ => None,
            }
        };
        let flat_args = |cg: &Self, r: std::ops::Range<usize>| -> R<Vec<S<'c>>> {
            let mut all = Vec::new();
            for i in r {
                all.extend(cg.as_nums(&args[i])?);
            }
            Ok(all)
        };
        let res: Val<'c> = match builtin {
            Builtin::Abs => Val::Num(nums(self, 0)?.into_iter().map(|s| self.abs(s)).collect()),
            Builtin::Floor => Val::Num(nums(self, 0)?.into_iter().map(|s| self.floor(s)).collect()),
            Builtin::Ceil => Val::Num(nums(self, 0)?.into_iter().map(|s| self.ceil(s)).collect()),
            Builtin::Sqrt => Val::Num(nums(self, 0)?.into_iter().map(|s| self.sqrt(s)).collect()),
            Builtin::Sign => Val::Num(
                nums(self, 0)?
                    .into_iter()
                    .map(|x| {
                        let r = if x.r == Repr::D { Repr::V } else { x.r };
                        let z = self.to(self.fc(0.0), r);
                        let gt = self.cmp(FloatPredicate::OGT, x, self.fc(0.0));
                        let lt = self.cmp(FloatPredicate::OLT, x, self.fc(0.0));
                        let inner = self.sel(lt, self.to(self.fc(-1.0), r), z);
                        let v = self.sel(gt, self.to(self.fc(1.0), r), inner);
                        self.to(v, x.r)
                    })
                    .collect(),
            ),
            Builtin::Round => Val::Num(
                nums(self, 0)?
                    .into_iter()
                    .map(|x| self.constant_part(x.r, self.unary_intr("llvm.round", x.v)))
                    .collect(),
            ),
            Builtin::InverseSqrt => Val::Num(nums(self, 0)?.into_iter().map(|x| self.rsqrt(x)).collect()),
            Builtin::Exp => un_rt(self, rt::Un::Exp as u32)?,
            Builtin::Log if n == 1 => un_rt(self, rt::Un::Log as u32)?,
            Builtin::Log if n == 2 => bin_rt(self, rt::Bin::LogBase as u32, nums(self, 0)?.len())?,
            Builtin::Sin => un_rt(self, rt::Un::Sin as u32)?,
            Builtin::Cos => un_rt(self, rt::Un::Cos as u32)?,
            Builtin::Tan => un_rt(self, rt::Un::Tan as u32)?,
            Builtin::Asin => un_rt(self, rt::Un::Asin as u32)?,
            Builtin::Acos => un_rt(self, rt::Un::Acos as u32)?,
            Builtin::Atan if n == 1 => un_rt(self, rt::Un::Atan as u32)?,
            Builtin::Atan if n == 2 => bin_rt(self, rt::Bin::Atan2 as u32, 1)?,
            Builtin::Radians => Val::Num(
                nums(self, 0)?.into_iter().map(|s| self.mul(s, self.fc(std::f64::consts::PI / 180.0))).collect(),
            ),
            Builtin::Degrees => Val::Num(
                nums(self, 0)?.into_iter().map(|s| self.mul(s, self.fc(180.0 / std::f64::consts::PI))).collect(),
            ),
            Builtin::Pow if n == 2 => bin_rt(self, rt::Bin::Pow as u32, nums(self, 0)?.len())?,
            Builtin::Mod if n == 2 => {
                let all = vec![nums(self, 0)?, nums(self, 1)?];
                let w = all[0].len();
                Val::Num(self.cwise(&all, w, |cg, x| cg.fmod(x[0], x[1])))
            }
            Builtin::Min | Builtin::Max if n >= 2 => {
                let all: Vec<Vec<S<'c>>> = (0..n).map(|i| nums(self, i)).collect::<R<_>>()?;
                let max = builtin == Builtin::Max;
                Val::Num(self.cwise(&all, rw, |cg, x| {
                    let mut r = cg.minmax(x[0], x[1], max);
                    for &z in &x[2..] {
                        r = cg.minmax(r, z, max);
                    }
                    r
                }))
            }
            Builtin::Step if n == 2 => {
                let all = vec![nums(self, 0)?, nums(self, 1)?];
                Val::Num(self.cwise(&all, rw, |cg, x| cg.step(x[0], x[1])))
            }
            Builtin::Clamp if n == 3 => {
                let all: Vec<Vec<S<'c>>> = (0..3).map(|i| nums(self, i)).collect::<R<_>>()?;
                Val::Num(self.cwise(&all, rw, |cg, x| cg.clamp(x[0], x[1], x[2])))
            }
            Builtin::Mix if n == 3 => {
                let all: Vec<Vec<S<'c>>> = (0..3).map(|i| nums(self, i)).collect::<R<_>>()?;
                Val::Num(self.cwise(&all, rw, |cg, x| cg.mix(x[0], x[1], x[2])))
            }
            Builtin::SmoothStep if n == 3 => {
                let all: Vec<Vec<S<'c>>> = (0..3).map(|i| nums(self, i)).collect::<R<_>>()?;
                Val::Num(self.cwise(&all, rw, |cg, x| cg.smoothstep(x[0], x[1], x[2])))
            }
            Builtin::Length => {
                let a = nums(self, 0)?;
                Val::Num(vec![self.length(&a)])
            }
            Builtin::Distance => {
                let (a, b) = (nums(self, 0)?, nums(self, 1)?);
                let d: Vec<S<'c>> = (0..3).map(|c| self.sub(a[c], b[c])).collect();
                Val::Num(vec![self.length(&d)])
            }
            Builtin::Normalize => {
                let a = nums(self, 0)?;
                if a.iter().any(|s| s.r == Repr::D) {
                    Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Normalize as u32, &a, 3, false))
                } else {
                    Val::Num(self.normalize(&a))
                }
            }
            Builtin::FaceForward => {
                let (nn, i) = (nums(self, 0)?, nums(self, 1)?);
                let nref = if n == 3 { nums(self, 2)? } else { self.read_global(Global::Ng) };
                let flip = self.cmp(FloatPredicate::OGT, self.dot(&i, &nref), self.fc(0.0));
                Val::Num(nn.iter().map(|&c| self.sel(flip, self.neg(c), c)).collect())
            }
            Builtin::Reflect => {
                let (i, nn) = (nums(self, 0)?, nums(self, 1)?);
                Val::Num(self.reflect(&i, &nn))
            }
            Builtin::Refract => {
                let a = flat_args(self, 0..3)?;
                if a.iter().any(|s| s.r == Repr::D) {
                    Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Refract as u32, &a, 3, false))
                } else {
                    Val::Num(self.refract(&a[0..3], &a[3..6], a[6]))
                }
            }
            Builtin::Fresnel => {
                let a = flat_args(self, 0..3)?;
                let r = if a.iter().any(|s| s.r == Repr::D) {
                    self.rt_call(RtKind::Geo, rt::Geo::Fresnel as u32, &a, 8, false)
                } else {
                    self.fresnel(&a[0..3], &a[3..6], a[6])
                };
                // Outputs in argument order: kr, kt[, R, T].
                let mut outs = Vec::new();
                let parts: [Vec<S<'c>>; 4] = [vec![r[0]], vec![r[1]], r[2..5].to_vec(), r[5..8].to_vec()];
                for (k, o) in outputs.iter().enumerate() {
                    if o.is_some() && k >= 3 {
                        outs.push(Val::Num(parts[(k - 3).min(3)].clone()));
                    }
                }
                let mut all = vec![Val::Void];
                all.extend(outs);
                return Ok(all);
            }
            Builtin::PtLineD => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::PtLineD as u32, &flat_args(self, 0..3)?, 1, false))
            }
            Builtin::Rotate if aty(0).is_triple() => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Rotate as u32, &flat_args(self, 0..4)?, 3, false))
            }
            Builtin::Rotate => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::RotateM as u32, &flat_args(self, 0..3)?, 16, false))
            }
            Builtin::Translate => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Translate as u32, &flat_args(self, 0..2)?, 16, false))
            }
            Builtin::Scale => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::ScaleM as u32, &flat_args(self, 0..2)?, 16, false))
            }
            Builtin::SpecularBrdf => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::SpecularBrdf as u32, &flat_args(self, 0..4)?, 3, false))
            }
            Builtin::XComp | Builtin::YComp | Builtin::ZComp => {
                let c = match builtin {
                    Builtin::XComp => 0,
                    Builtin::YComp => 1,
                    _ => 2,
                };
                Val::Num(vec![nums(self, 0)?[c]])
            }
            Builtin::SetXComp | Builtin::SetYComp | Builtin::SetZComp => {
                let c = match builtin {
                    Builtin::SetXComp => 0,
                    Builtin::SetYComp => 1,
                    _ => 2,
                };
                if let Some(Some(s)) = outputs.first() {
                    let x = nums(self, 0)?[0];
                    let m = self.load_mask(self.st().mask);
                    let m = if self.slots[s.0 as usize].r == Repr::U { None } else { Some(m) };
                    self.store_comp(*s, c, x, m);
                }
                Val::Void
            }
            Builtin::Comp if aty(0) == BaseType::Matrix => {
                let m = nums(self, 0)?;
                let (r, c) = (self.const_index(inst.args[1])?, self.const_index(inst.args[2])?);
                Val::Num(vec![m[r.min(3) * 4 + c.min(3)]])
            }
            Builtin::Comp => {
                let vv = nums(self, 0)?;
                let i = self.floor(nums(self, 1)?[0]);
                let i = self.minmax(self.minmax(i, self.fc(0.0), true), self.fc(2.0), false);
                let is0 = self.cmp(FloatPredicate::OEQ, i, self.fc(0.0));
                let is1 = self.cmp(FloatPredicate::OEQ, i, self.fc(1.0));
                let r = self.sel(is1, vv[1], vv[2]);
                Val::Num(vec![self.sel(is0, vv[0], r)])
            }
            Builtin::SetComp => {
                let Some(Some(s)) = outputs.first() else { return Ok(vec![Val::Void]) };
                let is_matrix = func.slot(*s).ty.base == BaseType::Matrix;
                let uni = self.slots[s.0 as usize].r == Repr::U;
                let m = self.load_mask(self.st().mask);
                if is_matrix {
                    let (r, c) = (self.const_index(inst.args[0])?, self.const_index(inst.args[1])?);
                    let x = nums(self, 2)?[0];
                    self.store_comp(*s, r.min(3) * 4 + c.min(3), x, if uni { None } else { Some(m) });
                } else {
                    let i = self.floor(nums(self, 0)?[0]);
                    let x = nums(self, 1)?[0];
                    for c in 0..3 {
                        let hit = self.cmp(FloatPredicate::OEQ, i, self.fc(c as f64));
                        let hm = if uni { hit } else { self.mand(m, hit) };
                        self.store_comp(*s, c, x, Some(hm));
                    }
                }
                Val::Void
            }
            Builtin::Transform | Builtin::VTransform | Builtin::NTransform => {
                let last = n - 1;
                let x = nums(self, last)?;
                match (0..n).find(|&i| aty(i) == BaseType::Matrix) {
                    Some(mi) => {
                        let aux = match (builtin, inst.ty.base) {
                            (Builtin::VTransform, _) | (_, BaseType::Vector) => rt::Geo::XformVector as u32,
                            (Builtin::NTransform, _) | (_, BaseType::Normal) => rt::Geo::XformNormal as u32,
                            _ => rt::Geo::XformPoint as u32,
                        };
                        let mut x = x;
                        if (0..n).any(|i| aty(i) == BaseType::String) {
                            // transform(fromspace, m, p): from `fromspace` to current, then by `m`.
                            let mut all = self.space_matrix(rt::SPACE_TO_CURRENT, &Self::as_str(&args[0]));
                            all.extend(x);
                            x = self.rt_call(RtKind::Geo, aux, &all, 3, false);
                        }
                        let mut all = nums(self, mi)?;
                        all.extend(x);
                        Val::Num(self.rt_call(RtKind::Geo, aux, &all, 3, false))
                    }
                    None => {
                        let aux = match (builtin, inst.ty.base) {
                            (Builtin::VTransform, _) | (_, BaseType::Vector) => rt::Geo::XformVector as u32,
                            (Builtin::NTransform, _) | (_, BaseType::Normal) => rt::Geo::XformNormal as u32,
                            _ => rt::Geo::XformPoint as u32,
                        };
                        let mut all = if n == 3 {
                            let names =
                                format!("{}{}{}", Self::as_str(&args[0]), rt::SPACE_SEPARATOR, Self::as_str(&args[1]));
                            self.space_matrix(rt::SPACE_BETWEEN, &names)
                        } else {
                            self.space_matrix(rt::SPACE_FROM_CURRENT, &Self::as_str(&args[0]))
                        };
                        all.extend(x);
                        Val::Num(self.rt_call(RtKind::Geo, aux, &all, 3, false))
                    }
                }
            }
            Builtin::CTransform => {
                let spaces = (0..n).filter(|&i| aty(i) == BaseType::String).count();
                let c = nums(self, spaces)?;
                let from = if spaces == 2 { space_index(&Self::as_str(&args[0])) } else { Some(0) };
                let to = space_index(&Self::as_str(&args[spaces - 1]));
                match (from, to) {
                    (Some(f), Some(t)) => {
                        Val::Num(self.rt_call(RtKind::Geo, rt::Geo::CTransform as u32 | f << 8 | t << 16, &c, 3, false))
                    }
                    _ => Val::Num(c),
                }
            }
            Builtin::Determinant => {
                Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Determinant as u32, &nums(self, 0)?, 1, false))
            }
            Builtin::Du | Builtin::Dv => {
                let x = nums(self, 0)?;
                let w = x.len() as u32;
                let idx = if builtin == Builtin::Du { Host::Du } else { Host::Dv };
                Val::Num(self.host_call(idx, w, &x, w as usize))
            }
            Builtin::Deriv => {
                let x = nums(self, 0)?;
                let w = x.len() as u32;
                let mut all = x;
                all.extend(nums(self, 1)?);
                Val::Num(self.host_call(Host::Deriv, w, &all, w as usize))
            }
            Builtin::Area => Val::Num(self.rt_call(RtKind::Geo, rt::Geo::Area as u32, &nums(self, 0)?, 1, true)),
            Builtin::CalculateNormal => Val::Num(self.host_call(Host::CalcNormal, 0, &nums(self, 0)?, 3)),
            Builtin::FilterWidth => {
                let x = nums(self, 0)?;
                let aux = if x.len() == 3 { rt::Geo::FilterWidthP as u32 } else { rt::Geo::FilterWidth as u32 };
                Val::Num(self.rt_call(RtKind::Geo, aux, &x, 1, true))
            }
            Builtin::FilterStep => {
                let nnum = (0..n).take_while(|&i| aty(i) != BaseType::String).count();
                let any_dual =
                    (0..nnum.min(3)).any(|i| matches!(&args[i], Val::Num(c) if c.iter().any(|s| s.r == Repr::D)));
                if nnum == 2 && !any_dual {
                    // No derivatives: the filter width is 0 and filterstep is step.
                    let (e, x) = (nums(self, 0)?[0], nums(self, 1)?[0]);
                    Val::Num(vec![self.step(e, x)])
                } else if nnum >= 3 {
                    Val::Num(self.rt_call(RtKind::Bin, rt::Bin::FilterStep3 as u32, &flat_args(self, 0..3)?, 1, true))
                } else {
                    Val::Num(self.rt_call(RtKind::Bin, rt::Bin::FilterStep as u32, &flat_args(self, 0..2)?, 1, true))
                }
            }
            Builtin::FilteredPulse => {
                let (e0, e1, x) = (nums(self, 0)?[0], nums(self, 1)?[0], nums(self, 2)?[0]);
                if [e0, e1, x].iter().any(|s| s.r == Repr::D) {
                    let a = self.rt_call(RtKind::Bin, rt::Bin::FilterStep as u32, &[e0, x], 1, true)[0];
                    let b = self.rt_call(RtKind::Bin, rt::Bin::FilterStep as u32, &[e1, x], 1, true)[0];
                    Val::Num(vec![self.sub(a, b)])
                } else {
                    // No derivatives: the filter width is 0 and the pulse is a difference of steps.
                    Val::Num(vec![self.sub(self.step(e0, x), self.step(e1, x))])
                }
            }
            Builtin::Noise | Builtin::SNoise | Builtin::CellNoise => {
                let dims = noise_dims(0, n).ok_or_else(|| CgError(format!("{builtin} arguments")))?;
                let kind = match builtin {
                    Builtin::Noise => noise::NoiseKind::Unsigned,
                    Builtin::SNoise => noise::NoiseKind::Signed,
                    _ => noise::NoiseKind::Cell,
                };
                let coords = flat_args(self, 0..n)?;
                debug_assert_eq!(coords.len(), dims as usize);
                // cellnoise is a hash of the cell: a few integer ops inline, where a call
                // would spill every live vector register; Perlin noise is inline on request.
                if self.t.inline_noise || kind == noise::NoiseKind::Cell {
                    Val::Num(self.noise_inline(kind, &coords, rw))
                } else {
                    // `noise` is `0.5 + 0.5·snoise` (`unsigned_noise`, the same two roundings
                    // here): one runtime kernel serves both.
                    let aux = rt::NoiseSel { kind: rt::NoiseOp::SNoise, dims, out: rw as u32, extra: 0 }.encode();
                    let s = self.rt_call(RtKind::Noise, aux, &coords, rw, false);
                    Val::Num(match kind {
                        noise::NoiseKind::Unsigned => {
                            let h = self.fc(0.5);
                            s.into_iter().map(|x| self.add(h, self.mul(h, x))).collect()
                        }
                        _ => s,
                    })
                }
            }
            Builtin::PNoise | Builtin::PSNoise => {
                let half = n / 2;
                let dims = noise_dims(0, half).ok_or_else(|| CgError(format!("{builtin} arguments")))?;
                let kind = if builtin == Builtin::PNoise { rt::NoiseOp::PNoise } else { rt::NoiseOp::PSNoise };
                let aux = rt::NoiseSel { kind, dims, out: rw as u32, extra: 0 }.encode();
                Val::Num(self.rt_call(RtKind::Noise, aux, &flat_args(self, 0..n)?, rw, false))
            }
            Builtin::Fbm | Builtin::Turbulence => {
                let dims = if aty(0).is_triple() { 3 } else { 1 };
                let used = 1;
                let kind = if builtin == Builtin::Fbm { rt::NoiseOp::Fbm } else { rt::NoiseOp::Turbulence };
                let extra = (n - used) as u32;
                let aux = rt::NoiseSel { kind, dims, out: 1, extra }.encode();
                Val::Num(self.rt_call(RtKind::Noise, aux, &flat_args(self, 0..n)?, 1, false))
            }
            Builtin::Random => Val::Num(self.host_call(Host::Random, rw as u32, &[], rw)),
            Builtin::Spline => {
                let basis = aty(0) == BaseType::String;
                let first = usize::from(basis);
                let bname = if basis { Self::as_str(&args[0]) } else { "catmull-rom".to_string() };
                let bi = anysl_core::stdlib::SplineBasis::from_name(&bname)
                    .and_then(|b| {
                        rt::SPLINE_BASES.iter().position(|n| {
                            anysl_core::stdlib::SplineBasis::from_name(n)
                                .is_some_and(|x| format!("{x:?}") == format!("{b:?}"))
                        })
                    })
                    .unwrap_or(0) as u32;
                let rest = first + 1..n;
                let (w, nk) = if rest.len() == 1 && aarr(first + 1).is_some() {
                    (aty(first + 1).components(), aarr(first + 1).unwrap_or(0) as usize)
                } else {
                    (rw, rest.len())
                };
                if nk > rt::MAX_KNOTS {
                    return err(format!("spline with {nk} knots (the JIT passes at most {})", rt::MAX_KNOTS));
                }
                let mut all = nums(self, first)?;
                all.extend(flat_args(self, rest)?);
                let aux = nk as u32 | bi << 8 | (w as u32) << 16;
                Val::Num(self.rt_call(RtKind::Spline, aux, &all, w, false))
            }
            Builtin::Ambient => Val::Num(self.light_call(Host::Ambient, 0, &[], 3)),
            Builtin::Diffuse => Val::Num(self.light_call(Host::Diffuse, 0, &nums(self, 0)?, 3)),
            Builtin::Specular => {
                let args = flat_args(self, 0..3)?;
                match self.lit_sums(&args) {
                    // specular ++ diffuse [++ ambient]; the call site keeps the sums.
                    Some(k) => Val::Num(self.light_call(Host::Specular, k, &args, 3 + 3 * k as usize)),
                    None => Val::Num(self.host_call(Host::Specular, 0, &args, 3)),
                }
            }
            Builtin::Phong => Val::Num(self.host_call(Host::Phong, 0, &flat_args(self, 0..3)?, 3)),
            Builtin::Trace => Val::Num(self.host_call(Host::Trace, 0, &flat_args(self, 0..2)?, 3)),
            Builtin::Concat => Val::Str(vec![args.iter().map(Self::as_str).collect()]),
            Builtin::Printf => Val::Void,
            Builtin::Match => {
                let (p, s) = (Self::as_str(&args[0]), Self::as_str(&args[1]));
                Val::Num(vec![self.fc(if anysl_rt::simple_match(&p, &s) { 1.0 } else { 0.0 })])
            }
            // Outside a scene: camera rays, nothing occludes, no indirect or caustic light,
            // nothing blocks transmission (as the interpreter).
            Builtin::RayInfo
            | Builtin::RayLevel
            | Builtin::IsShadowRay
            | Builtin::IsIndirectRay
            | Builtin::Occlusion => Val::Num(vec![self.fc(0.0)]),
            Builtin::IndirectDiffuse | Builtin::Caustic => Val::Num(vec![self.fc(0.0); 3]),
            Builtin::Transmission => Val::Num(vec![self.fc(1.0); 3]),
            // Arities the checker never produces.
            Builtin::Log
            | Builtin::Atan
            | Builtin::Pow
            | Builtin::Mod
            | Builtin::Min
            | Builtin::Max
            | Builtin::Step
            | Builtin::Clamp
            | Builtin::Mix
            | Builtin::SmoothStep => return err(format!("`{builtin}` with {n} arguments")),
            Builtin::Depth => return err("`depth` reached the back end: the front end lowers it to a transform"),
            // Strings are compile-time values in the JIT, and it has no texture host call.
            Builtin::Format | Builtin::Texture | Builtin::Environment | Builtin::Shadow => {
                return err(format!("built-in `{builtin}` is not supported by the JIT"))
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
            | Builtin::TextureInfo => Val::Num(vec![self.fc(0.0)]),
            Builtin::ShaderName => Val::Str(vec![String::new()]),
        };
        // Outputs not produced above keep their values.
        let mut all = vec![res];
        for o in outputs.iter().flatten() {
            let _ = o;
        }
        all.truncate(1);
        Ok(all)
    }

    /// anysl-core's `refract` for uniform and varying triples, operation for operation (dual
    /// triples use the runtime).
    fn refract(&self, i: &[S<'c>], n: &[S<'c>], eta: S<'c>) -> Vec<S<'c>> {
        let (one, zero) = (self.fc(1.0), self.fc(0.0));
        let idotn = self.dot(i, n);
        let k = self.sub(one, self.mul(self.mul(eta, eta), self.sub(one, self.mul(idotn, idotn))));
        let tir = self.cmp(FloatPredicate::OLT, k, zero);
        let s = self.add(self.mul(eta, idotn), self.sqrt(self.minmax(k, zero, true)));
        (0..3).map(|c| self.sel(tir, zero, self.sub(self.mul(i[c], eta), self.mul(n[c], s)))).collect()
    }

    /// anysl-core's `fresnel` for uniform and varying triples, operation for operation:
    /// `kr, kt, R, T` (dual triples use the runtime).
    fn fresnel(&self, i: &[S<'c>], n: &[S<'c>], eta: S<'c>) -> Vec<S<'c>> {
        let (one, zero) = (self.fc(1.0), self.fc(0.0));
        let iu = self.normalize(i);
        let c = self.minmax(self.abs(self.dot(&iu, n)), one, false);
        let inv_eta = self.div(one, eta);
        let g2 = self.add(self.sub(self.mul(inv_eta, inv_eta), one), self.mul(c, c));
        let tir = self.cmp(FloatPredicate::OLT, g2, zero);
        let g = self.sqrt(self.minmax(g2, zero, true));
        let (gpc, gmc) = (self.add(g, c), self.sub(g, c));
        let degenerate = self.mor(self.cmp(FloatPredicate::OLE, gpc, zero), tir);
        let a = self.div(gmc, self.sel(degenerate, one, gpc));
        let num = self.sub(self.mul(c, gpc), one);
        let den = self.add(self.mul(c, gmc), one);
        let b = self.div(num, self.sel(self.cmp(FloatPredicate::OEQ, den, zero), one, den));
        let half_a2 = self.mul(self.mul(self.mul(self.fc(0.5), a), a), self.add(one, self.mul(b, b)));
        let kr = self.sel(degenerate, one, self.minmax(half_a2, one, false));
        let kt = self.sub(one, kr);
        let mut out = vec![kr, kt];
        out.extend(self.reflect(&iu, n));
        out.extend(self.refract(&iu, n, eta));
        out
    }

    /// anysl-core's `reflect`: `i - n·(2·(i·n))`.
    fn reflect(&self, i: &[S<'c>], n: &[S<'c>]) -> Vec<S<'c>> {
        let k = self.mul(self.fc(2.0), self.dot(i, n));
        (0..3).map(|c| self.sub(i[c], self.mul(n[c], k))).collect()
    }

    /// `Vec3::normalize` for uniform and varying triples (dual triples use the runtime).
    pub(super) fn normalize(&self, a: &[S<'c>]) -> Vec<S<'c>> {
        let l2 = self.dot(a, a);
        // Zero lengths (1/√0 = inf) are among the lanes the rare path replaces, as in
        // anysl-core.
        let k = self.rsqrt(l2);
        let unit: Vec<S<'c>> = a.iter().map(|&c| self.mul(c, k)).collect();
        let lo = 2f64.powi(-120);
        let hi = 2f64.powi(120);
        let rescale =
            self.mor(self.cmp(FloatPredicate::OLT, l2, self.fc(lo)), self.cmp(FloatPredicate::OGT, l2, self.fc(hi)));
        // The rare path, normalize(v / max|c|), only when some lane needs it (as anysl-core).
        self.when_any(rescale, unit, |cg, unit| {
            let r = cg.normalize_rescaled(a);
            (0..3).map(|c| cg.sel(rescale, r[c], unit[c])).collect()
        })
    }

    /// `normalize(v / max|c|)` for the lanes whose squared length is out of range
    /// (`Vec3::normalize_rescaled`), emitted in place on the rare path. Not a call: x86-64
    /// preserves no vector register across one, so a call inside a light loop made the
    /// register allocator keep the loop's values in stack slots on the common path too.
    fn normalize_rescaled(&self, a: &[S<'c>]) -> Vec<S<'c>> {
        let r = a.iter().map(|s| s.r).max().unwrap_or(Repr::U);
        let a: Vec<S<'c>> = a.iter().map(|&s| S { r, v: self.to(s, r).v, d: None }).collect();
        let zero = self.fc(0.0);
        let m = self.minmax(self.minmax(self.abs(a[0]), self.abs(a[1]), true), self.abs(a[2]), true);
        let usable =
            self.mand(self.cmp(FloatPredicate::OGT, m, zero), self.cmp(FloatPredicate::OLT, m, self.fc(f64::INFINITY)));
        let den = self.sel(usable, m, self.fc(1.0));
        let w: Vec<S<'c>> = a.iter().map(|&c| self.div(c, den)).collect();
        let wl2 = self.dot(&w, &w);
        let wk = self.sel(self.cmp(FloatPredicate::OGT, wl2, zero), self.rsqrt(wl2), zero);
        w.iter().map(|&c| S { r, v: self.to(self.mul(c, wk), r).v, d: None }).collect()
    }

    /// `rare(common)` where some lane of `m` is set, else `common`: a branch around code that
    /// is needed only for unusual lanes (the values are merged with phis).
    pub(super) fn when_any(
        &self,
        m: M<'c>,
        common: Vec<S<'c>>,
        rare: impl FnOnce(&Self, &[S<'c>]) -> Vec<S<'c>>,
    ) -> Vec<S<'c>> {
        let f = self.cur_fn();
        let from = self.b.get_insert_block().expect("positioned");
        let rare_bb = self.cx.append_basic_block(f, "rare");
        let join = self.cx.append_basic_block(f, "join");
        self.b.build_conditional_branch(self.any(m), rare_bb, join).expect("br");
        self.b.position_at_end(rare_bb);
        let r: Vec<S<'c>> = rare(self, &common).into_iter().zip(&common).map(|(x, c)| self.to(x, c.r)).collect();
        let rare_end = self.b.get_insert_block().expect("positioned");
        self.b.build_unconditional_branch(join).expect("br");
        self.b.position_at_end(join);
        let phi = |a: BasicValueEnum<'c>, b: BasicValueEnum<'c>| -> BasicValueEnum<'c> {
            let p = self.b.build_phi(a.get_type(), "").expect("phi");
            p.add_incoming(&[(&a, from), (&b, rare_end)]);
            p.as_basic_value()
        };
        common
            .iter()
            .zip(&r)
            .map(|(c, x)| S {
                r: c.r,
                v: phi(c.v, x.v),
                d: match (c.d, x.d) {
                    (Some((cx, cy)), Some((xx, xy))) => Some((phi(cx, xx), phi(cy, xy))),
                    _ => None,
                },
            })
            .collect()
    }
}
