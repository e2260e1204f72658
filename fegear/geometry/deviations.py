"""Manufacturing and assembly deviations of a pair: what makes a real gear pair differ from the
exact one, tooth by tooth (docs/geometry.md, "Deviations", with the picture of the signs).

Per tooth of either gear (µm):

* **pitch**: the tooth displaced along its pitch circle, turned about its gear's centre (its
  position deviation: a measuring machine's cumulative pitch deviation at that tooth);
* **slope**: the profile slope deviation f_Hα, normal to the loaded flank, growing linearly
  along the active profile from nothing at its root end to the value at its tip end;
* **form**: the profile form deviation, a parabola along the active profile, nothing at its
  ends and the value at its middle (or a measured curve of roll fraction → µm, ``curve``).

Per pair: the **centre-distance** deviation (µm, the centres farther apart) and each gear's
**runout** (radial runout F_r, µm, twice the eccentricity of its teeth about its axis, and the
phase of the high point, degrees from tooth 0's centre in the gear's own frame).

**One sign for every deviation of a tooth: a positive value moves its loaded flank towards its
mate** (the flanks the torque on gear 1, counter-clockwise, presses together), adding material
or closing the clearance: gear 1's tooth is turned counter-clockwise, gear 2's clockwise, and a
profile deviation adds material. The centre distance and the runout are geometry: a positive
centre-distance deviation moves gear 1's centre away from gear 2's, which brings the teeth near
the pitch point deeper into the mesh.

Everything here is exact geometry in mm and rad (:meth:`Deviations.turns`,
:meth:`Deviations.flank_offset`, the centres and runouts where :class:`Placed` puts the gears);
the solve applies it to the rigid gaps of the model it keeps (docs/solve.md, "Deviations").
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from ..checks import require_finite
from ..errors import ParameterError
from ..planar import rotate
from .gear1 import gear1_profile
from .gear2 import gear2_curve, gear2_tooth

#: the largest deviation fegear takes, µm: far beyond ISO 1328-1's coarsest class for any
#: module fegear solves (class 11, m 100, d 2 m: about 900 µm) and below what closes a pair
LIMIT_UM = 1000.0
GEARS = (1, 2)


def _micron(name: str, value) -> float:
    if isinstance(value, bool):
        raise ParameterError(name, value, f"-{LIMIT_UM:g} <= {name} <= {LIMIT_UM:g} µm")
    try:
        x = float(value)
    except (TypeError, ValueError):
        x = math.nan
    if not math.isfinite(x) or abs(x) > LIMIT_UM:
        raise ParameterError(name, value, f"-{LIMIT_UM:g} <= {name} <= {LIMIT_UM:g} µm")
    return x


@dataclass(frozen=True)
class ToothDeviation:
    """One tooth's deviations (µm; positive: its loaded flank towards its mate): ``pitch``,
    ``slope``, ``form`` and a measured form ``curve`` ((roll fraction 0..1, µm) pairs, in
    place of the parabola)."""

    pitch: float = 0.0
    slope: float = 0.0
    form: float = 0.0
    curve: tuple[tuple[float, float], ...] = ()

    def __post_init__(self) -> None:
        for name in ("pitch", "slope", "form"):
            object.__setattr__(self, name, _micron(f"{name}-deviation", getattr(self, name)))
        if self.curve:
            u = np.array([c[0] for c in self.curve], dtype=float)
            if len(u) < 2 or not np.all(np.diff(u) > 0) or u[0] < 0 or u[-1] > 1:
                raise ParameterError("form-curve", self.curve, "two or more (roll fraction, µm) "
                                     "pairs, the fractions rising within 0 ... 1")
            for _, v in self.curve:
                _micron("form-curve", v)

    @property
    def profiled(self) -> bool:
        """Whether the flank itself departs from the exact profile."""
        return bool(self.slope or self.form or self.curve)

    def normal_um(self, roll: np.ndarray) -> np.ndarray:
        """The flank's normal departure (µm, + adds material) at roll fractions ``roll`` (0 at
        the active profile's root end, 1 at its tip end; outside, the end's value)."""
        u = np.clip(np.asarray(roll, dtype=float), 0.0, 1.0)
        out = self.slope * u
        if self.curve:
            out = out + np.interp(u, [c[0] for c in self.curve], [c[1] for c in self.curve])
        elif self.form:
            out = out + 4.0 * self.form * u * (1.0 - u)
        return out


@dataclass(frozen=True)
class Runout:
    """A gear's radial runout ``fr`` (µm, twice its eccentricity) with its high point at
    ``phase`` degrees from tooth 0's centre, in the gear's own frame."""

    fr: float = 0.0
    phase: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "fr", _micron("runout", self.fr))
        if self.fr < 0:
            raise ParameterError("runout", self.fr, f"0 <= runout <= {LIMIT_UM:g} µm (the radial "
                                 "runout; its direction is the phase)")
        object.__setattr__(self, "phase", require_finite("runout phase", self.phase))

    def offset(self, tooth0) -> np.ndarray:
        """The centre of the gear's teeth from its axis (mm, fixed frame) with tooth 0's
        centre at polar angle ``tooth0`` (rad, fixed frame, about the axis): (2,), or (n, 2)
        for n angles."""
        a = math.radians(self.phase) + np.asarray(tooth0, dtype=float)
        return 0.5e-3 * self.fr * np.stack([np.cos(a), np.sin(a)], axis=-1)


@dataclass(frozen=True)
class Deviations:
    """A pair's deviations: per tooth of gear 1 and of gear 2 (given as tooth index →
    deviation, kept as sorted pairs; a tooth not named has none), the centre distance's (µm)
    and each gear's runout. The empty one is the exact pair."""

    gear1: tuple = ()
    gear2: tuple = ()
    centre_distance: float = 0.0
    runout1: Runout = Runout()
    runout2: Runout = Runout()

    def __post_init__(self) -> None:
        object.__setattr__(self, "centre_distance",
                           _micron("centre-distance-deviation", self.centre_distance))
        for gear in GEARS:
            given = getattr(self, f"gear{gear}")
            teeth = dict(given.items() if isinstance(given, Mapping) else given)
            object.__setattr__(self, f"gear{gear}", tuple(
                (int(k), v) for k, v in sorted(teeth.items()) if v != ToothDeviation()))

    def teeth(self, gear: int) -> dict[int, ToothDeviation]:
        """``gear``'s teeth with deviations: tooth index → deviation."""
        return dict(self.gear1 if gear == 1 else self.gear2)

    def __bool__(self) -> bool:
        return bool(self.gear1 or self.gear2 or self.centre_distance or self.runout1.fr
                    or self.runout2.fr)

    def summary(self) -> dict:
        """The deviations as JSON (µm, degrees): per gear its teeth's, the centre distance's
        and each gear's runout."""
        def tooth(d: ToothDeviation) -> dict:
            out = {"pitch_um": d.pitch, "slope_um": d.slope, "form_um": d.form}
            if d.curve:
                out["form_curve_um"] = [list(c) for c in d.curve]
            return out

        return {"gear1": {str(t): tooth(d) for t, d in self.gear1},
                "gear2": {str(t): tooth(d) for t, d in self.gear2},
                "centre_distance_um": self.centre_distance,
                "runout1": {"fr_um": self.runout1.fr, "phase_deg": self.runout1.phase},
                "runout2": {"fr_um": self.runout2.fr, "phase_deg": self.runout2.phase}}

    def reach_um(self, tooth: int) -> float:
        """How far (µm) the deviations can move gear 1's tooth ``tooth`` towards gear 2 or away
        at most: what a contact grid on it must reach beyond the exact pair's. Its own
        deviations, the largest of gear 2's teeth's (any may face it), the centre distance's
        and the runouts'."""
        own = self.teeth(1).get(tooth)
        return (0.0 if own is None else _amount(own)) + self._shared_um()

    def widest_um(self) -> float:
        """The largest :meth:`reach_um` of any of gear 1's teeth."""
        return max((_amount(d) for _, d in self.gear1), default=0.0) + self._shared_um()

    def _shared_um(self) -> float:
        """What of :meth:`reach_um` every tooth of gear 1 shares: the largest of gear 2's
        teeth's, the centre distance's and the runouts'."""
        return (max((_amount(d) for _, d in self.gear2), default=0.0)
                + abs(self.centre_distance) + 0.5 * (self.runout1.fr + self.runout2.fr))

    def turns(self, gear: int, teeth: np.ndarray, r: float) -> np.ndarray:
        """The extra turn (rad, counter-clockwise) of each of ``teeth`` of ``gear`` about its
        centre, its pitch circle of radius ``r`` (mm): + for gear 1, − for gear 2 (module
        docstring)."""
        sign = 1.0 if gear == 1 else -1.0
        pitch = self._arrays(gear)[0]
        teeth = np.ravel(teeth).astype(int)
        um = np.zeros(len(teeth))
        inside = teeth < len(pitch)
        um[inside] = pitch[teeth[inside]]
        return sign * 1e-3 * um / r

    def flank_offset(self, gear: int, teeth: np.ndarray, roll: np.ndarray) -> np.ndarray:
        """The normal departure (mm, + adds material) of ``gear``'s loaded flanks at points
        of ``teeth`` at roll fractions ``roll``."""
        teeth, roll = np.ravel(teeth), np.ravel(roll)
        _, slope, form, curves = self._arrays(gear)
        out = np.zeros(len(teeth))
        if not len(slope) or not len(teeth):
            return out
        inside = teeth < len(slope)
        t, u = teeth[inside], np.clip(roll[inside], 0.0, 1.0)
        out[inside] = 1e-3 * (slope[t] * u + form[t] * 4.0 * u * (1.0 - u))
        for tooth, d in curves.items():   # a measured form: its own curve, not the parabola
            sel = teeth == tooth
            out[sel] = 1e-3 * d.normal_um(roll[sel])
        return out

    def _arrays(self, gear: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict]:
        """``gear``'s deviations as arrays by tooth (µm; zero where none): pitches, slopes,
        parabolas' amplitudes, and the teeth with measured form curves (made once: a solve
        asks for them at every gap it forms)."""
        key = f"_arrays{gear}"
        if key not in self.__dict__:
            table = self.teeth(gear)
            n = max(table, default=-1) + 1
            pitch, slope, form = np.zeros(n), np.zeros(n), np.zeros(n)
            for tooth, d in table.items():
                pitch[tooth], slope[tooth] = d.pitch, d.slope
                form[tooth] = 0.0 if d.curve else d.form
            self.__dict__[key] = (pitch, slope, form,
                                  {t: d for t, d in table.items() if d.curve})
        return self.__dict__[key]


