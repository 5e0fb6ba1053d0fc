"""The arch's checks in one place (archquake.geometry.checks): a study key and a command-line
option are refused at the same bounds, each named as its user typed it.

Oracle: the ranges the module states (RADIUS_RANGE, MIN/MAX_EMBRACE_DEG, ...), probed just
inside and just outside each bound; the two wordings must agree on every probe, and the texts
are the ones the CLI tests and study-file tests read (tests/cli, tests/sweeps)."""

from __future__ import annotations

import math

import pytest

from archquake.errors import InvalidParameterError
from archquake.geometry import checks as C

CASES = [  # (check, extra args, low, high, low closed, high closed)
    (C.check_radius, (), *C.RADIUS_RANGE, True, True),
    (C.check_embrace_deg, (), C.MIN_EMBRACE_DEG, C.MAX_EMBRACE_DEG, True, True),
    (C.check_depth, (), C.MIN_DEPTH, C.MAX_DEPTH, True, True),
    (C.check_density, (), C.MIN_DENSITY, C.MAX_DENSITY, True, True),
    (C.check_thickness, (10.0,), C.MIN_THICKNESS_RATIO * 10.0, 20.0, True, False),
]


def _accepts(check, value, extra, wording):
    try:
        check(value, *extra, wording)
    except InvalidParameterError:
        return False
    return True


@pytest.mark.parametrize("check, extra, low, high, low_closed, high_closed", CASES)
def test_both_wordings_refuse_at_the_same_bounds(check, extra, low, high, low_closed,
                                                 high_closed):
    for bound, closed, step in ((low, low_closed, -1), (high, high_closed, +1)):
        outside = math.nextafter(bound, step * math.inf)
        inside = math.nextafter(bound, -step * math.inf)
        for wording in (C.KEYS, C.OPTIONS):
            assert _accepts(check, inside, extra, wording)
            assert _accepts(check, bound, extra, wording) is closed
            assert not _accepts(check, outside, extra, wording)


def test_each_wording_names_the_parameter_as_typed():
    with pytest.raises(InvalidParameterError, match=r"^radius must be in \[0.001, 10000\] \(m\)"):
        C.check_radius(0.0)
    with pytest.raises(InvalidParameterError, match=r"^--radius must be in \[0.001, 10000\] m,"):
        C.check_radius(0.0, C.OPTIONS)
    with pytest.raises(InvalidParameterError, match=r"^--embrace must be in \[0.001, 240\] degrees"):
        C.check_embrace_deg(300.0, C.OPTIONS)
    with pytest.raises(InvalidParameterError, match=r"^voussoirs must be >= 3 and <= 2000, got 2"):
        C.check_voussoirs(2)
    with pytest.raises(InvalidParameterError,
                       match=r"^--voussoirs must be a whole number from 3 to 2000, got 2"):
        C.check_voussoirs(2, C.OPTIONS)
    with pytest.raises(InvalidParameterError, match=r"^piers need both --pier-height and"):
        C.check_piers(2.0, None, None, C.OPTIONS)
    with pytest.raises(InvalidParameterError, match=r"^pier_height and pier_width go together"):
        C.check_piers(2.0, None)
    assert C.check_piers(None, None) is False and C.check_piers(1.0, 2.0) is True
