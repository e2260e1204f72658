"""A root of a scalar function in a bracket: Brent's method (1973), step for step as scipy's
``brentq`` takes it (its C source, ``scipy/optimize/Zeros/brentq.c``), so the same function
gives the same root to the bit.

Why not scipy's own: importing ``scipy.optimize`` loads its linear-programming code and, with
it, ``scipy.fft``, ``scipy.special`` and ``numpy.f2py``: 0.23 s of every fresh process that
builds a profile (each ``fegear`` command and study worker), for a dozen scalar roots.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from ..errors import GeometryError

EPS = 2.220446049250313e-16
RTOL = 4 * EPS        # the smallest relative tolerance (scipy's default)
MAX_ITERATIONS = 100


def brentq(f: Callable[[float], float], a: float, b: float, xtol: float = 2e-12,
           rtol: float = RTOL, maxiter: int = MAX_ITERATIONS) -> float:
    """A root of ``f`` in [a, b], where f(a) and f(b) differ in sign, to within
    ``xtol + rtol |x|`` (inverse quadratic interpolation, secant or bisection steps)."""
    if xtol <= 0 or rtol < RTOL:
        raise ValueError(f"xtol must be > 0 and rtol >= {RTOL}")
    xpre, xcur = float(a), float(b)
    xblk = fblk = spre = scur = 0.0
    fpre, fcur = f(xpre), f(xcur)
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    if math.copysign(1.0, fpre) == math.copysign(1.0, fcur):
        raise GeometryError("brentq: f(a) and f(b) must have different signs")
    for _ in range(maxiter):
        if fpre != 0 and fcur != 0 and math.copysign(1.0, fpre) != math.copysign(1.0, fcur):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:          # interpolate
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:                     # extrapolate
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre, scur = scur, stry   # a good short step
            else:
                spre = scur = sbis        # bisect
        else:
            spre = scur = sbis            # bisect
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        fcur = f(xcur)
    raise GeometryError(f"brentq: no root to {xtol:g} in {maxiter} iterations")
