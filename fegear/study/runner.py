"""Run a study: every case a ``fegear solve``, on a local process pool or a Dask cluster.

Resumable by construction. Each case is stored as ``cases/<key>.json`` (the key hashes the
inputs, the kept outputs and the code version) and written atomically by this process once the
case has finished, after its kept files (``cases/<key>/``). A study that is killed and started
again finds the finished cases in its folder and computes only the missing ones; a case that was
running when the study died left nothing and runs again. A case that fails is stored with its
reason and does not stop the study (``retry_failed`` runs such cases again). A run stopped
before it finished a case leaves ``out`` as it found it: no folder it made, no marker, no
table rewritten.
"""

from __future__ import annotations

import json
import os
import signal
import socket
import tempfile
import threading
import time
import traceback
from collections.abc import Iterator
from contextlib import closing
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

from .. import __version__
from ..errors import FegearError
from ..files import prepare_dir, write_json
from ..provenance import code_version, library_versions
from ..running import Supervisor, WorkerFailed, connect
from ..timing import Stopwatch
from ..toothpair import prepare_job, run_job, solve_command
from .file import Outputs, Study, StudyCase, StudyError
from .records import finished, store, study_json
from .results import write_results

#: a case that was running when its worker process died this often is recorded as failed
WORKER_DEATHS = 2
_SOLVE_LOCK = threading.Lock()  # gmsh keeps one global session per process


class StudyInterrupted(FegearError):
    """SIGTERM or SIGINT stopped the study; the finished cases (``finished``, None: not
    counted yet) are kept in the folder."""

    def __init__(self, signum: int, finished: int | None = None) -> None:
        self.signum, self.finished = signum, finished
        name = signal.Signals(signum).name
        if finished == 0:
            super().__init__(f"stopped by {name} before any case finished; nothing was kept")
        else:
            super().__init__(f"stopped by {name}; the finished cases are kept: run the same "
                             "command again to compute the rest")


@dataclass(frozen=True)
class StudyReport:
    """What a run did: cases in the study that run, found finished in the folder, computed now (ok
    and failed), and times (s): the whole run, the solves summed, the workers' start-up (from
    the first submission to the first case starting) and writing the table and plots; and the
    cases refused before anything ran."""

    cases: int
    found: int
    computed: int
    failed: int
    wall_s: float
    solve_s: float
    startup_s: float
    table_s: float
    files: dict
    refused: int = 0

    @property
    def overhead_per_case_s(self) -> float:
        """Runner time per computed case that is not a solve, the one-off start-up and the
        table excluded (with one worker: the runner's whole per-case cost)."""
        if not self.computed:
            return 0.0
        return (self.wall_s - self.table_s - self.startup_s - self.solve_s) / self.computed


def run_study(study: Study, out: str | Path, workers: int | None = None,
              scheduler: str | None = None, retry_failed: bool = False,
              progress: bool = True, on_start=None) -> StudyReport:
    """Run the missing cases of ``study`` into ``out``, then write the table and plots.
    With ``scheduler``, on that Dask cluster; else on ``workers`` local processes (default:
    one per core). ``on_start(found, todo)`` is called once the finished cases are known.
    Raises :class:`StudyInterrupted` on SIGTERM or SIGINT, after writing the table of the
    finished cases; stopped before it finished a case, it leaves ``out`` as it found it (a
    folder it made, its parents too, removed)."""
    watch = Stopwatch()
    # a bad address creates no output
    client = connect(scheduler, StudyError) if scheduler else None
    made = _missing(Path(out))
    try:
        out = prepare_dir(out)
        with _exclusive(out):
            return _run(study, out, workers, client, retry_failed, progress, on_start, watch)
    finally:
        if client is not None:
            client.close()
        for folder in made:   # deepest first; one that holds anything stays
            try:
                folder.rmdir()
            except OSError:
                break


