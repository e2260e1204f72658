"""CalculiX on the extruded sector peer: the 3D check of the pair solved across the face
(``fegear solve --misalignment``, K_Hβ and the worst root stress; docs/validation.md,
"Across the face: a 3D FE of the pair").

:func:`ccx_face` solves the case's 2D sector model (:mod:`fegear.verify.sector`: which teeth,
the placed bodies, the loaded rotation), meshes its two sections again for the extrusion and
extrudes them across the face width into C3D15 wedges (:mod:`.ccx_face_mesh`), gear 1 sheared
by the misalignment, writes the deck (:mod:`.ccx_face_deck`: gear 2's rim held, gear 1's bore
turned by one rotation under the torque, contact per tooth and face layer) and runs CalculiX.
It reads back the line load of every paired tooth along the face (each pair's contact force
over its layer's width), K_Hβ, and the largest σ1 of ccx's nodal stresses on each gear's root
zone (the nodes of the sector model's root zone, on every plane of the face), with its ζ.

K_Hβ is the slice model's ratio (:attr:`~fegear.toothpair.ring.face_results.FaceSections.
load_factor`): the largest line load over the largest tooth mean. CalculiX gives layer means,
and a linear line load's end value exceeds its end layer's mean by half a layer's slope, so the
end values are extrapolated from the two end layers (``end_loads``); :func:`layer_means` gives
the slice model's line loads averaged over the same layers, to compare like with like.

``python -m fegear.verify.calculix_face [misalignment=9.9] [layers=6] [threads=2]`` prints both
models side by side.
"""

from __future__ import annotations

import json
import logging
import re
import sys
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from ..fe import mesh_bodies
from ..geometry import PairParameters
from ..timing import Stopwatch
from ..toothpair import prepare_job, solve_job
from .calculix_pair import CCX_PENALTY_FACTOR, frd_stress, turned_body
from .ccx_face_deck import FaceBodies, write_face_deck
from .ccx_face_mesh import FaceSizes, coarsened, extrude
from .ccx_files import PeerError, contact_forces, execute, floats, last_block
from .sector import SectorCase, solve_pair
from .sector.recovery import root_nodes

log = logging.getLogger(__name__)

LAYERS = 6          # across the face, 0.83 mm each: 250k DOFs, a factorisation of about 40 s
                    # on two threads and 20 of them a run (docs/validation.md)
SIZES = FaceSizes()  # the sections' element sizes (ccx_face_mesh)
BALANCE_TOL = 0.01  # the contact moments must balance the torque to 1 %
JOB = "face"


@dataclass(frozen=True)
class CcxFaceResult:
    """CalculiX's answer on the extruded pair. ``misalignment_um`` (µm over the face);
    ``zeta`` the layers' middles (fractions of the face ``width``, mm); per paired tooth
    (``teeth``) its ``line_load`` on each layer (N/mm, the layer's mean) and ``end_loads``
    (N/mm at ζ = −½ and ½, extrapolated); ``load_factor`` K_Hβ; ``root_stress`` (MPa) the
    largest σ1 on each gear's root zone and ``root_zeta`` where it is; ``rotation`` θ of gear 1
    (rad, from its kinematic position); ``torque`` (N·mm) the contact moment about gear 1's
    axis; ``wall_s`` ccx's wall clock, ``prepare_s`` the 2D solve, meshes and deck; ``dofs``
    3 × nodes; converged ``increments`` and their ``iterations``; ``penalty`` K per tooth."""

    misalignment_um: float
    width: float
    zeta: tuple[float, ...]
    teeth: tuple[int, ...]
    line_load: tuple[tuple[float, ...], ...]
    end_loads: tuple[tuple[float, float], ...]
    load_factor: float
    root_stress: tuple[float, float]
    root_zeta: tuple[float, float]
    rotation: float
    torque: float
    wall_s: float
    prepare_s: float
    dofs: int
    equations: int
    increments: int
    iterations: int
    penalty: tuple[float, ...]


def baseline_case(torque: float = 200.0) -> SectorCase:
    """The paper's baseline pair (shift 0.016, rotation 0.002 mm, 5 mm face) at ``torque``
    (N·m), β = 0, at ``coarse``: the case of the 3D check."""
    return SectorCase(PairParameters(shift=0.016, rotation=0.002), torque=torque,
                      quality="coarse")


