"""The ring model of a pair for one geometry, material and quality: both gears whole, each from
one template sector meshed, assembled, factorised and condensed once; reused for every torque
and rolling position.

Quality levels set the template's element sizes (fractions of the module for the root zones,
flanks and body; of the tip round for the round and its tangent points), the contact grid's
density (points per local Hertz half-width), the matching depth of the contact's finite-element
part (in local profile facets) and the submodel's element size at a contact peak (per local
Hertz half-width). Each level halves the sizes of the one before.
"""

from __future__ import annotations

import itertools
import weakref
from collections import OrderedDict
from dataclasses import dataclass, field, replace

from ... import provenance
from ...fe import (
    ElasticMaterial,
    assemble_cyclic,
    cyclic_parts,
    mesh_bodies,
    restore_cyclic,
    submodel_meshes,
)
from ...geometry import Gear1Profile, PairParameters, RoundedProfile, gear1_profile, gear2_curve
from ...timing import timed
from ..case import SolveCase
from . import cache
from .grid import ToothSamples, sample_tooth
from .side import GearSide
from .template import Template, TemplateSizes, gear1_template, gear2_template


@dataclass(frozen=True)
class RingLevel:
    """A quality level: template sizes as fractions of the module (root, flank, body) and of
    the tip round (round, junction); contact grid points per local Hertz half-width; matching
    depth in local profile facets; submodel elements per local Hertz half-width at a contact
    peak."""

    root: float
    flank: float
    round: float
    junction: float
    body: float
    per_b: float
    depth: float
    sub_per_b: float


# the submodels need about 12 elements per half-width at an edge contact whatever the level
# (6 left the baseline's von Mises 0.5 % noisy); the matching depth of 4 facets sits between
# the shallow depths where the templates are not yet accurate under the hats' loads and the
# deep ones where the half-plane stops describing a round: the baseline's peak pressure moves
# by ±0.3 % between 3 and 5 facets, and falls 1 % by 8 (docs/model.md, "The ring model")
LEVELS = {"coarse": RingLevel(1 / 10, 1 / 20, 1 / 8, 1 / 32, 1 / 2, 8, 4.0, 12),
          "fast": RingLevel(1 / 14, 1 / 28, 1 / 12, 1 / 48, 1 / 3, 12, 4.0, 12),
          "standard": RingLevel(1 / 20, 1 / 40, 1 / 16, 1 / 64, 1 / 4, 16, 4.0, 16),
          "fine": RingLevel(1 / 40, 1 / 80, 1 / 32, 1 / 128, 1 / 8, 32, 4.0, 32)}
ROUND_FLOOR = 0.05       # template sizes at the tip use a round of at least this many modules
THIN = 0.1               # a tip relief or tip trim thinner than this many flank elements is
                         # left to the contact's exact geometry: the templates are meshed
                         # without it (a relief search's trials then share one model)
GROWN = 1.25            # a model is kept in the model cache again once it holds this many
                        # times the responses of its entry (or new submodels)
#: the case fields a ring model depends on (not torque, position or the sector model's inputs)
GEOMETRY_KEYS = ("params", "thickness", "E", "nu", "quality", "rim1", "rim2", "tip_round")


@dataclass(eq=False)
class RingModel:
    """Both gears of a pair as rings of template sectors (any torque, any rolling position):
    the case it was built for, gear 1's exact and rounded profiles, tooth 0 sampled, gear 2's
    curve, the two :class:`GearSide` s, the level and the contact submodels prepared so far
    (:func:`~fegear.fe.solve_submodels`).

    A model is too big to copy: pickled, it is a reference to the model it is in the process
    that unpickles it (the solutions of a copy of this process come back to this one, which
    holds the same model; :func:`_live`)."""

    case: SolveCase
    profile: Gear1Profile
    shape: RoundedProfile
    samples: ToothSamples
    gears: tuple[GearSide, GearSide]
    level: RingLevel
    submodels: dict = field(default_factory=dict, repr=False)   # prepared, by key
    meshed: PairParameters | None = None    # the pair the templates were meshed for
    # a copy (dataclasses.replace) is another model with a reference of its own: had it taken
    # this one's, its end would have taken this one's reference with it
    token: int = field(default_factory=lambda: next(_TOKENS), init=False, repr=False)

    def __post_init__(self) -> None:
        if self.meshed is None:
            self.meshed = self.case.params
        _LIVE[self.token] = self

    def __reduce__(self):
        return _live, (self.token,)

    @property
    def curve2(self):
        return gear2_curve(self.case.params)

    @property
    def dofs(self) -> int:
        """Degrees of freedom of the two templates (each ring has count × about as many)."""
        return sum(g.body.ndofs for g in self.gears)

    def fits(self, case: SolveCase) -> bool:
        """Whether this model serves ``case``: same pair, material, rims, round and quality
        (torque and position are free)."""
        return all(getattr(case, k) == getattr(self.case, k) for k in GEOMETRY_KEYS)


