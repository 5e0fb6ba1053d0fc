"""Time histories of the two models side by side (paper Figure 4(b)-(d)).

The four-link model (`archquake.mechanism.simulate`) gives phi(t), the rotation of the
open mechanism's first link; the distinct-element model (`archquake.dem.simulate_dem`)
gives ``BlockResult.rotation``, the rotation of the chord from hinge A to hinge B (for the arch
cut at the four-link model's hinges, link AB itself; for the voussoir arch, voussoirs A..B taken as
one link). Both are signed: > 0 while the first mechanism is open, < 0 in the mirrored one.

Both results speak one vocabulary (`Outcome`, impact times, peak
rotation per half cycle, collapse half cycle: the DEM result computes its own, see
`archquake.blocks.result`); this module only runs the two models and compares them (each
model's run to a verdict lives with the model: `archquake.rigid.run.rigid_to_verdict`,
`archquake.dem.run.dem_to_verdict`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from archquake._deprecated import renamed
from archquake.blocks.assembly import (  # noqa: F401  (re-exported by archquake.compare)
    ASSEMBLIES,
    HINGES,
    VOUSSOIRS,
    Assembly,
    build_arch_assembly,
    dem_assembly,
    three_voussoir_assembly,
)
from archquake.constants import STANDARD_GRAVITY
from archquake.dem.run import default_dem_duration  # noqa: F401  (re-exported by archquake.compare)
from archquake.errors import InvalidParameterError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.ground.base import GroundMotion
from archquake.validation.paper import FIGURE4_DURATIONS

if TYPE_CHECKING:
    from archquake.blocks.result import BlockResult
    from archquake.mechanism.simulate import SimulationResult

# ----------------------------------------------------------------------------- comparison
@dataclass(frozen=True)
class HistoryComparison:
    """One arch, one ground motion, both models.

    Attributes
    ----------
    fourlink : SimulationResult
        The four-link model's run, with its history.
    dem : BlockResult
    assembly : str
        ``'voussoirs'`` or ``'hinges'`` (the three-voussoir arch).
    window : float
        End of the first half cycle compared, s: the earliest of the two models' first
        impacts and the four-link collapse (the four-link history ends there).
    max_difference : float
        max |rotation_DEM - phi_fourlink| over [0, window], rad.
    relative_difference : float
        ``max_difference`` / max |phi_fourlink| over the window (NaN if it never hinged).
    fourlink_seconds, dem_seconds : float
        Wall time of each run, s.

    The former names ``analytical``, ``analytical_seconds`` and ``analytical_first_impact``
    are read for one more release, with a DeprecationWarning.
    """

    fourlink: SimulationResult = field(repr=False)
    dem: BlockResult = field(repr=False)
    assembly: str
    window: float
    max_difference: float
    relative_difference: float
    fourlink_seconds: float
    dem_seconds: float

    analytical = renamed("analytical", "fourlink", "HistoryComparison")
    analytical_seconds = renamed("analytical_seconds", "fourlink_seconds", "HistoryComparison")
    analytical_first_impact = renamed("analytical_first_impact", "fourlink_first_impact",
                                      "HistoryComparison")

    @property
    def fourlink_first_impact(self) -> float | None:
        """The four-link model's first impact, s (None: it had none)."""
        r = self.fourlink
        return float(r.impact_times[0]) if r.impact_times.size else None

    @property
    def same_outcome(self) -> bool:
        """Same outcome and, for a collapse, the same half cycle (an indeterminate four-link
        verdict is never the same as the DEM's: it claims neither collapse nor survival)."""
        return (self.fourlink.outcome is self.dem.outcome
                and self.fourlink.collapse_half_cycle == self.dem.collapse_half_cycle)

    def to_dict(self) -> dict:
        a, d = self.fourlink, self.dem
        return {
            "assembly": self.assembly,
            "blocks": int(np.sum(~d.assembly.base)),
            "motion": d.motion,
            "fourlink": {"outcome": a.outcome.value, "collapse_half_cycle": a.collapse_half_cycle,
                         "impact_law": a.impact_law, "impact_validity": a.impact_validity,
                         "first_impact_time_s": self.fourlink_first_impact,
                         "collapse_time_s": a.collapse_time, "seconds": self.fourlink_seconds},
            "dem": {"outcome": d.outcome.value, "collapse_half_cycle": d.collapse_half_cycle,
                    "first_impact_time_s": d.first_impact_time, "collapse_time_s": d.collapse_time,
                    "end_time_s": d.end_time, "seconds": self.dem_seconds},
            "same_outcome": self.same_outcome,
            "first_half_cycle_window_s": self.window,
            "max_rotation_difference_rad": self.max_difference,
            "relative_rotation_difference": self.relative_difference,
        }


