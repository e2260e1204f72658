"""The results' one vocabulary (fegear/quantities.py, issue 68): its walkthrough runs, its
entries agree with the results they name, and no label table of a quantity grows again
outside it."""

import ast
import doctest
import re
from dataclasses import fields
from pathlib import Path

import pytest

from fegear import quantities
from fegear.quantities import FACTORS, HEADLINES, HELD, LEVEL_STRESSES, QUANTITIES, Quantity

PACKAGE = Path(quantities.__file__).parent
#: every name the registry gives a quantity or a factor: summary keys, a tooth's fields and
#: its summary names, a rated level's keys
NAMES = ({q.key for q in QUANTITIES.values()} | set(FACTORS)
         | {n for q in QUANTITIES.values() for n in (q.attribute, q.tooth_key) if n}
         | {n for k in LEVEL_STRESSES for n in (k, f"{k}_MPa")})
#: a name (``edge``, ``bending``, ``S_H``) or a mark (``-``, ``:``), not a label: a label has
#: a letter and a space or a sign (``root σ1, gear 1``, ``p flank``)
IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_.]*\Z")


def test_the_walkthrough_runs():
    result = doctest.testmod(quantities, optionflags=doctest.ELLIPSIS)
    assert result.attempted >= 5 and result.failed == 0


def test_the_headlines_are_a_solutions_headline_in_its_order():
    from fegear.toothpair import HEADLINE, SAFETY, TOOTH_SAFETY

    assert list(HEADLINE) == [q.key for q in HEADLINES]
    assert list(SAFETY) == list(FACTORS) == [q.safety for q in HELD]
    assert TOOTH_SAFETY["safety_contact_flank"] == ("contact", "flank_pressure_MPa")


def test_each_field_and_name_is_a_results_own():
    from fegear.toothpair import ToothResult

    tooth = {f.name for f in fields(ToothResult)}
    assert {q.attribute for q in QUANTITIES.values() if q.attribute} <= tooth
    labels = [q.label for q in QUANTITIES.values()] + [f.label for f in FACTORS.values()]
    shorts = [q.short for q in QUANTITIES.values()] + [f.symbol for f in FACTORS.values()]
    assert len(set(labels)) == len(labels) and len(set(shorts)) == len(shorts)


def test_a_quantity_says_what_it_is_held_against():
    with pytest.raises(ValueError, match="allowable 'yield'"):
        Quantity("x_MPa", "x", "x", "x", "MPa", allowable="yield", safety="safety_x")
    with pytest.raises(ValueError, match="needs an allowable"):
        Quantity("x_MPa", "x", "x", "x", "MPa", allowable="bending")


def _names_a_quantity(text: str | None) -> bool:
    """Whether ``text`` names a quantity: a registry name, or a label (:data:`IDENTIFIER`)."""
    return text is not None and (text in NAMES or (not IDENTIFIER.match(text)
                                                   and any(c.isalpha() for c in text)))


def _label_tables(source: str) -> list[str]:
    """Where ``source`` names a quantity of the registry in a table of its own: a dict that
    maps a registry name to a text (a label, another name: ``{"root1_MPa":
    "root_stress_gear1_MPa"}``) or to a tuple that names it again, or a text to a registry
    name (``{"S_F1": "safety_bending_gear1"}``); or a tuple that holds a registry name beside
    a label (``("root_stress_gear1_MPa", "root stress σ1, gear 1", 1)``)."""
    out = []

    def text(node) -> str | None:
        return node.value if isinstance(node, ast.Constant) and isinstance(node.value, str) \
            else None

    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Dict):
            for k, v in zip(node.keys, node.values):
                key, value = text(k) if k else None, text(v)
                if key is None:
                    continue
                named = (any(_names_a_quantity(text(e)) for e in v.elts)
                         if isinstance(v, ast.Tuple) else value is not None)
                if (key in NAMES and named) or value in NAMES:
                    out.append(f"{k.lineno}: {key!r}: {ast.unparse(v)}")
        elif isinstance(node, ast.Tuple):
            items = [text(e) for e in node.elts]
            if any(x in NAMES for x in items) and any(
                    _names_a_quantity(x) and x not in NAMES for x in items):
                out.append(f"{node.lineno}: {ast.unparse(node)}")
    return out


def test_the_check_finds_each_kind_of_label_table():
    source = ("HEADLINE = {'root_stress_gear1_MPa': 'root σ1, gear 1'}\n"
              "STATIC = {'safety_contact': ('S_H', 'contact_pressure_MPa', 'allowable')}\n"
              "FIELD = {'root1_MPa': 'root_stress_gear1_MPa'}\n"
              "LIMITS = {'S_F1': 'safety_bending_gear1'}\n"
              "PANELS = (('contact_pressure_MPa', 'contact pressure p_max', 1),)\n"
              "row = {'root_stress_gear1_MPa': t.root1_MPa, 'gear': 2, 'edge_load_N': 0.0}\n"
              "LAYOUT = (('von_mises_max_MPa', 'edge', 'key'),)\n"
              "SCATTER = {'contact_pressure_MPa': 0.7}\n"
              "MARKS = {'safety_bending_gear1': ('o', '-'), 'safety_contact': ('s', ':')}\n"
              "label = {q.key: q.label for q in HEADLINES}\n")
    found = _label_tables(source)
    assert [f.split(":")[0] for f in found] == ["1", "2", "3", "4", "5"], found


def test_no_label_table_outside_the_registry():
    """A quantity is named in fegear/quantities.py alone: a table elsewhere reads its labels,
    units, fields and allowables from there (issue 68, "Names that drift")."""
    found = [f"{path.relative_to(PACKAGE.parent)}:{hit}"
             for path in sorted(PACKAGE.rglob("*.py"))
             if path.relative_to(PACKAGE).as_posix() != "quantities.py"
             for hit in _label_tables(path.read_text())]
    assert not found, "\n".join(found)
