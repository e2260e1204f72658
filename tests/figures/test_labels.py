"""Labels and legends placed clear of the data: read back from the drawn artists' pixels."""

import numpy as np
import pytest
from labels import label_faults

from fegear.figures import pyplot
from fegear.figures.labels import Callout, legend_cover, place_callouts, place_legend
from fegear.figures.pixels import segments_cross, segments_near, segments_through_boxes


@pytest.fixture
def plt():
    p = pyplot()
    yield p
    p.close("all")


def test_crowded_labels_cover_no_marker_no_other_label_and_their_leaders_do_not_cross(plt):
    """Five labels for points 1 mm apart among markers, all preferring the same side: the
    first placement a fixed offset would give overlaps."""
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.set_xlim(0, 10)
    ax.set_ylim(0, 6)
    points = [(3.0 + k, 3.0 + 0.3 * (k % 2)) for k in range(5)]
    ax.plot(*np.array(points).T, "o", ms=10, mfc="none")
    ax.plot([3.5, 5.5], [2.2, 2.4], "x", ms=10)
    notes = place_callouts(ax, [Callout(f"tooth {k}\n{1000 + k} N", p, (0.0, -1.0),
                                        {"fontsize": 9, "bbox": {"boxstyle": "round"},
                                         "arrowprops": {"arrowstyle": "-"}})
                                for k, p in enumerate(points)])
    assert len(notes) == 5 and label_faults(ax) == []


def test_a_label_leaves_the_points_of_the_data_in_view(plt):
    """A field's high values to one side of the point: the label goes to the other."""
    fig, ax = plt.subplots(figsize=(5, 5))
    ax.set_xlim(-5, 5)
    ax.set_ylim(-5, 5)
    x, y = np.meshgrid(np.linspace(-5, 5, 80), np.linspace(-5, 5, 80))
    hot = np.column_stack([x.ravel(), y.ravel()])[y.ravel() < 0.5]
    note, = place_callouts(ax, [Callout("here", (0.0, 0.0))], data=hot)
    assert note.xyann[1] > 0.5


def test_segments_cross():
    assert segments_cross([0, 0], [1, 1], [0, 1], [1, 0])
    assert not segments_cross([0, 0], [1, 1], [2, 0], [3, 1])
    assert not segments_cross([0, 0], [1, 1], [1, 1], [2, 0])        # touching ends


def test_a_leader_goes_around_a_drawn_line(plt):
    """A line a few pixels above the point, across every side its label would rather take:
    the label goes below it rather than have its leader cross it (what the leaders' line
    cost is for)."""
    fig, ax = plt.subplots(figsize=(5, 5))
    ax.set_xlim(-5, 5)
    ax.set_ylim(-5, 5)
    ax.plot([-2.0, 5.0], [0.13, 0.13], color="C0")
    note, = place_callouts(ax, [Callout("peak", (0.0, 0.0), (1.0, 1.0),
                                        {"arrowprops": {"arrowstyle": "-"}})])
    assert note.xyann[1] < 0.0


def test_segments_through_boxes_and_near_discs():
    """Each segment against each box (k, n): through the middle with both ends out, one end
    in, beside; and against discs, the distance to the segment's end counting past it."""
    box = [[0.0, 0.0, 1.0, 1.0], [3.0, 0.0, 4.0, 1.0]]
    hit = segments_through_boxes([[-1.0, 0.5], [0.5, 0.5], [-1.0, 2.0]], [2.0, 0.5], box)
    assert hit.tolist() == [[True, False], [True, False], [False, False]]
    assert segments_through_boxes([[2.0, 0.5]], [[5.0, 0.5]], box).tolist() == [[False, True]]
    discs = [[1.0, 0.5, 0.6], [1.0, 0.5, 0.4], [3.0, 0.0, 1.1], [3.0, 0.0, 0.9]]
    assert segments_near([[0.0, 0.0]], [2.0, 0.0], discs).tolist() == [
        [True, False, True, False]]


def test_a_legend_goes_where_it_covers_no_line(plt):
    """A line along the top: the legend goes below it."""
    fig, ax = plt.subplots()
    ax.plot([0, 10], [0, 0], label="floor")
    ax.axhline(9.5, color="C3", label="allowable")
    ax.set_ylim(-1, 10)
    legend = place_legend(ax)
    assert legend_cover(ax, legend) == 0
    assert ax.get_ylim() == (-1, 10)


def test_with_no_free_place_the_axis_makes_room_above_the_data(plt):
    """Points over the whole panel: the y axis grows until an upper place is free."""
    fig, ax = plt.subplots()
    x, y = np.meshgrid(np.linspace(0, 10, 30), np.linspace(0, 10, 30))
    ax.plot(x.ravel(), y.ravel(), "o", ms=3, label="trials")
    ax.axhline(5.0, label="baseline")
    ax.set_ylim(0, 10.5)
    legend = place_legend(ax, fallback="headroom")
    assert legend_cover(ax, legend) == 0
    assert ax.get_ylim()[1] > 10.5


def test_or_outside_the_axes(plt):
    fig, ax = plt.subplots()
    x, y = np.meshgrid(np.linspace(0, 10, 30), np.linspace(0, 10, 30))
    ax.plot(x.ravel(), y.ravel(), "o", ms=3, label="trials")
    legend = place_legend(ax, fallback="outside")
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    assert legend.get_window_extent(renderer).x0 > ax.get_window_extent(renderer).x1
