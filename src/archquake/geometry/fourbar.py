"""Instantaneous kinematics of a planar four-bar linkage A-B-C-D with A and D on the ground.

Pure geometry: given the four pivot positions, the angular velocities of the links AB, BC and
CD per unit angular velocity of AB (the velocity ratios f_BC, f_CD of the paper's Eq. 1 at one
configuration). The full position/velocity/acceleration analysis along the motion is in
`archquake.mechanism.kinematics`; this is its plain, non-compiled twin at one instant and
is what the virtual-work (kinematic) limit analysis uses.
"""

from __future__ import annotations

import numpy as np

from archquake.geometry.planar import perp


def link_rates(points: np.ndarray) -> np.ndarray:
    """Angular velocities (omega_AB, omega_BC, omega_CD) for omega_AB = 1, rad/rad.

    Parameters
    ----------
    points : ndarray, shape (4, 2)
        Pivots A, B, C, D in m; A and D are fixed.

    Returns
    -------
    ndarray, shape (3,)
        Counter-clockwise positive rates. ``nan`` where the linkage is at a toggle
        (B, C and D collinear), where the rates are undefined.

    Examples
    --------
    A parallelogram moves by pure translation of BC:

    >>> import numpy as np
    >>> link_rates(np.array([[0.0, 0.0], [0.0, 1.0], [2.0, 1.0], [2.0, 0.0]])).round(12) + 0.0
    array([1., 0., 1.])
    """
    a, b, c, d = (np.asarray(p, dtype=float) for p in points)
    # v_B = J (B - A) for omega_AB = 1; v_C = v_B + w_bc J (C - B) = w_cd J (C - D).
    # In components with J(x, y) = (-y, x):  w_bc * J(C-B) - w_cd * J(C-D) = -J(B-A).
    jcb = perp(c - b)
    jcd = perp(c - d)
    jba = perp(b - a)
    mat = np.column_stack([jcb, -jcd])
    det = np.linalg.det(mat)
    scale = float(np.linalg.norm(c - b) * np.linalg.norm(c - d))
    if abs(det) <= 1e-12 * max(scale, 1e-300):
        return np.array([1.0, np.nan, np.nan])
    w_bc, w_cd = np.linalg.solve(mat, -jba)
    return np.array([1.0, w_bc, w_cd])


def point_velocity(rate: float, pivot: np.ndarray, point: np.ndarray) -> np.ndarray:
    """Velocity of ``point`` on a body turning at ``rate`` about the fixed ``pivot`` (m/s per rad/s)."""
    return rate * perp(np.asarray(point, dtype=float) - np.asarray(pivot, dtype=float))


__all__ = ["link_rates", "point_velocity"]
