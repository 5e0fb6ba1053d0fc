"""Time histories of the rocking arch (the paper's Figure 4) and animations of its motion."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation, PillowWriter

from archquake.constants import STANDARD_GRAVITY
from archquake.plotting.arch import plot_arch
from archquake.plotting.figures import save


def plot_history(result, ax=None, *, label: str | None = None, color: str | None = None,
                 marks: bool = True):
    """Rotation of the open mechanism against time, as in the paper's Figure 4(b)-(d).

    The curve is ``side * phi``: positive while a row mechanism of the impact law's table is
    open, negative while its mirror image is (under Eq. 4, after an odd number of impacts).
    Impacts are marked with dots, the collapse with a cross; where the law moves on to another
    mechanism than the mirror image (the chain law), each impact is labelled with the hinges of
    the mechanism that opens (``"0e 2i 5e 7i"``).

    Parameters
    ----------
    result : SimulationResult
        With its history recorded.
    ax : matplotlib Axes, optional
    label, color : str, optional
    marks : bool
        Mark impacts and collapse.

    Returns
    -------
    matplotlib Axes
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 3.2))
    h = result.history
    if h is None:
        raise ValueError("the result has no history: simulate with output_interval != 0")
    line, = ax.plot(h.t, h.signed_rotation, label=label, color=color, lw=1.4)
    if marks:
        if result.impact_times.size:
            ax.plot(result.impact_times, np.zeros_like(result.impact_times), "o", ms=4,
                    color=line.get_color(), label=None)
            events = [e for e in getattr(result, "mechanisms", ()) if e.kind != "onset"]
            if any(e.row > 0 for e in events):
                for e in events[:12]:
                    ax.annotate(e.hinges or "?", (e.time_s, 0.0), textcoords="offset points",
                                xytext=(2, 4), fontsize=6, rotation=60,
                                color=line.get_color())
        if result.collapse_time is not None:
            i = np.searchsorted(h.t, result.collapse_time) - 1
            ax.plot([result.collapse_time], [h.signed_rotation[max(i, 0)]], "x", ms=8,
                    color=line.get_color())
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("rotation phi [rad]")
    return ax


def verdict_text(result) -> str:
    """The verdict of a time history in words, with the impact law's validity: what the plots
    put in their titles (``"indeterminate (computed: collapse in half cycle 2); impact paper:
    outside"``)."""
    what = result.outcome.value.replace("_", " ")
    computed = getattr(result, "computed_outcome", None)
    if result.collapse_half_cycle:
        detail = f"collapse in half cycle {result.collapse_half_cycle}"
        what = (f"{what} (computed: {detail})" if computed is not None
                and computed is not result.outcome else f"{what} in half cycle "
                f"{result.collapse_half_cycle}")
    elif computed is not None and computed is not result.outcome:
        what += f" (computed: {computed.value.replace('_', ' ')})"
    law = getattr(result, "impact_law", None)
    if law is not None:
        what += f"; impact {law}: {result.impact_validity.replace('_', ' ')}"
    return what


def plot_ground_motion(motion, t_end: float, ax=None, *, label: str | None = None,
                       g: float = STANDARD_GRAVITY, samples: int = 2000):
    """Ground acceleration in g against time (the paper's Figure 4(a))."""
    if ax is None:
        _, ax = plt.subplots(figsize=(6.0, 2.4))
    t = np.linspace(0.0, t_end, samples)
    bps = np.asarray(motion.breakpoints(), dtype=float)
    t = np.unique(np.concatenate([t, bps, np.nextafter(bps, -np.inf)]))
    t = t[(t >= 0) & (t <= t_end)]
    ax.plot(t, np.asarray(motion.acceleration(t)) / g, label=label, lw=1.2)
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("ground acceleration [g]")
    return ax


