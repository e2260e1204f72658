"""What the sensitivities give a designer (``fegear solve --sensitivities``): each headline's
rate with each deviation of the teeth in mesh at the position of the largest gear-1 root
stress, and, with a class (``--grade``), the stress that one tolerance of each deviation
moves: which tooth's pitch, which profile, the centre distance or a runout decides the stress
(docs/tolerance.md, "Sensitivities"). Its files: sensitivities.csv and the tornado
(:func:`write_sensitivity_outputs`)."""

from __future__ import annotations

from pathlib import Path

from ....quantities import HELD, ROOT1
from ...present.writers import write_rows
from .plot import sensitivities_png


def tolerance_of(kind: str, gear: int | None, grade) -> float | None:
    """The class's tolerance (µm) that a deviation of ``kind`` on ``gear`` is measured
    against: a tooth's pitch against the single pitch f_pT, its slope against f_HαT, its form
    against f_fαT, a runout against F_rT, the centre distance against its ± tolerance (None
    where none is given, and without a class)."""
    if grade is None:
        return None
    if kind == "centre distance":
        return grade.centre_distance_um or None
    t = grade.gear1 if gear == 1 else grade.gear2
    return {"pitch": t.f_pT, "slope": t.f_HaT, "form": t.f_faT, "runout": t.F_rT}[kind]


def sensitivity_summary(sens, position_deg: float, grade=None) -> dict:
    """``summary["sensitivities"]``: the position and a row a deviation (its name, kind,
    gear, tooth, each headline's rate in MPa/µm, a runout's worst phase, and with a class
    its tolerance and the stresses one tolerance moves), the rows ordered by what they move
    gear 1's root stress (at a tolerance with a class, else per µm)."""
    rows = []
    for s in sens:
        tol = tolerance_of(s.kind, s.gear, grade)
        row = {"deviation": s.name, "kind": s.kind, "gear": s.gear, "tooth": s.tooth,
               **{f"{k.removesuffix('_MPa')}_per_um": v for k, v in s.per_um.items()},
               "phase_deg": s.phase_deg, "tolerance_um": tol}
        if tol is not None:
            row.update({f"{k.removesuffix('_MPa')}_at_tolerance": v * tol
                        for k, v in s.per_um.items()})
        rows.append(row)
    key = ("root_stress_gear1_at_tolerance" if grade is not None
           else "root_stress_gear1_per_um")
    rows.sort(key=lambda r: -abs(r.get(key) or 0.0))
    return {"position_deg": position_deg, "grade": None if grade is None else grade.grade,
            "rows": rows}


def sensitivity_table(s: dict, top: int = 12) -> str:
    """The ``top`` rows of :func:`sensitivity_summary` as the terminal shows them."""
    graded = s["grade"] is not None
    head = ["deviation", *(f"{q.head}/µm" for q in HELD)]
    if graded:
        head += ["tolerance µm", f"{ROOT1.short} at it"]
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join(["---"] + ["---:"] * (len(head) - 1))
             + "|"]
    for r in s["rows"][:top]:
        cells = [r["deviation"] + (f" (worst at {r['phase_deg']:.0f}°)"
                                   if r["phase_deg"] is not None else "")]
        cells += [f"{r[q.key.removesuffix('_MPa') + '_per_um']:+.2f}" for q in HELD]
        if graded:
            tol = r["tolerance_um"]
            cells += ["-", "-"] if tol is None else [
                f"{tol:g}", f"{r['root_stress_gear1_at_tolerance']:+.1f} MPa"]
        lines.append("| " + " | ".join(cells) + " |")
    more = len(s["rows"]) - top
    lines.append("")
    lines.append(f"at β = {s['position_deg']:.4g}° (the largest gear-1 root stress); a runout's "
                 "rate is the largest over its phase, per µm of F_r"
                 + (f"; {more} more rows in sensitivities.csv" if more > 0 else ""))
    return "\n".join(lines)


def sensitivity_columns(s: dict) -> dict:
    """The sensitivities as a study's columns: the deviation that moves gear 1's root stress
    most and its rate (MPa/µm), and what one tolerance of it moves with a class."""
    top = s["rows"][0]
    return {"sensitivities.largest": top["deviation"],
            "sensitivities.largest.root_stress_gear1_per_um": top["root_stress_gear1_per_um"],
            "sensitivities.largest.root_stress_gear1_at_tolerance":
                top.get("root_stress_gear1_at_tolerance")}


def write_sensitivity_outputs(sens: dict, out: Path, title: str, pictures: bool = True
                              ) -> dict[str, Path]:
    """sensitivities.csv (a row a deviation of the teeth in mesh: each headline's rate,
    MPa/µm, and with a class what one tolerance moves) and sensitivities.png (``pictures``:
    the tornado of the largest)."""
    files = {"sensitivities_csv": write_rows(out / "sensitivities.csv", sens["rows"])}
    if pictures:
        files["sensitivities_png"] = sensitivities_png(out / "sensitivities.png", sens, title)
    return files
