#!/usr/bin/env python3
"""Generates the polynomial coefficients used in `anysl-simd/src/math.rs`.

Method: Chebyshev interpolation (near-minimax; see L. N. Trefethen, *Approximation Theory
and Approximation Practice*, ch. 16) of each reduced function on its reduction interval,
converted exactly (rational arithmetic) to the monomial basis and rounded to f32. The
reduced functions are evaluated from their Taylor series in f64, which avoids the
cancellation of forms like (sin t - t) / t^3. Prints the coefficients (lowest degree first)
and the max error of the f32-rounded polynomial measured against the reference in f64.

Run: python3 anysl-simd/tools/polyfit.py
"""
import math
import struct
from fractions import Fraction


def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


def series(coef, z, kmax=80):
    return math.fsum(coef(k) * z**k for k in range(kmax))


def fit(fn, a, b, deg):
    n = deg + 1
    nodes = [(a + b) / 2 + (b - a) / 2 * math.cos(math.pi * (2 * i + 1) / (2 * n)) for i in range(n)]
    # Solve the Vandermonde system exactly.
    m = [[Fraction(x) ** j for j in range(n)] + [Fraction(fn(x))] for x in nodes]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        for r in range(n):
            if r != c and m[r][c] != 0:
                k = m[r][c] / m[c][c]
                m[r] = [x - k * y for x, y in zip(m[r], m[c])]
    return [f32(float(m[i][n] / m[i][i])) for i in range(n)]


def report(name, fn, a, b, deg, weight=lambda z: 1.0):
    c = fit(fn, a, b, deg)
    err = 0.0
    for i in range(4001):
        z = a + (b - a) * i / 4000
        p = 0.0
        for k in reversed(c):
            p = p * z + k
        err = max(err, abs(p - fn(z)) * weight(z))
    print(f"{name} on [{a}, {b}], degree {deg}: weighted max error {err:.3e}")
    print("    " + ", ".join(f"{x:.9e}" for x in c))


LN2 = math.log(2.0)
FACT = math.factorial

# 2^r = 1 + r * Q(r), |r| <= 0.5 (+ slack for the low part of pow's exponent).
Q = lambda r: series(lambda k: LN2 ** (k + 1) / FACT(k + 1), r, 40)
# weight: relative contribution to 2^r  (r * Q error / 2^r)
report("exp2 Q", Q, -0.5001, 0.5001, 6, lambda r: abs(r) / 2**r)

# ln(1+f) = f - f^2/2 + f^3 * L(f), f in [sqrt(1/2)-1, sqrt(2)-1]
L = lambda f: series(lambda k: (-1) ** k / (k + 3), f, 400)
lw = lambda f: abs(f**3 / math.log1p(f)) if f != 0 else 0.0
for d in (8, 9, 10):
    report("log L", L, math.sqrt(0.5) - 1, math.sqrt(2) - 1, d, lw)

# sin r = r + r^3 * S(r^2);  cos r = 1 - r^2/2 + r^4 * C(r^2);  |r| <= 0.82
ZS = 0.82**2
S = lambda z: series(lambda k: (-1) ** (k + 1) / FACT(2 * k + 3), z, 30)
C = lambda z: series(lambda k: (-1) ** k / FACT(2 * k + 4), z, 30)
for d in (3, 4):
    report("sin S", S, 0.0, ZS, d, lambda z: z)
for d in (3, 4):
    report("cos C", C, 0.0, ZS, d, lambda z: z * z / math.cos(math.sqrt(z)))

# tan r = r + r^3 * T(r^2), |r| <= 0.82
T = lambda z: (math.tan(math.sqrt(z)) - math.sqrt(z)) / (z * math.sqrt(z)) if z > 1e-4 else 1 / 3 + 2 * z / 15 + 17 * z * z / 315
for d in (6, 7, 8):
    report("tan T", T, 0.0, ZS, d, lambda z: z)

# asin t = t + t^3 * A(t^2), t in [0, 0.6] (|x| > 0.6 goes through asin(sqrt((1-x)/2)))
A = lambda z: series(lambda k: FACT(2 * k + 2) / (4 ** (k + 1) * FACT(k + 1) ** 2 * (2 * k + 3)), z, 400)
for d in (6, 7):
    report("asin A", A, 0.0, 0.36, d, lambda z: z)

# atan t = t + t^3 * P(t^2), t in [0, 1] (atan2 reduces to a ratio <= 1)
def P(z):
    if z > 1e-3:
        t = math.sqrt(z)
        return (math.atan(t) - t) / (z * t)
    return series(lambda k: (-1) ** (k + 1) / (2 * k + 3), z, 60)
for d in (8, 9):
    report("atan P", P, 0.0, 1.0, d, lambda z: z)

# Constants split for extended precision.
def split(x, bits=24):
    hi = f32(x)
    return hi, f32(x - hi)

def split_short(x, bits):
    e = math.frexp(x)[1]
    hi = math.floor(x * 2 ** (bits - e)) / 2 ** (bits - e)
    return hi, f32(x - hi)

print("log2(e) hi/lo", split(1 / LN2))
print("ln2 hi(16 bits)/lo", split_short(LN2, 16))
print("ln2 hi/lo", split(LN2))
print("pi/2 hi/lo", split(math.pi / 2))
print("pi/4 hi/lo", split(math.pi / 4))
print("pi hi/lo", split(math.pi))
from decimal import Decimal, getcontext
getcontext().prec = 60
HALF_PI = Decimal("3.14159265358979323846264338327950288419716939937510582097494") / 2
h = f32(HALF_PI)
m = f32(HALF_PI - Decimal(h))
print("pi/2 three-part (Cody-Waite)", h, m, f32(HALF_PI - Decimal(h) - Decimal(m)))

# log2(1+f) = f * Q(f), f in [sqrt(1/2)-1, sqrt(2)-1] (pow's logarithm): relative error of Q
def Q2(f):
    if abs(f) < 1e-3:
        return math.fsum((-1) ** k * f**k / (k + 1) for k in range(30)) / LN2
    return math.log1p(f) / f / LN2
report("log2 Q", Q2, math.sqrt(0.5) - 1, math.sqrt(2) - 1, 8, lambda f: 1 / Q2(f))
