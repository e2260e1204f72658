""""What relief do I need?": the smallest tip relief, of a given extent and shape, that keeps
every loaded contact off gear 1's tip rounds over a mesh cycle.

A trial is a relief amount C solved over ``positions`` rolling angles across one gear-2 pitch;
it passes when no tip round carries load at any of them. The search is done at the torque
raised by the ``margin`` (default +20 %): the approach of the teeth grows about linearly with
the load, so the relief found keeps the rounds unloaded up to that overload. It scans
C = 2, 4, 8, … µm until a trial passes, then bisects to ``tolerance``. A longer relief turns
gear 1 further before the teeth carry the torque, which can close a far-side tip onto its
round (docs/model.md, "Tip relief"). Such a far-side tip is kept off by a larger radial tip
clearance, which the search raises in steps of 0.002 m until the far side is off at the amount
found (and then checks that amount again on the trimmed tips); told to keep the tip clearance,
or if no amount up to the admissible limit passes, it says why and names what to change.

The relief found is then solved at the design torque beside the unrelieved pair: flank and
peak pressure, transmission error and load sharing over the cycle.

A trial of a tolerance class's pairs ends as soon as its answer is known: a trial asked
whether the rounds by the pitch point stay unloaded (the scan and the bisection) stops once
more pairs have loaded one of them than the quantile leaves, one asked about the far side
(the tip clearance's steps) once more have loaded a far-side round; that end changes no
decision of the search, and such a trial reports what it saw until then (``stopped``). And a
trial by the pitch point solves only the pairs that loaded a round there in the largest trial
below it solved whole (at the same torque and tip clearance): a larger relief cuts more of
every tip, and a round it keeps off at one amount stays off at a larger one
(docs/tolerance.md shows it on a class's pairs). The amount the scan and bisection end at is
then solved again with every pair, and where that fails (a pair left out that loads a round
after all) the search goes on above it: the amount found is always one solved whole.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace

from ..errors import FegearError, ParameterError
from ..geometry import gear1_profile
from ..planar import wrap
from ..running import SERIAL, Executor, Task
from ..toothpair import DEFAULT_ALLOWABLES, prepare_job, solve_job_positions

FIRST_UM = 2.0       # the scan's first amount
MARGIN = 0.2         # torque overload the relief must cover
TOLERANCE_UM = 0.5   # bisection stops when the bracket is this narrow
POSITIONS = 12       # rolling angles per trial
FAR_DEG = 45.0       # teeth farther than this from the pitch point (about O1) are far-side
CLEARANCE_STEP = 0.002  # × m: the tip clearance's step when a far-side tip lands on its round
#: a tooth's side of the mesh by where it stands (° from the pitch point about O1)
SIDES = {"near": lambda angle: abs(angle) <= FAR_DEG, "far": lambda angle: abs(angle) > FAR_DEG}


@dataclass(frozen=True)
class CycleResult:
    """A relief over a mesh cycle: amount (µm), torque (N·m), the largest load on the tip
    rounds at any position (N) and the teeth whose round carried some, the largest flank and
    overall contact pressure (MPa), the transmission error's mean and peak-to-peak (µrad),
    each tooth's largest load share, and the radial tip clearance (mm). Teeth more than
    ``FAR_DEG`` from the pitch point are far-side teeth: their tips meet gear 2's other flanks
    across the mesh. For a tolerance class's pairs (:func:`graded_cycle_result`) the rounds
    count as loaded where more pairs than the quantile leaves load them (``edge_share``: the
    share of the pairs that turn whose rounds carry load), the rest are the exact pair's."""

    amount_um: float
    torque: float
    edge_load_N: float
    edge_teeth: tuple[int, ...]      # each once a side of the mesh it loaded a round on …
    edge_angles: tuple[float, ...]   # … and where it stood: ° from the pitch point about O1
    flank_MPa: float
    contact_MPa: float
    te_mean_urad: float
    te_p2p_urad: float
    shares: dict
    tip_clearance_mm: float = 0.0
    edge_share: float | None = None   # a class's pairs: the share whose rounds carry load
    stopped: bool = False   # a class's trial that ended once its side had failed: what it saw
    loading: tuple = ((), ())   # … the pairs (by sample) that loaded a round by the pitch
                                # point, and across the mesh, of those it solved …
    left_out: int = 0           # … and how many it did not solve (:class:`Ask`)

    @property
    def off_the_rounds(self) -> bool:
        return self.edge_load_N <= 0.0


