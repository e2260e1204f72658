"""The contact solved across the face (:mod:`.face`): every section's points on a kept contact
(every column of A formed), their pressures complementary to their gaps, gear 1's one rotation
carrying the torque.

Section s's gaps are the 2D rigid gaps plus the face's offsets there plus the approach
A_hp p_s + A_fe Σ_t S_st p_t (with the coupling's ``across`` spreads, A_fe's blocks between
different grids take the spread between their teeth in place of S: one tooth's load reaches
the others through the rims; :mod:`.face_spread`).
The method is the 2D solve's (:func:`~.contact_system.active_set`: every violated point swapped at
once; the rigid gap linearised in the turn and evaluated again until the rotation settles).
The active points' system is never formed: N sections of n points would make a matrix N²
times the 2D one, and its LU N³ times as costly. GMRES (:mod:`.krylov`) solves it from two
products with the 2D parts a step, preconditioned by the face's own operator on the points
active at any section, every one of them active at every section (:class:`_Modes`: in the
spread's modes, about the near field's LU on each grid; S alone where other teeth take
spreads of their own), with the torque row bordered exactly: it differs from the face's only
where the sections' active points differ (the contact zones' edges). The first
linearisation's sets are solved loosely (their signs and the turn's step are all it passes
on), the later ones tightly, each from the one before's pressures (docs/model.md, "Across
the face").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from .contact import ARM_STEP, MAX_TURNS, RingContactError, rigid_gap
from .contact_system import MAX_ACTIVE_SET
from .face import FaceCoupling
from .face_spread import FaceSpread
from .influence import RingContact, near_field
from .krylov import gmres
from .model import RingModel

#: the points whose rigid gap at a section comes within this many elastic approaches (the
#: 2D solution's) of the least there take part in the iterations; the rest are checked at the
#: solution, and where one closes every point takes part
CANDIDATES = 2.0
#: GMRES's relative residual
GMRES_TOL = 1e-13
#: the first linearisation's GMRES tolerance: its active sets' signs need no more (1e-6 took
#: a few more sets on the baseline)
FIRST_TOL = 1e-7
#: the rank at which the preconditioner takes the finite-element part (:class:`_Modes`)
RANK = 20


@dataclass(frozen=True)
class FaceStart:
    """Where a face's solve starts: the 2D solution's rotation (rad) and active points, and its
    elastic approach (mm), which sets how far from closing a point still takes part."""

    rotation: float
    active: np.ndarray
    elastic: float


@dataclass(frozen=True)
class FaceSolution:
    """The contact solved across the face: the pressure (MPa) at every point of every section
    (points × sections), their gaps (mm), gear 1's rotation θ (rad, from its kinematic
    position), the active-set iterations and linearisations, and the pressures spread as the
    finite-element part takes them (points × sections: the loads whose fields, and so root
    stresses, each section sees)."""

    pressure: np.ndarray
    gap: np.ndarray
    rotation: float
    iterations: int
    turns: int
    spread_pressure: np.ndarray

    def line_loads(self, contact: RingContact) -> np.ndarray:
        """Each grid's (tooth's) line load at each section (N/mm; grids × sections)."""
        force = contact.weight[:, None] * self.pressure
        return np.add.reduceat(force, contact.offsets[:-1], axis=0)


def solve_face_contact(model: RingModel, contact: RingContact, start: FaceStart,
                       torque_nmm: float, offsets: np.ndarray, coupling: FaceCoupling
                       ) -> FaceSolution:
    """``contact`` (every column of A formed) across the face under ``torque_nmm`` (N·mm on
    gear 1), section s's rigid gaps the 2D ones plus ``offsets[:, s]`` (mm; points ×
    sections), from ``start``."""
    if not contact.complete:
        raise ValueError("a face's contact needs every column of A formed (a kept contact)")
    problem = _Problem(model, contact, offsets, coupling, torque_nmm)
    g = problem.rigid(start.rotation)[0][:, None] + offsets
    within = g <= g.min(axis=0) + CANDIDATES * start.elastic
    for _ in range(2):
        pressure, rotation, iterations, turns = problem.solve(start, within)
        gap = problem.rigid(rotation)[0][:, None] + offsets + problem.times(pressure)
        if (gap[~within] >= 0).all():
            return FaceSolution(pressure, gap, rotation, iterations, turns,
                                pressure @ coupling.spread.T)
        within = np.ones_like(within)
    raise RingContactError("a point closed outside the face's contact points")


@dataclass(frozen=True)
class _Linear:
    """One linearisation of the rigid gap over the candidate points: the gaps g0 (mm; points ×
    sections) and their rate a with the turn (mm/rad; points) at its rotation, and the
    torque's rate with the turn through its arms (N·mm/rad)."""

    g0: np.ndarray
    a: np.ndarray
    arm_rate: float


