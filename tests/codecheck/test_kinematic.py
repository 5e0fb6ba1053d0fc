"""The equivalent SDOF system and capacity curve of a local mechanism (C8.7.1.2.1.2-3).

Oracles: the rocking block's closed forms (alpha0 = b/h, e* = 1, alpha(d) = tan(asin(sin beta -
d/R)), d0 = b/2, all exact: tolerance 1e-12, round-off of a few operations); for the arch the
equivalent static analysis (limit_analysis, an independent linear program), the four-link
model's crest of the potential (its own bisection), its equation-of-motion terms G/H, and the
displaced arch of the plots; e* by hand for two blocks.
"""

import math

import numpy as np
import pytest

from archquake.codecheck.kinematic import (
    ControlPoint,
    FourHingeMechanism,
    RockingBlock,
    capacity_curve,
    participation,
)
from archquake.errors import InvalidParameterError
from archquake.geometry import Arch
from archquake.limit import limit_analysis
from archquake.mechanism.configuration import displaced_arch
from archquake.mechanism.kinematics import eom_terms


@pytest.mark.parametrize("b, h", [(0.5, 5.0), (0.4, 2.0), (1.0, 1.5)])
def test_rocking_block_closed_forms(b, h):
    curve = capacity_curve(RockingBlock.on_base(b, h))
    beta, radius = math.atan2(b, h), 0.5 * math.hypot(b, h)
    assert curve.alpha0 == pytest.approx(b / h, rel=1e-12)
    assert curve.e_star == pytest.approx(1.0, rel=1e-12)
    assert curve.m_star_kg == pytest.approx(2000.0 * b * h, rel=1e-12)
    assert curve.d0_m == pytest.approx(b / 2, rel=1e-12)
    assert curve.phi0_rad == pytest.approx(beta, rel=1e-12)
    for frac in (0.1, 0.4, 0.6, 0.9):
        d = frac * b / 2
        exact = math.tan(math.asin(math.sin(beta) - d / radius))
        assert curve.alpha_at(d) == pytest.approx(exact, rel=1e-12)


def test_participation_by_hand():
    # two masses 1 and 3 kg moving 1 and 2 per unit: (1 + 6)^2 / (4 (1 + 12)) = 49 / 52
    e, m = participation(np.array([1.0, 3.0]), np.array([1.0, 2.0]))
    assert e == pytest.approx(49 / 52, rel=1e-15)
    assert m == pytest.approx(4 * 49 / 52, rel=1e-15)
    # invariant under the scale of the virtual field
    assert participation(np.array([1.0, 3.0]), np.array([-7.0, -14.0]))[0] == pytest.approx(e)


@pytest.fixture(scope="module")
def arches():
    return {"oppenheim": Arch(10.0, 1.5, math.radians(157.5), 7),
            "bridge": Arch(5.0, 0.6, math.pi, 15)}


@pytest.fixture(scope="module")
def curves(arches):
    return {k: capacity_curve(a) for k, a in arches.items()}


@pytest.mark.parametrize("name", ["oppenheim", "bridge"])
def test_arch_alpha0_is_limit_analysis(name, arches, curves):
    # the collapse multiplier of the line-of-thrust LP and of virtual work over all mechanisms
    lam = limit_analysis(arches[name], method="both").collapse_acceleration_g
    assert curves[name].alpha0 == pytest.approx(lam, rel=1e-9)


@pytest.mark.parametrize("name", ["oppenheim", "bridge"])
def test_arch_curve_ends_at_critical_rotation(name, curves):
    c = curves[name]
    assert c.alphas[0] == pytest.approx(c.alpha0, rel=1e-12)
    # the four-link model's own crest search (bisection to round-off on G(phi) = 0)
    assert c.phi0_rad == pytest.approx(c.mechanism.critical_rotation, rel=1e-9)
    assert c.alpha_at(c.d0_m) == pytest.approx(0.0, abs=1e-9)
    assert np.all(np.diff(c.alphas) < 0.0)  # the capacity falls all the way (self-weight only)


@pytest.mark.parametrize("name", ["oppenheim", "bridge"])
def test_arch_alpha_is_equation_of_motion_ratio(name, curves):
    # the static multiplier along the motion is G/H of the four-link equation of motion (Eq. 2
    # with phi'' = phi' = 0 and x_g'' = -alpha g), link masses lumped there, per voussoir here
    c = curves[name]
    for phi in np.linspace(0.0, c.phi0_rad, 7)[:-1]:
        _, _, _, gg, hh = eom_terms(c.mechanism.prepared.packed, float(phi))
        assert c.alpha(float(phi)) == pytest.approx(gg / hh, rel=1e-9, abs=1e-12)


def test_motion_is_the_displaced_arch(curves):
    c = curves["oppenheim"]
    mech = c.mechanism
    phi = 0.6 * c.phi0_rad
    motion = mech.motion(phi)
    state = displaced_arch(mech.prepared, phi, phi_dot=0.0, phi_ddot=1.0)
    k = mech.voussoirs
    np.testing.assert_allclose(motion.centroids, state.centroids[k], rtol=0, atol=1e-12)
    np.testing.assert_allclose(motion.centroid_rates, state.accelerations[k], rtol=0, atol=1e-12)
    np.testing.assert_allclose(motion.rotations, state.rotations[k], rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ["oppenheim", "bridge"])
def test_control_point_changes_d_only_at_large_displacement(name, curves):
    c = curves[name]
    arch = c.mechanism.prepared.mechanism.arch
    small = 1e-5 * c.phi0_rad
    for block in (0, 2, len(c.mechanism.masses) - 1):
        k = c.mechanism.voussoirs[block]
        for point in (arch.voussoir_centroids[k], arch.extrados_points[k]):
            other = capacity_curve(c.mechanism, control=ControlPoint(block, point))
            assert other.e_star == c.e_star and other.m_star_kg == c.m_star_kg
            assert other.alpha0 == c.alpha0 and other.phi0_rad == c.phi0_rad
            # (C8.7.1.4) is exact to first order in phi: relative difference O(phi)
            assert other.displacement(small) == pytest.approx(c.displacement(small), rel=1e-4)


def test_control_point_that_does_not_move_is_refused(curves):
    c = curves["oppenheim"]
    a = c.mechanism.prepared.mechanism.points[0]
    with pytest.raises(InvalidParameterError, match="control point"):
        capacity_curve(c.mechanism, control=ControlPoint(0, a))
    with pytest.raises(InvalidParameterError, match="control block"):
        capacity_curve(c.mechanism, control=ControlPoint(99, a))


def test_four_hinge_of_arch(arches):
    mech = FourHingeMechanism.of(arches["oppenheim"])
    assert mech.prepared.mechanism.joints == (0, 3, 5, 7)
    assert mech.masses.sum() == pytest.approx(arches["oppenheim"].mass)
