"""The Hertz validation case's inputs: two disks pressed together, or a disk inside a bore,
checked before anything is meshed (:mod:`.disks` solves it)."""

from __future__ import annotations

from dataclasses import dataclass

from ..checks import number, require_finite, require_range
from ..errors import ParameterError
from ..fe import STEEL_E, STEEL_NU, ElasticMaterial, HertzLine, Plane, line_contact
from .disk_inputs import DISK_INPUTS, DISK_QUALITY
from .penalty import ContactSettings

_ROW = {row.name: row for row in DISK_INPUTS}


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
        r1 = _ROW["r1"].check(self.r1)
        bore = f"0 < r2 <= 10000 mm, or a bore: -10000 <= r2 < {-r1:g} mm"
        r2 = require_finite("r2", self.r2, bore)
        if not (0 < r2 <= 1e4 or -1e4 <= r2 < -r1):
            raise ParameterError("r2", self.r2, bore)
        ElasticMaterial(self.E, self.nu, self.thickness, self.plane)  # validates E, ν, t, plane
        if not (isinstance(self.quality, str) and self.quality in DISK_QUALITY
                or 1 <= (number(self.quality) or 0) <= 200):
            raise ParameterError("quality", self.quality, _ROW["quality"].range_text)
        _ROW["penalty-factor"].check(self.penalty_factor)
        top = self._largest_load()
        require_range("load", self.load, 0.0, top, lo_open=True, hi_open=True,
                      unit=f"N (the Hertz half-width b below r/2 at r1={r1:g}, r2={r2:g} mm)")

    def _largest_load(self) -> float:
        """The load (N) at which the Hertz half-width b reaches half the smaller radius."""
        unit = line_contact(self.r1, self.r2, 1.0, self.thickness, self.E, self.nu,
                            plane=self.plane)     # b grows as the load's square root
        return (0.5 * min(self.r1, abs(self.r2)) / unit.b) ** 2

    @property
    def material(self) -> ElasticMaterial:
        return ElasticMaterial(self.E, self.nu, self.thickness, self.plane)

    @property
    def hertz(self) -> HertzLine:
        return line_contact(self.r1, self.r2, self.load, self.thickness, self.E, self.nu,
                            plane=self.plane)

    @property
    def elements_per_b(self) -> float:
        return float(DISK_QUALITY[self.quality] if isinstance(self.quality, str) else self.quality)
