"""The Hertz validation case's inputs: two disks pressed together, or a disk inside a bore,
checked before anything is meshed (:mod:`.disks` solves it)."""

from __future__ import annotations

from dataclasses import dataclass

from ..checks import number, require_finite, require_range
from ..contact import ContactSettings
from ..errors import ParameterError
from ..fe import STEEL_E, STEEL_NU, HertzLine, Material, Plane, line_contact

#: elements across the Hertz half-width b in the contact windows, per quality level
DISK_QUALITY = {"coarse": 4, "standard": 8, "fine": 16}

@dataclass(frozen=True)
class DiskCase:
    """Inputs: radii r1 > 0 and r2 (mm; r2 < −r1 for a bore), normal ``load`` P (N),
    ``thickness`` (mm), one material for both bodies, the plane assumption and the mesh quality
    (a name from :data:`DISK_QUALITY` or a number of elements across b)."""

    r1: float = 10.0
    r2: float = 10.0
    load: float = 1000.0
    thickness: float = 5.0
    E: float = STEEL_E
    nu: float = STEEL_NU
    plane: Plane = "stress"
    quality: str | float = "standard"
    penalty_factor: float = ContactSettings.penalty_factor

    def __post_init__(self) -> None:
        require_range("r1", self.r1, 0.0, 1e4, lo_open=True, unit="mm")
        if not abs(require_finite("r2", self.r2)) <= 1e4:
            raise ParameterError("r2", self.r2, "0 < |r2| <= 10000 mm (negative: a bore)")
        Material(self.E, self.nu, self.thickness, self.plane)  # validates E, ν, t, plane
        if isinstance(self.quality, str) and self.quality not in DISK_QUALITY:
            raise ParameterError("quality", self.quality, " / ".join(DISK_QUALITY))
        if not isinstance(self.quality, str) and not 1 <= (number(self.quality) or 0) <= 200:
            raise ParameterError("quality", self.quality, "1 <= elements across b <= 200")
        require_range("penalty_factor", self.penalty_factor, 0.0, 1e6, lo_open=True)
        h = self.hertz  # validates r2, load, thickness, E, plane
        if h.b >= 0.5 * min(self.r1, abs(self.r2)):
            raise ParameterError("load", self.load, f"load giving b < r/2 (b = {h.b:.3g} mm)")

    @property
    def material(self) -> Material:
        return Material(self.E, self.nu, self.thickness, self.plane)

    @property
    def hertz(self) -> HertzLine:
        return line_contact(self.r1, self.r2, self.load, self.thickness, self.E, self.nu,
                            plane=self.plane)

    @property
    def elements_per_b(self) -> float:
        return float(DISK_QUALITY[self.quality] if isinstance(self.quality, str) else self.quality)
