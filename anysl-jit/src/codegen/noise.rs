//! `noise`, `snoise` and `cellnoise` emitted inline as LLVM IR instead of a runtime callback:
//! the same hashed gradient noise as `anysl_core::stdlib::noise` (Perlin's improved noise
//! with the table-free lattice hash), operation for operation, so the JIT and the
//! monomorphized build agree to the last bit on finite inputs. The float work goes through
//! the code generator's representation-aware helpers, so dual numbers carry their derivatives
//! exactly as `Dual<F>` does; the lattice hash is integer vector code (`i32` lanes).

use super::{Cg, Repr, M, S};
use inkwell::values::BasicValueEnum;
use inkwell::{FloatPredicate, IntPredicate};

use anysl_core::stdlib::lattice::{CELL_SEED, FINALIZE, HASH_PERIOD, PRIMES, VECTOR_SEEDS};

/// Which member of the family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum NoiseKind {
    /// `noise`: in [0, 1].
    Unsigned,
    /// `snoise`: in [-1, 1].
    Signed,
    /// `cellnoise`: constant per unit cell, in [0, 1).
    Cell,
}

/// Integer lanes shaped like a float value (scalar `i32` or `<N x i32>`).
#[derive(Clone, Copy)]
struct I<'c>(BasicValueEnum<'c>);

