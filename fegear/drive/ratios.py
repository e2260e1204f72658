"""Drive-level kinematics: transmission ratios and mesh efficiencies of planetary trains.

Carrier-fixed (transformed-mechanism) method (seed 002): subtracting the carrier speed ω_H from
every member turns the train into a fixed-axis train with the ratio
``i_ab^H = (ω_a − ω_H)/(ω_b − ω_H)``, signed (−1)^(external meshes) between a and b. With b
fixed: ``i_aH^b = ω_a/ω_H = 1 − i_ab^H``.

Efficiency by the meshing-power method (seed 002 §3): the transformed mechanism, with the same
torques, has the same mesh losses, ``η^H`` being the product of its mesh efficiencies. For a
moving central gear X, the other central gear fixed and ``i = i_XH = ω_X/ω_H``, the meshing
power is the fraction ``1 − 1/i`` of X's power; its sign says whether X drives the transformed
mechanism. Four cases (X driving or H driving, ``1 − 1/i`` positive or negative), each derived
from the torque balance ``T_X + T_fixed + T_H = 0`` with the loss ψ^H = 1 − η^H taken at the
driving end of the transformed mechanism. Only mesh losses: bearings, churning and the output
mechanism are not counted.

Conventions: ratios are ``ω_input/ω_output`` with signs (negative: the output turns the other
way); speeds positive in one chosen sense.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..checks import require_finite
from ..errors import ParameterError
from .inputs import RATIO_INPUTS

_ROW = {row.dest: row for row in RATIO_INPUTS}


@dataclass(frozen=True)
class Ratio:
    """A planetary train's ratio ω_input/ω_output (signed), the ratio of its transformed
    mechanism i^H (signed), and the members: fixed, input, output."""

    train: str
    value: float
    transformed: float
    fixed: str
    input: str
    output: str

    def efficiency(self, eta_h: float, reverse: bool = False) -> float:
        """Mesh efficiency input → output (``reverse``: output → input) by the meshing-power
        method (see the module)."""
        ix = 1.0 / self.value if self.input == "H" else self.value  # ω_X/ω_H
        return meshing_efficiency(ix, eta_h, carrier_drives=(self.input == "H") != reverse)


def _teeth(**z: int) -> None:
    for name, v in z.items():
        if isinstance(v, bool) or not isinstance(v, int) or v < 1:
            raise ParameterError(name, v, f"an integer number of teeth >= 1 ({name} >= 1)")


def carrier_ratio(i_ab_h: float) -> float:
    """``i_aH^b = 1 − i_ab^H``: central gear a to the carrier with central gear b fixed."""
    return 1.0 - i_ab_h


def ngw(za: int, zb: int) -> Ratio:
    """NGW (2K-H, negative): sun a in, ring b fixed, carrier H out; one planet meshes both.
    ``i_ab^H = −z_b/z_a``, ``i_aH^b = 1 + z_b/z_a``."""
    _teeth(za=za, zb=zb)
    t = -zb / za
    return Ratio("NGW", carrier_ratio(t), t, "b", "a", "H")


def two_kh(i_ab_h: float, fixed: str = "b") -> Ratio:
    """General 2K-H train given its transformed ratio i_ab^H (sign included): central gear b
    fixed, a in, carrier out (``i_aH^b = 1 − i_ab^H``); or ``fixed = "a"``: b in, H out
    (``i_bH^a = 1 − 1/i_ab^H``)."""
    row = _ROW["i_ab_h"]
    i = require_finite(row.name, i_ab_h, row.range_text)
    if i in (0.0, 1.0):
        raise ParameterError(row.name, i_ab_h, row.range_text)
    if fixed == "b":
        return Ratio("2K-H", carrier_ratio(i), i, "b", "a", "H")
    if fixed == "a":
        return Ratio("2K-H", carrier_ratio(1.0 / i), 1.0 / i, "a", "b", "H")
    raise ParameterError("fixed", fixed, '"a" or "b"')


def nn(zb: int, zc: int, zd: int, ze: int) -> Ratio:
    """NN (2K-H, positive): two rings, double planet c–d (c meshes the fixed ring b, d meshes
    the output ring e), carrier H in. ``i_eb^H = z_d z_b/(z_e z_c)``,
    ``i_He^b = 1/(1 − i_eb^H)``."""
    _teeth(zb=zb, zc=zc, zd=zd, ze=ze)
    t = zd * zb / (ze * zc)
    if t == 1.0:
        raise ParameterError("zd*zb/(ze*zc)", t, "≠ 1 (else ring e does not turn)")
    return Ratio("NN", 1.0 / carrier_ratio(t), t, "b", "H", "e")


def khv(zb: int, zc: int) -> Ratio:
    """N / K-H-V (few-tooth-difference): ring b fixed, eccentric H in, the planet's own rotation
    (V, through the W mechanism) out. ``i_cb^H = z_b/z_c``, ``i_HV = −z_c/(z_b − z_c)``."""
    _teeth(zb=zb, zc=zc)
    if zb <= zc:
        raise ParameterError("zb", zb, f"zb > zc = {zc} (internal ring around the planet)")
    t = zb / zc
    return Ratio("K-H-V", 1.0 / carrier_ratio(t), t, "b", "H", "V")


def internal_teeth(z1: int, z2: int) -> Ratio:
    """Internal-teeth planetary drive (seed 000, eq. 1): the internal ring 2 translates on two
    cranks (ω_2 = 0), crank H in, external gear 1 out. ``i_12^H = z_2/z_1``,
    ``i_H1 = −z_1/(z_2 − z_1)``: gear 1 turns against the crank."""
    _teeth(z1=z1, z2=z2)
    if z2 <= z1:
        raise ParameterError("z2", z2, f"z2 > z1 = {z1}")
    t = z2 / z1  # i_12^H: the internal mesh keeps the direction
    return Ratio("internal-teeth", 1.0 / carrier_ratio(t), t, "2", "H", "1")


def meshing_efficiency(i: float, eta_h: float, carrier_drives: bool) -> float:
    """Mesh efficiency of a 1-DOF 2K-H train between a moving central gear X and the carrier H
    (the other central gear fixed), ``i = ω_X/ω_H``, by the meshing-power method (seed 002):

    * X drives (X → H): ``1 − 1/i > 0``: ``[1 − η^H(1 − i)]/i``; else ``[η^H − (1 − i)]/(i η^H)``
    * H drives (H → X): ``1 − 1/i > 0``: ``i η^H/[η^H − (1 − i)]``; else ``i/[1 − η^H(1 − i)]``

    A result ≤ 0 means the train self-locks in that direction (only with H driven)."""
    eta = _ROW["eta_h"].check(eta_h)
    i = require_finite("ratio", i, "finite and non-zero")
    if i == 0.0:
        raise ParameterError("ratio", i, "finite and non-zero")
    if i == 1.0:
        return 1.0  # the train turns as a block: no meshing power, no mesh loss
    x_drives = 1.0 - 1.0 / i > 0.0  # X still drives the transformed mechanism
    if not carrier_drives:
        return ((1.0 - eta * (1.0 - i)) / i if x_drives
                else (eta - (1.0 - i)) / (i * eta))
    return (i * eta / (eta - (1.0 - i)) if x_drives
            else i / (1.0 - eta * (1.0 - i)))


def meshing_phase(rings: int) -> float:
    """Phase between the meshes of ``rings`` equally spaced rings (or eccentrics): 360°/n."""
    if isinstance(rings, bool) or not isinstance(rings, int) or rings < 1:
        raise ParameterError("rings", rings, "an integer >= 1")
    return 360.0 / rings
