"""Compiled event-driven integrator of the rigid-block chain (numba).

The same model as `archquake.rigid._step_kernels` (rigid voussoirs, unilateral
plastic corner contacts, no sliding), integrated between contact changes as an ODE in the
joints' relative rotations instead of by Moreau-Jean steps.

**Coordinates.** With no sliding, a joint is either *locked* (faces together: the two blocks
keep their undisplaced relative pose) or a *hinge* turning about one of its corners. So the
configuration is the relative rotation beta_j of each joint (right block minus left block,
counter-clockwise), joint j turning about corner 0 when ``beta_j sg_j > 0`` and corner 1 when
``beta_j sg_j < 0`` (``sg_j = t_j x n_j``, corner 1 is where corner 0's rotation opens the
gap). Between events the set of hinges (K of them, joint ``jh[k]``, pivot ``ch[k]``) is fixed,
the blocks between two consecutive hinges form one rigid link, and the chain closes on the
right springing: three holonomic constraints (rotation and position of the last link), so the
motion has K - 3 degrees of freedom (1 for four hinges, 2 for five). A chain whose last block
is free (a block on its base: no joint n) has no closure, K degrees of freedom and mu = 0.

**Equations.** Link k (after hinges 0..k-1) turns by Theta_k = sum beta_i and a point X on it
moves with v = sum_{i<k} beta_i' J (X - P_i) (P_i the current pivots, J the rotation by +90
deg). Kane's equations with the closure's multipliers mu (the wrench of the right springing on
the last link, moment about the material point that started at the origin, then force):

    M(beta) beta'' - C^T mu = Q - c,      C beta'' = -b_C,

M_il = sum_{k > max(i, l)} m_k (G_k - P_i).(G_k - P_l) + I_k, Q_i = sum_{k > i} m_k a_e .
J(G_k - P_i) (a_e = (-x_g'', -g), the load per unit mass in the ground's frame), c the
velocity-product terms, C the closure's Jacobian; a (K + 3) dense solve per evaluation.
Integrated by Dormand-Prince 5(4) with error control, never across a breakpoint of the ground
motion; the closure drift is projected out after every step.

**Events**, located on the step's cubic Hermite interpolant and then reached by a step that
ends on them:

* *closure*: a hinge's opening angle phi = +-beta returns to zero: a plastic impact, solved in
  full coordinates as the time stepper solves it, the kinetic-metric projection of the
  velocities onto the cone of the contacts touching (`_step_kernels.project_direct`);
  the joints whose relative rotation rate after it is nonzero are the new hinges;
* *opening*: the normal force of a corner of a locked joint (from the joint's force and moment,
  by statics of the links right of it and the springing's wrench) reaches zero: the joint
  becomes a hinge about its other corner with zero rate (kinetic energy continuous);
* *onset* from the locked, undisplaced arch: when the load leaves the safe domain
  (|x_g''| > lambda_+- g, found once per arch by the driver); the hinges are those of the
  Gauss projection of the free acceleration onto the cone (the acceleration-level form of the
  same projection).

What this integrator does not model, it reports and stops (``STATUS_FALLBACK``), and the driver
continues with the time stepper: a hinge whose reaction becomes tensile (flight), a joint that
separates at an impact, an opening whose hinge turns the wrong way, or more than
``CHATTER_EVENTS`` events within ``CHATTER_WINDOW`` s. It resumes from the stepper's state
only once no joint is open on both corners (the flight is over).

SI units throughout.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

import archquake._dopri as DP  # the Dormand-Prince 5(4) tableau
import archquake.rigid._step_kernels as RK
from archquake.blocks._kernels import collapsed
from archquake.ground._kernel import ground_in_piece, next_breakpoint, vertical_in_piece

#: Most hinges a mode may have.
MAX_HINGES = 24

# statuses
STATUS_DONE = 0  # reached t_end
STATUS_COLLAPSE = 1  # an output sample met a collapse criterion
STATUS_REST = 2  # at rest after the excitation (the remaining samples are the rest state)
STATUS_FALLBACK = 3  # a situation this integrator does not model (module docstring)

# fallback reasons
WHY_NONE = 0
WHY_TENSILE_HINGE = 1
WHY_SEPARATION = 2
WHY_WRONG_WAY = 3
WHY_CHATTER = 4
WHY_SINGULAR = 5
WHY_TOO_MANY_HINGES = 6

# counters
N_STEPS = 0
N_REJECTED = 1
N_EVALS = 2
N_CLOSURES = 3
N_OPENINGS = 4
N_ONSETS = 5
N_RELOCKS = 6
N_LOG = 7
N_ZENO = 8
N_SOLVES = 9  # factorised active sets and Gauss-Seidel sweeps of the impacts
N_COUNTERS = 10

# diagnostics (running)
E_DISSIPATED = 0  # J, energy removed by the impacts (and the drift projections)
E_INPUT = 1  # J, work of the inertial load on the relative motion
E_FRICTION = 2  # -, largest |V| / N at a joint in contact since the last sample
E_MAX_DRIFT = 3  # m, largest closure drift corrected
N_E = 4

#: A joint closing ``ZENO_CLOSURES`` times in a row at shrinking intervals, each shorter than
#: ``ZENO_WINDOW`` sqrt(L/g), stays closed (the accumulation point of the sequence).
ZENO_CLOSURES = 3
ZENO_WINDOW = 0.01
#: Active sets the exact impact solve may try before Gauss-Seidel (its guess: every touching
#: corner pushes, and an impact releases many of them).
IMPACT_ACTIVE_SETS = 30
#: Gauss-Seidel sweeps the contact solves (onset and impacts) may run after their active sets.
SOLVE_SWEEPS = 100_000
#: Resuming from block positions: a joint open by more than RESUME_GAP L is a hinge; a closed
#: joint whose corners move at more than RESUME_SPEED sqrt(g L) relative to each other too.
RESUME_GAP = 1.0e-7
RESUME_SPEED = 1.0e-6
#: ... and a joint whose corners are both open by more than RESUME_SEPARATION L has separated
#: (flight; the stepper's contact drift is below 2e-7 L): the time stepper goes on.
RESUME_SEPARATION = 1.0e-6
#: Events within this window (s) ...
CHATTER_WINDOW = 1.0e-3
#: ... more than this many: fallback.
CHATTER_EVENTS = 60


class Chain(NamedTuple):
    """The packed arrays of the chain that `run` reads and never writes, assembled once
    per run (`archquake.rigid.events.EventModel`).

    Blocks (n of them, in chain order): ``X0`` (n, 2) undisplaced centroids, m; ``mb``, ``ib``
    masses (kg) and inertias (kg m^2); prefix sums from the left ``S0`` (n + 1,) of the mass,
    kg, ``S1`` (n + 1, 2) of m X, kg m, ``S2`` (n + 1,) of m |X|^2 + I, kg m^2. Joints (nj):
    ``p0`` (nj, 2, 2) undisplaced corners, m; ``n0``, ``t0`` (nj, 2) normals and tangents;
    ``hw`` half-widths, m; ``sg`` = t x n (+-1); ``ja``, ``jb`` the blocks on either side (-1:
    a springing); ``arm_a``, ``arm_b`` the corners from those blocks' centroids, m (as the
    time stepper's `archquake.rigid._step_kernels` reads them). ``free_blocks`` and ``free``: the
    blocks the collapse criterion reads, and 1 for each movable block. ``cpar``: the collapse
    criterion's parameters (`archquake.blocks._kernels.collapsed`). ``lref``: the chain's
    reference length L, m (the radius of a circular arch).
    """

    X0: np.ndarray
    mb: np.ndarray
    ib: np.ndarray
    S0: np.ndarray
    S1: np.ndarray
    S2: np.ndarray
    p0: np.ndarray
    n0: np.ndarray
    t0: np.ndarray
    hw: np.ndarray
    sg: np.ndarray
    ja: np.ndarray
    jb: np.ndarray
    arm_a: np.ndarray
    arm_b: np.ndarray
    free_blocks: np.ndarray
    free: np.ndarray
    cpar: np.ndarray
    lref: float


class Span(NamedTuple):
    """What one call of `run` integrates: the ground motion (``kind``, ``gp``: its
    compiled description, `archquake.ground.GroundMotion.kernel_spec`), gravity ``g``
    (m/s^2), the end ``t_end`` (s) and the excitation's end ``t_exc_end`` (s); the onset
    thresholds ``lam_pos``, ``lam_neg`` (m/s^2, the ground acceleration that moves the locked
    arch either way); the error control ``rtol``, ``atol`` and largest step ``h_max`` (s); the
    sample interval ``dt_out`` (s); whether to stop at the first collapsed sample, and whether
    to resume from the block state (``State.fq``, ``State.fv``) first."""

    kind: int
    gp: np.ndarray
    g: float
    t_end: float
    t_exc_end: float
    lam_pos: float
    lam_neg: float
    rtol: float
    atol: float
    h_max: float
    dt_out: float
    stop_at_collapse: bool
    resume: bool


class State(NamedTuple):
    """The state `run` reads and updates in place: ``st`` = [K, jh, ch] (the hinge set),
    ``y`` = (beta, beta', W_in), ``tt`` (1,) the time (s); ``counters`` (N_COUNTERS), ``diag``
    (N_E); ``fq``, ``fv`` (n, 3) the block positions and velocities handed to and from the time
    stepper; ``log`` (rows, 4) the event log; ``state_all`` (n, 6) work array of the collapse
    criterion."""

    st: np.ndarray
    y: np.ndarray
    tt: np.ndarray
    counters: np.ndarray
    diag: np.ndarray
    fq: np.ndarray
    fv: np.ndarray
    log: np.ndarray
    state_all: np.ndarray


class Links(NamedTuple):
    """The links of the current hinge set (`link_properties`, updated in place at each
    change): mass ``lm`` (MAX_HINGES + 1,) kg, centroid ``lg0`` (MAX_HINGES + 1, 2) m and
    inertia ``li`` kg m^2 of each; ``closed``: the chain ends on a second springing."""

    lm: np.ndarray
    lg0: np.ndarray
    li: np.ndarray
    closed: bool


class Output(NamedTuple):
    """The samples `run` writes: block positions ``q`` and velocities ``v`` (cap, n, 3)
    and energies ``e`` (cap, 5: kinetic, potential, dissipated, input work (J), friction
    demand)."""

    q: np.ndarray
    v: np.ndarray
    e: np.ndarray


@nb.njit(cache=True)
def _jx(ux, uy):
    """J u: u turned by +90 degrees."""
    return -uy, ux


@nb.njit(cache=True)
def link_properties(K, jh, n, S0, S1, S2, lm, lg0, li, lstart):
    """Mass (kg), undisplaced centroid (m) and centroidal inertia (kg m^2) of links 0..K, and
    their first blocks (``lstart[k]``, ``lstart[K + 1] = n``), from the prefix sums."""
    lstart[0] = 0
    for k in range(K):
        lstart[k + 1] = jh[k]
    lstart[K + 1] = n
    for k in range(K + 1):
        a = lstart[k]
        b = lstart[k + 1]
        m = S0[b] - S0[a]
        lm[k] = m
        if m > 0.0:
            gx = (S1[b, 0] - S1[a, 0]) / m
            gy = (S1[b, 1] - S1[a, 1]) / m
            lg0[k, 0] = gx
            lg0[k, 1] = gy
            li[k] = (S2[b] - S2[a]) - m * (gx * gx + gy * gy)
        else:
            lg0[k, 0] = 0.0
            lg0[k, 1] = 0.0
            li[k] = 0.0


@nb.njit(cache=True)
def kinematics(K, jh, ch, beta, bdot, p0, lg0, th, dd, P, vP, G, om, vG):
    """Link rotations ``th`` and translations ``dd`` (T_k(x) = R(th_k) x + dd_k), current pivots
    ``P`` and their velocities ``vP``, link centroids ``G``, their velocities ``vG`` and the
    links' angular velocities ``om``; links 0..K."""
    th[0] = 0.0
    dd[0, 0] = 0.0
    dd[0, 1] = 0.0
    for i in range(K):
        px = p0[jh[i], ch[i], 0]
        py = p0[jh[i], ch[i], 1]
        c = math.cos(th[i])
        s = math.sin(th[i])
        P[i, 0] = c * px - s * py + dd[i, 0]
        P[i, 1] = s * px + c * py + dd[i, 1]
        th[i + 1] = th[i] + beta[i]
        c = math.cos(th[i + 1])
        s = math.sin(th[i + 1])
        dd[i + 1, 0] = P[i, 0] - (c * px - s * py)
        dd[i + 1, 1] = P[i, 1] - (s * px + c * py)
    for k in range(K + 1):
        c = math.cos(th[k])
        s = math.sin(th[k])
        G[k, 0] = c * lg0[k, 0] - s * lg0[k, 1] + dd[k, 0]
        G[k, 1] = s * lg0[k, 0] + c * lg0[k, 1] + dd[k, 1]
    om[0] = 0.0
    for k in range(1, K + 1):
        om[k] = om[k - 1] + bdot[k - 1]
    for i in range(K):
        vx = 0.0
        vy = 0.0
        for l_ in range(i):
            jx, jy = _jx(P[i, 0] - P[l_, 0], P[i, 1] - P[l_, 1])
            vx += bdot[l_] * jx
            vy += bdot[l_] * jy
        vP[i, 0] = vx
        vP[i, 1] = vy
    for k in range(K + 1):
        vx = 0.0
        vy = 0.0
        for i in range(k):
            jx, jy = _jx(G[k, 0] - P[i, 0], G[k, 1] - P[i, 1])
            vx += bdot[i] * jx
            vy += bdot[i] * jy
        vG[k, 0] = vx
        vG[k, 1] = vy


@nb.njit(cache=True)
def _solve(A, r, m):
    """Solve A[:m, :m] z = r[:m] in place (Gaussian elimination, partial pivoting); False if
    singular."""
    for col in range(m):
        piv = col
        big = abs(A[col, col])
        for row in range(col + 1, m):
            if abs(A[row, col]) > big:
                big = abs(A[row, col])
                piv = row
        if big == 0.0 or not math.isfinite(big):
            return False
        if piv != col:
            for c_ in range(m):
                tmp = A[col, c_]
                A[col, c_] = A[piv, c_]
                A[piv, c_] = tmp
            tmp = r[col]
            r[col] = r[piv]
            r[piv] = tmp
        inv = 1.0 / A[col, col]
        for row in range(col + 1, m):
            f = A[row, col] * inv
            if f != 0.0:
                for c_ in range(col, m):
                    A[row, c_] -= f * A[col, c_]
                r[row] -= f * r[col]
    for row in range(m - 1, -1, -1):
        acc = r[row]
        for c_ in range(row + 1, m):
            acc -= A[row, c_] * r[c_]
        r[row] = acc / A[row, row]
    return True


@nb.njit(cache=True)
def _link_accelerations(K, P, G, bdd, al, aG):
    """The links' angular accelerations ``al`` and their centroids' accelerations (``aG``, which
    holds their velocity-product part on entry)."""
    al[0] = 0.0
    for k in range(1, K + 1):
        al[k] = al[k - 1] + bdd[k - 1]
    for k in range(K + 1):
        for i in range(k):
            jx, jy = _jx(G[k, 0] - P[i, 0], G[k, 1] - P[i, 1])
            aG[k, 0] += bdd[i] * jx
            aG[k, 1] += bdd[i] * jy


@nb.njit(cache=True)
def _kkt_matrix(K, P, G, dd, lm, li, A, r, closed):
    """The KKT matrix of the links (after `kinematics`): the generalised mass
    M_il = sum_{k > max(i, l)} m_k (G_k - P_i).(G_k - P_l) + I_k in A[:K, :K] and, for a
    closed chain, the closure's Jacobian C (the last link's rotation and the velocity of its
    material point X = dd[K]) as [[M, -C^T], [C, 0]]; r zeroed. Returns the system's size."""
    m_ = K + 3 if closed else K
    for i in range(m_):
        r[i] = 0.0
        for l_ in range(m_):
            A[i, l_] = 0.0
    for i in range(K):
        for l_ in range(i, K):
            s = 0.0
            for k in range(max(i, l_) + 1, K + 1):
                s += lm[k] * ((G[k, 0] - P[i, 0]) * (G[k, 0] - P[l_, 0])
                              + (G[k, 1] - P[i, 1]) * (G[k, 1] - P[l_, 1])) + li[k]
            A[i, l_] = s
            A[l_, i] = s
    if closed:
        for i in range(K):
            jx, jy = _jx(dd[K, 0] - P[i, 0], dd[K, 1] - P[i, 1])
            A[K, i] = 1.0
            A[K + 1, i] = jx
            A[K + 2, i] = jy
            A[i, K] = -1.0
            A[i, K + 1] = -jx
            A[i, K + 2] = -jy
    return m_


@nb.njit(cache=True)
def dynamics(K, jh, ch, beta, bdot, p0, lm, lg0, li, ax, g, ws, closed):
    """Accelerations beta'' (``ws[11]``), the springing's wrench ``ws[12]`` and the kinematic
    quantities in ``ws`` (`workspace`) for load ``ax`` (x_g'', m/s^2); ``closed``: the
    chain ends on a springing (else its last link is free and mu = 0). Returns False if the
    KKT system is singular."""
    th, dd, P, vP, G, om, vG, aG, al, A, r, bdd, mu = ws
    kinematics(K, jh, ch, beta, bdot, p0, lg0, th, dd, P, vP, G, om, vG)
    # velocity-product part of each link centroid's acceleration (beta'' = 0)
    for k in range(K + 1):
        bx = 0.0
        by = 0.0
        for i in range(k):
            jx, jy = _jx(vG[k, 0] - vP[i, 0], vG[k, 1] - vP[i, 1])
            bx += bdot[i] * jx
            by += bdot[i] * jy
        aG[k, 0] = bx
        aG[k, 1] = by
    aex = -ax
    aey = -g
    m_ = _kkt_matrix(K, P, G, dd, lm, li, A, r, closed)
    for i in range(K):
        qi = 0.0
        ci = 0.0
        for k in range(i + 1, K + 1):
            jx, jy = _jx(G[k, 0] - P[i, 0], G[k, 1] - P[i, 1])
            qi += lm[k] * (aex * jx + aey * jy)
            ci += lm[k] * (aG[k, 0] * jx + aG[k, 1] * jy)
        r[i] = qi - ci
    if not closed:
        if not _solve(A, r, m_):
            return False
        for i in range(K):
            bdd[i] = r[i]
        mu[0] = 0.0
        mu[1] = 0.0
        mu[2] = 0.0
        _link_accelerations(K, P, G, bdd, al, aG)
        return True
    # the closure's velocity-product terms: the last link's material point X = dd[K]
    xx = dd[K, 0]
    xy = dd[K, 1]
    vxx = 0.0
    vxy = 0.0
    for i in range(K):
        jx, jy = _jx(xx - P[i, 0], xy - P[i, 1])
        vxx += bdot[i] * jx
        vxy += bdot[i] * jy
    bcx = 0.0
    bcy = 0.0
    for i in range(K):
        kx, ky = _jx(vxx - vP[i, 0], vxy - vP[i, 1])
        bcx += bdot[i] * kx
        bcy += bdot[i] * ky
    r[K] = 0.0
    r[K + 1] = -bcx
    r[K + 2] = -bcy
    if not _solve(A, r, m_):
        return False
    for i in range(K):
        bdd[i] = r[i]
    mu[0] = r[K]
    mu[1] = r[K + 1]
    mu[2] = r[K + 2]
    _link_accelerations(K, P, G, bdd, al, aG)
    return True


@nb.njit(cache=True)
def workspace(nh):
    """Scratch arrays of `dynamics`, sized for ``nh`` hinges: (th, dd, P, vP, G, om, vG,
    aG, al, A, r, bdd, mu)."""
    return (np.zeros(nh + 1), np.zeros((nh + 1, 2)), np.zeros((nh, 2)), np.zeros((nh, 2)),
            np.zeros((nh + 1, 2)), np.zeros(nh + 1), np.zeros((nh + 1, 2)),
            np.zeros((nh + 1, 2)), np.zeros(nh + 1), np.zeros((nh + 3, nh + 3)),
            np.zeros(nh + 3), np.zeros(nh), np.zeros(3))


@nb.njit(cache=True)
def _link_of(K, jh, b):
    """The link of block ``b``: the number of hinges at joints <= b."""
    k = 0
    while k < K and jh[k] <= b:
        k += 1
    return k


@nb.njit(cache=True)
def joint_forces(chain, K, jh, ch, ws, ax, g, out):
    """Every joint's force from its left part on its right part, after `dynamics` (the
    `Chain` ``chain``, the hinge set ``K``, ``jh``, ``ch``, ground acceleration ``ax`` and
    gravity ``g``, m/s^2):
    ``out[j] = (f0, f1, N, V)`` (``out`` has a row per joint: n + 1 for a closed chain, n for
    an open one) N, the corner normal forces of a locked joint (f0 + f1 = N) or,
    at a hinge, (nan, nan, N, V); V the shear."""
    th, dd, P, vP, G, om, vG, aG, al, A, r, bdd, mu = ws
    X0 = chain.X0
    mb = chain.mb
    ib = chain.ib
    p0 = chain.p0
    n0 = chain.n0
    hw = chain.hw
    sg = chain.sg
    n = X0.shape[0]
    fx = -mu[1]
    fy = -mu[2]
    xx = dd[K, 0]
    xy = dd[K, 1]
    mo = -(mu[0] + xx * mu[2] - xy * mu[1])
    aex = -ax
    aey = -g
    hi = K - 1
    nj = out.shape[0]
    for j in range(n, -1, -1):
        if j >= nj:
            pass  # an open chain: no joint after the last block
        elif hi >= 0 and jh[hi] == j:
            tm = 0.5 * (th[hi] + th[hi + 1])
            c = math.cos(tm)
            s = math.sin(tm)
            nx = c * n0[j, 0] - s * n0[j, 1]
            ny = s * n0[j, 0] + c * n0[j, 1]
            out[j, 0] = math.nan
            out[j, 1] = math.nan
            out[j, 2] = fx * nx + fy * ny
            out[j, 3] = fx * ny - fy * nx
            hi -= 1
        else:
            k = hi + 1
            c = math.cos(th[k])
            s = math.sin(th[k])
            nx = c * n0[j, 0] - s * n0[j, 1]
            ny = s * n0[j, 0] + c * n0[j, 1]
            cx = c * p0[j, 0, 0] - s * p0[j, 0, 1] + dd[k, 0]
            cy = s * p0[j, 0, 0] + c * p0[j, 0, 1] + dd[k, 1]
            nn = fx * nx + fy * ny
            mc0 = mo - (cx * fy - cy * fx)
            f1 = mc0 / (2.0 * hw[j] * sg[j])
            out[j, 0] = nn - f1
            out[j, 1] = f1
            out[j, 2] = nn
            out[j, 3] = fx * ny - fy * nx
        if j > 0:
            b = j - 1
            k = hi + 1  # hinges left of joint j: blocks up to the next hinge are in link hi + 1
            c = math.cos(th[k])
            s = math.sin(th[k])
            bx = c * X0[b, 0] - s * X0[b, 1] + dd[k, 0]
            by = s * X0[b, 0] + c * X0[b, 1] + dd[k, 1]
            rx = bx - G[k, 0]
            ry = by - G[k, 1]
            jx, jy = _jx(rx, ry)
            w2 = om[k] * om[k]
            abx = aG[k, 0] + al[k] * jx - w2 * rx - aex
            aby = aG[k, 1] + al[k] * jy - w2 * ry - aey
            fx += mb[b] * abx
            fy += mb[b] * aby
            mo += mb[b] * (bx * aby - by * abx) + ib[b] * al[k]


@nb.njit(cache=True)
def margins(K, jh, ch, forces, n, weight, skip):
    """(least corner force of a locked joint / W, its joint, the corner that unloads; least hinge
    reaction / W, its hinge index; largest |V| / N of a joint in compression). Joints with
    ``skip[j]`` are ignored (a hinge just closed whose force is at its tie)."""
    lo = math.inf
    lj = -1
    lc = -1
    ho = math.inf
    hk = -1
    fr = 0.0
    hi = 0
    for j in range(forces.shape[0]):
        nn = forces[j, 2]
        if nn > 1e-12 * weight:
            v = abs(forces[j, 3]) / nn
            if v > fr:
                fr = v
        if hi < K and jh[hi] == j:
            if nn / weight < ho:
                ho = nn / weight
                hk = hi
            hi += 1
            continue
        if skip[j]:
            continue
        for c in range(2):
            if forces[j, c] / weight < lo:
                lo = forces[j, c] / weight
                lj = j
                lc = c
    return lo, lj, lc, ho, hk, fr


@nb.njit(cache=True)
def rhs(K, jh, ch, y, p0, lm, lg0, li, ax, g, ws, ydot, closed, av):
    """dy/dt for y = (beta, beta', W_in): False if singular. ``av``: the upward ground
    acceleration (m/s^2): the links move under gravity g + av, and W_in counts its work."""
    ok = dynamics(K, jh, ch, y[:K], y[K:2 * K], p0, lm, lg0, li, ax, g + av, ws, closed)
    bdd = ws[11]
    vG = ws[6]
    for i in range(K):
        ydot[i] = y[K + i]
        ydot[K + i] = bdd[i]
    pw = 0.0
    for k in range(1, K + 1):
        pw -= ax * lm[k] * vG[k, 0]
    if av != 0.0:  # the vertical's work (without one, W_in as before to the bit)
        for k in range(1, K + 1):
            pw -= av * lm[k] * vG[k, 1]
    ydot[2 * K] = pw
    return ok


@nb.njit(cache=True)
def dopri_step(K, jh, ch, t, h, y, f0, p0, links, span, ws, ks, y1, f1):
    """One Dormand-Prince step from (t, y) with derivative f0: y1, f1 = f(t + h, y1) (the
    ground motion, ``g``, ``rtol`` and ``atol`` of the `Span` ``span``; ``links`` the
    `Links`; ``ks`` the stages' work arrays, six of 2 MAX_HINGES + 1); returns the error norm
    (<= 1 accepts), or inf if an evaluation was singular."""
    m = 2 * K + 1
    k2, k3, k4, k5, k6, ytmp = ks[0], ks[1], ks[2], ks[3], ks[4], ks[5]
    lm, lg0, li, closed = links
    kind = span.kind
    gp = span.gp
    g = span.g
    rtol = span.rtol
    atol = span.atol
    ok = True
    for i in range(m):
        ytmp[i] = y[i] + h * DP.A21 * f0[i]
    ok &= rhs(K, jh, ch, ytmp, p0, lm, lg0, li, ground_in_piece(kind, gp, t + DP.C2 * h, t), g, ws,
              k2, closed, vertical_in_piece(kind, gp, t + DP.C2 * h, t))
    for i in range(m):
        ytmp[i] = y[i] + h * (DP.A31 * f0[i] + DP.A32 * k2[i])
    ok &= rhs(K, jh, ch, ytmp, p0, lm, lg0, li, ground_in_piece(kind, gp, t + DP.C3 * h, t), g, ws,
              k3, closed, vertical_in_piece(kind, gp, t + DP.C3 * h, t))
    for i in range(m):
        ytmp[i] = y[i] + h * (DP.A41 * f0[i] + DP.A42 * k2[i] + DP.A43 * k3[i])
    ok &= rhs(K, jh, ch, ytmp, p0, lm, lg0, li, ground_in_piece(kind, gp, t + DP.C4 * h, t), g, ws,
              k4, closed, vertical_in_piece(kind, gp, t + DP.C4 * h, t))
    for i in range(m):
        ytmp[i] = y[i] + h * (DP.A51 * f0[i] + DP.A52 * k2[i] + DP.A53 * k3[i] + DP.A54 * k4[i])
    ok &= rhs(K, jh, ch, ytmp, p0, lm, lg0, li, ground_in_piece(kind, gp, t + DP.C5 * h, t), g, ws,
              k5, closed, vertical_in_piece(kind, gp, t + DP.C5 * h, t))
    for i in range(m):
        ytmp[i] = y[i] + h * (DP.A61 * f0[i] + DP.A62 * k2[i] + DP.A63 * k3[i] + DP.A64 * k4[i]
                              + DP.A65 * k5[i])
    ok &= rhs(K, jh, ch, ytmp, p0, lm, lg0, li, ground_in_piece(kind, gp, t + h, t), g, ws, k6, closed,
              vertical_in_piece(kind, gp, t + h, t))
    for i in range(m):
        y1[i] = y[i] + h * (DP.B1 * f0[i] + DP.B3 * k3[i] + DP.B4 * k4[i] + DP.B5 * k5[i] + DP.B6 * k6[i])
    ok &= rhs(K, jh, ch, y1, p0, lm, lg0, li, ground_in_piece(kind, gp, t + h, t), g, ws, f1, closed,
              vertical_in_piece(kind, gp, t + h, t))
    if not ok:
        return math.inf
    err = 0.0
    for i in range(2 * K):
        e = h * (DP.E1 * f0[i] + DP.E3 * k3[i] + DP.E4 * k4[i] + DP.E5 * k5[i] + DP.E6 * k6[i]
                 + DP.E7 * f1[i])
        sc = atol + rtol * max(abs(y[i]), abs(y1[i]))
        err += (e / sc) ** 2
    return math.sqrt(err / max(1, 2 * K))


@nb.njit(cache=True)
def hermite(y0, f0, y1, f1, t0, h, t, m, out):
    """Cubic Hermite interpolant of the step at t (first m components)."""
    s = (t - t0) / h
    h00 = (1.0 + 2.0 * s) * (1.0 - s) ** 2
    h10 = s * (1.0 - s) ** 2
    h01 = s * s * (3.0 - 2.0 * s)
    h11 = s * s * (s - 1.0)
    for i in range(m):
        out[i] = h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i]