#: every model of this process by its token, while it lives
_LIVE: weakref.WeakValueDictionary = weakref.WeakValueDictionary()
_TOKENS = itertools.count()


def _live(token: int) -> RingModel:
    """The model of ``token`` in this process (:class:`RingModel` pickles as its token)."""
    try:
        return _LIVE[token]
    except KeyError:
        raise LookupError("a ring model pickles as a reference to a model of the process "
                          "that unpickles it, and this process has none by that "
                          "reference") from None


#: ring models kept per process, most recent last: a study's cases that differ only in torque
#: or position, and the error estimate's second level, find theirs here (by the case's
#: GEOMETRY_KEYS; at most KEEP)
KEPT: OrderedDict = OrderedDict()
KEEP = 4


def ring_model(case: SolveCase, profile: Gear1Profile | None = None) -> RingModel:
    """The ring model for ``case``: one kept from an earlier case of the same geometry,
    material and quality; or one that shares the templates (meshes, factors and responses) of
    a kept model meshed for the same pair (:func:`meshed_params`); or, with the model cache on
    (:mod:`.cache`), one read back from it; or a new one (:func:`build_ring`). It is kept in
    memory (and in the model cache once solved: :func:`keep_cached`)."""
    key = tuple(getattr(case, k) for k in GEOMETRY_KEYS)
    model = KEPT.pop(key, None)
    if model is None:
        meshed = meshed_params(case)
        kin = next((m for m in reversed(KEPT.values())
                    if m.meshed == meshed and _same_body(m.case, case)), None)
        if kin is None and cache.enabled():
            model = _from_cache(case, profile)
        if model is None:
            model = build_ring(case, profile, kin)
        while len(KEPT) >= KEEP:
            KEPT.popitem(last=False)
    KEPT[key] = model
    return model


def meshed_params(case: SolveCase) -> PairParameters:
    """The pair ``case``'s templates are meshed for: its own, without a tip relief or a tip
    trim deeper than the default (a radial tip clearance above its default, the shift)
    thinner than :data:`THIN` flank elements of its level. Both move gear 1's surface by µm
    where the flank's elements are 25-100 µm, and both only take material away, so the
    exact profile lies within the templates (a tip clearance below the default would stand
    out of them: its pair is meshed as it is). The contact grids, gaps and loads follow the
    exact profile either way."""
    p = case.params
    thin = THIN * LEVELS[case.quality].flank * p.m
    if 0.0 < 1e-3 * p.relief <= thin:
        p = replace(p, relief=0.0, relief_extent=None, relief_start=None,
                    relief_shape="parabolic")
    if p.tip_clearance is not None and 0.0 <= p.tip_clearance - p.shift <= thin:
        p = replace(p, tip_clearance=None)
    return p


def _same_body(a: SolveCase, b: SolveCase) -> bool:
    """Whether two cases have the same material, rims, round and quality."""
    return all(getattr(a, k) == getattr(b, k) for k in GEOMETRY_KEYS if k != "params")


def build_templates(case: SolveCase, shape: RoundedProfile) -> tuple[Template, Template]:
    """Both template sectors of ``case`` at its quality, unmeshed (gear 1's from its rounded
    profile ``shape``)."""
    p = case.params
    level = LEVELS[case.quality]
    rho = max(case.edge_radius, ROUND_FLOOR * p.m)
    sizes = TemplateSizes(root=level.root * p.m, flank=level.flank * p.m,
                          round=level.round * rho, junction=level.junction * rho,
                          body=level.body * p.m)
    rim1, rim2 = case.rims
    return (gear1_template(p, shape, sizes, rim1),
            gear2_template(p, gear2_curve(p), sizes, rim2))


def build_ring(case: SolveCase, profile: Gear1Profile | None = None,
               kin: RingModel | None = None) -> RingModel:
    """Mesh both templates (for :func:`meshed_params`), assemble, factorise and condense them:
    once per geometry (the stages "profile", "mesh" and "assemble_factor" of a solve's
    times). With ``kin``, a model whose templates serve ``case`` too, they are shared
    (responses formed for one serve both)."""
    p = case.params
    level = LEVELS[case.quality]
    profile, shape, samples = _shapes(case, profile)
    meshed = meshed_params(case)
    if kin is not None:
        return RingModel(case, profile, shape, samples, kin.gears, level, meshed=meshed)
    with timed("mesh"):
        t1, t2 = _templates(case, shape, meshed)
        m1, m2 = mesh_bodies([t1.geometry, t2.geometry])
    with timed("assemble_factor"):
        mat = ElasticMaterial(case.E, case.nu, case.thickness, "stress")
        sides = (GearSide(assemble_cyclic(m1, mat, p.z1, t1.cut, (t1.held,)), t1),
                 GearSide(assemble_cyclic(m2, mat, p.z2, t2.cut, (t2.held,)), t2))
    return RingModel(case, profile, shape, samples, sides, level, meshed=meshed)


