"""The line of thrust of the moving arch (paper Figure 8): displaced voussoirs, the hinges of
the open mechanism and the line of thrust, with the joints where it leaves the section."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from archquake.geometry.arch import Arch
from archquake.plotting.arch import plot_arch
from archquake.plotting.figures import save


def plot_motion_state(arch: Arch, state, ax=None, *, title: str | None = None):
    """One snapshot: the arch in its displaced shape, hinges and line of thrust.

    Parameters
    ----------
    arch : Arch
    state : archquake.thrust.MotionState
    ax : matplotlib Axes, optional
    title : str, optional
        Default: time, rotation and where the line of thrust leaves the section.

    Returns
    -------
    matplotlib Axes
    """
    ax = plot_arch(arch, ax, voussoir_positions=state.positions,
                   hinges=state.hinge_points if state.hinge_points is not None else None,
                   thrust_line=state.thrust_points, show_ghost=True)
    out = state.outside
    bad = np.flatnonzero((out > 0) & np.isfinite(out))
    if bad.size:
        pts = state.thrust_points[bad]
        ax.plot(pts[:, 0], pts[:, 1], "x", color="#c0392b", markersize=9, markeredgewidth=2,
                label="outside the section", zorder=6)
    if title is None:
        j = state.exit_joint
        where = ("inside the section" if j is None else
                 f"leaves the section at joint {j} by {out[j]:.2f} m")
        side = {1: "", -1: "'", 0: " (locked)"}[state.side]
        title = (f"t = {state.t:.2f} s, phi{side} = {math.degrees(state.phi):.2f} deg\n"
                 f"thrust {where}")
    ax.set_title(title, fontsize=9)
    return ax


def save_thrust_snapshots(arch: Arch, states: Sequence, path: str | Path, *,
                          suptitle: str | None = None) -> Path:
    """Figure 8: one panel per state (three per row), saved to ``path``."""
    n = len(states)
    cols = min(3, n)
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.6 * cols, 3.4 * rows), squeeze=False)
    for k, (ax, state) in enumerate(zip(axes.flat, states)):
        plot_motion_state(arch, state, ax)
        ax.set_title(f"({chr(ord('a') + k)}) " + ax.get_title(), fontsize=9)
        if k:
            ax.set_xlabel("")
            ax.set_ylabel("")
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    for ax in list(axes.flat)[1:n]:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), frameon=False, fontsize=9)
    if suptitle:
        fig.suptitle(suptitle, fontsize=11)
    fig.tight_layout(rect=(0, 0.05, 1, 0.97 if suptitle else 1))
    return save(fig, path, dpi=130, tight=False)


__all__ = ["plot_motion_state", "save_thrust_snapshots"]
