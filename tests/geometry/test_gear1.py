"""Gear 1 as exact lower envelope, checked against an independent brute-force swept body."""

import numpy as np
import pytest
from swept_reference import sweep_min_distance

from fegear.geometry.parameters import PairParameters

UM = 1e-3  # mm
TOL = 0.05 * UM  # the exactness bound, 0.05 µm


def test_exact_conjugate_touches_everywhere_without_penetration(conjugate, conjugate_profile):
    """Every point of gear 1 touches the swept gear 2 (gap < 0.05 µm), none penetrates."""
    p = conjugate
    q = conjugate_profile.period_polyline(4e-4)
    d = sweep_min_distance(q, p.e, p.z1, p.r0, p.e1, p.e2, p.z2, 0.0, steps_per_pitch=60)
    assert d.min() > -TOL
    assert d.max() < TOL


def test_modified_gear1_against_its_generating_tool_and_assembled(baseline, baseline_profile):
    p = baseline
    g = baseline_profile
    q = g.period_polyline(4e-4)
    # against the Δ2 tool at the generating centre distance e + Δ1: no penetration, and the
    # working flanks (near-side pieces) touch
    d_gen = sweep_min_distance(q, p.e + p.shift, p.z1, p.r0, p.e1, p.e2, p.z2, p.rotation,
                               steps_per_pitch=60)
    assert d_gen.min() > -TOL
    phi = np.arctan2(q[:, 1], q[:, 0])
    near = g.evaluate(phi).xi  # parameter of the owning piece
    owner = _owner_branch(g, phi)
    assert np.all(d_gen[owner == 0] < TOL)
    # tip pieces come from the relief branch and clear the tool by shift + tip clearance
    assert d_gen[owner == 2].max() == pytest.approx(p.shift + p.radial_tip_clearance, abs=1e-6)
    # assembled at e with the nominal gear 2: free of interference, clearance everywhere
    d_asm = sweep_min_distance(q, p.e, p.z1, p.r0, p.e1, p.e2, p.z2, 0.0, steps_per_pitch=60)
    assert d_asm.min() > 1 * UM
    assert np.all(np.isfinite(near))


def _owner_branch(g, phi):
    rel = np.mod(phi - g.phi_space, g.pitch) + g.phi_space
    starts = np.array([pc.phi0 for pc in g.pieces])
    idx = np.clip(np.searchsorted(starts, rel, side="right") - 1, 0, len(g.pieces) - 1)
    return np.array([g.pieces[i].run.branch for i in idx])


def test_tip_and_root_radii_are_exact(conjugate_profile, baseline_profile):
    """Far-side trimming: the tip stops at r0 − 2e1 + e − tip clearance (44.8 mm at baseline)."""
    for g in (conjugate_profile, baseline_profile):
        p = g.params
        tip = g.radius(np.array([g.tooth_center]))[0]
        assert tip == pytest.approx(p.r0 - 2 * p.e1 + p.e - p.radial_tip_clearance, abs=1e-12)
        root = g.radius(np.array([g.phi_space]))[0]
        assert root == pytest.approx(p.r0 - 2 * p.e1 - p.e - p.shift, abs=1e-12)
    assert conjugate_profile.radius(np.array([conjugate_profile.tooth_center]))[0] == \
        pytest.approx(44.8, abs=1e-12)


def test_profile_is_periodic_symmetric_and_continuous(baseline_profile):
    g = baseline_profile
    phi = np.linspace(0, 2 * np.pi, 5001)
    r = g.radius(phi)
    assert np.abs(g.radius(phi + g.pitch) - r).max() < 1e-11
    c = g.tooth_center
    off = np.linspace(0, g.pitch / 2, 400)
    assert np.abs(g.radius(c + off) - g.radius(c - off)).max() < 1e-10
    # continuity across the piece junctions
    for pc in g.pieces:
        assert abs(g.radius(np.array([pc.phi1 - 1e-13]))[0]
                   - g.radius(np.array([pc.phi1 + 1e-13]))[0]) < 1e-9


