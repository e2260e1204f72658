"""Labels and legends placed clear of what a picture shows.

The placing is done in display pixels once the axes are laid out. A label (a
:class:`Callout`) is tried at a ring of offsets around the point it names. The kept offset
covers no marker, no other label and no text; its leader crosses no other leader and runs
through no label box or marker; and it covers the least of the data. Then each label is
placed again among the others until none moves. A legend goes where it covers no data: a
corner of its axes, else above the data (the y axis extended) or outside the axes.

The artists are read through their own methods (window extents, paths, offsets), so this
module imports no matplotlib.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

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
#: pixels between the samples of a line, the cells of the data grid, a box's clear margin
SAMPLE_PX, CELL_PX, MARGIN_PX = 3.0, 5.0, 3.0
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
    _settle(ax)
    renderer = ax.figure.canvas.get_renderer()
    frame = _box_of(ax.get_window_extent(renderer))
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
        box = _box_of((patch if patch is not None else note).get_window_extent(renderer))
        sizes.append((box[2] - box[0], box[3] - box[1]))
        notes.append(note)
    labels = [_Label(a, size, _direction(ax, c), bool(c.style.get("arrowprops")),
                     None if c.on is None or not len(c.on) else
                     _Cells.of(to_px(np.asarray(c.on, dtype=float)), frame, 2))
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
    on: _Cells | None


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
    _settle(ax)
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
    box = _box_of(legend.get_window_extent(renderer))
    return float(_cover(_Drawn.of(ax, renderer), box[None, :])[0])


def _place_cover(ax, legend, renderer, places) -> dict[str, float]:
    """How much data ``legend`` would cover at each of ``places`` in ``ax``."""
    box = _box_of(legend.get_window_extent(renderer))
    w, h = box[2] - box[0], box[3] - box[1]
    frame = _box_of(ax.get_window_extent(renderer))
    pad = legend.borderaxespad * legend.prop.get_size_in_points() * _pt(ax)
    boxes = np.array([_legend_box(frame, w, h, pad, p) for p in places])
    grown = boxes + np.array([-2, -2, 2, 2]) * MARGIN_PX       # clear of it, not touching
    return dict(zip(places, _cover(_Drawn.of(ax, renderer), grown)))


def _legend_box(frame, w: float, h: float, pad: float, place: str) -> np.ndarray:
    """The box (px) of a legend of size ``w`` × ``h`` at ``place`` in ``frame``."""
    x0, y0, x1, y1 = frame
    vertical, _, horizontal = place.partition(" ") if place != "center" else ("center", "",
                                                                             "center")
    left = {"left": x0 + pad, "right": x1 - pad - w, "center": (x0 + x1 - w) / 2}[horizontal]
    low = {"lower": y0 + pad, "upper": y1 - pad - h, "center": (y0 + y1 - h) / 2}[vertical]
    return np.array([left, low, left + w, low + h])


@dataclass(frozen=True)
class _Drawn:
    """What an axes shows, in display pixels: samples along its lines (every SAMPLE_PX),
    its markers, the boxes of its texts and the filled patches' display paths."""

    samples: np.ndarray
    markers: np.ndarray          # (n, 3): x, y, radius
    texts: np.ndarray            # (n, 4)
    fills: list

    @classmethod
    def of(cls, ax, renderer) -> _Drawn:
        samples, markers, texts, fills = [], [], [], []
        for line in ax.lines:
            if not line.get_visible():
                continue
            xy = line.get_transform().transform(np.asarray(line.get_xydata(), dtype=float))
            xy = xy[np.isfinite(xy).all(axis=1)]
            if line.get_linestyle() not in ("None", "", " ") and len(xy) > 1:
                samples.append(_along(xy))
            if line.get_marker() not in (None, "None", "", " ") and len(xy):
                r = (line.get_markersize() / 2 + line.get_markeredgewidth()) * _pt(ax)
                markers.append(np.column_stack([xy, np.full(len(xy), r)]))
        for c in ax.collections:
            offsets = np.asarray(c.get_offsets(), dtype=float)
            sizes = c.get_sizes() if hasattr(c, "get_sizes") else None
            if sizes is not None and len(sizes) and c.get_visible():   # a scatter's points
                xy = c.get_offset_transform().transform(offsets)
                r = np.sqrt(np.resize(sizes, len(xy))) / 2 * _pt(ax)
                markers.append(np.column_stack([xy, r]))
        for p in ax.patches:
            if not p.get_visible():
                continue
            path = p.get_transform().transform_path(p.get_path())
            if p.get_fill():
                fills.append(path)
            else:                                          # an outline: a line
                samples.append(_along(path.vertices))
        for t in ax.texts:
            if t.get_visible() and t.get_text():
                texts.append(_text_box(t, renderer))
        return cls(np.vstack(samples) if samples else np.zeros((0, 2)),
                   np.vstack(markers) if markers else np.zeros((0, 3)),
                   np.array(texts).reshape(-1, 4), fills)


