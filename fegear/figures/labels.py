"""Labels and legends placed clear of what a picture shows.

The placing is done in display pixels once the axes are laid out. A label (a
:class:`Callout`) is tried at a ring of offsets around the point it names. The kept offset
covers no marker, no other label and no text; its leader crosses no other leader and runs
through no label box or marker; and it covers the least of the data. Then each label is
placed again among the others until none moves, and the labels left with a fault are placed
first in another round. A name without a leader is tried over its point and near it,
preferring to lie over what it names. A legend goes where it covers no data: a corner of its
axes, else above the data (the y axis extended) or outside the axes.

The artists are read through their own methods (window extents, paths, offsets), so this
module imports no matplotlib.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from .pixels import (
    SAMPLE_PX,
    Cells,
    Drawn,
    apply_limits,
    box_of,
    discs_hit,
    inside,
    overlap,
    px_per_pt,
    segments_cross,
    segments_near,
    segments_through_boxes,
)

#: the cost of a fault a label must not have (a covered marker, crossed leaders, …)
FAULT = 1e6
#: a leader through a marker or a text: drawn over it, better avoided
GRAZE = 1e4
#: a sample of a drawn line (every SAMPLE_PX) under a box or a leader, and a box wholly
#: over the data
LINE_COST, DATA_COST = 300.0, 3000.0
#: a label in the direction opposite to the one it prefers costs as much as this many px
#: further away
PREFER_COST = 60.0
#: pixels a label keeps clear of what it must not cover
MARGIN_PX = 3.0
#: gaps (px) between a point and its label's nearest edge tried, and the directions
GAPS_PX = (14.0, 28.0, 48.0, 75.0, 110.0, 160.0, 230.0)
DIRECTIONS = 24


@dataclass(frozen=True)
class Callout:
    """A label of a point: its text, the point (data coordinates), the direction it would
    rather sit in from it (data coordinates; None: any), matplotlib's ``annotate`` keywords
    (font, box, leader) and the points of what it names that it should lie over ((n, 2),
    data coordinates; None: anywhere), for a name written on a body."""

    text: str
    anchor: tuple[float, float]
    prefer: tuple[float, float] | None = None
    style: Mapping = field(default_factory=dict)
    on: np.ndarray | None = field(default=None, repr=False)


def place_callouts(ax, callouts: Sequence[Callout], data: np.ndarray | None = None) -> list:
    """Annotate ``ax`` with ``callouts``, each box where it covers none of the markers, texts
    and other boxes, its leader crossing no other, and the least of the drawn lines and of
    ``data`` ((n, 2) points, data coordinates: what the boxes should leave in view, such as a
    field's high values). A callout without ``arrowprops`` has no leader: it is placed over
    its point or near it (a name written on what it names). Call it once the axes' limits
    and place are final. Returns the annotations, in the order of ``callouts``; their gid is
    "callout"."""
    apply_limits(ax)
    renderer = ax.figure.canvas.get_renderer()
    frame = box_of(ax.get_window_extent(renderer))
    scene = _Scene.of(ax, renderer, frame, data)
    to_px = ax.transData.transform
    anchors = to_px(np.array([c.anchor for c in callouts], dtype=float).reshape(-1, 2))
    notes, sizes = [], []
    for c in callouts:
        note = ax.annotate(c.text, c.anchor, xytext=c.anchor, textcoords="data", ha="center",
                           va="center", annotation_clip=False, **c.style)
        note.set_gid("callout")
        note.update_bbox_position_size(renderer)
        patch = note.get_bbox_patch()
        box = box_of((patch if patch is not None else note).get_window_extent(renderer))
        sizes.append((box[2] - box[0], box[3] - box[1]))
        notes.append(note)
    labels = [_Label(a, size, _direction(ax, c), bool(c.style.get("arrowprops")),
                     None if c.on is None or not len(c.on) else
                     Cells.of(to_px(np.asarray(c.on, dtype=float)), frame, 2))
              for c, a, size in zip(callouts, anchors, sizes)]
    placed, cost = _arrange(labels, range(len(labels)), scene, frame)
    last = cost
    for _ in range(3):      # the labels a round left with a fault placed first, the next
        faulty = [i for i, c in enumerate(last) if c >= FAULT]
        if not faulty:
            break
        again, last = _arrange(labels, faulty + [i for i in range(len(labels))
                                                 if i not in faulty], scene, frame)
        if sum(last) < sum(cost):
            placed, cost = again, last
    to_data = ax.transData.inverted().transform
    for note, (box, _) in zip(notes, placed):
        note.xyann = tuple(to_data([(box[0] + box[2]) / 2, (box[1] + box[3]) / 2]))
    return notes


@dataclass(frozen=True)
class _Label:
    """A callout in pixels: its point, its box's size, the direction it would rather take
    (a unit vector, or None), whether it has a leader and the cells it should lie over."""

    anchor: np.ndarray
    size: tuple[float, float]
    prefer: np.ndarray | None
    leader: bool
    on: Cells | None


def _arrange(labels: list[_Label], order, scene, frame):
    """Each label placed in ``order`` among those placed before, then again among all the
    others until none moves (at most four rounds): the (box, leader) of each and its cost."""
    placed: list = [None] * len(labels)
    cost = [0.0] * len(labels)
    for _ in range(4):
        moved = False
        for i in order:
            others = [p for j, p in enumerate(placed) if j != i and p is not None]
            # a label without a leader sits on its point: the others may cover that point
            rest = np.array([labels[j].anchor for j in range(len(labels))
                             if j != i and labels[j].leader]).reshape(-1, 2)
            box, line, cost[i] = _best(labels[i], others, rest, scene, frame)
            moved |= placed[i] is None or not np.allclose(box, placed[i][0])
            placed[i] = (box, line)
        if not moved:
            break
    return placed, cost


LEGEND_PLACES = ("upper right", "upper left", "lower right", "lower left", "center right",
                 "center left", "upper center", "lower center", "center")


def place_legend(ax, fallback: str = "headroom", **kw):
    """A legend of ``ax`` (``kw``: ``Axes.legend``'s) at the first of :data:`LEGEND_PLACES`
    where it covers no data: no line, marker, bar, shaded span or text. Where each place
    covers some, ``fallback``: "headroom" extends the y axis upwards until an upper place is
    free (axes whose y starts at a floor, as stresses at 0), "outside" puts the legend to the
    right of the axes. Call it once the axes' place is final; returns the legend."""
    apply_limits(ax)
    legend = ax.legend(**{"loc": "upper right", **kw})
    renderer = ax.figure.canvas.get_renderer()
    cover = _place_cover(ax, legend, renderer, LEGEND_PLACES)
    if min(cover.values()) > 0 and fallback == "headroom":
        lo, hi = ax.get_ylim()
        for k in range(1, 8):       # up to 2.7 times the span: the data keeps most of it
            ax.set_ylim(lo, lo + 1.15 ** k * (hi - lo))
            upper = _place_cover(ax, legend, renderer, UPPER_PLACES)
            if min(upper.values()) == 0:
                cover = upper
                break
        else:
            ax.set_ylim(lo, hi)
    free = [p for p, c in cover.items() if c == 0]
    if not free and fallback == "outside":
        legend.set_loc("upper left")
        legend.set_bbox_to_anchor((1.01, 1.0), transform=ax.transAxes)
    else:
        legend.set_loc(free[0] if free else min(cover, key=cover.get))
    return legend


UPPER_PLACES = ("upper right", "upper left", "upper center")


def legend_cover(ax, legend) -> float:
    """How much data ``legend`` covers in ``ax`` (0: none), as :func:`place_legend` counts
    it: samples of lines, markers, texts and the covered share of filled patches."""
    renderer = ax.figure.canvas.get_renderer()
    box = box_of(legend.get_window_extent(renderer))
    return float(_cover(Drawn.of(ax, renderer), box[None, :])[0])


def _place_cover(ax, legend, renderer, places) -> dict[str, float]:
    """How much data ``legend`` would cover at each of ``places`` in ``ax``."""
    box = box_of(legend.get_window_extent(renderer))
    w, h = box[2] - box[0], box[3] - box[1]
    frame = box_of(ax.get_window_extent(renderer))
    pad = legend.borderaxespad * legend.prop.get_size_in_points() * px_per_pt(ax)
    boxes = np.array([_legend_box(frame, w, h, pad, p) for p in places])
    grown = boxes + np.array([-2, -2, 2, 2]) * MARGIN_PX       # clear of it, not touching
    return dict(zip(places, _cover(Drawn.of(ax, renderer), grown)))


def _legend_box(frame, w: float, h: float, pad: float, place: str) -> np.ndarray:
    """The box (px) of a legend of size ``w`` × ``h`` at ``place`` in ``frame``."""
    x0, y0, x1, y1 = frame
    vertical, _, horizontal = place.partition(" ") if place != "center" else ("center", "",
                                                                             "center")
    left = {"left": x0 + pad, "right": x1 - pad - w, "center": (x0 + x1 - w) / 2}[horizontal]
    low = {"lower": y0 + pad, "upper": y1 - pad - h, "center": (y0 + y1 - h) / 2}[vertical]
    return np.array([left, low, left + w, low + h])


def _cover(drawn: Drawn, boxes: np.ndarray) -> np.ndarray:
    """For each box (k, 4): the line samples and markers inside, the texts it overlaps and
    the share of a 8 × 4 grid over it inside filled patches, summed."""
    cost = inside(drawn.samples, boxes).sum(axis=1).astype(float)
    if len(drawn.markers):
        cost += discs_hit(drawn.markers, boxes).sum(axis=1)
    if len(drawn.texts):
        cost += (overlap(boxes[:, None, :], drawn.texts[None, :, :]) > 0).sum(axis=1)
    if drawn.fills:
        u, v = np.meshgrid(np.linspace(0.02, 0.98, 8), np.linspace(0.05, 0.95, 4))
        for k, b in enumerate(boxes):
            grid = np.column_stack([b[0] + u.ravel() * (b[2] - b[0]),
                                    b[1] + v.ravel() * (b[3] - b[1])])
            cost[k] += sum(path.contains_points(grid).mean() for path in drawn.fills)
    return cost


@dataclass(frozen=True)
class _Scene:
    """What a label must not cover or cross, and the data it should rather leave in view, in
    display pixels: markers (x, y, r), text boxes, line samples and the data's cells."""

    markers: np.ndarray
    texts: np.ndarray
    samples: np.ndarray
    data: Cells | None

    @classmethod
    def of(cls, ax, renderer, frame, data) -> _Scene:
        drawn = Drawn.of(ax, renderer)
        cells = (Cells.of(ax.transData.transform(np.asarray(data, dtype=float)), frame, 1)
                 if data is not None and len(data) else None)
        return cls(drawn.markers, drawn.texts, drawn.samples, cells)


def _candidates(anchor, size, prefer, leader: bool):
    """Boxes (k, 4) a label of ``size`` may take about ``anchor``, where each one's leader
    leaves it (None for a label without one) and the cost of its distance and direction.
    With a leader: a ring of directions at each of GAPS_PX; without: the label over its point
    or shifted a little from it."""
    w, h = size
    if leader:
        angles = np.linspace(0.0, 2 * np.pi, DIRECTIONS, endpoint=False)
        u = np.column_stack([np.cos(angles), np.sin(angles)])
        reach = np.abs(u[:, 0]) * w / 2 + np.abs(u[:, 1]) * h / 2
        gaps = np.array(GAPS_PX)
        centres = (anchor + u[:, None, :] * (gaps[None, :, None]
                                             + reach[:, None, None])).reshape(-1, 2)
        steps = np.repeat(u, len(gaps), axis=0)
        exits = centres - steps * np.repeat(reach, len(gaps))[:, None]
        cost = np.tile(gaps, DIRECTIONS) + (0.0 if prefer is None
                                            else PREFER_COST * (1.0 - steps @ prefer))
    else:
        dx, dy = np.meshgrid(np.arange(-8, 9) * 30.0, np.arange(-6, 7) * 20.0)
        centres = anchor + np.column_stack([dx.ravel(), dy.ravel()])
        exits, cost = None, 0.5 * np.hypot(dx, dy).ravel()
    boxes = np.column_stack([centres - [w / 2, h / 2], centres + [w / 2, h / 2]])
    return boxes, exits, cost


def _best(label: _Label, placed, others, scene: _Scene, frame):
    """The box, leader (or None) and cost of the candidate of least cost for ``label`` among
    the ``placed`` labels and the ``others``' anchors."""
    anchor, on = label.anchor, label.on
    boxes, exits, cost = _candidates(anchor, label.size, label.prefer, label.leader)
    inner = frame + np.array([MARGIN_PX, MARGIN_PX, -MARGIN_PX, -MARGIN_PX])
    cost += FAULT * ~((boxes[:, :2] >= inner[:2]) & (boxes[:, 2:] <= inner[2:])).all(axis=1)
    grown = boxes + np.array([-MARGIN_PX, -MARGIN_PX, MARGIN_PX, MARGIN_PX])
    if len(scene.markers):
        cost += FAULT * discs_hit(scene.markers, grown).sum(axis=1)
    if len(others):
        cost += FAULT * inside(others, grown).sum(axis=1)
    cost += FAULT * (overlap(grown[:, None, :], scene.texts[None, :, :]) > 0).sum(axis=1)
    boxes_placed, leaders = _placed(placed)
    cost += FAULT * (overlap(grown[:, None, :], boxes_placed[None, :, :]) > 0).sum(axis=1)
    if len(leaders):
        cost += FAULT * segments_through_boxes(leaders[:, 0], leaders[:, 1], boxes).sum(axis=0)
    if exits is not None:
        cost += _leader_cost(exits, anchor, placed, scene)
    cost += LINE_COST * inside(scene.samples, boxes).sum(axis=1)
    if scene.data is not None:
        cost += DATA_COST * scene.data.share(boxes)
    if on is not None:                      # off what it names: as bad as over the data
        cost += DATA_COST * (1.0 - on.share(boxes))
    k = int(np.argmin(cost))
    return boxes[k], None if exits is None else (exits[k], anchor), float(cost[k])


def _leader_cost(exits, anchor, placed, scene: _Scene) -> np.ndarray:
    """The cost of leaders from ``exits`` to ``anchor``: crossing a placed leader or running
    through a placed label (faults), grazing a marker, a text or a drawn line."""
    boxes_placed, leaders = _placed(placed)
    cost = FAULT * segments_through_boxes(exits, anchor, boxes_placed).sum(axis=1)
    if len(leaders):
        cost += FAULT * segments_cross(exits[:, None, :], anchor, leaders[None, :, 0],
                                       leaders[None, :, 1]).sum(axis=1)
    if len(scene.markers):
        far = np.hypot(*(scene.markers[:, :2] - anchor).T) > scene.markers[:, 2] + 4.0
        cost += GRAZE * segments_near(exits, anchor, scene.markers[far]).sum(axis=1)
    cost += GRAZE * segments_through_boxes(exits, anchor, scene.texts).sum(axis=1)
    # only the samples within SAMPLE_PX of the leaders' bounding box can be near one
    ends = np.vstack([exits, anchor])
    low, high = ends.min(axis=0) - SAMPLE_PX, ends.max(axis=0) + SAMPLE_PX
    samples = scene.samples[((scene.samples >= low) & (scene.samples <= high)).all(axis=1)] \
        if len(scene.samples) else scene.samples
    if len(samples):
        # a sample's distance to each leader from its coordinates along and across it,
        # measured from the anchor that all the leaders share: two products, no (k, n, 2)
        d = exits - anchor                                  # (k, 2)
        length = np.maximum(np.hypot(*d.T), 1e-12)
        rel = samples - anchor                              # (n, 2)
        along = rel @ (d / length[:, None]).T               # (n, k)
        across = np.abs(rel[:, :1] * d[:, 1] - rel[:, 1:] * d[:, 0]) / length
        r2 = (rel * rel).sum(axis=1)[:, None]
        limit = SAMPLE_PX ** 2
        near = (((along >= 0.0) & (along <= length) & (across < SAMPLE_PX)) | (r2 < limit)
                | (r2 - 2.0 * along * length + length ** 2 < limit))
        cost += LINE_COST * near.sum(axis=0)
    return cost


def _placed(placed) -> tuple[np.ndarray, np.ndarray]:
    """The boxes (m, 4) of the ``placed`` labels and their leaders (l, 2, 2): exit, anchor."""
    boxes = np.array([box for box, _ in placed]).reshape(-1, 4)
    return boxes, np.array([line for _, line in placed if line is not None]).reshape(-1, 2, 2)


def _direction(ax, c: Callout):
    """A callout's preferred direction in display pixels (a unit vector), or None."""
    if c.prefer is None:
        return None
    a = np.asarray(c.anchor, dtype=float)
    d = ax.transData.transform(a + np.asarray(c.prefer)) - ax.transData.transform(a)
    return d / np.linalg.norm(d)


