"""``fegear drive reducer``'s results: the three builds' natural frequencies side by side, the
unbalance response of the seed's Figs. 2–6, the Campbell crossings, the misalignment at each
mesh under the rated torque (:mod:`.reducer_tilt`), the seed's findings each checked, and what
fegear's own mesh stiffness changes (:mod:`.reducer`)."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from ..errors import FegearError, ParameterError
from ..files import write_csv, write_json
from ..timing import Stopwatch
from ..toothpair import mesh_stiffness_of_cycle, prepare_job, read_mesh_stiffness, solve_job
from .plot import reducer_campbell_png, reducer_modes_png, reducer_response_png
from .reducer import (
    RESPONSES,
    build_reducer,
    frequency_spread,
    frozen_quasi_static,
    modes,
    over_turn,
    sweep,
    turning_geometry,
    turning_sweep,
    unbalance_resultants,
)
from .reducer_inputs import BUILDS, ReducerInputs
from .reducer_tilt import misalignment_table, rated_misalignment

FAR = 0.3          # "far from the working speed": outside ±30 % of it
CLOSE = 0.10       # the builds' frequencies "close": within 10 % of each other
REPEATED = 0.01    # a pair "repeated": within 1 %
PAIRS = ((4, 5), (6, 7), (9, 10))


@dataclass(frozen=True)
class MeshSource:
    """The single plate's mesh stiffness (N/m) the model uses and where it came from; with
    fegear's own (``fe``): its mean tangent and secant and the tangent's least and largest
    over the mesh cycle (N/m), and the FE cycle's own summary."""

    stiffness: float
    source: str
    secant: float | None = None
    tangent_min: float | None = None
    tangent_max: float | None = None
    fe: dict | None = None


def mesh_source(spec: str, inputs: ReducerInputs, quality: str = "coarse",
                positions: int = 12) -> MeshSource:
    """The mesh stiffness ``--mesh-stiffness`` names: "table" (Table 1's constant), a number
    (N/m), "fe" (fegear's cycle solve of the compound-cycloid pair of the same teeth and
    module, one plate's face width, at the output torque) or a mesh_stiffness.json (scaled
    from its face width to the plate's). fegear's stiffness is N·m/rad of the gear's rotation
    with the plate held; the model's spring acts along the line of action at the base radius
    r_b, so k = k_θ / r_b² keeps the torsional mesh stiffness. The model's spring is the mean
    tangent stiffness (a linearised model's), the secant beside it."""
    if spec == "table":
        return MeshSource(inputs.mesh_stiffness, "table")
    try:
        value = float(spec)
    except ValueError:
        value = None
    if value is not None:
        if not math.isfinite(value) or value <= 0:
            raise ParameterError("mesh_stiffness", spec, "table, fe, a mesh_stiffness.json "
                                 "or a stiffness > 0 [N/m]")
        return MeshSource(value, "given")
    if spec == "fe":
        mesh, fe = _fe_cycle(inputs, quality, positions)
        label = f"fegear {quality}, {positions} positions"
    else:
        try:
            mesh, fe = read_mesh_stiffness(spec), None
        except FegearError as exc:   # its message names fegear drive dynamics' option
            raise FegearError(str(exc).replace("--stiffness", "--mesh-stiffness", 1)) from None
        label = f"{spec} (at {mesh.torque:g} N·m, {mesh.thickness:g} mm, scaled to the plate)"
    if mesh.tangent is None:
        raise ParameterError("mesh_stiffness", spec, "a mesh_stiffness.json with the tangent "
                             "stiffness (solved again with this fegear)")
    scale = (inputs.plate_thickness_mm / mesh.thickness) / inputs.base_radius ** 2
    return MeshSource(scale * mesh.mean_tangent, label, secant=scale * mesh.mean,
                      tangent_min=scale * float(mesh.tangent.min()),
                      tangent_max=scale * float(mesh.tangent.max()),
                      fe={"torque_Nm": mesh.torque, "face_width_mm": mesh.thickness,
                          "z1": mesh.z1, "z2": mesh.z2, "module_mm": mesh.module,
                          "mean_tangent_Nm_per_rad": mesh.mean_tangent,
                          "mean_secant_Nm_per_rad": mesh.mean,
                          "tangent_Nm_per_rad": mesh.tangent.tolist(),
                          "secant_Nm_per_rad": mesh.stiffness.tolist(),
                          "phase": mesh.phase.tolist(), **(fe or {})})


