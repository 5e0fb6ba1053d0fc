"""The distinct-element side of the reproduction, through the DEM's public API only.

Every function returns None when the distinct-element model (or its plotting) is missing from
this build, so that the studies can say so in the report instead of failing.

DEM failure-domain points are found as the paper's UDEC ones were: for one pulse duration,
the magnitude is bisected between the no-hinging limit lambda (no motion) and a magnitude
that collapses the assembly. The first-half-cycle boundary uses the three-voussoir arch cut at
the analytical hinges (as the paper does, Figures 6a and 11), the governing boundary the
seven-voussoir arch.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from archquake.constants import STANDARD_GRAVITY
from archquake.geometry.arch import Arch


def available() -> bool:
    """True if the distinct-element model and its plotting are importable."""
    try:
        import archquake.dem  # noqa: F401
        import archquake.plotting.dem  # noqa: F401
        from archquake.dem import build_arch_assembly, simulate_dem  # noqa: F401
    except ImportError:
        return False
    return True


def three_voussoir(arch: Arch):
    """The arch cut only at the analytical hinges (paper Figure 4b, 6a, 11)."""
    from archquake.dem import build_arch_assembly
    from archquake.mechanism import default_mechanism

    return build_arch_assembly(arch, cut_joints=tuple(default_mechanism(arch).joints))


def collapses(result, first_half_cycle: bool) -> bool:
    """Did the DEM run collapse (before its first impact, if ``first_half_cycle``)?"""
    if result.outcome.value != "collapse":
        return False
    if not first_half_cycle:
        return True
    imp = result.first_impact_time
    return imp is None or (result.collapse_time is not None and result.collapse_time < imp)


@dataclass(frozen=True)
class DemBoundary:
    """DEM boundary points: durations (s), magnitudes (g; NaN if none up to ``ceiling_g``),
    bracket widths (g) and the number of DEM runs."""

    durations: np.ndarray
    magnitudes_g: np.ndarray
    widths_g: np.ndarray
    runs: int

    def to_dict(self) -> dict:
        return {
            "durations_s": self.durations,
            "magnitudes_g": self.magnitudes_g,
            "bracket_widths_g": self.widths_g,
            "runs": self.runs,
        }


def dem_boundary(
    assembly,
    family: str,
    durations,
    *,
    low_g: float,
    high_g,
    first_half_cycle: bool,
    iterations: int,
    tail: float,
    settings=None,
    g: float = STANDARD_GRAVITY,
) -> DemBoundary:
    """Bisect the collapse magnitude of ``assembly`` at each duration.

    Parameters
    ----------
    assembly : Assembly
    family : {'step', 'sine'}
    durations : array_like, s
        t_p (step) or T (sine).
    low_g : float
        A magnitude that does not collapse it (lambda), g.
    high_g : array_like
        Per duration, a first guess above the boundary (doubled, up to 5 g, until it collapses).
    first_half_cycle : bool
        Criterion: collapse before the first impact, or collapse at all.
    iterations : int
        Bisection steps (final bracket (high - low) / 2**iterations).
    tail : float
        Simulated time after the pulse ends, s.
    """
    from archquake.dem import DemSettings, simulate_dem
    from archquake.ground import SinePulse, StepImpulse

    base = DemSettings() if settings is None else settings
    runs = 0

    def collapse_at(a_g: float, d: float) -> bool:
        nonlocal runs
        runs += 1
        if family == "step":
            motion, end = StepImpulse.from_g(a_g, d, g=g), 3.0 * d
        else:
            motion, end = SinePulse.from_g(a_g, d, g=g), d
        st = base.with_(duration=end + tail, output_interval=0.01)
        return collapses(simulate_dem(assembly, motion, st, g=g), first_half_cycle)

    durations = np.atleast_1d(np.asarray(durations, float))
    highs = np.broadcast_to(np.asarray(high_g, float), durations.shape)
    mags, widths = [], []
    for d, hi in zip(durations, highs):
        lo = low_g
        while not collapse_at(hi, d):
            lo = hi
            if hi >= 5.0:
                hi = math.nan
                break
            hi = min(2.0 * hi, 5.0)
        if not math.isfinite(hi):
            mags.append(math.nan)
            widths.append(math.nan)
            continue
        for _ in range(iterations):
            mid = 0.5 * (lo + hi)
            if collapse_at(mid, d):
                hi = mid
            else:
                lo = mid
        mags.append(0.5 * (lo + hi))
        widths.append(hi - lo)
    return DemBoundary(durations, np.array(mags), np.array(widths), runs)


__all__ = ["DemBoundary", "available", "collapses", "dem_boundary", "three_voussoir"]
