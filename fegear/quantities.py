"""The results' one vocabulary: each quantity fegear reports, under the key the JSON summary
gives it, with its symbol, its labels, its unit, the tooth's field it is read from and the
allowable it is held against, and each safety factor.

The summary, the printed tables, the report page, the pictures, the sensitivities, a study's
table and the design search name a quantity through here, so no two places name one
differently: a table heads its column with the ``short`` label, a picture or a page with the
``label``. The keys are the summary's, which users' scripts and studies read; they do not
change.

>>> from fegear.quantities import FACTORS, HEADLINES, QUANTITIES
>>> root = QUANTITIES["root_stress_gear1_MPa"]
>>> root.label, root.short, root.unit
('root σ1, gear 1', 'σ1 g1', 'MPa')
>>> root.attribute, root.allowable, root.safety    # a ToothResult's field; held against σ_FP
('root1_MPa', 'bending', 'safety_bending_gear1')
>>> [q.short for q in HEADLINES]                   # the summary's headline stresses
['σ1 g1', 'σ1 g2', 'p_max', 'p flank', 'vM max']
>>> s_h = FACTORS["safety_contact_flank"]          # allowable / stress
>>> s_h.label, s_h.stress.label, s_h.stress.tooth_key
('S_H flank', 'flank pressure', 'flank_pressure_MPa')
>>> [f.name for f in FACTORS.values()]             # as a search's trials name them
['S_F1', 'S_F2', 'S_H', 'S_H_flank']
"""

from __future__ import annotations

from dataclasses import dataclass

#: the allowables a stress can be held against (:class:`fegear.fe.Allowables`' fields)
KINDS = ("bending", "contact")


@dataclass(frozen=True)
class Quantity:
    """One reported quantity. ``key``: the summary's (with its unit, ``root_stress_gear1_MPa``;
    a cycle's rows and a study's columns use it too); ``symbol`` (``σ_F1``); ``short``: a
    table's head (``σ1 g1``); ``label``: a picture's or a page's (``root σ1, gear 1``);
    ``unit``; ``attribute``: a :class:`~fegear.toothpair.ToothResult`'s field it is read
    from, per tooth (None: the pair's alone); ``tooth_key``: the summary's name of it in a
    tooth's entry (``teeth``); ``allowable``: what it is held against ("bending": σ_FP,
    "contact": σ_HP; None: nothing) and ``safety`` the summary's key of that safety factor;
    ``gear``: the gear whose teeth carry it, by whose numbers a tooth is named (None: the
    pair's)."""

    key: str
    symbol: str
    short: str
    label: str
    unit: str
    attribute: str | None = None
    tooth_key: str | None = None
    allowable: str | None = None
    safety: str | None = None
    gear: int | None = None

    def __post_init__(self) -> None:
        if self.allowable not in (None, *KINDS):
            raise ValueError(f"{self.key}: allowable {self.allowable!r} is none of {KINDS}")
        if (self.allowable is None) != (self.safety is None):
            raise ValueError(f"{self.key}: a safety factor needs an allowable and one only")

    @property
    def head(self) -> str:
        """The short label with its unit, as a table's head: ``p_max MPa``, ``edge N``."""
        return f"{self.short} {self.unit}"

    @property
    def axis(self) -> str:
        """The label with its unit, as a picture's axis: ``root σ1, gear 1 [MPa]``."""
        return f"{self.label} [{self.unit}]"


@dataclass(frozen=True)
class Factor:
    """A safety factor, the allowable over the stress ``stress`` (:class:`Quantity`):
    ``key`` the summary's (``safety_bending_gear1``), ``symbol`` a table's head (``S_F1``),
    ``label`` a picture's or a page's (``S_F gear 1``)."""

    key: str
    symbol: str
    label: str
    stress: Quantity

    def __post_init__(self) -> None:
        if self.stress.safety != self.key:
            raise ValueError(f"{self.key} divides {self.stress.key}, whose factor is "
                             f"{self.stress.safety}")

    @property
    def name(self) -> str:
        """The symbol as a name (``S_H_flank``): a design search's trials' columns."""
        return self.symbol.replace(" ", "_")


