"""Tolerance classes: the deviations an ISO 1328-1 class admits, drawn as Monte-Carlo gear
pairs, and the statistics of what the pairs carry (docs/tolerance.md).

>>> from fegear.geometry import PairParameters
>>> from fegear.tolerance import grade_of, sample_pair
>>> grade = grade_of(6, PairParameters(m=2.0, z2=45, z1=44, h1=0.3, f1=0.15))
>>> grade.gear1.f_pT, grade.gear1.F_pT, grade.gear1.F_rT       # µm, d1 = 88 mm
(8.5, 26.0, 24.0)
>>> pair = sample_pair(grade, seed=0, k=7)                       # the same pair in every run
>>> abs(pair.teeth(1)[3].pitch) <= grade.gear1.F_pT
True
"""

from .iso1328 import (
    CLASSES,
    ClassTolerances,
    HelixTolerances,
    check_grade,
    class_tolerances,
    helix_class,
    rounded,
)
from .sampling import (
    SIGMAS,
    Draw,
    FaceSample,
    Grade,
    grade_of,
    sample_face,
    sample_pair,
    tooth_positions,
)
from .stats import QUANTILES, Quantile, quantiles

__all__ = ["CLASSES", "QUANTILES", "SIGMAS", "ClassTolerances", "Draw", "FaceSample", "Grade",
           "HelixTolerances", "Quantile", "check_grade", "class_tolerances", "grade_of",
           "helix_class", "quantiles", "rounded", "sample_face", "sample_pair",
           "tooth_positions"]
