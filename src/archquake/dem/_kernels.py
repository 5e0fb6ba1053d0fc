"""Compiled hot loop of the distinct-element model (numba), on packed arrays.

Everything here is private; `archquake.dem.run` packs the arrays and
`archquake.dem._reference` is the plain-NumPy reference of `step` that the tests
hold it to (test-only: production code does not import it).

Packed layout (`Packed`)
-------------------------------
Blocks (``nb``): ``state[i] = (x, y, theta, vx, vy, omega)`` with the centroid position and the
rotation at step n and the velocities at n - 1/2 (absolute frame); ``mass``, ``inertia``
(about the centroid); ``free[i]`` 1 for a moving block, 0 for a block of the base (prescribed
motion). Vertices: block i owns ``vloc[vstart[i]:vstart[i+1]]`` (counter-clockwise, local
coordinates relative to the centroid at theta = 0); edge ``e`` runs from vertex ``e`` to the
next vertex of the same block, ``eloc[e]`` its unit tangent and length in the block's frame
(`archquake.dem.run.edge_frames`: a step turns them with the block).

Contact slots (``ns``): one per (vertex of block a, neighbouring block b):
``sl_i[s] = (vertex, a, b, rev_start, rev_end)`` where ``rev_start:rev_end`` are the slots of
b's vertices against a; ``sl_edge[s]`` the edge of b the vertex touches (-1: no contact);
``sl_f[s] = (K_n [N/m], K_s [N/m], F_s [N], F_n [N], plastic slip [m])``.

Parameters ``par``: see the P_* indices. Accumulators ``acc``: see the A_* indices; the
energies are kept in the frame of the (rigidly translating) ground.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from archquake._kernel_cache import stamp_kernels
from archquake.blocks._kernels import collapsed
from archquake.ground._kernel import ground_acceleration, vertical_in_piece

stamp_kernels()  # the cache checks each kernel against every source compiled into it

# parameter indices
P_DT, P_G, P_ALPHA, P_BETA, P_MU, P_KN, P_KS, P_TOL, P_DMAX, P_BROAD = range(10)
N_PAR = 10
# accumulator indices
A_VB, A_XB, A_DAMP, A_FRIC, A_WIN, A_KE, A_SE, A_KEPREV = range(8)
N_ACC = 8
# slot float columns
F_KN, F_KS, F_FS, F_FN, F_SLIP = range(5)

STATUS_DONE, STATUS_COLLAPSE, STATUS_REBUILD = 0, 1, 2


class Packed(NamedTuple):
    """The packed arrays of one assembly (module docstring): blocks, vertices and contact
    slots. The arrays are the run's mutable working state; ``y_ref`` (m) is each block's
    centroid height at t = 0 (the potential energy's origin) and ``radius`` (m) its bounding
    circle about the centroid."""

    state: np.ndarray
    mass: np.ndarray
    inertia: np.ndarray
    free: np.ndarray
    y_ref: np.ndarray
    vloc: np.ndarray
    vstart: np.ndarray
    radius: np.ndarray
    eloc: np.ndarray
    sl_i: np.ndarray
    sl_edge: np.ndarray
    sl_f: np.ndarray


class Scratch(NamedTuple):
    """Work arrays of one step: ``force``, ``dforce`` (nb, 3), ``record`` (nb, 6), world
    vertices ``vw`` (nv, 2), edge frames ``edir`` (nv, 3); ``slots``, the contact slots the
    step looks at (increasing: every slot, or those `slots_in_reach` keeps); ``cand``
    (as long), room for the free corners a step scans; ``blocker`` (ns,), for each slot the
    active slot whose corner it last coincided with (-1: none yet)."""

    force: np.ndarray
    dforce: np.ndarray
    record: np.ndarray
    vw: np.ndarray
    edir: np.ndarray
    slots: np.ndarray
    cand: np.ndarray
    blocker: np.ndarray


class Span(NamedTuple):
    """What `run` does: global steps ``step0`` to ``n_steps``, a sample every
    ``out_every`` steps (0: none), with the ground moving or not (``ground_on``), settling by
    kinetic damping or not (``settle``), stopping at the first collapsed sample or not."""

    step0: int
    n_steps: int
    out_every: int
    ground_on: bool
    settle: bool
    stop_at_collapse: bool


class Output(NamedTuple):
    """Samples written by `run`: ``times`` (k,), ``states`` (k, nb, 6), ``energies``
    (k, 8) and ``written`` (1,), the number written so far."""

    times: np.ndarray
    states: np.ndarray
    energies: np.ndarray
    written: np.ndarray


def scratch(packed: Packed) -> Scratch:
    """Zeroed work arrays for ``packed``, looking at every contact slot."""
    nbk, nv, ns = packed.state.shape[0], packed.vloc.shape[0], packed.sl_i.shape[0]
    return Scratch(np.zeros((nbk, 3)), np.zeros((nbk, 3)), np.zeros((nbk, 6)),
                   np.zeros((nv, 2)), np.zeros((nv, 3)), np.arange(ns, dtype=np.int64),
                   np.zeros(ns, dtype=np.int64), np.full(ns, -1, dtype=np.int64))


#: A vertex may touch an edge only if neither of its own edges dips into the face by more than
#: this (sine of the angle; about 3 deg).
ANGLE_TOL = 0.05


@nb.njit(cache=True, inline="always")
def _next_vertex(v, b, vstart):
    w = v + 1
    if w >= vstart[b + 1]:
        w = vstart[b]
    return w


@nb.njit(cache=True, inline="always")
def _prev_vertex(v, b, vstart):
    w = v - 1
    if w < vstart[b]:
        w = vstart[b + 1] - 1
    return w


@nb.njit(cache=True, inline="always")
def world_vertices(state, vloc, eloc, vstart, vw, edir):
    """World coordinates of every vertex (vw, (nv, 2)) and every edge's unit tangent and
    length (edir, (nv, 3)); edge e runs from vertex e to the next vertex of its block. The
    tangents are the blocks' own (``eloc``, `edge_frames`) turned with them."""
    for b in range(vstart.shape[0] - 1):
        c = math.cos(state[b, 2])
        s = math.sin(state[b, 2])
        for v in range(vstart[b], vstart[b + 1]):
            vw[v, 0] = state[b, 0] + c * vloc[v, 0] - s * vloc[v, 1]
            vw[v, 1] = state[b, 1] + s * vloc[v, 0] + c * vloc[v, 1]
            edir[v, 0] = c * eloc[v, 0] - s * eloc[v, 1]
            edir[v, 1] = s * eloc[v, 0] + c * eloc[v, 1]
            edir[v, 2] = eloc[v, 2]


@nb.njit(cache=True)
def slots_in_reach(state, radius, free, vw, sl_i, par, margin):
    """The contact slots (increasing) a step looks at until the neighbour lists are rebuilt,
    for the world vertices ``vw`` of ``state``: every slot with ``par[P_BROAD]`` = 0; else
    every slot of a base block, and those whose corner may come within reach of the other
    block (`update_contacts`) before then.

    Between rebuilds no free block moves by more than margin/2 (`run`'s check, the
    neighbour lists' own assumption), so a corner farther than radius + dmax + tol + margin
    from the other free block's centroid cannot come within reach; slots are kept up to
    radius + dmax + tol + 2 margin, twice the margin needed. Active contacts are within
    reach, so every one is kept. Slots of a base block are all kept (the base's own motion
    is not part of the rebuild check)."""
    ns = sl_i.shape[0]
    out = np.empty(ns, dtype=np.int64)
    broad = par[P_BROAD] != 0.0
    tol = par[P_TOL]
    dmax = par[P_DMAX]
    k = 0
    for s in range(ns):
        a = sl_i[s, 1]
        b = sl_i[s, 2]
        if broad and free[a] != 0 and free[b] != 0:
            v = sl_i[s, 0]
            dx = vw[v, 0] - state[b, 0]
            dy = vw[v, 1] - state[b, 1]
            reach = radius[b] + dmax + tol + 2.0 * margin
            if dx * dx + dy * dy > reach * reach:
                continue
        out[k] = s
        k += 1
    return out[:k].copy()


@nb.njit(cache=True, inline="always")
def _edge_frame(vw, edir, e, px, py):
    """Overlap of point p behind edge e (> 0 inside), its edge parameter in [0, 1] along
    the edge, the outward normal, the unit tangent and the edge length."""
    tx = edir[e, 0]
    ty = edir[e, 1]
    length = edir[e, 2]
    nx = ty
    ny = -tx
    rx = px - vw[e, 0]
    ry = py - vw[e, 1]
    overlap = -(rx * nx + ry * ny)
    spar = (rx * tx + ry * ty) / length
    return overlap, spar, nx, ny, tx, ty, length


@nb.njit(cache=True, inline="always")
def _coinciding(px, py, s, vw, sl_i, sl_edge, tol):
    """The first active slot among s's reverse slots whose corner (of the other block, in
    contact with s's block) lies within ``tol`` of point p; -1 if none."""
    for r in range(sl_i[s, 3], sl_i[s, 4]):
        if sl_edge[r] >= 0:
            q = sl_i[r, 0]
            if math.sqrt((px - vw[q, 0]) ** 2 + (py - vw[q, 1]) ** 2) < tol:
                return r
    return -1


@nb.njit(cache=True, inline="always")
def update_contacts(state, radius, vw, edir, vstart, sl_i, sl_edge, sl_f, slots, cand, blocker,
                    par, acc):
    """Drop contacts that opened or slid off their edge; create new ones (two passes, the
    lower-numbered block's vertices first; a vertex coinciding with an active vertex of the
    other block is skipped, so an edge-to-edge contact carries one contact per end).

    A new contact goes to the candidate edge (vertex behind it by 0 < overlap <= dmax, within
    its length, and neither edge at the vertex dipping into it by more than ANGLE_TOL) that
    best faces one of the two edges meeting at the vertex (most
    negative dot product of their directions; first such edge on ties): a corner lying in
    a corner of the other block touches the face it rests on, not the side it grazes.

    With ``par[P_BROAD]`` = 1 a free corner is first tested against the other block's reach
    (its bounding circle, ``radius`` about the centroid in ``state``, widened by dmax and the
    contact tolerance: an accepted edge puts the corner within dmax of a point of that edge),
    and a corner coinciding with an active corner of the other block is skipped before its
    edges are scanned. Both only leave out corners that the scan would reject, so the contacts,
    and every number after them, are the same bits as with 0 (every edge of every candidate
    scanned, as `archquake.dem._reference` does). Only the slots listed in ``slots`` are
    looked at (`slots_in_reach`).
    """
    tol = par[P_TOL]
    dmax = par[P_DMAX]
    broad = par[P_BROAD] != 0.0
    for k in range(slots.shape[0]):
        s = slots[k]
        e = sl_edge[s]
        if e < 0:
            continue
        v = sl_i[s, 0]
        a = sl_i[s, 1]
        b = sl_i[s, 2]
        px = vw[v, 0]
        py = vw[v, 1]
        overlap, spar, nx, ny, tx, ty, length = _edge_frame(vw, edir, e, px, py)
        slack = tol / length
        if overlap <= 0.0 or overlap > dmax or spar < -slack or spar > 1.0 + slack:
            ks = sl_f[s, F_KS]
            acc[A_FRIC] += 0.5 * sl_f[s, F_FS] * sl_f[s, F_FS] / ks
            sl_edge[s] = -1
            sl_f[s, F_FS] = 0.0
            sl_f[s, F_FN] = 0.0
    # the free corners to scan: with the broad phase, those within reach of the other block and
    # not on one of its active corners (contacts are only added below, so a corner skipped
    # here would be skipped there too)
    nc = 0
    for k in range(slots.shape[0]):
        s = slots[k]
        if sl_edge[s] >= 0:
            continue
        if broad:
            v = sl_i[s, 0]
            b = sl_i[s, 2]
            px = vw[v, 0]
            py = vw[v, 1]
            dx = px - state[b, 0]
            dy = py - state[b, 1]
            reach = radius[b] + dmax + tol
            if dx * dx + dy * dy > reach * reach:
                continue
            # the corner that blocked it last time first (then the others: the same answer)
            r = blocker[s]
            if r >= 0 and sl_edge[r] >= 0:
                q = sl_i[r, 0]
                if math.sqrt((px - vw[q, 0]) ** 2 + (py - vw[q, 1]) ** 2) < tol:
                    continue
            r = _coinciding(px, py, s, vw, sl_i, sl_edge, tol)
            if r >= 0:
                blocker[s] = r
                continue
        cand[nc] = s
        nc += 1
    for pas in range(2):
        for k in range(nc):
            s = cand[k]
            if sl_edge[s] >= 0:
                continue
            v = sl_i[s, 0]
            a = sl_i[s, 1]
            b = sl_i[s, 2]
            if (a > b) != (pas == 1):
                continue
            px = vw[v, 0]
            py = vw[v, 1]
            vp = _prev_vertex(v, a, vstart)
            best = -1
            best_score = 0.0
            best_len = 0.0
            for e in range(vstart[b], vstart[b + 1]):
                overlap, spar, nx, ny, tx, ty, length = _edge_frame(vw, edir, e, px, py)
                if overlap > 0.0 and overlap <= dmax and spar >= 0.0 and spar <= 1.0:
                    # both edges at the vertex must stay outside the face (no hooking on
                    # the side of a corner the vertex merely sits in)
                    out_n = edir[v, 0] * nx + edir[v, 1] * ny
                    out_p = -(edir[vp, 0] * nx + edir[vp, 1] * ny)
                    if out_n < -ANGLE_TOL or out_p < -ANGLE_TOL:
                        continue
                    score = min(edir[vp, 0] * tx + edir[vp, 1] * ty,
                                edir[v, 0] * tx + edir[v, 1] * ty)
                    if best < 0 or score < best_score:
                        best = e
                        best_score = score
                        best_len = length
            if best < 0:
                continue
            if _coinciding(px, py, s, vw, sl_i, sl_edge, tol) >= 0:
                continue
            # tributary length: half the shorter of the touched edge and the facing edge of a
            tx = edir[best, 0]
            ty = edir[best, 1]
            dot_p = edir[vp, 0] * tx + edir[vp, 1] * ty
            dot_n = edir[v, 0] * tx + edir[v, 1] * ty
            lf = edir[vp, 2] if dot_p < dot_n else edir[v, 2]
            trib = 0.5 * min(best_len, lf)
            sl_edge[s] = best
            sl_f[s, F_KN] = par[P_KN] * trib
            sl_f[s, F_KS] = par[P_KS] * trib
            sl_f[s, F_FS] = 0.0
            sl_f[s, F_FN] = 0.0


@nb.njit(cache=True, inline="always")
def contact_forces(state, vw, edir, sl_i, sl_edge, sl_f, slots, par, acc, force, dforce):
    """Add the contact forces to ``force`` (elastic + friction) and ``dforce`` (viscous part of
    the stiffness-proportional damping), both (nb, 3): Fx, Fy, moment about the centroid, for
    the active contacts among ``slots`` (every active one: `slots_in_reach`). Returns the
    elastic energy stored in the contact springs, J."""
    dt = par[P_DT]
    beta = par[P_BETA]
    mu = par[P_MU]
    strain = 0.0
    for k in range(slots.shape[0]):
        s = slots[k]
        e = sl_edge[s]
        if e < 0:
            continue
        v = sl_i[s, 0]
        a = sl_i[s, 1]
        b = sl_i[s, 2]
        px = vw[v, 0]
        py = vw[v, 1]
        overlap, spar, nx, ny, tx, ty, length = _edge_frame(vw, edir, e, px, py)
        rax = px - state[a, 0]
        ray = py - state[a, 1]
        rbx = px - state[b, 0]
        rby = py - state[b, 1]
        vrx = (state[a, 3] - state[a, 5] * ray) - (state[b, 3] - state[b, 5] * rby)
        vry = (state[a, 4] + state[a, 5] * rax) - (state[b, 4] + state[b, 5] * rbx)
        vn = vrx * nx + vry * ny
        vs = vrx * tx + vry * ty
        kn = sl_f[s, F_KN]
        ks = sl_f[s, F_KS]
        fn_el = kn * overlap
        fn_tot = fn_el - beta * kn * vn
        if fn_tot < 0.0:
            fn_tot = 0.0
        fn_visc = fn_tot - fn_el
        fs_trial = sl_f[s, F_FS] - ks * vs * dt
        limit = mu * fn_el
        if abs(fs_trial) > limit:
            fs = limit if fs_trial > 0.0 else -limit
            slip = (abs(fs_trial) - limit) / ks
            acc[A_FRIC] += limit * slip
            sl_f[s, F_SLIP] += slip
            fs_visc = 0.0
        else:
            fs = fs_trial
            fs_visc = -beta * ks * vs
        sl_f[s, F_FS] = fs
        sl_f[s, F_FN] = fn_tot
        strain += 0.5 * fn_el * overlap + 0.5 * fs * fs / ks
        fx = fn_el * nx + fs * tx
        fy = fn_el * ny + fs * ty
        dx = fn_visc * nx + fs_visc * tx
        dy = fn_visc * ny + fs_visc * ty
        force[a, 0] += fx
        force[a, 1] += fy
        force[a, 2] += rax * fy - ray * fx
        force[b, 0] -= fx
        force[b, 1] -= fy
        force[b, 2] -= rbx * fy - rby * fx
        dforce[a, 0] += dx
        dforce[a, 1] += dy
        dforce[a, 2] += rax * dy - ray * dx
        dforce[b, 0] -= dx
        dforce[b, 1] -= dy
        dforce[b, 2] -= rbx * dy - rby * dx
    return strain


@nb.njit(cache=True, inline="always")
def step(packed, par, acc, kind, gparams, t, ground_on, settle, work):
    """One central-difference step from t_n: contacts at x^n, forces with the lagged velocities
    v^(n-1/2), then v^(n+1/2) and x^(n+1). ``work.record[i] = (x, y, theta, vx, vy, omega)``
    at step n (velocities averaged over the two half steps) for output.

    Parameters
    ----------
    packed : Packed
    par, acc : (N_PAR,), (N_ACC,) parameters and accumulators (P_*, A_* indices)
    kind, gparams : the ground motion's kernel spec
    t : float, s
    ground_on, settle : bool
    work : Scratch

    Returns the ground acceleration used, m/s^2."""
    state, mass, inertia, free = packed.state, packed.mass, packed.inertia, packed.free
    force, dforce, record = work.force, work.dforce, work.record
    vw, edir, slots = work.vw, work.edir, work.slots
    vstart, sl_i, sl_edge, sl_f = packed.vstart, packed.sl_i, packed.sl_edge, packed.sl_f
    dt = par[P_DT]
    g = par[P_G]
    alpha = par[P_ALPHA]
    nbk = state.shape[0]
    world_vertices(state, packed.vloc, packed.eloc, vstart, vw, edir)
    update_contacts(state, packed.radius, vw, edir, vstart, sl_i, sl_edge, sl_f, slots, work.cand,
                    work.blocker, par, acc)
    force[:, :] = 0.0
    dforce[:, :] = 0.0
    acc[A_SE] = contact_forces(state, vw, edir, sl_i, sl_edge, sl_f, slots, par, acc, force,
                               dforce)
    ag = ground_acceleration(kind, gparams, t) if ground_on else 0.0
    # a vertical ground acceleration, in the ground's vertical frame: gravity g + av on every
    # free block (its input work -m av on the vertical velocities)
    av = vertical_in_piece(kind, gparams, t, t) if ground_on else 0.0
    vb_old = acc[A_VB]
    vb_new = vb_old + ag * dt
    kinetic = 0.0
    kinetic_half = 0.0
    p_damp = 0.0
    p_in = 0.0
    for i in range(nbk):
        for k in range(3):
            record[i, k] = state[i, k]
        if free[i] == 0:
            record[i, 3] = 0.5 * (vb_old + vb_new)
            record[i, 4] = 0.0
            record[i, 5] = 0.0
            state[i, 3] = vb_new
            state[i, 4] = 0.0
            state[i, 5] = 0.0
            state[i, 0] += dt * vb_new
            continue
        m = mass[i]
        inert = inertia[i]
        ux = state[i, 3] - vb_old
        uy = state[i, 4]
        w = state[i, 5]
        dforce[i, 0] -= alpha * m * ux
        dforce[i, 1] -= alpha * m * uy
        dforce[i, 2] -= alpha * inert * w
        fx = force[i, 0] + dforce[i, 0]
        fy = force[i, 1] + dforce[i, 1] - m * (g + av)
        mz = force[i, 2] + dforce[i, 2]
        vx = state[i, 3] + dt * fx / m
        vy = state[i, 4] + dt * fy / m
        wn = state[i, 5] + dt * mz / inert
        uxn = vx - vb_new
        # leapfrog energy: product of the two half-step velocities (exactly conserved by the
        # scheme for linear springs); work terms use their average
        kinetic += 0.5 * m * (ux * uxn + uy * vy) + 0.5 * inert * w * wn
        kinetic_half += 0.5 * m * (uxn * uxn + vy * vy) + 0.5 * inert * wn * wn
        mx = 0.5 * (ux + uxn)
        my = 0.5 * (uy + vy)
        mw = 0.5 * (w + wn)
        p_damp += dforce[i, 0] * mx + dforce[i, 1] * my + dforce[i, 2] * mw
        p_in += -m * ag * mx - m * av * my
        record[i, 3] = 0.5 * (state[i, 3] + vx)
        record[i, 4] = my
        record[i, 5] = mw
        state[i, 3] = vx
        state[i, 4] = vy
        state[i, 5] = wn
        state[i, 0] += dt * vx
        state[i, 1] += dt * vy
        state[i, 2] += dt * wn
    acc[A_VB] = vb_new
    acc[A_XB] += dt * vb_new
    acc[A_DAMP] -= p_damp * dt
    acc[A_WIN] += p_in * dt
    acc[A_KE] = kinetic
    if settle:
        # kinetic damping: stop every free block whenever the kinetic energy passes a peak
        if kinetic_half < acc[A_KEPREV]:
            for i in range(nbk):
                if free[i] != 0:
                    state[i, 3] = 0.0
                    state[i, 4] = 0.0
                    state[i, 5] = 0.0
            acc[A_KEPREV] = 0.0
        else:
            acc[A_KEPREV] = kinetic_half
    return ag


@nb.njit(cache=True)
def run(packed, par, acc, kind, gparams, cpar, ref, margin, span, out):
    """Advance from global step ``span.step0`` until ``span.n_steps`` (global), recording every
    ``span.out_every`` steps into ``out``. Returns (next global step, status): STATUS_DONE,
    STATUS_COLLAPSE (first output sample meeting a collapse criterion, when stopping at
    collapse) or STATUS_REBUILD (some block moved more than margin/2 from ``ref`` since the
    neighbour lists were built). The steps look at the slots `slots_in_reach` keeps for
    the positions at the call (those of ``ref``).

    Parameters
    ----------
    packed : Packed
    par, acc : parameters and accumulators
    kind, gparams : the ground motion's kernel spec
    cpar : (N_COLLAPSE,) collapse criteria (`collapsed`)
    ref : (nb, 3) block positions when the neighbour lists were built
    margin : float, m, the neighbour lists' margin
    span : Span
    out : Output
    """
    state, mass, free, y_ref = packed.state, packed.mass, packed.free, packed.y_ref
    radius = packed.radius
    nbk = state.shape[0]
    dt = par[P_DT]
    g = par[P_G]
    nv = packed.vloc.shape[0]
    vw = np.zeros((nv, 2))
    edir = np.zeros((nv, 3))
    world_vertices(state, packed.vloc, packed.eloc, packed.vstart, vw, edir)
    slots = slots_in_reach(state, radius, free, vw, packed.sl_i, par, margin)
    work = Scratch(np.zeros((nbk, 3)), np.zeros((nbk, 3)), np.zeros((nbk, 6)), vw, edir, slots,
                   np.zeros(slots.shape[0], dtype=np.int64),
                   np.full(packed.sl_i.shape[0], -1, dtype=np.int64))
    record = work.record
    out_every = span.out_every
    out_t, out_state, out_energy, out_count = out.times, out.states, out.energies, out.written
    n = span.step0
    while n < span.n_steps:
        t = n * dt
        step(packed, par, acc, kind, gparams, t, span.ground_on, span.settle, work)
        n += 1
        if out_every > 0 and (n - 1) % out_every == 0:
            k = out_count[0]
            if k < out_t.shape[0]:
                out_t[k] = t
                for i in range(nbk):
                    for j in range(6):
                        out_state[k, i, j] = record[i, j]
                pe = 0.0
                for i in range(nbk):
                    if free[i] != 0:
                        pe += mass[i] * g * (record[i, 1] - y_ref[i])
                out_energy[k, 0] = acc[A_KE]
                out_energy[k, 1] = pe
                out_energy[k, 2] = acc[A_SE]
                out_energy[k, 3] = acc[A_DAMP]
                out_energy[k, 4] = acc[A_FRIC]
                out_energy[k, 5] = acc[A_WIN]
                out_energy[k, 6] = acc[A_XB] - dt * acc[A_VB]
                out_energy[k, 7] = record[0, 3] if free[0] == 0 else acc[A_VB]
                out_count[0] = k + 1
                if span.stop_at_collapse and collapsed(record, free, cpar):
                    return n, STATUS_COLLAPSE
        if (n & 63) == 0:
            for i in range(nbk):
                if free[i] == 0:
                    continue
                dx = state[i, 0] - ref[i, 0]
                dy = state[i, 1] - ref[i, 1]
                moved = math.sqrt(dx * dx + dy * dy) + radius[i] * abs(state[i, 2] - ref[i, 2])
                if moved > 0.5 * margin:
                    return n, STATUS_REBUILD
    return n, STATUS_DONE
