"""CalculiX peer: the same bodies, supports, penalty and load, solved by CalculiX (``ccx``).

:func:`write_deck` writes a CalculiX 2.20 deck from assembled :class:`~fegear.fe.assembly.Body`
objects (those of a :class:`~fegear.verify.disks.DiskResult` or of a tooth-pair solution),
:func:`execute` runs ccx, :func:`run_ccx` reads a disk deck's answer back, :func:`ccx_disks`
does both beside our own solve of a disk case (the tooth pair: :mod:`fegear.verify.calculix_pair`).
Units: mm, N, MPa. Choices, each checked on the Hertz disks (r 10 mm, P 1000 N, t 5 mm, steel):

* **Mesh.** The very nodes and elements, placed (fixed frame): corners from ``mesh.t``, midside
  nodes from the P2 element dofs, in CalculiX order (1-2-3 corners counter-clockwise, 4 on 1-2,
  5 on 2-3, 6 on 3-1), both checked. Numbers get 13 digits: CalculiX reads at most 20
  characters, and ``-5.47622743141823e-08`` (21) was read as −5.48 ("nonpositive jacobian").
* **Plane stress as CPE6.** CalculiX expands a CPS6 into one layer of C3D15 wedges through the
  thickness; with a contact 2b = 0.22 mm wide in a 5 mm disk that layer is a plate, stiffer than
  plane stress: p_max 5.4 / 19.6 / 4.4 % above Hertz (coarse / standard / fine; the 19.6 % on
  two slave faces), yet 0.35 % above it at t = 0.05 mm. A plane-stress body is written as plane
  strain with E' = E(1 + 2ν)/(1 + ν)², ν' = ν/(1 + ν): exactly plane stress in the plane (σzz,
  εzz differ and are not compared). ``plane_stress_element="CPS6"`` writes the literal element.
* **Contact.** Face-to-face penalty (``TYPE=SURFACE TO SURFACE``): CalculiX advises against
  node-to-face contact on quadratic elements. Slave and master: each pair's boundaries (disk 1's
  and disk 2's "contact"), or a subset of the slave's facets. PRESSURE-OVERCLOSURE=LINEAR with
  K = penalty_factor·E*/h̄ (MPa/mm), h̄ the mean slave facet length (fegear's κ on its uniform
  window) unless the pair brings its own K, applied at the slave face integration points.
  That pointwise penalty needs matching meshes or a soft K: with disk 2 turned by 0.37 of an
  element (coarse), ccx's p_max was 102 / 24.5 / 0.6 % above ours at penalty factors 1000 /
  300 / 30 (matching meshes, 300 to 3000: within 0.05 % of ours).
* **Supports and load.** Fixed boundaries: u = 0. A translation link along x or y: the other
  component 0, the component along it equal to a reference link node's (``*EQUATION``), which
  carries the load. A rotation link: a free reference node at the placed centre c whose dof 1
  is θ, and per link node u_x + (y − c_y)θ = 0, u_y − (x − c_x)θ = 0 (a small rotation), the
  torque (N·mm) on θ. The link body floats until it touches (load control is singular there):
  step 1 prescribes a motion of the reference, a tiny δ0 or the given θ0 (first touch); step 2
  releases it (``*BOUNDARY, OP=NEW``) and applies the load by ``*CLOAD`` in one increment.
  Frictionless, elastic and small, the contact ends in the same state whatever step 1 did.
* **Convergence.** With a stiff penalty CalculiX's defaults (residual 0.5 %, correction 1 %,
  contact elements changing by 0.1 %) accepted wrong active sets: on the fine disks, springs in
  tension (−8.8e4 MPa) and p_max 7.8 % high. Step 2 demands a residual of 1e-6, a correction of
  1e-8 and an unchanged set of contact elements, and forbids CalculiX's automatic softening of
  K (kscalemax 1), within 200 iterations.
* **Read-back** (``.dat``): p_max, the largest CSTR pressure at the slave integration points (the
  ``.frd`` nodal values are extrapolated and overshoot at the contact edges); the contact normal
  force of each pair (``CF``); the total reaction of the fixed supports; θ of a rotation link's
  reference node. ``stresses=True`` also writes the step-2 displacements and stresses to the
  ``.frd``.
"""

from __future__ import annotations

