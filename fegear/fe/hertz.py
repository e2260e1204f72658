"""Hertz line contact (two cylinders, or a cylinder in a bore), per unit thickness.

    1/R* = 1/r1 + 1/r2   (a negative radius is concave: a bore)
    E*   = (1/E1' + 1/E2')⁻¹,  E' = E (plane stress) or E/(1 − ν²) (plane strain)
    b    = sqrt(4 q R* / (π E*)),   p0 = 2 q / (π b),   q = P / t

Valid for b ≪ R*: every result carries b/R* so that the caller can judge. Units mm, N, MPa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..checks import require_finite
from ..errors import ParameterError
from .material import STEEL_E, STEEL_NU, Plane, contact_modulus, plane_modulus


@dataclass(frozen=True)
class HertzLine:
    """Hertz line-contact estimate: ``b`` half-width (mm), ``p0`` peak pressure (MPa),
    ``R_star`` effective radius (mm), ``E_star`` contact modulus (MPa), ``q`` load per thickness
    (N/mm), ``b_over_R`` = b/R* (the validity indicator: Hertz assumes b/R* ≪ 1)."""

    b: float
    p0: float
    R_star: float
    E_star: float
    q: float

    @property
    def b_over_R(self) -> float:
        return self.b / self.R_star


def effective_radius(r1: float, r2: float) -> float:
    """R* from two signed curvature radii (mm; negative = concave, inf = flat)."""
    for name, r in (("r1", r1), ("r2", r2)):
        if r == 0 or math.isnan(r):
            raise ParameterError(name, r, "a non-zero radius (negative = concave bore)")
    curvature = 1.0 / r1 + 1.0 / r2
    if not curvature > 0:
        raise ParameterError("r2", r2, f"r2 > 0, or r2 < -r1 = {-r1:g} (disk inside a larger bore)",
                             "the bodies do not touch at one point")
    return 1.0 / curvature


def line_contact(r1: float, r2: float, load: float, thickness: float, E1: float = STEEL_E,
                 nu1: float = STEEL_NU, E2: float | None = None, nu2: float | None = None,
                 plane: Plane = "stress") -> HertzLine:
    """Hertz half-width and peak pressure for a normal load ``load`` (N) over ``thickness`` (mm)."""
    E2 = E1 if E2 is None else E2
    nu2 = nu1 if nu2 is None else nu2
    for name, v in (("load", load), ("thickness", thickness), ("E", E1), ("E", E2)):
        require_finite(name, v)
        if not v > 0:
            raise ParameterError(name, v, f"{name} > 0")
    R = effective_radius(r1, r2)
    E_star = contact_modulus(plane_modulus(E1, nu1, plane), plane_modulus(E2, nu2, plane))
    q = load / thickness
    b = math.sqrt(4.0 * q * R / (math.pi * E_star))
    return HertzLine(b=b, p0=2.0 * q / (math.pi * b), R_star=R, E_star=E_star, q=q)
