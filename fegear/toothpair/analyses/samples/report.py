"""What a tolerance class's samples give a designer (``fegear solve --grade``): each headline
stress's nominal, quantiles with their statistical errors and worst with its sample, the
safety factors that the ``--quantile`` share of the class's pairs meet, and the verdict
(docs/tolerance.md, "Reading the quantiles").

A pair that jams (its deviations take up the backlash) carries no stress a solve can give, and
it fails: its stresses count as beyond every other's, so a quantile is taken of all the pairs
drawn, and where the jammed share reaches past it the quantile is "jams". Across the face,
a pair's stresses are its worst section's, and its K_Hβ is read as they are (a jammed pair's
beyond every other's). Its files: samples.csv and samples.png (:func:`write_samples_outputs`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from ....fe import Allowables
from ....files import write_csv
from ....quantities import FACTORS
from ....tolerance import QUANTILES, Draw, quantiles
from ...case import HEADLINE
from ...face import Face
from ...safety import SAFETY, safety_factor
from .plot import samples_png
from .rows import K_HBETA

#: a jammed pair's stresses, beyond every solved one's (module docstring)
JAMMED = math.inf


@dataclass(frozen=True)
class ClassReading:
    """How a class's samples are read: the class and seed they were drawn with (``draw``),
    the share of the pairs (``quantile``) whose stresses the safety factors are stated at, the
    ``allowables`` (MPa) and the positions each pair is solved at (``positions``, over a whole
    ``revolution`` of gear 1 or a cycle), across the ``face`` where the job has one (its
    pairs' stresses their worst sections', and their K_Hβ); ``solved_per_pair``: a
    revolution screened, the positions solved a pair that turns (mean; None: all)."""

    draw: Draw
    quantile: float
    allowables: Allowables
    positions: int = 1
    revolution: bool = False
    face: Face | None = None
    solved_per_pair: float | None = None


def samples_summary(rows, nominal_rows: list[dict], reading: ClassReading) -> dict:
    """The samples' summary (``summary["samples"]``) as ``reading`` reads them: the class,
    the counts, the positions each pair is solved at, per headline stress and per safety
    factor the nominal (the exact pair's largest over the positions), the quantiles (of every
    pair drawn, and of the pairs that turn alone: ``turning``), the value at the quantile and
    the worst with its sample, the verdict and the rows (one a sample)."""
    rows = list(rows)
    n = len(rows)
    solved = [r for r in rows if r["status"] == "solved"]
    jammed = sum(r["status"] == "jammed" for r in rows)
    failed = [r for r in rows if r["status"] == "failed"]
    share = jammed / n
    grade, quantile = reading.draw.grade, reading.quantile
    stresses = _stresses(rows, nominal_rows, quantile, reading.draw.seed)
    safety = _safety(stresses, quantile, reading.allowables)
    across = {}
    if reading.face is not None:
        across = {"across": _across(reading),
                  "load_factor": _stresses(rows, nominal_rows, quantile, reading.draw.seed,
                                           (K_HBETA,))[K_HBETA]}
    return {"grade": grade.summary(), "samples": n, "seed": reading.draw.seed,
            "quantile": quantile, "positions_per_pair": reading.positions,
            "over": "revolution" if reading.revolution else "cycle",
            **({} if reading.solved_per_pair is None else
               {"screened": True, "positions_solved_per_pair": reading.solved_per_pair}),
            "solved": len(solved), "jammed": jammed, "failed": len(failed),
            "jammed_share": share, "jammed_share_error": math.sqrt(share * (1 - share) / n),
            "failures": sorted({r["why"] for r in failed}),
            "stresses": stresses, "safety": safety,
            "verdict": verdict(safety, share, quantile, grade.grade), **across, "rows": rows}


def _across(reading: ClassReading) -> dict:
    """What the class is solved across (JSON): the face's sections and inputs, the
    misalignment each pair is drawn about and its band (µm), and that the stresses are each
    pair's worst section's (the helix tolerances are the grade's)."""
    face, draw = reading.face, reading.draw
    return {"sections": face.sections, "misalignment_um": draw.misalignment_um,
            "misalignment_band_um": draw.band_um, "tilt_um": face.tilt,
            "crowning_um": face.crowning, "end_relief_um": face.end_relief,
            "stresses": "each pair's worst section's"}


def _stresses(rows: list[dict], nominal_rows: list[dict], quantile: float, seed: int,
              keys=tuple(HEADLINE)) -> dict:
    """Per headline stress (or other ``keys`` of the rows: K_Hβ): the nominal (the exact
    pair's largest over the positions), the quantiles of every pair drawn (a jammed pair's
    beyond every other's) and of the pairs that turn (``turning``), both with ``quantile``
    among them and bootstrapped with ``seed``, and the worst with its sample."""
    qs = tuple(sorted({*QUANTILES, quantile}))
    solved = [r for r in rows if r["status"] == "solved"]
    stresses = {}
    for key in keys:
        values = [r[key] if r["status"] == "solved" else JAMMED
                  for r in rows if r["status"] != "failed"]
        found = {q.q: q for q in quantiles(values, qs, seed=seed)}
        turning = quantiles([r[key] for r in solved], qs, seed=seed)
        worst = max(solved, key=lambda r: r[key]) if solved else None
        stresses[key] = {
            "nominal": max(r[key] for r in nominal_rows),
            "quantiles": [_quantile(found[q]) for q in qs],
            "turning": [_quantile(q) for q in turning],
            "worst": worst[key] if worst else None,
            "worst_sample": worst["sample"] if worst else None}
    return stresses


def _safety(stresses: dict, quantile: float, allowables: Allowables) -> dict:
    """Per safety factor, from its stress's entry of ``stresses``: the nominal, the factor at
    the ``quantile`` with its error, and the worst with its sample."""
    safety = {}
    for name, (which, key) in SAFETY.items():
        allowable = getattr(allowables, which)
        at = next(q for q in stresses[key]["quantiles"] if q["q"] == quantile)
        worst = stresses[key]["worst"]
        safety[name] = {"nominal": safety_factor(allowable, stresses[key]["nominal"]),
                        "at_quantile": _factor(allowable, at),
                        "at_quantile_error": _factor_error(allowable, at),
                        "worst": None if worst is None else safety_factor(allowable, worst),
                        "worst_sample": stresses[key]["worst_sample"]}
    return safety


def _quantile(q) -> dict:
    """A quantile as JSON: "jams" (its value None) where it falls among the jammed pairs."""
    jams = not math.isfinite(q.value)
    return {"q": q.q, "value": None if jams else q.value,
            "error": None if jams or not math.isfinite(q.error) else q.error,
            "jams": jams, "n": q.n}


def _factor(allowable: float, q: dict) -> float | None:
    return 0.0 if q["jams"] else safety_factor(allowable, q["value"])


def _factor_error(allowable: float, q: dict) -> float | None:
    """The standard error of allowable / stress from the stress's (to first order)."""
    if q["jams"] or q["error"] is None or not q["value"]:
        return None
    return allowable * q["error"] / q["value"] ** 2


def verdict(safety: dict, jammed_share: float, quantile: float, grade: int) -> str:
    """One line: whether the ``quantile`` share of class ``grade``'s pairs meet every safety
    factor (S >= 1), the limiting one, or that too many of them jam."""
    share = f"{100 * quantile:g} % of class-{grade} pairs"
    if jammed_share > 1.0 - quantile:
        return (f"FAIL: {100 * jammed_share:.3g} % of class-{grade} pairs jam (their deviations "
                f"take up the backlash), more than the {100 * (1 - quantile):.3g} % that "
                f"--quantile {quantile:g} leaves: a finer class, or more backlash (--shift)")
    have = {k: v["at_quantile"] for k, v in safety.items() if v["at_quantile"] is not None}
    if not have:
        return f"no safety factor: no stress at the quantile ({share})"
    key = min(have, key=have.get)
    word = "PASS" if have[key] >= 1.0 else "FAIL"
    return (f"{word}: {share} meet {FACTORS[key].label} >= {have[key]:.2f} (the limiting "
            f"factor; nominal {safety[key]['nominal']:.2f})")


def stress_cells(s: dict) -> tuple[list[str], dict[str, list[str]]]:
    """The class's band beside the report page's stresses: each headline's P50 and P95 with
    their bootstrap errors ("jams" where the quantile's pair jams), by headline key."""
    cells = {}
    for key, band in s["stresses"].items():
        qs = {q["q"]: q for q in band["quantiles"]}
        cells[key] = [_band_cell(qs.get(0.5)), _band_cell(qs.get(0.95))]
    return ["class P50", "class P95"], cells


def _band_cell(q: dict | None) -> str:
    if q is None:
        return "–"
    if q["jams"]:
        return "jams"
    err = "" if q["error"] is None else f" ± {q['error']:.1f}"
    return f"{q['value']:.1f}{err}"


def samples_table(s: dict) -> str:
    """The samples' summary as the terminal shows it: the stresses' quantiles with their
    errors, the safety factors at the quantile, the counts and the verdict."""
    q = s["quantile"]
    head = ["stress [MPa]", "nominal", *(f"P{100 * x:g}" for x in _shown(s)), "worst (sample)"]
    lines = ["| " + " | ".join(head) + " |",
             "|" + "|".join(["---"] + ["---:"] * (len(head) - 1)) + "|"]
    for key, label in HEADLINE.items():
        lines.append(_quantile_row(label, s["stresses"][key], _shown(s), 1))
    if "load_factor" in s:   # across the face: K_Hβ read as the stresses are
        lines.append(_quantile_row("K_Hβ [-]", s["load_factor"], _shown(s), 3))
    if s["jammed"] and s["solved"]:   # what the pairs that turn carry, the jammed aside
        lines += ["", "| of the pairs that turn [MPa] | "
                  + " | ".join(f"P{100 * x:g}" for x in _shown(s)) + " |",
                  "|---|" + "---:|" * len(_shown(s))]
        for key, label in HEADLINE.items():
            cells = [f"{x['value']:.1f} ± {x['error']:.1f}"
                     for x in s["stresses"][key]["turning"] if x["q"] in _shown(s)]
            lines.append(f"| {label} | " + " | ".join(cells) + " |")
    lines += ["", f"| safety factor | nominal | at P{100 * q:g} | worst |", "|---|---:|---:|---:|"]
    for key, f in FACTORS.items():
        v = s["safety"][key]
        at = ("jams" if v["at_quantile"] == 0.0 else "-" if v["at_quantile"] is None else
              f"{v['at_quantile']:.2f}" + (f" ± {v['at_quantile_error']:.2f}"
                                           if v["at_quantile_error"] is not None else ""))
        lines.append(f"| {f.label} | {_num(v['nominal'])} | {at} | {_num(v['worst'])} |")
    g = s["grade"]
    lines += ["", f"{s['samples']} pair{'' if s['samples'] == 1 else 's'} of ISO 1328-1:2013 "
              f"class {g['grade']} (seed "
              f"{s['seed']}): {s['solved']} solved, {s['jammed']} jammed "
              f"({100 * s['jammed_share']:.3g} ± {100 * s['jammed_share_error']:.2g} %), "
              f"{s['failed']} failed" + (f" ({'; '.join(s['failures'])})" if s["failures"]
                                         else ""),
              f"class {g['grade']}: f_pT {g['gear1']['f_pT_um']:g}/{g['gear2']['f_pT_um']:g}, "
              f"F_pT {g['gear1']['F_pT_um']:g}/{g['gear2']['F_pT_um']:g}, f_HαT "
              f"{g['gear1']['f_HaT_um']:g}/{g['gear2']['f_HaT_um']:g}, f_fαT "
              f"{g['gear1']['f_faT_um']:g}/{g['gear2']['f_faT_um']:g}, F_rT "
              f"{g['gear1']['F_rT_um']:g}/{g['gear2']['F_rT_um']:g} µm (gear 1/gear 2)"
              + (f", centre distance ±{g['centre_distance_tolerance_um']:g} µm"
                 if g["centre_distance_tolerance_um"] else ""),
              *([_across_line(s)] if "across" in s else []),
              f"verdict: {s['verdict']}"]
    return "\n".join(lines)


def _quantile_row(label: str, v: dict, shown: tuple[float, ...], digits: int) -> str:
    """A row of the stress table (a stress's, or K_Hβ's): its nominal, the ``shown``
    quantiles with their errors and the worst with its sample, to ``digits`` decimals."""
    cells = [label, f"{v['nominal']:.{digits}f}"]
    for x in v["quantiles"]:
        if x["q"] in shown:
            cells.append("jams" if x["jams"] else f"{x['value']:.{digits}f} ± " + (
                "∞" if x["error"] is None else f"{x['error']:.{digits}f}"))
    cells.append("-" if v["worst"] is None
                 else f"{v['worst']:.{digits}f} ({v['worst_sample']})")
    return "| " + " | ".join(cells) + " |"


def _across_line(s: dict) -> str:
    """The line that says the class is across the face: its sections, its helix tolerances
    and the misalignment it is drawn about, with its band."""
    a, g = s["across"], s["grade"]
    h1, h2 = g["helix1"], g["helix2"]
    band = (f" ± {a['misalignment_band_um']:g} (drawn, σ = a third)"
            if a["misalignment_band_um"] else "")
    return (f"across the face ({a['sections']} sections; each pair's stresses at its worst "
            f"section, K_Hβ its largest): f_HβT {h1['f_HbT_um']:g}/{h2['f_HbT_um']:g}, "
            f"f_fβT {h1['f_fbT_um']:g}/{h2['f_fbT_um']:g}, F_βT {h1['F_bT_um']:g}/"
            f"{h2['F_bT_um']:g} µm at b = {h1['b_mm']:g} mm, drawn with the pairs; "
            f"misalignment {a['misalignment_um']:g}{band} µm")


def _shown(s: dict) -> tuple[float, ...]:
    return tuple(sorted({*QUANTILES, s["quantile"]}))


def _num(x) -> str:
    return "-" if x is None else f"{x:.2f}"


def samples_columns(s: dict) -> dict:
    """A class's samples as a study's columns: the count, the jammed share, each headline's
    quantiles with their errors (None where one falls among the jammed pairs), each safety
    factor at the quantile and the verdict."""
    out = {"samples.n": s["samples"], "samples.jammed_share": s["jammed_share"]}
    for key, v in s["stresses"].items():
        for q in v["quantiles"]:
            tag = f"P{100 * q['q']:g}"
            out[f"samples.{key}.{tag}"] = q["value"]
            out[f"samples.{key}.{tag}_error"] = q["error"]
    for q in s.get("load_factor", {}).get("quantiles", ()):
        out[f"samples.K_Hbeta.P{100 * q['q']:g}"] = q["value"]
    for key, v in s["safety"].items():
        out[f"samples.{key}.at_quantile"] = v["at_quantile"]
    out["samples.verdict"] = s["verdict"]
    return out


def write_samples_outputs(samples: dict, out: Path, title: str, allowables,
                          pictures: bool = True) -> dict[str, Path]:
    """A tolerance class's files: samples.csv (a row a pair drawn: its deviations in brief,
    whether it was solved, jammed or failed and why, its largest stresses over the positions
    with where, its safety factors) and samples.png (``pictures``: each safety factor's
    distribution)."""
    rows = samples["rows"]
    cols = list(dict.fromkeys(k for r in rows for k in r))
    files = {"samples_csv": write_csv(out / "samples.csv", cols,
                                      ([r.get(c, "") for c in cols] for r in rows))}
    if pictures:
        files["samples_png"] = samples_png(out / "samples.png", samples, allowables, title)
    return files
