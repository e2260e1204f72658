"""Design parameters of a compound-cycloid internal tooth pair.

Conventions (docs/model.md, "Parameters", which corrects the seed paper's eq. 15):

* ``r0 = m z2 / 2`` (gear-2 pitch radius), ``e1 = m h1``, ``e2 = f1 e1``,
  ``e = m (z2 - z1) / 2`` (centre distance).
* Gear 2 is the internal gear, gear 1 the external gear, ``z2 - z1 >= 1``.

Units: lengths in mm, angles in rad.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..checks import Input, require_int, require_range
from ..errors import ParameterError

#: the lowest tooth-height coefficient: teeth 4 m h1 = 0.2 m high (the solve stopped settling
#: below h1 ≈ 0.03 on the seed paper's pair; the paper's own range is 0.2-0.4)
H1_MIN = 0.05

#: tip relief shapes (:mod:`.relief`) and the default extent, in modules
SHAPES = ("parabolic", "arc", "linear")
EXTENT_DEFAULT = 0.25

#: inputs renamed since an earlier release, with what a study file should say now
RENAMED = {"tip-relief": "tip-clearance (the radial clearance at gear 1's tip; tip relief now "
                         "means the flank modification: relief, relief-extent, relief-start, "
                         "relief-shape)"}

#: the pair's inputs (``fegear profile``, ``solve`` and ``bench``, study files); the ranges of
#: h1, shift, rotation and tip-clearance depend on the other inputs and are checked by
#: :class:`PairParameters` and :func:`~fegear.geometry.refusal.check_design`
PAIR_INPUTS = (
    Input("m", float, 2.0, "module", "mm", low=0.0, high=100.0, low_open=True),
    Input("z2", int, 45, "teeth of the internal gear (gear 2)", low=4, high=2000,
          limits="an integer z1 < z2 <= 2000"),
    Input("z1", int, 44, "teeth of the external gear (gear 1)", low=3, high=1999,
          limits="an integer 3 <= z1 < z2"),
    Input("h1", float, 0.30, "tooth-height coefficient (e1 = m h1)", low=H1_MIN,
          limits=f"{H1_MIN:g} <= h1 < z2/4 and the design admissible"),
    Input("f1", float, 0.15, "tooth-shape coefficient (e2 = f1 e1)", low=0.0, high=1.0,
          limits="0 <= f1 <= 1 and the design admissible"),
    Input("shift", float, None, "Δ1 negative shift: gear 1 generated at centre distance "
          "e + shift", "mm", limits="0 <= shift <= m h1/4 and the pair clear before any load",
          rule="0.008 m (the seed paper's 0.016 mm at m = 2), at most m h1/4"),
    Input("rotation", float, None, "Δ2 rotation modification of the generating tool", "mm",
          limits="|rotation| <= m h1/4 and the pair clear before any load",
          rule="0.001 m (the seed paper's 0.002 mm at m = 2), at most m h1/4, halved until "
               "the pair is clear before any load (at most six times, then 0)"),
    Input("tip-clearance", float, None, "radial clearance of gear 1's tip to the far side of "
          "gear 2", "mm", limits="-shift <= tip-clearance <= m h1 and the tip clear before "
          "any load", rule="= shift, at least 0.001 m"),
    Input("relief", float, 0.0, "tip relief of gear 1's flanks: depth cut normal to the "
          "profile at the tip end (0: none)", "µm", low=0.0,
          limits="0 <= relief <= 50 m µm and fitting the flank"),
    Input("relief-extent", float, None, "length of the tip relief along the flank from the "
          "tip end", "mm", low=0.0, low_open=True,
          limits="0 < relief-extent < the working flank's length",
          rule=f"{EXTENT_DEFAULT:g} m where there is a relief"),
    Input("relief-start", float, None, "or: the radius where the tip relief starts, instead "
          "of relief-extent", "mm", low=0.0, low_open=True,
          limits="gear 1's root radius < relief-start < its working flank's tip end",
          rule="none (relief-extent sets the start)"),
    Input("relief-shape", str, "parabolic", "shape of the tip relief", choices=SHAPES),
)
_ROW = {row.name: row for row in PAIR_INPUTS}
#: the modifications the seed paper's pair is built with, in modules: the command line's and
#: study files' defaults (Δ1 0.016, Δ2 0.002 mm at m = 2), kept within m h1/4 for low teeth.
#: :class:`PairParameters` itself defaults to the unmodified pair.
BUILT = {"shift": 0.008, "rotation": 0.001}


def built_modification(name: str, m: float, h1: float) -> float:
    """The default of ``shift`` or ``rotation`` [mm] for module ``m`` and height ``h1``:
    :data:`BUILT` times m, at most the m h1/4 the pair admits."""
    return min(BUILT[name] * m, 0.25 * m * h1)


def teeth_range(name: str, other: int | None) -> str:
    """The admissible teeth of gear 1 (``name`` z1) or gear 2 (z2) where the other gear has
    ``other`` teeth (None: not a sound number), as a refusal states them."""
    if name == "z1":
        top = _ROW["z1"].high if other is None else other - 1
        why = "" if other is None else f" (z1 < z2 = {other})"
        return f"an integer {_ROW['z1'].low} <= z1 <= {top}{why}"
    return f"an integer {other + 1} <= z2 <= {_ROW['z2'].high} (z2 > z1 = {other})"


def _whole(value: object, low: int, high: int) -> int | None:
    """``value`` as an int if it is a whole number from ``low`` to ``high``, else None."""
    try:
        return require_int("", value, low, high)
    except ParameterError:
        return None


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
        tip_clearance: radial clearance [mm] between gear 1's tip and the far side of the nominal
            gear 2 in the assembled pair. ``None`` means the default, equal to ``shift``: the
            negative shift already gives about ``shift`` of radial clearance on the near side,
            so the default makes the tip clearance the same on both sides and keeps the
            assembled pair free of interference. ``tip_clearance = -shift`` is the gear exactly as
            generated, without relief: it interferes by ≈ shift on the far side.
        relief: tip relief [µm], the depth the working flanks are cut back normal to the
            conjugate profile at their tip end (:mod:`.relief`); 0 for none.
        relief_extent: its length along the flank [mm] (``None``: ``0.25 m``, or
            ``relief_start``).
        relief_start: or the radius [mm] where it starts.
        relief_shape: ``parabolic``, ``arc`` or ``linear``.
    """

    m: float = 2.0
    z2: int = 45
    z1: int = 44
    h1: float = 0.30
    f1: float = 0.15
    shift: float = 0.0
    rotation: float = 0.0
    tip_clearance: float | None = None
    relief: float = 0.0
    relief_extent: float | None = None
    relief_start: float | None = None
    relief_shape: str = "parabolic"

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "m", _ROW["m"].check(self.m))
        self._check_teeth()
        set_(self, "h1", require_range("h1", self.h1, H1_MIN, self.z2 / 4.0, hi_open=True))
        set_(self, "f1", require_range("f1", self.f1, 0.0, 1.0))
        e1 = self.m * self.h1
        set_(self, "shift", require_range("shift", self.shift, 0.0, 0.25 * e1, unit="mm"))
        set_(self, "rotation", require_range("rotation", self.rotation, -0.25 * e1, 0.25 * e1,
                                             unit="mm"))
        if self.tip_clearance is not None:
            set_(self, "tip_clearance", require_range("tip_clearance", self.tip_clearance,
                                                      -self.shift, e1, unit="mm"))
        self._check_relief()

    def _check_teeth(self) -> None:
        """z1 and z2, each in its range at the other's value where that is a sound one; a pair
        whose gear 2 has no more teeth than gear 1 is refused as z2 (:func:`~.refusal.
        check_design` names z1 instead where only z1 was set)."""
        set_ = object.__setattr__
        two = _whole(self.z2, _ROW["z2"].low, _ROW["z2"].high)
        one = _whole(self.z1, _ROW["z1"].low, _ROW["z1"].high)
        if one is None:
            raise ParameterError("z1", self.z1, teeth_range("z1", two))
        if two is not None and two <= one:
            raise ParameterError("z2", self.z2, teeth_range("z2", one),
                                 "the internal gear needs more teeth than the external gear")
        if two is None:
            raise ParameterError("z2", self.z2, teeth_range("z2", one))
        set_(self, "z1", one)
        set_(self, "z2", two)

    def _check_relief(self) -> None:
        set_ = object.__setattr__
        set_(self, "relief", require_range("relief", self.relief, 0.0, 50.0 * self.m,
                                           unit="µm"))
        set_(self, "relief_shape", _ROW["relief-shape"].check(self.relief_shape))
        if self.relief_extent is not None and self.relief_start is not None:
            raise ParameterError("relief_start", self.relief_start, "unset when relief-extent "
                                 "is given (one or the other)")
        for name in ("relief-extent", "relief-start"):   # their fit: where the flank is built
            dest = _ROW[name].dest
            set_(self, dest, _ROW[name].check(getattr(self, dest)))
        if self.relief > 0 and self.relief_extent is None and self.relief_start is None:
            set_(self, "relief_extent", EXTENT_DEFAULT * self.m)

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
    def radial_tip_clearance(self) -> float:
        """Effective gear-1 tip clearance [mm] (``tip_clearance`` or its default, ``shift``)."""
        return self.shift if self.tip_clearance is None else self.tip_clearance

    def arc_um(self, turn):
        """Gear 1's turn (rad) as µm of arc at r0: how the clearance table measures it."""
        return turn * self.r0 * 1e3

    def turn_of(self, arc_um):
        """The turn (rad) of gear 1 that is ``arc_um`` µm of arc at r0."""
        return arc_um * 1e-3 / self.r0

    def describe(self) -> str:
        """Short text naming the parameters, for messages."""
        return (f"m={self.m:g}, z2={self.z2}, z1={self.z1}, h1={self.h1:g}, f1={self.f1:g}, "
                f"shift={self.shift:g}, rotation={self.rotation:g}")
