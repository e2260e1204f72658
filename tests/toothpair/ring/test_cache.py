"""The model cache (:mod:`fegear.toothpair.ring.cache`): a model read back solves
exactly as the one built, without meshing anything; an edit to the code, an unreadable entry
or an unwritable folder builds it again; the cap drops the least recently used entries."""

import logging
import os
import pickle
from dataclasses import replace

import numpy as np
import pytest

from fegear.geometry import PairParameters
from fegear.toothpair import SolveCase, cycle_positions, solve_positions
from fegear.toothpair.ring import cache
from fegear.toothpair.ring.model import KEPT

CASE = SolveCase(PairParameters(m=2, z2=25, z1=24, shift=0.016, rotation=0.002), torque=20.0,
                 quality="coarse")
BETAS = cycle_positions(0.0, 3, CASE.params.z2)


@pytest.fixture
def cache_on(tmp_path, monkeypatch):
    """The cache on, in a folder of the test's own, with no model kept in memory."""
    monkeypatch.setenv(cache.ENV_DIR, str(tmp_path / "cache"))
    monkeypatch.setenv(cache.ENV, "on")
    KEPT.clear()
    yield tmp_path / "cache"
    KEPT.clear()


def _numbers(sols):
    return np.array([[*s.headline().values(), s.rotation, s.tangent_stiffness]
                     for s in sols])


def _no_meshing(monkeypatch):
    def refuse(bodies):
        raise AssertionError(f"meshed {[b.name for b in bodies]}")
    monkeypatch.setattr("fegear.toothpair.ring.model.mesh_bodies", refuse)
    monkeypatch.setattr("fegear.fe.submodel.mesh_bodies", refuse)


def test_a_model_read_back_solves_as_the_one_built_without_meshing(cache_on, monkeypatch):
    built = solve_positions(CASE, BETAS, submodels="all")
    assert built[0].timings_s["mesh"] > 0 and built[0].timings_s["cache"] == 0
    (entry,) = cache.entries()
    KEPT.clear()
    with monkeypatch.context() as m:
        _no_meshing(m)
        read = solve_positions(CASE, BETAS, submodels="all")
    assert read[0].timings_s["cache"] > 0 and read[0].timings_s["mesh"] == 0
    assert not read[0].von_mises_estimated
    # the same factors of the same matrices: the same numbers to rounding
    np.testing.assert_allclose(_numbers(read), _numbers(built), rtol=1e-10)
    assert [t.load_N for t in read[0].teeth] == pytest.approx(
        [t.load_N for t in built[0].teeth], rel=1e-10)


def test_more_work_on_a_read_model_is_kept_again(cache_on):
    solve_positions(CASE, BETAS[:1])
    (first,) = cache.entries()
    KEPT.clear()
    heavier = solve_positions(replace(CASE, torque=200.0), BETAS)
    (again,) = cache.entries()
    assert again[0] == first[0] and again[1] > first[1]   # more responses formed
    KEPT.clear()
    fresh = solve_positions(replace(CASE, torque=200.0), BETAS)
    np.testing.assert_allclose(_numbers(fresh), _numbers(heavier), rtol=1e-10)


def test_an_edit_to_the_code_reads_no_older_entry(cache_on, monkeypatch):
    solve_positions(CASE, BETAS[:1])
    KEPT.clear()
    monkeypatch.setattr("fegear.provenance.code_version", lambda: "another version")
    again = solve_positions(CASE, BETAS[:1])
    assert again[0].timings_s["mesh"] > 0
    assert len(cache.entries()) == 2


def test_an_unreadable_entry_is_dropped_and_the_model_built_again(cache_on, caplog):
    built = solve_positions(CASE, BETAS[:1])
    (entry,) = cache.entries()
    entry[0].write_bytes(entry[0].read_bytes()[:1000])    # cut short, as by a full file system
    KEPT.clear()
    with caplog.at_level(logging.WARNING):
        again = solve_positions(CASE, BETAS[:1])
    assert "unreadable" in caplog.text and again[0].timings_s["mesh"] > 0
    np.testing.assert_allclose(_numbers(again), _numbers(built), rtol=1e-10)
    (entry,) = cache.entries()
    with open(entry[0], "rb") as f:
        assert pickle.load(f)["format"] == cache.FORMAT


