"""The tooth-pair FE scene: which teeth to mesh and pair, and the two sector bodies.

Frames (README "Conventions"): gear 2 centred at the origin, gear 1 at O1 = (0, e); at rolling
angle β gear 2 is turned by β and gear 1 by α = (z2/z1) β. Each body is meshed in its own frame
and placed at β (:class:`fegear.fe.BodyPlacement`), so one factorisation serves every position.

* Gear 1 is an annular sector: its exact profile over the chosen teeth, radial cuts through the
  middle of the ``extra``-th unpaired tooth beyond them at each end, and a bore of radius
  ρ1,min − ``rim1`` tied to the rotation unknown that carries the torque (a mechanism: rigid
  rotation about O1).
* Gear 2 is a ring sector: its exact profile over the same angular range, radial cuts through
  a gear-2 tooth tip just beyond gear 1's cuts, and the outer rim at ρ2,max + ``rim2``, fixed.
* Cut faces are traction free. The refined parts are a contact window on every paired flank
  (both gears), long enough to cover the tooth's contact points at every rolling angle of the
  scene, the root zone (the lower ``ROOT_BAND`` of the tooth height) of every tooth space,
  gear 1's tip rounds that a window reaches (and ``ROUND_SPILL`` round Hertz widths of flank
  beyond them), and gear 2's flank under each such round wherever the round comes within
  ``ROUND_GAP`` of it at some β, one Hertz width wider (an edge contact loads both sides over
  the same few µm, so both get the round's element size; gear 1, the contact slave, reaches
  further so that gear 2 never receives its forces as point loads from long slave facets).
  On gear 1 the two tangent points of each such round, where the curvature jumps and the
  edge pressure peaks, are refined again (``JUNCTION_SPAN``, ``JUNCTION_DENSITY``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ...errors import FegearError, ParameterError
from ...fe import BodyGeometry, Refinement, Segment, line_contact
from ...geometry import Cycloid, Gear1Profile, PairParameters, RoundedProfile, gear2_curve
from ...planar import rotate
from ...toothpair import (
    ROOT_BAND,
    SHARE_GUESS,
    Candidate,
    Gear2Master,
    Layout,
    PairProfiles,
    PolarCurve,
    candidate_data,
    gear2_outline,
    gear2_polar,
    path_windows,
    profile_segments,
    root_half_angle,
    round_strips,
    unwrap_near,
)
from .deviated import turned_outline

if TYPE_CHECKING:
    from .case import SectorCase

#: mesh quality → (elements across the Hertz half-width, root size / m, global size / m);
#: each level halves the element sizes of the one before
SECTOR_LEVELS = {"coarse": (2, 1 / 5, 1.0), "fast": (4, 1 / 10, 1 / 2),
           "standard": (8, 1 / 20, 1 / 4), "fine": (16, 1 / 40, 1 / 8)}
WINDOW_B = 2.5           # gear-1 window half-length, in Hertz half-widths at the shared load
WINDOW_MIN = 0.1         # … and at least this many modules
MASTER_FACTOR = 1.4      # gear-2 window half-length relative to gear 1's
# the contact elements and windows are sized for the driver's first load-share guess
# (SHARE_GUESS teeth, fegear/toothpair/positions.py)
ROUND_DENSITY = 2        # the edge zone is a third of the round's Hertz width: twice as fine
ROUND_SPILL = 2.0        # gear 1's round size reaches this many round Hertz widths onto the
                         # flank, gear 2's strip one: the slave is never coarser than the master
JUNCTION_SPAN = 0.25     # round-to-flank tangent points: refined over ± this many round
JUNCTION_DENSITY = 4     # Hertz widths, this many times finer than the round
SIZE_FLOOR = 1e-4        # smallest element, in modules (0.2 µm at m = 2): at light load the
                         # sizes that follow the Hertz widths would shrink to nanometres


@dataclass(frozen=True)
class Scene:
    """Both sector geometries for a set of rolling angles: the paired teeth (contact windows
    covering their contact points at every β of the set) and the exact gear-2 curve."""

    params: PairParameters
    betas: tuple[float, ...]
    gear1: BodyGeometry
    gear2: BodyGeometry
    paired: tuple[int, ...]       # gear-1 teeth with contact windows
    teeth1: tuple[int, ...]       # gear-1 teeth in the sector (paired teeth and extras)
    profile1: tuple[str, ...]     # boundary names along each gear's tooth profile
    profile2: tuple[str, ...]
    root_band1: tuple[float, float]  # radii (mm) of the root zone: the lower ROOT_BAND of the
    root_band2: tuple[float, float]  # tooth height, whatever segment the nodes belong to
    b_full: float                 # Hertz half-width for the whole load on one tooth, mm
    shape: RoundedProfile = field(repr=False)
    curve2: Cycloid = field(repr=False)
    contact_sizes: dict[int, float] = field(default_factory=dict)  # paired tooth → its
    # windows' element size (mm, both gears) …
    window_lengths: dict[int, float] = field(default_factory=dict)  # … and gear 1's window
    # length (mm of arc)

    def master(self, beta: float) -> Gear2Master:
        """Gear 2's exact curve placed at rolling angle β."""
        return Gear2Master(self.curve2, beta)


