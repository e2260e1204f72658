"""``fegear bench``: run time against error, per pipeline stage, with CalculiX beside it."""

from __future__ import annotations

import argparse

from ..checks import Input, number
from ..errors import ParameterError
from ..geometry.parameters import PAIR_INPUTS
from ..toothpair.inputs import QUALITY, SOLVE_INPUTS, check_torque
from .args import add_inputs, checked, given_values

#: the bench's own inputs beside the pair's (its torque is the solve's row)
BENCH_INPUTS = (
    Input("repeat", int, 3, "repetitions (the best is kept)", low=1, high=100),
    Input("pair-quality", str, "standard", "quality of the estimate, cycle and scaling runs "
          "(the default of fegear solve)", choices=QUALITY),
    Input("cycle", int, 24, "positions in the benchmarked mesh cycle (0: skip)", low=0,
          high=360, limits="an integer 0 (skip) or 2 <= cycle <= 360"),
    Input("disk-levels", str, "2,4,8,16,32", "Hertz-case ladder: elements across b, "
          "comma-separated", limits="two or more numbers 1 <= n <= 200"),
    Input("pair-levels", str, "coarse,fast,standard,fine", "tooth-pair (ring model) ladder: "
          "quality levels, comma-separated", limits="two or more of " + " / ".join(QUALITY)),
    Input("sector-levels", str, None, "also the sector model at these levels, with CalculiX "
          "on its meshes (e.g. coarse,fast; minutes each)",
          limits="some of " + " / ".join(QUALITY), rule="none"),
    SOLVE_INPUTS["torque"],
    Input("scaling", str, "45,90,180", "teeth of gear 2 for the cost-growth runs, module "
          "scaled to keep the pitch radius (empty: skip)",
          limits="numbers of teeth 12 <= z2 <= 400, comma-separated, or none"),
    Input("study-cases", int, 6, "solves in the study-runner overhead benchmark (0: skip)",
          low=0, high=1000, limits="an integer 0 (skip) or 2 <= study-cases <= 1000"),
)
_ROW = {row.name: row for row in BENCH_INPUTS}


def add_parser(sub) -> None:
    p = sub.add_parser("bench", help="time the pipeline stages and print a table")
    add_inputs(p, PAIR_INPUTS, "pair")
    add_inputs(p, BENCH_INPUTS)
    p.add_argument("--paper-study", action="store_true",
                   help="also time studies/paper_trends.toml on 2 workers (about a minute)")
    p.add_argument("--no-peer", action="store_true",
                   help="do not run CalculiX beside the ladders even if ccx is installed")
    p.add_argument("--study-only", action="store_true",
                   help="run only the study-runner overhead benchmark")
    p.add_argument("--contact-peer", action="store_true",
                   help="run only the contact-pressure comparison with CalculiX (an edge and a "
                        "flank-only case on the baseline pair at --sector-levels, default "
                        "coarse,fast; about 15 minutes; needs ccx)")
    p.add_argument("--sector", action="store_true",
                   help="only cross-check this design: solve it (one position, --torque, "
                        "--pair-quality) with the ring model and with the sector model, the "
                        "full-FE peer, and print both (standard: a minute or two; coarse: "
                        "seconds)")
    p.add_argument("--out", default="out/bench",
                   help="directory for bench.json and the plots (default out/bench)")


def _levels(name: str, text: str | None, allowed, least: int) -> list[str]:
    levels = [q.strip() for q in (text or "").split(",") if q.strip()]
    if ((text or "").strip() or least) and (len(levels) < least or any(q not in allowed
                                                                       for q in levels)):
        raise ParameterError(name, text, _ROW[name].range_text)
    return levels


def _numbers(name: str, text: str) -> list[float]:
    """The comma-separated numbers of option ``name``; text that is none is refused with
    the option's range."""
    values = [number(_read(x)) for x in text.split(",") if x.strip()]
    if any(v is None for v in values):
        raise ParameterError(name, text, _ROW[name].range_text)
    return values


