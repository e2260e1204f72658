"""Drive-level results as tables, JSON and CSV: bearing forces (seed 000), ratios and
efficiencies, and the lumped model's response (``fegear drive …``)."""

from __future__ import annotations

import math
from dataclasses import asdict
from pathlib import Path

import numpy as np

from ..files import write_csv, write_json
from ..toothpair import MeshStiffness
from .bearings import (
    LOAD_CASES,
    PAPER,
    RingDrive,
    bearing_forces,
    exact_extremes,
    extremes,
    support_reactions,
)
from .dynamics import Response, TorsionalPair
from .plot import bearings_png, dynamics_png


def bearings_summary(drive: RingDrive, step_deg: float) -> dict:
    """Extremes of every load case on the crank-angle grid and exact, support reactions,
    and the paper's printed values when ``drive`` is its worked example."""
    out = {"inputs": asdict(drive), "derived": {
        "ratio_i_H1": drive.ratio, "eccentricity_mm": drive.eccentricity,
        "omega_H_rad_s": drive.omega_H, "normal_force_N": drive.normal_force,
        "P_i2_N": drive.P_i2, "P_H_N": drive.P_H}, "grid_step_deg": step_deg,
        "load_cases": {str(c): {"gravity": g, "inertia": i} for c, (g, i) in LOAD_CASES.items()},
        "extremes": [asdict(e) for c in LOAD_CASES for e in extremes(drive, c, step_deg)],
        "exact_extremes": [asdict(e) for c in LOAD_CASES for e in exact_extremes(drive, c)]}
    if drive.rings == 3:
        out["support_reactions"] = asdict(support_reactions(drive))
    if drive == RingDrive():
        out["paper"] = asdict(PAPER)
    return out


def bearings_table(s: dict) -> str:
    """Markdown: the extremes (with the paper's beside them for its example) and the
    support reactions."""
    paper = {e["name"]: e for e in s.get("paper", {}).get("extremes", [])}
    exact = {e["name"]: e for e in s["exact_extremes"]}
    head = "| force | min [N] | at φ° | max [N] | at φ° | exact min at φ° | exact max at φ° |"
    if paper:
        head += " paper min at φ° | paper max at φ° |"
    lines = [f"Eccentric-bearing forces, {s['grid_step_deg']:g}° grid (cases: 1 no gravity "
             "and no inertia, 2 inertia only, 3 both)", "", head,
             "|---|" + "---:|" * (head.count("|") - 2)]
    for e in s["extremes"]:
        x = exact[e["name"]]
        row = (f"| {e['name']} | {e['min_N']:.2f} | {e['min_at_deg']:.0f} | {e['max_N']:.2f} | "
               f"{e['max_at_deg']:.0f} | {x['min_N']:.3f} at {x['min_at_deg']:.2f} | "
               f"{x['max_N']:.3f} at {x['max_at_deg']:.2f} |")
        if paper:
            p = paper[e["name"]]
            row += (f" {p['min_N']:.2f} at {p['min_at_deg']:.0f} | {p['max_N']:.2f} at "
                    f"{p['max_at_deg']:.0f} |")
        lines.append(row)
    r = s.get("support_reactions")
    if not r:
        lines += ["", f"(support reactions need 3 rings: eqs. 6-15 are derived for three "
                      f"eccentrics 120° apart; this drive has {s['inputs']['rings']})"]
    else:
        p = s.get("paper", {})
        lines += ["", "| support reaction [N] | ours | paper |", "|---|---:|---:|"]
        for key, label in (("R_G", "R_G (weights)"), ("R_Mi", "R_Mi (inertia couple)"),
                           ("R_MFn", "R_MFn (F_n couple)"), ("R_MFi", "R_MFi (resultant)"),
                           ("torque_term", "3 F_n r_b / (4l)"), ("R_D_max", "R_D max"),
                           ("R_C_max", "R_C max")):
            lines.append(f"| {label} | {r[key]:.2f} | "
                         f"{p[key] if key in p else '–'} |")
    d = s["derived"]
    lines += ["", f"i_H1 = {d['ratio_i_H1']:.4g}, a' = {d['eccentricity_mm']:.4f} mm, "
                  f"F_n = {d['normal_force_N']:.2f} N, P_i2 = {d['P_i2_N']:.1f} N, "
                  f"P_H = {d['P_H_N']:.1f} N"]
    return "\n".join(lines)


def write_bearings(out: Path, drive: RingDrive, summary: dict, step_deg: float) -> dict:
    """bearings.json, bearings.csv (F_A, F_B of each case over the crank angle) and
    bearings.png (the paper's Fig. 6)."""
    phi = np.arange(0.0, 360.0, step_deg)
    curves = {}
    for c, (g, i) in LOAD_CASES.items():
        f = bearing_forces(drive, phi, g, i)
        curves[f"F_A{c}"], curves[f"F_B{c}"] = f.F_A, f.F_B

    names = list(curves)
    table = ([f"{p:g}"] + [curves[n][j] for n in names] for j, p in enumerate(phi))
    return {"json": write_json(out / "bearings.json", summary),
            "csv": write_csv(out / "bearings.csv", ["phi_deg"] + [f"{n}_N" for n in names],
                             table),
            "png": bearings_png(out / "bearings.png", phi, curves)}