def test_an_unwritable_cache_warns_and_the_solve_goes_on(tmp_path, monkeypatch, caplog):
    blocker = tmp_path / "a file"
    blocker.write_text("")
    monkeypatch.setenv(cache.ENV_DIR, str(blocker / "cache"))
    monkeypatch.setenv(cache.ENV, "on")
    KEPT.clear()
    with caplog.at_level(logging.WARNING):
        sol = solve_positions(CASE, BETAS[:1])[0]
    KEPT.clear()
    assert "could not keep" in caplog.text
    assert sol.root_stress[0] > 0 and not list(tmp_path.glob("**/*.tmp"))


def test_the_cap_drops_the_least_recently_used_entries(cache_on, monkeypatch):
    monkeypatch.setenv(cache.ENV_CAP, "0.0035")   # 3.5 MB: three 1 MB entries fit, four not
    block = {"x": np.zeros(125_000)}             # 1 MB
    for k, name in enumerate("abc"):
        cache.keep(name, block)
        os.utime(cache.entry(name), (1000.0 + k, 1000.0 + k))   # a, b, c from old to new
    assert cache.load("a") is not None                           # a used: now the newest
    cache.keep("d", block)
    kept = {path for path, _, _ in cache.entries()}
    assert kept == {cache.entry(n) for n in "acd"}               # b, the least recent, went
    n, size = cache.clear()
    assert n == 3 and size == pytest.approx(3.0e6, rel=0.01)
    assert cache.entries() == []


def test_a_bad_cap_is_refused_by_name(monkeypatch):
    from fegear.errors import FegearError

    for text in ("-1", "0", "two", "nan", "inf"):
        monkeypatch.setenv(cache.ENV_CAP, text)
        with pytest.raises(FegearError, match=cache.ENV_CAP):
            cache.cap_bytes()


def test_the_switch_follows_option_then_environment_then_the_command(monkeypatch):
    from argparse import Namespace

    from fegear.cli.cache import apply_switch

    monkeypatch.delenv(cache.ENV, raising=False)
    for given, env, default, on in ((None, None, False, False), (None, None, True, True),
                                    (None, "on", False, True), (None, "off", True, False),
                                    (True, "off", False, True), (False, "on", True, False)):
        if env is None:
            monkeypatch.delenv(cache.ENV, raising=False)
        else:
            monkeypatch.setenv(cache.ENV, env)
        apply_switch(Namespace(cache=given), default)
        assert cache.enabled() is on
    with cache.model_cache(False):
        assert not cache.enabled()
    assert cache.enabled() is on
    folder = cache.directory()
    with cache.model_cache(True, folder / "elsewhere"):
        assert cache.enabled() and cache.directory() == folder / "elsewhere"
    assert cache.enabled() is on and cache.directory() == folder


def test_a_submodel_meshes_the_same_whatever_was_meshed_before_it(baseline, baseline_profile):
    """A kept submodel stands for every later one of its key, so its mesh must not depend on
    what else was meshed in the same call. The baseline's two peaks at `standard`: meshed in
    one gmsh session after gear 2's, gear 1's submodel came out with 1696 nodes instead of
    1692."""
    from fegear.fe import (
        ElasticMaterial,
        StarCurve,
        SubmodelProblem,
        prepare_submodels,
        submodel_meshes,
    )
    from fegear.geometry import RoundedProfile, gear2_curve

    shape = RoundedProfile(baseline_profile, 0.25)
    curve2 = gear2_curve(baseline)

    def point2(theta):
        r = curve2.radius_at_angle(theta)
        return np.column_stack([r * np.cos(theta), r * np.sin(theta)])

    def unused(x):
        return np.zeros(len(x))

    size, focus = 0.0008211879055212056, 0.03716272234383503
    one = SubmodelProblem(StarCurve(shape.point, inside=True), 0.0673121245250514,
                          0.052556025953357156, size, focus, unused, unused, key="one")
    two = SubmodelProblem(StarCurve(point2, inside=False, foot=lambda y: curve2.closest(y)[0]),
                          0.1011093291354564, 0.29730177875068026, size, focus, unused, unused,
                          key="two")
    kept_alone, kept_after = {}, {}
    prepare_submodels([one], ElasticMaterial(), kept_alone)          # its disk meshed alone …
    prepare_submodels([two, one], ElasticMaterial(), kept_after)     # … and after gear 2's, at once
    alone, after = (submodel_meshes(kept)["one"].mesh.mesh for kept in (kept_alone, kept_after))
    assert np.array_equal(alone.p, after.p)
    assert np.array_equal(alone.t, after.t)