def hertz_half_width(params: PairParameters, torque_nmm: float, c: Candidate, thickness: float,
                     E: float, nu: float) -> float:
    """Hertz b (mm) at a candidate if it carried ``torque_nmm`` alone (normal load T / r0)."""
    load = torque_nmm / params.r0
    try:
        return line_contact(c.radius1, c.radius2, load, thickness, E, nu).b
    except ParameterError:  # not a Hertz pair (1/R* <= 0): size as a cylinder on a plane
        r = max(abs(c.radius1), abs(c.radius2))
        return line_contact(r, math.inf, load, thickness, E, nu).b


@dataclass(frozen=True)
class Sizes:
    """Element sizes of a scene (mm) and the Hertz half-widths they follow: the contact
    windows, gear 1's tip rounds (and gear 2 under them), the rounds' tangent points, the root
    zones and the rest of the bodies; ``b_full`` for the whole load on the first-touching tooth,
    ``b_round`` for a round on gear 2's flank at the shared load."""

    contact: float
    round: float
    junction: float
    root: float
    body: float
    b_full: float
    b_round: float


def element_sizes(case: SectorCase, shape: RoundedProfile, first: list[Candidate]) -> Sizes:
    """Sizes from the tooth that touches first at each position (it carries the most load),
    not from every paired tooth: pairing more teeth leaves the mesh of the others. The rounds
    meet the gear-2 flank like a cylinder of radius ρ on a plane: their elements follow that
    Hertz half-width at the shared load."""
    p = case.params
    n_b, root_m, global_m = SECTOR_LEVELS[case.quality]
    torque_nmm = case.torque_Nmm
    b_full = max(hertz_half_width(p, torque_nmm, c, case.thickness, case.E, case.nu)
                 for c in first)
    b_shared = b_full / math.sqrt(SHARE_GUESS)  # b ∝ sqrt(load)
    floor = SIZE_FLOOR * p.m
    h_contact = max(b_shared / n_b, floor)
    b_round = min([b_shared] + [line_contact(f.radius, math.inf, torque_nmm / p.r0
                                             / SHARE_GUESS, case.thickness, case.E, case.nu).b
                                for f in shape.fillets])
    h_round = max(min(h_contact, b_round / (ROUND_DENSITY * n_b)), floor)
    return Sizes(contact=h_contact, round=h_round,
                 junction=max(h_round / JUNCTION_DENSITY, floor), root=root_m * p.m,
                 body=global_m * p.m, b_full=b_full, b_round=b_round)


@dataclass(frozen=True)
class Sector:
    """Gear 1's sector: the shortest run of consecutive teeth (indices modulo z1) that holds
    every paired tooth, from ``start``, widened by ``extra`` teeth on each side; tooth offsets
    ``lo`` … ``hi`` from ``start``, cut at polar angles ``phi_a`` < ``phi_b`` (body frame,
    rad, through the middle of the outermost teeth); ``teeth`` its tooth indices."""

    start: int
    lo: int
    hi: int
    phi_a: float
    phi_b: float
    teeth: tuple[int, ...]


def gear1_sector(p: PairParameters, shape: RoundedProfile, teeth, extra: int) -> Sector:
    pitch1 = shape.pitch
    start, span = tooth_run(teeth, p.z1)
    lo, hi = -extra, span + extra
    if hi - lo + 2 > p.z1:
        raise FegearError(f"the paired teeth {list(teeth)} and {extra} more on each side span "
                          f"{hi - lo + 1} of gear 1's {p.z1} teeth: a full-ring model is "
                          "not built (lower the torque or raise the tip clearance)")
    centre0 = shape.tooth_center + start * pitch1
    return Sector(start, lo, hi, centre0 + lo * pitch1, centre0 + hi * pitch1,
                  tuple(int((start + k) % p.z1) for k in range(lo, hi + 1)))


