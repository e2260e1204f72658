"""CalculiX peer of the tooth-pair solve: the same placed bodies, torque and contact windows.

:func:`ccx_pair` solves a :class:`~fegear.toothpair.SolveCase` with fegear (one position),
writes its bodies with :func:`fegear.verify.calculix.write_deck` and runs CalculiX on them.
Units: mm, N, MPa, rad; the torque is in N·m in the case and N·mm in the deck. Choices (see also
:mod:`fegear.verify.calculix`), measured on the baseline pair (shift 0.016, rotation 0.002):

* **Torque.** Gear 1's bore is tied to a free reference node by two ``*EQUATION`` s per bore
  node (a small rotation θ about O1, placed); its dof 1 carries the torque (``*CLOAD``). The
  rotation is linearised (u = θ ẑ × r), off the exact arc by θ²r/2 (5 nm at 200 N·m against an
  elastic approach of ≈ 16 µm).
* **First touch.** Gear 1 floats until a tooth touches. ``start="touch"`` (default): gear 1 is
  written turned exactly by our first-touch rotation θt (the meshed teeth on gear 2's exact
  curve), step 1 turns it on by ``PRELOAD_FRACTION`` of our elastic rotation, step 2 releases θ
  and applies the torque. ``start="solution"``: written at our converged θ, held there in step
  1 (CalculiX resolves the overclosure), then released; same answer (θ within 0.05 % of the
  elastic rotation at 200 N·m, coarse), same cost. CalculiX pairs its contact points once per
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
* **What agrees, what does not.** θ, the torque shares and tooth loads, and the root stresses
  agree with ours (elastic θ within 0.2 %, shares within 0.002, root σ1 within 2 %, coarse and
  fast, 1 to 200 N·m). ccx's p_max does not: 1.1-2.4× ours per tooth (4-7× at penalty factor
  1000), coarse or fast, penalty factor 3 to 30, either start, either side as slave; with gear
  2's P2 flank instead of its exact curve as our master, ours moved by < 0.1 %. At 20 N·m (flank
  contact, fast) ccx's pressures are ≈ 1.3× ours over a contact whose summed area is ≈ 0.78 ×
  2b·t at the same force, and its integration-point maxima reach 1.9×, while ours is within 2 %
  of Hertz and moves by 1 % from coarse to fast. On the Hertz disks (matched, shifted, in a
  conformal bore, turned in ten increments) ccx agreed within 2 % at penalty factor 30. Read
  ccx's p_max here as unconverged, not as a reference.
* **Read-back.** θ from the reference node (``.dat``); per pair the slave contact force, its
  moment about O1 (torque share: −M/T) and normal force; p_max the largest CSTR at the slave
  integration points, per tooth by the slave element and face; root σ1, the largest in-plane
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

from ..fe import Body, Placement, StressField, contact_modulus
from ..planar import rotate
from ..toothpair import PairSolution, SolveCase, solve_pair
from .calculix import write_deck
from .ccx_files import PeerError, contact_forces, execute, floats, last_block, read_text

CCX_PENALTY_FACTOR = 30.0  # CalculiX's K = this · E*/h (penalty_factor=None: the case's)
PRELOAD_FRACTION = 0.01    # step-1 rotation beyond our first touch, of our elastic rotation
BALANCE_TOL = 0.01         # the contact moments must balance the torque to 1 %
JOB = "pair"


@dataclass(frozen=True)
class CcxPairResult:
    """CalculiX's answer at one position. ``rotation`` θ of gear 1 (rad, from its kinematic
    position); ``p_max`` (MPa) the largest contact pressure; per paired tooth (``teeth``, in
    ``PairSolution.teeth`` order) the normal contact force ``tooth_load`` (N), the torque share
    ``tooth_share`` and ``tooth_p_max`` (MPa); ``root_stress`` (MPa) the largest in-plane σ1
    on each gear's root-zone nodes; ``torque`` (N·mm) the contact moment about O1, summed
    (balances the applied torque); ``wall_s`` ccx's wall clock; ``dofs`` 2 × mesh nodes,
    ``equations`` CalculiX's count; converged ``increments`` and their ``iterations`` (both
    steps); ``contact_points`` slave integration points in contact; ``penalty`` K per deck pair
    (MPa/mm) and ``pairs`` (deck pairs per tooth); ``start_rotation`` θ held in step 1."""

    rotation: float
    p_max: float
    teeth: tuple[int, ...]
    tooth_load: tuple[float, ...]
    tooth_share: tuple[float, ...]
    tooth_p_max: tuple[float, ...]
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


def ccx_pair(case: SolveCase, workdir: str | os.PathLike, threads: int = 1,
             timeout: float | None = None, penalty: str = "size",
             penalty_factor: float | None = CCX_PENALTY_FACTOR, start: str = "touch",
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
    if case.model != "sector":
        raise PeerError("CalculiX solves the sector model's meshes: the case's model must be "
                        "'sector'")
    if solution is not None and solution.case != case:
        raise PeerError("the solution given is not of this case")
    sol = solve_pair(case) if solution is None else solution
    torque = sol.case.torque * 1e3
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

    roots = _root_stress(work / f"{JOB}.frd", sol)
    m = re.search(r"number of equations\s+(\d+)", text)
    return sol, CcxPairResult(
        rotation=float(rotation), p_max=float(rows[:, 2].max()) if len(rows) else 0.0,
        teeth=tuple(t.tooth for t in sol.teeth), tooth_load=tuple(map(float, load)),
        tooth_share=tuple(map(float, share)), tooth_p_max=tuple(map(float, p_tooth)),
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
    return replace(body, placement=Placement(pl.angle + theta, tuple(map(float, offset))))


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
    """Node → (sxx, syy, szz, sxy, syz, szx) of the last STRESS block of an ASCII ``.frd``
    (fixed format: ``-1``, the node in 10 columns, values in 12)."""
    lines = read_text(frd).splitlines()
    at = [i for i, line in enumerate(lines) if line.startswith(" -4  STRESS")]
    if not at:
        raise PeerError(f"ccx wrote no stresses in {str(frd)!r}")
    out = {}
    for line in lines[at[-1] + 1:]:
        if line.startswith(" -3"):
            break
        if line.startswith(" -1"):
            out[int(line[3:13])] = [float(line[13 + 12 * j:25 + 12 * j]) for j in range(6)]
    if not out or not all(math.isfinite(v) for s in out.values() for v in s):
        raise PeerError(f"unreadable stresses in {str(frd)!r}")
    return out
