"""A tolerance class over a whole revolution, screened: each pair solved at every pitch at a
few of the cycle's places (the scouts), then at every other position about the scouts that
came nearest its largest, then beside those that came nearest (docs/tolerance.md, "The
revolution screened").

A pair's worst over a revolution is an event of one tooth (its root loaded hardest, its tip
round striking as it comes into mesh, its flank taking the load the round gave up) that
lasts a few of the cycle's places and recurs for every tooth. The scouts, :data:`SCOUTS`
places a pitch evenly apart, see every tooth's events from no more than half a pitch away;
each headline's scouts within its margin (:data:`MARGINS`) of that pair's largest scout are
then solved about, at every :data:`STRIDE`-th position nearer than the next scout on either
side (a flank's pressure before it alone: :data:`BEFORE`), and at the revolution's last
places (which no scout follows) at every one; last, each headline's positions solved within
half its margin of the pair's largest so far are solved beside at the positions between
them and the next solved ones. Nothing is estimated: every stress a row gives is a solve's,
and a row is the largest of the positions solved. What the screen can miss is an event that
no scout near it shows within the margin, or that falls between two positions of the second
round that both show it more than half the margin down; the margins were set on the whole
revolutions of 400 pairs and checked on 200 more, of another class and design, the stride on
600 and checked on 200 more (docs/tolerance.md).

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
#: taking over from the round) last a place or two and the scouts see them decayed; a
#: position of the second round, half as close to be solved beside
MARGINS = {"root_stress_gear1_MPa": 0.04, "root_stress_gear2_MPa": 0.04,
           "contact_pressure_MPa": 0.08, "flank_contact_pressure_MPa": 0.12,
           "von_mises_max_MPa": 0.08}
#: headlines solved about a scout only before it: a flank's largest pressure is where it
#: takes the load over from its tip round, a jump that the scout after it sees decaying
#: (by up to a fifth over half a pitch) and the scout before it not at all
BEFORE = frozenset({"flank_contact_pressure_MPa"})
#: about a scout, every this-many-th position is solved first (where the scouts stand more
#: than this apart), the ones between them after, beside those nearest the largest
STRIDE = 2


def scout_places(places: int) -> list[int] | None:
    """The places (of a cycle's ``places``) every pitch is solved at, :data:`SCOUTS` evenly
    apart; None where a cycle has too few places for a screen to spare any (fewer than two a
    scout)."""
    if places < 2 * SCOUTS:
        return None
    return list(range(0, places, places // SCOUTS))[:SCOUTS]


def stride_of(places: int) -> int:
    """The stride about the scouts for a cycle of ``places``: :data:`STRIDE` where the
    scouts stand further apart, else every position."""
    return STRIDE if places // SCOUTS > STRIDE else 1


def about_scouts(scouted: dict[int, dict], places: int, pitches: int) -> set[int]:
    """The positions (along the revolution: module docstring) to solve a pair at after its
    scouts (``scouted``: headline by position), beyond those: about each headline's scouts
    within its margin of its largest, every :func:`stride_of`-th position nearer than the
    next scout either side (before it alone for :data:`BEFORE`), and every one of the
    revolution's last places."""
    spacing, stride = places // SCOUTS, stride_of(places)
    end = places * pitches
    wanted = set(range(end - spacing + 1, end))
    at = sorted(scouted)
    for key, margin in MARGINS.items():
        values = np.array([scouted[r][key] for r in at])
        after = 1 if key in BEFORE else spacing
        for r in np.array(at)[values >= (1.0 - margin) * values.max()]:
            first = int(r) - (spacing - 1) // stride * stride
            wanted.update(range(max(first, int(r) % stride), min(int(r) + after, end), stride))
    return wanted - set(scouted)


def beside_largest(solved: dict[int, dict], places: int, pitches: int) -> set[int]:
    """The positions to solve a pair at last (``solved``: headline by position, the scouts'
    and :func:`about_scouts`'): beside each headline's positions within half its margin of
    its largest, those nearer than the next position of the stride either side (before it
    alone for :data:`BEFORE`), not solved yet."""
    stride, end = stride_of(places), places * pitches
    wanted: set[int] = set()
    at = np.array(sorted(solved))
    for key, margin in MARGINS.items():
        values = np.array([solved[r][key] for r in at])
        after = 1 if key in BEFORE else stride
        for r in at[values >= (1.0 - margin / 2) * values.max()]:
            wanted.update(range(max(int(r) - stride + 1, 0), min(int(r) + after, end)))
    return wanted - set(solved)


def screened(run: Chains, free: list[int], scouts: list[int], pitches: int):
    """A revolution screened (module docstring): the ``free`` samples at every pitch at the
    ``scouts`` places, then each about its scouts nearest its largest (:func:`about_scouts`),
    then beside its positions nearest its largest (:func:`beside_largest`): the exact pair's
    solutions by position, what the chains gave at all three, and the positions solved a
    sample (mean)."""
    states = run.states
    places = len(states.loaded)
    nominal, chains = run(work_of(free, scouts, pitches, run.parts))
    along = {states.beta(i, n): n * places + i for i in range(places) for n in range(pitches)}
    count = len(scouts) * pitches * len(free)
    rounds = [chains]
    for choose in (about_scouts, beside_largest):
        found = gathered([c for done in rounds for c in done])[0]
        jobs: dict[int, list[tuple[int, int]]] = {i: [] for i in range(places)}
        for k in free:
            got = found.get(k, [])
            if any(isinstance(head, str) for _, head in got):   # failed: its row says why
                continue
            for r in sorted(choose({along[beta]: head for beta, head in got}, places, pitches)):
                jobs[r % places].append((k, r // places))
                count += 1
        more_nominal, more = _solved_at(run, jobs, nominal)
        nominal = {**more_nominal, **nominal}
        rounds.append(more)
    return nominal, [c for done in rounds for c in done], count / max(len(free), 1)


def _solved_at(run: Chains, jobs: dict[int, list], nominal: dict):
    """The chains of ``jobs`` (by place, (sample, pitch) pairs) at the places that ask for a
    solve, or that have no exact pair's solution in ``nominal`` yet (the class's nominal
    row); none where none does."""
    rest = [i for i in jobs if jobs[i] or i not in nominal]
    if not rest:
        return {}, []
    return run([(rest[k::run.parts], jobs) for k in range(run.parts) if rest[k::run.parts]],
               exact=False)