def figure4(results: Sequence, motions: Sequence, labels: Sequence[str], path: str | Path, *,
            t_end: float = 3.0, title: str | None = None) -> Path:
    """The paper's Figure 4: the impulses (a) and the time histories (b), (c), (d)...

    Parameters
    ----------
    results : sequence of SimulationResult
    motions : sequence of GroundMotion
    labels : sequence of str
    path : output file (.png, .pdf, .svg)
    t_end : float, s
    """
    n = len(results)
    fig, axes = plt.subplots(n + 1, 1, figsize=(6.5, 2.1 * (n + 1)), sharex=True)
    for motion, label in zip(motions, labels):
        plot_ground_motion(motion, t_end, axes[0], label=label)
    axes[0].legend(fontsize=7, loc="upper right")
    axes[0].set_title("(a) impulses" if title is None else title, fontsize=9, loc="left")
    letters = "bcdefghij"
    for k, (res, label) in enumerate(zip(results, labels)):
        ax = axes[k + 1]
        plot_history(res, ax, label=label)
        what = verdict_text(res)
        if res.impact_times.size:
            what += f"; first impact {res.impact_times[0]:.2f} s"
        ax.set_title(f"({letters[k]}) {label}: {what}", fontsize=9, loc="left")
        lim = max(0.08, 1.2 * float(np.max(np.abs(res.history.signed_rotation[res.history.t <= t_end]),
                                           initial=0.0)))
        ax.set_ylim(-min(lim, 0.3), min(lim, 0.3))
        ax.set_xlim(0.0, t_end)
    for ax in axes[:-1]:
        ax.set_xlabel("")
    return save(fig, path, dpi=130)


def animate_history(prepared, result, path: str | Path, *, fps: int = 20, t_end: float | None = None,
                    frames: int | None = None, exaggerate: float = 1.0,
                    g: float = STANDARD_GRAVITY) -> Path:
    """An animated GIF of the rocking arch: voussoirs in their displaced positions, the hinges
    of the open mechanism, the ground acceleration in the title.

    Parameters
    ----------
    prepared : PreparedMechanism
        The mechanism the result was computed with.
    result : SimulationResult
        With its history recorded.
    path : str or Path
        Output .gif.
    fps : int
        Frames per second of real time (the GIF plays in real time).
    t_end : float, optional
        Last time shown, s (default: the end of the history).
    frames : int, optional
        Number of frames (default fps * t_end, at most 400).
    exaggerate : float
        Factor on the rotations for visibility (1 = true scale).
    """
    from archquake.mechanism.configuration import hinge_points, voussoir_positions
    from archquake.mechanism.prepared import PreparedMechanism

    h = result.history
    if h is None or h.t.size == 0:
        raise ValueError("the result has no history: simulate with output_interval != 0")
    t_last = float(h.t[-1]) if t_end is None else min(float(t_end), float(h.t[-1]))
    n_frames = frames or int(min(400, max(2, fps * t_last)))
    times = np.linspace(0.0, t_last, n_frames)
    idx = np.clip(np.searchsorted(h.t, times), 0, h.t.size - 1)
    arch = prepared.mechanism.arch
    lawful = PreparedMechanism.build(prepared, result.impact_law)  # the result's table
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    span = arch.extrados_radius * 1.15
    y0 = min(arch.springing_y, 0.0) - 0.15 * arch.radius

    def draw(i):
        ax.clear()
        k = idx[i]
        side = int(h.side[k])
        phi = float(h.phi[k]) * exaggerate
        # the mechanism open at this sample: a row of the impact law's table
        member = prepared
        if side != 0 and h.mechanism_row is not None and int(h.mechanism_row[k]) > 0:
            member = lawful.member(int(h.mechanism_row[k]))
        pos = voussoir_positions(member, phi, side)
        hinges = hinge_points(member, phi, side) if side != 0 else None
        plot_arch(arch, ax, voussoir_positions=pos, hinges=hinges, show_ghost=True)
        ax.set_xlim(-span, span)
        ax.set_ylim(y0, arch.extrados_radius * 1.1)
        ax.set_aspect("equal")
        ax.set_title(f"t = {h.t[k]:5.2f} s   ground {h.ground_acceleration[k] / g:+.2f} g   "
                     f"phi = {h.phi[k]:.3f} rad" + (f"  (x{exaggerate:g})" if exaggerate != 1 else ""),
                     fontsize=9)
        return ()

    anim = FuncAnimation(fig, draw, frames=n_frames, blit=False)
    path = Path(path)
    anim.save(path, writer=PillowWriter(fps=fps))
    plt.close(fig)
    return path


__all__ = ["animate_history", "figure4", "plot_ground_motion", "plot_history", "verdict_text"]