@dataclass(frozen=True)
class SectorBody:
    """One gear's sector geometry, the boundary names along its tooth profile, and the radii
    (mm) of its root zone: the lower ROOT_BAND of the tooth height, whatever segment the nodes
    belong to."""

    geometry: BodyGeometry
    profile: tuple[str, ...]
    root_band: tuple[float, float]


def build_scene(case: SectorCase, profile: Gear1Profile, positions, teeth: tuple[int, ...],
                shape: RoundedProfile | None = None,
                reach: dict[int, float] | None = None,
                finer: dict[int, float] | None = None) -> Scene:
    """Sector geometries for the paired ``teeth`` (gear-1 indices) over ``positions``, a
    sequence of (β, clearance state at β): each tooth's contact windows cover its predicted
    contact points at every β, and the gear-2 sector covers gear 1's at every β.

    Gear 1's tip edges are rounded to ``case.edge_radius`` (:mod:`fegear.geometry.tip_edge`);
    pass ``shape`` to reuse one :class:`RoundedProfile`. ``reach``: factors (tooth → factor)
    on the contact windows of teeth whose contact was longer than their window; ``finer``:
    factors (tooth → factor below 1) on the element size of the windows of teeth whose
    contact was narrower than the size was made for (a lightly loaded tooth)."""
    p = case.params
    shape = shape if shape is not None else RoundedProfile(profile, case.edge_radius)
    betas = tuple(b for b, _ in positions)
    at = [(b, candidate_data(p, shape, st, teeth, b)) for b, st in positions]
    cands = [(b, c) for b, cs in at for c in cs]
    if not cands:
        raise ParameterError("teeth", teeth, "teeth with a contact point on the + flank")
    sizes = element_sizes(case, shape, [min(cs, key=lambda c: c.clearance_um)
                                        for _, cs in at if cs])
    # window half-length per candidate: WINDOW_B Hertz half-widths of its own curvatures at
    # the shared load, at least WINDOW_MIN modules (a contact that only just closes)
    reach = reach or {}
    half = [(c, max(WINDOW_B * hertz_half_width(p, case.torque_Nmm, c, case.thickness, case.E,
                                                case.nu) / math.sqrt(SHARE_GUESS),
                    WINDOW_MIN * p.m) * reach.get(c.tooth, 1.0)) for _, c in cands]
    sector = gear1_sector(p, shape, teeth, case.extra_teeth)
    paired = tuple(sorted({c.tooth for _, c in cands}))
    finer = finer or {}
    floor = SIZE_FLOOR * p.m
    contact = {t: max(sizes.contact * finer.get(t, 1.0), floor) for t in paired}
    gear1, rounds, lengths = gear1_body(case, shape, sector, paired, half, sizes, contact)
    gear2, curve2 = gear2_body(case, shape, sector, paired, half, sizes, betas, rounds, contact)
    return Scene(params=p, betas=betas, gear1=gear1.geometry, gear2=gear2.geometry,
                 paired=paired, teeth1=sector.teeth, profile1=gear1.profile,
                 profile2=gear2.profile, root_band1=gear1.root_band, root_band2=gear2.root_band,
                 b_full=sizes.b_full, shape=shape, curve2=curve2, contact_sizes=contact,
                 window_lengths=lengths)


def _by_size(names: dict[str, float]) -> list[Refinement]:
    """One refinement per element size over the segments ``names`` (name → size) of it."""
    return [Refinement(tuple(n for n, h in names.items() if h == size), size)
            for size in sorted(set(names.values()))]


