"""Loaded at start-up by every Python process whose PYTHONPATH holds this folder: the study
tests' solves and workers. It makes one admissible case fail inside its solve (10 N·m at
β = 1.5°), as no admissible design does any more, so that the runner's handling of a failed
case stays tested; and a case at 7 N·m never finishes (its solve waits), so that a study can be
stopped before its first case has finished."""

import math
import time

from fegear.errors import GeometryError
from fegear.toothpair.ring.solver import RingSolver

_attempt = RingSolver.attempt


def attempt(self, case, state, trial, near):
    if case.torque == 10.0 and abs(case.beta - math.radians(1.5)) < 1e-12:
        raise GeometryError("injected by the study tests: a solve that fails")
    if case.torque == 7.0:
        time.sleep(600)   # the worker is stopped long before
    return _attempt(self, case, state, trial, near)


RingSolver.attempt = attempt
