"""The contact solved across the face (:mod:`.face`): every section's points on a kept contact
(every column of A formed), their pressures complementary to their gaps, gear 1's one rotation
carrying the torque.

Section s's gaps are the 2D rigid gaps plus the face's offsets there plus the approach
A_hp p_s + A_fe Σ_t S_st p_t. The method is the 2D solve's (:func:`~.contact.active_set`: every
violated point swapped at once; the rigid gap linearised in the turn and evaluated again until
the rotation settles). The active points' system is never formed: N sections of n points
would make a matrix N² times the 2D one, and its LU N³ times as costly. GMRES solves it from
two products with the 2D parts a step, preconditioned by the face's own operator on the
points active at any section, every one of them active at every section (:class:`_Modes`:
exact in the spread's modes, one 2D-sized LU a section), with the torque row bordered
exactly: it differs from the face's only where the sections' active points differ (the
contact zones' edges). On the baseline at 10 µm it reaches a residual of 1e-13 in about
thirty steps, where each section's own block alone took fifty and a quarter more time
(docs/model.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg
from scipy.sparse.linalg import LinearOperator, gmres

from .contact import ARM_STEP, MAX_ACTIVE_SET, MAX_TURNS, RingContactError, rigid_gap
from .face import FaceCoupling
from .influence import RingContact, near_field
from .model import RingModel

#: the points whose rigid gap at a section comes within this many elastic approaches (the
#: 2D solution's) of the least there take part in the iterations; the rest are checked at the
#: solution, and where one closes every point takes part
CANDIDATES = 2.0
#: GMRES: the relative residual, the restart length and the restarts
GMRES_TOL, GMRES_RESTART, GMRES_CYCLES = 1e-13, 80, 20


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


class _Problem:
    """One face's contact: the 2D parts of A (the finite-element part that spreads, the
    near field that stays), the points' force per unit pressure at each section, the
    offsets and the torque."""

    def __init__(self, model: RingModel, contact: RingContact, offsets: np.ndarray,
                 coupling: FaceCoupling, torque_nmm: float) -> None:
        self.model, self.contact, self.offsets, self.torque = model, contact, offsets, torque_nmm
        self.near = near_field(model, contact)
        self.far = contact.A - self.near
        self.spread = coupling.spread
        self.w = (contact.weight * model.case.thickness)[:, None] * coupling.share[None, :]
        self.alpha = model.case.params.ratio * contact.beta
        self.feet = contact.feet.copy()

    def rigid(self, theta: float, idx: np.ndarray | None = None):
        """The 2D rigid gaps (mm) and their rate with the turn (mm/rad) at rotation θ."""
        feet = self.feet if idx is None else self.feet[idx]
        return rigid_gap(self.model, self.contact, self.alpha + theta, feet, idx)

    def times(self, pressure: np.ndarray) -> np.ndarray:
        """The approach (points × sections) under ``pressure`` (points × sections)."""
        return self.far @ (pressure @ self.spread.T) + self.near @ pressure

    def solve(self, start: FaceStart, within: np.ndarray):
        """The linearisations of the rigid gap over the points ``within`` (points ×
        sections): the pressures (points × sections), rotation, iterations and
        linearisations."""
        points = np.flatnonzero(within.any(axis=1))   # the candidates of any section
        sections = _Sections(self, points, within[points])
        active = start.active[points][:, None] & sections.within
        pressure = np.zeros(active.shape)
        theta, total, turns = start.rotation, 0, 0
        while True:
            turns += 1
            g2, a2 = self.rigid(theta)
            g0, a = g2[points][:, None] + self.offsets[points], a2[points]
            arm_rate = self._arm_rate(theta, points, pressure, a)
            if not active.any():
                active = sections.within & (g0 <= g0[sections.within].min() + 1e-12)
            pressure, step, active, iterations = sections.active_set(g0, a, active, arm_rate)
            total += iterations
            theta += step
            if abs(step) <= max(1e-12 * abs(theta), 1e-13 / self.model.case.params.r0):
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
        self.far = problem.far[np.ix_(points, points)]
        self.near = problem.near[np.ix_(points, points)]
        self.spread, self.torque = problem.spread, problem.torque
        self.within, self.w = within, problem.w[points]
        self.eigen = spread_modes(problem.spread)
        self.factors: dict = {}

    def active_set(self, g0, a, active, arm_rate):
        """Pressures (points × sections) and rotation step with every active gap closed and
        the torque balanced, from ``active``, every violated point swapped at once; the
        active set and the iterations."""
        seen = set()
        for k in range(1, MAX_ACTIVE_SET + 1):
            pressure, step = self._on(g0, a, active, arm_rate)
            gap = g0 + a[:, None] * step + self.far @ (pressure @ self.spread.T) \
                + self.near @ pressure
            new = np.where(active, pressure > 0, (gap < 0) & self.within)
            if not new.any():
                new = self.within & (gap <= gap[self.within].min())
            if np.array_equal(new, active):
                return pressure, step, active, k
            key = new.tobytes()
            if key in seen:
                break
            seen.add(key)
            active = new
        raise RingContactError("the active set across the face did not settle")

    def _on(self, g0, a, active, arm_rate) -> tuple[np.ndarray, float]:
        """The bordered system A p + a δ = −g0 on the active points, (w a)·p + arm_rate δ =
        −T, by GMRES on the points active at any section (module docstring)."""
        union = np.flatnonzero(active.any(axis=1))
        on = active[union]
        far, near = self.far[np.ix_(union, union)], self.near[np.ix_(union, union)]
        sec_major = np.nonzero(on.T)
        local = (sec_major[1], sec_major[0])      # (point, section), section by section
        order = (union[local[0]], local[1])
        modes = self._modes(union, near, far)
        a_on = a[order[0]]
        wa = self.w[order] * a_on

        def times(x):
            p = np.zeros(on.shape)
            p[local] = x[:-1]
            u = (far @ (p @ self.spread.T) + near @ p)[local] + a_on * x[-1]
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

        size = len(a_on) + 1
        rhs = np.append(-g0[order], -self.torque)
        x, info = gmres(LinearOperator((size, size), matvec=times, dtype=float), rhs,
                        x0=precondition(rhs),
                        M=LinearOperator((size, size), matvec=precondition, dtype=float),
                        rtol=GMRES_TOL, atol=0.0, restart=GMRES_RESTART, maxiter=GMRES_CYCLES)
        if info != 0 or not np.isfinite(x).all():
            raise RingContactError("the contact across the face did not converge")
        pressure = np.zeros(active.shape)
        pressure[order] = x[:-1]
        return pressure, float(x[-1])

    def _modes(self, union: np.ndarray, near: np.ndarray, far: np.ndarray) -> _Modes:
        """The face's operator on every point of ``union`` at every section, in the spread's
        modes (:class:`_Modes`), kept per union."""
        key = union.tobytes()
        if key not in self.factors:
            self.factors[key] = _Modes(near, far, self.eigen)
        return self.factors[key]


class _Modes:
    """The face's operator with every point of a set active at every section, near X + far X
    Sᵀ (X: points × sections), solved exactly in the spread's modes: with S = V Λ V⁻¹, Z = X
    V⁻ᵀ takes it to near z_k + λ_k far z_k, one 2D-sized system a mode. Where the sections'
    active points are those of the set it is the face's operator itself; where they differ it
    is what GMRES is preconditioned with. (Solving the differing sets exactly, by the
    operator's inverse at the entries left out, cost two to three times the GMRES steps it
    saved: on the baseline some 800 entries are left out of 2800.)"""

    def __init__(self, near: np.ndarray, far: np.ndarray, eigen) -> None:
        self.lam, self.v, self.v_inv_t = eigen
        kind = self.lam.dtype
        self.factors = [scipy.linalg.lu_factor((near + lam * far).astype(kind),
                                               check_finite=False) for lam in self.lam]
        # LAPACK's own solve: scipy's lu_solve checks its arguments each call, and GMRES
        # calls it a section a step (most of its time on the baseline)
        self.getrs = scipy.linalg.get_lapack_funcs("getrs", (self.factors[0][0],))

    def solve(self, r: np.ndarray) -> np.ndarray:
        """X with near X + far X Sᵀ = ``r`` (points × sections)."""
        rt = r @ self.v_inv_t
        z = np.empty_like(rt)
        for k, (lu, piv) in enumerate(self.factors):
            z[:, k], info = self.getrs(lu, piv, rt[:, k])
            if info:
                raise RingContactError("a section's mode of the face's operator is singular")
        return np.real(z @ self.v.T)
