"""Unloaded tooth contact analysis: rotational clearance of every gear-1 tooth.

Frame (used everywhere in fegear): gear-2 centre at the origin, gear-1 centre ``O1 = (0, e)``,
the pitch point on +y. At rolling angle β gear 2 is turned by β and gear 1 by ``α = z2/z1 β``
(both counter-clockwise); at β = 0 gear 2's point ξ = 0 lies on +x and gear 1 is in its
generating orientation. The pair is assembled at the nominal centre distance ``e`` with the
nominal gear 2.

Clearance of gear-1 tooth j in direction ``+`` (gear 1 turning counter-clockwise about O1): the
extra rigid rotation of gear 1 that makes that tooth touch gear 2. A gear-1 point at radius ρ
about O1 moves on the circle of radius ρ, so its rotation to contact is the angle to the next
crossing of gear 2's boundary with that circle. Crossings are computed exactly: gear 2's
distance from O1 is split into monotone stretches (exact extrema) and inverted by Newton's
method. The minimum over the tooth's leading flank is refined by golden-section search on the
exact geometry. Negative clearance: the tooth interferes (the rotation needed to clear it).

Clearances are reported as µm of arc at the pitch radius r0 (``δ r0``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from ..errors import GeometryError
from ..planar import rotate as _rotate
from ..planar import wrap
from .gear1 import Gear1Profile
from .gear2 import Cycloid, gear2_curve
from .parameters import PairParameters

POINTS_PER_FLANK = 160
GEAR2_SAMPLES_PER_TOOTH = 48
GOLDEN = (np.sqrt(5.0) - 1.0) / 2.0
ANGLE_TOL = 1e-12  # rad: a crossing this close counts as the point itself


@dataclass(frozen=True)
class ToothClearance:
    """Clearance of one gear-1 tooth at one rolling angle.

    Attributes:
        tooth: gear-1 tooth index (tooth j is centred at ``tooth_center + j 2π/z1`` in gear 1's
            own frame).
        position_deg: angle of the tooth centre from the pitch line (+y) about O1 [deg], counter-
            clockwise positive, at this rolling angle.
        plus_um, minus_um: rotation of gear 1 that closes this tooth's clearance, counter-
            clockwise (+) and clockwise (−), as µm of arc at r0; negative if it interferes;
            ``None`` if no contact is possible within one pitch of rotation.
        plus_point, minus_point: the gear-1 point that closes the clearance, where it is at this
            rolling angle (fixed frame, mm; the rotation moves it on), or ``None``.
    """

    tooth: int
    position_deg: float
    plus_um: float | None
    minus_um: float | None
    plus_point: tuple[float, float] | None
    minus_point: tuple[float, float] | None


@dataclass(frozen=True)
class Interference:
    """Overlap of a gear-1 tooth with the nominal gear 2 at zero rotation.

    Attributes:
        tooth: gear-1 tooth index.
        depth_um: largest normal penetration depth [µm].
        point: deepest gear-1 point (fixed frame, mm).
    """

    tooth: int
    depth_um: float
    point: tuple[float, float]


@dataclass(frozen=True)
class ContactState:
    """Unloaded contact state at one rolling angle β [rad]."""

    beta: float
    teeth: tuple[ToothClearance, ...]
    interference: tuple[Interference, ...]

    def closest(self, direction: int) -> ToothClearance:
        """The tooth with the smallest clearance in ``direction`` (+1 or -1)."""
        key = "plus_um" if direction > 0 else "minus_um"
        finite = [t for t in self.teeth if getattr(t, key) is not None]
        if not finite:  # e.g. m 1.5, z 10/8, h1 0.01, f1 0 (a random case of the tests)
            raise GeometryError(f"no tooth can touch turning {'+' if direction > 0 else '−'} "
                                f"at β = {math.degrees(self.beta):.4g}°: the pair does not mesh")
        return min(finite, key=lambda t: getattr(t, key))


@dataclass(frozen=True)
class Backlash:
    """Smallest clearance over one mesh cycle, per direction [µm of arc at r0].

    ``beta_plus``/``beta_minus`` are the rolling angles where the minimum occurs.
    """

    plus_um: float
    minus_um: float
    beta_plus: float
    beta_minus: float


class ToothContact:
    """Unloaded TCA of an assembled pair (gear 1 from ``profile``, nominal gear 2)."""

    def __init__(self, params: PairParameters, profile: Gear1Profile | None = None) -> None:
        self.params = params
        self.gear1 = profile if profile is not None else Gear1Profile(params)
        self.gear2: Cycloid = gear2_curve(params)
        self.k = params.ratio

    # --- gear-1 tooth flanks (body frame, tooth 0) -----------------------------------------
    @cached_property
    def _flanks(self) -> dict[int, tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """Leading boundary of tooth 0 for each direction: (piece ids, params, points).

        ``+``: from the tip peak down to the next tooth-space centre; ``−``: from the previous
        tooth-space centre up to the tip peak. Samples are spaced evenly in each piece's
        parameter and include the exact junctions.
        """
        g = self.gear1
        ids, pars = [], []
        for i, pc in enumerate(g.pieces):
            n = max(8, int(POINTS_PER_FLANK * (pc.phi1 - pc.phi0) / (0.5 * g.pitch)))
            t = np.linspace(pc.xi0, pc.xi1, n)
            ids.append(np.full(n, i))
            pars.append(t)
        ids, pars = np.concatenate(ids), np.concatenate(pars)
        pts = self._points(ids, pars)
        phi = g.phi_space + wrap(np.arctan2(pts[:, 1], pts[:, 0]) - g.phi_space)
        phi = np.where(phi < g.phi_space, phi + 2 * np.pi, phi)
        rho = np.hypot(pts[:, 0], pts[:, 1])
        peak = phi[np.argmax(rho)]
        out = {}
        for direction, sel in ((+1, phi >= peak), (-1, phi <= peak)):
            out[direction] = (ids[sel], pars[sel], pts[sel])
        return out

    def _points(self, ids: np.ndarray, pars: np.ndarray) -> np.ndarray:
        """Exact gear-1 points (tooth 0, body frame) of pieces ``ids`` at parameters ``pars``."""
        g = self.gear1
        out = np.empty((len(ids), 2))
        for i in np.unique(ids):
            pc = g.pieces[i]
            sel = ids == i
            q = g.branches[pc.run.branch].evaluate(pars[sel]).q
            out[sel] = _rotate(q, pc.turn * g.pitch)
        return out

    # --- gear-2 crossings with circles about O1 ---------------------------------------------
    def _segments(self, betas) -> list[tuple]:
        """Monotone stretches of d(ξ) = |P(ξ) − O1'| on the whole gear-2 curve (gear-2 frame)
        at each rolling angle of ``betas``: gear 1's centre O1' there, the stretches' ends and
        their distances from it. All angles in one search (element by element the same
        numbers as one angle at a time: 60 bisection steps a search, not 60 an angle)."""
        e = self.params.e
        o1s = [_rotate(np.array([[0.0, e]]), -beta)[0] for beta in betas]
        n = self.params.z2 * GEAR2_SAMPLES_PER_TOOTH
        xi = np.linspace(0.0, 2 * np.pi, n + 1)
        p, d1 = self.gear2.derivatives(xi, 1)
        lo, hi, flo, owner = [], [], [], []
        for k, o1 in enumerate(o1s):
            f = np.einsum("ij,ij->i", p - o1, d1)
            # a sign change between samples; an extremum exactly on a sample (O1 on the
            # symmetry line of a tooth or space: f is 0 there) counts once, as f >= 0
            up = f >= 0
            idx = np.nonzero(up[:-1] != up[1:])[0]
            lo.append(xi[idx])
            hi.append(xi[idx + 1])
            flo.append(f[idx])
            owner.append(np.full(len(idx), k))
        lo, hi, flo, owner = (np.concatenate(c) for c in (lo, hi, flo, owner))
        centre = np.array(o1s)[owner] if len(owner) else np.zeros((0, 2))
        for _ in range(60):  # vectorized bisection on d'(ξ) = 0
            mid = 0.5 * (lo + hi)
            pm, dm = self.gear2.derivatives(mid, 1)
            fm = np.einsum("ij,ij->i", pm - centre, dm)
            left = np.sign(fm) == np.sign(flo)
            lo = np.where(left, mid, lo)
            flo = np.where(left, fm, flo)
            hi = np.where(left, hi, mid)
        ext = 0.5 * (lo + hi)
        cuts = []
        for k in range(len(o1s)):
            e_k = ext[owner == k]
            cuts.append(np.concatenate([e_k, [e_k[0] + 2 * np.pi]]) if len(e_k)
                        else np.array([0, 2 * np.pi]))
        # the stretches' end distances, every angle's in one evaluation
        sizes = [len(c) - 1 for c in cuts]
        o_all = np.repeat(np.array(o1s), sizes, axis=0)

        def distances(ends):   # from gear 1's centre, per angle
            return np.split(np.hypot(*(self.gear2.point(ends) - o_all).T), np.cumsum(sizes)[:-1])

        da = distances(np.concatenate([c[:-1] for c in cuts]))
        db = distances(np.concatenate([c[1:] for c in cuts]))
        return [(o1, c[:-1], c[1:], da_k, db_k) for o1, c, da_k, db_k in zip(o1s, cuts, da, db)]

    def _crossings(self, betas, segments, rho: np.ndarray) -> list[tuple]:
        """Angles (gear-1 body frame) where gear 2 crosses the circles of radii ``rho`` about
        O1, at each rolling angle of ``betas`` with its stretches ``segments``
        (:meth:`_segments`): per angle (angles, valid) of shape (len(rho), n_segments) and
        its stretches. The crossings of every angle are found in one search."""
        picks, entries = [], []
        for seg in segments:
            o1, a, b, da, db = seg
            lo_d, hi_d = np.minimum(da, db), np.maximum(da, db)
            valid = (rho[:, None] >= lo_d[None, :]) & (rho[:, None] <= hi_d[None, :])
            qi, si = np.nonzero(valid)
            picks.append((valid, qi, si))
            entries.append((np.broadcast_to(o1, (len(si), 2)), a[si], b[si], da[si], db[si],
                            rho[qi]))
        sizes = [len(qi) for _, qi, _ in picks]
        o1, a, b, da, db, r = (np.concatenate(c) for c in zip(*entries))
        xi = self._invert_segment(o1, a, b, da, db, r)
        p = self.gear2.point(xi) - o1
        angles = np.split(np.arctan2(p[:, 1], p[:, 0]), np.cumsum(sizes)[:-1])
        out = []
        for beta, seg, (valid, qi, si), found in zip(betas, segments, picks, angles):
            ang = np.full(valid.shape, np.nan)
            ang[qi, si] = found + beta - self.k * beta
            out.append((ang, valid, seg))
        return out

    def _invert_segment(self, o1, a, b, da, db, rho):
        """ξ in [a, b] with |P(ξ) − O1'| = ρ (d monotone on [a, b]); safeguarded Newton."""
        lo, hi = a.copy(), b.copy()
        inc = db > da
        frac = np.clip((rho - da) / np.where(db != da, db - da, 1.0), 0.0, 1.0)
        x = a + frac * (b - a)
        todo = np.arange(len(x))   # a converged point stays where it is: only the rest iterate
        o1 = np.broadcast_to(o1, (len(x), 2))   # one centre, or one a point
        for _ in range(60):
            xt, lt, ht = x[todo], lo[todo], hi[todo]
            p, d1 = self.gear2.derivatives(xt, 1)
            r = p - o1[todo]
            d = np.hypot(r[:, 0], r[:, 1])
            f = d - rho[todo]
            up = (f > 0) == inc[todo]
            ht = np.where(up, xt, ht)
            lt = np.where(up, lt, xt)
            xn = xt - f / (np.einsum("ij,ij->i", r, d1) / d)
            bad = ~((xn >= lt) & (xn <= ht)) | ~np.isfinite(xn)
            xn = np.where(bad, 0.5 * (lt + ht), xn)
            # d is known to ~1e-14 mm (rounding), so |f| <= 1e-13 is converged
            conv = (np.abs(f) <= 1e-13) | (np.abs(xn - xt) <= 1e-16) | (ht - lt <= 1e-16)
            x[todo], lo[todo], hi[todo] = np.where(conv, xt, xn), lt, ht
            todo = todo[~conv]
            if len(todo) == 0:
                break
        return x

    # --- clearance --------------------------------------------------------------------------
    def inside_gear2(self, x_fixed: np.ndarray, beta: float) -> np.ndarray:
        """True where fixed-frame points lie strictly inside gear-2 material."""
        y = _rotate(x_fixed, -beta)
        theta = np.arctan2(y[:, 1], y[:, 0])
        return np.hypot(y[:, 0], y[:, 1]) > self.gear2.radius_at_angle(theta)

    def _signed_angles(self, beta, rho, phi_body, ang, valid, direction, point):
        """Signed rotation to contact of points (ρ, φ) against crossing angles ``ang``.

        Outside gear 2: the angle to the next crossing ahead in ``direction``; inside: minus
        the angle back to the nearest crossing behind. Points on the boundary (within
        ``ANGLE_TOL``) give 0 either way. Returns (value, crossing index) per point.

        ``ang`` and ``valid`` are per circle: point i lies on circle ``point[i]``. Only the
        crossings next to a point's place in its circle's sorted crossings are compared
        (:func:`_nearest_crossings`); comparing every crossing of every tooth was quadratic
        in the teeth.
        """
        x_fixed = self._to_fixed(np.stack([rho * np.cos(phi_body), rho * np.sin(phi_body)], -1),
                                 beta)
        inside = self.inside_gear2(x_fixed, beta)
        (ahead, ahead_i), (behind, behind_i) = _nearest_crossings(ang, valid, phi_body, point,
                                                                  direction)
        val = np.where(inside, -behind, ahead)
        idx = np.where(inside, behind_i, ahead_i)
        return val, idx

    def _to_fixed(self, q_body: np.ndarray, beta: float) -> np.ndarray:
        x = _rotate(q_body, self.k * beta)
        x[:, 1] += self.params.e
        return x

    def state(self, beta: float = 0.0, teeth=None, refine: bool = True) -> ContactState:
        """Clearance of gear-1 teeth (default: all) in both directions, and any interference.

        With ``refine=False`` the clearances are the minima over the flank samples (an upper
        bound within a fraction of a µm), for scans.
        """
        return self.states((beta,), teeth, refine)[0]

    def states(self, betas, teeth=None, refine: bool = True,
               directions: tuple[int, ...] = (+1, -1)) -> list[ContactState]:
        """:meth:`state` at each rolling angle of ``betas``, the same values (to the search's
        accuracy, which a far tooth's value has); the refinement
        of every position is one search (about half the time of one search a position).
        Only in ``directions``: a direction left out has no
        contact point on any tooth (None), as a tooth-pair solve under a + torque needs.

        Angles a whole number of gear-2 pitches apart are one search: turning gear 2 by a
        pitch turns gear 1 by one of its own, and the pair stands as before with gear 1's
        teeth counted one on (:func:`_turned_on`), so a revolution's z1 pitches cost one
        pitch's search."""
        betas = [float(b) for b in np.atleast_1d(betas)]
        if teeth is not None or len(betas) < 2:
            return self._states(betas, teeth, refine, directions)
        places = [pitch_phase(b, self.params.z2) for b in betas]
        first: dict[int, int] = {}
        for i, (phase, _) in enumerate(places):
            first.setdefault(phase, i)
        if len(first) == len(betas):
            return self._states(betas, None, refine, directions)
        solved = dict(zip(first, self._states([betas[i] for i in first.values()], None,
                                              refine, directions)))
        return [_turned_on(solved[phase], beta, pitch - places[first[phase]][1],
                           self.params.z1) for (phase, pitch), beta in zip(places, betas)]

    def _states(self, betas, teeth, refine: bool,
                directions: tuple[int, ...]) -> list[ContactState]:
        """:meth:`states`, each angle searched."""
        g = self.gear1
        teeth = np.arange(self.params.z1) if teeth is None else np.asarray(teeth, dtype=int)
        betas = [float(b) for b in np.atleast_1d(betas)]
        nt = len(teeth)
        coarse = {+1: [], -1: []}
        segments = self._segments(betas)   # gear 2's stretches, once per angle
        for direction in directions:
            ids, pars, pts = self._flanks[direction]
            rho = np.hypot(pts[:, 0], pts[:, 1])
            phi0 = np.arctan2(pts[:, 1], pts[:, 0])
            # all teeth at once: (tooth, point)
            phi = (phi0[None, :] + teeth[:, None] * g.pitch).ravel()
            for beta, (ang, valid, seg) in zip(betas, self._crossings(betas, segments, rho)):
                vals, cross = self._signed_angles(beta, np.tile(rho, nt), phi, ang, valid,
                                                  direction, np.tile(np.arange(len(rho)), nt))
                coarse[direction].append((vals.reshape(nt, len(rho)),
                                          cross.reshape(nt, len(rho)), seg))
        none = [[(None, None)] * nt for _ in betas]
        found = {d: self._refine(betas, d, teeth, coarse[d], refine) if d in directions
                 else none for d in (+1, -1)}
        out = []
        for k, beta in enumerate(betas):
            rows = []
            for i, j in enumerate(teeth):
                centre = g.tooth_center + j * g.pitch + self.k * beta
                pos = np.degrees(wrap(centre - np.pi / 2))
                (vp, pp), (vm, pm) = found[+1][k][i], found[-1][k][i]
                rows.append(ToothClearance(int(j), float(pos), vp, vm, pp, pm))
            out.append(ContactState(beta, tuple(rows), self._interference(beta, teeth)))
        return out

    def _refine(self, betas, direction, teeth, coarse, refine=True):
        """Golden-section refinement of every tooth's minimum along its flank parameter, at
        every rolling angle: per angle, (value µm, fixed-frame point) or (None, None) per
        tooth.

        The coarse minimum of each tooth (``coarse``: per angle the sampled values, crossing
        indices and gear-2 stretches) is bracketed by its neighbouring samples (on the same
        piece) and searched with the crossing on the same gear-2 stretch, for all teeth and
        angles at once.
        """
        g, p = self.gear1, self.params
        ids, pars, _ = self._flanks[direction]
        n, nt = len(pars), len(teeth)
        entries = []                       # (angle, tooth row, piece, stretch, lo, hi)
        values, params, bests, oks = [], [], [], []
        for k, (vals, cross, _) in enumerate(coarse):
            best = np.argmin(vals, axis=1)
            v0 = vals[np.arange(nt), best]
            ok = np.isfinite(v0) & (v0 <= g.pitch)
            for j in np.nonzero(ok & refine)[0]:
                i = best[j]
                for a_i, b_i in ((max(i - 1, 0), i), (i, min(i + 1, n - 1))):
                    if a_i != b_i and ids[a_i] == ids[b_i]:
                        entries.append((k, j, ids[i], cross[j, i], pars[a_i], pars[b_i]))
            values.append(v0.copy())
            params.append(pars[best].copy())
            bests.append(best)
            oks.append(ok)
        if entries:
            k, j, piece, stretch, lo, hi = (np.array(c) for c in zip(*entries))
            # each entry's gear-2 stretch: gear 1's centre o1 (gear 2's frame) at its angle,
            # the stretch's ends a, b and their distances da, db from o1
            segs = [c[2] for c in coarse]
            seg = (np.array([segs[a][0] for a in k]),
                   *(np.array([segs[a][c][i] for a, i in zip(k, stretch)]) for c in range(1, 5)))
            fv, fx = self._golden(np.asarray(betas)[k], direction, teeth[j], piece, seg, lo,
                                  hi)
            for e in range(len(k)):
                if fv[e] < values[k[e]][j[e]]:
                    values[k[e]][j[e]], params[k[e]][j[e]] = fv[e], fx[e]
        out = []
        for beta, value, par, best, ok in zip(betas, values, params, bests, oks):
            x = np.full((nt, 2), np.nan)
            if ok.any():
                q = self._points(ids[best[ok]], par[ok])
                x[ok] = self._to_fixed(_rotate(q, teeth[ok] * g.pitch), beta)
            out.append([(float(value[j] * p.r0 * 1e3), (float(x[j, 0]), float(x[j, 1])))
                        if ok[j] else (None, None) for j in range(nt)])
        return out

    def _golden(self, beta, direction, tooth, piece, segment, a, b, iters=30):
        """Vectorized golden-section minimisation of the rotation to the crossing on a fixed
        gear-2 stretch, over flank parameters ``[a, b]`` (one search per entry, each with its
        rolling angle ``beta`` and its stretch ``segment``: gear 1's centre in gear 2's frame
        and the stretch's ends and distances, as :meth:`_segments` gives them)."""
        g = self.gear1
        o1, sa, sb, da, db = segment
        lo_d, hi_d = np.minimum(da, db), np.maximum(da, db)

        def f(t):
            q = _rotate(self._points(piece, t), tooth * g.pitch)
            rho = np.hypot(q[:, 0], q[:, 1])
            out = np.full(len(t), np.inf)
            ok = (rho >= lo_d) & (rho <= hi_d)
            if ok.any():
                xi = self._invert_segment(o1[ok], sa[ok], sb[ok], da[ok], db[ok], rho[ok])
                c = self.gear2.point(xi) - o1[ok]
                ang = np.arctan2(c[:, 1], c[:, 0]) + beta[ok] - self.k * beta[ok]
                out[ok] = wrap(direction * (ang - np.arctan2(q[ok, 1], q[ok, 0])))
            return out

        return golden_min(f, a, b, iters)

    @cached_property
    def _period_points(self) -> np.ndarray:
        return self.gear1.period_polyline(1e-4)

    def _interference(self, beta: float, teeth) -> tuple[Interference, ...]:
        g = self.gear1
        one = self._period_points
        x = np.vstack([self._to_fixed(_rotate(one, j * g.pitch), beta) for j in teeth])
        inside = self.inside_gear2(x, beta).reshape(len(teeth), len(one))
        found = []
        for r in np.nonzero(inside.any(axis=1))[0]:
            xr = x[r * len(one):(r + 1) * len(one)][inside[r]]
            depth = -self.gear2.signed_distance(_rotate(xr, -beta))
            k = int(np.argmax(depth))
            found.append(Interference(int(teeth[r]), float(depth[k] * 1e3),
                                      (float(xr[k, 0]), float(xr[k, 1]))))
        return tuple(found)

    def backlash(self, positions: int = 16) -> Backlash:
        """Smallest clearance per direction over one mesh cycle (β over one gear-2 pitch).

        A coarse scan over ``positions`` rolling angles (unrefined, all teeth) finds the
        closest teeth; the minimum is then refined by golden-section search in β between the
        neighbours of the best position, with refined clearances of the three closest teeth.
        """
        pitch2 = 2 * np.pi / self.params.z2
        betas = np.linspace(0.0, pitch2, positions, endpoint=False)
        h = betas[1] - betas[0]
        states = self.states(betas, refine=False)
        out = {}
        for direction, key in ((+1, "plus_um"), (-1, "minus_um")):
            vals = np.array([getattr(s.closest(direction), key) for s in states])
            i = int(np.argmin(vals))
            ranked = sorted((t for t in states[i].teeth if getattr(t, key) is not None),
                            key=lambda t: getattr(t, key))
            near = [t.tooth for t in ranked[:3]]

            def f(b, key=key, direction=direction, near=near):
                return getattr(self.state(b, teeth=near).closest(direction), key)

            fb, xb = golden_min(f, betas[i] - h, betas[i] + h, 16)
            out[direction] = min((float(fb), float(xb)), (float(f(betas[i])), float(betas[i])))
        return Backlash(float(out[1][0]), float(out[-1][0]), float(out[1][1]), float(out[-1][1]))


