"""Brute-force swept-body reference, independent of fegear's envelope code.

Gear 2 is written out literally from paper eq. (11) (with its term-by-term derivatives). A gear-1
point ``q`` is carried through one gear-2 tooth period of rolling (all gear-1 teeth are passed
in, so one period covers every relative position); at every rolling angle its exact signed
distance to gear 2 is found by Newton's method on the closest-point condition. The minimum
over the rolling angle is refined by golden-section search around the best coarse samples.

Signed distance > 0: the point is in the gap (outside gear-2 material); < 0: penetration.
"""

from __future__ import annotations

import numpy as np


def _terms(r0, e1, e2, z, d2):
    """Paper eq. (11) term by term: (amplitude_x, freq, kind_x, amplitude_y, kind_y), a kind
    "c" for a cosine, "s" for a sine."""
    return [
        (r0, 1, "c", r0, "s"),
        (-(e1 - d2), z - 1, "c", (e1 - d2), "s"),
        (-(e1 + d2), z + 1, "c", -(e1 + d2), "s"),
        (-e2, 2 * z - 1, "c", e2, "s"),
        (e2, 2 * z + 1, "c", e2, "s"),
    ]


def eq11(xi, r0, e1, e2, z, d2, der=0):
    """Paper eq. (11) and its ξ-derivatives (der = 0, 1, 2), term by term."""
    terms = _terms(r0, e1, e2, z, d2)

    def d(kind, f, x, n):
        # n-th derivative of cos(f x) or sin(f x)
        phase = {"c": np.pi / 2, "s": 0.0}[kind]
        return f**n * np.sin(f * x + phase + n * np.pi / 2)

    x = sum(ax * d(kx, f, xi, der) for ax, f, kx, ay, ky in terms)
    y = sum(ay * d(ky, f, xi, der) for ax, f, kx, ay, ky in terms)
    return np.stack([x, y], axis=-1)


def _nearest_sample(y, th, offs, r0, e1, e2, z, d2, block=4096):
    """For each point of ``y``, the parameter th + offs[j] of the sample of eq. (11) nearest
    it: the terms' cosines and sines at th + offs by the angle-addition formulas (ten per
    point and ten per offset, not ten per sample: 7x faster), in blocks of points."""
    out = np.empty(len(y))
    for a in range(0, len(y), block):
        t, yy = th[a:a + block, None], y[a:a + block]
        px = np.zeros((len(t), len(offs)))
        py = np.zeros_like(px)
        for ax, f, kx, ay, ky in _terms(r0, e1, e2, z, d2):
            c, s, c_off, s_off = np.cos(f * t), np.sin(f * t), np.cos(f * offs), np.sin(f * offs)
            trig = {"c": c * c_off - s * s_off, "s": s * c_off + c * s_off}
            px += ax * trig[kx]
            py += ay * trig[ky]
        near = np.argmin((px - yy[:, :1]) ** 2 + (py - yy[:, 1:]) ** 2, axis=1)
        out[a:a + block] = t[:, 0] + offs[near]
    return out


def signed_distance(y, r0, e1, e2, z, d2):
    """Exact signed distance of points ``y`` (gear-2 frame) to gear 2 (> 0 in the gap)."""
    # nearest of 96 samples over ±1 pitch around the polar angle, then Newton
    th = np.arctan2(y[:, 1], y[:, 0])
    offs = np.linspace(-2 * np.pi / z, 2 * np.pi / z, 97)
    xi = _nearest_sample(y, th, offs, r0, e1, e2, z, d2)
    limit = offs[1] - offs[0]
    active = np.arange(len(y))     # Newton on the points whose last step was not yet < 1e-15
    for _ in range(40):
        xa, ya = xi[active], y[active]
        p = eq11(xa, r0, e1, e2, z, d2)
        p1 = eq11(xa, r0, e1, e2, z, d2, 1)
        p2 = eq11(xa, r0, e1, e2, z, d2, 2)
        r = p - ya
        f = np.einsum("ij,ij->i", r, p1)
        df = np.einsum("ij,ij->i", p1, p1) + np.einsum("ij,ij->i", r, p2)
        step = np.clip(f / df, -limit, limit)
        xi[active] = xa - step
        active = active[np.abs(step) >= 1e-15]
        if not len(active):
            break
    p = eq11(xi, r0, e1, e2, z, d2)
    t = eq11(xi, r0, e1, e2, z, d2, 1)
    t /= np.hypot(t[:, 0], t[:, 1])[:, None]
    n_gap = np.stack([-t[:, 1], t[:, 0]], axis=-1)
    return np.einsum("ij,ij->i", y - p, n_gap)


