"""Plain-NumPy reference of `archquake.dem._kernels.step` (vectorised over slots and
blocks). Test-only: no production code imports it.

Written independently of the compiled loops (array expressions instead of scalar loops) so
that a test can hold the kernel to it: same trajectory to round-off over a few hundred steps.
Same packed layout (`Packed`) and the same rules, in the same
order (see the kernel module docstring).
"""

from __future__ import annotations

import numpy as np

from archquake.dem._kernels import (
    A_DAMP,
    A_FRIC,
    A_KE,
    A_KEPREV,
    A_SE,
    A_VB,
    A_WIN,
    A_XB,
    ANGLE_TOL,
    F_FN,
    F_FS,
    F_KN,
    F_KS,
    F_SLIP,
    P_ALPHA,
    P_BETA,
    P_DMAX,
    P_DT,
    P_G,
    P_KN,
    P_KS,
    P_MU,
    P_TOL,
)
from archquake.ground._kernel import ground_acceleration


def world_vertices(state, vloc, vstart):
    """World vertex coordinates (nv, 2) and edge tangents and lengths (nv, 3)."""
    nv = vloc.shape[0]
    blk = np.repeat(np.arange(len(vstart) - 1), np.diff(vstart))
    th = state[blk, 2]
    c, s = np.cos(th), np.sin(th)
    vw = np.stack(
        [state[blk, 0] + c * vloc[:, 0] - s * vloc[:, 1],
         state[blk, 1] + s * vloc[:, 0] + c * vloc[:, 1]],
        axis=1,
    )
    nxt = _next(np.arange(nv), blk, vstart)
    d = vw[nxt] - vw
    length = np.hypot(d[:, 0], d[:, 1])
    edir = np.column_stack([d[:, 0] / length, d[:, 1] / length, length])
    return vw, edir


def _next(v, blk, vstart):
    w = v + 1
    return np.where(w >= vstart[blk + 1], vstart[blk], w)


def _prev(v, blk, vstart):
    w = v - 1
    return np.where(w < vstart[blk], vstart[blk + 1] - 1, w)


def _edge_frame(vw, edir, e, p):
    t = edir[e, :2]
    length = edir[e, 2]
    n = np.stack([t[..., 1], -t[..., 0]], axis=-1)
    r = p - vw[e]
    overlap = -np.sum(r * n, axis=-1)
    spar = np.sum(r * t, axis=-1) / length
    return overlap, spar, n, t, length