NONE = NO_DEVIATIONS = Deviations()


def _amount(d: ToothDeviation) -> float:
    """How far (µm) a tooth's own deviations move it at most."""
    return (abs(d.pitch) + abs(d.slope) + abs(d.form)
            + max((abs(v) for _, v in d.curve), default=0.0))


#: the smallest lever arm (fraction of gear 1's pitch radius) by which a clearance's Newton
#: step divides a deviation's gap (:meth:`Placed.clearances`): below the flanks' own, down to
#: about 0.05 r1 on the teeth farthest from the mesh, above a tip meeting a tip
LEVER_FLOOR = 0.02
#: a closing point whose deviated gap's rate is below this fraction of r1 grazes gear 2 (a tip
#: passing a tip, the gap least about where the exact pair touches; the flanks' lever arms in
#: the mesh are several times more): a Newton step from it overshoots, and the deviated gap is
#: followed back along the turn instead (:func:`_grazed`)
GRAZING = 0.1
#: regula falsi's steps at most, and the deviated gap (mm) at which it stops, that follow a
#: grazing point's gap back along the turn (:func:`_grazed`); the times its bracket is widened
#: where the Newton step's turn is closed too
GRAZED_STEPS = 40
GRAZED_GAP = 1e-7
GRAZED_WIDER = 6
#: the tooth's outline about a grazing point (× m) whose deviated gaps it takes too, and the
#: chord (mm) its vertices stand within of the curve
GRAZED_NEAR = 0.1
GRAZED_CHORD = 2e-5


