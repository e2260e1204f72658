"""A tolerance class over a whole revolution, screened: each pair solved at every pitch at a
few of the cycle's places (the scouts), then at the positions about the scouts that came
nearest its largest (docs/tolerance.md, "The revolution screened").

A pair's worst over a revolution is an event of one tooth (its root loaded hardest, its tip
round striking as it comes into mesh, its flank taking the load the round gave up) that
lasts a few of the cycle's places and recurs for every tooth. The scouts, :data:`SCOUTS`
places a pitch evenly apart, see every tooth's events from no more than half a pitch away;
each headline's scouts within its margin (:data:`MARGINS`) of that pair's largest scout are
then solved about, at every position nearer than the next scout on either side (a flank's
pressure before it alone: :data:`BEFORE`), and the revolution's last places (which no scout
follows) too. Nothing is estimated: every stress a row gives is a solve's, and a row is the
largest of the positions solved. What the screen can miss is an event that no scout near it
shows within the margin; the margins were set on the whole revolutions of 400 pairs and
checked on 200 more, of another class and design (docs/tolerance.md).

The positions are numbered along the revolution, place by place within each pitch:
``r = n * places + i`` for place i, n gear-2 pitches on.
"""

from __future__ import annotations

import numpy as np

from .chains import Chains, work_of
from .rows import gathered

#: the cycle's places a pitch at which every pair is solved at every pitch
SCOUTS = 2
#: by headline, how close (a share of its largest) a scout must come to the pair's largest to
#: be solved about: the roots' maxima are broad, the pressures' (a round striking, a flank
#: taking over from the round) last a place or two and the scouts see them decayed
MARGINS = {"root_stress_gear1_MPa": 0.04, "root_stress_gear2_MPa": 0.04,
           "contact_pressure_MPa": 0.08, "flank_contact_pressure_MPa": 0.12,
           "von_mises_max_MPa": 0.08}
#: headlines solved about a scout only before it: a flank's largest pressure is where it
#: takes the load over from its tip round, a jump that the scout after it sees decaying
#: (by up to a fifth over half a pitch) and the scout before it not at all
BEFORE = frozenset({"flank_contact_pressure_MPa"})


def scout_places(places: int) -> list[int] | None:
    """The places (of a cycle's ``places``) every pitch is solved at, :data:`SCOUTS` evenly
    apart; None where a cycle has too few places for a screen to spare any (fewer than two a
    scout)."""
    if places < 2 * SCOUTS:
        return None
    return list(range(0, places, places // SCOUTS))[:SCOUTS]


def about_scouts(scouted: dict[int, dict], places: int, pitches: int) -> set[int]:
    """The positions (along the revolution: module docstring) to solve a pair at after its
    scouts (``scouted``: headline by position), beyond those: about each headline's scouts
    within its margin of its largest, every position nearer than the next scout either side
    (before it alone for :data:`BEFORE`), and the revolution's last places."""
    spacing = places // SCOUTS
    end = places * pitches
    wanted = set(range(end - spacing + 1, end))
    at = sorted(scouted)
    for key, margin in MARGINS.items():
        values = np.array([scouted[r][key] for r in at])
        after = 1 if key in BEFORE else spacing
        for r in np.array(at)[values >= (1.0 - margin) * values.max()]:
            wanted.update(range(max(int(r) - spacing + 1, 0), min(int(r) + after, end)))
    return wanted - set(scouted)


def screened(run: Chains, free: list[int], scouts: list[int], pitches: int):
    """A revolution screened (module docstring): the ``free`` samples at every pitch at the
    ``scouts`` places, then each at the positions about its scouts nearest its largest
    (:func:`about_scouts`): the exact pair's solutions by position, what the chains
    gave at both, and the positions solved a sample (mean)."""
    states = run.states
    places = len(states.loaded)
    nominal, chains = run(work_of(free, scouts, pitches, run.parts))
    along = {states.beta(i, n): n * places + i for i in scouts for n in range(pitches)}
    scouted = gathered(chains)[0]
    jobs: dict[int, list[tuple[int, int]]] = {i: [] for i in range(places) if i not in scouts}
    count = len(scouts) * pitches * len(free)
    for k in free:
        got = scouted.get(k, [])
        if any(isinstance(head, str) for _, head in got):   # failed: its row says why
            continue
        wanted = about_scouts({along[beta]: head for beta, head in got}, places, pitches)
        for r in sorted(wanted):
            jobs[r % places].append((k, r // places))
        count += len(wanted)
    rest = list(jobs)   # each, where no sample is solved, for the exact pair's solution
    more_nominal, more = run([(rest[k::run.parts], jobs) for k in range(run.parts)
                              if rest[k::run.parts]], exact=False)
    return {**more_nominal, **nominal}, [*chains, *more], count / max(len(free), 1)