def update_contacts(vw, edir, vstart, sl_i, sl_edge, sl_f, par, acc):
    """The kernel's contact update."""
    tol, dmax = par[P_TOL], par[P_DMAX]
    v, a, b = sl_i[:, 0], sl_i[:, 1], sl_i[:, 2]
    act = np.flatnonzero(sl_edge >= 0)
    if act.size:
        overlap, spar, _, _, length = _edge_frame(vw, edir, sl_edge[act], vw[v[act]])
        slack = tol / length
        drop = (overlap <= 0) | (overlap > dmax) | (spar < -slack) | (spar > 1 + slack)
        gone = act[drop]
        acc[A_FRIC] += float(np.sum(0.5 * sl_f[gone, F_FS] ** 2 / sl_f[gone, F_KS]))
        sl_edge[gone] = -1
        sl_f[gone, F_FS] = 0.0
        sl_f[gone, F_FN] = 0.0
    for pas in (0, 1):
        cand = np.flatnonzero((sl_edge < 0) & ((a > b) == (pas == 1)))
        if cand.size == 0:
            continue
        nedge = vstart[b[cand] + 1] - vstart[b[cand]]
        owner = np.repeat(np.arange(cand.size), nedge)
        offs = np.arange(owner.size) - np.repeat(np.cumsum(nedge) - nedge, nedge)
        edges = np.repeat(vstart[b[cand]], nedge) + offs
        s_of = cand[owner]
        vv = v[s_of]
        vp = _prev(vv, a[s_of], vstart)
        overlap, spar, n, t, length = _edge_frame(vw, edir, edges, vw[vv])
        out_n = np.sum(edir[vv, :2] * n, axis=1)
        out_p = -np.sum(edir[vp, :2] * n, axis=1)
        ok = (overlap > 0) & (overlap <= dmax) & (spar >= 0) & (spar <= 1)
        ok &= (out_n >= -ANGLE_TOL) & (out_p >= -ANGLE_TOL)
        face = np.minimum(np.sum(edir[vp, :2] * t, axis=1), np.sum(edir[vv, :2] * t, axis=1))
        score = np.where(ok, face, np.inf)
        best = np.full(cand.size, np.inf)
        np.minimum.at(best, owner, score)
        is_best = ok & (score == best[owner])
        pick = np.full(cand.size, -1)
        idx = np.flatnonzero(is_best)[::-1]
        pick[owner[idx]] = idx  # the first edge attaining the minimum, as the scalar loop does
        has = pick >= 0
        if not np.any(has):
            continue
        cs = cand[has]
        k = pick[has]
        pc = vw[v[cs]]
        # vertex-on-vertex duplicates against the active reverse slots
        nrev = sl_i[cs, 4] - sl_i[cs, 3]
        rown = np.repeat(np.arange(cs.size), nrev)
        roffs = np.arange(rown.size) - np.repeat(np.cumsum(nrev) - nrev, nrev)
        r = np.repeat(sl_i[cs, 3], nrev) + roffs
        live = sl_edge[r] >= 0
        q = vw[sl_i[r, 0]]
        close = live & (np.hypot(*(pc[rown] - q).T) < tol)
        blocked = np.zeros(cs.size, dtype=bool)
        blocked[rown[close]] = True
        keep = ~blocked
        cs, k = cs[keep], k[keep]
        if cs.size == 0:
            continue
        tb, lb = t[k], length[k]
        vp_c = vp[k]
        vv_c = vv[k]
        dot_p = np.sum(edir[vp_c, :2] * tb, axis=1)
        dot_n = np.sum(edir[vv_c, :2] * tb, axis=1)
        lf = np.where(dot_p < dot_n, edir[vp_c, 2], edir[vv_c, 2])
        trib = 0.5 * np.minimum(lb, lf)
        sl_edge[cs] = edges[k]
        sl_f[cs, F_KN] = par[P_KN] * trib
        sl_f[cs, F_KS] = par[P_KS] * trib
        sl_f[cs, F_FS] = 0.0
        sl_f[cs, F_FN] = 0.0


def contact_forces(state, vw, edir, sl_i, sl_edge, sl_f, par, acc, force, dforce):
    dt, beta, mu = par[P_DT], par[P_BETA], par[P_MU]
    act = np.flatnonzero(sl_edge >= 0)
    if act.size == 0:
        return 0.0
    v, a, b = sl_i[act, 0], sl_i[act, 1], sl_i[act, 2]
    p = vw[v]
    overlap, _, n, t, _ = _edge_frame(vw, edir, sl_edge[act], p)
    ra = p - state[a, :2]
    rb = p - state[b, :2]
    va = state[a, 3:5] + state[a, 5, None] * np.stack([-ra[:, 1], ra[:, 0]], axis=1)
    vb = state[b, 3:5] + state[b, 5, None] * np.stack([-rb[:, 1], rb[:, 0]], axis=1)
    vr = va - vb
    vn = np.sum(vr * n, axis=1)
    vs = np.sum(vr * t, axis=1)
    kn, ks = sl_f[act, F_KN], sl_f[act, F_KS]
    fn_el = kn * overlap
    fn_tot = np.maximum(fn_el - beta * kn * vn, 0.0)
    fn_visc = fn_tot - fn_el
    fs_trial = sl_f[act, F_FS] - ks * vs * dt
    limit = mu * fn_el
    sliding = np.abs(fs_trial) > limit
    fs = np.where(sliding, np.copysign(limit, fs_trial), fs_trial)
    slip = np.where(sliding, (np.abs(fs_trial) - limit) / ks, 0.0)
    acc[A_FRIC] += float(np.sum(limit * slip))
    sl_f[act, F_SLIP] += slip
    fs_visc = np.where(sliding, 0.0, -beta * ks * vs)
    sl_f[act, F_FS] = fs
    sl_f[act, F_FN] = fn_tot
    f = fn_el[:, None] * n + fs[:, None] * t
    d = fn_visc[:, None] * n + fs_visc[:, None] * t
    for arr, vec in ((force, f), (dforce, d)):
        np.add.at(arr[:, 0], a, vec[:, 0])
        np.add.at(arr[:, 1], a, vec[:, 1])
        np.add.at(arr[:, 2], a, ra[:, 0] * vec[:, 1] - ra[:, 1] * vec[:, 0])
        np.add.at(arr[:, 0], b, -vec[:, 0])
        np.add.at(arr[:, 1], b, -vec[:, 1])
        np.add.at(arr[:, 2], b, -(rb[:, 0] * vec[:, 1] - rb[:, 1] * vec[:, 0]))
    return float(np.sum(0.5 * fn_el * overlap + 0.5 * fs * fs / ks))