class _Problem:
    """One face's contact: the 2D parts of A (the finite-element part that spreads, the
    near field that stays), the points' force per unit pressure at each section, the
    offsets and the torque."""

    def __init__(self, model: RingModel, contact: RingContact, offsets: np.ndarray,
                 coupling: FaceCoupling, torque_nmm: float) -> None:
        self.model, self.contact, self.offsets, self.torque = model, contact, offsets, torque_nmm
        near = near_field(model, contact)
        contact.ready(np.arange(contact.npoints))
        # transposed: a set's products read the rows of its points, which are contiguous
        self.near_t = np.ascontiguousarray(near.T)
        self.far_t = np.subtract(contact.A.T, near.T, out=np.empty_like(near))
        self.spread = coupling.spread
        self.blocks = [contact.block(k) for k in range(len(contact.grids))]
        self.fe = FaceSpread(coupling, [g.tooth for g in contact.grids], model.case.params.z1)
        self.w = (contact.weight * model.case.thickness)[:, None] * coupling.share[None, :]
        self.alpha = model.case.params.ratio * contact.beta
        self.feet = contact.feet.copy()

    def rigid(self, theta: float, idx: np.ndarray | None = None):
        """The 2D rigid gaps (mm) and their rate with the turn (mm/rad) at rotation θ."""
        feet = self.feet if idx is None else self.feet[idx]
        return rigid_gap(self.model, self.contact, self.alpha + theta, feet, idx)

    def times(self, pressure: np.ndarray) -> np.ndarray:
        """The approach (points × sections) under ``pressure`` (points × sections)."""
        loaded = np.flatnonzero(pressure.any(axis=1))
        return self.approach(pressure[loaded], loaded, self.far_t[loaded],
                             self.near_t[loaded])

    def approach(self, p: np.ndarray, at: np.ndarray, far_rows: np.ndarray,
                 near_rows: np.ndarray) -> np.ndarray:
        """The approach (points × sections) at every point under the pressures ``p`` (len(at)
        × sections) at the points ``at`` (increasing), whose rows of the transposed parts
        are ``far_rows`` and ``near_rows``: the finite-element part between each pair of
        grids spread as the coupling spreads it between their teeth (:class:`FaceSpread`)."""
        u = self.fe.approach(p, grid_spans(at, self.contact.offsets), far_rows,
                             self.blocks)                         # sections × points
        return (u + p.T @ near_rows).T

    def solve(self, start: FaceStart, within: np.ndarray):
        """The linearisations of the rigid gap over the points ``within`` (points ×
        sections): the pressures (points × sections), rotation, iterations and
        linearisations. The first linearisation's active sets are solved to
        :data:`FIRST_TOL` (only their signs and the rotation's step count there, and the
        next linearisation corrects both), every later one to :data:`GMRES_TOL`, each
        started from the one before's pressures."""
        points = np.flatnonzero(within.any(axis=1))   # the candidates of any section
        sections = _Sections(self, points, within[points])
        active = start.active[points][:, None] & sections.within
        pressure = np.zeros(active.shape)
        theta, total, turns, warm = start.rotation, 0, 0, None
        while True:
            turns += 1
            g2, a2 = self.rigid(theta)
            a = a2[points]
            linear = _Linear(g2[points][:, None] + self.offsets[points], a,
                             self._arm_rate(theta, points, pressure, a))
            if not active.any():
                active = sections.within & (linear.g0 <= linear.g0[sections.within].min()
                                            + 1e-12)
            tol = FIRST_TOL if turns == 1 else GMRES_TOL
            pressure, step, active, iterations = sections.active_set(linear, active, tol, warm)
            warm = pressure
            total += iterations
            theta += step
            if abs(step) <= max(1e-12 * abs(theta), 1e-13 / self.model.case.params.r0) \
                    and turns > 1:   # a loose solve's step settles nothing
                break
            if turns == MAX_TURNS:
                raise RingContactError(f"the rotation did not settle in {MAX_TURNS} "
                                       "linearisations")
        full = np.zeros(self.offsets.shape)
        full[points] = pressure
        return full, float(theta), total, turns

    def _arm_rate(self, theta: float, points: np.ndarray, pressure: np.ndarray,
                  a: np.ndarray) -> float:
        """The torque's rate with the turn through its arms (Σ w p da/dθ, the loaded points'
        alone), as the 2D solve carries it."""
        loaded = np.flatnonzero(pressure.any(axis=1))
        if not len(loaded):
            return 0.0
        ahead = self.rigid(theta + ARM_STEP, points[loaded])[1]
        return float(np.sum(self.w[points[loaded]] * pressure[loaded]
                            * ((ahead - a[loaded]) / ARM_STEP)[:, None]))


