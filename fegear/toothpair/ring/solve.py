"""The ring model's solve at one rolling position, or at a set of them on one model.

Torque T (N·m) acts on gear 1 counter-clockwise (the ``+`` direction of the clearance table)
through a rigid rotation θ about its centre; gear 2's outer rim is held. At each position the
teeth that can touch are chosen from the clearance table and the expected loaded rotation
(:func:`~fegear.toothpair.teeth.choose_teeth`), each gets a pressure grid over the stretch of
its profile that the rotation can close, and the contact is solved. Then the same rule at the
solved rotation must choose no tooth without a grid, no grid may carry pressure at its ends and
the rotation the grids were placed at must be the solved one within a tenth of the elastic
part; otherwise the grids are placed again and the position solved again.

The model (meshes, factors, responses to unit loads) is built once per geometry and quality and
reused for every torque and position (:class:`~.model.RingModel`); a position after the first
starts from the previous one's rotation.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import replace

from ... import progress
from ...errors import FegearError
from ...fe import contact_modulus
from ...geometry import Gear1Profile, ToothContact
from ..case import ContactChecks, PairSolution, SolveCase
from ..teeth import TOOTH_STIFFNESS, candidate_data, choose_teeth, refuse_interference
from .contact import first_touch, solve_contact
from .grid import ToothGrid, tooth_grid, window
from .influence import RingContact, assemble_contact
from .model import RingModel, ring_model
from .results import RingDetail, tooth_results
from .stresses import ring_stresses

log = logging.getLogger(__name__)

REACH = 3.0          # grids reach where the rigid gap is within this many expected elastic
                     # approaches of closing …
REACH_FLOOR = 1e-4   # … and at least this many modules
SHARE_GUESS = 3.0    # teeth assumed to share the load when spacing the grids
GRID_FLOOR = 1e-5    # smallest grid spacing, in modules (20 nm at m = 2)
PLACEMENT = 0.5      # grids are placed again if the solved rotation's elastic part differs
                     # from the expected one by more than this fraction
ATTEMPTS = 5
PROBE_MARGIN_UM = 1.0  # fine grids also on teeth within this of closing at the expected rotation


def solve_pair(case: SolveCase, profile: Gear1Profile | None = None,
               model: RingModel | None = None) -> PairSolution:
    """Solve one position."""
    return solve_positions(case, (case.beta,), profile, model)[0]


def solve_positions(case: SolveCase, betas, profile: Gear1Profile | None = None,
                    model: RingModel | None = None) -> tuple[PairSolution, ...]:
    """Solve at each rolling angle of ``betas`` (rad) on one model (``model`` if it fits the
    case, else one built here)."""
    t0 = time.perf_counter()
    if model is None or not model.fits(case):
        progress.stage(f"model: both gears meshed and condensed at quality {case.quality}")
        model = ring_model(case, profile)
    fresh = not any(g.response_s for g in model.gears)
    t_model = time.perf_counter() - t0
    t0 = time.perf_counter()
    tca = ToothContact(case.params, model.profile)
    states = [(b, tca.state(b)) for b in betas]
    refuse_interference(states)
    t_tca = time.perf_counter() - t0
    sols = []
    for k, (beta, state) in enumerate(states):
        progress.stage(f"contact at β {math.degrees(beta):.3g}°"
                       + (f" ({k + 1} of {len(states)})" if len(states) > 1 else ""))
        sol = solve_position(model, replace(case, beta=beta), state,
                             sols[-1] if sols else None)
        if k == 0:  # the first position carries the one-off stages
            built = model.timings_s if fresh else {"model (kept)": t_model}
            sol = replace(sol, timings_s={**built, "clearance": t_tca, **sol.timings_s})
        sols.append(sol)
    return tuple(sols)


def solve_position(model: RingModel, case: SolveCase, state,
                   near: PairSolution | None = None) -> PairSolution:
    """Solve ``case`` (its torque and position β) on ``model``; ``state`` is the clearance
    state at β, ``near`` a solution at a nearby position to start from."""
    p = case.params
    torque = case.torque * 1e3
    times = {"grids": 0.0, "assemble": 0.0, "contact": 0.0}
    first_um = state.closest(+1).plus_um
    if near is not None:
        elastic_um = (near.rotation - near.first_touch) * p.r0 * 1e3
    else:
        elastic_um = torque / p.r0 / (case.thickness * TOOTH_STIFFNESS) / SHARE_GUESS
    reach = {}
    teeth = choose_teeth(state, first_um + elastic_um, case.extra_pairs)
    full = _expected(state, first_um + elastic_um)
    formed = sum(g.response_s for g in model.gears)
    for _ in range(ATTEMPTS):
        theta = (first_um + elastic_um) * 1e-3 / p.r0
        t0 = time.perf_counter()
        grids = _grids(model, case, teeth, full, theta, elastic_um, reach)
        times["grids"] += time.perf_counter() - t0
        t0 = time.perf_counter()
        contact = assemble_contact(model, grids, case.beta, p.ratio * case.beta + theta)
        times["assemble"] += time.perf_counter() - t0
        t0 = time.perf_counter()
        sol = solve_contact(model, contact, torque, first_um * 1e-3 / p.r0, guess=theta)
        times["contact"] += time.perf_counter() - t0
        more = set(choose_teeth(state, sol.rotation * p.r0 * 1e3, case.extra_pairs))
        ends = [g.tooth for k, g in enumerate(grids)
                if sol.pressure[contact.block(k)][[0, -1]].max() > 0]
        touched = {g.tooth for k, g in enumerate(grids)
                   if g.probe and sol.pressure[contact.block(k)].max() > 0}
        solved_um = sol.rotation * p.r0 * 1e3 - first_um
        moved = abs(solved_um - elastic_um) > PLACEMENT * max(abs(solved_um), 1e-3)
        if more <= set(teeth) and not ends and not moved and not touched:
            break
        log.info("β %.6f: placing the grids again (teeth %s, ends %s, probes touched %s, "
                 "elastic %.3g µm, expected %.3g)", case.beta, sorted(more - set(teeth)),
                 ends, sorted(touched), solved_um, elastic_um)
        teeth = tuple(sorted(set(teeth) | more))
        full = full | touched | _expected(state, sol.rotation * p.r0 * 1e3)
        for t in ends:
            reach[t] = 2.0 * reach.get(t, 1.0)
        elastic_um = max(solved_um, 1e-6)
    else:
        raise FegearError(f"the contact grids did not settle in {ATTEMPTS} placements")
    formed = sum(g.response_s for g in model.gears) - formed
    times["assemble"] -= formed
    times["responses"] = formed

    t0 = time.perf_counter()
    stresses = ring_stresses(model, contact, sol.pressure)
    touch = first_touch(model, contact, first_um * 1e-3 / p.r0)
    cands = candidate_data(p, model.shape, state, tuple(g.tooth for g in grids), case.beta)
    teeth_out = tooth_results(model, case, contact, sol, stresses, state, cands)
    times["stresses"] = time.perf_counter() - t0
    checks = ContactChecks(sol.balance_error, sol.max_penetration, sol.iterations,
                           tuple(_residuals(model, contact, sol, stresses)), contact.npoints)
    return PairSolution(
        case=case, model="ring", teeth=teeth_out,
        root_stress=(stresses.roots[0].max, stresses.roots[1].max),
        von_mises_max=stresses.von_mises_max, rotation=sol.rotation, first_touch=touch,
        dofs=model.dofs, checks=checks, timings_s=times,
        detail=RingDetail(model, case, contact, sol, stresses))


def _expected(state, closure_um: float) -> set[int]:
    """Teeth a rigid rotation of ``closure_um`` (µm of arc at r0) closes: they get fine grids,
    the others chosen coarse probe grids (:func:`~.grid.tooth_grid`)."""
    return {c.tooth for c in state.teeth
            if c.plus_um is not None and c.plus_um <= closure_um + PROBE_MARGIN_UM}


def _grids(model: RingModel, case: SolveCase, teeth, full: set[int], theta: float,
           elastic_um: float, reach: dict) -> tuple[ToothGrid, ...]:
    """A grid on each of ``teeth`` whose profile a rotation θ (rad, from the kinematic
    position) brings within reach of gear 2 (``reach``: extra factors per tooth); fine on the
    ``full`` ones, a probe on the others."""
    p = case.params
    base = REACH * elastic_um * 1e-3 + REACH_FLOOR * p.m
    turn = p.ratio * case.beta + theta - elastic_um * 1e-3 / p.r0   # at the first touch
    E_star = contact_modulus(case.E, case.E)
    load = case.torque * 1e3 / p.r0 / SHARE_GUESS / case.thickness
    out = []
    for tooth in teeth:
        win = window(model.samples, model.curve2, tooth, turn, case.beta, p.e,
                     base * reach.get(tooth, 1.0))
        if win is not None:
            out.append(tooth_grid(model.samples, win, load, E_star, model.level.per_b,
                                  GRID_FLOOR * p.m, probe=tooth not in full))
    if not out:
        raise FegearError("no tooth comes within reach of gear 2: the pair does not mesh")
    return tuple(out)


def _residuals(model: RingModel, contact: RingContact, sol, stresses) -> list[float]:
    """Each gear's equilibrium residual on its computed sectors (relative to its loads)."""
    out = []
    for side, loads, fields in zip(model.gears, contact.loads, stresses.fields):
        f = {t: b.vector(sol.pressure, side.body.ndofs) for t, b in loads.items()}
        out.append(side.body.residual(f, fields))
    return out

