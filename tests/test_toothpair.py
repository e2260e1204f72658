"""Tooth-pair scene and solve (issue 4, in progress)."""

import numpy as np
import pytest

from fegear.params import PairParameters
from fegear.scene import _profile_segments
from fegear.toothpair import SolveCase, solve_pair


def circle(phi):
    return 10.0 * np.column_stack([np.cos(phi), np.sin(phi)])


def test_profile_segments_are_contiguous_with_windows_over_roots():
    windows = [("w1", 0.30, 0.10), ("w2", 0.45, 0.10)]       # overlapping windows
    roots = [("r1", 0.20, 0.05), ("r2", 0.50, 0.02), ("r3", 0.40, 0.3)]  # r3 around all
    segs, root_names = _profile_segments("p", circle, None, 0.0, 1.0, windows, roots)
    for s0, s1 in zip(segs, segs[1:]):
        assert np.allclose(s0.points[-1], s1.points[0], atol=1e-12)
    assert np.allclose(segs[0].points[0], circle(np.array([0.0]))[0])
    assert np.allclose(segs[-1].points[-1], circle(np.array([1.0]))[0])
    names = [s.name for s in segs]
    assert names.count("w1") == 1 and names.count("w2") == 1
    w1 = segs[names.index("w1")].points
    w2 = segs[names.index("w2")].points
    ang = lambda p: np.arctan2(p[:, 1], p[:, 0])  # noqa: E731
    assert ang(w1)[-1] == pytest.approx(0.375) and ang(w2)[0] == pytest.approx(0.375)
    assert "r2" not in root_names  # wholly inside window w2
    assert names.count("r3") == 2  # split by the windows and r1, one name for both pieces


@pytest.mark.slow
def test_baseline_pair_balances_torque_and_shares():
    p = PairParameters(shift=0.016, rotation=0.002)
    r = solve_pair(SolveCase(p, torque=200.0, quality="fast"))
    assert r.contact.balance_error < 1e-6
    assert sum(t.load_share for t in r.teeth) == pytest.approx(1.0, abs=1e-3)
    assert max(r.contact.residuals) < 1e-9
    assert r.teeth_in_contact >= 2
    assert r.rotation > r.first_touch > 0


def test_profile_segments_with_many_zones_stay_contiguous():
    # a sector of 20 tooth spaces: every root is cut against every piece placed before it
    roots = [(f"r{k}", 0.05 * k + 0.025, 0.01) for k in range(20)]
    windows = [(f"w{k}", 0.05 * k + 0.04, 0.012) for k in range(0, 20, 2)]
    segs, root_names = _profile_segments("p", circle, None, 0.0, 1.0, windows, roots)
    for s0, s1 in zip(segs, segs[1:]):
        assert np.allclose(s0.points[-1], s1.points[0], atol=1e-12)
    assert len(root_names) == 20
