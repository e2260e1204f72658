"""The end column of the slice model against the 3D tooth: what an end-aware coupling gains
(docs/model.md, "Across the face: the tooth in 3D", "The end column: what was tried").

The measured kernel mirrored in the free ends, with the "slope" rows and no twist, reads the
baseline's 3D tooth within 0.43 % (peak) and 2.1 % (far) under a load at mid-face, 3.8 % and
17.8 % under a load at one end; the twist (P1 below, the product's:
docs/model.md, "The tooth's twist") takes the end column to 1.0 % and 6.8 %. Each variant
here keeps the uniform-face property (every row of the spread sums to one, so the slice
model's rows of G under an even load give the 2D pair's) and is read as
:func:`fegear.verify.face_slices.compare` reads the product's:

* the mirror images weighted by μ (0 none, 1 the product's), the rows corrected as before;
* S' = S + E with E = V C Vᵀ diag(share): V's columns shapes along the face of zero mean
  over it (E·1 = 0 exactly, E symmetric in the share's weights), C fitted in the least
  squares to the 3D tooth's columns (G_ij / uniform_i); P1 the linear shape (the tooth's
  twist: a load at one end tilts the whole face), P3 the cubic one, "end L" the even
  end layer exp(−z/Lh) + exp(−(b−z)/Lh) less its mean. P1 and P3 are odd about mid-face:
  they leave the mid-face column exactly as it was.
* P1 with its strength not fitted to the end column but from one number of the 3D tooth:
  the slope of its answer to a load linear across the face at mid-face (0.80 of an even
  load's on the baseline, the slice model's 0.71).

    .venv/bin/python studies/face_end_column.py             # the standard tooth, ~1 minute
    .venv/bin/python studies/face_end_column.py coarse      # the coarse tooth, ~15 s
    .venv/bin/python studies/face_end_column.py coarse --width 10 --patches 18
    .venv/bin/python studies/face_end_column.py --pair m=1.5     # another design
    .venv/bin/python studies/face_end_column.py --widths         # the twist's table, ~12 min
    .venv/bin/python studies/face_end_column.py --widths --gear 2   # gear 2's tooth, ~15 min

The twist, P1 fitted to the end column, is tabulated by the face width in tooth heights
(fegear.toothpair.ring.face.TWIST_TABLE, the product's): ``--widths`` fits it on the
baseline's tooth at b/h 1.5, 2, 2.5, 3.3 and 5 and prints the table, with the end column's
peak and far part without the twist and with it. The misaligned pair with and without it:
``studies/face_neighbours.py --pair-check``.

``--widths --gear 2`` measures gear 2's tooth (the internal gear, held at its outer rim) at the
same widths in its own tooth heights (4 e1, 2.4 mm on the baseline), the same patches. Its
twist cannot be fitted as gear 1's is: the slice model's 2D parts (:func:`band_compliance`:
the near field's share, on which the fit rests) are gear 1's ring model's, and gear 2's are
not measured. The table gives the raw 3D quantities instead (``--raw`` gives them for gear
1): the end column's own patch and far end and the mid-face column's own patch (G_ij /
uniform_i), the mid-face slope under a load linear across the face, the mean of the face
under the even load per plane stress, and the c that the fit would give if gear 2's near
share were gear 1's (the fit's dependence on it shown by half and one and a half times it).
"""

from __future__ import annotations

import argparse

import numpy as np

from fegear.geometry import PairParameters
from fegear.toothpair import correction_factors, kernel_weights, measured_kernel
from fegear.verify.face_slices import PER_PATCH, BandCompliance, band_compliance, compare
from fegear.verify.tooth3d import FaceInfluence, face_influence


