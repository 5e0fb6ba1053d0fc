"""The Moreau-Jean time stepper of the rigid-block chain (`archquake.rigid.model`), driven
chunk by chunk over a ground motion: ``simulate_rigid(..., solver="direct" or "pgs")``.

Each chunk of steps runs in the compiled kernel (`archquake.rigid._step_kernels.run`);
between chunks the run is checked for collapse (the DEM's criteria) and, past ``duration``
with ``until_rest``, for rest. The samples come back raw (`SteppedSamples`):
`archquake.rigid.run` turns them into a result.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass

import numpy as np

import archquake.rigid._step_kernels as RK
from archquake.blocks.criteria import BlockCriteria
from archquake.blocks.result import (
    collapse_parameters,
    crown_height,
    excitation_end,
    rest_threshold,
    settled,
)
from archquake.errors import SolverError
from archquake.rigid.model import (
    GAP_TOLERANCE,
    HOLD_TOLERANCE,
    MAX_SWEEPS,
    RigidModel,
    absolute_states,
    mean_acceleration,
    mean_vertical,
)

#: The contact step's solvers (``simulate_rigid``'s ``solver``) -> the kernel's method code.
METHODS = {"direct": RK.METHOD_DIRECT, "pgs": RK.METHOD_PGS}


@dataclass(frozen=True)
class SteppedSamples:
    """The recorded samples of a stepped run, relative to the ground.

    ``times`` (nt,) s; ``q``, ``v`` (nt, nb, 3) the free bodies' configurations and velocities
    (x, y m, theta rad, and rates); ``diag`` (nt, ``_step_kernels.N_DIAG``) the kernel's
    diagnostics at each sample; ``ground_displacement``, ``ground_velocity`` (nt,) m and m/s;
    ``time_step`` h, s; ``output_interval`` s (a whole number of steps); ``n_steps`` steps
    taken; ``max_sweeps`` most Gauss-Seidel sweeps of a step; ``wall_s`` wall time, s."""

    times: np.ndarray
    q: np.ndarray
    v: np.ndarray
    diag: np.ndarray
    ground_displacement: np.ndarray
    ground_velocity: np.ndarray
    time_step: float
    output_interval: float
    n_steps: int
    max_sweeps: int
    wall_s: float


def _at_rest(model: RigidModel, g: float, times: list, vs: list, motion) -> bool:
    """The samples so far end at rest (`archquake.blocks.result.settled`). ``times`` and
    ``vs`` are the recorded chunks, (n,) and (n, nb, 3) each; only the last window's are read."""
    window = rest_threshold(model.assembly, g)[1]
    t_last = float(times[-1][-1])
    first = len(times) - 1  # the chunks from this one on hold the window and the sample before
    while first > 0 and not times[first][0] <= t_last - window:
        first -= 1
    t = np.concatenate(times[first:])
    v = np.concatenate(vs[first:])
    k = len(t)
    while k > 1 and t[k - 1] > t_last - window:
        k -= 1
    kin = [model.kinetic_energy(vk) for vk in v[k - 1:]]
    return settled(model.assembly, g, t[k - 1:], np.array(kin), excitation_end(motion))