def _fe_cycle(inputs: ReducerInputs, quality: str, positions: int):
    """fegear's mesh cycle of the pair of the reducer's teeth and module: one plate's face
    width, the output torque on the gear (gear 1)."""
    watch = Stopwatch()
    job = prepare_job({"z1": inputs.z_gear, "z2": inputs.z_plate, "m": inputs.module_mm,
                       "face-width": inputs.plate_thickness_mm,
                       "torque": inputs.output_torque, "positions": positions,
                       "quality": quality, "no-estimate": True})
    solved = solve_job(job)
    p = job.case.params
    mesh = mesh_stiffness_of_cycle(solved.rows, p.z1, p.z2, p.m, job.case.thickness,
                                   job.case.torque)
    return mesh, {"solve_s": watch.s, "quality": quality,
                  "positions": positions,
                  "teeth_in_contact": [r["teeth_in_contact"] for r in solved.rows]}


def reducer_summary(inputs: ReducerInputs, mesh: MeshSource, count: int = 10,
                    speeds_rpm=None) -> dict:
    """Everything ``fegear drive reducer`` prints and writes, for the three builds."""
    watch = Stopwatch()
    km = mesh.stiffness
    if speeds_rpm is None:
        top = 1.5 * inputs.speed_rpm
        speeds_rpm = np.linspace(top / 60, top, 60)
    speeds_rpm = np.asarray(speeds_rpm, float)
    builds, frozen, turning = {}, {}, {}
    for plates in BUILDS:
        model = build_reducer(inputs, plates, km)
        ms = modes(model, count)
        turn_models = over_turn(inputs, plates, mesh_stiffness=km)
        spread = frequency_spread(turn_models, count)
        force, couple = unbalance_resultants(inputs, plates)
        frozen[plates] = sweep(model, speeds_rpm)
        turning[plates] = turning_sweep(turn_models, speeds_rpm)
        turn = turning_geometry(turn_models, inputs.omega)
        builds[str(plates)] = {
            "plates": [{"fraction": s.fraction, "phase_deg": math.degrees(s.phase),
                        "z_mm": 1e3 * s.z} for s in model.stations],
            "dofs": int(len(model.free)),
            "modes": [{"mode": k + 1, "rad_s": m.omega, "Hz": m.hz, "kind": m.kind,
                       "shares": dict(m.shares),
                       "spread_over_crank_angle_rad_s": float(np.ptp(spread[:, k]))}
                      for k, m in enumerate(ms)],
            "unbalance": {"force_N": force, "couple_Nm": couple},
            "at_working_speed": {
                "frozen": {k: float(np.interp(inputs.speed_rpm, speeds_rpm, v))
                           for k, v in frozen[plates].items()},
                "turning": {k: float(np.interp(inputs.speed_rpm, speeds_rpm, v))
                            for k, v in turning[plates].items()},
                "quasi_static_frozen": frozen_quasi_static(model),
                "quasi_static_turning": {
                    "input_support_um": float(turn["input_support_um"].max()),
                    "output_twist_urad": float(0.5 * np.ptp(turn["output_twist_urad"])),
                    "output_twist_mean_urad": float(turn["output_twist_urad"].mean())}},
            "_modes": ms, "_model": model}
    summary = {
        "inputs": asdict(inputs),
        "derived": {"ratio": inputs.ratio, "output_torque_Nm": inputs.output_torque,
                    "working_speed_rad_s": inputs.omega,
                    "mesh_frequency_rad_s": inputs.mesh_frequency,
                    "mesh_frequency_Hz": inputs.mesh_frequency / (2 * math.pi),
                    "working_pitch_radii_mm": [1e3 * r for r in inputs.working_pitch_radii],
                    "base_radius_mm": 1e3 * inputs.base_radius},
        "mesh": {"stiffness_N_per_m": km, "source": mesh.source, "table_N_per_m":
                 inputs.mesh_stiffness, "secant_N_per_m": mesh.secant,
                 "tangent_min_N_per_m": mesh.tangent_min,
                 "tangent_max_N_per_m": mesh.tangent_max, "fe": mesh.fe},
        "builds": builds,
        "speeds_rpm": speeds_rpm.tolist(),
        "response": {"frozen": {str(p): {k: v.tolist() for k, v in r.items()}
                                for p, r in frozen.items()},
                     "turning": {str(p): {k: v.tolist() for k, v in r.items()}
                                 for p, r in turning.items()}},
    }
    summary["misalignment"] = rated_misalignment(inputs, km)
    summary["campbell"] = _crossings(summary)
    summary["findings"] = findings(summary)
    if mesh.source != "table":
        summary["mesh_comparison"] = _comparison(inputs, mesh, count)
    summary["solve_s"] = watch.s
    return summary