def grid_spans(at: np.ndarray, offsets: np.ndarray) -> list[slice | None]:
    """Each grid's slice of the points ``at`` (increasing indices of the contact's points,
    whose grids start at ``offsets``), None where a grid has none of them."""
    cuts = np.searchsorted(at, offsets)
    return [slice(lo, hi) if hi > lo else None for lo, hi in zip(cuts[:-1], cuts[1:])]


def spread_modes(spread: np.ndarray):
    """The spread S's eigenvalues Λ, eigenvectors V and V⁻ᵀ (S = V Λ V⁻¹), real where S's
    are (to 1e-12 of the largest), else complex."""
    lam, v = scipy.linalg.eig(spread)
    if np.abs(lam.imag).max() <= 1e-12 * np.abs(lam).max() and np.abs(v.imag).max() <= 1e-12:
        lam, v = lam.real, v.real
    return lam, v, np.linalg.inv(v).T


class _Sections:
    """The active-set method on the candidate points of every section (module docstring)."""

    def __init__(self, problem: _Problem, points: np.ndarray, within: np.ndarray) -> None:
        self.problem, self.points, self.within = problem, points, within
        self.spread, self.torque = problem.spread, problem.torque
        self.w = problem.w[points]
        self.eigen = spread_modes(problem.spread)
        self.factors: dict = {}

    def active_set(self, linear: _Linear, active: np.ndarray, tol: float,
                   warm: np.ndarray | None):
        """Pressures (points × sections) and rotation step with every active gap closed and
        the torque balanced, from ``active``, every violated point swapped at once, each
        set's system solved to ``tol`` from ``warm`` (pressures, points × sections) if
        given; the active set and the iterations. A set met again at a loose ``tol`` is
        solved on to :data:`GMRES_TOL` (its solves' error may have made the cycle)."""
        seen = set()
        for k in range(1, MAX_ACTIVE_SET + 1):
            pressure, step, gap = self._on(linear, active, tol, warm)
            new = np.where(active, pressure > 0, (gap < 0) & self.within)
            if not new.any():
                new = self.within & (gap <= gap[self.within].min())
            if np.array_equal(new, active):
                return pressure, step, active, k
            key = new.tobytes()
            if key in seen:
                if tol == GMRES_TOL:
                    break
                tol, seen = GMRES_TOL, set()
            seen.add(key)
            active = new
        raise RingContactError("the active set across the face did not settle")

    def _on(self, linear: _Linear, active: np.ndarray, tol: float,
            warm: np.ndarray | None) -> tuple[np.ndarray, float, np.ndarray]:
        """The bordered system A p + a δ = −g0 on the active points, (w a)·p + arm_rate δ =
        −T, by GMRES on the points active at any section (module docstring): the pressures,
        the step δ and every candidate's gap."""
        union = np.flatnonzero(active.any(axis=1))
        on = active[union]
        at = self.points[union]
        far_rows, near_rows = self.problem.far_t[at], self.problem.near_t[at]
        far = np.ascontiguousarray(far_rows[:, at].T)
        # the near field stays on its grid: one block a grid, the union's points grid by grid
        spans = grid_spans(at, self.problem.contact.offsets)
        grids = [g for g in spans if g is not None]
        near = [np.ascontiguousarray(near_rows[g, at[g]].T) for g in grids]
        sec_major = np.nonzero(on.T)
        local = (sec_major[1], sec_major[0])      # (point, section), section by section
        order = (union[local[0]], local[1])
        modes = self._modes(union, _Near(grids, near), far)
        a_on = linear.a[order[0]]
        wa = self.w[order] * a_on
        arm_rate = linear.arm_rate
        fe = self.problem.fe.on_points(far, spans)

        def times(x):
            p = np.zeros(on.shape)
            p[local] = x[:-1]
            u = fe(p)
            for g, block in zip(grids, near):
                u[g] += block @ p[g]
            u = u[local] + a_on * x[-1]
            return np.append(u, wa @ x[:-1] + arm_rate * x[-1])

        def sections(x):   # the union's operator solved, read at the active entries
            r = np.zeros(on.shape)
            r[local] = x
            return modes.solve(r)[local]

        pa = sections(a_on)
        schur = arm_rate - wa @ pa
        if not schur:
            raise RingContactError("the contact points cannot carry the torque")

        def precondition(x):   # the coupled sections on the union, with the torque row
            y = sections(x[:-1])
            step = (x[-1] - wa @ y) / schur
            return np.append(y - pa * step, step)

        rhs = np.append(-linear.g0[order], -self.torque)
        x0 = precondition(rhs) if warm is None else np.append(warm[order], 0.0)
        found = gmres(times, precondition, rhs, x0, tol)
        if not found.converged or not np.isfinite(found.x).all():
            raise RingContactError("the contact across the face did not converge")
        pressure = np.zeros(active.shape)
        pressure[order] = found.x[:-1]
        approach = self.problem.approach(pressure[union], at, far_rows, near_rows)
        gap = linear.g0 + linear.a[:, None] * found.x[-1] + approach[self.points]
        return pressure, float(found.x[-1]), gap

    def _modes(self, union: np.ndarray, near: _Near, far: np.ndarray) -> _Modes:
        """The face's operator on every point of ``union`` at every section, in the spread's
        modes (:class:`_Modes`), kept per union."""
        key = union.tobytes()
        if key not in self.factors:
            self.factors[key] = _Modes(near, far, self.eigen)
        return self.factors[key]