@lru_cache(maxsize=64)
def _gear1_radii(params) -> tuple[float, float]:
    """Gear 1's root and tip radii (mm), where its flanks' roll runs from 0 to 1."""
    g1 = gear1_profile(params)
    return (float(g1.radius(np.array([g1.phi_space]))[0]),
            float(g1.radius(np.array([g1.tooth_center]))[0]))


class Placed:
    """A pair's deviations at one rolling angle β (or at one a point of the gaps asked for:
    ``beta`` an array): the exact unloaded gap of gear 1's points to gear 2 as the deviations
    leave them (:meth:`gap`), and each tooth's clearance moved by them (:meth:`clearances`).

    Gear 1 turns about its axis, which the centre-distance deviation moves along the line of
    centres; its teeth stand off that axis by its runout and gear 2's by its own (each turning
    with its gear from tooth 0's centre); a tooth's pitch deviation turns it about its gear's
    axis; a flank's deviation adds material along its normal. A flank's roll fraction runs
    from its root (0) to its tip (1) by radius: gear 1's root and tip radii, gear 2's
    r0 ± 2 e1."""

    def __init__(self, deviations: Deviations, params, beta: float) -> None:
        self.deviations, self.params, self.beta = deviations, params, beta
        self.curve2 = gear2_curve(params)
        g1 = gear1_profile(params)
        self.axis1 = np.array([0.0, params.e + 1e-3 * deviations.centre_distance])
        alpha = params.ratio * beta
        self.teeth_offset = (deviations.runout1.offset(g1.tooth_center + alpha)
                             - deviations.runout2.offset(beta))
        self.roots1, self.tips1 = _gear1_radii(params)
        self.roots2, self.tips2 = params.r0 + 2 * params.e1, params.r0 - 2 * params.e1

    def gap(self, x: np.ndarray, teeth: np.ndarray, turn: float,
            feet: np.ndarray | None = None, flanks: bool = True
            ) -> tuple[np.ndarray, np.ndarray]:
        """The exact gap (mm, > 0 open) of gear-1 points ``x`` (its own frame, (n, 2)) of its
        ``teeth`` to gear 2 with gear 1 turned by ``turn`` (rad, kinematic angle included), and
        the gap's rate with that turn (mm/rad). ``feet``: gear 2's parameters ξ to start the
        searches from, overwritten with those found. ``flanks``: whether the points are on the
        loaded flanks, which the slope and form deviations move (the coast flanks: False)."""
        dev, p = self.deviations, self.params
        turns = turn + dev.turns(1, teeth, p.r1)
        fixed = rotate(x, turns) + self.axis1 + self.teeth_offset
        feet = np.full(len(x), np.nan) if feet is None else feet
        k2 = np.zeros(len(x), dtype=int)
        turn2 = np.zeros(len(x))
        warm = bool(dev.gear2) and bool(np.isfinite(feet).all())
        if dev.gear2:            # gear 2's tooth under each point, then its own turn
            if not warm:         # (started at feet found before: the tooth they face)
                feet[:] = self.curve2.feet(rotate(fixed, -self.beta), start=feet)
            k2 = gear2_tooth(feet, p.z2)
            turn2 = dev.turns(2, k2, p.r0)
        y = rotate(fixed, -(self.beta + turn2))
        feet[:] = self.curve2.feet(y, start=feet)
        if warm:                 # a point now facing another tooth: found again, turned as it
            moved = np.flatnonzero(gear2_tooth(feet, p.z2) != k2)
            if len(moved):
                turn2[moved] = dev.turns(2, gear2_tooth(feet[moved], p.z2), p.r0)
                beta = self.beta if np.ndim(self.beta) == 0 else self.beta[moved]
                y[moved] = rotate(fixed[moved], -(beta + turn2[moved]))
                feet[moved] = self.curve2.feet(y[moved], start=feet[moved])
        foot, normal, dist = self.curve2.at_feet(y, feet)
        if dev.gear2:
            k2 = gear2_tooth(feet, p.z2)
        if flanks:
            dist = (dist - dev.flank_offset(1, teeth, self.roll(1, x))
                    - dev.flank_offset(2, k2, self.roll(2, foot)))
        r = rotate(fixed - self.axis1, -(self.beta + turn2))
        return dist, np.einsum("ij,ij->i", normal, np.column_stack([-r[:, 1], r[:, 0]]))

    def roll(self, gear: int, x: np.ndarray) -> np.ndarray:
        """The roll fractions on ``gear``'s flanks (0 at the root end, 1 at the tip end: class
        docstring) of its points ``x`` (n, 2, about its own axis)."""
        return self.roll_at(gear, np.hypot(x[:, 0], x[:, 1]))

    def roll_at(self, gear: int, r: np.ndarray) -> np.ndarray:
        """The roll fractions on ``gear``'s flanks of its points at the radii ``r`` (mm)."""
        if gear == 1:
            return (r - self.roots1) / (self.tips1 - self.roots1)
        return (self.roots2 - r) / (self.roots2 - self.tips2)

    def levers(self, rate: np.ndarray, direction: int) -> np.ndarray:
        """The size of closing points' gap rates (mm/rad) that a Newton step divides by, at
        least :data:`LEVER_FLOOR` r1: a point whose normal passes nearly through gear 1's axis
        (a tip meeting a tip, the rate near zero or of the other sign) is not where a deviated
        tooth closes, for the turn barely moves its gap; a tooth's other points, with the
        lever arms of its flanks, close first."""
        return np.maximum(-direction * np.asarray(rate), LEVER_FLOOR * self.params.r1)

    def clearances(self, state, direction: int = +1):
        """``state`` (a :class:`~.clearance.ContactState` at this β) with each tooth's
        clearance in ``direction`` (+1: the + torque's, the loaded flanks; -1: the coast
        flanks, which only the pitch, centre-distance and runout deviations move) moved by the
        deviations (:func:`moved_clearances`)."""
        return moved_clearances(self.deviations, self.params, [state], direction)[0]


