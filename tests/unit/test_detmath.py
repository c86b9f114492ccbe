"""The deterministic elementary functions (``kernels/src/detmath*.c``, through :mod:`flexbeam.numerics`) against
mpmath at 200 bits: error in ulps on dense grids, the hard cases of each function and Hypothesis-drawn arguments;
the special values of C99 Annex F; pow's exact cases; sincos = (sin, cos) bit for bit; the same bits whichever
variant of glibc's libm is loaded; and no call to a libm transcendental function in the source.

Error bounds.  Every function evaluates its result as a double-double whose relative error is below 2^-62 (the
error analyses in detmath*.c) and rounds it once, so it is within 0.5 ulp (that rounding) + 2^-62 / 2^-53 = 2^-9
ulp of the exact value.  Measured: the excess over 0.5 ulp is < 1.2e-4 ulp for every function but Gamma (2.2e5
random arguments and the grids below), so the bound is 16x the measurement.  Gamma: its double-double has an
absolute error of order 2^-62 in log Gamma; measured excess 5e-4 ulp, bound 2^-6 = 31x that.
"""

from __future__ import annotations

import ctypes
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from flexbeam import numerics
from flexbeam.kernels import _core

BOUND = 0.5 + 2.0**-9  # ulp: the final rounding + 2^-62 relative (module docstring)
GAMMA_BOUND = 0.5 + 2.0**-6  # ulp (module docstring)
DBL_MAX = sys.float_info.max
TINY = 5e-324
PREC = 200  # bits of the mpmath reference: 2^-147 beyond the double's 53 bits

KERNELS_SRC = Path(__file__).resolve().parents[2] / "src" / "flexbeam" / "kernels" / "src"
#: the elementary functions' sources: detmath.h, the internal headers and one file per function
DETMATH_FILES = sorted(KERNELS_SRC.glob("detmath*.[ch]"))


# ------------------------------------------------------------------------------------------------------ helpers
def ulp_errors(got, exact) -> np.ndarray:
    """|got - exact| in units of the spacing of doubles at ``exact`` (2^-1074 below the normal range).

    ``exact`` are mpmath numbers within the finite double range.  d = nearest double to exact and the residual
    exact - d rounded: got - d is exact for got within a few ulps of d (Sterbenz), so the error is
    |(got - d) - residual| / spacing, with the spacing of the binade below d when exact is just below a power of 2.
    """
    got = np.asarray(got, dtype=float).reshape(-1)
    d = np.array([float(e) for e in exact])
    res = np.array([float(e - mpmath.mpf(float(e))) for e in exact])
    spacing = np.spacing(np.abs(d))
    below = (np.abs(d) > 2.0**-1021) & (np.frexp(np.abs(d))[0] == 0.5) & (np.sign(res) == -np.sign(d))
    spacing[below] *= 0.5
    with np.errstate(invalid="ignore"):
        err = np.abs((got - d) - res) / spacing
    err[~np.isfinite(got)] = np.inf
    return err


def max_ulp(fn, ref, xs) -> tuple[float, float]:
    """(largest error in ulps, its argument) of numerics ``fn`` on the array ``xs`` against mpmath ``ref``."""
    xs = np.asarray(xs, dtype=float)
    with mpmath.workprec(PREC):
        exact = [ref(mpmath.mpf(x)) for x in xs]
        err = ulp_errors(fn(xs), exact)
    i = int(np.argmax(err))
    return float(err[i]), float(xs[i])


def max_ulp2(fn, ref, a, b) -> tuple[float, tuple[float, float]]:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    with mpmath.workprec(PREC):
        exact = [ref(mpmath.mpf(u), mpmath.mpf(v)) for u, v in zip(a, b)]
        err = ulp_errors(fn(a, b), exact)
    i = int(np.argmax(err))
    return float(err[i]), (float(a[i]), float(b[i]))


def one_ulp(fn, ref, x: float) -> float:
    with mpmath.workprec(PREC):
        return float(ulp_errors([fn(x)], [ref(mpmath.mpf(x))])[0])


def same(a: float, b: float) -> bool:
    """Equal as IEEE values including the sign of zero, or both NaN."""
    a, b = float(a), float(b)
    return (math.isnan(a) and math.isnan(b)) or (a == b and math.copysign(1.0, a) == math.copysign(1.0, b))


