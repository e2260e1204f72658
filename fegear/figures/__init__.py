"""Figures: matplotlib and pyvista set up for files (no screen), and PNGs written atomically.

matplotlib is imported here, inside the functions, so that no stage pays for it at import.
:mod:`.labels` places labels and legends clear of the data, among what :mod:`.pixels` reads
off a drawn axes; neither imports matplotlib.
"""

from __future__ import annotations

from pathlib import Path

from ..files import write_atomic


def pyplot():
    """``matplotlib.pyplot`` on the file-only Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_png(fig, path: Path, dpi: int) -> Path:
    """Write a matplotlib figure as PNG (atomically) and close it: :func:`png_bytes` into
    :func:`write_png`."""
    return write_png(path, png_bytes(fig, dpi))


def png_bytes(fig, dpi: int) -> bytes:
    """A matplotlib figure drawn as PNG, and closed: what :func:`write_png` writes, formed
    wherever the figure was drawn (a picture drawn in another process comes back as these).
    zlib at level 1: the default, 6, takes several times as long for files a fifth smaller at
    most."""
    import io

    import matplotlib.pyplot as plt

    buffer = io.BytesIO()
    try:
        fig.savefig(buffer, dpi=dpi, format="png", pil_kwargs={"compress_level": 1})
    finally:
        plt.close(fig)
    return buffer.getvalue()


def write_png(path: Path, data: bytes) -> Path:
    """Write a picture's PNG bytes (:func:`png_bytes`) to ``path``, atomically."""
    return write_atomic(path, lambda tmp: tmp.write_bytes(data))


def margins(fig, left: float, right: float, bottom: float, top: float,
            wspace: float = 0.0, hspace: float = 0.0) -> None:
    """Place a figure's subplot grid by fixed margins and gaps in inches: ``tight_layout``
    measured every tick label by drawing the figure once more, 0.8 of the 3.8 s the
    baseline's three pictures took."""
    w, h = fig.get_size_inches()
    rows, cols = fig.axes[0].get_subplotspec().get_gridspec().get_geometry()
    width = (w - left - right - (cols - 1) * wspace) / cols
    height = (h - top - bottom - (rows - 1) * hspace) / rows
    fig.subplots_adjust(left=left / w, right=1.0 - right / w, bottom=bottom / h,
                        top=1.0 - top / h, wspace=wspace / width, hspace=hspace / height)


def pyvista():
    """``pyvista`` set up for files: off-screen, and VTK's own log silenced (without a display
    VTK logs "bad X server connection" with terminal colour codes on every render, then
    renders off-screen all the same)."""
    import pyvista as pv

    pv.OFF_SCREEN = True
    pv.vtk_verbosity("off")
    return pv
