"""The tooth-pair stress solve: scene → meshes → bodies → contact → stresses, per position.

Torque T (N·m) acts on gear 1 counter-clockwise (the ``+`` direction of the clearance table),
through a rigid rotation θ of its bore about O1; gear 2's outer rim is fixed. Teeth are paired
from the unloaded clearance table and an estimate of the loaded rotation (:func:`choose_teeth`);
after the solve every unpaired tooth is checked against the computed rotation, and the scene is
rebuilt with more teeth if one would have closed.

A set of rolling angles (a mesh cycle) shares one scene, one factorisation and one flexibility
per body (:class:`PairModel`), whose rows are formed as contacts first reach their dofs; each
position only places the bodies, pairs the contact points against gear 2's exact curve and
solves the small contact problem.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from .assembly import Body, Material, Placement, RigidLink, assemble_body, facet_nodes
from .contact import ContactError, ContactModel, ContactPair, ContactSettings, build_contact
from .contact_solve import ContactSolution, first_touch, solve_contact
from .errors import FegearError, GeometryError, ParameterError
from .hertz import line_contact
from .mesh import mesh_bodies
from .params import PairParameters, require_range
from .profile import Gear1Profile, wrap
from .scene import QUALITY, Scene, build_scene, candidate_data
from .stress import StressField, recover
from .tca import ToothContact

log = logging.getLogger(__name__)

TOOTH_STIFFNESS = 14.0   # N/(mm·µm): ISO 6336 single-pair stiffness c', for the load estimate
MARGIN_UM = 3.0          # pair every tooth whose clearance is below the rigid closure + 3 µm,
MARGIN_FACTOR = 1.5      # … or below 1.5 × the closure + 3 µm within NEAR_TEETH of such a tooth
NEAR_TEETH = 2
TIP_ROUND = 0.125        # default tip-edge round of gear 1, in modules (0.25 mm at m = 2)
INTERFERENCE_UM = 1e-3   # a clearance below −1 nm of arc is an interference (touching teeth
                         # of a conformal pair come out at about −2e-10 µm)


@dataclass(frozen=True)
class SolveCase:
    """Inputs: the pair, torque (N·m) on gear 1, rolling angle β (rad), face width (mm), one
    material (E MPa, ν), quality, rim thicknesses below the roots (mm; default 3 m), unloaded
    extra teeth meshed on each side, extra teeth paired on each side of the chosen ones
    (beyond what the closure needs: the safety check), penalty factor, gear 1's tip-edge
    round (mm)."""

    params: PairParameters
    torque: float = 200.0
    beta: float = 0.0
    thickness: float = 5.0
    E: float = 206000.0
    nu: float = 0.29
    quality: str = "standard"
    rim1: float | None = None
    rim2: float | None = None
    extra_teeth: int = 2
    extra_pairs: int = 0
    penalty_factor: float = 1000.0
    tip_round: float | None = None

    def __post_init__(self) -> None:
        require_range("torque", self.torque, 0.0, 1e5, lo_open=True, unit="N·m")
        require_range("position", self.beta, -math.pi, math.pi, unit="rad")
        Material(self.E, self.nu, self.thickness)  # validates E, nu, thickness
        if self.quality not in QUALITY:
            raise ParameterError("quality", self.quality, " / ".join(QUALITY))
        for name in ("rim1", "rim2"):
            v = getattr(self, name)
            if v is not None:
                require_range(name, v, 0.5 * self.params.m, 20 * self.params.m, unit="mm")
        require_range("extra_teeth", self.extra_teeth, 1, 10)
        require_range("extra_pairs", self.extra_pairs, 0, 5)
        require_range("penalty_factor", self.penalty_factor, 0.0, 1e6, lo_open=True)
        if self.tip_round is not None:
            require_range("tip_round", self.tip_round, 0.0, 0.5 * self.params.m, unit="mm")

    @property
    def material(self) -> Material:
        return Material(self.E, self.nu, self.thickness, "stress")

    @property
    def edge_radius(self) -> float:
        """Gear 1's tip-edge round (mm); default TIP_ROUND · m."""
        return self.tip_round if self.tip_round is not None else TIP_ROUND * self.params.m

    @property
    def rims(self) -> tuple[float, float]:
        d = 3.0 * self.params.m
        return (self.rim1 if self.rim1 is not None else d,
                self.rim2 if self.rim2 is not None else d)


