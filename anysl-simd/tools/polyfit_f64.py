#!/usr/bin/env python3
"""Generates the f64 polynomial coefficients of `pow`'s f64 path in `anysl-simd/src/math.rs`
(`LN_ATANH_P`, `EXP2_D`) and prints each one's weighted max error.

Method: interpolation at the Chebyshev nodes of the interval (near-minimax; L. N. Trefethen,
*Approximation Theory and Approximation Practice*, ch. 16), solved in 60-digit arithmetic
(mpmath) and rounded to f64; the error is measured against the function in the same precision.

Run: python3 anysl-simd/tools/polyfit_f64.py   (needs `pip install mpmath`)
"""
import mpmath as mp

mp.mp.dps = 60


def fit(fn, a, b, deg):
    n = deg + 1
    nodes = [mp.mpf(a + b) / 2 + mp.mpf(b - a) / 2 * mp.cos(mp.pi * (2 * i + 1) / (2 * n)) for i in range(n)]
    c = mp.lu_solve(mp.matrix([[x**j for j in range(n)] for x in nodes]), mp.matrix([fn(x) for x in nodes]))
    return [float(c[i]) for i in range(n)]


def max_err(fn, c, a, b, weight, samples=4000):
    e = mp.mpf(0)
    for i in range(samples + 1):
        z = mp.mpf(a) + (mp.mpf(b) - a) * i / samples
        p = mp.mpf(0)
        for k in reversed(c):
            p = p * z + mp.mpf(k)
        e = max(e, abs(p - fn(z)) * weight(z))
    return e


def report(name, fn, a, b, deg, weight):
    c = fit(fn, a, b, deg)
    print(f"{name}, degree {deg}: weighted max error {float(max_err(fn, c, a, b, weight)):.3e}")
    print("    " + ", ".join(repr(x) for x in c))


# ln m = 2s + s·z·P(z), s = (m-1)/(m+1), z = s², m in [√½, √2): P(z) = (2·atanh s - 2s)/s³.
def atanh_tail(z):
    if z < mp.mpf(10) ** -40:
        return mp.mpf(2) / 3
    s = mp.sqrt(z)
    return (2 * mp.atanh(s) - 2 * s) / (s * z)


ZMAX = ((mp.sqrt(2) - 1) / (mp.sqrt(2) + 1)) ** 2
# weight: relative error of ln m = 2s·(1 + z·P/2) caused by an error in P.
report("LN_ATANH_P on [0, 0.02944]", atanh_tail, 0, ZMAX * 1.0001, 4, lambda z: (z / 2) / (1 + z * atanh_tail(z) / 2))
# 2^r, |r| <= 0.5 (the round-to-nearest reduction of pow's exponent); relative error.
report("EXP2_D on [-0.5, 0.5]", lambda r: mp.power(2, r), -0.5001, 0.5001, 8, lambda r: 1 / mp.power(2, r))
