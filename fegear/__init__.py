"""fegear: finite-element stress solver for compound-cycloid internal gear tooth pairs.

The pipeline, one subpackage per stage (docs/architecture.md):

* :mod:`fegear.geometry`: exact profiles, admissibility, unloaded contact, tip edges;
* :mod:`fegear.fe`: meshes, plane elasticity, stresses, Hertz;
* :mod:`fegear.contact`: the contact kernels of the product (the half-plane, the facet
  search, exact curves' closest points);
* :mod:`fegear.toothpair`: the tooth-pair solve, its error estimate and reports;
* :mod:`fegear.study`: parameter studies;
* :mod:`fegear.verify` and :mod:`fegear.drive` beside them: the Hertz case, the benchmark and
  CalculiX; the drive level;
* :mod:`fegear.cli`: the ``fegear`` command; :mod:`fegear.api`: the same solve from Python
  (:func:`solve`, :func:`cycle`, :func:`revolution`; docs/python.md).
"""

from .exports import lazy

__version__ = "0.1.0"

__getattr__, __dir__, __all__ = lazy(__name__, {
    "geometry": ("PairParameters", "Gear1Profile", "ToothContact", "PairGeometry",
                 "build_geometry"),
    "toothpair": ("SolveCase", "solve_pair", "solve_positions"),
    "errors": ("FegearError", "GeometryError", "ParameterError"),
    "api": ("solve", "cycle", "revolution", "Result"),
})
__all__ = [*__all__, "__version__"]
