"""How a load on a gear's tooth spreads along the face on its neighbours, in 3D: the part of
the pair's coupling that one tooth's kernel does not measure (docs/model.md, "The other
teeth's part, in 3D").

One kernel for all teeth, gear 1's tooth's answer to its own load, would spread the whole
finite-element part of the approach along the face alike. Of the pair's finite-element
approach at the loaded points, 16 % is the other loaded teeth's answer, through the rims.
This study reads that part in 3D on the body the tooth checks use
(:mod:`fegear.verify.tooth3d`: nine pitches of gear 1 about the loaded tooth 0, down to the
solve's bore): under each patch load on tooth 0's band, the displacement into teeth ±1, ±2 and
±3 at the same place of their loaded flanks, along the face; each row divided by the same
tooth's answer to the load spread evenly over the face, as the tooth checks divide tooth 0's
(``--gear 2``: gear 2's nine pitches, held at its rim).
The table's slice-model row is the tooth's own finite-element part (the near field stays on
the loaded tooth), spread by the kernel: how one kernel for all would read a neighbour.

    .venv/bin/python studies/face_neighbours.py              # standard 3D, about a minute
    .venv/bin/python studies/face_neighbours.py coarse       # about 15 s
    .venv/bin/python studies/face_neighbours.py --width 10 --patches 18
    .venv/bin/python studies/face_neighbours.py --gear 2     # gear 2's teeth, about a minute
    .venv/bin/python studies/face_neighbours.py --pair-check   # the pair with them, 15 s
    .venv/bin/python studies/face_neighbours.py --widths       # the tilts' table, ~6 min

``--pair-check`` solves the misaligned baseline as the 3D pair check does (docs/validation.md:
200 N·m, 9.9 µm, `coarse`) with the coupling's spread between teeth (``across``,
:class:`~fegear.toothpair.ring.face.FaceCoupling`) set in several ways, the tooth's own spread
with the twist (:data:`~fegear.toothpair.ring.face.TWIST_TABLE`) or without, the last the
product's (the tilts of :data:`~fegear.toothpair.ring.face.NEIGHBOUR_TILTS`); beside
CalculiX's numbers for the 3D pair. ``--widths`` fits the tilts at the twist table's face
widths and prints them as the source's NEIGHBOUR_TILTS.

Each neighbour is read at the section's boundary nodes within :data:`READ_RADIUS` of its band
centre (tooth 0's turned by whole pitches), or within 1.5 times the nearest one's distance where
that is farther (teeth ±2 and ±3 lie where the body's elements are 1.5 mm at `standard`), the
displacement along the flank's inward normal averaged over them.
"""

from __future__ import annotations

import argparse

import numpy as np

from fegear.fe import STEEL_E, STEEL_NU
from fegear.geometry import PairParameters
from fegear.verify.face_slices import band_compliance, product_influence
from fegear.verify.tooth3d import (
    SIZES,
    Extrusion,
    TwoLevel,
    gear2_band,
    load_band,
    section_of,
    tet_stiffness,
)

#: the boundary nodes read about a neighbour's band centre (mm)
READ_RADIUS = 0.35
NEIGHBOURS = (-3, -2, -1, 1, 2, 3)


def neighbour_columns(params: PairParameters, width: float, patches: int, size: str,
                      gear: int = 1):
    """``gear``'s 3D body's answers along the face (patch centres), per patch load and the
    even load: tooth 0's (its band's means) and each neighbour's (:data:`NEIGHBOURS`), µm per
    N, {tooth: (patches, patches + 1)}; and the patch centres (mm)."""
    level = SIZES[size]
    centre, outward, pitch = _band_centre(params, gear)
    section = section_of(params, 0.5, level, gear=gear)
    body = Extrusion(section, width, patches * level.layers)
    K = tet_stiffness(body, STEEL_E, STEEL_NU)
    F, means = body.band_loads(patches)
    F = np.column_stack([F, F.mean(axis=1)])
    U, _ = TwoLevel(body, K).solve(F)
    per = (len(body.level_z) - 1) // (2 * patches)
    centres = (2 * np.arange(patches) + 1) * per
    out = {0: (1e3 * F.T @ U)[:patches]}         # tooth 0: each patch's mean, as G is read
    points = section.points
    boundary = _boundary_nodes(section.triangles)
    for k in NEIGHBOURS:
        turn = k * pitch
        rot = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
        at, normal = rot @ centre, rot @ outward
        distance = np.hypot(*(points[boundary] - at).T)
        near = boundary[distance <= max(READ_RADIUS, 1.5 * distance.min())]
        rows = np.zeros((len(body.level_z), patches + 1))
        for node in near:
            dof = 3 * body.free[body.dof_at[node, :]]
            rows -= normal[0] * U[dof] + normal[1] * U[dof + 1]
        out[k] = 1e3 * rows[centres] / len(near)
    return out, (np.arange(patches) + 0.5) * width / patches


