"""Which teeth of a pair can touch at a rolling position, and what the unloaded contact
analysis says of them: shared by both tooth-pair models.

:func:`choose_teeth` picks the gear-1 teeth to give contact unknowns from the clearance table
and an estimate of the loaded rotation; after a solve the same rule, at the solved rotation,
tells whether a tooth left out would have closed. :func:`candidate_data` gives each chosen
tooth's predicted contact point and the curvature radii there (for Hertz beside the FE
values).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import GeometryError, ParameterError
from ..geometry import PairParameters, RoundedProfile, ToothEntry, gear2_curve
from ..planar import rotate

TOOTH_STIFFNESS = 14.0   # N/(mm·µm): ISO 6336 single-pair stiffness c', for the load estimate
MARGIN_UM = 3.0          # pair every tooth whose clearance is below the rigid closure + 3 µm,
MARGIN_FACTOR = 1.5      # … or below 1.5 × the closure + 3 µm within NEAR_TEETH of such a tooth
NEAR_TEETH = 2
INTERFERENCE_UM = 1e-3   # a clearance below −1 nm of arc is an interference (touching teeth
                         # of a conformal pair come out at about −2e-10 µm)


@dataclass(frozen=True)
class Candidate:
    """A gear-1 tooth paired for contact: unloaded clearance (µm of arc at r0), the predicted
    contact point (fixed frame at β once the clearance is closed, mm), its polar angle on gear 1
    (body frame, rad) and on gear 2 (body frame, rad), and the analytic curvature radii there
    (mm, + convex)."""

    tooth: int
    clearance_um: float
    point: tuple[float, float]
    phi1: float
    theta2: float
    radius1: float
    radius2: float

    def hertz(self, load: float, thickness: float, E: float, nu: float):
        """Hertz's line contact of the two curvature radii under ``load`` (N) over
        ``thickness`` (mm), one material (E MPa, ν): a :class:`~fegear.fe.HertzLine`, or None
        where the radii are not a Hertz pair (a flank conformal or concave beyond)."""
        from ..fe import line_contact  # lazy: heavy: scikit-fem, off a refused input's path

        try:
            return line_contact(self.radius1, self.radius2, load, thickness, E, nu)
        except ParameterError:
            return None


def candidate_data(params: PairParameters, shape: RoundedProfile, state, teeth,
                   beta: float) -> tuple[Candidate, ...]:
    """Contact point, polar angles and curvature radii of each paired tooth's + flank at β
    (teeth whose + flank has no contact point at β are left out)."""
    g2 = gear2_curve(params)
    alpha = params.ratio * beta
    chosen = [c for c in state.teeth if c.tooth in teeth and c.plus_point is not None]
    if not chosen:
        return ()
    # every tooth at once: the points are independent (one call each cost 0.6 ms of
    # curvature and closest-point overhead, 9 ms a position)
    x = np.array([c.plus_point for c in chosen])
    o1 = np.array([0.0, params.e])
    body1 = rotate(x - o1, -alpha)
    phi1 = np.arctan2(body1[:, 1], body1[:, 0])
    r1 = 1.0 / shape.curvature(phi1)
    # the gear-2 point is where that gear-1 point lands once the clearance is closed: on a
    # nearly conformal flank the relative curvature is a small difference of two large
    # ones, and gear 2's changes fast (the 6 µm of a baseline clearance doubled 1/R*)
    x = rotate(x - o1, np.array([params.turn_of(c.plus_um) for c in chosen])) + o1
    foot = g2.closest(rotate(x, -beta))[0]
    theta2 = np.arctan2(foot[:, 1], foot[:, 0])
    r2 = g2.curvature_radius(g2.xi_at_angle(theta2))
    return tuple(Candidate(c.tooth, float(c.plus_um), (float(x[i, 0]), float(x[i, 1])),
                           float(phi1[i]), float(theta2[i]), float(r1[i]), float(r2[i]))
                 for i, c in enumerate(chosen))


def choose_teeth(state, closure_um: float, widen: int = 0) -> tuple[int, ...]:
    """Gear-1 teeth to pair at one position, for a rigid closure ``closure_um`` (µm of arc at
    r0) of gear 1 against its kinematic position.

    A tooth is paired if its + clearance is below the closure plus MARGIN_UM, or, within
    NEAR_TEETH of such a tooth, below MARGIN_FACTOR × the closure plus MARGIN_UM (the loaded
    teeth's neighbours also move elastically); at least the closest tooth. ``widen`` adds that
    many teeth on each side of every paired tooth (to show the choice is safe)."""
    open_ = {c.tooth: c.plus_um for c in state.teeth if c.plus_um is not None}
    z1 = len(state.teeth)
    rigid = {t for t, c in open_.items() if c < closure_um + MARGIN_UM}
    rigid = rigid or {min(open_, key=open_.get)}
    near = {(t + k) % z1 for t in rigid for k in range(-NEAR_TEETH, NEAR_TEETH + 1)}
    chosen = rigid | {t for t in near if t in open_
                      and open_[t] < MARGIN_FACTOR * closure_um + MARGIN_UM}
    chosen |= {(t + k) % z1 for t in chosen for k in range(-widen, widen + 1)}
    return tuple(sorted(t for t in chosen if t in open_))


def refuse_interference(states) -> None:
    """A pair whose teeth overlap before any load is an interference fit: not modelled."""
    for beta, state in states:
        c = state.closest(+1)
        if c.plus_um < -INTERFERENCE_UM:
            raise GeometryError(f"the unloaded pair interferes: gear-1 tooth {c.tooth} overlaps "
                                f"gear 2 by {-c.plus_um:.3g} µm of arc at r0 at β = "
                                f"{math.degrees(beta):.4g}°; an interference fit is not "
                                "modelled (raise tip_clearance, or check shift and rotation)")


@dataclass(frozen=True)
class Closure:
    """Where deviations take up the pair's backlash: at ``beta`` (rad) gear 1's ``tooth``
    stands ``into_um`` into gear 2 (µm of arc at r0) and the coast flanks leave gear 1
    ``back_um`` to turn back (less than 0: the coast side is closed too, a coast flank that
    far into gear 2)."""

    beta: float
    tooth: int
    into_um: float
    back_um: float

    def __str__(self) -> str:
        coast = (f"the coast flanks leave gear 1 {self.back_um:.3g} µm to turn back"
                 if self.back_um >= 0 else "the coast side is closed too: a coast flank "
                 f"stands {-self.back_um:.3g} µm into gear 2, leaving gear 1 no room to "
                 "turn back")
        return (f"gear-1 tooth {self.tooth} stands {self.into_um:.3g} µm of arc at r0 into "
                f"gear 2 at β = {math.degrees(self.beta):.4g}°, and {coast}")


def closed(behind) -> Closure | None:
    """Where deviations take up the pair's whole backlash, else None: at some β a tooth stands
    into its mate on the loaded side (a tooth turned or grown beyond its clearance) by more
    than the coast flanks leave gear 1 to turn back, so the pair would be assembled with a
    preload. A loaded-side overlap within the backlash only sets gear 1 back from its
    kinematic position: that pair is solved. ``behind``: (β, loaded-side state, coast-side
    state) of the positions with a loaded-side overlap, both sides' clearances moved by the
    deviations."""
    for beta, state, coast in behind:
        c = state.closest(+1)
        where = closure(beta, c.tooth, c.plus_um, coast.closest(-1).minus_um)
        if where is not None:
            return where
    return None


def closure(beta: float, tooth: int, plus_um: float, back_um: float) -> Closure | None:
    """The :class:`Closure` at ``beta`` (rad) where gear 1's ``tooth``, the nearest to closing
    on the loaded side, has the deviated clearance ``plus_um`` there and the coast flanks'
    nearest ``back_um`` (µm of arc at r0), if together they take up the backlash
    (:func:`closed`); else None."""
    if plus_um + back_um < -INTERFERENCE_UM:
        return Closure(beta, tooth, -plus_um, back_um)
    return None


def refuse_closed(behind, deviations) -> None:
    """A pair its ``deviations`` close before any load (:func:`closed`) is refused naming the
    deviation to change."""
    where = closed(behind)
    if where is None:
        return
    name, given = _blamed(deviations, where.tooth)
    raise ParameterError(name, given, "deviations within the pair's backlash "
                         f"({where})", "the pair closes before any load")


def _blamed(deviations, tooth: int) -> tuple[str, object]:
    """The input a refusal of a closed pair names and the value it quotes: gear 1's
    ``tooth``'s own deviation as its option's entry (``1:11=30``, written by
    :class:`~fegear.geometry.ToothEntry`), else the centre distance's, else the deviations as
    given."""
    on_tooth = deviations.teeth(1).get(tooth)
    entry = None if on_tooth is None else ToothEntry.of(on_tooth, 1, tooth)
    if entry is not None:
        return entry.option, entry.text
    if deviations.centre_distance:
        return "centre-distance-deviation", deviations.centre_distance
    return "deviations", "as given"


def tension_fillets(tooth_centre: float, pitch1: float, theta2: float,
                    pitch2: float) -> tuple[float, float]:
    """The polar angles (rad, each gear's frame) of the tooth spaces whose root fillets a
    gear-1 tooth centred at ``tooth_centre`` bends in tension under the ``+`` torque: gear 1's
    space after it (larger polar angle) and, for the gear-2 tooth it presses at polar angle
    ``theta2``, gear 2's space before that tooth. (Measured on the baseline at 200 N·m: the
    loaded teeth's σ1 on those sides 245-287 and 231-269 MPa, on the other sides 0-39.)"""
    return tooth_centre + 0.5 * pitch1, (round(theta2 / pitch2) - 0.5) * pitch2