def _read(text: str) -> object:
    try:
        return float(text)
    except ValueError:
        return text


def _skip_or(name: str, value: int, skip: bool = True) -> int:
    """A count that is 0 (skip, where ``skip``) or at least 2."""
    if value == 1 or value == 0 and not skip:
        raise ParameterError(name, value, _ROW[name].range_text)
    return value


def run(a: argparse.Namespace) -> int:
    from ..files import check_dir
    from ..geometry import admissible_pair

    own = checked(a, [row for row in BENCH_INPUTS if not row.limits or row.kind is int])
    repeat = own["repeat"]
    cycle = _skip_or("cycle", own["cycle"])
    pair_levels = _levels("pair-levels", a.pair_levels, QUALITY, 2)
    sector_levels = _levels("sector-levels", a.sector_levels, QUALITY, 0)
    disk_levels = _numbers("disk-levels", a.disk_levels)
    if len(disk_levels) < 2 or not all(1 <= n <= 200 for n in disk_levels):
        raise ParameterError("disk-levels", a.disk_levels, _ROW["disk-levels"].range_text)
    teeth = _numbers("scaling", a.scaling)
    if not all(float(z).is_integer() and 12 <= z <= 400 for z in teeth):
        raise ParameterError("scaling", a.scaling, _ROW["scaling"].range_text)
    study_cases = _skip_or("study-cases", own["study_cases"], skip=not a.study_only)
    params = admissible_pair(given_values(a, PAIR_INPUTS))
    material = {k: SOLVE_INPUTS[k].default for k in ("E", "face-width")}
    torque = check_torque(a.torque, material["E"], params.m, material["face-width"],
                          params.r1)
    out = check_dir(a.out)         # before any work: --sector writes nothing, the rest do
    if a.study_only:
        return _study_bench(params, study_cases)
    if a.contact_peer:
        return _contact_peer(sector_levels, out)
    if a.sector:
        return _sector_check(params, torque, a.pair_quality)
    from ..files import prepare_dir

    out = prepare_dir(out)
    return _bench(a, params, torque, repeat, cycle, pair_levels, sector_levels, disk_levels,
                  [int(z) for z in teeth], study_cases, out)


def _sector_check(params, torque: float, quality: str) -> int:
    """The design by both models, side by side."""
    from ..toothpair import SolveCase
    from ..verify.sector import cross_check, cross_table

    ring, sector = cross_check(SolveCase(params, torque=torque, quality=quality))
    print(f"{params.describe()}, T {torque:g} N·m, β 0, quality {quality}: the ring model "
          "(fegear solve) and the sector model (its full-FE peer, docs/sector.md)\n")
    print(cross_table(ring, sector))
    return 0