@dataclass(frozen=True)
class _Near:
    """The near field on a union's points: its blocks, one a grid (it is zero between grids),
    and the union's slices they sit on."""

    grids: list
    blocks: list


class _Modes:
    """The face's operator with every point of a set active at every section, near X + far X
    Sᵀ (X: points × sections), solved in the spread's modes: with S = V Λ V⁻¹, Z = X V⁻ᵀ
    takes it to near z_k + λ_k far z_k, one 2D-sized system a mode. The finite-element part
    is smooth, and taken at rank :data:`RANK`, far ≈ Q B (Q spanning far's products with as
    many random vectors), so that every mode is solved about the near field N, one LU a grid
    (it is zero between grids), by Woodbury's identity:
    (N + λ Q B)⁻¹ = N⁻¹ − N⁻¹ Q (I + λ B N⁻¹ Q)⁻¹ λ B N⁻¹. Where the sections' active points
    are those of the set it is the face's operator to that rank; either way it only
    preconditions GMRES, whose solution is the face's own: the rank sets the steps, not the
    answer."""

    def __init__(self, near: _Near, far: np.ndarray, eigen) -> None:
        self.lam, self.v, self.v_inv_t = eigen
        kind = self.lam.dtype
        rank = min(RANK, len(far))
        sketch = np.random.default_rng(0).standard_normal((len(far), rank))
        q = np.linalg.qr(far @ sketch)[0]
        b = q.T @ far
        self.grids = near.grids
        self.lu = [scipy.linalg.lu_factor(block, check_finite=False) for block in near.blocks]
        # LAPACK's own solve: scipy's lu_solve checks its arguments each call, and GMRES
        # calls it every step
        self.getrs = scipy.linalg.get_lapack_funcs("getrs", (self.lu[0][0],))
        nq = self._near_solve(q)
        g = b @ nq
        eye = np.eye(rank)
        self.small = np.stack([lam * np.linalg.inv(eye + lam * g) for lam in self.lam])
        self.b, self.nq = b.astype(kind), nq.astype(kind)

    def _near_solve(self, r: np.ndarray) -> np.ndarray:
        """N⁻¹ ``r`` (real or complex columns)."""
        if np.iscomplexobj(r):
            return self._near_solve(r.real) + 1j * self._near_solve(r.imag)
        x = np.empty_like(r)
        for g, (lu, piv) in zip(self.grids, self.lu):
            x[g], info = self.getrs(lu, piv, r[g])
            if info or not np.isfinite(x[g]).all():
                raise RingContactError("the near field of the face's operator is singular")
        return x

    def solve(self, r: np.ndarray) -> np.ndarray:
        """X with near X + far X Sᵀ = ``r`` (points × sections), far at rank :data:`RANK`."""
        y = self._near_solve(r @ self.v_inv_t)
        z = y - self.nq @ np.einsum("kij,jk->ik", self.small, self.b @ y)
        return np.real(z @ self.v.T)
