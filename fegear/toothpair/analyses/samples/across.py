"""A tolerance class's pairs across the face (``fegear solve --grade … --misalignment …``): each
sample's own face (the job's, with its drawn helix deviations and misalignment:
:func:`~fegear.tolerance.sample_face`), read at its worst section, and the check that the
sample's face leaves the pair its backlash (:class:`FaceRoom`).

A sample is solved across the face on the contact kept at its position for its 2D solve
(:func:`~.ring.face_results.face_sections`, as the exact pair is by the face's analysis): its
headline stresses are its worst section's, and its K_Hβ the face's.

The room is :func:`~fegear.toothpair.face.face_room`'s (gear 1 one body along the face, whose
backlash the loaded flanks' closing at one section and the coast flanks' at another share),
for many pairs at once: the exact pair's closing points over a whole turn are found once,
with what a unit misalignment, tilt and helix deviation turn each one by (µm of arc at r0),
and a sample is then one batch of moved clearances on each side (its deviations in the plane:
:func:`~fegear.geometry.point_clearances`) and those rates times its own face, at the face's
sections. At the same clearance states its room is face_room's to rounding (tests/toothpair/
analyses/test_samples_across.py); a crowning and an end relief only open the gaps, and are
left out as there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ....geometry import closing_points, gear1_profile, point_clearances
from ....tolerance import Draw
from ...case import SolveCase
from ...face import Face, flank_levers
from ...face_drive import coupling_of
from ...ring.face import FaceCoupling
from ...ring.face_results import FaceSections
from ...teeth import INTERFERENCE_UM, closure


@dataclass(frozen=True)
class Across:
    """A class solved across the face: the job's ``face`` (the exact pair's), its sections'
    ``coupling`` and each sample's own face (``faces``, by sample: the job's with its drawn
    helix deviations and misalignment)."""

    face: Face
    coupling: FaceCoupling
    faces: tuple[Face, ...]

    @property
    def reach_um(self) -> float:
        """The most any sample's face moves a flank towards its mate or away at a section
        (µm): half its misalignment and tilt, and each gear's largest helix slope's half and
        form."""
        return max((_reach(face) for face in self.faces), default=0.0)


def across_of(case: SolveCase, face: Face, draw: Draw) -> Across:
    """``draw``'s samples across ``face`` (:class:`Across`), their sections coupled as the
    exact pair's (:func:`~...face_drive.coupling_of`)."""
    coupling = coupling_of(case, face)
    faces = []
    for k in range(draw.count):
        drawn = draw.face(k)
        faces.append(replace(face, helix1=drawn.helix.gear1, helix2=drawn.helix.gear2,
                             misalignment=drawn.misalignment))
    return Across(face, coupling, tuple(faces))


def _reach(face: Face) -> float:
    """What :attr:`Across.reach_um` takes of one face (µm)."""
    helix = [max((0.5 * abs(s) + abs(f) for _, s, f in h), default=0.0)
             for h in (face.helix1, face.helix2)]
    return 0.5 * (abs(face.misalignment) + abs(face.tilt)) + sum(helix)


def worst_sections(sections: FaceSections) -> dict[str, float]:
    """Each headline stress at its worst section (:meth:`~...ring.face_results.FaceSections.
    headline`), and the face's K_Hβ (``K_Hbeta``)."""
    out = {key: value for key, (_, value) in sections.worst_headlines().items()}
    out["K_Hbeta"] = sections.load_factor
    return out


@dataclass(frozen=True)
class _Side:
    """One side's closing points over the states (:class:`FaceRoom`): each one's state (index),
    its gear-1 and gear-2 teeth, what a unit of the axes' misalignment and tilt turns it by at
    ζ = 1 (µm of arc at r0 per µm), and its lever (r0 over its normal's arm: µm of arc a µm of
    offset)."""

    closing: object
    state: np.ndarray
    tooth1: np.ndarray
    tooth2: np.ndarray
    misalignment: np.ndarray
    tilt: np.ndarray
    lever: np.ndarray


