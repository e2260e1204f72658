""""What relief do I need?": the smallest tip relief, of a given extent and shape, that keeps
every loaded contact off gear 1's tip rounds over a mesh cycle.

A trial is a relief amount C solved over ``positions`` rolling angles across one gear-2 pitch;
it passes when no tip round carries load at any of them. The search is done at the torque
raised by the ``margin`` (default +20 %): the approach of the teeth grows about linearly with
the load, so the relief found keeps the rounds unloaded up to that overload. It scans
C = 2, 4, 8, … µm until a trial passes, then bisects to ``tolerance``. A longer relief turns
gear 1 further before the teeth carry the torque, which can close a far-side tip onto its
round (docs/model.md, "Tip relief"): if no amount up to the admissible limit passes, the
search says so and names the extent to change.

The relief found is then solved at the design torque beside the unrelieved pair: flank and
peak pressure, transmission error and load sharing over the cycle.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from ..errors import FegearError, ParameterError
from ..planar import wrap

FIRST_UM = 2.0       # the scan's first amount
MARGIN = 0.2         # torque overload the relief must cover
TOLERANCE_UM = 0.5   # bisection stops when the bracket is this narrow
POSITIONS = 12       # rolling angles per trial
FAR_DEG = 45.0       # teeth farther than this from the pitch point (about O1) are far-side


@dataclass(frozen=True)
class CycleResult:
    """A relief over a mesh cycle: amount (µm), torque (N·m), the largest load on the tip
    rounds at any position (N) and the teeth whose round carried some, the largest flank and
    overall contact pressure (MPa), the transmission error's mean and peak-to-peak (µrad),
    and each tooth's largest load share. Teeth more than ``FAR_DEG`` from the pitch point are
    far-side teeth: their tips meet gear 2's other flanks across the mesh."""

    amount_um: float
    torque: float
    edge_load_N: float
    edge_teeth: tuple[int, ...]
    edge_angles: tuple[float, ...]   # where those teeth stood: ° from the pitch point about O1
    flank_MPa: float
    contact_MPa: float
    te_mean_urad: float
    te_p2p_urad: float
    shares: dict

    @property
    def off_the_rounds(self) -> bool:
        return self.edge_load_N <= 0.0


@dataclass(frozen=True)
class ReliefSizing:
    """The search's trials (at the raised torque), the amount it found (µm), and the pair
    without and with that relief at the design torque."""

    extent_mm: float
    shape: str
    margin: float
    positions: int
    trials: tuple[CycleResult, ...]
    amount_um: float
    without: CycleResult
    with_relief: CycleResult

    def summary(self) -> dict:
        def row(r: CycleResult) -> dict:
            return {k: (list(v) if isinstance(v, tuple) else v) for k, v in r.__dict__.items()}

        return {"relief_um": self.amount_um, "relief_extent_mm": self.extent_mm,
                "relief_shape": self.shape, "margin": self.margin, "positions": self.positions,
                "without_relief": row(self.without), "with_relief": row(self.with_relief),
                "trials": [row(t) for t in self.trials]}


def cycle_result(values: Mapping, amount_um: float, torque: float, positions: int) -> CycleResult:
    """Solve the pair of ``values`` (``fegear solve`` inputs) with a relief of ``amount_um``
    at ``torque`` over ``positions`` rolling angles."""
    from ..geometry import gear1_profile
    from .job import prepare_job
    from .pair import solve_positions

    job = prepare_job({**values, "relief": amount_um, "torque": torque,
                       "positions": positions, "no-estimate": True})
    profile = gear1_profile(job.case.params)
    sols = solve_positions(job.case, job.betas, profile)
    edge = [(t, s.case.beta) for s in sols for t in s.teeth if t.edge_contact]
    p = job.case.params
    angles = {t.tooth: math.degrees(wrap(profile.tooth_center + t.tooth * profile.pitch
                                         + p.ratio * beta - 0.5 * math.pi))
              for t, beta in edge}
    te = [1e6 * (s.rotation - s.first_touch) for s in sols]
    shares: dict[int, float] = {}
    for s in sols:
        for t in s.teeth:
            shares[t.tooth] = max(shares.get(t.tooth, 0.0), t.load_share)
    return CycleResult(
        amount_um=amount_um, torque=torque,
        edge_load_N=max((sum(t.edge_load_N for t in s.teeth) for s in sols), default=0.0),
        edge_teeth=tuple(sorted(angles)), edge_angles=tuple(angles[k] for k in sorted(angles)),
        flank_MPa=max(s.flank_contact_pressure for s in sols),
        contact_MPa=max(s.contact_pressure for s in sols),
        te_mean_urad=sum(te) / len(te), te_p2p_urad=max(te) - min(te),
        shares={k: v for k, v in sorted(shares.items()) if v > 0})


