"""Drawing an arch: voussoirs (undisplaced or moved), hinges and a line of thrust.

`plot_arch` is the general drawing that the other figures build on (the collapse state
of the equivalent static analysis here; the line of thrust during motion and distinct-element
snapshots later). Matplotlib is imported only inside `archquake.plotting`, which never
chooses a backend; functions take an optional ``ax``, return it and never call ``show()``.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Polygon

from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.geometry.hinges import Hinge
from archquake.plotting.figures import save


def moved_outline(outline: np.ndarray, centroid: np.ndarray, position: np.ndarray) -> np.ndarray:
    """A voussoir outline after a rigid displacement (dx, dy) and a rotation about its centroid.

    Parameters
    ----------
    outline : ndarray, shape (m, 2)
        Points in the undisplaced arch, m.
    centroid : ndarray, shape (2,)
        The voussoir's undisplaced centroid, m.
    position : array_like, shape (3,)
        Centroid displacement dx, dy (m) and rotation (rad, counter-clockwise).
    """
    dx, dy, rot = (float(v) for v in position)
    c, s = np.cos(rot), np.sin(rot)
    rel = outline - centroid
    turned = np.column_stack([c * rel[:, 0] - s * rel[:, 1], s * rel[:, 0] + c * rel[:, 1]])
    return turned + centroid + np.array([dx, dy])


def plot_arch(
    arch: VoussoirChain,
    ax=None,
    *,
    voussoir_positions: np.ndarray | None = None,
    hinges: Sequence[Hinge] | np.ndarray | None = None,
    thrust_line: np.ndarray | None = None,
    hinge_labels: Sequence[str] | None = None,
    facecolor: str = "#d9c8a9",
    edgecolor: str = "#5a4a32",
    thrust_color: str = "#c0392b",
    hinge_color: str = "#1f4e9c",
    show_ghost: bool = False,
    ground: bool = True,
):
    """Draw ``arch``'s voussoirs, optionally moved, with hinges and a line of thrust.

    Parameters
    ----------
    arch : VoussoirChain
        Any arch (every shape, on piers, or blocks from a file).
    ax : matplotlib Axes, optional
        Drawn into (a new figure if None).
    voussoir_positions : ndarray, shape (n, 3), optional
        Rigid displacement of each voussoir: dx, dy of its centroid (m) and its rotation about
        its centroid (rad, counter-clockwise). None draws the undisplaced arch.
    hinges : sequence of Hinge or ndarray of shape (m, 2), optional
        Hinge points to mark (m), as given (not moved with the voussoirs).
    thrust_line : ndarray, shape (n+1, 2), optional
        Where the line of thrust crosses each joint (m); drawn as the polygon through them.
    hinge_labels : sequence of str, optional
        Labels of the hinges (default A, B, C, D when there are four).
    show_ghost : bool
        With ``voussoir_positions``, also draw the undisplaced arch faintly.
    ground : bool
        Draw the two springing supports.

    Returns
    -------
    matplotlib Axes
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(7.0, 4.2))
    n = arch.voussoirs
    positions = None
    if voussoir_positions is not None:
        positions = np.asarray(voussoir_positions, dtype=float)
        if positions.shape != (n, 3):
            raise ValueError(f"voussoir_positions must have shape ({n}, 3), got {positions.shape}")
    outlines = []
    for k in range(n):
        outline = arch.voussoir_outline(k)
        if positions is not None:
            if show_ghost:
                ax.add_patch(Polygon(outline, closed=True, facecolor="none", edgecolor="0.75",
                                     linewidth=0.6, linestyle=":"))
            outline = moved_outline(outline, arch.voussoir_centroids[k], positions[k])
        outlines.append(outline)
        ax.add_patch(Polygon(outline, closed=True, facecolor=facecolor, edgecolor=edgecolor,
                             linewidth=0.8))
    if ground:
        for j in (0, n):
            p, q = arch.intrados_points[j], arch.extrados_points[j]
            d = q - p
            normal = np.array([d[1], -d[0]]) * (-1 if j == 0 else 1)  # away from the arch
            normal = normal / np.linalg.norm(normal) * 0.25 * arch.thickness
            ax.add_patch(Polygon(np.array([p, q, q + normal, p + normal]), closed=True,
                                 facecolor="0.55", edgecolor="0.3", hatch="///", linewidth=0.6))
    if thrust_line is not None:
        tl = np.asarray(thrust_line, dtype=float)
        ax.plot(tl[:, 0], tl[:, 1], "-", color=thrust_color, linewidth=1.6, marker="o",
                markersize=3, label="line of thrust", zorder=4)
    if hinges is not None:
        if isinstance(hinges, np.ndarray):
            pts = np.asarray(hinges, dtype=float).reshape(-1, 2)
        else:
            pts = np.array([[h.x, h.y] for h in hinges]).reshape(-1, 2)
        labels = list(hinge_labels) if hinge_labels is not None else (
            list("ABCD") if len(pts) == 4 else [""] * len(pts))
        ax.plot(pts[:, 0], pts[:, 1], "o", markersize=8, markerfacecolor="white",
                markeredgecolor=hinge_color, markeredgewidth=2.0, label="hinges", zorder=5)
        pad = 0.06 * arch.radius
        # labels pushed away from the circle's centre (a circular arch) or a point below the
        # springing line (any other shape)
        below = arch.springing_y - 0.3 * arch.rise
        centre = np.zeros(2) if isinstance(arch, Arch) else np.array([0.0, below])
        for p, label in zip(pts, labels, strict=True):
            r = np.hypot(*(p - centre))
            offset = (p - centre) / r * pad if r > 0 else np.array([0.0, pad])
            ax.annotate(label, p + offset, ha="center", va="center", color=hinge_color,
                        fontsize=11, fontweight="bold", zorder=6)
    every = np.vstack(outlines)
    lo, hi = every.min(axis=0), every.max(axis=0)
    margin = 0.08 * (hi - lo).max()
    ax.set_xlim(lo[0] - margin, hi[0] + margin)
    ax.set_ylim(min(lo[1], arch.springing_y - 0.3 * arch.thickness) - margin, hi[1] + margin)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    return ax