impl<'c> Cg<'c, '_> {
    /// `kind` of the domain `coords` (1 to 4 floats) with `width` components (1 or 3).
    pub(super) fn noise_inline(&self, kind: NoiseKind, coords: &[S<'c>], width: usize) -> Vec<S<'c>> {
        let r = coords.iter().map(|c| c.r).max().unwrap_or(Repr::U);
        let d: Vec<S<'c>> = coords.iter().map(|&c| self.to(c, r)).collect();
        let d = self.reduce_to_period(d);
        let seeds: &[u32] = if width == 1 { &VECTOR_SEEDS[..1] } else { &VECTOR_SEEDS };
        let out: Vec<S<'c>> = match kind {
            NoiseKind::Cell => {
                let bits: Vec<I<'c>> = d.iter().map(|&x| self.floor_bits(x.v)).collect();
                seeds
                    .iter()
                    .map(|&s| {
                        let h = self.lattice_hash(&bits, CELL_SEED ^ s, d[0].v);
                        self.constant_part(r, self.bits_to_unit(h))
                    })
                    .collect()
            }
            NoiseKind::Signed | NoiseKind::Unsigned => seeds
                .iter()
                .map(|&s| {
                    let n = self.signed_noise(&d, s);
                    if kind == NoiseKind::Signed {
                        n
                    } else {
                        let h = self.fc(0.5);
                        self.add(h, self.mul(h, n))
                    }
                })
                .collect(),
        };
        // As a runtime call would return it: uniform, or the variant's full representation.
        let target = if r == Repr::U { Repr::U } else { self.full() };
        out.into_iter().map(|s| self.to(s, target)).collect()
    }

    /// Signed noise of a 1- to 4-D domain, clamped to [-1, 1], 0 for non-finite input
    /// (`anysl_core::stdlib::noise::signed`).
    fn signed_noise(&self, d: &[S<'c>], seed: u32) -> S<'c> {
        let off = self.to(self.fc(0.5), d[0].r);
        let n = match d.len() {
            1 => self.perlin3([d[0], off, off], seed),
            2 => self.perlin3([d[0], d[1], off], seed),
            3 => self.perlin3([d[0], d[1], d[2]], seed),
            _ => self.perlin4([d[0], d[1], d[2], d[3]], seed),
        };
        let nan = self.cmp(FloatPredicate::UNO, n, n);
        let c = self.clamp(n, self.fc(-1.0), self.fc(1.0));
        self.sel(nan, self.to(self.fc(0.0), c.r), c)
    }

    /// Each coordinate reduced modulo the hash period where |x| ≥ 2^31 (exact), else `x` bit
    /// for bit; the reduction runs only when some lane of some coordinate needs it (a branch,
    /// as the library's `reduce_to_hash_period` takes it).
    fn reduce_to_period(&self, d: Vec<S<'c>>) -> Vec<S<'c>> {
        let half = self.fc(HASH_PERIOD * 0.5);
        let bigs: Vec<M<'c>> = d.iter().map(|&x| self.cmp(FloatPredicate::OGE, self.abs(x), half)).collect();
        let Some(any_big) = bigs.iter().copied().reduce(|a, b| self.mor(a, b)) else { return d };
        self.when_any(any_big, d, |cg, xs| {
            xs.iter()
                .zip(&bigs)
                .map(|(&x, &big)| {
                    let scaled = cg.mul(x, cg.fc(1.0 / HASH_PERIOD));
                    let rounded = cg.constant_part(scaled.r, cg.unary_intr("llvm.round", scaled.v));
                    let r = cg.sub(x, cg.mul(cg.fc(HASH_PERIOD), rounded));
                    cg.sel(big, r, x)
                })
                .collect()
        })
    }

    /// `(fraction, bits of floor, bits of floor + 1)` of one coordinate (already reduced to the
    /// hash period).
    fn cell(&self, x: S<'c>) -> (S<'c>, I<'c>, I<'c>) {
        let xf = self.floor(x);
        let f = self.sub(x, xf);
        let i = self.lattice_bits(xf.v);
        let one = self.iconst(i, 1);
        (f, i, self.ibin('+', i, one))
    }

    fn perlin3(&self, p: [S<'c>; 3], seed: u32) -> S<'c> {
        let (fx, i0, i1) = self.cell(p[0]);
        let (fy, j0, j1) = self.cell(p[1]);
        let (fz, k0, k1) = self.cell(p[2]);
        let one = self.fc(1.0);
        let (gx0, gx1) = (fx, self.sub(fx, one));
        let (gy0, gy1) = (fy, self.sub(fy, one));
        let (gz0, gz1) = (fz, self.sub(fz, one));
        let like = fx.v;
        let c = |i, j, k, x, y, z| self.grad3(self.lattice_hash(&[i, j, k], seed, like), x, y, z);
        let u = self.fade(fx);
        let v = self.fade(fy);
        let w = self.fade(fz);
        let x00 = self.lerp(u, c(i0, j0, k0, gx0, gy0, gz0), c(i1, j0, k0, gx1, gy0, gz0));
        let x10 = self.lerp(u, c(i0, j1, k0, gx0, gy1, gz0), c(i1, j1, k0, gx1, gy1, gz0));
        let x01 = self.lerp(u, c(i0, j0, k1, gx0, gy0, gz1), c(i1, j0, k1, gx1, gy0, gz1));
        let x11 = self.lerp(u, c(i0, j1, k1, gx0, gy1, gz1), c(i1, j1, k1, gx1, gy1, gz1));
        self.lerp(w, self.lerp(v, x00, x10), self.lerp(v, x01, x11))
    }

    fn perlin4(&self, p: [S<'c>; 4], seed: u32) -> S<'c> {
        let (fx, i0, i1) = self.cell(p[0]);
        let (fy, j0, j1) = self.cell(p[1]);
        let (fz, k0, k1) = self.cell(p[2]);
        let (fw, l0, l1) = self.cell(p[3]);
        let one = self.fc(1.0);
        let like = fx.v;
        let c = |i, j, k, l, x, y, z, w| self.grad4(self.lattice_hash(&[i, j, k, l], seed, like), [x, y, z, w]);
        let (u, v, s, r) = (self.fade(fx), self.fade(fy), self.fade(fz), self.fade(fw));
        let (fx1, fy1, fz1) = (self.sub(fx, one), self.sub(fy, one), self.sub(fz, one));
        let slice = |l, gw: S<'c>| {
            let x00 = self.lerp(u, c(i0, j0, k0, l, fx, fy, fz, gw), c(i1, j0, k0, l, fx1, fy, fz, gw));
            let x10 = self.lerp(u, c(i0, j1, k0, l, fx, fy1, fz, gw), c(i1, j1, k0, l, fx1, fy1, fz, gw));
            let x01 = self.lerp(u, c(i0, j0, k1, l, fx, fy, fz1, gw), c(i1, j0, k1, l, fx1, fy, fz1, gw));
            let x11 = self.lerp(u, c(i0, j1, k1, l, fx, fy1, fz1, gw), c(i1, j1, k1, l, fx1, fy1, fz1, gw));
            self.lerp(s, self.lerp(v, x00, x10), self.lerp(v, x01, x11))
        };
        let fw1 = self.sub(fw, one);
        self.mul(self.lerp(r, slice(l0, fw), slice(l1, fw1)), self.fc(0.5))
    }

    /// Perlin's fade curve `t·t·t·(t·(t·6 − 15) + 10)`, in that operation order.
    fn fade(&self, t: S<'c>) -> S<'c> {
        let inner = self.add(self.mul(t, self.sub(self.mul(t, self.fc(6.0)), self.fc(15.0))), self.fc(10.0));
        self.mul(self.mul(self.mul(t, t), t), inner)
    }

    /// `a + t·(b − a)`.
    fn lerp(&self, t: S<'c>, a: S<'c>, b: S<'c>) -> S<'c> {
        self.add(a, self.mul(t, self.sub(b, a)))
    }

    /// `(h & m) == 0`.
    fn bit_clear(&self, h: I<'c>, m: u32) -> M<'c> {
        let a = self.ibin('&', h, self.iconst(h, m));
        self.ieq(a, self.iconst(h, 0))
    }

    /// Perlin's 16-case 3D gradient `dot(g[h & 15], (x, y, z))`: `±u ± v` with `u` = x or y
    /// (bit 3) and `v` = y, x or z (bits 2..3 and the cases 12, 14), each sign the xor of a hash
    /// bit moved to the float's sign bit — the library's register lookups (one rounding, the
    /// same value) as shifts, two selects and xors.
    fn grad3(&self, h: I<'c>, x: S<'c>, y: S<'c>, z: S<'c>) -> S<'c> {
        let lt8 = self.bit_clear(h, 8);
        let lt4 = self.bit_clear(h, 12);
        let is12or14 = self.ieq(self.ibin('&', h, self.iconst(h, 13)), self.iconst(h, 12));
        let u = self.sel(lt8, x, y);
        let v = self.sel(lt4, y, self.sel(is12or14, x, z));
        self.add(self.xor_sign(u, self.bit_to_sign(h, 0)), self.xor_sign(v, self.bit_to_sign(h, 1)))
    }

    /// Bit `k` of `h` moved to the sign bit, every other bit clear.
    fn bit_to_sign(&self, h: I<'c>, k: u32) -> I<'c> {
        self.ibin('&', self.ibin('<', h, self.iconst(h, 31 - k)), self.iconst(h, 0x8000_0000))
    }

    /// `s` with its sign bits (value and derivative parts alike) xored with `bits` (0 or the
    /// sign bit per lane): a negation where the bit is set, as `neg` computes it. `s` and
    /// `bits` have one shape: both come from the same (unified) coordinates.
    fn xor_sign(&self, s: S<'c>, bits: I<'c>) -> S<'c> {
        let flip = |f: BasicValueEnum<'c>| -> BasicValueEnum<'c> {
            let it = bits.0.get_type();
            let fi = self.b.build_bit_cast(f, it, "").expect("bitcast");
            let x = self.ibin('^', I(fi), bits).0;
            self.b.build_bit_cast(x, f.get_type(), "").expect("bitcast")
        };
        S { r: s.r, v: flip(s.v), d: s.d.map(|(dx, dy)| (flip(dx), flip(dy))) }
    }

    /// 4D gradient: the 16 corners (±1, ±1, ±1, ±1), hash bit `k` the sign of component `k`.
    fn grad4(&self, h: I<'c>, p: [S<'c>; 4]) -> S<'c> {
        let s = |k: u32| self.xor_sign(p[k as usize], self.bit_to_sign(h, k));
        self.add(self.add(self.add(s(0), s(1)), s(2)), s(3))
    }

    /// The lattice hash of the cell `c` (Teschner primes, then the `lowbias32` finaliser).
    fn lattice_hash(&self, c: &[I<'c>], seed: u32, like: BasicValueEnum<'c>) -> I<'c> {
        let mut h = self.iconst_like(like, seed.wrapping_mul(PRIMES[4]));
        for (axis, &ci) in c.iter().enumerate() {
            h = self.ibin('^', h, self.ibin('*', ci, self.iconst(ci, PRIMES[axis])));
        }
        h = self.ibin('^', h, self.ibin('>', h, self.iconst(h, 16)));
        h = self.ibin('*', h, self.iconst(h, FINALIZE[0]));
        h = self.ibin('^', h, self.ibin('>', h, self.iconst(h, 15)));
        h = self.ibin('*', h, self.iconst(h, FINALIZE[1]));
        self.ibin('^', h, self.ibin('>', h, self.iconst(h, 16)))
    }

    /// `(h >> 8) · 2^-24`: the top 24 hash bits as a float in [0, 1) (exact).
    fn bits_to_unit(&self, h: I<'c>) -> BasicValueEnum<'c> {
        let top = self.ibin('>', h, self.iconst(h, 8));
        let f: BasicValueEnum<'c> = match top.0 {
            BasicValueEnum::IntValue(x) => self.b.build_signed_int_to_float(x, self.f32t, "").expect("sitofp").into(),
            BasicValueEnum::VectorValue(x) => {
                let n = x.get_type().get_size();
                self.b.build_signed_int_to_float(x, self.f32t.vec_type(n), "").expect("sitofp").into()
            }
            _ => unreachable!("integer lanes"),
        };
        let scale = self.constant_like(f, 1.0 / 16_777_216.0);
        self.arith('*', f, scale)
    }

    /// Bits of `floor(x) as i32` (saturating, NaN → 0: Rust `as`, like `floor_bits`). Clamped
    /// into range before a plain conversion: LLVM 14 scalarizes `llvm.fptosi.sat` on vectors.
    fn floor_bits(&self, x: BasicValueEnum<'c>) -> I<'c> {
        let xf = self.unary_intr("llvm.floor", x);
        let lo = self.constant_like(x, -2_147_483_648.0);
        // The largest f32 below 2^31.
        let hi = self.constant_like(x, 2_147_483_520.0);
        let clamped = self.call_intr(
            "llvm.minnum",
            &[x.get_type()],
            &[self.call_intr("llvm.maxnum", &[x.get_type()], &[xf, lo]), hi],
        );
        let conv = self.fptosi(clamped);
        let over = self.fcmp_raw(FloatPredicate::OGE, xf, self.constant_like(x, 2_147_483_648.0));
        let nan = self.fcmp_raw(FloatPredicate::UNO, x, x);
        let v = self.sel_raw(over, self.iconst_like(x, i32::MAX as u32).0, conv);
        I(self.sel_raw(nan, self.iconst_like(x, 0).0, v))
    }

    /// Bits of the integer `x`, |x| ≤ 2^31, modulo 2^32 (`lattice_bits`): 2^31 gives the bits
    /// of -2^31. A plain conversion of the value clamped below 2^31 (out-of-range `fptosi` is
    /// poison), and i32::MIN where it was 2^31.
    fn lattice_bits(&self, x: BasicValueEnum<'c>) -> I<'c> {
        let top = self.constant_like(x, 2_147_483_648.0);
        // `x < hi ? x : hi`, one `minps` (NaN gives `hi`, in range): `llvm.minnum` would add
        // the NaN handling it specifies.
        let hi = self.constant_like(x, 2_147_483_520.0);
        let clamped = self.sel_raw(self.fcmp_raw(FloatPredicate::OLT, x, hi), x, hi);
        let conv = self.fptosi(clamped);
        let at_top = self.fcmp_raw(FloatPredicate::OGE, x, top);
        I(self.sel_raw(at_top, self.iconst_like(x, i32::MIN as u32).0, conv))
    }

    /// `fptosi` to i32 lanes shaped like `x` (in range: out of it the result is poison).
    fn fptosi(&self, x: BasicValueEnum<'c>) -> BasicValueEnum<'c> {
        match x {
            BasicValueEnum::FloatValue(f) => {
                self.b.build_float_to_signed_int(f, self.cx.i32_type(), "").expect("fptosi").into()
            }
            BasicValueEnum::VectorValue(v) => {
                let n = v.get_type().get_size();
                self.b.build_float_to_signed_int(v, self.cx.i32_type().vec_type(n), "").expect("fptosi").into()
            }
            _ => unreachable!("float lanes"),
        }
    }

    /// The float constant `c` shaped like `x`.
    fn constant_like(&self, x: BasicValueEnum<'c>, c: f64) -> BasicValueEnum<'c> {
        match x {
            BasicValueEnum::VectorValue(_) => self.fconst_r(c, Repr::V),
            _ => self.f32t.const_float(c).into(),
        }
    }

    /// The integer constant `c` in lanes shaped like the float value `x`.
    fn iconst_like(&self, x: BasicValueEnum<'c>, c: u32) -> I<'c> {
        let k = self.cx.i32_type().const_int(u64::from(c), false);
        I(match x {
            BasicValueEnum::VectorValue(v) => {
                let n = v.get_type().get_size() as usize;
                inkwell::types::VectorType::const_vector(&vec![k; n]).into()
            }
            _ => k.into(),
        })
    }

    /// The integer constant `c` shaped like `like`.
    fn iconst(&self, like: I<'c>, c: u32) -> I<'c> {
        self.iconst_like(like.0, c)
    }

    /// Wrapping integer op: `+`, `*`, `^`, `&`, `>` (logical shift right) or `<` (shift left).
    fn ibin(&self, op: char, a: I<'c>, b: I<'c>) -> I<'c> {
        macro_rules! go {
            ($x:expr, $y:expr) => {
                match op {
                    '+' => self.b.build_int_add($x, $y, "").expect("add").into(),
                    '*' => self.b.build_int_mul($x, $y, "").expect("mul").into(),
                    '^' => self.b.build_xor($x, $y, "").expect("xor").into(),
                    '&' => self.b.build_and($x, $y, "").expect("and").into(),
                    '<' => self.b.build_left_shift($x, $y, "").expect("shl").into(),
                    _ => self.b.build_right_shift($x, $y, false, "").expect("lshr").into(),
                }
            };
        }
        I(match (a.0, b.0) {
            (BasicValueEnum::IntValue(x), BasicValueEnum::IntValue(y)) => go!(x, y),
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => go!(x, y),
            _ => unreachable!("integer lanes of one shape"),
        })
    }

    /// `a == b` as a mask.
    fn ieq(&self, a: I<'c>, b: I<'c>) -> M<'c> {
        match (a.0, b.0) {
            (BasicValueEnum::IntValue(x), BasicValueEnum::IntValue(y)) => {
                let v = self.b.build_int_compare(IntPredicate::EQ, x, y, "").expect("cmp");
                // Scalar lanes: a uniform value, or any value of the scalar variant, where
                // `sel` treats uniform and varying masks alike.
                M { uni: true, v: v.into() }
            }
            (BasicValueEnum::VectorValue(x), BasicValueEnum::VectorValue(y)) => {
                M { uni: false, v: self.b.build_int_compare(IntPredicate::EQ, x, y, "").expect("cmp").into() }
            }
            _ => unreachable!("integer lanes of one shape"),
        }
    }
}
