"""Arches on piers (issue 12): the pier courses are more blocks of the same chain, so the
four-hinge mechanisms may put hinges in the piers.

Oracles: the two limit-analysis methods (static LP, virtual work over every mechanism,
hinges in the piers included) agreeing to 1e-6; the rigid-base arch (piers squat and wide
enough change nothing: same lambda); an upper bound (adding freedom - joints in the piers -
can only lower lambda).
"""

import math

import pytest

from archquake.errors import UnstableArchError
from archquake.geometry import Arch, OnPiers, Piers, check_tiling
from archquake.limit import limit_analysis

ARCH = Arch(5.0, 0.75, math.pi, 21)


def test_piers_tile_with_the_arch():
    chain = OnPiers(ARCH, Piers(4.0, 1.5, 4))
    check_tiling(chain)
    assert chain.voussoirs == 21 + 8
    # bed joints: horizontal, intrados end towards the opening
    assert chain.intrados_points[0].tolist() == pytest.approx([-4.625, -4.0])
    assert chain.extrados_points[0].tolist() == pytest.approx([-6.125, -4.0])


def test_squat_piers_do_not_change_the_arch():
    """Wide, low piers: the collapse mechanism stays in the arch (hinges shifted by the 4 pier
    joints) at the rigid-base lambda."""
    lam0 = limit_analysis(ARCH, method="both")
    res = limit_analysis(OnPiers(ARCH, Piers(2.0, 3.0, 4)), method="both")
    assert res.collapse_acceleration_g == pytest.approx(lam0.collapse_acceleration_g, rel=1e-9)
    assert res.mechanism.joints == tuple(j + 4 for j in lam0.mechanism.joints)


def test_slender_piers_fail_by_a_global_mechanism_at_a_lower_lambda():
    """4 m high, 1.5 m wide piers: the mechanism puts hinge D at the base of the right pier
    (joint 29, its outer face) and lambda drops from 0.148 g to about a third (0.0525 g)."""
    res = limit_analysis(OnPiers(ARCH, Piers(4.0, 1.5, 4)), method="both")
    lam0 = limit_analysis(ARCH).collapse_acceleration_g
    assert res.collapse_acceleration_g < 0.5 * lam0
    assert res.mechanism.joints[3] == 29 and res.mechanism.faces[3].value == "extrados"
    assert abs(res.static_collapse_acceleration_g - res.kinematic_collapse_acceleration_g) < 1e-6


def test_a_pier_too_slender_to_stand_is_one_line():
    with pytest.raises(UnstableArchError, match="the piers are too slender"):
        limit_analysis(OnPiers(ARCH, Piers(8.0, 1.5, 4)))
