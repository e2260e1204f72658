"""What a mesh cycle gives a designer (``fegear solve --positions N``): its table
(:func:`cycle_table`) and its files: cycle.csv and cycle.png (:func:`write_cycle_outputs`), the
mesh stiffness over a mesh period for the drive stage (:func:`write_mesh_stiffness`)."""

from __future__ import annotations

from pathlib import Path

from .... import quantities
from ....files import write_csv, write_json
from ....quantities import FACTORS, HELD
from ...case import HEADLINE
from ...present.tables import TABLE_SAFETY, aligned_table, factor_cell, stiffness_cell
from ...safety import smallest
from ...stiffness import mesh_stiffness_of_cycle
from .plot import cycle_png


def cycle_table(rows: list[dict]) -> str:
    """Markdown table of a cycle (the `fegear solve --positions` output) and the smallest
    safety factors over it."""
    share_keys = [k for k in rows[0] if k.startswith("share_")]
    shown = [k for k in share_keys if any(r[k] > 0 for r in rows)]
    head = ["β [deg]", *(h.short for h in HELD), quantities.EDGE_LOAD.head,
            quantities.VON_MISES.short, *(FACTORS[k].symbol for k in TABLE_SAFETY),
            quantities.TRANSMISSION_ERROR.head, quantities.MESH_STIFFNESS.head, "teeth",
            *(f"tooth {k[6:]}" for k in shown)]
    lines = aligned_table(head, [[
        f"{r['position_deg']:.3f}", f"{r['root_stress_gear1_MPa']:.1f}",
        f"{r['root_stress_gear2_MPa']:.1f}", f"{r['contact_pressure_MPa']:.0f}",
        f"{r['flank_contact_pressure_MPa']:.0f}", f"{r['edge_load_N']:.1f}",
        ("~" if r.get("von_mises_estimated") else "") + f"{r['von_mises_max_MPa']:.0f}",
        *(factor_cell(r.get(k)) for k in TABLE_SAFETY),
        f"{r['transmission_error_urad']:.1f}", stiffness_cell(r["mesh_stiffness_Nm_per_rad"]),
        str(r["teeth_in_contact"]),
        *(f"{r[k]:.3f}" if abs(r[k]) >= 5e-4 else "0.000" for k in shown)] for r in rows])
    if any(r.get("von_mises_estimated") for r in rows):
        lines += ["", "~ von Mises from the surface estimate: the contact submodels are solved "
                  "where the cycle's stresses peak (the estimate is within 1 % of them)"]
    least = smallest(rows)
    if any(v["min"] is not None for v in least.values()):
        lines += ["", "smallest safety factors over the cycle: " + ", ".join(
            f"{FACTORS[k].label} {v['min']:.2f} at β {v['at_position_deg']:.3f}°"
            for k, v in least.items() if v["min"] is not None)]
    return "\n".join(lines)


def write_cycle_outputs(rows: list[dict], out: Path, title: str,
                        allowables=None) -> dict[str, Path]:
    """cycle.csv (one row per position) and cycle.png (load shares, stresses with the
    ``allowables`` and the smallest safety factors, TE)."""
    cols = list(rows[0])
    files = {"csv": write_csv(out / "cycle.csv", cols, ([r[c] for c in cols] for r in rows))}
    files["cycle_png"] = cycle_png(out / "cycle.png", rows, title, HEADLINE, allowables)
    return files


def write_mesh_stiffness(out: Path, rows: list[dict], case) -> dict[str, Path]:
    """mesh_stiffness.json (for ``fegear drive dynamics`` and ``reducer``) and
    mesh_stiffness.csv: secant and tangent stiffness and unloaded transmission error over one
    mesh period, by mesh phase."""
    p = case.params
    mesh = mesh_stiffness_of_cycle(rows, p.z1, p.z2, p.m, case.thickness, case.torque)
    beta0 = rows[0]["position_deg"]
    tangent = mesh.tangent if mesh.tangent is not None else [""] * len(mesh.phase)
    table = ((ph, beta0 + ph * 360.0 / p.z2, k, kt, e)
             for ph, k, kt, e in zip(mesh.phase, mesh.stiffness, tangent, mesh.error))
    return {"mesh_stiffness": write_json(out / "mesh_stiffness.json", mesh.to_json()),
            "mesh_stiffness_csv": write_csv(
                out / "mesh_stiffness.csv",
                ("phase", "position_deg", "stiffness_Nm_per_rad", "tangent_stiffness_Nm_per_rad",
                 "error_rad"), table)}