def _run(study: Study, out: Path, workers: int | None, client, retry_failed: bool,
         progress: bool, on_start, watch: Stopwatch) -> StudyReport:
    running = out / "cases" / ".running"
    running.mkdir(parents=True, exist_ok=True)
    done = finished(study, out, retry_failed)
    solves: dict[str, StudyCase] = {}  # one per key: cases apart in allowables alone share it
    for c in study.cases:
        if c.key not in done:
            solves.setdefault(c.key, c)
    todo = list(solves.values())
    if on_start is not None:
        on_start(len(done), len(todo))
    code = code_version()
    stats = {"computed": 0, "failed": 0, "solve_s": 0.0, "first_start": None}
    # the workers' start-up is told by the first case's start (its record's, written in
    # another process, on another host with Dask): wall-clock time on both sides
    started = time.time()
    files, table_s, ended = {}, 0.0, False
    n = max(1, min(workers or os.cpu_count() or 1, len(todo)))
    try:
        with Supervisor(n, client, marks=running, retries=WORKER_DEATHS - 1) as tasks:
            results = _results(tasks, todo, study)
            bar = _progress(len(done) + len(todo), len(done), study.name, progress)
            with closing(results), bar:
                for case, record, files in results:
                    if record.get("code_version") not in (None, code):
                        record.update(status="failed", error=(
                            f"the worker ran other code ({record['code_version']}) than this "
                            f"study ({code}): install the same fegear on every worker"))
                        files = {}
                    if not stats["computed"]:
                        write_json(out / "study.json", study_json(study))
                    store(out, case, record, files)
                    stats["computed"] += 1
                    stats["failed"] += record["status"] != "ok"
                    stats["solve_s"] += record.get("solve_s") or 0.0
                    if stats["first_start"] is None:
                        stats["first_start"] = record["started_unix"]
                    bar.update(1)
                    bar.set_postfix(failed=stats["failed"], refresh=False)
        ended = True
    except StudyInterrupted as exc:
        raise StudyInterrupted(exc.signum, len(finished(study, out))) from None
    finally:
        _clear(running)
        # the table shows what is in the folder, also after an interruption; a run stopped before
        # it finished a case leaves the folder as it found it
        if ended or stats["computed"]:
            writing = Stopwatch()
            files = write_results(study, out)
            if files:
                write_json(out / "study.json", study_json(study))
            table_s = writing.s
    startup = 0.0 if stats["first_start"] is None else max(stats["first_start"] - started, 0.0)
    return StudyReport(cases=len(study.cases), found=len(done), computed=stats["computed"],
                       failed=stats["failed"], wall_s=watch.s,
                       solve_s=stats["solve_s"], startup_s=startup, table_s=table_s,
                       files=files, refused=len(study.refused))


def _missing(out: Path) -> list[Path]:
    """``out`` and those of its parents that do not exist yet, deepest first."""
    missing = []
    for folder in (out.absolute(), *out.absolute().parents):
        if folder.exists():
            break
        missing.append(folder)
    return missing


def _clear(running: Path) -> None:
    """Remove the run's markers (those of workers that were stopped while solving) and their
    folder, and ``cases/`` if no case is in it."""
    for mark in running.glob("*"):
        mark.unlink(missing_ok=True)
    for folder in (running, running.parent):
        try:
            folder.rmdir()
        except OSError:
            return