def _shapes(case: SolveCase, profile: Gear1Profile | None):
    """Gear 1's exact and rounded profiles and tooth 0 sampled."""
    with timed("profile"):
        profile = profile if profile is not None else gear1_profile(case.params)
        shape = RoundedProfile(profile, case.edge_radius)
        return profile, shape, sample_tooth(shape)


def _templates(case: SolveCase, shape: RoundedProfile, meshed: PairParameters):
    """Both templates for the pair ``meshed`` (:func:`meshed_params`), unmeshed: on
    ``case``'s own rounded profile ``shape`` where the two pairs have the same shape (a tip
    clearance given as its default, the shift, is no other shape)."""
    same = _shape_of(meshed) == _shape_of(case.params)
    base = shape if same else RoundedProfile(gear1_profile(meshed), case.edge_radius)
    return build_templates(replace(case, params=meshed), base)


def _shape_of(p: PairParameters) -> PairParameters:
    """``p`` with its tip clearance written out (None is the shift)."""
    return replace(p, tip_clearance=p.radial_tip_clearance)


# --- the model cache (:mod:`.cache`) --------------------------------------------------------------
#: per cache entry (its path), what this process last read from it or wrote to it
#: (:func:`_held`): models that share templates (a relief search's trials) share their entry
_CACHED: dict = {}


def _cache_key(case: SolveCase) -> str:
    """What a model's cache entry holds, in full: the pair its templates are meshed for, the
    body's inputs and the code version."""
    body = tuple((k, getattr(case, k)) for k in GEOMETRY_KEYS if k != "params")
    return f"ring model; {meshed_params(case)!r}; {body!r}; {provenance.code_version()}"


def _held(model: RingModel) -> tuple:
    """What of ``model`` an entry holds: the responses formed on each gear and the
    submodels."""
    return tuple(g.formed for g in model.gears) + (len(model.submodels),)


def _grown(held: tuple, entry: tuple | None) -> bool:
    """Whether a model holding ``held`` (:func:`_held`) is worth writing over ``entry``."""
    if entry is None:
        return True
    return held[-1] > entry[-1] or sum(held[:-1]) > GROWN * sum(entry[:-1])


def _from_cache(case: SolveCase, profile: Gear1Profile | None) -> RingModel | None:
    """``case``'s model read back from the model cache, or None."""
    key = _cache_key(case)
    if not cache.entry(key).exists():
        return None
    with timed("cache"):
        data = cache.load(key)
    if data is None:
        return None
    profile, shape, samples = _shapes(case, profile)
    with timed("cache"):
        mat = ElasticMaterial(case.E, case.nu, case.thickness, "stress")
        sides = []
        for part in data["gears"]:
            side = GearSide(restore_cyclic(part["mesh"], mat, part["body"]), part["template"])
            side.restore_responses(part["responses"])
            sides.append(side)
    model = RingModel(case, profile, shape, samples, tuple(sides), LEVELS[case.quality],
                      meshed=meshed_params(case))
    pair, meshes = data["submodels"]
    if pair == repr(case.params):   # cut from this pair's own profile (a thin relief's too)
        model.submodels.update(meshes)
    _CACHED[cache.entry(key)] = _held(model)
    return model


def keep_cached(model: RingModel) -> None:
    """Keep ``model`` in the model cache if the cache is on and it holds more than its entry: a new
    model, more submodels meshed, or :data:`GROWN` more responses formed (a mesh cycle's
    later positions load other template dofs; a relief search's trials add a few each, and
    writing a whole entry for each of them would cost more than the few they add save)."""
    if not cache.enabled():
        return
    key = _cache_key(model.case)
    path, held = cache.entry(key), _held(model)
    if path.exists() and not _grown(held, _CACHED.get(path)):
        return
    # a template's geometry is only for meshing (and holds the curves' functions, which do
    # not pickle)
    data = {"gears": [{"mesh": g.body.mesh_data, "body": cyclic_parts(g.body),
                       "template": replace(g.template, geometry=None),
                       "responses": g.responses()} for g in model.gears],
            "submodels": (repr(model.case.params), submodel_meshes(model.submodels))}
    cache.keep(key, data)
    _CACHED[path] = held
