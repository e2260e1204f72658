"""The CalculiX deck of the extruded pair (:mod:`fegear.verify.calculix_face`): two bodies of
C3D15 wedges (:mod:`fegear.verify.ccx_face_mesh`), supports, contact per tooth and face layer,
and the torque in one load step.

* **Material.** Each body's E and ν as they are: a 3D body, neither plane stress nor strain.
* **Supports.** Gear 2's rim (every node on it, across the face) held in x, y and z. Gear 1's
  bore tied to a reference node whose dof 1 is the rotation θ about gear 1's axis, as the 2D
  peer ties it (:mod:`fegear.verify.calculix`): per bore node u_x + (y − c_y)θ = 0,
  u_y − (x − c_x)θ = 0, with (x − c_x, y − c_y) the node's lever from the axis at its own ζ
  (the misaligned gear 1 is sheared with its axis). The bore is held axially (u_z = 0), the
  only axial support gear 1 needs: nothing else holds it along z. Both ends of the face free.
* **Contact.** Per paired gear-1 tooth and face layer a slave surface (that layer's faces of
  the tooth's window) against gear 2's whole window boundary, so that CalculiX's contact force
  per pair (``CF``) is the tooth's load on that layer: the line load without reading nodal
  forces. Face to face, linear penalty K = ``penalty_factor``·E*/h̄ per tooth (h̄ the mean
  in-plane slave facet length, E* of the 3D moduli E/(1 − ν²)), ccx_pair's factor 30.
* **Steps.** Gear 1 is written turned by the 2D solution's rotation; step 1 holds θ there
  (CalculiX resolves the overclosure, or the misalignment's), step 2 releases θ and applies
  the torque with the 2D peer's tight controls (``CONTROLS``).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .calculix import CONTROLS, FIELD
from .ccx_face_mesh import Extruded
from .ccx_files import PeerError, save_deck


@dataclass(frozen=True)
class FaceDeck:
    """A written deck: its ``path``; ``nodes`` and ``elements`` (both bodies, the reference
    node not counted); the reference node ``ref``; per deck contact pair its gear-1 ``tooth``
    and face ``layer``; ``penalty`` K per tooth (MPa/mm); the bore equations written."""

    path: Path
    nodes: int
    elements: int
    ref: int
    tooth: tuple[int, ...]
    layer: tuple[int, ...]
    penalty: dict[int, float]
    equations: int

    @property
    def dofs(self) -> int:
        return 3 * self.nodes


@dataclass(frozen=True)
class FaceBodies:
    """What the deck is written from: the extruded gears, gear 1's axis ``centre`` (fixed
    frame, mm, at ζ = 0) and the misalignment ``shear`` (mm at ζ = 1, as extruded); the
    boundary names of gear 1's bore and gear 2's rim; per paired tooth gear 1's slave window
    and gear 2's master boundary; E (MPa) and ν."""

    gear1: Extruded
    gear2: Extruded
    centre: tuple[float, float]
    shear: tuple[float, float]
    bore: str
    rim: str
    windows: dict[int, str]
    master: str
    E: float
    nu: float


def write_face_deck(bodies: FaceBodies, torque: float, directory, jobname: str,
                    penalty_factor: float) -> FaceDeck:
    """Write ``<directory>/<jobname>.inp`` for ``bodies`` under ``torque`` (N·mm on gear 1);
    see the module docstring."""
    g1, g2 = bodies.gear1, bodies.gear2
    n1, e1 = len(g1.nodes), len(g1.elements)
    ref = n1 + len(g2.nodes) + 1
    lines = ["*HEADING", f"fegear 3D pair: {g1.layers} layers, torque {_num(torque)} N mm",
             "*NODE, NSET=NALL"]
    lines += [f"{k + 1}, {_num(x)}, {_num(y)}, {_num(z)}" for k, (x, y, z)
              in enumerate(np.concatenate([g1.nodes, g2.nodes]))]
    lines += [f"{ref}, {_num(bodies.centre[0])}, {_num(bodies.centre[1])}, 0"]
    for i, (body, n0, e0) in enumerate(((g1, 0, 0), (g2, n1, e1))):
        lines.append(f"*ELEMENT, TYPE=C3D15, ELSET=BODY{i + 1}")
        for e, row in enumerate(body.elements + n0 + 1):
            ids = [str(e0 + e + 1)] + [str(v) for v in row]
            lines += [", ".join(ids[:11]) + ",", ", ".join(ids[11:])]
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{_num(bodies.E)}, {_num(bodies.nu)}",
              "*SOLID SECTION, ELSET=BODY1, MATERIAL=STEEL",
              "*SOLID SECTION, ELSET=BODY2, MATERIAL=STEEL"]
    bore = g1.boundary_nodes(bodies.bore) + 1
    lines += _nset("FIXED", g2.boundary_nodes(bodies.rim) + n1 + 1) + _nset("BORE", bore)
    lines += _nset("REF", [ref])
    equations, count = _bore_equations(g1, bore - 1, bodies, ref)
    lines += equations
    contact, tooth, layer, penalty = _contact_cards(bodies, e1, penalty_factor)
    lines += contact
    lines += _step_cards(torque, [f"S{t}L{k}" for t, k in zip(tooth, layer)])
    path = save_deck(directory, jobname, lines)
    return FaceDeck(path, ref - 1, e1 + len(g2.elements), ref, tuple(tooth), tuple(layer),
                    penalty, count)


