"""CalculiX peer of the tooth-pair solve: the same placed bodies, torque and contact windows.

:func:`ccx_pair` solves a :class:`~fegear.verify.sector.SectorCase` with fegear (one position),
writes its bodies with :func:`fegear.verify.calculix.write_deck` and runs CalculiX on them.
Units: mm, N, MPa, rad; the torque is in N·m in the case and N·mm in the deck. Choices (see also
:mod:`fegear.verify.calculix`), measured on the baseline pair (shift 0.016, rotation 0.002):

* **Torque.** Gear 1's bore is tied to a free reference node by two ``*EQUATION`` s per bore
  node (a small rotation θ about O1, placed); its dof 1 carries the torque (``*CLOAD``). The
  rotation is linearised (u = θ ẑ × r), off the exact arc by θ²r/2 (5 nm at 200 N·m against an
  elastic approach of ≈ 16 µm).
* **Start.** Gear 1 floats until a tooth touches. ``start="solution"`` (default): gear 1 is
  written at our converged θ, held there in step 1 (CalculiX resolves the overclosure), then
  released and loaded. ``start="touch"``: written turned exactly by our first-touch rotation θt
  (the meshed teeth on gear 2's exact curve), step 1 turns it on by ``PRELOAD_FRACTION`` of our
  elastic rotation, step 2 releases θ and applies the torque. Same answer (θ within 0.05 % of
  the elastic rotation at 200 N·m, coarse), same cost; but from θt ccx's displacements carry
  the elastic rotation (≈ 20 µm at the teeth), and the ``.frd``'s six digits of that, times our
  stiffness, left ±10-30 MPa of noise on the round's 1 µm facets where nothing touches, which
  widened a contact by 2.4 % (baseline, 200 N·m, fast); from our θ they are the deformation
  alone. CalculiX pairs its contact points once per
  increment, which goes wrong when the flanks slip far within one: a disk turned about an
  offset centre (6.5 µm of slip, coarse Hertz disks) gave p_max +7.7 % in one increment, +0.2 %
  in ten (``increments``). ccx's θ counts from the kinematic position, as ours.
* **Contact pairs and penalty.** One pair per paired tooth: its window ``g1_contact_<t>`` (slave)
  against gear 2's whole ``g2_contact`` boundary (master), as in our model. Our κ_i =
  penalty_factor·E*/h_i follows the local slave facet length, and a window's tip round is meshed
  up to 100× finer than its flank; CalculiX takes one K per interaction. With ``penalty="size"``
  (default) each window is split by facet length into factor-2 bands (h in (h_max/2^(k+1),
  h_max/2^k]), each band its own pair with K from its mean facet length (within a factor 2 of
  our κ everywhere); ``penalty="pair"`` gives each window one K from its mean facet length (stiffer
  than ours on the flank, softer on the round). CalculiX's penalty factor is
  ``CCX_PENALTY_FACTOR`` = 30, not the case's 1000: its pointwise penalty over-constrains
  non-matching quadratic faces (:mod:`fegear.verify.calculix`: disks shifted by 0.37 element, p_max
  +102 % at 1000, +0.6 % at 30) and at 1000 took twice the iterations (56 against 26,
  coarse, 1 N·m); θ moves by 0.1-0.2 % of the elastic rotation.
* **What agrees, and how ccx's pressure is read.** θ, the torque shares and tooth loads, and
  the root stresses agree with ours (elastic θ within 0.2 %, shares within 0.002, root σ1 within
  2 %, coarse and fast, 1 to 200 N·m). ccx's own pressure output, CSTR, is a pointwise penalty
  × overclosure at one slave integration point; in these decks about 30 % of the contact area
  carries no spring (ccx's reported contact area is 0.67-0.74 of the facets in contact, 1.00 on
  the Hertz disks) and the points scatter ±30 % within a facet, so its largest CSTR is 1.9-3.2×
  the pressure the contact transmits, at any penalty factor from 3 to 30, either start, either
  side as slave. The transmitted pressure is read instead from ccx's displacements: K u with
  our stiffness on the same mesh gives gear 1's nodal contact forces, which are averaged over
  our contact nodes' hats and then per facet, exactly as ours are read (:func:`facet_reading`);
  that agrees with ours within about 3 % in peak and 2 % in half-width per loaded tooth
  (docs/benchmark.md, "CalculiX"). On the Hertz disks (matched,
  shifted, in a conformal bore, turned in ten increments) even the CSTR maximum agreed within
  2 % at penalty factor 30.
* **Read-back.** θ from the reference node (``.dat``); per pair the slave contact force, its
  moment about O1 (torque share: −M/T) and normal force; the largest CSTR at the slave
  integration points, per tooth by the slave element and face; gear 1's displacements (``.frd``)
  for the transmitted pressure; root σ1, the largest in-plane
  principal stress of ccx's nodal stresses (``.frd``, extrapolated from the integration points
  and averaged: ours are L2-projected) over the root-zone nodes of each gear (the nodes of our
  ``root_stress``).
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from ..fe import Body, BodyPlacement, StressField, contact_modulus
from ..planar import rotate
from ..toothpair import PairSolution
from .calculix import write_deck
from .ccx_files import PeerError, contact_forces, execute, floats, last_block, read_text
from .penalty import forces_from_body
from .sector import SectorCase, contact_split, solve_pair

CCX_PENALTY_FACTOR = 30.0  # CalculiX's K = this · E*/h (penalty_factor=None: the case's)
PRELOAD_FRACTION = 0.01    # step-1 rotation beyond our first touch, of our elastic rotation
BALANCE_TOL = 0.01         # the contact moments must balance the torque to 1 %
JOB = "pair"


@dataclass(frozen=True)
class CcxPairResult:
    """CalculiX's answer at one position. ``rotation`` θ of gear 1 (rad, from its kinematic
    position); ``cstr_max`` (MPa) the largest CSTR (a pointwise penalty pressure, not the
    transmitted one: module docstring); per paired tooth (``teeth``, in ``PairSolution.teeth``
    order) the normal contact force ``tooth_load`` (N), the torque share ``tooth_share``,
    ``tooth_cstr_max`` (MPa) and, read from ccx's displacements as ours is read
    (:func:`facet_reading`), ``tooth_pressure`` (MPa), ``tooth_half_width`` (mm),
    ``tooth_facet_load`` (N), ``tooth_flank_pressure`` (MPa) and ``tooth_edge_load`` (N, on the
    tip round); ``root_stress`` (MPa) the largest in-plane σ1
    on each gear's root-zone nodes; ``torque`` (N·mm) the contact moment about O1, summed
    (balances the applied torque); ``wall_s`` ccx's wall clock; ``dofs`` 2 × mesh nodes,
    ``equations`` CalculiX's count; converged ``increments`` and their ``iterations`` (both
    steps); ``contact_points`` slave integration points in contact; ``penalty`` K per deck pair
    (MPa/mm) and ``pairs`` (deck pairs per tooth); ``start_rotation`` θ held in step 1."""

    rotation: float
    cstr_max: float
    teeth: tuple[int, ...]
    tooth_load: tuple[float, ...]
    tooth_share: tuple[float, ...]
    tooth_cstr_max: tuple[float, ...]
    tooth_pressure: tuple[float, ...]
    tooth_half_width: tuple[float, ...]
    tooth_facet_load: tuple[float, ...]
    tooth_flank_pressure: tuple[float, ...]
    tooth_edge_load: tuple[float, ...]
    root_stress: tuple[float, float]
    torque: float
    wall_s: float
    dofs: int
    equations: int
    increments: int
    iterations: int
    contact_points: int
    penalty: tuple[float, ...]
    pairs: tuple[int, ...]
    start_rotation: float

    @property
    def pressure(self) -> float:
        """The largest contact pressure (MPa), read from ccx's displacements as ours is."""
        return max(self.tooth_pressure, default=0.0)


