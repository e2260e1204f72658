"""The contact submodels of a mesh cycle, where its stresses peak.

A position's von Mises stress at its contacts is first the templates' surface estimate
(:func:`~.stresses.ring_stresses`); a fine submodel at each contact peak
(:func:`~.stresses.with_submodels`) resolves it. Over a cycle only the positions that decide
its largest von Mises stress need them (everything else a position reports, the other headline
stresses included, does not depend on submodels): where the largest gear-1 root stress is (the
position the job pictures and estimates), and wherever the estimate comes within
:data:`PEAK_MARGIN` of the largest von Mises stress solved, until no other does. A single
position is its own peak. A position whose stresses were read without their fields (a
revolution's on a kept contact: :attr:`~.solver.SolverModes.read_kept`) gets them, its
equilibrium residuals and its teeth's half-plane references where it gets its submodels
(:func:`whole`).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import replace

from ...timing import clocked, timed
from ..case import PairSolution
from .results import equilibrium_residuals, solved_rigid_gap, with_references
from .stresses import ring_stresses, with_submodels

PEAK_MARGIN = 0.02   # a cycle's position gets its submodels where its von Mises estimate is
                     # within this fraction of the cycle's largest von Mises stress (the
                     # estimate is within 0.6 % of the submodel at `standard`, 1 % at
                     # `coarse`, on the baseline's cycles, edge and relieved alike:
                     # docs/model.md, "Submodels over a cycle")


def with_peak_submodels(sols: tuple[PairSolution, ...]) -> tuple[PairSolution, ...]:
    """``sols`` with the submodels of the positions that decide the cycle's von Mises stress
    (module docstring); the others keep the surface estimate (``von_mises_estimated``). The
    first round takes, besides the pictured position, every position whose estimate is within
    the margin of the largest estimate: the submodels lift an estimate by a few tenths of a per
    cent, so these are mostly the positions a later round would add."""
    if not sols:
        return sols
    out = list(sols)
    want = _near_peak(sols, PEAK_MARGIN)
    done: set[int] = set()
    while want:
        for i in sorted(want):
            out[i] = with_submodels_of(out[i])
        done |= want
        solved = [s.von_mises_max for s in out if not s.von_mises_estimated]
        if not solved:   # no peak a submodel could take (no surface stress anywhere)
            break
        want = {i for i, s in enumerate(out) if i not in done
                and s.von_mises_max >= (1.0 - PEAK_MARGIN) * max(solved)}
    return tuple(out)


def peak_candidates(sols) -> set[int]:
    """The positions of ``sols`` (a chain's, of a cycle) that :func:`with_peak_submodels` can
    take wherever the other chains' positions peak: the largest gear-1 root stress among them
    and every one whose von Mises estimate comes within twice :data:`PEAK_MARGIN` of their
    largest (the cycle's largest is at least theirs, and a submodel moves an estimate by a
    few tenths of a per cent)."""
    return _near_peak(sols, 2.0 * PEAK_MARGIN) if sols else set()


def pictured(sols) -> int:
    """The index of the position pictured among ``sols``: the largest gear-1 root stress."""
    return max(range(len(sols)), key=lambda i: sols[i].root_stress[0])


def _near_peak(sols, margin: float) -> set[int]:
    """The pictured position of ``sols`` and every one whose von Mises estimate is within
    ``margin`` (a fraction) of their largest."""
    estimated = max(s.von_mises_max for s in sols)
    return {pictured(sols)} | {i for i, s in enumerate(sols)
                               if s.von_mises_max >= (1.0 - margin) * estimated}


def with_submodels_of(sol: PairSolution) -> PairSolution:
    """``sol`` with its contact submodels solved (their time in its "stresses" stage)."""
    sol = whole(sol)
    d = sol.detail
    with clocked() as clock, timed("stresses"):
        stresses = with_submodels(d.model, d.contact, d.solution.pressure, d.stresses)
    times = Counter(sol.timings_s)
    times.update(clock.stages)
    return replace(sol, von_mises_max=stresses.von_mises_max, timings_s=dict(times),
                   detail=replace(d, stresses=stresses),
                   von_mises_estimated=not stresses.submodels)


def whole(sol: PairSolution) -> PairSolution:
    """``sol`` with its loaded sectors' fields, its equilibrium residuals and its teeth's
    half-plane references, where it was read without them
    (:attr:`~.solver.SolverModes.read_kept`); else ``sol``. Its root stresses stay (the
    fields' root zones are the ones read, to rounding), its von Mises maximum is the fields'
    (the same where it lies at a contact or in a root zone)."""
    d = sol.detail
    if any(d.stresses.fields):
        return sol
    with timed("stresses"):
        stresses = ring_stresses(d.model, d.contact, d.solution.pressure, submodels=False)
        residuals = tuple(equilibrium_residuals(d.model, d.contact, d.solution, stresses))
        d = replace(d, stresses=stresses)
        teeth = with_references(d, sol.teeth, solved_rigid_gap(d))
    return replace(sol, teeth=teeth, von_mises_max=stresses.von_mises_max, detail=d,
                   checks=replace(sol.checks, residuals=residuals))