def logspace2(lo: float, hi: float, n: int) -> np.ndarray:
    """n doubles spread evenly in log2 between lo and hi (> 0), both included."""
    with np.errstate(over="ignore"):
        v = np.exp2(np.linspace(math.log2(lo), math.log2(hi), n))
    v[0], v[-1] = lo, hi
    return v


def nearest_doubles_to_multiples_of_pio2(kmax: int) -> np.ndarray:
    with mpmath.workprec(PREC):
        pio2 = mpmath.pi / 2
        return np.array([float(k * pio2) for k in range(1, kmax + 1)])


# --------------------------------------------------------------------------------------------------- exp, expm1
def test_exp_whole_range():
    xs = np.concatenate(
        [
            np.linspace(-745.13, 709.78, 6001),
            logspace2(1e-300, 1.0, 1000),
            -logspace2(1e-300, 1.0, 1000),
            np.linspace(-745.13, -708.4, 1001),  # subnormal results
            [709.782712893383, -745.1332191019411, 2.0**-53, -(2.0**-54), 1e-320],
        ]
    )
    err, x = max_ulp(numerics.exp, mpmath.exp, xs)
    assert err <= BOUND, (err, x)


@pytest.mark.parametrize("fn", ["exp", "expm1"])
def test_exp_overflow_threshold(fn):
    """inf exactly where e^x >= DBL_MAX + ulp/2 (rounds to inf), within the bound below; 8 doubles around."""
    f, ref = getattr(numerics, fn), getattr(mpmath, fn)
    x0 = 709.782712893384
    for x in [x0 + k * 2.0**-43 for k in range(-4, 5)]:  # 2^-43: the spacing at 709
        with mpmath.workprec(PREC):
            overflows = ref(mpmath.mpf(x)) >= mpmath.mpf(DBL_MAX) + mpmath.ldexp(1, 1023 - 53)
        if overflows:
            assert f(x) == math.inf, x
        else:
            assert one_ulp(f, ref, x) <= BOUND, x


def test_exp_underflow_threshold():
    """Around 2^-1075 (half the smallest subnormal): 0 below, 2^-1074 above, within the bound in subnormal ulps."""
    x0 = -745.1332191019411
    for x in [x0 + k * 2.0**-43 for k in range(-4, 5)] + [-744.4400719213812, -708.3964185322641]:
        assert one_ulp(numerics.exp, mpmath.exp, x) <= BOUND, x
    assert numerics.exp(-745.1332191019412) == 0.0 and numerics.exp(-745.1332191019411) == TINY


def test_expm1_whole_range():
    xs = np.concatenate(
        [
            np.linspace(-40.0, 709.78, 4001),
            logspace2(1e-300, 1.0, 1500),
            -logspace2(1e-300, 1.0, 1500),
            np.linspace(-0.36, 0.36, 1001),
            np.nextafter(0.0625, [0.0, 1.0]),  # the two branches meet
            np.nextafter(-0.0625, [0.0, -1.0]),
            [-37.5, -38.0, np.nextafter(-38.0, 0.0), 709.782712893383, 1e-320, -1e-320, 2.0**-60, 2.0**-61],
        ]
    )
    err, x = max_ulp(numerics.expm1, mpmath.expm1, xs)
    assert err <= BOUND, (err, x)


# ------------------------------------------------------------------------------------------------------ log, log1p
def test_log_whole_range():
    k = np.arange(1, 2001)
    xs = np.concatenate(
        [
            logspace2(TINY, DBL_MAX, 6001),  # subnormal and normal arguments
            1.0 + k * 2.0**-52,
            1.0 - k * 2.0**-53,
            np.linspace(0.99, 1.01, 2001),
            np.linspace(1.40, 1.43, 301),  # m and m/2 around the table's switch at 1.4140625
            [DBL_MAX, TINY, 2.0**-1022, np.nextafter(2.0**-1022, 0.0), 0.5, 2.0, math.e],
        ]
    )
    err, x = max_ulp(numerics.log, mpmath.log, xs)
    assert err <= BOUND, (err, x)