def public(summary: dict) -> dict:
    """The summary without its model objects (JSON)."""
    out = dict(summary)
    out["builds"] = {p: {k: v for k, v in b.items() if not k.startswith("_")}
                     for p, b in summary["builds"].items()}
    return out


def _crossings(s: dict) -> list[dict]:
    """Crank speeds (r/min) at which the unbalance (1×) and the mesh frequency (z_plate ×)
    meet each natural frequency of each build, and 2× a natural frequency for the mesh
    (principal parametric resonance)."""
    z = s["inputs"]["z_plate"]
    top = max(s["speeds_rpm"])
    out = []
    for p, b in s["builds"].items():
        for m in b["modes"]:
            w = m["rad_s"]
            rpm = w * 30 / math.pi
            out.append({"plates": int(p), "mode": m["mode"], "rad_s": w,
                        "unbalance_rpm": rpm if rpm <= top else None,
                        "mesh_rpm": rpm / z, "parametric_rpm": 2 * rpm / z})
    return out


def findings(s: dict) -> list[dict]:
    """Seed 003's findings, each measured on this model: what it says, what the model gives,
    a verdict and why."""
    b = s["builds"]
    w = {p: np.array([m["rad_s"] for m in b[p]["modes"]]) for p in b}
    work = s["derived"]["working_speed_rad_s"]
    n = min(len(v) for v in w.values())
    table = np.array([w[p][:n] for p in ("1", "2", "3")])
    spread = (table.max(0) - table.min(0)) / table.min(0)
    out = []

    worst = int(np.argmax(spread))
    out.append(_finding(
        "The three builds' natural frequencies are close",
        f"largest difference {100 * spread.max():.0f} % (mode {worst + 1}), median "
        f"{100 * np.median(spread):.1f} % over the first {n}",
        "reproduced" if spread.max() <= CLOSE else
        "partly" if np.median(spread) <= CLOSE else "not reproduced",
        "" if spread.max() <= CLOSE else
        f"mode {worst + 1} differs: {_kinds(b, worst)}. A single plate's mesh force bends the "
        "output shaft and its three cranks' torsion couples through it; two or three plates "
        "at 180° cancel those forces"))

    nearest = {p: float(w[p][np.argmin(np.abs(w[p] / work - 1))]) for p in w}
    near = [p for p, v in nearest.items() if abs(v / work - 1) <= FAR]
    out.append(_finding(
        "All natural frequencies far from the working speed",
        "nearest to it " + ", ".join(f"{v:.0f} rad/s ({v / work:.2f}×) with {_plates(p)}"
                                     for p, v in nearest.items())
        + f"; working speed {work:.0f} rad/s, far meaning outside ±{100 * FAR:.0f} %",
        "reproduced" if not near else "partly" if len(near) < len(nearest) else
        "not reproduced",
        "" if not near else
        "the lowest modes are the drive train's torsion: the cranks turning together against "
        "the output shaft's twist, which reaches the input divided by the ratio squared "
        f"({s['derived']['ratio']:.0f}²), and the cranks against each other; where they fall "
        "depends on the motor's inertia at the input (--motor-inertia), which the seed does "
        "not give"))

    crank = ("input torsion", "support 1 torsion", "support 2 torsion")
    first = {p: [sum(b[p]["modes"][k]["shares"].get(c, 0.0) for c in crank)
                 for k in range(3)] for p in b}
    torsion = all(min(v) >= 0.5 for v in first.values())
    equal = {p: (w[p][2] - w[p][0]) / w[p][0] for p in w}
    out.append(_finding(
        "Modes 1–3 equal: torsion of the three identical crank shafts",
        "crank torsion's share of modes 1–3: " + "; ".join(
            f"{_plates(p)} " + "/".join(f"{100 * x:.0f}" for x in v) + " %"
            for p, v in first.items())
        + "; modes 1 to 3 apart by " + ", ".join(f"{100 * v:.0f} %" for v in equal.values()),
        "reproduced" if torsion and max(equal.values()) <= REPEATED else
        "partly" if torsion or min(first[p][0] for p in first) >= 0.5 else "not reproduced",
        "the three cranks are not independent: they carry the same plate, so their torsion "
        "splits into turning together (the drive train, restrained by the output) and "
        "against each other (restrained by the planet bearings at the eccentricity); equal "
        "frequencies need the plate held still"))

    gaps = {p: [(w[p][c - 1] - w[p][a - 1]) / w[p][a - 1] for a, c in PAIRS
                if c <= len(w[p])] for p in w}
    repeated = {p: sum(g <= REPEATED for g in v) for p, v in gaps.items()}
    out.append(_finding(
        "Pairs 4–5, 6–7, 9–10 repeated (the same mode in x and y)",
        "; ".join(f"{_plates(p)} " + ", ".join(f"{100 * g:.1f} %" for g in v)
                  for p, v in gaps.items()),
        "reproduced" if all(v == len(PAIRS) for v in repeated.values()) else
        "partly" if any(repeated.values()) else "not reproduced",
        "pairs repeat where a mode is the same in x and y: the output shaft's bending, the "
        "plates' translation; the mesh spring acts along one line and splits the pairs it "
        "loads, and the order in which the kinds come is this model's, not the seed's"))

    order = np.mean((table[0] <= table[1] * (1 + 1e-9)) & (table[1] <= table[2] * (1 + 1e-9)))
    out.append(_finding(
        "One plate lowest, three plates highest",
        f"f(1 plate) ≤ f(2) ≤ f(3) in {100 * order:.0f} % of the first {n} modes",
        "reproduced" if order == 1 else "partly" if order >= 0.5 else "not reproduced",
        "splitting the plate moves its coupling to the shafts to two or three stations and "
        "cancels the single plate's forces on the output shaft"))

    ws = {p: b[p]["at_working_speed"] for p in b}
    sup_t = {p: ws[p]["turning"]["input_support_um"] for p in ws}
    sup_f = {p: ws[p]["frozen"]["input_support_um"] for p in ws}
    least_t, least_f = min(sup_t, key=sup_t.get), min(sup_f, key=sup_f.get)
    out.append(_finding(
        "Three plates: the smallest support-bearing amplitude",
        "input shaft's support journal at the working speed, turning mechanism "
        + _each(sup_t, ".3g") + " µm; the seed's frozen model " + _each(sup_f, ".3g")
        + " µm (1 / 2 / 3 plates)",
        "reproduced" if least_t == "3" and least_f == "3" else
        "partly" if least_t == "3" else "not reproduced",
        "with three plates the inertia forces and couples cancel, so the bearings see almost "
        "nothing in the turning mechanism"
        + ("" if least_f == "3" else "; the frozen model adds the spurious torsional "
           "excitation (below), which the drive-train mode near the working speed "
           "amplifies")))

    f2, c2 = b["2"]["unbalance"]["force_N"], b["2"]["unbalance"]["couple_Nm"]
    f1, f3, c3 = (b["1"]["unbalance"]["force_N"], b["3"]["unbalance"]["force_N"],
                  b["3"]["unbalance"]["couple_Nm"])
    out.append(_finding(
        "Two plates balance the inertia force but not its couple",
        f"by hand at the working speed: resultant {f1:.0f} / {f2:.2g} / {f3:.2g} N, couple "
        f"about the span's middle {b['1']['unbalance']['couple_Nm']:.2g} / {c2:.1f} / "
        f"{c3:.2g} N·m (1 / 2 / 3 plates)",
        "reproduced" if f2 < 1e-6 * f1 and c2 > 1e-3 and f3 < 1e-6 * f1 and c3 < 1e-6 * c2
        else "not reproduced",
        "two half plates at 180° cancel the force and leave it as a couple over their "
        "spacing; the 1/4, 1/2, 1/4 build cancels both. The single plate, at the middle of "
        "the span here, has a force and no couple about that middle"))

    qs = {p: ws[p]["quasi_static_frozen"]["output_twist_urad"] for p in ws}
    qt = {p: ws[p]["quasi_static_turning"]["output_twist_urad"] for p in ws}
    out.append(_finding(
        "The unbalance excites torsion as well as bending",
        "output twist at 1×, quasi-static at the working speed's forces: frozen model "
        + _each(qs, ".0f") + " µrad; turning mechanism " + _each(qt, ".2g")
        + " µrad (1 / 2 / 3 plates)",
        "explained: an artefact" if max(qt.values()) < 1e-3 * max(qs.values()) else
        "reproduced",
        "in the turning mechanism a plate's inertia force points along its crank and turns "
        "with it, as the eccentric and the mesh do: it pulls no torque out of the free cranks "
        "and so none out of the mesh. Frozen at one crank angle, the same force sweeps "
        "round a still mesh and eccentric and so drives torsion at 1×"))

    tw = {p: ws[p]["frozen"]["output_twist_urad"] for p in ws}
    more = tw["2"] > tw["1"] and tw["3"] > tw["1"]
    out.append(_finding(
        "Two and three plates twist the output shaft more than one",
        "frozen model at the working speed: " + _each(tw, ".3g") + " µrad (1 / 2 / 3 plates)",
        ("reproduced in the frozen model" if more else "not reproduced")
        + "; none in the turning mechanism",
        "in the frozen model the opposed plates' torques act at stations apart along the "
        "output shaft"
        + (", and two or three plates put the drive-train torsion mode nearer the working "
           "speed" if more else "")
        + "; the turning mechanism has no 1× twist to compare"))
    return out