@nb.njit(cache=True)
def project_closure(K, jh, ch, y, pinned, p0, lg0, ws, lref, closed):
    """Newton (minimum-norm) correction of the hinge rotations y[:K] (except ``pinned`` ones)
    back onto the closure (last link at rest in place), then of the rates y[K:2K] onto its
    tangent space; returns the position correction's size, m (0 for an open chain)."""
    if not closed:
        return 0.0
    th, dd, P, vP, G, om, vG, aG, al, A, r, bdd, mu = ws
    total = 0.0
    for _ in range(8):
        kinematics(K, jh, ch, y[:K], y[K:2 * K], p0, lg0, th, dd, P, vP, G, om, vG)
        e0 = th[K]
        e1 = dd[K, 0]
        e2 = dd[K, 1]
        size = abs(e0) * lref + abs(e1) + abs(e2)
        if size < 1e-15 * lref:
            break
        total += size
        # C C^T (3x3) over free columns
        cc = np.zeros((3, 3))
        cols = np.zeros((K, 3))
        for i in range(K):
            if pinned[i]:
                continue
            jx, jy = _jx(dd[K, 0] - P[i, 0], dd[K, 1] - P[i, 1])
            cols[i, 0] = 1.0
            cols[i, 1] = jx
            cols[i, 2] = jy
            for a in range(3):
                for b in range(3):
                    cc[a, b] += cols[i, a] * cols[i, b]
        rr = np.array([e0, e1, e2])
        if not _solve(cc, rr, np.int64(3)):
            return -1.0
        for i in range(K):
            y[i] -= cols[i, 0] * rr[0] + cols[i, 1] * rr[1] + cols[i, 2] * rr[2]
    # rates
    kinematics(K, jh, ch, y[:K], y[K:2 * K], p0, lg0, th, dd, P, vP, G, om, vG)
    cc = np.zeros((3, 3))
    cols = np.zeros((K, 3))
    rv = np.zeros(3)
    for i in range(K):
        jx, jy = _jx(dd[K, 0] - P[i, 0], dd[K, 1] - P[i, 1])
        cols[i, 0] = 1.0
        cols[i, 1] = jx
        cols[i, 2] = jy
        for a in range(3):
            rv[a] += cols[i, a] * y[K + i]
            for b in range(3):
                cc[a, b] += cols[i, a] * cols[i, b]
    if K >= 3 and _solve(cc, rv, np.int64(3)):
        for i in range(K):
            y[K + i] -= cols[i, 0] * rv[0] + cols[i, 1] * rv[1] + cols[i, 2] * rv[2]
    return total


