"""The sector model's solve: scene → meshes → bodies → contact → stresses, per position.

Torque T (N·m) acts on gear 1 counter-clockwise (the ``+`` direction of the clearance table),
through a rigid rotation θ of its bore about O1; gear 2's outer rim is fixed. Teeth are paired
from the unloaded clearance table and an estimate of the loaded rotation (:func:`choose_teeth`);
after the solve every unpaired tooth is checked against the computed rotation, and the scene is
rebuilt with more teeth if one would have closed. The loop over positions and attempts is the
product's (:mod:`fegear.toothpair.positions`); this module supplies one position.

A set of rolling angles (a mesh cycle) shares one scene, one factorisation and one flexibility
per body (:class:`PairModel`), whose rows are formed as contacts first reach their dofs; each
position only places the bodies, pairs the contact points against gear 2's exact curve and
solves the small contact problem.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field, replace

import numpy as np

from ... import progress
from ...fe import (
    Body,
    BodyPlacement,
    RigidLink,
    assemble_body,
    mesh_bodies,
    recover,
    vtu_fields,
)
from ...geometry import Gear1Profile
from ...planar import wrap
from ...timing import timed
from ...toothpair import (
    Attempt,
    BodyField,
    ContactChecks,
    ContactZone,
    PairSolution,
    Trial,
    candidate_data,
    choose_teeth,
    drive,
    expected_elastic_um,
    first_teeth,
)
from ..penalty import (
    ContactError,
    ContactModel,
    ContactPair,
    ContactSettings,
    ContactSolution,
    build_contact,
    first_touch,
    nodal_pressure,
    solve_contact,
)
from .case import SectorCase
from .recovery import root_nodes, root_stresses, tooth_results
from .scene import SECTOR_LEVELS, Scene, build_scene

log = logging.getLogger(__name__)

@dataclass(frozen=True)
class PairModel:
    """The meshed and factorised sector bodies (in their own frames) for a set of rolling
    angles; :func:`solve_position` places them at one β and solves the contact there."""

    case: SectorCase
    scene: Scene = field(repr=False)
    bodies: tuple[Body, Body] = field(repr=False)
    root_zones: tuple[np.ndarray, np.ndarray] = field(repr=False)


def build_model(case: SectorCase, profile: Gear1Profile, positions, teeth,
                reach: dict[int, float] | None = None,
                finer: dict[int, float] | None = None) -> PairModel:
    """Mesh and factorise the sector for the paired ``teeth`` over ``positions`` (β, state);
    ``reach`` and ``finer``: factors on some teeth's contact windows and on their element
    sizes (:func:`~.scene.build_scene`)."""
    with timed("mesh"):
        scene = build_scene(case, profile, positions, teeth, reach=reach, finer=finer)
        m1, m2 = mesh_bodies([scene.gear1, scene.gear2])
    with timed("assemble_factor"):
        mat = case.material
        g1 = assemble_body(m1, mat, link=RigidLink("g1_bore", "rotation", (0.0, 0.0)))
        g2 = assemble_body(m2, mat, fixed=("g2_rim",))
    zones = (root_nodes(g1, scene.profile1, scene.root_band1),
             root_nodes(g2, scene.profile2, scene.root_band2))
    return PairModel(case, scene, (g1, g2), zones)


def solve_positions(case: SectorCase, betas, profile: Gear1Profile | None = None
                    ) -> tuple[PairSolution, ...]:
    """Solve at each rolling angle of ``betas`` (rad) through the product's driver
    (:mod:`fegear.toothpair.positions`): the teeth, the attempts and the timings as the ring
    model's."""
    return drive(case, betas, SectorSolver(), profile)


def solve_pair(case: SectorCase, profile: Gear1Profile | None = None) -> PairSolution:
    """Solve one position."""
    return solve_positions(case, (case.beta,), profile)[0]