def _band_centre(params: PairParameters, gear: int) -> tuple[np.ndarray, np.ndarray, float]:
    """The load band's centre on ``gear``'s tooth 0 (mm, the gear's frame), the flank's
    outward normal there (out of the tooth) and the gear's pitch (rad)."""
    if gear == 1:
        _, shape, band = load_band(params, 0.5)
        phi = np.array([band.centre])
        return shape.point(phi)[0], shape.frame(phi)[1][0], shape.pitch
    curve, band = gear2_band(params, 0.5)
    xi = curve.xi_at_angle(np.array([band.centre]), tabled=False)
    return curve.point(xi)[0], curve.frame(xi)[2][0], 2 * np.pi / params.z2


def _boundary_nodes(triangles: np.ndarray) -> np.ndarray:
    """The section's boundary corners: those of the edges that one triangle alone has."""
    edges = np.sort(triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    return np.unique(unique[counts == 1])


def slice_columns(params: PairParameters, width: float, patches: int) -> np.ndarray:
    """The slice model's finite-element part on the patches, as the product couples the face
    (:func:`~fegear.verify.face_slices.product_influence` less its near field, which stays on
    the loaded patch), each row divided by its mean: a neighbour's column as the product
    spreads it."""
    band = band_compliance(params)
    G = product_influence(band, width, patches) - np.eye(patches) * band.near * patches / width
    return G / G.mean(axis=1)[:, None]


def tilts(answers: dict, z: np.ndarray, width: float) -> dict[int, float]:
    """Each distance's tilt c: the neighbours' end columns (rows divided by the even load's)
    fitted in the least squares as 1 + c P1(z) P1(z0) over both sides (P1 = 2 z / b − 1, z0
    the loaded end patch)."""
    p1 = 2 * z / width - 1
    out = {}
    for d in sorted({abs(k) for k in answers if k}):
        r = np.concatenate([answers[k][:, 0] / answers[k][:, -1] - 1 for k in (-d, d)])
        x = np.concatenate([p1 * p1[0]] * 2)
        out[d] = float(x @ r / (x @ x))
    return out


def table(params: PairParameters, width: float, patches: int, size: str, gear: int = 1) -> str:
    """The mid-face and end columns of each tooth's answer (rows divided by the even load's)
    and the slice model's finite-element part (gear 1's kernel, whichever ``gear``)."""
    answers, z = neighbour_columns(params, width, patches, size, gear)
    model = slice_columns(params, width, patches)
    lines = [f"gear {gear}, {size} 3D, face {width:g} mm, {patches} patches (z = "
             + " ".join(f"{v:.2f}" for v in z) + " mm)"]
    for column, name in ((patches // 2, "mid-face"), (0, "one end")):
        lines.append(f"load at {name} (patch {column}): G_ij / uniform_i")
        lines.append(f"  {'slice model, FE part':<24} " + " ".join(
            f"{v:6.3f}" for v in model[:, column]))
        for k in sorted(answers, key=abs):
            G = answers[k]
            shape = G[:, column] / G[:, -1]
            lines.append(f"  {'tooth ' + format(k, '+d') if k else 'tooth 0 (loaded)':<24} "
                         + " ".join(f"{v:6.3f}" for v in shape))
    lines.append("the tilt c of each distance (the end column, both sides, fitted as "
                 "1 + c P1(z) P1(z0), P1 = 2 z / b - 1): " + ", ".join(
                     f"{d} apart {c:+.3f}" for d, c in tilts(answers, z, width).items()))
    lines.append("the even load's answer (µm per kN), tooth 0 and its neighbours, at the "
                 "middle patch and an end one:")
    mid = answers[0][patches // 2, -1]
    for k in sorted(answers, key=abs):
        u = 1e3 * answers[k][:, -1]
        lines.append(f"  tooth {k:+d}: {u[patches // 2]:.3f} mid, {u[0]:.3f} end "
                     f"({u[0] / u[patches // 2]:.3f}; {u[patches // 2] / (1e3 * mid):.3f}"
                     " of tooth 0's)")
    return "\n".join(lines)


def tilt_table(params: PairParameters, size: str) -> str:
    """Each distance's tilt (:func:`tilts`) at the twist table's face widths in tooth heights
    (face_end_column.WIDTHS), with the largest departure of the neighbours' end columns from
    the fitted line, and the table as the source's NEIGHBOUR_TILTS."""
    from face_end_column import WIDTHS

    h = band_compliance(params).tooth_height
    lines = [f"{'b/h':>4} {'face mm':>7}   tilt 1, 2, 3 apart   largest departure from the line"]
    rows = []
    for b_h, patches in WIDTHS:
        width = round(b_h * h, 3)
        answers, z = neighbour_columns(params, width, patches, size)
        c = tilts(answers, z, width)
        p1 = 2 * z / width - 1
        off = max(float(np.abs(answers[k][:, 0] / answers[k][:, -1] - 1
                               - c[abs(k)] * p1 * p1[0]).max()) for k in NEIGHBOURS)
        lines.append(f"{b_h:4.1f} {width:7.3f}   " + " ".join(f"{c[d]:+.3f}" for d in (1, 2, 3))
                     + f"   {off:.3f}")
        rows.append(f"({b_h}, ({', '.join(f'{c[d]:.2f}' for d in (1, 2, 3))}))")
    return "\n".join(lines + ["NEIGHBOUR_TILTS = (" + ", ".join(rows) + ")"])


#: CalculiX on the extruded pair at 9.9 µm (docs/validation.md, "Across the face: a 3D FE of
#: the pair"): K_Hβ (its end values extrapolated from its two end layers) and the worst root
#: σ1 of gear 1 and gear 2 (MPa)
CALCULIX = (1.500, 381.6, 352.1)


def pair_check() -> str:
    """K_Hβ and the worst root stresses of the baseline at 200 N·m and 9.9 µm (`coarse`)
    with each coupling variant (module docstring), fegear's K_Hβ also read as CalculiX's is
    (its line loads averaged over the six layers, the ends extrapolated from the two end
    layers), and the differences from CalculiX's."""
    from unittest import mock

    from fegear.toothpair.job import prepare_job, solve_job
    from fegear.toothpair.ring import face
    from fegear.verify.calculix_face import LAYERS, end_loads, layer_means, load_factor

    def variant(twist: bool, across):
        def make(sections, width, tooth_height, near_share):
            c = face.tooth_coupling(sections, width, tooth_height, near_share,
                                    face.twist_of(width, tooth_height) if twist else 0.0)
            return c if across is None else face.tilted_across(c, *np.atleast_1d(across))
        return make

    k0, r1, r2 = CALCULIX
    lines = [f"CalculiX 3D pair: K_Hβ {k0:.3f}, root σ1 {r1:.1f} / {r2:.1f} MPa",
             f"{'coupling':<52} {'K_Hβ':>6} {'layers':>6} "
             f"{'root σ1 gear 1 / 2':>18}   CalculiX above: K_Hβ, layers, roots"]
    for name, make in (
            ("one kernel for all, no twist (before 2026-12-03)", variant(False, None)),
            ("the tooth's twist, one kernel for all", variant(True, None)),
            ("no twist; between teeth even", variant(False, 0.0)),
            ("the tooth's twist; between teeth even", variant(True, 0.0)),
            ("the tooth's twist; between teeth even + 0.31 P1", variant(True, 0.31)),
            ("the product: twist; by distance (NEIGHBOUR_TILTS)", face.product_coupling)):
        with mock.patch.object(face, "product_coupling", make):
            f = solve_job(prepare_job({"torque": 200.0, "quality": "coarse",
                                       "no-estimate": True, "misalignment": 9.9})).summary["face"]
        means = layer_means(f["positions"][0]["line_loads_N_per_mm"], f["zeta"], LAYERS)
        loads = np.array(list(means.values()))
        k, layered = f["K_Hbeta"], load_factor(loads, end_loads(loads))
        g1, g2 = (f["worst"][f"root_stress_gear{g}_MPa"]["value"] for g in (1, 2))
        lines.append(f"{name:<52} {k:6.3f} {layered:6.3f} {g1:8.1f} / {g2:6.1f}   "
                     f"{100 * (k0 / k - 1):+.1f} %, {100 * (k0 / layered - 1):+.1f} %, "
                     f"{100 * (r1 / g1 - 1):+.1f} / {100 * (r2 / g2 - 1):+.1f} %")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("size", nargs="?", default="standard", choices=sorted(SIZES))
    parser.add_argument("--width", type=float, default=5.0, help="face width (mm)")
    parser.add_argument("--patches", type=int, default=9)
    parser.add_argument("--gear", type=int, default=1, choices=(1, 2),
                        help="gear 2's teeth (held at its rim) instead of gear 1's")
    parser.add_argument("--widths", action="store_true",
                        help="the tilts at the twist table's face widths (gear 1)")
    parser.add_argument("--pair-check", action="store_true",
                        help="the misaligned pair with each coupling, against CalculiX")
    a = parser.parse_args()
    if a.pair_check:
        print(pair_check())
        return
    params = PairParameters(shift=0.016, rotation=0.002)
    if a.widths:
        print(tilt_table(params, a.size))
        return
    print(table(params, a.width, a.patches, a.size, a.gear))


if __name__ == "__main__":
    main()