class _exclusive:
    """Within the block this process alone runs a study in ``out`` (an advisory lock on
    ``out/.lock``): a second run into the same directory is refused, not interleaved."""

    def __init__(self, out: Path) -> None:
        self.path = out / ".lock"

    def __enter__(self):
        import fcntl

        self.f = open(self.path, "a+")
        try:
            fcntl.flock(self.f, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            self.f.seek(0)
            holder = self.f.read().strip() or "?"
            self.f.close()
            raise StudyError(f"--out {str(self.path.parent)!r}: another study is running "
                             f"there (pid {holder}); wait for it or choose another --out"
                             ) from None
        if os.fstat(self.f.fileno()).st_ino != _inode(self.path):
            # the run before removed the file between our open and our lock: ours is stale
            self.f.close()
            return self.__enter__()
        self.f.seek(0)
        self.f.truncate()
        self.f.write(str(os.getpid()))
        self.f.flush()
        return self

    def __exit__(self, *exc):
        self.path.unlink(missing_ok=True)  # removed while still held, so no run takes it over
        self.f.close()  # closing releases the lock


def _inode(path: Path) -> int | None:
    try:
        return path.stat().st_ino
    except FileNotFoundError:
        return None


def run_case(key: str, values: dict, outputs: Outputs) -> tuple[dict, dict[str, bytes]]:
    """Solve one case (in a worker): its record and the bytes of its kept files. Never
    raises for a failing case: the record says ``failed`` and why."""
    watch = Stopwatch()
    # when it started, as a date: the study's start-up is counted from the first case's
    record = {"key": key, "status": "ok", "error": None, "inputs": values,
              "started_unix": time.time(), "host": socket.gethostname(), "pid": os.getpid()}
    files: dict[str, bytes] = {}
    try:
        with _SOLVE_LOCK, tempfile.TemporaryDirectory(prefix="fegear-case-") as tmp:
            keep = outputs.vtu or outputs.png or outputs.report
            result = run_job(prepare_job(values), Path(tmp) if keep else None,
                             fields=outputs.vtu, pictures=outputs.png or outputs.report,
                             report=solve_command(values) if outputs.report else None)
            # a report's pictures are in it: their files are kept only where asked for
            files = {p.name: p.read_bytes() for k, p in result.files.items()
                     if k != "summary" and (outputs.png or p.suffix != ".png")}
        try:
            json.dumps(result.summary, allow_nan=False)
            record.update(summary=result.summary, solve_s=result.solve_s)
        except ValueError:
            record.update(status="failed", error="the solve returned a non-finite value "
                          "(NaN or infinity) in its summary", solve_s=result.solve_s)
    except FegearError as exc:
        record.update(status="failed", error=f"{type(exc).__name__}: {exc}")
    except Exception as exc:  # a bug, not a user error: keep the traceback with the case
        record.update(status="failed", error=f"{type(exc).__name__}: {exc}",
                      traceback=traceback.format_exc())
    record.update(case_wall_s=watch.s, fegear=__version__,
                  code_version=code_version(), versions=library_versions(),
                  finished_utc=datetime.now(UTC).isoformat(timespec="seconds"))
    return record, files


def _results(tasks: Supervisor, todo: list[StudyCase], study: Study) -> Iterator:
    """The cases of ``todo`` solved on ``tasks``, each as it finishes: a case whose worker
    process died WORKER_DEATHS times while it ran, or that the Dask cluster lost, is recorded
    as failed. Raises :class:`StudyInterrupted` once SIGTERM or SIGINT stopped the run."""
    cases = {c.key: c for c in todo}
    for c in todo:
        tasks.submit(c.key, run_case, c.key, c.values, study.outputs)
    while not tasks.stopped and tasks.under_way:
        for o in tasks.ended():
            case = cases[o.name]
            if o.lost is None:
                record, files = o.value
            elif isinstance(o.lost, WorkerFailed):
                record, files = _died(case), {}
            else:   # the cluster lost it (KilledWorker …)
                record, files = {**_died(case), "error": f"{type(o.lost).__name__}: {o.lost}"}, {}
            yield case, record, files
    if tasks.stopped:
        raise StudyInterrupted(tasks.stopped)


def _died(case: StudyCase) -> dict:
    return {"key": case.key, "status": "failed", "inputs": case.values,
            "error": f"the worker process died {WORKER_DEATHS} times while solving this case "
                     "(out of memory? a crash in gmsh?)", "started_unix": time.time(),
            "case_wall_s": None, "fegear": __version__,
            "finished_utc": datetime.now(UTC).isoformat(timespec="seconds")}


def _progress(total: int, initial: int, name: str, enabled: bool):
    from tqdm import tqdm

    return tqdm(total=total, initial=initial, desc=name, unit="case", disable=not enabled,
                mininterval=1.0, dynamic_ncols=True)
