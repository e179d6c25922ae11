//! Float and mask algebra on [`S`] and [`M`]: representation changes, arithmetic (fused
//! where anysl-core fuses), comparisons, selects, mask logic, and the composite numerics built
//! from them (dot, cross, clamp, step, smoothstep, fmod, mix, length).

use super::value::{Repr, M, S};
use super::Cg;
use inkwell::types::VectorType;
use inkwell::values::{BasicValueEnum, IntValue};
use inkwell::FloatPredicate;

impl<'c> Cg<'c, '_> {
    pub(super) fn splat(&self, v: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        if self.t.lanes == 1 {
            return v;
        }
        if let BasicValueEnum::FloatValue(f) = v {
            if let Some(c) = f.get_constant() {
                return self.fconst_r(c.0, Repr::V);
            }
        }
        let vty = self.f32t.vec_type(self.t.lanes);
        let undef = vty.get_undef();
        let ins = self.b.build_insert_element(undef, v, self.i32c(0), "").expect("insert");
        let zeros = self.cx.i32_type().vec_type(self.t.lanes).const_zero();
        self.b.build_shuffle_vector(ins, undef, zeros, "").expect("shuffle").into()
    }

    pub(super) fn splat_mask(&self, m: M<'c>) -> M<'c> {
        if !m.uni || self.t.lanes == 1 {
            return M { uni: false, v: m.v };
        }
        let vty = self.cx.bool_type().vec_type(self.t.lanes);
        let undef = vty.get_undef();
        let ins = self.b.build_insert_element(undef, m.v, self.i32c(0), "").expect("insert");
        let zeros = self.cx.i32_type().vec_type(self.t.lanes).const_zero();
        M { uni: false, v: self.b.build_shuffle_vector(ins, undef, zeros, "").expect("shuffle").into() }
    }

    fn zero_r(&self, r: Repr) -> BasicValueEnum<'c> {
        self.fconst_r(0.0, r)
    }

    /// `s` converted to representation `r`.
    pub(super) fn to(&self, s: S<'c>, r: Repr) -> S<'c> {
        if s.r == r {
            return s;
        }
        match (s.r, r) {
            (Repr::U, Repr::V) => S { r, v: self.splat(s.v), d: None },
            (Repr::U, Repr::D) => {
                let z = self.zero_r(Repr::V);
                S { r, v: self.splat(s.v), d: Some((z, z)) }
            }
            (Repr::V, Repr::D) => {
                let z = self.zero_r(Repr::V);
                S { r, v: s.v, d: Some((z, z)) }
            }
            (Repr::D, Repr::V) => S { r, v: s.v, d: None },
            (_, Repr::U) => {
                // Only reached for values the analysis proved uniform: lane 0 holds them.
                let v = if self.t.lanes == 1 {
                    s.v
                } else {
                    self.b.build_extract_element(s.v.into_vector_value(), self.i32c(0), "").expect("extract")
                };
                S { r, v, d: None }
            }
            _ => s,
        }
    }

    pub(super) fn arith(&self, op: char, a: BasicValueEnum<'c>, b: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        macro_rules! go {
            ($x:expr, $y:expr) => {
                match op {
                    '+' => self.b.build_float_add($x, $y, "").expect("op").into(),
                    '-' => self.b.build_float_sub($x, $y, "").expect("op").into(),
                    '*' => self.b.build_float_mul($x, $y, "").expect("op").into(),
                    _ => self.b.build_float_div($x, $y, "").expect("op").into(),
                }
            };
        }
        match (a, b) {
            (BasicValueEnum::FloatValue(x), BasicValueEnum::FloatValue(y)) => go!(x, y),
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => go!(x, y),
            _ => panic!("arith on mixed types {a:?} {b:?}"),
        }
    }
    fn fneg_raw(&self, a: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        match a {
            BasicValueEnum::FloatValue(x) => self.b.build_float_neg(x, "").expect("neg").into(),
            BasicValueEnum::VectorValue(x) => self.b.build_float_neg(x, "").expect("neg").into(),
            _ => panic!("neg"),
        }
    }
    pub(super) fn fcmp_raw(
        &self,
        p: FloatPredicate,
        a: BasicValueEnum<'c>,
        b: BasicValueEnum<'c>,
    ) -> BasicValueEnum<'c> {
        match (a, b) {
            (BasicValueEnum::FloatValue(x), BasicValueEnum::FloatValue(y)) => {
                self.b.build_float_compare(p, x, y, "").expect("cmp").into()
            }
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => {
                self.b.build_float_compare(p, x, y, "").expect("cmp").into()
            }
            _ => panic!("cmp"),
        }
    }
    pub(super) fn sel_raw(
        &self,
        m: BasicValueEnum<'c>,
        a: BasicValueEnum<'c>,
        b: BasicValueEnum<'c>,
    ) -> BasicValueEnum<'c> {
        match m {
            BasicValueEnum::IntValue(c) => self.b.build_select(c, a, b, "").expect("select"),
            BasicValueEnum::VectorValue(c) => self.b.build_select(c, a, b, "").expect("select"),
            _ => panic!("select"),
        }
    }
    pub(super) fn unary_intr(&self, name: &str, a: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        self.call_intr(name, &[a.get_type()], &[a])
    }

    pub(super) fn unify(&self, a: S<'c>, b: S<'c>) -> (S<'c>, S<'c>) {
        let r = a.r.max(b.r);
        (self.to(a, r), self.to(b, r))
    }

    pub(super) fn add(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        let (a, b) = self.unify(a, b);
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => Some((self.arith('+', ax, bx), self.arith('+', ay, by))),
            _ => None,
        };
        S { r: a.r, v: self.arith('+', a.v, b.v), d }
    }
    pub(super) fn sub(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        let (a, b) = self.unify(a, b);
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => Some((self.arith('-', ax, bx), self.arith('-', ay, by))),
            _ => None,
        };
        S { r: a.r, v: self.arith('-', a.v, b.v), d }
    }
    pub(super) fn mul(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        let (a, b) = self.unify(a, b);
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => {
                let dx = self.arith('+', self.arith('*', ax, b.v), self.arith('*', a.v, bx));
                let dy = self.arith('+', self.arith('*', ay, b.v), self.arith('*', a.v, by));
                Some((dx, dy))
            }
            _ => None,
        };
        S { r: a.r, v: self.arith('*', a.v, b.v), d }
    }
    /// `a·m + c` as the library's `ShadingFloat::mul_add`: fused (`llvm.fma`) where the
    /// library's is ([`anysl_simd::kernel_consts::FUSED_MUL_ADD`]), dual numbers fused in
    /// their value with `∂a·m + (a·∂m + ∂c)` as derivatives.
    pub(super) fn fma(&self, a: S<'c>, m: S<'c>, c: S<'c>) -> S<'c> {
        if !anysl_simd::kernel_consts::FUSED_MUL_ADD {
            return self.add(self.mul(a, m), c);
        }
        let r = a.r.max(m.r).max(c.r);
        let (a, m, c) = (self.to(a, r), self.to(m, r), self.to(c, r));
        let f = |x: BasicValueEnum<'c>, y: BasicValueEnum<'c>, z: BasicValueEnum<'c>| {
            self.call_intr("llvm.fma", &[x.get_type()], &[x, y, z])
        };
        let d = match (a.d, m.d, c.d) {
            (Some((ax, ay)), Some((mx, my)), Some((cx, cy))) => {
                Some((f(ax, m.v, f(a.v, mx, cx)), f(ay, m.v, f(a.v, my, cy))))
            }
            _ => None,
        };
        S { r, v: f(a.v, m.v, c.v), d }
    }
    fn finite_or_zero(&self, x: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        let ax = self.unary_intr("llvm.fabs", x);
        let inf = self.fconst_r(f64::INFINITY, Repr::V);
        let ok = self.fcmp_raw(FloatPredicate::OLT, ax, inf);
        self.sel_raw(ok, x, self.zero_r(Repr::V))
    }
    pub(super) fn div(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        let (a, b) = self.unify(a, b);
        let q = self.arith('/', a.v, b.v);
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => {
                let inv = self.arith('/', self.fconst_r(1.0, Repr::V), b.v);
                let dx = self.arith('*', self.arith('-', ax, self.arith('*', q, bx)), inv);
                let dy = self.arith('*', self.arith('-', ay, self.arith('*', q, by)), inv);
                Some((self.finite_or_zero(dx), self.finite_or_zero(dy)))
            }
            _ => None,
        };
        S { r: a.r, v: q, d }
    }
    pub(super) fn neg(&self, a: S<'c>) -> S<'c> {
        S { r: a.r, v: self.fneg_raw(a.v), d: a.d.map(|(x, y)| (self.fneg_raw(x), self.fneg_raw(y))) }
    }
    pub(super) fn constant_part(&self, r: Repr, v: BasicValueEnum<'c>) -> S<'c> {
        let z = self.zero_r(Repr::V);
        S { r, v, d: (r == Repr::D).then_some((z, z)) }
    }
    pub(super) fn floor(&self, a: S<'c>) -> S<'c> {
        self.constant_part(a.r, self.unary_intr("llvm.floor", a.v))
    }
    pub(super) fn ceil(&self, a: S<'c>) -> S<'c> {
        self.constant_part(a.r, self.unary_intr("llvm.ceil", a.v))
    }
    pub(super) fn abs(&self, a: S<'c>) -> S<'c> {
        let v = self.unary_intr("llvm.fabs", a.v);
        let d = a.d.map(|(x, y)| {
            let neg = self.fcmp_raw(FloatPredicate::OLT, a.v, self.zero_r(Repr::V));
            (self.sel_raw(neg, self.fneg_raw(x), x), self.sel_raw(neg, self.fneg_raw(y), y))
        });
        S { r: a.r, v, d }
    }
    pub(super) fn sqrt(&self, a: S<'c>) -> S<'c> {
        let s = self.unary_intr("llvm.sqrt", a.v);
        let d = a.d.map(|(x, y)| {
            let k = self.finite_or_zero(self.arith('/', self.fconst_r(0.5, Repr::V), s));
            (self.arith('*', x, k), self.arith('*', y, k))
        });
        S { r: a.r, v: s, d }
    }
    /// A constant of `x`'s shape (scalar or vector of the variant's lanes).
    fn const_like(&self, x: BasicValueEnum<'c>, v: f64) -> BasicValueEnum<'c> {
        self.fconst_r(v, if x.is_vector_value() { Repr::V } else { Repr::U })
    }
    /// `a·m + c` fused on raw values ([`Cg::fma`] without derivatives).
    fn fma_raw(&self, a: BasicValueEnum<'c>, m: BasicValueEnum<'c>, c: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        if anysl_simd::kernel_consts::FUSED_MUL_ADD {
            self.call_intr("llvm.fma", &[a.get_type()], &[a, m, c])
        } else {
            self.arith('+', self.arith('*', a, m), c)
        }
    }
    /// The hardware estimate of 1/√x that `anysl_core::rsqrt_f32` and the SIMD kernels start
    /// from — AVX-512's `vrsqrt14` or the SSE/AVX `rsqrt` ([`anysl_core::RSQRT_ESTIMATE_14`])
    /// — for a scalar or a vector of 4, 8 or 16 lanes.
    fn rsqrt_estimate(&self, x: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        if !cfg!(target_arch = "x86_64") {
            return self.arith('/', self.const_like(x, 1.0), self.unary_intr("llvm.sqrt", x));
        }
        if let BasicValueEnum::VectorValue(v) = x {
            if v.get_type().get_size() > self.t.native {
                let parts: Vec<_> =
                    self.packets_of(v).into_iter().map(|p| self.rsqrt_estimate(p.into()).into_vector_value()).collect();
                return self.concat(&parts).into();
            }
        }
        let v4 = self.f32t.vec_type(4);
        let ones8 = self.cx.i8_type().const_all_ones();
        let est14 = anysl_core::RSQRT_ESTIMATE_14;
        match x {
            BasicValueEnum::FloatValue(f) => {
                let zero = self.i32c(0);
                let xv: BasicValueEnum<'c> =
                    self.b.build_insert_element(v4.get_undef(), f, zero, "").expect("insert").into();
                let r = if est14 {
                    self.call_intr("llvm.x86.avx512.rsqrt14.ss", &[], &[xv, xv, v4.const_zero().into(), ones8.into()])
                } else {
                    self.call_intr("llvm.x86.sse.rsqrt.ss", &[], &[xv])
                };
                self.b.build_extract_element(r.into_vector_value(), zero, "").expect("extract")
            }
            BasicValueEnum::VectorValue(v) => {
                let n = v.get_type().get_size();
                let vz: BasicValueEnum<'c> = v.get_type().const_zero().into();
                match (n, est14) {
                    (4, true) => self.call_intr("llvm.x86.avx512.rsqrt14.ps.128", &[], &[x, vz, ones8.into()]),
                    (8, true) => self.call_intr("llvm.x86.avx512.rsqrt14.ps.256", &[], &[x, vz, ones8.into()]),
                    (16, true) => self.call_intr(
                        "llvm.x86.avx512.rsqrt14.ps.512",
                        &[],
                        &[x, vz, self.cx.i16_type().const_all_ones().into()],
                    ),
                    (4, false) => self.call_intr("llvm.x86.sse.rsqrt.ps", &[], &[x]),
                    (8, false) => self.call_intr("llvm.x86.avx.rsqrt.ps.256", &[], &[x]),
                    (16, false) => {
                        // Two 8-lane halves, as the library's 16 lanes without AVX-512.
                        let half = |lo: u32| {
                            let idx: Vec<_> = (lo..lo + 8).map(|i| self.i32c(u64::from(i))).collect();
                            let h = self
                                .b
                                .build_shuffle_vector(v, v.get_type().get_undef(), VectorType::const_vector(&idx), "")
                                .expect("shuffle");
                            self.call_intr("llvm.x86.avx.rsqrt.ps.256", &[], &[h.into()]).into_vector_value()
                        };
                        let (a, b) = (half(0), half(8));
                        let idx: Vec<_> = (0..16).map(|i| self.i32c(i)).collect();
                        self.b.build_shuffle_vector(a, b, VectorType::const_vector(&idx), "").expect("shuffle").into()
                    }
                    _ => panic!("rsqrt estimate of {n} lanes"),
                }
            }
            _ => panic!("rsqrt of a non-float"),
        }
    }
    /// `ShadingFloat::rsqrt` as `f32` and its SIMD types compute it (`anysl_core::rsqrt_f32`):
    /// the estimate, one Newton step `y + y/2·(1 - (x·y)·y)`, the estimate where that gives
    /// NaN, subnormal inputs scaled by 2^24 for the 12-bit estimate; dual numbers with the
    /// derivative `-r³/2` (0 where not finite), as `anysl-ad`.
    pub(super) fn rsqrt(&self, a: S<'c>) -> S<'c> {
        let x = a.v;
        let c = |v: f64| self.const_like(x, v);
        let legacy = !anysl_core::RSQRT_ESTIMATE_14;
        let tiny = legacy.then(|| {
            self.fcmp_raw(FloatPredicate::OLT, self.unary_intr("llvm.fabs", x), c(f64::from(f32::MIN_POSITIVE)))
        });
        let xs = match tiny {
            Some(t) => self.sel_raw(t, self.arith('*', x, c(16_777_216.0)), x),
            None => x,
        };
        let y = self.rsqrt_estimate(xs);
        let t = self.arith('*', xs, y);
        let e = self.fma_raw(self.fneg_raw(t), y, c(1.0));
        let r = self.fma_raw(self.arith('*', y, c(0.5)), e, y);
        let r = self.sel_raw(self.fcmp_raw(FloatPredicate::UNO, r, r), y, r);
        let r = match tiny {
            Some(t) => self.sel_raw(t, self.arith('*', r, c(4096.0)), r),
            None => r,
        };
        let d = a.d.map(|(dx, dy)| {
            let k = self.arith('*', self.arith('*', self.arith('*', c(-0.5), r), r), r);
            let k = self.finite_or_zero(k);
            (self.arith('*', dx, k), self.arith('*', dy, k))
        });
        S { r: a.r, v: r, d }
    }
    pub(super) fn minmax(&self, a: S<'c>, b: S<'c>, max: bool) -> S<'c> {
        let (a, b) = self.unify(a, b);
        let v = if self.t.lanes == 1 {
            // `f32::max` / `f32::min`.
            let name = if max { "llvm.maxnum" } else { "llvm.minnum" };
            self.call_intr(name, &[a.v.get_type()], &[a.v, b.v])
        } else {
            // The SIMD library's: `a` NaN → `b`; else x86's `maxps(b, a)` (`b > a ? b : a`,
            // ties to `a`) — uniform operands too, which the library computes as splats.
            let p = if max { FloatPredicate::OGT } else { FloatPredicate::OLT };
            let hw = self.sel_raw(self.fcmp_raw(p, b.v, a.v), b.v, a.v);
            self.sel_raw(self.fcmp_raw(FloatPredicate::UNO, a.v, a.v), b.v, hw)
        };
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => {
                // Derivatives of the operand chosen; ties take `a` (anysl-ad).
                let lt = if max {
                    self.fcmp_raw(FloatPredicate::OLT, a.v, b.v)
                } else {
                    self.fcmp_raw(FloatPredicate::OLT, b.v, a.v)
                };
                let nan = self.fcmp_raw(FloatPredicate::UNO, a.v, a.v);
                let take = self.mor(M { uni: false, v: lt }, M { uni: false, v: nan }).v;
                Some((self.sel_raw(take, bx, ax), self.sel_raw(take, by, ay)))
            }
            _ => None,
        };
        S { r: a.r, v, d }
    }
    pub(super) fn cmp(&self, p: FloatPredicate, a: S<'c>, b: S<'c>) -> M<'c> {
        let (a, b) = self.unify(a, b);
        M { uni: a.r == Repr::U, v: self.fcmp_raw(p, a.v, b.v) }
    }
    /// `m ? a : b`.
    pub(super) fn sel(&self, m: M<'c>, a: S<'c>, b: S<'c>) -> S<'c> {
        let (mut a, mut b) = self.unify(a, b);
        let m = if !m.uni && a.r == Repr::U {
            a = self.to(a, Repr::V);
            b = self.to(b, Repr::V);
            m
        } else if m.uni && a.r != Repr::U {
            self.splat_mask(m)
        } else {
            m
        };
        let d = match (a.d, b.d) {
            (Some((ax, ay)), Some((bx, by))) => Some((self.sel_raw(m.v, ax, bx), self.sel_raw(m.v, ay, by))),
            _ => None,
        };
        S { r: a.r, v: self.sel_raw(m.v, a.v, b.v), d }
    }

    fn munify(&self, a: M<'c>, b: M<'c>) -> (M<'c>, M<'c>) {
        if a.uni == b.uni {
            (a, b)
        } else {
            (self.splat_mask(a), self.splat_mask(b))
        }
    }
    pub(super) fn mand(&self, a: M<'c>, b: M<'c>) -> M<'c> {
        let (a, b) = self.munify(a, b);
        let v = match (a.v, b.v) {
            (BasicValueEnum::IntValue(x), BasicValueEnum::IntValue(y)) => {
                self.b.build_and(x, y, "").expect("and").into()
            }
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => {
                self.b.build_and(x, y, "").expect("and").into()
            }
            _ => panic!("and"),
        };
        M { uni: a.uni, v }
    }
    pub(super) fn mor(&self, a: M<'c>, b: M<'c>) -> M<'c> {
        let (a, b) = self.munify(a, b);
        let v = match (a.v, b.v) {
            (BasicValueEnum::IntValue(x), BasicValueEnum::IntValue(y)) => self.b.build_or(x, y, "").expect("or").into(),
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => {
                self.b.build_or(x, y, "").expect("or").into()
            }
            _ => panic!("or"),
        };
        M { uni: a.uni, v }
    }
    pub(super) fn mxor(&self, a: M<'c>, b: M<'c>) -> M<'c> {
        let (a, b) = self.munify(a, b);
        let v = match (a.v, b.v) {
            (BasicValueEnum::IntValue(x), BasicValueEnum::IntValue(y)) => {
                self.b.build_xor(x, y, "").expect("xor").into()
            }
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => {
                self.b.build_xor(x, y, "").expect("xor").into()
            }
            _ => panic!("xor"),
        };
        M { uni: a.uni, v }
    }
    pub(super) fn mnot(&self, a: M<'c>) -> M<'c> {
        let v = match a.v {
            BasicValueEnum::IntValue(x) => self.b.build_not(x, "").expect("not").into(),
            BasicValueEnum::VectorValue(x) => self.b.build_not(x, "").expect("not").into(),
            _ => panic!("not"),
        };
        M { uni: a.uni, v }
    }
    pub(super) fn msel(&self, c: M<'c>, a: M<'c>, b: M<'c>) -> M<'c> {
        // (c & a) | (!c & b), as Mask::select_mask.
        self.mor(self.mand(c, a), self.mand(self.mnot(c), b))
    }
    /// Some lane set (an `i1`).
    pub(super) fn any(&self, m: M<'c>) -> IntValue<'c> {
        match m.v {
            BasicValueEnum::IntValue(x) => x,
            BasicValueEnum::VectorValue(x) => {
                self.call_intr("llvm.vector.reduce.or", &[x.get_type().into()], &[x.into()]).into_int_value()
            }
            _ => panic!("any"),
        }
    }

    /// `Vec3::dot`: `x·x' + (y·y' + z·z')`, fused.
    pub(super) fn dot(&self, a: &[S<'c>], b: &[S<'c>]) -> S<'c> {
        self.fma(a[0], b[0], self.fma(a[1], b[1], self.mul(a[2], b[2])))
    }
    pub(super) fn cross(&self, a: &[S<'c>], b: &[S<'c>]) -> Vec<S<'c>> {
        vec![
            self.sub(self.mul(a[1], b[2]), self.mul(a[2], b[1])),
            self.sub(self.mul(a[2], b[0]), self.mul(a[0], b[2])),
            self.sub(self.mul(a[0], b[1]), self.mul(a[1], b[0])),
        ]
    }
    pub(super) fn clamp(&self, x: S<'c>, lo: S<'c>, hi: S<'c>) -> S<'c> {
        self.minmax(self.minmax(x, lo, true), hi, false)
    }
    pub(super) fn step(&self, e: S<'c>, x: S<'c>) -> S<'c> {
        let lt = self.cmp(FloatPredicate::OLT, x, e);
        let r = e.r.max(x.r);
        let (z, o) = (self.to(self.fc(0.0), r), self.to(self.fc(1.0), r));
        self.sel(lt, z, o)
    }
    pub(super) fn smoothstep(&self, e0: S<'c>, e1: S<'c>, x: S<'c>) -> S<'c> {
        let w = self.sub(e1, e0);
        let degenerate = self.cmp(FloatPredicate::OEQ, w, self.fc(0.0));
        let den = self.sel(degenerate, self.fc(1.0), w);
        let t = self.clamp(self.div(self.sub(x, e0), den), self.fc(0.0), self.fc(1.0));
        let s = self.mul(self.mul(t, t), self.sub(self.fc(3.0), self.mul(self.fc(2.0), t)));
        self.sel(degenerate, self.step(e0, x), s)
    }
    /// `fmod` as anysl-core defines it (result in `[0, b)`, 0 for `b = 0`).
    pub(super) fn fmod(&self, a: S<'c>, b: S<'c>) -> S<'c> {
        let z = self.fc(0.0);
        let bz = self.cmp(FloatPredicate::OEQ, b, z);
        let bb = self.sel(bz, self.fc(1.0), b);
        let r = self.sub(a, self.mul(bb, self.floor(self.div(a, bb))));
        let fold = self.mand(self.cmp(FloatPredicate::OGE, r, bb), self.cmp(FloatPredicate::OGT, bb, z));
        let r = self.sel(fold, self.sub(r, bb), r);
        self.sel(bz, z, r)
    }
    pub(super) fn mix(&self, a: S<'c>, b: S<'c>, t: S<'c>) -> S<'c> {
        self.add(a, self.mul(t, self.sub(b, a)))
    }
    pub(super) fn length(&self, a: &[S<'c>]) -> S<'c> {
        self.sqrt(self.dot(a, a))
    }
}
