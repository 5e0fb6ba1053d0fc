"""Study ``friction``: the friction that prevents sliding (p. 2131) and the distinct-element
thresholds (p. 2134)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from archquake.geometry.arch import Arch
from archquake.ground import StepImpulse
from archquake.reproduce.core import Row, StudyResult, paper_row
from archquake.validation.paper import (
    DEM_FRICTION_05G,
    DEM_FRICTION_1G,
    FIGURE4_DURATIONS,
    FRICTION_05G,
    FRICTION_1G,
    FRICTION_MAGNITUDES_G,
)


def study(arch: Arch, quick: bool, figures: Path) -> StudyResult:
    """Minimum friction to prevent sliding (p. 2131) and the DEM thresholds (p. 2134)."""
    from archquake.mechanism import PreparedMechanism
    from archquake.thrust.friction import friction_demand

    prepared = PreparedMechanism.build(arch, "paper")  # the paper's Eq. 4, always
    n = arch.voussoirs
    durations = FIGURE4_DURATIONS[1:2] if quick else FIGURE4_DURATIONS
    res = {
        (a, tp): friction_demand(prepared, StepImpulse.from_g(a, tp))
        for a in FRICTION_MAGNITUDES_G
        for tp in durations
    }
    f10, f05 = res[(1.0, durations[0])], res[(0.5, durations[0])]
    where = all(r.joint == n and r.time == 0.0 for r in res.values())
    same = all(
        abs(r.max_friction_demand - res[(a, durations[0])].max_friction_demand) < 1e-9
        for (a, _), r in res.items()
    )
    src = "p. 2131"
    rows = [
        paper_row(
            "friction to prevent sliding, a = 1.0 g",
            FRICTION_1G,
            f"{f10.max_friction_demand:.4f}",
            f10.max_friction_demand,
        ),
        paper_row(
            "friction to prevent sliding, a = 0.5 g",
            FRICTION_05G,
            f"{f05.max_friction_demand:.4f}",
            f05.max_friction_demand,
        ),
        Row(
            "where and when: right springing (hinge D) at t = 0+, whatever t_p",
            src,
            "joint 7, t = 0+, independent of t_p",
            f"joint(s) {sorted({r.joint for r in res.values()})}, t = "
            f"{sorted({r.time for r in res.values()})} s, t_p = {', '.join(f'{d:.2f}' for d in durations)} s",
            "exact",
            "a statement",
            where and same,
        ),
    ]
    departures = [
        f"Friction at 1.0 g: archquake finds {f10.max_friction_demand:.3f}, the paper "
        f"{FRICTION_1G.stated} with its analytical model and {DEM_FRICTION_1G.value:g} with UDEC; "
        "archquake's four-link value equals the paper's UDEC threshold (the paper's analytical "
        "number is given only approximately)."
    ]
    data: dict[str, Any] = {f"{a:g} g, t_p {tp:.2f} s": r.to_dict() for (a, tp), r in res.items()}
    from archquake.dem.studies import friction_threshold

    rtol = 1e-2 if quick else 2.5e-3
    for a, paper in ((1.0, DEM_FRICTION_1G), (0.5, DEM_FRICTION_05G)):
        mu = friction_threshold(arch, a, low=0.4, high=0.7, rtol=rtol)
        rows.append(
            paper_row(
                f"DEM friction threshold, a = {a:.1f} g",
                paper,
                f"{mu:.3f}",
                mu,
                justification=f"{paper.why} {rtol:g}",
            )
        )
        data[f"dem threshold {a:g} g"] = mu
    return StudyResult(
        "friction",
        "Friction to prevent sliding (p. 2131, 2134)",
        tuple(rows),
        (),
        tuple(departures),
        data,
    )


__all__ = ["study"]