class Slices:
    """The slice model's pieces on ``patches`` patches of a face ``width`` (mm): the
    sections (PER_PATCH a patch), their shares and the product's spread (mirror weight μ)."""

    def __init__(self, band: BandCompliance, width: float, patches: int) -> None:
        self.band, self.width, self.patches = band, width, patches
        n = patches * PER_PATCH + 1
        kernel = measured_kernel(band.tooth_height, band.near_share)
        self.z, self.share, self.mirrored = kernel_weights(n, width, kernel, True)
        self.direct = kernel_weights(n, width, kernel, False)[2]
        self.w = width / patches
        self.within = np.zeros((n, patches))      # ∫ over patch j of section i's hat
        step = self.w / PER_PATCH
        for j in range(patches):
            self.within[j * PER_PATCH:(j + 1) * PER_PATCH + 1, j] = step
            self.within[[j * PER_PATCH, (j + 1) * PER_PATCH], j] = 0.5 * step

    def spread(self, mu: float = 1.0) -> np.ndarray:
        """The spread with the images weighted by ``mu``, its rows corrected ("slope")."""
        w = (1.0 - mu) * self.direct + mu * self.mirrored
        return w * correction_factors(self.z, self.share, w, "slope")

    def influence(self, spread: np.ndarray, near: bool = True) -> np.ndarray:
        """G on the patches (µm per N) from a ``spread``, with the near field or without."""
        load = self.within / self.w / (self.share * self.width)[:, None]
        G = self.band.fe * (self.within.T / self.w) @ spread @ load
        return G + np.eye(self.patches) * self.band.near / self.w if near else G

    def shape(self, name: str) -> np.ndarray:
        """A shape along the face at the sections, its mean over the face taken off."""
        x = 2.0 * self.z / self.width - 1.0
        if name == "P1":
            v = x
        elif name == "P3":
            v = 0.5 * (5.0 * x ** 3 - 3.0 * x)
        else:                                       # "end L": the even end layer
            length = float(name.split()[1]) * self.band.tooth_height
            v = np.exp(-self.z / length) + np.exp(-(self.width - self.z) / length)
        return v - self.share @ v

    def term(self, a: str, b: str) -> np.ndarray:
        """E for C's entries (a, b) and (b, a) one (the spread's units)."""
        va, vb = self.shape(a), self.shape(b)
        pair = np.outer(va, vb)
        return (pair + pair.T if a != b else pair) * self.share[None, :]