import math
import os
import re
import shutil
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from ..fe import Body, contact_modulus, facet_nodes
from .ccx_files import (
    PeerError,
    contact_forces,
    deck_counts,
    execute,
    floats,
    last_block,
    read_text,
    save_deck,
)
from .disks import DiskCase, DiskResult, solve_disks
from .penalty import ContactSettings

#: step-2 convergence controls (see the module docstring)
CONTROLS = ("*CONTROLS, PARAMETERS=FIELD", "1e-6, 1e-8, , , 1e-6, 1e-5, 1e-3, 1e-8",
            "*CONTROLS, PARAMETERS=TIME INCREMENTATION", "4, 8, 200, 200, 10, 4, 0, 5",
            "*CONTROLS, PARAMETERS=CONTACT", "0, 0.1, 1, 200")
PRELOAD = 1e-6  # step-1 motion δ0, as a fraction of the link body's size
FIELD = 20      # CalculiX reads a number from at most this many characters


@dataclass(frozen=True)
class CcxDeck:
    """A written deck: ``path`` of ``<jobname>.inp``; ``nodes`` and ``elements`` (2D, the
    reference node of a rotation link not counted); ``element_type``; ``penalty`` K per pair
    (MPa/mm); ``preload`` δ0 (mm) or θ0 (rad) of step 1; ``load`` P (N) or T (N·mm); ``link``
    kind; ``equations`` written; ``ref`` the reference node (deck number)."""

    path: Path
    jobname: str
    nodes: int
    elements: int
    element_type: str
    penalty: tuple[float, ...]
    preload: float
    load: float
    link: str = "translation"
    equations: int = 0
    ref: int = 0

    @property
    def dofs(self) -> int:
        return 2 * self.nodes


@dataclass(frozen=True)
class CcxResult:
    """CalculiX's answer. ``p_max`` (MPa) largest contact pressure; ``load`` (N) contact normal
    force, summed over the pairs; ``reaction`` (N) magnitude of the fixed supports' total
    reaction; ``wall_s`` (s) ccx's wall clock; ``dofs`` = 2 × ``nodes`` of the 2D deck,
    ``equations`` CalculiX's count after its 2D → 3D expansion; converged ``increments`` and
    their ``iterations`` over both steps; ``contact_points``: slave integration points in
    contact (of the expanded faces)."""

    p_max: float
    load: float
    reaction: float
    wall_s: float
    dofs: int
    equations: int
    nodes: int
    elements: int
    increments: int
    iterations: int
    contact_points: int


def ccx_available() -> bool:
    """True when a ``ccx`` executable is on the PATH."""
    return shutil.which("ccx") is not None


def _num(x: float) -> str:
    s = f"{float(x):.13g}"
    if len(s) > FIELD or not math.isfinite(float(x)):
        raise PeerError(f"number {x!r} does not fit CalculiX's {FIELD}-character field")
    return s


def _nset(name: str, nodes: np.ndarray) -> list[str]:
    items = [str(int(n)) for n in nodes]
    return [f"*NSET, NSET={name}"] + [", ".join(items[k:k + 8]) + ","
                                      for k in range(0, len(items), 8)]


def element_nodes(body: Body) -> np.ndarray:
    """(nelem, 6) node indices in CalculiX's CPS6/CPE6 order, checked: positive corner area,
    each midside node near the middle of its edge (1-2, 2-3, 3-1)."""
    mesh = body.mesh
    conn = np.asarray(mesh.dofs.element_dofs).T  # corners, then the edges of t2f: 01, 12, 02
    x = mesh.doflocs.T[conn]
    d1, d2 = x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]
    if np.any(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] <= 0):
        raise PeerError(f"body {body.name!r}: element with non-positive corner area")
    for mid, (a, b) in zip((3, 4, 5), ((0, 1), (1, 2), (2, 0))):
        off = np.linalg.norm(x[:, mid] - 0.5 * (x[:, a] + x[:, b]), axis=1)
        if np.any(off > 0.25 * np.linalg.norm(x[:, b] - x[:, a], axis=1)):
            raise PeerError(f"body {body.name!r}: node {mid + 1} is not on edge {a + 1}-{b + 1}")
    return conn


