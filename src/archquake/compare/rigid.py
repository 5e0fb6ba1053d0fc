"""The rigid limit: the DEM's energy over a half cycle against its contact model, and
the rigid-block chain (`archquake.rigid`) through the same protocol.

Protocols are `archquake.compare.impacts`'s (energy kept over the first half cycle,
`half_cycle_of`) and the critical step-pulse duration at a
given magnitude (Oppenheim's `StepImpulse`, first collapsing t_p by
bisection, which assumes survival below the threshold, as the DEM's 0.259-0.2625 s did).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from archquake.constants import STANDARD_GRAVITY
from archquake.geometry.arch import Arch


def scaled_contact(stiffness: float = 1.0, damping: float = 1.0):
    """``DemSettings()`` with the joint stiffnesses (normal and shear) times ``stiffness`` and
    the Rayleigh pair (alpha, beta) times ``damping``: the code's damping definition kept, so
    the stiffness-proportional damping ratio at the contact frequency, beta omega / 2, grows as
    sqrt(stiffness)."""
    from archquake.dem.settings import ContactLaw, DemSettings

    s = DemSettings()
    kn = s.contact.normal_stiffness * stiffness
    return s.with_(contact=ContactLaw(normal_stiffness=kn, shear_stiffness=kn,
                                      friction=s.contact.friction),
                   damping=(s.damping[0] * damping, s.damping[1] * damping))


def rigid_half_cycle(arch: Arch, *, time_step: float | None = None, window: float = 0.01,
                     solver: str = "direct", g: float = STANDARD_GRAVITY):
    """The rigid chain through its first impact under the comparison's pulse
    (`archquake.compare.impacts.rocking_pulse`); returns (DemHalfCycle, RigidRun).
    ``solver``: `simulate_rigid`'s."""
    from archquake.compare.impacts import half_cycle_of, rocking_pulse
    from archquake.rigid import DEFAULT_TIME_STEP, simulate_rigid

    pulse, tp, t_imp = rocking_pulse(arch, g=g)
    run = simulate_rigid(arch, pulse, duration=t_imp * 1.5 + 0.1,
                         time_step=DEFAULT_TIME_STEP if time_step is None else time_step, g=g,
                         solver=solver)
    return half_cycle_of(run, tp, t_imp, window=window), run


def step_collapses(model: str, arch: Arch, magnitude_g: float, tp: float, *,
                   settings=None, time_step: float | None = None, tail: float = 4.0,
                   solver_tolerance: float | None = None, solver: str = "direct",
                   g: float = STANDARD_GRAVITY, friction: float | None = None) -> bool:
    """Whether ``model`` ("dem" or "rigid") collapses under StepImpulse(magnitude_g, tp),
    run for 3 t_p + ``tail`` s (the DEM's collapses in the second half cycle come 3.6-4.7 s
    after the start on Oppenheim's arch: its default 3 s duration misses them). ``solver``
    and ``friction`` (the joints' Coulomb coefficient, None: no sliding): the rigid chain's
    (`simulate_rigid`)."""
    from archquake.ground import StepImpulse

    motion = StepImpulse.from_g(magnitude_g, tp, g=g)
    if model == "dem":
        from archquake.dem import simulate_dem
        from archquake.dem.settings import DemSettings

        s = (DemSettings() if settings is None else settings).with_(
            duration=3 * tp + tail, output_interval=2e-3)
        return simulate_dem(arch, motion, s, g=g).outcome.value == "collapse"
    from archquake.rigid import DEFAULT_TIME_STEP, simulate_rigid
    from archquake.rigid.model import SOLVER_TOLERANCE

    run = simulate_rigid(arch, motion, duration=3 * tp + tail, output_interval=2e-3,
                         time_step=DEFAULT_TIME_STEP if time_step is None else time_step, g=g,
                         solver_tolerance=(SOLVER_TOLERANCE if solver_tolerance is None
                                           else solver_tolerance), solver=solver,
                         friction=friction)
    return run.outcome.value == "collapse"


@dataclass(frozen=True)
class Threshold:
    """The first collapsing step duration lies in (``survives_s``, ``collapses_s``]."""

    survives_s: float
    collapses_s: float


def critical_step_duration(model: str, arch: Arch, magnitude_g: float, low: float,
                           high: float, *, resolution: float = 0.0025, **kwargs) -> Threshold:
    """Bisection of `step_collapses` on t_p in [low, high] s down to ``resolution`` s."""
    if step_collapses(model, arch, magnitude_g, low, **kwargs):
        raise ValueError(f"t_p = {low} s already collapses")
    if not step_collapses(model, arch, magnitude_g, high, **kwargs):
        raise ValueError(f"t_p = {high} s survives")
    while high - low > resolution:
        mid = 0.5 * (low + high)
        if step_collapses(model, arch, magnitude_g, mid, **kwargs):
            high = mid
        else:
            low = mid
    return Threshold(low, high)


def oppenheim() -> Arch:
    """Oppenheim's arch: R 10 m, t 1.5 m, 157.5 deg, 7 voussoirs."""
    return Arch(10.0, 1.5, math.radians(157.5), 7)


__all__ = [
    "Threshold",
    "critical_step_duration",
    "oppenheim",
    "rigid_half_cycle",
    "scaled_contact",
    "step_collapses",
]
