"""What varies across the face width of a pair (``fegear solve --misalignment`` and the
options beside it; docs/model.md, "Across the face"): the inputs of a solve across the face,
and what each adds to a contact point's rigid gap at a section of the face. The coupling of
the sections and the solve are the ring model's (:mod:`.ring.face`, :mod:`.ring.face_contact`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..geometry import gear2_tooth, helix_trace
from ..planar import rotate
from .case import revolution_positions

if TYPE_CHECKING:   # a contact's points, normals and feet: read, never built here
    from .ring.influence import RingContact

#: sections across the face where none are given: K_Hβ and the worst root stress move by less
#: than 1 % from 9 to 17 on the baseline (docs/model.md)
SECTIONS = 9
#: the deepest lead modification (crowning and end relief at an end together) per mm of module
#: (µm): the bound the profile's tip relief takes (``--relief``), a grinding depth that leaves
#: the tooth its flank
LEAD_DEPTH_PER_MODULE = 50.0


def deepest_lead_um(m: float) -> float:
    """The deepest lead modification a tooth of module ``m`` (mm) takes (µm):
    :data:`LEAD_DEPTH_PER_MODULE` m."""
    return LEAD_DEPTH_PER_MODULE * m


@dataclass(frozen=True)
class Face:
    """What varies across the face, in µm over the face width unless named otherwise.
    ``sections``: how many sections the line load is linear between (both ends among them).
    ``misalignment``: gear 1's axis displaced against gear 2's across the line of centres,
    from the face's first end (ζ = −½) to its second, + in the direction gear 1's loaded
    flanks push gear 2's at the pitch point (−x under a positive torque), so that the second
    end closes first; ``tilt``: the same along the line of centres (+: the centre distance
    grows towards the second end). ``crowning`` C_β: gear 1's teeth thinned by a parabola
    across the face, zero at mid-face and C_β at each end; ``end_relief`` C_I over
    ``end_length`` (mm) from each end, linear. ``helix1``/``helix2``: a tooth's helix slope
    f_Hβ (+: its loaded flank towards its mate at the second end, as much away at the first)
    and helix form f_fβ (+: towards its mate at mid-face, a parabola zero at the ends), as
    (gear-1 or gear-2 tooth, f_Hβ, f_fβ); ``leads1``/``leads2``: a tooth's measured lead as
    (tooth, places from the face's first end (mm), the flank's deviations there (µm, +: towards
    its mate))."""

    sections: int = SECTIONS
    misalignment: float = 0.0
    tilt: float = 0.0
    crowning: float = 0.0
    end_relief: float = 0.0
    end_length: float = 0.0
    helix1: tuple[tuple[int, float, float], ...] = ()
    helix2: tuple[tuple[int, float, float], ...] = ()
    leads1: tuple = ()
    leads2: tuple = ()

    @property
    def uneven_teeth(self) -> bool:
        """Whether a tooth has deviations across the face of its own (a helix deviation or a
        measured lead): the teeth of a gear then differ across the face."""
        return bool(self.helix1 or self.helix2 or self.leads1 or self.leads2)

    def per_tooth(self, zeta: np.ndarray, width: float) -> tuple[dict, dict]:
        """What each tooth's own deviations across the face add to its loaded flank's gap
        (µm, + opens) at the sections ``zeta`` of a face ``width`` mm wide, per gear: tooth →
        values. A helix slope f_Hβ subtracts f_Hβ ζ, a helix form f_fβ subtracts
        f_fβ (1 − 4ζ²), a measured lead its trace (linear between its points, its end
        values beyond them)."""
        out = []
        for helix, leads in ((self.helix1, self.leads1), (self.helix2, self.leads2)):
            teeth: dict[int, np.ndarray] = {}
            for tooth, slope, form in helix:
                teeth[tooth] = teeth.get(tooth, 0.0) - helix_trace(slope, form, zeta)
            for tooth, places, um in leads:
                teeth[tooth] = teeth.get(tooth, 0.0) - np.interp((zeta + 0.5) * width,
                                                                 places, um)
            out.append(teeth)
        return out[0], out[1]

    def offsets(self, contact: RingContact, turn: float, zeta: np.ndarray, width: float,
                z2: int) -> np.ndarray:
        """What the face's inputs add to the rigid gap (mm) of each of ``contact``'s points
        (gear 1 turned by ``turn``, rad) at sections ``zeta`` (fractions of the face
        ``width``, mm, from its middle): points × sections. A displacement d of gear 1 moves
        a point's gap by −n · d (n its outward normal in the fixed frame)."""
        n = rotate(contact.normal, turn)
        closing = n[:, 0] * self.misalignment - n[:, 1] * self.tilt   # −n · d per unit ζ
        out = np.outer(closing, zeta)
        out += self.crowning * (2.0 * zeta) ** 2
        if self.end_relief:
            beyond = np.abs(zeta) * width - (0.5 * width - self.end_length)
            out += self.end_relief * np.clip(beyond / self.end_length, 0.0, None)
        for teeth, own in zip((contact.teeth, gear2_tooth(contact.feet, z2)),
                              self.per_tooth(zeta, width)):
            for tooth, um in own.items():
                out[teeth == tooth] += um
        return 1e-3 * out


@dataclass(frozen=True)
class Room:
    """How far gear 1 can turn across the whole face (:func:`face_room`): ``um``, the least
    room over the positions checked (µm of arc at r0: the loaded side's clearance at the
    face's tightest section plus the coast side's at its own tightest; below zero the pair
    jams), at ``beta`` (rad), and ``scale``, the largest factor on the face's misalignment,
    tilt and helix deviations that leaves the pair room everywhere (inf where they open it)."""

    um: float
    beta: float
    scale: float


