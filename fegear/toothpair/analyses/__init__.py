"""Analyses of a solved pair, each one subpackage (its plug-in in its ``__init__``; its solve,
report and pictures beside it): what it needs from the solve, how it solves, and how its
result is printed, written, judged, shown on the report page and tabled in a study
(:class:`~.base.Analysis`). This module is their registry, the one face the rest of the stage
reaches them through.

The job solves the core (the exact pair at its positions, the error estimate, the summary
with the cycle's rows) and then each analysis the run asked for, in the order of
:data:`ANALYSES`, each into its own entry of the summary. ``fegear solve``'s printer, the
files, the report page and a study's table loop over the same list: a new analysis is a
subpackage here and a line in :data:`ANALYSES` (docs/architecture.md, "Analyses plug in").

>>> from fegear.toothpair import prepare_job
>>> job = prepare_job({"z2": 25, "z1": 24, "positions": 4, "sensitivities": True})
>>> [a.key for a in asked(job)]
['cycle', 'sensitivities']
>>> [a.key for a in shown({"cycle": {}, "revolution": {}})]   # a revolution's table instead
['revolution']
"""

from __future__ import annotations

from .base import Analysis, Run, Verdict, Writing
from .cycle import CYCLE
from .face import FACE
from .rating import RATING
from .revolution import REVOLUTION
from .samples import SAMPLES
from .sensitivities import SENSITIVITIES

#: every analysis, in the order they solve, print and write
ANALYSES: tuple[Analysis, ...] = (CYCLE, REVOLUTION, SAMPLES, SENSITIVITIES, RATING, FACE)


def asked(job) -> list[Analysis]:
    """The analyses ``job`` asks for (the cycle: more than one position)."""
    return [a for a in ANALYSES if a.wanted(job)]


def shown(summary: dict) -> list[Analysis]:
    """The analyses whose entries ``summary`` holds, less those another one present replaces
    (a revolution's table stands where its cycle's would)."""
    present = [a for a in ANALYSES if a.key in summary]
    replaced = {key for a in present for key in a.replaces}
    return [a for a in present if a.key not in replaced]


__all__ = ["ANALYSES", "Analysis", "Run", "Verdict", "Writing", "asked", "shown"]
