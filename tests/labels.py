"""What a picture's labels do wrong, read off the drawn artists' pixels (a test helper): a label
box over a marker or over another box, leaders that cross, a box out of its axes."""

from __future__ import annotations

import numpy as np

from fegear.figures.pixels import segments_cross


def label_boxes(ax) -> list[tuple[np.ndarray, np.ndarray | None]]:
    """(box x0, y0, x1, y1 in px, the point its leader names in px, None without a leader)
    of each placed label of ``ax``, as drawn."""
    ax.figure.canvas.draw()
    renderer = ax.figure.canvas.get_renderer()
    out = []
    for t in ax.texts:
        if t.get_gid() != "callout":
            continue
        b = t.get_bbox_patch().get_window_extent(renderer)
        out.append((np.array([b.x0, b.y0, b.x1, b.y1]),
                    None if t.arrow_patch is None else ax.transData.transform(t.xy)))
    return out


def markers(ax) -> np.ndarray:
    """(x, y, radius) in px of every marker drawn by a line of ``ax``."""
    pt = ax.figure.dpi / 72
    rows = []
    for line in ax.lines:
        if line.get_marker() in (None, "None", "", " "):
            continue
        xy = line.get_transform().transform(np.asarray(line.get_xydata(), dtype=float))
        r = (line.get_markersize() / 2 + line.get_markeredgewidth() / 2) * pt
        rows += [(x, y, r) for x, y in xy]
    return np.array(rows).reshape(-1, 3)


def label_faults(ax) -> list[str]:
    """Each fault of the labels of ``ax``, in words (none: an empty list)."""
    frame = ax.get_window_extent(ax.figure.canvas.get_renderer())
    labels = label_boxes(ax)
    faults = []
    for k, (box, _) in enumerate(labels):
        if box[0] < frame.x0 or box[1] < frame.y0 or box[2] > frame.x1 or box[3] > frame.y1:
            faults.append(f"label {k} leaves its axes")
        for x, y, r in markers(ax):
            dx = max(box[0] - x, x - box[2], 0.0)
            dy = max(box[1] - y, y - box[3], 0.0)
            if np.hypot(dx, dy) < r:
                faults.append(f"label {k} covers the marker at ({x:.0f}, {y:.0f}) px")
    for i, (a, pa) in enumerate(labels):
        for j, (b, pb) in enumerate(labels[:i]):
            if min(a[2], b[2]) > max(a[0], b[0]) and min(a[3], b[3]) > max(a[1], b[1]):
                faults.append(f"labels {j} and {i} overlap")
            ca, cb = (a[:2] + a[2:]) / 2, (b[:2] + b[2:]) / 2
            if pa is not None and pb is not None and segments_cross(ca, pa, cb, pb):
                faults.append(f"the leaders of labels {j} and {i} cross")
    return faults


def panels_overlapping(fig) -> list[tuple[int, int]]:
    """The pairs of ``fig``'s axes whose drawn extents (frame, tick labels, axis labels and
    title) overlap: a panel's label written over its neighbour's ticks."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes = [ax.get_tightbbox(renderer) for ax in fig.axes]
    return [(j, i) for i, a in enumerate(boxes) for j, b in enumerate(boxes[:i])
            if min(a.x1, b.x1) > max(a.x0, b.x0) and min(a.y1, b.y1) > max(a.y0, b.y0)]