def gear1_body(case: SectorCase, shape: RoundedProfile, sector: Sector, paired, half,
               sizes: Sizes, contact: dict[int, float]
               ) -> tuple[SectorBody, list[tuple[float, float]], dict[int, float]]:
    """Gear 1's sector: its profile over the sector (windows, each at its tooth's ``contact``
    element size; roots; the refined tip rounds and their tangent points), two radial cuts and
    the bore. Also the body angle ranges of the refined rounds (gear 2 is refined under
    them) and each window's length (mm of arc, about)."""
    m = case.params.m
    pitch1 = shape.pitch
    mid1 = 0.5 * (sector.phi_a + sector.phi_b)
    rho = shape.radius(np.linspace(0, pitch1, 400) + shape.phi_space)
    rho_min, rho_max = float(rho.min()), float(rho.max())
    bore = rho_min - case.rims[0]
    windows1 = path_windows(
        paired, [(c.tooth, unwrap_near(c.phi1, mid1),
                  w / math.hypot(*shape.point(np.array([c.phi1]))[0])) for c, w in half])
    roots1 = [(k, shape.phi_space + (sector.start + k) * pitch1)
              for k in range(sector.lo + 1, sector.hi + 1)]
    root_half1 = root_half_angle(shape.radius, roots1[0][1], pitch1, rho_min, rho_max)
    turn0 = math.floor((sector.phi_a - shape.phi_space) / pitch1)
    # refine the rounds that a contact window reaches (the others never touch)
    fillets = shape.fillet_angles(range(turn0 - 1, turn0 + sector.hi - sector.lo + 2))
    rounds = [(c - h, c + h) for c, h, _ in fillets
              if any(abs(c - p_) < h + w for _, p_, w in windows1)]
    # the tangent points of every round within a module of a window cut the polyline: a
    # spline through a curvature jump overshoots by µm, which snapping onto the exact curve
    # cannot undo in µm elements (further away the elements are coarse; cut there too, a tip
    # land 0.1 mm long became two boundary edges of a sliver under 2 mm elements)
    reach = m / rho_max
    tangents = [(x, x, None) for c, h, _ in fillets for x in (c - h, c + h)
                if any(abs(x - p_) < w + reach for _, p_, w in windows1)]
    spill = ROUND_SPILL * sizes.b_round / rho_max
    # where a round meets the flank the curvature jumps (4 → 0.3 /mm on the baseline): the
    # pressure peaks there over a few µm, so those tangent points get a finer zone of their own
    span = JUNCTION_SPAN * sizes.b_round / rho_max
    junctions = [(x - span, x + span, "g1_junction") for a, b in rounds for x in (a, b)]

    g1_point, g1_project = turned_outline(shape, case.deviations, case.params.r1,
                                          case.params.z1)
    segs1, names1 = profile_segments(
        "g1", PolarCurve(g1_point, g1_project), sector.phi_a, sector.phi_b, Layout(
            windows=tuple((f"g1_contact_{t}", p_, w) for t, p_, w in windows1),
            roots=tuple((f"g1_root_{k}", p_, root_half1) for k, p_ in roots1),
            marks=tuple(junctions + [(a - spill, b + spill, "g1_round") for a, b in rounds]
                        + tangents),
            sizes={"g1_round": sizes.round, "g1_junction": sizes.junction,
                   **{f"g1_contact_{t}": contact[t] for t in paired}}))
    a0 = g1_point(np.array([sector.phi_a]))[0]
    b0 = g1_point(np.array([sector.phi_b]))[0]
    bore_pts = bore * np.column_stack([np.cos(np.linspace(sector.phi_b, sector.phi_a, 60)),
                                       np.sin(np.linspace(sector.phi_b, sector.phi_a, 60))])

    def bore_project(x):
        return bore * x / np.linalg.norm(x, axis=1)[:, None]

    refine1 = [*_by_size({f"g1_contact_{t}": contact[t] for t in paired}),
               Refinement(tuple(n for n in names1 if n.startswith("g1_root")), sizes.root)]
    if any(s.zone == "g1_round" for s in segs1):
        refine1.append(Refinement(("g1_round",), sizes.round))
    if any(s.zone == "g1_junction" for s in segs1):
        refine1.append(Refinement(("g1_junction",), sizes.junction))
    geo1 = BodyGeometry("gear1", (
        *segs1,
        Segment("g1_cut_b", np.array([b0, bore_pts[0]])),
        Segment("g1_bore", bore_pts, bore_project),
        Segment("g1_cut_a", np.array([bore_pts[-1], a0])),
    ), size=sizes.body, refinements=tuple(refine1))
    band1 = (rho_min, rho_min + ROOT_BAND * (rho_max - rho_min))
    lengths = {t: 2.0 * w * float(np.hypot(*shape.point(np.array([p_]))[0]))
               for t, p_, w in windows1}
    return SectorBody(geo1, names1, band1), rounds, lengths


