"""The code check of a local mechanism drawn in the acceleration-displacement plane: the capacity
curve a(d) = alpha(d) g / (e* FC) of the equivalent SDOF system beside the site's demand spectra
(S_e against S_De, the damping of each limit state), with the displacement capacities marked."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from archquake.plotting.figures import save

_COLOURS = {"SLD": "tab:green", "SLV": "tab:orange", "SLC": "tab:red"}


def plot_code_check(result, ax=None):
    """Draw a `CodeCheck` into ``ax`` (a new figure if None).

    Accelerations in g, displacements in m. The demand spectra are the site's, at the damping
    each nonlinear check reads them with, up to the largest period read plus a margin.

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(7.0, 4.6))
    curve = result.curve
    g = curve.g
    fc = result.confidence_factor
    scale = 1.0 / (curve.e_star * fc)
    ax.plot(curve.displacements_m, curve.alphas * scale, color="k", lw=2,
            label=f"capacity a(d) = alpha(d) g / (e* FC), FC = {fc:.2f}")
    top = result.a0_star / g
    periods = [c.period_s for c in result.checks if c.period_s is not None]
    # long periods too: in the window of the capacity curve (accelerations up to about a0*)
    # the demand spectra are their long-period branches, which stopped short of it at 1.5 T
    t_max = max(1.5 * max(periods), 10.0) if periods else 10.0
    t = np.linspace(1e-3, t_max, 2000)
    for c in result.checks:
        colour = _COLOURS.get(c.limit_state, "tab:blue")
        spec = result.spectra[c.limit_state]
        if c.quantity == "displacement":
            damping = c.damping if c.damping is not None else 0.05
            if result.position.at_ground:
                ax.plot(spec.sd(t, damping), spec.sa(t, damping) / g, color=colour, lw=1,
                        label=f"{c.limit_state} demand, site a_g {c.demand_ag_g:.3f} g, "
                              f"damping {damping:.0%}")
            a = curve.acceleration_at(c.capacity, fc) / g
            ax.plot([c.capacity], [a], "o", color=colour,
                    label=f"d_{c.limit_state} = {c.capacity:.3f} m, T = {c.period_s:.2f} s "
                          f"({c.method}, ratio {c.ratio:.2f})")
            ax.axvline(c.demand, color=colour, ls=":", lw=1)  # the demand at the site's a_g
        elif c.limit_state == "SLD":
            ax.axhline(c.demand / g, color=colour, ls="--", lw=1,
                       label=f"SLD demand a_Z {c.demand / g:.3f} g (ratio {c.ratio:.2f})")
            top = max(top, c.demand / g)
    demands = [c.demand for c in result.checks if c.quantity == "displacement"]
    ax.set_xlim(0.0, 1.1 * max([curve.d0_m, *demands]))
    ax.set_ylim(0.0, 1.15 * top)
    ax.set_xlabel("spectral displacement d (m)")
    ax.set_ylabel("spectral acceleration a (g)")
    ax.set_title(f"Code check, Circolare {result.procedure.value}: capacity curve and demand")
    # below the axes: inside, it hid the demand spectra where they cross the capacity's range
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2,
              frameon=False)
    ax.grid(alpha=0.3)
    return ax


def save_code_check(result, path: str | Path) -> Path:
    """Draw `plot_code_check` into a new figure and save it to ``path``."""
    fig, ax = plt.subplots(figsize=(7.5, 6.0))
    plot_code_check(result, ax)
    return save(fig, path, dpi=150)


__all__ = ["plot_code_check", "save_code_check"]
