"""FE stage: plane bodies meshed, assembled, supported, factorised, and their stresses.

A body is a closed loop of named :class:`Segment` s along exact curves (:mod:`.mesh`, the only
module that imports gmsh), meshed with quadratic triangles and its boundary nodes snapped onto
the curves. :func:`assemble_body` builds the P2 plane-elasticity stiffness (:mod:`.material`:
plane stress or strain), holds its fixed boundaries, ties at most one boundary to a rigid
rotation or translation (:class:`RigidLink`) and factorises the free block once; every later
solve (contact condensation, load steps, positions) reuses that factor. :func:`recover`
projects the stresses onto the nodes; :func:`line_contact` is Hertz. Nothing here knows gears.

A bar 20 × 2 mm, its left end held, its right end pulled along x by one translation unknown:

>>> import numpy as np
>>> from fegear.fe import (BodyGeometry, ElasticMaterial, RigidLink, Segment, assemble_body,
...                        line_contact, mesh_bodies, recover)
>>> corners = np.array([[0.0, 0.0], [20.0, 0.0], [20.0, 2.0], [0.0, 2.0]])
>>> names = ("bottom", "end", "top", "wall")
>>> bar = BodyGeometry("bar", tuple(Segment(name, corners[[i, (i + 1) % 4]])
...                                 for i, name in enumerate(names)), size=0.5)
>>> (mesh,) = mesh_bodies([bar])
>>> body = assemble_body(mesh, ElasticMaterial(thickness=1.0), fixed=("wall",),
...                      link=RigidLink("end", "translation", direction=(1.0, 0.0)))
>>> round(body.link_stiffness / (206000.0 * 2.0 / 20.0), 3)  # k against E A / L (N/mm)
1.002
>>> stress = recover(body, body.psi)         # the end moved by 1 mm
>>> centre = np.argmin(np.linalg.norm(mesh.mesh.doflocs.T - [10.0, 1.0], axis=1))
>>> round(float(stress.sxx[centre]) / (206000.0 / 20.0), 3)  # σxx against E/L
1.002
>>> hertz = line_contact(10.0, 10.0, 1000.0, 5.0)  # two 10 mm disks, 1000 N over 5 mm
>>> round(hertz.p0, 1), round(hertz.b, 4), round(hertz.b_over_R, 4)
(1145.2, 0.1112, 0.0222)
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "mesh": ("Segment", "Refinement", "Periodic", "BodyGeometry", "BodyMesh", "MeshQuality",
             "MeshError", "mesh_bodies", "mesh_quality", "jiggle", "halved", "Circle",
             "write_step"),
    "libraries": ("import_libraries", "keep_freed_memory"),
    "material": ("ElasticMaterial", "MATERIAL_INPUTS", "ALLOWABLE_INPUTS", "Allowables",
                 "plane_modulus", "contact_modulus", "Plane", "PLANE_MODES", "STEEL_E",
                 "STEEL_NU"),
    "assembly": ("Body", "RigidLink", "BodyPlacement", "SupportError", "assemble_body"),
    "dofs": ("node_dofs", "facet_nodes"),
    "flexibility": ("WindowFlexibility",),
    "stress": ("StressField", "recover", "recover_many", "projection_matrices", "projector",
               "stress_field"),
    "hertz": ("HertzLine", "line_contact"),
    "vtu": ("FIELD_DTYPE", "vtu_fields", "write_vtu", "written_name"),
    "solvers": ("Factor", "SingularError", "BLAS_THREADS", "blas_threads"),
    "cyclic": ("CyclicBody", "assemble_cyclic", "cyclic_parts", "restore_cyclic"),
    "probe": ("Probe", "Cells"),
    "submodel": ("StarCurve", "Submodel", "SubmodelProblem", "SubmodelMesh", "solve_submodels",
                 "submodel_meshes", "prepare_submodels"),
})