@dataclass(frozen=True)
class ReliefSizing:
    """The search's trials (at the raised torque), the amount it found (µm), the radial tip
    clearance given and the one it needed (mm), and the pair as given (no relief) and with the
    relief and tip clearance found, at the design torque."""

    extent_mm: float
    shape: str
    margin: float
    positions: int
    trials: tuple[CycleResult, ...]
    amount_um: float
    given_tip_clearance_mm: float
    tip_clearance_mm: float
    without: CycleResult
    with_relief: CycleResult
    pitches: int = 1   # gear-2 pitches a trial's positions repeat over: z1 over a revolution

    def summary(self) -> dict:
        def row(r: CycleResult) -> dict:
            return {k: (list(v) if isinstance(v, tuple) else v) for k, v in r.__dict__.items()}

        return {"relief_um": self.amount_um, "tip_clearance_mm": self.tip_clearance_mm,
                "given_tip_clearance_mm": self.given_tip_clearance_mm,
                "relief_extent_mm": self.extent_mm,
                "relief_shape": self.shape, "margin": self.margin, "positions": self.positions,
                "pitches": self.pitches,
                "without_relief": row(self.without), "with_relief": row(self.with_relief),
                "trials": [row(t) for t in self.trials]}


def cycle_result(values: Mapping, amount_um: float, torque: float, positions: int,
                 ask: Ask | None = None) -> CycleResult:
    """Solve the pair of ``values`` (``fegear solve`` inputs) with a relief of ``amount_um``
    at ``torque`` over ``positions`` rolling angles. ``ask``: what a trial asks
    (:func:`graded_cycle_result`); one pair's cycle is solved whole whatever it asks (no pair
    to leave out)."""
    job = prepare_job({**values, "relief": amount_um, "torque": torque,
                       "positions": positions, "no-estimate": True})
    profile = gear1_profile(job.case.params)
    # the search reads contact loads and pressures only: no stresses, no submodels
    sols = solve_job_positions(job, contact_only=True)
    return _exact(sols, profile, job.case.params, amount_um, torque)


def _tip_angles(profile, params, sol) -> list[tuple[int, float]]:
    """The teeth whose tip rounds carry load in the solution ``sol``, each with where it
    stands (° from the pitch point about O1)."""
    beta = sol.case.beta
    return [(t.tooth, math.degrees(wrap(profile.tooth_center + t.tooth * profile.pitch
                                        + params.ratio * beta - 0.5 * math.pi)))
            for t in sol.teeth if t.edge_contact]


@dataclass(frozen=True)
class Ask:
    """What a trial is asked: about the rounds on ``side`` ("near": by the pitch point, "far":
    across the mesh), and of a class's pairs ``only`` these (by sample; None: every one), the
    others known to keep that side's rounds unloaded (module docstring)."""

    side: str
    only: frozenset[int] | None = None


@dataclass(frozen=True)
class Graded:
    """A relief's trials on a tolerance class: ``draw``'s pairs, the rounds judged at the
    ``quantile`` of those that turn; called as a search's ``solve`` (:func:`size_relief`),
    :func:`graded_cycle_result`."""

    draw: object
    quantile: float

    def __call__(self, values: Mapping, amount_um: float, torque: float, positions: int,
                 ask: Ask | None = None) -> CycleResult:
        return graded_cycle_result(values, amount_um, torque, positions, self, ask)


