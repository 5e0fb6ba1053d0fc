"""Failure-domain figures like the paper's: Figure 5 (regions), 6 (scale), 7 (geometry), 11 (sine).

Functions take results from `archquake.domains`, an optional ``ax``, return it and never
call ``show()``; ``save_*`` helpers write a file and close the figure.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from archquake.domains import FailureDomain, StudyCase, paper_boundary, similar_boundary
from archquake.plotting.figures import save

_REGION_COLOURS = {"no hinging": "#e8e8e8", "recovery": "#cfe8cf",
                   "collapse in 2nd half cycle": "#f6d7a7", "collapse in 1st half cycle": "#f0a8a8"}


def plot_domain(domain: FailureDomain, ax=None, *, regions: bool = True, bands: bool = True,
                title: str | None = None):
    """Figure 5: the two boundaries with the regions labelled.

    Regions (bottom to top): no hinging (below lambda), recovery (the arch hinges and survives),
    collapse in the 2nd half cycle (between the governing and the 1st-half-cycle boundaries;
    "2nd" is what the paper finds for the step impulse: the label states the half cycles actually
    found at the governing boundary), collapse in the 1st half cycle. Non-monotonic bands are
    drawn as vertical bars.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.6))
    d = domain.durations
    lam = domain.no_hinging_g
    first = domain.first_half_cycle_g
    coll = domain.collapse_g
    top = np.nanmax(np.concatenate([first, coll, lam])) * 1.15
    top = min(top, domain.settings.max_magnitude_g) if np.isfinite(top) else domain.settings.max_magnitude_g
    halves = sorted(set(int(h) for h in domain.collapse_half_cycle if h > 1))
    later = "collapse in 2nd half cycle" if halves in ([], [2]) else (
        "collapse in half cycle " + ", ".join(str(h) for h in halves))
    if regions:
        c_top = np.where(np.isfinite(coll), coll, top)
        f_top = np.where(np.isfinite(first), first, top)
        ax.fill_between(d, 0, lam, color=_REGION_COLOURS["no hinging"], lw=0)
        if domain.impact_described:
            ax.fill_between(d, lam, c_top, color=_REGION_COLOURS["recovery"], lw=0)
            ax.fill_between(d, c_top, f_top, color=_REGION_COLOURS["collapse in 2nd half cycle"],
                            lw=0)
        else:  # every verdict after an impact is indeterminate (outcome.qualify)
            ax.fill_between(d, lam, f_top, facecolor="0.92", edgecolor="0.6", hatch="//", lw=0,
                            label=f"indeterminate: impact law {domain.impact_law} "
                                  f"{domain.impact_validity.replace('_', ' ')}")
        ax.fill_between(d, f_top, top, color=_REGION_COLOURS["collapse in 1st half cycle"], lw=0)
    searched = bool(np.any(np.isfinite(first)))  # governing-only searches leave it NaN
    ax.plot(d, first, "-", color="firebrick", lw=1.8,
            label="failure during 1st half cycle" if searched else None)
    if domain.impact_described:
        ax.plot(d, coll, "-", color="darkorange", lw=1.8, label="failure (governing; " +
                later.replace("collapse in ", "") + ")")
    else:
        ax.plot(d, coll, ":", color="darkorange", lw=1.8,
                label=f"computed with impact law {domain.impact_law} (indeterminate)")
    ax.plot(d, lam, "--", color="0.4", lw=1, label=f"no hinging below lambda = {lam[0]:.3f} g")
    if bands:
        for k, b in enumerate(domain.non_monotonic_bands):
            ax.plot([b.duration, b.duration], [b.lower_g, b.upper_g], color="navy", lw=2.5,
                    label="survives above a collapse (non-monotonic)" if k == 0 else None)
    if regions:
        ok = np.flatnonzero(np.isfinite(first) & np.isfinite(coll))
        i = int(ok[len(ok) // 4]) if ok.size else len(d) // 2
        x = d[i]

        def mid(lo, hi):
            return 0.5 * (lo + hi) if np.isfinite(lo) and np.isfinite(hi) else None

        labels = [("no hinging", 0.5 * lam[i]), ("recovery", mid(lam[i], coll[i])),
                  (later, mid(coll[i], first[i])),
                  ("collapse in 1st half cycle", mid(first[i], top))]
        if not domain.impact_described:
            labels[1:3] = [("indeterminate", mid(lam[i], first[i]))]
        for text, y in labels:
            if y is not None:
                ax.text(x, y, text, ha="left", va="center", fontsize=8, color="0.15")
    ax.set_xlim(d.min(), d.max())
    ax.set_ylim(0, top)
    ax.set_xlabel(domain.family.duration_label.capitalize())
    ax.set_ylabel("Impulse magnitude a [g]")
    ax.set_title(title or f"Failure domain, {domain.family.value} pulse, R = {domain.arch.radius:g} m")
    ax.legend(fontsize=7, loc="upper right")
    return ax


def plot_domains(cases: Sequence[StudyCase], ax=None, *, boundary: str = "collapse",
                 title: str | None = None):
    """Figures 6 and 7: one boundary (``collapse`` or ``first_half_cycle``) per arch.

    Cases without a domain, or with an energy-gaining impact model, are named in the legend
    with their problem.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.6))
    for case in cases:
        if case.domain is None:
            ax.plot([], [], " ", label=f"{case.label}: no domain ({case.problem})"[:90])
            continue
        d = case.domain
        y = d.collapse_g if boundary == "collapse" else d.first_half_cycle_g
        style = ":" if d.energy_gain or not d.impact_described else "-"
        note = f" (c_v = {d.restitution_cv:.3f} > 1)" if d.energy_gain else ""
        sym = "sym." if d.mechanism.get("symmetric") else "asym."
        ax.plot(d.durations, y, style, lw=1.6, label=f"{case.label}, {sym}{note}")
    ax.set_xlabel(cases[0].domain.family.duration_label.capitalize() if cases and cases[0].domain
                  else "Impulse duration [s]")
    ax.set_ylabel("Impulse magnitude a [g]")
    which = "governing (2nd half cycle)" if boundary == "collapse" else "1st half cycle"
    ax.set_title(title or f"Failure domains, {which}")
    ax.legend(fontsize=7)
    return ax


def plot_scaling(reference: FailureDomain, others: Sequence[FailureDomain], ax=None, *,
                 boundary: str = "collapse"):
    """Figure 6 redrawn with both mappings from the reference arch: computed domains (solid),
    exact dynamic similarity (durations x sqrt(k), circles) and the paper's sqrt(R) rule
    (magnitudes x sqrt(k), dashed)."""
    if ax is None:
        _, ax = plt.subplots(figsize=(6.8, 4.8))

    def pick(dom):
        return dom.collapse_g if boundary == "collapse" else dom.first_half_cycle_g

    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    r0 = reference.arch.radius
    ax.plot(reference.durations, pick(reference), "-", color="k", lw=2,
            label=f"R = {r0:g} m (reference)")
    for n, dom in enumerate(others):
        c = colours[n % len(colours)]
        k = dom.arch.radius / r0
        ax.plot(dom.durations, pick(dom), "-", color=c, lw=1.6, label=f"R = {dom.arch.radius:g} m computed")
        xs, ys = similar_boundary(reference.durations, pick(reference), k)
        keep = xs <= dom.durations.max()
        ax.plot(xs[keep], ys[keep], "o", ms=3.5, mfc="none", color=c,
                label="exact similarity: t x sqrt(R/R_ref)" if n == 0 else None)
        xp, yp = paper_boundary(reference.durations, pick(reference), k)
        ax.plot(xp, yp, "--", color=c, lw=1, label="paper: a x sqrt(R/R_ref)" if n == 0 else None)
    ax.set_xlabel(reference.family.duration_label.capitalize())
    ax.set_ylabel("Impulse magnitude a [g]")
    top = np.nanmax(np.concatenate([pick(d) for d in (reference, *others)]))
    ax.set_ylim(0, min(top * 1.1, reference.settings.max_magnitude_g * 1.5))
    ax.set_title("Scale effect: exact similarity vs the paper's sqrt(R) rule")
    ax.legend(fontsize=7)
    return ax


def save_domain(domain: FailureDomain, path: str | Path) -> Path:
    """Figure 5 for ``domain``, written to ``path``."""
    return save(plot_domain(domain), path)


__all__ = ["plot_domain", "plot_domains", "plot_scaling", "save", "save_domain"]