def _each(values: dict, fmt: str) -> str:
    """The three builds' values, 1 / 2 / 3 plates."""
    return " / ".join(format(values[p], fmt) for p in ("1", "2", "3"))


def _plates(p) -> str:
    return f"{p} plate" + ("" if str(p) == "1" else "s")


def _finding(claim: str, measured: str, verdict: str, why: str) -> dict:
    return {"finding": claim, "measured": measured, "verdict": verdict, "why": why}


def _kinds(b: dict, k: int) -> str:
    return "; ".join(f"{_plates(p)} {b[p]['modes'][k]['rad_s']:.0f} rad/s, "
                     f"{b[p]['modes'][k]['kind']}" for p in b)


def _comparison(inputs: ReducerInputs, mesh: MeshSource, count: int) -> dict:
    """The frequencies and the working-speed response with Table 1's constant mesh stiffness
    beside fegear's mean tangent, its secant, and the tangent's least and largest over the
    mesh cycle (the frequencies' band under the parametric excitation)."""
    used = "tangent" if mesh.secant is not None else "given"
    cases = {"table": inputs.mesh_stiffness, used: mesh.stiffness}
    for name, v in (("secant", mesh.secant), ("tangent_min", mesh.tangent_min),
                    ("tangent_max", mesh.tangent_max)):
        if v is not None:
            cases[name] = v
    out = {"stiffness_N_per_m": cases, "used": used, "builds": {}}
    for plates in BUILDS:
        row = {}
        for name, k in cases.items():
            model = build_reducer(inputs, plates, k)
            row[name] = {"rad_s": [m.omega for m in modes(model, count)],
                         "at_working_speed": {
                             key: float(v[0]) for key, v in
                             sweep(model, [inputs.speed_rpm]).items()}}
        out["builds"][str(plates)] = row
    return out