@nb.njit(cache=True)
def to_full(K, jh, ch, y, p0, lg0, X0, ws, n, q, v):
    """Block positions q (n, 3) (x, y, theta) and velocities v (n, 3) of the reduced state."""
    th, dd, P, vP, G, om, vG, aG, al, A, r, bdd, mu = ws
    kinematics(K, jh, ch, y[:K], y[K:2 * K], p0, lg0, th, dd, P, vP, G, om, vG)
    k = 0
    for b in range(n):
        while k < K and jh[k] <= b:
            k += 1
        c = math.cos(th[k])
        s = math.sin(th[k])
        x = c * X0[b, 0] - s * X0[b, 1] + dd[k, 0]
        yy = s * X0[b, 0] + c * X0[b, 1] + dd[k, 1]
        q[b, 0] = x
        q[b, 1] = yy
        q[b, 2] = th[k]
        jx, jy = _jx(x - G[k, 0], yy - G[k, 1])
        v[b, 0] = vG[k, 0] + om[k] * jx
        v[b, 1] = vG[k, 1] + om[k] * jy
        v[b, 2] = om[k]


@nb.njit(cache=True)
def energies(K, ws, lm, lg0, li, g):
    """(kinetic, potential) energy of the links, J, potential relative to the undisplaced arch
    (after `kinematics` or `dynamics`)."""
    G, om, vG = ws[4], ws[5], ws[6]
    kin = 0.0
    pot = 0.0
    for k in range(1, K + 1):
        kin += 0.5 * (lm[k] * (vG[k, 0] ** 2 + vG[k, 1] ** 2) + li[k] * om[k] ** 2)
        pot += g * lm[k] * (G[k, 1] - lg0[k, 1])
    return kin, pot