def _faces(body: Body, name: str, facets=None) -> tuple[np.ndarray, np.ndarray]:
    """Elements (0-based) and CalculiX face numbers (1: edge 1-2, 2: 2-3, 3: 3-1) of a boundary,
    or of those of its ``facets`` given."""
    mesh = body.mesh
    f = _boundary(body, name)
    if facets is not None:
        if not np.all(np.isin(facets, f)):
            raise PeerError(f"slave facets outside boundary {name!r} of {body.name!r}")
        f = np.asarray(facets)
    elem = mesh.f2t[0, f]
    if np.any(mesh.f2t[1, f] >= 0):
        raise PeerError(f"boundary {name!r} of {body.name!r} is not on the outside")
    local = np.argmax(mesh.t2f[:, elem] == f, axis=0)
    corners = mesh.t[:, elem].T
    pairs = np.array([[0, 1], [1, 2], [2, 0]])[local]
    ends = np.sort(np.take_along_axis(corners, pairs, axis=1), axis=1)
    if not np.array_equal(ends, np.sort(mesh.facets[:, f].T, axis=1)):
        raise PeerError(f"boundary {name!r} of {body.name!r}: face numbering mismatch")
    return elem, local + 1


def _boundary(body: Body, name: str) -> np.ndarray:
    if name not in body.mesh.boundaries:
        raise PeerError(f"body {body.name!r} has no boundary {name!r}")
    return np.asarray(body.mesh.boundaries[name])


def _nodes(body: Body, names: Sequence[str]) -> np.ndarray:
    """Mesh nodes (0-based) on the named boundaries."""
    return np.unique(np.concatenate([np.zeros(0, dtype=np.int64)] + [
        facet_nodes(body.mesh, _boundary(body, n)).ravel() for n in names]))


def write_deck(bodies: Sequence[Body], load: float, directory: str | os.PathLike,
               jobname: str = "peer", pairs: Sequence | None = None,
               penalty_factor: float = ContactSettings.penalty_factor,
               plane_stress_element: str = "CPE6", preload: float | None = None,
               stresses: bool = False, increments: int = 1) -> CcxDeck:
    """Write ``<directory>/<jobname>.inp`` for ``bodies`` under the link's generalised force
    ``load``: N for a translation link, N·mm (a torque) for a rotation link.

    ``pairs``: objects with ``slave``, ``slave_boundary``, ``master``, ``master_boundary``
    (such as :class:`~fegear.verify.penalty.ContactPair`), optionally ``slave_facets`` (a subset of
    the slave boundary's facets) and ``penalty`` (K, MPa/mm; default penalty_factor·E*/h̄ of
    the pair's slave facets); default: the disk pair, body 0's "contact" against body 1's.
    ``preload``: step-1 motion of the link, δ0 (mm; default 1e-6 × the link body's size) or
    θ0 (rad; required for a rotation link). ``stresses``: write the step-2 displacements and
    stresses to the ``.frd`` (``*NODE FILE``, ``*EL FILE``). ``increments``: step 2 applies
    the load in at least this many increments (CalculiX pairs the contact points once per
    increment).
    """
    linked = _check_deck(bodies, load, penalty_factor, plane_stress_element, preload,
                         increments)
    if pairs is None:
        pairs = [SimpleNamespace(slave=0, slave_boundary="contact", master=1,
                                 master_boundary="contact")]
    lb = bodies[linked]
    numbering = _Numbering.of(bodies)
    lines = ["*HEADING", f"fegear peer deck: {len(bodies)} bodies, load {_num(load)}"]
    lines += _mesh_cards(bodies, numbering, plane_stress_element)
    link = _link_cards(bodies, linked, numbering, preload)
    lines += link.cards
    contact, penalty = _contact_cards(bodies, pairs, numbering, penalty_factor)
    lines += contact
    lines += _step_cards(link, load, increments, len(pairs), stresses)
    path = save_deck(directory, jobname, lines)
    types = {_element_type(b.material, plane_stress_element) for b in bodies}
    return CcxDeck(path=path, jobname=jobname, nodes=numbering.nodes,
                   elements=numbering.elements, element_type="/".join(sorted(types)),
                   penalty=tuple(penalty), preload=link.delta, load=float(load),
                   link=lb.link.kind, equations=link.equations, ref=link.ref)