def moved_clearances(deviations: Deviations, params, states, direction: int = +1,
                     closing: Closing | None = None) -> list:
    """``states`` (:class:`~.clearance.ContactState` s, each at its own β) with each tooth's
    clearance in ``direction`` (+1: the + torque's, the loaded flanks; -1: the coast flanks,
    which only the pitch, centre-distance and runout deviations move) moved by
    ``deviations``: one Newton step on the deviated gap at the point that closes it (exact for
    a pitch deviation of gear 1, to the second order in the deviation otherwise). Every
    state's closing points are one batch of gaps (:class:`Placed` with a β a point): a whole
    turn's states cost about what one does. ``closing``: the states' closing points in
    ``direction`` where found before (:meth:`Closing.found`: their feet where the searches
    start), else found here."""
    key = "plus_um" if direction > 0 else "minus_um"
    closing = closing_points(params, states, direction) if closing is None else closing
    um = _moved_um(deviations, params, closing)
    out, k = [], 0
    for s, c in zip(states, closing.teeth):
        moved = {t.tooth: float(um[k + i]) for i, t in enumerate(c)}
        k += len(c)
        out.append(replace(s, teeth=tuple(replace(t, **{key: moved[t.tooth]})
                                          if t.tooth in moved else t for t in s.teeth)))
    return out


