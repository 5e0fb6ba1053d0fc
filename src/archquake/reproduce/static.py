"""Study ``static``: the equivalent static analysis of Oppenheim's arch (p. 2126; the hinges of
Figures 1 and 7; the friction demand 0.50 of p. 2131)."""

from __future__ import annotations

from pathlib import Path

from archquake.geometry.arch import Arch
from archquake.reproduce.core import Figure, Row, StudyResult, paper_row, within
from archquake.validation.paper import ONSET_ACCELERATION, STATIC_FRICTION


def study(arch: Arch, quick: bool, figures: Path) -> StudyResult:
    """Equivalent static analysis (p. 2126; hinges of Figures 1 and 7; friction 0.50, p. 2131)."""
    from archquake.limit import limit_analysis
    from archquake.plotting.arch import save_limit_analysis

    res = limit_analysis(arch, method="both")
    assert res.kinematic_collapse_acceleration_g is not None  # method "both" sets both
    assert res.static_collapse_acceleration_g is not None
    fig = save_limit_analysis(res, figures / "static_collapse.png")
    lam = res.collapse_acceleration_g
    n = arch.voussoirs
    rows = [
        paper_row(
            "acceleration that starts hinging (static LP)",
            ONSET_ACCELERATION,
            f"{res.static_collapse_acceleration_g:.4f} g",
            res.static_collapse_acceleration_g,
        ),
        Row(
            "same, by virtual work over all admissible mechanisms",
            ONSET_ACCELERATION.where,
            ONSET_ACCELERATION.stated,
            f"{res.kinematic_collapse_acceleration_g:.4f} g",
            "equal to the static LP to 1e-6 g",
            "the lower- and upper-bound theorems meet at collapse (an independent check)",
            within(res.kinematic_collapse_acceleration_g, res.static_collapse_acceleration_g, 1e-6),
        ),
        Row(
            "hinge locations of Oppenheim's arch",
            "Figure 7 (asymmetric mechanism)",
            "asymmetric",
            f"joints {res.mechanism.joints} ({'symmetric' if res.symmetric else 'asymmetric'})",
            "exact",
            "a statement, not a measurement",
            not res.symmetric,
        ),
        paper_row(
            "friction demand of the equivalent static analysis",
            STATIC_FRICTION,
            f"{res.min_friction:.4f} at joint {res.min_friction_joint}"
            + (" (right springing)" if res.min_friction_joint == n else ""),
            res.min_friction,
        ),
    ]
    return StudyResult(
        "static",
        "Equivalent static analysis",
        tuple(rows),
        (
            Figure(
                fig.name,
                f"Oppenheim's arch at collapse: hinges and line of thrust (lambda = {lam:.4f} g)",
            ),
        ),
        data={"limit_analysis": res.to_dict()},
    )


__all__ = ["study"]