def size_relief(values: Mapping, positions: int = POSITIONS, margin: float = MARGIN,
                tolerance_um: float = TOLERANCE_UM,
                solve: Callable[..., CycleResult] | None = None,
                report: Callable[[str], None] | None = None) -> ReliefSizing:
    """The smallest relief (module docstring) for the pair, torque, extent and shape of
    ``values``; ``solve`` evaluates one trial (values, amount µm, torque, positions) →
    :class:`CycleResult` (default :func:`cycle_result`), ``report`` is told of each trial."""
    from .job import prepare_job

    solve = solve or cycle_result
    # every input checked before any solve, the extent and shape with a relief in place
    params = prepare_job({**values, "relief": FIRST_UM, "positions": positions,
                          "no-estimate": True}).case.params
    torque = float(values.get("torque", 200.0))
    raised = torque * (1.0 + margin)
    limit = 50.0 * params.m                                     # the relief input's range
    trials = []

    def trial(amount: float) -> CycleResult:
        r = solve(values, amount, raised, positions)
        trials.append(r)
        if report:
            where = (f"rounds of teeth {list(r.edge_teeth)} carry {r.edge_load_N:.1f} N"
                     if not r.off_the_rounds else "off the rounds")
            report(f"relief {amount:7.3f} µm at {raised:g} N·m: {where}; flank "
                   f"{r.flank_MPa:.0f} MPa")
        return r

    low, high = 0.0, None
    if not trial(0.0).off_the_rounds:
        amount = FIRST_UM
        while amount <= limit:
            try:
                passed = trial(amount).off_the_rounds
            except ParameterError as exc:   # deeper than the extent can take: the scan ends
                if exc.name != "relief":
                    raise
                break
            if passed:
                high = amount
                break
            low, amount = amount, 2.0 * amount
        if high is None:
            raise FegearError(_no_relief(trials, params.relief_extent, raised))
        while high - low > tolerance_um:
            mid = 0.5 * (low + high)
            if trial(mid).off_the_rounds:
                high = mid
            else:
                low = mid
    else:
        high = 0.0
    without = solve(values, 0.0, torque, positions)
    found = solve(values, high, torque, positions) if high > 0 else without
    return ReliefSizing(params.relief_extent, params.relief_shape, margin, positions,
                        tuple(trials), high, without, found)


def _no_relief(trials, extent: float, torque: float) -> str:
    """Why no amount passed, and what to change."""
    def sides(t):
        far = [k for k, a in zip(t.edge_teeth, t.edge_angles) if abs(a) > FAR_DEG]
        return [k for k in t.edge_teeth if k not in far], far

    why = []
    far = [(t.amount_um, sides(t)[1]) for t in trials if sides(t)[1]]
    if far:
        teeth = sorted({k for _, ks in far for k in ks})
        why.append(f"far-side teeth {teeth} press on their rounds from {far[0][0]:g} µm on "
                   "(their tips meet gear 2 across the mesh; a relief turns gear 1 further "
                   "onto them, a larger tip_clearance keeps them off)")
    near = sides(trials[-1])[0]
    if near:
        why.append(f"teeth {near} by the pitch point still do at {trials[-1].amount_um:g} µm "
                   "(a longer relief_extent reaches further down the flank)")
    else:
        clear = next(t.amount_um for t in trials if not sides(t)[0])
        why.append(f"the rounds by the pitch point are unloaded from {clear:g} µm on")
    return (f"no tip relief over {extent:g} mm keeps the tip rounds unloaded at {torque:g} N·m "
            f"(tried up to {trials[-1].amount_um:g} µm): " + "; ".join(why))


def sizing_table(s: ReliefSizing) -> str:
    """What ``fegear relief`` prints."""
    a, b = s.without, s.with_relief
    lines = [f"tip relief {s.amount_um:.2f} µm, {s.shape}, over {s.extent_mm:g} mm along the "
             f"flank: the smallest that keeps every tip round unloaded over the cycle at "
             f"{(1 + s.margin) * a.torque:g} N·m ({100 * s.margin:.0f} % over {a.torque:g})",
             "",
             f"| over the cycle at {a.torque:g} N·m | no relief | {s.amount_um:.2f} µm |",
             "|---|---:|---:|",
             f"| peak contact pressure [MPa] | {a.contact_MPa:.0f} | {b.contact_MPa:.0f} |",
             f"| flank pressure [MPa] | {a.flank_MPa:.0f} | {b.flank_MPa:.0f} |",
             f"| load on the tip rounds, largest [N] | {a.edge_load_N:.1f} | "
             f"{b.edge_load_N:.1f} |",
             f"| transmission error, mean [µrad] | {a.te_mean_urad:.1f} | {b.te_mean_urad:.1f} |",
             f"| transmission error, peak to peak [µrad] | {a.te_p2p_urad:.1f} | "
             f"{b.te_p2p_urad:.1f} |"]
    for tooth in sorted(set(a.shares) | set(b.shares)):
        lines.append(f"| largest load share, tooth {tooth} | {a.shares.get(tooth, 0.0):.3f} | "
                     f"{b.shares.get(tooth, 0.0):.3f} |")
    lines += ["", f"{len(s.trials)} trials, each over {s.positions} positions:"]
    lines += [f"  {t.amount_um:7.3f} µm: " + ("off the rounds" if t.off_the_rounds else
                                              f"rounds of teeth {list(t.edge_teeth)} carry "
                                              f"{t.edge_load_N:.1f} N")
              for t in s.trials]
    return "\n".join(lines)


def stderr_report(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