def sweep_min_distance(q, a, z1, r0, e1, e2, z2, d2, steps_per_pitch=100, keep=0.02):
    """Minimum over rolling of the signed distance of gear-1 points ``q`` (gear-1 frame).

    Gear 1's centre is at ``(0, a)``; gear 2 turns by β, gear 1 by ``z2/z1 β``. β runs over a
    whole turn of gear 1 (every tooth passes every gear-2 tooth position), in
    ``z1 * steps_per_pitch`` coarse steps. Exact distances are computed only where a point
    lies in gear 2's radial band (elsewhere it is farther than the band gap from gear 2);
    the lowest coarse minima closer than ``keep`` mm are refined by golden-section search.
    """
    k = z2 / z1
    n_beta = z1 * steps_per_pitch
    betas = np.linspace(0.0, 2 * np.pi / k, n_beta, endpoint=False)
    h = betas[1] - betas[0]
    band_lo, band_hi = r0 - 2 * e1 - 2 * keep, r0 + 2 * e1 + 2 * keep

    def to_gear2(qq, beta):
        al = k * beta
        x = np.stack([np.cos(al) * qq[:, 0] - np.sin(al) * qq[:, 1],
                      np.sin(al) * qq[:, 0] + np.cos(al) * qq[:, 1] + a], axis=-1)
        return np.stack([np.cos(beta) * x[:, 0] + np.sin(beta) * x[:, 1],
                         -np.sin(beta) * x[:, 0] + np.cos(beta) * x[:, 1]], axis=-1)

    def dist(qq, beta):
        return signed_distance(to_gear2(qq, beta), r0, e1, e2, z2, d2)

    npts = len(q)
    qi = np.repeat(np.arange(npts)[None, :], n_beta, axis=0).ravel()
    bi = np.repeat(betas[:, None], npts, axis=1).ravel()
    y = to_gear2(q[qi], bi)
    rad = np.hypot(y[:, 0], y[:, 1])
    coarse = np.full(n_beta * npts, np.inf)
    inband = (rad > band_lo) & (rad < band_hi)
    coarse[inband] = signed_distance(y[inband], r0, e1, e2, z2, d2)
    coarse = coarse.reshape(n_beta, npts)
    best = coarse.min(axis=0)
    cand = np.nonzero(best < keep)[0]
    order = np.argsort(coarse[:, cand], axis=0)[:2]
    g = (np.sqrt(5) - 1) / 2
    qq = q[cand]
    for j in range(order.shape[0]):
        lo = betas[order[j]] - h
        hi = betas[order[j]] + h
        x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
        f1, f2 = dist(qq, x1), dist(qq, x2)
        for _ in range(50):
            left = f1 < f2
            hi = np.where(left, x2, hi)
            lo = np.where(left, lo, x1)
            x_new = np.where(left, hi - g * (hi - lo), lo + g * (hi - lo))
            f_new = dist(qq, x_new)
            x1, x2 = np.where(left, x_new, x2), np.where(left, x1, x_new)
            f1, f2 = np.where(left, f_new, f2), np.where(left, f1, f_new)
        best[cand] = np.minimum(best[cand], np.minimum(f1, f2))
    return best
