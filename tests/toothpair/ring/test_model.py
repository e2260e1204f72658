"""The ring model (:mod:`fegear.toothpair.ring.model`): the templates tile each gear and the
rings close, a thin relief shares the unmodified pair's templates, jiggled templates move no
headline stress by 2 %, and a solution pickles with its model as a reference."""

import math
from dataclasses import replace

import numpy as np
import pytest
from converged import assert_converged
from skfem import Basis, ElementTriP2, Functional

import fegear.toothpair.ring.model as ring_model
from fegear.fe.mesh import jiggle, mesh_bodies
from fegear.planar import rotate
from fegear.toothpair import solve_pair
from fegear.toothpair.case import HEADLINE
from fegear.toothpair.ring import build_ring


def _area(side):
    m = side.body.mesh
    return float(Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(Basis(m, ElementTriP2())))


def test_templates_tile_each_gear_exactly(model):
    """z1 (z2) copies of a template cover gear 1 (gear 2): the template's area is one pitch of
    the area between the exact rounded profile and the bore (rim), to the mesh's accuracy."""
    p = model.case.params
    shape = model.shape
    g1, g2 = model.gears
    phi = np.linspace(shape.tooth_center, shape.tooth_center + shape.pitch, 20001)
    r1 = shape.radius(phi)
    bore = float(np.min(np.linalg.norm(g1.body.mesh.doflocs, axis=0)))
    expected1 = 0.5 * np.trapezoid(r1 ** 2, phi) - 0.5 * bore ** 2 * shape.pitch
    assert _area(g1) == pytest.approx(expected1, rel=1e-6)
    theta = np.linspace(0.0, 2 * math.pi / p.z2, 20001)
    r2 = model.curve2.radius_at_angle(theta)
    rim = float(np.max(np.linalg.norm(g2.body.mesh.doflocs, axis=0)))
    expected2 = 0.5 * rim ** 2 * 2 * math.pi / p.z2 - 0.5 * np.trapezoid(r2 ** 2, theta)
    assert _area(g2) == pytest.approx(expected2, rel=1e-6)


def test_cut_faces_match_and_the_rings_close(model):
    p = model.case.params
    for side, z in zip(model.gears, (p.z1, p.z2)):
        body = side.body
        x = body.mesh.doflocs.T
        a, b = body.face_a[0::2] // 2, body.face_b[0::2] // 2
        assert np.abs(rotate(x[a], side.pitch) - x[b]).max() < 1e-9
        assert side.count == z and side.pitch * z == pytest.approx(2 * math.pi)


def test_a_thin_relief_and_tip_trim_share_the_templates_and_change_nothing_they_would_mesh(
        monkeypatch, baseline_200):
    """A 4 µm relief and a 4 µm deeper tip trim are a tenth of `coarse`'s 100 µm flank
    elements or less: their ring model shares the unmodified pair's templates (meshes, factors,
    responses), while 20 µm of relief gets its own, and so does a tip trimmed less than the
    default (the templates would not hold all of it). The shared templates give the headline
    stresses and the load shares of the relieved pair meshed as it is within 0.2 %."""
    base = replace(baseline_200.case, quality="coarse")
    params = replace(base.params, relief=4.0, relief_extent=0.5, tip_clearance=0.020)
    thin = replace(base, params=params)
    thick = replace(base, params=replace(params, relief=20.0))
    assert ring_model.meshed_params(thin) == base.params
    assert ring_model.meshed_params(thick) == replace(params, relief=20.0, tip_clearance=None)
    # a tip clearance below the default leaves more tip than the templates hold: meshed as is
    proud = replace(base, params=replace(base.params, tip_clearance=0.014))
    assert ring_model.meshed_params(proud) == proud.params
    kept = ring_model.ring_model(base)
    shared = ring_model.ring_model(thin)
    assert shared.gears is kept.gears and shared.profile is not kept.profile
    assert ring_model.ring_model(thick).gears is not kept.gears
    sol = solve_pair(thin, model=shared)
    monkeypatch.setattr(ring_model, "THIN", 0.0)
    own = build_ring(thin)
    assert own.gears is not kept.gears
    alone = solve_pair(thin, model=own)
    assert_converged(sol)
    for key, value in alone.headline().items():
        assert sol.headline()[key] == pytest.approx(value, rel=2e-3), key
    shares = {t.tooth: t.load_share for t in alone.teeth}
    for t in sol.teeth:
        assert t.load_share == pytest.approx(shares.get(t.tooth, 0.0), abs=2e-3)


@pytest.mark.slow  # 11 s: the default suite stays under 5 min
def test_jiggled_templates_move_headline_stresses_by_less_than_2pct(monkeypatch, baseline_200):
    case = baseline_200.case
    for seed in (1, 2):
        def jiggled(geometries, seed=seed):
            return tuple(jiggle(b, 0.1, seed + 10 * k)
                         for k, b in enumerate(mesh_bodies(geometries)))
        monkeypatch.setattr(ring_model, "mesh_bodies", jiggled)
        sol = solve_pair(case, model=build_ring(case))
        assert_converged(sol)
        assert sol.headline() != baseline_200.headline()  # the meshes did move
        for key in HEADLINE:
            assert sol.headline()[key] == pytest.approx(baseline_200.headline()[key],
                                                        rel=0.02), key


def test_a_copy_of_a_model_is_another_reference(baseline_200):
    # a model changed by dataclasses.replace (another matching depth, say) is a model of its
    # own: when it ends, the original still pickles as its reference
    import gc
    import pickle
    from dataclasses import replace

    model = baseline_200.detail.model
    copy = replace(model, level=replace(model.level, depth=3.0))
    assert copy.token != model.token
    assert pickle.loads(pickle.dumps(copy)) is copy
    del copy
    gc.collect()
    assert pickle.loads(pickle.dumps(model)) is model


def test_a_solution_pickles_with_its_model_as_a_reference(baseline_200):
    # a model is too big to copy: a solution crosses from a forked copy with a reference to
    # the model both processes hold, and one with no such model here is told so
    import pickle

    from fegear.toothpair.ring.model import RingModel

    data = pickle.dumps(baseline_200)
    assert len(data) < 20e6
    back = pickle.loads(data)
    assert back.detail.model is baseline_200.detail.model
    assert back.headline() == baseline_200.headline()
    model = baseline_200.detail.model
    foreign = pickle.dumps(RingModel(model.case, model.profile, model.shape, model.samples,
                                     model.gears, model.level))
    import gc

    gc.collect()
    with pytest.raises(LookupError, match="reference to a model"):
        pickle.loads(foreign)