@dataclass(frozen=True)
class Closing:
    """Clearance states' closing points in one ``direction``, as arrays (:func:`closing_points`):
    per state its closing teeth (``teeth``), and per point its state's β (rad), its clearance
    (µm of arc at r0), where it is (gear 1's frame, mm), its tooth, and its foot's parameter
    ξ on gear 2's curve where found (NaN before: each deviated gap's search starts there)."""

    direction: int
    teeth: list
    beta: np.ndarray
    um: np.ndarray
    x: np.ndarray
    tooth: np.ndarray
    feet: np.ndarray

    def reachable(self, params, reach_um: float) -> Closing:
        """The points whose clearance deviations that move no flank point more than
        ``reach_um`` (µm, along any normal: :meth:`Deviations.reach_um`) could take up: the
        clearance moves by the gap over the lever (:func:`moved_clearances`), here the exact
        pair's lever, with a factor 2 for the lever's own move. A state left without points
        cannot close (its least clearance is +inf)."""
        feet = self.feet.copy()
        _, lever = _gaps(NONE, params, self, feet)
        keep = self.um < 2.0 * params.arc_um(1e-3 * reach_um / lever)
        ends = np.cumsum([0] + [len(c) for c in self.teeth])
        teeth = [[t for t, k in zip(c, keep[a:b]) if k]
                 for c, a, b in zip(self.teeth, ends[:-1], ends[1:])]
        return Closing(self.direction, teeth, self.beta[keep], self.um[keep], self.x[keep],
                       self.tooth[keep], feet[keep])

    def states(self) -> np.ndarray:
        """Each point's state (index into ``teeth``)."""
        return np.repeat(np.arange(len(self.teeth)), [len(c) for c in self.teeth])

    def of_states(self, index: np.ndarray) -> Closing:
        """The closing points of the states ``index`` (increasing) alone, their feet copied."""
        pick = np.flatnonzero(np.isin(self.states(), index))
        return Closing(self.direction, [self.teeth[i] for i in index], self.beta[pick],
                       self.um[pick], self.x[pick], self.tooth[pick], self.feet[pick])

    def found(self, params) -> Closing:
        """These points with their feet found on the exact pair, where each closes it: where
        many pairs' deviated clearances of the same states are moved (:func:`moved_clearances`,
        a class's samples at one place), each pair's searches start there, not anew."""
        feet = self.feet.copy()
        _gaps(NONE, params, self, feet)
        return replace(self, feet=feet)

    def turns(self, params) -> np.ndarray:
        """Gear 1's turn (rad, kinematic angle included) at which each point closes the exact
        pair: its state's β turned on by its clearance."""
        return params.ratio * self.beta + self.direction * params.turn_of(self.um)