def step(packed, par, acc, kind, gparams, t, ground_on, settle, work):
    """NumPy reference of `archquake.dem._kernels.step` (same arguments, same effects;
    ``work.vw`` and ``work.edir`` are not used)."""
    state, mass, inertia, free = packed.state, packed.mass, packed.inertia, packed.free
    vloc, vstart = packed.vloc, packed.vstart
    sl_i, sl_edge, sl_f = packed.sl_i, packed.sl_edge, packed.sl_f
    force, dforce, record = work.force, work.dforce, work.record
    dt, g, alpha = par[P_DT], par[P_G], par[P_ALPHA]
    vw, edir = world_vertices(state, vloc, vstart)
    update_contacts(vw, edir, vstart, sl_i, sl_edge, sl_f, par, acc)
    force[:] = 0.0
    dforce[:] = 0.0
    acc[A_SE] = contact_forces(state, vw, edir, sl_i, sl_edge, sl_f, par, acc, force, dforce)
    ag = float(ground_acceleration(kind, gparams, t)) if ground_on else 0.0
    vb_old = acc[A_VB]
    vb_new = vb_old + ag * dt
    fr = free != 0
    record[:, :3] = state[:, :3]
    fixed = ~fr
    record[fixed, 3] = 0.5 * (vb_old + vb_new)
    record[fixed, 4:] = 0.0
    state[fixed, 3] = vb_new
    state[fixed, 4:] = 0.0
    state[fixed, 0] += dt * vb_new
    m, inert = mass[fr], inertia[fr]
    u_old = state[fr, 3:6].copy()
    u_old[:, 0] -= vb_old
    dforce[fr, 0] -= alpha * m * u_old[:, 0]
    dforce[fr, 1] -= alpha * m * u_old[:, 1]
    dforce[fr, 2] -= alpha * inert * u_old[:, 2]
    total = force[fr] + dforce[fr]
    total[:, 1] -= m * g
    new = state[fr, 3:6] + dt * total / np.stack([m, m, inert], axis=1)
    u_new = new.copy()
    u_new[:, 0] -= vb_new
    mvec = np.stack([m, m, inert], axis=1)
    kinetic = float(np.sum(0.5 * mvec * u_old * u_new))
    kinetic_half = float(np.sum(0.5 * mvec * u_new * u_new))
    mean = 0.5 * (u_old + u_new)
    p_damp = float(np.sum(dforce[fr] * mean))
    p_in = float(np.sum(-m * ag * mean[:, 0]))
    rec = record[fr]
    rec[:, 3] = 0.5 * (state[fr, 3] + new[:, 0])
    rec[:, 4:] = mean[:, 1:]
    record[fr] = rec
    state[fr, 3:6] = new
    state[fr, :3] += dt * new
    acc[A_VB] = vb_new
    acc[A_XB] += dt * vb_new
    acc[A_DAMP] -= p_damp * dt
    acc[A_WIN] += p_in * dt
    acc[A_KE] = kinetic
    if settle:
        if kinetic_half < acc[A_KEPREV]:
            state[fr, 3:6] = 0.0
            acc[A_KEPREV] = 0.0
        else:
            acc[A_KEPREV] = kinetic_half
    return ag
