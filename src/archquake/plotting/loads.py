"""Figures of the loads an arch carries: the fill drawn under the line of thrust at collapse,
and the traffic load's multiplier along the span."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from archquake.plotting.arch import arch_title, draw_loads, plot_arch
from archquake.plotting.figures import save


def plot_capacity(result, ax=None):
    """The arch at the traffic load's collapse: fill, hinges, line of thrust, load.

    Parameters
    ----------
    result : archquake.limit.capacity.TrafficCapacity
    """
    arch = result.arch
    ax = plot_arch(arch, ax, hinges=result.mechanism.hinges, thrust_line=result.thrust_line)
    draw_loads(ax, arch, result.carried, result.loads, result.extent_m)
    ax.set_title(f"{arch_title(arch)}\ntraffic {result.traffic.load / 1e3:g} kN/m at "
                 f"{result.traffic.position:.3g} m: collapse multiplier {result.multiplier:.3f} "
                 f"({result.collapse_load_N_m / 1e3:.4g} kN/m)", fontsize=10)
    top = result.carried.surface if result.carried.surface is not None else arch.crown_point[1]
    lo, hi = ax.get_ylim()
    ax.set_ylim(lo, max(hi, float(top) + 0.3 * arch.radius))
    ax.legend(loc="lower center", fontsize=8, frameon=False)
    return ax


def plot_capacity_scan(scan, ax=None):
    """The traffic load's multiplier against its position along the span."""
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(scan.positions_m, scan.multipliers, color="tab:blue", marker=".", markersize=3)
    crit = scan.critical
    ax.plot([crit.traffic.position], [crit.multiplier], "o", color="tab:red",
            label=f"critical: {crit.multiplier:.3f} at {crit.traffic.position:.3g} m")
    ax.set_xlabel("load position from the left springing of the intrados (m)")
    ax.set_ylabel("collapse multiplier on the traffic load")
    ax.set_ylim(0, min(float(np.max(scan.multipliers)), 5 * crit.multiplier) * 1.05)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=9, frameon=False)
    return ax


def save_capacity(result, path: str | Path, scan=None) -> Path:
    """The collapse at the (critical) position, beside the multiplier along the span when
    ``scan`` is given, saved to ``path``."""
    if scan is None:
        fig, ax = plt.subplots(figsize=(7.5, 4.8))
        plot_capacity(result, ax)
        return save(fig, path, dpi=150)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(13, 4.8))
    plot_capacity(result, a1)
    plot_capacity_scan(scan, a2)
    return save(fig, path, dpi=150)


__all__ = ["plot_capacity", "plot_capacity_scan", "save_capacity"]