def closing_points(params, states, direction: int = +1) -> Closing:
    """``states``' closing points in ``direction`` (:class:`Closing`): one set of arrays for
    the deviated clearances of many pairs (:func:`least_clearances`)."""
    key, point = ("plus_um", "plus_point") if direction > 0 else ("minus_um", "minus_point")
    teeth = [[t for t in s.teeth if getattr(t, key) is not None
              and getattr(t, point) is not None] for s in states]
    flat = [t for c in teeth for t in c]
    beta = np.repeat([s.beta for s in states], [len(c) for c in teeth]).astype(float)
    x = np.array([getattr(t, point) for t in flat]).reshape(-1, 2)
    return Closing(direction, teeth, beta, np.array([getattr(t, key) for t in flat], float),
                   rotate(x - np.array([0.0, params.e]), -params.ratio * beta),
                   np.array([t.tooth for t in flat], int), np.full(len(flat), np.nan))


def least_clearances(deviations: Deviations, params, closing: Closing
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Each state's smallest clearance in the ``closing`` points' direction moved by
    ``deviations`` (µm; +inf where no tooth closes) and its tooth (−1 where none):
    :func:`moved_clearances`' numbers without new states (a whole turn's states a pair of
    many: new states a tooth cost more than the gaps). The points' feet are kept for the
    next pair's searches."""
    return least_of_states(_moved_um(deviations, params, closing), closing)


