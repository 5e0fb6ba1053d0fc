"""Compiled joint-force probes of the rigid chain (numba): `archquake.rigid.forces.
joint_forces` over every sample in one call.

At each recorded sample the stepper's next step is repeated (`archquake.rigid.
_step_kernels.project` at the mid-step configuration, warm-started from the previous sample's
impulses), exactly as the plain loop of `archquake.rigid.forces.joint_forces_reference`
does it, which a test holds this kernel to. The samples depend on each other only through that
warm start, so they are probed in order, in one compiled loop.

The rank test of `archquake.rigid.forces` (the smallest singular value of the active
rows above ``RANK_TOLERANCE`` times the largest) is settled here where a bound proves it
(`rank_certificate`); the samples it leaves open go to numpy's SVD.

SI units throughout: m, s, kg, N s.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

import archquake.rigid._step_kernels as RK
from archquake._kernel_cache import stamp_kernels

stamp_kernels()  # the cache checks each kernel against every source compiled into it

#: A sample's rows are certified independent when the bound on s_min / s_max exceeds this: far
#: above the rank test's 1e-8, so that no rounding of the bound or of an SVD can disagree.
CERTIFIED_RATIO = 1e-6


@nb.njit(cache=True)
def _entry(row, q, body, px, py, dx, dy, sign, isq_m, isq_i):
    if body < 0:
        return
    rx, ry = px - q[body, 0], py - q[body, 1]
    row[3 * body] += sign * dx * isq_m[body]
    row[3 * body + 1] += sign * dy * isq_m[body]
    row[3 * body + 2] += sign * (rx * dy - ry * dx) * isq_i[body]


@nb.njit(cache=True)
def rank_certificate(q, act, ja, jb, nrm, tan, pts, isq_m, isq_i):
    """1 where the active rows (as `archquake.rigid.forces._rows` builds them, each
    scaled to unit norm) are proven independent with s_min / s_max > `CERTIFIED_RATIO`;
    0 where they cannot be (more rows than velocities, or no row: 1); -1 where not proven.

    The bound: with G = R R^T = L L^T (Cholesky), lambda_min(G) = 1 / ||G^-1||_2 >=
    1 / ||L^-1||_F^2, and lambda_max(G) <= trace(G) = the number of rows (unit rows), so
    s_min / s_max >= (||L^-1||_F^2 nr)^-1/2. A Cholesky that meets a pivot <= 0 proves nothing."""
    nj = ja.shape[0]
    ncols = 3 * q.shape[0]
    nr = 0
    for j in range(nj):
        if act[j, 0] or act[j, 1]:
            nr += 1 + int(act[j, 0]) + int(act[j, 1])
    if nr == 0:
        return 1
    if nr > ncols:
        return 0
    rows = np.zeros((nr, ncols))
    r = 0
    for j in range(nj):
        for c in range(2):
            if act[j, c]:
                _entry(rows[r], q, ja[j], pts[j, c, 0, 0], pts[j, c, 0, 1], nrm[j, 0], nrm[j, 1],
                       -1.0, isq_m, isq_i)
                _entry(rows[r], q, jb[j], pts[j, c, 1, 0], pts[j, c, 1, 1], nrm[j, 0], nrm[j, 1],
                       1.0, isq_m, isq_i)
                r += 1
        if act[j, 0] or act[j, 1]:
            w = 0.5 if (act[j, 0] and act[j, 1]) else (1.0 if act[j, 0] else 0.0)
            _entry(rows[r], q, ja[j], w * pts[j, 0, 0, 0] + (1 - w) * pts[j, 1, 0, 0],
                   w * pts[j, 0, 0, 1] + (1 - w) * pts[j, 1, 0, 1], tan[j, 0], tan[j, 1], -1.0,
                   isq_m, isq_i)
            _entry(rows[r], q, jb[j], w * pts[j, 0, 1, 0] + (1 - w) * pts[j, 1, 1, 0],
                   w * pts[j, 0, 1, 1] + (1 - w) * pts[j, 1, 1, 1], tan[j, 0], tan[j, 1], 1.0,
                   isq_m, isq_i)
            r += 1
    for i in range(nr):
        norm = 0.0
        for k in range(ncols):
            norm += rows[i, k] * rows[i, k]
        norm = math.sqrt(norm)
        if norm == 0.0:
            return -1
        for k in range(ncols):
            rows[i, k] /= norm
    low = np.zeros((nr, nr))
    for i in range(nr):  # Cholesky of G = R R^T, row by row
        for jj in range(i + 1):
            gij = 0.0
            for k in range(ncols):
                gij += rows[i, k] * rows[jj, k]
            for k in range(jj):
                gij -= low[i, k] * low[jj, k]
            if jj == i:
                if gij <= 0.0:
                    return -1
                low[i, i] = math.sqrt(gij)
            else:
                low[i, jj] = gij / low[jj, jj]
    frob = 0.0  # ||L^-1||_F^2, column by column of L^-1 (forward substitution)
    x = np.zeros(nr)
    for col in range(nr):
        for i in range(nr):
            acc = 1.0 if i == col else 0.0
            for k in range(col, i):
                acc -= low[i, k] * x[k]
            x[i] = acc / low[i, i] if i >= col else 0.0
            frob += x[i] * x[i]
    if frob * nr * CERTIFIED_RATIO * CERTIFIED_RATIO < 1.0:
        return 1
    return -1


@nb.njit(cache=True)
def probe(chain, cfg, pos, vel, base_u, base_v, acc, lref, impulsive_factor, vacc):
    """The joint impulses of the chain's next step at each sample, and what the rank test needs.

    Parameters
    ----------
    chain : Chain
        The `RigidModel`'s packed arrays (`archquake.rigid._step_kernels.Chain`).
    cfg : Stepping
        The step ``h`` (s), gravity ``g`` (m/s^2) and the projection's settings, as
        `project` takes them (``h_corr``: the position-level correction's time, s).
    pos, vel : ndarray (nt, nb, 3)
        The free bodies' absolute configurations (m, m, rad) and velocities at the samples.
    base_u, base_v : ndarray (nt,)
        Ground displacement (m) and velocity (m/s) at the samples.
    acc : ndarray (nt,)
        The ground acceleration over each sample's step, m/s^2.
    lref : float
        The assembly's reference length, m (a rotation rate's velocity).
    impulsive_factor : float
        A sample is impulsive when a velocity jumps by more than this times h (g + |acc|).
    vacc : ndarray (nt,) or (0,)
        The upward ground acceleration over each sample's step, m/s^2 (gravity reads
        g + vacc); empty for none.

    Returns
    -------
    imp : ndarray (nt, nj, 3)
        Impulses over the step, N s: normal at corner 0, at corner 1, tangential.
    impulsive : ndarray (nt,) bool
    active : ndarray (nt, nj, 2) bool
        The corners the projection treats as in contact (its hold included).
    qm : ndarray (nt, nb, 3)
        The mid-step configurations relative to the ground.
    nrm, tan : ndarray (nt, nj, 2)
        The joints' normals and tangents at ``qm``.
    pts : ndarray (nt, nj, 2, 2, 2)
        The corners on each side at ``qm``: [sample, joint, corner, side, xy], m.
    certified : ndarray (nt,) int8
        `rank_certificate` of each sample's active rows: 1 independent, 0 dependent,
        -1 left to the SVD.
    """
    nt, nb_, _ = pos.shape
    ja = chain.ja
    jb = chain.jb
    nj = ja.shape[0]
    h = cfg.h
    g = cfg.g
    gap_tol = cfg.gap_tol
    hold = cfg.hold
    inv_m = chain.inv_m
    inv_i = chain.inv_i
    isq_m = np.sqrt(inv_m)
    isq_i = np.sqrt(inv_i)
    certified = np.zeros(nt, dtype=np.int8)
    imp_all = np.zeros((nt, nj, 3))
    impulsive = np.zeros(nt, dtype=np.bool_)
    active = np.zeros((nt, nj, 2), dtype=np.bool_)
    qm_all = np.zeros((nt, nb_, 3))
    nrm_all = np.zeros((nt, nj, 2))
    tan_all = np.zeros((nt, nj, 2))
    pts_all = np.zeros((nt, nj, 2, 2, 2))
    p_warm = np.zeros((nj, 3))
    half_h = 0.5 * h
    for k in range(nt):
        q = pos[k].copy()
        v = vel[k].copy()
        for b in range(nb_):
            q[b, 0] -= base_u[k]
            v[b, 0] -= base_v[k]
        qm = q + half_h * v
        geo = RK.geometry(qm, ja, jb, chain.arm_a, chain.arm_b, chain.n0, chain.t0)
        gaps, nrm, tan, pts = geo
        vf = v.copy()
        gk = g + vacc[k] if vacc.shape[0] > 0 else g
        for b in range(nb_):
            vf[b, 0] -= h * acc[k]
            vf[b, 1] -= h * gk
        for j in range(nj):
            for c in range(2):
                active[k, j, c] = (gaps[j, c] <= gap_tol
                                   or (p_warm[j, c] > 0.0 and gaps[j, c] <= hold))
        certified[k] = rank_certificate(qm, active[k], ja, jb, nrm, tan, pts, isq_m, isq_i)
        vn, imp, _, _ = RK.project(chain, cfg, qm, geo, vf, p_warm, np.empty(0), np.empty(0))
        jump = -math.inf
        for b in range(nb_):
            dx = vn[b, 0] - v[b, 0]
            dy = vn[b, 1] - v[b, 1]
            jump = max(jump, math.hypot(dx, dy) + abs(vn[b, 2] - v[b, 2]) * lref)
        impulsive[k] = jump > impulsive_factor * h * (gk + abs(acc[k]))
        # element by element: an array assigned to a slice compiles numba's shape-mismatch
        # error (about 4 s of the first compilation) for a mismatch these shapes cannot have
        for b in range(nb_):
            for c in range(3):
                qm_all[k, b, c] = qm[b, c]
        for j in range(nj):
            for c in range(3):
                imp_all[k, j, c] = imp[j, c]
            for c in range(2):
                nrm_all[k, j, c] = nrm[j, c]
                tan_all[k, j, c] = tan[j, c]
                for s in range(2):
                    for e in range(2):
                        pts_all[k, j, c, s, e] = pts[j, c, s, e]
        p_warm = imp
    return imp_all, impulsive, active, qm_all, nrm_all, tan_all, pts_all, certified
