"""fegear from Python: :func:`solve` and :func:`cycle`, the same job as ``fegear solve``.

The inputs are ``fegear solve``'s, under their Python names (``--face-width`` →
``face_width``, ``--tip-clearance`` → ``tip_clearance``), with the same defaults, checks and
one-line refusals (:class:`~fegear.errors.ParameterError`); nothing is written until
:meth:`Result.write` is called. docs/python.md shows it as a notebook user uses it.

A light pair (25/24 teeth) at 20 N·m, coarse, without the error estimate:

>>> import fegear
>>> r = fegear.solve(z2=25, z1=24, torque=20, quality="coarse", no_estimate=True)
>>> h = r.headline
>>> print(f"root {h.root_stress_gear1_MPa:.1f} MPa, contact {h.contact_pressure_MPa:.0f} MPa")
root 74.5 MPa, contact 805 MPa
>>> r.teeth.loc[r.teeth.load_N > 0, "load_share"].round(2).to_dict()
{5: 0.44, 6: 0.56}
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from .errors import ParameterError
from .files import check_dir
from .toothpair import HEADLINE, JOB_INPUTS, SAFETY, model_cache, prepare_job, solve_job, write_job

if TYPE_CHECKING:
    import pandas as pd

    from .toothpair import Solved

__all__ = ["Result", "cycle", "solve"]

#: the column :attr:`Result.positions` is indexed by (the rolling angle β, degrees)
POSITION = "position_deg"


@dataclass(frozen=True)
class Result:
    """A solved design. ``summary`` is ``fegear solve --json``'s dictionary; the properties
    are views of it: the headline numbers, the per-tooth table, the error estimate and, for
    a cycle, the table of positions and the worst over them."""

    summary: dict
    solved: Solved

    @property
    def headline(self) -> pd.Series:
        """The five headline stresses (MPa) and the four safety factors, by their JSON names,
        at the position the files are written for (the largest gear-1 root stress)."""
        import pandas as pd

        return pd.Series({k: self.summary[k] for k in (*HEADLINE, *SAFETY)}, name="headline")

    @property
    def teeth(self) -> pd.DataFrame:
        """One row per paired gear-1 tooth (index ``tooth``): clearance, load and share,
        pressures (flank, edge, Hertz, half-plane), root stresses, safety factors."""
        import pandas as pd

        return pd.DataFrame(self.summary["teeth"]).set_index("tooth")

    @property
    def estimate(self) -> dict[str, object] | None:
        """The discretisation-error estimate: ``pct`` (the largest over the headline
        stresses, %), ``by_stress`` (% per headline) and ``quality`` (the second level it
        comes from); None when solved with ``no_estimate=True``."""
        if self.summary["error_estimate_pct"] is None:
            return None
        return {"pct": self.summary["error_estimate_pct"],
                "by_stress": self.summary["error_estimate_by_stress_pct"],
                "quality": self.summary["error_estimate_from"]}

    @property
    def positions(self) -> pd.DataFrame | None:
        """For a cycle, one row per rolling position (index ``position_deg``): the headline
        stresses, safety factors, rotation and mesh stiffness; None for one position."""
        import pandas as pd

        rows = self.solved.rows
        return None if rows is None else pd.DataFrame(rows).set_index(POSITION)

    @property
    def worst(self) -> dict[str, dict] | None:
        """For a cycle, the largest of each headline stress (``max``) and the smallest of
        each safety factor (``min``) over its positions, each with the position where it
        occurs (``at_position_deg``); None for one position."""
        cycle = self.summary.get("cycle")
        return None if cycle is None else {k: cycle[k] for k in (*HEADLINE, *SAFETY)}

    @property
    def revolution(self) -> dict | None:
        """For a whole revolution of gear 1 (``revolution=True``): ``worst``, each headline
        stress's largest with its gear, tooth and position and each safety factor's smallest;
        ``teeth``, a DataFrame indexed by gear and tooth of the largest root stress (and, for
        gear 1's teeth, contact pressure) each tooth carried; ``spectrum``, a DataFrame of
        the loaded rotation's largest harmonics by order; ``rotation_urad``, its range. None
        otherwise."""
        import pandas as pd

        rev = self.summary.get("revolution")
        if rev is None:
            return None
        per = rev["per_tooth"]
        teeth = pd.DataFrame(
            [{"gear": g, "tooth": t, "root_stress_MPa": v,
              "contact_pressure_MPa": per["contact_pressure_MPa"].get(t) if g == 1 else None}
             for g in (1, 2) for t, v in per[f"root_stress_gear{g}_MPa"].items()]
        ).set_index(["gear", "tooth"])
        return {"worst": rev["worst"], "teeth": teeth, "rotation_urad": rev["rotation_urad"],
                "spectrum": pd.DataFrame(rev["spectrum"]).set_index("order")}

    @property
    def samples(self) -> dict | None:
        """For a tolerance class's pairs (``grade=...``, docs/tolerance.md): ``rows``, a
        DataFrame indexed by sample (its deviations in brief, status, largest stresses and
        safety factors); ``quantiles``, a DataFrame indexed by stress and quantile of the
        value, its bootstrap error and whether it falls among the jammed pairs; ``safety``,
        a DataFrame indexed by safety factor of the nominal, the value at the quantile, its
        error and the worst; the counts (``solved``, ``jammed``, ``failed``) and the
        ``verdict``. None otherwise."""
        import pandas as pd

        s = self.summary.get("samples")
        if s is None:
            return None
        quantiles = pd.DataFrame(
            [{"stress": k, **q} for k, v in s["stresses"].items() for q in v["quantiles"]]
        ).set_index(["stress", "q"])
        safety = pd.DataFrame([{"factor": k, **v} for k, v in s["safety"].items()]
                              ).set_index("factor")
        return {"rows": pd.DataFrame(s["rows"]).set_index("sample"), "quantiles": quantiles,
                "safety": safety, "solved": s["solved"], "jammed": s["jammed"],
                "failed": s["failed"], "verdict": s["verdict"]}

    def write(self, out: str | Path, fields: bool = True,
              pictures: bool = True) -> dict[str, Path]:
        """Write the files ``fegear solve --out`` writes into ``out``: summary.json, the VTU
        fields (``fields``), the pictures (``pictures``), and a cycle's table, PVD series and
        plot. Returns name → path."""
        return write_job(self.solved, check_dir(str(out)), fields, pictures)


def solve(cache: bool | None = None, **inputs: object) -> Result:
    """Solve one position of a design: ``fegear solve``'s inputs by their Python names
    (``m``, ``h1``, ``f1``, ``torque``, ``position``, ``face_width``, ``quality``,
    ``no_estimate``, …), every other at its default. Raises
    :class:`~fegear.errors.ParameterError` naming the input and its range for a design fegear
    refuses. ``cache``: read the meshed and condensed model from the model cache and keep it
    there (``fegear solve --cache``; None: as the FEGEAR_CACHE environment variable says,
    off where it is unset). Within one Python process a design's model is kept in memory
    anyway: the model cache serves the next process, a restarted kernel."""
    try:
        job = prepare_job(_named(inputs))
    except ParameterError as err:   # the input as the caller spelt it: tip_clearance
        err.args = (err.describe(err.name.replace("-", "_")),)
        raise
    with model_cache(cache):
        solved = solve_job(job)
    return Result(solved.summary, solved)


def _named(inputs: dict[str, object]) -> dict[str, object]:
    """Python names → the schema's (``face_width`` → ``face-width``); an unknown name is
    refused with the nearest known one."""
    import difflib

    known = [row.dest for row in JOB_INPUTS.values()]
    known += [a.replace("-", "_") for row in JOB_INPUTS.values() for a in row.aliases]
    for name, value in inputs.items():
        if name not in known:
            close = difflib.get_close_matches(name, known, n=1)
            hint = f"did you mean {close[0]}? " if close else ""
            raise ParameterError(name, value, f"{hint}one of {', '.join(known)}",
                                 "unknown input")
    return {name.replace("_", "-"): value for name, value in inputs.items()}


def cycle(positions: int = 24, cache: bool | None = None, **inputs: object) -> Result:
    """Solve ``positions`` rolling positions across one tooth pitch of gear 2 from
    ``position`` (degrees, default 0) on one model; ``cache`` and the other inputs as
    :func:`solve`."""
    return solve(cache=cache, positions=positions, **inputs)


def revolution(positions: int = 24, cache: bool | None = None, **inputs: object) -> Result:
    """Solve a whole revolution of gear 1, ``positions`` a pitch from ``position`` (degrees,
    default 0), on one model: every tooth pair that meets, the deviations given with
    ``pitch_deviation``, ``runout``, … as ``fegear solve --revolution``; ``cache`` and the
    other inputs as :func:`solve`."""
    return solve(cache=cache, positions=positions, revolution=True, **inputs)
