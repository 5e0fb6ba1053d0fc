"""Driver of the distinct-element model: pack, settle, step, record.

The three layers follow scipy's ``solve_ivp``: the compiled step
(`archquake.dem._kernels.step`, NumPy reference in `archquake.dem._reference`), a
stepper loop with a written contract (`archquake.dem._kernels.run`), and this driver that
packs the assembly, chooses the time step, brings the assembly to rest under gravity, runs it
and hands the samples to `archquake.blocks.BlockResult`, which classifies the run.

Frames. Positions and velocities are absolute; the base blocks move with the ground, whose
velocity and displacement are the central-difference integrals of x_g''(t_n) taken inside the
same time stepping (v_b^(n+1/2) = v_b^(n-1/2) + x_g''(t_n) dt). Mass-proportional damping acts
on the block velocities *relative to the base*: a rigid translation with the ground is not
resisted (damping the absolute velocity, as UDEC does, would add a spurious drag
-alpha m v_g that depends on the ground's velocity, i.e. on the frame; with the paper's
alpha = 6.28e-5 1/s either choice changes the forces by < 1e-4 of the weight).
Stiffness-proportional damping acts on the contact relative velocities (frame-independent).
Energies are those of the motion relative to the ground, where the ground's acceleration is
the inertial body force -m x_g'': kinetic + potential + strain + damping + friction - input
work stays constant (`BlockResult.energy_error`).
"""

from __future__ import annotations

import math

import numpy as np

import archquake.dem._kernels as K
from archquake._validate import require_gravity
from archquake.blocks.assembly import Assembly, build_arch_assembly
from archquake.blocks.criteria import DEFAULT_TAIL, default_window
from archquake.blocks.result import (
    BlockResult,
    collapse_parameters,
    crown_height,
    excitation_end,
    rest_threshold,
    settled,
)
from archquake.constants import STANDARD_GRAVITY
from archquake.dem._kernels import Packed
from archquake.dem.settings import DemSettings
from archquake.errors import InvalidParameterError, SolverError
from archquake.geometry.arch import Arch
from archquake.geometry.chain import VoussoirChain
from archquake.ground.base import GroundMotion, check_lift_off, check_motion
from archquake.ranges import DEM_MAX_BLOCK_STEPS, DEM_SECONDS_PER_BLOCK_STEP

#: Most time steps a run may take (guards against absurd stiffness/duration choices).
MAX_STEPS = 200_000_000

#: Most bytes the recorded output of one run may take (its samples are allocated up front,
#: duration / output_interval of them).
MAX_OUTPUT_BYTES = 1_000_000_000


# --------------------------------------------------------------------------- packing
def pack(assembly: Assembly) -> Packed:
    """Blocks at rest in the undisplaced configuration (theta = 0, local = polygon - centroid),
    no contact slots yet (`build_slots`)."""
    nb = assembly.n_blocks
    cents = np.array(assembly.centroids, dtype=float)
    counts = np.array([len(p) for p in assembly.polygons])
    vstart = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    vloc = np.vstack([p - c for p, c in zip(assembly.polygons, cents)])
    radius = np.array([np.max(np.hypot(*(p - c).T)) for p, c in zip(assembly.polygons, cents)])
    state = np.zeros((nb, 6))
    state[:, :2] = cents
    free = (~np.asarray(assembly.base)).astype(np.int64)
    return Packed(
        state=state,
        mass=np.where(free == 1, assembly.masses, 1.0).astype(float),
        inertia=np.where(free == 1, assembly.inertias, 1.0).astype(float),
        free=free,
        y_ref=cents[:, 1].copy(),
        vloc=vloc,
        vstart=vstart,
        radius=radius,
        eloc=edge_frames(vloc, vstart),
        sl_i=np.zeros((0, 5), np.int64),
        sl_edge=np.zeros(0, np.int64),
        sl_f=np.zeros((0, 5)),
    )