def _cover(drawn: _Drawn, boxes: np.ndarray) -> np.ndarray:
    """For each box (k, 4): the line samples and markers inside, the texts it overlaps and
    the share of a 8 × 4 grid over it inside filled patches, summed."""
    cost = _inside(drawn.samples, boxes).sum(axis=1).astype(float)
    if len(drawn.markers):
        cost += _discs_hit(drawn.markers, boxes).sum(axis=1)
    if len(drawn.texts):
        cost += (_overlap(boxes[:, None, :], drawn.texts[None, :, :]) > 0).sum(axis=1)
    if drawn.fills:
        u, v = np.meshgrid(np.linspace(0.02, 0.98, 8), np.linspace(0.05, 0.95, 4))
        for k, b in enumerate(boxes):
            grid = np.column_stack([b[0] + u.ravel() * (b[2] - b[0]),
                                    b[1] + v.ravel() * (b[3] - b[1])])
            cost[k] += sum(path.contains_points(grid).mean() for path in drawn.fills)
    return cost


@dataclass(frozen=True)
class _Cells:
    """Where a set of points lies, as cells of CELL_PX over a frame (px): a summed-area
    table, so that the share of a box's cells that hold a point is four look-ups."""

    table: np.ndarray
    frame: np.ndarray

    @classmethod
    def of(cls, xy: np.ndarray, frame, dilation: int) -> _Cells:
        """``xy`` (px) binned, each filled cell grown by ``dilation`` cells: a coarse mesh
        leaves empty cells between its nodes."""
        nx = int(np.ceil((frame[2] - frame[0]) / CELL_PX))
        ny = int(np.ceil((frame[3] - frame[1]) / CELL_PX))
        counts, _, _ = np.histogram2d(xy[:, 0], xy[:, 1], bins=(nx, ny),
                                      range=((frame[0], frame[0] + nx * CELL_PX),
                                             (frame[1], frame[1] + ny * CELL_PX)))
        full = counts > 0
        for _ in range(dilation):
            full[1:] |= full[:-1].copy()
            full[:-1] |= full[1:].copy()
            full[:, 1:] |= full[:, :-1].copy()
            full[:, :-1] |= full[:, 1:].copy()
        table = np.zeros((nx + 1, ny + 1))
        table[1:, 1:] = full.cumsum(axis=0).cumsum(axis=1)
        return cls(table, np.asarray(frame, dtype=float))

    def share(self, boxes: np.ndarray) -> np.ndarray:
        """The share of each box's cells that hold a point."""
        nx, ny = self.table.shape[0] - 1, self.table.shape[1] - 1
        f = self.frame
        i0 = np.clip(((boxes[:, 0] - f[0]) / CELL_PX).astype(int), 0, nx)
        i1 = np.clip(np.ceil((boxes[:, 2] - f[0]) / CELL_PX).astype(int), 0, nx)
        j0 = np.clip(((boxes[:, 1] - f[1]) / CELL_PX).astype(int), 0, ny)
        j1 = np.clip(np.ceil((boxes[:, 3] - f[1]) / CELL_PX).astype(int), 0, ny)
        t = self.table
        full = t[i1, j1] - t[i0, j1] - t[i1, j0] + t[i0, j0]
        return full / np.maximum((i1 - i0) * (j1 - j0), 1)