def graded_cycle_result(values: Mapping, amount_um: float, torque: float, positions: int,
                        graded: Graded, ask: Ask | None = None) -> CycleResult:
    """:func:`cycle_result` for the pairs of a tolerance class (``graded``): the exact pair's
    loads, pressures and transmission error, and its tip rounds counted as loaded where, of
    the pairs that turn, more than ``1 - quantile`` load a round by the pitch point, or a
    far-side one (the search then raises the tip clearance as for one pair). ``ask``: the
    trial ends once more pairs than that have loaded a round on its side, and solves only
    its ``only`` pairs, the others counted as turning with that side's rounds unloaded
    (module docstring; a pair that would fail at a position left unsolved counts as
    turning). A class of which more pairs jam than the quantile leaves has no relief:
    refused by name."""
    from ..toothpair import (  # lazy: heavy: scikit-fem; `fegear relief` imports this
        Enough,
        class_samples,
    )

    job = prepare_job({**values, "relief": amount_um, "torque": torque,
                       "positions": positions, "no-estimate": True})
    draw, quantile = graded.draw, graded.quantile
    job = replace(job, draw=draw, quantile=quantile)
    p = job.case.params
    profile = gear1_profile(p)
    enough = None if ask is None else Enough(
        lambda taken: any(SIDES[ask.side](a) for _, a in taken[1]), 1.0 - quantile, ask.only)
    sampled = class_samples(job, DEFAULT_ALLOWABLES, contact_only=True,
                            read=lambda sol: (sum(t.edge_load_N for t in sol.teeth),
                                              _tip_angles(profile, p, sol)), enough=enough)
    turning, jammed = sampled.turning, sampled.jammed_share
    if jammed > 1.0 - quantile:
        raise ParameterError("grade", draw.grade.grade, f"a class whose pairs turn in "
                             f"{100 * quantile:g} % of cases at least ({100 * jammed:.3g} % "
                             "of these jam: no relief frees them; a finer class or more "
                             "backlash, --shift)")
    exact = _exact(sampled.nominal, profile, p, amount_um, torque)
    loaded = {k: [e for load, tips in sampled.readings.get(k, []) for e in tips]
              for k in turning}
    tips: list[tuple[int, float]] = []
    loading = []
    for side in SIDES.values():
        hit = [k for k in turning if any(side(a) for _, a in loaded[k])]
        loading.append(tuple(hit))
        if len(hit) > (1.0 - quantile) * len(turning):
            tips += [(t, a) for k in hit for t, a in loaded[k] if side(a)]
    any_round = sum(bool(loaded[k]) for k in turning) / max(len(turning), 1)
    most = max((load for k in turning for load, _ in sampled.readings.get(k, [])),
               default=0.0)
    teeth, angles = by_side(tips)
    return CycleResult(amount_um, torque, most if teeth else 0.0, teeth, angles, exact.flank_MPa,
                       exact.contact_MPa, exact.te_mean_urad, exact.te_p2p_urad, exact.shares,
                       p.radial_tip_clearance, any_round, sampled.stopped, tuple(loading),
                       sum(r["status"] == "left out" for r in sampled.rows))


def _exact(sols, profile, p, amount_um: float, torque: float) -> CycleResult:
    """The exact pair's :class:`CycleResult` from its solutions over the cycle."""
    teeth, angles = by_side(e for s in sols for e in _tip_angles(profile, p, s))
    te = [1e6 * (s.rotation - s.first_touch) for s in sols]
    shares: dict[int, float] = {}
    for s in sols:
        for t in s.teeth:
            shares[t.tooth] = max(shares.get(t.tooth, 0.0), t.load_share)
    return CycleResult(
        amount_um=amount_um, torque=torque,
        edge_load_N=max((sum(t.edge_load_N for t in s.teeth) for s in sols), default=0.0),
        edge_teeth=teeth, edge_angles=angles,
        flank_MPa=max(s.flank_contact_pressure for s in sols),
        contact_MPa=max(s.contact_pressure for s in sols),
        te_mean_urad=sum(te) / len(te), te_p2p_urad=max(te) - min(te),
        shares={k: v for k, v in sorted(shares.items()) if v > 0},
        tip_clearance_mm=p.radial_tip_clearance)


@dataclass(frozen=True)
class ReliefSearch:
    """How the search runs: ``positions`` rolling angles a trial, the torque ``margin`` the
    relief must cover, the bisection's ``tolerance_um`` and whether a far-side tip on its
    round raises the radial tip clearance (``clearance``) or ends the search."""

    positions: int = POSITIONS
    margin: float = MARGIN
    tolerance_um: float = TOLERANCE_UM
    clearance: bool = True


