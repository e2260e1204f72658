"""Manufacturing and assembly deviations of a pair: what makes a real gear pair differ from the
exact one, tooth by tooth (docs/geometry.md, "Deviations", with the picture of the signs).

Per tooth of either gear (µm):

* **pitch**: the tooth displaced along its pitch circle, turned about its gear's centre (its
  position deviation: a measuring machine's cumulative pitch deviation at that tooth);
* **slope**: the profile slope deviation f_Hα, normal to the loaded flank, growing linearly
  along the active profile from nothing at its root end to the value at its tip end;
* **form**: the profile form deviation, a parabola along the active profile, nothing at its
  ends and the value at its middle (or a measured curve of roll fraction → µm, ``curve``).

Per pair: the **centre-distance** deviation (µm, the centres farther apart) and each gear's
**runout** (radial runout F_r, µm, twice the eccentricity of its teeth about its axis, and the
phase of the high point, degrees from tooth 0's centre in the gear's own frame).

**One sign for every deviation of a tooth: a positive value moves its loaded flank towards its
mate** (the flanks the torque on gear 1, counter-clockwise, presses together), adding material
or closing the clearance: gear 1's tooth is turned counter-clockwise, gear 2's clockwise, and a
profile deviation adds material. The centre distance and the runout are geometry: a positive
centre-distance deviation moves gear 1's centre away from gear 2's, which brings the teeth near
the pitch point deeper into the mesh.

Everything here is exact geometry in mm and rad (:meth:`Deviations.turns`,
:meth:`Deviations.centre_offset`, :meth:`Deviations.flank_offset`); the solve applies it to the
rigid gaps of the model it keeps (docs/solve.md, "Deviations").
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ..checks import require_finite
from ..errors import ParameterError

#: the largest deviation fegear takes, µm: far beyond ISO 1328-1's coarsest class for any
#: module fegear solves (class 11, m 100, d 2 m: about 900 µm) and below what closes a pair
LIMIT_UM = 1000.0
GEARS = (1, 2)


def _micron(name: str, value) -> float:
    if isinstance(value, bool):
        raise ParameterError(name, value, f"-{LIMIT_UM:g} <= {name} <= {LIMIT_UM:g} µm")
    try:
        x = float(value)
    except (TypeError, ValueError):
        x = math.nan
    if not math.isfinite(x) or abs(x) > LIMIT_UM:
        raise ParameterError(name, value, f"-{LIMIT_UM:g} <= {name} <= {LIMIT_UM:g} µm")
    return x


@dataclass(frozen=True)
class ToothDeviation:
    """One tooth's deviations (µm; positive: its loaded flank towards its mate): ``pitch``,
    ``slope``, ``form`` and a measured form ``curve`` ((roll fraction 0..1, µm) pairs, in
    place of the parabola)."""

    pitch: float = 0.0
    slope: float = 0.0
    form: float = 0.0
    curve: tuple[tuple[float, float], ...] = ()

    def __post_init__(self) -> None:
        for name in ("pitch", "slope", "form"):
            object.__setattr__(self, name, _micron(f"{name}-deviation", getattr(self, name)))
        if self.curve:
            u = np.array([c[0] for c in self.curve], dtype=float)
            if len(u) < 2 or not np.all(np.diff(u) > 0) or u[0] < 0 or u[-1] > 1:
                raise ParameterError("form-curve", self.curve, "two or more (roll fraction, µm) "
                                     "pairs, the fractions rising within 0 ... 1")
            for _, v in self.curve:
                _micron("form-curve", v)

    @property
    def profiled(self) -> bool:
        """Whether the flank itself departs from the exact profile."""
        return bool(self.slope or self.form or self.curve)

    def normal_um(self, roll: np.ndarray) -> np.ndarray:
        """The flank's normal departure (µm, + adds material) at roll fractions ``roll`` (0 at
        the active profile's root end, 1 at its tip end; outside, the end's value)."""
        u = np.clip(np.asarray(roll, dtype=float), 0.0, 1.0)
        out = self.slope * u
        if self.curve:
            out = out + np.interp(u, [c[0] for c in self.curve], [c[1] for c in self.curve])
        elif self.form:
            out = out + 4.0 * self.form * u * (1.0 - u)
        return out


@dataclass(frozen=True)
class Runout:
    """A gear's radial runout ``fr`` (µm, twice its eccentricity) with its high point at
    ``phase`` degrees from tooth 0's centre, in the gear's own frame."""

    fr: float = 0.0
    phase: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "fr", _micron("runout", self.fr))
        if self.fr < 0:
            raise ParameterError("runout", self.fr, f"0 <= runout <= {LIMIT_UM:g} µm (the radial "
                                 "runout; its direction is the phase)")
        object.__setattr__(self, "phase", require_finite("runout phase", self.phase))

    def offset(self, tooth0: float) -> np.ndarray:
        """The centre of the gear's teeth from its axis (mm, fixed frame) with tooth 0's
        centre at polar angle ``tooth0`` (rad, fixed frame, about the axis)."""
        a = math.radians(self.phase) + tooth0
        return 0.5e-3 * self.fr * np.array([math.cos(a), math.sin(a)])


@dataclass(frozen=True)
class Deviations:
    """A pair's deviations: per tooth of gear 1 and of gear 2 (tooth index → deviation; a
    tooth not named has none), the centre distance's (µm) and each gear's runout. The empty
    one is the exact pair."""

    gear1: Mapping[int, ToothDeviation] = field(default_factory=dict)
    gear2: Mapping[int, ToothDeviation] = field(default_factory=dict)
    centre_distance: float = 0.0
    runout1: Runout = Runout()
    runout2: Runout = Runout()

    def __post_init__(self) -> None:
        object.__setattr__(self, "centre_distance",
                           _micron("centre-distance-deviation", self.centre_distance))
        for gear in GEARS:
            teeth = dict(self.teeth(gear))
            object.__setattr__(self, f"gear{gear}", {int(k): v for k, v in sorted(teeth.items())
                                                    if v != ToothDeviation()})

    def teeth(self, gear: int) -> Mapping[int, ToothDeviation]:
        return self.gear1 if gear == 1 else self.gear2

    def __bool__(self) -> bool:
        return bool(self.gear1 or self.gear2 or self.centre_distance or self.runout1.fr
                    or self.runout2.fr)

    def check_teeth(self, z1: int, z2: int) -> None:
        """Refuse, by name, a tooth that does not exist on its gear."""
        for gear, z in ((1, z1), (2, z2)):
            for tooth in self.teeth(gear):
                if not 0 <= tooth < z:
                    raise ParameterError("pitch-deviation", f"{gear}:{tooth}", f"a tooth "
                                         f"0 ... {z - 1} of gear {gear} (z{gear} = {z})")

    def largest_um(self) -> float:
        """The largest amount any deviation moves a flank (µm): what a contact grid must reach
        beyond the exact pair's."""
        per_tooth = [abs(d.pitch) + abs(d.slope) + abs(d.form)
                     + max((abs(v) for _, v in d.curve), default=0.0)
                     for gear in GEARS for d in self.teeth(gear).values()]
        return (max(per_tooth, default=0.0) + abs(self.centre_distance)
                + 0.5 * (self.runout1.fr + self.runout2.fr))

    def turns(self, gear: int, teeth: np.ndarray, r: float) -> np.ndarray:
        """The extra turn (rad, counter-clockwise) of each of ``teeth`` of ``gear`` about its
        centre, its pitch circle of radius ``r`` (mm): + for gear 1, − for gear 2 (module
        docstring)."""
        table = self.teeth(gear)
        sign = 1.0 if gear == 1 else -1.0
        um = np.array([table[t].pitch if t in table else 0.0 for t in np.ravel(teeth)])
        return sign * 1e-3 * um / r

    def centre_offset(self, tooth0_1: float, tooth0_2: float) -> np.ndarray:
        """Where gear 1's teeth stand relative to gear 2's, from the exact pair (mm, fixed
        frame), with tooth 0 of gear 1 at polar angle ``tooth0_1`` about its axis and tooth 0
        of gear 2 at ``tooth0_2`` about its own (rad, fixed frame): the centre distance's
        deviation along the line of centres, each gear's runout turning with it."""
        return (np.array([0.0, 1e-3 * self.centre_distance]) + self.runout1.offset(tooth0_1)
                - self.runout2.offset(tooth0_2))

    def flank_offset(self, gear: int, teeth: np.ndarray, roll: np.ndarray) -> np.ndarray:
        """The normal departure (mm, + adds material) of ``gear``'s loaded flanks at points
        of ``teeth`` at roll fractions ``roll``."""
        table = self.teeth(gear)
        teeth, roll = np.ravel(teeth), np.ravel(roll)
        out = np.zeros(len(teeth))
        for t in np.unique(teeth):
            d = table.get(int(t))
            if d is not None and d.profiled:
                sel = teeth == t
                out[sel] = 1e-3 * d.normal_um(roll[sel])
        return out


NONE = Deviations()