@nb.njit(cache=True)
def _corner_normal_velocity(q, v, j, c, ja, jb, arm_a, arm_b, nrm):
    """Normal relative velocity (right minus left) of corner c of joint j, m/s."""
    ax_, ay_ = RK._point(q, ja[j], arm_a[j, c])
    vx = 0.0
    vy = 0.0
    if jb[j] >= 0:
        b = jb[j]
        bx, by = RK._point(q, b, arm_b[j, c])
        jx, jy = _jx(bx - q[b, 0], by - q[b, 1])
        vx += v[b, 0] + v[b, 2] * jx
        vy += v[b, 1] + v[b, 2] * jy
    if ja[j] >= 0:
        a = ja[j]
        jx, jy = _jx(ax_ - q[a, 0], ay_ - q[a, 1])
        vx -= v[a, 0] + v[a, 2] * jx
        vy -= v[a, 1] + v[a, 2] * jy
    return vx * nrm[j, 0] + vy * nrm[j, 1]


@nb.njit(cache=True)
def modes_after_projection(blocks, sg, q, vn, nrm, beta_j, rel_tol, vel_tol, abs_tol, jh, ch,
                           rates):
    """The hinge set after a projection: a joint open before (``beta_j != 0``) stays a hinge on
    its corner; a closed joint whose relative rotation rate is nonzero opens on the corner its
    rate turns about (the joints of ``blocks``, `archquake.rigid._step_kernels.Chain`, ``sg``
    their t x n, ``nrm`` their normals at ``q``). Returns (K, ok): ok False if a joint
    separates (its pivot moving away)."""
    ja = blocks.ja
    jb = blocks.jb
    arm_a = blocks.arm_a
    arm_b = blocks.arm_b
    nj = beta_j.shape[0]
    big = 0.0
    for j in range(nj):
        wa = 0.0 if ja[j] < 0 else vn[ja[j], 2]
        wb = 0.0 if jb[j] < 0 else vn[jb[j], 2]
        rates[j] = wb - wa
        if abs(rates[j]) > big:
            big = abs(rates[j])
    K = 0
    ok = True
    for j in range(nj):
        c = -1
        if beta_j[j] != 0.0:
            c = 0 if beta_j[j] * sg[j] > 0.0 else 1
        elif abs(rates[j]) > rel_tol * big and abs(rates[j]) > abs_tol:
            c = 0 if rates[j] * sg[j] > 0.0 else 1
        if c >= 0:
            jh[K] = j
            ch[K] = c
            K += 1
            if abs(_corner_normal_velocity(q, vn, j, c, ja, jb, arm_a, arm_b, nrm)) > vel_tol:
                ok = False
        else:
            for cc in range(2):
                if abs(_corner_normal_velocity(q, vn, j, cc, ja, jb, arm_a, arm_b, nrm)) > vel_tol:
                    ok = False
    return K, ok


