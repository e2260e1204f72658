"""A tolerance class's pairs across the face (``fegear solve --grade … --misalignment …``): each
sample's own face (the job's, with its drawn helix deviations and misalignment:
:func:`~fegear.tolerance.sample_face`), read at its worst section, and the check that the
sample's face leaves the pair its backlash (:class:`~fegear.toothpair.face_room.FaceRoom`,
for all of them at once).

A sample is solved across the face on the contact kept at its position for its 2D solve
(:func:`~.ring.face_results.face_sections`, as the exact pair is by the face's analysis): its
headline stresses are its worst section's, and its K_Hβ the face's.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ....tolerance import Draw
from ...case import SolveCase
from ...face import Face
from ...face_drive import coupling_of
from ...ring.face import FaceCoupling
from ...ring.face_results import FaceSections


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
