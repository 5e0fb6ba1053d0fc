"""Compiled Moreau-Jean stepper of :mod:`archquake.mechanism.rigid_chain` (numba).

One step, h, from (q_k, v_k) (per free body: x, y, theta and their rates, relative to the
ground; base bodies fixed in the ground's frame):

1. q_m = q_k + h/2 v_k (mid-step configuration);
2. at q_m, every joint's two corner gaps g_c = (P_b - P_a) . n, n the joint normal carried by
   the mean rotation of its two bodies (so the gap is mirror-symmetric); a corner is active when
   g_c <= ``gap_tol``; a joint with an active corner carries its no-slip row (tangential
   relative velocity zero, at the active corner, or at the mid-point of both);
3. v_free = v_k + h M^-1 f(t_m), f = (-m x_g'', -m g, 0);
4. v_{k+1} = argmin 1/2 ||v - v_free||_M over {H_N v >= 0, H_T v = 0}: projected Gauss-Seidel on
   the contact impulses p (p_N >= 0, p_T free), v = v_free + M^-1 H^T p, over-relaxed
   (:data:`RELAX`), warm-started from the previous step's impulses (perfectly plastic: e = 0).
   With a finite friction coefficient mu, each joint's tangential impulse is clamped to
   |p_T| <= mu (p_N0 + p_N1), the current normal impulses of its corners: a fixed point of the
   sweep then satisfies Coulomb's law in 2D (stick with |p_T| < mu p_N, or slip opposite to p_T
   at the bound). That is no longer a projection (Coulomb's law has no potential), so neither
   uniqueness nor convergence is guaranteed; the sweep count and residual are reported;
5. q_{k+1} = q_m + h/2 v_{k+1}.

SI units throughout: masses kg, inertias kg m^2, impulses N s.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

#: Columns of the per-sample diagnostics.
D_DISSIPATED = 0  # J, cumulated energy removed by the contact projections
D_INPUT = 1  # J, cumulated work of the inertial load -m x_g'' on the relative motion
D_PENETRATION = 2  # m, largest penetration (negative gap) since the last sample
D_FRICTION = 3  # -, largest |p_T| / p_N of a joint (p_N > 1e-12 h g max m) since the last sample
D_ITERATIONS = 4  # -, most Gauss-Seidel sweeps of a step since the last sample
D_RESIDUAL = 5  # m/s, largest velocity correction of a step's last sweep since the last sample
N_DIAG = 6

#: Over-relaxation of the Gauss-Seidel sweep (projected SOR; converges for 0 < RELAX < 2 on the
#: positive semi-definite Delassus matrix). 1.3 halves the sweeps on Oppenheim's arch (280 -> 145
#: at worst, 1.9 -> 1.1 s per 4 s history) and changes the energy kept over its half cycle by
#: 2e-5.
RELAX = 1.3


@nb.njit(cache=True)
def _point(q, body, arm):
    """World (ground-frame) position of a point of ``body`` at local ``arm`` (base: arm itself)."""
    if body < 0:
        return arm[0], arm[1]
    c = math.cos(q[body, 2])
    s = math.sin(q[body, 2])
    return q[body, 0] + c * arm[0] - s * arm[1], q[body, 1] + s * arm[0] + c * arm[1]


@nb.njit(cache=True)
def geometry(q, ja, jb, arm_a, arm_b, n0, t0):
    """Corner gaps (nj, 2), m; the joint normals and tangents (nj, 2); the corner positions on
    each side (nj, 2, 2, 2): [joint, corner, side a/b, xy]."""
    nj = ja.shape[0]
    gaps = np.zeros((nj, 2))
    nrm = np.zeros((nj, 2))
    tan = np.zeros((nj, 2))
    pts = np.zeros((nj, 2, 2, 2))
    for j in range(nj):
        tha = 0.0 if ja[j] < 0 else q[ja[j], 2]
        thb = 0.0 if jb[j] < 0 else q[jb[j], 2]
        th = 0.5 * (tha + thb)
        c = math.cos(th)
        s = math.sin(th)
        nrm[j, 0] = c * n0[j, 0] - s * n0[j, 1]
        nrm[j, 1] = s * n0[j, 0] + c * n0[j, 1]
        tan[j, 0] = c * t0[j, 0] - s * t0[j, 1]
        tan[j, 1] = s * t0[j, 0] + c * t0[j, 1]
        for k in range(2):
            ax, ay = _point(q, ja[j], arm_a[j, k])
            bx, by = _point(q, jb[j], arm_b[j, k])
            pts[j, k, 0, 0] = ax
            pts[j, k, 0, 1] = ay
            pts[j, k, 1, 0] = bx
            pts[j, k, 1, 1] = by
            gaps[j, k] = (bx - ax) * nrm[j, 0] + (by - ay) * nrm[j, 1]
    return gaps, nrm, tan, pts


@nb.njit(cache=True)
def _row(q, body, px, py, dx, dy, sign, out):
    """Jacobian entries (3,) of ``sign`` times the velocity of the body point (px, py) along d."""
    if body < 0:
        out[0] = 0.0
        out[1] = 0.0
        out[2] = 0.0
        return
    rx = px - q[body, 0]
    ry = py - q[body, 1]
    out[0] = sign * dx
    out[1] = sign * dy
    out[2] = sign * (rx * dy - ry * dx)


@nb.njit(cache=True)
def project(q, v_free, inv_m, inv_i, ja, jb, gaps, nrm, tan, pts, gap_tol, p_warm, tol, max_iter,
            mu):
    """The contact step: v = argmin ||v - v_free||_M over the admissible cone of the active
    contacts (module docstring, step 4).

    ``mu``: friction coefficient; ``mu <= 0`` means no slip (the tangential impulse is free).

    Returns (v (nb, 3), impulses (nj, 3): normal at corner 0, normal at corner 1, tangential,
    N s; sweeps taken; final residual m/s)."""
    nj = ja.shape[0]
    nrows = 0
    rows_j = np.zeros(3 * nj, np.int64)
    rows_k = np.zeros(3 * nj, np.int64)
    ja_rows = np.zeros((3 * nj, 3))
    jb_rows = np.zeros((3 * nj, 3))
    tmp = np.zeros(3)
    for j in range(nj):
        act0 = gaps[j, 0] <= gap_tol
        act1 = gaps[j, 1] <= gap_tol
        for k in range(2):
            if (k == 0 and act0) or (k == 1 and act1):
                rows_j[nrows] = j
                rows_k[nrows] = k
                _row(q, ja[j], pts[j, k, 0, 0], pts[j, k, 0, 1], nrm[j, 0], nrm[j, 1], -1.0, tmp)
                ja_rows[nrows] = tmp
                _row(q, jb[j], pts[j, k, 1, 0], pts[j, k, 1, 1], nrm[j, 0], nrm[j, 1], 1.0, tmp)
                jb_rows[nrows] = tmp
                nrows += 1
        if act0 or act1:
            # no slip at the active corner, or at the mid-point when both are active
            wa = 0.5 if (act0 and act1) else (1.0 if act0 else 0.0)
            ax = wa * pts[j, 0, 0, 0] + (1.0 - wa) * pts[j, 1, 0, 0]
            ay = wa * pts[j, 0, 0, 1] + (1.0 - wa) * pts[j, 1, 0, 1]
            bx = wa * pts[j, 0, 1, 0] + (1.0 - wa) * pts[j, 1, 1, 0]
            by = wa * pts[j, 0, 1, 1] + (1.0 - wa) * pts[j, 1, 1, 1]
            rows_j[nrows] = j
            rows_k[nrows] = 2
            _row(q, ja[j], ax, ay, tan[j, 0], tan[j, 1], -1.0, tmp)
            ja_rows[nrows] = tmp
            _row(q, jb[j], bx, by, tan[j, 0], tan[j, 1], 1.0, tmp)
            jb_rows[nrows] = tmp
            nrows += 1
    v = v_free.copy()
    p = np.zeros(nrows)
    diag = np.zeros(nrows)
    pn_joint = np.zeros(nj)
    for r in range(nrows):
        j = rows_j[r]
        a = ja[j]
        b = jb[j]
        d = 0.0
        if a >= 0:
            d += (ja_rows[r, 0] ** 2 + ja_rows[r, 1] ** 2) * inv_m[a] + ja_rows[r, 2] ** 2 * inv_i[a]
        if b >= 0:
            d += (jb_rows[r, 0] ** 2 + jb_rows[r, 1] ** 2) * inv_m[b] + jb_rows[r, 2] ** 2 * inv_i[b]
        diag[r] = d
        p[r] = p_warm[j, rows_k[r]]
        if rows_k[r] < 2 and p[r] < 0.0:
            p[r] = 0.0
        if rows_k[r] < 2:
            pn_joint[j] += p[r]
        elif mu > 0.0:
            p[r] = min(max(p[r], -mu * pn_joint[j]), mu * pn_joint[j])
        if p[r] != 0.0:
            _apply(v, a, b, ja_rows[r], jb_rows[r], p[r], inv_m, inv_i)
    sweeps = 0
    change = 0.0
    for it in range(max_iter):
        sweeps = it + 1
        change = 0.0
        for r in range(nrows):
            j = rows_j[r]
            a = ja[j]
            b = jb[j]
            w = 0.0
            if a >= 0:
                w += ja_rows[r, 0] * v[a, 0] + ja_rows[r, 1] * v[a, 1] + ja_rows[r, 2] * v[a, 2]
            if b >= 0:
                w += jb_rows[r, 0] * v[b, 0] + jb_rows[r, 1] * v[b, 1] + jb_rows[r, 2] * v[b, 2]
            new = p[r] - RELAX * w / diag[r]
            if rows_k[r] < 2:
                if new < 0.0:
                    new = 0.0
                pn_joint[j] += new - p[r]
            elif mu > 0.0:
                bound = mu * pn_joint[j]
                new = min(max(new, -bound), bound)
            dp = new - p[r]
            if dp != 0.0:
                _apply(v, a, b, ja_rows[r], jb_rows[r], dp, inv_m, inv_i)
                p[r] = new
                dv = abs(dp) * diag[r]
                if dv > change:
                    change = dv
        if change <= tol:
            break
    imp = np.zeros((nj, 3))
    for r in range(nrows):
        imp[rows_j[r], rows_k[r]] = p[r]
    return v, imp, sweeps, change


@nb.njit(cache=True)
def _apply(v, a, b, ra, rb, dp, inv_m, inv_i):
    if a >= 0:
        v[a, 0] += ra[0] * dp * inv_m[a]
        v[a, 1] += ra[1] * dp * inv_m[a]
        v[a, 2] += ra[2] * dp * inv_i[a]
    if b >= 0:
        v[b, 0] += rb[0] * dp * inv_m[b]
        v[b, 1] += rb[1] * dp * inv_m[b]
        v[b, 2] += rb[2] * dp * inv_i[b]


@nb.njit(cache=True)
def run(q, v, p_warm, mass, inertia, ja, jb, arm_a, arm_b, n0, t0, acc, h, g, gap_tol, tol,
        max_iter, mu, out_every, out_q, out_v, out_diag, diag):
    """Advance ``acc.shape[0]`` steps (``acc[k]``: the mean ground acceleration over step k,
    m/s^2), writing q, v, diagnostics after every ``out_every`` steps into row ``k // out_every``
    of ``out_*``. ``q``, ``v``, ``p_warm``, ``diag`` (running D_* values) are updated in place.
    Returns the number of sweeps of the worst step."""
    nb_ = mass.shape[0]
    inv_m = 1.0 / mass
    inv_i = 1.0 / inertia
    worst = 0
    for k in range(acc.shape[0]):
        qm = q + 0.5 * h * v
        gaps, nrm, tan, pts = geometry(qm, ja, jb, arm_a, arm_b, n0, t0)
        vf = v.copy()
        for i in range(nb_):
            vf[i, 0] -= h * acc[k]
            vf[i, 1] -= h * g
        vn, imp, sweeps, res = project(qm, vf, inv_m, inv_i, ja, jb, gaps, nrm, tan, pts,
                                       gap_tol, p_warm, tol, max_iter, mu)
        t_free = 0.0
        t_new = 0.0
        w_in = 0.0
        for i in range(nb_):
            t_free += mass[i] * (vf[i, 0] ** 2 + vf[i, 1] ** 2) + inertia[i] * vf[i, 2] ** 2
            t_new += mass[i] * (vn[i, 0] ** 2 + vn[i, 1] ** 2) + inertia[i] * vn[i, 2] ** 2
            w_in -= acc[k] * mass[i] * 0.5 * h * (v[i, 0] + vn[i, 0])
        diag[D_DISSIPATED] += 0.5 * (t_free - t_new)
        diag[D_INPUT] += w_in
        for j in range(ja.shape[0]):
            for c in range(2):
                if -gaps[j, c] > diag[D_PENETRATION]:
                    diag[D_PENETRATION] = -gaps[j, c]
            pn = imp[j, 0] + imp[j, 1]
            if pn > 0.0 and pn > 1e-12 * h * g * (mass.max()):
                fr = abs(imp[j, 2]) / pn
                if fr > diag[D_FRICTION]:
                    diag[D_FRICTION] = fr
            p_warm[j, 0] = imp[j, 0]
            p_warm[j, 1] = imp[j, 1]
            p_warm[j, 2] = imp[j, 2]
        if sweeps > diag[D_ITERATIONS]:
            diag[D_ITERATIONS] = sweeps
        if res > diag[D_RESIDUAL]:
            diag[D_RESIDUAL] = res
        if sweeps > worst:
            worst = sweeps
        v[:, :] = vn
        q[:, :] = qm + 0.5 * h * vn
        if (k + 1) % out_every == 0:
            row = (k + 1) // out_every - 1
            out_q[row] = q
            out_v[row] = v
            out_diag[row] = diag
            diag[D_PENETRATION] = 0.0
            diag[D_FRICTION] = 0.0
            diag[D_ITERATIONS] = 0.0
            diag[D_RESIDUAL] = 0.0
    return worst