@dataclass(frozen=True)
class ToothResult:
    """One paired gear-1 tooth: normal load (N), torque share, FE contact pressure peak (MPa)
    and half-width (mm), Hertz p0 and b from the FE load and the analytic curvature radii
    (None where the curvatures are not a Hertz pair), b/R*, unloaded clearance (µm); whether
    the peak sits on gear 1's tip round (edge contact)."""

    tooth: int
    clearance_um: float | None    # None: no + contact point on this tooth at this β
    load_N: float
    load_share: float
    p_max_MPa: float
    half_width_mm: float
    hertz_p0_MPa: float | None
    hertz_b_mm: float | None
    b_over_R: float | None
    root1_MPa: float          # max σ1 in the root zone within ± half a pitch of this tooth
    root2_MPa: float          # … and of the gear-2 tooth it meshes with
    peak_on_round: bool       # the largest traction sits on gear 1's tip-edge round


@dataclass(frozen=True)
class PairSolution:
    """One position of the tooth-pair solve (see module docstring). Stresses in MPa."""

    case: SolveCase
    scene: Scene = field(repr=False)
    bodies: tuple[Body, ...] = field(repr=False)
    model: ContactModel = field(repr=False)
    contact: ContactSolution = field(repr=False)
    stresses: tuple[StressField, ...] = field(repr=False)
    teeth: tuple[ToothResult, ...]
    root_stress: tuple[float, float]          # max σ1 on the root zones of gear 1, gear 2
    von_mises_max: float
    rotation: float                           # θ of gear 1 (rad), from its kinematic position
    first_touch: float                        # θ at which the first tooth touches (rad)
    dofs: int
    timings_s: dict

    @property
    def contact_pressure(self) -> float:
        return max(t.p_max_MPa for t in self.teeth if t.load_N > 0)

    @property
    def mesh_stiffness(self) -> float:
        """Secant mesh stiffness T / (θ − θ_touch), N·m/rad."""
        return self.case.torque / (self.rotation - self.first_touch)

    @property
    def teeth_in_contact(self) -> int:
        return sum(1 for t in self.teeth if t.load_N > 0)

    def headline(self) -> dict[str, float]:
        return {"root_stress_gear1_MPa": self.root_stress[0],
                "root_stress_gear2_MPa": self.root_stress[1],
                "contact_pressure_MPa": self.contact_pressure,
                "von_mises_max_MPa": self.von_mises_max}


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


@dataclass(frozen=True)
class PairModel:
    """The meshed and factorised sector bodies (in their own frames) for a set of rolling
    angles; :func:`solve_position` places them at one β and solves the contact there."""

    case: SolveCase
    scene: Scene = field(repr=False)
    bodies: tuple[Body, Body] = field(repr=False)
    root_zones: tuple[np.ndarray, np.ndarray] = field(repr=False)
    timings_s: dict