@dataclass(frozen=True)
class Room:
    """A sample's least room across the face (µm of arc at r0; below zero it jams) at the state
    ``state`` (index), the loaded side's least clearance there (``plus_um``, with its gear-1
    ``tooth``) and the coast side's (``back_um``), each at its own tightest section."""

    um: float
    state: int
    tooth: int
    plus_um: float
    back_um: float


class FaceRoom:
    """The pair's room across the face for many samples (module docstring): the exact pair's
    clearance ``states`` ((β, state) pairs, both sides found), their closing points that the
    deviations and faces reaching ``reach_um`` (µm) could close, at ``sections`` across the
    face."""

    def __init__(self, case: SolveCase, states, reach_um: float, sections: int) -> None:
        p = case.params
        self.case, self.states = case, list(states)
        self.zeta = np.linspace(-0.5, 0.5, sections)
        found = [s for _, s in self.states]
        self.sides = tuple(self._side(closing_points(p, found, d).reachable(p, reach_um), d)
                           for d in (+1, -1))

    def _side(self, closing, direction: int) -> _Side:
        """The closing points' face rates on one side (face_room's, point by point:
        :func:`~...face.flank_levers`)."""
        p = self.case.params
        n, lever, tooth2 = flank_levers(p, gear1_profile(p), closing.x, closing.beta,
                                        direction)
        counts = [len(c) for c in closing.teeth]
        state = np.repeat(np.arange(len(counts)), counts)
        return _Side(closing, state, closing.tooth, tooth2, n[:, 0] * lever,
                     -n[:, 1] * lever, lever)

    def room(self, deviations, face: Face) -> Room:
        """The least room across the face that ``deviations`` (in the plane) and ``face``
        (its axes' misalignment and tilt, its teeth's helix deviations) leave the pair."""
        drive, coast = (self._least(side, deviations, face, loaded)
                        for side, loaded in zip(self.sides, (True, False)))
        room = drive[0] + coast[0]
        i = int(np.argmin(room))
        if not math.isfinite(room[i]):
            return Room(math.inf, -1, -1, math.inf, math.inf)
        tooth = int(self.sides[0].tooth1[drive[1][i]])
        return Room(float(room[i]), i, tooth, float(drive[0][i]), float(coast[0][i]))

    def _least(self, side: _Side, deviations, face: Face, loaded: bool):
        """Each state's least clearance on ``side`` over its points and the face's sections
        (µm; +inf where it has none) and the point that gives it."""
        p, zeta = self.case.params, self.zeta
        um = point_clearances(deviations, p, side.closing)
        axes = side.misalignment * face.misalignment + side.tilt * face.tilt
        turn = axes[:, None] * zeta
        if loaded:   # a flank's helix deviations, the loaded flank's alone (face_room)
            own = face.per_tooth(zeta, self.case.thickness)
            for teeth, deviated in zip((side.tooth1, side.tooth2), own):
                for tooth, offset in deviated.items():
                    on = teeth == tooth
                    turn[on] += side.lever[on, None] * offset
        value = um + turn.min(axis=1)
        least = np.full(len(self.states), np.inf)
        np.minimum.at(least, side.state, value)
        point = np.full(len(self.states), -1)
        order = np.argsort(value)[::-1]            # the least last: it wins each state
        point[side.state[order]] = order
        return least, point

    def jammed(self, deviations, face: Face) -> str | None:
        """Where ``deviations`` and ``face`` take up the pair's backlash across the face, in
        words (:func:`~...teeth.closure`), else None."""
        room = self.room(deviations, face)
        if room.um >= -INTERFERENCE_UM:
            return None
        where = closure(self.states[room.state][0], room.tooth, room.plus_um, room.back_um)
        return f"{where}, across the face" if where is not None else None
