"""Spectra figures: a code's elastic spectrum, records' response spectra, a selected set.

Functions take a result, an optional ``ax``, and return the ``ax``; the ``save_*`` functions
write a file through `archquake.plotting.figures.save`. Accelerations are drawn in g,
periods in s.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from archquake.plotting.figures import axes


def plot_elastic_spectrum(spectrum, periods, *, damping: float = 0.05, ax=None,
                          displacement: bool = False, label: str | None = None):
    """A code's elastic spectrum (``archquake.codes.ElasticSpectrum``): S_e in g against T (s),
    or S_De in m with ``displacement``; the corner periods marked."""
    ax = axes(ax)
    t = np.asarray(periods, dtype=float)
    y = spectrum.sd(t, damping) if displacement else spectrum.sa(t, damping) / spectrum.g
    ax.plot(t, y, "k-", lw=1.8, label=label or f"{spectrum.label()}, {100 * damping:g} %")
    for name in ("TB", "TC", "TD", "TE"):
        corner = getattr(spectrum, name)
        if np.isfinite(corner) and t.min() <= corner <= t.max():
            ax.axvline(corner, color="0.6", lw=0.6, ls=":")
            ax.annotate(f"$T_{name[1]}$", (corner, 0), xytext=(2, 2), textcoords="offset points",
                        xycoords=("data", "axes fraction"), fontsize=7, color="0.4")
    ax.set_xlabel("period T (s)")
    ax.set_ylabel("S$_{De}$ (m)" if displacement else "S$_e$ (g)")
    ax.set_xlim(t.min(), t.max())
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper right", fontsize=8)
    return ax


def save_elastic_spectrum(spectrum, periods, path: str | Path, *, damping: float = 0.05) -> Path:
    """Acceleration and displacement spectra side by side, written to ``path``."""
    from matplotlib.figure import Figure

    from archquake.plotting.figures import save

    fig = Figure(figsize=(11, 4.4))
    ax1, ax2 = fig.subplots(1, 2)
    plot_elastic_spectrum(spectrum, periods, damping=damping, ax=ax1)
    plot_elastic_spectrum(spectrum, periods, damping=damping, ax=ax2, displacement=True)
    return save(fig, path, dpi=120)


def plot_record_spectra(spectra, ax=None, *, title: str | None = None):
    """Each record's response spectrum (thin) and their mean (thick), Sa in g against T in s
    (``archquake.ground.response_spectra.RecordSpectra``)."""
    ax = axes(ax)
    t, g = spectra.periods_s, spectra.g
    for row in spectra.sa:
        ax.plot(t, row / g, "-", color="0.65", lw=0.6)
    if len(spectra) > 1:
        ax.plot([], [], "-", color="0.65", lw=0.6, label=f"{len(spectra)} records")
        ax.plot(t, spectra.mean / g, "k-", lw=2.0, label="mean")
    else:
        ax.lines[-1].set(color="k", lw=1.5, label=spectra.names[0])
    ax.set_xlabel("period T (s)")
    ax.set_ylabel(f"Sa (g), {100 * spectra.damping:g} % damping")
    ax.set_xlim(t.min(), t.max())
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper right", fontsize=8)
    if title:
        ax.set_title(title, fontsize=10)
    return ax


def plot_selection(selection, ax=None, *, target_label: str = "target",
                   title: str | None = None):
    """A selected set (``archquake.ground.selection.Selection``): each scaled spectrum, their
    mean, the target and the band the mean must stay in."""
    ax = axes(ax)
    t, g = selection.periods_s, selection.spectra.g
    for name, row, f in zip(selection.spectra.names, selection.spectra.sa,
                            selection.scale_factors):
        ax.plot(t, row / g, "-", lw=0.7, alpha=0.8, label=f"{name} x {f:.2f}")
    target = selection.target / g
    ax.fill_between(t, target * selection.lower,
                    np.where(np.isfinite(selection.upper), target * selection.upper, np.nan),
                    color="C0", alpha=0.12, lw=0, label="band")
    ax.plot(t, target * selection.lower, "--", color="C0", lw=0.9)
    if np.any(np.isfinite(selection.upper)):
        ax.plot(t, target * selection.upper, "--", color="C0", lw=0.9)
    ax.plot(t, target, "-", color="C0", lw=2.0, label=target_label)
    ax.plot(t, selection.mean / g, "k-", lw=2.2,
            label="mean" + ("" if selection.compatible else " (outside the band)"))
    ax.set_xlabel("period T (s)")
    ax.set_ylabel(f"Sa (g), {100 * selection.spectra.damping:g} % damping")
    ax.set_xlim(t.min(), t.max())
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper right", fontsize=7, ncol=2)
    if title:
        ax.set_title(title, fontsize=10)
    return ax


def save_record_spectra(spectra, path: str | Path, *, title: str | None = None) -> Path:
    """`plot_record_spectra` written to ``path``."""
    from matplotlib.figure import Figure

    from archquake.plotting.figures import save

    fig = Figure(figsize=(7, 4.8))
    plot_record_spectra(spectra, fig.subplots(), title=title)
    return save(fig, path, dpi=120)


def save_selection(selection, path: str | Path, *, target_label: str = "target",
                   title: str | None = None) -> Path:
    """`plot_selection` written to ``path``."""
    from matplotlib.figure import Figure

    from archquake.plotting.figures import save

    fig = Figure(figsize=(8, 5.2))
    plot_selection(selection, fig.subplots(), target_label=target_label, title=title)
    return save(fig, path, dpi=120)


__all__ = [
    "plot_elastic_spectrum",
    "plot_record_spectra",
    "plot_selection",
    "save_elastic_spectrum",
    "save_record_spectra",
    "save_selection",
]
