"""The statics of a voussoir chain (limit.thrust.joint_forces) against independent equilibrium.

Oracles: each voussoir's equilibrium written out directly from forces and points (not through
the cumulative sums), invariance under a rigid motion of the whole configuration (what the
line of thrust during motion relies on), and a hand-solved strut.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from archquake.geometry import Arch
from archquake.limit import arch_joint_points, joint_forces, moments_about_origin


def _random_case(rng: np.random.Generator, n: int):
    arch = Arch.from_ratio(rng.uniform(0.05, 0.4), math.radians(rng.uniform(60, 240)), n, radius=3.0)
    pts = arch_joint_points(arch) + rng.normal(0, 0.05, (n + 1, 2, 2))  # any configuration
    forces = rng.normal(0, 100.0, (n, 2))
    at = arch.voussoir_centroids + rng.normal(0, 0.1, (n, 2))
    couples = rng.normal(0, 50.0, n)
    moments = moments_about_origin(forces, at, couples)
    reaction = rng.normal(0, 300.0, 2)
    reaction_moment = float(rng.normal(0, 300.0))
    return pts, forces, at, couples, moments, reaction, reaction_moment


@given(st.integers(0, 2**32 - 1), st.integers(3, 25))
@settings(max_examples=40, deadline=None)
def test_every_voussoir_is_in_equilibrium(seed, n):
    """Sum of forces and of moments about an arbitrary point vanish on every voussoir, using
    the thrust points (where the joint resultants act) rather than the moments returned."""
    rng = np.random.default_rng(seed)
    pts, forces, at, couples, _, reaction, r_m = _random_case(rng, n)
    jf = joint_forces(pts, forces, moments_about_origin(forces, at, couples), reaction, r_m)
    assert np.allclose(jf.force[0], reaction)
    pole = rng.normal(0, 5.0, 2)
    scale = np.abs(jf.force).max() * 10.0
    for k in range(n):
        total = forces[k] + jf.force[k] - jf.force[k + 1]
        assert np.allclose(total, 0.0, atol=1e-9 * scale)

        def m_about_pole(f, p):
            return (p[0] - pole[0]) * f[1] - (p[1] - pole[1]) * f[0]

        mom = (
            m_about_pole(forces[k], at[k]) + couples[k]
            + m_about_pole(jf.force[k], jf.thrust_points[k])
            - m_about_pole(jf.force[k + 1], jf.thrust_points[k + 1])
        )
        assert abs(mom) <= 1e-8 * scale
    # components: N along the joint normal, V along the joint, and they rebuild the force
    rebuilt = jf.normal[:, None] * jf.normals + jf.shear[:, None] * jf.tangents
    assert np.allclose(rebuilt, jf.force)
    assert np.allclose(np.einsum("ij,ij->i", jf.normals, jf.tangents), 0.0)
    # the thrust point lies on the joint line
    d = jf.thrust_points - pts[:, 0]
    along = pts[:, 1] - pts[:, 0]
    assert np.allclose(d[:, 0] * along[:, 1] - d[:, 1] * along[:, 0], 0.0, atol=1e-9)


@given(st.integers(0, 2**32 - 1), st.floats(-math.pi, math.pi), st.integers(3, 12))
@settings(max_examples=30, deadline=None)
def test_rigid_motion_leaves_joint_actions_unchanged(seed, angle, n):
    """Rotating and translating the whole configuration and its loads (a frame change) leaves
    N, V and the eccentricities unchanged: the function is valid in any configuration."""
    rng = np.random.default_rng(seed)
    pts, forces, at, couples, _, reaction, _ = _random_case(rng, n)
    r_at = pts[0].mean(axis=0)  # the reaction acts at the left joint centre
    r_m = float(moments_about_origin(reaction, r_at))
    base = joint_forces(pts, forces, moments_about_origin(forces, at, couples), reaction, r_m)
    rot = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    shift = rng.normal(0, 10.0, 2)

    def move(p):
        return p @ rot.T + shift

    r2 = reaction @ rot.T
    moved = joint_forces(
        move(pts),
        forces @ rot.T,
        moments_about_origin(forces @ rot.T, move(at), couples),
        r2,
        float(moments_about_origin(r2, move(r_at))),
    )
    assert np.allclose(moved.normal, base.normal, atol=1e-9 * np.abs(base.normal).max())
    assert np.allclose(moved.shear, base.shear, atol=1e-9 * np.abs(base.normal).max())
    assert np.allclose(moved.eccentricity, base.eccentricity, rtol=1e-7, atol=1e-9)
    assert np.allclose(moved.thrust_points, move(base.thrust_points), atol=1e-7)


def test_inclined_joint_strut_by_hand():
    """A weightless block between joints inclined at 45 degrees, pushed by a horizontal force P
    through the joint centres: N = P cos 45, |V| = P sin 45, friction demand tan 45 = 1."""
    s = math.sqrt(0.5)
    pts = np.array([[[0.0, 0.0], [s, s]], [[2.0, 0.0], [2.0 + s, s]]])
    centre = 0.5 * (pts[0, 0] + pts[0, 1])
    p = 7.0
    jf = joint_forces(pts, np.zeros((1, 2)), np.zeros(1), np.array([p, 0.0]),
                      float(moments_about_origin(np.array([p, 0.0]), centre)))
    assert np.allclose(jf.normal, p * s)
    assert np.allclose(np.abs(jf.shear), p * s)
    assert np.allclose(jf.friction_ratio, 1.0)
    assert np.allclose(jf.eccentricity, 0.0)