def size_bands(h: np.ndarray) -> np.ndarray:
    """Band k of each facet length h: h in (h_max/2^(k+1), h_max/2^k]."""
    h = np.asarray(h, dtype=float)
    return np.floor(np.log2(h.max() / h) + 1e-9).astype(np.int64)


def pair_surfaces(sol: PairSolution, penalty: str = "size",
                  penalty_factor: float | None = None) -> tuple[list, list[int]]:
    """Deck contact pairs for a tooth-pair solution (see the module docstring) and, per deck
    pair, the index of its tooth in ``sol.teeth``. ``penalty_factor``: default the case's."""
    if penalty not in ("size", "pair"):
        raise PeerError(f"penalty must be 'size' or 'pair': {penalty!r}")
    pf = sol.case.penalty_factor if penalty_factor is None else float(penalty_factor)
    if not (math.isfinite(pf) and pf > 0):
        raise PeerError(f"penalty_factor must be > 0: {penalty_factor!r}")
    g1, g2 = sol.detail.bodies
    modulus = contact_modulus(g1.material.plane_modulus, g2.material.plane_modulus)
    pairs, owner = [], []
    for k, pair in enumerate(sol.detail.model.pairs):
        facets = np.asarray(g1.mesh.boundaries[pair.slave_boundary])
        ends = g1.mesh.doflocs.T[g1.mesh.facets[:, facets]]
        h = np.linalg.norm(ends[1] - ends[0], axis=1)
        bands = size_bands(h) if penalty == "size" else np.zeros(len(h), dtype=np.int64)
        for band in np.unique(bands):
            sel = bands == band
            pairs.append(SimpleNamespace(
                slave=pair.slave, slave_boundary=pair.slave_boundary, slave_facets=facets[sel],
                master=pair.master, master_boundary=pair.master_boundary,
                penalty=pf * modulus / h[sel].mean()))
            owner.append(k)
    return pairs, owner