def _check_deck(bodies, load, penalty_factor, plane_stress_element, preload,
                increments) -> int:
    """Refuse what cannot be exported; the index of the body that carries the load link."""
    if not (isinstance(increments, int) and increments >= 1):
        raise PeerError(f"increments must be an integer >= 1: {increments!r}")
    if plane_stress_element not in ("CPE6", "CPS6"):
        raise PeerError(f"plane_stress_element must be 'CPE6' or 'CPS6': {plane_stress_element!r}")
    if not (math.isfinite(load) and load != 0 and penalty_factor > 0):
        raise PeerError(f"load ({load!r}) must be nonzero, penalty_factor ({penalty_factor!r})"
                        " > 0")
    linked = [i for i, b in enumerate(bodies) if b.link is not None]
    if len(linked) != 1:
        raise PeerError(f"exactly one body must carry the load link, found {len(linked)}")
    lb = bodies[linked[0]]
    if lb.link.kind not in ("translation", "rotation"):
        raise PeerError(f"link kind {lb.link.kind!r} is not exported")
    if lb.link.kind == "rotation" and preload is None:
        raise PeerError("a rotation link needs the step-1 rotation (preload, rad)")
    if lb.link.kind == "translation" and load < 0:
        raise PeerError(f"load ({load!r} N) must be > 0 along the link direction")
    return linked[0]


@dataclass(frozen=True)
class _Numbering:
    """Deck numbering: each body's first node and element (0-based offsets), and the totals."""

    node0: tuple[int, ...]
    elem0: tuple[int, ...]
    nodes: int
    elements: int

    @classmethod
    def of(cls, bodies: Sequence[Body]) -> _Numbering:
        nodes = [b.mesh.doflocs.shape[1] for b in bodies]
        elems = [b.mesh.t.shape[1] for b in bodies]
        return cls(tuple(np.cumsum([0] + nodes[:-1]).tolist()),
                   tuple(np.cumsum([0] + elems[:-1]).tolist()), sum(nodes), sum(elems))


def _element_type(mat, plane_stress_element: str) -> str:
    literal = mat.plane == "strain" or plane_stress_element == "CPS6"
    return "CPS6" if mat.plane == "stress" and literal else "CPE6"


def _mesh_cards(bodies, numbering: _Numbering, plane_stress_element: str) -> list[str]:
    """Nodes (placed, fixed frame), elements, materials and sections of every body. A plane
    stress body is written as plane strain with E', ν' unless ``plane_stress_element`` is
    CPS6 (see the module docstring)."""
    lines = ["*NODE, NSET=NALL"]
    for body, n0 in zip(bodies, numbering.node0):
        for k, (x, y) in enumerate(body.placement.to_fixed(body.mesh.doflocs.T)):
            lines.append(f"{n0 + k + 1}, {_num(x)}, {_num(y)}, 0")
    for i, body in enumerate(bodies):
        conn = element_nodes(body)
        mat = body.material
        literal = mat.plane == "strain" or plane_stress_element == "CPS6"
        E, nu = (mat.E, mat.nu) if literal else (mat.E * (1 + 2 * mat.nu) / (1 + mat.nu) ** 2,
                                                 mat.nu / (1 + mat.nu))
        lines.append(f"*ELEMENT, TYPE={_element_type(mat, plane_stress_element)}, "
                     f"ELSET=BODY{i + 1}")
        lines += [f"{numbering.elem0[i] + e + 1}, "
                  + ", ".join(str(numbering.node0[i] + n + 1) for n in row)
                  for e, row in enumerate(conn)]
        lines += [f"*MATERIAL, NAME=MAT{i + 1}", "*ELASTIC", f"{_num(E)}, {_num(nu)}",
                  f"*SOLID SECTION, ELSET=BODY{i + 1}, MATERIAL=MAT{i + 1}",
                  _num(mat.thickness)]
    return lines


@dataclass(frozen=True)
class _Link:
    """The supports and the load link as deck cards: the reference node and its dof that
    carries the load (with its sign), the support lines, the equations written and the step-1
    motion ``delta``."""

    cards: list[str]
    ref: int
    dof: int
    sign: float
    supports: list[str]
    equations: int
    kind: str
    delta: float


def _link_cards(bodies, linked: int, numbering: _Numbering, preload: float | None) -> _Link:
    lb = bodies[linked]
    fixed = np.concatenate([numbering.node0[i] + _nodes(b, b.fixed_boundaries) + 1
                            for i, b in enumerate(bodies)])
    if len(fixed) == 0:
        raise PeerError("no body has a fixed boundary: nothing reacts the load")
    link = np.setdiff1d(numbering.node0[linked] + _nodes(lb, (lb.link.boundary,)) + 1, fixed)
    cards = _nset("FIXED", fixed) + _nset("LINK", link)
    if lb.link.kind == "rotation":
        card, ref, dof, sign, supports, equations = _rotation_link(
            lb, link, numbering.node0[linked], numbering.nodes + 1)
        delta = float(preload)
    else:
        card, ref, dof, sign, supports, equations = _translation_link(lb, link)
        size = float(np.ptp(lb.mesh.doflocs, axis=1).max())
        delta = PRELOAD * size if preload is None else float(preload)
    return _Link(cards + card, ref, dof, sign, supports, equations, lb.link.kind, delta)


