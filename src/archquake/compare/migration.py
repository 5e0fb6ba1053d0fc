"""Hinge migration: energy kept over the first half cycle and the hinge sequence,
fixed hinges (Eq. 4 and the chain law) against the migrating model and the DEM.

The protocol is :mod:`archquake.compare.impacts`'s: one rectangular pulse towards -x of twice
the static collapse acceleration, sized so that the analytical (fixed-hinge) first half cycle
peaks at 0.35 times the crest rotation; then free rocking. The energy kept is
``E(first closing impact + 10 ms) / E(end of the pulse)`` (kinetic + potential (+ contact strain
in the DEM), relative to the arch at rest, in the frame of the ground, which moves at constant
velocity after the pulse). For the fixed-hinge models it is the impact's c_T exactly (energy is
conserved in free motion between impacts).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from archquake.constants import STANDARD_GRAVITY
from archquake.geometry.arch import Arch


@dataclass(frozen=True)
class RectangularPulse:
    """x_g'' = ``acceleration`` (m/s^2) for 0 <= t < ``pulse_duration`` (s), then 0: the exact
    rectangle the DEM's sampled :func:`archquake.dem.studies.rectangular_pulse` approximates
    (its fall takes t_p / 2000)."""

    acceleration_m_s2: float
    pulse_duration: float

    @property
    def duration(self) -> float:
        return self.pulse_duration

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        return np.where((t >= 0) & (t < self.pulse_duration), self.acceleration_m_s2, 0.0)

    def breakpoints(self) -> np.ndarray:
        return np.array([0.0, self.pulse_duration])

    def mirrored(self) -> RectangularPulse:
        return RectangularPulse(-self.acceleration_m_s2, self.pulse_duration)


#: (label, R m, t m, embrace deg, voussoirs) of the issue's table.
MIGRATION_GEOMETRIES = (
    ("Oppenheim", 10.0, 1.5, 157.5, 7),
    ("t/R=0.13", 10.0, 1.3, 157.5, 7),
    ("semicircle R=5 t=0.9 n=15", 5.0, 0.9, 180.0, 15),
    ("t/R=0.19 (sym)", 10.0, 1.9, 157.5, 7),
)


def migrating_half_cycle(arch: Arch, *, g: float = STANDARD_GRAVITY, after: float = 0.01):
    """The migrating model through its first closing impact under the comparison's pulse.

    Returns (kept, MigrationResult, pulse duration s, analytical fixed-hinge impact time s)."""
    from archquake.compare.impacts import rocking_pulse
    from archquake.mechanism.migration import simulate_migrating

    pulse, tp, t_imp = rocking_pulse(arch, g=g)
    rect = RectangularPulse(float(pulse.acceleration(0.0)), tp)
    res = simulate_migrating(arch, rect, t_end=3.0 * t_imp, stop_after_impacts=1, g=g)
    e0 = res.energy_at(tp)
    imp = res.impacts
    kept = imp[0].energy_after / e0 if imp else math.nan
    return kept, res, tp, t_imp


@dataclass(frozen=True)
class DemHalfCycle:
    """The DEM through its first impact under the comparison's pulse.

    ``kept`` = E(t_i + 10 ms) / E(t_p); ``kept_before`` = E(t_i - 10 ms) / E(t_p) (what the
    swing itself lost); ``sequence``: (t s, open joints) each time the DEM's hinge set
    (:func:`archquake.compare.dem_hinges`, sampled every 5 ms) changes, from t_p to t_i + 0.1 s.
    """

    pulse_duration_s: float
    impact_time_s: float | None
    kept: float | None
    kept_before: float | None
    kept_wide: float | None
    sequence: tuple
    t: np.ndarray
    energy_fraction: np.ndarray
    energy_error: float


def dem_half_cycle(arch: Arch, *, settings=None, window: float = 0.01, g: float = STANDARD_GRAVITY
                   ) -> DemHalfCycle:
    """Run the DEM (the paper's stiffness and damping, no sliding: ``DemSettings()``) through the
    first impact after the comparison's pulse (:func:`archquake.compare.impacts.rocking_pulse`),
    measuring energy as :mod:`archquake.compare.impacts` does."""
    from archquake.compare.impacts import rocking_pulse
    from archquake.dem import simulate_dem
    from archquake.dem.settings import DemSettings

    pulse, tp, t_imp = rocking_pulse(arch, g=g)
    settings = DemSettings() if settings is None else settings
    settings = settings.with_(duration=t_imp * 1.5 + 0.1, output_interval=5e-4,
                              stop_at_collapse=True)
    res = simulate_dem(arch, pulse, settings, g=g)
    return half_cycle_of(res, tp, t_imp, window=window)


def half_cycle_of(res, tp: float, t_imp: float, *, window: float = 0.01) -> DemHalfCycle:
    """The :class:`DemHalfCycle` measures of a recorded run ``res`` (a
    :class:`archquake.dem.DemResult`, from the DEM or from the rigid chain,
    :mod:`archquake.mechanism.rigid_chain`) under the comparison's pulse of duration ``tp`` s,
    ``t_imp`` s being the fixed-hinge model's first impact (the end of the hinge sequence when
    the run has none)."""
    from archquake.compare.impacts import WIDE_WINDOW
    from archquake.compare.snapshots import dem_hinges

    ti = res.first_impact_time
    e = res.kinetic + res.potential + res.strain
    e_rest = float(res.potential[0] + res.strain[0])

    def at(t):
        return float(np.interp(t, res.times, e)) - e_rest

    e0 = at(tp)
    seq: list[tuple[float, str]] = []
    for t in np.arange(tp, min(float(res.times[-1]), (ti or t_imp) + 0.1), 0.005):
        h = " ".join(f"{j}{f[0]}" for j, f in dem_hinges(res, t))
        if not seq or seq[-1][1] != h:
            seq.append((round(float(t), 4), h))
    return DemHalfCycle(
        pulse_duration_s=tp, impact_time_s=ti,
        kept=None if ti is None else at(ti + window) / e0,
        kept_before=None if ti is None else at(ti - window) / e0,
        kept_wide=None if ti is None else at(ti + WIDE_WINDOW) / e0,
        sequence=tuple(seq), t=res.times, energy_fraction=(e - e_rest) / e0,
        energy_error=res.energy_error)


def fixed_hinge_kept(arch: Arch) -> dict:
    """c_T of Eq. 4 and of the chain law for the arch's limit-analysis mechanism."""
    from archquake.compare.impacts import analytical_impacts

    _, laws, _, _ = analytical_impacts(arch)
    return {"paper": laws["paper"]["ct"], "chain": laws["chain"]["ct"]}


__all__ = [
    "MIGRATION_GEOMETRIES",
    "DemHalfCycle",
    "RectangularPulse",
    "dem_half_cycle",
    "fixed_hinge_kept",
    "half_cycle_of",
    "migrating_half_cycle",
]