def golden_min(f, a, b, iters: int):
    """Golden-section minimisation of ``f`` on ``[a, b]``, elementwise over arrays.

    Returns (smallest value found, its argument), with the shapes of ``a`` and ``b``.
    """
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    x1, x2 = b - GOLDEN * (b - a), a + GOLDEN * (b - a)
    f1, f2 = f(x1), f(x2)
    for _ in range(iters):
        left = f1 < f2
        b = np.where(left, x2, b)
        a = np.where(left, a, x1)
        xn = np.where(left, b - GOLDEN * (b - a), a + GOLDEN * (b - a))
        fn = f(xn)
        x1, x2 = np.where(left, xn, x2), np.where(left, x1, xn)
        f1, f2 = np.where(left, fn, f2), np.where(left, f1, fn)
    take1 = f1 < f2
    return np.where(take1, f1, f2), np.where(take1, x1, x2)


NEIGHBOURS = 3   # crossings tried on each side of a point's place among its circle's crossings


#: the parts of a gear-2 pitch in which rolling angles whole pitches apart count as the same
#: place of the mesh (:func:`pitch_phase`): angles within one part of it share a search
#: (:meth:`ToothContact.states`) and a revolution's kept contact
#: (:mod:`fegear.toothpair.ring.phases`)
PHASES = 10 ** 9


