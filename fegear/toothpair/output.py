"""Results of the tooth-pair solve: JSON summary, table, VTU files and the von Mises picture.

Files are written in the fixed frame (gear 2 centred at the origin, gear 1 at (0, e), both at
the solved rolling angle), so the two VTUs overlay in ParaView. Stress components are rotated
into that frame; invariants (von Mises, σ1, σ2) need no rotation.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..contact import nodal_pressure
from ..fe import vtu_fields, write_vtu
from ..files import write_csv, write_json
from .case import HEADLINE, PairSolution
from .plot import cycle_png, von_mises_png


def write_cycle_outputs(rows: list[dict], out: Path, title: str) -> dict[str, Path]:
    """cycle.csv (one row per position) and cycle.png (load shares, stresses, TE)."""
    cols = list(rows[0])
    files = {"csv": write_csv(out / "cycle.csv", cols, ([r[c] for c in cols] for r in rows))}
    files["cycle_png"] = cycle_png(out / "cycle.png", rows, title, HEADLINE)
    return files


def fixed_frame_fields(sol: PairSolution, body: int) -> tuple[np.ndarray, dict]:
    """Node coordinates (fixed frame) and VTU point data of one body."""
    b, u, s = sol.bodies[body], sol.contact.displacements[body], sol.stresses[body]
    ang = b.placement.angle
    c, si = math.cos(ang), math.sin(ang)
    data = vtu_fields(b.mesh, u, s, {"contact_pressure": nodal_pressure(sol.model, sol.contact,
                                                                         body)})
    disp = data["displacement"]
    disp[:, :2] = b.placement.vec_to_fixed(disp[:, :2])
    sxx, syy, sxy = s.sxx, s.syy, s.sxy
    data["sxx"] = c * c * sxx + si * si * syy - 2 * c * si * sxy
    data["syy"] = si * si * sxx + c * c * syy + 2 * c * si * sxy
    data["sxy"] = c * si * (sxx - syy) + (c * c - si * si) * sxy
    return b.placement.to_fixed(b.mesh.doflocs.T), data


def write_pair_outputs(sol: PairSolution, out: Path, summary: dict, fields: bool = True,
                       pictures: bool = True) -> dict[str, Path]:
    """gear1.vtu, gear2.vtu (fixed frame; ``fields``), von_mises.png (``pictures``) and
    summary.json in ``out``."""
    files = {}
    data = ([fixed_frame_fields(sol, i) for i in range(len(sol.bodies))]
            if fields or pictures else [])
    if fields:
        for b, (xy, point_data) in zip(sol.bodies, data):
            files[b.name] = write_vtu(out / f"{b.name}.vtu", b.mesh, point_data, xy)
    if pictures:
        files["png"] = von_mises_png(out / "von_mises.png", sol, data)
    summary = {**summary, "files": {**summary.get("files", {}),
                                    **{k: str(v) for k, v in files.items()}}}
    files["summary"] = write_json(out / "summary.json", summary)
    return files


def write_mesh_stiffness(out: Path, rows: list[dict], case) -> dict[str, Path]:
    """mesh_stiffness.json (for ``fegear drive dynamics``) and mesh_stiffness.csv: stiffness
    and unloaded transmission error over one mesh period, by mesh phase."""
    from ..files import write_csv, write_json
    from .stiffness import mesh_stiffness_of_cycle

    p = case.params
    mesh = mesh_stiffness_of_cycle(rows, p.z1, p.z2, p.m, case.thickness, case.torque)
    beta0 = rows[0]["position_deg"]
    table = ((ph, beta0 + ph * 360.0 / p.z2, k, e)
             for ph, k, e in zip(mesh.phase, mesh.stiffness, mesh.error))
    return {"mesh_stiffness": write_json(out / "mesh_stiffness.json", mesh.to_json()),
            "mesh_stiffness_csv": write_csv(
                out / "mesh_stiffness.csv",
                ("phase", "position_deg", "stiffness_Nm_per_rad", "error_rad"), table)}