def _bench(a, params, torque, repeat, cycle, pair_levels, sector_levels, disk_levels, teeth,
           study_cases, out) -> int:
    from ..files import write_json
    from ..provenance import code_version
    from ..verify import (  # the FE stack, once every input is sound
        PEER_TARGET,
        Series,
        disk_ladder,
        geometry_bench,
        history,
        ladder_json,
        ladder_png,
        ladder_table,
        ladder_targets,
        pair_ladder,
        ring_ladder,
        ring_table,
        run_fresh,
        scaling_png,
        scaling_runs,
        scaling_table,
    )
    from ..verify import ring_bench as rb
    from ..verify.bench import HERTZ_TARGET

    print(geometry_bench(params, repeat))
    print()
    disks = disk_ladder(disk_levels, repeat, peer=not a.no_peer)
    print(ladder_table(disks))
    print()
    for t in ladder_targets(disks):
        print(f"* {t.line()}")
    print()
    print(f"### Tooth pair, ring model: {params.describe()}, T {torque:g} N·m, one position, "
          "each level in a fresh process")
    print()
    ring = ring_ladder(params, torque, pair_levels)
    print(ring_table(ring))
    record = {"ring": [r.__dict__ for r in ring]}
    default = next((r for r in ring if r.label == a.pair_quality), None)
    if default is None:
        default = run_fresh(a.pair_quality, params, torque, a.pair_quality)
    extra = run_fresh(f"{a.pair_quality}, with estimate", params, torque, a.pair_quality,
                      estimate=True)
    cyc = (run_fresh(f"{a.pair_quality}, {cycle}-position cycle", params, torque,
                     a.pair_quality, cycle=cycle) if cycle else None)
    pair_args = [x for k, v in given_values(a, PAIR_INPUTS).items() for x in (f"--{k}", f"{v}")]
    cached = rb.disk_runs(params, torque, a.pair_quality, pair_args)
    print()
    print(f"### The disk cache (`--cache`): the model built, or read back (`{a.pair_quality}`, "
          "each in a fresh process)")
    print()
    print(rb.disk_table(cached, default, extra))
    record["default"] = default.__dict__
    record["extras"] = extra.__dict__
    record["cycle"] = cyc.__dict__ if cyc else None
    record["disk"] = {"read": cached.read.__dict__, "read_estimate": cached.read_estimate.__dict__,
                      "commands_s": cached.commands_s}
    sector = None
    if sector_levels:
        print()
        sector = pair_ladder(params, torque, sector_levels, peer=not a.no_peer)
        print(ladder_table(sector))
    scale = scaling_runs(params, torque, a.pair_quality, teeth) if teeth else []
    if scale:
        print()
        print("### How the cost grows: the same pair with more, smaller teeth "
              f"(`{a.pair_quality}`)")
        print()
        print(scaling_table(scale))
        scaling_png(out / "bench_scaling.png", ring, scale)
        record["scaling"] = [r.__dict__ for r in scale]
    study = rb.paper_study_s() if a.paper_study else None
    if study is not None:
        record["paper_study_s"] = study[0]
    print()
    lines = _targets(rb, default, extra, cyc, sector, ring, study, PEER_TARGET, cached)
    print("\n".join(lines))
    record["targets"] = lines
    series = [Series("Hertz disks", [(r.total_s, disks.error_pct(r.values, disks.judged),
                                      r.level) for r in disks.rungs],
                     [(r.peer_s, disks.error_pct(r.peer_values, disks.judged))
                      for r in disks.rungs if r.peer_s], HERTZ_TARGET),
              Series("tooth pair, ring model",
                     [(r.total_s, _sector_error(rb, r.values), r.label) for r in ring],
                     target=rb.SINGLE_TARGET),
              Series("tooth pair, ring model read from the disk cache",
                     [(cached.read.total_s, _sector_error(rb, cached.read.values),
                       f"{a.pair_quality}, read back")])]
    if sector is not None:
        series.append(Series("tooth pair, sector model",
                             [(r.total_s, _sector_error(rb, r.values), r.level)
                              for r in sector.rungs],
                             [(r.peer_s, _sector_error(rb, r.peer_values, PEER_KEYS))
                              for r in sector.rungs if r.peer_s],
                             peer_note=" (root stresses)"))
    ladder_png(out / "bench.png", series)
    everything = {**ladder_json([disks] + ([sector] if sector else []), ladder_targets(disks)),
                  "ring": record}
    before = history.last_run(out)
    write_json(out / "bench.json", everything)
    metrics = history.bench_metrics(everything)
    if before is not None:
        print()
        print(f"### Beside the last run in {out}")
        print()
        print(history.beside_table(before, metrics))
    history.remember(out, metrics, code_version(), everything["machine"])
    print(f"\nbench.json, bench.png{', bench_scaling.png' if scale else ''}, "
          f"{history.HISTORY} in {out}")
    if study_cases:
        print()
        _study_bench(params, study_cases)
    return 0