def ccx_face(case: SectorCase, workdir, misalignment_um: float = 0.0, layers: int = LAYERS,
             threads: int = 1, timeout: float | None = None) -> CcxFaceResult:
    """Solve ``case`` (one position) on the extruded sector peer with CalculiX, gear 1
    misaligned by ``misalignment_um`` (µm over the face width, as ``fegear solve
    --misalignment``): see the module docstring. The deck and ccx's files stay in
    ``workdir``; ccx runs with ``threads`` threads, killed after ``timeout`` s. Raises
    :class:`~fegear.verify.ccx_files.PeerError` when ccx is missing or fails, or when its
    contact moments do not balance the torque (1 %)."""
    watch = Stopwatch()
    sol = solve_pair(case)
    bodies, zones = face_bodies(sol, misalignment_um, layers)
    torque = case.torque_Nmm
    deck = write_face_deck(bodies, torque, workdir, JOB, CCX_PENALTY_FACTOR)
    prepare = watch.s
    log.info("3D deck: %d nodes, %d C3D15, %d contact pairs (%.1f s)", deck.nodes,
             deck.elements, len(deck.tooth), prepare)
    work = Path(workdir)
    wall, text, steps, dat = execute(work, JOB, threads, timeout)

    ref, _ = last_block(dat, "displacements (vx,vy,vz) for set REF")
    forces = contact_forces(dat, len(deck.tooth))
    c = bodies.centre
    moments = forces[:, 5] - (c[0] * forces[:, 1] - c[1] * forces[:, 0])
    total = -float(moments.sum())
    if not abs(total - torque) <= BALANCE_TOL * torque:
        raise PeerError(f"ccx's contact moment {total:.6g} N·mm does not balance the torque "
                        f"{torque:.6g} N·mm")
    teeth = tuple(bodies.windows)
    loads = np.zeros((len(teeth), layers))
    for (t, k), f in zip(zip(deck.tooth, deck.layer), -forces[:, 6]):
        loads[teeth.index(t), k] = f * layers / case.thickness + 0.0  # ccx's −0 out of contact
    ends = end_loads(loads)
    roots, where = root_stress(work / f"{JOB}.frd", bodies, zones)
    m = re.search(r"number of equations\s+(\d+)", text)
    return CcxFaceResult(
        misalignment_um=float(misalignment_um), width=case.thickness,
        zeta=tuple(float(z) for z in (np.arange(layers) + 0.5) / layers - 0.5), teeth=teeth,
        line_load=tuple(tuple(map(float, row)) for row in loads),
        end_loads=tuple((float(a), float(b)) for a, b in ends),
        load_factor=load_factor(loads, ends), root_stress=roots, root_zeta=where,
        rotation=sol.rotation + floats(ref[0])[1], torque=total, wall_s=wall,
        prepare_s=prepare, dofs=deck.dofs, equations=int(m.group(1)) if m else 0,
        increments=len(steps), iterations=sum(int(s[3]) for s in steps),
        penalty=tuple(deck.penalty[t] for t in teeth))


def face_bodies(sol, misalignment_um: float, layers: int, sizes: FaceSizes = SIZES):
    """The deck's bodies for a 2D sector solution: its sections meshed again at ``sizes``
    (:func:`~.ccx_face_mesh.coarsened`), extruded across the face, gear 1 written turned by
    the solution's rotation and sheared by the misalignment (−ζ·f along x: the slice model's
    displacement of gear 1, :meth:`fegear.toothpair.face.Face.offsets`); and each gear's
    root-zone section nodes."""
    case, scene = sol.case, sol.detail.scene
    g1, g2 = sol.detail.bodies
    placed1 = turned_body(g1, sol.rotation).placement
    loaded = [k for k, t in enumerate(sol.teeth) if t.load_N > 0]
    if not loaded:
        raise PeerError("the 2D solution has no loaded tooth")
    pairs = sol.detail.model.pairs
    g1_mesh = g1.mesh
    window = np.concatenate([g1_mesh.doflocs[:, np.unique(g1_mesh.facets[:, g1_mesh.boundaries[
        pairs[k].slave_boundary]])] for k in loaded], axis=1).T
    near1 = window.mean(axis=0)
    near2 = g2.placement.to_body(placed1.to_fixed(near1[None]))[0]
    meshes = mesh_bodies([coarsened(scene.gear1, sizes, near1),
                          coarsened(scene.gear2, sizes, near2)])
    shear = (-1e-3 * misalignment_um, 0.0)
    ext1 = extrude("gear1", meshes[0].mesh, placed1.to_fixed, layers, case.thickness, shear)
    ext2 = extrude("gear2", meshes[1].mesh, g2.placement.to_fixed, layers, case.thickness)
    centre = placed1.to_fixed(np.asarray([g1.link.center]))[0]
    windows = {t.tooth: p.slave_boundary for t, p in zip(sol.teeth, pairs)}
    bodies = FaceBodies(ext1, ext2, (float(centre[0]), float(centre[1])), shear,
                        g1.link.boundary, g2.fixed_boundaries[0], windows,
                        pairs[0].master_boundary, case.E, case.nu)
    zones = (root_nodes(ext1, scene.profile1, scene.root_band1),
             root_nodes(ext2, scene.profile2, scene.root_band2))
    return bodies, zones


