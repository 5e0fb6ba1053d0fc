"""The rigid-block chain integrated from event to event: ``simulate_rigid(...,
solver="events")``.

The model is `archquake.rigid`'s (rigid voussoirs, plastic no-slip corner
contacts, any number of hinges); only the integration differs. Between contact changes the arch
moves with K - 3 degrees of freedom (K hinges), an ODE in the hinges' relative rotations
integrated to a tolerance; closures (plastic impacts, the same cone projection as the time
stepper's), openings (a corner force of a locked joint reaching zero) and the onset are located
as events (`archquake.rigid._event_kernels`). Energy between events is conserved to
the integrator's tolerance, instead of the stepper's O(h) loss in persistent contact.

What the event integrator does not model (a hinge in tension, a joint separating, chattering
contacts) it hands to the time stepper at that instant, which finishes the run; the run says so
(``RigidRun.events["fallback_at_s"]``).
"""

from __future__ import annotations

import math
import threading
import time as _time
from dataclasses import dataclass
from functools import cached_property

import numpy as np

import archquake.rigid._event_kernels as EK
import archquake.rigid._step_kernels as RK
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.ground.base import check_motion_lift_off
from archquake.rigid.model import (
    DEFAULT_TIME_STEP,
    GAP_TOLERANCE,
    MAX_SWEEPS,
    SOLVER_TOLERANCE,
    RigidModel,
    mean_acceleration,
    mean_vertical,
)

#: Relative and absolute (rad, rad/s) tolerances of the Dormand-Prince steps. With these and
#: ``MAX_STEP`` the energy between closures of free rocking is constant to 5e-9 of itself
#: (Oppenheim's arch; at 1e-10 / 0.02 it is 4e-7, mostly the samples' cubic interpolation).
EVENT_RTOL = 1.0e-12
EVENT_ATOL = 1.0e-14
#: Longest step, in units of sqrt(L/g) (L the assembly's reference length): bounds how far a
#: contact force can dip below zero and back unseen (each step is also checked at its middle)
#: and the samples' interpolation error.
MAX_STEP = 0.005
#: How long the time stepper runs when the event integrator hands over, in sqrt(L/g) (then the
#: event integrator resumes from the stepper's state).
FALLBACK_WINDOW = 0.02

WHY = {EK.WHY_NONE: "", EK.WHY_TENSILE_HINGE: "a hinge's reaction became tensile (flight)",
       EK.WHY_SEPARATION: "a joint separated (its pivot moved away)",
       EK.WHY_WRONG_WAY: "an opening hinge turned the wrong way",
       EK.WHY_CHATTER: f"more than {EK.CHATTER_EVENTS} contact events within "
                       f"{EK.CHATTER_WINDOW * 1e3:g} ms",
       EK.WHY_SINGULAR: "the mechanism's equations became singular",
       EK.WHY_TOO_MANY_HINGES: f"more than {EK.MAX_HINGES} hinges"}


#: The onset bisection's last bracket, g: an arch that stays at rest under this ground
#: acceleration has no onset the package looks for (its ``onset_g`` is inf).
ONSET_CEILING_G = 1.0e6
#: An arch that moves under every ground acceleration down to this one, g, is taken to move
#: under its own weight: its onset is 0 (the bisection's bound is relative: towards 0 it would
#: halve about 1,100 times). An arch that moves at 0 (a chain at its least thickness, read
#: through the projection's tolerances) is found so by one projection first.
ONSET_FLOOR_G = 1.0e-9

#: Held while an event model is built, so that threads asking at once share one.
_BUILDING = threading.Lock()


