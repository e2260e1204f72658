"""Tip relief of gear 1: the working flanks cut back near the tip, as ISO 21771 tip relief.

On each flank of every tooth, material is removed along the normal of the conjugate profile by
δ(w), w the arc length of the conjugate flank from the start of the relief towards the tip
end. The tip end is where the conjugate flank met the tip trim (the kink the tip round breaks);
there δ equals the relief amount C. With t = w / L (L the extent):

* ``parabolic``: δ = C t²;
* ``arc``: the circle through the start (tangent to the flank) and (L, C) in the (w, δ) plane,
  δ = R − √(R² − w²), R = (L² + C²) / (2C);
* ``linear``: δ = C k (t − τ/2) with a quadratic run-in δ = C k t² / (2τ) over t < τ = 0.2,
  k = 1 / (1 − τ/2), so that its slope does not jump where it starts.

Every shape starts with δ = δ' = 0: the relieved flank joins the conjugate one with a continuous
tangent (G1); its curvature jumps there by δ'' (2C/L² for ``parabolic``). Past the tip end the
same formula goes on until the relieved flank meets the tip trim again, a little nearer the tooth
centre (C / tan of the kink angle along the flank); that new corner is what the tip round breaks.

The relieved flank is evaluated exactly like the conjugate one (point, unit normal, curvature),
so the clearance table, the profile files and the meshes see it without approximation: for a
curve q(s) with tangent T, outward normal n and curvature κ (dT/ds = −κ n, dn/ds = κ T), the
offset c = q − δ n has c' = (1 − δκ) T − δ' n and c'' = −(2δ'κ + δκ') T − ((1 − δκ)κ + δ'') n.
The arc length w(ξ) along the branch parameter is a Chebyshev series of the branch's speed,
integrated term by term (exact to rounding on the smooth flank).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import chebyshev as cheb

from ..errors import ParameterError
from .envelope import Branch, BranchPoints
from .roots import brentq

RUN_IN = 0.2             # the linear shape's quadratic run-in, as a fraction of the extent
CHEB_DEGREE = 64         # Chebyshev degree of the arc length over a relief zone
BEYOND = 0.5             # the zone goes on past the tip end by this fraction of the extent …
BEYOND_FLOOR = 0.05      # … plus this many modules
DKAPPA_STEP = 1e-6       # relative step (of the zone's ξ span) for dκ/dξ by central differences


@dataclass(frozen=True)
class ReliefShape:
    """δ(w) of a relief: amount ``amount`` (mm) at w = ``extent`` (mm), ``shape`` one of
    :data:`~fegear.geometry.parameters.SHAPES`."""

    amount: float
    extent: float
    shape: str

    def depth(self, w: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """δ, dδ/dw and d²δ/dw² (mm, 1, 1/mm) at arc lengths ``w`` from the start (0 before
        it)."""
        w = np.asarray(w, dtype=float)
        c, length = self.amount, self.extent
        t = np.maximum(w, 0.0) / length
        if self.shape == "parabolic":
            d, d1, d2 = c * t**2, 2 * c * t / length, np.full_like(t, 2 * c / length**2)
        elif self.shape == "arc":
            radius = (length**2 + c**2) / (2 * c)
            x = t * length
            root = np.sqrt(radius**2 - x**2)
            d, d1, d2 = x**2 / (radius + root), x / root, radius**2 / root**3
        else:
            k = 1.0 / (1.0 - 0.5 * RUN_IN)
            run = t < RUN_IN
            d = np.where(run, c * k * t**2 / (2 * RUN_IN), c * k * (t - 0.5 * RUN_IN))
            d1 = np.where(run, c * k * t / (RUN_IN * length), c * k / length)
            d2 = np.where(run, c * k / (RUN_IN * length**2), 0.0)
        before = w <= 0.0
        return (np.where(before, 0.0, d), np.where(before, 0.0, d1), np.where(before, 0.0, d2))


@dataclass(frozen=True)
class ReliefZone:
    """Where a relief acts on one flank, in the branch parameter ξ: from ``start`` (w = 0)
    through the tip end ``end`` (w = L) to ``stop`` (beyond which δ stays at its value
    there); its δ(w) ``shape``; and w(ξ) as a Chebyshev series ``arc`` on [lo, hi]."""

    shape: ReliefShape
    start: float
    end: float
    stop: float
    lo: float
    hi: float
    arc: np.ndarray

    def arc_length(self, xi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """w (mm) at ``xi`` (< 0 before the start, held beyond the stop) and whether each is
        beyond the stop."""
        toward = math.copysign(1.0, self.stop - self.start)
        bounds = (self.lo, self.stop) if toward > 0 else (self.stop, self.hi)
        beyond = toward * (xi - self.stop) > 0
        return cheb.chebval(_unit(np.clip(xi, *bounds), self.lo, self.hi), self.arc), beyond

    def depth(self, xi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """δ, dδ/dw, d²δ/dw² at ``xi`` (held beyond the stop, 0 before the start) and the
        direction of ξ towards the tip."""
        toward = math.copysign(1.0, self.stop - self.start)
        w, beyond = self.arc_length(xi)
        d, d1, d2 = self.shape.depth(w)
        return d, np.where(beyond, 0.0, d1), np.where(beyond, 0.0, d2), toward


class RelievedBranch:
    """A generating branch with tip relief on its flank ``zones``: the same parameter ξ, the
    points moved inward along the normal by δ (module docstring). Other attributes are the
    branch's."""

    def __init__(self, branch: Branch, zones: tuple[ReliefZone, ...]):
        self.branch = branch
        self.zones = zones

    def __getattr__(self, name):
        return getattr(self.branch, name)

    def depth(self, xi: np.ndarray) -> np.ndarray:
        """δ (mm) at branch parameters ``xi`` (0 outside the zones)."""
        return self._depth(np.atleast_1d(np.asarray(xi, dtype=float)))[0]

    def _depth(self, xi):
        d, d1, d2, toward = (np.zeros_like(xi) for _ in range(4))
        for z in self.zones:     # the zones lie on either side of the tooth space's middle
            dz, dz1, dz2, sign = z.depth(xi)
            hit = (dz > 0) | (dz2 > 0)    # just past the start δ can round to 0, δ'' not
            d[hit], d1[hit], d2[hit], toward[hit] = dz[hit], dz1[hit], dz2[hit], sign
        return d, d1, d2, toward

    def evaluate(self, xi: np.ndarray) -> BranchPoints:
        """The relieved branch's points, tangents, normals and curvature (exact)."""
        xi = np.atleast_1d(np.asarray(xi, dtype=float))
        base = self.branch.evaluate(xi)
        d, d_w, d_ww, toward = self._depth(xi)
        moved = np.flatnonzero(toward != 0)
        if len(moved) == 0:
            return base
        x = xi[moved]
        sigma = base.speed[moved]
        T, n, kappa = base.tangent[moved], base.normal[moved], base.kappa[moved]
        h = DKAPPA_STEP * max(abs(z.stop - z.start) for z in self.zones)
        ends = self.branch.evaluate(np.concatenate([x - h, x + h]))
        dkappa = (ends.kappa[len(x):] - ends.kappa[:len(x)]) / (2 * h) / sigma   # dκ/ds
        # s runs with ξ; w runs towards the tip: dw/ds = toward · sign σ
        eta = toward[moved] * np.sign(sigma)
        dd, d2 = eta * d_w[moved], d_ww[moved]
        dm = d[moved]
        along = 1.0 - dm * kappa
        c1 = along[:, None] * T - dd[:, None] * n
        c2 = (-(2 * dd * kappa + dm * dkappa))[:, None] * T - (along * kappa + d2)[:, None] * n
        size = np.hypot(c1[:, 0], c1[:, 1])
        Tc = c1 / size[:, None]
        turn = np.sign(T[:, 0] * n[:, 1] - T[:, 1] * n[:, 0])   # n = turn · (T turned +90°)
        nc = turn[:, None] * np.column_stack([-Tc[:, 1], Tc[:, 0]])
        fields = {f: getattr(base, f).copy() for f in ("q", "tangent", "normal", "kappa",
                                                       "speed")}
        fields["q"][moved] = base.q[moved] - dm[:, None] * n
        fields["tangent"][moved] = Tc
        fields["normal"][moved] = nc
        fields["kappa"][moved] = -np.einsum("ij,ij->i", c2, nc) / size**2
        fields["speed"][moved] = sigma * size
        return BranchPoints(xi=base.xi, beta=base.beta, disc=base.disc, **fields)


