"""System programs some tests need (CalculiX's ``ccx``, Chromium), installed by the tests' set-up
where they can be: from Debian's packages, as root, with apt-get. Elsewhere the test is skipped with
the reason it could not be installed.

A test asks for one by a fixture of the program's name (``ccx``, ``chromium``). A run whose
collected tests ask for missing ones starts installing them all at once, in the background, in one
apt-get call (:func:`start_installs`, from conftest.py), so that it overlaps the tests that need
nothing (a first ``make test`` took 2.5 min longer than the next, the installs in the tests'
set-up one after the other; both at once, 12 s on a machine with a near mirror), and a test that
needs one waits for it in :func:`installed`.

Run as a script, ``python tests/system.py start PROGRAM...`` starts that install (``make test``
does, before it builds .venv); ``python system.py FD PACKAGE...`` is the install itself, holding
the lock it was handed as file descriptor FD."""

import fcntl
import os
import shutil
import subprocess
import sys
import time
from functools import cache
from pathlib import Path

#: a lock file held by whoever runs apt-get for the tests (a test worker, or the background
#: install a run started), across workers and runs: a program found while its install still ran
#: failed to start (ccx exited 127: the BLAS it links was unpacked, not yet set up)
LOCK = Path("/tmp/fegear-tests-apt.lock")
#: what each apt-get step may take (s)
TIMEOUT_S = 600
#: the background install's log: what it ran, how long it took, how it ended
LOG = Path("/tmp/fegear-tests-apt.log")

#: each program the tests' fixtures name: the commands that would do, the Debian package that
#: installs the first
PROGRAMS = {
    "ccx": (("ccx",), "calculix-ccx"),
    "chromium": (("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"),
                 "chromium"),
}

_FAILED: dict[str, str] = {}
#: the background install this process started (kept so that it is not reaped as garbage)
_STARTED: list[subprocess.Popen] = []


def which(program: str) -> str | None:
    """The path of the first of ``program``'s commands on the PATH, else None."""
    return next(filter(None, map(shutil.which, PROGRAMS[program][0])), None)


@cache
def installed(program: str) -> str | None:
    """The path of ``program`` (a name of :data:`PROGRAMS`), installed from its Debian package
    first if it is missing; None (with the reason in :func:`why_not`) where it cannot be. An
    install under way (the background one, another worker's, another run's) is waited for."""
    if _reason(program) is not None:
        return which(program)
    with LOCK.open("a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if which(program) is None:
            failed = apt_get([PROGRAMS[program][1]])
            if failed:
                _FAILED[program] = failed
                return None
    return which(program)


def apt_get(packages: list[str]) -> str | None:
    """Install Debian's ``packages`` in one call after one ``apt-get update``: None, else what
    failed. Without the packages they recommend (chromium's pulled in 116 packages, avahi, samba
    and printer set-up among them; headless, it needs none of them)."""
    env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
    for args in (["apt-get", "update", "-qq"],
                 ["apt-get", "install", "-y", "-qq", "--no-install-recommends", *packages]):
        try:
            done = subprocess.run(args, env=env, capture_output=True, text=True,
                                  timeout=TIMEOUT_S)
        except subprocess.TimeoutExpired:
            return f"`{' '.join(args)}` did not finish in {TIMEOUT_S} s"
        if done.returncode != 0:
            return (f"`{' '.join(args)}` failed: "
                    f"{(done.stderr or done.stdout).strip()[-200:]}")
    return None


def start_installs(programs) -> None:
    """Start installing those of ``programs`` that are missing, in the background, in one
    apt-get call, holding :data:`LOCK` until it ends (the tests that need one wait for it; the
    others run meanwhile). Nothing where nothing is missing, the tests cannot install (not root,
    no apt-get) or another worker or run holds the lock (it is installing)."""
    missing = [p for p in programs if which(p) is None and _reason(p) is None]
    if not missing:
        return
    lock = LOCK.open("a")
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        lock.close()
        return
    with lock:      # the child holds the lock from here until it ends
        fd = lock.fileno()
        # a session of its own: a Ctrl-C of the tests does not stop dpkg halfway
        _STARTED.append(subprocess.Popen(
            [sys.executable, __file__, str(fd), *(PROGRAMS[p][1] for p in missing)],
            pass_fds=(fd,), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL, start_new_session=True))


def _reason(program: str) -> str | None:
    command, package = PROGRAMS[program][0][0], PROGRAMS[program][1]
    if shutil.which("apt-get") is None:
        return f"{command} is not installed and there is no apt-get to install {package}"
    if os.geteuid() != 0:
        return f"{command} is not installed (as root, the tests install Debian's {package})"
    return None


def why_not(program: str) -> str:
    """Why :func:`installed` found no ``program``."""
    return _FAILED.get(program) or _reason(program) or f"{PROGRAMS[program][0][0]} is not installed"


if __name__ == "__main__":
    if sys.argv[1] == "start":
        # `make test`, before it builds .venv (this file needs Python alone): start installing
        # the programs named after "start"
        start_installs(sys.argv[2:])
    else:
        # the background install: argv[1] is the lock's descriptor, held until this ends
        t0 = time.perf_counter()
        failed = apt_get(sys.argv[2:])
        with LOG.open("a") as log:
            log.write(f"{time.strftime('%Y-%m-%d %H:%M:%S')} apt-get install "
                      f"{' '.join(sys.argv[2:])}: {failed or 'installed'} in "
                      f"{time.perf_counter() - t0:.1f} s\n")