def end_loads(loads: np.ndarray) -> np.ndarray:
    """Per tooth the line load at ζ = −½ and ½ (N/mm), each extrapolated linearly from its two
    end layers' means (the mean of a linear load is its value at the layer's middle)."""
    if loads.shape[1] < 2:
        return np.column_stack([loads[:, 0], loads[:, -1]])
    first = loads[:, 0] + 0.5 * (loads[:, 0] - loads[:, 1])
    last = loads[:, -1] + 0.5 * (loads[:, -1] - loads[:, -2])
    return np.maximum(np.column_stack([first, last]), 0.0)


def load_factor(loads: np.ndarray, ends: np.ndarray) -> float:
    """K_Hβ: the largest line load (layer means and end values) over the largest tooth mean."""
    return float(max(loads.max(), ends.max()) / loads.mean(axis=1).max())


def root_stress(frd: Path, bodies: FaceBodies, zones) -> tuple[tuple[float, float],
                                                               tuple[float, float]]:
    """The largest σ1 (MPa) of ccx's last nodal stresses on each gear's root zone, on every
    plane across the face, and the ζ of each."""
    stress = frd_stress(frd)
    out, where, offset = [], [], 0
    for body, zone in zip((bodies.gear1, bodies.gear2), zones):
        nodes = body.through(zone)
        missing = [n for n in nodes if n + offset + 1 not in stress]
        if missing:
            raise PeerError(f"ccx wrote no stress at root node {missing[0] + offset + 1}")
        s = np.array([stress[n + offset + 1] for n in nodes])  # sxx syy szz sxy syz szx
        tensor = np.stack([s[:, [0, 3, 5]], s[:, [3, 1, 4]], s[:, [5, 4, 2]]], axis=1)
        s1 = np.linalg.eigvalsh(tensor)[:, -1]
        k = int(np.argmax(s1))
        out.append(float(s1[k]))
        where.append(float(body.zeta[nodes[k]]))
        offset += len(body.nodes)
    return (out[0], out[1]), (where[0], where[1])


def layer_means(line_loads: dict, zeta_sections, layers: int) -> dict[int, list[float]]:
    """The slice model's line loads (tooth → values at sections ``zeta_sections``, linear
    between) averaged over ``layers`` equal layers of the face."""
    z = np.asarray(zeta_sections, dtype=float)
    fine = np.linspace(-0.5, 0.5, 64 * layers + 1)
    out = {}
    for tooth, row in line_loads.items():
        q = np.interp(fine, z, np.asarray(row, dtype=float))
        out[int(tooth)] = [float(np.trapezoid(q[k * 64:(k + 1) * 64 + 1],
                                              fine[k * 64:(k + 1) * 64 + 1]) * layers)
                           for k in range(layers)]
    return out


