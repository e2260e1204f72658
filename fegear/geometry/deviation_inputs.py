"""Deviations as a user gives them (:mod:`.deviations`): on the command line and in study files
as short texts, or as a file of measured deviations.

* ``GEAR:TOOTH=µm``, comma-separated: a tooth's pitch, slope or form deviation
  (``--pitch-deviation 1:11=5,2:30=-3``), and across the face its helix slope or form
  deviation (``--helix-slope-deviation 1:11=4``: :class:`Helix`);
* ``GEAR=µm[@deg]``, comma-separated: a gear's radial runout and the angle of its high point
  (``--runout 1=10@90``; without ``@deg``, 0°);
* a CSV file, one row per tooth as a gear measuring machine reports them: columns ``gear``,
  ``tooth`` and any of ``fp`` (the tooth's position deviation; also ``pitch``), ``fpt`` (its
  single pitch deviation from the tooth before, summed into positions: every tooth of that gear
  then), ``fHa`` (profile slope), ``ffa`` (profile form), ``fHb`` (helix slope) and ``ffb``
  (helix form), each with its unit in brackets,
  ``[µm]``, ``[um]`` or ``[mm]`` (``fp [µm]``), in the header grammar of every input table
  (:mod:`fegear.files`: commas, or semicolons with decimal commas; lines starting with ``#``
  are comments). A tooth has one row.

Whatever is wrong is refused in one line naming the option, the row or the column.

The texts are read here once, each per-tooth entry into a :class:`ToothEntry` and each runout
into a :class:`~.deviations.Runout`; whatever quotes one back (a refusal, a case file) writes it
with :attr:`ToothEntry.text` or :func:`runout_text`, so this module alone knows the grammar,
both ways.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator, Mapping
from dataclasses import dataclass

from ..errors import ParameterError
from ..files import Column, read_table, read_text
from .deviations import LIMIT_UM, Deviations, Runout, ToothDeviation

#: the per-tooth options and the field each sets
PER_TOOTH = {"pitch-deviation": "pitch", "slope-deviation": "slope", "form-deviation": "form"}
#: the per-tooth options across the face (a :class:`Helix`'s fields), which only a solve
#: across the face reads (docs/model.md, "Across the face")
HELIX = {"helix-slope-deviation": "helix_slope", "helix-form-deviation": "helix_form"}
#: every option of the ``GEAR:TOOTH=µm`` grammar
TOOTH_OPTIONS = {**PER_TOOTH, **HELIX}
#: a deviation column's units: one must be given (µm or mm, a factor of 1000 apart)
UNITS = {"µm": 1.0, "um": 1.0, "mm": 1e3}
#: the file's columns, and the field each deviation column sets ("fpt" is summed into
#: positions)
COLUMNS = (Column(("gear",)), Column(("tooth",)), Column(("fp", "pitch"), UNITS, None),
           Column(("fpt",), UNITS, None), Column(("fHa", "slope"), UNITS, None),
           Column(("ffa", "form"), UNITS, None), Column(("fHb", "helix-slope"), UNITS, None),
           Column(("ffb", "helix-form"), UNITS, None))
FIELDS = {"fp": "pitch", "fpt": "fpt", "fHa": "slope", "ffa": "form", "fHb": "helix_slope",
          "ffb": "helix_form"}
HEADER = ("columns gear, tooth and any of fp (or pitch), fpt, fHa (or slope), ffa (or form), "
          "fHb (or helix-slope), ffb (or helix-form)")
TOOTH_SPEC = "GEAR:TOOTH=µm, comma-separated (e.g. 1:11=5,2:30=-3), GEAR 1 or 2"
RUNOUT_SPEC = ("GEAR=µm[@deg], comma-separated (e.g. 1=10@90; without @deg, 0°), GEAR 1 or 2, "
               "0 <= µm <= 1000")
#: what stands before an entry's ``=``: ``GEAR:TOOTH`` (a per-tooth option's), ``GEAR`` (a runout's)
_TOOTH = re.compile(r"\s*([12])\s*:\s*(\d+)\s*")
_GEAR = re.compile(r"\s*([12])\s*")


@dataclass(frozen=True)
class ToothEntry:
    """One entry of a per-tooth option, ``GEAR:TOOTH=µm``, as read (:func:`per_tooth`): the
    ``option`` it was given to (a key of :data:`TOOTH_OPTIONS`), the ``gear`` (1 or 2), its
    ``tooth`` (index from 0) and the deviation ``um`` (µm; + moves the tooth's loaded flank
    towards its mate). :attr:`text` writes it back: the one writer of the grammar, as
    :func:`per_tooth` is its one reader."""

    option: str
    gear: int
    tooth: int
    um: float

    def __post_init__(self) -> None:
        if self.option not in TOOTH_OPTIONS:
            raise ValueError(f"a per-tooth option ({', '.join(TOOTH_OPTIONS)}), not "
                             f"{self.option!r}")
        if (self.gear not in (1, 2) or self.tooth < 0 or not math.isfinite(self.um)
                or abs(self.um) > LIMIT_UM):
            raise ParameterError(self.option, self.text, f"{TOOTH_SPEC}, |µm| <= {LIMIT_UM:g}")

    @classmethod
    def of(cls, deviation: ToothDeviation, gear: int, tooth: int) -> ToothEntry | None:
        """The entry that gives ``deviation`` of ``gear``'s ``tooth`` (its pitch deviation,
        else its slope, else its form: what a message about the tooth quotes), or None where
        it has none of them (a measured form curve alone)."""
        for option, field in PER_TOOTH.items():
            if getattr(deviation, field):
                return cls(option, gear, tooth, getattr(deviation, field))
        return None

    @property
    def field(self) -> str:
        """The :class:`~.deviations.ToothDeviation` or :class:`Helix` field the entry
        sets."""
        return TOOTH_OPTIONS[self.option]

    @property
    def where(self) -> str:
        """The tooth in the grammar, ``GEAR:TOOTH``."""
        return f"{self.gear}:{self.tooth}"

    @property
    def text(self) -> str:
        """The entry in the grammar, ``GEAR:TOOTH=µm``, which :func:`per_tooth` reads back to
        the same entry."""
        return f"{self.where}={_number_text(self.um)}"


def runout_text(gear: int, runout: Runout) -> str:
    """``gear``'s runout in the grammar of ``--runout``, ``GEAR=µm@deg``, which
    :func:`runouts` reads back to the same :class:`~.deviations.Runout`."""
    return f"{gear}={_number_text(runout.fr)}@{_number_text(runout.phase)}"


def check_teeth(deviations: Deviations, z1: int, z2: int) -> None:
    """Refuse, by its option and as it was given, an entry for a tooth that its gear of
    ``z1``/``z2`` teeth does not have."""
    for gear, z in ((1, z1), (2, z2)):
        for tooth, d in deviations.teeth(gear).items():
            if not 0 <= tooth < z:
                entry = ToothEntry.of(d, gear, tooth)
                option, text = (("form-curve", f"{gear}:{tooth}") if entry is None
                                else (entry.option, entry.text))
                raise ParameterError(option, text, f"a tooth 0 ... {z - 1} of gear {gear} "
                                     f"(z{gear} = {z})")


def per_tooth(name: str, given) -> tuple[ToothEntry, ...]:
    """The ``GEAR:TOOTH=µm`` entries of option ``name`` (module docstring; :func:`_entries`
    for the forms ``given`` takes), in the order given; an entry that is not one is refused
    quoting it."""
    out = []
    for entry, where, value in _entries(given):
        m, um = _TOOTH.fullmatch(where), _number(value)
        if not m or not math.isfinite(um):
            raise ParameterError(name, entry, f"{TOOTH_SPEC}, |µm| <= {LIMIT_UM:g}")
        out.append(ToothEntry(name, int(m.group(1)), int(m.group(2)), um))
    return tuple(out)


def runouts(given) -> dict[int, Runout]:
    """``GEAR=µm[@deg]`` entries of ``--runout`` → {gear: Runout} (without ``@deg``, the high
    point at 0°); an entry that is not one is refused quoting it."""
    out: dict[int, Runout] = {}
    for entry, gear, value in _entries(given):
        m = _GEAR.fullmatch(gear)
        fr, at, deg = str(value).partition("@")
        fr, phase = _number(fr), _number(deg) if at else 0.0
        if not m or not (math.isfinite(fr) and 0 <= fr <= LIMIT_UM and math.isfinite(phase)):
            raise ParameterError("runout", entry, RUNOUT_SPEC)
        out[int(m.group(1))] = Runout(fr, phase)
    return out


@dataclass(frozen=True)
class Helix:
    """The helix deviations of the teeth across the face (µm), per gear: (tooth, f_Hβ, f_fβ)
    for every tooth given one, by tooth. f_Hβ, the helix slope deviation: the loaded flank
    towards its mate at the face's second end, as much away at its first; f_fβ, the helix
    form deviation: towards its mate at mid-face, a parabola zero at the ends."""

    gear1: tuple[tuple[int, float, float], ...] = ()
    gear2: tuple[tuple[int, float, float], ...] = ()

    def __bool__(self) -> bool:
        return bool(self.gear1 or self.gear2)


def helix_trace(slope, form, zeta):
    """A tooth's loaded flank towards its mate (µm) at the places ``zeta`` across the face
    (fractions of the face width from its middle) under a helix slope deviation ``slope`` and
    a helix form deviation ``form`` (µm, :class:`Helix`): slope ζ + form (1 − 4ζ²)."""
    return slope * zeta + form * (1.0 - (2.0 * zeta) ** 2)


def tooth_deviations(values: Mapping[str, object], z1: int, z2: int
                     ) -> tuple[Deviations, Helix]:
    """The deviations the solve inputs name (by their option names: the file first, then the
    per-tooth options over it, the centre distance and the runouts), in the plane and across
    the face, the file read once for both; each tooth refused by name where ``z1`` or ``z2``
    has no such tooth."""
    teeth = _given_teeth(values, TOOTH_OPTIONS, z1, z2)
    planar = {key: {f: v for f, v in got.items() if f in PER_TOOTH.values()}
              for key, got in teeth.items()}
    planar = {key: ToothDeviation(**got) for key, got in planar.items() if got}
    runout = runouts(values.get("runout"))
    deviations = Deviations({t: d for (g, t), d in planar.items() if g == 1},
                            {t: d for (g, t), d in planar.items() if g == 2},
                            float(values.get("centre-distance-deviation") or 0.0),
                            runout.get(1, Runout()), runout.get(2, Runout()))
    helix = {g: tuple((t, got.get("helix_slope", 0.0), got.get("helix_form", 0.0))
                      for (gear, t), got in sorted(teeth.items())
                      if gear == g and (got.get("helix_slope") or got.get("helix_form")))
             for g in (1, 2)}
    return deviations, Helix(helix[1], helix[2])


def deviations_of(values: Mapping[str, object], z1: int, z2: int) -> Deviations:
    """The deviations in the plane of :func:`tooth_deviations` (``fegear profile``'s)."""
    return tooth_deviations(values, z1, z2)[0]


def _given_teeth(values: Mapping[str, object], options: Mapping[str, str], z1: int,
                 z2: int) -> dict[tuple[int, int], dict[str, float]]:
    """{(gear, tooth): {field: µm}} of the deviations file's columns and then the per-tooth
    ``options`` over them (a key of ``options`` → the field it sets)."""
    teeth: dict[tuple[int, int], dict[str, float]] = {}
    if values.get("deviations"):
        teeth.update(read_measured(values["deviations"], z1, z2))
    z = {1: z1, 2: z2}
    for name in options:
        for entry in per_tooth(name, values.get(name)):
            g = entry.gear
            if entry.tooth >= z[g]:
                raise ParameterError(name, entry.where, f"a tooth 0 ... {z[g] - 1} of gear {g} "
                                     f"(z{g} = {z[g]})")
            teeth.setdefault((g, entry.tooth), {})[entry.field] = entry.um
    return teeth


def read_deviations(path, z1: int, z2: int) -> dict[tuple[int, int], ToothDeviation]:
    """The per-tooth deviations in the plane of the file ``path`` (module docstring) →
    {(gear, tooth): deviation}; a tooth with only helix deviations has none."""
    planar = {key: {f: v for f, v in got.items() if f not in HELIX.values()}
              for key, got in read_measured(path, z1, z2).items()}
    return {key: ToothDeviation(**got) for key, got in planar.items() if got}


def read_measured(path, z1: int, z2: int) -> dict[tuple[int, int], dict[str, float]]:
    """Every deviation of the file ``path`` (module docstring) → {(gear, tooth): {field:
    µm}}, the fields those of :class:`~.deviations.ToothDeviation` and :class:`Helix`, each
    checked as a tooth's is."""
    table = read_table(read_text(path, "deviations", "CSV file of measured deviations"),
                       COLUMNS, "deviations", path, HEADER)
    fields = [c for c in table.columns if c in FIELDS]
    if not {"gear", "tooth"} <= set(table.columns) or not fields:
        raise ParameterError("deviations", str(path), "a header with gear, tooth and at least "
                             "one deviation column (with its unit: fp [µm]), and a row a "
                             "tooth")
    z = {1: z1, 2: z2}
    got: dict[tuple[int, int], dict[str, float]] = {}
    lines: dict[tuple[int, int], int] = {}
    for row in table.rows:
        gear, tooth = _row_tooth(path, row, "deviations", z1, z2)
        if (gear, tooth) in lines:   # measured twice: which row is meant is the user's call
            raise ParameterError("deviations", str(path), f"one row a tooth (lines "
                                 f"{lines[(gear, tooth)]} and {row.line} both give gear "
                                 f"{gear} tooth {tooth})")
        lines[(gear, tooth)] = row.line
        got[(gear, tooth)] = {FIELDS[c]: row.values[c] for c in fields}
    for gear in (1, 2):   # single pitch deviations: each tooth's position is their running sum
        mine = sorted(t for g, t in got if g == gear)
        if "fpt" in fields and mine:
            if mine != list(range(z[gear])):
                raise ParameterError("deviations", str(path), f"every tooth 0 ... "
                                     f"{z[gear] - 1} of gear {gear}: fpt, the single pitch "
                                     "deviations, add up to the teeth's positions")
            total = 0.0
            for t in mine:
                total += got[(gear, t)].pop("fpt")
                got[(gear, t)]["pitch"] = got[(gear, t)].get("pitch", 0.0) + total
    for (gear, tooth), values in got.items():
        for field, um in values.items():
            if not (math.isfinite(um) and abs(um) <= LIMIT_UM):
                option = next(o for o, f in TOOTH_OPTIONS.items() if f == field)
                raise ParameterError("deviations", str(path), f"-{LIMIT_UM:g} <= {option} <= "
                                     f"{LIMIT_UM:g} µm", f"line {lines[(gear, tooth)]}: "
                                     f"{um:g}")
    return got


#: a measured lead's columns: the tooth, its place across the face and the flank's deviation
LEAD_COLUMNS = (Column(("gear",)), Column(("tooth",)),
                Column(("z",), {"mm": 1.0, "µm": 1e-3, "um": 1e-3}, None),
                Column(("deviation", "lead", "fb"), UNITS, None))
LEAD_HEADER = "columns gear, tooth, z [mm] (from the face's first end) and deviation [µm]"


def read_leads(path, z1: int, z2: int, width: float) -> Helix:
    """The measured leads of the file ``path``: a row a point of a tooth's trace across the
    face (columns :data:`LEAD_HEADER`; + moves the loaded flank towards its mate), each
    tooth's trace two or more points, its places rising within the face of ``width`` mm.
    Returned as a :class:`Helix` whose entries are (tooth, places (mm), deviations (µm))."""
    table = read_table(read_text(path, "lead", "CSV file of measured leads"), LEAD_COLUMNS,
                       "lead", path, LEAD_HEADER)
    if set(table.columns) != {"gear", "tooth", "z", "deviation"}:
        raise ParameterError("lead", str(path), f"a header with {LEAD_HEADER[8:]}, and a row a "
                             "point of a tooth's trace")
    traces: dict[tuple[int, int], list[tuple[float, float, int]]] = {}
    for row in table.rows:
        gear, tooth = _row_tooth(path, row, "lead", z1, z2)
        place, um = row.values["z"], row.values["deviation"]
        if not 0.0 <= place <= width:
            raise ParameterError("lead", str(path), f"line {row.line}: 0 <= z <= {width:g} mm "
                                 f"(the face width), not {place:g}")
        if abs(um) > LIMIT_UM:
            raise ParameterError("lead", str(path), f"line {row.line}: |deviation| <= "
                                 f"{LIMIT_UM:g} µm, not {um:g}")
        traces.setdefault((gear, tooth), []).append((place, um, row.line))
    out: dict[int, list] = {1: [], 2: []}
    for (gear, tooth), points in sorted(traces.items()):
        points.sort()
        places = [p for p, _, _ in points]
        if len(points) < 2 or any(b <= a for a, b in zip(places, places[1:])):
            lines = ", ".join(str(line) for _, _, line in points)
            raise ParameterError("lead", str(path), f"two or more points a tooth at different "
                                 f"places (gear {gear} tooth {tooth}: lines {lines})")
        out[gear].append((tooth, tuple(places), tuple(u for _, u, _ in points)))
    return Helix(tuple(out[1]), tuple(out[2]))


def _row_tooth(path, row, option: str, z1: int, z2: int) -> tuple[int, int]:
    """A file row's gear and tooth, refused by ``option`` (the file's) where they are no
    whole numbers or its gear of ``z1``/``z2`` teeth has no such tooth."""
    gear, tooth = _whole(path, row, "gear", option), _whole(path, row, "tooth", option)
    if gear not in (1, 2) or not 0 <= tooth < (z1 if gear == 1 else z2):
        raise ParameterError(option, str(path), f"line {row.line}: gear 1 (teeth 0 ... "
                             f"{z1 - 1}) or 2 (teeth 0 ... {z2 - 1}), not gear {gear} "
                             f"tooth {tooth}")
    return gear, tooth


def _whole(path, row, column: str, option: str) -> int:
    value = row.values[column]
    if value != int(value):
        raise ParameterError(option, str(path), f"line {row.line}: a whole number in "
                             f"column {column!r}, not {value:g}")
    return int(value)


def _entries(given) -> Iterator[tuple[object, str, object]]:
    """The entries of a deviation option, each as (the entry as given, for a refusal to quote;
    the text before its ``=``; its value): a text of comma-separated entries, a list of such
    texts (the option given more than once, a study file's list) or a mapping of the texts
    before ``=`` to values (``{"1:11": 5}`` from Python)."""
    if isinstance(given, Mapping):
        yield from (({k: v}, str(k), v) for k, v in given.items())
        return
    if isinstance(given, (list, tuple)):
        given = ",".join(str(g) for g in given)
    for part in str(given or "").split(","):
        if part.strip():
            before, _, after = part.partition("=")
            yield part.strip(), before, after


def _number(text) -> float:
    if isinstance(text, bool):   # True is no number of µm
        return math.nan
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def _number_text(x: float) -> str:
    """``x`` as short as it reads back exactly: 5 for 5.0, 0.1 for 0.1."""
    short = f"{x:g}"
    return short if float(short) == x else repr(float(x))
