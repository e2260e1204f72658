"""Monte-Carlo gear pairs of an ISO 1328-1 class: each sample a :class:`~fegear.geometry.
Deviations` that a gear measuring machine would pass for the class (docs/tolerance.md,
"Samples").

Every deviation is drawn normal about zero with a third of its tolerance as its standard
deviation (:data:`SIGMAS`: a process just capable of the class, C_p = 1), and a gear is kept
only where every measured quantity lies within its class, as an inspected gear would be:

* **Runout**: the teeth's centre off the axis by an eccentricity whose two components are
  normal, σ = F_rT / 6 each (the largest eccentricity the class admits is F_rT / 2); the runout
  F_r is twice the eccentricity, its phase uniform.
* **Pitch**: each tooth's indexing error (fegear's per-tooth pitch deviation) is normal with
  σ = f_pT / (3√2), so that a single pitch (the difference of two neighbours) has σ = f_pT /
  3, taken from the gear's mean (a turn of the whole gear is no deviation). A measuring
  machine reads a tooth's position as its indexing error plus the eccentricity's component
  along the tooth's pitch circle: those positions' single pitches (neighbours' differences)
  must lie within ±f_pT and their cumulative pitch (their range over the gear) within F_pT,
  so the one cumulative pitch is consistent with the single pitches and with the runout. (The
  solve takes the eccentricity from the runout, turning with the gear, not from the teeth.)
* **Profile**: each tooth's slope deviation f_Hα and form deviation (a parabola's amplitude,
  which is its f_fα), each half a gear-wide part (the machine's setting) and half the tooth's
  own (variances), σ = f_HαT / 3 and f_fαT / 3 in all; each within its tolerance and the total
  profile deviation (the range of the two along the profile) within F_αT.
* **Centre distance**, where a tolerance ±T is given: normal, σ = T / 3, within ±T.

A pair solved across the face (:func:`sample_face`) draws besides, as the profile's:

* **Helix**: each tooth's helix slope f_Hβ and helix form f_fβ (the amplitude of a parabola
  zero at the face's ends), each half a gear-wide part (the machine's setting) and half the
  tooth's own, σ = f_HβT / 3 and f_fβT / 3 in all, from the tolerances at the pair's face
  width; each within its tolerance and the total helix deviation (the range of the two along
  the face) within F_βT.
* **Misalignment**, where a band ±B is given: normal about the misalignment given, σ = B / 3,
  within ±B.

A sample is drawn from its own generator, seeded by the study's seed and its own index
(``numpy.random.default_rng([seed, k])``), so sample k is the same gear pair in a run of 100
samples and in one of 10 000, and in every design a search compares (common random numbers).
Its helix and its misalignment come from generators of their own (``[seed, k, 1]`` and
``[seed, k, 2]``): across the face or not, with a band or without, sample k keeps its
deviations in the plane.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import FegearError, ParameterError
from ..geometry import Deviations, Helix, Runout, ToothDeviation, helix_trace
from .iso1328 import ClassTolerances, HelixTolerances, check_grade, class_tolerances, helix_class

#: a deviation's tolerance over its standard deviation
SIGMAS = 3.0
#: draws of one gear before its class is declared out of reach (about 0.7 of them pass; a
#: thousand failures in a row is a bug, not bad luck)
DRAWS = 1000
#: roll fractions along the profile at which the total profile deviation is measured
_ROLL = np.linspace(0.0, 1.0, 41)
#: places across the face (fractions of the face width from its middle) at which the total
#: helix deviation is measured
_ZETA = np.linspace(-0.5, 0.5, 41)
#: the generator streams of a sample's helix and misalignment, beside its own (module
#: docstring)
HELIX_STREAM, MISALIGNMENT_STREAM = 1, 2


@dataclass(frozen=True)
class Grade:
    """What a pair of class ``grade`` is drawn within: each gear's tolerances, the centre
    distance's tolerance ±``centre_distance_um`` (0: none drawn) and, for pairs solved across
    the face, each gear's helix tolerances (``helix1``, ``helix2``; None: in the plane)."""

    grade: int
    gear1: ClassTolerances
    gear2: ClassTolerances
    centre_distance_um: float = 0.0
    helix1: HelixTolerances | None = None
    helix2: HelixTolerances | None = None

    def summary(self) -> dict:
        """As JSON (µm)."""
        out = {"grade": self.grade, "gear1": self.gear1.summary(),
               "gear2": self.gear2.summary(),
               "centre_distance_tolerance_um": self.centre_distance_um,
               "sigmas": SIGMAS}
        if self.helix1 is not None:
            out["helix1"], out["helix2"] = self.helix1.summary(), self.helix2.summary()
        return out

    def reach_um(self) -> float:
        """The most the deviations of any pair drawn can move one tooth of gear 1 towards
        gear 2 or away (what :meth:`~fegear.geometry.Deviations.reach_um` can give at most):
        each gear's cumulative pitch, profile slope and form, the centre distance's and half
        the two runouts."""
        def gear(t: ClassTolerances) -> float:
            return t.F_pT + t.f_HaT + t.f_faT + 0.5 * t.F_rT
        return gear(self.gear1) + gear(self.gear2) + self.centre_distance_um


