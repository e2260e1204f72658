"""Design parameters of a compound-cycloid internal tooth pair.

Conventions (``../shared/DOMAIN.md`` §1, which corrects the paper's eq. 15):

* ``r0 = m z2 / 2`` (gear-2 pitch radius), ``e1 = m h1``, ``e2 = f1 e1``,
  ``e = m (z2 - z1) / 2`` (centre distance).
* Gear 2 is the internal gear, gear 1 the external gear, ``z2 - z1 >= 1``.

Units: lengths in mm, angles in rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import ParameterError


def require_finite(name: str, value: float) -> float:
    """Return ``value`` as float or raise :class:`ParameterError` if it is not a finite number."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "a finite number") from None
    if not math.isfinite(x):
        raise ParameterError(name, value, "a finite number")
    return x


def require_range(name: str, value: float, lo: float | None, hi: float | None,
                  lo_open: bool = False, hi_open: bool = False, unit: str = "") -> float:
    """Check ``lo (<|<=) value (<|<=) hi``; raise a :class:`ParameterError` naming the range."""
    x = require_finite(name, value)
    ok_lo = lo is None or (x > lo if lo_open else x >= lo)
    ok_hi = hi is None or (x < hi if hi_open else x <= hi)
    if not (ok_lo and ok_hi):
        raise ParameterError(name, value, describe_range(name, lo, hi, lo_open, hi_open, unit))
    return x


def describe_range(name: str, lo: float | None, hi: float | None,
                   lo_open: bool = False, hi_open: bool = False, unit: str = "") -> str:
    """Human-readable interval such as ``0 < h1 <= 0.412``."""
    u = f" {unit}" if unit else ""
    left = "" if lo is None else f"{lo:.6g} {'<' if lo_open else '<='} "
    right = "" if hi is None else f" {'<' if hi_open else '<='} {hi:.6g}{u}"
    return f"{left}{name}{right}"


def require_int(name: str, value: object, lo: int) -> int:
    """Return ``value`` as int (an integral float is accepted) or raise a
    :class:`ParameterError` naming the bound."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(name, value, f"an integer >= {lo}")
    if isinstance(value, float) and (not math.isfinite(value) or value != int(value)):
        raise ParameterError(name, value, f"an integer >= {lo}")
    if int(value) < lo:
        raise ParameterError(name, value, f"an integer >= {lo}")
    return int(value)


@dataclass(frozen=True)
class PairParameters:
    """Compound-cycloid internal gear pair.

    Attributes:
        m: module [mm], > 0.
        z2: teeth of the internal gear (gear 2).
        z1: teeth of the external gear (gear 1), ``3 <= z1 < z2``.
        h1: tooth-height coefficient, ``e1 = m h1``.
        f1: tooth-shape coefficient, ``e2 = f1 e1``.
        shift: Δ1 [mm], "negative shift": gear 1 is generated at centre distance ``e + shift``.
        rotation: Δ2 [mm], "rotation" modification: the generating gear-2 tool uses
            ``e1 ∓ rotation`` (paper eq. 11); the gear 2 of the pair stays nominal.
        tip_relief: radial clearance [mm] between gear 1's tip and the far side of the nominal
            gear 2 in the assembled pair. ``None`` means the default, equal to ``shift``: the
            negative shift already gives about ``shift`` of radial clearance on the near side,
            so the default makes the tip clearance the same on both sides and keeps the
            assembled pair free of interference. ``tip_relief = -shift`` is the gear exactly as
            generated, without relief: it interferes by ≈ shift on the far side.
    """

    m: float = 2.0
    z2: int = 45
    z1: int = 44
    h1: float = 0.30
    f1: float = 0.15
    shift: float = 0.0
    rotation: float = 0.0
    tip_relief: float | None = None

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "m", require_range("m", self.m, 0.0, 100.0, lo_open=True, unit="mm"))
        set_(self, "z1", require_int("z1", self.z1, 3))
        set_(self, "z2", require_int("z2", self.z2, 4))
        if self.z2 <= self.z1:
            raise ParameterError("z2", self.z2, f"an integer z2 > z1 = {self.z1}",
                                 "the internal gear needs more teeth than the external gear")
        if self.z2 > 2000:
            raise ParameterError("z2", self.z2, f"an integer with {self.z1} < z2 <= 2000")
        set_(self, "h1", require_range("h1", self.h1, 0.0, self.z2 / 4.0,
                                       lo_open=True, hi_open=True))
        set_(self, "f1", require_range("f1", self.f1, 0.0, 1.0))
        e1 = self.m * self.h1
        set_(self, "shift", require_range("shift", self.shift, 0.0, 0.25 * e1, unit="mm"))
        set_(self, "rotation", require_range("rotation", self.rotation, -0.25 * e1, 0.25 * e1,
                                             unit="mm"))
        if self.tip_relief is not None:
            set_(self, "tip_relief", require_range("tip_relief", self.tip_relief, -self.shift,
                                                   e1, unit="mm"))

    @property
    def r0(self) -> float:
        """Gear-2 pitch radius [mm] (``m z2 / 2``)."""
        return self.m * self.z2 / 2.0

    @property
    def r1(self) -> float:
        """Gear-1 pitch radius [mm] (``m z1 / 2``)."""
        return self.m * self.z1 / 2.0

    @property
    def e1(self) -> float:
        """First crank length [mm] (``m h1``)."""
        return self.m * self.h1

    @property
    def e2(self) -> float:
        """Second crank length [mm] (``f1 e1``)."""
        return self.f1 * self.e1

    @property
    def e(self) -> float:
        """Nominal (assembled) centre distance [mm] (``m (z2 - z1) / 2``)."""
        return self.m * (self.z2 - self.z1) / 2.0

    @property
    def ratio(self) -> float:
        """Rolling-angle ratio α/β = z2/z1 (gear-1 angle per gear-2 angle)."""
        return self.z2 / self.z1

    @property
    def tip_clearance(self) -> float:
        """Effective gear-1 tip relief [mm] (``tip_relief`` or its default, ``shift``)."""
        return self.shift if self.tip_relief is None else self.tip_relief

    def describe(self) -> str:
        """Short text naming the parameters, for messages."""
        return (f"m={self.m:g}, z2={self.z2}, z1={self.z1}, h1={self.h1:g}, f1={self.f1:g}, "
                f"shift={self.shift:g}, rotation={self.rotation:g}")