def plot_limit_analysis(result, ax=None):
    """The arch at collapse: hinges A-D and the line of thrust through them.

    Parameters
    ----------
    result : archquake.limit.LimitAnalysis
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes
    """
    arch = result.arch
    ax = plot_arch(arch, ax, hinges=result.mechanism.hinges, thrust_line=result.thrust_line)
    if getattr(result, "carried", None) is not None:
        draw_loads(ax, arch, result.carried, result.loads)
    # the horizontal load, drawn at the crown (above the fill)
    top = float(arch.crown_point[1])
    if getattr(result, "carried", None) is not None and result.carried.surface is not None:
        top = max(top, result.carried.surface)
    crown = np.array([0.0, top + 0.12 * arch.radius])
    ax.annotate("", crown + [0.12 * arch.radius, 0.0], crown,
                arrowprops={"arrowstyle": "-|>", "color": "0.2", "linewidth": 1.5})
    ax.text(crown[0] - 0.02 * arch.radius, crown[1], rf"$\lambda g$ = {result.collapse_acceleration_g:.3f} g",
            ha="right", va="center", fontsize=10)
    where = "symmetric" if result.symmetric else "asymmetric"
    ax.set_title(
        f"{arch_title(arch)}: collapse at {result.collapse_acceleration_g:.3f} g, "
        f"{where} hinges\nfriction demand {result.min_friction:.3f} at joint "
        f"{result.min_friction_joint}",
        fontsize=10,
    )
    lo, hi = ax.get_ylim()
    ax.set_ylim(lo, max(hi, crown[1] + 0.05 * arch.radius))
    ax.legend(loc="lower center", fontsize=9, frameon=False)
    return ax


def draw_loads(ax, arch, carried, loads=None, extent=None):
    """Shade the fill columns (``carried.fill_columns``), draw the fill surface, the backing's
    top, the point loads and the traffic's loaded length (``extent``, x from/to, m)."""
    for col in carried.fill_columns:
        if col.size:
            ax.add_patch(Polygon(col, closed=True, facecolor="#e8d9b5", edgecolor="#cdb98a",
                                 linewidth=0.4, zorder=0))
    if carried.surface is not None:
        xs = [c[:, 0] for c in carried.fill_columns if c.size]
        if xs:
            x_all = np.concatenate(xs)
            ax.plot([x_all.min(), x_all.max()], [carried.surface] * 2, color="#8a6d3b",
                    linewidth=1.0, label="fill surface")
    if loads is not None and loads.backing is not None:
        ep = arch.extrados_points
        for end, h, out in ((0, loads.backing.left, -1), (-1, loads.backing.right, 1)):
            if h > 0:
                y = float(arch.intrados_points[end, 1]) + h
                x = float(ep[end, 0])
                ax.plot([x, x + out * 0.15 * arch.radius], [y, y], color="0.3", linewidth=1.5,
                        label="backing" if end == 0 else None)
    if extent is not None:
        a, b = extent
        top = carried.surface if carried.surface is not None else float(arch.crown_point[1])
        y = top + 0.08 * arch.radius
        if b - a > 1e-9:
            ax.plot([a, b], [y, y], color="tab:red", linewidth=3, label="traffic (spread)")
        else:
            ax.annotate("", (a, top), (a, y + 0.1 * arch.radius),
                        arrowprops={"arrowstyle": "-|>", "color": "tab:red", "linewidth": 2})
    return ax


def arch_title(arch: VoussoirChain) -> str:
    """A short description of any arch for a figure title (m, degrees)."""
    d = arch.describe()
    if "radius_m" in d and "shape" not in d:
        text = (f"t/R = {arch.thickness_ratio:.3g}, embrace {np.degrees(arch.embrace):.4g} deg, "
                f"{d['voussoirs']} voussoirs")
    else:
        text = (f"{d.get('shape', 'blocks')}, span {arch.span:.3g} m, rise {arch.rise:.3g} m, "
                f"t = {arch.thickness:.3g} m, {d['voussoirs']} voussoirs")
    if "joints" in d and d["joints"] != "radial":
        text += f" ({d['joints']} joints)"
    if "pier_height_m" in d:
        text += f", piers {d['pier_height_m']:g} x {d['pier_width_m']:g} m"
    return text


def plot_shapes(arches: Sequence[VoussoirChain], titles: Sequence[str] | None = None, *,
                columns: int = 3):
    """A gallery: every arch of ``arches`` drawn in its own panel (the figure of
    docs/geometry.md). Returns the figure."""
    rows = -(-len(arches) // columns)
    fig, axes = plt.subplots(rows, columns, figsize=(4.2 * columns, 3.2 * rows), squeeze=False)
    for k, ax in enumerate(axes.flat):
        if k >= len(arches):
            ax.axis("off")
            continue
        plot_arch(arches[k], ax)
        ax.set_title(titles[k] if titles is not None else arch_title(arches[k]), fontsize=9)
    fig.tight_layout()
    return fig


def save_limit_analysis(result, path: str | Path) -> Path:
    """Draw `plot_limit_analysis` into a new figure and save it to ``path``."""
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    plot_limit_analysis(result, ax)
    return save(fig, path, dpi=150)


__all__ = ["arch_title", "draw_loads", "moved_outline", "plot_arch", "plot_limit_analysis", "plot_shapes",
           "save_limit_analysis"]
