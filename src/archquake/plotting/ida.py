"""Incremental dynamic analysis figures: IDA curves and fragility curves.

Functions take an `archquake.ida.IdaResult` (and fits from
`archquake.ida.fragility`), an optional ``ax``, and return the ``ax``; they never call
``show()`` and do not choose a matplotlib backend (`save_ida` writes a file through a
figure it creates and closes, so it works without a display).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np


def _axes(ax, size=(6.4, 4.6)):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=size)
    return ax


def plot_ida_curves(result, ax=None, *, title: str | None = None):
    """IDA curves: intensity (vertical) against the peak rotation over the crest rotation
    phi / phi_crit (horizontal), one line per record through its surviving runs.

    Collapses are drawn at phi / phi_crit = 1 as crosses; the first collapse of each record
    closes its line (a flat-lining IDA curve); surviving runs above a record's first collapse
    (resurrections) are drawn as open circles.
    """
    ax = _axes(ax)
    crit = result.critical_rotation_rad
    cmap = _cmap(len(result.records))
    first_collapses, resurrected = [], []
    for i, rec in enumerate(result.records):
        colour = cmap(i)
        ratio = np.minimum(rec.peak_rotation / crit, 1.0)
        collapsed = rec.collapsed
        first = rec.first_collapse
        below = rec.levels < (first.low if first is not None else np.inf)
        xs = list(ratio[below])
        ys = list(rec.levels[below])
        if first is not None:
            xs.append(1.0)
            ys.append(first.low)
            first_collapses.append(first.low)
        ax.plot(xs, ys, "-", color=colour, lw=0.9, alpha=0.85)
        ax.plot(ratio[below], rec.levels[below], ".", color=colour, ms=3)
        ax.plot(np.ones(int(collapsed.sum())), rec.levels[collapsed], "x", color=colour, ms=4,
                alpha=0.7)
        res = ~collapsed & ~below
        if res.any():
            resurrected.append((ratio[res], rec.levels[res], colour))
    for x, y, colour in resurrected:
        ax.plot(x, y, "o", mfc="none", mec=colour, ms=5)
    # legend proxies
    ax.plot([], [], "kx", label="collapse (drawn at the crest)")
    ax.plot([], [], "ko", mfc="none", label="survives above a collapse (resurrection)")
    ax.set_xlabel(r"peak rotation / rotation at the crest, $\varphi_{max}/\varphi_{crit}$")
    ax.set_ylabel(result.im.description)
    ax.set_xlim(0, 1.08)
    ax.set_ylim(0, result.ceiling * 1.02)
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title(title or f"IDA curves, {len(result.records)} records "
                          f"({result.model.value} model)", fontsize=10)
    return ax


def plot_fragility(result, fits: dict, ax=None, *, title: str | None = None):
    """Fragility: the collapse fraction per level (points), the empirical distribution of the
    first-collapse intensities (steps) and the two lognormal fits (``fits`` from
    `archquake.ida.fragility.fragility_of`)."""
    ax = _axes(ax)
    levels = fits["levels"]
    ax.plot(levels, fits["fraction"], "o", color="C0", ms=4,
            label="collapse fraction per level")
    first = np.sort(result.first_collapse_levels[np.isfinite(result.first_collapse_levels)])
    n = len(result.records)
    if first.size:
        ax.step(np.r_[first[0], first], np.r_[0, np.arange(1, first.size + 1) / n], where="post",
                color="C1", lw=1, label="first collapses (cumulative)")
    x = np.geomspace(min(levels[0], first[0] if first.size else levels[0]), result.ceiling, 200)
    unit = result.im.unit
    for key, colour, style in (("first_collapse", "C1", "--"), ("collapse_fraction", "C0", "-")):
        fit = fits.get(key)
        if fit is None:
            continue
        ax.plot(x, fit.probability(x), style, color=colour,
                label=f"lognormal fit ({key.replace('_', ' ')}): median {fit.median:.3g} "
                      f"{unit}, beta {fit.beta:.2f}")
    ax.set_xlabel(result.im.description)
    ax.set_ylabel("probability of collapse")
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlim(0, result.ceiling)
    ax.legend(loc="lower right", fontsize=7)
    ax.set_title(title or "collapse fragility", fontsize=10)
    return ax


def save_ida(result, fits: dict, path: str | Path) -> Path:
    """IDA curves beside the fragility curves, written to ``path`` (.png, .pdf, .svg)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(12, 4.8))
    ax1, ax2 = fig.subplots(1, 2)
    plot_ida_curves(result, ax1)
    plot_fragility(result, fits, ax2)
    from archquake.plotting.figures import save

    return save(fig, path, dpi=120)


def _cmap(n: int):
    import matplotlib

    cmap = matplotlib.colormaps["viridis"]
    return lambda i: cmap(i / max(1, n - 1) * 0.9)


__all__ = ["plot_fragility", "plot_ida_curves", "save_ida"]
