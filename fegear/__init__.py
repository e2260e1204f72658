"""fegear: finite-element stress solver for compound-cycloid internal gear tooth pairs.

Pipeline stages, one module each: params → cycloid (gear 2) → envelope/profile (gear 1) →
admissible → tca (unloaded contact) → pair (the geometry stage as one call) → output/plot.
"""

from .errors import FegearError, GeometryError, ParameterError
from .pair import PairGeometry, build_pair
from .params import PairParameters
from .profile import Gear1Profile
from .tca import ToothContact

__version__ = "0.1.0"

__all__ = ["FegearError", "GeometryError", "ParameterError", "PairParameters", "Gear1Profile",
           "ToothContact", "PairGeometry", "build_pair", "__version__"]
