"""Figures of ``archquake reproduce``: the paper's figures with the distinct-element results
laid over the analytical ones (Figures 4, 6, 11), built on the other plotting modules."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from archquake.plotting.domains import plot_domain, plot_domains, save  # noqa: E402
from archquake.plotting.history import plot_ground_motion, plot_history  # noqa: E402

#: A distinct-element boundary to lay over a domain: (label, durations s, magnitudes g, style).
DemSeries = tuple[str, np.ndarray, np.ndarray, str]


def figure4_with_dem(
    results: Sequence,
    motions: Sequence,
    labels: Sequence[str],
    dem: Sequence,
    path: str | Path,
    *,
    t_end: float = 3.0,
    dem_labels: Sequence[str] | None = None,
) -> Path:
    """The paper's Figure 4: impulses (a) and the analytical histories (b)-(d), each with the
    distinct-element rotation (``DemResult.rotation``, dashed) where ``dem[k]`` is not None."""
    n = len(results)
    fig, axes = plt.subplots(n + 1, 1, figsize=(6.8, 2.2 * (n + 1)), sharex=True)
    for motion, label in zip(motions, labels):
        plot_ground_motion(motion, t_end, axes[0], label=label)
    axes[0].legend(fontsize=7, loc="upper right")
    axes[0].set_title("(a) impulses", fontsize=9, loc="left")
    for k, (res, label) in enumerate(zip(results, labels)):
        ax = axes[k + 1]
        plot_history(res, ax, label="analytical", color="k")
        d = dem[k] if k < len(dem) else None
        if d is not None:
            keep = d.times <= t_end
            ax.plot(
                d.times[keep],
                d.rotation[keep],
                "--",
                color="tab:red",
                lw=1.3,
                label=dem_labels[k] if dem_labels else "DEM",
            )
        what = res.outcome.value.replace("_", " ")
        if res.collapse_half_cycle:
            what += f" in half cycle {res.collapse_half_cycle}"
        ax.set_title(f"({'bcdefgh'[k]}) {label}: analytical {what}", fontsize=9, loc="left")
        h = res.history
        lim = max(0.08, 1.2 * float(np.max(np.abs(h.signed_rotation[h.t <= t_end]), initial=0.0)))
        ax.set_ylim(-min(lim, 0.3), min(lim, 0.3))
        ax.set_xlim(0.0, t_end)
        ax.legend(fontsize=7, loc="lower left")
    for ax in axes[:-1]:
        ax.set_xlabel("")
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _overlay(ax, series: Sequence[DemSeries]) -> None:
    for label, x, y, style in series:
        ax.plot(np.asarray(x), np.asarray(y), style, ms=6, lw=1.2, label=label)
    ax.legend(fontsize=7, loc="upper right")


def domain_with_dem(
    domain, series: Sequence[DemSeries], path: str | Path, *, title: str | None = None
) -> Path:
    """A failure domain (Figures 5, 11) with distinct-element boundary points laid over it."""
    ax = plot_domain(domain, title=title)
    _overlay(ax, series)
    return save(ax, path)


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
    _overlay(ax, series)
    return save(ax, path)


__all__ = ["DemSeries", "domain_with_dem", "domains_with_dem", "figure4_with_dem"]
