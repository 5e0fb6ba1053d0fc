"""Study ``damping``: the distinct-element model's stiffness and Rayleigh damping (p. 2131,
p. 2133) and the reduced damping run of Figure 10."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from archquake.geometry.arch import Arch
from archquake.reproduce.core import Figure, Row, StudyResult, paper_row
from archquake.validation.paper import (
    CRITICAL_FREQUENCY,
    DEM_DAMPING,
    DEM_NORMAL_STIFFNESS_PA_M,
    FIGURE10_DAMPING,
    FIGURE10_PULSE,
    FIGURE10_TIME,
    RAYLEIGH_ALPHA,
    RAYLEIGH_BETA,
    REDUCED_CRITICAL_FREQUENCY,
    REDUCED_RAYLEIGH_ALPHA,
    REDUCED_RAYLEIGH_BETA,
)

#: DEM simulated time of the damping study, s: long enough to see the outcome of Figure 10's pulse.
DAMPING_RUN = 6.0


def study(arch: Arch, quick: bool, figures: Path) -> StudyResult:
    """The DEM's stiffness and Rayleigh damping as the paper reads (p. 2131, 2133) and the reduced
    damping run of Figure 10."""
    from archquake.compare import dem_assembly, reduced_damping_snapshot
    from archquake.dem import DemSettings, stable_time_step
    from archquake.plotting.compare import figure10

    src = "p. 2131"
    a1, b1 = DemSettings.rayleigh_from_minimum(*DEM_DAMPING)
    a2, b2 = DemSettings.rayleigh_from_minimum(*FIGURE10_DAMPING)
    f_crit1, f_crit2 = 1 / (math.pi * b1), 1 / (math.pi * b2)  # xi = 1 where beta omega / 2 = 1
    asm = dem_assembly(arch)
    dt_pa, _ = stable_time_step(asm, DemSettings())
    gpa_m = DemSettings().contact.__class__(normal_stiffness=1e9 * DEM_NORMAL_STIFFNESS_PA_M)
    dt_gpa, _ = stable_time_step(asm, DemSettings().with_(contact=gpa_m))
    snap = reduced_damping_snapshot(arch, end_time=DAMPING_RUN)
    std, red = snap.paper, snap.reduced
    slip_std, slip_red = (float(np.max(np.abs(r.joint_slip))) for r in (std, red))
    a_g, t_p = FIGURE10_PULSE
    rows = [
        Row(
            "Rayleigh damping from xi_min = 0.01 % at 0.1 Hz",
            src,
            f"alpha {RAYLEIGH_ALPHA.stated}, beta {RAYLEIGH_BETA.stated}",
            f"alpha {a1:.3g}, beta {b1:.3g}",
            f"alpha {RAYLEIGH_ALPHA.tolerance_text}, beta {RAYLEIGH_BETA.tolerance_text} (3 digits)",
            RAYLEIGH_ALPHA.why,
            RAYLEIGH_ALPHA.within(a1) and RAYLEIGH_BETA.within(b1),
        ),
        paper_row("critically damped above", CRITICAL_FREQUENCY, f"{f_crit1:.0f} Hz", f_crit1),
        Row(
            "reduced damping (xi_min = 0.001 % at 0.05 Hz)",
            "p. 2133 (text repeats the first alpha, beta)",
            f"alpha {REDUCED_RAYLEIGH_ALPHA.stated}, beta {REDUCED_RAYLEIGH_BETA.stated} (notes)",
            f"alpha {a2:.3g}, beta {b2:.3g}; critical above {f_crit2:.0f} Hz",
            f"alpha {REDUCED_RAYLEIGH_ALPHA.tolerance_text}, beta {REDUCED_RAYLEIGH_BETA.tolerance_text}"
            f" (3 digits); critical frequency {REDUCED_CRITICAL_FREQUENCY.stated} "
            f"{REDUCED_CRITICAL_FREQUENCY.tolerance_text}",
            REDUCED_RAYLEIGH_ALPHA.why,
            REDUCED_RAYLEIGH_ALPHA.within(a2)
            and REDUCED_RAYLEIGH_BETA.within(b2)
            and REDUCED_CRITICAL_FREQUENCY.within(f_crit2),
        ),
        Row(
            "joint stiffness unit: 10^12 read as Pa/m",
            "p. 2131 ('10^12 GPa/m')",
            "range 5e11-5e12 usable",
            f"stable time step {dt_pa:.2e} s at 1e12 Pa/m; {dt_gpa:.1e} s if GPa/m (1e21 Pa/m): "
            f"{1.6 / dt_gpa:.1e} steps for 1.6 s",
            "GPa/m implausible (> 1e9 steps)",
            "the paper's 'smaller time steps' remark only makes sense near 1e12 Pa/m",
            1.6 / dt_gpa > 1e9,
        ),
        Row(
            f"reduced damping: inter-stone displacements appear (a = {a_g:g} g, t_p = {t_p:g} s)",
            "p. 2133, Figure 10",
            "relative displacements similar to sliding",
            f"largest joint slip {1000 * slip_red:.1f} mm vs {1000 * slip_std:.1f} mm "
            "with the paper's damping",
            "at least twice as large",
            "the paper shows them only with reduced damping",
            slip_red >= 2 * slip_std,
        ),
        Row(
            "reduced damping: outcome unchanged",
            "p. 2134",
            "failure domain not significantly affected",
            f"{red.outcome.value} (reduced) vs {std.outcome.value} (paper's damping)",
            "same outcome",
            "one point of the domain",
            red.outcome == std.outcome,
        ),
    ]
    path = figure10(red, FIGURE10_TIME, figures / "figure10_reduced_damping.png", reference=std)
    data = {
        "rayleigh_paper": [a1, b1],
        "rayleigh_reduced": [a2, b2],
        "critical_hz": [f_crit1, f_crit2],
        "max_slip_m": {"paper_damping": slip_std, "reduced": slip_red},
        "outcomes": {"paper_damping": std.outcome.value, "reduced": red.outcome.value},
        "snapshot": snap.to_dict(),
    }
    return StudyResult(
        "damping",
        "DEM stiffness and damping (p. 2131, Figure 10)",
        tuple(rows),
        (
            Figure(
                path.name,
                f"Figure 10: the arch at {FIGURE10_TIME:g} s with reduced Rayleigh damping, and the "
                "inter-stone displacements at every joint beside those with the paper's damping",
            ),
        ),
        (),
        data,
    )


__all__ = ["DAMPING_RUN", "study"]
