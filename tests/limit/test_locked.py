"""The least-friction admissible line of thrust of the locked arch (limit/locked.py).

Oracle: the bisection on the friction coefficient with one linear feasibility program per
step (the method it replaces, written out here), run to 1e-10; the lower-bound theorem (the
line is inside the section and in compression); and the arch's mirror symmetry.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import linprog

from archquake import Arch
from archquake.constants import STANDARD_GRAVITY as G
from archquake.errors import SolverError
from archquake.limit import arch_joint_points, joint_forces, locked_joint_forces, moments_about_origin

ARCHES = (Arch(10.0, 1.5, math.radians(157.5), 7), Arch(5.0, 0.9, math.radians(140.0), 11),
          Arch(10.0, 1.2, math.radians(180.0), 16))


def _loads(arch, a):
    """Weight and ground inertia of each voussoir under a horizontal ground acceleration a g."""
    f = -arch.voussoir_masses[:, None] * np.array([a * G, G])
    return f, moments_about_origin(f, arch.voussoir_centroids)


def _bisection_mu(arch, loads, moments, tol=1e-10):
    """Least mu for which some line inside the section has |V| <= mu N everywhere, or None."""
    pts = arch_joint_points(arch)
    w = float(np.abs(loads).sum())
    base = joint_forces(pts, loads, moments, np.zeros(2), 0.0)
    units = [joint_forces(pts, 0 * loads, 0 * moments, r, rm) for r, rm in
             ((np.array([w, 0.0]), 0.0), (np.array([0.0, w]), 0.0), (np.zeros(2), w * arch.radius))]
    h = base.half_widths
    n0, v0, m0 = base.normal, base.shear, base.moment
    n1, v1, m1 = (np.array([getattr(u, k) for u in units]).T for k in ("normal", "shear", "moment"))

    def feasible(mu):
        a = np.vstack([m1 - h[:, None] * n1, -m1 - h[:, None] * n1, v1 - mu * n1, -v1 - mu * n1])
        b = -np.concatenate([m0 - h * n0, -m0 - h * n0, v0 - mu * n0, -v0 - mu * n0])
        return linprog(np.zeros(3), A_ub=a / w, b_ub=b / w, bounds=[(None, None)] * 3,
                       method="highs").status == 0

    lo, hi = 0.0, 4.0
    if not feasible(hi):
        return None
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if feasible(mid) else (mid, hi)
    return hi


@pytest.mark.parametrize("arch", ARCHES, ids=lambda a: f"n{a.voussoirs}")
def test_least_friction_equals_the_bisection(arch):
    """Same coefficient as the bisection to 1e-6 (the bisection's former tolerance; measured
    <= 3.7e-7, the linear programs' own feasibility tolerance), and the same verdict where no
    line fits; the line found is inside the section and in compression."""
    for a in (-0.3, -0.12, 0.0, 0.07, 0.2, 0.3):
        loads, moments = _loads(arch, a)
        mu = _bisection_mu(arch, loads, moments)
        if mu is None:
            with pytest.raises(SolverError):
                locked_joint_forces(arch, loads, moments)
            continue
        jf = locked_joint_forces(arch, loads, moments)
        assert jf.friction_ratio.max() == pytest.approx(mu, abs=1e-6), a
        assert jf.admissible(rtol=1e-7) and np.all(jf.normal > 0)


def test_mirror_loads_need_the_same_friction():
    """A symmetric arch under a g and under -a g: mirror images, the same least friction."""
    arch = ARCHES[0]
    mus = [locked_joint_forces(arch, *_loads(arch, a)).friction_ratio.max() for a in (0.15, -0.15)]
    assert mus[0] == pytest.approx(mus[1], abs=1e-6)


def test_a_warm_start_gives_the_same_line_within_tol():
    """Starting from the answer for nearby loads (as a time history does) changes the
    coefficient by less than tol = 1e-6, whether the start line fits the new loads or not."""
    arch = ARCHES[1]
    previous = locked_joint_forces(arch, *_loads(arch, 0.10))
    for a in (0.1005, 0.12, -0.2):
        loads, moments = _loads(arch, a)
        cold = locked_joint_forces(arch, loads, moments)
        warm = locked_joint_forces(arch, loads, moments, start=previous)
        assert warm.friction_ratio.max() == pytest.approx(cold.friction_ratio.max(), abs=1e-6)
        assert warm.admissible(rtol=1e-7)
