"""Pictures of a tooth-pair solve: von Mises on both gears (pyvista) and the mesh cycle."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..figures import pyplot, pyvista, save_png
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


def von_mises_png(path: Path, sol: PairSolution, bodies, peaks=()) -> Path:
    """Von Mises (pyvista, off-screen): the loaded teeth, clipped at twice the larger root
    stress so that the bending shows beside the contact; and the most loaded contact, with the
    submodels that resolve its peak (``peaks``; the ring model) drawn over the bodies, on their
    own scale. ``bodies`` and ``peaks``: :class:`~.case.BodyField` s."""
    pv = pyvista()
    grids = [_polydata(pv, b) for b in bodies]
    fine = [_polydata(pv, b) for b in peaks]
    zone = sol.detail.contact_zone()
    p = sol.case.params
    teeth_half = 2.5 * 2 * np.pi / p.z1 * p.r0          # two and a half gear-1 pitches
    clip = 2.0 * max(sol.root_stress)
    peak = max([sol.von_mises_max] + [float(g.point_data["vm"].max()) for g in fine])
    if fine:
        near = max(np.ptp(g.points[:, :2], axis=0).max() for g in fine)
        zoom = min(0.6 * near, max(12.0 * zone.half_width, 0.02 * p.m))
    else:
        zoom = max(8.0 * zone.half_width, 0.05 * p.m)

    def view(plotter, meshes, half, clim, title):
        for g in meshes:
            plotter.add_mesh(g, scalars="vm", cmap="turbo", clim=clim, show_scalar_bar=True,
                             scalar_bar_args={"vertical": True, "position_x": 0.87,
                                              "position_y": 0.1, "width": 0.08,
                                              "title": title, "fmt": "%.0f",
                                              "title_font_size": 14, "label_font_size": 12})
        plotter.camera_position = "xy"
        plotter.camera.focal_point = (zone.centre[0], zone.centre[1], 0.0)
        plotter.camera.position = (zone.centre[0], zone.centre[1], 10.0 * half + 100.0)
        plotter.camera.parallel_projection = True
        plotter.camera.parallel_scale = half

    plot = pv.Plotter(off_screen=True, shape=(1, 2), window_size=(1600, 800))
    plot.subplot(0, 0)
    # distinct titles: pyvista shares one colour table between scalar bars of the same title,
    # and the zoom's full range then recoloured the clipped overview
    view(plot, grids, teeth_half, (0.0, clip), "vM [MPa], clipped")
    plot.add_text(f"von Mises, T {sol.case.torque:g} N·m: the loaded teeth\n"
                  f"(colours clipped at {clip:.0f} MPa, twice the root stress)", font_size=11)
    plot.subplot(0, 1)
    view(plot, grids + fine, zoom, (0.0, peak), "vM [MPa]")
    what = "submodels resolve the peak" if fine else "the mesh resolves the contact"
    plot.add_text(f"contact peak ({zone.label}), ±{zoom * 1e3:.3g} µm: {what}\n"
                  f"max {peak:.0f} MPa", font_size=11)

    def w(tmp: Path) -> None:
        plot.screenshot(str(tmp))

    try:
        return write_atomic(path, w)
    finally:
        plot.close()


def _polydata(pv, b):
    """A body's corner triangles (a linear picture is enough) with its von Mises."""
    pts = np.column_stack([b.points, np.zeros(len(b.points))])
    tri = b.cells[:, :3]
    g = pv.PolyData(pts, faces=np.column_stack([np.full(len(tri), 3), tri]).ravel())
    g.point_data["vm"] = b.data["von_mises"]
    return g
