"""The table of docs/solve.md, "Across the face": the baseline and the relieved baseline across
the face at 0, 5, 8, 10 and 20 µm of misalignment and with the helix slope deviations of ISO
1328-1 classes 5 and 7, each row one `fegear solve … --json` (a refused input: its one line).

    .venv/bin/python studies/face_table.py                  # about 5 minutes on two cores
    .venv/bin/python studies/face_table.py --crowning 3     # the same rows with lead crowning

Every row solves a mesh cycle (--positions, default 6) at --quality (default coarse) under
200 N·m, without the error estimate, and reads the face's summary: K_Hβ and method C at the
cycle's worst, gear 1's root stress and the flank pressure at their worst sections with their
ratio to the 2D pair there, and the share of the face the most loaded tooth touches where K_Hβ
is largest (its line load linear between the sections).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys

from fegear.geometry import PairParameters
from fegear.tolerance.iso1328 import helix_tolerances

PAIRS = {"baseline": [],
         "relieved baseline": ["--relief", "3", "--relief-extent", "0.5",
                               "--tip-clearance", "0.02"]}
FACE_WIDTH = 5.0   # mm, the baseline's


def rows() -> list[tuple[str, list[str]]]:
    """Each row's name and its face inputs."""
    p = PairParameters()
    out = [(f"misalignment {f:g} µm", ["--misalignment", f"{f:g}"]) for f in (0, 5, 8, 10, 20)]
    for grade in (5, 7):
        slope, _ = helix_tolerances(grade, p.m * p.z1, FACE_WIDTH)
        teeth = ",".join(f"1:{t}={slope:g}" for t in range(p.z1))
        out.append((f"class {grade}: gear 1's helix slope +f_HβT = {slope:g} µm",
                    ["--helix-slope-deviation", teeth]))
        both = teeth + "," + ",".join(f"2:{t}={slope:g}" for t in range(p.z2))
        out.append((f"class {grade}: both gears' helix slope +f_HβT", ["--helix-slope-deviation",
                                                                        both]))
    return out


def contact_share(loads: list[float]) -> float:
    """The share of the face where a line load linear between equally spaced sections is
    positive."""
    n = len(loads) - 1
    touching = 0.0
    for a, b in zip(loads, loads[1:]):
        if a > 0 and b > 0:
            touching += 1.0
        elif a > 0 or b > 0:
            touching += max(a, b) / (abs(a) + abs(b)) if a != b else 0.0
    return touching / n


def solve(args: list[str]) -> dict | str:
    """``fegear solve ARGS --json``'s face summary, or the refusal's line."""
    done = subprocess.run([sys.executable, "-m", "fegear", "solve", *args, "--json"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        return done.stderr.strip().splitlines()[-1]
    return json.loads(done.stdout)["face"]


def table_row(name: str, face: dict | str) -> str:
    if isinstance(face, str):   # "fegear: error: --x = v is not admissible (why); admissible: …"
        why = face.partition("is not admissible (")[2].split(":")[0] or face
        admissible = face.rpartition("admissible: ")[2].split(" with ")[0].rstrip(",")
        text = f"refused: {why}; admissible {admissible}".replace("|", "\\|")
        return f"| {name} | {text} | | | | |"
    worst = max(face["positions"], key=lambda r: r["K_Hbeta"])
    tooth = max(worst["line_loads_N_per_mm"].values(), key=sum)
    root, flank = (face["worst"][k] for k in ("root_stress_gear1_MPa",
                                              "flank_contact_pressure_MPa"))
    return (f"| {name} | {face['K_Hbeta']:.3f} | {face['K_Hbeta_method_c']:.3f} | "
            f"{root['value']:.0f} (×{root['ratio']:.3f}) | {flank['value']:.0f} "
            f"(×{flank['ratio']:.3f}) | {100 * contact_share(tooth):.0f} % |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--crowning", type=float, default=None)
    parser.add_argument("--positions", type=int, default=6)
    parser.add_argument("--quality", default="coarse")
    a = parser.parse_args()
    common = ["--torque", "200", "--quality", a.quality, "--positions", str(a.positions),
              "--no-estimate"]
    if a.crowning is not None:
        common += ["--crowning", f"{a.crowning:g}"]
    for pair, extra in PAIRS.items():
        print(f"\n{pair}{'' if a.crowning is None else f', crowning {a.crowning:g} µm'}:\n")
        print("| inputs | K_Hβ | method C | root σ1 gear 1, MPa (×2D) | flank pressure, MPa "
              "(×2D) | face in contact |")
        print("|---|---:|---:|---:|---:|---:|")
        for name, face in rows():
            print(table_row(name, solve([*common, *extra, *face])), flush=True)


if __name__ == "__main__":
    main()
