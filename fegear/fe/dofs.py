"""Dof numbering of P2 vector fields on a ``MeshTri2``: node k carries dofs 2k (x) and 2k+1 (y);
a facet's nodes are its two corners, then its midside node (numbered after the corners)."""

from __future__ import annotations

import numpy as np


def node_dofs(nodes: np.ndarray) -> np.ndarray:
    """(n, 2) dofs (x, y) of nodes: node k ↔ dofs 2k, 2k+1 (checked in :func:`assemble_body`)."""
    nodes = np.asarray(nodes)
    return np.stack([2 * nodes, 2 * nodes + 1], axis=-1)


def facet_nodes(mesh, facets: np.ndarray) -> np.ndarray:
    """(n, 3) node indices of facets of a MeshTri2: first corner, second corner, midside."""
    facets = np.asarray(facets)
    return np.column_stack([mesh.facets[0, facets], mesh.facets[1, facets],
                            mesh.nvertices + facets])