class SectorSolver:
    """The sector model as a :class:`~fegear.toothpair.positions.PositionModel`. One scene
    covers every position's contact path for the teeth paired so far; a position whose solved
    rotation would close a tooth outside it is solved again on a scene rebuilt with that tooth,
    and one whose pressure reaches the end of a tooth's contact window (the window is shorter
    than the contact: a near-conformal flank) on a scene with that window twice as long, and
    one where a tooth's flank contact is narrower than its window's elements were made for (a
    lightly loaded tooth: :func:`too_coarse`) on a scene whose window of that tooth is as fine
    as its contact needs (the positions before keep theirs: they settled on theirs)."""

    def __init__(self) -> None:
        self.model: PairModel | None = None
        self.reach: dict[int, float] = {}
        self.finer: dict[int, float] = {}

    def build(self, case: SectorCase, profile: Gear1Profile, states) -> None:
        self.profile, self.states = profile, states()
        elastic = expected_elastic_um(case)
        self._scene(case, _union(first_teeth(case, st, elastic) for _, st in self.states))

    def _scene(self, case: SectorCase, teeth: tuple[int, ...]) -> None:
        progress.stage(f"model: sector meshes of both gears at quality {case.quality}")
        self.model = build_model(case, self.profile, self.states, teeth, self.reach,
                                 self.finer)

    def attempt(self, case: SectorCase, state, trial: Trial,
                near: PairSolution | None) -> Attempt:
        paired = set(self.model.scene.paired)
        if not set(trial.teeth) <= paired:
            log.info("teeth %s would close: rebuilding the scene",
                     sorted(set(trial.teeth) - paired))
            self._scene(case, _union((tuple(paired), trial.teeth)))
            near = None   # its loaded nodes are another scene's
        sol = solve_position(self.model, case.beta, state, near)
        p = case.params
        more = set(choose_teeth(state, p.arc_um(sol.rotation), case.extra_pairs))
        ends = window_ends(sol)
        coarse = too_coarse(sol, SECTOR_LEVELS[case.quality][0])
        if more <= set(self.model.scene.paired) and not ends and not coarse:
            return Attempt(sol, None)
        for tooth in ends:
            self.reach[tooth] = 2.0 * self.reach.get(tooth, 1.0)
        for tooth, factor in coarse.items():
            self.finer[tooth] = factor * self.finer.get(tooth, 1.0)
        if ends or coarse:
            self._scene(case, _union((self.model.scene.paired, trial.teeth)))
        again = Trial(_union((trial.teeth, tuple(more))), trial.elastic_um)
        return Attempt(sol, again, f"teeth {sorted(more - set(self.model.scene.paired))} "
                                   f"would close, windows of teeth {ends} too short, of teeth "
                                   f"{sorted(coarse)} too coarse")

    def finish(self, case: SectorCase, state, attempt: Attempt) -> PairSolution:
        return attempt.solved


#: a tooth's flank contact is resolved where its window's elements are at most this many
#: times the quality's (its elements across the Hertz half-width, SECTOR_LEVELS) at its load
RESOLVED = 2.0
#: a tooth carrying less of the normal load than this is a touch, not a contact to resolve
LIGHT_SHARE = 1e-3
#: the most elements a refined window is cut into (along gear 1's arc): a tooth that barely
#: touches would otherwise take its window to the size floor and the mesh to millions
WINDOW_ELEMENTS = 400


def too_coarse(sol: PairSolution, across: int) -> dict[int, float]:
    """The paired teeth whose flank contact is narrower than their windows' elements were made
    for: each tooth's windows are sized from the Hertz half-width of the first-touching tooth
    at a shared load, so a lightly loaded tooth (a far-side tooth, or a deviated pair's
    unloaded one) has few elements across its contact (one or two: its peak pressure read
    half of the ring's). Per such tooth, where its size exceeds RESOLVED times ``across``
    elements across its Hertz half-width at its solved load, the factor on that size that
    puts ``across`` there, or WINDOW_ELEMENTS along the window if fewer. A contact the round
    carries alone is left to the rounds' size, and a touch (under LIGHT_SHARE of the normal
    load) is left alone."""
    scene = sol.detail.scene
    total = sum(t.load_N for t in sol.teeth)
    out = {}
    for t in sol.teeth:
        h = scene.contact_sizes.get(t.tooth)
        if (h is None or t.load_N <= LIGHT_SHARE * total or t.hertz_b_mm is None
                or t.edge_load_N >= t.load_N):
            continue
        want = max(t.hertz_b_mm / across,
                   scene.window_lengths.get(t.tooth, 0.0) / WINDOW_ELEMENTS)
        if h > RESOLVED * want:
            out[t.tooth] = want / h
    return out


def window_ends(sol: PairSolution) -> list[int]:
    """The paired teeth whose contact pressure reaches either end of their window."""
    d = sol.detail
    out = []
    for k, tooth in enumerate(d.scene.paired):
        sel = np.flatnonzero(d.model.pair_index == k)
        if not len(sel):
            continue
        x = d.model.x[sel]
        phi = np.arctan2(x[:, 1], x[:, 0])
        phi = phi[0] + wrap(phi - phi[0])
        ends = sel[[np.argmin(phi), np.argmax(phi)]]
        if d.contact.pressure[ends].max() > 0:
            out.append(tooth)
    return out


def _union(groups) -> tuple[int, ...]:
    return tuple(sorted(set().union(*groups)))


