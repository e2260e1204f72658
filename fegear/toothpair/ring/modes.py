"""What a ring solver gives beyond a position's contact and what it keeps between positions
(:class:`SolverModes`), the modes of :class:`~.solver.RingSolver`."""

from __future__ import annotations

from dataclasses import dataclass

#: where the contact submodels are solved: at every position, only where a cycle's von Mises
#: peak is (and where any other headline stress peaks), or nowhere
SUBMODELS = ("all", "peaks", "none")


@dataclass(frozen=True)
class SolverModes:
    """What a :class:`~.solver.RingSolver` gives beyond a position's contact and what it
    keeps between positions; the defaults give a position whole (:data:`WHOLE`). Variants by
    :func:`dataclasses.replace`.

    ``submodels``: where the contact submodels are solved (:data:`SUBMODELS`,
    :meth:`~.solver.RingSolver.at_peaks`): "peaks" where a cycle's headline stresses peak,
    "all" at every position, "none" nowhere; without one, the von Mises stress at a contact
    is the template's surface estimate (:func:`~.stresses.ring_stresses`) and all else the
    same: for a caller that reads the estimate or no von Mises stress (a class's samples).
    ``contact_only``: no stresses at all, for a caller that reads only the contact (loads,
    shares, pressures, flank and edge apart, rotations: the tip-relief search), which then
    skips their projection and readout; the root and von Mises stresses NaN, the teeth's Hertz
    values and half-plane references None.
    ``roots_only``: the contact and the root stresses read without fields
    (:func:`~.readout.brief_stresses`), as a sample's are, for a caller that reads those alone
    (a load spectrum's levels); the von Mises stress and the tangent stiffness NaN. Not with
    ``contact_only``.
    ``keep_phases``: each position's contact kept for its phase and the positions whole gear-2
    pitches on solved on it (:mod:`.phases`), for positions that repeat over whole pitches (a
    revolution) or one position solved for many deviation sets (a class's samples:
    :meth:`~.solver.RingSolver.on_kept`): a contact solve each instead of a placement. The
    kept grids reach as far beyond the exact pair's as the deviations there, or the sets to be
    solved on them (:meth:`~.solver.RingSolver.reach`), need; a lighter torque is solved on
    the contacts kept at the heaviest, with its own solutions repeated over the pitches
    (:meth:`~.solver.RingSolver.again`).
    ``read_kept`` (with ``keep_phases``): a position solved on its phase's kept contact has its
    stresses read as a sample's are (:func:`~.readout.brief_stresses`: the root zones and the
    surface estimate, the same headline stresses), without the fields, the equilibrium
    residuals, the submodels or its teeth's half-plane references; the position pictured and
    the cycle's peaks get them (:meth:`~.solver.RingSolver.with_pictured`,
    :meth:`~.solver.RingSolver.at_peaks`): for a revolution, of whose thousand positions the
    others are read for their headlines, shares, rotations and stiffness alone."""

    submodels: str = "peaks"
    contact_only: bool = False
    roots_only: bool = False
    keep_phases: bool = False
    read_kept: bool = False

    def __post_init__(self) -> None:
        if self.submodels not in SUBMODELS:
            raise ValueError(f"submodels must be one of {SUBMODELS}, not {self.submodels!r}")
        if self.contact_only and self.roots_only:
            raise ValueError("contact_only reads no stresses, roots_only the roots': not both")
        if self.read_kept and not self.keep_phases:
            raise ValueError("read_kept reads the positions on kept contacts: keep_phases too")

    @property
    def solved_submodels(self) -> str:
        """Where the submodels are solved in effect: ``submodels``, or "none" where no von
        Mises stress is read (``contact_only``, ``roots_only``)."""
        return "none" if self.contact_only or self.roots_only else self.submodels


#: the defaults: a position whole
WHOLE = SolverModes()
