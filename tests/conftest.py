import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from fegear.geometry.gear1 import Gear1Profile
from fegear.geometry.parameters import PairParameters

BASE = PairParameters()  # paper baseline m 2, z2 45, z1 44, h1 0.3, f1 0.15, no modification
CONJUGATE = PairParameters(shift=0.0, rotation=0.0, tip_relief=0.0)
MODIFIED = PairParameters(shift=0.016, rotation=0.002)  # paper §2, default tip relief


@pytest.fixture(scope="session")
def conjugate_profile():
    return Gear1Profile(CONJUGATE)


@pytest.fixture(scope="session")
def modified_profile():
    return Gear1Profile(MODIFIED)