@dataclass(frozen=True)
class EventModel:
    """A `RigidModel` laid out for the event integrator:
    blocks in chain order (joint j between blocks j - 1 and j, the springings -1; a chain whose
    last block is free, such as a block on its base, has no joint n), prefix sums
    of the blocks' mass properties, the joints' undisplaced corners ``p0`` (nj, 2, 2), normals,
    tangents, half-widths ``hw`` (m) and ``sg`` = t x n (+-1)."""

    rigid: RigidModel
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

    @classmethod
    def build(cls, rigid: RigidModel) -> EventModel:
        n = rigid.n_bodies
        closed = (np.array_equal(rigid.ja, np.arange(-1, n))
                  and np.array_equal(rigid.jb, np.r_[np.arange(n), -1]))
        open_ = (np.array_equal(rigid.ja, np.arange(-1, n - 1))
                 and np.array_equal(rigid.jb, np.arange(n)))
        if not (closed or open_):
            raise InvalidParameterError(
                "the event integrator needs a single chain of blocks from a base, ending on a "
                "second springing or free (use solver='direct')")
        X0 = np.asarray(rigid.centroids, float)
        mb = np.asarray(rigid.mass, float)
        ib = np.asarray(rigid.inertia, float)
        S0 = np.r_[0.0, np.cumsum(mb)]
        S1 = np.vstack([np.zeros(2), np.cumsum(mb[:, None] * X0, axis=0)])
        S2 = np.r_[0.0, np.cumsum(mb * (X0 ** 2).sum(1) + ib)]
        p0 = np.asarray(rigid.arm_b, float).copy()
        for j in range(min(n, len(p0))):
            p0[j] += X0[j]
        n0 = np.asarray(rigid.n0, float)
        t0 = np.asarray(rigid.t0, float)
        hw = 0.5 * np.linalg.norm(p0[:, 1] - p0[:, 0], axis=1)
        sg = np.sign(t0[:, 0] * n0[:, 1] - t0[:, 1] * n0[:, 0])
        return cls(rigid, X0, mb, ib, S0, S1, S2, p0, n0, t0, hw, sg)

    @classmethod
    def of(cls, rigid: RigidModel) -> EventModel:
        """`build`, once per rigid model: kept on the model itself (its onset thresholds are
        computed once), so that the model needs nothing of the event integrator."""
        with _BUILDING:  # one for threads that ask at once
            cached = rigid.__dict__.get("_event_model")
            if cached is None:
                cached = rigid.__dict__["_event_model"] = cls.build(rigid)
        return cached

    @property
    def closed(self) -> bool:
        """The chain ends on a second springing (an arch), not free (a block on its base)."""
        return len(self.rigid.ja) == self.rigid.n_bodies + 1

    @property
    def lref(self) -> float:
        return float(self.rigid.assembly.reference_length)

    def _projected(self, ax_g: float, warm: np.ndarray, geo=None
                   ) -> tuple[np.ndarray, np.ndarray]:
        """The Gauss projection of the locked arch's free acceleration under x_g'' = ax_g (in
        g, g = 1), from the impulses ``warm``: (accelerations, impulses). ``geo``: the rest
        configuration's geometry, if the caller has it."""
        r = self.rigid
        n = r.n_bodies
        q, _ = r.rest()
        a = np.zeros((n, 3))
        a[:, 0] = -ax_g
        a[:, 1] = -1.0
        cfg = RK.solving(1e-9 * self.lref, 1e-13 * math.sqrt(self.lref), EK.SOLVE_SWEEPS)
        acc, imp, _, _ = RK.project_direct(r.chain, cfg, q, r.geometry(q) if geo is None else geo,
                                           a, warm, np.empty(0), np.empty(0))
        return acc, imp

    @cached_property
    def _resting_impulses(self) -> np.ndarray:
        """The contact impulses of the locked arch under its own weight alone: the start of
        every onset projection (`_moves`). From it the active sets reach the exact projection
        in a few corrections even next to the onset, where from no impulses they cycled and
        handed the projection to Gauss-Seidel (tens of thousands of sweeps)."""
        return self._projected(0.0, np.zeros((len(self.rigid.ja), 3)))[1]

    def _moves(self, ax_g: float) -> bool:
        """Whether the locked arch starts to move under x_g'' = ax_g (in g, g = 1): the Gauss
        projection of the free acceleration, from the impulses under the arch's own weight
        (the same start for every ``ax_g``, so the answer is a function of ``ax_g`` alone),
        opens four or more hinges."""
        r = self.rigid
        q, _ = r.rest()
        geo = r.geometry(q)
        nrm = geo.nrm
        acc, _ = self._projected(ax_g, self._resting_impulses, geo)
        nj = len(r.ja)
        jh = np.zeros(nj, np.int64)
        k, _ = EK.modes_after_projection(r.chain, self.sg, q, acc, nrm, np.zeros(nj), 1e-7,
                                         1e-7 * (1 + abs(ax_g)), 1e-9 / self.lref, jh, jh.copy(),
                                         np.zeros(nj))
        return k >= (4 if self.closed else 1)

    @cached_property
    def onset_g(self) -> tuple[float, float]:
        """(lambda_+, lambda_-): the ground accelerations, in g, towards +x and -x at which the
        locked arch starts to move (the no-slip rigid chain's collapse multipliers), by
        bisection on the Gauss projection to 1e-12 (bracketed by 20 g, doubled while the arch
        stays); inf above `ONSET_CEILING_G`, 0 below `ONSET_FLOOR_G`. `onset_near`
        gives the same numbers with fewer projections when they are known roughly."""
        return self._bisect(1.0), self._bisect(-1.0)

    def onset_near(self, hint_g: float) -> tuple[float, float]:
        """`onset_g`, the same numbers, found with fewer projections from a rough value
        ``hint_g`` (g) of lambda_+ (the limit analysis's, which the chain's exceeds by 1e-8 to
        2e-7 of itself: its projection's tolerances).

        The bisection of `onset_g` is replayed step by step, but a projection whose
        answer a bracket already gives is not computed: once the arch is shown to stay at
        ``a`` and to move at ``b``, every midpoint below ``a`` stays and every one above ``b``
        moves (the bisection's own premise), so only the midpoints inside (a, b) are
        projected. The bracket is ``hint_g`` (1 - 1e-7) to ``hint_g`` (1 + 1e-6) for
        lambda_+, then lambda_+ (1 -+ 1e-10) for lambda_- (equal to 1e-12 for a
        mirror-symmetric chain); a bracket that fails its check is dropped (a plain
        bisection). About 32 projections instead of 94."""
        cached = self.__dict__.get("onset_g")
        if cached is not None:
            return cached
        if math.isfinite(hint_g) and hint_g > 0.0:
            plus = self._bisect(1.0, *self._bracket(1.0, hint_g * (1 - 1e-7), hint_g * (1 + 1e-6)))
        else:
            plus = self._bisect(1.0)
        if math.isfinite(plus):
            minus = self._bisect(-1.0, *self._bracket(-1.0, plus * (1 - 1e-10), plus * (1 + 1e-10)))
        else:
            minus = self._bisect(-1.0)
        self.__dict__["onset_g"] = (plus, minus)  # what the cached property would have found
        return plus, minus

    def _bracket(self, sgn: float, low: float, high: float) -> tuple[float, float]:
        """(a, b) with the arch at rest under ``sgn`` a and moving under ``sgn`` b, g; (0, inf)
        (nothing known) if (``low``, ``high``) is not such a bracket."""
        if 0.0 < low < high < 20.0 and not self._moves(sgn * low) and self._moves(sgn * high):
            return low, high
        return 0.0, math.inf

    def _bisect(self, sgn: float, stays: float = 0.0, moves: float = math.inf) -> float:
        """The bisection of `onset_g` towards ``sgn`` x, taking the arch to stay at rest
        at or below ``stays`` and to move at or above ``moves`` (g) without projecting."""

        def moving(x: float) -> bool:
            if x <= stays:
                return False
            if x >= moves:
                return True
            return self._moves(sgn * x)

        if stays == 0.0 and self._moves(0.0):  # moves under its own weight: no bracket
            return 0.0
        lo, hi = 0.0, 20.0
        while not moving(hi):  # a stout arch: double the bracket, up to ONSET_CEILING_G
            if hi >= ONSET_CEILING_G:
                return math.inf
            lo, hi = hi, 2.0 * hi
        while hi - lo > 1e-12 * hi:
            if lo == 0.0 and hi < ONSET_FLOOR_G:  # indistinguishable from its own weight
                return 0.0
            mid = 0.5 * (lo + hi)
            if moving(mid):
                hi = mid
            else:
                lo = mid
        return hi