# --- text ------------------------------------------------------------------------------------

def reducer_table(s: dict, shown: int) -> str:
    """The frequency table of the three builds side by side, the response at the working
    speed, the Campbell crossings and the findings (markdown)."""
    d, m = s["derived"], s["mesh"]
    lines = [f"Seed 003's three-axis reducer: ratio {d['ratio']:g}, output torque "
             f"{d['output_torque_Nm']:.0f} N·m, working speed {d['working_speed_rad_s']:.1f} "
             f"rad/s ({s['inputs']['speed_rpm']:g} r/min), mesh frequency "
             f"{d['mesh_frequency_rad_s']:.0f} rad/s ({d['mesh_frequency_Hz']:.0f} Hz)",
             f"mesh stiffness {m['stiffness_N_per_m']:.4g} N/m a single plate ({m['source']}"
             + (f"; Table 1's {m['table_N_per_m']:.3g}" if m["source"] != "table" else "")
             + ")", ""]
    head = "| mode | " + " | ".join(f"{p} plate{'s' if p != '1' else ''}: rad/s | Hz | kind"
                                    for p in s["builds"]) + " |"
    lines += [head, "|---:|" + "---:|---:|:---|" * len(s["builds"])]
    count = len(next(iter(s["builds"].values()))["modes"])
    for k in range(count):
        cells = []
        for b in s["builds"].values():
            mo = b["modes"][k]
            cells.append(f"{mo['rad_s']:.1f} | {mo['Hz']:.1f} | {mo['kind']}")
        lines.append(f"| {k + 1} | " + " | ".join(cells) + " |")
    spread = max(mo["spread_over_crank_angle_rad_s"] for b in s["builds"].values()
                 for mo in b["modes"])
    lines += ["", f"the frequencies move by at most {spread:.2g} rad/s over the crank angle "
              "(the model is frozen at one)"]
    lines += ["", "Unbalance response at the working speed (turning mechanism / the seed's "
              "frozen model):", "",
              "| | " + " | ".join(f"{p} plate{'s' if p != '1' else ''}" for p in s["builds"])
              + " |", "|:---|" + "---:|" * len(s["builds"])]
    for key, label in RESPONSES.items():
        lines.append(f"| {label} [{'µrad' if 'urad' in key else 'µm'}] | " + " | ".join(
            f"{b['at_working_speed']['turning'][key]:.3g} / "
            f"{b['at_working_speed']['frozen'][key]:.3g}" for b in s["builds"].values()) + " |")
    cross = [c for c in s["campbell"] if c["plates"] == shown and c["mode"] <= 5]
    lines += ["", f"Campbell ({shown} plate{'s' if shown != 1 else ''}): the unbalance (1×) "
              "meets " + (", ".join(f"mode {c['mode']} at {c['unbalance_rpm']:.0f} r/min"
                                    for c in cross if c["unbalance_rpm"]) or "no mode")
              + " below 1.5× the working speed; the mesh frequency meets modes 1–5 at "
              + ", ".join(f"{c['mesh_rpm']:.1f}" for c in cross) + " r/min (2×, parametric: "
              + ", ".join(f"{c['parametric_rpm']:.1f}" for c in cross) + ")"]
    if "mesh_comparison" in s:
        lines += ["", _comparison_table(s)]
    lines += ["", misalignment_table(s["misalignment"])]
    lines += ["", "Seed 003's findings, checked:", "",
              "| finding | this model | verdict |", "|:---|:---|:---|"]
    for f in s["findings"]:
        lines.append(f"| {f['finding']} | {f['measured']} | {f['verdict']} |")
    return "\n".join(lines)


