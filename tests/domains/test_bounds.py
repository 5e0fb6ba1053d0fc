"""Searches that end (issue 15): precision floors and iteration caps."""

from __future__ import annotations

import math

import pytest

from archquake.domains import DomainSettings, failure_domain
from archquake.domains.domain import PRECISION_FLOOR
from archquake.errors import InvalidParameterError
from archquake.geometry import Arch
from archquake.limit.static import MIN_RTOL, min_thickness_ratio

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


@pytest.mark.parametrize("precision", [1e-300, 1e-14, 0.9 * PRECISION_FLOOR * 5.0])
def test_precision_below_the_float_floor_is_refused(precision):
    # before: domain --precision 1e-300 never ended (the midpoint of a bracket one ulp wide
    # is one of its ends)
    with pytest.raises(InvalidParameterError, match="precision_g must be >= "):
        DomainSettings(max_magnitude_g=5.0, precision_g=precision)


def test_search_at_the_precision_floor_ends_and_agrees():
    # Oracle: the same boundary found at 1e-3 g lies inside the bracket found at the floor.
    coarse = DomainSettings(coarse_points=12, fine_points=4)
    fine = DomainSettings(coarse_points=12, fine_points=4, precision_g=PRECISION_FLOOR * 5.0)
    a = failure_domain(OPPENHEIM, "step", [0.44], settings=coarse)
    b = failure_domain(OPPENHEIM, "step", [0.44], settings=fine)
    assert b.collapse_g[0] - b.collapse_below_g[0] <= 1e-10
    assert a.collapse_below_g[0] <= b.collapse_g[0] <= a.collapse_g[0]


@pytest.mark.parametrize("rtol", [0.0, -1.0, math.nan, math.inf, 1e-300, 0.9 * MIN_RTOL, 1.0])
def test_min_thickness_rtol_outside_its_range_is_refused(rtol):
    # before: rtol <= 0 never ended and rtol = nan returned 0.5
    with pytest.raises(InvalidParameterError, match="rtol must be"):
        min_thickness_ratio(math.pi, 7, rtol=rtol)


def test_min_thickness_at_the_finest_rtol_ends_and_agrees():
    # Oracle: the default-precision answer (rtol 1e-7) brackets the finest one.
    a = min_thickness_ratio(math.pi, 7)
    b = min_thickness_ratio(math.pi, 7, rtol=MIN_RTOL)
    assert abs(a - b) <= 1e-7 * a