ROOT1 = Quantity("root_stress_gear1_MPa", "σ_F1", "σ1 g1", "root σ1, gear 1", "MPa",
                 attribute="root1_MPa", tooth_key="root_stress_gear1_MPa",
                 allowable="bending", safety="safety_bending_gear1", gear=1)
ROOT2 = Quantity("root_stress_gear2_MPa", "σ_F2", "σ1 g2", "root σ1, gear 2", "MPa",
                 attribute="root2_MPa", tooth_key="root_stress_gear2_MPa",
                 allowable="bending", safety="safety_bending_gear2", gear=2)
#: the largest contact pressure wherever it sits, on a flank or on gear 1's tip round
PEAK = Quantity("contact_pressure_MPa", "p_max", "p_max", "contact pressure, peak", "MPa",
                attribute="p_max_MPa", tooth_key="p_max_MPa",
                allowable="contact", safety="safety_contact", gear=1)
#: the flanks' own pressure, the tip rounds' left out
FLANK = Quantity("flank_contact_pressure_MPa", "p_flank", "p flank", "flank pressure", "MPa",
                 attribute="flank_p_MPa", tooth_key="flank_pressure_MPa",
                 allowable="contact", safety="safety_contact_flank", gear=1)
VON_MISES = Quantity("von_mises_max_MPa", "σ_vM", "vM max", "von Mises max", "MPa")
#: the pressure on gear 1's tip round (edge contact) and the load the rounds carry
EDGE_PRESSURE = Quantity("edge_pressure_MPa", "p_edge", "p edge",
                         "pressure on gear 1's tip round", "MPa", attribute="edge_p_MPa",
                         tooth_key="edge_pressure_MPa", gear=1)
EDGE_LOAD = Quantity("edge_load_N", "F_edge", "edge", "load on gear 1's tip rounds", "N",
                     attribute="edge_load_N", tooth_key="edge_load_N", gear=1)
#: gear 1's elastic rotation θ − θ_touch under the load
TRANSMISSION_ERROR = Quantity("transmission_error_urad", "TE", "TE", "transmission error",
                              "µrad")
MESH_STIFFNESS = Quantity("mesh_stiffness_Nm_per_rad", "k", "k", "mesh stiffness", "N·m/rad")

#: every quantity, by its summary key
QUANTITIES = {q.key: q for q in (ROOT1, ROOT2, PEAK, FLANK, VON_MISES, EDGE_PRESSURE,
                                 EDGE_LOAD, TRANSMISSION_ERROR, MESH_STIFFNESS)}
#: the headline stresses: a solution's :meth:`~fegear.toothpair.PairSolution.headline`, in
#: the summary's order
HEADLINES = (ROOT1, ROOT2, PEAK, FLANK, VON_MISES)
#: the headline stresses held against an allowable, a safety factor each
HELD = tuple(q for q in HEADLINES if q.allowable)
#: the safety factors, by summary key, in the summary's order
FACTORS = {f.key: f for f in (Factor("safety_bending_gear1", "S_F1", "S_F gear 1", ROOT1),
                              Factor("safety_bending_gear2", "S_F2", "S_F gear 2", ROOT2),
                              Factor("safety_contact", "S_H", "S_H", PEAK),
                              Factor("safety_contact_flank", "S_H flank", "S_H flank", FLANK))}
#: a rated level's stresses by tooth (the summary's ``rating.levels``, each key with ``_MPa``):
#: each gear's teeth's root stress and flank pressure (the tip rounds' left out, as the life
#: lines were measured), by key → (quantity, the gear whose teeth)
LEVEL_STRESSES = {"root1": (ROOT1, 1), "root2": (ROOT2, 2), "flank1": (FLANK, 1),
                  "flank2": (FLANK, 2)}
