"""What the FE core's tests share: a coarse ring whose boundary elements are curved."""

import math

import numpy as np
import pytest

from fegear.fe.mesh import BodyGeometry, Segment, mesh_bodies


@pytest.fixture(scope="module")
def annulus():
    """A ring 6 < r < 10 mm meshed coarsely: its boundary elements are curved."""
    def circle(r, reverse=False):
        t = np.linspace(0.0, 2 * math.pi, 80)[:-1]
        t = t[::-1] if reverse else t
        return r * np.column_stack([np.cos(t), np.sin(t)])

    def snap(r):
        return lambda x: r * x / np.linalg.norm(x, axis=1)[:, None]

    outer = circle(10.0)
    inner = circle(6.0, reverse=True)
    geo = BodyGeometry("ring", (Segment("outer", np.vstack([outer, outer[:1]]), snap(10.0)),),
                       size=1.5, holes=((Segment("inner", np.vstack([inner, inner[:1]]),
                                                 snap(6.0)),),))
    return mesh_bodies([geo])[0].mesh
