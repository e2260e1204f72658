"""A position across the face read as results (:mod:`fegear.toothpair.ring.face_results`): an
even face's sections are the 2D pair's brief reading, headline by headline; a misaligned face
names its worst section at the end that closes, with K_Hβ the largest line load over the
tooth's mean."""

from dataclasses import replace

import numpy as np
import pytest

from fegear.fe import blas_threads
from fegear.geometry import gear1_profile
from fegear.running import SERIAL
from fegear.toothpair.face import Face
from fegear.toothpair.positions import Clearances, positions_of
from fegear.toothpair.ring.face import exponential_kernel, face_coupling
from fegear.toothpair.ring.face_results import face_sections
from fegear.toothpair.ring.solver import RingSolver, SolverModes

COUPLING = face_coupling(5, 5.0, exponential_kernel(1.5))


@pytest.fixture(scope="module")
def kept(baseline_ring):
    case = replace(baseline_ring.case, torque=200.0)
    solver = RingSolver(baseline_ring, SolverModes(keep_phases=True))
    positions_of(solver, False)(case, (0.0,), SERIAL)
    state = Clearances(case, gear1_profile(case.params), (0.0,)).get()[0][1]
    return solver, case, state


def _sections(kept, face):
    solver, case, state = kept
    with blas_threads():
        return face_sections(solver.model, solver.phases, case, state, face, COUPLING)


def test_an_even_face_reads_as_the_2d_pair_in_every_section(kept):
    solver, case, state = kept
    alone = solver.on_kept(case, state, brief=True).headline()
    even = _sections(kept, Face(5))
    assert even.load_factor == pytest.approx(1.0, abs=1e-9)
    for section in even.sections:
        got = section.headline()
        for key, value in alone.items():
            assert got[key] == pytest.approx(value, rel=1e-9, nan_ok=True), key


def test_a_misaligned_face_is_worst_at_the_end_it_closes(kept):
    solver, case, state = kept
    alone = solver.on_kept(case, state, brief=True).headline()
    tilted = _sections(kept, Face(5, misalignment=8.0))
    key = "root_stress_gear1_MPa"
    worst = tilted.worst_headlines()[key][0]
    assert worst == 4
    assert tilted.sections[worst].headline()[key] > 1.05 * alone[key]
    assert tilted.sections[0].headline()[key] < alone[key]
    mean = tilted.line_loads @ COUPLING.share
    most = int(np.argmax(mean))
    assert tilted.load_factor >= tilted.line_loads[most].max() / mean[most] > 1.1
