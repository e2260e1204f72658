"""Shared cases, built once per test session: the seed paper's baseline pair and its variants,
their exact gear 1, and the small solved cases that several test modules read."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

# BLAS and OpenMP on one thread in the tests and in the processes they start, read when numpy
# loads: the two test workers keep the two cores busy, and OpenBLAS's threads beside a busy
# process spin against it (fegear drive reducer's eigh took 35 s for 5 s on one thread)
for _threads in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ.setdefault(_threads, "1")

sys.path.insert(0, str(Path(__file__).parent))  # draws: a test helper
sys.path.insert(0, str(Path(__file__).parent / "geometry"))  # swept_reference, a test helper

import system  # noqa: E402  (a test helper, found on the path set above)


def pytest_collection_finish(session):
    """The system programs the collected tests ask for by fixture (``ccx``, ``chromium``) and
    miss are installed in the background while the other tests run (tests/system.py)."""
    if not session.config.option.collectonly:
        system.start_installs(sorted({name for item in session.items
                                      for name in getattr(item, "fixturenames", ())
                                      if name in system.PROGRAMS}))


#: the modules run first, longest first: each shares a costly fixture among its tests (the killed
#: study's three runs, 8-10 s; the 3D tooth's coarse influence, 8-12 s; the light pair's sector
#: solve, 5-6 s) or holds long runs of processes. xdist's workers take long runs of consecutive
#: tests at the start and two at a time at the end, where such a module's tests went to both
#: workers and each built its fixture (the light pair twice, the last one the run's last 6 s).
#: Those that ask for CalculiX or Chromium come last of them: on a first run their install has
#: had two minutes by then
FIRST = ("optimize/test_optimize.py", "study/test_study.py", "toothpair/analyses/test_samples.py",
         "toothpair/ring/test_phases.py", "toothpair/present/test_outputs.py",
         "toothpair/analyses/test_revolution.py", "study/test_cycle.py",
         "verify/test_tooth3d.py", "cli/test_profile_drawings.py",
         "toothpair/present/test_html_report.py", "verify/test_calculix.py")


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(items):
    """The modules of :data:`FIRST` first, in its order; every test's order within its module
    and the other modules' order kept (a stable sort)."""
    here = Path(__file__).parent
    rank = {name: k for k, name in enumerate(FIRST)}

    def first(item) -> int:
        try:
            return rank.get(item.path.relative_to(here).as_posix(), len(FIRST))
        except ValueError:   # a test outside this folder
            return len(FIRST)

    items.sort(key=first)


#: where fegear would keep its models for the user running the tests (FEGEAR_CACHE_DIR, else
#: $XDG_CACHE_HOME/fegear, else ~/.cache/fegear), read before the session changes anything
USER_CACHES = {Path(p).expanduser().absolute() for p in (
    os.environ.get("FEGEAR_CACHE_DIR") or None,
    Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "fegear") if p}


def cache_of(env) -> Path:
    """The model cache a fegear process started with the environment ``env`` would use (as
    :func:`fegear.toothpair.ring.cache.directory` finds it)."""
    if env.get("FEGEAR_CACHE_DIR"):
        return Path(env["FEGEAR_CACHE_DIR"]).expanduser().absolute()
    home = Path(env["HOME"]) if env.get("HOME") else Path.home()
    return Path(env.get("XDG_CACHE_HOME") or home / ".cache").absolute() / "fegear"


@pytest.fixture(scope="session", autouse=True)
def _model_cache_of_the_session(tmp_path_factory):
    """The model cache in a folder of this session's, off unless a test turns
    it on: the tests neither read what the user's runs kept nor write into their cache. The
    environment is set here, so the workers the tests spawn inherit it; a process started
    with an environment of its own must carry a cache that is not the user's (one copied from
    ``os.environ`` before this ran does not: :func:`_no_process_with_the_users_cache`). A run
    that made the user's cache folder fails at its end."""
    saved = {k: os.environ.get(k) for k in ("FEGEAR_CACHE", "FEGEAR_CACHE_DIR",
                                            "FEGEAR_CACHE_GB")}
    made = {p for p in USER_CACHES if not p.exists()}
    os.environ["FEGEAR_CACHE_DIR"] = str(tmp_path_factory.mktemp("fegear-cache"))
    os.environ.pop("FEGEAR_CACHE", None)
    os.environ.pop("FEGEAR_CACHE_GB", None)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(subprocess.Popen, "__init__", _checked_popen(subprocess.Popen.__init__))
        yield os.environ["FEGEAR_CACHE_DIR"]
    for k, v in saved.items():
        if v is None:
            os.environ.pop(k, None)
        else:
            os.environ[k] = v
    made = [str(p) for p in made if p.exists()]
    assert not made, f"the test run made the user's fegear cache {', '.join(made)}"