def least_of_states(um: np.ndarray, closing: Closing) -> tuple[np.ndarray, np.ndarray]:
    """Each of the ``closing`` states' least of its points' clearances ``um`` (µm; +inf
    where it has no point) and the tooth of its first point that holds it (−1 where none)."""
    state = closing.states()
    least = np.full(len(closing.teeth), np.inf)
    np.minimum.at(least, state, um)
    teeth = np.full(len(closing.teeth), -1)
    first = np.flatnonzero(um == least[state])[::-1]   # the first of a state's written last
    teeth[state[first]] = closing.tooth[first]
    return least, teeth


def point_clearances(deviations: Deviations, params, closing: Closing) -> np.ndarray:
    """Each of the ``closing`` points' clearance moved by ``deviations`` (µm): the numbers
    :func:`least_clearances` takes each state's least of, for a caller that adds to them
    point by point (the offsets across the face). The points' feet are kept as there."""
    return _moved_um(deviations, params, closing)


def _moved_um(deviations: Deviations, params, closing: Closing) -> np.ndarray:
    """The ``closing`` points' clearances moved by ``deviations`` (µm): one batch of gaps,
    their searches started at the points' feet, which they leave there
    (:func:`moved_clearances`)."""
    if not len(closing.um):
        return np.zeros(0)
    g, lever = _gaps(deviations, params, closing, closing.feet)
    # the gap's rate with the turn is < 0 on a loaded flank and > 0 on a coast flank:
    # either way the clearance grows by the gap over its rate's size
    um = closing.um + params.arc_um(np.abs(g) / lever) * np.sign(g)
    # a grazing point's step lies below its clearance: where it leaves the point open, the
    # smaller number costs no more than a tooth paired that does not touch; where it puts
    # the point in its mate, the tooth's gap is followed (a pair is not refused on it)
    grazing = np.flatnonzero(grazes(g, lever, params) & (um < 0))
    if len(grazing):
        um[grazing] = _grazed(deviations, params, closing, grazing, um[grazing], g[grazing])
    return um


def grazes(gap: np.ndarray, lever: np.ndarray, params) -> np.ndarray:
    """Which closing points graze gear 2 where their deviated ``gap`` (mm) closes them: the
    gap's rate (``lever``, mm/rad) below :data:`GRAZING` r1. A Newton step does not give
    their clearance (:func:`_grazed`), but lies below it: a screen of many pairs that keeps the
    step (:class:`~fegear.toothpair.analyses.samples.states.ClosingCircles`) measures their
    states sooner, not later."""
    return (gap < 0) & (lever < GRAZING * params.r1)