@dataclass(frozen=True)
class Draw:
    """Which pairs are solved: ``count`` samples of class ``grade`` drawn with ``seed``;
    across the face (the grade's helix tolerances given), each at ``misalignment_um`` (µm)
    or drawn within ±``band_um`` about it."""

    grade: Grade
    count: int
    seed: int
    misalignment_um: float = 0.0
    band_um: float = 0.0

    def pair(self, k: int) -> Deviations:
        """Sample ``k``'s deviations (:func:`sample_pair`)."""
        return sample_pair(self.grade, self.seed, k)

    @property
    def across(self) -> bool:
        """Whether the pairs are solved across the face (their helix drawn)."""
        return self.grade.helix1 is not None

    def face(self, k: int) -> FaceSample:
        """Sample ``k``'s helix deviations and misalignment (:func:`sample_face`)."""
        return sample_face(self, k)


@dataclass(frozen=True)
class FaceSample:
    """A sample's draw across the face: each tooth's helix slope and form deviations
    (``helix``, µm, every tooth of both gears) and the misalignment it is solved at (µm)."""

    helix: Helix
    misalignment: float


def tooth_positions(deviations: Deviations, gear: int, z: int) -> np.ndarray:
    """What a measuring machine reads of ``gear``'s teeth's positions (µm, in the gear's sign
    of a pitch deviation): each tooth's indexing error (its pitch deviation) and its runout's
    eccentricity along the tooth's pitch circle (module docstring)."""
    teeth, runout = deviations.teeth(gear), getattr(deviations, f"runout{gear}")
    index = np.array([teeth[t].pitch if t in teeth else 0.0 for t in range(z)])
    return index + _along(runout.fr, math.radians(runout.phase), z, 1.0 if gear == 1 else -1.0)


def _along(fr: float, phase: float, z: int, sign: float) -> np.ndarray:
    """A runout ``fr`` (µm) at ``phase`` (rad)'s component along each of z teeth's pitch
    circles (counter-clockwise, times the gear's ``sign`` of a pitch deviation)."""
    return sign * 0.5 * fr * np.sin(phase - 2.0 * np.pi * np.arange(z) / z)


def grade_of(grade, params, centre_distance_tolerance: float = 0.0,
             face_width: float | None = None) -> Grade:
    """Class ``grade``'s tolerances for both gears of the pair ``params`` (module m, z1 and
    z2 teeth) and the centre distance's tolerance (µm), refused by name outside their
    ranges; with the ``face_width`` (mm), its helix tolerances too (pairs solved across the
    face)."""
    tol = float(centre_distance_tolerance or 0.0)
    if not (math.isfinite(tol) and 0.0 <= tol <= 1000.0):
        raise ParameterError("centre-distance-tolerance", centre_distance_tolerance,
                             "0 <= centre-distance-tolerance <= 1000 µm (the ± tolerance)")
    grade = check_grade(grade)
    gear1 = class_tolerances(grade, params.m, params.z1)
    gear2 = class_tolerances(grade, params.m, params.z2)
    if face_width is None:
        return Grade(grade, gear1, gear2, tol)
    return Grade(grade, gear1, gear2, tol, helix_class(grade, gear1.d, face_width),
                 helix_class(grade, gear2.d, face_width))


def sample_pair(grade: Grade, seed: int, k: int) -> Deviations:
    """Sample ``k`` of the pairs of ``grade`` drawn with ``seed`` (module docstring)."""
    rng = np.random.default_rng([int(seed), int(k)])
    teeth1, runout1 = _gear(rng, grade.gear1, +1.0)
    teeth2, runout2 = _gear(rng, grade.gear2, -1.0)
    cd = 0.0
    if grade.centre_distance_um > 0:
        cd = _within(rng, grade.centre_distance_um)
    return Deviations(teeth1, teeth2, cd, runout1, runout2)


