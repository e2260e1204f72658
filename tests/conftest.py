"""Shared cases, built once per test session: the seed paper's baseline pair and its variants,
their exact gear 1, and the small solved cases that several test modules read."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))  # draws: a test helper
sys.path.insert(0, str(Path(__file__).parent / "geometry"))  # swept_reference, a test helper


@pytest.fixture(scope="session", autouse=True)
def _disk_cache_of_the_session(tmp_path_factory):
    """The disk cache of ring models in a folder of this session's, off unless a test turns
    it on: the tests neither read what the user's runs kept nor write into their cache. The
    environment is set here, so the workers the tests spawn inherit it."""
    import os

    saved = {k: os.environ.get(k) for k in ("FEGEAR_CACHE", "FEGEAR_CACHE_DIR",
                                            "FEGEAR_CACHE_GB")}
    os.environ["FEGEAR_CACHE_DIR"] = str(tmp_path_factory.mktemp("fegear-cache"))
    os.environ.pop("FEGEAR_CACHE", None)
    os.environ.pop("FEGEAR_CACHE_GB", None)
    yield
    for k, v in saved.items():
        if v is None:
            os.environ.pop(k, None)
        else:
            os.environ[k] = v


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