def stays_at_rest(model: RigidModel, motion, *, g: float = STANDARD_GRAVITY) -> bool:
    """Whether the chain, at rest, stays at rest through the whole of ``motion``: the exact
    onset test.

    The ground accelerations a under which the locked chain is in equilibrium (contact forces
    inside their cones balancing gravity and the inertia force -m a) form an interval, since
    the conditions are linear in the forces and in a. So the chain stays at rest through the
    whole motion exactly when it stays under the motion's largest acceleration towards +x and
    its largest towards -x (`archquake.ground.base.acceleration_peaks`): two Gauss
    projections (`EventModel._moves`, the test of `EventModel.onset_g`), whatever
    the motion's length. Then the time stepper's every step projects the free velocity back to
    zero, and the event integrator never finds an onset.

    Parameters
    ----------
    model : RigidModel
        No sliding (the paper's joints; Coulomb joints may slip below the onset of hinging).
    motion : GroundMotion
        Ground acceleration, m/s^2.
    g : float
        m/s^2.

    Returns
    -------
    bool
        False also where the test does not apply (a motion that does not describe its peaks, a
        model that is not a single chain, a peak beyond `ONSET_CEILING_G`).
    """
    from archquake.ground.base import acceleration_peaks

    peaks = acceleration_peaks(motion)
    if peaks is None:
        return False
    try:
        em = EventModel.of(model)
    except InvalidParameterError:  # not a single chain
        return False
    plus, minus = peaks[0] / g, peaks[1] / g
    if not (plus <= ONSET_CEILING_G and minus <= ONSET_CEILING_G):
        return False
    return not em._moves(plus) and (minus == plus == 0.0 or not em._moves(-minus))


