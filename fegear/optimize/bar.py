"""When a design search's design on a tolerance class's pairs is answered before its pairs are
solved everywhere (:class:`Beaten`, the samples' :class:`~fegear.toothpair.Enough` for a
search).

A design is measured by the smallest safety factor that the quantile of its class's pairs
meets (:func:`~.design.evaluate`): each factor the allowable over the quantile of the pairs'
largest stresses, a jammed pair's beyond every other's. A pair's largest stress over the
positions solved so far is at most its largest over all of them, and a quantile does not rise
where any of its values falls or a value below all of them is added: so the pairs' stresses
read so far (a pair not read yet at zero, a jammed one beyond every other) give the quantile
of the stresses no more than it will be, and the objective no less. Once that bound is below
the ``bar``, the objective of the search's kept designs (the last of the best it will solve
again), the design cannot be one of them, and its pairs are solved no further: Optuna's
pruning, read from the pairs rather than from a learning curve.
"""

from __future__ import annotations

import numpy as np

from ..toothpair import Enough

#: a jammed pair's stress in the bound: beyond every other's, and finite, so that a quantile
#: between it and a finite one stays defined (its factor then about 0)
_BEYOND = 1e30


def loads_a_round(taken: tuple[float, np.ndarray]) -> bool:
    """Whether a pair's reading (the load on its tip rounds, N, and its limiting stresses)
    loads one of its rounds."""
    return taken[0] > 0.0


def objective_bound(tops: list[np.ndarray], unread: int, jammed: int, quantile: float,
                    allowable: np.ndarray) -> float:
    """The most the design's objective can be: the smallest of the limiting factors, each the
    ``allowable`` stress (MPa, a limit each) over the ``quantile`` of the pairs' stresses: the
    pairs' largest so far (``tops``, each the limits' stresses), ``unread`` pairs at zero and
    ``jammed`` beyond every other (module docstring; a pair that failed somewhere is none of
    them, as the class's quantiles leave it out)."""
    rows = [*tops, *([np.zeros(len(allowable))] * unread),
            *([np.full(len(allowable), _BEYOND)] * jammed)]
    stress = np.quantile(np.array(rows), quantile, axis=0)
    return float(min(a / s if s > 0 else np.inf for a, s in zip(allowable, stress)))


def bound_of(readings: dict[int, list], turning: list[int], jammed: int, quantile: float,
             allowable: np.ndarray) -> float:
    """:func:`objective_bound` of a run's ``readings`` (by pair, each a list of (load on the
    rounds, limiting stresses)) over its ``turning`` pairs (those that neither jam nor
    failed) and ``jammed`` ones."""
    tops = [np.max([r[1] for r in readings[k]], axis=0) for k in turning if readings.get(k)]
    return objective_bound(tops, len(turning) - len(tops), jammed, quantile, allowable)


class Beaten(Enough):
    """:class:`~fegear.toothpair.Enough` for a design search's design, its pairs read as (load
    on the rounds, limiting stresses) a position: not solved where more of them jam than the
    ``quantile`` leaves, solved no further once more than that have loaded a tip round
    (either constraint broken whatever the rest give), nor once the pairs read so far bound
    its objective below ``bar`` (module docstring; None: no bar yet), each limit's factor its
    ``allowable`` stress over the quantile's. Each chain bounds from its own positions, which
    is enough for the whole."""

    def __init__(self, quantile: float, allowable: np.ndarray, bar: float | None) -> None:
        super().__init__(loads_a_round, 1.0 - quantile, jams=1.0 - quantile)
        self.quantile, self.allowable, self.bar = quantile, allowable, bar
        self.tops: dict[int, np.ndarray] = {}
        self.out: set[int] = set()
        self.below = False

    def saw(self, k: int, reading) -> None:
        super().saw(k, reading)
        if self.bar is None or self.below or k in self.out:
            return
        self.tops[k] = np.maximum(self.tops.get(k, 0.0), reading[1])
        bound = objective_bound(list(self.tops.values()),
                                self.turning - len(self.tops) - len(self.out),
                                self.count - self.turning, self.quantile, self.allowable)
        self.below = bound < self.bar

    def failed(self, k: int) -> None:
        self.out.add(k)
        self.tops.pop(k, None)

    @property
    def reached(self) -> bool:
        return super().reached or self.below
