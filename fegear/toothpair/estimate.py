"""The discretisation-error estimate: the same case solved at a second mesh level, and
Roache's two-grid convergence index per headline stress, never below the scatter the ring
model's meshes carry (:data:`MESH_SCATTER_PCT`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

from ..quantities import HELD
from .case import HEADLINE, PairSolution, SolveCase
from .inputs import QUALITY
from .pair import solve_pair, solve_positions

GCI_FS = 3.0  # safety factor of the grid convergence index from two mesh levels (Roache)
#: the least error (%) the ring model's estimate gives a headline stress: the scatter between
#: meshes that are equally good. Two levels see the trend of the error with the element size;
#: a stress that also moves by a few tenths of a per cent from one mesh of a level to another
#: (where gmsh happens to put the nodes) can come out nearly the same at both levels, and their
#: difference then says far less than the error. Measured (docs/validation.md, "The error
#: estimate's floor"): six designs, each at `fast`, `standard` and `fine` on five meshes that
#: differ only in gmsh's curve precision, spread (max − min over the mean) up to 0.61 % for the
#: pressures and the von Mises stress and 0.17 % for the root stresses; and the paper study's
#: f1 0.2 case at `fast`, two such meshes, 0.66 % and 0.31 %
MESH_SCATTER_PCT = {"root_stress_gear1_MPa": 0.35, "root_stress_gear2_MPa": 0.35,
                    "contact_pressure_MPa": 0.7, "flank_contact_pressure_MPa": 0.7,
                    "von_mises_max_MPa": 0.7}


def error_estimate(fine: dict[str, float], coarse: dict[str, float],
                   ratio: float = 2.0) -> dict[str, float]:
    """Discretisation error (%) of each headline stress of the finer mesh: Roache's grid
    convergence index for two grids, e ≈ Fs · |s_fine − s_coarse| / (r^p − 1) with the
    two-grid safety factor Fs = 3, the mesh ratio r (element sizes coarse / fine) and the P2
    stress order p = 2; e ≈ |s_fine − s_coarse| for r = 2, 3 |s_fine − s_coarse| for
    r = √2. (Plain Richardson, Fs = 1, understated the sector model's von Mises error at
    ``standard`` 7×: peaks on a contact edge are not yet in the asymptotic range.)"""
    return _gci({k: fine[k] for k in HEADLINE}, coarse, ratio)


def mesh_ratio(coarse: str, fine: str) -> float:
    """Element sizes at quality ``coarse`` over those at ``fine`` in the ring model: its
    templates (their root zones) shrink by about √2 up to ``standard`` and by 2 to ``fine``."""
    from .ring.model import LEVELS  # lazy: heavy: the ring model loads scikit-fem

    return LEVELS[coarse].root / LEVELS[fine].root


def second_quality(quality: str) -> str:
    """The quality the estimate solves again at: the next coarser one (``fast`` for
    ``coarse``: the next finer)."""
    levels = tuple(QUALITY)  # coarsest first
    k = levels.index(quality)
    return levels[k - 1] if k > 0 else levels[1]


def second_level_estimate(sol: PairSolution, ratio: Callable[[str, str], float] = mesh_ratio,
                          second: dict[str, float] | None = None,
                          floor: dict[str, float] | None = None
                          ) -> tuple[dict[str, float], str]:
    """Solve the same case at the :func:`second_quality` and estimate the headline errors
    (%) of ``sol``, each at least its ``floor`` (%; the ring model's mesh scatter,
    :data:`MESH_SCATTER_PCT`, by default). Returns the estimate and the other quality.
    ``ratio``: the mesh ratio between two qualities (:func:`mesh_ratio`); ``second``: the
    headline of that second solve if it is solved already (:func:`second_headline`'s, a task
    of its own)."""
    floor = MESH_SCATTER_PCT if floor is None else floor
    estimate, other = _two_levels(sol, ratio, second)
    return {k: max(v, floor.get(k, 0.0)) for k, v in estimate.items()}, other


def _two_levels(sol: PairSolution, ratio: Callable[[str, str], float],
                second: dict[str, float] | None
                ) -> tuple[dict[str, float], str]:
    """:func:`second_level_estimate` without its floor."""
    other = second_quality(sol.case.quality)
    if second is None:
        second = solve_pair(replace(sol.case, quality=other)).headline()
    own = sol.headline()
    return _level_errors({k: own[k] for k in HEADLINE}, second, sol.case.quality, ratio), other


def _level_errors(own: dict[str, float], second: dict[str, float], quality: str,
                  ratio: Callable[[str, str], float]) -> dict[str, float]:
    """The error (%) of each stress ``own`` at ``quality`` from the same stresses ``second``
    at :func:`second_quality`: the two-grid index where the second level is coarser; at the
    coarsest level, whose second is finer, r² that (rate h²), relative to its own value."""
    levels = tuple(QUALITY)  # coarsest first
    k = levels.index(quality)
    other = second_quality(quality)
    if k > 0:
        return _gci(own, second, ratio(other, levels[k]))
    r = ratio(levels[0], other)
    return {f: r ** 2 * v for f, v in _gci(own, second, r).items()}


#: each loaded tooth's stresses that get an estimate of their own, those held against an
#: allowable: the tooth's field → the headline stress whose mesh scatter floors it
TOOTH_STRESSES = {q.attribute: q.key for q in HELD}


@dataclass(frozen=True)
class SecondSolve:
    """The estimate's second solve: its headline, and each loaded tooth's stresses
    (:data:`TOOTH_STRESSES`) by tooth."""

    headline: dict[str, float]
    teeth: dict[int, dict[str, float]]


def second_headline(case: SolveCase) -> SecondSolve:
    """``case`` solved at its :func:`second_quality`: the estimate's second solve, as a task
    of its own (:func:`~.job.solve_job` hands it to an executor)."""
    second = replace(case, quality=second_quality(case.quality))
    sol = solve_positions(second, (second.beta,))[0]
    return SecondSolve(sol.headline(), {t.tooth: {k: getattr(t, k) for k in TOOTH_STRESSES}
                                        for t in sol.teeth if t.load_N > 0})


def tooth_estimates(sol: PairSolution, second: dict[int, dict[str, float]],
                    ratio: Callable[[str, str], float] = mesh_ratio,
                    floor: dict[str, float] | None = None) -> dict[int, dict[str, float]]:
    """Each loaded tooth's own error estimate (%) of its stresses (:data:`TOOTH_STRESSES`),
    from the same tooth at the second level (``second``: :attr:`SecondSolve.teeth`) as the
    headline's, each at least its headline's floor. A tooth that a deviation or a
    neighbour's relief loads lightly is resolved by fewer grid points than the headline tooth:
    its estimate is its own, not the headline's. A tooth loaded at one level only is compared
    with 0 there."""
    floor = MESH_SCATTER_PCT if floor is None else floor
    out = {}
    for t in sol.teeth:
        if t.load_N <= 0:
            continue
        mine = {f: getattr(t, f) for f in TOOTH_STRESSES}
        theirs = second.get(t.tooth, dict.fromkeys(TOOTH_STRESSES, 0.0))
        pct = _level_errors(mine, theirs, sol.case.quality, ratio)
        out[t.tooth] = {f: max(v, floor.get(TOOTH_STRESSES[f], 0.0)) for f, v in pct.items()}
    return out


def _gci(fine: dict[str, float], coarse: dict[str, float], ratio: float) -> dict[str, float]:
    """:func:`error_estimate` of any stresses by name."""
    return {k: 100.0 * GCI_FS * abs(fine[k] - coarse[k]) / (ratio ** 2 - 1.0)
            / max(abs(fine[k]), 1e-300) for k in fine}