def _grazed(deviations: Deviations, params, closing: Closing, idx: np.ndarray,
            newton: np.ndarray, shut_gap: np.ndarray) -> np.ndarray:
    """The clearances (µm) of the ``closing`` points ``idx`` that graze gear 2
    (:data:`GRAZING`) and that the deviations close (their deviated gap ``shut_gap`` < 0 mm at
    the exact pair's clearance): the turn at which the deviated gap of the point or of its
    tooth's outline about it (:data:`GRAZED_NEAR`: a grazing tip's closure moves along it
    under the deviations) first closes, by regula falsi (the Illinois variant) between the
    exact pair's clearance and the Newton step's ``newton`` (or below, where the outline is
    closed there too, down to :data:`GRAZED_WIDER` doublings of the bracket; closed still, the
    lowest turn tried: the tooth stands in its mate at least that far). A grazing gap is about
    convex in the turn, so the step's tangent lies below it and the step overshoots, by as much
    as its rate is small (docs/deviations.md)."""
    owner, x, tooth = _about(params, closing, idx)
    beta = closing.beta[idx][owner]
    at = Placed(deviations, params, beta)
    feet = closing.feet[idx][owner]
    flanks = closing.direction > 0

    def least(um: np.ndarray) -> np.ndarray:   # each point's least gap over its outline
        turn = params.ratio * beta + closing.direction * params.turn_of(um[owner])
        out = np.full(len(idx), np.inf)
        np.minimum.at(out, owner, at.gap(x, tooth, turn, feet, flanks=flanks)[0])
        return out

    high = closing.um[idx].copy()
    f_high = np.minimum(shut_gap, least(high))
    low = newton.copy()
    f_low = least(low)
    for _ in range(GRAZED_WIDER):               # closed at the step too: a wider bracket
        shut = f_low <= 0
        if not shut.any():
            break
        low = np.where(shut, high - 2.0 * (high - low), low)
        f_low = np.where(shut, least(low), f_low)
    last = np.zeros(len(idx))                   # the end moved last: +1 low, −1 high
    root = low.copy()
    for _ in range(GRAZED_STEPS):
        span = np.where(f_low > f_high, f_low - f_high, 1.0)   # > 0 in a bracket
        root = np.where(f_low > 0, high + f_high * (high - low) / span, low)
        f = least(root)
        closed = f <= 0
        f_low = np.where(closed & (last < 0), 0.5 * f_low, f_low)      # Illinois: an end kept
        f_high = np.where(~closed & (last > 0), 0.5 * f_high, f_high)  # twice weighs half
        high, f_high = np.where(closed, root, high), np.where(closed, f, f_high)
        low, f_low = np.where(closed, low, root), np.where(closed, f_low, f)
        last = np.where(closed, -1.0, 1.0)
        if np.all((np.abs(f) < GRAZED_GAP) | (f_low <= 0)):
            break
    return root


def _about(params, closing: Closing, idx: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The points ``idx`` of ``closing`` and their teeth's outline vertices within
    :data:`GRAZED_NEAR` of each: which of them each belongs to (index into ``idx``), where
    they are (gear 1's frame) and their teeth."""
    outline = _outline(params)
    pitch = 2.0 * math.pi / params.z1
    owner, x, tooth = [], [], []
    for j, i in enumerate(idx):
        pts = rotate(outline, closing.tooth[i] * pitch)
        near = pts[np.hypot(*(pts - closing.x[i]).T) < GRAZED_NEAR * params.m]
        owner.append(np.full(len(near) + 1, j))
        x.append(np.vstack([closing.x[i][None], near]))
        tooth.append(np.full(len(near) + 1, closing.tooth[i]))
    return np.concatenate(owner), np.vstack(x), np.concatenate(tooth)


@lru_cache(maxsize=16)
def _outline(params) -> np.ndarray:
    """Tooth 0's outline (gear 1's frame): a pitch of its profile, its vertices within
    :data:`GRAZED_CHORD` of the curve."""
    return gear1_profile(params).period_polyline(GRAZED_CHORD)


def _gaps(deviations: Deviations, params, closing: Closing, feet: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray]:
    """The ``closing`` points' deviated gaps (mm) where each closes the exact pair, and the
    lever (mm/rad) a Newton step on the clearance divides them by (:meth:`Placed.levers`);
    the foot searches start at ``feet``, overwritten with the feet found."""
    at = Placed(deviations, params, closing.beta)
    g, rate = at.gap(closing.x, closing.tooth, closing.turns(params), feet,
                     flanks=closing.direction > 0)
    return g, at.levers(rate, closing.direction)
