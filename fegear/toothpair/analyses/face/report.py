"""What the solve across the face gives a designer: K_Hβ beside ISO 6336-1's method C, each
headline at its worst section and how far it is above the 2D pair's (for the roots, K_Fβ as
fegear measures it), the table ``fegear solve`` prints, face.csv (each loaded tooth's line
load at each section at each position) and the contact pattern (:mod:`.plot`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....files import write_atomic, write_csv
from ....quantities import FACTORS, HEADLINES
from ...present.html_parts import escape, safety_cell, table
from ...safety import safety_factors
from .plot import face_png


def face_summary(rows: list[dict], coupling, face, allowables, width: float) -> dict:
    """``summary["face"]``: the inputs across the face, the sections' places, a row a
    position (:func:`~.solve.position_entry`), over the positions the largest K_Hβ (with
    method C's at that position) and each headline's largest, where and its ratio to the 2D
    pair's at the same position, and the safety factors of those largest stresses against
    ``allowables``; ``width``: the face width (mm)."""
    top = max(rows, key=lambda r: r["K_Hbeta"])
    worst = {}
    for q in HEADLINES:
        row = max(rows, key=lambda r: r["worst"][q.key]["value"])
        worst[q.key] = {**row["worst"][q.key], "position_deg": row["position_deg"]}
    return {"inputs": {"sections": face.sections, "misalignment_um": face.misalignment,
                       "tilt_um": face.tilt, "crowning_um": face.crowning,
                       "end_relief_um": face.end_relief, "end_length_mm": face.end_length,
                       "helix_gear1": [list(h) for h in face.helix1],
                       "helix_gear2": [list(h) for h in face.helix2]},
            "width_mm": width, "zeta": [float(z) for z in coupling.zeta],
            "K_Hbeta": top["K_Hbeta"], "K_Hbeta_method_c": top["K_Hbeta_method_c"],
            "at_position_deg": top["position_deg"], "worst": worst,
            "safety": safety_factors({k: w["value"] for k, w in worst.items()}, allowables),
            "positions": rows}


def face_verdict(s: dict, width: float) -> tuple[bool, str]:
    """Whether every safety factor at the worst sections is at least one, and the line that
    says which limits and where."""
    have = {k: v for k, v in s["safety"].items() if v is not None}
    key = min(have, key=have.get)
    factor = FACTORS[key]
    w = s["worst"][factor.stress.key]
    passed = have[key] >= 1.0
    return passed, (f"{factor.label} {have[key]:.2f} at its worst section, "
                    f"{(w['zeta'] + 0.5) * width:.2g} mm from the first end, limits "
                    f"({'at least 1' if passed else 'below 1'}; K_Hβ {s['K_Hbeta']:.2f})")


def face_safety_html(s: dict, width: float) -> str:
    """The report page's safety factors across the face: each one at its stress's worst
    section (the stress, where across the face and at which rolling angle), as the static
    table gives the 2D pair's."""
    rows = []
    for key, value in s["safety"].items():
        if value is None:
            continue
        w = s["worst"][FACTORS[key].stress.key]
        rows.append([FACTORS[key].label, safety_cell(value), f"{w['value']:.1f}",
                     f"{(w['zeta'] + 0.5) * width:.2f}", f"{w['position_deg']:.3g}"])
    return table(["factor", "S", "stress MPa", "at z mm", "at β °"], rows)


def face_html(s: dict, width: float) -> str:
    """The report page's section: each headline at its worst section against the 2D pair's,
    and K_Hβ beside method C's."""
    rows = _worst_rows(s, width)
    i = s["inputs"]
    given = ", ".join(f"{name} {i[key]:g} {unit}" for name, key, unit in (
        ("misalignment", "misalignment_um", "µm"), ("tilt", "tilt_um", "µm"),
        ("crowning", "crowning_um", "µm"), ("end relief", "end_relief_um", "µm"))
        if i[key])
    helix = [f"{len(i[key])} gear-{g} {'tooth' if len(i[key]) == 1 else 'teeth'}"
             for g, key in ((1, "helix_gear1"), (2, "helix_gear2")) if i.get(key)]
    if helix:
        given = ", ".join([*filter(None, [given]), "helix deviations on " + " and ".join(helix)])
    return (f"<p>{escape(given or 'an even face')}, {i['sections']} sections. K_Hβ "
            f"{s['K_Hbeta']:.3f}; ISO 6336-1 method C for the same mismatch and the pair's "
            f"own approach: {s['K_Hbeta_method_c']:.3f}.</p>"
            + table(["stress", "2D MPa", "worst section MPa", "ratio", "at z mm",
                     "at β °"], rows))


def face_table(s: dict, width: float) -> str:
    """The terminal's table: each headline's 2D value, its worst section's and their ratio,
    then K_Hβ beside method C's."""
    lines = ["| stress | 2D MPa | worst section MPa | ratio | where |",
             "|---|---:|---:|---:|---|"]
    for label, flat, worst, ratio, z, beta in _worst_rows(s, width):
        lines.append(f"| {label} | {flat} | {worst} | {ratio} | {z} mm from the first end, "
                     f"β {beta}° |")
    lines += ["", f"K_Hβ {s['K_Hbeta']:.3f} (largest line load over its tooth's mean, at β "
                  f"{s['at_position_deg']:.3g}°); ISO 6336-1 method C for the same mismatch "
                  f"and the pair's own approach: {s['K_Hbeta_method_c']:.3f}"]
    return "\n".join(lines)


def _worst_rows(s: dict, width: float) -> list[list[str]]:
    """Each headline's cells, as the table and the page show them: its label, the 2D
    pair's value, its worst section's, their ratio, where across the face (mm from the
    first end) and at which rolling angle (°)."""
    rows = []
    for q in HEADLINES:
        w = s["worst"][q.key]
        ratio = w["ratio"]
        rows.append([q.label, "–" if not ratio else f"{w['value'] / ratio:.1f}",
                     f"{w['value']:.1f}", "–" if ratio is None else f"{ratio:.3f}",
                     f"{(w['zeta'] + 0.5) * width:.2f}", f"{w['position_deg']:.3g}"])
    return rows


def write_face_outputs(s: dict, out: Path, title: str, width: float,
                       pictures: bool = True, patterns=None) -> dict[str, Path]:
    """face.csv (a row a position, tooth and section: its place and the line load), with
    ``pictures`` face.png, and with ``patterns`` (each position's
    :class:`~.solve.FacePattern`) face.vtu, the slices at the position of the largest K_Hβ
    (:func:`write_slices`)."""
    rows = ([r["position_deg"], int(tooth), k, (z + 0.5) * width, load]
            for r in s["positions"] for tooth, loads in r["line_loads_N_per_mm"].items()
            for k, (z, load) in enumerate(zip(s["zeta"], loads)))
    files = {"face_csv": write_csv(out / "face.csv", ["position_deg", "tooth", "section",
                                                      "z_mm", "line_load_N_per_mm"], rows)}
    if pictures:
        files["face_png"] = face_png(out / "face.png", s, title, width)
    if patterns:
        top = max(range(len(s["positions"])), key=lambda k: s["positions"][k]["K_Hbeta"])
        files["face_vtu"] = write_slices(out / "face.vtu", patterns[top], s["zeta"], width)
    return files


def write_slices(path: Path, pattern, zeta, width: float) -> Path:
    """The contact across the face as a surface for ParaView (VTU, atomically): each loaded
    tooth's grid points in the fixed frame (x, y, mm) at every section (z: its place from the
    face's first end, mm), joined in quadrilaterals along the profile and across the face,
    with the pressure (MPa) and the gap (µm) at each node and the tooth on each face."""
    import meshio

    n, sections = pattern.pressure.shape
    z = (np.asarray(zeta) + 0.5) * width
    points = np.column_stack([np.repeat(pattern.xy, sections, axis=0),
                              np.tile(z, n)])            # node i * sections + s
    along = np.flatnonzero(pattern.tooth[1:] == pattern.tooth[:-1])   # within one grid
    s = np.arange(sections - 1)
    first = (along[:, None] * sections + s[None, :]).ravel()
    quads = np.column_stack([first, first + sections, first + sections + 1, first + 1])
    mesh = meshio.Mesh(points, [("quad", quads)],
                       point_data={"contact_pressure_MPa": pattern.pressure.ravel(),
                                   "gap_um": pattern.gap_um.ravel()},
                       cell_data={"tooth": [np.repeat(pattern.tooth[along], sections - 1)]})
    return write_atomic(path, lambda tmp: meshio.write(tmp, mesh, file_format="vtu"))