def ccx_pair(case: SectorCase, workdir: str | os.PathLike, threads: int = 1,
             timeout: float | None = None, penalty: str = "size",
             penalty_factor: float | None = CCX_PENALTY_FACTOR, start: str = "solution",
             increments: int = 1,
             solution: PairSolution | None = None) -> tuple[PairSolution, CcxPairResult]:
    """Solve ``case`` (one position, β = ``case.beta``) with fegear, or take its ``solution``,
    and run CalculiX on the same placed bodies, contact windows and torque:
    ``(PairSolution, CcxPairResult)``. The deck (``pair.inp``) and ccx's files stay in
    ``workdir``; ccx runs with ``threads`` threads, killed after ``timeout`` s.

    ``penalty``: "size" or "pair" (K per facet-size band or per window); ``penalty_factor``:
    CalculiX's (None: the case's); ``start``: "touch" or "solution" (where gear 1 is written and
    held in step 1); ``increments``: at least this many increments in step 2 (see the module
    docstring). Raises :class:`~fegear.verify.calculix.PeerError` when ccx is missing or
    fails, or when its contact moments do not balance the torque (1 %)."""
    if not isinstance(case, SectorCase):
        raise PeerError("CalculiX solves the sector model's meshes: the case must be a "
                        "SectorCase")
    if solution is not None and solution.case != case:
        raise PeerError("the solution given is not of this case")
    sol = solve_pair(case) if solution is None else solution
    torque = sol.case.torque_Nmm
    pairs, owner = pair_surfaces(sol, penalty, penalty_factor)
    if start == "solution":
        turned, theta0 = sol.rotation, 0.0
    elif start == "touch":
        turned, theta0 = sol.first_touch, PRELOAD_FRACTION * (sol.rotation - sol.first_touch)
    else:
        raise PeerError(f"start must be 'solution' or 'touch': {start!r}")
    g1, g2 = sol.detail.bodies
    deck = write_deck((turned_body(g1, turned), g2), torque, workdir, JOB, pairs,
                      sol.case.penalty_factor, preload=theta0, stresses=True,
                      increments=increments)
    work = Path(workdir)
    wall, text, steps, dat = execute(work, JOB, threads, timeout)

    ref, _ = last_block(dat, "displacements (vx,vy,vz) for set REF")
    rotation = turned + floats(ref[0])[1]
    centre = g1.placement.to_fixed(np.asarray([g1.link.center]))[0]
    forces = contact_forces(dat, len(pairs))
    moments = forces[:, 5] - (centre[0] * forces[:, 1] - centre[1] * forces[:, 0])
    n = len(sol.teeth)
    load = np.bincount(owner, -forces[:, 6], minlength=n)
    share = np.bincount(owner, -moments, minlength=n) / torque
    total = -float(moments.sum())
    if not abs(total - torque) <= BALANCE_TOL * torque:
        raise PeerError(f"ccx's contact moment {total:.6g} N·mm does not balance the torque "
                        f"{torque:.6g} N·mm")

    press, when = last_block(dat, "contact stress")
    if abs(when - 2.0) > 1e-9:
        raise PeerError(f"ccx's last contact output is at time {when}, not at the full load")
    rows = np.array([floats(r)[:3] for r in press]).reshape(-1, 3)
    which = _face_owner(deck.path, len(pairs))
    p_tooth = np.zeros(n)
    for e, f, p in rows:
        k = which.get((int(e), int(f) - 2))  # a 2D face S<f> is face f + 2 of the wedge
        if k is None:
            raise PeerError(f"ccx contact stress on element {int(e)} face {int(f)}: no pair")
        p_tooth[owner[k]] = max(p_tooth[owner[k]], p)

    frd = work / f"{JOB}.frd"
    roots = _root_stress(frd, sol)
    read = recovered_contact(sol, turned, frd_block(frd, "DISP", 3))
    m = re.search(r"number of equations\s+(\d+)", text)
    return sol, CcxPairResult(
        rotation=float(rotation), cstr_max=float(rows[:, 2].max()) if len(rows) else 0.0,
        teeth=tuple(t.tooth for t in sol.teeth), tooth_load=tuple(map(float, load)),
        tooth_share=tuple(map(float, share)), tooth_cstr_max=tuple(map(float, p_tooth)),
        **{f"tooth_{k}": tuple(r[k] for r in read)
           for k in ("pressure", "half_width", "facet_load", "flank_pressure", "edge_load")},
        root_stress=roots, torque=total, wall_s=wall, dofs=deck.dofs,
        equations=int(m.group(1)) if m else 0, increments=len(steps),
        iterations=sum(int(s[3]) for s in steps),
        contact_points=int(np.count_nonzero(rows[:, 2] > 0)), penalty=deck.penalty,
        pairs=tuple(int(c) for c in np.bincount(owner, minlength=n)),
        start_rotation=turned + theta0)


