"""Writing a figure to a file: the one save helper of `archquake.plotting`.

Plot functions draw into an ``ax`` (a new figure if None), return it and never call ``show()``
nor choose a backend: importing `archquake.plotting` leaves matplotlib's backend as the
user set it (a notebook keeps its inline backend). Saving works with any backend; the command
line selects Agg for itself before matplotlib is first imported.
"""

from __future__ import annotations

import threading
from pathlib import Path

import matplotlib.pyplot as plt
from matplotlib.axes import Axes
from matplotlib.figure import Figure, SubFigure


def axes(ax=None, size: tuple[float, float] = (6.4, 4.6)):
    """``ax`` itself, or the axes of a new figure ``size`` inches wide and high when it is None:
    the start of every plot function that takes an optional ``ax``."""
    if ax is None:
        _, ax = plt.subplots(figsize=size)
    return ax


def save(target: Figure | Axes, path: str | Path, *, dpi: int = 150, tight: bool = True) -> Path:
    """Write ``target``'s figure to ``path`` and close it.

    Parameters
    ----------
    target : matplotlib Figure or Axes
        The figure, or any axes of it.
    path : str or Path
        Output file; the format follows the suffix (.png, .pdf, .svg).
    dpi : int
        Resolution of raster formats, dots per inch.
    tight : bool
        Apply ``tight_layout()`` first (False when the caller has laid the figure out itself).

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    fig: Figure | SubFigure | Axes = target
    while not isinstance(fig, Figure):  # axes -> (sub)figure -> the figure that is saved
        fig = fig.figure
    with DRAWING:
        if tight:
            fig.tight_layout()
        fig.savefig(path, dpi=dpi)
        plt.close(fig)
    return path


#: Held while a figure is laid out and drawn: matplotlib's text layout (its shared font cache)
#: and pyplot's figure registry are not thread-safe, and ``archquake assess`` builds the figures
#: of independent sections in threads side by side.
DRAWING = threading.RLock()

__all__ = ["DRAWING", "axes", "save"]