@dataclass(frozen=True)
class _Scene:
    """What a label must not cover or cross, and the data it should rather leave in view, in
    display pixels: markers (x, y, r), text boxes, line samples and the data's cells."""

    markers: np.ndarray
    texts: np.ndarray
    samples: np.ndarray
    data: _Cells | None

    @classmethod
    def of(cls, ax, renderer, frame, data) -> _Scene:
        drawn = _Drawn.of(ax, renderer)
        cells = (_Cells.of(ax.transData.transform(np.asarray(data, dtype=float)), frame, 1)
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
        cost += FAULT * _discs_hit(scene.markers, grown).sum(axis=1)
    if len(others):
        cost += FAULT * _inside(others, grown).sum(axis=1)
    for t in scene.texts:
        cost += FAULT * (_overlap(grown, t) > 0)
    for box, line in placed:
        cost += FAULT * (_overlap(grown, box) > 0)
        if line is not None:
            cost += FAULT * _segment_hits_boxes(*line, boxes)
    if exits is not None:
        cost += _leader_cost(exits, anchor, placed, scene)
    cost += LINE_COST * _inside(scene.samples, boxes).sum(axis=1)
    if scene.data is not None:
        cost += DATA_COST * scene.data.share(boxes)
    if on is not None:                      # off what it names: as bad as over the data
        cost += DATA_COST * (1.0 - on.share(boxes))
    k = int(np.argmin(cost))
    return boxes[k], None if exits is None else (exits[k], anchor), float(cost[k])


def _leader_cost(exits, anchor, placed, scene: _Scene) -> np.ndarray:
    """The cost of leaders from ``exits`` to ``anchor``: crossing a placed leader or running
    through a placed label (faults), grazing a marker, a text or a drawn line."""
    cost = np.zeros(len(exits))
    for box, line in placed:
        cost += FAULT * _segment_hits_box(exits, anchor, box)
        if line is not None:
            cost += FAULT * segments_cross(exits, anchor, *line)
    if len(scene.markers):
        far = np.hypot(*(scene.markers[:, :2] - anchor).T) > scene.markers[:, 2] + 4.0
        for m in scene.markers[far]:
            cost += GRAZE * _segment_near(exits, anchor, m[:2], m[2])
    for t in scene.texts:
        cost += GRAZE * _segment_hits_box(exits, anchor, t)
    if len(scene.samples):
        d = anchor - exits                                  # (k, 2)
        rel = scene.samples[None, :, :] - exits[:, None, :]
        t = np.clip((rel * d[:, None, :]).sum(axis=2)
                    / np.maximum((d * d).sum(axis=1), 1e-12)[:, None], 0.0, 1.0)
        near = np.hypot(*(rel - t[..., None] * d[:, None, :]).transpose(2, 0, 1)) < SAMPLE_PX
        cost += LINE_COST * near.sum(axis=1)
    return cost


def _settle(ax) -> None:
    """The limits and box ``ax`` will be drawn with: matplotlib scales the axes to the data
    and applies an equal aspect only when drawing, or when the limits are read."""
    ax.get_xlim()
    ax.get_ylim()
    ax.apply_aspect()


def _direction(ax, c: Callout):
    """A callout's preferred direction in display pixels (a unit vector), or None."""
    if c.prefer is None:
        return None
    a = np.asarray(c.anchor, dtype=float)
    d = ax.transData.transform(a + np.asarray(c.prefer)) - ax.transData.transform(a)
    return d / np.linalg.norm(d)


def _along(xy: np.ndarray) -> np.ndarray:
    """Points every SAMPLE_PX along a polyline (px)."""
    out = [xy[:1]]
    for p, q in zip(xy[:-1], xy[1:]):
        n = max(int(np.hypot(*(q - p)) / SAMPLE_PX), 1)
        out.append(p + (q - p) * (np.arange(1, n + 1) / n)[:, None])
    return np.vstack(out)


def _pt(ax) -> float:
    """Pixels in a point."""
    return ax.figure.dpi / 72.0


def _box_of(bbox) -> np.ndarray:
    return np.array([bbox.x0, bbox.y0, bbox.x1, bbox.y1], dtype=float)


def _text_box(t, renderer) -> np.ndarray:
    """A text's box in px: its bbox patch's where it has one."""
    if hasattr(t, "update_positions"):          # an annotation: its text placed first
        t.update_positions(renderer)
    t.update_bbox_position_size(renderer)
    patch = t.get_bbox_patch()
    return _box_of((patch if patch is not None else t).get_window_extent(renderer))


def _inside(points: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """(k, n): point n inside box k."""
    p = points[None, :, :2]
    b = boxes[:, None, :]
    return ((p[..., 0] > b[..., 0]) & (p[..., 0] < b[..., 2])
            & (p[..., 1] > b[..., 1]) & (p[..., 1] < b[..., 3]))


def _discs_hit(discs: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """(k, n): disc n (x, y, r) reaches into box k."""
    c = discs[None, :, :2]
    b = boxes[:, None, :]
    dx = np.maximum(np.maximum(b[..., 0] - c[..., 0], c[..., 0] - b[..., 2]), 0.0)
    dy = np.maximum(np.maximum(b[..., 1] - c[..., 1], c[..., 1] - b[..., 3]), 0.0)
    return np.hypot(dx, dy) < discs[None, :, 2]


def _overlap(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The overlapping area of boxes ``a`` and ``b`` (broadcast)."""
    w = np.minimum(a[..., 2], b[..., 2]) - np.maximum(a[..., 0], b[..., 0])
    h = np.minimum(a[..., 3], b[..., 3]) - np.maximum(a[..., 1], b[..., 1])
    return np.maximum(w, 0.0) * np.maximum(h, 0.0)


def _cross(o, a, b):
    """The z of (a − o) × (b − o), broadcast over rows."""
    return ((a[..., 0] - o[..., 0]) * (b[..., 1] - o[..., 1])
            - (a[..., 1] - o[..., 1]) * (b[..., 0] - o[..., 0]))


def segments_cross(p1, p2, q1, q2) -> np.ndarray:
    """Whether segments p1–p2 and q1–q2 cross (broadcast over rows; touching ends do not
    count)."""
    p1, p2, q1, q2 = (np.asarray(v, dtype=float) for v in (p1, p2, q1, q2))
    d1, d2 = _cross(q1, q2, p1), _cross(q1, q2, p2)
    d3, d4 = _cross(p1, p2, q1), _cross(p1, p2, q2)
    return (d1 * d2 < 0) & (d3 * d4 < 0)


def _segment_hits_box(p, q, box) -> np.ndarray:
    """Whether segments p–q (rows of ``p``; ``q`` one point) pass through ``box``."""
    p = np.asarray(p, dtype=float)
    q = np.broadcast_to(np.asarray(q, dtype=float), p.shape)
    return _hits(p, q, np.broadcast_to(box, (len(p), 4)))


def _segment_hits_boxes(p, q, boxes) -> np.ndarray:
    """Whether the one segment p–q passes through each of ``boxes``."""
    n = len(boxes)
    return _hits(np.broadcast_to(p, (n, 2)), np.broadcast_to(q, (n, 2)), boxes)


def _hits(p, q, boxes) -> np.ndarray:
    """Row-wise: segment p–q meets box (an end inside, or a crossed edge)."""
    inside = ((boxes[:, 0] < p[:, 0]) & (p[:, 0] < boxes[:, 2]) & (boxes[:, 1] < p[:, 1])
              & (p[:, 1] < boxes[:, 3]))
    inside |= ((boxes[:, 0] < q[:, 0]) & (q[:, 0] < boxes[:, 2]) & (boxes[:, 1] < q[:, 1])
               & (q[:, 1] < boxes[:, 3]))
    x0, y0, x1, y1 = boxes.T
    corners = [np.column_stack(c) for c in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))]
    for a, b in zip(corners, corners[1:] + corners[:1]):
        inside |= segments_cross(p, q, a, b)
    return inside


def _segment_near(p, q, c, r) -> np.ndarray:
    """Whether segments p–q (rows of ``p``; ``q`` one point) pass within ``r`` of ``c``."""
    d = q - p
    t = np.clip(((c - p) * d).sum(axis=1) / np.maximum((d * d).sum(axis=1), 1e-12), 0.0, 1.0)
    return np.hypot(*(p + t[:, None] * d - c).T) < r
