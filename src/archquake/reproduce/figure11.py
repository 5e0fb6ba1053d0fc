"""Study ``figure11``: the one-cycle sine pulse (p. 2134, Figure 11), four-link and DEM."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from archquake.geometry.arch import Arch
from archquake.reproduce._dem_domains import dem_domain_rows, dem_domains
from archquake.reproduce.core import (
    Figure,
    Row,
    StudyResult,
    domain_settings,
    fmt,
    nondecreasing,
    paper_row,
)
from archquake.validation.paper import ONSET_ACCELERATION


def study(arch: Arch, quick: bool, figures: Path) -> StudyResult:
    """Figure 11: the one-cycle sine pulse, four-link and DEM."""
    from archquake.domains import failure_domain
    from archquake.plotting.compare import plot_domain_comparison
    from archquake.plotting.domains import save

    settings = domain_settings(quick)
    periods = np.linspace(0.5, 4.0, 8) if quick else np.linspace(0.25, 4.0, 31)
    dom = failure_domain(arch, "sine", periods, settings=settings, impact="paper", model="fourlink")
    first, coll = dom.first_half_cycle_g, dom.collapse_g
    both = np.isfinite(first) & np.isfinite(coll)
    tol = 2 * settings.precision_g
    src = "p. 2134, Figure 11"
    rows = [
        paper_row(
            "no-hinging limit",
            ONSET_ACCELERATION,
            f"{dom.no_hinging_g[0]:.4f} g",
            float(dom.no_hinging_g[0]),
            source=src,
            paper=f"{ONSET_ACCELERATION.stated} (same arch)",
        ),
        Row(
            "governing boundary below the 1st-half-cycle boundary",
            src,
            "below",
            f"at {int(np.sum(coll[both] <= first[both] + tol))} of {int(both.sum())} periods",
            f"every period, within {tol:g} g",
            "the figure's labels",
            bool(np.all(coll[both] <= first[both] + tol)),
        ),
        Row(
            "both boundaries fall as T grows",
            src,
            "decreasing",
            f"1st: {fmt(first[both][0])} -> {fmt(first[-1])} g; governing {fmt(coll[both][0])} -> "
            f"{fmt(coll[-1])} g",
            f"non-increasing within {tol:g} g",
            "the figure",
            nondecreasing(-first, tol) and nondecreasing(-coll, tol),
        ),
    ]
    halves = sorted({int(h) for h in dom.collapse_half_cycle if h})
    departures = []
    if halves and max(halves) > 2:
        departures.append(
            f"Sine pulse: for long periods the governing collapse comes in half cycle(s) "
            f"{[h for h in halves if h > 2]} (the pulse is still acting after the first impacts); "
            "the paper labels the region 'failure during 2nd half cycle'."
        )
        rows.append(
            Row(
                "half cycle of the governing collapse",
                src,
                "2nd half cycle (figure label)",
                f"half cycles {halves}",
                "-",
                "-",
                None,
                "departure: " + departures[-1],
                departure=True,
            )
        )
    d_first = (1.0, 2.0) if quick else (0.75, 1.0, 1.5, 2.0, 3.0, 4.0)
    d_gov = (1.5,) if quick else (1.0, 1.5, 2.0, 3.0)
    comparison = dem_domains(arch, "sine", dom, d_first, d_gov, quick, "sine")
    rows += dem_domain_rows(comparison, src, settings.precision_g)
    data = {"domain": dom.to_dict(), "summary": dom.summary(), "dem": comparison.to_dict()}
    fig = save(
        plot_domain_comparison(
            comparison, title="Figure 11: one-cycle sine pulse (regions four-link, markers DEM)"
        ),
        figures / "figure11_domain_sine.png",
    )
    return StudyResult(
        "figure11",
        "Sine pulse (Figure 11)",
        tuple(rows),
        (
            Figure(
                fig.name,
                "Figure 11: failure domain for a one-cycle sine pulse, four-link with DEM points",
            ),
        ),
        tuple(departures),
        data,
    )


__all__ = ["study"]