class _Ahead:
    """Trials by key (amount µm, torque, tip clearance mm or None for the one given, what it
    is asked (:class:`Ask`) or None), solved by ``solve`` on ``executor``, a guessed next one
    with a needed one while a worker is free. A trial's error is raised where it is
    needed."""

    def __init__(self, solve: Callable[..., CycleResult], values: Mapping, positions: int,
                 executor: Executor) -> None:
        self.solve, self.values, self.positions, self.executor = solve, values, positions, \
            executor
        self.tasks: dict[tuple, Task] = {}

    def _args(self, key: tuple) -> tuple:
        amount, torque, tip, ask = key
        values = self.values if tip is None else {**self.values, "tip-clearance": tip}
        return values, amount, torque, self.positions, ask

    def get(self, key: tuple, guess: tuple | None = None) -> CycleResult:
        # a guess goes with a trial submitted now, not with one already under way (it
        # was itself a guess; guessing past it kept a worker from the next needed trial)
        if key not in self.tasks:
            busy = sum(not t.done() for t in self.tasks.values())
            self.tasks[key] = self.executor.submit(self.solve, *self._args(key))
            if guess is not None and guess not in self.tasks and \
                    busy + 1 < self.executor.workers:
                self.tasks[guess] = self.executor.submit(self.solve, *self._args(guess))
        return self.tasks[key].result()


def size_relief(values: Mapping, search: ReliefSearch = ReliefSearch(),
                executor: Executor = SERIAL, solve: Callable[..., CycleResult] | None = None,
                report: Callable[[str], None] | None = None) -> ReliefSizing:
    """The smallest relief (module docstring) for the pair, torque, extent and shape of
    ``values``, as ``search`` says. ``executor`` solves trials, the next one guessed ahead
    where it has a worker free. ``solve`` evaluates one trial (values, amount µm, torque,
    positions, what it is asked: an :class:`Ask`, or None for all of it) →
    :class:`CycleResult` (default :func:`cycle_result`), ``report`` is told of each trial."""
    # every input checked before any solve, the extent and shape with a relief in place
    params = prepare_job({**values, "relief": FIRST_UM, "positions": search.positions,
                          "no-estimate": True}).case.params
    ahead = _Ahead(solve or cycle_result, values, search.positions, executor)
    found = _Sizing(params, float(values.get("torque", 200.0)), search, ahead, report).run()
    return replace(found, pitches=params.z1 if values.get("revolution") else 1)