def solve_position(model: PairModel, beta: float, state,
                   near: PairSolution | None = None) -> PairSolution:
    """Place the model's bodies at β, pair the contact points and solve; stresses per tooth.
    ``state`` is the clearance state at β (for the predicted contact points); ``near``, a
    solution on the same model at a nearby β, starts the contact iterations from its rotation
    and loaded nodes (if that start fails, they start from the first touch)."""
    case = replace(model.case, beta=beta)
    with timed("condense"):
        bodies = place(model, beta)
        contact = pair_contact(model.scene, bodies, beta, case.penalty_factor)
    with timed("contact"):   # the flexibility columns it forms meanwhile: "condense"
        sol = _solve_loaded(contact, case.torque_Nmm, near, beta)
    with timed("recovery"):
        stresses = tuple(recover(b, u) for b, u in zip(bodies, sol.displacements))
        cands = candidate_data(case.params, model.scene.shape, state, model.scene.paired, beta)
        teeth = tooth_results(case, model.scene, bodies, contact, sol, stresses,
                              model.root_zones, cands)
        roots = root_stresses(stresses, model.root_zones)
        vm = float(max(s.von_mises.max() for s in stresses))
    checks = ContactChecks(sol.balance_error, sol.max_penetration, sol.iterations,
                           tuple(sol.residuals), int(contact.npoints))
    return PairSolution(
        case=case, teeth=teeth, root_stress=roots, von_mises_max=vm,
        rotation=sol.link_value, first_touch=_touch_rotation(contact),
        dofs=sum(b.ndofs for b in bodies), checks=checks, timings_s={},
        detail=SectorDetail(model.scene, bodies, contact, sol, stresses, model.root_zones))


@dataclass(frozen=True)
class SectorDetail:
    """The sector model's record of a solved position: scene, placed bodies, contact model and
    solution, nodal stresses and root-zone nodes per body."""

    scene: Scene
    bodies: tuple[Body, Body]
    model: ContactModel
    contact: ContactSolution
    stresses: tuple
    root_zones: tuple[np.ndarray, np.ndarray]

    def body_fields(self, around: int | None = None) -> tuple[BodyField, ...]:
        """Both sectors in the fixed frame with displacement, stresses (components turned into
        the fixed frame) and contact pressure (``around``: no effect, the sectors are the
        loaded teeth already)."""
        out = []
        for i, (b, u, s) in enumerate(zip(self.bodies, self.contact.displacements,
                                          self.stresses)):
            data = vtu_fields(u, s, {"contact_pressure": nodal_pressure(
                self.model, self.contact, i)})
            data["displacement"][:, :2] = b.placement.vec_to_fixed(data["displacement"][:, :2])
            data.update(s.turned(b.placement.angle))
            out.append(BodyField(b.name, b.placement.to_fixed(b.mesh.doflocs.T),
                                 b.mesh.dofs.element_dofs.T, data))
        return tuple(out)

    def peak_fields(self) -> tuple[BodyField, ...]:
        """None: the sector meshes resolve the contacts themselves."""
        return ()

    def flank_pressures(self) -> tuple:
        """None: the sector model's pressures are its nodes' (the VTUs show them)."""
        return ()

    def contact_zone(self) -> ContactZone:
        loaded = max(self.contact.zones, key=lambda z: z.load)
        return ContactZone(tuple(loaded.center), loaded.half_width, loaded.pair)



def place(model: PairModel, beta: float) -> tuple[Body, Body]:
    """The model's bodies placed at rolling angle β: gear 2 turned by β, gear 1 by
    α = (z2/z1) β about its centre (0, e), e with the centre distance's deviation. The factors
    and caches are shared."""
    p = model.case.params
    e = p.e + 1e-3 * model.case.deviations.centre_distance
    return (replace(model.bodies[0], placement=BodyPlacement(p.ratio * beta, (0.0, e))),
            replace(model.bodies[1], placement=BodyPlacement(beta)))


def pair_contact(scene: Scene, bodies: tuple[Body, Body], beta: float,
                 penalty_factor: float) -> ContactModel:
    """The contact model at β: each paired tooth's window on gear 1 against gear 2's exact
    curve, its facets for the elastic part."""
    master = scene.master(beta)
    pairs = [ContactPair(f"tooth {t}", 0, f"g1_contact_{t}", 1, "g2_contact", master)
             for t in scene.paired]
    return build_contact(bodies, pairs, ContactSettings(penalty_factor=penalty_factor))


def _solve_loaded(contact: ContactModel, torque_nmm: float, near: PairSolution | None,
                  beta: float) -> ContactSolution:
    """The contact under the torque, started from ``near``'s rotation and loaded nodes if
    given (and from the first touch if that start fails)."""
    if near is not None:
        loaded = near.detail.model.node[near.detail.contact.force > 0]
        try:
            return solve_contact(contact, load=torque_nmm,
                                 start=(near.rotation, np.isin(contact.node, loaded)))
        except ContactError as err:
            log.info("β %.6f: started from the last position, %s; starting again", beta, err)
    return solve_contact(contact, load=torque_nmm)


def _touch_rotation(model) -> float:
    """Rotation θ (rad) of the rigid gear 1 at which the first slave point touches (the meshed,
    tip-rounded teeth): the linearised first touch, repeated on the exact rigid gaps."""
    theta = 0.0
    for _ in range(6):
        step = first_touch(*model.gap0(theta), load=1.0, k_link=0.0)
        theta += step
        if abs(step) < 1e-13:
            break
    return theta