def _comparison_table(s: dict) -> str:
    c = s["mesh_comparison"]
    k, used = c["stiffness_N_per_m"], c["used"]
    names = list(k)
    short = {"input_support_um": "input support journal", "output_twist_urad": "output twist"}
    lines = ["fegear's mesh stiffness against Table 1's (single plate, N/m: " + ", ".join(
        f"{n} {v:.4g}" for n, v in k.items()) + "):", "",
        "| plates | mode | " + " | ".join(f"{n} [rad/s]" for n in names)
        + f" | {used} vs table |",
        "|---:|---:|" + "---:|" * (len(names) + 1)]
    for p, row in c["builds"].items():
        for j in range(min(5, len(row["table"]["rad_s"]))):
            t, f = row["table"]["rad_s"][j], row[used]["rad_s"][j]
            lines.append(f"| {p} | {j + 1} | " + " | ".join(
                f"{row[n]['rad_s'][j]:.1f}" for n in names) + f" | {100 * (f / t - 1):+.1f} % |")
    lines += ["", f"the seed's frozen model at the working speed, table → {used}: "
              + "; ".join(f"{_plates(p)}: " + ", ".join(
                  f"{label} {row['table']['at_working_speed'][key]:.3g} → "
                  f"{row[used]['at_working_speed'][key]:.3g}" for key, label in short.items())
                  for p, row in c["builds"].items())
              + " (µm, µrad)"]
    return "\n".join(lines)


# --- files -----------------------------------------------------------------------------------

def write_reducer(out: Path, s: dict, shown: int) -> dict[str, Path]:
    """reducer.json, frequencies.csv, response.csv and the pictures."""
    files = {"json": write_json(out / "reducer.json", public(s))}
    rows = [(int(p), mo["mode"], mo["rad_s"], mo["Hz"], mo["kind"])
            for p, b in s["builds"].items() for mo in b["modes"]]
    files["frequencies_csv"] = write_csv(out / "frequencies.csv",
                                         ("plates", "mode", "rad_s", "Hz", "kind"), rows)
    header = ["model", "plates", "speed_rpm", *RESPONSES]
    resp = [(model, int(p), n, *(r[k][i] for k in RESPONSES))
            for model, builds in s["response"].items() for p, r in builds.items()
            for i, n in enumerate(s["speeds_rpm"])]
    files["response_csv"] = write_csv(out / "response.csv", header, resp)
    files["campbell_png"] = reducer_campbell_png(out / "campbell.png", s)
    b = s["builds"][str(shown)]
    files["modes_png"] = reducer_modes_png(out / "modes.png", b["_model"], b["_modes"])
    for n, key in enumerate(RESPONSES, start=2):
        files[f"fig{n}_png"] = reducer_response_png(out / f"fig{n}_{key.rsplit('_', 1)[0]}.png",
                                                    s, key)
    return files
