"""Benchmarks: time per pipeline stage, printed as a markdown table (never asserted in tests)."""

from __future__ import annotations

import platform
import time

import numpy as np

from .cycloid import gear2_curve
from .params import PairParameters
from .profile import Gear1Profile
from .tca import ToothContact

GEOMETRY_TARGET_S = 1.0


def _best(fn, repeat: int):
    best, value = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        value = fn()
        best = min(best, time.perf_counter() - t0)
    return best, value


def geometry_bench(params: PairParameters, repeat: int = 3, chord_error: float = 1e-4) -> str:
    """Time the geometry stage: profiles plus clearance table (target < 1 s), and backlash."""
    rows = []
    t_env, g1 = _best(lambda: Gear1Profile(params), repeat)
    rows.append(("gear-1 envelope (exact pieces)", t_env))
    t_poly, _ = _best(lambda: (g1.polyline(chord_error),
                               gear2_curve(params).polyline(chord_error)), repeat)
    rows.append((f"polylines, both gears (chord error {chord_error * 1e3:g} µm)", t_poly))
    t_tca, _ = _best(lambda: ToothContact(params, g1).state(0.0), repeat)
    rows.append((f"clearance table at β = 0 ({params.z1} teeth × 2 directions)", t_tca))
    total = t_env + t_poly + t_tca
    t_bl, bl = _best(lambda: ToothContact(params, g1).backlash(), 1)
    lines = [
        f"fegear geometry benchmark: {params.describe()}",
        f"python {platform.python_version()}, numpy {np.__version__}, "
        f"{platform.machine()}, best of {repeat}",
        "",
        "| stage | time [s] |",
        "|---|---:|",
    ]
    lines += [f"| {name} | {t:.3f} |" for name, t in rows]
    status = "met" if total < GEOMETRY_TARGET_S else "MISSED"
    lines.append(f"| **profiles + clearance table** (target < {GEOMETRY_TARGET_S:g} s: {status})"
                 f" | **{total:.3f}** |")
    lines.append(f"| backlash over one mesh cycle (+ {bl.plus_um:.3f} µm, − {bl.minus_um:.3f} µm)"
                 f" | {t_bl:.3f} |")
    return "\n".join(lines)


def hertz_bench(repeat: int = 3) -> str:
    """Time the FE stages on the Hertz case (two 10 mm disks, 1000 N, 5 mm) per quality level."""
    from .disks import QUALITY, DiskCase, solve_disks

    lines = ["fegear FE benchmark: two disks r 10 mm, P 1000 N, t 5 mm, plane stress "
             f"(best of {repeat} per stage)", "",
             "| quality | DOFs | contact points | mesh | assemble+factor | condense | contact | "
             "recovery | total [s] | p_max err % | b err % |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for quality in QUALITY:
        runs = [solve_disks(DiskCase(quality=quality)) for _ in range(repeat)]
        best = {k: min(r.timings_s[k] for r in runs) for k in runs[0].timings_s}
        r = runs[0]
        lines.append(f"| {quality} | {r.dofs} | {r.contact_points} | {best['mesh']:.3f} | "
                     f"{best['assemble_factor']:.3f} | {best['condense']:.3f} | "
                     f"{best['contact']:.3f} | {best['recovery']:.3f} | "
                     f"{sum(best.values()):.3f} | {r.p_error_pct:+.3f} | {r.b_error_pct:+.3f} |")
    return "\n".join(lines)


CYCLE_TARGET = 3.0  # a mesh cycle of N positions costs less than 3× one position


def pair_bench(params: PairParameters, torque: float = 200.0, quality: str = "standard",
               positions: int = 24) -> str:
    """Time the baseline tooth-pair solve at one position against a mesh cycle of
    ``positions`` rolling angles on one mesh (target: the cycle < 3× one position)."""
    from .toothpair import SolveCase, cycle_positions, solve_positions

    case = SolveCase(params, torque=torque, quality=quality)
    profile = Gear1Profile(params)
    t0 = time.perf_counter()
    one = solve_positions(case, (case.beta,), profile)[0]
    t_one = time.perf_counter() - t0
    t0 = time.perf_counter()
    cycle = solve_positions(case, cycle_positions(case.beta, positions, params.z2), profile)
    t_cycle = time.perf_counter() - t0
    stages = ("profile", "mesh", "assemble_factor", "condense", "contact", "recovery")
    later = cycle[1:]

    def per_position(k):
        return sum(s.timings_s[k] for s in later) / len(later) if later else 0.0

    lines = [f"fegear tooth-pair benchmark: {params.describe()}, T {torque:g} N·m, quality "
             f"{quality}", "",
             "| run | DOFs | contact points | " + " | ".join(stages) + " | total [s] |",
             "|---|---:|---:|" + "---:|" * (len(stages) + 1)]
    for name, s, total in (("one position", one, f"{t_one:.2f}"),
                           (f"cycle, first of {positions}", cycle[0], "")):
        times = " | ".join(f"{s.timings_s.get(k, 0.0):.2f}" for k in stages)
        lines.append(f"| {name} | {s.dofs} | {s.model.npoints} | {times} | {total} |")
    lines.append(f"| cycle, each later position (mean) | | | | | | {per_position('condense'):.2f}"
                 f" | {per_position('contact'):.2f} | {per_position('recovery'):.2f} | |")
    ratio = t_cycle / t_one
    status = "met" if ratio < CYCLE_TARGET else "MISSED"
    lines.append(f"| **{positions}-position cycle** (target < {CYCLE_TARGET:g}× one position: "
                 f"{status}, {ratio:.2f}×) | | | | | | | | | **{t_cycle:.2f}** |")
    return "\n".join(lines)
