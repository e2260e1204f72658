"""A position's deviation sets solved on its kept contact and read together
(:mod:`fegear.toothpair.ring.kept_batch`): each set's record is the one it has solved alone,
whether the sets share their contact's numbering or are turned by whole pitches apart."""

import math
from dataclasses import replace

import numpy as np
import pytest

from fegear.geometry import Deviations, Runout, ToothDeviation, gear1_profile, moved_clearances
from fegear.running import SERIAL
from fegear.toothpair.positions import Clearances, positions_of
from fegear.toothpair.ring import RingSolver, SolverModes
from fegear.toothpair.ring.kept_batch import KeptBatch

#: deviation sets of a few µm on the teeth in mesh at β = 0, each kind on its own and mixed
SETS = (Deviations(gear1={10: ToothDeviation(pitch=3.0)}),
        Deviations(gear1={11: ToothDeviation(pitch=-2.0, slope=2.0)}),
        Deviations(centre_distance=4.0),
        Deviations(gear1={9: ToothDeviation(form=2.0)}, runout1=Runout(6.0, 30.0),
                   runout2=Runout(5.0, 120.0)))


@pytest.fixture(scope="module")
def kept(kept_at_zero):
    return kept_at_zero(SETS)


def _jobs(case, pitches: int):
    """Each set at β = 0 and ``pitches`` gear-2 pitches on, with its clearance state."""
    beta = pitches * 2 * math.pi / case.params.z2
    state = Clearances(case, gear1_profile(case.params), (beta,)).get()[0][1]
    return [(replace(case, beta=beta, deviations=d), moved_clearances(d, case.params,
                                                                      [state])[0])
            for d in SETS]


def test_sets_read_together_are_each_one_solved_alone(kept):
    solver, case = kept
    jobs = _jobs(case, 0) + _jobs(case, 3)    # two numberings of the kept contact
    alone = [solver.on_kept(one, state, brief=True) for one, state in jobs]
    batch = KeptBatch(solver)
    assert all(batch.add(one, state) for one, state in jobs)
    together = batch.finish()
    assert batch.finish() == []   # none held after
    for a, b in zip(alone, together, strict=True):
        assert b.case is not None and b.case.deviations == a.case.deviations
        for key, value in a.headline().items():
            assert b.headline()[key] == pytest.approx(value, rel=1e-9, nan_ok=True), key
        np.testing.assert_allclose([t.root1_MPa for t in b.teeth],
                                   [t.root1_MPa for t in a.teeth], rtol=1e-9)
    # the sets differ: each reads its own pressures, not its neighbour's
    roots = [s.headline()["root_stress_gear1_MPa"] for s in together[:len(SETS)]]
    assert len({round(r, 6) for r in roots}) == len(SETS)


def test_a_solver_that_reads_only_the_contact_reads_no_stresses_together(baseline_ring):
    # the tip-relief search's trials: the contact alone, whether finished alone or together
    case = replace(baseline_ring.case, torque=200.0)
    solver = RingSolver(baseline_ring, SolverModes(keep_phases=True, contact_only=True))
    positions_of(solver, False)(case, (0.0,), SERIAL)
    jobs = _jobs(case, 0)[:3]
    alone = [solver.on_kept(one, state, brief=True) for one, state in jobs]
    batch = KeptBatch(solver)
    assert all(batch.add(one, state) for one, state in jobs)
    for a, b in zip(alone, batch.finish(), strict=True):
        assert math.isnan(b.root_stress[0]) and math.isnan(a.root_stress[0])
        assert b.contact_pressure == pytest.approx(a.contact_pressure, rel=1e-12)
