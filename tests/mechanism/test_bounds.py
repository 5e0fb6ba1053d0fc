"""Resource bounds and wrong answers of the analytical model at the edges of its input
(issue 15): time floors, history memory, the API's errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake.constants import STANDARD_GRAVITY as G
from archquake.errors import InvalidParameterError
from archquake.geometry import Arch
from archquake.ground import SinePulse, StepImpulse
from archquake.ground.base import time_floor
from archquake.ground.records import Record
from archquake.mechanism import Outcome, simulate

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)
TAU = math.sqrt(10.0 / G)


# ------------------------------------------------------------------ time floors (item 3)
@pytest.mark.parametrize("t_p", [3e-13, 1e-13, 1e-14])
def test_step_shorter_than_the_time_resolution_is_refused(t_p):
    # before: the breakpoint search (tolerance 1e-12 (1 + t) s) skipped every breakpoint of
    # such a pulse, its first lobe acted for the whole run, and the arch "collapsed"
    with pytest.raises(InvalidParameterError, match=r"pulse duration t_p must be >= "):
        simulate(OPPENHEIM, StepImpulse.from_g(5.0, t_p))


def test_record_time_step_below_the_floor_is_refused():
    rec = Record(np.array([0.0, -5.0, -5.0, 0.0]) * G, 1e-15)
    with pytest.raises(InvalidParameterError, match=r"record time step DT must be >= "):
        simulate(OPPENHEIM, rec)


@pytest.mark.parametrize("motion", [StepImpulse, SinePulse])
def test_pulse_just_above_the_floor_cannot_collapse(motion):
    # Oracle: the impulse a t_p of a 5 g pulse lasting 2e-9 s gives the mechanism a rate of
    # order a t_p / R ~ 1e-8 rad/s, whose kinetic energy is ~1e-16 of the barrier to the crest;
    # the arch hinges (a > lambda g) and must survive.
    d = 4.0 * time_floor(TAU, 1.0)
    r = simulate(OPPENHEIM, motion.from_g(5.0, d))
    assert r.onset_time == 0.0 or r.onset_time is not None
    assert r.outcome is Outcome.SURVIVES


def test_domain_refuses_durations_below_the_floor():
    from archquake.domains import failure_domain

    # before: every magnitude above lambda "collapsed", boundary at lambda = 0.370 g
    with pytest.raises(InvalidParameterError, match="pulse duration t_p"):
        failure_domain(OPPENHEIM, "step", [1e-13])
    with pytest.raises(InvalidParameterError, match="period T"):
        failure_domain(OPPENHEIM, "sine", [1e-12])
