//! The transcendental functions of the SIMD float types emitted inline as LLVM IR, instead of
//! a call into the runtime library that spills every live vector register: the algorithms of
//! `anysl-simd`'s vector kernels (its `src/math.rs`), operation for operation and with its
//! constants ([`anysl_simd::kernel_consts`]), so the JIT computes the library's bits. Lanes
//! whose trigonometric argument is too large for the vector reduction go, as in the library,
//! through std's `f32` function ([`crate::rt::rt_trig_lanes`], on a branch taken only when
//! such a lane exists).
//!
//! Only varying values of the vector variants take this path; `f32` (std's functions), uniform
//! values (computed once, as `f32`) and dual numbers (their derivative rules) call the
//! runtime library as before.

use super::{Cg, Repr, S};
use crate::rt::{self, RtKind};
use anysl_simd::kernel_consts as kc;
use inkwell::types::VectorType;
use inkwell::values::{IntValue, VectorValue};
use inkwell::{AddressSpace, FloatPredicate, IntPredicate};

/// A transcendental function the code generator can emit inline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum MathFn {
    /// `sin x`
    Sin,
    /// `cos x`
    Cos,
    /// `tan x`
    Tan,
    /// `asin x`
    Asin,
    /// `acos x`
    Acos,
    /// `atan x`
    Atan,
    /// `atan2(y, x)`
    Atan2,
    /// `e^x`
    Exp,
    /// `ln x`
    Ln,
    /// `x^y`
    Pow,
    /// `ln x / ln base`
    LogBase,
}

impl MathFn {
    /// The function for a runtime selector: unary ([`rt::Un`]) or binary ([`rt::Bin`]).
    pub(super) fn of(kind: RtKind, aux: u32) -> Option<Self> {
        use rt::{Bin, Un};
        Some(match kind {
            RtKind::Un => match Un::from_aux(aux)? {
                Un::Sin => Self::Sin,
                Un::Cos => Self::Cos,
                Un::Tan => Self::Tan,
                Un::Asin => Self::Asin,
                Un::Acos => Self::Acos,
                Un::Atan => Self::Atan,
                Un::Exp => Self::Exp,
                Un::Log => Self::Ln,
                _ => return None,
            },
            RtKind::Bin => match Bin::from_aux(aux)? {
                Bin::Atan2 => Self::Atan2,
                Bin::Pow => Self::Pow,
                Bin::LogBase => Self::LogBase,
                _ => return None,
            },
            _ => return None,
        })
    }
}

type V<'c> = VectorValue<'c>;

/// The sign bit of an `i32` lane.
const SIGN: u32 = 0x8000_0000;

