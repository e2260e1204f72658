"""Admissibility: the designs fegear builds and solves, and the range a refusal states.

A design is admissible when gear 1 can be built and the assembled pair is free before any load.
Each condition is a boundary of the design space (``fegear profile --map``, docs/geometry.md):

* ``loop``: the gear-2 curve, nominal or the Δ2 tool, is not star-shaped about its centre
  (``P × P' <= 0`` somewhere: its flank folds back or loops), which the profile code needs;
* ``undercut``: gear 1's working flank does not run unbroken from the middle of the tooth space
  to its tip corner (a cusp of the working branch, or another branch, cuts it);
* ``no conjugate``: gear 1's profile has a gap where a branch ends at a fold (a stretch of gear
  2 with no conjugate point) and nothing closes it;
* ``interference``: somewhere, at some rolling angle, gear 1 is nearer gear 2 than
  :data:`CLEARANCE` before any load. Gear 1 clears the nominal gear 2 at every rolling angle
  exactly when its polar radius stays below the exact conjugate's (the complement of gear 2's
  swept body) at every polar angle, so the test compares two exact profiles;
* ``relief``: the tip relief does not fit the flank (:mod:`.relief`).

Stretches of gear 2 whose normal misses the instantaneous-centre circle have no conjugate
point; they never shape gear 1 and are left out (:func:`~.gear1._split_runs`). They are a
boundary only where they break the profile (``undercut``, ``no conjugate``).

A refused design names one input the user set, with the interval of that input, at the other
inputs' values, in which the design is admissible (found by bisection from an admissible
value; every default derived from it follows, as a user would get it), and a second input that
fixes it as an alternative. The defaults of the modifications follow rules that keep the pair
free (:func:`resolve`, docs/cli.md).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from ..errors import ParameterError
from .gear1 import Gear1Profile, gear1_profile
from .gear2 import gear2_curve
from .parameters import H1_MIN, PAIR_INPUTS, PairParameters, built_modification

CLEARANCE = 1e-5        # mm: the least clearance before any load (10 nm: touching profiles
                        # are refused, the clearance table cannot tell their sides apart)
TIP_FLOOR = 0.001       # the tip clearance's default is at least this many modules
HALVINGS = 6            # the rotation's default is halved at most this often (to 1/64)
JOIN_TOL = 1e-6         # mm: a jump in gear 1's radius at a piece junction larger is a gap
                        # (the gaps found are µm; junctions round to 0.2 nm)
PROFILE_SAMPLES = 1024  # polar angles per pitch for the clearance against the conjugate
BISECT = 60             # bisection steps at most

#: the reasons, as a message gives them
REASONS = {
    "loop": "the gear-2 curve folds back (it is not star-shaped about its centre)",
    "undercut": "gear 1 would be undercut (its working flank is cut before the tip)",
    "no conjugate": "gear 1's tip needs a conjugate point that gear 2's far side does not "
                    "have",
    "interference": "gear 1 is not clear of gear 2 before any load",
    "relief": "the tip relief does not fit the flank",
}
#: the inputs that fix each kind of defect, the first preferred where the user set none of them
FIXES = {"loop": ("f1", "h1"), "undercut": ("h1", "f1"), "no conjugate": ("h1", "f1"),
         "relief": ("relief", "relief-extent", "relief-start")}


@dataclass(frozen=True)
class Defect:
    """Why a design is not admissible: ``kind`` (a key of :data:`REASONS`), the reason as a
    message gives it, and the inputs that can fix it (preferred first)."""

    kind: str
    reason: str
    fixes: tuple[str, ...]


def curves_defect(p: PairParameters) -> Defect | None:
    """``loop`` if the nominal or the tool curve of gear 2 is not star-shaped (cheap)."""
    if not all(gear2_curve(p, tool).star_shaped() for tool in (False, True)):
        return Defect("loop", REASONS["loop"], FIXES["loop"])
    return None


def defect(p: PairParameters) -> Defect | None:
    """Why ``p`` is not admissible, or ``None``. Builds gear 1 (kept by
    :func:`~.gear1.gear1_profile`) and the exact conjugate it is compared with."""
    found = curves_defect(p)
    if found is not None:
        return found
    try:
        g = gear1_profile(p)
    except ParameterError as exc:   # the relief does not fit
        return Defect("relief", f"{REASONS['relief']}: {exc.reason or exc.admissible}",
                      FIXES["relief"])
    return profile_defect(g) or interference(g)


def profile_defect(g: Gear1Profile) -> Defect | None:
    """``undercut`` or ``no conjugate`` from the pieces of a built gear 1."""
    pieces = g.pieces
    for a, b in zip(pieces[:-1], pieces[1:]):
        jump = abs(float(np.diff(g.radius(np.array([a.phi1 - 1e-13, b.phi0 + 1e-13])))[0]))
        if jump > JOIN_TOL:
            return Defect("no conjugate", REASONS["no conjugate"], FIXES["no conjugate"])
    first, last = pieces[0], pieces[-1]
    middle = g.phi_space + 0.5 * g.pitch
    for flank, after in ((first, pieces[1]), (last, pieces[-2])):
        reaches_middle = abs(flank.phi1 - middle) < 1e-9 or abs(flank.phi0 - middle) < 1e-9
        if flank.run.branch != 0 or (after.run.branch == 0 and not reaches_middle):
            return Defect("undercut", REASONS["undercut"], FIXES["undercut"])
    return None


def conjugate_of(p: PairParameters) -> PairParameters:
    """The exact conjugate of ``p``'s gear 2: no shift, no rotation, no tip clearance, no
    relief (the largest gear 1 that clears gear 2 at every rolling angle)."""
    return PairParameters(m=p.m, z2=p.z2, z1=p.z1, h1=p.h1, f1=p.f1, tip_clearance=0.0)


def clearance(g: Gear1Profile) -> float:
    """The least clearance (mm) of gear 1 to the nominal gear 2 over every rolling angle: the
    least radius difference to the exact conjugate at one polar angle."""
    c = gear1_profile(conjugate_of(g.params))
    ends = np.array([pc.phi0 for pc in (*g.pieces, *c.pieces)])
    phi = np.concatenate([g.phi_space + g.pitch * np.linspace(0.0, 1.0, PROFILE_SAMPLES),
                          ends, np.nextafter(ends, np.inf), np.nextafter(ends, -np.inf)])
    return float(np.min(c.radius(phi) - g.radius(phi)))


def interference(g: Gear1Profile) -> Defect | None:
    """``interference`` if gear 1 comes nearer gear 2 than :data:`CLEARANCE` before any load.
    It is at the tip if the largest tip clearance frees it (the tip clearance fixes it), else
    on the working flank (the rotation and the shift fix it)."""
    gap = clearance(g)
    if gap >= CLEARANCE:
        return None
    p = g.params
    trimmed = _built(replace(p, tip_clearance=p.e1))
    at_tip = trimmed is not None and clearance(trimmed) >= CLEARANCE
    how = f"overlaps it by {-gap * 1e3:.3g} µm" if gap < 0 else (
        f"comes within {gap * 1e3:.2g} µm of it")
    where, fixes = ("tip", ("tip-clearance",)) if at_tip else ("working flank",
                                                               ("rotation", "shift"))
    return Defect("interference", f"{REASONS['interference']}: its {where} {how}", fixes)


# --- the inputs as a user gives them -------------------------------------------------------
def resolve(values: Mapping[str, object]) -> PairParameters:
    """The pair of the pair inputs given by name (:data:`~.parameters.PAIR_INPUTS`), missing
    ones at their defaults, without the admissibility check. The modifications' defaults
    (docs/cli.md):

    * shift: 0.008 m, at most m h1/4 (the seed paper's 0.016 mm at m = 2);
    * tip clearance: the shift, at least :data:`TIP_FLOOR` m;
    * rotation: 0.001 m, at most m h1/4; where that leaves gear 1 nearer gear 2 than
      :data:`CLEARANCE` (the rotation takes more backlash than the shift gives), halved until
      it does not, at most :data:`HALVINGS` times, then none.
    """
    v = {row.name: values.get(row.name, row.default) for row in PAIR_INPUTS}
    try:
        m, h1 = float(v["m"]), float(v["h1"])
    except (TypeError, ValueError):
        m, h1 = 0.0, 0.0   # the parameters refuse m or h1 first
    if v["shift"] is None:
        v["shift"] = built_modification("shift", m, h1)
    if v["tip-clearance"] is None:
        try:
            v["tip-clearance"] = max(float(v["shift"]), TIP_FLOOR * m)
        except (TypeError, ValueError):
            pass            # the parameters refuse the shift
    derived_rotation = v["rotation"] is None
    if derived_rotation:
        v["rotation"] = built_modification("rotation", m, h1)
    p = PairParameters(**{row.dest: v[row.name] for row in PAIR_INPUTS})
    if derived_rotation:
        p = _rotation_default(p)
    return p


@lru_cache(maxsize=4096)
def _rotation_default(p: PairParameters) -> PairParameters:
    """``p`` with the rotation's default rule applied (see :func:`resolve`): the rotation
    halved, up to :data:`HALVINGS` times, until the pair is clear before any load. The
    clearance falls about linearly with the rotation, so the number of halvings is first
    estimated from the clearance with none, then checked."""
    if curves_defect(p) is not None:
        return p

    def gap(k: int) -> float:
        g = _built(replace(p, rotation=p.rotation / 2**k) if k else p)
        if g is None or profile_defect(g) is not None:
            return -math.inf
        return clearance(g) - CLEARANCE

    at_default = gap(0)
    if at_default >= 0 or at_default == -math.inf:
        return p
    g0 = _built(replace(p, rotation=0.0))
    free = -math.inf if g0 is None or profile_defect(g0) else clearance(g0) - CLEARANCE
    if free < 0:
        return replace(p, rotation=0.0) if free == -math.inf else p   # none frees it
    share = free / (free - at_default)          # the fraction of the default that closes it
    k = min(HALVINGS, max(1, math.ceil(math.log2(1.0 / share))))
    while k < HALVINGS and gap(k) < 0:
        k += 1
    while k > 1 and gap(k - 1) >= 0:             # the rule: the fewest halvings that free it
        k -= 1
    return replace(p, rotation=p.rotation / 2**k if gap(k) >= 0 else 0.0)


def _built(p: PairParameters) -> Gear1Profile | None:
    try:
        return gear1_profile(p)
    except ParameterError:
        return None


def design_defect(values: Mapping[str, object]) -> Defect | None:
    """The defect of the design given by input values (defaults derived as :func:`resolve`
    does); an input outside its static range is a defect too."""
    try:
        p = resolve(values)
    except ParameterError as exc:
        return Defect("range", str(exc), (exc.name,))
    return defect(p)


# --- the ranges a refusal states --------------------------------------------------------------
#: the inputs a geometry refusal may blame, with their static bounds (at the other inputs)
def _span(name: str, values: Mapping[str, object]) -> tuple[float, float] | None:
    p = _loose(values)
    if p is None:
        return None
    e1 = p.m * p.h1
    spans = {"h1": (H1_MIN, min(2.0, 0.999 * p.z2 / 4)), "f1": (0.0, 1.0),
             "shift": (0.0, 0.25 * e1), "rotation": (-0.25 * e1, 0.25 * e1),
             "tip-clearance": (0.0, e1),
             "relief": (0.0, 50.0 * p.m), "relief-extent": (1e-4 * p.m, 2.0 * p.m),
             "relief-start": (p.r1 - 2 * p.m, p.r1 + 2 * p.m)}
    return spans.get(name)


def _loose(values: Mapping[str, object]) -> PairParameters | None:
    """The pair at the given values with the modifications left unmodified, for spans."""
    v = {k: values[k] for k in ("m", "z2", "z1", "h1", "f1") if values.get(k) is not None}
    try:
        return PairParameters(**v)
    except ParameterError:
        return None


#: the inputs a refusal may name with an interval
SEARCHED = ("h1", "f1", "rotation", "shift", "tip-clearance", "relief", "relief-extent",
            "relief-start")
#: values of each input to start the search from, tried first (then a grid over its span)
ANCHORS = {"h1": (0.3, 0.2, 0.1, 0.5), "f1": (0.15, 0.1, 0.0, 0.3), "relief": (0.0,),
           "rotation": (0.0,), "tip-clearance": (0.016,), "shift": (0.016,)}
RESOLUTION = 2e-4       # an input's interval is found to this fraction of its span, and
CHECKS = 2              # checked at this many designs inside it


_MARGINS: dict[tuple, float] = {}   # margin of each design asked for, in this process


def margin(values: Mapping[str, object]) -> float:
    """How far the design given by input values is inside the admissible set: its least
    clearance before any load less :data:`CLEARANCE` (mm, continuous in the modifications),
    or ``-inf`` for any other defect. Kept for the designs asked for before (a refusal's
    searches ask for many, and several refusals of one design for the same)."""
    key = tuple(sorted((k, v) for k, v in values.items() if v is not None))
    if key not in _MARGINS:
        if len(_MARGINS) > 50_000:
            _MARGINS.clear()
        _MARGINS[key] = _margin(values)
    return _MARGINS[key]


def _margin(values: Mapping[str, object]) -> float:
    try:
        p = resolve(values)
    except ParameterError:
        return -math.inf
    if curves_defect(p) is not None:
        return -math.inf
    g = _built(p)
    if g is None or profile_defect(g) is not None:
        return -math.inf
    return clearance(g) - CLEARANCE


def _curves_ok(values: Mapping[str, object]) -> bool:
    """The cheap part of the test: the static ranges and the gear-2 curves (milliseconds)."""
    v = {row.name: values.get(row.name, row.default) for row in PAIR_INPUTS}
    try:
        m, h1 = float(v["m"]), float(v["h1"])
        for name in ("shift", "rotation"):
            if v[name] is None:
                v[name] = built_modification(name, m, h1)
        p = PairParameters(**{row.dest: v[row.name] for row in PAIR_INPUTS
                              if row.name != "tip-clearance"})
    except (ParameterError, TypeError, ValueError):
        return False
    return curves_defect(p) is None


def _edge(f, good: float, bad: float, tol: float) -> float:
    """The last admissible value from ``good`` (f >= 0) towards ``bad`` (f < 0), to ``tol``:
    regula falsi with the Illinois step where both ends have finite margins (the clearance
    is smooth in the modifications), a bisection elsewhere and after any step that did not
    halve the bracket (a margin can jump where a default's rule starts)."""
    fg, fb = f(good), f(bad)
    side, width = 0, abs(bad - good)
    for _ in range(BISECT):
        if abs(bad - good) <= tol:
            break
        x = 0.5 * (good + bad)
        interpolate = math.isfinite(fb) and math.isfinite(fg) and fg > fb
        if interpolate and abs(bad - good) <= 0.5 * width:
            x = bad - fb * (bad - good) / (fb - fg)
            if not min(good, bad) < x < max(good, bad):
                x = 0.5 * (good + bad)
        width = abs(bad - good)
        fx = f(x)
        if fx >= 0:
            good, fg = x, fx
            if side == +1 and math.isfinite(fb):
                fb *= 0.5       # Illinois: the end kept twice has its value halved
            side = +1
            if fx < 1e-2 * CLEARANCE:   # on the boundary, on its admissible side
                break
        else:
            bad, fb = x, fx
            if side == -1 and math.isfinite(fg):
                fg *= 0.5
            side = -1
    return good


def interval(values: Mapping[str, object], name: str, resolution: float = RESOLUTION,
             checks: int = CHECKS) -> tuple[float, float] | None:
    """The interval of input ``name``, at the other inputs' values, in which the design is
    admissible, nearest the value given (``None`` if there is none in the input's span). From
    an admissible value, each end is found towards the given value (a known bad one) or the
    span's end: first with the cheap test alone, then with the whole one from where that
    stopped (the admissible values of one input are taken to be one interval, as every test
    and the sweeps of docs/geometry.md find them), to ``resolution`` of the span, and checked
    at ``checks`` designs inside."""
    span = _span(name, values)
    if span is None:
        return None
    lo, hi = span
    tol = resolution * (hi - lo)
    memo: dict[float, float] = {}

    def full(x: float) -> float:
        if x not in memo:
            memo[x] = margin({**values, name: x})
        return memo[x]

    def cheap(x: float) -> float:
        return math.inf if _curves_ok({**values, name: x}) else -math.inf

    def ok(x: float) -> bool:
        return cheap(x) >= 0 and full(x) >= 0

    given = values.get(name)
    target = float(given) if isinstance(given, (int, float)) else None
    grid = sorted(np.linspace(lo, hi, 9), key=lambda a: abs(a - (target or 0.0)))
    first = [a * (values.get("m") or 2.0) / 2.0 if name in ("tip-clearance", "shift") else a
             for a in ANCHORS.get(name, ())]
    anchor = next((a for a in [*first, *grid] if lo <= a <= hi and ok(a)), None)
    if anchor is None:
        return None
    ends = []
    for end in (lo, hi):
        if target is not None and min(anchor, end) <= target <= max(anchor, end) and \
                not ok(target):
            end = target            # the given value is refused: the edge lies before it
        elif ok(end):
            ends.append(end)
            continue
        edge = end if cheap(end) >= 0 else _edge(cheap, anchor, end, tol)
        ends.append(edge if full(edge) >= 0 else _edge(full, anchor, edge, tol))
    # the interval is checked at a few designs inside it; one that is refused (a pocket the
    # search stepped over) shortens it to the edge before that design
    for x in np.linspace(ends[0], ends[1], checks + 2)[1:-1]:
        if ends[0] < x < ends[1] and not ok(x):
            side = 0 if x < anchor else 1
            ends[side] = _edge(full, anchor, x, tol)
    return ends[0], ends[1]


def _range_text(name: str, bounds: tuple[float, float], values: Mapping[str, object]) -> str:
    """``lo <= name <= hi unit``, rounded inwards so that both ends hold."""
    unit = {"shift": " mm", "rotation": " mm", "tip-clearance": " mm", "relief": " µm",
            "relief-extent": " mm", "relief-start": " mm"}.get(name, "")
    lo, hi = bounds
    digits = 4 if unit in ("", " µm") else 5
    scale = 10.0 ** digits
    lo_t = math.ceil(lo * scale - 1e-9) / scale
    hi_t = math.floor(hi * scale + 1e-9) / scale
    fmt = f"{{:.{digits}f}}"
    return f"{fmt.format(lo_t)} <= {name} <= {fmt.format(hi_t)}{unit}"


def _others(values: Mapping[str, object], name: str) -> str:
    p = _loose(values)
    keys = [k for k in ("h1", "f1", "m", "z2", "z1") if k != name]
    text = ", ".join(f"{k}={getattr(p, k):g}" for k in keys) if p else ""
    relieved = bool(values.get("relief"))
    set_ = [k for k in ("shift", "rotation", "tip-clearance", "relief", "relief-extent",
                        "relief-start")
            if k != name and values.get(k) is not None
            and (relieved or not k.startswith("relief"))]
    return text + "".join(f", {k}={values[k]:g}" for k in set_)


def check_design(values: Mapping[str, object], given: Iterable[str] | None = None
                 ) -> PairParameters:
    """The pair of the inputs given by name, checked: raises :class:`ParameterError` naming
    the input the user changed (``given``; default: those in ``values`` not None) that fixes
    the defect, with its admissible interval at the other inputs' values and another input's
    as an alternative."""
    values = {k: v for k, v in values.items() if v is not None}
    try:
        p = resolve(values)
    except ParameterError as exc:   # a static range: told as the admissible interval
        finite = isinstance(exc.value, (int, float)) and math.isfinite(exc.value)
        bounds = interval(values, exc.name) if exc.name in ANCHORS and finite else None
        if bounds is None:
            raise
        raise ParameterError(exc.name, exc.value, f"{_range_text(exc.name, bounds, values)} "
                             f"at {_others(values, exc.name)}", exc.reason) from None
    found = defect(p)
    if found is None:
        return p
    given = set(values if given is None else given)
    candidates = [f for f in found.fixes if f in given] or list(found.fixes)
    ranges = {}
    for name in found.fixes:   # the alternatives only roughly (the printed digits hold)
        bounds = interval(values, name) if name in candidates[:1] or found.kind in (
            "undercut", "no conjugate") else interval(values, name, 10 * RESOLUTION, 0)
        if bounds is not None:
            ranges[name] = bounds
    usable = [c for c in candidates if c in ranges]
    if not usable:   # none of the usual fixes works here: another input the user set may
        for name in (n for n in SEARCHED if n in given and n not in ranges):
            bounds = interval(values, name)
            if bounds is not None:
                ranges[name], usable = bounds, [name]
                break
    if found.kind in ("undercut", "no conjugate") and len(usable) > 1:
        usable.sort(key=lambda c: _relative_change(getattr(p, c), ranges[c]))
    if not usable:
        name = candidates[0]
        raise ParameterError(name, _value(p, name), f"none at {_others(values, name)}",
                             found.reason)
    name = usable[0]
    alternatives = [f for f in found.fixes if f != name and f in ranges]
    extra = f" (or {_range_text(alternatives[0], ranges[alternatives[0]], values)})" if (
        alternatives) else ""
    raise ParameterError(name, _value(p, name), f"{_range_text(name, ranges[name], values)} "
                         f"at {_others(values, name)}{extra}", found.reason)


def _value(p: PairParameters, name: str) -> float:
    return {"tip-clearance": p.radial_tip_clearance}.get(name, getattr(p, name.replace("-", "_"),
                                                                       None))


def _relative_change(value: float, bounds: tuple[float, float]) -> float:
    lo, hi = bounds
    if lo <= value <= hi:
        return 0.0
    edge = hi if value > hi else lo
    return abs(value - edge) / max(abs(value), 1e-12)


def admissible_pair(values: Mapping[str, object],
                    given: Iterable[str] | None = None) -> PairParameters:
    """The pair of the pair inputs given by name (missing ones at their defaults,
    :func:`resolve`), checked for an admissible geometry before any work starts: a refused
    design is blamed on an input the user set (:func:`check_design`)."""
    pair = {row.name: values.get(row.name) for row in PAIR_INPUTS}
    if given is None:
        given = (k for k, x in pair.items() if x is not None)
    return check_design(pair, {g for g in given if g in pair})


def check_admissible(p: PairParameters, given: Iterable[str] = ()) -> None:
    """Raise :class:`ParameterError` if ``p`` is not admissible (blaming an input of
    ``given`` where it can)."""
    check_design(_values_of(p), given)


def _values_of(p: PairParameters) -> dict[str, object]:
    out = {row.name: getattr(p, row.dest) for row in PAIR_INPUTS}
    out["tip-clearance"] = p.radial_tip_clearance
    return out