def _bore_equations(g1: Extruded, bore: np.ndarray, bodies: FaceBodies,
                    ref: int) -> tuple[list[str], int]:
    """u_x + (y − c_y)θ = 0 and u_y − (x − c_x)θ = 0 per bore node, levers from the axis at
    the node's own ζ."""
    x = g1.nodes[bore]
    lever = x[:, :2] - np.asarray(bodies.centre) - np.outer(x[:, 2] / g1.width, bodies.shear)
    if np.any(np.hypot(lever[:, 0], lever[:, 1]) < 1e-6):
        raise PeerError("a bore node lies on gear 1's axis")
    lines, count = ["*EQUATION"], 0
    for n, (dx, dy) in zip(bore + 1, lever):
        for dof, arm in ((1, dy), (2, -dx)):
            if abs(arm) < 1e-9:   # an equation needs a nonzero second term: no lever, no θ
                continue
            lines += ["2", f"{n}, {dof}, 1., {ref}, 1, {_num(arm)}"]
            count += 1
    return lines, count


def _contact_cards(bodies: FaceBodies, e1: int, penalty_factor: float):
    """The master surface, one interaction per tooth, one slave surface and contact pair per
    tooth and layer; (cards, tooth and layer per pair, K per tooth)."""
    g1, g2 = bodies.gear1, bodies.gear2
    E3 = bodies.E / (1.0 - bodies.nu ** 2)
    modulus = 0.5 * E3          # E* of two equal bodies
    lines = ["*SURFACE, NAME=MASTER, TYPE=ELEMENT"]
    for k in range(g2.layers):
        elem, face = g2.faces(bodies.master, k)
        lines += [f"{e1 + e + 1}, S{f}" for e, f in zip(elem, face)]
    tooth, layer, penalty = [], [], {}
    for t, window in bodies.windows.items():
        facets = g1.boundary(window)
        ends = g1.mesh.doflocs.T[g1.mesh.facets[:, facets]]
        h = float(np.linalg.norm(ends[1] - ends[0], axis=1).mean())
        penalty[t] = penalty_factor * modulus / h
        lines += [f"*SURFACE INTERACTION, NAME=PENALTY{t}",
                  "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", _num(penalty[t])]
        for k in range(g1.layers):
            name = f"S{t}L{k}"
            elem, face = g1.faces(window, k)
            lines.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
            lines += [f"{e + 1}, S{f}" for e, f in zip(elem, face)]
            lines += [f"*CONTACT PAIR, INTERACTION=PENALTY{t}, TYPE=SURFACE TO SURFACE",
                      f"{name}, MASTER"]
            tooth.append(t)
            layer.append(k)
    return lines, tooth, layer, penalty


def _step_cards(torque: float, slaves: list[str]) -> list[str]:
    supports = ["FIXED, 1, 3", "BORE, 3, 3"]
    lines = ["*BOUNDARY", *supports,
             "*STEP", "*STATIC", "1., 1.", "*BOUNDARY", "REF, 1, 1, 0", "*END STEP",
             "*STEP, INC=1000", "*STATIC", "1., 1., 1e-5, 1.", *CONTROLS,
             "*BOUNDARY, OP=NEW", *supports, "*CLOAD", f"REF, 1, {_num(torque)}",
             "*NODE PRINT, NSET=REF", "U"]
    for name in slaves:
        lines += [f"*CONTACT PRINT, SLAVE={name}, MASTER=MASTER", "CF"]
    return lines + ["*NODE FILE", "U", "*EL FILE", "S", "*END STEP"]


def _nset(name: str, nodes) -> list[str]:
    items = [str(int(n)) for n in nodes]
    return [f"*NSET, NSET={name}"] + [", ".join(items[k:k + 8]) + ","
                                      for k in range(0, len(items), 8)]


def _num(x: float) -> str:
    s = f"{float(x):.13g}"
    if len(s) > FIELD or not np.isfinite(float(x)):
        raise PeerError(f"number {x!r} does not fit CalculiX's {FIELD}-character field")
    return s
