"""FE stage: plane bodies meshed, assembled, supported, factorised, and their stresses.

TODO walkthrough
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "mesh": ("Segment", "Refinement", "BodyGeometry", "BodyMesh", "MeshQuality", "MeshError",
             "mesh_bodies", "mesh_quality", "jiggle"),
    "material": ("Material", "plane_modulus", "contact_modulus"),
    "assembly": ("Body", "RigidLink", "Placement", "SupportError", "assemble_body"),
    "dofs": ("node_dofs", "facet_nodes"),
    "flexibility": ("WindowFlexibility",),
    "stress": ("StressField", "recover"),
    "hertz": ("HertzLine", "line_contact"),
    "vtu": ("vtu_fields", "write_vtu"),
})
