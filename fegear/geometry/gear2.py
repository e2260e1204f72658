"""Gear 2: the 4th-order compound cycloid of paper eq. (11), evaluated exactly.

In gear 2's own frame the curve, with parameter ξ, is written in the rotating basis
``ê_r = (cos ξ, sin ξ)``, ``t̂ = (-sin ξ, cos ξ)`` as

    P(ξ) = u(ξ) ê_r + w(ξ) t̂,
    u = r0 - 2 e1 cos(z ξ),   w = 2 e2 sin(2 z ξ) - 2 Δ2 sin(z ξ),

which expands exactly to eq. (11). The curve runs counter-clockwise; gear-2 material lies
outside it. ``ξ = 0`` is the middle of a tooth tip (radius ``r0 - 2 e1``); ``ξ = π/z2`` the
middle of a tooth space (radius ``r0 + 2 e1``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import GeometryError
from .parameters import PairParameters

#: a Newton iteration in ξ is done within this many ulps of ξ (an absolute 1e-15 is below one
#: ulp for |ξ| > 4.5, where the residual θ(ξ) − θ only rounds)
_ULPS = 4


def _turned(c: np.ndarray, s: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """cos and sin of (a + kπ/2), k = 1 … 3, from c = cos a and s = sin a."""
    return (-s, c) if k == 1 else (-c, -s) if k == 2 else (s, -c)


@dataclass(frozen=True)
class Cycloid:
    """Compound cycloid with ``z`` lobes (lengths in mm).

    Attributes:
        r0: pitch radius.
        e1: first crank length.
        e2: second crank length.
        z: number of teeth.
        d2: rotation modification Δ2 (0 for the nominal gear).
    """

    r0: float
    e1: float
    e2: float
    z: int
    d2: float = 0.0

    # --- the scalar functions u, w and their derivatives --------------------------------
    def _uw(self, xi: np.ndarray, order: int) -> list[tuple[np.ndarray, np.ndarray]]:
        z, e1, e2, d2 = self.z, self.e1, self.e2, self.d2
        c1, s1 = np.cos(z * xi), np.sin(z * xi)
        c2, s2 = np.cos(2 * z * xi), np.sin(2 * z * xi)
        out = [(self.r0 - 2 * e1 * c1, 2 * e2 * s2 - 2 * d2 * s1)]
        # k-th derivative of cos(zξ) is z^k cos(zξ + kπ/2), of sin(zξ) z^k sin(zξ + kπ/2): the
        # quarter turns cycle through ±cos, ±sin (four evaluations of the trigonometric
        # functions for any order, not three more per order)
        for k in range(1, order + 1):
            ck1, sk1 = _turned(c1, s1, k)
            sk2 = _turned(c2, s2, k)[1]
            out.append((-2 * e1 * z**k * ck1, 2 * e2 * (2 * z) ** k * sk2 - 2 * d2 * z**k * sk1))
        return out

    def derivatives(self, xi: np.ndarray, order: int = 2) -> list[np.ndarray]:
        """Return ``[P, P', ..., P^(order)]`` (order ≤ 3) at ``xi``, each an (n, 2) array.

        With ``d/dξ (a ê_r + b t̂) = (a' - b) ê_r + (b' + a) t̂`` applied to the closed-form
        derivatives of u and w, every derivative is exact.
        """
        return [np.column_stack(xy) for xy in self.components(xi, order)]

    def components(self, xi: np.ndarray, order: int = 2) -> list[tuple[np.ndarray, np.ndarray]]:
        """:meth:`derivatives` as (x, y) pairs of (n,) arrays, the same numbers: what the
        envelope (:meth:`~.envelope.Branch.evaluate`, called hundreds of times a profile on a
        few points) reads without stacking and slicing columns."""
        if not 0 <= order <= 3:
            raise ValueError("order must be 0..3")
        xi = np.atleast_1d(np.asarray(xi, dtype=float))
        c, s = np.cos(xi), np.sin(xi)
        return [(a * c - b * s, a * s + b * c) for a, b in self._rotating(xi, order)]

    def _rotating(self, xi: np.ndarray, order: int) -> list[tuple[np.ndarray, np.ndarray]]:
        """The ê_r and t̂ components of ``[P, P', ..., P^(order)]`` at ``xi`` (order ≤ 3)."""
        uw = self._uw(xi, order)
        out = [uw[0]]
        if order >= 1:
            (u, w), (u1, w1) = uw[:2]
            out.append((u1 - w, w1 + u))
        if order >= 2:
            u2, w2 = uw[2]
            out.append((u2 - 2 * w1 - u, w2 + 2 * u1 - w))
        if order >= 3:
            u3, w3 = uw[3]
            out.append((u3 - 3 * w2 - 3 * u1 + w, w3 + 3 * u2 - 3 * w1 - u))
        return out

    # --- point, tangent, normal, curvature ----------------------------------------------
    def point(self, xi: np.ndarray) -> np.ndarray:
        """Curve points (n, 2)."""
        return self.derivatives(xi, 0)[0]

    def frame(self, xi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Return point, unit tangent, unit gap-side normal and signed curvature at ``xi``.

        The normal ``n = J t`` (t rotated +90°) points away from gear-2 material (into the
        tooth gap, towards the centre). The curvature ``κ = (P' × P'') / |P'|³`` is positive
        where the curve turns towards ``n``.
        """
        p, d1, d2 = self.derivatives(xi, 2)
        speed = np.hypot(d1[:, 0], d1[:, 1])
        t = d1 / speed[:, None]
        n = np.stack([-t[:, 1], t[:, 0]], axis=-1)
        kappa = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / speed**3
        return p, t, n, kappa

    def curvature_rate(self, xi: np.ndarray) -> np.ndarray:
        """The signed curvature's rate with arc length, dκ/ds (1/mm²), at ``xi``: with
        κ = (P' × P'') / |P'|³, dκ/dξ = (P' × P''') / |P'|³ − 3 κ (P' · P'') / |P'|², and
        ds/dξ = |P'|."""
        _, d1, d2, d3 = self.derivatives(xi, 3)
        speed = np.hypot(d1[:, 0], d1[:, 1])
        kappa = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / speed**3
        cross3 = (d1[:, 0] * d3[:, 1] - d1[:, 1] * d3[:, 0]) / speed**3
        return (cross3 - 3.0 * kappa * np.einsum("ij,ij->i", d1, d2) / speed**2) / speed

    def curvature_radius(self, xi: np.ndarray) -> np.ndarray:
        """Signed curvature radius [mm]: > 0 where gear 2's surface is convex, < 0 concave.

        Gear-2 material lies on the ``-n`` side, so the surface is convex where the curve
        turns away from ``n`` (κ < 0).
        """
        _, _, _, kappa = self.frame(xi)
        with np.errstate(divide="ignore"):
            return -1.0 / kappa

    def polar_rate(self, xi: np.ndarray) -> np.ndarray:
        """``P × P'`` = |P|² dθ/dξ; positive everywhere iff the curve is star-shaped."""
        p, d1 = self.derivatives(xi, 1)
        return p[:, 0] * d1[:, 1] - p[:, 1] * d1[:, 0]

    def star_shaped(self, samples: int = 2048) -> bool:
        """Whether the curve is star-shaped about its centre (``P × P' > 0`` at ``samples``
        points of one tooth pitch): what the polar form below needs."""
        xi = np.linspace(-np.pi / self.z, np.pi / self.z, samples + 1)
        return bool(self.polar_rate(xi).min() > 0.0)

    # --- polar form ----------------------------------------------------------------------
    def polar_angle(self, xi: np.ndarray) -> np.ndarray:
        """Continuous polar angle θ(ξ) = ξ + atan2(w, u) of the point (valid while u > 0)."""
        xi = np.asarray(xi, dtype=float)
        u, w = self._uw(np.atleast_1d(xi), 0)[0]
        return np.atleast_1d(xi) + np.arctan2(w, u)

    def xi_at_angle(self, theta: np.ndarray, tol: float = 1e-15,
                    tabled: bool = True) -> np.ndarray:
        """Invert θ(ξ) (increasing on a star-shaped curve): Newton's method inside the bracket
        ``|θ − ξ| <= atan(|w|max / u_min)``, a bisection where a step leaves it. A point is
        done when its step or bracket is within ``tol`` or a few ulps of ξ; only the points
        not done are iterated again. Newton starts from a table of one pitch (three steps),
        or without ``tabled`` from ξ = θ (six). What a mesh is made from (the templates' and
        submodels' geometry and sizes) is inverted without it: a gmsh mesh is not continuous
        in its inputs, and the table's ulp in ξ moved a `fine` gear-2 template's nodes by
        1e-8 mm and the baseline's edge pressure with them by 0.16 %."""
        theta = np.atleast_1d(np.asarray(theta, dtype=float))
        reach = np.arctan2(2 * self.e2 + 2 * abs(self.d2), self.r0 - 2 * self.e1) + 1e-12
        lo, hi = theta - reach, theta + reach
        xi = np.clip(self._polar_start(theta), lo, hi) if tabled else theta.copy()
        todo = np.arange(theta.size)
        for _ in range(100):
            x, t, a, b = xi[todo], theta[todo], lo[todo], hi[todo]
            (u, w), (du, dw) = self._uw(x, 1)
            f = x + np.arctan2(w, u) - t
            b = np.where(f > 0, x, b)
            a = np.where(f > 0, a, x)
            df = 1.0 + (u * dw - w * du) / (u * u + w * w)
            with np.errstate(divide="ignore", invalid="ignore"):
                new = x - f / df
            # a step that lands on the bracket's end is kept: a root hit exactly (f = 0) ends its
            # own bracket, and bisecting there sent ξ away again (47 iterations, not 6)
            new = np.where((new >= a) & (new <= b), new, 0.5 * (a + b))
            step = np.abs(new - x)
            xi[todo], lo[todo], hi[todo] = new, a, b
            floor = np.maximum(tol, _ULPS * np.spacing(np.abs(new)))
            todo = todo[(step > floor) & (b - a > floor)]
            if todo.size == 0:
                return xi
        if np.max(step) > 1e-12:
            raise GeometryError("gear-2 polar inversion did not converge")
        return xi

    def _polar_start(self, theta: np.ndarray) -> np.ndarray:
        """ξ at polar angles ``theta`` read from a table of one pitch (Newton's start: three
        steps from it, six from ξ = θ)."""
        table = _POLAR_TABLES.get(self)
        if table is None:
            if len(_POLAR_TABLES) >= POLAR_TABLES:   # a design search's many curves
                _POLAR_TABLES.clear()
            xi = np.linspace(-np.pi / self.z, np.pi / self.z, POLAR_TABLE + 1)
            table = _POLAR_TABLES[self] = (self.polar_angle(xi), xi)
        pitch = 2.0 * np.pi / self.z
        k = np.round(theta / pitch)
        return np.interp(theta - k * pitch, *table) + k * pitch

    def radius_at_angle(self, theta: np.ndarray, tabled: bool = True) -> np.ndarray:
        """Exact radius R2(θ) of the curve at polar angle θ (star-shaped curves only;
        ``tabled``: :meth:`xi_at_angle`)."""
        xi = self.xi_at_angle(theta, tabled=tabled)
        u, w = self._uw(xi, 0)[0]
        return np.hypot(u, w)

    def signed_distance(self, y: np.ndarray) -> np.ndarray:
        """Exact signed distance [mm] of points ``y`` (n, 2) to the curve; > 0 in the gap."""
        return self.closest(y)[2]

    def closest(self, y: np.ndarray, tabled: bool = True, start: np.ndarray | None = None
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Foot points, unit gap-side normals and signed distances (> 0 in the gap) of ``y``
        (:meth:`feet`, :meth:`at_feet`)."""
        y = np.atleast_2d(np.asarray(y, dtype=float))
        return self.at_feet(y, self.feet(y, tabled, start))

    def feet(self, y: np.ndarray, tabled: bool = True, start: np.ndarray | None = None
             ) -> np.ndarray:
        """The parameters ξ of the feet of ``y`` (n, 2) on the curve.

        Newton's method on the foot-point condition ``(P(ξ) - y) · P'(ξ) = 0``, started at
        ``start`` where given and finite (a foot found before for a point moved a little: two
        steps, not the polar start's three and four), else at the point of the curve with the
        same polar angle (meant for points within a fraction of a tooth of the curve;
        ``tabled``: :meth:`xi_at_angle`).
        """
        y = np.atleast_2d(np.asarray(y, dtype=float))
        if start is None:
            xi = self.xi_at_angle(np.arctan2(y[:, 1], y[:, 0]), tabled=tabled)
        else:
            xi = np.array(start, dtype=float)
            new = ~np.isfinite(xi)
            if new.any():
                xi[new] = self.xi_at_angle(np.arctan2(y[new, 1], y[new, 0]), tabled=tabled)
        limit = 0.25 * np.pi / self.z
        todo = np.arange(len(y))
        for _ in range(50):
            x = xi[todo]
            # in the rotating basis at ξ (ê_r, t̂), where P and its derivatives are written
            c, s = np.cos(x), np.sin(x)
            yt = y[todo]
            (a0, b0), (a1, b1), (a2, b2) = self._rotating(x, 2)
            r_r = a0 - (yt[:, 0] * c + yt[:, 1] * s)
            r_t = b0 - (yt[:, 1] * c - yt[:, 0] * s)
            f = r_r * a1 + r_t * b1
            speed2 = a1 * a1 + b1 * b1
            df = speed2 + r_r * a2 + r_t * b2
            # beyond the centre of curvature (d κ near 1 or more) Newton heads for the farthest
            # point and cycled there for all 50 steps (points 2 mm off a tooth tip): a
            # Gauss-Newton step instead, downhill for the distance
            df = np.where(df > 0.1 * speed2, df, speed2)
            step = np.clip(f / df, -limit, limit)
            xi[todo] = x - step
            todo = todo[np.abs(step) > np.maximum(1e-15, _ULPS * np.spacing(np.abs(x)))]
            if todo.size == 0:
                break
        return xi

    def at_feet(self, y: np.ndarray, xi: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Foot points, unit gap-side normals and signed distances of ``y`` (n, 2) whose feet
        are at parameters ``xi`` (:meth:`feet`)."""
        p, d1 = self.derivatives(xi, 1)
        t = d1 / np.hypot(d1[:, 0], d1[:, 1])[:, None]
        n = np.stack([-t[:, 1], t[:, 0]], axis=-1)
        return p, n, np.einsum("ij,ij->i", y - p, n)

    def polyline(self, chord_error: float, xi0: float = 0.0, xi1: float | None = None
                 ) -> np.ndarray:
        """Points on [xi0, xi1] (default: the closed curve), chord error <= ``chord_error``."""
        if xi1 is None:
            xi1 = xi0 + 2 * np.pi
        xi = adaptive_parameters(lambda s: self.derivatives(s, 2), xi0, xi1, chord_error)
        return self.point(xi)


#: samples of one pitch in the table that starts the polar inversion; tables kept at most
POLAR_TABLE = 256
POLAR_TABLES = 64
_POLAR_TABLES: dict = {}

#: a polyline longer than this is refused: the curve has a cusp (random admissible-looking
#: pairs such as m 6, z 9/8, h1 0.5, f1 0, rotation 0.5 asked for 22 million points)
MAX_POLYLINE_POINTS = 2_000_000


def adaptive_parameters(derivs, a: float, b: float, chord_error: float,
                        n0: int = 64) -> np.ndarray:
    """Parameters on ``[a, b]`` whose chords deviate from the curve by at most ``chord_error``.

    The sagitta of a chord of length L on a curve of curvature κ is ``κ L² / 8``; the
    parameter step is chosen from the largest curvature over each coarse interval, so the bound
    holds with the curvature sampled at ``n0`` points plus their neighbours.
    """
    if not chord_error > 0:
        raise ValueError("chord_error must be > 0")
    s = np.linspace(a, b, n0 + 1)
    pts, total = [], 0
    for s0, s1 in zip(s[:-1], s[1:]):
        probe = np.linspace(s0, s1, 9)
        _, d1, d2 = derivs(probe)
        speed = np.hypot(d1[:, 0], d1[:, 1])
        cross = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
        with np.errstate(divide="ignore", invalid="ignore"):
            kappa = cross / speed**3
        if not np.isfinite(kappa).all():  # speed 0: a singular point, curvature unbounded
            raise GeometryError(
                f"the curve has a cusp (a singular point at parameter "
                f"{probe[~np.isfinite(kappa)][0]:.6g}): no polyline of chord error "
                f"{chord_error:g} mm follows it")
        # arc length per parameter unit and curvature, worst case over the interval
        kmax = 1.5 * kappa.max() + 1e-12
        seg = np.sqrt(8.0 * chord_error / kmax)
        n = max(1, int(np.ceil(speed.max() * (s1 - s0) / seg)))
        total += n
        if total > MAX_POLYLINE_POINTS:
            raise GeometryError(
                f"a polyline with chord error {chord_error:g} mm needs more than "
                f"{MAX_POLYLINE_POINTS} points: the curve has a cusp or a near-cusp "
                f"(curvature {kappa.max():.3g} /mm, speed {speed.min():.3g} mm/rad)")
        pts.append(np.linspace(s0, s1, n, endpoint=False))
    pts.append(np.array([b]))
    return np.concatenate(pts)


def gear2_tooth(xi, z2: int) -> np.ndarray:
    """The gear-2 tooth (0 … z2 − 1) whose flanks hold the curve's points at parameters
    ``xi`` (rad): tooth k spans a pitch about ξ = 2π k / z2."""
    return np.mod(np.round(np.asarray(xi) * z2 / (2 * np.pi)).astype(int), z2)


def gear2_curve(p: PairParameters, tool: bool = False) -> Cycloid:
    """Nominal gear 2 of the pair, or the generating tool (with the rotation modification)."""
    return Cycloid(p.r0, p.e1, p.e2, p.z2, p.rotation if tool else 0.0)