def gear2_body(case: SectorCase, shape: RoundedProfile, sector: Sector, paired, half,
               sizes: Sizes, betas, rounds, contact: dict[int, float]
               ) -> tuple[SectorBody, Cycloid]:
    """Gear 2's ring sector, in its own frame: the fixed-frame range of gear 1's sector at
    every β, cut at gear-2 tooth tips; its windows (one boundary, ``g2_contact``: the contact's
    master; a window whose gear-1 tooth has a finer ``contact`` size than the rest is a zone
    of that size), roots and the strips under gear 1's refined rounds; the fixed outer rim.
    Also gear 2's exact curve."""
    params = case.params
    phi_a, phi_b = sector.phi_a, sector.phi_b
    g2 = gear2_curve(params)
    pitch2 = 2 * math.pi / params.z2

    def body2_angle(phi, beta):  # polar angle in gear 2's frame of a gear-1 body point at β
        x = rotate(shape.point(np.array([phi])), params.ratio * beta)[0] + np.array([0.0,
                                                                                      params.e])
        return math.atan2(x[1], x[0]) - beta

    t_a = min(unwrap_near(body2_angle(phi_a, b), 0.0) for b in betas)
    t_b = max(unwrap_near(body2_angle(phi_b, b), t_a + (phi_b - phi_a)) for b in betas)
    k_a, k_b = math.floor(t_a / pitch2), math.ceil(t_b / pitch2)
    th_a, th_b = k_a * pitch2, k_b * pitch2  # tooth tips (ξ = 2πk/z2 is a tip)
    R_max, R_min = params.r0 + 2 * params.e1, params.r0 - 2 * params.e1
    outer = R_max + case.rims[1]
    windows2 = path_windows(
        paired, [(c.tooth, unwrap_near(c.theta2, 0.5 * (th_a + th_b)),
                  MASTER_FACTOR * w / params.r0) for c, w in half])
    roots2 = [(k, (k + 0.5) * pitch2) for k in range(k_a, k_b)]
    root_half2 = root_half_angle(lambda t: g2.radius_at_angle(t, tabled=False), roots2[0][1],
                                 pitch2, R_min, R_max, inverted=True)   # a mesh's input

    g2_profile = gear2_polar(g2)

    # where a refined round comes near gear 2 at some β, gear 2 under it gets the same size
    marks2 = round_strips(PairProfiles(params, shape, g2), rounds, betas,
                          sizes.b_round / params.r0, 0.5 * (th_a + th_b))
    coarsest = max(contact.values())
    finer = [(t, p_, w) for t, p_, w in windows2 if contact[t] < coarsest]
    finer_sizes = {f"g2_contact_{t}": contact[t] for t, _, _ in finer}
    segs2, names2 = profile_segments("g2", g2_profile, th_a, th_b, Layout(
        windows=tuple(("g2_contact", p_, w) for _, p_, w in windows2),
        roots=tuple((f"g2_root_{k}", p_, root_half2) for k, p_ in roots2),
        marks=tuple(marks2) + tuple((p_ - w, p_ + w, f"g2_contact_{t}") for t, p_, w in finer),
        # (where they overlap, a round's strip rules)
        sizes={"g2_contact": coarsest, "g2_round": sizes.round, **finer_sizes}))
    geo2 = BodyGeometry("gear2", gear2_outline(g2_profile.point, segs2, th_a, th_b, outer, 80),
                        size=sizes.body, refinements=(
        Refinement(("g2_contact",), coarsest),
        *_by_size({z: h for z, h in finer_sizes.items() if any(s.zone == z for s in segs2)}),
        Refinement(tuple(n for n in names2 if n.startswith("g2_root")), sizes.root),
        *([Refinement(("g2_round",), sizes.round)] if marks2 else [])))
    band2 = (R_max - ROOT_BAND * (R_max - R_min), R_max)
    return SectorBody(geo2, names2, band2), g2


def tooth_run(teeth, z: int) -> tuple[int, int]:
    """The shortest run of consecutive tooth indices (modulo ``z``) that holds all of
    ``teeth``: its first tooth and its length minus one. The run leaves out the largest gap
    between paired teeth, wherever the indices wrap."""
    t = sorted({int(k) % z for k in teeth})
    gap, i = max(((t[(i + 1) % len(t)] - t[i]) % z or z, i) for i in range(len(t)))
    return t[(i + 1) % len(t)], z - gap
