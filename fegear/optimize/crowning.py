""""What lead crowning do I need?": the smallest crowning C_β of gear 1's teeth that keeps
the face load factor K_Hβ at most a target over a misalignment band ±F (``fegear crowning``).

A trial is a crowning solved across the face (``fegear solve --crowning C --misalignment f``)
over ``positions`` rolling angles across one gear-2 pitch, at the band's ends f = ±F and at
the aligned pair f = 0; its K_Hβ is the worst of them. Crowning helps the band's ends and hurts
its middle: at ±F it moves the load off the face's closing end, so K_Hβ falls at first (and
rises again once the crowning gathers the load more than the misalignment did), while on the
aligned pair it gathers the load at mid-face, so K_Hβ grows from 1. The worst over the band
falls, then rises. The search doubles C from F/4 (the least crowning whose gap at ±F is least
on the face, not at its end: fζ + 4Cζ² is least at ζ = −f/(8C)) until a trial passes, then
bisects between it and the last one that failed down to ``tolerance_um``. If the worst rises
before any trial passes, a golden-section search in the last three trials' bracket finds the
crowning that minimises it; a trial that passes on the way ends it in the same bisection, and
none passing means no crowning reaches the target.

With ``modification="end-relief"`` the same search sizes an end relief C_I over a given
length from each end (``--end-relief``, ``--end-length``) instead: it too is even in ζ, opens
the closing end and, on the aligned pair, takes load off both ends.

Without helix deviations the pair is its own mirror across mid-face (−F at ζ is +F at −ζ;
crowning and end relief are even in ζ): the band's −F end is then +F's, and a trial costs two
solves (one for the even face, which is the 2D pair at every section: K_Hβ 1). With them,
three.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace

from .. import progress
from ..errors import ParameterError
from ..running import SERIAL, Executor
from ..timing import Stopwatch
from ..toothpair import deepest_lead_um, prepare_job, solve_command, solve_job

#: the K_Hβ the search keeps under where none is given: ISO 6336-1's method C gives 1.15 for
#: a linear mismatch of 0.3 times the mesh's approach, a face well matched by its correction
TARGET = 1.15
#: rolling angles a trial takes across one pitch: the worst position moves with the crowning
POSITIONS = 6
#: the solves' mesh: the ranking of crownings needs no finer one, and a trial's solves take
#: 3-5 s at coarse over 6 positions on two cores
QUALITY = "coarse"
#: the bisection's and golden section's end (µm): finer than a crowning is ground to; within
#: 0.5 µm of its least the baseline's worst K_Hβ moves by less than 0.005 (docs/optimize.md)
TOLERANCE_UM = 0.5
#: what the search can size: the solve's option, and the modification's name and symbol
MODIFICATIONS = {"crowning": ("lead crowning", "C_β"), "end-relief": ("end relief", "C_I")}
#: the golden section's step: the share of the larger interval a new trial goes into
GOLDEN = (3.0 - math.sqrt(5.0)) / 2.0


@dataclass(frozen=True)
class BandPoint:
    """One misalignment of the band solved across the face: ``misalignment_um``, the largest
    K_Hβ over the positions, and the worst section's gear-1 and gear-2 root stress and peak
    contact pressure each over the 2D pair's at the same position (the largest over the
    positions)."""

    misalignment_um: float
    K_Hbeta: float
    root_ratio_gear1: float
    root_ratio_gear2: float
    pressure_ratio: float

    @property
    def root_ratio(self) -> float:
        return max(self.root_ratio_gear1, self.root_ratio_gear2)


@dataclass(frozen=True)
class Trial:
    """A crowning or end relief (µm) solved over the band: its points (the solved
    misalignments; a mirrored pair's −F end is its +F end's) and the number of solves it
    took."""

    amount_um: float
    points: tuple[BandPoint, ...]
    solves: int

    @property
    def K_Hbeta(self) -> float:
        """The worst K_Hβ over the band."""
        return max(p.K_Hbeta for p in self.points)

    @property
    def aligned(self) -> BandPoint:
        return next(p for p in self.points if p.misalignment_um == 0.0)

    @property
    def ends(self) -> tuple[BandPoint, ...]:
        return tuple(p for p in self.points if p.misalignment_um != 0.0)

    @property
    def root_ratio(self) -> float:
        return max(p.root_ratio for p in self.points)

    @property
    def pressure_ratio(self) -> float:
        return max(p.pressure_ratio for p in self.points)

    def row(self) -> dict:
        return {"amount_um": self.amount_um, "K_Hbeta": self.K_Hbeta,
                "root_ratio": self.root_ratio, "pressure_ratio": self.pressure_ratio,
                "solves": self.solves, "points": [dict(p.__dict__) for p in self.points]}


@dataclass(frozen=True)
class CrowningSearch:
    """What the search covers: the misalignment band ±``band_um`` (µm over the face), the K_Hβ
    ``target``, ``positions`` rolling angles across one pitch (1: the one at ``--position``),
    the solves' ``quality`` and the search's ``tolerance_um``, and what it sizes
    (``modification``, one of :data:`MODIFICATIONS`; an end relief over ``end_length_mm``
    from each end, None: the solve's default, a fifth of the face width); each checked by
    name."""

    band_um: float | None
    target: float = TARGET
    positions: int = POSITIONS
    quality: str = QUALITY
    tolerance_um: float = TOLERANCE_UM
    modification: str = "crowning"
    end_length_mm: float | None = None

    def __post_init__(self) -> None:
        if self.band_um is None:
            raise ParameterError("misalignment-band", None, "0 < misalignment-band <= 200 µm",
                                 "required: the band ±F the crowning must cover")
        if not 0.0 < self.band_um <= 200.0:
            raise ParameterError("misalignment-band", self.band_um,
                                 "0 < misalignment-band <= 200 µm")
        if not 1.0 < self.target <= 3.0:
            raise ParameterError("target", self.target, "1 < target <= 3 (K_Hβ is at least 1)")
        if not 1 <= self.positions <= 360:
            raise ParameterError("positions", self.positions, "an integer 1 <= positions <= 360")
        if not 0.0 < self.tolerance_um <= 10.0:
            raise ParameterError("tolerance", self.tolerance_um, "0 < tolerance <= 10 µm")
        if self.modification not in MODIFICATIONS:
            raise ParameterError("modification", self.modification, " / ".join(MODIFICATIONS))
        if self.end_length_mm is not None and self.modification != "end-relief":
            raise ParameterError("end-length", self.end_length_mm, "with --modification "
                                 "end-relief only (the length of the end relief sized)")

    def inputs(self, amount_um: float) -> dict:
        """The ``fegear solve`` inputs of the modification at ``amount_um``."""
        if self.modification == "crowning":
            return {"crowning": amount_um}
        return {"end-relief": amount_um, "end-length": self.end_length_mm}


@dataclass(frozen=True)
class CrowningSizing:
    """The search's trials in the order tried, the amount chosen (µm), whether it keeps
    K_Hβ at most the target (else it is the one that minimises K_Hβ over the band), whether
    the pair was mirrored (two solves a trial), the solves and the wall time (s), and the
    ``fegear solve`` inputs of the pair as given (the modification and misalignment
    aside)."""

    search: CrowningSearch
    trials: tuple[Trial, ...]
    amount_um: float
    reached: bool
    mirrored: bool
    solves: int
    wall_s: float
    values: Mapping[str, object]

    def trial(self, amount_um: float) -> Trial:
        return next(t for t in self.trials if t.amount_um == amount_um)

    @property
    def before(self) -> Trial:
        return self.trial(0.0)

    @property
    def chosen(self) -> Trial:
        return self.trial(self.amount_um)

    def command(self) -> str:
        """The ``fegear solve`` line of the amount chosen at the band's +F end."""
        s = self.search
        return solve_command({**self.values, "quality": s.quality,
                              "positions": s.positions if s.positions > 1 else None,
                              **s.inputs(self.amount_um), "misalignment": s.band_um})

    def summary(self) -> dict:
        s = self.search
        return {"modification": s.modification, "end_length_mm": s.end_length_mm,
                "misalignment_band_um": s.band_um, "target": s.target,
                "positions": s.positions, "quality": s.quality, "tolerance_um": s.tolerance_um,
                "amount_um": self.amount_um, "reached": self.reached,
                "K_Hbeta_before": self.before.K_Hbeta, "K_Hbeta": self.chosen.K_Hbeta,
                "mirrored": self.mirrored, "solves": self.solves, "wall_s": self.wall_s,
                "command": self.command(), "trials": [t.row() for t in self.trials]}


def band_point(values: Mapping, amount_um: float, misalignment_um: float,
               search: CrowningSearch, executor: Executor = SERIAL) -> BandPoint:
    """The pair of ``values`` (``fegear solve`` inputs) with the search's modification at
    ``amount_um`` and ``misalignment_um``, solved across the face over its positions."""
    job = prepare_job({**values, **search.inputs(amount_um), "misalignment": misalignment_um,
                       "quality": search.quality, "no-estimate": True,
                       "positions": search.positions if search.positions > 1 else None})
    face = solve_job(job, executor).summary["face"]
    worst = face["worst"]
    return BandPoint(misalignment_um, face["K_Hbeta"],
                     worst["root_stress_gear1_MPa"]["ratio"] or 1.0,
                     worst["root_stress_gear2_MPa"]["ratio"] or 1.0,
                     worst["contact_pressure_MPa"]["ratio"] or 1.0)


def band_checked(values: Mapping, search: CrowningSearch) -> tuple[bool, float]:
    """Whether the pair of ``values`` is its own mirror across mid-face (no helix
    deviations), and the deepest modification its teeth take (µm: the solve's bound,
    :func:`~fegear.toothpair.face.deepest_lead_um`), its inputs and the modification's
    checked as the solve checks them; a band that jams it (the solve's own check of its room
    across the face) is refused naming ``misalignment-band``."""
    mirrored = True
    for f in (search.band_um, -search.band_um):
        try:
            job = prepare_job({**values, **search.inputs(0.0), "misalignment": f,
                               "quality": search.quality})
        except ParameterError as exc:
            if exc.name != "misalignment":
                raise
            raise ParameterError("misalignment-band", search.band_um, "0 < " + exc.admissible
                                 .replace("|misalignment|", "misalignment-band"),
                                 exc.reason) from None
        mirrored = not (job.face.helix1 or job.face.helix2)
        if mirrored:
            break
    return mirrored, deepest_lead_um(job.case.params.m)


class _Band:
    """Trials by amount, each solved once by ``solve`` (:func:`band_point`'s signature), in
    the order tried; ``report`` is told of each solve (a stage on the progress bar)."""

    def __init__(self, values: Mapping, search: CrowningSearch, mirrored: bool,
                 executor: Executor, report: Callable[[str], None],
                 solve: Callable[..., BandPoint]) -> None:
        self.values, self.search, self.mirrored = values, search, mirrored
        self.executor, self.report, self.solve = executor, report, solve
        self.trials: dict[float, Trial] = {}

    def __call__(self, amount_um: float) -> Trial:
        if amount_um not in self.trials:
            self.trials[amount_um] = self._solve(amount_um)
        return self.trials[amount_um]

    def _solve(self, c: float) -> Trial:
        F = self.search.band_um
        points, solves = {}, 0
        for f in (F, 0.0) if self.mirrored else (F, -F, 0.0):
            if f == 0.0 and c == 0.0 and self.mirrored:   # an even face: the 2D pair
                points[f] = BandPoint(0.0, 1.0, 1.0, 1.0, 1.0)
                continue
            self.report(f"{self.search.modification} {c:.3g} µm at misalignment {f:+g} µm")
            with progress.reporting(None):   # one stage a solve, whatever the solve's are
                points[f] = self.solve(self.values, c, f, self.search, self.executor)
            solves += 1
        if self.mirrored:
            points[-F] = replace(points[F], misalignment_um=-F)
        return Trial(c, tuple(points[f] for f in (-F, 0.0, F)), solves)

    def passes(self, c: float) -> bool:
        return self(c).K_Hbeta <= self.search.target


def size_crowning(values: Mapping, search: CrowningSearch, executor: Executor = SERIAL,
                  report: Callable[[str], None] = lambda text: None,
                  solve: Callable[..., BandPoint] = band_point) -> CrowningSizing:
    """The smallest crowning (or end relief) of the pair of ``values`` (``fegear solve``
    inputs, the modification and misalignment aside) whose K_Hβ stays at most
    ``search.target`` over the band, or the one that minimises K_Hβ over it where none does
    (module docstring); ``solve`` gives a point of the band (default :func:`band_point`)."""
    watch = Stopwatch()
    mirrored, deepest = band_checked(values, search)
    band = _Band(values, search, mirrored, executor, report, solve)
    chosen, reached = _search(band, search, deepest)
    trials = tuple(band.trials.values())
    return CrowningSizing(search, trials, chosen, reached, mirrored,
                          sum(t.solves for t in trials), watch.s, dict(values))


def _search(band: _Band, search: CrowningSearch, most: float) -> tuple[float, bool]:
    """(the crowning chosen, whether it passes): doubling from F/4 until a trial passes or
    the worst K_Hβ rises, at most ``most`` µm, then a bisection or a golden section."""
    if band.passes(0.0):
        return 0.0, True
    before, low, c = 0.0, 0.0, min(0.25 * search.band_um, most)
    while True:
        if band.passes(c):
            return _smallest(band, low, c), True
        if band(c).K_Hbeta >= band(low).K_Hbeta:
            break   # past the least: it lies in [before, c]
        if c >= most:
            return c, False   # still falling at the most the teeth take
        before, low, c = low, c, min(2.0 * c, most)
    return _least(band, before, low, c)


def _smallest(band: _Band, low: float, high: float) -> float:
    """The bisection between a failing crowning ``low`` below the band's least and a passing
    one ``high``: the smallest that passes, within the tolerance."""
    while high - low > band.search.tolerance_um:
        mid = 0.5 * (low + high)
        if band.passes(mid):
            high = mid
        else:
            low = mid
    return high


def _least(band: _Band, a: float, b: float, c: float) -> tuple[float, bool]:
    """The golden section for the crowning that minimises the worst K_Hβ in [a, c], b inside
    with the least K_Hβ of the three; a trial that passes ends it in a bisection from the
    largest failing crowning tried below it."""
    K = lambda x: band(x).K_Hbeta   # noqa: E731
    while c - a > band.search.tolerance_um:
        x = b - GOLDEN * (b - a) if b - a > c - b else b + GOLDEN * (c - b)
        if band.passes(x):
            below = max(t for t in band.trials if t < x)
            return _smallest(band, below, x), True
        if K(x) < K(b):
            a, c = (a, b) if x < b else (b, c)
            b = x
        elif x < b:
            a = x
        else:
            c = x
    return b, False


def sizing_table(s: CrowningSizing) -> str:
    """What ``fegear crowning`` prints: the verdict, every amount tried (K_Hβ aligned and at
    the band's ends, the worst, and the worst section's root stress and peak pressure over
    the 2D pair's, each the largest over the band), the solves and the line that solves the
    amount chosen."""
    q, F = s.search, s.search.band_um
    name, symbol = MODIFICATIONS[q.modification]
    over = (f"over the misalignment band ±{F:g} µm (±{F:g} µm and the aligned pair, "
            f"{q.positions} position{'s' * (q.positions > 1)} across a pitch, {q.quality})")
    if s.reached and s.amount_um == 0.0:
        head = f"no {name} needed: K_Hβ stays at most {q.target:g} {over}"
    elif s.reached:
        head = (f"{name} {symbol} {s.amount_um:.2f} µm{_over(q)}: the smallest that keeps "
                f"K_Hβ at most "
                f"{q.target:g} {over}")
    else:
        head = (f"no {name}{_over(q)} keeps K_Hβ at most {q.target:g} {over}: {symbol} "
                f"{s.amount_um:.2f} µm minimises it, to {s.chosen.K_Hbeta:.3f}")
    ends = [(f"K_Hβ at ±{F:g} µm", F)] if s.mirrored else [(f"K_Hβ at {f:+g} µm", f)
                                                           for f in (-F, F)]
    columns = [f"{symbol} [µm]", "K_Hβ aligned", *(c for c, _ in ends), "worst K_Hβ",
               "root stress ratio", "peak pressure ratio"]
    lines = [head, "", "| " + " | ".join(columns) + " |", "|" + "---:|" * len(columns)]
    for t in sorted(s.trials, key=lambda t: t.amount_um):
        at = {p.misalignment_um: p.K_Hbeta for p in t.points}
        mark = " (chosen)" if t.amount_um == s.amount_um else ""
        cells = [f"{t.amount_um:.2f}{mark}", f"{at[0.0]:.3f}",
                 *(f"{at[f]:.3f}" for _, f in ends), f"{t.K_Hbeta:.3f}", f"{t.root_ratio:.3f}",
                 f"{t.pressure_ratio:.3f}"]
        lines.append("| " + " | ".join(cells) + " |")
    mirror = f" (the −{F:g} µm end is the +{F:g} µm one mirrored)" if s.mirrored else ""
    lines += ["", "ratios: the worst section's stress over the 2D pair's at the same position, "
                  "the largest over the band",
              f"{len(s.trials)} amounts tried, {s.solves} solves{mirror}, {s.wall_s:.1f} s",
              f"solve it: {s.command()}"]
    return "\n".join(lines)


def _over(q: CrowningSearch) -> str:
    """An end relief's length as the verdict states it ('' for a crowning)."""
    if q.modification != "end-relief":
        return ""
    return (" from each end" if q.end_length_mm is None else
            f" over {q.end_length_mm:g} mm from each end")
