"""Materials of plane bodies: elastic constants, the plane assumption, and the moduli that
Hertz theory and the contact penalty use.

scikit-fem 12.0.2's ``plane_stress(E, nu)`` returns the plane-stress Lamé pair (λ*, μ) to feed
``linear_elasticity`` directly; the older idiom ``lame_parameters(*plane_stress(E, nu))``
silently gives λ < 0 (docs/model.md, "Library notes"). Units MPa, mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, get_args

from ..checks import Input
from ..errors import ParameterError

#: the plane assumption: σzz = 0 (a thin gear) or εzz = 0
Plane = Literal["stress", "strain"]
PLANE_MODES: tuple[str, ...] = get_args(Plane)
#: the steel every default means (42CrMo): Young's modulus (MPa) and Poisson ratio
STEEL_E = 206000.0
STEEL_NU = 0.29


def plane_modulus(E: float, nu: float, plane: Plane) -> float:
    """E' = E in plane stress, E/(1 − ν²) in plane strain (MPa)."""
    if plane not in PLANE_MODES:
        raise ParameterError("plane", plane, "'stress' or 'strain'")
    return E if plane == "stress" else E / (1.0 - nu * nu)


def contact_modulus(E1_plane: float, E2_plane: float) -> float:
    """E* = 1 / (1/E1' + 1/E2') from the two plane moduli (MPa)."""
    return 1.0 / (1.0 / E1_plane + 1.0 / E2_plane)


#: one isotropic material, and the thickness (face width) of a plane body
MATERIAL_INPUTS = (
    Input("face-width", float, 5.0, "face width: the thickness of the plane bodies", "mm",
          low=0.0, high=1e4, low_open=True, aliases=("thickness",)),
    Input("E", float, STEEL_E, "Young's modulus", "MPa", low=0.0, high=1e7,
          low_open=True),  # diamond: 1.2e6
    Input("nu", float, STEEL_NU, "Poisson ratio", low=0.0, high=0.5, high_open=True),
)

#: allowable stresses of the material, for the safety factors S = allowable / stress; the
#: defaults are 42CrMo's (quenched and tempered): σ_FP 558 MPa in bending, σ_HP 745 MPa in
#: contact. They only read the results (``post``): no solve depends on them.
ALLOWABLE_INPUTS = (
    Input("allowable-bending", float, 558.0, "allowable root stress σ_FP of the material "
          "(42CrMo) for the bending safety factors S_F = σ_FP / root σ1", "MPa",
          low=0.0, high=1e5, low_open=True, post=True),
    Input("allowable-contact", float, 745.0, "allowable contact pressure σ_HP of the material "
          "(42CrMo) for the contact safety factor S_H = σ_HP / peak contact pressure", "MPa",
          low=0.0, high=1e5, low_open=True, post=True),
)
_ROW = {row.name: row for row in (*MATERIAL_INPUTS, *ALLOWABLE_INPUTS)}


@dataclass(frozen=True)
class ElasticMaterial:
    """Isotropic linear-elastic plane body: Young's modulus ``E`` (MPa), Poisson ratio ``nu``,
    ``thickness`` (mm) and the plane assumption: ``"stress"`` (σzz = 0, thin gear) or
    ``"strain"`` (εzz = 0)."""

    E: float = STEEL_E
    nu: float = STEEL_NU
    thickness: float = 5.0
    plane: Plane = "stress"

    def __post_init__(self) -> None:
        for name, field in (("E", "E"), ("nu", "nu"), ("face-width", "thickness")):
            _ROW[name].check(getattr(self, field))
        if self.plane not in PLANE_MODES:
            raise ParameterError("plane", self.plane, "'stress' or 'strain'")

    @property
    def lame(self) -> tuple[float, float]:
        """In-plane Lamé parameters (λ, μ) of the chosen plane assumption, MPa."""
        from skfem.models.elasticity import lame_parameters, plane_stress

        if self.plane == "stress":
            return plane_stress(self.E, self.nu)
        return lame_parameters(self.E, self.nu)

    @property
    def plane_modulus(self) -> float:
        """E' of Hertz theory: E in plane stress, E/(1 − ν²) in plane strain (MPa)."""
        return plane_modulus(self.E, self.nu, self.plane)

    @property
    def shear_modulus(self) -> float:
        return self.E / (2.0 * (1.0 + self.nu))


@dataclass(frozen=True)
class Allowables:
    """A material's allowable stresses (MPa): ``bending`` σ_FP at the tooth root (max
    principal stress), ``contact`` σ_HP on the flank (contact pressure). The defaults are
    42CrMo's. Plain material limits, not ISO 6336 permissible stresses (no life, size,
    roughness or lubrication factors)."""

    bending: float = 558.0
    contact: float = 745.0

    def __post_init__(self) -> None:
        _ROW["allowable-bending"].check(self.bending)
        _ROW["allowable-contact"].check(self.contact)
