"""Study ``figure8``: the line of thrust during motion (p. 2129-2130, Figure 8)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from archquake.geometry.arch import Arch
from archquake.ground import StepImpulse
from archquake.reproduce.core import Figure, Row, StudyResult
from archquake.validation.paper import FIGURE8_PULSE, FIGURE8_TIMES


def study(arch: Arch, quick: bool, figures: Path) -> StudyResult:
    """Figure 8: the line of thrust during motion (a = 1.0 g, t_p = 0.20 s)."""
    from archquake.mechanism import PreparedMechanism
    from archquake.plotting.thrust import save_thrust_snapshots
    from archquake.thrust import states

    prepared = PreparedMechanism.build(arch, "paper")  # the paper's Eq. 4, always
    snaps = states(prepared, StepImpulse.from_g(*FIGURE8_PULSE), FIGURE8_TIMES)
    fig = save_thrust_snapshots(
        arch, snaps, figures / "figure8_thrust.png", suptitle="Figure 8: step impulse 1.0 g, 0.20 s"
    )
    t = arch.thickness
    first = snaps[0]
    out0 = float(first.outside[first.exit_joint]) if first.exit_joint is not None else 0.0
    later = [float(s.outside[s.exit_joint]) if s.exit_joint is not None else 0.0 for s in snaps[1:]]
    n_out = [int(np.sum(s.outside > 0)) for s in snaps[1:]]
    left_half = first.outside[: arch.voussoirs // 2 + 1]
    src = "p. 2129, Figure 8"
    rows = [
        Row(
            "t = 0.20 s: the line of thrust leaves the section",
            src + "(a)",
            "exits the thickness",
            f"by {out0:.3f} m ({out0 / t:.2f} t) at joint {first.exit_joint}",
            "> 0",
            "a statement",
            out0 > 0,
        ),
        Row(
            "t = 0.20 s: where the second hinge would move",
            "p. 2130",
            "between the 2nd and 3rd voussoirs (joint 2)",
            f"joint {int(np.argmax(left_half))} (farthest outside on the left of the crown)",
            "exact",
            "a statement",
            int(np.argmax(left_half)) == 2,
        ),
        Row(
            "later snapshots: exits at limited locations, by a limited distance",
            src + "(b)-(f)",
            "limited",
            "largest exits "
            + ", ".join(f"{x / t:.2f} t" for x in later)
            + f"; at most {max(n_out)} joint(s) per snapshot",
            "each smaller than at 0.20 s, at most 2 joints",
            "'limited' read relative to snapshot (a)",
            all(x < out0 for x in later) and max(n_out) <= 2,
        ),
        Row(
            "equilibrium of every link in the snapshots",
            "(our check)",
            "-",
            f"largest residual {max(s.equilibrium_residual for s in snaps):.1e}",
            "<= 1e-9",
            "the moving arch's forces satisfy the links' equations (Eq. 2)",
            max(s.equilibrium_residual for s in snaps) <= 1e-9,
        ),
    ]
    return StudyResult(
        "figure8",
        "Line of thrust during motion (Figure 8)",
        tuple(rows),
        (
            Figure(
                fig.name, "Figure 8: hinges and line of thrust at 0.20, 0.50, 0.80, 1.10, 1.50, 2.22 s"
            ),
        ),
        (),
        {"snapshots": [s.to_dict() for s in snaps]},
    )


__all__ = ["study"]
