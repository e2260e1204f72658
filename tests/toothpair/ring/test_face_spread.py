"""A_fe's blocks spread across the face (fegear.toothpair.ring.face_spread): the low-rank form
of the spreads between teeth gives what each block with its own spread gives."""

import numpy as np
import pytest

from fegear.toothpair.ring.face import (
    exponential_kernel,
    face_coupling,
    product_coupling,
    tilted_across,
)
from fegear.toothpair.ring.face_contact import grid_spans
from fegear.toothpair.ring.face_spread import FaceSpread

#: five grids: gear 1's teeth 43, 0, 1, 2 and 4 of 44 (0 and 43 adjacent across the count)
TEETH = [43, 0, 1, 2, 4]
SIZES = [3, 4, 0, 5, 2]


def _dense(coupling, far, sizes, teeth, z1, p):
    """Σ_j F_ij P_j X_ijᵀ block by block, X_ij the spread between the teeth of grids i and j."""
    cuts = np.concatenate([[0], np.cumsum(sizes)])
    u = np.zeros_like(p)
    for i in range(len(sizes)):
        for j in range(len(sizes)):
            gi, gj = slice(cuts[i], cuts[i + 1]), slice(cuts[j], cuts[j + 1])
            d = min((teeth[i] - teeth[j]) % z1, (teeth[j] - teeth[i]) % z1)
            u[gi] += far[gi, gj] @ p[gj] @ coupling.between(d).T
    return u


@pytest.mark.parametrize("coupling", [
    product_coupling(9, 5.0, 2.0, 0.2),
    tilted_across(face_coupling(7, 5.0, exponential_kernel(1.5)), 0.3),
    face_coupling(5, 5.0, exponential_kernel(1.5))])        # one spread for every block
def test_the_spreads_low_rank_form_is_each_blocks_own_spread(coupling):
    rng = np.random.default_rng(3)
    n, sections = sum(SIZES), len(coupling.share)
    far = rng.standard_normal((n, n))
    p = rng.standard_normal((n, sections))
    spread = FaceSpread(coupling, TEETH, 44)
    cuts = np.concatenate([[0], np.cumsum(SIZES)])
    spans = [slice(lo, hi) if hi > lo else None for lo, hi in zip(cuts[:-1], cuts[1:])]
    reference = _dense(coupling, far, SIZES, TEETH, 44, p)
    np.testing.assert_allclose(spread.on_points(far, spans)(p), reference, atol=1e-12)
    # the approach at every point from the loaded ones' rows of A_feᵀ: grid 3 unloaded
    loaded = np.concatenate([np.arange(lo, hi) for k, (lo, hi) in
                             enumerate(zip(cuts[:-1], cuts[1:])) if k != 3])
    sources = grid_spans(loaded, cuts)
    assert sources[3] is None
    targets = [slice(lo, hi) for lo, hi in zip(cuts[:-1], cuts[1:])]
    p_loaded = p[loaded]
    at = np.zeros_like(p)
    at[loaded] = p_loaded
    got = spread.approach(p_loaded, sources, far.T[loaded], targets)
    np.testing.assert_allclose(got.T, _dense(coupling, far, SIZES, TEETH, 44, at), atol=1e-12)


def test_the_products_spreads_between_teeth_are_two_shapes():
    # an even load and a tilt, whatever the distance: rank 2 on both sides
    spread = FaceSpread(product_coupling(9, 5.0, 2.0, 0.2), TEETH, 44)
    assert spread.left.shape == spread.right.shape == (9, 2)
    assert not spread.single and np.all(spread.small[np.arange(5), np.arange(5)] == 0)