#: what CalculiX gives that means what ours means: its largest CSTR is a pointwise penalty
#: pressure at one integration point, not a contact pressure (docs/benchmark.md)
PEER_KEYS = ("root_stress_gear1_MPa", "root_stress_gear2_MPa")


def _sector_error(rb, values: dict, keys=None) -> float:
    """Largest error (%) of ``values`` against the references, von Mises against the
    resolved one (:mod:`fegear.verify.ring_bench`)."""
    ref = dict(rb.SECTOR_REFERENCE, von_mises_max_MPa=rb.VON_MISES_RESOLVED)
    keys = ref if keys is None else keys
    return max(abs(100.0 * (values[k] / ref[k] - 1.0)) for k in keys)


def _targets(rb, default, extra, cyc, sector, ring, study, peer_target,
             cached=None) -> list[str]:
    """The issue's targets, each met or MISSED with its number."""
    err = max(abs(v) for v in default.error_pct(rb.SECTOR_REFERENCE).values())
    resolved = dict(rb.SECTOR_REFERENCE, von_mises_max_MPa=rb.VON_MISES_RESOLVED)
    err_resolved = max(abs(v) for v in default.error_pct(resolved).values())
    worst = max(default.timings_s, key=default.timings_s.get)
    lines = ["### Targets", ""]

    def status(ok):
        return "met" if ok else "MISSED"

    e_lim, t_lim = rb.SINGLE_TARGET
    lines.append(f"* baseline pair, default quality (`{default.label}`), every headline within "
                 f"{e_lim:g} % in {t_lim:g} s: {default.total_s:.2f} s, largest error "
                 f"{err:.2f} % against the sector references, {err_resolved:.2f} % with the "
                 f"resolved von Mises reference: "
                 f"{status(default.total_s <= t_lim and err_resolved <= e_lim)} "
                 f"({default.total_s / rb.GOAL_S:.1f}× the {rb.GOAL_S:g} s goal; largest stage "
                 f"{worst} {default.timings_s[worst]:.2f} s)")
    if cached is not None:
        lines += _disk_targets(rb, default, cached, status)
    est = extra.extra.get("estimate_s")
    if est is not None:
        ratio = est / extra.total_s
        lines.append(f"* with the error estimate (second level "
                     f"`{extra.extra['estimate_from']}`): {est:.2f} s, {ratio:.2f}× the single "
                     f"solve (target <= {rb.ESTIMATE_TARGET:g}×): "
                     f"{status(ratio <= rb.ESTIMATE_TARGET)}")
    if cyc is not None:  # each in its own process, from nothing
        ratio = cyc.extra["cycle_s"] / default.total_s
        later = cyc.extra["cycle_later_s"]
        top = max(later, key=later.get)
        lines.append(f"* {cyc.label}: {cyc.extra['cycle_s']:.2f} s, "
                     f"{ratio:.2f}× one position (target <= {rb.CYCLE_TARGET:g}×): "
                     f"{status(ratio <= rb.CYCLE_TARGET)}; each later position "
                     f"{sum(later.values()):.2f} s, most in {top} ({later[top]:.2f} s)")
    peak = max(r.peak_mb for r in (default, extra, cyc) if r is not None) / 1024.0
    lines.append(f"* peak memory, default quality with estimate and cycle: {peak:.2f} GB "
                 f"(target <= {rb.MEMORY_TARGET_GB:g} GB): {status(peak <= rb.MEMORY_TARGET_GB)}")
    if study is not None:
        lines.append(f"* studies/paper_trends.toml, {study[1]} cases with estimates, 2 workers: "
                     f"{study[0]:.1f} s (target <= {rb.STUDY_TARGET_S:g} s): "
                     f"{status(study[0] <= rb.STUDY_TARGET_S)}")
    if sector is not None:
        for r in sector.rungs:
            if not r.peer_s:
                continue
            peer_err = _sector_error(rb, r.peer_values, PEER_KEYS)
            ours = [x for x in ring if _sector_error(rb, x.values, PEER_KEYS) <= peer_err]
            if not ours:
                lines.append(f"* CalculiX on the sector model's `{r.level}` mesh, "
                             f"{r.peer_s:.0f} s, root stresses within {peer_err:.2f} %: no "
                             f"ring level is as close (target >= {peer_target:g}× at equal "
                             "error): MISSED")
                continue
            fastest = min(ours, key=lambda x: x.total_s)
            ratio = r.peer_s / fastest.total_s
            lines.append(f"* CalculiX on the sector model's `{r.level}` mesh, {r.peer_s:.0f} s, "
                         f"root stresses within {peer_err:.2f} % of the references, against the "
                         f"ring model's `{fastest.label}` "
                         f"({_sector_error(rb, fastest.values, PEER_KEYS):.2f} %), "
                         f"{fastest.total_s:.2f} s: {ratio:.1f}× (target >= {peer_target:g}× "
                         f"at equal error): {status(ratio >= peer_target)}")
    return lines


