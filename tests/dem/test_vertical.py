"""The DEM under a pulse's vertical part: gravity g + a_v(t) on every free block, in the
ground's vertical frame.

Oracles: the onset of hinging of the limit analysis, |a_h| > lambda (g + a_v) (a long step
pulse 3 % either side of lambda g / (1 - R lambda), the penalty contacts' compliance taking the
rest); the energy balance, which closes to the DEM's own level (3e-4 here, as without a
vertical) only if the input work counts -m a_v on the vertical velocities.
"""

from __future__ import annotations

import math

import pytest

from archquake.dem import DemSettings, simulate_dem
from archquake.geometry import Arch
from archquake.ground import StepImpulse
from archquake.limit import limit_analysis

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


@pytest.mark.parametrize("ratio", [0.5, -0.5])
def test_onset_of_hinging_reads_g_plus_av(ratio):
    lam = limit_analysis(OPPENHEIM).collapse_acceleration_g
    threshold = lam / (1.0 - ratio * lam)
    settings = DemSettings(duration=3.0)
    below = simulate_dem(OPPENHEIM, StepImpulse.from_g(0.97 * threshold, 1.0, vertical=ratio),
                         settings)
    above = simulate_dem(OPPENHEIM, StepImpulse.from_g(1.03 * threshold, 1.0, vertical=ratio),
                         settings)
    assert below.outcome.value == "no_hinging"
    assert above.outcome.value != "no_hinging"


def test_energy_balance_counts_the_vertical_work():
    settings = DemSettings(duration=3.0)
    up = simulate_dem(OPPENHEIM, StepImpulse.from_g(0.5, 0.2, vertical=0.5), settings)
    plain = simulate_dem(OPPENHEIM, StepImpulse.from_g(0.5, 0.2), settings)
    assert up.energy_error < 2e-3 and plain.energy_error < 2e-3
    assert abs(up.input_work[-1] / plain.input_work[-1] - 1.0) > 0.1