def _contact_cards(bodies, pairs, numbering: _Numbering,
                   penalty_factor: float) -> tuple[list[str], list[float]]:
    """Slave and master surfaces, a linear penalty interaction and a contact pair per pair;
    the penalty K (MPa/mm) of each."""
    lines, penalty = [], []
    for k, pair in enumerate(pairs):
        sb, mb = bodies[pair.slave], bodies[pair.master]
        sub = getattr(pair, "slave_facets", None)
        for role, b, name, facets in (("SLAVE", pair.slave, pair.slave_boundary, sub),
                                      ("MASTER", pair.master, pair.master_boundary, None)):
            elem, face = _faces(bodies[b], name, facets)
            lines.append(f"*SURFACE, NAME={role}{k + 1}, TYPE=ELEMENT")
            lines += [f"{numbering.elem0[b] + e + 1}, S{f}" for e, f in zip(elem, face)]
        facets = _boundary(sb, pair.slave_boundary) if sub is None else np.asarray(sub)
        ends = sb.mesh.doflocs.T[sb.mesh.facets[:, facets]]
        h = np.linalg.norm(ends[1] - ends[0], axis=1).mean()  # mean slave facet length, mm
        K = getattr(pair, "penalty", None)
        penalty.append(float(K) if K is not None else penalty_factor * contact_modulus(
            sb.material.plane_modulus, mb.material.plane_modulus) / h)
        lines += [f"*SURFACE INTERACTION, NAME=PENALTY{k + 1}",
                  "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", _num(penalty[-1]),
                  f"*CONTACT PAIR, INTERACTION=PENALTY{k + 1}, TYPE=SURFACE TO SURFACE",
                  f"SLAVE{k + 1}, MASTER{k + 1}"]
    return lines, penalty


def _step_cards(link: _Link, load: float, increments: int, npairs: int,
                stresses: bool) -> list[str]:
    """Step 1 moves the link's reference by δ0 (or θ0); step 2 releases it and applies the
    load with tight controls; the outputs read back."""
    lines = ["*BOUNDARY", *link.supports,
             "*STEP", "*STATIC", "1., 1.", "*BOUNDARY",
             f"REF, {link.dof}, {link.dof}, {_num(link.sign * link.delta)}", "*END STEP",
             "*STEP, INC=1000", "*STATIC", f"{_num(1 / increments)}, 1., 1e-5, "
             f"{_num(1 / increments)}", *CONTROLS,
             "*BOUNDARY, OP=NEW", *link.supports, "*CLOAD",
             f"REF, {link.dof}, {_num(link.sign * load)}",
             "*NODE PRINT, NSET=FIXED, TOTALS=ONLY", "RF", "*CONTACT PRINT", "CSTR"]
    if link.kind == "rotation":
        lines += ["*NODE PRINT, NSET=REF", "U"]
    for k in range(npairs):
        lines += [f"*CONTACT PRINT, SLAVE=SLAVE{k + 1}, MASTER=MASTER{k + 1}", "CF"]
    if stresses:
        lines += ["*NODE FILE", "U", "*EL FILE", "S"]
    lines.append("*END STEP")
    return lines


def _translation_link(lb: Body, link: np.ndarray) -> tuple:
    """Deck lines of a translation link along x or y: the first link node is the reference,
    the others follow it along the link (``*EQUATION``) and are held across it."""
    d = lb.placement.vec_to_fixed(np.asarray([lb.link.direction]))[0]  # bodies are placed
    axis = int(np.argmax(np.abs(d)))
    if abs(abs(d[axis]) - 1.0) > 1e-12:
        raise PeerError(f"link direction {tuple(d)} is not along x or y")
    ref = int(link[0])
    card = [*_nset("REF", [ref]), "*EQUATION"]
    for n in link[1:]:
        card += ["2", f"{n}, {axis + 1}, 1., {ref}, {axis + 1}, -1."]
    perp = 2 - axis  # CalculiX dof (1 or 2) across the link direction
    return (card, ref, axis + 1, float(np.sign(d[axis])), ["FIXED, 1, 2", f"LINK, {perp}, {perp}"],
            len(link) - 1)


