"""A DEM run that ends once at rest (``DemSettings.stop_at_rest``) is the same run cut short:
the oracle is the full-length run itself (its samples bit for bit up to the stop, and the
verdict it gives at its own end), and the rule is the block models' rest rule
(`archquake.blocks.result.settled`)."""

from __future__ import annotations

import numpy as np
import pytest

from archquake.blocks.result import rest_threshold, settled
from archquake.dem import DemSettings, block_on_base, simulate_dem
from archquake.ground.pulses import SinePulse, StepImpulse
from archquake.outcome import Outcome

#: A block b 0.4 m x h 2 m (onset g b / h = 0.2 g) with enough mass-proportional damping
#: (8 1/s, relative to the base) to come to rest within the window after a pulse that rocks it.
BLOCK = block_on_base(0.4, 2.0)
DAMPED = DemSettings(duration=4.0, damping=(8.0, 1.59e-4))


@pytest.mark.parametrize("motion", [StepImpulse.from_g(0.3, 0.1), SinePulse.from_g(0.4, 0.2)],
                         ids=["step", "sine"])
def test_a_run_stopped_at_rest_is_the_full_run_cut_short(motion):
    full = simulate_dem(BLOCK, motion, DAMPED)
    short = simulate_dem(BLOCK, motion, DAMPED.with_(stop_at_rest=True))
    assert full.outcome is short.outcome is Outcome.SURVIVES
    assert short.impact_times.size >= 3  # it rocked, then came to rest
    k = short.times.size
    assert k < full.times.size / 2  # at rest well before the window's end
    np.testing.assert_array_equal(short.times, full.times[:k])
    np.testing.assert_array_equal(short.positions, full.positions[:k])
    np.testing.assert_array_equal(short.kinetic, full.kinetic[:k])
    # it stopped on the rule, and within a quarter of the rest window of where the rule
    # first holds on the full run's samples
    assert settled(BLOCK, 9.80665, short.times, short.kinetic, short.excitation_end)
    window = rest_threshold(BLOCK, 9.80665)[1]
    first = next(j for j in range(2, full.times.size)
                 if settled(BLOCK, 9.80665, full.times[:j], full.kinetic[:j],
                            full.excitation_end))
    assert full.times[first - 1] <= short.end_time <= full.times[first - 1] + 0.25 * window + 0.01
    assert "at rest" in short.verdict_reason


def test_collapse_and_a_run_that_never_rests_are_unchanged():
    """A collapse stops at the collapse as before; an undamped block still rocking at the end
    runs the whole window and stays indeterminate."""
    tipping = StepImpulse.from_g(0.8, 1.0)
    a = simulate_dem(BLOCK, tipping, DAMPED)
    b = simulate_dem(BLOCK, tipping, DAMPED.with_(stop_at_rest=True))
    assert a.outcome is b.outcome is Outcome.COLLAPSE
    np.testing.assert_array_equal(a.positions, b.positions)
    rocking = StepImpulse.from_g(0.3, 0.1)
    c = simulate_dem(BLOCK, rocking, DemSettings(duration=2.0, stop_at_rest=True))
    assert c.outcome is Outcome.INDETERMINATE and c.end_time > 1.99
