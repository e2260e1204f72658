"""The ring solver's modes (:mod:`fegear.toothpair.ring.modes`): what they refuse, and where
the submodels are solved in effect."""

from dataclasses import replace

import pytest

from fegear.toothpair.ring import SolverModes


def test_the_solver_modes_refuse_what_they_cannot_do():
    with pytest.raises(ValueError, match="submodels must be one of"):
        SolverModes(submodels="some")
    with pytest.raises(ValueError, match="not both"):
        SolverModes(contact_only=True, roots_only=True)
    with pytest.raises(ValueError, match="keep_phases"):
        SolverModes(read_kept=True)
    # no von Mises stress read, no submodel solved for it
    assert SolverModes(contact_only=True).solved_submodels == "none"
    assert replace(SolverModes(roots_only=True), roots_only=False).solved_submodels == "peaks"
