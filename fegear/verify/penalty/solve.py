"""Solving the condensed contact problem (see :mod:`fegear.verify.penalty`) and reading it
back.

Load control (given the link's generalised force F, find θ) or motion control (given θ, find F).
Unknowns are the point forces λ ≥ 0 (N) and θ; with P = diag(κ w) the penalty,

    active set A:   (G_AA + P_A⁻¹) λ_A + a_A θ = −h_A        (gap = −λ/(κw) on A)
    link balance:   k θ − a_Aᵀ λ_A = F

where h + a θ is the exact rigid gap linearised at the current θ. A is updated to the points
with negative gap until it repeats; then the exact gap is re-evaluated at the new θ. Under load
control the load is raised in ``LOAD_STEPS``, each converged step starting the next.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np

from ...fe import facet_nodes
from .model import ContactError, ContactModel

log = logging.getLogger(__name__)

#: load control applies the load in these fractions, each step starting from the last one's
#: active set and link motion. Started at the first touch with the full load, one point took
#: it all, the link overshot, and the iterations went on to visit 925 of the 1412 contact
#: nodes of the `fast` baseline (326 in these steps), each needing its column of G.
LOAD_STEPS = (1 / 16, 1 / 4, 1.0)

#: mm: a link update that moves no gap by more than this is converged. At 1 mN on the Hertz
#: disks (approach 1e-9 mm) the relative test alone never held: each update crept by 3e-18 mm,
#: at the rounding of the exact gaps. This floor is far above that and, at a contact stiffness
#: of 1e6 N/mm, moves the force by 1e-8 N.
GAP_ROUNDING = 1e-14


@dataclass(frozen=True)
class PairZone:
    """One contact zone of a pair. ``load`` (N); ``p_max`` (MPa), the largest node pressure
    (a parabola through it and its neighbours overshot Hertz by 2 % at 4 elements per b);
    ``half_width`` (mm), twice the standard deviation of the traction along the slave arc (b for
    a Hertz ellipse), the node forces spread over their hats; ``center`` (mm, fixed frame)."""

    pair: str
    load: float
    p_max: float
    half_width: float
    center: tuple[float, float]
    points: int


@dataclass(frozen=True)
class ContactSolution:
    """Converged contact state. Forces in N, lengths in mm, pressures in MPa.

    ``link_value`` θ (rad) or δ (mm); ``link_force`` F (N·mm or N); ``displacements`` per body
    (ndofs,), including θψ; ``residuals`` per body, relative ‖K u − f‖ on the free dofs.
    """

    link_value: float
    link_force: float
    force: np.ndarray = field(repr=False)
    pressure: np.ndarray = field(repr=False)
    gap: np.ndarray = field(repr=False)
    iterations: int
    outer_iterations: int
    max_penetration: float
    balance_error: float
    displacements: tuple[np.ndarray, ...] = field(repr=False)
    residuals: tuple[float, ...]
    zones: tuple[PairZone, ...]

    @property
    def total_load(self) -> float:
        return float(self.force.sum())


def solve_contact(model: ContactModel, load: float | None = None,
                  motion: float | None = None,
                  start: tuple[float, np.ndarray] | None = None) -> ContactSolution:
    """Solve for the contact forces under the link force ``load`` or the link ``motion``.

    ``start`` (load control): a link motion and active set (bool per point) near the answer,
    such as the last position's of a mesh cycle; the full load is then applied from there,
    without the first touch and the load steps."""
    if (load is None) == (motion is None):
        raise ValueError("give exactly one of load (link force) and motion (link value)")
    lb = model.link_body
    if lb is None:
        raise ContactError("no body carries a rigid link: nothing drives the contact")
    k_link = model.bodies[lb].link_stiffness
    inv_pen = 1.0 / (model.kappa * model.weight)
    st = model.settings
    steps = (None,) if motion is not None else tuple(f * load for f in LOAD_STEPS)
    if motion is not None:
        theta = float(motion)
        g0, a = model.gap0(theta)
        active = g0 < 0
    elif start is not None:
        theta, steps = float(start[0]), (load,)
        g0, a = model.gap0(theta)
        active = np.asarray(start[1], dtype=bool).copy()
    else:
        g0, a = model.gap0(0.0)
        theta = first_touch(g0, a, steps[0], k_link)
        g0, a = model.gap0(theta)
        active = g0 < 0
    if motion is None and not active.any():
        active = g0 <= g0.min()
    total_inner = outer = 0
    lam = np.zeros(model.npoints)
    for step in steps:
        step_outer = 0
        while step_outer < st.max_iterations:
            step_outer += 1
            h = g0 - a * theta
            seen = set()
            for _ in range(st.max_iterations):
                total_inner += 1
                lam, theta_new = _linear_step(model.G, inv_pen, h, a, active, step, theta,
                                              k_link)
                gap = h + a * theta_new + model.G @ lam
                new = gap < 0
                if np.array_equal(new, active):
                    break
                key = new.tobytes()
                if key in seen:
                    raise ContactError("active-set iterations cycle (contact ill-posed at "
                                       "this load)")
                seen.add(key)
                active = new
                if motion is None and not active.any():
                    active = gap <= gap.min()
            else:
                raise ContactError(f"active set not stable after {st.max_iterations} "
                                   "iterations")
            change = abs(theta_new - theta)
            theta = theta_new
            g0, a = model.gap0(theta)
            if motion is not None or change <= max(st.link_tol * abs(theta),
                                                   GAP_ROUNDING / max(np.abs(a).max(), 1e-300)):
                break
        else:
            raise ContactError(f"link motion not converged after {step_outer} updates")
        outer += step_outer

    gap = g0 + model.G @ lam
    lam = np.where(gap < 0, -gap / inv_pen, 0.0)
    force_on_link = float(a @ lam)
    link_force = k_link * theta - force_on_link
    balance = abs(link_force - load) / max(abs(load), 1e-300) if load is not None else 0.0
    displacements, residuals = _displacements(model, lam, theta)
    pressure = model.kappa * np.maximum(-gap, 0.0)
    zones = _zones(model, lam)
    max_pen = float(max(0.0, -gap.min()))
    widest = max((z.half_width for z in zones), default=0.0)
    if widest > 0 and max_pen > st.penetration_tol * widest:
        raise ContactError(f"penalty too soft: penetration {max_pen * 1e3:.3g} µm exceeds "
                           f"{st.penetration_tol:.0%} of the contact half-width "
                           f"{widest * 1e3:.3g} µm; raise the penalty factor")
    return ContactSolution(link_value=theta, link_force=link_force, force=lam, pressure=pressure,
                           gap=gap, iterations=total_inner, outer_iterations=outer,
                           max_penetration=max_pen, balance_error=balance,
                           displacements=displacements, residuals=residuals, zones=zones)


def first_touch(g0: np.ndarray, a: np.ndarray, load: float, k_link: float) -> float:
    """Link motion at which the first point closes, moving the way the load pushes, for the
    gaps g0 + a·motion linearised at the current motion (for a stiff link: load / k)."""
    if k_link > 0:
        return load / k_link
    direction = np.sign(load) if load != 0 else -1.0
    closing = a * direction < 0
    if not closing.any():
        raise ContactError("the applied load moves the link away from every contact point")
    return float(direction * np.min(g0[closing] / np.abs(a[closing])))


def _linear_step(G, inv_pen, h, a, active, load, theta, k_link):
    idx = np.flatnonzero(active)
    lam = np.zeros(len(h))
    M = G.block(idx) + np.diag(inv_pen[idx])
    if load is None:  # motion control: θ given
        lam[idx] = np.linalg.solve(M, -(h[idx] + a[idx] * theta))
        return lam, theta
    n = len(idx)
    A = np.zeros((n + 1, n + 1))
    A[:n, :n] = M
    A[:n, n] = a[idx]
    A[n, :n] = a[idx]
    A[n, n] = -k_link
    rhs = np.concatenate([-h[idx], [-load]])
    try:
        sol = np.linalg.solve(A, rhs)
    except np.linalg.LinAlgError:
        raise ContactError("the active contact points cannot carry the link load") from None
    lam[idx] = sol[:n]
    return lam, float(sol[n])


def _displacements(model: ContactModel, lam: np.ndarray, theta: float):
    us, res = [], []
    for b, body in enumerate(model.bodies):
        f = model.C[b].T @ lam
        v = body.solve(f)
        u = body.displacement(v, theta) if body.link is not None else v
        us.append(u)
        res.append(body.residual(v, f) if np.any(f) else 0.0)
    return tuple(us), tuple(res)


def _zones(model: ContactModel, lam: np.ndarray) -> tuple[PairZone, ...]:
    out = []
    for k, pair in enumerate(model.pairs):
        sel = (model.pair_index == k) & (lam > 0)
        if not sel.any():
            continue
        w = lam[sel]
        s = model.arc[sel]
        mean = np.sum(w * s) / w.sum()
        # each node force spread over its hat (half-width h_i, variance h_i²/6)
        h = model.weight[sel] / model.bodies[pair.slave].material.thickness
        half = 2.0 * np.sqrt(np.sum(w * ((s - mean) ** 2 + h**2 / 6)) / w.sum())
        placed = model.bodies[pair.slave].placement.to_fixed(model.x[sel])
        centre = np.sum(w[:, None] * placed, axis=0) / w.sum()
        p_max = float(np.max(lam[sel] / model.weight[sel]))
        out.append(PairZone(pair=pair.name, load=float(w.sum()), p_max=p_max,
                            half_width=float(half), center=(float(centre[0]), float(centre[1])),
                            points=int(sel.sum())))
    return tuple(out)


def forces_from_body(model: ContactModel, body: int, f: np.ndarray) -> np.ndarray:
    """The contact node forces λ (N) that a body's nodal forces ``f`` (its frame, (ndofs,),
    e.g. K u of a displacement another code computed on the same mesh) stand for.

    Per pair of which ``body`` is the slave, λ is the least-squares fit of C_bᵀλ = f over the
    dofs of the pair's rows: the hat-weighted pressure whose consistent nodal forces come
    closest to ``f``. For this model's own solution it returns its λ (C_bᵀλ is what the body
    carries); for another code's it averages that code's nodal contact forces over the same
    hats, so that the two are read alike (:mod:`fegear.verify.peer_contact`)."""
    C = model.C[body].tocsc()
    lam = np.zeros(model.npoints)
    for k, pair in enumerate(model.pairs):
        if pair.slave != body:
            continue
        rows = np.flatnonzero(model.pair_index == k)
        A = C[rows].tocsc()
        cols = np.flatnonzero(np.diff(A.indptr))
        lam[rows] = np.linalg.lstsq(A[:, cols].toarray().T, np.asarray(f)[cols], rcond=None)[0]
    return lam


def nodal_pressure(model: ContactModel, solution: ContactSolution, body: int) -> np.ndarray:
    """Contact pressure (MPa) at the nodes of ``body``'s contact boundaries, 0 elsewhere.

    The quadrature-point tractions of each pair are interpolated linearly along the polyline of
    their points, onto the slave nodes and the master nodes of that pair."""
    b = model.bodies[body]
    out = np.zeros(b.mesh.doflocs.shape[1])
    for k, pair in enumerate(model.pairs):
        names = [n for owner, n in ((pair.slave, pair.slave_boundary),
                                    (pair.master, pair.master_boundary)) if owner == body]
        sel = np.flatnonzero(model.pair_index == k)
        if not names or len(sel) < 2:
            continue
        order = sel[np.argsort(model.arc[sel])]
        xq = model.bodies[pair.slave].placement.to_fixed(model.x[order])
        for name in names:
            nodes = np.unique(facet_nodes(b.mesh, b.mesh.boundaries[name]))
            p = _along(xq, solution.pressure[order], b.placement.to_fixed(b.mesh.doflocs.T[nodes]))
            out[nodes] = np.maximum(out[nodes], p)
    return out


def _along(xq: np.ndarray, pq: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Linear interpolation of values pq on the polyline xq at the closest point of each y."""
    a, d = xq[:-1], np.diff(xq, axis=0)
    t = np.clip(np.einsum("nsd,sd->ns", y[:, None] - a[None], d) / np.sum(d * d, axis=1), 0, 1)
    dist = np.linalg.norm(a[None] + t[..., None] * d[None] - y[:, None], axis=2)
    j = np.argmin(dist, axis=1)
    tj = t[np.arange(len(y)), j]
    far = dist[np.arange(len(y)), j] > np.linalg.norm(d, axis=1).max()
    return np.where(far, 0.0, (1 - tj) * pq[j] + tj * pq[j + 1])
