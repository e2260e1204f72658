"""Contact kernels of the product: what the ring model's contact solve
(:mod:`fegear.toothpair.ring.contact`) is built on. The contact solve itself lives with the
ring model; the penalty contact the peers solve with (the Hertz case, the sector model,
CalculiX's decks) is :mod:`fegear.verify.penalty`.

* :mod:`.halfplane`: the elastic half-plane under a piecewise-linear pressure (Flamant, plane
  stress), in closed form: the near field of a contact that the finite elements need not
  resolve (how far a surface point approaches the point at a depth below it, the tangential
  strain there), and the line contact of two half-planes on any gap.
* :mod:`.search`: which quadratic facet of a mesh lies under a point, and where on it
  (:class:`FacetLocator`: the nearest chord, then Newton on the facet curve), with the P2
  shape functions along a facet.
* :mod:`.curves`: the closest points on an exact curve (:class:`CurvePoints`), which a gap to
  gear 2 is measured to.

Hertz's line contact from the half-plane alone: the Hertz case's two 10 mm disks, 1000 N over
5 mm, their gap the parabola s²/(2R*) on a grid of 16 points per Hertz half-width:

>>> import numpy as np
>>> from fegear.contact import FacetLocator, gap_contact, p2_edge_shape
>>> from fegear.fe import BodyGeometry, Segment, facet_nodes, line_contact, mesh_bodies
>>> hertz = line_contact(10.0, 10.0, 1000.0, 5.0)
>>> s = np.linspace(-2.0, 2.0, 65) * hertz.b
>>> p = gap_contact(s, s * s / (2.0 * hertz.R_star), hertz.q, hertz.E_star)  # MPa
>>> round(float(p.max()), 1), round(hertz.p0, 1)
(1145.5, 1145.2)
>>> on = s[p > 0]
>>> round(float(on.max() - on.min()) / 2, 4), round(hertz.b, 4)   # half-width, mm
(0.1112, 0.1112)

The facet of a meshed plate's top under a point just above it, and the point on that facet:

>>> corners = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 1.0], [0.0, 1.0]])
>>> names = ("bottom", "right", "top", "left")
>>> plate = BodyGeometry("plate", tuple(Segment(name, corners[[i, (i + 1) % 4]])
...                                     for i, name in enumerate(names)), size=0.5)
>>> (mesh,) = mesh_bodies([plate])
>>> facet, at = FacetLocator(mesh.mesh, mesh.mesh.boundaries["top"]).locate([[1.3, 1.02]])
>>> nodes = mesh.mesh.doflocs.T[facet_nodes(mesh.mesh, facet)[0]]   # corners, midside
>>> (p2_edge_shape(at)[0] @ nodes).round(6)
array([1.3, 1. ])
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "curves": ("CurvePoints", "ExactCurve"),
    "search": ("locate_on_facets", "FacetLocator", "p2_edge_shape", "facet_curve",
               "ordered_boundary"),
    "halfplane": ("approach_matrix", "hat_columns", "strain_matrix", "surface_matrix",
                  "gap_contact"),
})
