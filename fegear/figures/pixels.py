"""What a drawn axes shows, in display pixels, and the geometry of boxes and segments there:
what :mod:`fegear.figures.labels` places labels and legends among. Boxes are (x0, y0, x1, y1)
arrays, points (x, y); the functions broadcast over rows.

The artists are read through their own methods (window extents, paths, offsets), so this
module imports no matplotlib.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: pixels between the samples of a drawn line, and the side of a cell of :class:`Cells`
SAMPLE_PX, CELL_PX = 3.0, 5.0


@dataclass(frozen=True)
class Drawn:
    """What an axes shows, in display pixels: samples along its lines (every SAMPLE_PX),
    its markers, the boxes of its texts and the filled patches' display paths."""

    samples: np.ndarray
    markers: np.ndarray          # (n, 3): x, y, radius
    texts: np.ndarray            # (n, 4)
    fills: list

    @classmethod
    def of(cls, ax, renderer) -> Drawn:
        samples, markers, texts, fills = [], [], [], []
        for line in ax.lines:
            if not line.get_visible():
                continue
            xy = line.get_transform().transform(np.asarray(line.get_xydata(), dtype=float))
            xy = xy[np.isfinite(xy).all(axis=1)]
            if line.get_linestyle() not in ("None", "", " ") and len(xy) > 1:
                samples.append(along(xy))
            if line.get_marker() not in (None, "None", "", " ") and len(xy):
                r = (line.get_markersize() / 2 + line.get_markeredgewidth()) * px_per_pt(ax)
                markers.append(np.column_stack([xy, np.full(len(xy), r)]))
        for c in ax.collections:
            offsets = np.asarray(c.get_offsets(), dtype=float)
            sizes = c.get_sizes() if hasattr(c, "get_sizes") else None
            if sizes is not None and len(sizes) and c.get_visible():   # a scatter's points
                xy = c.get_offset_transform().transform(offsets)
                r = np.sqrt(np.resize(sizes, len(xy))) / 2 * px_per_pt(ax)
                markers.append(np.column_stack([xy, r]))
        for p in ax.patches:
            if not p.get_visible():
                continue
            path = p.get_transform().transform_path(p.get_path())
            if p.get_fill():
                fills.append(path)
            else:                                          # an outline: a line
                samples.append(along(path.vertices))
        for t in ax.texts:
            if t.get_visible() and t.get_text():
                texts.append(text_box(t, renderer))
        return cls(np.vstack(samples) if samples else np.zeros((0, 2)),
                   np.vstack(markers) if markers else np.zeros((0, 3)),
                   np.array(texts).reshape(-1, 4), fills)


@dataclass(frozen=True)
class Cells:
    """Where a set of points lies, as cells of CELL_PX over a frame (px): a summed-area
    table, so that the share of a box's cells that hold a point is four look-ups."""

    table: np.ndarray
    frame: np.ndarray

    @classmethod
    def of(cls, xy: np.ndarray, frame, dilation: int) -> Cells:
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


def apply_limits(ax) -> None:
    """The limits and box ``ax`` will be drawn with: matplotlib scales the axes to the data
    and applies an equal aspect only when drawing, or when the limits are read."""
    ax.get_xlim()
    ax.get_ylim()
    ax.apply_aspect()


def along(xy: np.ndarray) -> np.ndarray:
    """Points every SAMPLE_PX along a polyline (px)."""
    out = [xy[:1]]
    for p, q in zip(xy[:-1], xy[1:]):
        n = max(int(np.hypot(*(q - p)) / SAMPLE_PX), 1)
        out.append(p + (q - p) * (np.arange(1, n + 1) / n)[:, None])
    return np.vstack(out)


def px_per_pt(ax) -> float:
    """Pixels in a point."""
    return ax.figure.dpi / 72.0


def box_of(bbox) -> np.ndarray:
    return np.array([bbox.x0, bbox.y0, bbox.x1, bbox.y1], dtype=float)


def text_box(t, renderer) -> np.ndarray:
    """A text's box in px: its bbox patch's where it has one."""
    if hasattr(t, "update_positions"):          # an annotation: its text placed first
        t.update_positions(renderer)
    t.update_bbox_position_size(renderer)
    patch = t.get_bbox_patch()
    return box_of((patch if patch is not None else t).get_window_extent(renderer))


def inside(points: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """(k, n): point n inside box k."""
    p = points[None, :, :2]
    b = boxes[:, None, :]
    return ((p[..., 0] > b[..., 0]) & (p[..., 0] < b[..., 2])
            & (p[..., 1] > b[..., 1]) & (p[..., 1] < b[..., 3]))


def discs_hit(discs: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """(k, n): disc n (x, y, r) reaches into box k."""
    c = discs[None, :, :2]
    b = boxes[:, None, :]
    dx = np.maximum(np.maximum(b[..., 0] - c[..., 0], c[..., 0] - b[..., 2]), 0.0)
    dy = np.maximum(np.maximum(b[..., 1] - c[..., 1], c[..., 1] - b[..., 3]), 0.0)
    return np.hypot(dx, dy) < discs[None, :, 2]


def overlap(a: np.ndarray, b: np.ndarray) -> np.ndarray:
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


def segments_through_boxes(p, q, boxes) -> np.ndarray:
    """(k, n): whether segment p–q (rows of ``p``, and of ``q`` or ``q`` one point) passes
    through box n of ``boxes``: an end inside it, or one of its edges crossed."""
    p = np.asarray(p, dtype=float).reshape(-1, 2)
    q = np.broadcast_to(np.asarray(q, dtype=float), p.shape)
    p, q, b = p[:, None, :], q[:, None, :], np.asarray(boxes, dtype=float).reshape(1, -1, 4)
    hit = _in(p, b) | _in(q, b)
    x0, y0, x1, y1 = b[..., 0], b[..., 1], b[..., 2], b[..., 3]
    corners = [np.stack(c, axis=-1) for c in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))]
    for a, c in zip(corners, corners[1:] + corners[:1]):
        hit |= segments_cross(p, q, a, c)
    return hit


def _in(p, b) -> np.ndarray:
    """Point ``p`` strictly inside box ``b`` (broadcast)."""
    return ((b[..., 0] < p[..., 0]) & (p[..., 0] < b[..., 2]) & (b[..., 1] < p[..., 1])
            & (p[..., 1] < b[..., 3]))


def segments_near(p, q, discs) -> np.ndarray:
    """(k, n): whether segment p–q (rows of ``p``; ``q`` one point) passes within disc n's
    radius of its centre (``discs``: rows x, y, r)."""
    p = np.asarray(p, dtype=float).reshape(-1, 2)
    d = (np.asarray(q, dtype=float) - p)[:, None, :]
    c = np.asarray(discs, dtype=float).reshape(-1, 3)
    rel = c[None, :, :2] - p[:, None, :]
    t = np.clip((rel * d).sum(axis=2) / np.maximum((d * d).sum(axis=2), 1e-12), 0.0, 1.0)
    return np.hypot(*(t[..., None] * d - rel).transpose(2, 0, 1)) < c[None, :, 2]
