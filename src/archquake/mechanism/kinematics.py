"""Position, velocity and acceleration analysis of the arch's four-link mechanism (paper Eq. 1).

The mechanism is packed once into a float64 array (the layout below, filled by
`archquake.mechanism.prepared.pack_mechanism`) and every function here is plain scalar
Python decorated with `numba.extending.register_jitable`: called from Python it runs as
ordinary Python (the readable reference, used by the ``solve_ivp`` driver), called from compiled
code it is compiled inline (the fast kernels). One source, two uses. This module imports no other
module of the package's mechanism layer (the compiled kernels import it, never the reverse).

Generalised coordinate: ``phi`` = rotation of link AB about A in its opening sense
(the paper's theta0 - theta); ``phi > 0`` while the mechanism is open. Primes are d/dphi.

Links: AB turns about the fixed hinge A, BC is the coupler, CD turns about the fixed hinge D.
For link k with centroid r_k and rotation psi_k (counter-clockwise, from the undisplaced state)
the Lagrangian reduces to (paper Eq. 2, written in phi):

    m_eff(phi) phi'' + 1/2 m_eff'(phi) phi'^2 + g G(phi) + x_g'' H(phi) = 0,
    m_eff = sum m_k |r_k'|^2 + I_k psi_k'^2,   G = sum m_k y_k',   H = sum m_k x_k'.
"""

from __future__ import annotations

import math

from numba.extending import register_jitable

# packed layout ---------------------------------------------------------------------------
AX, AY, B0X, B0Y, C0X, C0Y, DX, DY = 0, 1, 2, 3, 4, 5, 6, 7
SIGMA, BRANCH, LBC, LCD = 8, 9, 10, 11
LINK0 = 12  # per link: mass, rho0_x, rho0_y, inertia (rho0 = centroid - pivot, undisplaced)
PHI_CRIT, PHI_TOGGLE, MASS, LENGTH, G0, H0 = 24, 25, 26, 27, 28, 29
PACKED_SIZE = 30


