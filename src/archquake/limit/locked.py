"""The line of thrust of the locked arch: the admissible one that needs the least friction.

While the arch does not hinge (before the onset, and after it comes to rest) it moves rigidly
with the ground, and its internal forces are statically indeterminate: three redundants, the
left reaction (H, V) and its moment. By the lower-bound (safe) theorem of limit analysis a line
of thrust inside the section and in compression exists whenever the arch stands; of those, the
one reported is the line that needs the least friction coefficient: a generalized fractional
program (minimise the largest |V|/N over the joints), solved exactly by Dinkelbach's method,
a few linear programs in all. The statics of every joint are those of
`archquake.limit.thrust.joint_forces`, the package's one statics routine.
"""

from __future__ import annotations

import math

import numpy as np

from archquake.errors import SolverError
from archquake.geometry.chain import VoussoirChain
from archquake.limit.thrust import JointForces, arch_joint_points, joint_forces


def locked_joint_forces(arch: VoussoirChain, loads: np.ndarray, moments: np.ndarray, *,
                        tol: float = 1e-6, start: JointForces | None = None) -> JointForces:
    """The admissible line of thrust of the undisplaced arch that needs the least friction.

    Unknowns: the left reaction (H, V) and its moment M0 about O. Every joint's N, V and M are
    affine in them. Over the lines inside the section (|M_j| <= h_j N_j) the program minimises
    mu = max_j |V_j| / N_j. Dinkelbach's method for a max of ratios (Crouzeix, Ferland and
    Schaible, J. Optim. Theory Appl. 47, 1985): given mu_k and the line x_k, the linear program
    min t s.t. |V_j| - mu_k N_j <= t N_j(x_k) gives x_{k+1}, whose mu_{k+1} is lower, until it
    drops by less than ``tol`` (typically three to five programs; a bisection on mu with a
    feasibility program each, which this replaces, needed twenty-one for the same tolerance).
    The reaction is bounded by 1000 times the total load, which keeps every program bounded.

    Parameters
    ----------
    arch : Arch
    loads : ndarray, (n, 2)
        Force on each voussoir, N.
    moments : ndarray, (n,)
        Their moments about O, N m.
    tol : float
        Stop when an iteration lowers the friction coefficient by less than this.
    start : JointForces, optional
        A line of thrust to start from, e.g. this function's answer for nearby loads (a time
        history's previous instant): its support reaction under ``loads`` gives the first
        iteration's mu and weights (it need not lie inside the section). It saves a linear
        program or two; the answer agrees within ``tol``.

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
    k = half.size

    def affine(attr):
        return getattr(base, attr), np.array([getattr(u, attr) for u in units]).T  # (n+1,), (n+1, 3)

    (n0, n1), (v0, v1), (m0, m1) = affine("normal"), affine("shear"), affine("moment")
    # inside the section: M - hN <= 0, -M - hN <= 0 (rows scaled by W R); unknowns (x, t)
    a_in = np.vstack([m1 - half[:, None] * n1, -m1 - half[:, None] * n1]) / scale_m
    b_in = -np.concatenate([m0 - half * n0, -m0 - half * n0]) / scale_m
    a_in = np.hstack([a_in, np.zeros((2 * k, 1))])

    def ratio(x: np.ndarray) -> float:
        n = n0 + n1 @ x
        if np.any(n <= 0.0):
            return math.inf
        return float(np.max(np.abs(v0 + v1 @ x) / n))

    def step(mu: float, d: np.ndarray) -> np.ndarray:
        """min t s.t. +-V - mu N <= t d (rows scaled by W), inside the section."""
        a_fr = np.vstack([v1 - mu * n1, -v1 - mu * n1]) / w
        b_fr = -np.concatenate([v0 - mu * n0, -v0 - mu * n0]) / w
        a_fr = np.hstack([a_fr, -np.concatenate([d, d])[:, None] / w])
        from scipy.optimize import linprog  # (lazy: scipy is slow to import)

        res = linprog(np.array([0.0, 0.0, 0.0, 1.0]), A_ub=np.vstack([a_in, a_fr]),
                      b_ub=np.concatenate([b_in, b_fr]), bounds=[(-1e3, 1e3)] * 3 + [(None, None)],
                      method="highs")
        if res.status != 0:
            raise SolverError("no admissible line of thrust fits in the locked arch under these loads")
        return res.x[:3]

    # Dinkelbach's method for a max of ratios (Crouzeix, Ferland & Schaible 1985): from the
    # line that needs the least |V| (mu = 0, unit weights), or from the start line, each
    # linear program lowers mu = max |V|/N, until the drop is below tol.
    if start is not None:  # the same support reaction under these loads sets mu_0 and weights
        (fx, fy), (px, py) = start.force[0], start.mid_points[0]
        x_start = np.array([fx / w, fy / w, (start.moment[0] + px * fy - py * fx) / scale_m])
        mu_start = ratio(x_start)
    if start is not None and math.isfinite(mu_start):
        x = step(mu_start, n0 + n1 @ x_start)
    else:
        x = step(0.0, np.full(k, w))
    mu = ratio(x)
    for _ in range(100):
        n = n0 + n1 @ x
        x_new = step(mu, np.maximum(n, 1e-12 * w))
        mu_new = ratio(x_new)
        if not mu_new < mu:
            break
        done = mu - mu_new <= tol
        x, mu = x_new, mu_new
        if done:
            break
    if not math.isfinite(mu):
        raise SolverError("no line of thrust in compression fits in the locked arch under these loads")
    return joint_forces(pts, loads, moments, np.array([x[0] * w, x[1] * w]), x[2] * scale_m)


__all__ = ["locked_joint_forces"]
