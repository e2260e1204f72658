"""Pictures of a tooth-pair solve: von Mises on both gears (pyvista) and the mesh cycle."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..figures import pyplot, save_png
from ..files import write_atomic
from .case import PairSolution


def cycle_png(path: Path, rows: list[dict], title: str, stresses: dict[str, str]) -> Path:
    """Load share per tooth, the ``stresses`` (row key → label) and gear 1's rotation against
    position, from the rows of :func:`fegear.toothpair.report.cycle_rows`."""
    plt = pyplot()

    beta = [r["position_deg"] for r in rows]
    fig, ax = plt.subplots(3, 1, figsize=(8, 10), sharex=True)
    for k in (k for k in rows[0] if k.startswith("share_")):
        v = [r[k] for r in rows]
        if any(x > 0 for x in v):
            ax[0].plot(beta, v, marker="o", ms=3, label=f"tooth {k[6:]}")
    ax[0].set_ylabel("load share")
    ax[0].legend(fontsize=8, ncol=3)
    for k, label in stresses.items():
        ax[1].plot(beta, [r[k] for r in rows], marker="o", ms=3, label=label)
    ax[1].set_yscale("log")
    ax[1].set_ylabel("stress [MPa]")
    ax[1].legend(fontsize=8)
    ax[2].plot(beta, [r["rotation_urad"] for r in rows], marker="o", ms=3,
               label="loaded rotation θ (from kinematic)")
    ax[2].plot(beta, [r["first_touch_urad"] for r in rows], marker="o", ms=3,
               label="unloaded (first touch)")
    ax[2].plot(beta, [r["transmission_error_urad"] for r in rows], marker="o", ms=3,
               label="elastic part θ − θ_touch")
    ax[2].set_ylabel("gear-1 rotation [µrad]")
    ax[2].set_xlabel("rolling angle β of gear 2 [deg]")
    ax[2].legend(fontsize=8)
    for a in ax:
        a.grid(alpha=0.3)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()

    return save_png(fig, path, 110)


def von_mises_png(path: Path, sol: PairSolution, bodies) -> Path:
    """Von Mises on both bodies (pyvista, off-screen) with a zoomed inset on the most loaded
    contact zone; ``bodies``: the solution's :class:`~.case.BodyField` s."""
    import pyvista as pv

    pv.OFF_SCREEN = True
    grids = []
    for b in bodies:
        pts = np.column_stack([b.points, np.zeros(len(b.points))])
        tri = b.cells[:, :3]  # corner nodes: a linear picture is enough
        cells = np.column_stack([np.full(len(tri), 3), tri]).ravel()
        g = pv.PolyData(pts, faces=cells)
        g.point_data["von Mises [MPa]"] = b.data["von_mises"]
        grids.append(g)
    # colour scale: up to twice the larger root stress, so that the tooth bending shows beside
    # the (much higher, very local) contact peak, which saturates
    vmax = min(max(float(g.point_data["von Mises [MPa]"].max()) for g in grids),
               2.0 * max(sol.root_stress))
    zone = sol.detail.contact_zone()
    cx, cy = zone.centre
    zoom = max(8.0 * zone.half_width, 1.5 * sol.case.params.m)

    def scene(plotter, focus, half, bar):
        for g in grids:
            plotter.add_mesh(g, scalars="von Mises [MPa]", cmap="turbo", clim=(0.0, vmax),
                             show_scalar_bar=bar,
                             scalar_bar_args={"vertical": True, "position_x": 0.82,
                                              "title": "von Mises [MPa] (clipped)"})
        plotter.camera_position = "xy"
        plotter.camera.focal_point = (focus[0], focus[1], 0.0)
        plotter.camera.position = (focus[0], focus[1], 10.0 * half + 100.0)
        plotter.camera.parallel_projection = True
        plotter.camera.parallel_scale = half

    bounds = np.vstack([g.points[:, :2] for g in grids])
    centre = 0.5 * (bounds.min(axis=0) + bounds.max(axis=0))
    half = 0.55 * float(np.ptp(bounds[:, 1]) + 0.5 * np.ptp(bounds[:, 0]))
    p = pv.Plotter(off_screen=True, shape=(1, 2), window_size=(1600, 800))
    p.subplot(0, 0)
    scene(p, centre, half, False)
    p.add_text(f"von Mises, T {sol.case.torque:g} N·m", font_size=10)
    p.subplot(0, 1)
    scene(p, (cx, cy), zoom, True)
    p.add_text(f"contact zone ({zone.label}), ±{zoom:.2g} mm", font_size=10)

    def w(tmp: Path) -> None:
        p.screenshot(str(tmp))

    try:
        return write_atomic(path, w)
    finally:
        p.close()
