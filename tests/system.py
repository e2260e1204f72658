"""System programs some tests need (CalculiX's ``ccx``), installed by the tests' set-up where
they can be: from Debian's packages, as root, with apt-get. Elsewhere the test is skipped with
the reason it could not be installed."""

import fcntl
import os
import shutil
import subprocess
from functools import cache
from pathlib import Path

#: a lock file that keeps two test workers from running apt-get at once
LOCK = Path("/tmp/fegear-tests-apt.lock")
TIMEOUT_S = 600


@cache
def installed(command: str, package: str) -> str | None:
    """The path of ``command``, installed from Debian's ``package`` first if it is missing;
    None (with the reason in :func:`why_not`) where it cannot be."""
    found = shutil.which(command)
    if found or _reason(command, package) is not None:
        return found
    with LOCK.open("w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)   # another worker may be installing it meanwhile
        if shutil.which(command) is None:
            env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
            for args in (["apt-get", "update", "-qq"],
                         ["apt-get", "install", "-y", "-qq", package]):
                done = subprocess.run(args, env=env, capture_output=True, text=True,
                                      timeout=TIMEOUT_S)
                if done.returncode != 0:
                    _FAILED[command] = (f"`{' '.join(args)}` failed: "
                                        f"{(done.stderr or done.stdout).strip()[-200:]}")
                    return None
    return shutil.which(command)


_FAILED: dict[str, str] = {}


def _reason(command: str, package: str) -> str | None:
    if shutil.which("apt-get") is None:
        return f"{command} is not installed and there is no apt-get to install {package}"
    if os.geteuid() != 0:
        return f"{command} is not installed (as root, the tests install Debian's {package})"
    return None


def why_not(command: str, package: str) -> str:
    """Why :func:`installed` found no ``command``."""
    return _FAILED.get(command) or _reason(command, package) or f"{command} is not installed"
