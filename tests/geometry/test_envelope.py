"""Gear 1 branches: law of gearing, exact tangent/speed and curvature."""

import numpy as np
import pytest

from fegear.geometry.envelope import FAR, NEAR
from fegear.geometry.gear1 import generating_branches
from fegear.geometry.parameters import PairParameters

OTHER = PairParameters(m=1.5, z2=31, z1=29, h1=0.25, f1=0.1)


@pytest.mark.parametrize("case", ["nominal", "baseline", "other"])
def test_law_of_gearing(case, request):
    """At 1000+ sampled contact points the common normal passes through the pitch point."""
    p = OTHER if case == "other" else request.getfixturevalue(case)
    for b in generating_branches(p):
        xi = np.linspace(-np.pi / p.z2, np.pi / p.z2, 1201)[1:-1]
        e = b.evaluate(xi)
        # contact point and gear-1 normal in the fixed frame (gear 1 turned by α = kβ about O1)
        alpha = p.ratio * e.beta
        c, s = np.cos(alpha), np.sin(alpha)
        x = np.stack([c * e.q[:, 0] - s * e.q[:, 1], s * e.q[:, 0] + c * e.q[:, 1] + b.a], -1)
        n = np.stack([c * e.normal[:, 0] - s * e.normal[:, 1],
                      s * e.normal[:, 0] + c * e.normal[:, 1]], -1)
        pitch = np.array([0.0, b.r_instant])
        d = pitch - x
        miss = np.abs(d[:, 0] * n[:, 1] - d[:, 1] * n[:, 0])  # distance of N from the normal
        assert miss.max() < 1e-9
        # and the gear-1 point is on gear 2 (the tool) turned by β
        tool = b.tool.point(xi)
        cb, sb = np.cos(e.beta), np.sin(e.beta)
        y = np.stack([cb * tool[:, 0] - sb * tool[:, 1], sb * tool[:, 0] + cb * tool[:, 1]], -1)
        assert np.abs(y - x).max() < 1e-10


@pytest.mark.parametrize("side", [NEAR, FAR])
def test_tangent_speed_and_curvature_are_exact(side, baseline):
    p = baseline
    b = [br for br in generating_branches(p) if br.side == side][0]
    xi = np.linspace(-0.9 * np.pi / p.z2, 0.9 * np.pi / p.z2, 37)
    h = 1e-6
    e, ep, em = b.evaluate(xi), b.evaluate(xi + h), b.evaluate(xi - h)
    dq = (ep.q - em.q) / (2 * h)
    assert np.abs(dq - e.speed[:, None] * e.tangent).max() < 1e-7 * np.abs(dq).max()
    ddq = (ep.q - 2 * e.q + em.q) / h**2
    kap = (dq[:, 0] * ddq[:, 1] - dq[:, 1] * ddq[:, 0]) / np.hypot(*dq.T) ** 3
    ok = np.abs(e.speed) > 1.0  # away from cusps, where curvature is unbounded
    assert np.abs(kap * np.sign(e.speed) - e.kappa)[ok].max() < 1e-3 * np.abs(e.kappa[ok]).max()
    # outward normal points away from gear 1's centre on average (material inside)
    assert np.mean(np.einsum("ij,ij->i", e.normal, e.q)) > 0


def test_near_branch_reaches_45_2_alone():
    """docs/model.md, "Gear 1": the near branch alone reaches 45.2 mm; the far branch trims it."""
    b = generating_branches(PairParameters(tip_clearance=0.0))[0]
    xi = np.linspace(-np.pi / 45, np.pi / 45, 4001)
    assert b.evaluate(xi).radius.max() == pytest.approx(45.2, abs=1e-9)