def face_room(face: Face, params, drive, coast, width: float) -> Room:
    """The room :class:`Room` a pair keeps with ``face``'s inputs, from its unloaded clearance
    states (each a :class:`~fegear.geometry.ContactState` at its own β, with each tooth's
    closing point) on the loaded flanks (``drive``) and the coast flanks (``coast``), its
    face ``width`` mm wide.

    Gear 1 is one body along the face: where the face's inputs close the loaded flanks at one
    section and the coast flanks at another, the pair's backlash has to cover both. A point's
    offset (µm along its normal, + opens) is read as gear 1's turn that makes it up, in µm of
    arc at r0: the offset times r0 over the normal's arm about gear 1's centre, the normal gear
    1's flank's at the point (not the line to the pitch point: a closing point a few µm off
    the line of action near the pitch point would turn that line anywhere). Crowning and end
    relief only open the gap and are left out; the coast flanks carry only the axes'
    misalignment and tilt (a deviation is given for the loaded flank). A gear-2 tooth's helix
    deviations reach the points in its pitch (gear 2 turned by β)."""
    from ..geometry import gear1_profile  # lazy: heavy: scipy (the profile the check built)

    profile = gear1_profile(params)
    zeta = np.linspace(-0.5, 0.5, face.sections)
    own = face.per_tooth(zeta, width)
    least, beta, scale = np.inf, 0.0, np.inf
    for d, c in zip(drive, coast):
        base_d, rate_d = _turns(face, params, d, +1, (zeta, own), profile)
        base_c, rate_c = _turns(face, params, c, -1, (zeta, own), profile)
        if not len(base_d) or not len(base_c):
            continue
        room = base_d[:, None] + base_c[None, :] + rate_d[:, None] + rate_c[None, :]
        if room.min() < least:
            least, beta = float(room.min()), d.beta
        slope = rate_d[:, None] + rate_c[None, :]
        closing = slope < 0
        if closing.any():
            gap = (base_d[:, None] + base_c[None, :])[closing]
            scale = min(scale, float(np.min(np.maximum(gap, 0.0) / -slope[closing])))
    return Room(least, beta, scale)


def _turns(face: Face, params, state, direction: int, sections, profile):
    """Every closing point's clearance in ``direction`` (µm of arc at r0) and the turn the
    face's inputs add to it at each of the sections (``sections``: their ζ, and each tooth's
    own offsets there, :meth:`Face.per_tooth`; the same unit), flattened over the points and
    sections; the points' normals are gear 1's ``profile``'s there (gear 1 at (0, e), turned
    by ratio β)."""
    zeta, own = sections
    key, point = ("plus_um", "plus_point") if direction > 0 else ("minus_um", "minus_point")
    rows = [(t.tooth, getattr(t, key), getattr(t, point)) for t in state.teeth
            if getattr(t, key) is not None and getattr(t, point) is not None]
    if not rows:
        return np.zeros(0), np.zeros(0)
    teeth = np.array([r[0] for r in rows])
    clearance = np.array([r[1] for r in rows])
    x = np.array([r[2] for r in rows])
    local = rotate(x - np.array([0.0, params.e]), -params.ratio * state.beta)  # gear 1's
    n, lever, teeth2 = flank_levers(params, profile, local, state.beta, direction)
    offset = np.outer(n[:, 0] * face.misalignment - n[:, 1] * face.tilt, zeta)
    if direction > 0:
        for mine, deviated in zip((teeth, teeth2), own):
            for tooth, um in deviated.items():
                offset[mine == tooth] += um
    return np.repeat(clearance, len(zeta)), (offset * lever[:, None]).ravel()


def flank_levers(params, profile, local: np.ndarray, beta, direction: int
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """At closing points ``local`` (mm, gear 1's frame) at rolling angles ``beta`` (rad, one
    or one a point): gear 1's ``profile``'s normal there in the fixed frame, pointing the way
    the point moves as gear 1 turns in ``direction`` (+1 onto the loaded flanks, −1 the coast
    flanks); the lever that reads an offset along it as gear 1's turn (µm of arc at r0 a µm:
    r0 over the normal's arm about gear 1's centre); and gear 2's tooth whose pitch holds the
    point's polar angle (:func:`face_room`)."""
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


def room_of(face: Face, case) -> Room:
    """:func:`face_room` of ``case``'s pair (its deviations' clearances moved as the solve
    moves them: over a whole turn of gear 1) with ``face``'s inputs. An exact pair's
    clearances are kept (:data:`_KEPT`): a search over what varies across the face (``fegear
    crowning``'s trials) checks its room once."""
    from ..geometry import ToothContact, gear1_profile, moved_clearances  # lazy: heavy: scipy

    params = case.params
    key = None if case.deviations else (params, float(case.beta))
    if key in _KEPT:
        return face_room(face, params, *_KEPT[key], case.thickness)
    pitch2 = 2.0 * np.pi / params.z2
    if case.deviations:
        betas = revolution_positions(case.beta, ROOM_ANGLES, params.z1, params.z2)
    else:
        betas = case.beta + pitch2 * np.arange(ROOM_ANGLES) / ROOM_ANGLES
    states = ToothContact(params, gear1_profile(params)).states(betas)
    drive = coast = states
    if case.deviations:
        drive = moved_clearances(case.deviations, params, states, +1)
        coast = moved_clearances(case.deviations, params, states, -1)
    if key is not None:
        while len(_KEPT) >= KEEP_ROOMS:
            _KEPT.pop(next(iter(_KEPT)))
        _KEPT[key] = (drive, coast)
    return face_room(face, params, drive, coast, case.thickness)


#: the exact pairs' clearance states kept for their room (:func:`room_of`), the oldest let go
#: beyond this many
KEEP_ROOMS = 4
_KEPT: dict = {}