def edge_frames(vloc: np.ndarray, vstart: np.ndarray) -> np.ndarray:
    """Each edge's unit tangent and length in its block's own frame, (nv, 3): edge e runs from
    vertex e to the next vertex of its block (``vloc``, m, relative to the centroid)."""
    out = np.empty((vloc.shape[0], 3))
    for b in range(vstart.size - 1):
        lo, hi = int(vstart[b]), int(vstart[b + 1])
        d = np.roll(vloc[lo:hi], -1, axis=0) - vloc[lo:hi]
        length = np.hypot(d[:, 0], d[:, 1])
        out[lo:hi, :2] = d / length[:, None]
        out[lo:hi, 2] = length
    return out


def neighbour_pairs(packed: Packed, margin: float) -> list[tuple[int, int]]:
    """Block pairs (a < b, not both base) whose bounding circles are closer than ``margin``."""
    xy = packed.state[:, :2]
    r = packed.radius
    d = np.hypot(xy[:, None, 0] - xy[None, :, 0], xy[:, None, 1] - xy[None, :, 1])
    close = d < r[:, None] + r[None, :] + margin
    pairs = []
    nb = len(r)
    for a in range(nb):
        for b in range(a + 1, nb):
            if close[a, b] and (packed.free[a] or packed.free[b]):
                pairs.append((a, b))
    return pairs


def build_slots(packed: Packed, pairs: list[tuple[int, int]]) -> Packed:
    """``packed`` with its contact slots (re)built for ``pairs``, keeping the state of
    surviving contacts (the block arrays are shared, not copied)."""
    old = {}
    for s in range(packed.sl_i.shape[0]):
        if packed.sl_edge[s] >= 0:
            old[(int(packed.sl_i[s, 0]), int(packed.sl_i[s, 2]))] = (
                packed.sl_edge[s],
                packed.sl_f[s].copy(),
            )
    rows: list[tuple[int, int, int, int, int]] = []
    vs = packed.vstart
    for a, b in pairs:
        na, nbv = vs[a + 1] - vs[a], vs[b + 1] - vs[b]
        s0 = len(rows)
        for v in range(vs[a], vs[a + 1]):
            rows.append((v, a, b, s0 + na, s0 + na + nbv))
        for v in range(vs[b], vs[b + 1]):
            rows.append((v, b, a, s0, s0 + na))
    sl_i = np.array(rows, dtype=np.int64).reshape(-1, 5)
    sl_edge = np.full(len(rows), -1, dtype=np.int64)
    sl_f = np.zeros((len(rows), 5))
    sl_f[:, K.F_KS] = 1.0
    for s, (v, _, b, _, _) in enumerate(rows):
        kept = old.get((v, b))
        if kept is not None:
            sl_edge[s], sl_f[s] = kept
    return packed._replace(sl_i=sl_i, sl_edge=sl_edge, sl_f=sl_f)


def _params(assembly: Assembly, settings: DemSettings, dt: float, g: float, *,
            broad_phase: bool = True) -> np.ndarray:
    law = settings.contact
    par = np.zeros(K.N_PAR)
    par[K.P_DT] = dt
    par[K.P_G] = g
    par[K.P_ALPHA], par[K.P_BETA] = settings.damping
    par[K.P_MU] = law.friction
    par[K.P_KN] = law.normal_stiffness * assembly.depth
    par[K.P_KS] = float(law.shear_stiffness or law.normal_stiffness) * assembly.depth
    par[K.P_TOL] = contact_tolerance(assembly)
    par[K.P_DMAX] = 0.25 * assembly.min_edge
    par[K.P_BROAD] = 1.0 if broad_phase else 0.0  # (K.update_contacts, K.slots_in_reach)
    return par


def contact_tolerance(assembly: Assembly) -> float:
    """Length (m) within which two corners count as the same point and a contact may slide
    past the end of its edge before it is dropped: 1e-3 of the shortest polygon edge."""
    return 1e-3 * assembly.min_edge