def test_log1p_whole_range():
    k = np.arange(1, 1001)
    xs = np.concatenate(
        [
            logspace2(TINY, DBL_MAX, 4001),
            -logspace2(TINY, 1.0 - 2.0**-53, 4001),
            -1.0 + k * 2.0**-53,  # 1 + x near 0
            k * 2.0**-52,
            -k * 2.0**-53,
            np.linspace(-0.01, 0.01, 2001),
            np.nextafter(2.0**-8, [0.0, 1.0]),  # the two branches meet
            np.nextafter(-(2.0**-8), [0.0, -1.0]),
            [2.0**-60, 2.0**-61, -(2.0**-61), 1e-320],
        ]
    )
    err, x = max_ulp(numerics.log1p, mpmath.log1p, xs)
    assert err <= BOUND, (err, x)


# --------------------------------------------------------------------------------------------------- sin, cos
def test_sin_cos_grids():
    xs = np.concatenate(
        [
            np.linspace(-10.0, 10.0, 4001),
            logspace2(TINY, 1e6, 2001),
            -logspace2(1e-10, 1e6, 2001),
            logspace2(1e6, 2.0**30, 1001),  # past the Cody-Waite range (1.6e6): Payne-Hanek
            logspace2(2.0**30, DBL_MAX, 1001),
            [355.0, float(np.pi * 1e6), 1.6e6, np.nextafter(1.6e6, 0.0), float(np.pi / 4), 2.0**20, 2.0**30],
            [2.0**52, 2.0**53, 2.0**1023, DBL_MAX, 6381956970095103 * 2.0**797],  # the last: |x mod pi/2| ~ 2^-61
        ]
    )
    for fn, ref in ((numerics.sin, mpmath.sin), (numerics.cos, mpmath.cos)):
        err, x = max_ulp(fn, ref, xs)
        assert err <= BOUND, (fn.__name__, err, x)


def test_sin_cos_at_the_doubles_nearest_to_multiples_of_pio2():
    """The doubles closest to k pi/2, k = 1..1e5: the function that vanishes there (sin for even k, cos for odd k)
    is as small as |x - k pi/2| (2^-60.5 at k = 29): the reduction must keep ~120 bits of pi/2."""
    kmax = 100_000
    xs = nearest_doubles_to_multiples_of_pio2(kmax)
    k = np.arange(1, kmax + 1)
    even = k % 2 == 0
    err_s, x_s = max_ulp(numerics.sin, mpmath.sin, xs[even])
    err_c, x_c = max_ulp(numerics.cos, mpmath.cos, xs[~even])
    assert err_s <= BOUND, (err_s, x_s)
    assert err_c <= BOUND, (err_c, x_c)
    # and the other one (+-1 up to 2^-120) at a sample
    err_o, x_o = max_ulp(numerics.cos, mpmath.cos, xs[even][::50])
    assert err_o <= BOUND, (err_o, x_o)


def test_sincos_is_sin_and_cos_bit_for_bit():
    """fb_sincos (the integrator's call, not exposed in Python: through ctypes) gives the bits of fb_sin, fb_cos."""
    lib = ctypes.CDLL(_core.__file__)
    sincos = lib.fb_sincos
    sincos.restype = None
    sincos.argtypes = [ctypes.c_double, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)]
    xs = np.concatenate(
        [
            np.linspace(-20.0, 20.0, 2001),
            nearest_doubles_to_multiples_of_pio2(200),
            -logspace2(TINY, DBL_MAX, 301),
            logspace2(TINY, DBL_MAX, 301),
            [0.0, -0.0, math.inf, -math.inf, math.nan],
        ]
    )
    s_ref, c_ref = numerics.sin(xs), numerics.cos(xs)
    s, c = ctypes.c_double(), ctypes.c_double()
    for x, sr, cr in zip(xs, s_ref, c_ref):
        sincos(float(x), ctypes.byref(s), ctypes.byref(c))
        assert same(s.value, sr) and same(c.value, cr), x