impl<'c> Cg<'c, '_> {
    /// `f(args)` as inline IR when the arguments are varying values of a vector variant
    /// (uniform arguments are splatted, as a runtime call would); `None` otherwise.
    pub(super) fn math_inline(&mut self, f: MathFn, args: &[S<'c>]) -> Option<S<'c>> {
        if self.t.lanes == 1 || args.iter().any(|a| a.r == Repr::D) || args.iter().all(|a| a.r == Repr::U) {
            return None;
        }
        let a: Vec<V<'c>> = args.iter().map(|&s| self.to(s, Repr::V).v.into_vector_value()).collect();
        let v = match f {
            MathFn::Sin => self.k_trig(a[0], f),
            MathFn::Cos => self.k_trig(a[0], f),
            MathFn::Tan => self.k_trig(a[0], f),
            MathFn::Asin => self.k_asin(a[0]),
            MathFn::Acos => self.k_acos(a[0]),
            MathFn::Atan => {
                let one = self.kf(1.0);
                let t = self.k_atan_ratio(self.k_abs(a[0]), one);
                self.k_xor_sign(t, self.k_sign_bit(a[0]))
            }
            MathFn::Atan2 => self.k_atan2(a[0], a[1]),
            MathFn::Exp => self.k_exp(a[0]),
            MathFn::Ln => self.k_ln(a[0]),
            MathFn::Pow if args[1].r == Repr::U => self.k_pow_uniform(a[0], args[1].v.into_float_value(), a[1]),
            MathFn::Pow => self.k_pow(a[0], a[1]),
            MathFn::LogBase => {
                let (x, b) = (self.k_ln(a[0]), self.k_ln(a[1]));
                self.kdiv(x, b)
            }
        };
        Some(S { r: Repr::V, v: v.into(), d: None })
    }

    // ------------------------------------------------------------ lane-wise primitives

    fn kvt(&self) -> VectorType<'c> {
        self.f32t.vec_type(self.t.lanes)
    }
    fn kit(&self) -> VectorType<'c> {
        self.cx.i32_type().vec_type(self.t.lanes)
    }
    /// Every lane `x`.
    fn kf(&self, x: f32) -> V<'c> {
        self.fconst_r(f64::from(x), Repr::V).into_vector_value()
    }
    /// Every integer lane `x`.
    fn ki(&self, x: u32) -> V<'c> {
        let k = self.cx.i32_type().const_int(u64::from(x), false);
        VectorType::const_vector(&vec![k; self.t.lanes as usize])
    }
    fn kadd(&self, a: V<'c>, b: V<'c>) -> V<'c> {
        self.b.build_float_add(a, b, "").expect("fadd")
    }
    fn ksub(&self, a: V<'c>, b: V<'c>) -> V<'c> {
        self.b.build_float_sub(a, b, "").expect("fsub")
    }
    fn kmul(&self, a: V<'c>, b: V<'c>) -> V<'c> {
        self.b.build_float_mul(a, b, "").expect("fmul")
    }
    fn kdiv(&self, a: V<'c>, b: V<'c>) -> V<'c> {
        self.b.build_float_div(a, b, "").expect("fdiv")
    }
    fn kneg(&self, a: V<'c>) -> V<'c> {
        self.b.build_float_neg(a, "").expect("fneg")
    }
    /// `a·m + b`, fused when the library's is ([`kc::FUSED_MUL_ADD`]); f32 or f64 lanes.
    fn kfma(&self, a: V<'c>, m: V<'c>, b: V<'c>) -> V<'c> {
        if kc::FUSED_MUL_ADD {
            self.call_intr("llvm.fma", &[a.get_type().into()], &[a.into(), m.into(), b.into()]).into_vector_value()
        } else {
            self.kadd(self.kmul(a, m), b)
        }
    }
    fn kintr(&self, name: &str, a: V<'c>) -> V<'c> {
        self.unary_intr(name, a.into()).into_vector_value()
    }
    /// Polynomial `c[0] + c[1]·x + …` by Estrin's scheme (the library's `estrin`: pairs with
    /// `x`, then pairs of pairs with `x²`, `x⁴`, …).
    fn kestrin(&self, x: V<'c>, c: &[f32]) -> V<'c> {
        let mut v: Vec<V<'c>> = c
            .chunks(2)
            .map(|p| if p.len() == 2 { self.kfma(x, self.kf(p[1]), self.kf(p[0])) } else { self.kf(p[0]) })
            .collect();
        let mut p = x;
        while v.len() > 1 {
            p = self.kmul(p, p);
            v = v.chunks(2).map(|q| if q.len() == 2 { self.kfma(p, q[1], q[0]) } else { q[0] }).collect();
        }
        v[0]
    }
    /// `c[0] + x·estrin(x, c[1..])` (the library's `estrin1`).
    fn kestrin1(&self, x: V<'c>, c: &[f32]) -> V<'c> {
        self.kfma(x, self.kestrin(x, &c[1..]), self.kf(c[0]))
    }
    /// Polynomial `c[0] + c[1]·x + …` by Horner's rule with FMA (the library's `horner`).
    fn khorner(&self, x: V<'c>, c: &[f32]) -> V<'c> {
        self.horner_of(x, c.iter().map(|&v| self.kf(v)).collect())
    }
    /// Horner's rule over coefficient vectors `c` (lowest degree first).
    fn horner_of(&self, x: V<'c>, c: Vec<V<'c>>) -> V<'c> {
        let (last, rest) = c.split_last().expect("a coefficient");
        rest.iter().rev().fold(*last, |acc, &ci| self.kfma(acc, x, ci))
    }
    fn kbits(&self, a: V<'c>) -> V<'c> {
        self.b.build_bit_cast(a, self.kit(), "").expect("bitcast").into_vector_value()
    }
    fn kfrom_bits(&self, a: V<'c>) -> V<'c> {
        self.b.build_bit_cast(a, self.kvt(), "").expect("bitcast").into_vector_value()
    }
    /// Integer lane op: `+`, `-`, `&`, `^`, `<` (shift left), `>` (arithmetic shift right).
    fn kint(&self, op: char, a: V<'c>, b: V<'c>) -> V<'c> {
        let r = match op {
            '+' => self.b.build_int_add(a, b, ""),
            '-' => self.b.build_int_sub(a, b, ""),
            '&' => self.b.build_and(a, b, ""),
            '^' => self.b.build_xor(a, b, ""),
            '<' => self.b.build_left_shift(a, b, ""),
            _ => self.b.build_right_shift(a, b, true, ""),
        };
        r.expect("integer op")
    }
    /// Float compare as a lane mask (`<N x i1>`); ordered predicates, as the library's.
    fn kcmp(&self, p: FloatPredicate, a: V<'c>, b: V<'c>) -> V<'c> {
        self.b.build_float_compare(p, a, b, "").expect("fcmp")
    }
    fn kand(&self, a: V<'c>, b: V<'c>) -> V<'c> {
        self.b.build_and(a, b, "").expect("and")
    }
    fn kor(&self, a: V<'c>, b: V<'c>) -> V<'c> {
        self.b.build_or(a, b, "").expect("or")
    }
    fn knot(&self, a: V<'c>) -> V<'c> {
        self.b.build_not(a, "").expect("not")
    }
    /// `m ? a : b`.
    fn ksel(&self, m: V<'c>, a: V<'c>, b: V<'c>) -> V<'c> {
        self.b.build_select(m, a, b, "").expect("select").into_vector_value()
    }
    /// Truncating conversion with the x86 "integer indefinite" for NaN and out-of-range lanes
    /// (`i32::MIN`), as the library's `to_int`; a plain `fptosi` would be poison there.
    fn kto_int(&self, x: V<'c>) -> V<'c> {
        let ok = self.kcmp(FloatPredicate::OLT, self.kintr("llvm.fabs", x), self.kf(2_147_483_648.0));
        let safe = self.ksel(ok, x, self.kf(0.0));
        let i = self.b.build_float_to_signed_int(safe, self.kit(), "").expect("fptosi");
        self.ksel(ok, i, self.ki(SIGN))
    }
    fn kfrom_int(&self, i: V<'c>) -> V<'c> {
        self.b.build_signed_int_to_float(i, self.kvt(), "").expect("sitofp")
    }
    /// The lanes whose integer `i` has bit 0 set (the library's `(i << 31) >> 31` mask).
    fn kodd(&self, i: V<'c>) -> V<'c> {
        let low = self.kint('&', i, self.ki(1));
        self.b.build_int_compare(IntPredicate::NE, low, self.ki(0), "").expect("icmp")
    }
    /// The lanes whose sign bit is set (the library's `from_bits(bits >> 31)` mask).
    fn ksign_set(&self, x: V<'c>) -> V<'c> {
        self.b.build_int_compare(IntPredicate::SLT, self.kbits(x), self.ki(0), "").expect("icmp")
    }
    /// Some lane of mask `m` is set.
    fn kany(&self, m: V<'c>) -> IntValue<'c> {
        self.call_intr("llvm.vector.reduce.or", &[m.get_type().into()], &[m.into()]).into_int_value()
    }

    // ------------------------------------------------------------ helpers of the kernels

    fn k_abs(&self, x: V<'c>) -> V<'c> {
        self.kfrom_bits(self.kint('&', self.kbits(x), self.ki(!SIGN)))
    }
    fn k_sign_bit(&self, x: V<'c>) -> V<'c> {
        self.kint('&', self.kbits(x), self.ki(SIGN))
    }
    fn k_xor_sign(&self, x: V<'c>, s: V<'c>) -> V<'c> {
        self.kfrom_bits(self.kint('^', self.kbits(x), s))
    }
    fn k_is_nan(&self, x: V<'c>) -> V<'c> {
        self.kcmp(FloatPredicate::UNO, x, x)
    }
    /// `2^n` for integer lanes `n` in the normal exponent range.
    fn k_pow2i(&self, n: V<'c>) -> V<'c> {
        let e = self.kint('<', self.kint('+', n, self.ki(127)), self.ki(23));
        self.kfrom_bits(e)
    }

    // ------------------------------------------------------------ exponential and logarithm

    /// `2^(hi + lo)` (the library's `exp2_dd`).
    fn k_exp2_dd(&self, hi: V<'c>, lo: V<'c>) -> V<'c> {
        use FloatPredicate::{OLE, OLT};
        let in_range = self.kcmp(OLE, self.k_abs(hi), self.kf(152.0));
        let h = self.ksel(self.kcmp(OLT, self.kf(129.0), hi), self.kf(129.0), hi);
        let h = self.ksel(self.kcmp(OLT, h, self.kf(-151.0)), self.kf(-151.0), h);
        let l = self.ksel(in_range, lo, self.kf(0.0));
        let n = self.kintr("llvm.roundeven", h);
        let r = self.kadd(self.ksub(h, n), l);
        let p = self.kfma(r, self.kestrin(r, &kc::EXP2_Q), self.kf(1.0));
        let ni = self.kto_int(n);
        let n1 = self.kint('>', ni, self.ki(1));
        let n2 = self.kint('-', ni, n1);
        self.kmul(self.kmul(p, self.k_pow2i(n1)), self.k_pow2i(n2))
    }

    /// `e^x`.
    fn k_exp(&self, x: V<'c>) -> V<'c> {
        let hi = self.kmul(x, self.kf(kc::LOG2E_HI));
        let lo = self.kfma(x, self.kf(kc::LOG2E_LO), self.kfma(x, self.kf(kc::LOG2E_HI), self.kneg(hi)));
        self.k_exp2_dd(hi, lo)
    }

    /// `(e, ln_hi, ln_lo)` with `x = 2^e·(1+f)` (the library's `log_reduce`).
    fn k_log_reduce(&self, x: V<'c>) -> (V<'c>, V<'c>, V<'c>) {
        let tiny = self.kcmp(FloatPredicate::OLT, x, self.kf(f32::MIN_POSITIVE));
        let xs = self.ksel(tiny, self.kmul(x, self.kf(16_777_216.0)), x);
        let u = self.kbits(xs);
        let e = self.kint('>', self.kint('-', u, self.ki(0x3f35_04f3)), self.ki(23));
        let m = self.kfrom_bits(self.kint('-', u, self.kint('<', e, self.ki(23))));
        let e = self.ksub(self.kfrom_int(e), self.ksel(tiny, self.kf(24.0), self.kf(0.0)));
        let f = self.ksub(m, self.kf(1.0));
        let f2 = self.kmul(f, f);
        let b_hi = self.kmul(f2, self.kf(-0.5));
        let b_lo = self.kmul(self.kfma(f, f, self.kneg(f2)), self.kf(-0.5));
        let s_hi = self.kadd(f, b_hi);
        let s_lo = self.kadd(self.ksub(f, s_hi), b_hi);
        let lo = self.kfma(self.kmul(f2, f), self.khorner(f, &kc::LOG_L), self.kadd(s_lo, b_lo));
        (e, s_hi, lo)
    }

    /// The logarithm `v` of `x`, with the C99 values for `x ≤ 0` and `+inf`.
    fn k_log_specials(&self, x: V<'c>, v: V<'c>) -> V<'c> {
        use FloatPredicate::{OEQ, OLT};
        let inf = self.kf(f32::INFINITY);
        let ok = self.kand(self.kcmp(OLT, self.kf(0.0), x), self.kcmp(OLT, x, inf));
        let special = self.ksel(
            self.kcmp(OEQ, x, self.kf(0.0)),
            self.kf(f32::NEG_INFINITY),
            self.ksel(self.kcmp(OEQ, x, inf), x, self.kf(f32::NAN)),
        );
        self.ksel(ok, v, special)
    }

    /// `ln x`.
    fn k_ln(&self, x: V<'c>) -> V<'c> {
        let (e, ln_hi, ln_lo) = self.k_log_reduce(x);
        let p_hi = self.kmul(e, self.kf(kc::LN2_HI16));
        let hi = self.kadd(p_hi, ln_hi);
        let lo = self.kadd(self.kadd(self.ksub(p_hi, hi), ln_hi), self.kfma(e, self.kf(kc::LN2_LO16), ln_lo));
        self.k_log_specials(x, self.kadd(hi, lo))
    }

    /// `ax^y` for `ax >= 0` (the library's `pow_mag` in its general form, which computes the
    /// bits of its fast path for every lane that path takes).
    fn k_pow_mag(&self, ax: V<'c>, y: V<'c>) -> V<'c> {
        use FloatPredicate::{OEQ, OLT};
        // log2_split
        let tiny = self.kcmp(OLT, ax, self.kf(f32::MIN_POSITIVE));
        let xs = self.ksel(tiny, self.kmul(ax, self.kf(16_777_216.0)), ax);
        let u = self.kbits(xs);
        let ei = self.kint('>', self.kint('-', u, self.ki(kc::SQRT_HALF_BITS)), self.ki(23));
        let m = self.kfrom_bits(self.kint('-', u, self.kint('<', ei, self.ki(23))));
        let e = self.ksub(self.kfrom_int(ei), self.ksel(tiny, self.kf(24.0), self.kf(0.0)));
        let f = self.ksub(m, self.kf(1.0));
        let l = self.kmul(f, self.kestrin1(f, &kc::LOG2_Q));
        let s = self.kadd(e, l);
        let sl = self.kadd(self.ksub(e, s), l);
        // log2 of 0 and inf
        let inf = self.kf(f32::INFINITY);
        let finite = self.kcmp(OLT, ax, inf);
        let zero = self.kcmp(OEQ, ax, self.kf(0.0));
        let lh = self.ksel(zero, self.kf(f32::NEG_INFINITY), self.ksel(finite, s, ax));
        let ll = self.ksel(self.kand(finite, self.knot(zero)), sl, self.kf(0.0));
        let th = self.kmul(y, lh);
        let tl = self.kfma(y, ll, self.kfma(y, lh, self.kneg(th)));
        self.k_exp2_dd(th, tl)
    }

    /// `f()` on a branch taken when some lane of mask `m` is set, else `common`; the values
    /// (vectors of any element type, masks too) joined by phis.
    fn k_when_any(&self, m: V<'c>, common: Vec<V<'c>>, f: impl FnOnce(&Self) -> Vec<V<'c>>) -> Vec<V<'c>> {
        self.k_when(self.kany(m), common, f)
    }

    /// `f()` on a branch taken when `cond` holds, else `common`; joined by phis.
    fn k_when(&self, cond: IntValue<'c>, common: Vec<V<'c>>, f: impl FnOnce(&Self) -> Vec<V<'c>>) -> Vec<V<'c>> {
        let func = self.cur_fn();
        let from = self.b.get_insert_block().expect("positioned");
        let then_bb = self.cx.append_basic_block(func, "when");
        let join = self.cx.append_basic_block(func, "join");
        self.b.build_conditional_branch(cond, then_bb, join).expect("br");
        self.b.position_at_end(then_bb);
        let r = f(self);
        let then_end = self.b.get_insert_block().expect("positioned");
        self.b.build_unconditional_branch(join).expect("br");
        self.b.position_at_end(join);
        common
            .iter()
            .zip(&r)
            .map(|(&c, &x)| {
                let p = self.b.build_phi(c.get_type(), "").expect("phi");
                p.add_incoming(&[(&c, from), (&x, then_end)]);
                p.as_basic_value().into_vector_value()
            })
            .collect()
    }

    /// `x^y` (C99 `pow`), as the library computes it: binary powering for the lanes with a
    /// base in `[+0, inf)` under an exponent in `{0, 1/2, …, 16}` whose result is in range
    /// ([`Cg::k_pow_halves`]), the exponential of the logarithm for the others, each on a
    /// branch taken when some lane needs it.
    fn k_pow(&self, x: V<'c>, y: V<'c>) -> V<'c> {
        use FloatPredicate::{OEQ, OLE};
        let n2 = self.kadd(y, y);
        let halves = self.kand(
            self.kand(self.kcmp(OLE, self.kf(0.0), n2), self.kcmp(OLE, n2, self.kf(32.0))),
            self.kcmp(OEQ, self.kintr("llvm.roundeven", n2), n2),
        );
        let r = self.k_when_any(halves, vec![self.kf(0.0)], |cg| vec![cg.k_pow_halves(x, n2)])[0];
        self.k_pow_keep(x, y, r, halves)
    }

    /// The powered `r` for the lanes of `halves` with a base in `[+0, inf)` whose result is in
    /// range (or whose base is 0), `2^(y·log2|x|)` for the others (the end of the library's
    /// `pow`).
    fn k_pow_keep(&self, x: V<'c>, y: V<'c>, r: V<'c>, halves: V<'c>) -> V<'c> {
        use FloatPredicate::{OEQ, OLE, OLT};
        let inf = self.kf(f32::INFINITY);
        let in_range = self.kand(self.kcmp(OLE, self.kf(kc::POW_HALVES_MIN), r), self.kcmp(OLT, r, inf));
        let ok_base = self.kand(self.knot(self.ksign_set(x)), self.kcmp(OLT, x, inf));
        let fast = self.kand(halves, self.kand(ok_base, self.kor(in_range, self.kcmp(OEQ, x, self.kf(0.0)))));
        self.k_when_any(self.knot(fast), vec![r], |cg| vec![cg.ksel(fast, r, cg.k_pow_exp_log(x, y))])[0]
    }

    /// `(rh, rl)·(bh, bl)` as an unnormalized double-f32 (the library's `dd_mul`).
    fn k_dd_mul(&self, rh: V<'c>, rl: V<'c>, bh: V<'c>, bl: V<'c>) -> (V<'c>, V<'c>) {
        let p = self.kmul(rh, bh);
        (p, self.kfma(rl, bh, self.kfma(rh, bl, self.kfma(rh, bh, self.kneg(p)))))
    }

    /// `(bh, bl)²` (the library's `dd_sq`).
    fn k_dd_sq(&self, bh: V<'c>, bl: V<'c>) -> (V<'c>, V<'c>) {
        let p = self.kmul(bh, bh);
        (p, self.kfma(self.kadd(bh, bh), bl, self.kfma(bh, bh, self.kneg(p))))
    }

    /// `x^y` for a uniform `y` (scalar `y`, splatted `ys`): for `2y` an integer in `[0, 32]`
    /// the powering steered by scalar branches on its bits (the library's
    /// `pow_halves_uniform`), with the lanes out of its range through the exponential of the
    /// logarithm; else that exponential for every lane.
    fn k_pow_uniform(&self, x: V<'c>, y: inkwell::values::FloatValue<'c>, ys: V<'c>) -> V<'c> {
        use FloatPredicate::{OEQ, OLE};
        let b = &self.b;
        let n0 = b.build_float_add(y, y, "").expect("fadd");
        let k0 = |v: f64| self.f32t.const_float(v);
        let round = self.unary_intr("llvm.roundeven", n0.into()).into_float_value();
        let c1 = b.build_float_compare(OLE, k0(0.0), n0, "").expect("fcmp");
        let c2 = b.build_float_compare(OLE, n0, k0(32.0), "").expect("fcmp");
        let c3 = b.build_float_compare(OEQ, round, n0, "").expect("fcmp");
        let cond = b.build_and(b.build_and(c1, c2, "").expect("and"), c3, "").expect("and");
        // The branch on `cond` with an else: the exponential of the logarithm is computed on
        // one side only.
        let func = self.cur_fn();
        let (then_bb, else_bb, join) = (
            self.cx.append_basic_block(func, "halves"),
            self.cx.append_basic_block(func, "explog"),
            self.cx.append_basic_block(func, "join"),
        );
        b.build_conditional_branch(cond, then_bb, else_bb).expect("br");
        b.position_at_end(then_bb);
        let n = b.build_float_to_unsigned_int(round, self.cx.i32_type(), "").expect("fptoui");
        let one = self.cx.i32_type().const_int(1, false);
        let zero = self.cx.i32_type().const_zero();
        // The library's steps less those whose result is known: the power is 1 until the
        // first set bit (`started`), whose power is then taken as it is; the first square and
        // the factor `√x` have a zero low part, so no cross term.
        let (mut rh, mut rl) = (self.kf(1.0), self.kf(0.0));
        let (mut bh, mut bl) = (x, self.kf(0.0));
        let mut started = self.cx.bool_type().const_zero();
        let mut rest = b.build_right_shift(n, one, false, "").expect("lshr");
        for step in 0..5 {
            let bit = b
                .build_int_compare(IntPredicate::NE, b.build_and(rest, one, "").expect("and"), zero, "")
                .expect("icmp");
            let later = b.build_and(bit, started, "").expect("and");
            let first = b.build_and(bit, b.build_not(started, "").expect("not"), "").expect("and");
            let r = self.k_when(later, vec![rh, rl], |cg| {
                let (p, e) = cg.k_dd_mul(rh, rl, bh, bl);
                vec![p, e]
            });
            let r = self.k_when(first, r, |_| vec![bh, bl]);
            (rh, rl) = (r[0], r[1]);
            started = b.build_or(started, bit, "").expect("or");
            rest = b.build_right_shift(rest, one, false, "").expect("lshr");
            if step == 4 {
                break;
            }
            let more = b.build_int_compare(IntPredicate::NE, rest, zero, "").expect("icmp");
            let sq = self.k_when(more, vec![bh, bl], |cg| {
                if step == 0 {
                    let p = cg.kmul(bh, bh);
                    vec![p, cg.kfma(bh, bh, cg.kneg(p))]
                } else {
                    let (p, e) = cg.k_dd_sq(bh, bl);
                    vec![p, e]
                }
            });
            (bh, bl) = (sq[0], sq[1]);
        }
        let odd = b.build_int_compare(IntPredicate::NE, b.build_and(n, one, "").expect("and"), zero, "").expect("icmp");
        let r = self.k_when(odd, vec![rh, rl], |cg| {
            let s = cg.kintr("llvm.sqrt", x);
            let p = cg.kmul(rh, s);
            vec![p, cg.kfma(rl, s, cg.kfma(rh, s, cg.kneg(p)))]
        });
        let r = self.kadd(r[0], r[1]);
        let every = self.kcmp(FloatPredicate::PredicateTrue, x, x);
        let halves = self.k_pow_keep(x, ys, r, every);
        let halves_end = b.get_insert_block().expect("positioned");
        b.build_unconditional_branch(join).expect("br");
        b.position_at_end(else_bb);
        let general = self.k_pow_exp_log(x, ys);
        let else_end = b.get_insert_block().expect("positioned");
        b.build_unconditional_branch(join).expect("br");
        b.position_at_end(join);
        let p = b.build_phi(x.get_type(), "").expect("phi");
        p.add_incoming(&[(&halves, halves_end), (&general, else_end)]);
        p.as_basic_value().into_vector_value()
    }

    /// `x^(n2/2)` by binary powering in double-f32 and `√x` for odd `n2` (the library's
    /// `pow_halves`, step for step, each step on a branch taken when some lane needs it).
    fn k_pow_halves(&self, x: V<'c>, n2: V<'c>) -> V<'c> {
        let n = self.kto_int(n2);
        let (mut rh, mut rl) = (self.kf(1.0), self.kf(0.0));
        let (mut bh, mut bl) = (x, self.kf(0.0));
        let mut rest = self.kint('>', n, self.ki(1));
        for step in 0..5 {
            let bit = self.kodd(rest);
            let r = self.k_when_any(bit, vec![rh, rl], |cg| {
                let (p, e) = cg.k_dd_mul(rh, rl, bh, bl);
                vec![cg.ksel(bit, p, rh), cg.ksel(bit, e, rl)]
            });
            (rh, rl) = (r[0], r[1]);
            rest = self.kint('>', rest, self.ki(1));
            if step == 4 {
                break;
            }
            let more = self.b.build_int_compare(IntPredicate::NE, rest, self.ki(0), "").expect("icmp");
            let b = self.k_when_any(more, vec![bh, bl], |cg| {
                let (p, e) = cg.k_dd_sq(bh, bl);
                vec![p, e]
            });
            (bh, bl) = (b[0], b[1]);
        }
        let half = self.kodd(n);
        let r = self.k_when_any(half, vec![rh, rl], |cg| {
            let (p, e) = cg.k_dd_mul(rh, rl, cg.kintr("llvm.sqrt", x), cg.kf(0.0));
            vec![cg.ksel(half, p, rh), cg.ksel(half, e, rl)]
        });
        self.kadd(r[0], r[1])
    }

    /// `x^y` through `2^(y·log2|x|)` (the library's `pow_exp_log`): its fast path (every lane
    /// a positive normal base, or `+0` under a positive exponent, with a normal result:
    /// one-step scaling, no fix-ups), else the general form on a branch taken when some lane
    /// needs it.
    fn k_pow_exp_log(&self, x: V<'c>, y: V<'c>) -> V<'c> {
        use FloatPredicate::{OLE, OLT};
        let zero = self.kf(0.0);
        let is_pz = self.b.build_int_compare(IntPredicate::EQ, self.kbits(x), self.ki(0), "").expect("icmp");
        let plus_zero = self.kand(is_pz, self.kcmp(OLT, zero, y));
        let xb = self.ksel(plus_zero, self.kf(1.0), x);
        // log2_split without the subnormal scaling
        let u = self.kbits(xb);
        let ei = self.kint('>', self.kint('-', u, self.ki(kc::SQRT_HALF_BITS)), self.ki(23));
        let m = self.kfrom_bits(self.kint('-', u, self.kint('<', ei, self.ki(23))));
        let e = self.kfrom_int(ei);
        let f = self.ksub(m, self.kf(1.0));
        let l = self.kmul(f, self.kestrin1(f, &kc::LOG2_Q));
        let lh = self.kadd(e, l);
        let ll = self.kadd(self.ksub(e, lh), l);
        let th = self.kmul(y, lh);
        let tl = self.kfma(y, ll, self.kfma(y, lh, self.kneg(th)));
        let ok = self.kand(
            self.kand(self.kcmp(OLE, self.kf(f32::MIN_POSITIVE), xb), self.kcmp(OLT, xb, self.kf(f32::INFINITY))),
            self.kcmp(OLE, self.k_abs(th), self.kf(125.0)),
        );
        let n = self.kintr("llvm.roundeven", th);
        let r = self.kadd(self.ksub(th, n), tl);
        let p = self.kfma(r, self.kestrin(r, &kc::EXP2_Q), self.kf(1.0));
        // |n| <= 125 wherever the result is used: a plain conversion.
        let ni = self.b.build_float_to_signed_int(n, self.kit(), "").expect("fptosi");
        let fast = self.ksel(plus_zero, zero, self.kmul(p, self.k_pow2i(ni)));
        let vs = |v: V<'c>| S { r: Repr::V, v: v.into(), d: None };
        let not_ok = super::M { uni: false, v: self.knot(ok).into() };
        self.when_any(not_ok, vec![vs(fast)], |cg, _| vec![vs(cg.k_pow_general(x, y))])[0].v.into_vector_value()
    }

    /// `x^y` for any lanes (the library's `pow_general`).
    fn k_pow_general(&self, x: V<'c>, y: V<'c>) -> V<'c> {
        use FloatPredicate::{OEQ, OLT};
        let ax = self.k_abs(x);
        let a = self.k_pow_mag(ax, y);
        let inf = self.kf(f32::INFINITY);
        let finite = self.kcmp(OLT, ax, inf);

        let y_int = self.kcmp(OEQ, self.kintr("llvm.floor", y), y);
        let half = self.kmul(y, self.kf(0.5));
        let y_odd = self.kand(y_int, self.knot(self.kcmp(OEQ, self.kintr("llvm.floor", half), half)));
        let x_neg = self.kand(self.ksign_set(x), self.knot(self.k_is_nan(x)));
        let flip = self.ksel(self.kand(x_neg, y_odd), self.ki(SIGN), self.ki(0));
        let a = self.k_xor_sign(a, flip);
        let domain_error = self.kand(self.kand(self.kcmp(OLT, x, self.kf(0.0)), finite), self.knot(y_int));
        let a = self.ksel(domain_error, self.kf(f32::NAN), a);
        let one = self.kor(
            self.kor(self.kcmp(OEQ, y, self.kf(0.0)), self.kcmp(OEQ, x, self.kf(1.0))),
            self.kand(self.kcmp(OEQ, ax, self.kf(1.0)), self.kcmp(OEQ, self.k_abs(y), inf)),
        );
        self.ksel(one, self.kf(1.0), a)
    }

    // ------------------------------------------------------------ trigonometry

    /// `|x| = n·π/2 + r`: `(r, n)` (the library's `reduce_pio2`).
    fn k_reduce_pio2(&self, ax: V<'c>) -> (V<'c>, V<'c>) {
        let n = self.kintr("llvm.roundeven", self.kmul(ax, self.kf(kc::FRAC_2_PI)));
        let r = self.kfma(n, self.kf(-kc::PIO2_1), ax);
        let r = self.kfma(n, self.kf(-kc::PIO2_2), r);
        let r = self.kfma(n, self.kf(-kc::PIO2_3), r);
        (r, self.kto_int(n))
    }

    /// `sin |x|` (`shift` 0) or `cos |x|` (`shift` 1).
    fn k_sin_cos_abs(&self, ax: V<'c>, shift: u32) -> V<'c> {
        let (r, n) = self.k_reduce_pio2(ax);
        let q = self.kint('+', n, self.ki(shift));
        let z = self.kmul(r, r);
        let s = self.kfma(self.kmul(r, z), self.khorner(z, &kc::SIN_S), r);
        let c = self.kfma(z, self.kfma(z, self.khorner(z, &kc::COS_C), self.kf(-0.5)), self.kf(1.0));
        let v = self.ksel(self.kodd(q), c, s);
        self.k_xor_sign(v, self.kint('&', self.kint('<', q, self.ki(30)), self.ki(SIGN)))
    }

    /// `sin`, `cos` or `tan` of `x`: the vector kernel, and std's function for the lanes
    /// beyond [`kc::TRIG_VECTOR_LIMIT`] (±inf included) when there are any.
    fn k_trig(&mut self, x: V<'c>, f: MathFn) -> V<'c> {
        let ax = self.k_abs(x);
        let (v, which) = match f {
            MathFn::Sin => (self.k_xor_sign(self.k_sin_cos_abs(ax, 0), self.k_sign_bit(x)), rt::Un::Sin as u32),
            MathFn::Cos => (self.k_sin_cos_abs(ax, 1), rt::Un::Cos as u32),
            _ => {
                let (r, n) = self.k_reduce_pio2(ax);
                let z = self.kmul(r, r);
                let t = self.kfma(self.kmul(r, z), self.khorner(z, &kc::TAN_T), r);
                let v = self.ksel(self.kodd(n), self.kdiv(self.kf(-1.0), t), t);
                (self.k_xor_sign(v, self.k_sign_bit(x)), rt::Un::Tan as u32)
            }
        };
        let big = self.kcmp(FloatPredicate::OLT, self.kf(kc::TRIG_VECTOR_LIMIT), ax);
        let func = self.cur_fn();
        let from = self.b.get_insert_block().expect("positioned");
        let cold = self.cx.append_basic_block(func, "trig.big");
        let join = self.cx.append_basic_block(func, "trig.join");
        let br = self.b.build_conditional_branch(self.kany(big), cold, join).expect("br");
        self.mark_unlikely(br);
        self.b.position_at_end(cold);
        let lanes = self.trig_lanes(which, x, big);
        let w = self.ksel(big, lanes, v);
        let cold_end = self.b.get_insert_block().expect("positioned");
        self.b.build_unconditional_branch(join).expect("br");
        self.b.position_at_end(join);
        let phi = self.b.build_phi(self.kvt(), "").expect("phi");
        phi.add_incoming(&[(&v, from), (&w, cold_end)]);
        phi.as_basic_value().into_vector_value()
    }

    /// [`rt::rt_trig_lanes`]: std's `which` on the lanes of `x` in `mask`.
    fn trig_lanes(&self, which: u32, x: V<'c>, mask: V<'c>) -> V<'c> {
        let inp = self.entry_alloca(self.kvt().into());
        self.b.build_store(inp, x).expect("store");
        let out = self.entry_alloca(self.kvt().into());
        let mbuf = self.entry_alloca(self.kit().into());
        let m32 = self.b.build_int_s_extend(mask, self.kit(), "").expect("sext");
        self.b.build_store(mbuf, m32).expect("store");
        let f32p = self.f32t.ptr_type(AddressSpace::default());
        let i32p = self.cx.i32_type().ptr_type(AddressSpace::default());
        let cast = |p: inkwell::values::PointerValue<'c>, t| self.b.build_pointer_cast(p, t, "").expect("cast");
        let fnp = self.const_fn_ptr(rt::rt_trig_lanes as crate::abi::RtFn as usize);
        let callee = inkwell::values::CallableValue::try_from(fnp).expect("callable");
        let aux = which | self.t.lanes << 8;
        self.b
            .build_call(
                callee,
                &[
                    self.i8p().const_null().into(),
                    cast(mbuf, i32p).into(),
                    cast(inp, f32p).into(),
                    cast(out, f32p).into(),
                    self.i32c(u64::from(aux)).into(),
                ],
                "",
            )
            .expect("call");
        self.b.build_load(out, "").expect("load").into_vector_value()
    }

    /// Marks a conditional branch as almost never taken to its first successor.
    fn mark_unlikely(&self, br: inkwell::values::InstructionValue<'c>) {
        let weights = self.cx.metadata_node(&[
            self.cx.metadata_string("branch_weights").into(),
            self.i32c(1).into(),
            self.i32c(1 << 20).into(),
        ]);
        br.set_metadata(weights, self.cx.get_kind_id("prof")).expect("branch weights");
    }

    /// `(p, big)`: `asin a`, or for `a > 0.6` the `p` with `asin a = π/2 − 2p` (the library's
    /// `asin_core`).
    fn k_asin_core(&self, a: V<'c>) -> (V<'c>, V<'c>) {
        let big = self.kcmp(FloatPredicate::OLT, self.kf(0.6), a);
        let z = self.ksel(big, self.kmul(self.ksub(self.kf(1.0), a), self.kf(0.5)), self.kmul(a, a));
        let t = self.ksel(big, self.kintr("llvm.sqrt", z), a);
        let p = self.kfma(self.kmul(t, z), self.khorner(z, &kc::ASIN_A), t);
        (p, big)
    }

    /// `asin x`.
    fn k_asin(&self, x: V<'c>) -> V<'c> {
        let ax = self.k_abs(x);
        let (p, big) = self.k_asin_core(ax);
        let far = self.ksub(self.kf(kc::PIO2_1), self.kfma(p, self.kf(2.0), self.kf(-kc::PIO2_LO)));
        let v = self.ksel(big, far, p);
        let v = self.ksel(self.kcmp(FloatPredicate::OLT, self.kf(1.0), ax), self.kf(f32::NAN), v);
        self.k_xor_sign(v, self.k_sign_bit(x))
    }

    /// `acos x`.
    fn k_acos(&self, x: V<'c>) -> V<'c> {
        let ax = self.k_abs(x);
        let (p, big) = self.k_asin_core(ax);
        let neg = self.kcmp(FloatPredicate::OLT, x, self.kf(0.0));
        let signed = self.k_xor_sign(p, self.k_sign_bit(x));
        let small = self.ksub(self.kf(kc::PIO2_1), self.ksub(signed, self.kf(kc::PIO2_LO)));
        let big_pos = self.kmul(p, self.kf(2.0));
        let big_neg = self.ksub(self.kf(kc::PI_HI), self.kfma(p, self.kf(2.0), self.kf(-kc::PI_LO)));
        let v = self.ksel(big, self.ksel(neg, big_neg, big_pos), small);
        self.ksel(self.kcmp(FloatPredicate::OLT, self.kf(1.0), ax), self.kf(f32::NAN), v)
    }

    /// `atan(ay / ax)` for `ay, ax ≥ 0` (the library's `atan_ratio`).
    fn k_atan_ratio(&self, ay: V<'c>, ax: V<'c>) -> V<'c> {
        let swap = self.kcmp(FloatPredicate::OLT, ax, ay);
        let w = self.kdiv(self.ksel(swap, ax, ay), self.ksel(swap, ay, ax));
        let z = self.kmul(w, w);
        let p = self.kfma(self.kmul(w, z), self.khorner(z, &kc::ATAN_P), w);
        self.ksel(swap, self.ksub(self.kf(kc::PIO2_1), self.ksub(p, self.kf(kc::PIO2_LO))), p)
    }

    /// `atan2(y, x)` with the C99 special cases.
    fn k_atan2(&self, y: V<'c>, x: V<'c>) -> V<'c> {
        use FloatPredicate::OEQ;
        let (ax, ay) = (self.k_abs(x), self.k_abs(y));
        let t = self.k_atan_ratio(ay, ax);
        let (zero, inf) = (self.kf(0.0), self.kf(f32::INFINITY));
        let t = self.ksel(self.kand(self.kcmp(OEQ, ay, zero), self.kcmp(OEQ, ax, zero)), zero, t);
        let both_inf = self.kand(self.kcmp(OEQ, ay, inf), self.kcmp(OEQ, ax, inf));
        let t = self.ksel(both_inf, self.kf(core::f32::consts::FRAC_PI_4), t);
        let left = self.ksub(self.kf(kc::PI_HI), self.ksub(t, self.kf(kc::PI_LO)));
        let t = self.ksel(self.ksign_set(x), left, t);
        self.k_xor_sign(t, self.k_sign_bit(y))
    }
}
