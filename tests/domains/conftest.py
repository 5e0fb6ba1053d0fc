"""Domains shared by the tests of this folder (computed once per session)."""

from __future__ import annotations

import math

import pytest

from archquake.domains import DomainSettings, failure_domain
from archquake.geometry import Arch
from archquake.mechanism import PreparedMechanism

#: Durations t_p (s) spanning Figure 5, including the paper's Figure 4 pulses.
STEP_DURATIONS = (0.2, 0.27, 0.44, 0.7, 1.2)
#: Periods T (s) spanning Figure 11.
SINE_PERIODS = (0.8, 1.6, 3.5)
#: A lighter scan than the default (the brackets still end at 0.001 g).
QUICK = DomainSettings(coarse_points=40, fine_points=24)


@pytest.fixture(scope="session")
def quick() -> DomainSettings:
    return QUICK


@pytest.fixture(scope="session")
def oppenheim_prepared() -> PreparedMechanism:
    return PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7))


@pytest.fixture(scope="session")
def step_domain(oppenheim_prepared):
    return failure_domain(oppenheim_prepared, "step", STEP_DURATIONS, settings=QUICK)


@pytest.fixture(scope="session")
def sine_domain(oppenheim_prepared):
    return failure_domain(oppenheim_prepared, "sine", SINE_PERIODS, settings=QUICK)