def ratio_table(r, eta_h: float | None) -> str:
    """The ratio, the transformed mechanism's, and efficiencies in both directions."""
    lines = [f"{r.train}: {r.fixed} fixed, {r.input} → {r.output}",
             f"ratio ω_{r.input}/ω_{r.output} = {r.value:.6g}"
             + ("  (output turns against the input)" if r.value < 0 else ""),
             f"transformed (carrier-fixed) ratio i^H = {r.transformed:.6g}"]
    if eta_h is not None:
        for label, eta in ((f"{r.input} → {r.output}", r.efficiency(eta_h)),
                           (f"{r.output} → {r.input}", r.efficiency(eta_h, reverse=True))):
            note = "  (self-locking)" if eta <= 0 else ""
            lines.append(f"mesh efficiency {label} at η^H = {eta_h:g}: {eta:.6f}{note}")
    return "\n".join(lines)


def dynamics_summary(pair: TorsionalPair, mesh: MeshStiffness, torque: float,
                     responses: list[Response], spring: str = "secant") -> dict:
    w, _ = pair.modes()
    return {"model": {"J1_kgm2": pair.J1, "J2_kgm2": pair.J2, "ratio": pair.ratio,
                      "equivalent_inertia_kgm2": pair.equivalent_inertia,
                      "spring": spring,
                      "stiffness_Nm_per_rad": pair.stiffness, "zeta": pair.zeta,
                      "damping_Nms_per_rad": pair.damping, "torque_Nm": torque},
            "natural_frequencies_rad_s": w.tolist(),
            "natural_frequency_Hz": pair.natural_frequency / (2 * math.pi),
            "mesh": {"torque_Nm": mesh.torque, "mean_stiffness_Nm_per_rad": mesh.mean,
                     "mean_tangent_Nm_per_rad": mesh.mean_tangent,
                     "harmonics": mesh.harmonics(), "z1": mesh.z1, "z2": mesh.z2},
            "speeds": [{"speed_rpm": r.speed * 30 / math.pi,
                        "mesh_frequency_Hz": r.mesh_frequency / (2 * math.pi),
                        "dynamic_factor": r.dynamic_factor, "min_factor": r.min_factor,
                        "contact_loss": r.min_factor < 0,
                        "dynamic_q_peak_to_peak_urad": 1e6 * r.q_peak_to_peak,
                        "floquet_multiplier": r.multiplier, "stable": r.multiplier < 1}
                       for r in responses]}


def dynamics_table(s: dict) -> str:
    m = s["model"]
    lines = [f"J1 {m['J1_kgm2']:.4g} kg·m², J2 {m['J2_kgm2']:.4g} kg·m², i = z2/z1 = "
             f"{m['ratio']:.6g}, J_e {m['equivalent_inertia_kgm2']:.4g} kg·m²",
             f"mean mesh stiffness {m['stiffness_Nm_per_rad']:.5g} N·m/rad ({m['spring']}"
             f"{_other_spring(s)}), ζ {m['zeta']:g}, "
             f"c {m['damping_Nms_per_rad']:.4g} N·m·s/rad",
             f"natural frequencies: 0 (rigid rotation), {s['natural_frequency_Hz']:.1f} Hz",
             "", "| speed [r/min] | mesh freq [Hz] | max F / T | min F / T | "
                 "dynamic q p-p [µrad] | Floquet |μ| |", "|---:|---:|---:|---:|---:|---:|"]
    for r in s["speeds"]:
        loss = " (teeth separate: linear model invalid)" if r["contact_loss"] else ""
        lines.append(f"| {r['speed_rpm']:.0f} | {r['mesh_frequency_Hz']:.1f} | "
                     f"{r['dynamic_factor']:.4f} | {r['min_factor']:.4f}{loss} | "
                     f"{r['dynamic_q_peak_to_peak_urad']:.3f} | "
                     f"{r['floquet_multiplier']:.4f}{'' if r['stable'] else ' UNSTABLE'} |")
    return "\n".join(lines)


def _other_spring(s: dict) -> str:
    """The mean of the spring not used, for comparison."""
    mesh, spring = s["mesh"], s["model"]["spring"]
    if spring == "tangent":
        return f"; secant {mesh['mean_stiffness_Nm_per_rad']:.5g}"
    if mesh.get("mean_tangent_Nm_per_rad") is None:
        return ""
    return f"; tangent {mesh['mean_tangent_Nm_per_rad']:.5g}"


def write_dynamics(out: Path, summary: dict) -> dict:
    """dynamics.json, dynamics.csv (one row per speed) and dynamics.png."""
    rows = summary["speeds"]
    cols = list(rows[0])
    return {"json": write_json(out / "dynamics.json", summary),
            "csv": write_csv(out / "dynamics.csv", cols, ([r[c] for c in cols] for r in rows)),
            "png": dynamics_png(out / "dynamics.png", rows, summary["natural_frequency_Hz"])}