def build_model(case: SolveCase, profile: Gear1Profile, positions, teeth) -> PairModel:
    """Mesh and factorise the sector for the paired ``teeth`` over ``positions`` (β, state)."""
    p = case.params
    times = {}
    t0 = time.perf_counter()
    rim1, rim2 = case.rims
    scene = build_scene(p, profile, positions, teeth, case.torque * 1e3, case.thickness, case.E,
                        case.nu, case.quality, rim1, rim2, case.extra_teeth, case.edge_radius)
    m1, m2 = mesh_bodies([scene.gear1, scene.gear2])
    times["mesh"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    mat = case.material
    g1 = assemble_body(m1, mat, link=RigidLink("g1_bore", "rotation", (0.0, 0.0)))
    g2 = assemble_body(m2, mat, fixed=("g2_rim",))
    times["assemble_factor"] = time.perf_counter() - t0
    zones = (_root_nodes(g1, scene.profile1, scene.root_band1),
             _root_nodes(g2, scene.profile2, scene.root_band2))
    return PairModel(case, scene, (g1, g2), zones, times)


def solve_pair(case: SolveCase, profile: Gear1Profile | None = None) -> PairSolution:
    """Solve one position; pairs more teeth until no unpaired tooth would close."""
    profile = profile if profile is not None else Gear1Profile(case.params)
    return solve_positions(case, (case.beta,), profile)[0]


def cycle_positions(beta0: float, n: int, z2: int) -> tuple[float, ...]:
    """``n`` rolling angles evenly across one tooth pitch 2π/z2 of gear 2, from β0."""
    return tuple(float(wrap(beta0 + k * 2 * math.pi / z2 / n)) for k in range(n))


def solve_positions(case: SolveCase, betas, profile: Gear1Profile | None = None
                    ) -> tuple[PairSolution, ...]:
    """Solve at each rolling angle of ``betas`` on one mesh: the windows cover every paired
    tooth's contact path over the positions, the bodies are factorised once (their flexibility
    rows are formed when a position first needs them, then kept), and each position only
    re-pairs the contact points and solves the small contact problem.
    If an unpaired tooth would close at some position, the scene is rebuilt with it."""
    p = case.params
    t0 = time.perf_counter()
    profile = profile if profile is not None else Gear1Profile(p)
    tca = ToothContact(p, profile)
    states = [(b, tca.state(b)) for b in betas]
    t_profile = time.perf_counter() - t0
    _refuse_interference(states)
    force = case.torque * 1e3 / p.r0
    estimate_um = force / (case.thickness * TOOTH_STIFFNESS) / 3.0
    teeth = _union(choose_teeth(st, _first_clearance(st) + estimate_um, case.extra_pairs)
                   for _, st in states)
    for _ in range(4):
        model = build_model(case, profile, states, teeth)
        sols = []
        for k, (beta, state) in enumerate(states):
            sol = solve_position(model, beta, state, sols[-1] if sols else None)
            if k == 0:  # the first position carries the one-off stages
                sol = replace(sol, timings_s={"profile": t_profile, **model.timings_s,
                                              **sol.timings_s})
            sols.append(sol)
        more = _union(choose_teeth(st, s.rotation * p.r0 * 1e3, case.extra_pairs)
                      for (_, st), s in zip(states, sols))
        if set(more) <= set(model.scene.paired):
            return tuple(sols)
        log.info("teeth %s would close: rebuilding the scene", sorted(set(more) - set(teeth)))
        teeth = _union((teeth, more))
    raise FegearError("the paired teeth did not settle after 4 rebuilds")


def _refuse_interference(states) -> None:
    """A pair whose teeth overlap before any load is an interference fit: not modelled."""
    for beta, state in states:
        c = state.closest(+1)
        if c.plus_um < -INTERFERENCE_UM:
            raise GeometryError(f"the unloaded pair interferes: gear-1 tooth {c.tooth} overlaps "
                                f"gear 2 by {-c.plus_um:.3g} µm of arc at r0 at β = "
                                f"{math.degrees(beta):.4g}°; an interference fit is not "
                                "modelled (raise tip_relief, or check shift and rotation)")


def _first_clearance(state) -> float:
    """Smallest + clearance at a position (µm): the rigid closure at first touch."""
    return state.closest(+1).plus_um


def _union(groups) -> tuple[int, ...]:
    return tuple(sorted(set().union(*groups)))


def solve_position(model: PairModel, beta: float, state,
                   near: PairSolution | None = None) -> PairSolution:
    """Place the model's bodies at β, pair the contact points and solve; stresses per tooth.
    ``state`` is the clearance state at β (for the predicted contact points); ``near``, a
    solution on the same model at a nearby β, starts the contact iterations from its rotation
    and loaded nodes (if that start fails, they start from the first touch)."""
    case = replace(model.case, beta=beta)
    p, scene = case.params, model.scene
    times: dict[str, float] = {}
    t0 = time.perf_counter()
    alpha = p.ratio * beta
    g1 = replace(model.bodies[0], placement=Placement(alpha, (0.0, p.e)))
    g2 = replace(model.bodies[1], placement=Placement(beta))
    cands = candidate_data(p, scene.shape, state, scene.paired, beta)
    master = scene.master(beta)
    pairs = [ContactPair(f"tooth {t}", 0, f"g1_contact_{t}", 1, "g2_contact", master)
             for t in scene.paired]
    contact = build_contact([g1, g2], pairs, ContactSettings(penalty_factor=case.penalty_factor))
    times["condense"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    torque = case.torque * 1e3
    sol = None
    if near is not None:
        loaded = near.model.node[near.contact.force > 0]
        try:
            sol = solve_contact(contact, load=torque,
                                start=(near.rotation, np.isin(contact.node, loaded)))
        except ContactError as err:
            log.info("β %.6f: started from the last position, %s; starting again", beta, err)
    if sol is None:
        sol = solve_contact(contact, load=torque)
    # flexibility columns are formed as the active set reaches them: book that as condensing
    times["contact"] = time.perf_counter() - t0 - contact.G.seconds
    times["condense"] += contact.G.seconds

    t0 = time.perf_counter()
    stresses = tuple(recover(b, u) for b, u in zip((g1, g2), sol.displacements))
    zone1, zone2 = model.root_zones
    roots = (float(stresses[0].max_principal[zone1].max()),
             float(stresses[1].max_principal[zone2].max()))
    pitch1, pitch2 = scene.shape.pitch, 2 * math.pi / p.z2
    vm = float(max(s.von_mises.max() for s in stresses))
    patches = {pt.pair: pt for pt in sol.patches}
    a = contact.gap0(sol.link_value)[1]
    by_tooth = {c.tooth: c for c in cands}
    results = []
    for k, tooth in enumerate(scene.paired):
        c = by_tooth.get(tooth)
        sel = contact.pair_index == k
        share = float(-(a[sel] @ sol.force[sel]) / torque)
        patch = patches.get(pairs[k].name)
        load = patch.load if patch else 0.0
        hz = _hertz(c, load, case) if load > 0 and c is not None else None
        clearance = c.clearance_um if c is not None else None
        on_round = _peak_on_round(scene.shape, contact.x[sel], sol.pressure[sel])
        root2 = (_sector_max(g2, stresses[1], zone2, round(c.theta2 / pitch2) * pitch2, pitch2)
                 if c is not None else 0.0)  # gear-2 tooth tips sit at 2πk/z2
        results.append(ToothResult(
            tooth, clearance, load, share, patch.p_max if patch else 0.0,
            patch.half_width if patch else 0.0, hz.p0 if hz else None, hz.b if hz else None,
            hz.b_over_R if hz else None,
            _sector_max(g1, stresses[0], zone1, scene.shape.tooth_center + tooth * pitch1,
                        pitch1), root2, on_round))
    times["recovery"] = time.perf_counter() - t0
    first = _touch_rotation(contact)
    return PairSolution(case, scene, (g1, g2), contact, sol, stresses, tuple(results), roots, vm,
                        sol.link_value, first, g1.ndofs + g2.ndofs, dict(times))


def _peak_on_round(shape, x: np.ndarray, pressure: np.ndarray) -> bool:
    """Whether the largest traction at the points ``x`` (gear 1's frame) sits on a tip round."""
    if not len(pressure) or pressure.max() <= 0:
        return False
    i = int(np.argmax(pressure))
    return bool(shape.on_round(np.arctan2(x[i:i + 1, 1], x[i:i + 1, 0]))[0])


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


def _hertz(c, load: float, case: SolveCase):
    try:
        return line_contact(c.radius1, c.radius2, load, case.thickness, case.E, case.nu)
    except ParameterError:
        return None


def _root_nodes(body: Body, names: tuple[str, ...], band: tuple[float, float]) -> np.ndarray:
    """Profile nodes (on boundaries ``names``) whose radius lies in ``band`` (mm, body frame):
    the root zone, whichever segment (root, flank or contact window) the nodes belong to."""
    nodes = np.unique(np.concatenate([facet_nodes(body.mesh, body.mesh.boundaries[n]).ravel()
                                      for n in names]))
    r = np.linalg.norm(body.mesh.doflocs[:, nodes], axis=0)
    return nodes[(r >= band[0] - 1e-9) & (r <= band[1] + 1e-9)]


def _sector_max(body: Body, stress: StressField, nodes: np.ndarray, centre: float,
                pitch: float) -> float:
    """Largest σ1 among ``nodes`` within half a pitch of the polar angle ``centre``."""
    x = body.mesh.doflocs[:, nodes]
    near = np.abs(wrap(np.arctan2(x[1], x[0]) - centre)) <= 0.5 * pitch
    return float(stress.max_principal[nodes[near]].max()) if near.any() else 0.0