def test_polyline_points_lie_on_the_exact_profile(baseline_profile):
    g = baseline_profile
    pts = g.polyline(1e-4)
    assert len(pts) % g.params.z1 == 0
    phi = np.arctan2(pts[:, 1], pts[:, 0])
    assert np.abs(np.hypot(*pts.T) - g.radius(phi)).max() < 1e-11
    # counter-clockwise and simple: polar angle strictly increasing
    assert np.all(np.diff(np.unwrap(phi)) > 0)


def test_curvature_radius_on_flank(baseline_profile):
    """Exact curvature radius agrees with the circle through three close exact points."""
    g = baseline_profile
    phi0 = g.phi_space + 0.25 * g.pitch
    h = 1e-5
    pts = g.evaluate(np.array([phi0 - h, phi0, phi0 + h])).q
    a, b, c = pts
    area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    r_circ = np.linalg.norm(a - b) * np.linalg.norm(b - c) * np.linalg.norm(c - a) / (2 * area2)
    assert g.evaluate(np.array([phi0])).curvature_radius[0] == pytest.approx(r_circ, rel=1e-4)


def test_a_degenerate_pair_raises_a_named_error_and_is_refused_before():
    """A random case of a property-based run: a cusp off the working flank (the adaptive
    polyline asked for 22 million points). Built anyway, the library names it; the
    admissibility check refuses it first, naming the rotation the user set."""
    from fegear.errors import GeometryError, ParameterError
    from fegear.geometry.build import build_geometry
    from fegear.geometry.refusal import check_design

    values = {"m": 6.0, "z2": 9, "z1": 8, "h1": 0.5, "f1": 0.0, "rotation": 0.5}
    with pytest.raises(GeometryError, match="cusp"):
        build_geometry(PairParameters(**values), chord_error=1e-3, backlash_positions=4)
    with pytest.raises(ParameterError) as err:
        check_design(values)
    assert err.value.name == "rotation" and "<= rotation <=" in err.value.admissible


def test_a_singular_point_of_the_envelope_is_refused_by_name(monkeypatch, baseline_profile):
    """Where the envelope's speed σ vanishes (a cusp of gear 1's profile, where a piece can
    end) its curvature is unbounded: the sampler refuses the curve with a GeometryError (found
    by the property test: a bare ValueError, NaN curvature, from an admissible draw)."""
    from dataclasses import replace

    from fegear.errors import GeometryError
    from fegear.geometry.envelope import Branch

    evaluate = Branch.evaluate

    def singular_at_the_first_point(self, xi):
        e = evaluate(self, xi)
        speed, kappa = e.speed.copy(), e.kappa.copy()
        speed[0], kappa[0] = 0.0, np.inf
        return replace(e, speed=speed, kappa=kappa)

    assert np.isfinite(baseline_profile.period_polyline(1e-3)).all()
    monkeypatch.setattr(Branch, "evaluate", singular_at_the_first_point)
    with pytest.raises(GeometryError, match="cusp"):
        baseline_profile.period_polyline(1e-3)


def test_brents_root_is_scipys_to_the_bit():
    """fegear's own Brent (``geometry/roots.py``: scipy.optimize costs 0.23 s to import) takes
    scipy's steps: the same root, bit for bit, at the tolerances the geometry asks for."""
    import math

    from scipy.optimize import brentq as scipys

    from fegear.errors import GeometryError
    from fegear.geometry.roots import brentq

    rng = np.random.default_rng(1)
    functions = [lambda x, c=c, d=d: math.sin(c * x) - d for c, d in rng.uniform(0.5, 3, (40, 2))]
    functions += [lambda x, c=c: x ** 3 - c for c in rng.uniform(0.1, 5, 40)]
    functions += [lambda x, c=c: math.exp(x) - c * x - 2 for c in rng.uniform(0.1, 1, 40)]
    compared = 0
    for f in functions:
        for a, b in ((-1.3, 2.1), (0.0, 3.0), (-2.0, 0.7)):
            if f(a) * f(b) >= 0:
                continue
            for xtol, rtol in ((1e-15, 1e-15), (1e-15, 4 * np.finfo(float).eps), (1e-6, 1e-10)):
                assert brentq(f, a, b, xtol=xtol, rtol=rtol) == scipys(f, a, b, xtol=xtol,
                                                                       rtol=rtol)
                compared += 1
    assert compared > 300
    with pytest.raises(GeometryError, match="different signs"):
        brentq(lambda x: x * x + 1.0, -1.0, 1.0)