def _unit(x, a, b):
    return (2.0 * x - (a + b)) / (b - a)


def relief_zones(branch: Branch, tip_ends: list[tuple[float, float]], amount: float,
                 extent: float | None, shape: str, module: float,
                 start_radius: float | None = None) -> tuple[ReliefZone, ...]:
    """The zones of a relief of ``amount`` (mm) on ``branch``: one per flank, given as (ξ at
    the tip end, ξ at the flank's root end). The relief reaches ``extent`` (mm) along the flank
    from the tip end, or down to ``start_radius`` (mm) if that is given."""
    zones = []
    for end, root in tip_ends:
        toward = math.copysign(1.0, end - root)       # ξ direction towards the tip
        along = _arc_length(branch, root, end, toward)[1]
        flank = along(end) - along(root)
        if start_radius is not None:
            start = _radius_point(branch, root, end, start_radius)
            if start is None:
                r = branch.evaluate(np.array([root, end])).radius
                raise ParameterError("relief_start", start_radius,
                                     f"{min(r):.6g} < relief-start < {max(r):.6g} mm (the "
                                     "working flank's radii)")
            length = along(end) - along(start)
        else:
            length = extent
            if not 0.0 < length < flank:
                raise ParameterError("relief_extent", length,
                                     f"0 < relief-extent < {flank:.4g} mm (the working flank "
                                     "from root to tip end)")
            start = brentq(_short_of(along, end, length), root, end, xtol=1e-15, rtol=1e-15)
        stop = _past(branch, end, toward, BEYOND * length + BEYOND_FLOOR * module)
        arc, along = _arc_length(branch, root, stop, toward)
        arc[0] -= along(start)          # w = 0 at the start
        lo, hi = min(root, stop), max(root, stop)
        zones.append(ReliefZone(ReliefShape(amount, length, shape), float(start), float(end),
                                float(stop), lo, hi, arc))
    return tuple(zones)


