"""Distinct-element results drawn: snapshots of the displaced blocks with velocity arrows
and hinge markers (the paper's Figures 9 and 10), the rotation history against the
four-link model's phi, and an animation (GIF)."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation, PillowWriter
from matplotlib.patches import Polygon


def _displaced(assembly, pos_k: np.ndarray, block: int, pts: np.ndarray) -> np.ndarray:
    local = np.asarray(pts) - assembly.centroids[block]
    th = pos_k[block, 2]
    c, s = np.cos(th), np.sin(th)
    return np.column_stack(
        [pos_k[block, 0] + c * local[:, 0] - s * local[:, 1],
         pos_k[block, 1] + s * local[:, 0] + c * local[:, 1]]
    )


def _sample(result, time: float) -> int:
    return int(np.clip(np.searchsorted(result.times, time), 0, len(result.times) - 1))


def plot_dem_snapshot(result, time: float, ax=None, *, arrows: bool = True,
                      relative: bool = True, arrow_scale: float | None = None):
    """The blocks at ``time`` (s), with centroid velocity arrows and hinge markers.

    Parameters
    ----------
    result : BlockResult
    time : float
        s; the nearest recorded sample is drawn.
    ax : matplotlib Axes, optional
    arrows : bool
        Draw velocity vectors (relative to the ground when ``relative``), as in Figure 9.
    relative : bool
        Draw in the frame of the ground (subtract the base displacement and velocity).
    arrow_scale : float, optional
        Arrow length per m/s, m (default: a tenth of the assembly width per peak speed).

    Returns
    -------
    matplotlib Axes

    Notes
    -----
    A hinge marker (dot) sits at the closed end of every joint whose other end is open by
    more than ``settings.hinge_opening * reference_length``.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4))
    asm = result.assembly
    k = _sample(result, time)
    pos = result.positions[k].copy()
    vel = result.velocities[k].copy()
    if relative:
        pos[:, 0] -= result.base_displacement[k]
        vel[:, 0] -= result.base_velocity[k]
    for i, outline in enumerate(asm.outlines):
        xy = _displaced(asm, pos, i, outline)
        base = bool(asm.base[i])
        ax.add_patch(Polygon(xy, closed=True, facecolor="0.75" if base else "0.9",
                             edgecolor="0.3" if base else "k", lw=0.8))
    free = asm.free_blocks
    if arrows and len(free):
        speeds = np.hypot(vel[free, 0], vel[free, 1])
        width = np.ptp(np.vstack(asm.polygons)[:, 0])
        scale = arrow_scale or (0.1 * width / max(float(np.max(np.abs(result.velocities[:, free, :2]))),
                                                 1e-9))
        if np.any(speeds > 0):
            ax.quiver(pos[free, 0], pos[free, 1], vel[free, 0] * scale, vel[free, 1] * scale,
                      angles="xy", scale_units="xy", scale=1, color="tab:blue", width=0.004)
    opened = result.hinge_open[k]
    for j, joint in enumerate(asm.joints):
        for end in range(2):
            if opened[j, 1 - end] and not opened[j, end]:
                p = _displaced(asm, pos, joint.left, joint.points[end : end + 1])[0]
                ax.plot(p[0], p[1], "o", color="tab:red", ms=6, zorder=5)
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    from archquake.blocks.result import hinge_label, open_hinges

    ax.set_title(f"t = {result.times[k]:.2f} s   {hinge_label(open_hinges(result, result.times[k]))}",
                 fontsize=9)
    return ax


def plot_dem_snapshots(result, times, *, ncols: int = 3):
    """A grid of `plot_dem_snapshot` panels (the paper's Figure 9). Returns the Figure."""
    times = list(times)
    nrows = int(np.ceil(len(times) / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(4 * ncols, 3 * nrows), squeeze=False)
    for ax, t in zip(axes.flat, times):
        plot_dem_snapshot(result, t, ax)
    for ax in list(axes.flat)[len(times):]:
        ax.set_visible(False)
    fig.tight_layout()
    return fig


def plot_dem_rotation(result, ax=None, *, label: str = "DEM", color: str | None = None):
    """The rotation measure (rad) against time, comparable with the four-link model's phi
    (``History.signed_rotation``); first impact and collapse marked."""
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 3.5))
    ax.plot(result.times, result.rotation, label=label, color=color)
    if result.first_impact_time is not None:
        ax.axvline(result.first_impact_time, color="0.5", ls=":", lw=0.8)
    if result.collapse_time is not None:
        k = _sample(result, result.collapse_time)
        ax.plot(result.times[k], result.rotation[k], "x", color="tab:red", ms=8)
    ax.axhline(0.0, color="0.7", lw=0.6)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("rotation of the first link (rad)")
    ax.legend()
    return ax


def animate_dem(result, path: str | Path, *, fps: int = 20, every: int | None = None) -> Path:
    """Write a GIF of the motion (frames every ``every`` samples, default ~``fps`` per s)."""
    path = Path(path)
    if every is None:
        dt = float(np.median(np.diff(result.times))) if len(result.times) > 1 else 1.0
        every = max(1, int(round(1.0 / (fps * dt))))
    frames = list(range(0, len(result.times), every))
    fig, ax = plt.subplots(figsize=(6, 4))
    allxy = np.vstack(result.assembly.outlines)
    pad = 0.1 * np.ptp(allxy[:, 0])
    limits = (allxy[:, 0].min() - pad, allxy[:, 0].max() + pad,
              allxy[:, 1].min() - pad, allxy[:, 1].max() + pad)

    def draw(k):
        ax.clear()
        plot_dem_snapshot(result, float(result.times[k]), ax)
        ax.set_xlim(limits[0], limits[1])
        ax.set_ylim(limits[2], limits[3])

    anim = FuncAnimation(fig, draw, frames=frames)
    anim.save(str(path), writer=PillowWriter(fps=fps))
    plt.close(fig)
    return path


__all__ = ["animate_dem", "plot_dem_rotation", "plot_dem_snapshot", "plot_dem_snapshots"]