# -------------------------------------------------------------------------------------------------------- pow
def test_pow_grid():
    """x over the whole range, y such that z = y log x spans the finite results (-745, 709.7), subnormal ones
    included; x near 1 with |y| up to 2^61, where log x needs its double-double."""
    rng = np.random.default_rng(7)
    x = np.concatenate(
        [logspace2(TINY, DBL_MAX, 2000), 1.0 + np.arange(1, 501) * 2.0**-52, 1.0 - np.arange(1, 501) * 2.0**-53]
    )
    z = np.concatenate([rng.uniform(-745.0, 709.7, x.size - 500), rng.uniform(-745.0, -708.4, 500)])
    y = z / np.log(x)  # numpy's log: any y will do, the reference is mpmath's x^y
    err, xy = max_ulp2(numerics.pow, mpmath.power, x, y)
    assert err <= BOUND, (err, xy)
    small = logspace2(1e-3, 1e3, 400)
    yy = np.linspace(-30.0, 30.0, 400)
    err, xy = max_ulp2(numerics.pow, mpmath.power, small, yy)
    assert err <= BOUND, (err, xy)


#: pow(x, 1.5) and pow(x, 2.5) on (2^-300, 2^300) take x sqrt(x) in double-double (detmath_pow.c, pow_odd_half):
#: relative error before the final rounding ~2^-103 (derived there), i.e. below 0.5 + 2^-40 ulp
ODD_HALF_BOUND = 0.5 + 2.0**-40
HARD_ODD_HALF = {
    1.5: ["0x1.ecc44cf035a36p+3", "0x1.9dc9f2fc94ec8p-21", "0x1.db90e92191582p-29"],
    2.5: ["0x1.e4ec4bae68d77p-31", "0x1.4e8c30e902df8p-19", "0x1.42da210a74462p-18", "0x1.1ee971bcdf978p-11"],
}


@pytest.mark.parametrize("y", [1.5, 2.5])
def test_pow_odd_half_is_correctly_rounded(y):
    """The contact laws' exponent 3/2 and their potential's 5/2: x spread over the fast path's whole range, and
    contact-like penetrations (1e-12 to 1e-2 m) densely; both ends of the range and just beyond (the general
    path)."""
    rng = np.random.default_rng(11)
    x = np.concatenate(
        [logspace2(2.0**-300, 2.0**300, 3000), np.exp(rng.uniform(math.log(1e-12), math.log(1e-2), 20000))]
    )
    x = np.concatenate([x, np.nextafter([2.0**-300, 2.0**300], [0.0, math.inf]), [2.0**-300, 2.0**300]])
    err, xy = max_ulp2(numerics.pow, mpmath.power, x, np.full_like(x, y))
    assert err <= ODD_HALF_BOUND, (err, xy)
    # arguments whose x^y lies 1e-6 to 2e-5 ulp from a rounding midpoint, found among 2e6 random ones: exp(y log x)
    # (error < 0.502 ulp) rounded them the wrong way; within 2^-50 ulp the fast path rounds them correctly
    hard = [float.fromhex(h) for h in HARD_ODD_HALF[y]]
    err, xy = max_ulp2(numerics.pow, mpmath.power, hard, np.full(len(hard), y))
    assert err < 0.5, (err, xy)


def test_pow_integer_powers_of_negative_bases():
    x = -logspace2(1e-3, 1e3, 300)
    y = np.tile(np.arange(-50.0, 51.0, 1.0), 3)[: x.size]
    err, xy = max_ulp2(numerics.pow, mpmath.power, x, y)
    assert err <= BOUND, (err, xy)
    assert numerics.pow(-2.0, 3.0) == -8.0 and numerics.pow(-2.0, -3.0) == -0.125


def test_pow_exact_cases():
    """pow(x, 0) = 1, pow(x, 1) = x, pow(x, 2) = x*x, pow(x, 0.5) = sqrt(x) for x >= 0, bit for bit."""
    xs = np.concatenate(
        [logspace2(TINY, DBL_MAX, 500), -logspace2(TINY, DBL_MAX, 500), [0.0, -0.0, math.inf, -math.inf]]
    )
    for x in xs:
        x = float(x)
        assert same(numerics.pow(x, 0.0), 1.0) and same(numerics.pow(x, -0.0), 1.0)
        assert same(numerics.pow(x, 1.0), x)
        assert same(numerics.pow(x, 2.0), x * x)
        if x > 0.0:
            assert same(numerics.pow(x, 0.5), math.sqrt(x))
    assert same(numerics.pow(math.nan, 0.0), 1.0) and same(numerics.pow(1.0, math.nan), 1.0)
    assert same(numerics.pow(0.0, 0.5), 0.0) and same(numerics.pow(-0.0, 0.5), 0.0)  # +0 per Annex F


