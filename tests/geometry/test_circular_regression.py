"""Today's numbers of the circular arch, pinned before the block-chain refactor (issue 12).

Oracle: the values printed by the closed-form annular-sector ``Arch`` and the limit analysis
at commit 2077232 (before ``Arch`` became one builder of the voussoir chain). Every result of
the package flows from these, so they must survive the refactor to round-off (rtol 1e-12 for
the closed forms; the minimum thickness is a bisection to rtol 1e-7 and is pinned to 1e-9 of
its own value, i.e. the same bisection path).
"""

import math

import numpy as np

from archquake.geometry import Arch
from archquake.limit import limit_analysis, min_thickness_ratio
from archquake.mechanism import PreparedMechanism

OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


def test_oppenheim_lambda_and_hinges_unchanged():
    res = limit_analysis(OPPENHEIM, method="both")
    assert math.isclose(res.collapse_acceleration_g, 0.3700097380218764, rel_tol=1e-12)
    assert res.mechanism.joints == (0, 3, 5, 7)
    assert [f.value for f in res.mechanism.faces] == ["intrados", "extrados", "intrados", "extrados"]


def test_semicircle_min_thickness_unchanged():
    assert math.isclose(min_thickness_ratio(math.pi, 200), 0.10746461153030396, rel_tol=1e-9)


def test_oppenheim_mass_properties_unchanged():
    np.testing.assert_allclose(OPPENHEIM.voussoir_masses, 11780.972450961723, rtol=1e-12)
    np.testing.assert_allclose(OPPENHEIM.voussoir_inertias, 17323.499338711597, rtol=1e-12)
    np.testing.assert_allclose(
        OPPENHEIM.voussoir_centroids,
        [[-9.19675720336116, 3.809421563484655], [-7.0388932264212265, 7.038893226421227],
         [-3.8094215634846473, 9.196757203361164], [0.0, 9.954498264901012],
         [3.809421563484652, 9.19675720336116], [7.038893226421228, 7.038893226421226],
         [9.196757203361164, 3.8094215634846478]],
        rtol=1e-12, atol=1e-12,
    )


def test_oppenheim_prepared_mechanism_unchanged():
    packed = PreparedMechanism.build(OPPENHEIM).packed
    expected = [
        -9.072263843729882, 1.8045854786491897, -2.0972209616733757, 10.543441764334728,
        5.139024655431323, 7.691093913798542, 10.543441764334728, 2.0972209616733766, -1.0, 1.0,
        7.778119238705804, 7.778119238705805, 35342.91735288517, 2.3905731793075367,
        4.877105185773158, 398403.7331741259, 23561.944901923445, 4.001931743415703,
        -0.9678140302036429, 123510.07373897772, 23561.944901923445, -2.4256165494435304,
        3.3269364332795606, 123510.07373897778, 0.06906469353926892, 1.7962017436217037,
        82466.80715673206, 10.0, 265204.9589864539, 716751.2952612443,
    ]
    np.testing.assert_allclose(packed, expected, rtol=1e-12, atol=1e-12)
