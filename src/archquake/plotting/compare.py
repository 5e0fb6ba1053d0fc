"""The four-link model beside the distinct-element model: Figure 4(b)-(d) overlays, failure
domains with DEM boundaries (Figures 6, 11), Figure 8 next to Figure 9, and Figure 10's
inter-stone displacements."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from archquake.plotting.dem import plot_dem_rotation, plot_dem_snapshot
from archquake.plotting.domains import plot_domain
from archquake.plotting.figures import save
from archquake.plotting.history import plot_ground_motion, plot_history
from archquake.plotting.thrust import plot_motion_state

_DEM_STYLE = {"hinges": ("--", "tab:blue", "DEM, arch cut at the hinges"),
              "voussoirs": ("-.", "tab:red", "DEM, every voussoir a block")}


def save_dem_rotation(result, path: str | Path, *, label: str | None = None) -> Path:
    """The rotation history of a block model alone (``archquake run --plot`` with ``--model
    dem`` or ``rigid``, whose chain returns the same result)."""
    fig, (ax, strip) = plt.subplots(2, 1, figsize=(6.4, 4.6), sharex=True,
                                    gridspec_kw={"height_ratios": [3, 1]})
    plot_dem_rotation(result, ax, label=label or f"DEM ({result.assembly.name})")
    ax.set_xlabel("")
    plot_hinge_sets(result, strip)
    return save(fig, path, dpi=120)


def plot_hinge_sets(result, ax, *, labels: int = 12):
    """The number of open hinges of a block model against time (a step line), each change of
    the hinge set marked and, when there are at most ``labels`` changes, labelled with its
    hinges (``BlockResult.hinge_sets``)."""
    sets = result.hinge_sets()
    end = result.end_time
    if sets:
        t = [e.time_s for e in sets] + [end]
        n = [len(e.hinges.split()) for e in sets]
        ax.step(t, n + n[-1:], where="post", color="0.2", lw=1.0)
        if len(sets) <= labels:
            for e, ni in zip(sets, n):
                ax.annotate(e.hinges or "closed", (e.time_s, ni), fontsize=6, rotation=60,
                            xytext=(2, 2), textcoords="offset points")
    ax.set_ylabel("hinges")
    ax.set_xlabel("time (s)")
    ax.set_xlim(0.0, max(end, 1e-9))
    return ax


def plot_history_comparison(comparisons: Sequence, ax=None, *, t_end: float | None = None):
    """One motion: the four-link model's phi (black, impacts dotted, collapse crossed) and the DEM
    rotation of each comparison (``HistoryComparison``) dashed.

    Returns
    -------
    matplotlib Axes
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 3.2))
    first = comparisons[0]
    plot_history(first.fourlink, ax, label="four-link", color="k")
    for c in comparisons:
        style, colour, label = _DEM_STYLE.get(c.assembly, ("--", None, c.assembly))
        d = c.dem
        keep = d.times <= (t_end if t_end is not None else np.inf)
        ax.plot(d.times[keep], d.rotation[keep], style, color=colour, lw=1.3, label=label)
        if d.collapse_time is not None and (t_end is None or d.collapse_time <= t_end):
            k = int(np.searchsorted(d.times, d.collapse_time))
            k = min(k, d.times.size - 1)
            ax.plot(d.times[k], d.rotation[k], "x", color=colour, ms=8)
    if t_end is not None:
        ax.set_xlim(0, t_end)
    ax.legend(fontsize=7, loc="lower left")
    return ax


def figure4_comparison(comparisons: dict, path: str | Path, *, t_end: float = 4.0,
                       magnitude_g: float = 1.0) -> Path:
    """The paper's Figure 4 with both DEM arches: (a) the impulses, then one panel per t_p.

    Parameters
    ----------
    comparisons : dict
        ``{(t_p, assembly): HistoryComparison}`` (`archquake.compare.figure4_comparisons`).
    path : output file
    t_end : float, s
    """
    from archquake.ground.pulses import StepImpulse

    tps = sorted({tp for tp, _ in comparisons}, reverse=True)
    fig, axes = plt.subplots(len(tps) + 1, 1, figsize=(7.0, 2.3 * (len(tps) + 1)), sharex=True)
    for tp in tps:
        plot_ground_motion(StepImpulse.from_g(magnitude_g, tp), t_end, axes[0],
                           label=f"t_p = {tp:.2f} s")
    axes[0].legend(fontsize=7, loc="upper right")
    axes[0].set_title(f"(a) step impulses, a = {magnitude_g:g} g", fontsize=9, loc="left")
    for k, tp in enumerate(tps):
        ax = axes[k + 1]
        cs = [c for (t, _), c in comparisons.items() if t == tp]
        plot_history_comparison(cs, ax, t_end=t_end)
        fl = cs[0].fourlink
        parts = [f"four-link {_what(fl.outcome.value, fl.collapse_half_cycle)}"]
        for c in cs:
            parts.append(f"DEM {c.assembly} {_what(c.dem.outcome.value, c.dem.collapse_half_cycle)}")
        ax.set_title(f"({'bcdefgh'[k]}) t_p = {tp:.2f} s: " + "; ".join(parts), fontsize=8, loc="left")
        rot = fl.history.signed_rotation
        lim = max(0.08, 1.2 * float(np.max(np.abs(rot), initial=0.0)))
        ax.set_ylim(-min(lim, 0.25), min(lim, 0.25))
        if k < len(tps) - 1:
            ax.set_xlabel("")
    axes[0].set_xlabel("")
    return save(fig, path, dpi=120)


