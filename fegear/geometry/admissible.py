"""Admissibility: the designs fegear builds and solves.

A design is admissible when gear 1 can be built and the assembled pair is free before any load.
Each condition is a boundary of the design space (``fegear profile --map``, docs/geometry.md):

* ``loop``: the gear-2 curve, nominal or the Δ2 tool, is not star-shaped about its centre
  (``P × P' <= 0`` somewhere: its flank folds back or loops), which the profile code needs;
* ``undercut``: gear 1's working flank does not run unbroken from the middle of the tooth space
  to its tip corner (a cusp of the working branch, or another branch, cuts it);
* ``no conjugate``: gear 1's profile has a gap where a branch ends at a fold (a stretch of gear
  2 with no conjugate point) and nothing closes it;
* ``interference``: somewhere, at some rolling angle, gear 1 overlaps gear 2 before any load
  by more than the profiles' rounding (:func:`overlap_tolerance`). Gear 1 clears the nominal
  gear 2 at every rolling angle exactly when its polar radius stays below the exact
  conjugate's (the complement of gear 2's swept body) at every polar angle, so the test
  compares two exact profiles. Touching is admissible: the exact conjugate itself (no shift,
  no rotation) touches gear 2 on every tooth of the line of action;
* ``relief``: the tip relief does not fit the flank (:mod:`.relief`).

Stretches of gear 2 whose normal misses the instantaneous-centre circle have no conjugate
point; they never shape gear 1 and are left out (:mod:`.runs`). They are a boundary only where
they break the profile (``undercut``, ``no conjugate``).

The defaults of the modifications follow rules that keep the pair free (:func:`resolve`,
docs/cli.md). A refused design is told by :mod:`.refusal`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from ..errors import ParameterError
from .gear1 import Gear1Profile, gear1_profile
from .gear2 import gear2_curve
from .parameters import PAIR_INPUTS, PairParameters, built_modification

ROUNDING = 1e-12        # of the pitch radius: the overlap of two exact profiles that is
                        # rounding (the worst of 1700 touching designs, m 0.3-50, z2 12-400:
                        # 7e-15; a µm is 2e-5 of the baseline's 45 mm)
TIP_FLOOR = 0.001       # the tip clearance's default is at least this many modules
HALVINGS = 6            # the rotation's default is halved at most this often (to 1/64)
JOIN_TOL = 1e-6         # mm: a jump in gear 1's radius at a piece junction larger is a gap
                        # (the gaps found are µm; junctions round to 0.2 nm)
PROFILE_SAMPLES = 1024  # polar angles per pitch for the clearance against the conjugate

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


@lru_cache(maxsize=64)
def defect(p: PairParameters) -> Defect | None:
    """Why ``p`` is not admissible, or ``None``. Builds gear 1 (kept by
    :func:`~.gear1.gear1_profile`) and the exact conjugate it is compared with. Kept for the
    last few pairs, as gear 1 is: a study's cases of one pair at other torques each check
    it."""
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
    # the working flanks are the first and the last piece (from the middles of the tooth
    # spaces); each runs to the tip trim, or into the other when the near branch makes the
    # whole tooth; another near-branch piece after it is a cusp's (an undercut)
    first, last = pieces[0], pieces[-1]
    for flank, after in ((first, pieces[1]), (last, pieces[-2])):
        into_the_other = len(pieces) == 2
        if flank.run.branch != 0 or (after.run.branch == 0 and not into_the_other):
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


def overlap_tolerance(p: PairParameters) -> float:
    """The largest overlap (mm) of gear 1 and gear 2 that is the profiles' rounding, not an
    interference: :data:`ROUNDING` of the pitch radius."""
    return ROUNDING * p.r0


def clearance_margin(g: Gear1Profile) -> float:
    """How far (mm) the pair is from interfering: its least clearance before any load plus
    the rounding it tolerates; >= 0 where admissible, continuous in the modifications."""
    return clearance(g) + overlap_tolerance(g.params)


def interference(g: Gear1Profile) -> Defect | None:
    """``interference`` if gear 1 overlaps gear 2 before any load beyond rounding. It is at
    the tip if the largest tip clearance frees it (the tip clearance fixes it), else on the
    working flank (the rotation and the shift fix it)."""
    if clearance_margin(g) >= 0:
        return None
    gap = clearance(g)
    p = g.params
    trimmed = _built(replace(p, tip_clearance=p.e1))
    at_tip = trimmed is not None and clearance_margin(trimmed) >= 0
    where, fixes = ("tip", ("tip-clearance",)) if at_tip else ("working flank",
                                                               ("rotation", "shift"))
    return Defect("interference", f"{REASONS['interference']}: its {where} overlaps it by "
                  f"{-gap * 1e3:.3g} µm", fixes)


# --- the inputs as a user gives them -------------------------------------------------------
def resolve(values: Mapping[str, object]) -> PairParameters:
    """The pair of the pair inputs given by name (:data:`~.parameters.PAIR_INPUTS`), missing
    ones at their defaults, without the admissibility check. The modifications' defaults
    (docs/cli.md):

    * shift: 0.008 m, at most m h1/4 (the seed paper's 0.016 mm at m = 2);
    * tip clearance: the shift, at least :data:`TIP_FLOOR` m;
    * rotation: 0.001 m, at most m h1/4; where that makes gear 1 overlap gear 2 (the rotation
      takes more backlash than the shift gives), halved until it does not, at most
      :data:`HALVINGS` times, then none.
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
        return clearance_margin(g)

    at_default = gap(0)
    if at_default >= 0 or at_default == -math.inf:
        return p
    g0 = _built(replace(p, rotation=0.0))
    free = -math.inf if g0 is None or profile_defect(g0) else clearance_margin(g0)
    if free < 0:
        return p                                 # no rotation down to none frees it
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
