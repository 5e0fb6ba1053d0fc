"""The displaced arch: where every voussoir is for a given mechanism rotation."""

from __future__ import annotations

import math

import numpy as np

from archquake.errors import SolverError
from archquake.mechanism.kinematics import link_states
from archquake.mechanism.prepared import PreparedMechanism


def voussoir_positions(prepared: PreparedMechanism, phi: float, side: int = 1) -> np.ndarray:
    """Rigid displacement of every voussoir when the mechanism has turned by ``phi``.

    Parameters
    ----------
    prepared : PreparedMechanism
        The first mechanism (side +1).
    phi : float
        Rotation of the open mechanism, rad (>= 0).
    side : {+1, -1, 0}
        +1 the first mechanism, -1 its mirror image, 0 locked (no displacement).

    Returns
    -------
    ndarray, shape (n, 3)
        Centroid displacement dx, dy (m) and rotation (rad, counter-clockwise) of each voussoir,
        the format :func:`archquake.plotting.arch.plot_arch` draws.

    Examples
    --------
    >>> import math
    >>> from archquake import Arch
    >>> prep = PreparedMechanism.build(Arch(10.0, 1.5, math.radians(157.5), 7))
    >>> voussoir_positions(prep, 0.0).any()
    np.False_
    """
    mech = prepared.mechanism
    arch = mech.arch
    n = arch.voussoirs
    out = np.zeros((n, 3))
    if side == 0 or phi == 0.0:
        return out
    st = link_states(prepared.packed, float(phi))
    if not st[0]:
        raise SolverError(f"the mechanism cannot be assembled at phi = {phi:.6g} rad (beyond its toggle)")
    a0, b0, _c0, d0 = mech.points
    b = np.array([st[10], st[11]])
    pivots = ((a0, a0, st[1]), (b, b0, st[4]), (d0, d0, st[7]))
    cen0 = arch.voussoir_centroids
    for rng, (p, p0, psi) in zip(mech.link_voussoirs, pivots):
        c, s = math.cos(psi), math.sin(psi)
        for k in rng:
            r = cen0[k] - p0
            out[k, 0:2] = p + np.array([c * r[0] - s * r[1], s * r[0] + c * r[1]]) - cen0[k]
            out[k, 2] = psi
    if side < 0:
        out = out[::-1] * np.array([-1.0, 1.0, -1.0])
    return out


def hinge_points(prepared: PreparedMechanism, phi: float, side: int = 1) -> np.ndarray:
    """The four hinge points A, B, C, D of the open mechanism in the displaced arch, m, (4, 2)."""
    mech = prepared.mechanism
    st = link_states(prepared.packed, float(phi))
    a0, _b0, _c0, d0 = mech.points
    pts = np.array([a0, [st[10], st[11]], [st[12], st[13]], d0])
    if side < 0:
        pts = pts[::-1] * np.array([-1.0, 1.0])
    return pts


__all__ = ["hinge_points", "voussoir_positions"]
