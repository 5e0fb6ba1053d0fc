"""The equation of motion (paper Eq. 2) against an independent sympy derivation.

Oracle: sympy differentiates the Lagrangian of the same four-bar written in three absolute link
angles (q1, q2, q3) with the loop-closure constraint enforced by Lagrange multipliers, the
formulation of sympy's four-bar linkage example. Nothing is shared with archquake's closed-form
kinematics except the link masses, centroids and inertias. The two accelerations must agree to
round-off (1e-9 relative).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import root

from archquake.constants import STANDARD_GRAVITY as G
from archquake.geometry import Arch
from archquake.mechanism import PreparedMechanism
from archquake.mechanism.kinematics import LINK0, SIGMA, acceleration


def _rot(q):
    return sp.Matrix([[sp.cos(q), -sp.sin(q)], [sp.sin(q), sp.cos(q)]])


def _lagrangian_model(packed: np.ndarray):
    a = sp.Matrix(packed[0:2])
    b0 = sp.Matrix(packed[2:4])
    c0 = sp.Matrix(packed[4:6])
    d = sp.Matrix(packed[6:8])
    q = sp.Matrix(sp.symbols("q1:4"))
    qd = sp.Matrix(sp.symbols("u1:4"))
    xg = sp.Symbol("xg")
    b = a + _rot(q[0]) * (b0 - a)
    pivots = [a, b, d]
    T = 0
    V = 0
    for k in range(3):
        m, rx, ry, inertia = (float(x) for x in packed[LINK0 + 4 * k: LINK0 + 4 * k + 4])
        r = pivots[k] + _rot(q[k]) * sp.Matrix([rx, ry])
        v = r.jacobian(q) * qd
        T += sp.Rational(1, 2) * m * (v.T * v)[0] + sp.Rational(1, 2) * inertia * qd[k] ** 2
        V += m * G * r[1] + m * xg * r[0]  # gravity and the ground's inertia force
    phi = b + _rot(q[1]) * (c0 - b0) - d - _rot(q[2]) * (c0 - d)  # loop closure
    mass = sp.hessian(T, qd)
    dT_dqd = sp.Matrix([sp.diff(T, u) for u in qd])
    h = dT_dqd.jacobian(q) * qd - sp.Matrix([sp.diff(T, x) for x in q])
    dv = sp.Matrix([sp.diff(V, x) for x in q])
    jac = phi.jacobian(q)
    jac_dot_qd = (jac * qd).jacobian(q) * qd
    args = (list(q), list(qd), xg)
    return (sp.lambdify(args, mass), sp.lambdify(args, h), sp.lambdify(args, dv),
            sp.lambdify(args, jac), sp.lambdify(args, jac_dot_qd), sp.lambdify([list(q)], phi))


@pytest.fixture(scope="module")
def model():
    prep = PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7))
    return prep.packed, _lagrangian_model(prep.packed)


@pytest.mark.parametrize(("phi", "rate", "ground"),
                         [(0.0, 0.0, -9.8), (0.02, 0.3, -9.8), (0.05, -0.2, 4.9), (0.3, 1.1, 0.0),
                          (0.8, 0.5, 2.0)])
def test_phi_ddot_matches_constrained_lagrangian(model, phi, rate, ground):
    packed, (mass, h, dv, jac, jac_dot_qd, closure) = model
    sigma = packed[SIGMA]
    q1 = sigma * phi
    # assemble the linkage independently: solve the closure for q2, q3 (from the undisplaced state)
    solved = root(lambda x: np.array(closure([q1, x[0], x[1]]), dtype=float).ravel(), [0.0, 0.0],
                  method="lm", tol=1e-15)
    q = [q1, *solved.x]
    assert np.max(np.abs(np.array(closure(q), dtype=float))) < 1e-12
    jq = np.array(jac(q, [0, 0, 0], ground), dtype=float)
    # velocities consistent with the constraint: J qdot = 0 with qdot1 = sigma * rate
    u23 = np.linalg.solve(jq[:, 1:], -jq[:, 0] * sigma * rate)
    qd = [sigma * rate, *u23]
    m = np.array(mass(q, qd, ground), dtype=float)
    rhs_q = -(np.array(h(q, qd, ground), dtype=float) + np.array(dv(q, qd, ground), dtype=float)).ravel()
    rhs_c = -np.array(jac_dot_qd(q, qd, ground), dtype=float).ravel()
    kkt = np.block([[m, -jq.T], [jq, np.zeros((2, 2))]])
    sol = np.linalg.solve(kkt, np.concatenate([rhs_q, rhs_c]))
    expected = sigma * sol[0]
    got = acceleration(packed, phi, rate, ground, G)
    assert got == pytest.approx(expected, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("phi", [0.0, 0.03, 0.2, 0.6])
def test_paper_form_of_eq2_reproduces_the_acceleration(model, phi):
    """M R theta'' + L R theta'^2 + F g = P x_g'' with theta'' = -phi'' (paper Eq. 2), and the
    coefficients do not depend on the size of the arch."""
    from archquake.mechanism.kinematics import LENGTH, paper_coefficients

    packed, _ = model
    big = PreparedMechanism.build(Arch(37.0, 5.55, math.radians(157.5), 7, density=1234.0)).packed
    rate, ground = 0.4, -6.0
    mm, ll, ff, pp = paper_coefficients(packed, phi)
    theta_ddot = (pp * ground - ff * G - ll * packed[LENGTH] * rate**2) / (mm * packed[LENGTH])
    assert -theta_ddot == pytest.approx(acceleration(packed, phi, rate, ground, G), rel=1e-12)
    np.testing.assert_allclose(paper_coefficients(big, phi), (mm, ll, ff, pp), rtol=1e-10)