class _Sizing:
    """One search's state: the trials so far at the torque raised by the margin, and the tip
    clearance it stands at."""

    def __init__(self, params, torque: float, search: ReliefSearch, ahead: _Ahead,
                 report: Callable[[str], None] | None) -> None:
        self.params, self.torque, self.search, self.ahead, self.report = \
            params, torque, search, ahead, report
        self.raised = torque * (1.0 + search.margin)
        self.limit = 50.0 * params.m                       # the relief input's range
        self.most = params.m * params.h1                    # the tip_clearance input's range
        self.tip = params.radial_tip_clearance
        self.trials: list[CycleResult] = []
        self.tip_note = "a larger tip_clearance keeps them off"

    def trial(self, amount: float, guess: tuple | None = None, ask: Ask | None = None
              ) -> CycleResult:
        """The trial of ``amount`` (µm) at the raised torque and the present tip clearance,
        asked ``ask`` (default: about the near side, :meth:`asked`); ``guess``: a key to
        solve ahead."""
        ask = ask or self.asked(amount)
        r = self.ahead.get((amount, self.raised, self.tip, ask), guess)
        self.trials.append(r)
        if self.report:
            where = (f"rounds of teeth {sorted(set(r.edge_teeth))} carry "
                     f"{r.edge_load_N:.1f} N"
                     if not r.off_the_rounds else "off the rounds")
            where += " (stopped there)" if r.stopped else ""
            where += f" ({r.left_out} pairs left out)" if r.left_out else ""
            self.report(f"relief {amount:7.3f} µm, tip clearance {1e3 * self.tip:5.1f} µm at "
                        f"{self.raised:g} N·m: {where}; flank {r.flank_MPa:.0f} MPa")
        return r

    def asked(self, amount: float) -> Ask:
        """What the trial of ``amount`` is asked about the rounds by the pitch point: of a
        class's pairs, only those that loaded one in the largest trial below it solved whole
        at this torque and tip clearance (a larger relief keeps the others' off: module
        docstring), where there is one."""
        below = [t for t in self.trials if t.amount_um < amount and t.edge_share is not None
                 and not (t.stopped or t.left_out) and t.torque == self.raised
                 and abs(t.tip_clearance_mm - self.tip) < 1e-12]
        if not below:
            return Ask("near")
        return Ask("near", frozenset(max(below, key=lambda t: t.amount_um).loading[0]))

    def near_side(self, low: float) -> float | None:
        """The smallest amount above ``low`` (which fails, or is 0) whose near-side rounds stay
        unloaded at the present tip clearance, to the tolerance, its trial solved whole; None
        if none up to the limit. The trials' far-side teeth are left to the caller."""
        while True:
            high = self._bracketed(low)
            latest = None if high is None else self.latest(high)
            if latest is None or not latest.left_out:
                return high
            if not near(self.trial(high, ask=Ask("near"))):   # the pairs left out kept off
                return high
            low = high

    def latest(self, amount: float) -> CycleResult:
        """The last trial of ``amount``."""
        return next(t for t in reversed(self.trials) if t.amount_um == amount)

    def _bracketed(self, low: float) -> float | None:
        """:meth:`near_side`'s scan and bisection, its trials of a class's pairs asked of
        some (:meth:`asked`)."""
        if low == 0.0 and not near(self.trial(0.0, (0.0, self.torque, None, None))):
            return 0.0
        amount, high = max(FIRST_UM, 2.0 * low), None
        while amount <= self.limit:
            guess = (2.0 * amount, self.raised, self.tip, self.asked(2.0 * amount)) \
                if 2.0 * amount <= self.limit else None
            try:
                passed = not near(self.trial(amount, guess))
            except ParameterError as exc:   # deeper than the extent can take: the scan ends
                if exc.name != "relief":
                    raise
                break
            if passed:
                high = amount
                break
            low, amount = amount, 2.0 * amount
        while high is not None and high - low > self.search.tolerance_um:
            mid = 0.5 * (low + high)
            quarter = 0.5 * (low + mid)
            if near(self.trial(mid, (quarter, self.raised, self.tip, self.asked(quarter)))):
                low = mid
            else:
                high = mid
        return high

    def refused(self) -> FegearError:
        return FegearError(_no_relief(self.trials, self.params.relief_extent, self.raised,
                                      self.tip_note))

    def far_side_off(self, high: float) -> CycleResult:
        """The trial at ``high`` once the tip clearance is raised until its far-side rounds
        are off (the search's ``clearance``), in steps of ``CLEARANCE_STEP`` · m."""
        last = self.latest(high)
        if far(last) and not self.search.clearance:
            self.tip_note = ("a larger tip_clearance keeps them off: without "
                             "--keep-tip-clearance fegear relief raises it")
            raise self.refused()
        step = CLEARANCE_STEP * self.params.m
        while far(last):
            self.tip += step
            if self.tip > self.most:
                self.tip_note = (f"they still do with the tip clearance raised to "
                                 f"{1e3 * (self.tip - step):.0f} µm, the most this pair "
                                 f"takes is {1e3 * self.most:.0f} µm")
                raise self.refused()
            last = self.trial(high, (high, self.torque, self.tip, None), Ask("far"))
        return last

    def run(self) -> ReliefSizing:
        low = 0.0
        while True:
            high = self.near_side(low)
            if high is None:
                raise self.refused()
            if not near(self.far_side_off(high)):
                break
            low = high                            # the trimmed tips need a little more
        p = self.params
        return ReliefSizing(p.relief_extent, p.relief_shape, self.search.margin,
                            self.search.positions, tuple(self.trials), high,
                            p.radial_tip_clearance, self.tip,
                            self.ahead.get((0.0, self.torque, None, None)),
                            self.ahead.get((high, self.torque, self.tip, None)))


def by_side(tips) -> tuple[tuple[int, ...], tuple[float, ...]]:
    """The teeth of ``tips`` ((tooth, ° from the pitch point) where a round carried load),
    each once a side of the mesh it stood on (:data:`SIDES`; the last angle seen there), in
    order, and those angles: over a whole turn every tooth passes both sides, and a tooth
    kept once would be read on the side it was seen last (a round loaded by the pitch point
    then hid behind one loaded across the mesh)."""
    last = {(t, SIDES["far"](a)): a for t, a in tips}
    keys = sorted(last)
    return tuple(t for t, _ in keys), tuple(last[k] for k in keys)


def near(r: CycleResult) -> list[int]:
    """The teeth by the pitch point whose rounds carried load in the trial ``r``."""
    return [k for k, a in zip(r.edge_teeth, r.edge_angles) if SIDES["near"](a)]


def far(r: CycleResult) -> list[int]:
    """The far-side teeth whose rounds carried load in the trial ``r``."""
    return [k for k, a in zip(r.edge_teeth, r.edge_angles) if SIDES["far"](a)]


