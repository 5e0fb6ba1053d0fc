"""Figures of ``archquake reproduce`` that `archquake.plotting.compare` does not draw: the
paper's Figure 6, several arches' boundaries on one axes with the distinct-element boundary
points laid over them (Figures 4, 9, 10 and 11 come from `archquake.plotting.compare`)."""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from archquake.plotting.domains import plot_domains
from archquake.plotting.figures import save

#: A distinct-element boundary to lay over a domain: (label, durations s, magnitudes g, style).
DemSeries = tuple[str, np.ndarray, np.ndarray, str]


def _overlay(ax, series: Sequence[DemSeries]) -> None:
    """Markers in the colour of the four-link curve of the same arch (matched on the label's
    "R = ... m" part before " DEM"), so that each radius reads as one colour."""
    curves = {line.get_label(): line.get_color() for line in ax.get_lines()}
    for label, x, y, style in series:
        arch_label = label.split(" DEM")[0]
        colour = next((c for name, c in curves.items()
                       if name == arch_label or name.startswith(arch_label + ",")), None)
        ax.plot(np.asarray(x), np.asarray(y), style, ms=6, lw=1.2, label=label, color=colour)
    ax.legend(fontsize=7, loc="upper right")


def domains_with_dem(
    cases: Sequence,
    series: Sequence[DemSeries],
    path: str | Path,
    *,
    boundary: str = "collapse",
    title: str | None = None,
) -> Path:
    """Several arches' boundaries (Figures 6, 7) with distinct-element points laid over them."""
    ax = plot_domains(cases, boundary=boundary, title=title)
    if title:
        ax.set_title("\n".join(textwrap.wrap(title, 60)), fontsize=9)
    _overlay(ax, series)
    return save(ax, path)


__all__ = ["DemSeries", "domains_with_dem"]