def turned_body(body: Body, theta: float) -> Body:
    """``body`` placed turned by its rotation link's exact rotation θ (about the link centre)."""
    c = np.asarray([body.link.center], dtype=float)
    pl = body.placement
    offset = np.asarray(pl.offset) + pl.vec_to_fixed(c - rotate(c, theta))[0]
    return replace(body, placement=BodyPlacement(pl.angle + theta, tuple(map(float, offset))))


def _face_owner(inp: Path, npairs: int) -> dict[tuple[int, int], int]:
    """(element, 2D face) → deck pair, from the deck's SLAVE surfaces."""
    which, k = {}, None
    for line in read_text(inp).splitlines():
        if line.startswith("*"):
            m = re.match(r"\*SURFACE, NAME=SLAVE(\d+)", line)
            k = int(m.group(1)) - 1 if m else None
        elif k is not None and line.strip():
            e, f = line.split(",")
            which[(int(e), int(f.strip()[1:]))] = k
    if len(set(which.values())) != npairs:
        raise PeerError(f"the deck has {len(set(which.values()))} slave surfaces, not {npairs}")
    return which


def _root_stress(frd: Path, sol: PairSolution) -> tuple[float, float]:
    """Largest in-plane σ1 (MPa) of ccx's last nodal stresses on each gear's root-zone nodes."""
    stress = frd_stress(frd)
    out, offset = [], 0
    for body, zone in zip(sol.detail.bodies, sol.detail.root_zones):
        nodes = offset + zone + 1
        offset += body.mesh.doflocs.shape[1]
        missing = [n for n in nodes if n not in stress]
        if missing:
            raise PeerError(f"ccx wrote no stress at root node {missing[0]}")
        s = np.array([stress[n] for n in nodes]).T  # sxx, syy, szz, sxy, …
        out.append(float(StressField(s[0], s[1], s[3], s[2], "stress").s1.max()))
    return out[0], out[1]


def frd_stress(frd: Path) -> dict[int, list[float]]:
    """Node → (sxx, syy, szz, sxy, syz, szx) of the last STRESS block of an ASCII ``.frd``."""
    return frd_block(frd, "STRESS", 6)


