"""The line of thrust in motion under a vertical ground acceleration.

Oracle: gravity enters the four-link model's equations of motion and its joint forces only as
g + a_v(t), so a steady upward acceleration c g is the same arch under gravity (1 + c) g: the
states at the same instants (the friction demand, where the thrust leaves each joint) agree to
round-off (1e-9), while each state's ``g`` is the nominal gravity its accelerations in g are read
against.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake import Arch
from archquake.constants import STANDARD_GRAVITY
from archquake.ground.pulses import StepImpulse
from archquake.thrust import states

G = STANDARD_GRAVITY
ARCH = Arch(10.0, 1.5, math.radians(157.5), 7)  # Oppenheim's arch
TIMES = (0.0, 0.2, 0.5, 0.8)


@pytest.mark.parametrize("c", [0.3, -0.25])
def test_steady_vertical_is_gravity_times_one_plus_c(c):
    arch = ARCH
    pulse = StepImpulse.from_g(1.0, 0.27)
    lifted = StepImpulse(pulse.magnitude, pulse.pulse_duration, pulse.direction,
                         steady_vertical=c * G)
    with_c = states(arch, lifted, TIMES)
    heavier = states(arch, pulse, TIMES, g=(1.0 + c) * G)
    for a, b in zip(with_c, heavier, strict=True):
        assert a.side == b.side
        np.testing.assert_allclose(a.phi, b.phi, rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(a.friction_demand, b.friction_demand, rtol=1e-7, atol=1e-9)
        np.testing.assert_allclose(a.outside, b.outside, rtol=1e-7, atol=1e-9)
        assert a.g == G


def test_no_vertical_reads_nominal_gravity():
    """A vertical that changes the weight changes the friction demand (the test above could not
    pass with the vertical left out)."""
    arch = ARCH
    pulse = StepImpulse.from_g(1.0, 0.27)
    lifted = StepImpulse(pulse.magnitude, pulse.pulse_duration, pulse.direction,
                         steady_vertical=0.3 * G)
    a = states(arch, pulse, (0.0,))[0]
    b = states(arch, lifted, (0.0,))[0]
    assert not np.allclose(a.friction_demand, b.friction_demand, rtol=1e-3)