INF = math.inf
# C99 Annex F, F.9.4.4: pow(x, y)
POW_SPECIAL = [
    (0.0, -3.0, INF),
    (-0.0, -3.0, -INF),
    (0.0, -2.0, INF),
    (-0.0, -2.0, INF),
    (-0.0, -0.5, INF),
    (0.0, -INF, INF),
    (-0.0, -INF, INF),
    (0.0, 3.0, 0.0),
    (-0.0, 3.0, -0.0),
    (-0.0, 2.0, 0.0),
    (-0.0, 0.5, 0.0),
    (-0.0, INF, 0.0),
    (-1.0, INF, 1.0),
    (-1.0, -INF, 1.0),
    (1.0, math.nan, 1.0),
    (math.nan, 0.0, 1.0),
    (math.nan, -0.0, 1.0),
    (-2.0, 0.5, math.nan),
    (-2.0, -1.5, math.nan),
    (0.5, -INF, INF),
    (-0.5, -INF, INF),
    (2.0, -INF, 0.0),
    (-2.0, -INF, 0.0),
    (0.5, INF, 0.0),
    (-0.5, INF, 0.0),
    (2.0, INF, INF),
    (-2.0, INF, INF),
    (-INF, -3.0, -0.0),
    (-INF, -2.0, 0.0),
    (-INF, -0.5, 0.0),
    (-INF, 3.0, -INF),
    (-INF, 2.0, INF),
    (-INF, 0.5, INF),
    (INF, -0.5, 0.0),
    (INF, 0.5, INF),
    (math.nan, 1.5, math.nan),
    (1.5, math.nan, math.nan),
    (2.0, 1e300, INF),  # |y log x| beyond 745: overflow and underflow, signs of odd and even powers
    (2.0, -1e300, 0.0),
    (-2.0, 1e300, INF),
    (-2.0, 2.0**53 + 2.0, INF),
    (-2.0, -(2.0**52) - 1.0, -0.0),
    (1.0 + 2.0**-52, 2.0**64, INF),
    (1.0 - 2.0**-53, 2.0**64, 0.0),
    (-1.0, 2.0**64, 1.0),
    (-1.0, 3.0, -1.0),
    (-1.0, 2.0**53 - 1.0, -1.0),
    (10.0, 308.5, INF),
    (10.0, -324.0, 0.0),
    (-10.0, -323.0, -1e-323),
]


@pytest.mark.parametrize("x, y, expected", POW_SPECIAL)
def test_pow_special_values(x, y, expected):
    assert same(numerics.pow(x, y), expected)


@given(
    st.floats(min_value=2.0**-60, max_value=2.0**60, allow_nan=False),
    st.floats(min_value=-745.0, max_value=709.0, allow_nan=False),
)
def test_pow_hypothesis(x, z):
    if x == 1.0:
        return
    y = z / math.log(x)
    if not math.isfinite(y):
        return
    with mpmath.workprec(PREC):
        err = float(ulp_errors([numerics.pow(x, y)], [mpmath.power(mpmath.mpf(x), mpmath.mpf(y))])[0])
    assert err <= BOUND, (x, y, err)


# ------------------------------------------------------------------------------------------------------- atan2
def test_atan2_grid_all_quadrants():
    theta = np.linspace(-math.pi, math.pi, 2001)
    rows = []
    for r in (1e-300, 1e-5, 1.0, 1e5, 1e300):
        rows.append((r * np.sin(theta), r * np.cos(theta)))
    t = np.concatenate([np.linspace(0.0, 1.0, 1001), logspace2(2.0**-70, 2.0**-50, 101)])  # ratios: the table's i/64
    for sy, sx in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
        rows.append((sy * t, sx * np.ones_like(t)))
        rows.append((sy * np.ones_like(t), sx * t))
    rows.append((logspace2(TINY, 1e-300, 200), logspace2(1e-310, 1e300, 200)))  # subnormal and extreme ratios
    rows.append((logspace2(1e300, DBL_MAX, 200), -logspace2(1e290, DBL_MAX, 200)))
    y = np.concatenate([r[0] for r in rows])
    x = np.concatenate([r[1] for r in rows])
    keep = (x != 0.0) & (y != 0.0)  # zeros: the special values below (mpmath has no signed zero)
    err, yx = max_ulp2(numerics.atan2, mpmath.atan2, y[keep], x[keep])
    assert err <= BOUND, (err, yx)


