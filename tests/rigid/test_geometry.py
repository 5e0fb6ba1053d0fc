"""The rigid step's geometry (`archquake.rigid._step_kernels.geometry`): corners, joint normals
and tangents, and gaps at any configuration, against the same quantities computed directly
with each angle's own cosine and sine (the kernel takes them from half angles by the addition
formulas)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import archquake.rigid._step_kernels as RK
from archquake.geometry import Arch
from archquake.rigid import RigidModel

MODEL = RigidModel.build(Arch(10.0, 1.5, math.radians(157.5), 7))


def _direct(model: RigidModel, q: np.ndarray):
    """Oracle: every corner, normal and gap with math.cos and math.sin of the angle itself
    (a body's rotation; a joint's mean rotation (theta_a + theta_b) / 2), in plain Python."""
    nj = len(model.ja)
    nrm = np.zeros((nj, 2))
    tan = np.zeros((nj, 2))
    pts = np.zeros((nj, 2, 2, 2))
    gaps = np.zeros((nj, 2))

    def point(body, arm):
        if body < 0:
            return arm[0], arm[1]
        c, s = math.cos(q[body, 2]), math.sin(q[body, 2])
        return q[body, 0] + c * arm[0] - s * arm[1], q[body, 1] + s * arm[0] + c * arm[1]

    for j in range(nj):
        a, b = model.ja[j], model.jb[j]
        th = 0.5 * ((0.0 if a < 0 else q[a, 2]) + (0.0 if b < 0 else q[b, 2]))
        c, s = math.cos(th), math.sin(th)
        nrm[j] = c * model.n0[j, 0] - s * model.n0[j, 1], s * model.n0[j, 0] + c * model.n0[j, 1]
        tan[j] = c * model.t0[j, 0] - s * model.t0[j, 1], s * model.t0[j, 0] + c * model.t0[j, 1]
        for k in range(2):
            pts[j, k, 0] = point(a, model.arm_a[j, k])
            pts[j, k, 1] = point(b, model.arm_b[j, k])
            gaps[j, k] = (pts[j, k, 1] - pts[j, k, 0]) @ nrm[j]
    return gaps, nrm, tan, pts


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from([1e-6, 1e-3, 0.05, 0.5, 3.0]))
def test_geometry_equals_direct_trigonometry(seed, spread):
    """Random displacements and rotations of the 7 voussoirs (rotations up to 3 rad, beyond any
    collapse): the kernel's corners and gaps agree with the direct computation to 5e-14 m, its
    normals and tangents to 2e-15, whatever the rotation's size."""
    rng = np.random.default_rng(seed)
    q0, _ = MODEL.rest()
    q = q0.copy()
    q[:, :2] += rng.uniform(-0.01, 0.01, (q.shape[0], 2))
    q[:, 2] = rng.uniform(-spread, spread, q.shape[0])
    got = RK.geometry(q, MODEL.ja, MODEL.jb, MODEL.arm_a, MODEL.arm_b, MODEL.n0, MODEL.t0)
    gaps, nrm, tan, pts = _direct(MODEL, q)
    np.testing.assert_allclose(got.nrm, nrm, rtol=0, atol=2e-15)
    np.testing.assert_allclose(got.tan, tan, rtol=0, atol=2e-15)
    np.testing.assert_allclose(got.pts, pts, rtol=0, atol=5e-14)
    np.testing.assert_allclose(got.gaps, gaps, rtol=0, atol=5e-14)
    assert np.allclose(np.hypot(got.nrm[:, 0], got.nrm[:, 1]), 1.0, rtol=0, atol=1e-15)