@nb.njit(cache=True)
def metric_projection(chain, K, jh, ch, y, vn, links, ws):
    """Rates y[K:2K] of the hinge set (jh, ch) nearest, in the kinetic-energy metric, to the
    block velocities ``vn`` (n, 3) (at the configuration y[:K]): the normal equations
    M beta' = J^T M_b vn under the closure C beta' = 0 (the `Chain` ``chain``, the
    `Links` ``links``). Returns False if singular."""
    th, dd, P, vP, G, om, vG, aG, al, A, r, bdd, mu = ws
    lm, lg0, li, closed = links
    p0 = chain.p0
    X0 = chain.X0
    mb = chain.mb
    ib = chain.ib
    n = X0.shape[0]
    kinematics(K, jh, ch, y[:K], y[K:2 * K], p0, lg0, th, dd, P, vP, G, om, vG)
    m_ = _kkt_matrix(K, P, G, dd, lm, li, A, r, closed)
    k = 0
    for b in range(n):
        while k < K and jh[k] <= b:
            k += 1
        c = math.cos(th[k])
        s_ = math.sin(th[k])
        bx = c * X0[b, 0] - s_ * X0[b, 1] + dd[k, 0]
        by = s_ * X0[b, 0] + c * X0[b, 1] + dd[k, 1]
        for i in range(k):
            jx, jy = _jx(bx - P[i, 0], by - P[i, 1])
            r[i] += mb[b] * (vn[b, 0] * jx + vn[b, 1] * jy) + ib[b] * vn[b, 2]
    if not _solve(A, r, m_):
        return False
    for i in range(K):
        y[K + i] = r[i]
    return True


@nb.njit(cache=True)
def _phi(y, i, ch, sg, jh):
    """Opening angle of hinge i (>= 0 while open on its corner), rad."""
    s = sg[jh[i]] * (1.0 - 2.0 * ch[i])
    return s * y[i]


@nb.njit(cache=True)
def _first_root_cubic(y0, f0, y1, f1, t0, h, idx, sgn):
    """Earliest t in (t0, t0 + h] where the Hermite interpolant of sgn * y[idx] reaches zero from
    above (NaN if it stays positive at 16 probes and at the end)."""
    tmp = np.zeros(idx + 1)
    prev_t = t0
    for p in range(1, 17):
        tp = t0 + h * p / 16.0
        if p == 16:
            v = sgn * y1[idx]
        else:
            hermite(y0, f0, y1, f1, t0, h, tp, idx + 1, tmp)
            v = sgn * tmp[idx]
        if v < 0.0:
            lo = prev_t
            hi = tp
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                hermite(y0, f0, y1, f1, t0, h, mid, idx + 1, tmp)
                if sgn * tmp[idx] < 0.0:
                    hi = mid
                else:
                    lo = mid
                if hi - lo < 1e-15 * (1.0 + abs(t0)):
                    break
            return hi
        prev_t = tp
    return math.nan


@nb.njit(cache=True)
def _insert_hinge(K, jh, ch, y, j, c):
    """Insert a hinge at joint j on corner c with zero rotation and rate (y re-laid out)."""
    m = 2 * K + 1
    old = y[:m].copy()
    pos = 0
    while pos < K and jh[pos] < j:
        pos += 1
    for i in range(K, pos, -1):
        jh[i] = jh[i - 1]
        ch[i] = ch[i - 1]
    jh[pos] = j
    ch[pos] = c
    K1 = K + 1
    for i in range(K1):
        src = i if i < pos else i - 1
        if i == pos:
            y[i] = 0.0
            y[K1 + i] = 0.0
        else:
            y[i] = old[src]
            y[K1 + i] = old[K + src]
    y[2 * K1] = old[2 * K]
    return K1, pos


@nb.njit(cache=True)
def _remove_hinge(K, jh, ch, y, pos):
    m = 2 * K + 1
    old = y[:m].copy()
    for i in range(pos, K - 1):
        jh[i] = jh[i + 1]
        ch[i] = ch[i + 1]
    K1 = K - 1
    for i in range(K1):
        src = i if i < pos else i + 1
        y[i] = old[src]
        y[K1 + i] = old[K + src]
    y[2 * K1] = old[2 * K]
    return K1


@nb.njit(cache=True)
def _unsafe(kind, gp, ts, t, lam_pos, lam_neg, g):
    """Whether the ground acceleration at ``ts`` (in the piece of ``t``) leaves the safe domain
    x_g'' in [-lam_neg, lam_pos] (m/s^2, at gravity g), both ends scaled by (g + a_v) / g."""
    a = ground_in_piece(kind, gp, ts, t)
    s = 1.0 + vertical_in_piece(kind, gp, ts, t) / g
    return a > lam_pos * s or a < -lam_neg * s


@nb.njit(cache=True)
def onset_time(kind, gp, t, t_end, lam_pos, lam_neg, g):
    """First time in [t, t_end) at which the ground acceleration leaves the safe domain
    (x_g'' > lam_pos or x_g'' < -lam_neg, m/s^2, both times (g + a_v) / g under a vertical
    ground acceleration a_v); inf if none. Sub-steps of at most 1 ms within each piece of the
    motion, then bisection to 1e-13 s."""
    while t < t_end:
        bp = min(next_breakpoint(kind, gp, t), t_end)
        if _unsafe(kind, gp, t, t, lam_pos, lam_neg, g):
            return t
        nsub = max(1, int(math.ceil((bp - t) / 1e-3)))
        prev = t
        for s in range(1, nsub + 1):
            ts = t + (bp - t) * s / nsub
            if _unsafe(kind, gp, ts, t, lam_pos, lam_neg, g):
                lo = prev
                hi = ts
                for _ in range(80):
                    mid = 0.5 * (lo + hi)
                    if _unsafe(kind, gp, mid, t, lam_pos, lam_neg, g):
                        hi = mid
                    else:
                        lo = mid
                    if hi - lo < 1e-13:
                        break
                return hi
            prev = ts
        t = bp
    return math.inf


@nb.njit(cache=True)
def _emit(chain, span, state, output, links, t_to, written, step, K, jh, ch, ws, yo):
    """Write the samples at k dt_out <= t_to from the interpolant of the step ``step`` = (y0,
    f0, y1, f1, t0, h) into ``output`` (`Output`; ``span.dt_out``, `Span`); returns
    (written, collapsed)."""
    y0, f0, y1, f1, t0, h = step
    out_q, out_v, out_e = output
    cap = out_q.shape[0]
    dt_out = span.dt_out
    g = span.g
    stop_at_collapse = span.stop_at_collapse
    diag = state.diag
    state_all = state.state_all
    lm, lg0, li, _ = links
    p0 = chain.p0
    X0 = chain.X0
    freemap = chain.free_blocks
    free = chain.free
    cpar = chain.cpar
    n = X0.shape[0]
    m = 2 * K + 1
    while written < cap and dt_out * (written + 1) <= t_to + 1e-12 * (1.0 + t_to):
        ts = dt_out * (written + 1)
        if h > 0.0:
            hermite(y0, f0, y1, f1, t0, h, ts, m, yo)
        else:
            for i in range(m):
                yo[i] = y0[i]
        if K == 0:
            for b in range(n):
                out_q[written, b, 0] = X0[b, 0]
                out_q[written, b, 1] = X0[b, 1]
                out_q[written, b, 2] = 0.0
                out_v[written, b, 0] = 0.0
                out_v[written, b, 1] = 0.0
                out_v[written, b, 2] = 0.0
            kin = 0.0
            pot = 0.0
            win = yo[0]
        else:
            to_full(K, jh, ch, yo, p0, lg0, X0, ws, n, out_q[written], out_v[written])
            kin, pot = energies(K, ws, lm, lg0, li, g)
            win = yo[2 * K]
        out_e[written, 0] = kin
        out_e[written, 1] = pot
        out_e[written, 2] = diag[E_DISSIPATED]
        out_e[written, 3] = win
        out_e[written, 4] = diag[E_FRICTION]
        diag[E_FRICTION] = 0.0
        for b in range(n):
            state_all[freemap[b], 0] = out_q[written, b, 0]
            state_all[freemap[b], 1] = out_q[written, b, 1]
            state_all[freemap[b], 2] = out_q[written, b, 2]
        written += 1
        if stop_at_collapse and collapsed(state_all, free, cpar):
            return written, True
    return written, False


