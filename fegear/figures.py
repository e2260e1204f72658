"""Figures: matplotlib set up for files (no screen), and PNGs written atomically.

matplotlib is imported here, inside the functions, so that no stage pays for it at import.
"""

from __future__ import annotations

from pathlib import Path

from .files import write_atomic


def pyplot():
    """``matplotlib.pyplot`` on the file-only Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_png(fig, path: Path, dpi: int) -> Path:
    """Write a matplotlib figure as PNG (atomically) and close it."""
    import matplotlib.pyplot as plt

    def w(tmp: Path) -> None:
        fig.savefig(tmp, dpi=dpi, format="png")

    try:
        return write_atomic(path, w)
    finally:
        plt.close(fig)
