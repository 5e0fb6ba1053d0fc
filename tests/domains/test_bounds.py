"""Searches that end (issue 15): precision floors and iteration caps."""

from __future__ import annotations

import math

import numpy as np
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
    a = failure_domain(OPPENHEIM, "step", [0.44], settings=coarse, model="fourlink")
    b = failure_domain(OPPENHEIM, "step", [0.44], settings=fine, model="fourlink")
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


def test_scan_grid_does_not_depend_on_the_ceiling():
    from archquake.domains.domain import coarse_scan

    lam = 0.37
    a = coarse_scan(lam, 5.0, 60, 5.0)
    b = coarse_scan(lam, 3.0, 60, 5.0)
    c = coarse_scan(lam, 8.0, 60, 5.0)
    assert a.size == 60 and a[-1] == pytest.approx(5.0)
    np.testing.assert_array_equal(b[:-1], a[a < 3.0])  # the same magnitudes below 3 g
    np.testing.assert_array_equal(c[: a.size], a)
    # doubling the points only adds magnitudes between the previous ones
    d = coarse_scan(lam, 5.0, 120, 5.0)
    np.testing.assert_allclose(d[1::2], a, rtol=1e-14)


def test_same_band_found_whatever_the_ceiling():
    # before: the grid was geometric from lambda to the ceiling, so the step impulse's
    # recovery band at t_p = 0.27 s (docs/domains.md) was scanned at other magnitudes for
    # each ceiling and its edges (or its presence) moved with --max-magnitude.
    bands = {}
    for top in (2.5, 5.0, 9.0):
        s = DomainSettings(max_magnitude_g=top, coarse_points=40, fine_points=24)
        d = failure_domain(OPPENHEIM, "step", [0.27], settings=s, model="fourlink")
        bands[top] = [(b.criterion, b.lower_g, b.upper_g) for b in d.non_monotonic_bands
                      if b.upper_g < 2.5]
        bands[top + 0.5] = float(d.collapse_g[0])
    assert bands[2.5] and bands[2.5] == bands[5.0] == bands[9.0]
    assert bands[3.0] == bands[5.5] == bands[9.5]
