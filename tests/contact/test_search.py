"""The facet search (fegear/contact/search.py): the nearest chord among chord pieces found as
among all chords, and a chain around the origin searched by angle finds the tree's chord."""

import numpy as np
import pytest

from fegear.contact import search


@pytest.mark.parametrize("candidates", [4, 16, 1000])
def test_nearest_chord_search_matches_the_search_among_all_chords(candidates, monkeypatch):
    # a long chord and, just above it, a cluster of tiny ones: the point 0.01 above the long
    # chord, where two of its pieces meet, has only tiny chords (0.05 away or more) among its
    # 16 nearest midpoints, so a search among those alone would miss the long chord
    rng = np.random.default_rng(2)
    xs = rng.uniform(0.21, 0.29, 40)
    a = np.vstack([[0.0, 0.0], np.column_stack([xs, rng.uniform(0.065, 0.09, 40)])])
    ab = np.vstack([[10.0, 0.0], np.tile([0.01, 0.0], (40, 1))])
    y = np.vstack([[0.25, 0.01], rng.uniform(-2.0, 12.0, (300, 2))])
    monkeypatch.setattr(search, "LOCATE_CANDIDATES", candidates)
    best, t = search.Chords(a, ab).nearest(y)
    foot = a[best] + np.clip(t, 0, 1)[:, None] * ab[best]
    s = np.clip(np.einsum("qcd,cd->qc", y[:, None] - a, ab) / np.sum(ab * ab, axis=1), 0, 1)
    every = np.linalg.norm(a + s[..., None] * ab - y[:, None], axis=2).min(axis=1)
    assert best[0] == 0 and t[0] == pytest.approx(0.025)
    assert np.allclose(np.linalg.norm(foot - y, axis=1), every, rtol=0, atol=1e-12)


def test_a_chain_around_the_origin_is_searched_by_angle_and_finds_the_trees_chord():
    # a wavy arc of 200 chords about the origin, 40° wide, as a gear template's profile:
    # points on it, µm off it, far off it and beyond its ends; and points on its nodes, as
    # near to two chords, where the tree's choice is kept
    rng = np.random.default_rng(5)
    phi = np.sort(rng.uniform(0.3, 1.0, 201))
    r = 20.0 + 0.8 * np.sin(9.0 * phi)
    nodes = np.column_stack([r * np.cos(phi), r * np.sin(phi)])
    a, ab = nodes[:-1], np.diff(nodes, axis=0)
    on = a + rng.uniform(0, 1, (200, 1)) * ab
    y = np.vstack([on, on + 1e-3 * rng.normal(size=on.shape), on + 2.0 * rng.normal(size=on.shape),
                   30.0 * np.column_stack([np.cos([0.1, 1.2]), np.sin([0.1, 1.2])]), nodes[1:-1]])
    chords = search.Chords(a, ab)
    assert chords.polar is not None
    best, t = chords.nearest(y)
    chords.polar = None
    tree_best, tree_t = chords.nearest(y)
    assert np.array_equal(best, tree_best) and np.array_equal(t, tree_t)
    _, sure = search.Chords(a, ab)._by_angle(y)
    assert sure[:200].all() and not sure[-199:].any()   # on it by angle; its nodes by the tree
    # chords that do not chain by angle (the test above's) are searched by the tree alone
    assert search.Chords(np.array([[0.0, 0.0], [1.0, 1.0], [3.0, 0.0]]),
                          np.array([[1.0, 0.0], [1.0, 0.0], [0.0, 1.0]])).polar is None