@nb.njit(cache=True)
def _log(log, counters, t, kind, joint, K):
    r = counters[N_LOG]
    if r < log.shape[0]:
        log[r, 0] = t
        log[r, 1] = kind
        log[r, 2] = joint
        log[r, 3] = K
        counters[N_LOG] += 1


@nb.njit(cache=True)
def _save(t, K, y, tt, st, diag):
    """Record where the run stops: time, hinge count, the input work carried in y."""
    tt[0] = t
    st[0] = K
    diag[E_INPUT] = y[2 * K] if K > 0 else y[0]


@nb.njit(cache=True)
def _fallback(chain, state, links, K, jh, ch, ws, why, t):
    """Stop for a hand-over to the time stepper (`_save`): the block positions and
    velocities of the reduced state (``state.y``) into ``state.fq``, ``state.fv``; returns
    ``why``."""
    y = state.y
    fq = state.fq
    fv = state.fv
    lg0 = links.lg0
    p0 = chain.p0
    X0 = chain.X0
    n = X0.shape[0]
    _save(t, K, y, state.tt, state.st, state.diag)
    if K == 0:
        for b in range(n):
            fq[b, 0] = X0[b, 0]
            fq[b, 1] = X0[b, 1]
            fq[b, 2] = 0.0
            fv[b, 0] = 0.0
            fv[b, 1] = 0.0
            fv[b, 2] = 0.0
    else:
        to_full(K, jh, ch, y, p0, lg0, X0, ws, n, fq, fv)
    return why