def _what(outcome: str, half: int | None) -> str:
    return outcome.replace("_", " ") + (f" ({half})" if half else "")


def plot_domain_comparison(comparison, ax=None, *, title: str | None = None):
    """The four-link failure domain (regions and boundaries) with the DEM boundaries as markers:
    triangles the three-voussoir arch's first-half-cycle boundary, squares the voussoir arch's
    governing boundary (paper Figures 6, 11)."""
    ax = plot_domain(comparison.fourlink, ax, title=title, bands=False)
    for dd, marker, colour, label in (
        (comparison.first, "v", "firebrick", "DEM 1st half cycle (arch cut at the hinges)"),
        (comparison.governing, "s", "darkorange", "DEM governing (every voussoir a block)"),
    ):
        if dd is None:
            continue
        ax.plot(dd.domain.durations, dd.boundary_g, marker, color=colour, mec="k", ms=7, ls="none",
                label=label)
    ax.legend(fontsize=7, loc="upper right")
    return ax


def domain_comparison_figure(comparisons: Sequence, path: str | Path) -> Path:
    """One panel per `DomainComparison` (several radii, or step and
    sine), saved to ``path``."""
    n = len(comparisons)
    cols = min(3, n)
    rows = -(-n // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(6.0 * cols, 4.6 * rows), squeeze=False)
    for ax, c in zip(axes.flat, comparisons):
        plot_domain_comparison(c, ax, title=c.label or None)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    return save(fig, path, dpi=120)


def figure9_comparison(arch, states: Sequence, dem_result, path: str | Path) -> Path:
    """Figure 8 (the four-link mechanism's line of thrust and hinges, left) next to Figure 9 (DEM blocks,
    velocity arrows relative to the ground and hinge dots, right), one row per instant."""
    n = len(states)
    fig, axes = plt.subplots(n, 2, figsize=(10.0, 3.0 * n), squeeze=False)
    for k, state in enumerate(states):
        plot_motion_state(arch, state, axes[k, 0])
        axes[k, 0].set_title(f"({chr(97 + k)}) four-link, " + axes[k, 0].get_title(), fontsize=8)
        plot_dem_snapshot(dem_result, state.t, axes[k, 1])
        axes[k, 1].set_title(f"({chr(97 + k)}) DEM, t = {state.t:.2f} s: hinges (dots), velocities",
                             fontsize=8)
        for ax in axes[k]:
            ax.set_xlabel("")
            ax.set_ylabel("")
            leg = ax.get_legend()
            if leg is not None:
                leg.remove()
    return save(fig, path, dpi=100)


def figure10(result, time: float, path: str | Path, *, reference=None) -> Path:
    """Figure 10: the DEM snapshot at ``time`` and the relative displacements of the voussoirs
    at every joint (slip along the joint and opening at its intrados and extrados ends, mm);
    ``reference`` (another BlockResult, e.g. with the paper's damping) drawn alongside."""
    from archquake.compare.snapshots import joint_displacements

    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11.0, 4.0),
                                   gridspec_kw={"width_ratios": [1.2, 1.0]})
    plot_dem_snapshot(result, time, ax0)
    runs = [("reduced damping", result)] + ([("paper's damping", reference)] if reference else [])
    width = 0.8 / (2 * len(runs))
    for n, (label, res) in enumerate(runs):
        jd = joint_displacements(res, time)
        x = np.arange(jd["slip_m"].size)
        ax1.bar(x + (2 * n) * width - 0.4 + width / 2, 1e3 * jd["slip_m"], width,
                label=f"slip, {label}")
        ax1.bar(x + (2 * n + 1) * width - 0.4 + width / 2, 1e3 * jd["max_opening_m"], width,
                label=f"opening, {label}", alpha=0.6)
    ax1.set_xlabel("joint (0 = left springing)")
    ax1.set_ylabel("relative displacement [mm]")
    ax1.set_title(f"inter-stone displacements at t = {time:.2f} s", fontsize=9)
    ax1.axhline(0, color="0.6", lw=0.6)
    ax1.legend(fontsize=7)
    return save(fig, path, dpi=120)


__all__ = [
    "domain_comparison_figure",
    "figure10",
    "figure4_comparison",
    "figure9_comparison",
    "plot_domain_comparison",
    "plot_hinge_sets",
    "plot_history_comparison",
    "save_dem_rotation",
]