def compare_history(
    arch: Arch,
    motion: GroundMotion,
    *,
    assembly: str = VOUSSOIRS,
    settings=None,
    duration: float | None = None,
    g: float = STANDARD_GRAVITY,
) -> HistoryComparison:
    """Run both models on ``arch`` under ``motion`` and compare their rotations.

    Parameters
    ----------
    arch : Arch
    motion : GroundMotion
    assembly : {'voussoirs', 'hinges'}
        The DEM arch: every voussoir a block, or cut at the four-link model's hinges.
    settings : DemSettings, optional
        Default: the paper's stiffness and damping; its ``duration`` is replaced by
        ``duration``.
    duration : float, optional
        DEM simulated time, s (default `default_dem_duration`). The four-link model
        runs to its own end (rest or collapse).
    g : float
        Gravity, m/s^2.

    Returns
    -------
    HistoryComparison

    Examples
    --------
    The paper's Figure 4(b): a = 1.0 g, t_p = 0.44 s, the three-voussoir DEM arch
    (the DEM's collapse comes later: its criterion is a fall of the crown by t):

    >>> import math
    >>> from archquake.ground import StepImpulse
    >>> c = compare_history(Arch(10.0, 1.5, math.radians(157.5), 7),
    ...                     StepImpulse.from_g(1.0, 0.44), assembly="hinges", duration=3.0)
    >>> c.same_outcome, c.relative_difference < 0.02
    (True, True)
    """
    from archquake.dem import DemSettings, simulate_dem
    from archquake.mechanism import PreparedMechanism
    from archquake.mechanism.simulate import (
        simulate,  # the function (the module of its name can shadow it on the package)
    )

    if not isinstance(arch, VoussoirChain):
        raise InvalidParameterError(f"compare_history needs an Arch, got {type(arch).__name__}")
    asm = dem_assembly(arch, assembly)
    st = DemSettings() if settings is None else settings
    st = st.with_(duration=duration if duration is not None else default_dem_duration(arch, motion, g=g))
    t0 = time.perf_counter()
    an = simulate(PreparedMechanism.build(arch), motion, g=g)
    t1 = time.perf_counter()
    dm = simulate_dem(asm, motion, st, g=g)
    t2 = time.perf_counter()
    window, diff, rel = first_half_cycle_difference(an, dm)
    return HistoryComparison(an, dm, assembly, window, diff, rel, t1 - t0, t2 - t1)


def first_half_cycle_difference(fourlink, dem) -> tuple[float, float, float]:
    """(window end s, max |rotation_DEM - phi| rad, that / max |phi|) over the first half cycle.

    The window ends at the earliest of the four-link collapse, the four-link first impact,
    the DEM's first impact and the DEM's last sample; the DEM rotation is interpolated
    linearly onto the four-link samples (DEM output every 5 ms; the curvature error of that
    interpolation is ~1e-6 rad for these motions).
    """
    h = fourlink.history
    if h is None:
        raise InvalidParameterError("the four-link result needs its history (output_interval != 0)")
    ends = [float(h.t[-1]), float(dem.times[-1])]
    if fourlink.collapse_time is not None:
        ends.append(fourlink.collapse_time)
    if fourlink.impact_times.size:
        ends.append(float(fourlink.impact_times[0]))
    if dem.first_impact_time is not None:
        ends.append(dem.first_impact_time)
    window = min(ends)
    sel = h.t <= window
    an = h.signed_rotation[sel]
    dm = np.interp(h.t[sel], dem.times, dem.rotation)
    diff = float(np.max(np.abs(dm - an))) if an.size else 0.0
    peak = float(np.max(np.abs(an))) if an.size else 0.0
    return window, diff, diff / peak if peak > 0 else math.nan




def figure4_comparisons(
    arch: Arch,
    durations=FIGURE4_DURATIONS,
    *,
    magnitude_g: float = 1.0,
    assemblies=ASSEMBLIES,
    settings=None,
    duration: float | None = None,
    g: float = STANDARD_GRAVITY,
) -> dict[tuple[float, str], HistoryComparison]:
    """`compare_history` for the step impulses of Figure 4, for each DEM assembly.

    Returns
    -------
    dict
        ``{(t_p, assembly): HistoryComparison}``.
    """
    from archquake.ground.pulses import StepImpulse

    out = {}
    for tp in durations:
        motion = StepImpulse.from_g(magnitude_g, float(tp), g=g)
        for asm in assemblies:
            out[(float(tp), asm)] = compare_history(arch, motion, assembly=asm, settings=settings,
                                                    duration=duration, g=g)
    return out


__all__ = [
    "ASSEMBLIES",
    "FIGURE4_DURATIONS",
    "HINGES",
    "HistoryComparison",
    "VOUSSOIRS",
    "compare_history",
    "default_dem_duration",
    "dem_assembly",
    "figure4_comparisons",
    "first_half_cycle_difference",
    "three_voussoir_assembly",
]