def _no_relief(trials, extent: float, torque: float, tip_note: str) -> str:
    """Why no amount passed, and what to change (``tip_note``: what the tip clearance did)."""
    why = []
    far_side = [(t.amount_um, far(t)) for t in trials if far(t)]
    if far_side:
        teeth = sorted({k for _, ks in far_side for k in ks})
        why.append(f"far-side teeth {teeth} press on their rounds from {far_side[0][0]:g} µm "
                   "on (their tips meet gear 2 across the mesh; a relief turns gear 1 further "
                   f"onto them; {tip_note})")
    still = near(trials[-1])
    if still:
        why.append(f"teeth {still} by the pitch point still do at {trials[-1].amount_um:g} µm "
                   "(a longer relief_extent reaches further down the flank)")
    else:
        clear = next(t.amount_um for t in trials if not near(t))
        why.append(f"the rounds by the pitch point are unloaded from {clear:g} µm on")
    return (f"no tip relief over {extent:g} mm keeps the tip rounds unloaded at {torque:g} N·m "
            f"(tried up to {trials[-1].amount_um:g} µm): " + "; ".join(why))


def sizing_table(s: ReliefSizing) -> str:
    """What ``fegear relief`` prints: over a whole turn of gear 1 where the trials took one
    (``s.pitches`` > 1), and for a class's pairs the share of them that load a round in each
    trial."""
    a, b = s.without, s.with_relief
    over = "over the cycle" if s.pitches == 1 else "over a whole turn of gear 1"
    lines = [f"tip relief {s.amount_um:.2f} µm, {s.shape}, over {s.extent_mm:g} mm along the "
             f"flank: the smallest that keeps every tip round unloaded {over} at "
             f"{(1 + s.margin) * a.torque:g} N·m ({100 * s.margin:.0f} % over {a.torque:g})"]
    found = f"{s.amount_um:.2f} µm"
    if s.tip_clearance_mm > s.given_tip_clearance_mm:
        lines.append(f"tip clearance raised from {1e3 * s.given_tip_clearance_mm:.1f} to "
                     f"{1e3 * s.tip_clearance_mm:.1f} µm (--tip-clearance "
                     f"{s.tip_clearance_mm:.4g}): with less, far-side tips land on their rounds")
        found += f", tip clearance {1e3 * s.tip_clearance_mm:.1f} µm"
    lines += ["",
              f"| over the cycle at {a.torque:g} N·m | as given | {found} |",
              "|---|---:|---:|",
              f"| peak contact pressure [MPa] | {a.contact_MPa:.0f} | {b.contact_MPa:.0f} |",
              f"| flank pressure [MPa] | {a.flank_MPa:.0f} | {b.flank_MPa:.0f} |",
              f"| load on the tip rounds, largest [N] | {a.edge_load_N:.1f} | "
              f"{b.edge_load_N:.1f} |",
              f"| transmission error, mean [µrad] | {a.te_mean_urad:.1f} | "
              f"{b.te_mean_urad:.1f} |",
              f"| transmission error, peak to peak [µrad] | {a.te_p2p_urad:.1f} | "
              f"{b.te_p2p_urad:.1f} |"]
    for tooth in sorted(set(a.shares) | set(b.shares)):
        lines.append(f"| largest load share, tooth {tooth} | {a.shares.get(tooth, 0.0):.3f} | "
                     f"{b.shares.get(tooth, 0.0):.3f} |")
    each = (f"{s.positions} positions" if s.pitches == 1 else
            f"{s.positions} positions a pitch, {s.positions * s.pitches} over the turn")
    lines += ["", f"{len(s.trials)} trials, each over {each}:"]
    lines += [f"  {t.amount_um:7.3f} µm, tip clearance {1e3 * t.tip_clearance_mm:5.1f} µm: "
              + ("off the rounds" if t.off_the_rounds else
                 f"rounds of teeth {sorted(set(t.edge_teeth))} carry {t.edge_load_N:.1f} N")
              + ("" if t.edge_share is None else
                 f" ({100 * t.edge_share:.0f} % of the pairs that turn "
                 + ("had loaded one when it stopped: more than the quantile leaves)"
                    if t.stopped else "load one)"))
              + (f"; {t.left_out} pairs left out, off by the pitch point at a smaller relief"
                 if t.left_out else "")
              for t in s.trials]
    return "\n".join(lines)