@register_jitable
def fourbar(mech, phi):
    """Pivot motion of the four-bar at rotation ``phi``.

    Returns
    -------
    tuple
        ``(ok, bx, by, bpx, bpy, bppx, bppy, cx, cy, cpx, cpy, cppx, cppy)``: B and C with their
        first and second derivatives with respect to phi (m, m/rad, m/rad^2); ``ok`` is False
        beyond the toggle (B, C, D collinear), where the linkage cannot be assembled.
    """
    ax, ay = mech[AX], mech[AY]
    dx, dy = mech[DX], mech[DY]
    sigma = mech[SIGMA]
    ang = sigma * phi
    ca, sa = math.cos(ang), math.sin(ang)
    rx0, ry0 = mech[B0X] - ax, mech[B0Y] - ay
    rx, ry = ca * rx0 - sa * ry0, sa * rx0 + ca * ry0
    bx, by = ax + rx, ay + ry
    bpx, bpy = -sigma * ry, sigma * rx  # sigma J (B - A)
    bppx, bppy = -rx, -ry  # (sigma J)^2 (B - A)
    # C: intersection of the circles |C - B| = l_BC and |C - D| = l_CD on the initial branch
    lbc, lcd = mech[LBC], mech[LCD]
    ex, ey = dx - bx, dy - by
    e2 = ex * ex + ey * ey
    e = math.sqrt(e2)
    along = (lbc * lbc - lcd * lcd + e2) / (2.0 * e)
    h2 = lbc * lbc - along * along
    if h2 <= 0.0:
        return (False, bx, by, bpx, bpy, bppx, bppy, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    h = mech[BRANCH] * math.sqrt(h2)
    cx = bx + (along * ex - h * ey) / e
    cy = by + (along * ey + h * ex) / e
    # velocity: u.(C' - B') = 0, w.C' = 0 with u = C - B, w = C - D
    ux, uy = cx - bx, cy - by
    wx, wy = cx - dx, cy - dy
    det = ux * wy - uy * wx
    r1 = ux * bpx + uy * bpy
    cpx = r1 * wy / det
    cpy = -r1 * wx / det
    # acceleration: u.(C'' - B'') = -|C' - B'|^2, w.C'' = -|C'|^2
    vx, vy = cpx - bpx, cpy - bpy
    s1 = ux * bppx + uy * bppy - (vx * vx + vy * vy)
    s2 = -(cpx * cpx + cpy * cpy)
    cppx = (s1 * wy - s2 * uy) / det
    cppy = (ux * s2 - wx * s1) / det
    return (True, bx, by, bpx, bpy, bppx, bppy, cx, cy, cpx, cpy, cppx, cppy)


@register_jitable
def _link_terms(mass, rho0x, rho0y, inertia, px, py, ppx, ppy, pppx, pppy,
                cos_psi, sin_psi, w, alpha):
    """Centroid position, velocity and acceleration (d/dphi) of a link and its energy terms."""
    rx = cos_psi * rho0x - sin_psi * rho0y
    ry = sin_psi * rho0x + cos_psi * rho0y
    x, y = px + rx, py + ry
    vx, vy = ppx - w * ry, ppy + w * rx
    acx = pppx - alpha * ry - w * w * rx
    acy = pppy + alpha * rx - w * w * ry
    meff = mass * (vx * vx + vy * vy) + inertia * w * w
    dmeff = 2.0 * (mass * (vx * acx + vy * acy) + inertia * w * alpha)
    return x, y, vx, vy, meff, dmeff


@register_jitable
def link_states(mech, phi):
    """Rotation and its phi-derivatives for the three links, and the pivots B, C.

    Returns ``(ok, psi_ab, w_ab, a_ab, psi_bc, w_bc, a_bc, psi_cd, w_cd, a_cd, bx, by, cx, cy)``:
    rotations (rad, counter-clockwise from the undisplaced state), d psi/d phi and
    d^2 psi/d phi^2 (the paper's velocity ratios f_BC, f_CD are w_bc/w_ab and w_cd/w_ab).
    """
    (ok, bx, by, bpx, bpy, bppx, bppy, cx, cy, cpx, cpy, cppx, cppy) = fourbar(mech, phi)
    sigma = mech[SIGMA]
    if not ok:
        return (False, sigma * phi, sigma, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, bx, by, cx, cy)
    ux, uy = cx - bx, cy - by
    u0x, u0y = mech[C0X] - mech[B0X], mech[C0Y] - mech[B0Y]
    wx, wy = cx - mech[DX], cy - mech[DY]
    w0x, w0y = mech[C0X] - mech[DX], mech[C0Y] - mech[DY]
    lbc2 = mech[LBC] * mech[LBC]
    lcd2 = mech[LCD] * mech[LCD]
    psi_bc = math.atan2(u0x * uy - u0y * ux, u0x * ux + u0y * uy)
    psi_cd = math.atan2(w0x * wy - w0y * wx, w0x * wx + w0y * wy)
    w_bc = (ux * (cpy - bpy) - uy * (cpx - bpx)) / lbc2
    w_cd = (wx * cpy - wy * cpx) / lcd2
    a_bc = (ux * (cppy - bppy) - uy * (cppx - bppx)) / lbc2
    a_cd = (wx * cppy - wy * cppx) / lcd2
    return (True, sigma * phi, sigma, 0.0, psi_bc, w_bc, a_bc, psi_cd, w_cd, a_cd, bx, by, cx, cy)


@register_jitable
def eom_terms(mech, phi):
    """Coefficients of the equation of motion at ``phi``.

    Returns
    -------
    tuple
        ``(ok, m_eff, dm_eff, G, H)``: generalised mass m_eff (kg m^2), its derivative
        d m_eff/d phi (kg m^2/rad), gravity term G = sum m_k dy_k/dphi and ground term
        H = sum m_k dx_k/dphi (kg m), so that
        ``m_eff phi'' = -1/2 dm_eff phi'^2 - g G - x_g'' H``.
    """
    (ok, bx, by, bpx, bpy, bppx, bppy, cx, cy, cpx, cpy, cppx, cppy) = fourbar(mech, phi)
    if not ok:
        return (False, 0.0, 0.0, 0.0, 0.0)
    (ok2, psi_ab, w_ab, a_ab, psi_bc, w_bc, a_bc, psi_cd, w_cd, a_cd,
     _bx, _by, _cx, _cy) = link_states(mech, phi)
    meff = 0.0
    dmeff = 0.0
    gg = 0.0
    hh = 0.0
    for k in range(3):
        base = LINK0 + 4 * k
        mass = mech[base]
        if mass == 0.0:
            continue
        if k == 0:
            px, py, ppx, ppy, pppx, pppy = mech[AX], mech[AY], 0.0, 0.0, 0.0, 0.0
            psi, w, alpha = psi_ab, w_ab, a_ab
        elif k == 1:
            px, py, ppx, ppy, pppx, pppy = bx, by, bpx, bpy, bppx, bppy
            psi, w, alpha = psi_bc, w_bc, a_bc
        else:
            px, py, ppx, ppy, pppx, pppy = mech[DX], mech[DY], 0.0, 0.0, 0.0, 0.0
            psi, w, alpha = psi_cd, w_cd, a_cd
        x, y, vx, vy, m_k, dm_k = _link_terms(
            mass, mech[base + 1], mech[base + 2], mech[base + 3],
            px, py, ppx, ppy, pppx, pppy, math.cos(psi), math.sin(psi), w, alpha)
        meff += m_k
        dmeff += dm_k
        gg += mass * vy
        hh += mass * vx
    return (True, meff, dmeff, gg, hh)


@register_jitable
def potential(mech, phi):
    """Gravity potential of the moving links relative to phi = 0, divided by g:
    sum m_k (y_k - y_k0), kg m."""
    (ok, psi_ab, w_ab, a_ab, psi_bc, w_bc, a_bc, psi_cd, w_cd, a_cd,
     bx, by, cx, cy) = link_states(mech, phi)
    total = 0.0
    for k in range(3):
        base = LINK0 + 4 * k
        mass = mech[base]
        rho0x, rho0y = mech[base + 1], mech[base + 2]
        if k == 0:
            py, p0y, psi = mech[AY], mech[AY], psi_ab
        elif k == 1:
            py, p0y, psi = by, mech[B0Y], psi_bc
        else:
            py, p0y, psi = mech[DY], mech[DY], psi_cd
        y = py + math.sin(psi) * rho0x + math.cos(psi) * rho0y
        total += mass * (y - (p0y + rho0y))
    return total


@register_jitable
def acceleration(mech, phi, phidot, ground, g):
    """phi'' (rad/s^2) from the equation of motion; ``ground`` is x_g'' in m/s^2."""
    ok, meff, dmeff, gg, hh = eom_terms(mech, phi)
    if not ok:
        return math.nan
    return (-0.5 * dmeff * phidot * phidot - g * gg - ground * hh) / meff


@register_jitable
def _bisect_valid(mech, lo, hi):
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if fourbar(mech, mid)[0]:
            lo = mid
        else:
            hi = mid
    return lo


@register_jitable
def linkage_limits(mech, samples=4000):
    """Rotation at which gravity can no longer bring the mechanism back (the crest of the
    potential, G(phi) = 0) and the toggle rotation where the linkage locks, both rad.

    The toggle is searched over (0, pi]; if the linkage never toggles there, pi is returned.
    If G has no zero before the toggle, the crest is the toggle.
    """
    toggle = math.pi
    last_ok = 0.0
    for i in range(1, samples + 1):
        p = math.pi * i / samples
        if not fourbar(mech, p)[0]:
            toggle = _bisect_valid(mech, last_ok, p)
            break
        last_ok = p
    crit = toggle
    prev_p = 0.0
    prev_g = eom_terms(mech, 0.0)[3]
    for i in range(1, samples):
        p = toggle * i / samples
        gval = eom_terms(mech, p)[3]
        if prev_g > 0.0 >= gval:
            lo, hi = prev_p, p
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if eom_terms(mech, mid)[3] > 0.0:
                    lo = mid
                else:
                    hi = mid
            crit = 0.5 * (lo + hi)
            break
        prev_p, prev_g = p, gval
    return crit, toggle


__all__ = [
    "PACKED_SIZE",
    "acceleration",
    "eom_terms",
    "fourbar",
    "link_states",
    "linkage_limits",
    "paper_coefficients",
    "potential",
]


def paper_coefficients(mech, phi: float) -> tuple[float, float, float, float]:
    """The paper's dimensionless coefficient functions M, L, F, P of Eq. 2 at ``phi``.

    With theta = theta0 - phi (so d/dtheta = -d/dphi) and m the arch's total mass, Eq. 2
    ``M R theta'' + L R theta'^2 + F g = P x_g''`` is this module's equation of motion divided
    by -m R::

        M = m_eff / (m R^2),  L = -(d m_eff / d phi) / (2 m R^2),  F = -G / (m R),  P = H / (m R).

    They depend on the geometry's proportions only (not on R, density or depth).

    Parameters
    ----------
    mech : ndarray, shape (30,)
        Packed mechanism (`archquake.mechanism.prepared.pack_mechanism`).
    phi : float
        Rotation theta0 - theta, rad.

    Returns
    -------
    (M, L, F, P) : tuple of float
    """
    ok, meff, dmeff, gg, hh = eom_terms(mech, phi)
    if not ok:
        raise ValueError(f"the mechanism cannot be assembled at phi = {phi:g} rad (beyond its toggle)")
    m, r = mech[MASS], mech[LENGTH]
    return meff / (m * r * r), -dmeff / (2.0 * m * r * r), -gg / (m * r), hh / (m * r)