def sample_face(draw: Draw, k: int) -> FaceSample:
    """Sample ``k``'s helix deviations and misalignment of ``draw`` (a draw across the face:
    module docstring), each from its own generator."""
    grade = draw.grade
    if grade.helix1 is None:
        raise ValueError("a draw across the face needs the grade's helix tolerances")
    rng = np.random.default_rng([int(draw.seed), int(k), HELIX_STREAM])
    helix = Helix(_helix(rng, grade.helix1, grade.gear1.z),
                  _helix(rng, grade.helix2, grade.gear2.z))
    misalignment = draw.misalignment_um
    if draw.band_um > 0:
        misalignment += _within(np.random.default_rng(
            [int(draw.seed), int(k), MISALIGNMENT_STREAM]), draw.band_um)
    return FaceSample(helix, misalignment)


def _helix(rng: np.random.Generator, tol: HelixTolerances, z: int
           ) -> tuple[tuple[int, float, float], ...]:
    """One gear's z teeth's (tooth, f_Hβ, f_fβ) that pass its class (module docstring)."""
    for _ in range(DRAWS):
        slope, form = _shared_and_own(rng, tol.f_HbT, z), _shared_and_own(rng, tol.f_fbT, z)
        trace = helix_trace(slope[:, None], form[:, None], _ZETA)
        if (np.abs(slope).max() <= tol.f_HbT and np.abs(form).max() <= tol.f_fbT
                and np.ptp(trace, axis=1).max() <= tol.F_bT):
            return tuple((i, float(slope[i]), float(form[i])) for i in range(z))
    raise FegearError(f"no gear of class {tol.grade} drawn within its helix tolerances in "
                      f"{DRAWS} draws")   # pragma: no cover


def _shared_and_own(rng: np.random.Generator, tolerance: float, z: int) -> np.ndarray:
    """A deviation of each of z teeth (µm): half its variance a part all the gear's teeth
    share (the machine's setting), drawn first, half each tooth's own; σ = tolerance /
    :data:`SIGMAS` in all."""
    sigma = tolerance / SIGMAS * (1.0 / math.sqrt(2.0))
    return rng.normal(0.0, sigma) + rng.normal(0.0, sigma, z)


def _within(rng: np.random.Generator, tolerance: float) -> float:
    """One normal draw (σ = tolerance / :data:`SIGMAS`) within ±tolerance."""
    for _ in range(DRAWS):
        x = rng.normal(0.0, tolerance / SIGMAS)
        if abs(x) <= tolerance:
            return float(x)
    raise FegearError("no draw within its tolerance")   # pragma: no cover


def _gear(rng: np.random.Generator, tol: ClassTolerances, sign: float
          ) -> tuple[dict[int, ToothDeviation], Runout]:
    """One gear's teeth and runout that pass its class (module docstring); ``sign``: +1 for
    gear 1, whose positive pitch deviation turns a tooth counter-clockwise, −1 for gear 2."""
    z = tol.z
    for _ in range(DRAWS):
        ecc = rng.normal(0.0, tol.F_rT / (2.0 * SIGMAS), 2)
        phase = math.atan2(ecc[1], ecc[0])
        fr = 2.0 * math.hypot(*ecc)
        index = rng.normal(0.0, tol.f_pT / (SIGMAS * math.sqrt(2.0)), z)
        index -= index.mean()
        # what a measuring machine reads: the indexing error and the centre's offset along
        # each tooth's pitch circle (counter-clockwise), in the gear's sign of a pitch
        # deviation; the solve takes the offset from the runout, so a tooth's own pitch
        # deviation is its indexing error alone
        position = index + _along(fr, phase, z, sign)
        slope, form = _shared_and_own(rng, tol.f_HaT, z), _shared_and_own(rng, tol.f_faT, z)
        profile = slope[:, None] * _ROLL + 4.0 * form[:, None] * _ROLL * (1.0 - _ROLL)
        if (fr <= tol.F_rT
                and np.abs(position - np.roll(position, 1)).max() <= tol.f_pT
                and np.ptp(position) <= tol.F_pT
                and np.abs(slope).max() <= tol.f_HaT and np.abs(form).max() <= tol.f_faT
                and np.ptp(profile, axis=1).max() <= tol.F_aT):
            teeth = {i: ToothDeviation(float(index[i]), float(slope[i]), float(form[i]))
                     for i in range(z)}
            return teeth, Runout(fr, math.degrees(phase))
    raise FegearError(f"no gear of class {tol.grade} drawn within its tolerances in "
                      f"{DRAWS} draws")   # pragma: no cover