def _arc_length(branch: Branch, a: float, b: float, toward: float):
    """Arc length along ``branch`` between ξ = a and b as a Chebyshev series of the unit
    variable on [min, max] (|σ| fitted at Chebyshev points and integrated), growing in ξ
    direction ``toward``; and the function evaluating it at one ξ."""
    lo, hi = min(a, b), max(a, b)
    nodes = np.cos(np.pi * (np.arange(CHEB_DEGREE + 1) + 0.5) / (CHEB_DEGREE + 1))
    speed = np.abs(branch.evaluate(0.5 * (lo + hi) + 0.5 * (hi - lo) * nodes).speed)
    series = toward * 0.5 * (hi - lo) * cheb.chebint(cheb.chebfit(nodes, speed, CHEB_DEGREE))

    def along(x: float) -> float:
        return float(cheb.chebval(_unit(x, lo, hi), series))

    return series, along


def _short_of(along, end: float, length: float):
    """The function whose root is the point ``length`` (mm) before ``end`` along the flank."""
    return lambda x: along(end) - along(x) - length


def _past(branch: Branch, end: float, toward: float, length: float) -> float:
    """ξ a length ``length`` (mm) along the branch past ``end`` in direction ``toward``, or
    short of that where the branch ends first: at a fold (a stretch of gear 2 with no
    conjugate point) or a cusp, where its speed changes sign."""
    speed = abs(float(branch.evaluate(np.array([end])).speed[0]))
    stop = end + toward * length / max(speed, 1e-12)
    xi = np.linspace(end, stop, 65)
    ev = branch.evaluate(xi)
    live = (ev.disc > 0) & (np.sign(ev.speed) == np.sign(ev.speed[0]))
    if live.all():
        return stop
    k = int(np.argmin(live))          # the first sample past the branch's end
    lo, hi = xi[k - 1], xi[k]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        e = branch.evaluate(np.array([mid]))
        ok = e.disc[0] > 0 and np.sign(e.speed[0]) == np.sign(ev.speed[0])
        lo, hi = (mid, hi) if ok else (lo, mid)
    return float(lo)


def _radius_point(branch: Branch, root: float, end: float, radius: float) -> float | None:
    """ξ between ``root`` and ``end`` where the branch's radius is ``radius`` (None if
    outside)."""
    def f(x):
        return float(branch.evaluate(np.array([x])).radius[0]) - radius

    fa, fb = f(root), f(end)
    if fa * fb >= 0:
        return None
    return brentq(f, root, end, xtol=1e-15, rtol=1e-15)