PI, PIO2, PIO4 = math.pi, math.pi / 2, math.pi / 4  # the nearest doubles, as Annex F asks for
# C99 Annex F, F.9.1.4: atan2(y, x)
ATAN2_SPECIAL = [
    (0.0, -0.0, PI),
    (-0.0, -0.0, -PI),
    (0.0, 0.0, 0.0),
    (-0.0, 0.0, -0.0),
    (0.0, -1.0, PI),
    (-0.0, -1.0, -PI),
    (0.0, 1.0, 0.0),
    (-0.0, 1.0, -0.0),
    (-1.0, 0.0, -PIO2),
    (-1.0, -0.0, -PIO2),
    (1.0, 0.0, PIO2),
    (1.0, -0.0, PIO2),
    (1.0, -INF, PI),
    (-1.0, -INF, -PI),
    (1.0, INF, 0.0),
    (-1.0, INF, -0.0),
    (INF, 1.0, PIO2),
    (-INF, 1.0, -PIO2),
    (INF, -INF, 3 * PIO4),
    (-INF, -INF, -3 * PIO4),
    (INF, INF, PIO4),
    (-INF, INF, -PIO4),
    (math.nan, 1.0, math.nan),
    (1.0, math.nan, math.nan),
    (TINY, DBL_MAX, 0.0),  # the ratio underflows
    (-TINY, -DBL_MAX, -PI),
    (1.0, 1.0, PIO4),
    (-1.0, -1.0, -3 * PIO4),
]


@pytest.mark.parametrize("y, x, expected", ATAN2_SPECIAL)
def test_atan2_special_values(y, x, expected):
    assert same(numerics.atan2(y, x), expected)


@given(
    st.floats(allow_nan=False, allow_infinity=False, allow_subnormal=True),
    st.floats(allow_nan=False, allow_infinity=False, allow_subnormal=True),
)
def test_atan2_hypothesis(y, x):
    if x == 0.0 or y == 0.0:  # the special values above (mpmath has no signed zero)
        return
    with mpmath.workprec(PREC):
        err = float(ulp_errors([numerics.atan2(y, x)], [mpmath.atan2(mpmath.mpf(y), mpmath.mpf(x))])[0])
    assert err <= BOUND, (y, x, err)


# ------------------------------------------------------------------------------------------------------- Gamma
def test_gamma_grid():
    xs = np.concatenate(
        [
            np.linspace(2.0**-10, 171.62, 4001),
            logspace2(2.0**-1000, 1.0, 1001),
            np.arange(0.5, 171.0, 1.0),
            np.nextafter(12.0, [0.0, 13.0]),  # the recurrence and Stirling's series meet
            [2.0**-960, np.nextafter(2.0**-960, 0.0), 1e-300, 171.62437695630272],  # the last: Gamma ~ DBL_MAX
        ]
    )
    err, x = max_ulp(numerics.gamma, mpmath.gamma, xs)
    assert err <= GAMMA_BOUND, (err, x)


def test_gamma_hertz_contact_time_factor():
    """Gamma(1 + a) / Gamma(1/2 + a), a in (0, 1]: the use in the Hertz contact time."""
    a = np.linspace(2.0**-20, 1.0, 2001)
    for xs in (1.0 + a, 0.5 + a):
        err, x = max_ulp(numerics.gamma, mpmath.gamma, xs)
        assert err <= GAMMA_BOUND, (err, x)


def test_gamma_exact_values():
    """Gamma(n) = (n-1)! exactly for n <= 23 ((n-1)! is a double there, and the error before the final
    rounding, < 2^-6 ulp, cannot move a double's value to another); Gamma(1/2) = sqrt(pi) rounded."""
    for n in range(1, 24):
        assert numerics.gamma(float(n)) == float(math.factorial(n - 1)), n
    with mpmath.workprec(PREC):
        assert numerics.gamma(0.5) == float(mpmath.sqrt(mpmath.pi))


