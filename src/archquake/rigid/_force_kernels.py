"""Compiled joint-force probes of the rigid chain (numba): :func:`archquake.rigid.forces.
joint_forces` over every sample in one call.

At each recorded sample the stepper's next step is repeated (:func:`archquake.rigid.
_step_kernels.project` at the mid-step configuration, warm-started from the previous sample's
impulses), exactly as the plain loop of :func:`archquake.rigid.forces.joint_forces_reference`
does it, which a test holds this kernel to. The samples depend on each other only through that
warm start, so they are probed in order, in one compiled loop.

SI units throughout: m, s, kg, N s.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

import archquake.rigid._step_kernels as RK


@nb.njit(cache=True)
def probe(pos, vel, base_u, base_v, acc, mass, inertia, ja, jb, arm_a, arm_b, n0, t0, h, g,
          gap_tol, tol, max_sweeps, mu, correction, hold, lref, impulsive_factor):
    """The joint impulses of the chain's next step at each sample, and what the rank test needs.

    Parameters
    ----------
    pos, vel : ndarray (nt, nb, 3)
        The free bodies' absolute configurations (m, m, rad) and velocities at the samples.
    base_u, base_v : ndarray (nt,)
        Ground displacement (m) and velocity (m/s) at the samples.
    acc : ndarray (nt,)
        The ground acceleration over each sample's step, m/s^2.
    mass, inertia, ja, jb, arm_a, arm_b, n0, t0
        The :class:`~archquake.rigid.model.RigidModel`'s arrays.
    h, g, gap_tol, tol, max_sweeps, mu, correction, hold
        The step (s), gravity (m/s^2) and the projection's settings, as
        :func:`~archquake.rigid._step_kernels.project` takes them.
    lref : float
        The assembly's reference length, m (a rotation rate's velocity).
    impulsive_factor : float
        A sample is impulsive when a velocity jumps by more than this times h (g + |acc|).

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
    """
    nt, nb_, _ = pos.shape
    nj = ja.shape[0]
    inv_m = 1.0 / mass
    inv_i = 1.0 / inertia
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
        gaps, nrm, tan, pts = RK.geometry(qm, ja, jb, arm_a, arm_b, n0, t0)
        vf = v.copy()
        for b in range(nb_):
            vf[b, 0] -= h * acc[k]
            vf[b, 1] -= h * g
        for j in range(nj):
            for c in range(2):
                active[k, j, c] = (gaps[j, c] <= gap_tol
                                   or (p_warm[j, c] > 0.0 and gaps[j, c] <= hold))
        vn, imp, _, _ = RK.project(qm, vf, inv_m, inv_i, ja, jb, gaps, nrm, tan, pts, gap_tol,
                                   p_warm, tol, max_sweeps, mu, correction, hold)
        jump = -math.inf
        for b in range(nb_):
            dx = vn[b, 0] - v[b, 0]
            dy = vn[b, 1] - v[b, 1]
            jump = max(jump, math.hypot(dx, dy) + abs(vn[b, 2] - v[b, 2]) * lref)
        impulsive[k] = jump > impulsive_factor * h * (g + abs(acc[k]))
        imp_all[k] = imp
        qm_all[k] = qm
        nrm_all[k] = nrm
        tan_all[k] = tan
        pts_all[k] = pts
        p_warm = imp
    return imp_all, impulsive, active, qm_all, nrm_all, tan_all, pts_all