@nb.njit(cache=True)
def run(chain, span, state, output, written):
    """Integrate from ``state.tt[0]`` to ``span.t_end`` (module docstring): ``chain`` a
    `Chain`, ``span`` a `Span`, ``state`` a `State` (updated in place),
    ``output`` an `Output`. ``st`` = [K, jh (MAX_HINGES), ch (MAX_HINGES)] and ``y`` =
    (beta, beta', W_in) are the state, updated in place; samples at k ``dt_out`` (k = written +
    1, ...) go to ``output`` (``e``: kinetic, potential, dissipated, input, friction demand).
    ``log`` (rows: t s, kind (1 closure, 2 opening, 3 relock, 4 onset, 5 rest), joint, hinges
    after) gets every event while it has room
    (``counters[N_LOG]`` rows written). With ``resume`` the state is first read from the block
    positions and velocities ``fq``, ``fv`` (the time stepper's, after a fallback window):
    a joint open by more than ``RESUME_GAP`` L, or closed but turning (its corner speed above
    ``RESUME_SPEED`` sqrt(g L)), is a hinge (a joint open on both corners by more than
    ``RESUME_SEPARATION`` L: still in flight, returns ``STATUS_FALLBACK`` at once); the
    rotations are projected on the closure and the velocities on the hinge set's in the
    kinetic-energy metric (the energy that removes is counted as dissipated);
    ``diag[E_INPUT]`` carries the input work.
    Returns (status, reason, samples written)."""
    X0, mb, ib, S0, S1, S2, p0, n0, t0, hw, sg, ja, jb, arm_a, arm_b, freemap, free, cpar, lref = (
        chain)
    kind, gp, g, t_end, t_exc_end, lam_pos, lam_neg, rtol, atol, h_max, dt_out = span[:11]
    resume = span.resume
    st, y, tt, counters, diag, fq, fv, log, state_all = state
    out_q, out_v, out_e = output
    n = X0.shape[0]
    MX = MAX_HINGES
    jh = st[1:1 + MX]
    ch = st[1 + MX:1 + 2 * MX]
    K = st[0]
    ws = workspace(np.int64(MX))
    ytmp = np.zeros(2 * MX + 1)
    # the Dormand-Prince stages and their argument (`dopri_step`)
    ks = (np.zeros(2 * MX + 1), np.zeros(2 * MX + 1), np.zeros(2 * MX + 1), np.zeros(2 * MX + 1),
          np.zeros(2 * MX + 1), ytmp)
    y1 = np.zeros(2 * MX + 1)
    f0 = np.zeros(2 * MX + 1)
    f1 = np.zeros(2 * MX + 1)
    yo = np.zeros(2 * MX + 1)
    lm = np.zeros(MX + 1)
    lg0 = np.zeros((MX + 1, 2))
    li = np.zeros(MX + 1)
    lstart = np.zeros(MX + 2, np.int64)
    nj = ja.shape[0]
    closed = nj == n + 1
    links = Links(lm, lg0, li, closed)
    kmin = 4 if closed else 1  # fewest hinges of a mechanism
    forces = np.zeros((nj, 4))
    skip = np.zeros(nj, np.bool_)
    pinned = np.zeros(MX, np.bool_)
    beta_j = np.zeros(nj)
    rates = np.zeros(nj)
    z_last = np.full(nj, -math.inf)
    z_dt = np.full(nj, math.inf)
    z_cnt = np.zeros(nj, np.int64)
    jh2 = np.zeros(nj, np.int64)
    ch2 = np.zeros(nj, np.int64)
    qf = np.zeros((n, 3))
    vf = np.zeros((n, 3))
    inv_m = 1.0 / mb
    inv_i = 1.0 / ib
    blocks = RK.Chain(mb, ib, inv_m, inv_i, ja, jb, arm_a, arm_b, n0, t0)
    p_guess = np.ones((nj, 3))
    weight = g * S0[n]
    ftol = 1e-9
    ang_tol = 1e-13
    # the contact solve's limits as run-time integers: a literal constant argument would compile
    # a copy of the solver specialised to it (11 s each), where these share the one compiled
    # for the onset search of `archquake.rigid.events`
    max_sweeps = np.int64(SOLVE_SWEEPS)
    onset_sets = np.int64(RK.ACTIVE_SET_ITERATIONS)
    impact_sets = np.int64(IMPACT_ACTIVE_SETS)
    gap_tol = 1e-9 * lref
    # the contact solves' settings: the onset's Gauss projection, the impacts' projection
    onset_cfg = RK.Stepping(0.0, 0.0, gap_tol, 1e-13 * math.sqrt(g * lref), int(max_sweeps),
                            0.0, RK.METHOD_DIRECT, 0.0, 0.0, int(onset_sets))
    impact_cfg = RK.Stepping(0.0, 0.0, gap_tol, 1e-11 * math.sqrt(g * lref), int(max_sweeps),
                             0.0, RK.METHOD_DIRECT, 0.0, 0.0, int(impact_sets))
    ev_ring = np.full(CHATTER_EVENTS, -math.inf)
    ev_pos = 0
    link_properties(K, jh, n, S0, S1, S2, lm, lg0, li, lstart)
    t = tt[0]
    h = min(h_max, 1e-3)
    if resume:
        gaps, nrm, tan, pts = RK.geometry(fq, ja, jb, arm_a, arm_b, n0, t0)
        for j in range(n + 1):
            if min(gaps[j, 0], gaps[j, 1]) > RESUME_SEPARATION * lref:
                # still in flight: no hinge set holds this state (resuming would snap the
                # joint shut); the time stepper goes on from it
                return STATUS_FALLBACK, WHY_SEPARATION, written
        kin0 = 0.0
        for b in range(n):
            kin0 += 0.5 * (mb[b] * (fv[b, 0] ** 2 + fv[b, 1] ** 2) + ib[b] * fv[b, 2] ** 2)
        K = np.int64(0)
        for j in range(nj):
            tha = 0.0 if ja[j] < 0 else fq[ja[j], 2]
            thb = 0.0 if jb[j] < 0 else fq[jb[j], 2]
            wa = 0.0 if ja[j] < 0 else fv[ja[j], 2]
            wb = 0.0 if jb[j] < 0 else fv[jb[j], 2]
            gmax = max(gaps[j, 0], gaps[j, 1])
            if gmax > RESUME_GAP * lref:
                c = 0 if gaps[j, 1] > gaps[j, 0] else 1
                bet = thb - tha
                if bet * sg[j] * (1.0 - 2.0 * c) < 0.0:
                    bet = 0.0
            elif abs(wb - wa) * 2.0 * hw[j] > RESUME_SPEED * math.sqrt(g * lref):
                c = 0 if (wb - wa) * sg[j] > 0.0 else 1
                bet = 0.0
            else:
                continue
            jh[K] = j
            ch[K] = c
            y[K] = bet
            K += 1
        for i in range(K):  # lay out (beta, rates, W)
            y[K + i] = 0.0
        y[2 * K] = diag[E_INPUT]
        link_properties(K, jh, n, S0, S1, S2, lm, lg0, li, lstart)
        if K < kmin:
            K = np.int64(0)
            y[0] = diag[E_INPUT]
            link_properties(K, jh, n, S0, S1, S2, lm, lg0, li, lstart)
            diag[E_DISSIPATED] += kin0
        else:
            pinned[:K] = False
            project_closure(K, jh, ch, y, pinned, p0, lg0, ws, lref, closed)
            metric_projection(chain, K, jh, ch, y, fv, links, ws)
            project_closure(K, jh, ch, y, pinned, p0, lg0, ws, lref, closed)
            kinematics(K, jh, ch, y[:K], y[K:2 * K], p0, lg0, ws[0], ws[1], ws[2], ws[3],
                       ws[4], ws[5], ws[6])
            kin1, _ = energies(K, ws, lm, lg0, li, g)
            diag[E_DISSIPATED] += kin0 - kin1
        _log(log, counters, t, np.int64(6), np.int64(-1), K)
    while t < t_end - 1e-13:
        # ---------------------------------------------------------------- locked, at rest
        if K == 0:
            t_on = onset_time(kind, gp, t, t_end, lam_pos, lam_neg, g)
            t_stop = min(t_on, t_end)
            written, col = _emit(chain, span, state, output, links, t_stop, written,
                                  (y, f0, y, f0, t, 0.0), K, jh, ch, ws, yo)
            if t_on >= t_end:
                t = t_end
                break
            t = t_on
            ax = ground_in_piece(kind, gp, t, t)
            av = vertical_in_piece(kind, gp, t, t)
            s_on = 1.0 + av / g  # the thresholds at gravity g + av
            if ax > 0.0:
                ax = max(ax, lam_pos * s_on * (1.0 + 1e-6))
            else:
                ax = min(ax, -lam_neg * s_on * (1.0 + 1e-6))
            for b in range(n):
                qf[b, 0] = X0[b, 0]
                qf[b, 1] = X0[b, 1]
                qf[b, 2] = 0.0
                vf[b, 0] = -ax
                vf[b, 1] = -(g + av)
                vf[b, 2] = 0.0
            geo = RK.geometry(qf, ja, jb, arm_a, arm_b, n0, t0)
            nrm = geo.nrm
            acc, imp, _, _ = RK.project_direct(blocks, onset_cfg, qf, geo, vf, np.zeros((nj, 3)),
                                               np.empty(0), np.empty(0))
            beta_j[:] = 0.0
            K2, ok = modes_after_projection(blocks, sg, qf, acc, nrm, beta_j, 1e-7,
                                            1e-7 * (g + abs(ax)), 1e-9 * g / lref, jh2, ch2,
                                            rates)
            counters[N_ONSETS] += 1
            if not ok or K2 > MX:
                return STATUS_FALLBACK, _fallback(chain, state, links, K, jh, ch, ws,
                                                  np.int64(WHY_SEPARATION), t), written
            if K2 < kmin:
                t += 1e-9  # no motion after all (at the threshold): keep scanning
                continue
            win = y[0]
            K = K2
            for i in range(K):
                jh[i] = jh2[i]
                ch[i] = ch2[i]
                y[i] = 0.0
                y[K + i] = 0.0
            y[2 * K] = win
            link_properties(K, jh, n, S0, S1, S2, lm, lg0, li, lstart)
            _log(log, counters, t, np.int64(4), np.int64(-1), K)
            h = min(h_max, 1e-4)
            # fall through to the consistency check below
        else:
            # ------------------------------------------------------------ one step
            ax0 = ground_in_piece(kind, gp, t, t)
            if not rhs(K, jh, ch, y, p0, lm, lg0, li, ax0, g, ws, f0, closed,
                       vertical_in_piece(kind, gp, t, t)):
                return STATUS_FALLBACK, _fallback(chain, state, links, K, jh, ch, ws,
                                                  np.int64(WHY_SINGULAR), t), written
            counters[N_EVALS] += 1
            while True:
                bp = next_breakpoint(kind, gp, t)
                hh = min(h, h_max, bp - t, t_end - t)
                err = dopri_step(K, jh, ch, t, hh, y, f0, p0, links, span, ws, ks, y1, f1)
                counters[N_EVALS] += 6
                if err <= 1.0:
                    break
                if not math.isfinite(err) or hh < 1e-12:
                    return STATUS_FALLBACK, _fallback(chain, state, links, K, jh, ch, ws,
                                                      np.int64(WHY_SINGULAR), t), written
                h = hh * max(0.2, 0.9 * err ** -0.2)
                counters[N_REJECTED] += 1
            fac = 5.0 if err == 0.0 else min(5.0, max(0.2, 0.9 * err ** -0.2))
            h_next = hh * fac if hh >= h else max(h, hh * fac)
            t1 = t + hh
            t_step = t
            # -------- events in (t, t1]
            t_ev = math.inf
            ev_kind = 0
            ev_i = -1
            for i in range(K):
                s = sg[jh[i]] * (1.0 - 2.0 * ch[i])
                phi0 = s * y[i]
                dphi0 = s * y[K + i]
                if phi0 <= ang_tol:
                    if dphi0 < -1e-12:
                        # closed and closing already (a rate the last projection left): the
                        # impact is now
                        t_ev = t
                        ev_kind = 1
                        ev_i = i
                        break
                    if dphi0 <= 1e-12:
                        if s * y1[i] < -ang_tol:
                            t_ev = t
                            ev_kind = 3  # relock: the new hinge turns the wrong way
                            ev_i = i
                        continue
                tc = _first_root_cubic(y, f0, y1, f1, t, hh, i, s)
                if tc < t_ev:
                    t_ev = tc
                    ev_kind = 1
                    ev_i = i
            ax1 = ground_in_piece(kind, gp, t1, t)
            g1 = g + vertical_in_piece(kind, gp, t1, t)  # gravity with the vertical
            joint_forces(chain, K, jh, ch, ws, ax1, g1, forces)
            lo, lj, lc, ho, hk, fr = margins(K, jh, ch, forces, n, weight, skip)
            if fr > diag[E_FRICTION]:
                diag[E_FRICTION] = fr
            # the mid-step too (a margin dipping below zero and back within one step)
            if lo >= -ftol and ho >= -ftol:
                tm = t + 0.5 * hh
                hermite(y, f0, y1, f1, t, hh, tm, 2 * K + 1, ytmp)
                gm = g + vertical_in_piece(kind, gp, tm, t)
                dynamics(K, jh, ch, ytmp[:K], ytmp[K:2 * K], p0, lm, lg0, li,
                         ground_in_piece(kind, gp, tm, t), gm, ws, closed)
                joint_forces(chain, K, jh, ch, ws, ground_in_piece(kind, gp, tm, t), gm, forces)
                lo_m, _, _, ho_m, _, _ = margins(K, jh, ch, forces, n, weight, skip)
                counters[N_EVALS] += 1
                if lo_m < lo:
                    lo = lo_m
                if ho_m < ho:
                    ho = ho_m
            if lo < -ftol or ho < -ftol:
                a_ = t
                b_ = t1
                for _ in range(60):
                    mid = 0.5 * (a_ + b_)
                    hermite(y, f0, y1, f1, t, hh, mid, 2 * K + 1, ytmp)
                    axm = ground_in_piece(kind, gp, mid, t)
                    gm = g + vertical_in_piece(kind, gp, mid, t)
                    dynamics(K, jh, ch, ytmp[:K], ytmp[K:2 * K], p0, lm, lg0, li, axm, gm, ws, closed)
                    joint_forces(chain, K, jh, ch, ws, axm, gm, forces)
                    lo_m, _, _, ho_m, _, _ = margins(K, jh, ch, forces, n, weight, skip)
                    counters[N_EVALS] += 1
                    if lo_m < 0.0 or ho_m < 0.0:
                        b_ = mid
                    else:
                        a_ = mid
                    if b_ - a_ < 1e-14 * (1.0 + t):
                        break
                if b_ < t_ev:
                    t_ev = b_
                    ev_kind = 2
            if t_ev == math.inf:
                written, col = _emit(chain, span, state, output, links, t1, written,
                                      (y, f0, y1, f1, t, hh), K, jh, ch, ws, yo)
                for i in range(2 * K + 1):
                    y[i] = y1[i]
                t = t1
                pinned[:K] = False
                d = project_closure(K, jh, ch, y, pinned, p0, lg0, ws, lref, closed)
                if d > diag[E_MAX_DRIFT]:
                    diag[E_MAX_DRIFT] = d
                counters[N_STEPS] += 1
                h = h_next
                if col:
                    _save(t, K, y, tt, st, diag)
                    return STATUS_COLLAPSE, WHY_NONE, written
                continue
            # -------- reach the event
            if t_ev > t:
                he = t_ev - t
                dopri_step(K, jh, ch, t, he, y, f0, p0, links, span, ws, ks, y1, f1)
                counters[N_EVALS] += 6
                written, col = _emit(chain, span, state, output, links, t_ev, written,
                                      (y, f0, y1, f1, t, he), K, jh, ch, ws, yo)
                for i in range(2 * K + 1):
                    y[i] = y1[i]
                t = t_ev
                if col:
                    _save(t, K, y, tt, st, diag)
                    return STATUS_COLLAPSE, WHY_NONE, written
            # chatter guard
            ev_ring[ev_pos % CHATTER_EVENTS] = t
            ev_pos += 1
            if ev_pos >= CHATTER_EVENTS and t - ev_ring[ev_pos % CHATTER_EVENTS] < CHATTER_WINDOW:
                return STATUS_FALLBACK, _fallback(chain, state, links, K, jh, ch, ws,
                                                  np.int64(WHY_CHATTER), t), written
            h = min(h_next, 1e-3)
            if ev_kind == 2:
                # which margin: recompute at the event
                axe = ground_in_piece(kind, gp, t, t_step)
                ge = g + vertical_in_piece(kind, gp, t, t_step)
                dynamics(K, jh, ch, y[:K], y[K:2 * K], p0, lm, lg0, li, axe, ge, ws, closed)
                joint_forces(chain, K, jh, ch, ws, axe, ge, forces)
                lo, lj, lc, ho, hk, fr = margins(K, jh, ch, forces, n, weight, skip)
                if ho < lo:
                    return STATUS_FALLBACK, _fallback(chain, state, links, K, jh, ch, ws,
                                                      np.int64(WHY_TENSILE_HINGE), t), written
                if K + 1 > MX:
                    return STATUS_FALLBACK, _fallback(chain, state, links, K, jh, ch, ws,
                                                      np.int64(WHY_TOO_MANY_HINGES), t), written
                K, _ = _insert_hinge(K, jh, ch, y, lj, 1 - lc)
                counters[N_OPENINGS] += 1
                _log(log, counters, t, np.int64(2), lj, K)
                link_properties(K, jh, n, S0, S1, S2, lm, lg0, li, lstart)
            elif ev_kind == 3:
                _log(log, counters, t, np.int64(3), jh[ev_i], K - 1)
                K = _remove_hinge(K, jh, ch, y, ev_i)
                counters[N_RELOCKS] += 1
                link_properties(K, jh, n, S0, S1, S2, lm, lg0, li, lstart)
            else:
                # closure of hinge ev_i: a plastic impact
                counters[N_CLOSURES] += 1
                jclose = jh[ev_i]
                y[ev_i] = 0.0
                pinned[:K] = False
                pinned[ev_i] = True
                for i in range(K):  # hinges closed to within the contact tolerance close too
                    if _phi(y, i, ch, sg, jh) * 2.0 * hw[jh[i]] < gap_tol:
                        y[i] = 0.0
                        pinned[i] = True
                if K - 1 < kmin:
                    for i in range(K):
                        y[i] = 0.0
                        pinned[i] = True
                project_closure(K, jh, ch, y, pinned, p0, lg0, ws, lref, closed)
                to_full(K, jh, ch, y, p0, lg0, X0, ws, n, qf, vf)
                kin0, _ = energies(K, ws, lm, lg0, li, g)
                beta_j[:] = 0.0
                for i in range(K):
                    beta_j[jh[i]] = y[i]
                geo = RK.geometry(qf, ja, jb, arm_a, arm_b, n0, t0)
                nrm = geo.nrm
                vscale = 0.0
                for b in range(n):
                    vscale = max(vscale, abs(vf[b, 0]) + abs(vf[b, 1]) + abs(vf[b, 2]) * lref)
                # the guessed active set: every touching corner pushes (the exact solve drops
                # the tensile ones)
                vn, imp, nsolve, _ = RK.project_direct(blocks, impact_cfg, qf, geo, vf, p_guess,
                                                        np.empty(0), np.empty(0))
                counters[N_SOLVES] += nsolve
                K2, ok = modes_after_projection(blocks, sg, qf, vn, nrm, beta_j, 1e-8,
                                                1e-7 * max(vscale, 1e-300),
                                                1e-12 * math.sqrt(g / lref), jh2, ch2, rates)
                if not ok or K2 > MX:
                    _save(t, K, y, tt, st, diag)
                    fq[:, :] = qf
                    fv[:, :] = vn  # the stepper takes over from the impact
                    return STATUS_FALLBACK, WHY_SEPARATION, written
                # accumulation: the same joint closing again and again at shrinking intervals
                # (it reopens from the impulse its neighbours transmit) stays closed from the
                # third such closure on: the limit of the sequence
                dtz = t - z_last[jclose]
                if dtz < z_dt[jclose] and dtz < ZENO_WINDOW * math.sqrt(lref / g):
                    z_cnt[jclose] += 1
                else:
                    z_cnt[jclose] = 1
                z_dt[jclose] = dtz
                z_last[jclose] = t
                if z_cnt[jclose] >= ZENO_CLOSURES:
                    for i in range(K2):
                        if jh2[i] == jclose and beta_j[jclose] == 0.0:
                            for i2 in range(i, K2 - 1):
                                jh2[i2] = jh2[i2 + 1]
                                ch2[i2] = ch2[i2 + 1]
                            K2 -= 1
                            counters[N_ZENO] += 1
                            break
                win = y[2 * K]
                displaced = False
                for i in range(K2):
                    if beta_j[jh2[i]] != 0.0:
                        displaced = True
                K = K2
                for i in range(K):
                    jh[i] = jh2[i]
                    ch[i] = ch2[i]
                    y[i] = beta_j[jh[i]]
                    y[K + i] = 0.0
                y[2 * K] = win
                link_properties(K, jh, n, S0, S1, S2, lm, lg0, li, lstart)
                kin1 = 0.0
                if K >= kmin - 1 and K > 0:
                    if not metric_projection(chain, K, jh, ch, y, vn, links, ws):
                        return STATUS_FALLBACK, _fallback(chain, state, links, K, jh, ch, ws,
                                                          np.int64(WHY_SINGULAR), t), written
                    pinned[:K] = False
                    project_closure(K, jh, ch, y, pinned, p0, lg0, ws, lref, closed)
                    kinematics(K, jh, ch, y[:K], y[K:2 * K], p0, lg0, ws[0], ws[1], ws[2],
                               ws[3], ws[4], ws[5], ws[6])
                    kin1, _ = energies(K, ws, lm, lg0, li, g)
                diag[E_DISSIPATED] += kin0 - kin1
                if K == 0 or K < kmin - 1 or (not displaced and (kin1 == 0.0 or (
                        t >= t_exc_end and kin1 < 1e-12 * weight * lref))):
                    _log(log, counters, t, np.int64(5), jclose, np.int64(0))
                    K = np.int64(0)
                    y[0] = win
                    link_properties(K, jh, n, S0, S1, S2, lm, lg0, li, lstart)
                    continue
                _log(log, counters, t, np.int64(1), jclose, K)
        # ---------------------------------------------------------------- consistency
        for _ in range(2 * nj):
            axc = ground_in_piece(kind, gp, t, t)
            gc = g + vertical_in_piece(kind, gp, t, t)
            if not dynamics(K, jh, ch, y[:K], y[K:2 * K], p0, lm, lg0, li, axc, gc, ws, closed):
                return STATUS_FALLBACK, _fallback(chain, state, links, K, jh, ch, ws,
                                                  np.int64(WHY_SINGULAR), t), written
            joint_forces(chain, K, jh, ch, ws, axc, gc, forces)
            lo, lj, lc, ho, hk, fr = margins(K, jh, ch, forces, n, weight, skip)
            if ho < -ftol:
                return STATUS_FALLBACK, _fallback(chain, state, links, K, jh, ch, ws,
                                                  np.int64(WHY_TENSILE_HINGE), t), written
            if lo >= -ftol:
                break
            if K + 1 > MX:
                return STATUS_FALLBACK, _fallback(chain, state, links, K, jh, ch, ws,
                                                  np.int64(WHY_TOO_MANY_HINGES), t), written
            K, _ = _insert_hinge(K, jh, ch, y, lj, 1 - lc)
            counters[N_OPENINGS] += 1
            _log(log, counters, t, np.int64(2), lj, K)
            link_properties(K, jh, n, S0, S1, S2, lm, lg0, li, lstart)
    _save(t, K, y, tt, st, diag)
    if K == 0 and t >= t_exc_end:
        return STATUS_REST, WHY_NONE, written
    return STATUS_DONE, WHY_NONE, written