@pytest.mark.parametrize(
    "x, expected",
    [
        (0.0, INF),
        (-0.0, -INF),
        (INF, INF),
        (math.nan, math.nan),
        (-1.0, math.nan),
        (-0.5, math.nan),  # defined here for x > 0 only (detmath.h)
        (-INF, math.nan),
        (171.7, INF),
        (1e300, INF),
        (TINY, INF),  # 1/x overflows
        (1e-308, 1e308),
    ],
)
def test_gamma_special_values(x, expected):
    assert same(numerics.gamma(x), expected)


def test_gamma_overflow_threshold():
    """Finite up to the largest x with Gamma(x) below DBL_MAX + ulp/2, inf beyond."""
    x = 171.62437695630272
    for k in range(-3, 4):
        xk = x + k * 2.0**-45
        with mpmath.workprec(PREC):
            g = mpmath.gamma(mpmath.mpf(xk))
            overflows = g >= mpmath.mpf(DBL_MAX) + mpmath.ldexp(1, 1023 - 53)
        if overflows:
            assert numerics.gamma(xk) == INF
        else:
            assert one_ulp(numerics.gamma, mpmath.gamma, xk) <= GAMMA_BOUND


# ------------------------------------------------------------------------------------------------ special values
SPECIAL = {
    "exp": [(math.nan, math.nan), (INF, INF), (-INF, 0.0), (0.0, 1.0), (-0.0, 1.0), (710.0, INF), (-746.0, 0.0)],
    "expm1": [(math.nan, math.nan), (INF, INF), (-INF, -1.0), (0.0, 0.0), (-0.0, -0.0), (TINY, TINY), (-TINY, -TINY)]
    + [(-38.5, -1.0), (710.0, INF)],
    "log": [(math.nan, math.nan), (INF, INF), (-INF, math.nan), (0.0, -INF), (-0.0, -INF), (-1.0, math.nan)]
    + [(-TINY, math.nan), (1.0, 0.0)],
    "log1p": [(math.nan, math.nan), (INF, INF), (-INF, math.nan), (0.0, 0.0), (-0.0, -0.0), (-1.0, -INF)]
    + [(-2.0, math.nan), (TINY, TINY), (-TINY, -TINY)],
    "sin": [(math.nan, math.nan), (INF, math.nan), (-INF, math.nan), (0.0, 0.0), (-0.0, -0.0), (TINY, TINY)]
    + [(-TINY, -TINY), (1e-200, 1e-200)],
    "cos": [(math.nan, math.nan), (INF, math.nan), (-INF, math.nan), (0.0, 1.0), (-0.0, 1.0), (TINY, 1.0)],
}


@pytest.mark.parametrize("name", sorted(SPECIAL))
def test_special_values(name):
    fn = getattr(numerics, name)
    for x, expected in SPECIAL[name]:
        assert same(fn(x), expected), (name, x, fn(x))
        assert same(fn(np.array([x]))[0], expected), (name, x)  # the array path too


# -------------------------------------------------------------------------------------- Hypothesis, one argument
UNARY = {
    "exp": (mpmath.exp, st.floats(min_value=-745.13, max_value=709.78)),
    "expm1": (mpmath.expm1, st.floats(min_value=-40.0, max_value=709.78)),
    "log": (mpmath.log, st.floats(min_value=TINY, max_value=DBL_MAX)),
    "log1p": (mpmath.log1p, st.floats(min_value=-1.0, max_value=DBL_MAX, exclude_min=True)),
    "sin": (mpmath.sin, st.floats(allow_nan=False, allow_infinity=False)),
    "cos": (mpmath.cos, st.floats(allow_nan=False, allow_infinity=False)),
    "gamma": (mpmath.gamma, st.floats(min_value=TINY, max_value=171.6, exclude_min=True)),
}


@pytest.mark.parametrize("name", sorted(UNARY))
def test_unary_hypothesis(name):
    ref, strategy = UNARY[name]
    fn = getattr(numerics, name)
    bound = GAMMA_BOUND if name == "gamma" else BOUND

    @given(strategy)
    def check(x):
        if name == "gamma" and x < 1.0 / DBL_MAX:  # Gamma(x) > DBL_MAX
            assert fn(x) == INF
            return
        assert one_ulp(fn, ref, x) <= bound, (name, x)

    check()


