"""``fegear solve``: the tooth-pair stress solve at one position or over a mesh cycle."""

from __future__ import annotations

import argparse
import json

from ..toothpair.inputs import (
    DEVIATION_INPUTS,
    FACE_INPUTS,
    JOB_INPUTS,
    LOAD_INPUTS,
    MODEL_INPUTS,
    PAIR_INPUTS,
    RATING_INPUTS,
    TOLERANCE_INPUTS,
)
from .args import add_inputs, typed_values
from .cache import add_switch, apply_switch

#: ``--help``'s groups of the schema's rows, by task: every input of :data:`JOB_INPUTS` once
#: (tests/cli/test_solve_help.py holds them to it); the README and docs/cli.md use the same
HELP_GROUPS = {
    "the pair": (*PAIR_INPUTS, JOB_INPUTS["face-width"]),
    "load and positions": LOAD_INPUTS,
    "deviations of a real pair (docs/deviations.md)": DEVIATION_INPUTS,
    "tolerance class (docs/tolerance.md)": TOLERANCE_INPUTS,
    "material, allowables and life rating (docs/rating.md)": (
        JOB_INPUTS["E"], JOB_INPUTS["nu"], JOB_INPUTS["allowable-bending"],
        JOB_INPUTS["allowable-contact"], *RATING_INPUTS),
    "across the face width (docs/model.md)": FACE_INPUTS,
    "model and mesh": MODEL_INPUTS,
}


def add_parser(sub) -> None:
    p = sub.add_parser("solve", help="tooth-pair FE solve: stresses, load sharing, stiffness",
                       usage="fegear solve [--case FILE] [options]",
                       description="The tooth-pair FE solve at one position, over a mesh "
                                   "cycle or a whole revolution; every option below, by "
                                   "task (docs/cli.md).")
    design = p.add_argument_group("a design as a file")
    design.add_argument("--case", default=None, metavar="FILE",
                        help="read the inputs from a case file: TOML, a `name = value` line "
                             "per option of this command (units as here; a deviations, "
                             "spectrum or material file it names is found beside it), or "
                             "a summary.json of an earlier solve; options typed beside it "
                             "win, and the output says so")
    design.add_argument("--save-case", default=None, metavar="FILE",
                        help="write every input as run, the defaults written out, to FILE "
                             "(TOML) once the solve has succeeded: --case FILE solves it "
                             "again")
    for title, rows in HELP_GROUPS.items():
        add_inputs(p, rows, title)
    outputs = p.add_argument_group("outputs")
    outputs.add_argument("--out", default=None,
                         help="output directory for summary.json, VTU files and pictures, "
                              "made when the solve has succeeded (default: none, the table "
                              "only)")
    outputs.add_argument("--json", action="store_true", help="print the summary as JSON")
    outputs.add_argument("--report", action="store_true",
                         help="write report.html into --out: one self-contained page, the "
                              "verdict first (docs/outputs.md, \"The report\")")
    running = p.add_argument_group("running")
    running.add_argument("--scheduler", default=None,
                         help="with --grade: solve the class's pairs on this Dask distributed "
                              "scheduler (e.g. tcp://host:8786; its workers need fegear) "
                              "instead of this machine's second core")
    add_switch(running, default=False)


def _values(a: argparse.Namespace) -> tuple[dict, list[str]]:
    """The solve's inputs by name: a ``--case`` file's, the options typed beside it over
    them; and a line for each value of the file that a typed option replaced."""
    typed = typed_values(a, JOB_INPUTS.values())
    if a.case is None:
        return typed, []
    from ..toothpair import read_case

    case = read_case(a.case)
    notes = [f"--{k} {_text(v)} typed beside --case wins over {a.case}'s {_text(case[k])}"
             for k, v in typed.items() if k in case and case[k] != v]
    return {**case, **typed}, notes


def _text(value) -> str:
    """An input's value as a note shows it."""
    return ",".join(map(str, value)) if isinstance(value, list) else f"{value}"


def run(a: argparse.Namespace) -> int:
    from ..running import spare_core
    from ..toothpair import prepare_pictures

    # the processes that will draw the pictures, made now: they import matplotlib on the core
    # that idles while this one reads the inputs and imports the solver's libraries
    spare = None if a.scheduler else spare_core(
        prepare_pictures if a.out is not None else None, ready=2)
    try:
        return _run(a, spare)
    finally:
        if spare is not None:
            spare.close()