def fitted(slices: Slices, solid: FaceInfluence, names: list[str],
           columns: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """The spread S + E, C diagonal over ``names``, fitted to ``solid``'s ``columns``; and C."""
    S = slices.spread()
    G0 = slices.influence(S)
    mean = G0.mean(axis=1)[:, None]                 # unchanged by E (E·1 = 0)
    target = solid.G / solid.uniform[:, None]
    terms = [slices.term(n, n) for n in names]
    A = np.column_stack([(slices.influence(E, near=False) / mean)[:, columns].ravel()
                         for E in terms])
    c = np.linalg.lstsq(A, (target - G0 / mean)[:, columns].ravel(), rcond=None)[0]
    return S + sum(ci * E for ci, E in zip(c, terms)), c


def mid_slope(G: np.ndarray, z: np.ndarray, width: float) -> float:
    """The slope at mid-face of G's answer to a load linear across the face, per the even
    load's answer (ζ the patches' place, −½ … ½)."""
    zeta = z / width - 0.5
    r = (G @ zeta) / G.sum(axis=1)
    m = len(z) // 2
    return float((r[m + 1] - r[m - 1]) / (zeta[m + 1] - zeta[m - 1]))


def twist_from_slope(slices: Slices, solid: FaceInfluence) -> tuple[np.ndarray, float]:
    """S + c P1 P1ᵀ diag(share), c making the slice model's mid-face slope the 3D tooth's."""
    S = slices.spread()
    z = solid.z
    E = slices.term("P1", "P1")
    s0 = mid_slope(slices.influence(S), z, slices.width)
    s1 = mid_slope(slices.influence(S + E), z, slices.width)
    c = (mid_slope(solid.G, z, slices.width) - s0) / (s1 - s0)   # linear in c: G·1 fixed
    return S + c * E, c


def row(name: str, slices: Slices, solid: FaceInfluence, spread: np.ndarray,
        note: str = "") -> str:
    """One line of the table: mid-face and end columns' peak and far (%), the rows'
    sums' spread under the even load (the uniform-face property) and ``note``."""
    G = slices.influence(spread)
    mid, end = compare(solid, G, slices.patches // 2), compare(solid, G, 0)
    sums = np.abs(spread.sum(axis=1) - 1.0).max()
    ok = "yes" if sums < 1e-12 else f"no ({sums:.1e})"
    return (f"{name:<34} {100 * mid.peak:5.2f} {100 * mid.far:5.1f}   {100 * end.peak:5.2f} "
            f"{100 * end.far:5.1f}   {ok:<6} {note}")


def table(solid: FaceInfluence, band: BandCompliance) -> str:
    """Every variant's line (module docstring)."""
    width, patches = solid.z[0] + solid.z[-1], len(solid.z)
    slices = Slices(band, width, patches)
    end, both, every = [0], [0, patches // 2], list(range(patches))
    lines = [f"{solid.size} 3D, face {width:g} mm, {patches} patches; slopes at mid-face "
             f"3D {mid_slope(solid.G, solid.z, width):.3f}, slice model "
             f"{mid_slope(slices.influence(slices.spread()), solid.z, width):.3f}",
             f"{'variant':<34} {'mid: peak far %':<16} {'end: peak far %':<17} rows=1",
             row("no twist (mirror μ 1)", slices, solid, slices.spread())]
    for mu in (0.0, 0.5, 0.75, 1.25, 1.5):
        lines.append(row(f"mirror μ {mu:g}", slices, solid, slices.spread(mu)))
    spread, c = twist_from_slope(slices, solid)
    lines.append(row("P1, c from the 3D mid-face slope", slices, solid, spread, f"c {c:.3f}"))
    for names, columns, label in ((["P1"], end, "end"), (["P1", "P3"], end, "end"),
                                  (["P1", "end 0.5"], end, "end"),
                                  (["P1", "end 0.5"], both, "end+mid"),
                                  (["P1", "P3", "end 0.5"], both, "end+mid"),
                                  (["P1", "P3", "end 0.5"], every, "all"),
                                  (["P1", "P3", "end 0.25"], both, "end+mid")):
        spread, c = fitted(slices, solid, names, columns)
        lines.append(row(f"{' + '.join(names)}, fit {label}", slices, solid, spread,
                         "c " + " ".join(f"{v:.3f}" for v in c)))
    return "\n".join(lines)


#: the twist table's widths in tooth heights and the patches across each (about 0.56 mm each)
WIDTHS = ((1.5, 5), (2.0, 7), (2.5, 9), (3.3, 11), (5.0, 18))


def twist_table(params: PairParameters, size: str) -> str:
    """P1's coefficient fitted to the end column at each of :data:`WIDTHS`, with the end
    column read without the twist and with it, and the table as the source's TWIST_TABLE
    (fegear.toothpair.ring.face)."""
    band = band_compliance(params, quality="standard")
    h = band.tooth_height
    lines, table = [f"{'b/h':>4} {'face mm':>7} {'c':>7}   end without: peak far %   with"], []
    for b_h, patches in WIDTHS:
        width = round(b_h * h, 3)
        solid = face_influence(params, thickness=width, patches=patches, size=size)
        slices = Slices(band, width, patches)
        spread, c = fitted(slices, solid, ["P1"], [0])
        plain = compare(solid, slices.influence(slices.spread()), 0)
        twisted = compare(solid, slices.influence(spread), 0)
        lines.append(f"{b_h:4g} {width:7.3f} {c[0]:7.4f}   {100 * plain.peak:5.2f} "
                     f"{100 * plain.far:5.1f}            {100 * twisted.peak:5.2f} "
                     f"{100 * twisted.far:5.1f}")
        table.append(f"({b_h:g}, {c[0]:.4f})")
    return "\n".join(lines + ["TWIST_TABLE = (" + ", ".join(table) + ")"])


def raw_table(params: PairParameters, size: str, gear: int) -> str:
    """``gear``'s tooth at each of :data:`WIDTHS` in its own tooth heights: the raw 3D
    quantities and c with gear 1's near share (module docstring), then the end and mid-face
    columns in full."""
    one = band_compliance(params, quality="standard")
    head = (f"gear {gear}'s tooth, {size}; G_ij / uniform_i: end column (patch 0) own, far; "
            f"mid-face column own; c with gear 1's near share {one.near_share:.3f} (× 0.5, 1.5)")
    lines = [head, f"{'b/h':>4} {'face mm':>7} {'n':>3} {'end own':>8} {'far':>8} "
                   f"{'mid own':>8} {'slope':>6} {'3D/pl.σ':>8} {'c':>7} {'c×0.5':>7} {'c×1.5':>7}"]
    columns = []
    for b_h, patches in WIDTHS:
        h = one.tooth_height if gear == 1 else 4 * params.e1     # gear 2's: r0 ± 2 e1
        width = round(b_h * h, 3)
        solid = face_influence(params, thickness=width, patches=patches, size=size,
                               gear=gear)
        columns.append((b_h, solid.G / solid.uniform[:, None]))
        cs = []
        for k in (1.0, 0.5, 1.5):
            share = k * one.near_share
            band = BandCompliance(share * one.total, (1 - share) * one.total,
                                  solid.tooth_height)
            cs.append(fitted(Slices(band, width, patches), solid, ["P1"], [0])[1][0])
        col, mid = columns[-1][1], patches // 2
        lines.append(f"{b_h:4g} {width:7.3f} {patches:3d} {col[0, 0]:8.4f} {col[-1, 0]:8.4f} "
                     f"{col[mid, mid]:8.4f} {mid_slope(solid.G, solid.z, width):6.3f} "
                     f"{solid.uniform.mean() / solid.plane_stress:8.4f} "
                     + " ".join(f"{c:7.4f}" for c in cs))
    for b_h, col in columns:
        lines += [f"b/h {b_h:g} end column: " + " ".join(f"{v:.3f}" for v in col[:, 0]),
                  f"b/h {b_h:g} mid column: " + " ".join(
                      f"{v:.3f}" for v in col[:, len(col) // 2])]
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("size", nargs="?", default="standard", help="the 3D tooth's size")
    parser.add_argument("--width", type=float, default=5.0, help="face width, mm")
    parser.add_argument("--patches", type=int, default=9, help="patches across the face")
    parser.add_argument("--pair", action="append", default=[], metavar="NAME=VALUE",
                        help="a PairParameters field (e.g. m=1.5), repeatable")
    parser.add_argument("--widths", action="store_true",
                        help="fit the twist at each tabulated face width (TWIST_TABLE)")
    parser.add_argument("--gear", type=int, default=1, choices=(1, 2),
                        help="the gear whose tooth is measured (2: raw quantities)")
    parser.add_argument("--raw", action="store_true",
                        help="with --widths: the raw 3D quantities (gear 2's always)")
    args = parser.parse_args()
    given = dict(a.split("=", 1) for a in args.pair)
    params = PairParameters(**{k: int(v) if k in ("z1", "z2") else float(v)
                               for k, v in given.items()})
    if args.widths:
        print(raw_table(params, args.size, args.gear) if args.raw or args.gear == 2
              else twist_table(params, args.size))
        return
    if args.gear == 2:
        parser.error("--gear 2 is measured with --widths (its 2D parts are not gear 1's)")
    band = band_compliance(params, quality="standard")
    solid = face_influence(params, thickness=args.width, patches=args.patches, size=args.size)
    print(table(solid, band))


if __name__ == "__main__":
    main()