def frd_block(frd: Path, name: str, ncomp: int) -> dict[int, list[float]]:
    """Node → its ``ncomp`` values in the last ``name`` block (``STRESS``, ``DISP``) of an ASCII
    ``.frd`` (fixed format: ``-1``, the node in 10 columns, values in 12)."""
    lines = read_text(frd).splitlines()
    at = [i for i, line in enumerate(lines) if line.startswith(f" -4  {name} ")]
    if not at:
        raise PeerError(f"ccx wrote no {name} block in {str(frd)!r}")
    out = {}
    for line in lines[at[-1] + 1:]:
        if line.startswith(" -3"):
            break
        if line.startswith(" -1"):
            out[int(line[3:13])] = [float(line[13 + 12 * j:25 + 12 * j]) for j in range(ncomp)]
    if not out or not all(math.isfinite(v) for s in out.values() for v in s):
        raise PeerError(f"unreadable {name} block in {str(frd)!r}")
    return out


def recovered_contact(sol: PairSolution, turned: float,
                      disp: dict[int, list[float]]) -> list[dict[str, float]]:
    """CalculiX's contact per paired tooth, read as :func:`facet_reading` reads ours: gear 1's
    nodal forces K u from ccx's displacements ``disp`` (node → (ux, uy, uz), fixed frame, gear 1
    written turned by ``turned``) and our stiffness, averaged over our contact nodes' hats
    (:func:`~fegear.verify.penalty.forces_from_body`)."""
    g1 = sol.detail.bodies[0]
    nodes = np.arange(g1.mesh.doflocs.shape[1])
    if any(n + 1 not in disp for n in nodes):
        raise PeerError("ccx wrote no displacement at some of gear 1's nodes")
    U = np.array([disp[n + 1][:2] for n in nodes])
    u = np.zeros(g1.ndofs)
    u[g1.node_dofs(nodes)] = turned_body(g1, turned).placement.vec_to_body(U)
    return facet_reading(sol, forces_from_body(sol.detail.model, 0, g1.K @ u))


def facet_reading(sol: PairSolution, lam: np.ndarray) -> list[dict[str, float]]:
    """Per paired tooth, the contact of node forces ``lam`` (N, the contact model's nodes) read
    per slave facet: the facet's mean pressure p̄ = (p_a + p_b)/2 of its corner nodes' λ/D, which
    takes out the node-to-node zig-zag a pointwise penalty leaves. ``pressure`` the largest p̄
    (MPa); ``half_width`` (mm) from the second moment of the facet loads over the run of
    loaded facets around the peak (2·√(Σ F (s − s̄)² + F h²/12)/Σ F), as an elliptic pressure
    gives its b; ``facet_load`` (N) of that run; ``flank_pressure`` (MPa) and the round's
    ``edge_load`` (N) as :func:`~fegear.verify.sector.contact_split` splits them."""
    model = sol.detail.model
    thickness = sol.case.thickness
    out = []
    for k in range(len(model.pairs)):
        sel = np.flatnonzero(model.pair_index == k)
        sel = sel[np.argsort(model.arc[sel])]
        p = lam[sel] / model.weight[sel]
        bar = np.maximum(0.5 * (p[1:] + p[:-1]), 0.0)
        zero = {"pressure": 0.0, "half_width": 0.0, "facet_load": 0.0, "flank_pressure": 0.0,
                "edge_load": 0.0}
        if not len(bar) or bar.max() <= 0:
            out.append(zero)
            continue
        j = int(np.argmax(bar))
        lo, hi = j, j + 1
        while lo > 0 and bar[lo - 1] > 0:
            lo -= 1
        while hi < len(bar) and bar[hi] > 0:
            hi += 1
        s = model.arc[sel]
        h, mid = np.diff(s)[lo:hi], 0.5 * (s[1:] + s[:-1])[lo:hi]
        F = bar[lo:hi] * h * thickness
        mean = np.sum(F * mid) / F.sum()
        half = 2.0 * math.sqrt(np.sum(F * ((mid - mean) ** 2 + h**2 / 12)) / F.sum())
        x = 0.5 * (model.x[sel][1:] + model.x[sel][:-1])
        split = contact_split(sol.detail.scene.shape, x, bar, sol.case, half)
        out.append({"pressure": float(bar[j]), "half_width": half, "facet_load": float(F.sum()),
                    "flank_pressure": split.get("flank_p_MPa", 0.0),
                    "edge_load": split.get("edge_load_N", 0.0)})
    return out
