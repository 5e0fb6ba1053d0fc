"""Compiled Moreau-Jean stepper of `archquake.rigid` (numba).

One step, h, from (q_k, v_k) (per free body: x, y, theta and their rates, relative to the
ground; base bodies fixed in the ground's frame):

1. q_m = q_k + h/2 v_k (mid-step configuration);
2. at q_m, every joint's two corner gaps g_c = (P_b - P_a) . n, n the joint normal carried by
   the mean rotation of its two bodies (so the gap is mirror-symmetric); a corner is active when
   g_c <= ``gap_tol``, or g_c <= ``hold_tol`` if it pushed at the previous step (the hold of
   the position correction, below); a joint with an active corner carries its no-slip row
   (tangential relative velocity zero, at the active corner, or at the mid-point of both);
3. v_free = v_k + h M^-1 f(t_m), f = (-m x_g'', -m g, 0);
4. v_{k+1} = argmin 1/2 ||v - v_free||_M over {H_N v >= b_N, H_T v = b_T}: projected Gauss-Seidel on
   the contact impulses p (p_N >= 0, p_T free), v = v_free + M^-1 H^T p, over-relaxed
   (`RELAX`), warm-started from the previous step's impulses (perfectly plastic: e = 0).
   With a finite friction coefficient mu, each joint's tangential impulse is clamped to
   |p_T| <= mu (p_N0 + p_N1), the current normal impulses of its corners: a fixed point of the
   sweep then satisfies Coulomb's law in 2D (stick with |p_T| < mu p_N, or slip opposite to p_T
   at the bound). That is no longer a projection (Coulomb's law has no potential), so neither
   uniqueness nor convergence is guaranteed; the sweep count and residual are reported.
   `run`'s default solver (``METHOD_DIRECT``, `project_direct`) solves the
   no-slip projection exactly on a guessed active set (the contacts that pushed at the
   previous step): one banded Cholesky of the Delassus matrix per set, corrected sets when
   the guess fails. While the guessed set is the previous step's and its matrix is regular
   (its impulses unique), the previous factor is kept as the refinement's preconditioner and
   the set's impulses are extrapolated from the last steps (`project_direct`): about 9 steps
   in 10 then assemble and factorise nothing. A set whose refinement does not converge (its
   equalities have no solution) is corrected like any other. Gauss-Seidel runs only when no set
   is accepted: after `ACTIVE_SET_ITERATIONS` sets, or at a set that cannot be factorised, or
   that cannot be solved and breaks no condition (none of the 3996 steps of Oppenheim's 4 s
   history at the verdict's step; 11 of the 297,353 steps of the bridge's verdicts under the 28
   near-field records at 0.11 g, each after 24 sets); it returns the converged Gauss-Seidel's
   velocities (docs/notes/mechanism.md, "Speed of the rigid chain"; docs/notes/measurements.md,
   "Where the rigid chain's step goes").
   With friction the no-slip solution is kept when every joint's tangential impulse lies in
   its cone, |p_T| <= mu p_N (`_in_cone`): every joint then sticks, which is Coulomb's
   law, so it is a solution of the frictional step (and its velocity, the no-slip
   projection, is unique). Only when a joint's impulse leaves its cone does the step run the
   clamped Gauss-Seidel, from the no-slip impulses clamped into the cones. The impulses of
   the closed chain are not unique (it is statically indeterminate: on the 15-voussoir bridge
   48 rows on 45 velocities), and the test reads the one the direct solve gives, the nearest
   the previous step's; another split could stick where this one does not, and then the
   Gauss-Seidel finds a solution that may slip. On the bridge (R 5 m, t 0.6 m, mu 0.6) under
   IMPVALL-H-E06_233 at the verdict's step, 1 step in 8770 leaves the cone, and the run costs
   0.07 s of CPU against 19.6 s for the clamped Gauss-Seidel at every step (``METHOD_PGS``:
   901 sweeps a step on average, 55 steps stopped at ``max_iter`` with residuals up to
   7.7e-7 m/s, against the 2.4e-11 m/s asked);
5. q_{k+1} = q_m + h/2 v_{k+1}.

**Coulomb joints and the correction** (`_record_slip`). A joint whose tangential impulse
ends a step on its cone's edge slips, and its reference offset (``slip_ref``) is released: the
next step takes the offset it has then. Its slip is motion, not a drift for the tangential
correction to undo. The reference was once kept through the slip. The correction's bound,
b_T = -(s - s_0) / h, then grew with the slip (10 m/s for 1 mm at h = 1e-4 s), and the
clamped impulse, which opposes H_T v - b_T, drove the joint back over its own slip at mu p_N:
the friction force did positive work. On Oppenheim's arch under a step pulse of 1 g, t_p
0.2 s, with mu 0.8, the contacts did 4.6e6 J of work and the arch collapsed where the no-slip
chain survives.

**Position-level correction** (`run`'s ``correction``, on by default; `project`
and `project_direct` without it unless asked, as the event integrator and the force
probes call them). With b = 0 the scheme holds velocities only, and a pivot in persistent
contact drifts: q is advanced linearly in theta, so a corner turning about its pivot at omega
leaves it by about r omega^2 h^2 / 2 a step (7e-8 m on a parabolic arch at 3 lambda), past
``gap_tol`` (1e-9 L): the corner dropped out with its joint's no-slip row and the block slid
(33 mm in 0.29 s, docs/notes/mechanism.md). The bounds (`_targets`): b_N = -g_c / h on a
corner open by g_c > 0 (pulled shut in one step; a penetration is not pushed out, which would
throw the corner off at |g_c| / h: half the approach speed after an impact, a restitution the
plastic model has not: it moved the energy kept over the half cycles of
docs/notes/mechanism.md by -0.022 to +0.037);
b_T = -(s - s_0) / h, s the joint's tangential offset at its no-slip point and s_0 its value
when the contact began (``slip_ref``, NaN while the joint is open: a flight's offset is the
model's, not an error); and a corner that pushed stays active while g_c <= ``hold_tol``
(larger than a step's drift), so that the correction can act on it.

**Energy.** D_DISSIPATED stays the kinetic energy the projection removes, 1/2 (T_free - T_new)
= 1/2 p^T W p - p^T b (complementarity p_r (H_r v - b_r) = 0), which with b != 0 is not all
dissipation: -p^T b (D_CORRECTION) is the correction's work, positive when a pushing corner is
pulled shut. It is kept in D_DISSIPATED because that is what closes the balance
T + V + D_DISSIPATED - D_INPUT = const of the discrete scheme: the positions the correction
moves change V by what the drift had changed it (measured: the balance error of Oppenheim's
half cycle 0.0168 of the input with and without the correction; subtracting D_CORRECTION made
it 1.6 when penetrations were pushed out). D_CORRECTION is reported to show its size (7 J of
41.7 kJ on Oppenheim's half cycle).

D_DISSIPATED is not what the contacts dissipate. With the free velocity v_free = v_k + h M^-1 f,
1/2 (T_free - T_new) also counts the work of the applied load f over the velocity change
that the contacts make in the step. An arch at rest on its supports
"dissipates" 1/2 h^2 f^T M^-1 f per step by it. D_CONTACT_WORK is the contacts' own work on the
step's mean velocity, -p^T H (v_k + v_{k+1}) / 2 = -(v_{k+1} - v_free)^T M (v_k + v_{k+1}) / 2.
The positions advance by h (v_k + v_{k+1}) / 2 and the input work D_INPUT is taken on the same
mean velocity, so T + V + D_CONTACT_WORK - D_INPUT is constant to rounding: the balance the runs
report (`archquake.rigid.run.EnergyBalance`). It is 0 where nothing moves relative to the
ground. D_FRICTION_WORK is its part on the slipping joints' tangential rows, -p_T H_T (v_k +
v_{k+1}) / 2: mu p_N times the step's slip. D_DISSIPATED stays the ``damping`` column of the
result, which the digests of the no-slip runs hold.

SI units throughout: masses kg, inertias kg m^2, impulses N s.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numba as nb
import numpy as np

from archquake._kernel_cache import stamp_kernels

stamp_kernels()  # the cache checks each kernel against every source compiled into it

#: Columns of the per-sample diagnostics.
D_DISSIPATED = 0  # J, cumulated energy removed by the contact projections
D_INPUT = 1  # J, cumulated work of the inertial load -m x_g'' on the relative motion
D_PENETRATION = 2  # m, largest penetration (negative gap) since the last sample
D_FRICTION = 3  # -, largest |p_T| / p_N of a joint (p_N > 1e-12 h g max m) since the last sample
D_ITERATIONS = 4  # -, most Gauss-Seidel sweeps of a step since the last sample
D_RESIDUAL = 5  # m/s, largest velocity correction of a step's last sweep since the last sample
D_CORRECTION = 6  # J, cumulated part of D_DISSIPATED that is the position correction's work,
#: -p^T b (module docstring, "Energy")
D_CONTACT_WORK = 7  # J, cumulated work done on the contacts, -p^T H (v_k + v_k+1) / 2 (module
#: docstring, "Energy"): what the balance T + V + D_CONTACT_WORK - D_INPUT = const closes with
D_FRICTION_WORK = 8  # J, the part of D_CONTACT_WORK done on the slipping joints' tangential rows
N_DIAG = 9

#: Over-relaxation of the Gauss-Seidel sweep (projected SOR; converges for 0 < RELAX < 2 on the
#: positive semi-definite Delassus matrix). 1.3 halves the sweeps on Oppenheim's arch (280 -> 145
#: at worst, 1.9 -> 1.1 s per 4 s history) and changes the energy kept over its half cycle by
#: 2e-5.
RELAX = 1.3

#: Contact solvers of `run`: the plain projected Gauss-Seidel (`project`, the
#: reference) and the exact solve on a guessed active set (`project_direct`).
METHOD_PGS = 0
METHOD_DIRECT = 1
#: `project_direct`: regularisation of the (singular) Delassus matrix, relative to its
#: largest diagonal entry; refinement solves per active set; active sets tried before
#: Gauss-Seidel. An accepted active set gives the exact projection whatever the number of
#: sets tried, so the cap only decides when Gauss-Seidel takes over, and Gauss-Seidel is what
#: costs: on the 15-voussoir semicircle (R 5 m, t 0.6 m) under the 28 near-field records at
#: 0.11 g, 0.2 % of the steps needed 7 to 15 sets, and each of them, sent to Gauss-Seidel after
#: 6, took ~1600 sweeps of 44 rows (up to the 5000 allowed): 60 % of the run's time
#: (docs/notes/measurements.md, "The rigid chain's step on 15 voussoirs").
EPS_REG = 1.0e-10
REFINEMENTS = 6
ACTIVE_SET_ITERATIONS = 24
#: `project_direct` between steps (its work arrays kept, as `run` and the verdict's loop keep
#: them): while the first guessed set is the set factorised last and every pivot of that
#: factorisation was above ``REUSE_PIVOT`` times its row's Delassus diagonal (a regular set,
#: whose impulses are unique), the old factor preconditions the refinement, which reads the
#: true residual with the current rows, for at most ``REUSE_REFINEMENTS`` solves; the set's
#: matrix is assembled and factorised again when that does not reach ``tol``
#: (docs/notes/measurements.md, "The rigid chain's step with its factor kept").
REUSE_REFINEMENTS = 3
REUSE_PIVOT = 1.0e-6


#: numba's option to compile a kernel without reference counting (a private option of numba,
#: hence passed by name). The stepping loops (`_steps`, the verdict's) are compiled so: they
#: allocate nothing, and with reference counting each step took and dropped a reference to
#: every array of the packed tuples it passes on (`advance`).
NO_REFCOUNT: dict[str, Any] = {"_nrt": False}


class Chain(NamedTuple):
    """The chain's packed arrays (`archquake.rigid.model.RigidModel`'s): per free body
    ``mass`` (kg), ``inertia`` (kg m^2) and their inverses ``inv_m``, ``inv_i``; per joint the
    free bodies on its two sides ``ja``, ``jb`` (int, -1: the base), the corners relative to
    their bodies' centroids ``arm_a``, ``arm_b`` (nj, 2, 2) m, the undisplaced normal ``n0``
    and tangent ``t0`` (nj, 2)."""

    mass: np.ndarray
    inertia: np.ndarray
    inv_m: np.ndarray
    inv_i: np.ndarray
    ja: np.ndarray
    jb: np.ndarray
    arm_a: np.ndarray
    arm_b: np.ndarray
    n0: np.ndarray
    t0: np.ndarray


def pack_chain(model) -> Chain:
    """The `Chain` of a `RigidModel` (its arrays, not
    copied; the inverses computed once)."""
    return Chain(model.mass, model.inertia, 1.0 / model.mass, 1.0 / model.inertia, model.ja,
                 model.jb, model.arm_a, model.arm_b, model.n0, model.t0)


class Stepping(NamedTuple):
    """The settings of a step: ``h`` (s), ``g`` (m/s^2), ``gap_tol`` (m, a corner is active
    below it), ``tol`` (m/s, the solver's), ``max_iter`` (Gauss-Seidel sweeps), ``mu``
    (friction coefficient, 0: no slip), ``method`` (`METHOD_PGS` or
    `METHOD_DIRECT`), ``h_corr`` (s, the position correction's time, 0: none) and
    ``hold`` (m, its hold; module docstring), ``max_sets`` (active sets the direct solve
    tries before Gauss-Seidel, `project_direct`)."""

    h: float
    g: float
    gap_tol: float
    tol: float
    max_iter: int
    mu: float
    method: int
    h_corr: float
    hold: float
    max_sets: int


def stepping(h: float, g: float, gap_tol: float, tol: float, max_iter: int, mu: float,
             method: int, correction: bool = True, hold_tol: float = 0.0,
             max_sets: int = ACTIVE_SET_ITERATIONS) -> Stepping:
    """A `Stepping` (types fixed for the compiled kernels): ``correction`` False turns
    the position-level correction off (``h_corr`` and ``hold`` 0)."""
    return Stepping(float(h), float(g), float(gap_tol), float(tol), int(max_iter), float(mu),
                    int(method), float(h) if correction else 0.0,
                    float(hold_tol) if correction else 0.0, int(max_sets))


def solving(gap_tol: float, tol: float, max_iter: int, mu: float = 0.0, *,
            correction: float = 0.0, hold_tol: float = 0.0,
            max_sets: int = ACTIVE_SET_ITERATIONS) -> Stepping:
    """The `Stepping` of one contact projection alone (`project`, `project_direct`: no
    step, so ``h`` and ``g`` 0): ``correction`` (s) the position-level correction's time, 0
    for the velocity-level cone alone, ``hold_tol`` (m) its hold."""
    return Stepping(0.0, 0.0, float(gap_tol), float(tol), int(max_iter), float(mu),
                    METHOD_DIRECT, float(correction), float(hold_tol), int(max_sets))


class Geometry(NamedTuple):
    """`geometry`'s arrays at a configuration: corner ``gaps`` (nj, 2) m, joint normals
    ``nrm`` and tangents ``tan`` (nj, 2), corner positions ``pts`` (nj, 2, 2, 2) m."""

    gaps: np.ndarray
    nrm: np.ndarray
    tan: np.ndarray
    pts: np.ndarray


class State(NamedTuple):
    """What a run updates in place: ``q``, ``v`` (nb, 3) the free bodies' configuration and
    velocity (x, y m, theta rad, and rates), ``p_warm`` (nj, 3) the previous step's impulses
    (N s: normal at corner 0, at corner 1, tangential), ``slip_ref`` (nj,) m the joints'
    tangential offsets when their contact began (NaN: open)."""

    q: np.ndarray
    v: np.ndarray
    p_warm: np.ndarray
    slip_ref: np.ndarray


class Record(NamedTuple):
    """Where `run` writes its samples: every ``out_every`` steps a row of ``q``, ``v``
    (k, nb, 3) and ``diag`` (k, `N_DIAG`)."""

    out_every: int
    q: np.ndarray
    v: np.ndarray
    diag: np.ndarray


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
    geometry_into(q, ja, jb, arm_a, arm_b, n0, t0, gaps, nrm, tan, pts, np.zeros((q.shape[0], 4)))
    return Geometry(gaps, nrm, tan, pts)


@nb.njit(cache=True, inline="always")
def _corner(q, trig, body, arms, j, k):
    """`_point` of corner ``k`` of joint ``j`` (``arms[j, k]``, read by scalar indexing) with
    the body's cos and sin read from ``trig`` (`geometry_into`'s)."""
    if body < 0:
        return arms[j, k, 0], arms[j, k, 1]
    c = trig[body, 0]
    s = trig[body, 1]
    return (q[body, 0] + c * arms[j, k, 0] - s * arms[j, k, 1],
            q[body, 1] + s * arms[j, k, 0] + c * arms[j, k, 1])


@nb.njit(cache=True, inline="always")
def geometry_into(q, ja, jb, arm_a, arm_b, n0, t0, gaps, nrm, tan, pts, trig):
    """`geometry` written into preallocated ``gaps``, ``nrm``, ``tan``, ``pts`` (every
    entry is overwritten); ``trig`` (nb, 4) scratch: each body's cos and sin, and those of half
    its rotation, computed once a step. A body's own cos and sin, and its joints' mean
    rotations (theta_a + theta_b) / 2, follow from the half angles by the addition formulas: a
    cos-sin pair a body instead of one a body and one a joint (7 pairs instead of 15 on a
    7-voussoir arch; they were half of the geometry's time)."""
    nj = ja.shape[0]
    for i in range(q.shape[0]):
        hc = math.cos(0.5 * q[i, 2])
        hs = math.sin(0.5 * q[i, 2])
        trig[i, 0] = (hc - hs) * (hc + hs)
        trig[i, 1] = 2.0 * hs * hc
        trig[i, 2] = hc
        trig[i, 3] = hs
    for j in range(nj):
        # the joint's mean rotation (theta_a + theta_b) / 2 by the addition formulas
        ca, sa = (1.0, 0.0) if ja[j] < 0 else (trig[ja[j], 2], trig[ja[j], 3])
        cb, sb = (1.0, 0.0) if jb[j] < 0 else (trig[jb[j], 2], trig[jb[j], 3])
        c = ca * cb - sa * sb
        s = sa * cb + ca * sb
        nrm[j, 0] = c * n0[j, 0] - s * n0[j, 1]
        nrm[j, 1] = s * n0[j, 0] + c * n0[j, 1]
        tan[j, 0] = c * t0[j, 0] - s * t0[j, 1]
        tan[j, 1] = s * t0[j, 0] + c * t0[j, 1]
        for k in range(2):
            ax, ay = _corner(q, trig, ja[j], arm_a, j, k)
            bx, by = _corner(q, trig, jb[j], arm_b, j, k)
            pts[j, k, 0, 0] = ax
            pts[j, k, 0, 1] = ay
            pts[j, k, 1, 0] = bx
            pts[j, k, 1, 1] = by
            gaps[j, k] = (bx - ax) * nrm[j, 0] + (by - ay) * nrm[j, 1]


@nb.njit(cache=True, inline="always")
def _row(q, body, px, py, dx, dy, sign, out, r):
    """Jacobian entries ``out[r]`` (3,) of ``sign`` times the velocity of the body point (px,
    py) along d."""
    if body < 0:
        out[r, 0] = 0.0
        out[r, 1] = 0.0
        out[r, 2] = 0.0
        return
    rx = px - q[body, 0]
    ry = py - q[body, 1]
    out[r, 0] = sign * dx
    out[r, 1] = sign * dy
    out[r, 2] = sign * (rx * dy - ry * dx)


@nb.njit(cache=True, inline="always")
def _rows_into(chain, q, geo, gap_tol, hold_tol, p_warm, ws):
    """The rows of the active contacts at ``q`` (`Geometry` ``geo``), in joint order (per
    joint: normal at corner 0, normal at corner 1, tangential), written into ``ws`` (`Work`,
    3 nj rows, the first ``nrows`` set): ``rows_j``, ``rows_k`` (joint, row kind),
    ``ja_rows``, ``jb_rows`` (the Jacobian entries on either side), ``diag`` (the Delassus
    diagonal, m/s per N s) and ``offset`` (tangential rows: the tangential offset (P_b - P_a) . t
    of the row's point, m). A corner is active when its gap is <= ``gap_tol``, or <=
    ``hold_tol`` (m) if it pushed at the previous step (``p_warm`` > 0; the position-level
    correction's hold, `run`). Returns ``nrows``."""
    ja = chain.ja
    jb = chain.jb
    inv_m = chain.inv_m
    inv_i = chain.inv_i
    gaps = geo.gaps
    nrm = geo.nrm
    tan = geo.tan
    pts = geo.pts
    rows_j = ws.rows_j
    rows_k = ws.rows_k
    ja_rows = ws.ja_rows
    jb_rows = ws.jb_rows
    diag = ws.diag
    offset = ws.offset
    nj = ja.shape[0]
    nrows = np.int64(0)  # typed int64: the literal 0 would compile copies of the solvers
    for j in range(nj):
        act0 = gaps[j, 0] <= gap_tol or (p_warm[j, 0] > 0.0 and gaps[j, 0] <= hold_tol)
        act1 = gaps[j, 1] <= gap_tol or (p_warm[j, 1] > 0.0 and gaps[j, 1] <= hold_tol)
        for k in range(2):
            if (k == 0 and act0) or (k == 1 and act1):
                rows_j[nrows] = j
                rows_k[nrows] = k
                offset[nrows] = 0.0
                _row(q, ja[j], pts[j, k, 0, 0], pts[j, k, 0, 1], nrm[j, 0], nrm[j, 1], -1.0,
                     ja_rows, nrows)
                _row(q, jb[j], pts[j, k, 1, 0], pts[j, k, 1, 1], nrm[j, 0], nrm[j, 1], 1.0,
                     jb_rows, nrows)
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
            offset[nrows] = (bx - ax) * tan[j, 0] + (by - ay) * tan[j, 1]
            _row(q, ja[j], ax, ay, tan[j, 0], tan[j, 1], -1.0, ja_rows, nrows)
            _row(q, jb[j], bx, by, tan[j, 0], tan[j, 1], 1.0, jb_rows, nrows)
            nrows += 1
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
    return nrows


@nb.njit(cache=True, inline="always")
def _targets_into(nrows, rows_j, rows_k, gaps, offset, correction, slip_ref, target, seen):
    """`_targets` written into ``target`` (its first ``nrows`` entries), ``seen`` (nj,)
    bool scratch."""
    for r in range(nrows):
        target[r] = 0.0
    if correction <= 0.0:
        return
    for r in range(nrows):
        if rows_k[r] < 2:
            gap = gaps[rows_j[r], rows_k[r]]
            if gap > 0.0:
                target[r] = -gap / correction
    if slip_ref.shape[0] > 0:
        for j in range(slip_ref.shape[0]):
            seen[j] = False
        for r in range(nrows):
            if rows_k[r] == 2:
                j = rows_j[r]
                seen[j] = True
                if math.isnan(slip_ref[j]):
                    slip_ref[j] = offset[r]
                target[r] = -(offset[r] - slip_ref[j]) / correction
        for j in range(slip_ref.shape[0]):
            if not seen[j]:
                slip_ref[j] = math.nan


@nb.njit(cache=True, **NO_REFCOUNT)
def _correction_work(nrows, p, target):
    """-sum_r p_r target_r, J: the part of the kinetic energy a projection removes that is the
    position-level correction's (impulses ``p`` N s, bounds ``target`` m/s; `run`)."""
    w = 0.0
    for r in range(nrows):
        w -= p[r] * target[r]
    return w


@nb.njit(cache=True, **NO_REFCOUNT)
def _pgs(chain, cfg, v, p, nrows, ws):
    """Projected over-relaxed Gauss-Seidel on the rows of ``ws`` (`Work`, `_rows_into`) from the
    impulses ``p`` (nrows,), already applied to ``v``; both updated in place. ``ws.target``
    (nrows,), m/s: the rows' bounds, H_r v >= target[r] (normal rows) or H_r v = target[r]
    (tangential rows) (`_targets_into`); ``cfg.tol``, ``cfg.max_iter`` and ``cfg.mu`` as
    `Stepping`'s. Returns (sweeps, residual m/s)."""
    ja = chain.ja
    jb = chain.jb
    inv_m = chain.inv_m
    inv_i = chain.inv_i
    rows_j = ws.rows_j
    rows_k = ws.rows_k
    ja_rows = ws.ja_rows
    jb_rows = ws.jb_rows
    diag = ws.diag
    target = ws.target
    pn_joint = ws.pn
    tol = cfg.tol
    max_iter = cfg.max_iter
    mu = cfg.mu
    for j in range(ja.shape[0]):
        pn_joint[j] = 0.0
    for r in range(nrows):
        if rows_k[r] < 2:
            pn_joint[rows_j[r]] += p[r]
    sweeps = 0
    change = 0.0
    for it in range(max_iter):
        sweeps = it + 1
        change = 0.0
        for r in range(nrows):
            j = rows_j[r]
            w = _row_velocity(v, r, rows_j, ja, jb, ja_rows, jb_rows) - target[r]
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
                _apply_row(v, r, rows_j, ja, jb, ja_rows, jb_rows, dp, inv_m, inv_i)
                p[r] = new
                dv = abs(dp) * diag[r]
                if dv > change:
                    change = dv
        if change <= tol:
            break
    return sweeps, change


@nb.njit(cache=True)
def project(chain, cfg, q, geo, v_free, p_warm, slip_ref, work):
    """The contact step: v = argmin ||v - v_free||_M over the admissible cone of the active
    contacts (module docstring, step 4), by projected Gauss-Seidel alone (the plain stepper,
    ``method = 0`` of `run`).

    Parameters
    ----------
    chain : Chain
    cfg : Stepping
        ``gap_tol``, ``tol``, ``max_iter``; ``mu`` the friction coefficient (``mu <= 0``: no
        slip, the tangential impulse is free); ``h_corr`` (s) > 0 for the position-level
        correction of step 4 (the normal rows bound H_n v >= -gap / ``h_corr``,
        `_targets_into`), 0: the cone H_n v >= 0; ``hold`` (m) its hold (`solving`).
    q : ndarray (nb, 3)
        The configuration, and ``geo`` its `Geometry`.
    v_free : ndarray (nb, 3)
        The unconstrained velocity.
    p_warm : ndarray (nj, 3)
        The previous impulses, N s (the warm start).
    slip_ref : ndarray (nj,)
        The joints' reference offsets, m (`run`), updated in place; empty (``np.empty(0)``)
        for none: the tangential rows are then not corrected.
    work : ndarray (1,)
        Receives the correction's work, J (`run`); empty for none. (Empty arrays, not None:
        one compiled version of the solve serves every caller.)

    Returns (v (nb, 3), impulses (nj, 3): normal at corner 0, normal at corner 1, tangential,
    N s; sweeps taken; final residual m/s)."""
    ws = workspace(chain.inv_m.shape[0], chain.ja.shape[0])
    sweeps, change = _project_into(chain, cfg, q, geo, v_free, p_warm, slip_ref, work, ws)
    return ws.vn, ws.imp, sweeps, change


@nb.njit(cache=True, nogil=True, forceinline=True, **NO_REFCOUNT)
def _project_into(chain, cfg, q, geo, v_free, p_warm, slip_ref, work, ws):
    """`project` in the work arrays ``ws`` (`Work`): the velocity is written into
    ``ws.vn``, the impulses into ``ws.imp``, the slipping joints into ``ws.slip_p``,
    ``ws.t_ja``, ``ws.t_jb`` (`_record_slip`); returns (sweeps, residual)."""
    ja = chain.ja
    jb = chain.jb
    inv_m = chain.inv_m
    inv_i = chain.inv_i
    mu = cfg.mu
    nj = ja.shape[0]
    rows_j = ws.rows_j
    rows_k = ws.rows_k
    ja_rows = ws.ja_rows
    jb_rows = ws.jb_rows
    target = ws.target
    p = ws.p
    nrows = _rows_into(chain, q, geo, cfg.gap_tol, cfg.hold, p_warm, ws)
    _targets_into(nrows, rows_j, rows_k, geo.gaps, ws.offset, cfg.h_corr, slip_ref, target,
                  ws.seen)
    v = ws.vn
    _copy3(v, v_free)
    pn_joint = ws.pn
    for j in range(nj):
        pn_joint[j] = 0.0
    for r in range(nrows):
        j = rows_j[r]
        p[r] = p_warm[j, rows_k[r]]
        if rows_k[r] < 2 and p[r] < 0.0:
            p[r] = 0.0
        if rows_k[r] < 2:
            pn_joint[j] += p[r]
        elif mu > 0.0:
            p[r] = min(max(p[r], -mu * pn_joint[j]), mu * pn_joint[j])
        if p[r] != 0.0:
            _apply_row(v, r, rows_j, ja, jb, ja_rows, jb_rows, p[r], inv_m, inv_i)
    sweeps, change = _pgs(chain, cfg, v, p, nrows, ws)
    imp = ws.imp
    for j in range(nj):
        imp[j, 0] = 0.0
        imp[j, 1] = 0.0
        imp[j, 2] = 0.0
    for r in range(nrows):
        imp[rows_j[r], rows_k[r]] = p[r]
    _record_slip(nrows, rows_j, rows_k, p, mu, ja_rows, jb_rows, slip_ref, ws)
    if work.shape[0] > 0:
        work[0] = _correction_work(nrows, p, target)
    return sweeps, change


@nb.njit(cache=True, inline="always")
def _record_slip(nrows, rows_j, rows_k, p, mu, ja_rows, jb_rows, slip_ref, ws):
    """After a Coulomb solve (``mu`` > 0): every joint whose tangential impulse sits on its
    cone's edge, |p_T| >= mu p_N (1 - 1e-9), slips. Its impulse goes to ``ws.slip_p`` (nj,) N s
    and its tangential Jacobian rows to ``ws.t_ja``, ``ws.t_jb`` (nj, 3), for the friction's
    work (`run`); its reference offset ``slip_ref`` is released (NaN: taken anew when
    the joint next sticks), since its slip is motion, not drift for the correction to undo.
    ``ws.slip_p`` is zero for the other joints (all of them when ``mu`` <= 0)."""
    slip_p = ws.slip_p
    for j in range(slip_p.shape[0]):
        slip_p[j] = 0.0
    if mu <= 0.0:
        return
    for r in range(nrows):
        if rows_k[r] == 2:
            j = rows_j[r]
            bound = mu * max(_joint_normal(r, rows_j, rows_k, p), 0.0)
            if abs(p[r]) >= bound * (1.0 - 1e-9):
                slip_p[j] = p[r]
                for c in range(3):
                    ws.t_ja[j, c] = ja_rows[r, c]
                    ws.t_jb[j, c] = jb_rows[r, c]
                if slip_ref.shape[0] > 0:
                    slip_ref[j] = math.nan


@nb.njit(cache=True, inline="always")
def _coupling(r, s, rows_j, ja, jb, ja_rows, jb_rows, inv_m, inv_i):
    """Delassus entry W[r, s] = H_r M^-1 H_s^T (m/s per N s); scalar indexing only (no
    views: this is the inner loop of the assembly)."""
    jr = rows_j[r]
    js = rows_j[s]
    w = 0.0
    for side_r in range(2):
        br = ja[jr] if side_r == 0 else jb[jr]
        if br < 0:
            continue
        for side_s in range(2):
            bs = ja[js] if side_s == 0 else jb[js]
            if bs != br:
                continue
            if side_r == 0:
                h0, h1, h2 = ja_rows[r, 0], ja_rows[r, 1], ja_rows[r, 2]
            else:
                h0, h1, h2 = jb_rows[r, 0], jb_rows[r, 1], jb_rows[r, 2]
            if side_s == 0:
                w += (h0 * ja_rows[s, 0] + h1 * ja_rows[s, 1]) * inv_m[br] \
                    + h2 * ja_rows[s, 2] * inv_i[br]
            else:
                w += (h0 * jb_rows[s, 0] + h1 * jb_rows[s, 1]) * inv_m[br] \
                    + h2 * jb_rows[s, 2] * inv_i[br]
    return w


@nb.njit(cache=True, inline="always")
def _apply_row(v, r, rows_j, ja, jb, ja_rows, jb_rows, dp, inv_m, inv_i):
    """v += M^-1 H_r^T dp (scalar indexing)."""
    j = rows_j[r]
    a = ja[j]
    b = jb[j]
    if a >= 0:
        v[a, 0] += ja_rows[r, 0] * dp * inv_m[a]
        v[a, 1] += ja_rows[r, 1] * dp * inv_m[a]
        v[a, 2] += ja_rows[r, 2] * dp * inv_i[a]
    if b >= 0:
        v[b, 0] += jb_rows[r, 0] * dp * inv_m[b]
        v[b, 1] += jb_rows[r, 1] * dp * inv_m[b]
        v[b, 2] += jb_rows[r, 2] * dp * inv_i[b]


@nb.njit(cache=True, inline="always")
def _copy3(dst, src):
    """dst[:, :] = src for (n, 3) arrays, as a plain loop (cheaper than a slice assignment in
    the step's inner code)."""
    for i in range(src.shape[0]):
        dst[i, 0] = src[i, 0]
        dst[i, 1] = src[i, 1]
        dst[i, 2] = src[i, 2]


@nb.njit(cache=True, inline="always")
def _row_velocity(v, r, rows_j, ja, jb, ja_rows, jb_rows):
    j = rows_j[r]
    a = ja[j]
    b = jb[j]
    w = 0.0
    if a >= 0:
        w += ja_rows[r, 0] * v[a, 0] + ja_rows[r, 1] * v[a, 1] + ja_rows[r, 2] * v[a, 2]
    if b >= 0:
        w += jb_rows[r, 0] * v[b, 0] + jb_rows[r, 1] * v[b, 1] + jb_rows[r, 2] * v[b, 2]
    return w


@nb.njit(cache=True, inline="always")
def _envelope_solve(w_mat, first, n, rhs, out):
    """Solve L L^T x = rhs with ``w_mat`` holding the envelope Cholesky factor L (rows i,
    columns first[i]..i) in its lower triangle; ``out`` (n,)."""
    for i in range(n):
        s = rhs[i]
        for k in range(first[i], i):
            s -= w_mat[i, k] * out[k]
        out[i] = s / w_mat[i, i]
    for i in range(n - 1, -1, -1):
        out[i] /= w_mat[i, i]
        xi = out[i]
        for k in range(first[i], i):
            out[k] -= w_mat[i, k] * xi


@nb.njit(cache=True, inline="always")
def _envelope_solve_inv(w_mat, dinv, first, n, rhs, out):
    """`_envelope_solve` with the reciprocals ``dinv`` (n,) of the factor's diagonal: a
    multiplication where it divides (the solve's chain of dependent operations is shorter)."""
    for i in range(n):
        s = rhs[i]
        for k in range(first[i], i):
            s -= w_mat[i, k] * out[k]
        out[i] = s * dinv[i]
    for i in range(n - 1, -1, -1):
        out[i] *= dinv[i]
        xi = out[i]
        for k in range(first[i], i):
            out[k] -= w_mat[i, k] * xi


@nb.njit(cache=True)
def project_direct(chain, cfg, q, geo, v_free, p_warm, slip_ref, work):
    """The same contact step as `project`, solved exactly on a guessed active set,
    Gauss-Seidel only when the guess fails, or (``mu > 0``) when a joint's tangential impulse
    leaves its Coulomb cone (module docstring, step 4).

    The equality set S holds every tangential row and the normal rows whose impulse was
    positive at the previous step. On S the velocity is the exact kinetic-metric projection of
    v_free onto {H_S v = 0}: W_SS d = -H_S v_w, W = H M^-1 H^T the Delassus matrix (banded: a
    joint couples only its two bodies; envelope Cholesky), v_w the velocity after the previous
    impulses. W_SS is singular when the closed chain is statically indeterminate; it is
    regularised by ``EPS_REG`` times its largest diagonal and refined until the equality residual
    is below ``tol`` (m/s), which gives of all the impulses that satisfy the equalities the
    one nearest to the previous step's (the redundant part of the impulses follows the warm
    start, the velocity is unique). The result is accepted when it satisfies the cone's
    conditions to ``tol``: normal impulses in S >= -tol / W_rr, normal rows outside S separating
    (H_r v >= -tol). Otherwise S is corrected (violated rows added, tensile rows removed) up
    to ``cfg.max_sets`` (``ACTIVE_SET_ITERATIONS``) times, and then projected Gauss-Seidel
    (`_pgs`) finishes from the previous step's impulses. A set whose refinement does not reach
    ``tol`` is corrected in the same way: its equalities have no solution (its rows
    over-determine the velocities, as when every corner of a closed arch is active), and the
    rows whose impulses the refinement drives negative along the matrix's near-null
    directions leave it. With ``mu > 0`` an accepted
    set's impulses are tested against the Coulomb cones, |p_T| <= mu (p_N0 + p_N1) + tol /
    W_TT at every joint (`_in_cone`): kept if they pass (every joint sticks), otherwise
    clamped into the cones (`_clamp_to_cone`) and finished by the clamped Gauss-Seidel.
    The parameters are `project`'s (with ``cfg.h_corr`` > 0 the equalities and the
    separating test read H_r v = target_r, H_r v >= target_r - tol). Returns as `project`;
    the count is the number of active sets tried plus any Gauss-Seidel sweeps.

    Across steps (the work arrays kept, `_direct_into`, as `run` and the verdict's loop do):
    when the first guessed set is the set factorised last and that factorisation was regular
    (every pivot above `REUSE_PIVOT` times its row's diagonal: H_S of full row rank, so the
    impulses are unique and the warm start does not choose among them), the set is not
    assembled nor factorised: the old factor, of the Delassus matrix some steps earlier,
    preconditions the same refinement, which reads the true residual with the current rows
    and accepts on the same test (below ``tol``), so the result is the same projection to the
    solver's tolerance. Its start is the set's impulses extrapolated from the steps over which
    the set has held (linearly after two, quadratically after three). If
    `REUSE_REFINEMENTS` solves do not reach ``tol`` (or the residual falls too slowly to),
    the set is assembled and factorised as any other, from the previous impulses: that step
    is then the full solve, bit for bit. A singular set (the closed chain at rest, or any
    statically indeterminate set) is always factorised afresh. A `project_direct` call alone
    (new work arrays) never reuses."""
    ws = workspace(chain.inv_m.shape[0], chain.ja.shape[0])
    count, change = _direct_into(chain, cfg, q, geo, v_free, p_warm, slip_ref, work, ws)
    return ws.vn, ws.imp, count, change


class Work(NamedTuple):
    """The work arrays of one step (`workspace`): allocated once per run, overwritten by every step
    (the step itself allocates nothing). ``qm``, ``vf``, ``vn`` (nb, 3): the mid-step
    configuration, the free and the projected velocity; ``imp`` (nj, 3) the impulses; ``gaps``,
    ``nrm``, ``tan``, ``pts``: `geometry`'s; ``corr`` (1,): the correction's work of the step,
    J; ``trig`` (nb, 4): the bodies' cos and sin, and those of their half rotations; ``sa``,
    ``sb``, ``ha``, ``hb``, ``tg``: the direct solve's equality rows packed in set order
    (bodies, Jacobian entries, bounds); ``pn`` (nj,) the joints' normal impulses (Gauss-Seidel's
    scratch); ``slip_p`` (nj,) the tangential impulse of each joint that slipped in the step
    (N s, 0 for the others) and ``t_ja``, ``t_jb`` (nj, 3) its tangential Jacobian rows
    (`_record_slip`); ``fac`` (3 nj + 1,) the set whose factor ``mat`` holds (its size, -1: none,
    then each row as 3 joint + kind), ``fpiv`` (3 nj,) whether each of its pivots was regular
    (the factor is kept for the next step only if all were), ``feps`` (1,) its regularisation
    (a later set of the same step refactorises only from its first changed row), ``held`` (1,)
    the steps over which that set has been accepted, ``pw2``, ``pw3`` (nj, 3) the impulses of
    the two steps before the previous one, ``dinv`` (3 nj,) the reciprocals of the factor's
    diagonal (`project_direct`, across steps); the others the contact rows' and the direct
    solve's scratch."""

    qm: np.ndarray
    vf: np.ndarray
    vn: np.ndarray
    imp: np.ndarray
    gaps: np.ndarray
    nrm: np.ndarray
    tan: np.ndarray
    pts: np.ndarray
    rows_j: np.ndarray
    rows_k: np.ndarray
    ja_rows: np.ndarray
    jb_rows: np.ndarray
    diag: np.ndarray
    offset: np.ndarray
    target: np.ndarray
    seen: np.ndarray
    in_s: np.ndarray
    pw: np.ndarray
    idx: np.ndarray
    first: np.ndarray
    mat: np.ndarray
    rhs: np.ndarray
    d: np.ndarray
    p: np.ndarray
    cnt: np.ndarray
    lst_i: np.ndarray
    lst_side: np.ndarray
    corr: np.ndarray
    trig: np.ndarray
    sa: np.ndarray
    sb: np.ndarray
    ha: np.ndarray
    hb: np.ndarray
    tg: np.ndarray
    pn: np.ndarray
    slip_p: np.ndarray
    t_ja: np.ndarray
    t_jb: np.ndarray
    fac: np.ndarray
    held: np.ndarray
    pw2: np.ndarray
    dinv: np.ndarray
    pw3: np.ndarray
    fpiv: np.ndarray
    feps: np.ndarray


@nb.njit(cache=True)
def workspace(nbody, nj):
    """The `Work` arrays of one step of ``nbody`` free bodies and ``nj`` joints:
    allocated once, reused by every step (`advance`)."""
    nr = 3 * nj
    return Work(np.zeros((nbody, 3)), np.zeros((nbody, 3)), np.zeros((nbody, 3)),
                np.zeros((nj, 3)), np.zeros((nj, 2)), np.zeros((nj, 2)), np.zeros((nj, 2)),
                np.zeros((nj, 2, 2, 2)), np.zeros(nr, np.int64), np.zeros(nr, np.int64),
                np.zeros((nr, 3)), np.zeros((nr, 3)), np.zeros(nr), np.zeros(nr), np.zeros(nr),
                np.zeros(nj, np.bool_), np.zeros(nr, np.bool_), np.zeros(nr),
                np.zeros(nr, np.int64), np.zeros(nr, np.int64), np.zeros((nr, nr)),
                np.zeros(nr), np.zeros(nr), np.zeros(nr), np.zeros(nbody, np.int64),
                np.zeros((nbody, nr), np.int64), np.zeros((nbody, nr), np.int64), np.zeros(1),
                np.zeros((nbody, 4)), np.zeros(nr, np.int64), np.zeros(nr, np.int64),
                np.zeros((nr, 3)), np.zeros((nr, 3)), np.zeros(nr), np.zeros(nj), np.zeros(nj),
                np.zeros((nj, 3)), np.zeros((nj, 3)), np.full(nr + 1, -1, np.int64),
                np.zeros(1, np.int64), np.zeros((nj, 3)), np.zeros(nr), np.zeros((nj, 3)),
                np.zeros(nr, np.bool_), np.zeros(1))


@nb.njit(cache=True, nogil=True, forceinline=True, **NO_REFCOUNT)
def _direct_into(chain, cfg, q, geo, v_free, p_warm, slip_ref, work, ws):
    """`project_direct` in the work arrays ``ws`` (`Work`): the velocity is
    written into ``ws.vn``, the impulses into ``ws.imp``; returns (count, residual)."""
    ja = chain.ja
    jb = chain.jb
    inv_m = chain.inv_m
    inv_i = chain.inv_i
    tol = cfg.tol
    mu = cfg.mu
    nj = ja.shape[0]
    v = ws.vn
    imp = ws.imp
    rows_j = ws.rows_j
    rows_k = ws.rows_k
    ja_rows = ws.ja_rows
    jb_rows = ws.jb_rows
    diag = ws.diag
    offset = ws.offset
    target = ws.target
    in_s = ws.in_s
    pw = ws.pw
    idx = ws.idx
    first = ws.first
    w_mat = ws.mat
    rhs = ws.rhs
    d = ws.d
    p = ws.p
    cnt = ws.cnt
    lst_i = ws.lst_i
    lst_side = ws.lst_side
    sa = ws.sa
    sb = ws.sb
    ha = ws.ha
    hb = ws.hb
    tg = ws.tg
    fac = ws.fac
    held = ws.held
    pw2 = ws.pw2
    pw3 = ws.pw3
    dinv = ws.dinv
    nrows = _rows_into(chain, q, geo, cfg.gap_tol, cfg.hold, p_warm, ws)
    for j in range(nj):
        imp[j, 0] = 0.0
        imp[j, 1] = 0.0
        imp[j, 2] = 0.0
    _targets_into(nrows, rows_j, rows_k, geo.gaps, offset, cfg.h_corr, slip_ref, target, ws.seen)
    if nrows == 0:
        _record_slip(0, rows_j, rows_k, ws.p, 0.0, ja_rows, jb_rows, slip_ref, ws)
        _copy3(v, v_free)
        ws.held[0] = 0
        if work.shape[0] > 0:
            work[0] = 0.0
        return 0, 0.0
    for r in range(nrows):
        pw[r] = p_warm[rows_j[r], rows_k[r]]
        in_s[r] = rows_k[r] == 2 or pw[r] > 0.0
    nbody = inv_m.shape[0]
    solves = 0
    fpiv = ws.fpiv
    factorised = False  # a set factorised in this step (its rows are this step's)
    accepted = False
    first_stale = False
    last_fac = False
    for _ in range(cfg.max_sets):
        solves += 1
        n = 0
        for r in range(nrows):
            if in_s[r]:
                idx[n] = r
                n += 1
        # the factor of the previous step's set, while the set holds and its matrix is
        # regular: the refinement's preconditioner (it reads the true residual with the
        # current rows); refactorised when it does not converge in REUSE_REFINEMENTS
        stale = n > 0 and solves == 1 and fac[0] == n
        if stale:
            for i in range(n):
                if fac[1 + i] != 3 * rows_j[idx[i]] + rows_k[idx[i]] or not fpiv[i]:
                    stale = False
                    break
        if solves == 1:
            first_stale = stale
        # the set held over the last steps: its impulses extrapolated from them (linearly
        # after two steps, quadratically after three)
        order = min(held[0] - 1, 2) if stale else 0
        # v_w and p: the previous impulses on S
        _copy3(v, v_free)
        for r in range(nrows):
            p[r] = pw[r] if in_s[r] else 0.0
            if in_s[r] and order == 2:
                p[r] = 3.0 * (pw[r] - pw2[rows_j[r], rows_k[r]]) + pw3[rows_j[r], rows_k[r]]
            elif in_s[r] and order == 1:
                p[r] = 2.0 * pw[r] - pw2[rows_j[r], rows_k[r]]
            if p[r] != 0.0:
                _apply_row(v, r, rows_j, ja, jb, ja_rows, jb_rows, p[r], inv_m, inv_i)
        last_fac = False
        converged = True  # an empty set: nothing to solve
        if n > 0:
            # W_SS + eps I in the envelope, factorised in place (lower triangle)
            dmax = 0.0
            for i in range(n):
                if diag[idx[i]] > dmax:
                    dmax = diag[idx[i]]
            eps = EPS_REG * dmax
            for i in range(n):
                # the set's rows packed in set order, for the refinement's inner loops
                r = idx[i]
                sa[i] = ja[rows_j[r]]
                sb[i] = jb[rows_j[r]]
                tg[i] = target[r]
                for c3 in range(3):
                    ha[i, c3] = ja_rows[r, c3]
                    hb[i, c3] = jb_rows[r, c3]
            ok = True
            converged = False
            r_first = 0.0
            while True:
                if not stale:
                    # a set of this step after the one factorised last: the factor's rows before
                    # the first changed row are that set's, the same numbers (a row of a Cholesky
                    # factor depends only on the rows before it), if the regularisation is too
                    start = 0
                    if factorised and eps == ws.feps[0]:
                        last = min(n, fac[0])
                        while start < last and \
                                fac[1 + start] == 3 * rows_j[idx[start]] + rows_k[idx[start]]:
                            start += 1
                    # W = sum over bodies c of H_c M_c^-1 H_c^T: the rows touching each body
                    for c in range(nbody):
                        cnt[c] = 0
                    for i in range(n):
                        r = idx[i]
                        j = rows_j[r]
                        if ja[j] >= 0:
                            c = ja[j]
                            lst_i[c, cnt[c]] = i
                            lst_side[c, cnt[c]] = 0
                            cnt[c] += 1
                        if jb[j] >= 0:
                            c = jb[j]
                            lst_i[c, cnt[c]] = i
                            lst_side[c, cnt[c]] = 1
                            cnt[c] += 1
                    # the envelope: row i meets the rows from the first one touching either of its
                    # bodies (the lists are in set order); only the envelope is cleared and read
                    for i in range(start, n):
                        f = i
                        if sa[i] >= 0 and lst_i[sa[i], 0] < f:
                            f = lst_i[sa[i], 0]
                        if sb[i] >= 0 and lst_i[sb[i], 0] < f:
                            f = lst_i[sb[i], 0]
                        first[i] = f
                        for k in range(f, i + 1):
                            w_mat[i, k] = 0.0
                    for c in range(nbody):
                        for u in range(cnt[c]):
                            i = lst_i[c, u]
                            if i < start:
                                continue
                            if lst_side[c, u] == 0:
                                h0, h1, h2 = ha[i, 0], ha[i, 1], ha[i, 2]
                            else:
                                h0, h1, h2 = hb[i, 0], hb[i, 1], hb[i, 2]
                            for u2 in range(cnt[c]):
                                k = lst_i[c, u2]
                                if k > i:
                                    continue
                                if lst_side[c, u2] == 0:
                                    g0, g1, g2 = ha[k, 0], ha[k, 1], ha[k, 2]
                                else:
                                    g0, g1, g2 = hb[k, 0], hb[k, 1], hb[k, 2]
                                w_mat[i, k] += (h0 * g0 + h1 * g1) * inv_m[c] + h2 * g2 * inv_i[c]
                    for i in range(start, n):
                        w_mat[i, i] += eps
                    ok = True
                    regular = True
                    for i in range(start):
                        if not fpiv[i]:
                            regular = False
                    for i in range(start, n):
                        for k in range(first[i], i + 1):
                            s = w_mat[i, k]
                            lo = first[i] if first[i] > first[k] else first[k]
                            for m in range(lo, k):
                                s -= w_mat[i, m] * w_mat[k, m]
                            if k == i:
                                if s <= 0.0:
                                    ok = False
                                    break
                                fpiv[i] = s >= REUSE_PIVOT * diag[idx[i]]
                                if not fpiv[i]:
                                    regular = False
                                w_mat[i, i] = math.sqrt(s)
                                dinv[i] = 1.0 / w_mat[i, i]
                            else:
                                w_mat[i, k] = s / w_mat[k, k]
                        if not ok:
                            break
                    if not ok:
                        fac[0] = -1
                        factorised = False
                        last_fac = False
                        break
                    factorised = True
                    fac[0] = n
                    for i in range(n):
                        fac[1 + i] = 3 * rows_j[idx[i]] + rows_k[idx[i]]
                    ws.feps[0] = eps
                    last_fac = regular
                # refine: the equality residual -H_S v, m/s, solved for the impulse increment
                converged = False
                for _ref in range(REUSE_REFINEMENTS if stale else REFINEMENTS):
                    big = 0.0
                    for i in range(n):
                        a = sa[i]
                        b = sb[i]
                        w = 0.0
                        if a >= 0:
                            w += ha[i, 0] * v[a, 0] + ha[i, 1] * v[a, 1] + ha[i, 2] * v[a, 2]
                        if b >= 0:
                            w += hb[i, 0] * v[b, 0] + hb[i, 1] * v[b, 1] + hb[i, 2] * v[b, 2]
                        rhs[i] = tg[i] - w
                        if abs(rhs[i]) > big:
                            big = abs(rhs[i])
                    if big <= tol:
                        converged = True
                        break
                    if stale:
                        if _ref == 0:
                            r_first = big
                        elif big * big > tol * r_first:
                            break  # contracting too slowly to reach tol: refactorise
                    if stale:
                        _envelope_solve_inv(w_mat, dinv, first, n, rhs, d)
                    else:
                        _envelope_solve(w_mat, first, n, rhs, d)
                    for i in range(n):
                        p[idx[i]] += d[i]
                        dp = d[i]
                        a = sa[i]
                        b = sb[i]
                        if a >= 0:
                            v[a, 0] += ha[i, 0] * dp * inv_m[a]
                            v[a, 1] += ha[i, 1] * dp * inv_m[a]
                            v[a, 2] += ha[i, 2] * dp * inv_i[a]
                        if b >= 0:
                            v[b, 0] += hb[i, 0] * dp * inv_m[b]
                            v[b, 1] += hb[i, 1] * dp * inv_m[b]
                            v[b, 2] += hb[i, 2] * dp * inv_i[b]
                if converged and stale:
                    last_fac = True
                if converged or not stale:
                    break
                # refactorise, and solve again from the previous impulses
                stale = False
                _copy3(v, v_free)
                for i in range(n):
                    p[idx[i]] = pw[idx[i]]
                    if pw[idx[i]] != 0.0:
                        _apply_row(v, idx[i], rows_j, ja, jb, ja_rows, jb_rows, pw[idx[i]], inv_m,
                                   inv_i)
            if not ok:
                break
        # the cone's conditions. A set whose refinement did not converge has no solution on it
        # (its rows over-determine the velocities: a closed arch with every corner active), and
        # its impulses grow along the matrix's near-null directions; the rows they turn negative
        # leave the set here, as any other's, rather than the step falling to Gauss-Seidel
        changed = False
        for r in range(nrows):
            if rows_k[r] == 2:
                continue
            if in_s[r]:
                if p[r] < -tol / diag[r]:
                    in_s[r] = False
                    changed = True
            elif _row_velocity(v, r, rows_j, ja, jb, ja_rows, jb_rows) < target[r] - tol:
                in_s[r] = True
                changed = True
        if not changed:
            accepted = converged
            break
    # the steps over which the factor's set has held, and the previous impulses
    if accepted and last_fac:
        held[0] = held[0] + 1 if (first_stale and solves == 1) else 1
    else:
        held[0] = 0
    for j in range(nj):
        pw3[j, 0] = pw2[j, 0]
        pw3[j, 1] = pw2[j, 1]
        pw3[j, 2] = pw2[j, 2]
        pw2[j, 0] = p_warm[j, 0]
        pw2[j, 1] = p_warm[j, 1]
        pw2[j, 2] = p_warm[j, 2]
    sweeps = 0
    change = 0.0
    sweep = False
    if accepted and mu > 0.0 and not _in_cone(nrows, rows_j, rows_k, p, diag, mu, tol):
        # a joint's tangential impulse outside its Coulomb cone: the joint slips. Gauss-Seidel
        # with the clamp, from the no-slip impulses clamped into the cones
        _clamp_to_cone(nrows, rows_j, rows_k, p, mu)
        sweep = True
    elif not accepted:
        # Gauss-Seidel from the previous step's impulses, not from the last set tried (after
        # many sets those can be far off, and the sweeps then take thousands of passes)
        for r in range(nrows):
            p[r] = pw[r]
            if rows_k[r] < 2 and p[r] < 0.0:
                p[r] = 0.0
        sweep = True
    if sweep:
        held[0] = 0
        _copy3(v, v_free)
        for r in range(nrows):
            if p[r] != 0.0:
                _apply_row(v, r, rows_j, ja, jb, ja_rows, jb_rows, p[r], inv_m, inv_i)
        sweeps, change = _pgs(chain, cfg, v, p, nrows, ws)
        _record_slip(nrows, rows_j, rows_k, p, mu, ja_rows, jb_rows, slip_ref, ws)
    else:
        _record_slip(nrows, rows_j, rows_k, p, 0.0, ja_rows, jb_rows, slip_ref, ws)
    for r in range(nrows):
        imp[rows_j[r], rows_k[r]] = p[r]
    if work.shape[0] > 0:
        work[0] = _correction_work(nrows, p, target)
    return solves + sweeps, change


@nb.njit(cache=True, inline="always")
def _joint_normal(r, rows_j, rows_k, p):
    """The normal impulse p_N0 + p_N1 (N s) of the joint of tangential row ``r``: the sum over
    the normal rows just before it (the rows are in joint order, normals first)."""
    j = rows_j[r]
    pn = 0.0
    s = r - 1
    while s >= 0 and rows_j[s] == j and rows_k[s] < 2:
        pn += p[s]
        s -= 1
    return pn


@nb.njit(cache=True, **NO_REFCOUNT)
def _in_cone(nrows, rows_j, rows_k, p, diag, mu, tol):
    """Every active joint's tangential impulse lies in its Coulomb cone, |p_T| <= mu p_N
    (p_N = p_N0 + p_N1, N s), to the solve's accuracy ``tol`` / W_TT (``tol`` m/s, W_TT the
    tangential row's Delassus diagonal): the no-slip solution then sticks at every joint, and
    satisfies Coulomb's law (`project_direct`)."""
    for r in range(nrows):
        if rows_k[r] == 2:
            pn = _joint_normal(r, rows_j, rows_k, p)
            if abs(p[r]) > mu * max(pn, 0.0) + tol / diag[r]:
                return False
    return True


@nb.njit(cache=True, **NO_REFCOUNT)
def _clamp_to_cone(nrows, rows_j, rows_k, p, mu):
    """Project the impulses ``p`` (nrows,) in place: normal ones to p_N >= 0, then each
    tangential one to |p_T| <= mu p_N of its joint (Gauss-Seidel's start after a failed stick
    test)."""
    for r in range(nrows):
        if rows_k[r] < 2 and p[r] < 0.0:
            p[r] = 0.0
    for r in range(nrows):
        if rows_k[r] == 2:
            bound = mu * _joint_normal(r, rows_j, rows_k, p)
            p[r] = min(max(p[r], -bound), bound)


@nb.njit(cache=True, nogil=True, forceinline=True, **NO_REFCOUNT)
def advance(chain, cfg, state, acc_k, ws, av_k):
    """One Moreau-Jean step of the `Chain` ``chain`` from ``state`` (`State`)
    under the mean ground acceleration ``acc_k`` (m/s^2) and the mean upward ground
    acceleration ``av_k`` (m/s^2, gravity reads g + av_k), with the settings ``cfg``
    (`Stepping`): steps 1-4 of the module docstring. ``state.slip_ref`` is updated in
    place; ``state.q``, ``state.v`` and ``state.p_warm`` are not changed: the caller sets
    v = vn, q = qm + h/2 vn (step 5) and the warm start. The step writes into ``ws``
    (`Work`, allocated once per run): ``ws.qm``, ``ws.gaps`` (at qm), ``ws.vf`` (v_free),
    ``ws.vn``, ``ws.imp`` (nj, 3) and ``ws.corr`` (the correction's work). Returns (sweeps,
    residual m/s).

    Compiled without numba's reference counting, and inlined by LLVM (``forceinline``) into
    the stepping loops (`_steps`, the verdict's), which are compiled without it too: in a loop
    that passes the packed tuples to a call, each step took and dropped a reference to each of
    their 52 arrays (104 atomic operations, 15 % of a step on Oppenheim's arch), and a call
    that is not inlined passes them flattened (a step 15 % slower). LLVM's inlining, not
    numba's (``inline="always"``), because numba's types the inlined body again in every
    caller: 60 of the 88 s the verdict's loop took to compile."""
    q = state.q
    v = state.v
    h = cfg.h
    nb_ = q.shape[0]
    qm = ws.qm
    vf = ws.vf
    for i in range(nb_):
        for c in range(3):
            qm[i, c] = q[i, c] + 0.5 * h * v[i, c]
    geometry_into(qm, chain.ja, chain.jb, chain.arm_a, chain.arm_b, chain.n0, chain.t0, ws.gaps,
                  ws.nrm, ws.tan, ws.pts, ws.trig)
    _copy3(vf, v)
    for i in range(nb_):
        vf[i, 0] -= h * acc_k
        vf[i, 1] -= h * (cfg.g + av_k)
    geo = Geometry(ws.gaps, ws.nrm, ws.tan, ws.pts)
    if cfg.method == METHOD_DIRECT:
        sweeps, res = _direct_into(chain, cfg, qm, geo, vf, state.p_warm, state.slip_ref, ws.corr,
                                   ws)
    else:
        sweeps, res = _project_into(chain, cfg, qm, geo, vf, state.p_warm, state.slip_ref,
                                    ws.corr, ws)
    return sweeps, res


@nb.njit(cache=True)
def run(chain, cfg, state, acc, vacc, record, diag):
    """Advance ``acc.shape[0]`` steps (``acc[k]``: the mean ground acceleration over step k,
    m/s^2; ``vacc[k]``: the mean upward ground acceleration, or ``vacc`` empty for none; the
    input work counts both) of the `Chain` ``chain`` with the settings ``cfg`` (`Stepping`; its
    ``h_corr`` and ``hold``: the position-level correction, module docstring; 0: the
    velocity-level scheme alone, as the event integrator's stepping windows), writing q, v,
    diagnostics after every ``record.out_every`` steps into row ``k // out_every`` of
    ``record``'s arrays (`Record`). ``state`` (`State`) and ``diag`` (the running
    D_* values) are updated in place. Returns the number of sweeps of the worst step."""
    return _steps(chain, cfg, state, acc, vacc, record, diag,
                  workspace(chain.mass.shape[0], chain.ja.shape[0]))


@nb.njit(cache=True, **NO_REFCOUNT)
def _steps(chain, cfg, state, acc, vacc, record, diag, ws):
    """`run`'s loop, in the work arrays ``ws`` (`workspace`): compiled without reference
    counting (`advance`), so it allocates nothing."""
    q = state.q
    v = state.v
    p_warm = state.p_warm
    mass = chain.mass
    inertia = chain.inertia
    h = cfg.h
    g = cfg.g
    out_every = record.out_every
    nb_ = mass.shape[0]
    nj = chain.ja.shape[0]
    worst = 0
    vf = ws.vf
    vn = ws.vn
    imp = ws.imp
    gaps = ws.gaps
    qm = ws.qm
    m_max = mass[0]
    for i in range(1, nb_):
        m_max = max(m_max, mass[i])
    vertical = vacc.shape[0] > 0
    for k in range(acc.shape[0]):
        av = vacc[k] if vertical else 0.0
        sweeps, res = advance(chain, cfg, state, acc[k], ws, av)
        t_free = 0.0
        t_new = 0.0
        w_in = 0.0
        for i in range(nb_):
            t_free += mass[i] * (vf[i, 0] ** 2 + vf[i, 1] ** 2) + inertia[i] * vf[i, 2] ** 2
            t_new += mass[i] * (vn[i, 0] ** 2 + vn[i, 1] ** 2) + inertia[i] * vn[i, 2] ** 2
            w_in -= acc[k] * mass[i] * 0.5 * h * (v[i, 0] + vn[i, 0])
            if vertical:
                w_in -= av * mass[i] * 0.5 * h * (v[i, 1] + vn[i, 1])
        diag[D_DISSIPATED] += 0.5 * (t_free - t_new)
        diag[D_CORRECTION] += ws.corr[0]
        diag[D_INPUT] += w_in
        # the contacts' work on the step's mean velocity: H^T p = M (v_k+1 - v_free)
        w_c = 0.0
        for i in range(nb_):
            w_c += 0.5 * (mass[i] * ((vn[i, 0] - vf[i, 0]) * (v[i, 0] + vn[i, 0])
                                     + (vn[i, 1] - vf[i, 1]) * (v[i, 1] + vn[i, 1]))
                          + inertia[i] * (vn[i, 2] - vf[i, 2]) * (v[i, 2] + vn[i, 2]))
        diag[D_CONTACT_WORK] -= w_c
        for j in range(nj):
            pt = ws.slip_p[j]
            if pt != 0.0:
                a = chain.ja[j]
                b = chain.jb[j]
                w_t = 0.0
                if a >= 0:
                    for c in range(3):
                        w_t += ws.t_ja[j, c] * 0.5 * (v[a, c] + vn[a, c])
                if b >= 0:
                    for c in range(3):
                        w_t += ws.t_jb[j, c] * 0.5 * (v[b, c] + vn[b, c])
                diag[D_FRICTION_WORK] -= pt * w_t
        for j in range(nj):
            for c in range(2):
                if -gaps[j, c] > diag[D_PENETRATION]:
                    diag[D_PENETRATION] = -gaps[j, c]
            pn = imp[j, 0] + imp[j, 1]
            if pn > 0.0 and pn > 1e-12 * h * g * m_max:
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
        for i in range(nb_):
            for c in range(3):
                v[i, c] = vn[i, c]
                q[i, c] = qm[i, c] + 0.5 * h * vn[i, c]
        if (k + 1) % out_every == 0:
            row = (k + 1) // out_every - 1
            for i in range(nb_):
                for c in range(3):
                    record.q[row, i, c] = q[i, c]
                    record.v[row, i, c] = v[i, c]
            for c in range(diag.shape[0]):
                record.diag[row, c] = diag[c]
            diag[D_PENETRATION] = 0.0
            diag[D_FRICTION] = 0.0
            diag[D_ITERATIONS] = 0.0
            diag[D_RESIDUAL] = 0.0
    return worst
