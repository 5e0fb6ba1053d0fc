"""Markdown tables of the comparisons (used by the demo step and docs/dem.md)."""

from __future__ import annotations

import math

import numpy as np


def _f(x, fmt: str = ".3f", none: str = "-") -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return none
    return format(x, fmt)


def _outcome(outcome: str, half) -> str:
    return outcome.replace("_", " ") + (f" (half cycle {half})" if half else "")


def figure4_table(comparisons: dict) -> str:
    """One row per (t_p, DEM assembly) of :func:`~archquake.compare.figure4_comparisons`."""
    lines = ["| t_p (s) | DEM arch | analytical | DEM | 1st impact an. / DEM (s) | collapse an. / DEM (s) "
             "| max diff. 1st half cycle (rad, % of peak) | window (s) | DEM run (s) |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for (tp, asm), c in sorted(comparisons.items(), key=lambda kv: (-kv[0][0], kv[0][1])):
        a, d = c.analytical, c.dem
        blocks = int(np.sum(~d.assembly.base))
        lines.append(
            f"| {tp:.2f} | {blocks} blocks ({asm}) | {_outcome(a.outcome.value, a.collapse_half_cycle)} | "
            f"{_outcome(d.outcome.value, c.dem_collapse_half_cycle)} | "
            f"{_f(c.analytical_first_impact)} / {_f(d.first_impact_time)} | "
            f"{_f(a.collapse_time, '.2f')} / {_f(d.collapse_time, '.2f')} | "
            f"{c.max_difference:.2e} ({100 * c.relative_difference:.1f} %) | {c.window:.2f} | "
            f"{c.dem_seconds:.2f} |")
    return "\n".join(lines)


def hinge_table(hinges) -> str:
    """Figure 8 vs Figure 9: hinge joints of both models at each instant."""
    lines = ["| t (s) | analytical hinges (joints) | DEM hinges (joint face) | same joints |",
             "| --- | --- | --- | --- |"]
    for r in hinges.rows():
        an = "locked" if r["analytical_joints"] is None else ", ".join(map(str, r["analytical_joints"]))
        lines.append(f"| {r['time_s']:.2f} | {an} | {', '.join(r['dem_hinges']) or 'none'} | "
                     f"{'yes' if r['same'] else 'no'} |")
    return "\n".join(lines)


def reduced_damping_table(snapshot) -> str:
    """Figure 10: slip and opening at every joint, reduced vs the paper's damping (mm)."""
    red, pap = snapshot.reduced_displacements, snapshot.paper_displacements
    lines = ["| joint | slip, reduced (mm) | slip, paper's (mm) | opening, reduced (mm) | "
             "opening, paper's (mm) |", "| --- | --- | --- | --- | --- |"]
    joints = snapshot.reduced.assembly.meta.get("cut_joints", list(range(red["slip_m"].size)))
    for k, j in enumerate(joints):
        lines.append(f"| {j} | {1e3 * red['slip_m'][k]:+.2f} | {1e3 * pap['slip_m'][k]:+.2f} | "
                     f"{1e3 * red['max_opening_m'][k]:.2f} | {1e3 * pap['max_opening_m'][k]:.2f} |")
    return "\n".join(lines)


def domain_table(comparisons) -> str:
    """Analytical vs DEM boundaries of several :class:`~archquake.compare.DomainComparison`."""
    lines = ["| case | boundary | DEM arch | duration (s) | analytical (g) | DEM (g) | DEM / an. - 1 |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for c in comparisons:
        for r in c.rows():
            rel = r["relative"]
            lines.append(f"| {c.label} | {r['boundary'].replace('_', ' ')} | {r['assembly']} | "
                         f"{r['duration_s']:.2f} | {_f(r['analytical_g'])} | {_f(r['dem_g'])} | "
                         f"{'-' if rel is None else f'{100 * rel:+.1f} %'} |")
    return "\n".join(lines)


def domain_costs(comparisons) -> str:
    """DEM runs and wall time of each domain."""
    lines = ["| case | DEM arch | durations | runs | wall time (s) | workers |",
             "| --- | --- | --- | --- | --- | --- |"]
    for c in comparisons:
        for dd in (c.first, c.governing):
            if dd is not None:
                lines.append(f"| {c.label} | {dd.assembly} | {dd.domain.durations.size} | {dd.runs} | "
                             f"{dd.seconds:.0f} | {dd.workers} |")
    return "\n".join(lines)


__all__ = ["domain_costs", "domain_table", "figure4_table", "hinge_table", "reduced_damping_table"]