# --------------------------------------------------------------------------- time step
def block_steps(assembly: Assembly, duration: float, dt: float, settle_time: float) -> int:
    """The work of a run, in block-steps (blocks times steps, the settling's included): what
    ``ranges.DEM_MAX_BLOCK_STEPS`` bounds. ``duration``, ``dt``, ``settle_time`` in s."""
    steps = int(math.ceil(duration / dt - 1e-9)) + int(math.ceil(settle_time / dt - 1e-9))
    return steps * assembly.n_blocks


def stable_time_step(
    assembly: Assembly, settings: DemSettings, *, g: float = STANDARD_GRAVITY
) -> tuple[float, float]:
    """Stable central-difference time step, s, and the bound on the highest circular
    frequency, rad/s, used for it.

    omega_max^2 is the largest eigenvalue of the mass-normalised stiffness M^-1/2 K M^-1/2 of
    the contacts present at rest (normal and shear spring of every corner contact, lever arms
    included; base blocks rigid): exact for up to 500 blocks, Gershgorin's bound beyond.
    With Rayleigh damping the lagged-velocity central-difference scheme is stable for
    omega dt < 2 (sqrt(1 + xi^2) - xi), xi = alpha / (2 omega) + beta omega / 2, so

        dt = safety * 2 / omega_max * (sqrt(1 + xi_max^2) - xi_max).

    Contacts that form later (impacts) use the same tributary lengths, so the bound holds
    while the contact set does not grow beyond the one at rest (true for arches and rocking
    blocks; pass ``DemSettings.time_step`` for assemblies that start apart).
    """
    packed = pack(assembly)
    packed = build_slots(packed, neighbour_pairs(packed, 0.1 * float(packed.radius.min())))
    par = _params(assembly, settings, 1.0, g)
    vw, edir = _at_rest_frames(packed)
    _contacts_at_rest(vw, edir, packed, par)
    act = np.flatnonzero(packed.sl_edge >= 0)
    if act.size == 0:
        raise InvalidParameterError(
            "no contacts at rest: give DemSettings.time_step explicitly for assemblies that start apart"
        )
    st = packed.state
    nb = st.shape[0]
    tangent = edir[:, :2]
    # the stiffness as a sum of rank-one terms k w w^T, each w touching the 3 coordinates of at
    # most two blocks: kept sparse (a dense (3 nb)^2 matrix built term by term cost minutes
    # and a gigabyte for 2000 blocks)
    rows: list[np.ndarray] = []
    cols: list[np.ndarray] = []
    vals: list[np.ndarray] = []
    for s in act:
        v, a, b = packed.sl_i[s, :3]
        tx, ty = tangent[packed.sl_edge[s]]
        p = vw[v]
        for k, direction in ((packed.sl_f[s, K.F_KN], (ty, -tx)), (packed.sl_f[s, K.F_KS], (tx, ty))):
            idx: list[int] = []
            w: list[float] = []
            for blk, sgn in ((a, 1.0), (b, -1.0)):
                if not packed.free[blk]:
                    continue
                r = p - st[blk, :2]
                lever = r[0] * direction[1] - r[1] * direction[0]
                sm, si = math.sqrt(packed.mass[blk]), math.sqrt(packed.inertia[blk])
                idx.extend((3 * blk, 3 * blk + 1, 3 * blk + 2))
                w.extend((sgn * direction[0] / sm, sgn * direction[1] / sm, sgn * lever / si))
            if not idx:
                continue
            ii, ww = np.asarray(idx), np.asarray(w)
            rows.append(np.repeat(ii, ii.size))
            cols.append(np.tile(ii, ii.size))
            vals.append(k * np.outer(ww, ww).ravel())
    # each entry summed in contact order, from 0.0, as a dense stiff += k w w^T would (np.add.at
    # adds in the order given): the same bits, so the time step and every DEM number stay
    # byte-identical to the dense computation
    r_all, c_all = np.concatenate(rows), np.concatenate(cols)
    keys, inverse = np.unique(r_all * (3 * nb) + c_all, return_inverse=True)
    summed = np.zeros(keys.size)
    np.add.at(summed, inverse, np.concatenate(vals))
    from scipy.sparse import coo_matrix  # (the DEM's only use of scipy: imported here)

    stiff = coo_matrix((summed, (keys // (3 * nb), keys % (3 * nb))), shape=(3 * nb, 3 * nb))
    if nb <= 500:
        lam = float(np.linalg.eigvalsh(stiff.toarray())[-1])
    else:  # Gershgorin bound (row sums over the nonzeros: may differ from a dense sum by ulps)
        lam = float(np.max(np.asarray(abs(stiff.tocsr()).sum(axis=1)).ravel()))
    omega = math.sqrt(lam)
    alpha, beta = settings.damping
    xi = alpha / (2 * omega) + beta * omega / 2
    dt = settings.safety * 2.0 / omega * (math.sqrt(1 + xi * xi) - xi)
    return dt, omega


def _at_rest_frames(packed: Packed) -> tuple[np.ndarray, np.ndarray]:
    """World vertices (nv, 2) of the undisplaced blocks and every edge's unit tangent and
    length (nv, 3), as `archquake.dem._kernels.world_vertices` lays them out (at theta = 0 the
    blocks' own edge frames, `edge_frames`)."""
    blk = np.repeat(np.arange(len(packed.vstart) - 1), np.diff(packed.vstart))
    vw = packed.state[blk, :2] + packed.vloc  # theta = 0
    return vw, packed.eloc.copy()


def _contacts_at_rest(vw: np.ndarray, edir: np.ndarray, packed: Packed, par: np.ndarray) -> None:
    """The contacts of the undisplaced assembly, written into ``packed.sl_edge``/``sl_f``.

    The kernel's rule for new contacts (`archquake.dem._kernels.update_contacts`: an
    edge within whose length the corner lies, neither edge at the corner dipping into it by
    more than ``ANGLE_TOL``, best facing; the lower-numbered block's corners first, a corner
    coinciding with an active corner of the other block skipped), except that corners up to
    the contact tolerance *outside* an edge count: at rest the blocks exactly touch
    (overlap 0), which the kernel's rule (overlap > 0) would not accept.
    """
    tol = float(par[K.P_TOL])
    sl_i, sl_edge, sl_f, vstart = packed.sl_i, packed.sl_edge, packed.sl_f, packed.vstart
    v, a, b = sl_i[:, 0], sl_i[:, 1], sl_i[:, 2]
    blk = np.repeat(np.arange(len(vstart) - 1), np.diff(vstart))
    nrm = np.column_stack([edir[:, 1], -edir[:, 0]])
    for pas in (0, 1):
        cand = np.flatnonzero((sl_edge < 0) & ((a > b) == (pas == 1)))
        if cand.size == 0:
            continue
        nedge = vstart[b[cand] + 1] - vstart[b[cand]]
        owner = np.repeat(np.arange(cand.size), nedge)
        edges = np.repeat(vstart[b[cand]], nedge) + (
            np.arange(owner.size) - np.repeat(np.cumsum(nedge) - nedge, nedge))
        vv = v[cand[owner]]
        vp = np.where(vv - 1 < vstart[blk[vv]], vstart[blk[vv] + 1] - 1, vv - 1)
        r = vw[vv] - vw[edges]
        overlap = -np.sum(r * nrm[edges], axis=1)
        spar = np.sum(r * edir[edges, :2], axis=1) / edir[edges, 2]
        ok = (overlap > -tol) & (overlap <= par[K.P_DMAX]) & (spar >= 0) & (spar <= 1)
        ok &= np.sum(edir[vv, :2] * nrm[edges], axis=1) >= -K.ANGLE_TOL
        ok &= -np.sum(edir[vp, :2] * nrm[edges], axis=1) >= -K.ANGLE_TOL
        dot_p = np.sum(edir[vp, :2] * edir[edges, :2], axis=1)
        dot_n = np.sum(edir[vv, :2] * edir[edges, :2], axis=1)
        score = np.where(ok, np.minimum(dot_p, dot_n), np.inf)
        best = np.full(cand.size, np.inf)
        np.minimum.at(best, owner, score)
        pick = np.full(cand.size, -1)
        idx = np.flatnonzero(ok & (score == best[owner]))[::-1]
        pick[owner[idx]] = idx  # the first edge attaining the minimum, as the kernel does
        for c, k in zip(cand[pick >= 0], pick[pick >= 0]):
            rev = np.arange(sl_i[c, 3], sl_i[c, 4])
            live = rev[sl_edge[rev] >= 0]
            if np.any(np.hypot(*(vw[v[c]] - vw[sl_i[live, 0]]).T) < tol):
                continue
            lf = edir[vp[k], 2] if dot_p[k] < dot_n[k] else edir[vv[k], 2]
            trib = 0.5 * min(edir[edges[k], 2], lf)
            sl_edge[c] = edges[k]
            sl_f[c, K.F_KN] = par[K.P_KN] * trib
            sl_f[c, K.F_KS] = par[K.P_KS] * trib


# --------------------------------------------------------------------------- driver
def simulate_dem(
    arch_or_assembly: Arch | Assembly,
    motion: GroundMotion,
    settings: DemSettings | None = None,
    *,
    g: float = STANDARD_GRAVITY,
    broad_phase: bool = True,
) -> BlockResult:
    """Run the distinct-element model of an arch (or any block assembly) under ``motion``.

    Parameters
    ----------
    arch_or_assembly : Arch or Assembly
        An Arch is built with `build_arch_assembly` (every voussoir a block).
    motion : GroundMotion
        Horizontal ground acceleration (any archquake motion: pulses, records).
    settings : DemSettings, optional
        Default ``DemSettings()`` (the paper's stiffness and damping).
    g : float
        Gravity, m/s^2.
    broad_phase : bool
        Leave out of the contact search the corners that cannot touch the other block (out of
        its reach, or on one of its active corners). False scans every corner against every
        edge of each neighbouring block: the same numbers, bit for bit, slower (for tests and
        benchmarks).

    Returns
    -------
    BlockResult
    """
    assembly = (
        build_arch_assembly(arch_or_assembly) if isinstance(arch_or_assembly, VoussoirChain)
        else arch_or_assembly
    )
    if not isinstance(assembly, Assembly):
        raise InvalidParameterError(
            f"simulate_dem needs an Arch or an Assembly, got {type(arch_or_assembly).__name__}"
        )
    settings = DemSettings() if settings is None else settings
    if not isinstance(settings, DemSettings):
        raise InvalidParameterError(f"settings must be a DemSettings, got {type(settings).__name__}")
    g = require_gravity(g)
    kind, gparams = check_motion(motion).kernel_spec()
    check_lift_off(kind, gparams, g)
    gparams = np.ascontiguousarray(gparams, dtype=float)
    omega = float("nan")
    if settings.time_step is None:
        dt, omega = stable_time_step(assembly, settings, g=g)
    else:
        dt = settings.time_step
    n_steps = int(math.ceil(settings.duration / dt - 1e-9))
    settle_steps = int(math.ceil(settings.settle_time / dt - 1e-9))
    if n_steps + settle_steps > MAX_STEPS:
        raise InvalidParameterError(
            f"{n_steps + settle_steps} time steps of {dt:.3g} s exceed {MAX_STEPS}: shorten the "
            "duration or soften the contact stiffness"
        )
    out_every = max(1, int(round(settings.output_interval / dt)))
    n_out = n_steps // out_every + 2
    out_bytes = n_out * (assembly.n_blocks * 6 + 9) * 8
    if out_bytes > MAX_OUTPUT_BYTES:
        raise InvalidParameterError(
            f"the recorded output would take {out_bytes / 1e9:.3g} GB ({n_out} samples of "
            f"{assembly.n_blocks} blocks), more than {MAX_OUTPUT_BYTES / 1e9:g} GB: raise "
            f"output_interval (now {settings.output_interval:g} s) or shorten the duration "
            f"(now {settings.duration:g} s)"
        )
    work = block_steps(assembly, settings.duration, dt, settings.settle_time)
    if work > DEM_MAX_BLOCK_STEPS:
        raise InvalidParameterError(
            f"{assembly.n_blocks} blocks over {n_steps + settle_steps:,} time steps of "
            f"{dt:.3g} s are {work:.3g} block-steps, more than {DEM_MAX_BLOCK_STEPS:.0e} (the "
            f"explicit DEM's time step shrinks with the blocks: about "
            f"{work * DEM_SECONDS_PER_BLOCK_STEP / 3600:.2g} h at "
            f"{DEM_SECONDS_PER_BLOCK_STEP * 1e6:g} us per block-step): use fewer voussoirs or "
            f"a shorter duration (now {settings.duration:g} s)")
    packed = pack(assembly)
    margin = 0.2 * float(packed.radius[packed.free == 1].min())
    packed = build_slots(packed, neighbour_pairs(packed, margin))
    par = _params(assembly, settings, dt, g, broad_phase=broad_phase)
    acc = np.zeros(K.N_ACC)
    # the crown's drop is measured from its height at t = 0, after settling (set below)
    criteria = settings.criteria
    cpar = collapse_parameters(assembly, criteria, math.nan)

    def advance(packed, ref, span, out):
        """Run ``span``, rebuilding the neighbour lists (built at the positions ``ref``) as the
        blocks move; returns (packed, ref, next step, status)."""
        while True:
            n, status = K.run(packed, par, acc, kind, gparams, cpar, ref, margin, span, out)
            if not np.all(np.isfinite(packed.state)):
                raise SolverError(
                    "the distinct-element state became non-finite: reduce DemSettings.safety or "
                    "time_step"
                )
            if status == K.STATUS_REBUILD:
                packed = build_slots(packed, neighbour_pairs(packed, margin))
                ref = packed.state[:, :3].copy()
                span = span._replace(step0=n)
                continue
            return packed, ref, n, status

    if settle_steps:
        none = K.Output(np.zeros(0), np.zeros((0, assembly.n_blocks, 6)), np.zeros((0, 8)),
                        np.zeros(1, dtype=np.int64))
        packed, _, _, _ = advance(packed, packed.state[:, :3].copy(),
                                  K.Span(0, settle_steps, 0, False, True, False), none)
    # start from rest, with the settled contact forces
    packed.state[:, 3:] = 0.0
    packed = packed._replace(y_ref=packed.state[:, 1].copy())
    acc[:] = 0.0
    cpar[:] = collapse_parameters(assembly, criteria,
                                  crown_height(assembly, packed.state[None, :, :3])[0])
    out = K.Output(np.zeros(n_out), np.zeros((n_out, assembly.n_blocks, 6)), np.zeros((n_out, 8)),
                   np.zeros(1, dtype=np.int64))
    span = K.Span(0, n_steps, out_every, True, False, settings.stop_at_collapse)
    ref = packed.state[:, :3].copy()
    exc_end = excitation_end(motion)
    if not settings.stop_at_rest or exc_end is None:
        packed, ref, taken, _ = advance(packed, ref, span, out)
    else:
        # in stretches of a quarter of the rest window, checking between them whether the run
        # is at rest after the excitation (the samples and the state are those of one run:
        # the same numbers as without the stops)
        window = rest_threshold(assembly, g)[1]
        stretch = max(out_every, int(0.25 * window / dt) // out_every * out_every)
        first = max(0, int(math.ceil((exc_end + window) / dt)))
        taken = 0
        while taken < n_steps:
            upto = min(n_steps, max(first, taken + stretch))
            packed, ref, taken, status = advance(packed, ref, span._replace(step0=taken,
                                                                           n_steps=upto), out)
            if status == K.STATUS_COLLAPSE:
                break
            k = int(out.written[0])
            if taken >= first and settled(assembly, g, out.times[:k], out.energies[:k, 0],
                                          exc_end):
                break
    k = int(out.written[0])
    return BlockResult.from_samples(
        assembly, settings,
        motion.to_dict() if hasattr(motion, "to_dict") else {"name": str(motion)}, g,
        dt, omega, taken, settle_steps, out.times[:k], out.states[:k], out.energies[:k],
        excitation_end=exc_end,
    )


__all__ = [
    "MAX_STEPS",
    "Packed",
    "block_steps",
    "contact_tolerance",
    "pack",
    "simulate_dem",
    "stable_time_step",
]


# ----------------------------------------------------------------------------- to a verdict
def default_dem_duration(arch, motion: GroundMotion, *, tail: float = DEFAULT_TAIL,
                         g: float = STANDARD_GRAVITY) -> float:
    """End of the excitation plus ``tail`` sqrt(R/g), s: the DEM's default simulated time
    (``arch``: anything with a ``radius``, m): `archquake.blocks.default_window`."""
    return default_window(motion, arch.radius, tail=tail, g=g)


#: Tails (sqrt(R/g)) after the excitation within which `dem_to_verdict` looks for a verdict.
VERDICT_TAILS = (DEFAULT_TAIL, 10.0, 20.0)


def dem_to_verdict(arch_or_assembly, motion: GroundMotion, settings=None, *,
                   radius: float | None = None, tails=VERDICT_TAILS,
                   g: float = STANDARD_GRAVITY) -> BlockResult:
    """The DEM run long enough for a verdict: one run to the end of the excitation plus the
    longest of ``tails`` sqrt(R/g) that stays within ``ranges.DEM_T_END_MAX_S`` and
    ``ranges.DEM_MAX_BLOCK_STEPS`` (the first one at least: a longer record's run may not
    afford the longest tail), ending at the collapse or once at rest after the excitation
    (``DemSettings.stop_at_rest``: `archquake.blocks.result.settled`, the rule of the
    ``survives`` verdict). Its outcome is ``indeterminate`` only if the arch still moves at
    the end of the longest tail.

    This is the verdict that running each tail in turn from the start, until one is not
    ``indeterminate``, gives: after the excitation the energy can only decrease, so an arch at
    rest stays at rest, and an arch still moving at the end of one tail was not at rest
    before it. It costs one run up to the verdict, where the tries cost a run per tail (a
    verdict in the second tail about three times the first's).

    ``radius``: R, m (default: the arch's; required for an Assembly)."""
    from archquake.ranges import DEM_T_END_MAX_S

    if not tails:
        raise InvalidParameterError("tails must give at least one tail, in sqrt(R/g)")
    r = float(radius if radius is not None else arch_or_assembly.radius)
    base = DemSettings() if settings is None else settings
    windows = [default_window(motion, r, tail=tail, g=g) for tail in tails]
    assembly = (build_arch_assembly(arch_or_assembly)
                if isinstance(arch_or_assembly, VoussoirChain) else arch_or_assembly)
    dt = (base.time_step if base.time_step is not None
          else stable_time_step(assembly, base, g=g)[0])
    longest = max([windows[0], *(
        w for w in windows[1:] if w <= DEM_T_END_MAX_S
        and block_steps(assembly, w, dt, base.settle_time) <= DEM_MAX_BLOCK_STEPS)])
    return simulate_dem(assembly, motion, base.with_(duration=longest, stop_at_rest=True), g=g)


__all__ += ["DEFAULT_TAIL", "VERDICT_TAILS", "default_dem_duration", "dem_to_verdict"]
