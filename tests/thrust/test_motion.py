"""Line of thrust of the moving arch (paper "Line of thrust during motion", Figure 8) and the
friction demand (paper p. 2131).

Oracles: the statics of each link (nine equations, one more than the unknowns: it holds only
if phi'' obeys the equation of motion), zero moment at the hinges, finite differences of the
displaced positions, the mirror symmetry of the two mechanisms, the equivalent static analysis
at the onset threshold (the paper's friction numbers: tests/paper/test_friction.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from archquake import Arch
from archquake.constants import STANDARD_GRAVITY as G
from archquake.ground import StepImpulse
from archquake.limit import limit_analysis
from archquake.mechanism import PreparedMechanism, simulate
from archquake.thrust import state_at, states

ARCH = Arch(10.0, 1.5, math.radians(157.5), 7)
R = ARCH.radius


@pytest.fixture(scope="module")
def prepared():
    return PreparedMechanism.build(ARCH)


@pytest.fixture(scope="module")
def fig8_history(prepared):
    """Figure 8's case (1.0 g, 0.20 s): many instants of both half cycles, and both sides of
    the first impact (t = 0.601 s)."""
    motion = StepImpulse.from_g(1.0, 0.20)
    result = simulate(prepared, motion, t_end=3.0)
    t_imp = float(result.impact_times[0])
    times = sorted({*np.linspace(0.0, 2.2, 45).tolist(), t_imp - 1e-6, t_imp + 1e-6})
    return result, states(prepared, motion, times)


def _cross(p, f):
    return p[0] * f[1] - p[1] * f[0]


def test_history_has_both_mechanisms_and_the_impact(fig8_history):
    result, snaps = fig8_history
    sides = {s.side for s in snaps}
    assert sides == {1, -1}
    t_imp = float(result.impact_times[0])
    before = [s for s in snaps if s.t < t_imp][-1]
    after = [s for s in snaps if s.t > t_imp][0]
    assert (before.side, after.side) == (1, -1)


def test_line_of_thrust_passes_through_the_four_hinges(fig8_history):
    """Zero moment at A, B, C, D at every instant: the thrust point is the hinge point (1e-9 R)."""
    _, snaps = fig8_history
    for s in snaps:
        for j, p in zip(s.hinge_joints, s.hinge_points, strict=True):
            assert np.linalg.norm(s.thrust_points[j] - p) < 1e-9 * R, (s.t, j)
            assert abs(abs(s.relative_eccentricity[j]) - 1.0) < 1e-9


def test_every_link_and_the_whole_arch_are_in_equilibrium(fig8_history):
    """Sum of forces and moments about O on each link (loads + hinge forces) and on the whole
    arch (loads + support reactions) vanish, relative to W and W R, to 1e-9."""
    _, snaps = fig8_history
    weight = ARCH.mass * G
    for s in snaps:
        j, p, f = s.hinge_joints, s.hinge_points, s.hinge_forces
        for link in range(3):
            sl = slice(j[link], j[link + 1])
            force = f[link] - f[link + 1] + s.loads[sl].sum(axis=0)
            moment = _cross(p[link], f[link]) - _cross(p[link + 1], f[link + 1]) + s.load_moments[sl].sum()
            assert np.abs(force).max() < 1e-9 * weight
            assert abs(moment) < 1e-9 * weight * R
        # whole arch: the reactions act at the springing hinges A (joint 0) and D (joint 7)
        total_f = s.left_reaction + s.right_reaction + s.loads.sum(axis=0)
        total_m = (_cross(p[0], s.left_reaction) + _cross(p[3], s.right_reaction)
                   + s.load_moments.sum())
        assert np.abs(total_f).max() < 1e-9 * weight
        assert abs(total_m) < 1e-9 * weight * R
        assert s.equilibrium_residual < 1e-12


def test_the_ninth_equation_needs_the_equation_of_motion(prepared):
    """With a wrong phi'' the links cannot all be in equilibrium: the check can fail."""
    import importlib

    from archquake.mechanism.configuration import displaced_arch

    S = importlib.import_module("archquake.thrust.states")  # the module (its function shares the name)

    s = state_at(prepared, 0.0, 0.01, 0.05, 1, -G)
    config = displaced_arch(prepared, 0.01, 1, phi_dot=0.05, phi_ddot=1.1 * s.phi_ddot)
    loads, moments = S._voussoir_loads(ARCH, config.centroids, config.accelerations,
                                       config.angular_accelerations, -G, G)
    _, residual = S._hinge_forces(config, loads, moments, ARCH.mass * G, ARCH.mass * G * R)
    assert residual > 1e-4


@pytest.mark.parametrize("side", [1, -1])
def test_accelerations_match_finite_differences_of_positions(prepared, side):
    """Centroid accelerations r' phi'' + r'' phi'^2 against central differences in time of the
    displaced centroids along phi(t) = phi + v dt + phi'' dt^2 / 2 (error O(dt^2))."""
    phi, v, xg = 0.02, 0.08, -0.3 * G
    s = state_at(prepared, 0.0, phi, v, side, xg)
    dt = 1e-4
    pos = [state_at(prepared, 0.0, phi + v * h + 0.5 * s.phi_ddot * h * h, v, side, xg).centroids
           for h in (-dt, 0.0, dt)]
    acc_fd = (pos[0] - 2 * pos[1] + pos[2]) / dt**2
    # the inertia part of each load: -m (a + (xg, g))
    acc = -s.loads / ARCH.voussoir_masses[:, None] - np.array([xg, G])
    assert np.abs(acc - acc_fd).max() < 1e-5 * np.abs(acc).max()


def test_mirror_mechanism_is_the_mirror_image(prepared):
    """Side -1 under x_g'' is the mirror image of side +1 under -x_g'': same N and |V| at the
    mirrored joints, eccentricities mirrored (intrados/extrados kept), thrust points mirrored."""
    a = state_at(prepared, 0.0, 0.015, -0.04, 1, 0.4 * G)
    b = state_at(prepared, 0.0, 0.015, -0.04, -1, -0.4 * G)
    np.testing.assert_allclose(b.forces.normal, a.forces.normal[::-1], rtol=1e-12)
    np.testing.assert_allclose(np.abs(b.forces.shear), np.abs(a.forces.shear[::-1]), rtol=1e-10)
    np.testing.assert_allclose(b.forces.eccentricity, a.forces.eccentricity[::-1], atol=1e-12 * R)
    np.testing.assert_allclose(b.thrust_points, a.thrust_points[::-1] * [-1, 1], atol=1e-12 * R)


def test_at_rest_the_line_of_thrust_lies_inside_the_section(prepared):
    s = state_at(prepared, 0.0, 0.0, 0.0, 0, 0.0)
    assert s.locked and s.exit_joint is None
    assert s.forces.admissible(rtol=1e-7)
    assert np.all(s.forces.normal > 0)
    # the arch and its loads are symmetric; the least-friction line is too
    np.testing.assert_allclose(s.friction_demand, s.friction_demand[::-1], atol=1e-5)


def test_at_the_threshold_the_moving_arch_is_the_static_collapse_state(prepared):
    """At phi = 0 with x_g'' = -lambda g, phi'' = 0 and the joint forces are those of the
    equivalent static analysis (another solver: the limit analysis' linear algebra)."""
    la = limit_analysis(ARCH)
    s = state_at(prepared, 0.0, 0.0, 0.0, 1, -la.collapse_acceleration_g * G)
    assert abs(s.phi_ddot) < 1e-9
    np.testing.assert_allclose(s.friction_demand, la.friction_ratios, rtol=1e-7)
    np.testing.assert_allclose(s.forces.normal, la.joint_forces.normal, rtol=1e-7)


def test_figure_8a_line_of_thrust_leaves_between_the_second_and_third_voussoirs(fig8_history):
    """Paper p. 2129: at t = 0.20 s the line of thrust exits the thickness; the second hinge
    would move between the second and third voussoirs (joint 2)."""
    _, snaps = fig8_history
    (s,) = [s for s in snaps if abs(s.t - 0.2) < 1e-9]
    assert s.exit_joint == 2
    assert s.outside[2] > 0.5