def run_steps(model: RigidModel, motion, settings: BlockCriteria, *, duration: float,
              time_step: float, output_interval: float,
              initial: tuple[np.ndarray, np.ndarray] | None, g: float, chunk: float,
              solver_tolerance: float, friction: float, solver: str,
              until_rest: float | None, progress=None) -> SteppedSamples:
    """Step the chain from ``initial`` (default rest) over ``motion``.

    Parameters
    ----------
    model : RigidModel
    motion : GroundMotion
    settings : BlockCriteria
        Its collapse criteria and ``stop_at_collapse`` are read.
    duration, time_step, output_interval, chunk : float
        s (validated by the caller).
    initial : (q, v), optional
        (nb, 3) each.
    g : float
        m/s^2.
    solver_tolerance : float
        Fraction of sqrt(g L).
    friction : float
        Coulomb coefficient of every joint, 0 for no sliding.
    solver : {"direct", "pgs"}
    until_rest : float, optional
        s: go on past ``duration`` until rest or this time.
    progress : callable, optional
        ``progress(steps_done, steps_at_most)``, called after each chunk.
    """
    import archquake.blocks._kernels as DK

    asm = model.assembly
    mu = friction
    h = float(time_step)
    out_every = max(1, int(round(output_interval / h)))
    n_total = int(math.ceil(duration / h - 1e-9))
    per_chunk = max(out_every, int(round(chunk / h)) // out_every * out_every)
    q, v = model.rest() if initial is None else (np.array(initial[0], float),
                                                  np.array(initial[1], float))
    p_warm = np.zeros((len(model.ja), 3))
    slip_ref = np.full(len(model.ja), np.nan)  # the joints' tangential offsets at contact, m
    state = RK.State(q, v, p_warm, slip_ref)
    diag = np.zeros(RK.N_DIAG)
    lref = asm.reference_length
    tol = float(solver_tolerance) * math.sqrt(g * lref)
    chain = model.chain
    cfg = RK.stepping(h, g, GAP_TOLERANCE * lref, tol, MAX_SWEEPS, mu, METHODS[solver], True,
                      HOLD_TOLERANCE * lref)
    free = (~np.asarray(asm.base, dtype=bool)).astype(np.int64)
    cpar = collapse_parameters(asm, settings, math.nan)
    # the samples, one array per chunk (the first chunk: the initial state)
    times: list[np.ndarray] = [np.zeros(1)]
    qs, vs, ds = [q[None].copy()], [v[None].copy()], [diag[None].copy()]
    ug: list[np.ndarray] = [np.zeros(1)]
    vg: list[np.ndarray] = [np.zeros(1)]
    u_cur = v_cur = 0.0
    step = 0
    worst = 0
    t_wall = _time.perf_counter()
    cpar[DK.C_CROWN_Y0] = crown_height(asm, absolute_states(model, q[None], v[None], np.zeros(1),
                                                            np.zeros(1))[:, :, :3])[0]
    collapsed = False
    n_cap = n_total if until_rest is None else max(n_total, int(math.ceil(until_rest / h - 1e-9)))
    while step < n_cap and not collapsed:
        if step >= n_total and _at_rest(model, g, times, vs, motion):
            break
        n = min(per_chunk, n_cap - step)
        n -= n % out_every if n >= out_every else 0
        n = max(n, 1)
        acc = mean_acceleration(motion, step * h, h, n)
        vacc = mean_vertical(motion, step * h, h, n)
        n_out = n // out_every
        oq = np.zeros((n_out, model.n_bodies, 3))
        ov = np.zeros_like(oq)
        od = np.zeros((n_out, RK.N_DIAG))
        w = RK.run(chain, cfg, state, acc, vacc, RK.Record(out_every, oq, ov, od), diag)
        worst = max(worst, int(w))
        if not np.all(np.isfinite(q)):
            raise SolverError("the rigid-chain state became non-finite")
        # the ground's velocity and displacement (trapezoid on the step means: exact for them)
        vg_steps = v_cur + h * np.cumsum(acc)
        ug_steps = u_cur + h * np.cumsum(0.5 * (np.concatenate([[v_cur], vg_steps[:-1]])
                                                 + vg_steps))
        if n_out:
            k = (np.arange(n_out) + 1) * out_every - 1  # the recorded steps of the chunk
            times.append((step + k + 1) * h)
            qs.append(oq)
            vs.append(ov)
            ds.append(od)
            ug.append(ug_steps[k])
            vg.append(vg_steps[k])
        u_cur, v_cur = float(ug_steps[-1]), float(vg_steps[-1])
        step += n
        if progress is not None:
            progress(step, n_cap)
        if settings.stop_at_collapse and n_out:
            last = absolute_states(model, oq[-1:], ov[-1:], ug[-1][-1:], vg[-1][-1:])[0]
            collapsed = bool(DK.collapsed(last, free, cpar))
    wall = _time.perf_counter() - t_wall
    return SteppedSamples(times=np.concatenate(times), q=np.concatenate(qs),
                          v=np.concatenate(vs), diag=np.concatenate(ds),
                          ground_displacement=np.concatenate(ug),
                          ground_velocity=np.concatenate(vg), time_step=h,
                          output_interval=out_every * h, n_steps=step, max_sweeps=worst,
                          wall_s=wall)


__all__ = ["METHODS", "SteppedSamples", "run_steps"]