@dataclass(frozen=True)
class FaceCheck:
    """The 3D check of one case: fegear's numbers and CalculiX's. ``fegear_load_factor``
    K_Hβ of the slice model (1 when aligned), ``fegear_root_stress`` (MPa, gear 1 and 2) its
    worst root stresses over the face (the 2D pair's when aligned), ``fegear_line_load`` the
    slice model's line loads averaged over CalculiX's layers (tooth → N/mm, the 2D pair's
    tooth loads over the face width when aligned); ``fegear_s`` its solve's wall time."""

    ccx: CcxFaceResult
    fegear_load_factor: float
    fegear_root_stress: tuple[float, float]
    fegear_line_load: dict[int, list[float]]
    fegear_s: float

    def table(self) -> str:
        """Both models side by side, as a Markdown table."""
        c = self.ccx
        rows = [("K_Hβ", self.fegear_load_factor, c.load_factor),
                ("root σ1, gear 1 [MPa]", self.fegear_root_stress[0], c.root_stress[0]),
                ("root σ1, gear 2 [MPa]", self.fegear_root_stress[1], c.root_stress[1])]
        for t, row in zip(c.teeth, c.line_load):
            ours = self.fegear_line_load.get(t)
            if ours is None and not any(row):
                continue
            for k in (0, len(row) // 2, len(row) - 1):
                rows.append((f"tooth {t} line load at ζ {c.zeta[k]:+.3f} [N/mm]",
                             ours[k] if ours else 0.0, row[k]))
        lines = ["| quantity | fegear | CalculiX 3D | CalculiX − fegear [%] |",
                 "|---|---:|---:|---:|"]
        for name, a, b in rows:
            diff = f"{100 * (b / a - 1):+.2f}" if a else "–"
            lines.append(f"| {name} | {a:.4g} | {b:.4g} | {diff} |")
        return "\n".join(lines)


def face_check(misalignment_um: float, workdir, torque: float = 200.0,
               layers: int = LAYERS, threads: int = 1,
               timeout: float | None = None) -> FaceCheck:
    """The baseline at ``torque`` (N·m), ``coarse``, misaligned by ``misalignment_um``, by
    fegear (``fegear.solve``: the slice model across the face, the 2D pair when aligned) and
    by CalculiX on the extruded sector peer (:func:`ccx_face`)."""
    watch = Stopwatch()
    summary = solve_job(prepare_job({"torque": torque, "quality": "coarse", "no-estimate": True,
                                     "misalignment": misalignment_um or None})).summary
    took = watch.s
    case = baseline_case(torque)
    if misalignment_um:
        face = summary["face"]
        at = face["positions"][0]
        worst = face["worst"]
        ours = (face["K_Hbeta"], (worst["root_stress_gear1_MPa"]["value"],
                                  worst["root_stress_gear2_MPa"]["value"]),
                layer_means(at["line_loads_N_per_mm"], face["zeta"], layers))
    else:
        flat = {int(t["tooth"]): t["load_N"] / case.thickness
                for t in summary["teeth"] if t["load_N"] > 0}
        ours = (1.0, (summary["root_stress_gear1_MPa"], summary["root_stress_gear2_MPa"]),
                {t: [q] * layers for t, q in flat.items()})
    ccx = ccx_face(case, workdir, misalignment_um, layers, threads, timeout)
    return FaceCheck(ccx, ours[0], ours[1], ours[2], took)


def main(argv: list[str]) -> str:
    """``python -m fegear.verify.calculix_face [name=value ...]``: the 3D check of the
    baseline, both models side by side; the names are misalignment (µm, default 9.9: the
    baseline's room is 9.95), torque
    (N·m, 200), layers (LAYERS), threads (2) and workdir (where ccx's files stay; default a
    temporary directory)."""
    given = dict(a.split("=", 1) for a in argv if "=" in a)
    unknown = set(given) - {"misalignment", "torque", "layers", "threads", "workdir"}
    if unknown or len(given) != len(argv):
        raise PeerError(f"arguments are name=value with the names of main's docstring: {argv}")
    logging.basicConfig(level=logging.INFO, format="%(message)s", stream=sys.stderr)
    with tempfile.TemporaryDirectory() as tmp:
        check = face_check(float(given.get("misalignment", 9.9)), given.get("workdir", tmp),
                           float(given.get("torque", 200.0)),
                           int(given.get("layers", LAYERS)), int(given.get("threads", 2)))
    c = check.ccx
    loads = "\n".join(f"tooth {t}: " + " ".join(f"{q:7.1f}" for q in row)
                      for t, row in zip(c.teeth, c.line_load) if any(row))
    return (f"{check.table()}\n\nCalculiX line loads [N/mm] at ζ "
            + " ".join(f"{z:+7.3f}" for z in c.zeta) + f"\n{loads}\n\n"
            f"CalculiX: {c.dofs} DOFs, {c.increments} increments, {c.iterations} iterations, "
            f"{c.wall_s:.0f} s (+ {c.prepare_s:.0f} s: 2D solve, meshes and deck); fegear "
            f"{check.fegear_s:.1f} s; worst gear-1 root at ζ {c.root_zeta[0]:+.3f}\n"
            + json.dumps(asdict(c)))


if __name__ == "__main__":
    sys.stdout.write(main(sys.argv[1:]) + "\n")