def ground_kinematics(motion, times: np.ndarray, step: float = 1e-4
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Ground displacement (m) and velocity (m/s) at ``times`` (s, from 0): the trapezoid rule
    on a grid of ``step`` s (exact for the piecewise-constant pulses on their breakpoints)."""
    t_end = float(times[-1])
    n = max(2, int(math.ceil(t_end / step)) + 1)
    grid = np.linspace(0.0, t_end, n)
    a = np.asarray(motion.acceleration(grid), float)
    vg = np.r_[0.0, np.cumsum(0.5 * (a[1:] + a[:-1]) * np.diff(grid))]
    ug = np.r_[0.0, np.cumsum(0.5 * (vg[1:] + vg[:-1]) * np.diff(grid))]
    return np.interp(times, grid, ug), np.interp(times, grid, vg)


def _stepper_window(model: EventModel, motion, chain: EK.Chain, state: EK.State,
                    output: EK.Output, t0: float, window: float, dt_out: float, written: int,
                    g: float, stop_at_collapse: bool) -> tuple[int, float, bool]:
    """Run the time stepper (`archquake.rigid._step_kernels.run`, direct solve, its
    default step) from the block state (q, v) = (``state.fq``, ``state.fv``) at t0 to the
    first output time at least ``window`` s later, writing the samples it passes into
    ``output`` (every ``dt_out`` s) and the energies into ``state.diag``; (q, v) become its end
    state. The collapse criterion is ``chain``'s. Returns (samples written, end time,
    collapsed)."""
    q, v, diag, state_all = state.fq, state.fv, state.diag, state.state_all
    out_q, out_v, out_e = output
    free, cpar = chain.free, chain.cpar
    import archquake.blocks._kernels as DK

    r = model.rigid
    lref = model.lref
    cap = out_q.shape[0]
    tol = SOLVER_TOLERANCE * math.sqrt(g * lref)
    p_warm = np.zeros((len(r.ja), 3))
    k_first = written + 1  # the next sample, at k_first dt_out >= t0
    k_last = min(cap, int(math.ceil((t0 + window) / dt_out - 1e-9)))
    t = t0
    collapsed = False
    for k in range(k_first, k_last + 1):
        t_k = k * dt_out
        ns = max(1, int(math.ceil((t_k - t) / DEFAULT_TIME_STEP - 1e-9)))
        h = (t_k - t) / ns
        dg = np.zeros(RK.N_DIAG)
        oq = np.zeros((1, r.n_bodies, 3))
        ov = np.zeros_like(oq)
        od = np.zeros((1, RK.N_DIAG))
        if h > 0.0:
            acc = mean_acceleration(motion, t, h, ns)
            cfg = RK.stepping(h, g, GAP_TOLERANCE * lref, tol, MAX_SWEEPS, 0.0,
                              RK.METHOD_DIRECT, correction=False)
            RK.run(r.chain, cfg, RK.State(q, v, p_warm, np.full(len(r.ja), np.nan)),
                   acc, mean_vertical(motion, t, h, ns), RK.Record(ns, oq, ov, od), dg)
        diag[EK.E_DISSIPATED] += dg[RK.D_DISSIPATED]
        diag[EK.E_INPUT] += dg[RK.D_INPUT]
        i = k - 1
        out_q[i] = q
        out_v[i] = v
        out_e[i, 0] = r.kinetic_energy(v)
        out_e[i, 1] = r.potential_energy(q, g)
        out_e[i, 2] = diag[EK.E_DISSIPATED]
        out_e[i, 3] = diag[EK.E_INPUT]
        out_e[i, 4] = 0.0
        state_all[r.free_blocks, :3] = q
        written = k
        t = t_k
        if stop_at_collapse and DK.collapsed(state_all, free, cpar):
            collapsed = True
            break
    return written, t, collapsed


def run_events(model: EventModel, motion, *, duration: float, output_interval: float,
               g: float = STANDARD_GRAVITY, settings=None, until_rest: float | None = None,
               rtol: float = EVENT_RTOL, atol: float = EVENT_ATOL,
               max_step: float = MAX_STEP, fallback_window: float = FALLBACK_WINDOW,
               initial: tuple[np.ndarray, np.ndarray] | None = None) -> dict:
    """Run the event integrator from rest, or from ``initial`` = (q, v) (nb, 3) each, a
    configuration of the model (joints closed or turning about a corner; read as after a
    hand-over: ``_event_kernels.RESUME_GAP``).

    Returns
    -------
    dict
        ``times`` (nt,) s; ``q``, ``v`` (nt, nb, 3); ``e`` (nt, 5): kinetic, potential,
        dissipated, input work (J), friction demand; ``status`` (``_event_kernels.STATUS_*``)
        and ``t`` (s) reached; ``windows_s``: the times at which the time stepper took over for
        ``fallback_window`` sqrt(L/g), with ``window_why`` the reasons (`WHY`);
        ``counters`` and ``log`` (``_event_kernels.run``); ``max_drift_m``; ``state``: the final
        (st, y) of the kernel; ``wall_s``.
    """
    import archquake.blocks._kernels as DK
    from archquake.blocks.criteria import block_criteria
    from archquake.blocks.result import (
        collapse_parameters,
        crown_height,
        excitation_end,
        settled,
    )

    r = model.rigid
    asm = r.assembly
    settings = block_criteria(settings, caller="run_events")
    n = r.n_bodies
    lref = model.lref
    check_motion_lift_off(motion, g)
    kind, gp = motion.kernel_spec()
    t_exc = excitation_end(motion)
    t_exc = math.inf if t_exc is None else float(t_exc)
    lam_p, lam_n = model.onset_g
    t_cap = duration if until_rest is None else max(duration, float(until_rest))
    n_out = int(math.floor(t_cap / output_interval + 1e-9))
    out_q = np.zeros((n_out, n, 3))
    out_v = np.zeros((n_out, n, 3))
    out_e = np.zeros((n_out, 5))
    st = np.zeros(1 + 2 * EK.MAX_HINGES, np.int64)
    y = np.zeros(2 * EK.MAX_HINGES + 1)
    tt = np.zeros(1)
    free = (~np.asarray(asm.base, dtype=bool)).astype(np.int64)
    state_all = np.zeros((len(free), 6))
    state_all[:, :2] = np.asarray(asm.centroids, float)
    cpar = collapse_parameters(asm, settings, math.nan)
    cpar[DK.C_CROWN_Y0] = crown_height(asm, state_all[None, :, :3])[0]
    counters = np.zeros(EK.N_COUNTERS, np.int64)
    diag = np.zeros(EK.N_E)
    fq = np.zeros((n, 3))
    fv = np.zeros((n, 3))
    log = np.zeros((100_000, 4))
    h_max = max_step * math.sqrt(lref / g)
    whys: list[int] = []
    written = 0
    windows: list[float] = []
    wall = _time.perf_counter()
    t_stop = duration
    resume = initial is not None
    if initial is not None:
        fq[:] = np.asarray(initial[0], float)
        fv[:] = np.asarray(initial[1], float)
    chain = EK.Chain(model.X0, model.mb, model.ib, model.S0, model.S1, model.S2, model.p0,
                     model.n0, model.t0, model.hw, model.sg, r.ja, r.jb, r.arm_a, r.arm_b,
                     r.free_blocks, free, cpar, lref)
    state = EK.State(st, y, tt, counters, diag, fq, fv, log, state_all)
    output = EK.Output(out_q, out_v, out_e)
    while True:
        span = EK.Span(kind, gp, g, min(t_stop, n_out * output_interval + 1e-12), t_exc,
                       lam_p * g, lam_n * g, rtol, atol, h_max, output_interval,
                       bool(settings.stop_at_collapse), resume)
        status, why, written = EK.run(chain, span, state, output, written)
        resume = False
        if status == EK.STATUS_FALLBACK:
            windows.append(float(tt[0]))
            whys.append(int(why))
            written, t_w, collapsed = _stepper_window(
                model, motion, chain, state, output, float(tt[0]),
                fallback_window * math.sqrt(lref / g), output_interval, written, g,
                bool(settings.stop_at_collapse))
            if collapsed:
                status = EK.STATUS_COLLAPSE
                break
            if written >= n_out:
                status = EK.STATUS_DONE
                break
            if t_w >= t_stop - 1e-12:
                if until_rest is None or t_stop >= t_cap - 1e-12:
                    status = EK.STATUS_DONE
                    break
                t_stop = min(t_cap, t_w + 0.05)  # a window ran past t_stop: go on until rest
            tt[0] = t_w
            resume = True
            continue
        if (status not in (EK.STATUS_DONE, EK.STATUS_REST) or until_rest is None
                or t_stop >= t_cap - 1e-12):
            break
        # go on until rest, as the stepper does: until the samples end with a rest window (a
        # locked arch too: STATUS_REST at t_stop does not yet make the window)
        if written and settled(asm, g, output_interval * np.arange(1, written + 1),
                               out_e[:written, 0], excitation_end(motion)):
            break
        t_stop = min(t_cap, t_stop + 0.05)
    wall = _time.perf_counter() - wall
    times = output_interval * np.arange(1, written + 1)
    return {"times": times, "q": out_q[:written], "v": out_v[:written], "e": out_e[:written],
            "status": int(status), "t": float(tt[0]), "windows_s": windows, "window_why": whys,
            "counters": counters.copy(), "log": log[:counters[EK.N_LOG]].copy(),
            "max_drift_m": float(diag[EK.E_MAX_DRIFT]), "state": (st.copy(), y.copy()),
            "wall_s": wall}


#: The event log's kinds (`archquake.rigid._event_kernels.run`).
EVENT_KINDS = {1: "closure", 2: "opening", 3: "relock", 4: "onset", 5: "rest", 6: "resume"}


def events_summary(raw: dict) -> dict:
    """The event integrator's record for JSON: counts of closures, openings, onsets and cut
    accumulations, the times (s) and reasons the time stepper took over, the steps taken, and
    the event log: every event with its time (s), kind (`EVENT_KINDS`), joint (-1 for
    none) and the number of hinges after it."""
    c = raw["counters"]
    return {"closures": int(c[EK.N_CLOSURES]), "openings": int(c[EK.N_OPENINGS]),
            "onsets": int(c[EK.N_ONSETS]), "accumulations_cut": int(c[EK.N_ZENO]),
            "steps": int(c[EK.N_STEPS]), "rejected_steps": int(c[EK.N_REJECTED]),
            "handovers_s": [round(t, 6) for t in raw["windows_s"]],
            "handover_reasons": [WHY[w] for w in raw["window_why"]],
            "max_closure_drift_m": raw["max_drift_m"],
            "log": [{"time_s": float(t), "kind": EVENT_KINDS.get(int(k), str(int(k))),
                     "joint": int(j), "hinges_after": int(n)} for t, k, j, n in raw["log"]]}


__all__ = ["EVENT_ATOL", "EVENT_KINDS", "EVENT_RTOL", "EventModel", "MAX_STEP",
           "ONSET_CEILING_G", "events_summary", "ground_kinematics", "run_events",
           "stays_at_rest"]