def _disk_targets(rb, default, cached, status) -> list[str]:
    """The targets a model read back from the disk cache meets: one position in the goal's
    second, the whole command in two."""
    read = cached.read
    resolved = dict(rb.SECTOR_REFERENCE, von_mises_max_MPa=rb.VON_MISES_RESOLVED)
    e_lim = rb.SINGLE_TARGET[0]
    lines = []
    read_err = max(abs(v) for v in read.error_pct(resolved).values())
    lines.append(f"* one position with its model read from the disk cache (`--cache`): "
                 f"{read.total_s:.2f} s after import, largest error {read_err:.2f} % "
                 f"(goal <= {rb.GOAL_S:g} s within {e_lim:g} %): "
                 f"{status(read.total_s <= rb.GOAL_S and read_err <= e_lim)}; built: "
                 f"{default.total_s:.2f} s ({default.total_s / rb.GOAL_S:.1f}× the goal)")
    cmd = cached.commands_s
    lines.append(f"* the whole `fegear solve` without `--out` (imports, checks, the estimate): "
                 f"{cmd['without the cache']:.2f} s, {cmd['models read from disk']:.2f} s "
                 f"with the models read from disk (target <= {rb.COMMAND_TARGET_S:g} s): "
                 f"{status(cmd['without the cache'] <= rb.COMMAND_TARGET_S)} built, "
                 f"{status(cmd['models read from disk'] <= rb.COMMAND_TARGET_S)} read back")
    return lines


def _study_bench(params, cases: int) -> int:
    from ..verify import overhead_table, study_overhead

    print(overhead_table(study_overhead(params, cases, workers=1), workers=1))
    return 0


def _contact_peer(levels: list[str], out) -> int:
    """The contact pressures beside CalculiX's, read alike (:mod:`fegear.verify.peer_contact`),
    at ``levels`` (none: its ``LEVELS``); the table printed and kept in ``contact_peer.json``."""
    from ..files import prepare_dir, write_json
    from ..verify.calculix import ccx_available
    from ..verify.ccx_files import PeerError
    from ..verify.peer_contact import CASES, LEVELS, contact_peer, peer_table

    if not ccx_available():
        raise PeerError("fegear bench --contact-peer needs CalculiX's ccx on the PATH "
                        "(Debian: apt install calculix-ccx)")
    results = []
    for name, torque, beta in CASES:
        for level in levels or LEVELS:
            results.append(contact_peer(name, torque, beta, level))
            print(f"{name} at `{level}` done (ccx {results[-1].ccx_s:.0f} s)", flush=True)
    table = peer_table(results)
    print()
    print(table)
    directory = prepare_dir(out)
    write_json(directory / "contact_peer.json", {"table": table, "cases": [
        {**{k: v for k, v in r.__dict__.items() if k != "teeth"},
         "teeth": [t.__dict__ for t in r.teeth]} for r in results]})
    print(f"\ncontact_peer.json in {directory}")
    return 0