def pitch_phase(beta: float, z2: int) -> tuple[int, int]:
    """(phase, pitch) of the rolling angle ``beta`` (rad): its place within a gear-2 pitch, in
    :data:`PHASES` parts, and how many whole pitches of gear 2's ``z2`` it lies from zero.
    Two angles with one phase are the same pair, gear 1's and gear 2's teeth counted on by
    the difference of their pitches."""
    steps = round(beta / (2 * math.pi / z2) * PHASES)
    return steps % PHASES, steps // PHASES


def _turned_on(state: ContactState, beta: float, pitches: int, z1: int) -> ContactState:
    """``state`` as it stands ``pitches`` gear-2 pitches on, at ``beta``: gear 1's tooth j
    there is tooth j + ``pitches`` here, at the same place."""
    rows = {t.tooth: t for t in state.teeth}
    teeth = tuple(replace(rows[(j + pitches) % z1], tooth=j) for j in range(z1))
    hits = tuple(replace(i, tooth=(i.tooth - pitches) % z1) for i in state.interference)
    return ContactState(beta, teeth, tuple(sorted(hits, key=lambda i: i.tooth)))


def _nearest_crossings(ang: np.ndarray, valid: np.ndarray, phi: np.ndarray, point: np.ndarray,
                       direction: int):
    """For point i at polar angle ``phi[i]`` on circle ``point[i]``: the nearest crossing of
    that circle (``ang``, ``valid``: per circle and gear-2 stretch) ahead in ``direction``
    (d = wrap(direction (angle − φ)) ≥ −ANGLE_TOL, the smallest d) and behind (d ≤ ANGLE_TOL,
    the smallest −d), each as (value, stretch index); inf and 0 where there is none.

    The same values and indices as comparing every crossing (ties to the lowest index, as
    ``argmin``): a circle's crossings are sorted once by direction · angle mod 2π, and only
    the :data:`NEIGHBOURS` on each side of the point's place are compared, with d formed as
    the full comparison forms it. The nearest ahead is the first crossing at or after the
    point in that order and the nearest behind the last at or before it; rounding in the
    sort key can move either by a place, not by three."""
    n, m = ang.shape
    key = np.where(valid, np.mod(direction * np.where(valid, ang, 0.0), 2 * np.pi), 7.0)
    order = np.argsort(key, axis=1, kind="stable")
    # every circle's sorted keys (below 8) shifted by 8 a circle: one sorted array, searched
    # for all points at once (the shift rounds the keys by ~1e-13 rad at 160 circles, far
    # below the spacing of distinct crossings)
    flat = (np.take_along_axis(key, order, axis=1) + 8.0 * np.arange(n)[:, None]).ravel()
    x = np.mod(direction * phi, 2 * np.pi)
    count = valid.sum(axis=1)[point]
    pos = np.searchsorted(flat, x + 8.0 * point) - m * point
    step = np.arange(-NEIGHBOURS, NEIGHBOURS)
    place = np.mod(pos[:, None] + step[None, :], np.maximum(count, 1)[:, None])
    cols = order[point[:, None], place]
    d = wrap(direction * (ang[point[:, None], cols] - phi[:, None]))
    has = (count > 0)[:, None]
    out = []
    for value in (np.where(has & (d >= -ANGLE_TOL), d, np.inf),
                  np.where(has & (d <= ANGLE_TOL), -d, np.inf)):
        best = value.min(axis=1)
        col = np.where(value == best[:, None], cols, m).min(axis=1)
        out.append((best, np.where(np.isfinite(best), col, 0)))
    return out