# ------------------------------------------------------------------------------------------ machine independence
# The child reads the arguments' bytes from stdin (numpy's own exp2/cos that made them may change bits with the
# libm variant too) and prints the results' bytes.
_CHILD = """
import sys
import numpy as np
from flexbeam import numerics as N
x, p, q = np.frombuffer(bytes.fromhex(sys.stdin.read()), dtype=float).reshape(3, -1)
out = [N.sin(x), N.cos(x), N.exp(x % 1400.0 - 700.0), N.expm1(x % 1400.0 - 700.0), N.log(np.abs(x)),
       N.log1p(np.abs(x)), N.gamma(np.abs(x) % 171.0), N.pow(np.abs(x), p), N.atan2(x, q)]
print(np.concatenate(out).tobytes().hex())
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="GLIBC_TUNABLES: glibc only")
def test_bits_do_not_depend_on_the_libm_variant():
    """glibc picks FMA/AVX2 variants of exp, sin, cos, pow by CPU; with them disabled in a child process the
    functions give the same bits as here, on arguments that take every path of every function."""
    x = np.concatenate(
        [
            np.linspace(-20.0, 20.0, 801),
            logspace2(TINY, DBL_MAX, 400),
            -logspace2(1e-300, 1e300, 400),
            nearest_doubles_to_multiples_of_pio2(199),
        ]
    )
    p = np.linspace(-3.0, 3.0, x.size)
    q = np.cos(np.arange(x.size))  # any fixed values
    env = dict(os.environ, GLIBC_TUNABLES="glibc.cpu.hwcaps=-AVX2,-FMA")
    child = subprocess.run(
        [sys.executable, "-c", _CHILD],
        input=np.concatenate([x, p, q]).tobytes().hex(),
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert child.returncode == 0, child.stderr
    N = numerics
    mine = [N.sin(x), N.cos(x), N.exp(x % 1400.0 - 700.0), N.expm1(x % 1400.0 - 700.0), N.log(np.abs(x))]
    mine += [N.log1p(np.abs(x)), N.gamma(np.abs(x) % 171.0), N.pow(np.abs(x), p), N.atan2(x, q)]
    assert child.stdout.strip() == np.concatenate(mine).tobytes().hex()


# ------------------------------------------------------------------------------------------------ no libm calls
FORBIDDEN = {
    "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "asinh", "acosh", "atanh",
    "exp", "exp2", "exp10", "expm1", "log", "log2", "log10", "log1p", "logb", "ilogb", "pow", "pow10", "cbrt",
    "hypot", "erf", "erfc", "tgamma", "lgamma", "lgamma_r", "gamma", "sincos", "sinpi", "cospi", "fma", "j0",
    "j1", "jn", "y0", "y1", "yn",
}  # fmt: skip


def forbidden_calls(source: str) -> set[str]:
    """Names of libm transcendental functions (or fma; double, float, long double, __builtin_ spellings) called
    in C ``source``, comments ignored."""
    code = re.sub(r"/\*.*?\*/", " ", source, flags=re.S)
    code = re.sub(r"//[^\n]*", " ", code)
    called = set(re.findall(r"\b([A-Za-z_]\w*)\s*\(", code))
    bad = set()
    for name in called:
        base = name.removeprefix("__builtin_")
        if base in FORBIDDEN or (base[-1:] in ("f", "l") and base[:-1] in FORBIDDEN):
            bad.add(name)
    return bad


def test_the_detector_finds_a_libm_call():
    planted = "static double f(double x) { return exp(x) + __builtin_sinf(x) + fb_exp(x); } /* log(x) */ // pow(x)"
    assert forbidden_calls(planted) == {"exp", "__builtin_sinf"}


def test_detmath_calls_no_libm_transcendental_function():
    sources = {f.name: f.read_text() for f in DETMATH_FILES}
    # the scan covers the code: every function of detmath.h is defined in a scanned file
    declared = set(re.findall(r"\b(fb_\w+)\s*\(", sources["detmath.h"]))
    code = "".join(text for name, text in sources.items() if name.endswith(".c"))
    defined = {name for name in declared if re.search(rf"^(?:double|void) {name}\([^;{{]*\)\s*{{", code, flags=re.M)}
    assert len(declared) == 10 and defined == declared
    assert {name: bad for name, text in sources.items() if (bad := forbidden_calls(text))} == {}
