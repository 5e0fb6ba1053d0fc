"""The line of thrust of the locked arch: the admissible one that needs the least friction.

While the arch does not hinge (before the onset, and after it comes to rest) it moves rigidly
with the ground, and its internal forces are statically indeterminate: three redundants, the
left reaction (H, V) and its moment. By the lower-bound (safe) theorem of limit analysis a line
of thrust inside the section and in compression exists whenever the arch stands; of those, the
one reported is the line that needs the least friction coefficient, found by bisection on the
coefficient with a linear feasibility program. The statics of every joint are those of
:func:`archquake.limit.thrust.joint_forces`, the package's one statics routine.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linprog

from archquake.errors import SolverError
from archquake.geometry.arch import Arch
from archquake.limit.thrust import JointForces, arch_joint_points, joint_forces


def locked_joint_forces(arch: Arch, loads: np.ndarray, moments: np.ndarray, *,
                        tol: float = 1e-6) -> JointForces:
    """The admissible line of thrust of the undisplaced arch that needs the least friction.

    Unknowns: the left reaction (H, V) and its moment M0 about O. Every joint's N, V and M are
    affine in them; the program asks |M_j| <= h_j N_j (inside the section) and
    |V_j| <= mu N_j, and the least feasible mu is found by bisection.

    Parameters
    ----------
    arch : Arch
    loads : ndarray, (n, 2)
        Force on each voussoir, N.
    moments : ndarray, (n,)
        Their moments about O, N m.
    tol : float
        Absolute tolerance on the friction coefficient.

    Returns
    -------
    JointForces

    Raises
    ------
    SolverError
        No admissible line of thrust exists (the arch could not stand under these loads).

    Examples
    --------
    Oppenheim's arch under its own weight: the least-friction line lies inside the section
    (lower-bound theorem) and, like the arch, is symmetric.

    >>> import math
    >>> import numpy as np
    >>> from archquake import Arch
    >>> from archquake.limit import moments_about_origin
    >>> arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    >>> w = np.column_stack([np.zeros(7), -9.81 * arch.voussoir_masses])
    >>> jf = locked_joint_forces(arch, w, moments_about_origin(w, arch.voussoir_centroids))
    >>> jf.admissible(rtol=1e-7), bool(abs(jf.friction_ratio[0] - jf.friction_ratio[-1]) < 1e-5)
    (True, True)
    """
    pts = arch_joint_points(arch)
    w = float(np.abs(loads).sum())
    scale_m = w * arch.radius
    base = joint_forces(pts, loads, moments, np.zeros(2), 0.0)
    units = [joint_forces(pts, np.zeros_like(loads), np.zeros_like(moments), r, rm)
             for r, rm in ((np.array([w, 0.0]), 0.0), (np.array([0.0, w]), 0.0), (np.zeros(2), scale_m))]
    half = base.half_widths

    def affine(attr):
        return getattr(base, attr), np.array([getattr(u, attr) for u in units]).T  # (n+1,), (n+1, 3)

    (n0, n1), (v0, v1), (m0, m1) = affine("normal"), affine("shear"), affine("moment")

    def solve(mu: float):
        # rows: M - hN <= 0, -M - hN <= 0, V - mu N <= 0, -V - mu N <= 0
        a = np.vstack([m1 - half[:, None] * n1, -m1 - half[:, None] * n1,
                       v1 - mu * n1, -v1 - mu * n1])
        b = -np.concatenate([m0 - half * n0, -m0 - half * n0, v0 - mu * n0, -v0 - mu * n0])
        scale = np.concatenate([np.full(2 * len(half), scale_m), np.full(2 * len(half), w)])
        res = linprog(np.zeros(3), A_ub=a / scale[:, None], b_ub=b / scale,
                      bounds=[(None, None)] * 3, method="highs")
        return res.x if res.status == 0 else None

    lo, hi = 0.0, 1.0
    x = solve(hi)
    while x is None:
        lo, hi = hi, 2.0 * hi
        if hi > 1e3:
            raise SolverError("no admissible line of thrust fits in the locked arch under these loads")
        x = solve(hi)
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        xm = solve(mid)
        if xm is None:
            lo = mid
        else:
            hi, x = mid, xm
    return joint_forces(pts, loads, moments, np.array([x[0] * w, x[1] * w]), x[2] * scale_m)


__all__ = ["locked_joint_forces"]
