"""A job's tolerance class (``--grade`` and the inputs beside it: docs/tolerance.md): which
pairs are drawn, in the plane or across the face, their inputs checked and refused by name
(:func:`class_draw`)."""

from __future__ import annotations

from collections.abc import Mapping

from ..errors import ParameterError
from ..tolerance import Draw, grade_of
from .case import SolveCase
from .inputs import FACE_INPUTS, JOB_INPUTS, REQUIRES, check_band


def class_draw(v: dict, given: Mapping[str, object], case: SolveCase) -> Draw | None:
    """The tolerance class's pairs to solve (``--grade``), refused by name with deviations
    given (the class draws them); across the face (any of :data:`~.inputs.FACE_INPUTS`
    given) each pair's helix drawn too, at the face width, and its misalignment about the
    one given within ``--misalignment-band`` (:func:`~.inputs.check_band`), over a cycle's
    positions or a whole turn; None without a class. ``v``: every input by name at its value
    or default; ``given``: those given."""
    grade = v["grade"]
    if grade is None:
        for name in (name for name, switch in REQUIRES.items() if switch == "grade"):
            if given.get(name) is not None:
                JOB_INPUTS[name].check(given[name])   # its value first, then whether read
                raise ParameterError(name, given[name], "with --grade only (the pairs of a "
                                     "tolerance class are drawn only where it is given)")
        return None
    grade = JOB_INPUTS["grade"].check(grade)
    if case.deviations:
        raise ParameterError("grade", grade, "without deviations given (the class draws each "
                             "pair's deviations)")
    across = any(v[row.name] is not None for row in FACE_INPUTS)
    misalignment = v["misalignment"] or 0.0
    band = check_band(v["misalignment-band"], misalignment, across)
    return Draw(grade_of(grade, case.params, v["centre-distance-tolerance"],
                         case.thickness if across else None),
                JOB_INPUTS["samples"].check(v["samples"]),
                JOB_INPUTS["seed"].check(v["seed"]), misalignment, band)
