"""The flank tolerances of an ISO 1328-1:2013 class for a gear of module m and reference
diameter d (docs/tolerance.md, "Classes").

ISO 1328-1:2013 ("Cylindrical gears — ISO system of flank tolerance classification — Part 1")
gives each tolerance of class A as a formula in m and d (µm, mm), a factor √2 from one class to
the next, class 5 the base:

* single pitch        f_pT  = (0.001 d + 0.4 m + 5) · √2^(A−5)            (formula 5)
* cumulative pitch    F_pT  = (0.002 d + 0.55 √d + 0.7 m + 12) · √2^(A−5)  (formula 6)
* profile slope       f_HαT = (0.4 m + 0.001 d + 4) · √2^(A−5)             (formula 7)
* profile form        f_fαT = (0.55 m + 5) · √2^(A−5)                      (formula 8)
* total profile       F_αT  = √(f_HαT² + f_fαT²)                           (formula 9)
* runout              F_rT  = 0.9 F_pT                           (its informative annex)

and across the face, with the face width b (mm; :func:`helix_tolerances`):

* helix slope         f_HβT = (0.05 √d + 0.35 √b + 4) · √2^(A−5)
* helix form          f_fβT = (0.07 √d + 0.45 √b + 4) · √2^(A−5)
* total helix         F_βT  = √(f_HβT² + f_fβT²)                         (as F_αT)

Each is rounded as the standard rounds them: above 10 µm to the whole µm, from 5 to 10 µm to
0.5 µm, below 5 µm to 0.1 µm (F_αT from the unrounded two). The classes run from 1 (finest)
to 11; the formulas hold for 0.5 <= m <= 70 mm, 5 <= d <= 15 000 mm and 5 <= z <= 1 000. A
compound-cycloid gear has no pressure angle of its own in these formulas: only m and d = m z
enter, as for any cylindrical gear.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import ParameterError

#: the classes ISO 1328-1:2013 defines, finest first
CLASSES = range(1, 12)
#: where its formulas hold: module (mm), reference diameter (mm), number of teeth
MODULE_RANGE = (0.5, 70.0)
DIAMETER_RANGE = (5.0, 15000.0)
TEETH_RANGE = (5, 1000)


def rounded(um: float) -> float:
    """A tolerance rounded as ISO 1328-1:2013 rounds them (module docstring)."""
    if um > 10.0:
        return float(round(um))
    if um >= 5.0:
        return round(2.0 * um) / 2.0
    return round(10.0 * um) / 10.0


@dataclass(frozen=True)
class ClassTolerances:
    """The tolerances (µm) of class ``grade`` for one gear of module ``m`` (mm) and ``z``
    teeth (reference diameter d = m z): single pitch ``f_pT``, cumulative pitch ``F_pT``,
    profile slope ``f_HaT``, profile form ``f_faT``, total profile ``F_aT`` and runout
    ``F_rT``, each rounded as the standard does."""

    grade: int
    m: float
    z: int
    f_pT: float
    F_pT: float
    f_HaT: float
    f_faT: float
    F_aT: float
    F_rT: float

    @property
    def d(self) -> float:
        """The reference diameter (mm)."""
        return self.m * self.z

    def summary(self) -> dict:
        """As JSON (µm)."""
        return {"grade": self.grade, "m_mm": self.m, "z": self.z, "d_mm": self.d,
                "f_pT_um": self.f_pT, "F_pT_um": self.F_pT, "f_HaT_um": self.f_HaT,
                "f_faT_um": self.f_faT, "F_aT_um": self.F_aT, "F_rT_um": self.F_rT}


def check_grade(grade) -> int:
    """``grade`` as a class of :data:`CLASSES`, refused by name otherwise."""
    admissible = f"a whole number {CLASSES[0]} ... {CLASSES[-1]} (ISO 1328-1:2013's classes)"
    if isinstance(grade, bool):
        raise ParameterError("grade", grade, admissible)
    try:
        a = float(grade)
    except (TypeError, ValueError):
        raise ParameterError("grade", grade, admissible) from None
    if not math.isfinite(a) or a != int(a) or int(a) not in CLASSES:
        raise ParameterError("grade", grade, admissible)
    return int(a)


def class_tolerances(grade: int, m: float, z: int) -> ClassTolerances:
    """Class ``grade``'s tolerances for a gear of module ``m`` (mm) and ``z`` teeth (module
    docstring); a gear outside the formulas' range is refused by name."""
    grade = check_grade(grade)
    d = m * z
    for name, value, (lo, hi) in (("m", m, MODULE_RANGE), ("z", z, TEETH_RANGE)):
        if not lo <= value <= hi:
            raise ParameterError("grade", grade, f"a gear within ISO 1328-1:2013's range "
                                 f"({lo:g} <= {name} <= {hi:g}; this one's {name} is "
                                 f"{value:g})")
    if not DIAMETER_RANGE[0] <= d <= DIAMETER_RANGE[1]:
        raise ParameterError("grade", grade, f"a gear within ISO 1328-1:2013's range "
                             f"({DIAMETER_RANGE[0]:g} <= d <= {DIAMETER_RANGE[1]:g} mm; this "
                             f"one's d = m z is {d:g} mm)")
    step = math.sqrt(2.0) ** (grade - 5)
    f_p = (0.001 * d + 0.4 * m + 5.0) * step
    F_p = (0.002 * d + 0.55 * math.sqrt(d) + 0.7 * m + 12.0) * step
    f_H = (0.4 * m + 0.001 * d + 4.0) * step
    f_f = (0.55 * m + 5.0) * step
    return ClassTolerances(grade, m, z, rounded(f_p), rounded(F_p), rounded(f_H), rounded(f_f),
                           rounded(math.hypot(f_H, f_f)), rounded(0.9 * F_p))


@dataclass(frozen=True)
class HelixTolerances:
    """The helix tolerances (µm) of class ``grade`` for one gear of reference diameter ``d``
    and face width ``b`` (mm): helix slope ``f_HbT``, helix form ``f_fbT`` and total helix
    ``F_bT``, each rounded as the standard does (:func:`helix_class`)."""

    grade: int
    d: float
    b: float
    f_HbT: float
    f_fbT: float
    F_bT: float

    def summary(self) -> dict:
        """As JSON (µm)."""
        return {"grade": self.grade, "d_mm": self.d, "b_mm": self.b, "f_HbT_um": self.f_HbT,
                "f_fbT_um": self.f_fbT, "F_bT_um": self.F_bT}


def helix_class(grade: int, d: float, b: float) -> HelixTolerances:
    """Class ``grade``'s helix tolerances for a gear of reference diameter ``d`` and face
    width ``b`` (mm; module docstring): the total F_βT from the unrounded two, as F_αT."""
    step = math.sqrt(2.0) ** (check_grade(grade) - 5)
    f_H = (0.05 * math.sqrt(d) + 0.35 * math.sqrt(b) + 4.0) * step
    f_f = (0.07 * math.sqrt(d) + 0.45 * math.sqrt(b) + 4.0) * step
    return HelixTolerances(int(grade), d, b, rounded(f_H), rounded(f_f),
                           rounded(math.hypot(f_H, f_f)))


def helix_tolerances(grade: int, d: float, b: float) -> tuple[float, float]:
    """Class ``grade``'s helix slope and helix form tolerances f_HβT and f_fβT (µm, rounded as
    the others) for a gear of reference diameter ``d`` and face width ``b`` (mm; module
    docstring): :func:`helix_class`'s."""
    t = helix_class(grade, d, b)
    return t.f_HbT, t.f_fbT
