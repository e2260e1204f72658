"""A solved pair made ready to draw in another process (:func:`for_pictures`): the solution
without its model (:class:`PicturedDetail`), and of its fields only the cells that von Mises
shows, with the box they are chosen by (:func:`frame_of`, :func:`in_box`), which the picture
itself is framed by (:mod:`.plot`)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..case import BodyField, PairSolution
from .marks import field_max, labelled_box, root_hot_spots


class PicturedDetail:
    """What the pictures read of a solved position's own record (its flank pressures and its
    contact zone), without the model behind it: a :class:`~.case.PairSolution` carrying this
    pickles in a few kilobytes (:func:`for_pictures`)."""

    def __init__(self, detail) -> None:
        self._flanks, self._zone = detail.flank_pressures(), detail.contact_zone()

    def flank_pressures(self):
        return self._flanks

    def contact_zone(self):
        return self._zone


@dataclass(frozen=True)
class ToDraw:
    """A solved pair made ready to send to a process that draws it: the solution with a
    :class:`PicturedDetail`, the bodies' cells that von Mises shows (every node of the
    pictured box and its margin, with their von Mises and σ1) and the root hot spots found on
    the whole bodies."""

    sol: PairSolution
    bodies: tuple[BodyField, ...]
    peaks: tuple[BodyField, ...]
    spots: tuple


def light(sol: PairSolution) -> PairSolution:
    """``sol`` with a :class:`PicturedDetail` (itself where it has one already): what a
    process that draws it is sent."""
    if isinstance(sol.detail, PicturedDetail):
        return sol
    return dataclasses.replace(sol, detail=PicturedDetail(sol.detail))


def for_pictures(sol: PairSolution, bodies, peaks=()) -> ToDraw:
    """:class:`ToDraw` of a solved pair and its fields: von Mises from it is the same picture
    as from the whole fields, byte for byte."""
    sol = light(sol)
    spots = root_hot_spots(sol, bodies)
    box = frame_of(sol, bodies, peaks, spots).box
    shown = tuple(part for b in bodies if (part := _cropped(b, box)) is not None)
    return ToDraw(sol, shown, tuple(peaks), spots)


#: the sectors either side of the loaded ones whose fields von Mises is first drawn from: the
#: picture frames the loaded teeth and their roots (:func:`same_drawing` confirms it)
PICTURED_AROUND = 1


def same_drawing(a: ToDraw, b: ToDraw) -> bool:
    """Whether von Mises of ``a`` and of ``b`` is the same picture: the same cells in the same
    order, the same hot spots, and the values within :data:`ROUNDING` of each field's largest
    (the loaded sectors' stresses recovered on their own round apart from the whole gear's in
    the last bits: the colours and the printed values cannot tell)."""
    if len(a.bodies) != len(b.bodies) or len(a.spots) != len(b.spots):
        return False

    def close(x, y) -> bool:
        return np.allclose(x, y, rtol=0.0, atol=ROUNDING * max(np.abs(y).max(), 1.0))

    spots = all(s.gear == t.gear and np.array_equal(s.point, t.point)
                and close(s.value, t.value) for s, t in zip(a.spots, b.spots))
    return spots and all(
        x.name == y.name and np.array_equal(x.points, y.points)
        and np.array_equal(x.cells, y.cells) and x.data.keys() == y.data.keys()
        and all(close(x.data[k], y.data[k]) for k in x.data)
        for x, y in zip(a.bodies, b.bodies))


#: the relative difference in the pictured values that :func:`same_drawing` takes for none
ROUNDING = 1e-9


def _cropped(b: BodyField, box) -> BodyField | None:
    """The cells of ``b`` that von Mises draws in ``box`` (or in a box inside it), with
    the fields the picture reads; None if there are none."""
    keep = in_box(b, box)
    if not keep.any():
        return None
    used, local = np.unique(b.cells[keep], return_inverse=True)
    return BodyField(b.name, b.points[used], local.reshape(-1, b.cells.shape[1]),
                     {k: b.data[k][used] for k in ("von_mises", "s1")})


def in_box(b: BodyField, box) -> np.ndarray:
    """Which corner triangles of ``b`` have their centroid in ``box`` and a tenth of its width
    around it."""
    tri = b.cells[:, :3]
    # the corners' centroids a coordinate at a time: a whole ring's (n, 3, 2) gather costs
    # three times as much
    x, y = ((b.points[tri[:, 0], k] + b.points[tri[:, 1], k] + b.points[tri[:, 2], k]) / 3
            for k in (0, 1))
    pad = 0.1 * (box[1] - box[0])
    return (x > box[0] - pad) & (x < box[1] + pad) & (y > box[2] - pad) & (y < box[3] + pad)


@dataclass(frozen=True)
class Frame:
    """Where von Mises looks: the box of the loaded teeth, the largest von Mises and where it
    is, and the contact's points."""

    box: tuple[float, float, float, float]
    peak_at: np.ndarray
    peak: float
    contact: list


def frame_of(sol: PairSolution, bodies, peaks, spots) -> Frame:
    """The :class:`Frame` of a solved pair: the box around its contact's points and its root
    hot spots."""
    fine = list(peaks)
    # where the submodels resolve the peak, the bodies' nodes under them are not the answer
    peak_at, peak = field_max(fine or list(bodies), "von_mises")
    contact = [f.points[f.pressure > 0] for f in sol.detail.flank_pressures()] \
        or [np.array([peak_at])]
    box = labelled_box(np.vstack([*contact, *[sp.point for sp in spots]]), sol.case.params.m)
    return Frame(box, peak_at, peak, contact)