def _rotation_link(lb: Body, link: np.ndarray, offset: int, ref: int) -> tuple:
    """Deck lines of a rotation link: a free reference node at the (placed) centre c whose dof 1
    is θ, and per link node u_x + (y − c_y) θ = 0, u_y − (x − c_x) θ = 0 (small rotation). A
    dof whose lever is zero is held instead (an equation needs a nonzero second term)."""
    x = lb.placement.to_fixed(lb.mesh.doflocs.T[link - 1 - offset])  # deck ids are 1-based
    c = lb.placement.to_fixed(np.asarray([lb.link.center]))[0]
    card = ["*NODE, NSET=REF", f"{ref}, {_num(c[0])}, {_num(c[1])}, 0", "*EQUATION"]
    held, count = [], 0
    tiny = 1e-12 * max(float(np.abs(x - c).max()), 1.0)
    for n, (dx, dy) in zip(link, x - c):
        for dof, lever in ((1, dy), (2, -dx)):
            if abs(lever) <= tiny:
                held.append(f"{n}, {dof}, {dof}")
                continue
            card += ["2", f"{n}, {dof}, 1., {ref}, 1, {_num(lever)}"]
            count += 1
    return card, ref, 1, 1.0, ["FIXED, 1, 2", *held], count


def run_ccx(deck_dir: str | os.PathLike, jobname: str, threads: int = 1,
            timeout: float | None = None) -> CcxResult:
    """Run ``ccx -i <jobname>`` in ``deck_dir`` with ``threads`` threads and read the results
    of a deck from :func:`write_deck` with a translation link. Raises :class:`PeerError` when
    ccx is missing, fails, times out or does not complete the load step, and when the forces
    do not balance."""
    work = Path(deck_dir)
    inp = work / f"{jobname}.inp"
    if inp.is_file() and "*NODE, NSET=REF" in read_text(inp):
        raise PeerError("a rotation-link deck: run it with fegear.verify.calculix_pair.ccx_pair")
    wall, text, steps, dat = execute(work, jobname, threads, timeout)
    pressure, when = last_block(dat, "contact stress")
    if abs(when - 2.0) > 1e-9:
        raise PeerError(f"ccx's last contact output is at time {when}, not at the full load")
    p = np.array([floats(r)[2] for r in pressure])
    if not np.any(p > 0):
        raise PeerError("ccx found no contact at the full load")
    nodes, elements, applied, npairs = deck_counts(read_text(inp))
    load = -contact_forces(dat, npairs)[:, 6].sum()
    reaction, _ = last_block(dat, "total force (fx,fy,fz) for set FIXED")
    m = re.search(r"number of equations\s+(\d+)", text)
    rf = np.array(floats(reaction[0])[:2])
    result = CcxResult(p_max=float(p.max()), load=float(load),
                       reaction=float(np.linalg.norm(rf)), wall_s=wall, dofs=2 * nodes,
                       equations=int(m.group(1)) if m else 0, nodes=nodes, elements=elements,
                       increments=len(steps), iterations=sum(int(s[3]) for s in steps),
                       contact_points=int(np.count_nonzero(p > 0)))
    if not abs(result.load - applied) <= 0.01 * applied:
        raise PeerError(f"contact force {result.load:.6g} N does not balance the load "
                        f"{applied:.6g} N")
    return result


def ccx_disks(case: DiskCase, workdir: str | os.PathLike, threads: int = 1,
              plane_stress_element: str = "CPE6", timeout: float | None = None,
              result: DiskResult | None = None) -> tuple[DiskResult, CcxResult]:
    """Solve the disk ``case`` with fegear (or take its ``result``), export the same bodies and
    pair, and run CalculiX: ``(DiskResult, CcxResult)``. The deck and ccx's files stay in
    ``workdir``."""
    if result is not None and result.case != case:
        raise PeerError("the result given is not of this case")
    result = solve_disks(case) if result is None else result
    write_deck(result.bodies, case.load, workdir, "disks", result.model.pairs,
               case.penalty_factor, plane_stress_element)
    return result, run_ccx(workdir, "disks", threads, timeout)
