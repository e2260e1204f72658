"""Gear materials for a life rating: each one's endurance limits and the S-N lines its
treatment takes (docs/rating.md, "Materials", gives each number's source).

``sigma_Hlim`` is the flank's endurance limit in contact pressure and ``sigma_FE`` the root's
in local stress (ISO 6336-5's σ_Flim times the reference test gear's stress correction Y_ST =
2): the FE root stress is a local notch stress, so it is held against σ_FE, not against the
nominal σ_Flim that ISO 6336-3 multiplies by form and correction factors first.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, fields
from pathlib import Path

from ..errors import ParameterError
from .life import TREATMENTS


@dataclass(frozen=True)
class GearMaterial:
    """A gear material: ``name``, ``treatment`` (one of
    :data:`~.life.TREATMENTS`), the endurance limits ``sigma_Hlim`` (contact pressure, MPa)
    and ``sigma_FE`` (local root stress, MPa) and where they come from (``source``)."""

    name: str
    treatment: str
    sigma_Hlim: float
    sigma_FE: float
    source: str

    def __post_init__(self) -> None:
        if self.treatment not in TREATMENTS:
            raise ParameterError("treatment", self.treatment, " or ".join(TREATMENTS))
        for name in ("sigma_Hlim", "sigma_FE"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and 100.0 <= value <= 3000.0):
                raise ParameterError(name.replace("_", "-"), value, "100 <= MPa <= 3000")


#: the materials fegear knows by name; the first is the default
MATERIALS = {m.name: m for m in (
    GearMaterial("42CrMo", "through-hardened", 745.0, 558.0,
                 "seed paper 001: 42CrMo's allowable contact 745 MPa and bending 558 MPa, taken "
                 "as the endurance limits (the paper gives no S-N curve)"),
    GearMaterial("42CrMo-QT", "through-hardened", 770.0, 630.0,
                 "ISO 6336-5:2016, through-hardened wrought alloy steel, quality MQ, at 300 HV: "
                 "sigma_Hlim 770, sigma_Flim 315 MPa (sigma_FE = 2 sigma_Flim)"),
    GearMaterial("42CrMo-nitrided", "nitrided", 1000.0, 740.0,
                 "ISO 6336-5:2016, through-hardening steel nitrided, quality MQ: sigma_Hlim 1000, "
                 "sigma_Flim 370 MPa"),
    GearMaterial("20CrMnTi", "case-hardened", 1500.0, 1000.0,
                 "ISO 6336-5:2016, case-hardened wrought steel, quality MQ (GB/T 3480.5 gives "
                 "the same for 20CrMnTi carburised): sigma_Hlim 1500, sigma_Flim 500 MPa"),
    GearMaterial("18CrNiMo7-6", "case-hardened", 1500.0, 1000.0,
                 "ISO 6336-5:2016, case-hardened wrought steel, quality MQ: sigma_Hlim 1500, "
                 "sigma_Flim 500 MPa"),
)}


def material(name: str) -> GearMaterial:
    """The material of that name, or one read from a TOML file of that path (its keys
    :class:`GearMaterial`'s fields, ``name`` and ``source`` optional), refused by name."""
    if name in MATERIALS:
        return MATERIALS[name]
    path = Path(name)
    if not path.suffix == ".toml":
        raise ParameterError("material", name,
                             f"one of {', '.join(MATERIALS)} or a .toml file")
    try:
        values = tomllib.loads(path.read_text())
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise ParameterError("material", name, f"a readable TOML file ({exc})") from None
    known = {f.name for f in fields(GearMaterial)}
    unknown = sorted(set(values) - known)
    if unknown:
        raise ParameterError("material", name, f"keys among {', '.join(sorted(known))}, "
                             f"not {', '.join(unknown)}")
    missing = sorted({"treatment", "sigma_Hlim", "sigma_FE"} - set(values))
    if missing:
        raise ParameterError("material", name, f"a file giving {', '.join(missing)}")
    return GearMaterial(**{"name": path.stem, "source": f"given in {path.name}", **values})
