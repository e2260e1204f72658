"""The room a pair keeps across the face (:class:`FaceRoom`): how far gear 1 can still turn
with the face's inputs, for one pair (:func:`room_of`, what a solve's inputs are refused by)
or for a tolerance class's many (the samples across the face).

Gear 1 is one body along the face: where the face's inputs close the loaded flanks at one
section and the coast flanks at another, the pair's backlash has to cover both. The exact
pair's closing points over the rolling angles checked are found once, each with what a unit
misalignment, tilt and helix deviation turn it by, and a pair is then one batch of moved
clearances on each side (its deviations in the plane: :func:`~fegear.geometry.
point_clearances`) and those rates times its face, at the face's sections.

A point's offset (µm along its normal, + opens) is read as gear 1's turn that makes it up, in
µm of arc at r0: the offset times r0 over the normal's arm about gear 1's centre, the normal
gear 1's flank's at the point (not the line to the pitch point: a closing point a few µm off
the line of action near the pitch point would turn that line anywhere). Crowning and end
relief only open the gap and are left out; the coast flanks carry only the axes'
misalignment and tilt (a deviation is given for the loaded flank). A gear-2 tooth's helix
deviations reach the points in its pitch (gear 2 turned by β).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry import gear2_tooth
from ..planar import rotate
from .case import SolveCase, revolution_positions
from .face import Face
from .teeth import INTERFERENCE_UM, closure


@dataclass(frozen=True)
class Room:
    """A pair's least room across the face (µm of arc at r0; below zero it jams) at the state
    ``state`` (index; −1 where no state has closing points on both sides), at rolling angle
    ``beta`` (rad), the loaded side's least clearance there (``plus_um``, with its gear-1
    ``tooth``) and the coast side's (``back_um``), each at its own tightest section; and
    ``scale``, the largest factor on the face's misalignment, tilt and helix deviations that
    leaves the pair room everywhere (inf where they open it; :meth:`FaceRoom.room` with
    ``scale``)."""

    um: float
    state: int
    beta: float
    tooth: int
    plus_um: float
    back_um: float
    scale: float = math.inf


@dataclass(frozen=True)
class _Side:
    """One side's closing points over the states: each one's state (index), its gear-1 and
    gear-2 teeth, what a unit of the axes' misalignment and tilt turns it by at ζ = 1 (µm of
    arc at r0 per µm), and its lever (r0 over its normal's arm: µm of arc a µm of offset)."""

    closing: object
    state: np.ndarray
    tooth1: np.ndarray
    tooth2: np.ndarray
    misalignment: np.ndarray
    tilt: np.ndarray
    lever: np.ndarray


class FaceRoom:
    """The pair's room across the face (module docstring) for the exact pair's clearance
    ``states`` ((β, state) pairs, both sides found), their closing points that deviations and
    faces reaching ``reach_um`` (µm; inf: every one) could close, at ``sections`` across the
    face."""

    def __init__(self, case: SolveCase, states, reach_um: float, sections: int) -> None:
        from ..geometry import closing_points  # lazy: heavy: scipy (the refusals import this)

        p = case.params
        self.case, self.states = case, list(states)
        self.zeta = np.linspace(-0.5, 0.5, sections)
        found = [s for _, s in self.states]
        self.sides = tuple(self._side(closing_points(p, found, d).reachable(p, reach_um), d)
                           for d in (+1, -1))

    def _side(self, closing, direction: int) -> _Side:
        """The closing points' face rates on one side (:func:`flank_levers`)."""
        from ..geometry import gear1_profile  # lazy: heavy: scipy

        p = self.case.params
        n, lever, tooth2 = flank_levers(p, gear1_profile(p), closing.x, closing.beta,
                                        direction)
        counts = [len(c) for c in closing.teeth]
        state = np.repeat(np.arange(len(counts)), counts)
        return _Side(closing, state, closing.tooth, tooth2, n[:, 0] * lever,
                     -n[:, 1] * lever, lever)

    def room(self, deviations, face: Face, scale: bool = False) -> Room:
        """The least room across the face that ``deviations`` (in the plane) and ``face``
        (its axes' misalignment and tilt, its teeth's helix deviations) leave the pair; with
        ``scale``, also the largest factor on the face's inputs that leaves it room."""
        drive, coast = (self._entries(side, deviations, face, loaded)
                        for side, loaded in zip(self.sides, (True, False)))
        (d_least, d_point), (c_least, _) = (self._least(side, *entries) for side, entries
                                            in zip(self.sides, (drive, coast)))
        room = d_least + c_least
        factor = self._scale(drive, coast) if scale else math.inf
        i = int(np.argmin(room)) if len(room) else 0
        if not len(room) or not math.isfinite(room[i]):
            return Room(math.inf, -1, float(self.case.beta), -1, math.inf, math.inf, factor)
        tooth = int(self.sides[0].tooth1[d_point[i]])
        return Room(float(room[i]), i, float(self.states[i][0]), tooth, float(d_least[i]),
                    float(c_least[i]), factor)

    def _entries(self, side: _Side, deviations, face: Face, loaded: bool):
        """Each point's clearance on ``side`` moved by ``deviations`` (µm of arc) and the turn
        ``face`` adds to it at each section (points × sections, the same unit)."""
        from ..geometry import point_clearances  # lazy: heavy: scipy

        um = point_clearances(deviations, self.case.params, side.closing)
        axes = side.misalignment * face.misalignment + side.tilt * face.tilt
        turn = axes[:, None] * self.zeta
        if loaded:   # a flank's helix deviations, the loaded flank's alone
            own = face.per_tooth(self.zeta, self.case.thickness)
            for teeth, deviated in zip((side.tooth1, side.tooth2), own):
                for tooth, offset in deviated.items():
                    on = teeth == tooth
                    turn[on] += side.lever[on, None] * offset
        return um, turn

    def _least(self, side: _Side, um: np.ndarray, turn: np.ndarray):
        """Each state's least clearance on ``side`` over its points and the face's sections
        (µm; +inf where it has none) and the point that gives it."""
        value = um + turn.min(axis=1)
        least = np.full(len(self.states), np.inf)
        np.minimum.at(least, side.state, value)
        point = np.full(len(self.states), -1)
        order = np.argsort(value)[::-1]            # the least last: it wins each state
        point[side.state[order]] = order
        return least, point

    def _scale(self, drive, coast) -> float:
        """The largest factor s on the face's turns that keeps every state's loaded and coast
        clearances, each point at each section against each, from summing below zero:
        a pair of entries closing under the face (their turns summing below zero) bounds s by
        their clearances over that sum."""
        scale = math.inf
        (ud, td), (uc, tc) = drive, coast
        sd, sc = self.sides[0].state, self.sides[1].state
        for k in range(len(self.states)):
            d, c = sd == k, sc == k
            if not d.any() or not c.any():
                continue
            slope = td[d].ravel()[:, None] + tc[c].ravel()[None, :]
            closing = slope < 0
            if closing.any():
                n = len(self.zeta)
                gap = np.repeat(ud[d], n)[:, None] + np.repeat(uc[c], n)[None, :]
                scale = min(scale, float(np.min(np.maximum(gap[closing], 0.0)
                                                / -slope[closing])))
        return scale

    def jammed(self, deviations, face: Face) -> str | None:
        """Where ``deviations`` and ``face`` take up the pair's backlash across the face, in
        words (:func:`~.teeth.closure`), else None."""
        room = self.room(deviations, face)
        if room.um >= -INTERFERENCE_UM:
            return None
        where = closure(self.states[room.state][0], room.tooth, room.plus_um, room.back_um)
        return f"{where}, across the face" if where is not None else None


def flank_levers(params, profile, local: np.ndarray, beta, direction: int
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """At closing points ``local`` (mm, gear 1's frame) at rolling angles ``beta`` (rad, one
    or one a point): gear 1's ``profile``'s normal there in the fixed frame, pointing the way
    the point moves as gear 1 turns in ``direction`` (+1 onto the loaded flanks, −1 the coast
    flanks); the lever that reads an offset along it as gear 1's turn (µm of arc at r0 a µm:
    r0 over the normal's arm about gear 1's centre); and gear 2's tooth whose pitch holds the
    point's polar angle."""
    normal = profile.evaluate(np.arctan2(local[:, 1], local[:, 0])).normal
    along = normal[:, 0] * -local[:, 1] + normal[:, 1] * local[:, 0]   # n · d x / d turn
    normal = normal * (direction * np.sign(along) + (along == 0))[:, None]
    turn = params.ratio * np.asarray(beta)
    fixed = rotate(local, turn) + np.array([0.0, params.e])
    tooth2 = gear2_tooth(np.arctan2(fixed[:, 1], fixed[:, 0]) - beta, params.z2)
    return rotate(normal, turn), params.r0 / np.maximum(np.abs(along), 1e-9), tooth2


#: rolling angles a gear-2 pitch at which a face's room is checked: an exact pair's clearances
#: repeat every pitch; a deviated pair's are checked at as many a pitch over a whole turn
ROOM_ANGLES = 12


def room_of(face: Face, case: SolveCase) -> Room:
    """The room :class:`FaceRoom` gives ``case``'s pair (its deviations over a whole turn of
    gear 1; an exact pair over a gear-2 pitch) with ``face``'s inputs, and their scale. An
    exact pair's :class:`FaceRoom` is kept (:data:`_KEPT`): a search over what varies across
    the face (``fegear crowning``'s trials) finds its closing points once."""
    from ..geometry import ToothContact, gear1_profile  # lazy: heavy: scipy

    params = case.params
    key = None if case.deviations else (params, float(case.beta), case.thickness,
                                        face.sections)
    room = _KEPT.get(key) if key is not None else None
    if room is None:
        if case.deviations:
            betas = revolution_positions(case.beta, ROOM_ANGLES, params.z1, params.z2)
        else:
            betas = case.beta + 2.0 * np.pi / params.z2 * np.arange(ROOM_ANGLES) / ROOM_ANGLES
        states = ToothContact(params, gear1_profile(params)).states(betas)
        room = FaceRoom(case, list(zip(betas, states)), math.inf, face.sections)
        if key is not None:
            while len(_KEPT) >= KEEP_ROOMS:
                _KEPT.pop(next(iter(_KEPT)))
            _KEPT[key] = room
    return room.room(case.deviations, face, scale=True)


#: the exact pairs' rooms kept (:func:`room_of`), the oldest let go beyond this many
KEEP_ROOMS = 4
_KEPT: dict = {}
