"""Gear 1: the exact lower envelope of gear 2's generating motion.

Gear 1 is made of *pieces*: parts of the runs of envelope branches (:mod:`.runs`), each
monotone in the polar angle φ about gear 1's centre. The pieces are chosen by comparing the
radius of every run on a fine φ grid (interpolated in each run's table, exact wherever two
come near each other) and joined at exact crossings (Newton's method in a bracket, to 1e-15
rad), so the profile is exact to floating-point precision everywhere, including at the tip
corners where the far-side branch trims the working flank.

Branches that shape gear 1 (docs/model.md, "Gear 1"):

* near side of the Δ2 tool at ``e + shift`` (working flanks, negative shift);
* far side of the same tool at ``e + shift`` (what the generating tool itself cuts);
* far side of the nominal gear 2 at ``e - tip_clearance`` (the tip trim: the assembled pair
  keeps ``tip_clearance`` of radial clearance at the middle of the tip).

With a tip relief the working branch is cut back near the tip (:mod:`.relief`) and the envelope
found again.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property, lru_cache

import numpy as np

from ..errors import GeometryError, ParameterError
from ..planar import rotate, wrap
from .envelope import FAR, NEAR, Branch, BranchPoints
from .gear2 import adaptive_parameters, gear2_curve
from .parameters import PairParameters
from .relief import RelievedBranch, relief_zones
from .runs import Run, split_runs

ENVELOPE_GRID = 2048
TABLE_POINTS = 1025     # ξ samples a run keeps to start its inversions from …
AMBIGUOUS = 1e-3        # … and to rank the runs by radius, exactly where two come this near (mm;
                        # its interpolation is within 1e-4 mm on the designs tested)


@dataclass(frozen=True)
class Piece:
    """Part of gear 1's profile: a run restricted to ``[xi0, xi1]``, turned by ``turn`` pitches.

    ``phi0 < phi1`` are its polar angles (continuous, in the period frame).
    """

    run: Run
    xi0: float
    xi1: float
    phi0: float
    phi1: float
    turn: int


def generating_branches(p: PairParameters) -> tuple[Branch, ...]:
    """The three branches whose lower envelope is gear 1 (see module docstring)."""
    tool, nominal = gear2_curve(p, tool=True), gear2_curve(p)
    a_gen = p.e + p.shift
    return (
        Branch(tool, a_gen, p.z2, p.z1, NEAR),
        Branch(tool, a_gen, p.z2, p.z1, FAR),
        Branch(nominal, p.e - p.radial_tip_clearance, p.z2, p.z1, FAR),
    )


class Gear1Profile:
    """Exact profile of the external gear 1, in its own frame (β = 0 orientation).

    Gear-1 material lies inside the curve. One pitch period of pieces starts at the middle of a
    tooth space (``phi_space``); the other teeth are copies turned by ``2π/z1``.
    """

    def __init__(self, params: PairParameters) -> None:
        self.params = params
        self._tables: dict = {}
        if params.relief > 0:
            # the conjugate profile does not depend on the relief: the unrelieved pair's,
            # kept (:func:`gear1_profile`), serves every relief tried on it (a refusal's
            # search for the deepest, the relief sizing's trials)
            plain = gear1_profile(replace(params, relief=0.0, relief_extent=None,
                                          relief_start=None, relief_shape="parabolic"))
            self.branches, self.pitch, self.phi_space = (plain.branches, plain.pitch,
                                                         plain.phi_space)
            self.runs, self.pieces = plain.runs, plain.pieces
            self._relieve()
            return
        if not all(gear2_curve(params, tool).star_shaped() for tool in (False, True)):
            raise GeometryError("the gear-2 curve folds back (it is not star-shaped about "
                                "its centre): check the pair with refusal.check_design")
        self.branches = generating_branches(params)
        self.pitch = 2 * np.pi / params.z1
        near = self.branches[0].evaluate(np.array([0.0]))
        self.phi_space = float(np.arctan2(near.q[0, 1], near.q[0, 0]))
        self.runs = tuple(r for i, b in enumerate(self.branches) for r in split_runs(b, i))
        self.pieces = self._lower_envelope()

    def _relieve(self) -> None:
        """Cut the working flanks back by the tip relief (:mod:`.relief`): the zones are placed
        on the conjugate profile's flanks, measured from where they meet the tip trim; then
        the envelope is found again with the relieved branch."""
        p = self.params
        ends = self.tip_ends()
        if len(ends) < 2:
            raise ParameterError("relief", p.relief, "0 here: gear 1's teeth are pointed, "
                                 "with no tip corner for a relief to end at")
        extent = p.relief_extent if p.relief_start is None else None
        zones = relief_zones(self.branches[0], ends, p.relief * 1e-3, extent, p.relief_shape,
                             p.m, p.relief_start)
        self.branches = (RelievedBranch(self.branches[0], zones), *self.branches[1:])
        self._tables = {}
        self.runs = tuple(r for i, b in enumerate(self.branches) for r in split_runs(b, i))
        self.pieces = self._lower_envelope()
        if len(self.tip_ends()) < 2:
            raise ParameterError("relief", p.relief, "a smaller relief or a longer "
                                 "relief-extent: the relieved flanks meet each other before "
                                 "the tip trim (no tip land left)")
        for (end, _), zone in zip(self.tip_ends(), zones):
            toward = np.sign(zone.stop - zone.start)
            if not toward * (end - zone.end) > 0 or not toward * (zone.stop - end) > 0:
                raise ParameterError("relief", p.relief, "a smaller relief or a longer "
                                     "relief-extent: the relieved flank must meet the tip "
                                     "trim within 0.5 relief-extent + 0.05 m past its tip "
                                     "end")

    def tip_ends(self) -> list[tuple[float, float]]:
        """Per working flank of tooth 0 that meets the tip trim: (ξ of the working branch at
        that corner, ξ at the flank's other end). The working flanks are the first and the
        last piece of the pitch, which start in the middle of the tooth spaces; a flank that
        runs into the next working flank (a pointed tooth) has no tip end."""
        out = []
        pieces = self.pieces
        for flank, after, at_start in ((pieces[0], pieces[1], False),
                                       (pieces[-1], pieces[-2], True)):
            if len(pieces) < 3 or flank.run.branch != 0 or after.run.branch == 0:
                continue
            # φ grows with ξ on an increasing run: the corner is at the first flank's phi1
            # and the last flank's phi0
            corner_low = at_start == flank.run.increasing
            out.append((flank.xi0, flank.xi1) if corner_low else (flank.xi1, flank.xi0))
        return out

    # --- construction --------------------------------------------------------------------
    def _run_polar(self, run: Run, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """ξ and radius of ``run`` at polar angles ``phi``; NaN where the run does not reach."""
        b = self.branches[run.branch]
        _, table, _ = self._table(run)
        phi_ends = table[[0, -1]]
        span = wrap(phi_ends[1] - phi_ends[0])
        lo, hi = (phi_ends[0], phi_ends[0] + span) if span > 0 else (phi_ends[0] + span,
                                                                      phi_ends[0])
        # bring targets into [lo, lo + 2π)
        rel = np.mod(phi - lo, 2 * np.pi)
        inside = rel <= hi - lo
        xi = np.full(phi.shape, np.nan)
        if inside.any():
            xi[inside] = self._invert(run, lo + rel[inside])
        rad = np.full(phi.shape, np.nan)
        ok = ~np.isnan(xi)
        rad[ok] = b.evaluate(xi[ok]).radius
        return xi, rad

    def _table(self, run: Run) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """ξ at :data:`TABLE_POINTS` points of a run, their polar angles unwrapped from the
        run's start and their radii: φ is monotone on a run, so this brackets every inversion
        and tells which run is lowest almost everywhere."""
        key = (run.branch, run.xi0, run.xi1)
        if key not in self._tables:
            xi = np.linspace(run.xi0, run.xi1, TABLE_POINTS)
            ev = self.branches[run.branch].evaluate(xi)
            phi = np.unwrap(np.arctan2(ev.q[:, 1], ev.q[:, 0]))
            self._tables[key] = (xi, phi, ev.radius)
        return self._tables[key]

    def _in_run(self, run: Run, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Polar angles in the frame of a run's table (the turn nearest the run's middle: a
        run can span a whole gear-1 pitch, and a target at one end must not go to the
        other), and whether the run reaches them."""
        _, ps, _ = self._table(run)
        mid = 0.5 * (ps[0] + ps[-1])
        rel = np.asarray(phi, dtype=float)
        rel = rel - 2 * np.pi * np.round((rel - mid) / (2 * np.pi))
        inside = (rel >= min(ps[0], ps[-1])) & (rel <= max(ps[0], ps[-1]))
        return rel, inside

    def _approx_radius(self, run: Run, phi: np.ndarray) -> np.ndarray:
        """The run's radius at polar angles ``phi`` interpolated in its table (NaN where it
        does not reach): within :data:`AMBIGUOUS` of the exact radius."""
        _, ps, rs = self._table(run)
        rel, inside = self._in_run(run, phi)
        order = slice(None) if ps[-1] > ps[0] else slice(None, None, -1)
        out = np.interp(rel, ps[order], rs[order])
        return np.where(inside, out, np.nan)

    def _invert(self, run: Run, phi: np.ndarray) -> np.ndarray:
        """Solve φ(ξ) = phi on a run: from the run's table (:meth:`_table`), Newton steps kept
        inside the bracketing table interval, a bisection wherever a step falls outside it or
        does not halve the step before last (near a cusp end Newton can cycle between two
        points inside the bracket)."""
        b = self.branches[run.branch]
        xs, ps, _ = self._table(run)
        sign = 1.0 if run.increasing else -1.0
        rel = np.clip(self._in_run(run, phi)[0], min(ps[0], ps[-1]), max(ps[0], ps[-1]))
        order = ps if sign > 0 else ps[::-1]
        k = np.clip(np.searchsorted(order, rel), 1, len(xs) - 1)
        if sign < 0:
            k = len(xs) - k
        lo, hi = xs[k - 1], xs[k]
        p_lo, p_hi = ps[k - 1], ps[k]
        with np.errstate(divide="ignore", invalid="ignore"):
            frac = np.clip(np.where(p_hi != p_lo, (rel - p_lo) / (p_hi - p_lo), 0.5), 0, 1)
        x = lo + frac * (hi - lo)
        conv = np.zeros(x.shape, dtype=bool)
        before = np.full(x.shape, np.inf)    # the step before last
        last = np.full(x.shape, np.inf)
        for _ in range(100):
            pts = b.evaluate(x)
            f = wrap(np.arctan2(pts.q[:, 1], pts.q[:, 0]) - phi)
            pos = sign * f > 0
            hi = np.where(pos, x, hi)
            lo = np.where(pos, lo, x)
            with np.errstate(divide="ignore", invalid="ignore"):  # a cusp: rate 0
                xn = x - f / pts.polar_rate
            bad = (~((xn >= lo) & (xn <= hi)) | ~np.isfinite(xn)
                   | (np.abs(xn - x) > 0.5 * before))
            xn = np.where(bad, 0.5 * (lo + hi), xn)
            # φ is only known to ~1e-16 rad (rounding in q), so |f| <= 1e-15 is converged
            conv |= (np.abs(f) <= 1e-15) | (np.abs(xn - x) <= 1e-16) | (hi - lo <= 1e-16)
            before, last = last, np.abs(xn - x)
            x = np.where(conv, x, xn)
            if conv.all():
                return x
        raise GeometryError("gear-1 polar inversion did not converge")

    def _lower_envelope(self) -> tuple[Piece, ...]:
        n = ENVELOPE_GRID
        phi = self.phi_space + self.pitch * (np.arange(n) + 0.5) / n
        # radius of every run (and its copies turned by whole pitches) at every grid angle,
        # from the runs' tables; exact where two come within AMBIGUOUS of each other
        radii, labels = [], []
        for r_i, run in enumerate(self.runs):
            for turn in self._turns(run):
                rad = self._approx_radius(run, phi - turn * self.pitch)
                if np.all(np.isnan(rad)):
                    continue
                radii.append(rad)
                labels.append((r_i, turn))
        radii = np.where(np.isnan(radii), np.inf, np.array(radii))
        if np.isinf(radii).all(axis=0).any():
            raise GeometryError("gear-1 envelope does not cover a full pitch")
        close = radii <= radii.min(axis=0) + AMBIGUOUS
        for k in np.nonzero(close.sum(axis=1) * (close.sum(axis=0) > 1).any())[0]:
            cols = np.nonzero(close[k] & (close.sum(axis=0) > 1))[0]
            if len(cols):
                r_i, turn = labels[k]
                _, exact = self._run_polar(self.runs[r_i], phi[cols] - turn * self.pitch)
                radii[k, cols] = np.where(np.isnan(exact), np.inf, exact)
        best = np.argmin(radii, axis=0)
        # group consecutive grid points with the same label, join at exact crossings
        bounds = [self.phi_space]
        owners = [best[0]]
        for i in range(1, n):
            if best[i] != owners[-1]:
                bounds.append(self._junction(labels[owners[-1]], labels[best[i]],
                                             phi[i - 1], phi[i]))
                owners.append(best[i])
        bounds.append(self.phi_space + self.pitch)
        pieces = []
        for j, owner in enumerate(owners):
            r_i, turn = labels[owner]
            run = self.runs[r_i]
            a, b = bounds[j], bounds[j + 1]
            xa = self._invert(run, np.array([a - turn * self.pitch]))[0]
            xb = self._invert(run, np.array([b - turn * self.pitch]))[0]
            pieces.append(Piece(run, min(xa, xb), max(xa, xb), a, b, turn))
        return tuple(pieces)

    def _turns(self, run: Run) -> range:
        """Whole-pitch turns that bring some of ``run`` into the period frame."""
        ends = self.branches[run.branch].evaluate(np.array([run.xi0, run.xi1]))
        phi = np.arctan2(ends.q[:, 1], ends.q[:, 0])
        step = wrap(phi[1] - phi[0])
        lo = self.phi_space + wrap(min(phi[0], phi[0] + step) - self.phi_space)
        first = int(np.floor((self.phi_space - lo - abs(step)) / self.pitch))
        last = int(np.ceil((self.phi_space + self.pitch - lo) / self.pitch))
        return range(first, last + 1)

    def _junction(self, la, lb, p0: float, p1: float) -> float:
        """Exact polar angle in ``[p0, p1]`` where two labelled runs have equal radius."""
        ra, rb = self.runs[la[0]], self.runs[lb[0]]

        def diff(x: float) -> float:
            _, r1 = self._run_polar(ra, np.array([x - la[1] * self.pitch]))
            _, r2 = self._run_polar(rb, np.array([x - lb[1] * self.pitch]))
            return float(r1[0] - r2[0])

        f0, f1 = diff(p0), diff(p1)
        if np.isfinite(f0) and np.isfinite(f1) and f0 * f1 < 0:
            return self._crossing(ra, la[1], rb, lb[1], p0, p1, f0, f1)
        # a run ends inside the cell: the junction is at its end (where one run ends exactly
        # where the other begins, as at the middle of a tooth both of whose halves the near
        # branch makes, that end; else found by bisection)
        ends = []
        for run, turn in ((ra, la[1]), (rb, lb[1])):
            _, ps, _ = self._table(run)
            for x in (ps[0], ps[-1]):
                x += turn * self.pitch
                x -= 2 * np.pi * np.round((x - p0) / (2 * np.pi))
                if p0 <= x <= p1:
                    ends.append(x)
        # … unless both runs reach past that end and still cross beyond it: where the new run
        # starts above the old one (a branch leaving a fold), the two meet at a crossing
        # after its start, not at the start itself
        inset = 1e-9 * (p1 - p0)
        for end in ends:
            after, before = end + inset, end - inset
            f_after, f_before = diff(after), diff(before)
            if np.isfinite(f_after) and np.isfinite(f1) and f_after * f1 < 0:
                return self._crossing(ra, la[1], rb, lb[1], after, p1, f_after, f1)
            if np.isfinite(f_before) and np.isfinite(f0) and f0 * f_before < 0:
                return self._crossing(ra, la[1], rb, lb[1], p0, before, f0, f_before)
        if ends and max(ends) - min(ends) <= 1e-12:
            return float(min(ends))
        a, b = p0, p1
        for _ in range(60):
            mid = 0.5 * (a + b)
            if np.isfinite(diff(mid)) and (not np.isfinite(f1) or diff(mid) * f0 > 0):
                a = mid
            else:
                b = mid
        return 0.5 * (a + b)

    def _crossing(self, ra: Run, ta: int, rb: Run, tb: int, lo: float, hi: float,
                  f_lo: float, f_hi: float) -> float:
        """Where two runs (turned by ``ta``, ``tb`` pitches) have equal radius in [lo, hi],
        the difference changing sign: Newton's method on it with its exact slope dr/dφ =
        (dr/dξ)/(dφ/dξ), kept inside the bracket (a bisection where a step leaves it), to
        1e-15 rad."""
        def slope(run: Run, turn: int, x: float) -> tuple[float, float]:
            xi, _ = self._run_polar(run, np.array([x - turn * self.pitch]))
            e = self.branches[run.branch].evaluate(xi)
            r = e.radius[0]
            dr = float(e.q[0] @ e.tangent[0]) * e.speed[0] / r
            return r, dr / e.polar_rate[0]

        x = lo - f_lo * (hi - lo) / (f_hi - f_lo)
        for _ in range(60):
            (r1, d1), (r2, d2) = slope(ra, ta, x), slope(rb, tb, x)
            f = r1 - r2
            if not np.isfinite(f):
                return 0.5 * (lo + hi)
            lo, hi = (x, hi) if (f < 0) == (f_lo < 0) else (lo, x)
            if abs(f) <= 1e-15 or hi - lo <= 1e-15:
                return float(x)
            with np.errstate(divide="ignore", invalid="ignore"):
                xn = x - f / (d1 - d2)   # a slope that is infinite (a cusp) stalls it:
            if not (lo < xn < hi) or not abs(xn - x) > 1e-16:
                xn = 0.5 * (lo + hi)     # … then, and out of the bracket, bisect
            x = xn
        return float(x)

    # --- evaluation ----------------------------------------------------------------------
    def _locate(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Piece index, tooth turn and local angle of every polar angle."""
        rel = np.mod(phi - self.phi_space, 2 * np.pi)
        tooth = np.floor(rel / self.pitch).astype(int)
        local = self.phi_space + rel - tooth * self.pitch
        starts = np.array([pc.phi0 for pc in self.pieces])
        idx = np.clip(np.searchsorted(starts, local, side="right") - 1, 0, len(self.pieces) - 1)
        return idx, tooth, local

    def evaluate(self, phi: np.ndarray) -> BranchPoints:
        """Exact profile at polar angles ``phi`` (point, normal, curvature in gear 1's frame)."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        idx, tooth, local = self._locate(phi)
        xi = np.empty_like(phi)
        branch = np.empty(phi.shape, dtype=int)
        turn = np.empty(phi.shape)
        for k, pc in enumerate(self.pieces):
            sel = idx == k
            if sel.any():
                xi[sel] = self._invert(pc.run, local[sel] - pc.turn * self.pitch)
                branch[sel] = pc.run.branch
                turn[sel] = pc.turn + tooth[sel]
        parts = {}
        for bi in np.unique(branch):
            sel = branch == bi
            parts[bi] = (sel, self.branches[bi].evaluate(xi[sel]))
        fields = {f: np.empty((len(phi), 2)) for f in ("q", "tangent", "normal")}
        scal = {f: np.empty(len(phi)) for f in ("xi", "beta", "kappa", "speed", "disc")}
        for _, (sel, pts) in parts.items():
            ang = turn[sel] * self.pitch
            for f in fields:
                fields[f][sel] = rotate(getattr(pts, f), ang)
            for f in scal:
                scal[f][sel] = getattr(pts, f)
        return BranchPoints(**fields, **scal)

    def radius(self, phi: np.ndarray) -> np.ndarray:
        """Exact polar radius ρ1(φ) [mm]."""
        return self.evaluate(phi).radius

    @cached_property
    def tooth_center(self) -> float:
        """Polar angle of the middle of tooth 0's tip [rad]."""
        return self.phi_space + 0.5 * self.pitch

    def period_polyline(self, chord_error: float, relief: bool = False):
        """One pitch of the profile (tooth space centre to next), chord error ≤ ``chord_error``;
        with ``relief``, also the tip relief's depth (mm) at each point."""
        pts, depth = [], []
        for pc in self.pieces:
            b = self.branches[pc.run.branch]

            def derivs(s, b=b):
                e = b.evaluate(s)
                # dq/dξ = σ t ; d²q/dξ² normal part = κ σ² n_left  (enough for curvature bound)
                d1 = e.speed[:, None] * e.tangent
                with np.errstate(invalid="ignore"):  # NaN at a singular point: refused below
                    d2 = (e.kappa * e.speed**2)[:, None] * (-e.normal)
                return e.q, d1, d2

            xi = adaptive_parameters(derivs, pc.xi0, pc.xi1, chord_error, n0=16)
            q = rotate(b.evaluate(xi).q, pc.turn * self.pitch)
            d = b.depth(xi) if isinstance(b, RelievedBranch) else np.zeros(len(xi))
            ang = np.unwrap(np.arctan2(q[:, 1], q[:, 0]))
            if ang[-1] < ang[0]:
                q, d = q[::-1], d[::-1]
            pts.append(q[:-1])
            depth.append(d[:-1])
        if relief:
            return np.concatenate(pts), np.concatenate(depth)
        return np.concatenate(pts)

    def polyline(self, chord_error: float, relief: bool = False):
        """Closed gear-1 profile (all teeth, counter-clockwise, last point not repeated); with
        ``relief``, also the tip relief's depth (mm) at each point."""
        one, depth = self.period_polyline(chord_error, relief=True)
        pts = np.concatenate([rotate(one, j * self.pitch) for j in range(self.params.z1)])
        return (pts, np.tile(depth, self.params.z1)) if relief else pts

    def relief_chart(self, count: int = 200) -> list[dict]:
        """The tip relief of each working flank of tooth 0 as a profile chart: per flank, the
        arc length from the flank's tip corner (mm, < 0 towards the root), the depth (µm) and
        the radius (mm) from before the relief's start to the corner; the amount (µm) and
        where it is reached (the conjugate flank's tip end, mm from the corner), the start and
        corner radii and the extent. Empty without relief."""
        b = self.branches[0]
        if not isinstance(b, RelievedBranch):
            return []
        out = []
        for (corner, _), zone in zip(self.tip_ends(), b.zones):
            xi = np.linspace(zone.start - 0.2 * (zone.end - zone.start), corner, count)
            w, _ = zone.arc_length(xi)
            ev = b.evaluate(xi)
            out.append({"arc_mm": w - w[-1], "depth_um": b.depth(xi) * 1e3,
                        "amount_um": zone.shape.amount * 1e3,
                        "end_arc_mm": float(zone.shape.extent - w[-1]),
                        "radius_mm": ev.radius, "extent_mm": zone.shape.extent,
                        "start_radius_mm": float(b.evaluate(np.array([zone.start])).radius[0]),
                        "corner_radius_mm": float(ev.radius[-1]),
                        "corner_depth_um": float(b.depth(np.array([corner]))[0] * 1e3)})
        return out


@lru_cache(maxsize=64)
def gear1_profile(params: PairParameters) -> Gear1Profile:
    """:class:`Gear1Profile` of ``params``, kept for the last few pairs: a relieved pair is
    built when its inputs are checked (a relief that does not fit is refused before any output)
    and again by the solve."""
    return Gear1Profile(params)
