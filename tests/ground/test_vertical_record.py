"""A record with its vertical component, described to the compiled kernels (kind 3): each
component on its own time step, the breakpoints the union of both components' samples.

Oracles: `Record.acceleration` of each component (the same linear interpolation, so equal to
rounding: checked to 1e-12 of the largest sample); the union of the two sample grids, walked
by `next_breakpoint`; the longer component's end as the motion's duration; and the one-line
refusals (lift-off, a time step below the integrators' resolution).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from archquake.constants import STANDARD_GRAVITY as G
from archquake.errors import InvalidParameterError
from archquake.ground._kernel import (
    evaluate,
    evaluate_vertical,
    ground_duration,
    ground_in_piece,
    next_breakpoint,
    vertical_in_piece,
)
from archquake.ground.base import (
    KIND_SAMPLED_VERTICAL,
    check_lift_off,
    check_motion_lift_off,
    check_time_resolution,
    has_vertical,
)
from archquake.ground.records import Record
from archquake.ground.vertical import WithVertical

samples = st.lists(st.floats(-5.0, 5.0), min_size=2, max_size=25)
steps = st.sampled_from([0.005, 0.01, 0.02, 0.0125])


@given(samples, steps, samples, steps)
@settings(max_examples=80, deadline=None)
def test_each_component_is_its_own_record(xh, dth, xv, dtv):
    xh, xv = np.asarray(xh), np.asarray(xv)
    h, v = Record(xh, dth), Record(xv, dtv)
    kind, params = WithVertical(h, v).kernel_spec()
    assert kind == KIND_SAMPLED_VERTICAL
    end = max(h.duration, v.duration)
    assert ground_duration(kind, params) == pytest.approx(end, rel=1e-15)
    # the walk through the breakpoints is the union of both sample grids
    pts, t = [], -1.0
    while np.isfinite(t := next_breakpoint(kind, params, t)):
        pts.append(t)
    union = np.union1d(h.times, v.times)
    union = union[np.r_[True, np.diff(union) > 1e-12 * (1.0 + union[1:])]]  # one grid point
    assert np.allclose(pts, union, rtol=0, atol=1e-12)
    # inside every piece both components are linear, and equal to each record's own value
    t = np.r_[0.5 * (union[:-1] + union[1:]), union[0] + 0.3 * np.diff(union)]
    tol = 1e-12 * (1.0 + max(np.abs(xh).max(), np.abs(xv).max()))
    assert np.allclose(evaluate(kind, params, t), h.acceleration(t), rtol=0, atol=tol)
    assert np.allclose(evaluate_vertical(kind, params, t), v.acceleration(t), rtol=0, atol=tol)
    for left, right in zip(union[:-1], union[1:], strict=True):
        mid = 0.5 * (left + right)
        assert ground_in_piece(kind, params, right, mid) == pytest.approx(
            h.acceleration(right - 1e-9 * (right - left)), abs=1e-6 * (1 + abs(xh).max()))
        assert vertical_in_piece(kind, params, right, mid) == pytest.approx(
            v.acceleration(right - 1e-9 * (right - left)) if right <= v.duration else 0.0,
            abs=1e-6 * (1 + abs(xv).max()))


def test_scaling_scales_both_and_mirroring_the_horizontal_only():
    both = WithVertical(Record([0.0, 2.0, -1.0], 0.01), Record([1.0, -3.0], 0.02))
    k, p = both.kernel_spec()
    k2, p2 = both.scaled(2.0).kernel_spec()
    assert k2 == k and np.array_equal(p2[3:6], 2.0 * p[3:6]) and np.array_equal(
        p2[8:], 2.0 * p[8:])
    _, pm = both.mirrored().kernel_spec()
    assert np.array_equal(pm[3:6], -p[3:6]) and np.array_equal(pm[6:], p[6:])
    assert has_vertical(both)


def test_lift_off_and_time_resolution_read_the_vertical():
    h = Record([0.0, 1.0, 0.0], 0.01)
    down = WithVertical(h, Record([0.0, -1.05 * G], 0.01))
    with pytest.raises(InvalidParameterError, match="1.05 g downward"):
        check_lift_off(*down.kernel_spec(), G)
    with pytest.raises(InvalidParameterError, match="lifts the arch off"):
        check_motion_lift_off(down, G)
    check_lift_off(*WithVertical(h, Record([0.0, -0.9 * G], 0.01)).kernel_spec(), G)
    fine = WithVertical(h, Record([0.0, 1.0, 0.0], 1e-12))
    with pytest.raises(InvalidParameterError, match="record time step DT"):
        check_time_resolution(*fine.kernel_spec(), 1.0)