def _run(a: argparse.Namespace, spare) -> int:
    """:func:`run` on ``spare`` (None: on the cluster of ``--scheduler``)."""
    import shlex
    import shutil
    import sys

    from ..errors import FegearError
    from ..files import check_dir
    from ..running import Cluster, connect
    from ..toothpair import run_job
    from .terminal import command_wall_s

    values, notes = _values(a)
    job = _prepared(values, a)
    save = None if a.save_case is None else _save_target(a.save_case)
    if a.report and a.out is None:
        raise FegearError("--report: with --out DIR (the page is written there, beside the "
                          "pictures it shows)")
    if a.scheduler and job.draw is None:
        raise FegearError("--scheduler: with --grade only (a class's pairs are the work a "
                          "cluster shares)")
    apply_switch(a, default=False)
    out = None if a.out is None else check_dir(a.out)
    made = out is not None and not out.exists()
    try:
        with Cluster(connect(a.scheduler)) if spare is None else spare as executor:
            result = run_job(job, out, executor=executor,
                             report=shlex.join(["fegear", *a.argv]) if a.report else None)
    except BaseException:
        if made and out.exists():  # made by this run: nothing half-written stays
            shutil.rmtree(out, ignore_errors=True)
        raise
    if save is not None:
        result.files["case"] = _save_case(save, job, a)
    files = {k: str(v) for k, v in result.files.items()}
    for note in notes:
        print(f"fegear: {note}", file=sys.stderr)
    if a.json:
        print(json.dumps({**result.summary, "files": files}, indent=2))
        return 0
    _print(result.summary)
    for k, v in files.items():
        print(f"{k:10s} {v}")
    if out is None:
        print("(no files written: --out DIR writes summary.json, VTU files and pictures)")
    print(f"wall {command_wall_s():.1f} s for the whole command")
    return 0


def _print(summary: dict) -> None:
    """The tables of a solve: each analysis's that comes before the pair's (a cycle's, a
    revolution's), the pair's, then the others' (:mod:`fegear.toothpair.analyses`)."""
    from ..toothpair import pair_table
    from ..toothpair.analyses import shown

    before = [a for a in shown(summary) if a.before_pair]
    after = [a for a in shown(summary) if not a.before_pair]
    texts = [a.printed(summary[a.key], summary) for a in before]
    texts += [pair_table(summary)] + [a.printed(summary[a.key], summary) for a in after]
    for text in texts:
        if text:
            print(text)


def _prepared(values: dict, a: argparse.Namespace):
    """The checked job of ``values``; a refused value that came from the ``--case`` file (not
    typed) is refused naming the file and its key."""
    from ..errors import FegearError, ParameterError
    from ..toothpair import prepare_job

    try:
        return prepare_job(values)
    except ParameterError as exc:
        typed = getattr(a, "typed", set())
        if a.case is None or exc.name not in values or exc.name.replace("-", "_") in typed:
            raise
        raise FegearError(f"{a.case}: {exc.describe(exc.name)}") from None


def _save_target(path: str):
    """``--save-case``'s file, checked before the solve: a file (not a folder) in a folder
    that is, or can be made, writable."""
    from pathlib import Path

    from ..errors import FegearError
    from ..files import check_dir

    target = Path(path)
    if target.is_dir():
        raise FegearError(f"--save-case {path!r} is a folder; give a file, e.g. "
                          f"{target / 'design.toml'}")
    check_dir(target.parent)
    return target


def _save_case(target, job, a: argparse.Namespace):
    """Write the job's inputs as run (:func:`~fegear.toothpair.case_toml`) to ``target``."""
    import shlex

    from .. import __version__
    from ..files import write_atomic
    from ..toothpair import case_toml

    title = (f"fegear {__version__}: a tooth-pair case, every input as run (the defaults "
             f"written out)\nfrom: {shlex.join(['fegear', *a.argv])}\n"
             f"again: fegear solve --case {target}")
    text = case_toml(job.record, where=target.absolute().parent, title=title)
    target.parent.mkdir(parents=True, exist_ok=True)
    return write_atomic(target, lambda tmp: tmp.write_text(text, encoding="utf-8"))