@pytest.fixture(scope="session", autouse=True)
def _strict_workers():
    """A task that fails in a worker process raises in the tests (in use, a warning is logged
    and the task runs again in the process that gave it): a change that stops something
    pickling must fail a test, not pass as lost speed. Set in the environment, so the
    processes the tests start inherit it."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("FEGEAR_STRICT_WORKERS", "1")
        yield


@pytest.fixture(autouse=True)
def _no_process_with_the_users_cache(_model_cache_of_the_session):
    """Each test leaves the session's cache in the environment (what the workers it and the
    tests after it start inherit)."""
    yield
    assert os.environ.get("FEGEAR_CACHE_DIR") == _model_cache_of_the_session, (
        "a test left FEGEAR_CACHE_DIR changed: "
        f"{os.environ.get('FEGEAR_CACHE_DIR')!r}, not the session's")


def _checked_popen(popen_init):
    """Popen.__init__ that refuses a child whose environment would have it use the user's
    fegear cache (an environment copied before the session set its own, say)."""
    def init(self, args, *rest, **kw):
        env = kw.get("env", rest[9] if len(rest) > 9 else None)   # Popen's 11th parameter
        if env is not None and cache_of(env) in USER_CACHES:
            raise AssertionError(f"{args!r} would be started with the user's fegear cache "
                                 f"{cache_of(env)}: build its environment from os.environ "
                                 "when it is started, not at import")
        popen_init(self, args, *rest, **kw)

    return init


@pytest.fixture(scope="session")
def nominal():
    """The seed paper's baseline design (m 2, z 45/44, h1 0.3, f1 0.15), unmodified."""
    from fegear.geometry import PairParameters

    return PairParameters()


@pytest.fixture(scope="session")
def conjugate():
    """The exact conjugate pair: no shift, no rotation, zero tip clearance (zero clearance)."""
    from fegear.geometry import PairParameters

    return PairParameters(shift=0.0, rotation=0.0, tip_clearance=0.0)


@pytest.fixture(scope="session")
def baseline():
    """The baseline pair as the seed paper builds it (§2): shift Δ1 0.016 mm, rotation
    Δ2 0.002 mm, the default tip clearance."""
    from fegear.geometry import PairParameters

    return PairParameters(shift=0.016, rotation=0.002)


@pytest.fixture(scope="session")
def conjugate_profile(conjugate):
    from fegear.geometry import Gear1Profile

    return Gear1Profile(conjugate)


@pytest.fixture(scope="session")
def baseline_profile(baseline):
    from fegear.geometry import Gear1Profile

    return Gear1Profile(baseline)


@pytest.fixture(scope="session")
def coarse_disks():
    """The Hertz case (two 10 mm disks, 1000 N over 5 mm) at 4 elements across b."""
    from fegear.verify import DiskCase, solve_disks

    return solve_disks(DiskCase(quality="coarse"))


@pytest.fixture(scope="session")
def sector_light_touch(baseline):
    """The baseline pair at 1 N·m, coarse, by the sector model: one or two teeth carry it
    (3 s)."""
    from fegear.verify.sector import SectorCase, solve_pair

    return solve_pair(SectorCase(baseline, torque=1.0, quality="coarse"))


@pytest.fixture(scope="session")
def baseline_ring():
    """The ring model of the baseline pair at ``coarse`` (any torque, any position)."""
    from fegear.geometry import PairParameters
    from fegear.toothpair import SolveCase
    from fegear.toothpair.ring import build_ring

    return build_ring(SolveCase(PairParameters(shift=0.016, rotation=0.002), quality="coarse"))
