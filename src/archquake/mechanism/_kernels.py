"""Compiled time history of the rocking arch: Dormand-Prince 5(4) with events.

State machine over a stack of mechanisms (rows of an (m, 30) array, each packed by
`archquake.mechanism.prepared.pack_mechanism`; `ImpactTable`
holds the stack and its impact table). The kernels take the model packed once: the stack and its
impact table in a `Table`, the ground motion in an `Excitation`, the solver's settings in one
float array (`settings`, indices ``S_*``), the buffers they write in an `Output` (and
`Requested`); the integrator's inner functions take the open mechanism over one piece of the
excitation as a `Piece`. The state is (row, side, phi, phi'): the open mechanism
is row ``row`` (side +1) or its mirror image (side -1, the paper's Eq. 3: the same coefficients
with the ground term negated).

* ``side = 0``: locked. The arch moves rigidly with the ground until the ground acceleration
  opens a mechanism of row 0 (the limit-analysis mechanism): side +1 when
  ``-g G0 - a(t) H0 > 0``, side -1 when ``-g G0 + a(t) H0 > 0``. These are exactly
  ``|a| > lambda g`` in the right direction. With a vertical ground acceleration a_v(t)
  (upward) every g here and below reads g + a_v(t).
* ``side = +-1``: open, integrating ``m_eff phi'' = -1/2 m_eff' phi'^2 - g G - side a(t) H``
  of the current row. Steps never straddle a breakpoint of the excitation (where it jumps or
  kinks).
* Closure (phi returns to 0 while closing): located on the step's cubic Hermite interpolant,
  then refined by re-integrating to the event (Newton on phi). The impact table gives the next
  state: ``row = nxt[row]``, ``side = side * flip[row]``, ``phi' = ratio[row] |phi'|`` (the
  post mechanism's own rate; for the paper's law one row, ``nxt = 0``, ``flip = -1``,
  ``ratio = c_v``). A row whose impact leaves the tabulated set (``nxt < 0``) stops the run
  (``FINAL_UNRESOLVED``). If the next half cycle's peak (on the new row) would be below
  ``rest_rotation`` the arch locks (rest).
* Collapse: once the excitation is over, phi >= phi_crit (the crest of the potential, where
  gravity can no longer bring it back) while opening; or, at any time, phi reaching the toggle
  of the linkage.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from archquake._dopri import (  # the Dormand-Prince 5(4) tableau
    A21,
    A31,
    A32,
    A41,
    A42,
    A43,
    A51,
    A52,
    A53,
    A54,
    A61,
    A62,
    A63,
    A64,
    A65,
    B1,
    B3,
    B4,
    B5,
    B6,
    C2,
    C3,
    C4,
    C5,
    E1,
    E3,
    E4,
    E5,
    E6,
    E7,
)
from archquake._kernel_cache import stamp_kernels
from archquake.ground._kernel import (
    ground_duration,
    ground_in_piece,
    next_breakpoint,
    vertical_in_piece,
)
from archquake.ground.base import KIND_SAMPLED, KIND_SAMPLED_VERTICAL, KIND_STEP
from archquake.mechanism.kinematics import (
    G0,
    H0,
    LENGTH,
    LINK0,
    PHI_CRIT,
    PHI_TOGGLE,
    acceleration,
    eom_terms,
    linkage_limits,
    potential,
)

stamp_kernels()  # the cache checks each kernel against every source compiled into it

#: The crest/toggle search of `archquake.mechanism.kinematics.linkage_limits`, compiled.
linkage_limits_compiled = nb.njit(cache=True)(linkage_limits)

OUTCOME_NO_HINGING = 0
OUTCOME_SURVIVES = 1
OUTCOME_COLLAPSE = 2
FINAL_REST = 0
FINAL_MOVING = 1
FINAL_COLLAPSED = 2
FINAL_STALLED = 3
FINAL_UNRESOLVED = 4
#: Columns of the impacts array: time, rate before, rate after, row before, row after (-1: the
#: impact leaves the tabulated set), side after, 1 if the arch locked at the impact (rest or cap).
IMPACT_COLUMNS = 7
#: Columns of the history and of the requested states.
HIST_COLUMNS = 6

#: End of the excitation, s (kept under this name for the kernels that use it).
excitation_end = ground_duration

#: Indices of the settings array (`settings`): gravity, m/s^2; end of the analysis, s; relative
#: tolerance; absolute tolerance on phi, rad; rest rotation, rad; cap on impacts; output
#: interval, s; locked output interval, s; cap on history samples; initial opening rate, rad/s.
(S_G, S_T_END, S_RTOL, S_ATOL_PHI, S_REST_ROTATION, S_MAX_IMPACTS, S_DT_OUT, S_DT_LOCK,
 S_HIST_LIMIT, S_INITIAL_RATE) = range(10)
N_SETTINGS = 10


class Table(NamedTuple):
    """The stack of packed mechanisms and its impact table, as the kernels take them
    (`archquake.mechanism.prepared.PreparedMechanism.kernel_table`).

    Attributes
    ----------
    mechs : ndarray (m, 30)
        Packed mechanisms (row 0: the limit-analysis mechanism, which the onsets open).
    nxt : ndarray (m,) int64
        Row after an impact of each row (-1: outside the set).
    flip : ndarray (m,) int64
        +-1: the side after an impact is the side before times this.
    ratio : ndarray (m,)
        Opening rate of the post mechanism per unit closing rate (the paper's law: c_v).
    undescribed : ndarray (m,) bool
        The impact law does not describe the row's impact.
    ct_max : float
        The largest kinetic-energy ratio of the rows' impacts.
    v_toggle : ndarray (m,)
        Potential/g at each row's toggle, kg m, for the no-return collapse criterion on a
        record (`no_return`; nan: the criterion does not apply to that row).
    """

    mechs: np.ndarray
    nxt: np.ndarray
    flip: np.ndarray
    ratio: np.ndarray
    undescribed: np.ndarray
    ct_max: float
    v_toggle: np.ndarray


class Excitation(NamedTuple):
    """The ground motion as the kernels take it (`excitation`).

    Attributes
    ----------
    kind : int
        Ground-motion kind (``GroundMotion.kernel_spec``).
    params : ndarray (k,) float64
        Its kernel parameters.
    tail : ndarray (N,)
        For a sampled record, ``int_{t_i}^{end} |x_g''| dt`` from each sample time t_i to the
        record's end, m/s (empty: no collapse before the excitation's end); with it a
        collapse is declared during the record once the remaining motion cannot bring the
        mechanism back over the crest (`no_return`).
    """

    kind: int
    params: np.ndarray
    tail: np.ndarray


class Output(NamedTuple):
    """What a run writes (`simulate_kernel_eval`).

    Attributes
    ----------
    hist : ndarray (cap, 6)
        t, phi, phi', side, x_g'', row. Samples beyond ``cap`` are counted (in counters[0]) but
        not written: the caller sizes the buffer again and reruns.
    impacts : ndarray (max_impacts, 7)
        The `IMPACT_COLUMNS`.
    peaks : ndarray (max_impacts + 1,)
        Peak phi of each half cycle, rad.
    counters : ndarray (10,)
        n_hist (samples wanted, may exceed cap), n_impacts, n_half_cycles, n_steps, n_rejected,
        n_rhs, onset_time, collapse_time, 1 if the run stopped because the history reached the
        settings' ``S_HIST_LIMIT`` samples (counters[8] is written only then), n_onsets.
    onsets : ndarray (k, 2)
        Time and side of each onset of hinging from rest (row 0), as many as fit (an onset
        follows a lock, and a lock an impact: max_impacts + 1 always fit).
    """

    hist: np.ndarray
    impacts: np.ndarray
    peaks: np.ndarray
    counters: np.ndarray
    onsets: np.ndarray


class Requested(NamedTuple):
    """Requested times and the states there (`simulate_kernel_eval`).

    Attributes
    ----------
    times : ndarray (n,)
        Requested times, s, sorted (non-decreasing).
    states : ndarray (n, 6)
        Out: phi, phi', phi'', side, x_g'', row at each time reached (in order).
    """

    times: np.ndarray
    states: np.ndarray


class Piece(NamedTuple):
    """What the open mechanism's equation of motion holds fixed between two events or
    breakpoints of the excitation: the packed row ``mech`` (30,) and its index ``row``, the
    ``side`` (+-1), the `Excitation`, gravity ``g`` (m/s^2) and ``t_left`` (s), the start of the
    excitation's piece (the ground is evaluated as its right limit there)."""

    mech: np.ndarray
    row: int | np.integer
    side: int
    exc: Excitation
    g: float
    t_left: float


def _kernel_array(values: np.ndarray) -> np.ndarray:
    """``values`` as an aligned, C-contiguous, writable float64 array (a copy only where it is
    not one already): the one array type the kernels are compiled for."""
    out = np.ascontiguousarray(values, dtype=np.float64)
    if not (out.flags.writeable and out.flags.aligned):
        out = out.copy()
    return out


def excitation(kind: int, params: np.ndarray, tail: np.ndarray | None = None) -> Excitation:
    """The `Excitation` of a ground motion's ``kernel_spec()`` with a record's ``tail``
    (default none), in the one type the kernels are compiled for (a read-only record is
    copied)."""
    return Excitation(int(kind), _kernel_array(params),
                      np.empty(0) if tail is None else _kernel_array(tail))


def settings(g: float, t_end: float, rtol: float, atol_phi: float, rest_rotation: float,
             max_impacts: int, *, dt_out: float = 0.0, dt_lock: float | None = None,
             hist_limit: int = 1, initial_rate: float = 0.0) -> np.ndarray:
    """The settings array of a run (indices ``S_*``).

    Parameters
    ----------
    g : float
        Gravity, m/s^2.
    t_end : float
        End of the analysis, s.
    rtol, atol_phi : float
        Tolerances (the rate's absolute tolerance is ``atol_phi sqrt(g / R)``, so that similar
        arches take similar steps), atol_phi in rad.
    rest_rotation : float
        Rad: below this peak the next half cycle is not started (the arch locks).
    max_impacts : int
        The run locks the arch at this many impacts.
    dt_out : float
        Output interval, s (0: no history; < 0: every accepted step and event).
    dt_lock : float, optional
        History interval while locked, s (>= dt_out; when larger, each locked stretch also
        gets a sample at its end and the moving samples restart from there). Default dt_out.
    hist_limit : int
        The run stops (counters[8] = 1) when the history reaches this many samples.
    initial_rate : float
        Rad/s (>= 0); if > 0 the first mechanism starts open at t = 0 with this opening rate
        (free rocking), instead of from rest.

    Returns
    -------
    ndarray (N_SETTINGS,) float64
    """
    out = np.empty(N_SETTINGS)
    out[S_G] = g
    out[S_T_END] = t_end
    out[S_RTOL] = rtol
    out[S_ATOL_PHI] = atol_phi
    out[S_REST_ROTATION] = rest_rotation
    out[S_MAX_IMPACTS] = max_impacts
    out[S_DT_OUT] = dt_out
    out[S_DT_LOCK] = dt_out if dt_lock is None else dt_lock
    out[S_HIST_LIMIT] = hist_limit
    out[S_INITIAL_RATE] = initial_rate
    return out


@nb.njit(cache=True, nogil=True)
def run_settings(base, t_end, max_impacts):
    """A copy of the settings ``base`` ending at ``t_end`` (s) with at most ``max_impacts``
    impacts (the batches' per-case runs)."""
    out = base.copy()
    out[S_T_END] = t_end
    out[S_MAX_IMPACTS] = max_impacts
    return out


@nb.njit(cache=True, nogil=True)
def _rhs(mech, kind, params, side, g, t, t_left, phi, v):
    """phi'' of the open mechanism (Eq. 2) at (t, phi, phi' = v), from the fields of a `Piece`
    that `dopri_step` unpacks once per step (a Piece passed to each of the seven evaluations
    cost 2.5 % of a history; inlining it instead cost 10 % more compile time)."""
    return acceleration(mech, phi, v, side * ground_in_piece(kind, params, t, t_left),
                        g + vertical_in_piece(kind, params, t, t_left))


@nb.njit(cache=True, nogil=True)
def dopri_step(piece, t, phi, v, k1, h):
    """One Dormand-Prince step of the open mechanism ``piece`` (a `Piece`) from (t, phi, v)
    with phi''(t) = k1. Returns (phi1, v1, k7 = phi''(t+h), err_phi, err_v); nan if a stage
    left the linkage's range (beyond the toggle)."""
    mech, side, kind, params, g, t_left = (piece.mech, piece.side, piece.exc.kind,
                                           piece.exc.params, piece.g, piece.t_left)
    p1, q1 = v, k1
    p2 = v + h * A21 * q1
    q2 = _rhs(mech, kind, params, side, g, t + C2 * h, t_left, phi + h * A21 * p1, p2)
    ph3 = phi + h * (A31 * p1 + A32 * p2)
    p3 = v + h * (A31 * q1 + A32 * q2)
    q3 = _rhs(mech, kind, params, side, g, t + C3 * h, t_left, ph3, p3)
    ph4 = phi + h * (A41 * p1 + A42 * p2 + A43 * p3)
    p4 = v + h * (A41 * q1 + A42 * q2 + A43 * q3)
    q4 = _rhs(mech, kind, params, side, g, t + C4 * h, t_left, ph4, p4)
    ph5 = phi + h * (A51 * p1 + A52 * p2 + A53 * p3 + A54 * p4)
    p5 = v + h * (A51 * q1 + A52 * q2 + A53 * q3 + A54 * q4)
    q5 = _rhs(mech, kind, params, side, g, t + C5 * h, t_left, ph5, p5)
    ph6 = phi + h * (A61 * p1 + A62 * p2 + A63 * p3 + A64 * p4 + A65 * p5)
    p6 = v + h * (A61 * q1 + A62 * q2 + A63 * q3 + A64 * q4 + A65 * q5)
    q6 = _rhs(mech, kind, params, side, g, t + h, t_left, ph6, p6)
    phi1 = phi + h * (B1 * p1 + B3 * p3 + B4 * p4 + B5 * p5 + B6 * p6)
    v1 = v + h * (B1 * q1 + B3 * q3 + B4 * q4 + B5 * q5 + B6 * q6)
    q7 = _rhs(mech, kind, params, side, g, t + h, t_left, phi1, v1)
    err_phi = h * (E1 * p1 + E3 * p3 + E4 * p4 + E5 * p5 + E6 * p6 + E7 * v1)
    err_v = h * (E1 * q1 + E3 * q3 + E4 * q4 + E5 * q5 + E6 * q6 + E7 * q7)
    return phi1, v1, q7, err_phi, err_v


@nb.njit(cache=True, nogil=True)
def hermite(s, h, y0, d0, y1, d1):
    """Cubic Hermite interpolant on [0, h] at s (value), from values and derivatives."""
    x = s / h
    h00 = (1.0 + 2.0 * x) * (1.0 - x) * (1.0 - x)
    h10 = x * (1.0 - x) * (1.0 - x)
    h01 = x * x * (3.0 - 2.0 * x)
    h11 = x * x * (x - 1.0)
    return h00 * y0 + h10 * h * d0 + h01 * y1 + h11 * h * d1


@nb.njit(cache=True, nogil=True)
def _hermite_root(h, y0, d0, y1, d1, target, lo):
    """Root in (lo, h] of hermite(s) - target given a sign change there (bisection)."""
    hi = h
    flo = hermite(lo, h, y0, d0, y1, d1) - target
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        fm = hermite(mid, h, y0, d0, y1, d1) - target
        if (fm > 0.0) == (flo > 0.0):
            lo, flo = mid, fm
        else:
            hi = mid
    return 0.5 * (lo + hi)


@nb.njit(cache=True, nogil=True)
def _locate(piece, t, phi, v, k1, s_guess, target, lo, hi):
    """Re-integrate from (t, phi, v) to the event phi = target, with Newton on the step size
    safeguarded by the bracket [lo, hi] (phi - target changes sign across it; bisection when
    Newton leaves it). Returns (s, phi_s, v_s, a_s)."""
    s = min(max(s_guess, lo), hi)
    f_lo_positive = True
    if lo > 0.0:
        ph_lo = dopri_step(piece, t, phi, v, k1, lo)[0]
        f_lo_positive = ph_lo - target > 0.0
    else:
        f_lo_positive = phi - target > 0.0
    for _ in range(60):
        ph, vv, aa, e1, e2 = dopri_step(piece, t, phi, v, k1, s)
        f = ph - target
        if (f > 0.0) == f_lo_positive:
            lo = s
        else:
            hi = s
        s_new = s - f / vv if vv != 0.0 else 0.5 * (lo + hi)
        if not (lo < s_new < hi):
            s_new = 0.5 * (lo + hi)
        if abs(s_new - s) <= 1e-15 * (1.0 + abs(t)) or hi - lo <= 1e-15 * (1.0 + abs(t)):
            s = s_new
            break
        s = s_new
    ph, vv, aa, e1, e2 = dopri_step(piece, t, phi, v, k1, s)
    return s, ph, vv, aa


@nb.njit(cache=True, nogil=True)
def _opening_force(mech, side, a, g):
    return -g * mech[G0] - side * a * mech[H0]


@nb.njit(cache=True, nogil=True)
def find_onset(mech, exc, g, t, t_limit):
    """Earliest time >= t at which the ground acceleration (the `Excitation` ``exc``) opens
    the mechanism ``mech`` under gravity ``g``, and its side.

    Returns (time, side) with side 0 if none before ``t_limit``.
    """
    kind, params = exc.kind, exc.params
    t_cur = t
    while t_cur < t_limit:
        t_next = min(next_breakpoint(kind, params, t_cur), t_limit)
        nsub = 1 if kind == KIND_STEP else (2 if kind >= KIND_SAMPLED else 64)
        prev_t = t_cur
        for j in range(nsub + 1):
            tj = t_cur + (t_next - t_cur) * j / nsub
            if j == nsub and kind == KIND_STEP:
                break
            a = ground_in_piece(kind, params, tj, t_cur)
            gv = g + vertical_in_piece(kind, params, tj, t_cur)
            for side in (1, -1):
                f = _opening_force(mech, side, a, gv)
                if f > 0.0:
                    if j == 0:
                        return tj, side
                    # bisection on the crossing inside the piece (continuous there)
                    lo, hi = prev_t, tj
                    for _ in range(80):
                        mid = 0.5 * (lo + hi)
                        a_mid = ground_in_piece(kind, params, mid, t_cur)
                        g_mid = g + vertical_in_piece(kind, params, mid, t_cur)
                        if _opening_force(mech, side, a_mid, g_mid) > 0.0:
                            hi = mid
                        else:
                            lo = mid
                    return hi, side
            prev_t = tj
        if not math.isfinite(t_next):
            break
        t_cur = t_next
    return t_limit, 0


@nb.njit(cache=True, nogil=True)
def _record_states(piece, t, phi, v, k1, t_last, s_max, requested, i_ev):
    """States at the `Requested` times in (t, t_last] of the step of ``piece`` that starts at
    (t, phi, v): each is one Dormand-Prince step from the step's start landing on the time
    (never an interpolant), capped at ``s_max``, written from index ``i_ev`` on. Returns (next
    index into the requested times, rhs evaluations)."""
    t_eval, eval_out = requested.times, requested.states
    exc = piece.exc
    n_rhs = 0
    while i_ev < t_eval.shape[0] and t_eval[i_ev] <= t_last:
        sub = min(t_eval[i_ev] - t, s_max)
        if sub > 0.0:
            ph, vv, aa, _e1, _e2 = dopri_step(piece, t, phi, v, k1, sub)
            n_rhs += 6
        else:
            ph, vv, aa = phi, v, k1
        eval_out[i_ev, 0] = ph
        eval_out[i_ev, 1] = vv
        eval_out[i_ev, 2] = aa
        eval_out[i_ev, 3] = piece.side
        eval_out[i_ev, 4] = ground_in_piece(exc.kind, exc.params, t + sub, piece.t_left)
        eval_out[i_ev, 5] = piece.row
        i_ev += 1
    return i_ev, n_rhs


@nb.njit(cache=True, nogil=True)
def no_return(piece, phi, v, kappa2, v_crest, v_toggle):
    """True if the ground motion left after the start ``t_left`` of the `Piece` ``piece``
    (its excitation's ``tail``) cannot bring a mechanism that is past its crest
    (``phi >= phi_crit``) and opening (``v >= 0``) back over the crest.

    The sufficient criterion of ``docs/notes/mechanism.md`` (collapse on a record): the ground's power
    on the mechanism is ``P = -side x_g'' H(phi) phi'`` and by Cauchy-Schwarz
    ``|H| <= sqrt(M m_eff)`` (M = ``kappa2``, the moving links' mass), so
    ``|P| <= |x_g''| sqrt(2 M T)``. Until it recrosses the crest the mechanism stays in
    [phi_crit, phi_toggle], where the potential decreases (checked by the caller), so its
    kinetic energy is at most ``D + U`` with ``D = E0 - g V(phi_toggle)`` and U the work the
    ground has exchanged, which gives ``sqrt(D + U) <= sqrt(D) + sqrt(M/2) A`` with
    ``A = int |x_g''| dt`` over the rest of the record. Turning back and recrossing needs
    ``U >= T0 + g (V(phi_crit) - V(phi))``; the criterion is that the bound is below it (with
    a relative margin of 1e-9).
    """
    mech, params, tail, t_left, g = piece.mech, piece.exc.params, piece.exc.tail, piece.t_left, piece.g
    # the tail's grid: the horizontal's samples (a record with its vertical: after its count)
    t0, dt = ((params[1], params[2]) if piece.exc.kind == KIND_SAMPLED_VERTICAL
              else (params[0], params[1]))
    n = tail.shape[0]
    i = int(math.floor((t_left - t0) / dt + 1e-9))
    if i < 0:
        a_rem = tail[0]
    elif i >= n:
        a_rem = 0.0
    else:
        a_rem = tail[i]  # from the start of the current piece: an upper bound
    ok, meff, _dm, _gg, _hh = eom_terms(mech, phi)
    if not ok:
        return False
    kinetic = 0.5 * meff * v * v
    v_here = potential(mech, phi)
    d = max(kinetic + g * (v_here - v_toggle), 0.0)
    root = math.sqrt(d) + math.sqrt(0.5 * kappa2) * a_rem
    exchanged = root * root - d
    needed = kinetic + g * (v_crest - v_here)
    return exchanged < (1.0 - 1e-9) * needed


@nb.njit(cache=True, nogil=True)
def _row_terms(table, row, use_tail):
    """What the kernel keeps of the mechanism row it moves on (taken once per half cycle, when
    the row changes): the packed row, its crest and toggle rotations (rad), m_eff at phi = 0,
    kappa2 = the sum of the link masses (|H| <= sqrt(kappa2 m_eff), Cauchy-Schwarz, for
    `no_return`), the potential/g at the crest (kg m; 0 without a record tail) and whether
    the no-return criterion applies on this row."""
    mech = table.mechs[row]
    phi_crit = mech[PHI_CRIT]
    _ok, meff0, _dm, _gg, _hh = eom_terms(mech, 0.0)
    kappa2 = 0.0
    for k in range(3):
        kappa2 += mech[LINK0 + 4 * k]
    v_crest = potential(mech, phi_crit) if use_tail else 0.0
    row_tail = use_tail and math.isfinite(table.v_toggle[row])
    return mech, phi_crit, mech[PHI_TOGGLE], meff0, kappa2, v_crest, row_tail


@nb.njit(cache=True, nogil=True)
def simulate_kernel(table, exc, settings, out):
    """Integrate one time history (`simulate_kernel_eval` without requested times).

    Returns
    -------
    (outcome, final_state, collapse_half_cycle)
    """
    requested = Requested(np.empty(0), np.empty((0, HIST_COLUMNS)))
    outcome, final, collapse_half, _n = simulate_kernel_eval(table, exc, settings, out,
                                                             requested)
    return outcome, final, collapse_half


@nb.njit(cache=True, nogil=True)
def simulate_kernel_eval(table, exc, settings, out, requested):
    """Integrate one time history, with the states at requested times. See the module
    docstring for the logic.

    Parameters
    ----------
    table : Table
        The mechanism stack and its impact table.
    exc : Excitation
        The ground motion (with a record's tail for the no-return criterion).
    settings : ndarray (N_SETTINGS,)
        Gravity, end time, tolerances, caps and output intervals (`settings`, ``S_*``).
    out : Output
        Written: the history, impacts, peaks, counters and onsets.
    requested : Requested
        Times, s, sorted (non-decreasing). A time inside an accepted step gets one extra
        Dormand-Prince step from the step's start landing on it (the step sequence, and so the
        history and events, are those of a run without requested times). A time at an impact
        gets the closing state; at the onset of hinging, the opening one (phi = 0, the ground
        just after the onset). Times after the arch has come to rest for good are locked
        states; times after a collapse or beyond ``t_end`` are not reached. Their states:
        phi, phi', phi'', side, x_g'', row at each time reached (in order); x_g'' is the
        value the step used there (at a breakpoint ending a step, the left limit).

    Returns
    -------
    (outcome, final_state, collapse_half_cycle, number of requested times reached)
    """
    kind, params, tail = exc.kind, exc.params, exc.tail
    g = settings[S_G]
    t_end = settings[S_T_END]
    rtol = settings[S_RTOL]
    atol_phi = settings[S_ATOL_PHI]
    rest_rotation = settings[S_REST_ROTATION]
    max_impacts = int(settings[S_MAX_IMPACTS])
    dt_out = settings[S_DT_OUT]
    dt_lock = settings[S_DT_LOCK]
    hist_limit = int(settings[S_HIST_LIMIT])
    initial_rate = settings[S_INITIAL_RATE]
    hist, impacts, peaks, counters, onsets = (out.hist, out.impacts, out.peaks, out.counters,
                                              out.onsets)
    t_eval, eval_out = requested.times, requested.states
    nxt, flip, ratio, v_toggle = table.nxt, table.flip, table.ratio, table.v_toggle
    t_exc = excitation_end(kind, params)
    row = np.int64(0)  # typed int64, not the literal 0, so that `_row_terms` compiles once
    use_tail = tail.shape[0] > 0
    mech, phi_crit, phi_toggle, meff0, kappa2, v_crest, row_tail = _row_terms(
        table, row, use_tail)
    atol_v = atol_phi * math.sqrt(g / mech[LENGTH])
    n_on = 0
    n_hist = 0
    cap = hist.shape[0]
    n_imp = 0
    half = 0
    n_steps = 0
    n_rej = 0
    n_rhs = 0
    onset_time = math.nan
    collapse_time = math.nan
    outcome = OUTCOME_NO_HINGING
    final = FINAL_REST
    collapse_half = 0
    t = 0.0
    side = 0
    phi = 0.0
    v = 0.0
    t_out = 0.0
    overflow = False
    i_ev = np.int64(0)  # typed int64, not the literal 0 (`_record_states` compiles once)
    n_eval = t_eval.shape[0]
    tau = math.sqrt(mech[LENGTH] / g)
    h = 1e-3 * tau
    h_min = 1e-14 * tau
    if initial_rate > 0.0:
        side = 1
        v = initial_rate
        half = 1
        peaks[0] = 0.0
        outcome = OUTCOME_SURVIVES
        onset_time = 0.0
    while t < t_end:
        if side == 0:
            t_on, s_on = find_onset(mech, exc, g, t, max(t, min(t_exc, t_end)))
            # history while locked
            if dt_out > 0.0:
                t_last = -1.0
                while t_out <= t_on:
                    if n_hist >= hist_limit:
                        overflow = True
                        break
                    if n_hist < cap:
                        hist[n_hist, 0] = t_out
                        hist[n_hist, 1] = 0.0
                        hist[n_hist, 2] = 0.0
                        hist[n_hist, 3] = 0.0
                        hist[n_hist, 4] = ground_in_piece(kind, params, t_out, t_out)
                        hist[n_hist, 5] = 0.0
                    t_last = t_out
                    n_hist += 1
                    t_out += dt_lock
                if dt_lock > dt_out and not overflow:
                    # sparse locked samples: close the stretch at its end, resume from there
                    if t_last < t_on and n_hist < hist_limit:
                        if n_hist < cap:
                            hist[n_hist, 0] = t_on
                            hist[n_hist, 1] = 0.0
                            hist[n_hist, 2] = 0.0
                            hist[n_hist, 3] = 0.0
                            hist[n_hist, 4] = ground_in_piece(kind, params, t_on, t_on)
                            hist[n_hist, 5] = 0.0
                        n_hist += 1
                    t_out = t_on + dt_out
                if overflow:
                    break
            # requested times while locked (all of them once at rest after the excitation)
            while i_ev < n_eval and (t_eval[i_ev] < t_on or (
                    s_on == 0 and (t_on >= t_exc or t_eval[i_ev] <= t_end))):
                eval_out[i_ev, 0] = 0.0
                eval_out[i_ev, 1] = 0.0
                eval_out[i_ev, 2] = 0.0
                eval_out[i_ev, 3] = 0.0
                eval_out[i_ev, 4] = ground_in_piece(kind, params, t_eval[i_ev], t_eval[i_ev])
                eval_out[i_ev, 5] = 0.0
                i_ev += 1
            if s_on == 0:
                t = t_on
                if final != FINAL_STALLED:  # locked by max_impacts after the excitation
                    final = FINAL_REST
                break
            t = t_on
            side = s_on
            phi = 0.0
            v = 0.0
            if n_on < onsets.shape[0]:
                onsets[n_on, 0] = t_on
                onsets[n_on, 1] = s_on
            n_on += 1
            half += 1
            peaks[half - 1] = 0.0
            if outcome == OUTCOME_NO_HINGING:
                outcome = OUTCOME_SURVIVES
                onset_time = t
            continue
        # ---------------------------------------------------------------- open
        t_left = t
        piece = Piece(mech, row, side, exc, g, t_left)
        t_stop = min(next_breakpoint(kind, params, t), t_end)
        k1 = _rhs(mech, kind, params, side, g, t, t_left, phi, v)
        n_rhs += 1
        if i_ev < n_eval and t_eval[i_ev] <= t:  # at the onset (or t = 0 of free rocking)
            i_ev, extra = _record_states(piece, t, phi, v, k1, t, 0.0, requested, i_ev)
        excitation_over = t >= t_exc - 1e-12 * (1.0 + t_exc)
        if excitation_over and phi >= phi_crit and v >= 0.0:
            outcome = OUTCOME_COLLAPSE
            final = FINAL_COLLAPSED
            collapse_time = t
            collapse_half = half
            break
        event_done = False
        while t < t_stop and not event_done:
            hh = min(h, t_stop - t)
            if hh < h_min:
                if i_ev < n_eval:
                    i_ev, extra = _record_states(piece, t, phi, v, k1, t_stop, hh, requested,
                                                 i_ev)
                    n_rhs += extra
                t = t_stop
                break
            phi1, v1, k7, ep, ev = dopri_step(piece, t, phi, v, k1, hh)
            n_rhs += 6
            if not (math.isfinite(phi1) and math.isfinite(v1) and math.isfinite(k7)):
                n_rej += 1
                h = 0.25 * hh
                if h < h_min:
                    # the linkage cannot go further: it has reached its toggle
                    outcome = OUTCOME_COLLAPSE
                    final = FINAL_COLLAPSED
                    collapse_time = t
                    collapse_half = half
                    event_done = True
                    t_end = t
                continue
            sc_p = atol_phi + rtol * max(abs(phi), abs(phi1))
            sc_v = atol_v + rtol * max(abs(v), abs(v1))
            err = math.sqrt(0.5 * ((ep / sc_p) ** 2 + (ev / sc_v) ** 2))
            if err > 1.0:
                n_rej += 1
                h = hh * max(0.2, 0.9 * err ** -0.2)
                continue
            n_steps += 1
            h_next = hh * min(5.0, 0.9 * err ** -0.2) if err > 0.0 else 5.0 * hh
            # ---- events inside [t, t + hh]
            ev_kind = 0  # 1 closure, 2 collapse (crest), 3 toggle
            s_ev = hh
            s_lo = 0.0
            if phi1 < 0.0 and phi >= 0.0:
                ev_kind = 1
                if v > 0.0:  # opening at the start: the closure comes after the top
                    s_lo = _hermite_root(hh, v, k1, v1, k7, 0.0, 0.0)
                s_ev = _hermite_root(hh, phi, v, phi1, v1, 0.0, s_lo)
            if excitation_over and phi1 >= phi_crit and v1 >= 0.0:
                if phi < phi_crit:
                    s_c = _hermite_root(hh, phi, v, phi1, v1, phi_crit, 0.0)
                elif v < 0.0:  # beyond the crest, closing, and turning back open: collapse
                    s_c = _hermite_root(hh, v, k1, v1, k7, 0.0, 0.0)
                else:
                    s_c = 0.0
                if ev_kind == 0 or s_c < s_ev:
                    ev_kind = 2
                    s_ev = s_c
            if phi1 >= phi_toggle * (1.0 - 1e-9) and (ev_kind == 0):
                ev_kind = 3
                s_ev = hh
            # ---- dense output up to the event (or the step end)
            if dt_out > 0.0:
                while t_out <= t + s_ev:
                    if n_hist >= hist_limit:
                        overflow = True
                        break
                    s = t_out - t
                    if n_hist < cap:
                        hist[n_hist, 0] = t_out
                        hist[n_hist, 1] = hermite(s, hh, phi, v, phi1, v1)
                        hist[n_hist, 2] = hermite(s, hh, v, k1, v1, k7)
                        hist[n_hist, 3] = side
                        hist[n_hist, 4] = ground_in_piece(kind, params, t_out, t_left)
                        hist[n_hist, 5] = row
                    n_hist += 1
                    t_out += dt_out
                if overflow:
                    break
            # ---- peak of the half cycle over [t, t + s_ev] (extremum of the interpolant)
            pk = max(phi, hermite(s_ev, hh, phi, v, phi1, v1))
            if v > 0.0 and v1 <= 0.0:
                s_top = _hermite_root(hh, v, k1, v1, k7, 0.0, 0.0)
                if s_top <= s_ev:
                    pk = max(pk, hermite(s_top, hh, phi, v, phi1, v1))
            if pk > peaks[half - 1]:
                peaks[half - 1] = pk
            if ev_kind == 0:
                t_new = t + hh if t + hh < t_stop else t_stop
                if i_ev < n_eval:
                    i_ev, extra = _record_states(piece, t, phi, v, k1, t_new, hh, requested,
                                                 i_ev)
                    n_rhs += extra
                t = t_new
                phi, v, k1 = phi1, v1, k7
                h = h_next
                if dt_out < 0.0:  # the integrator's own states
                    if n_hist >= hist_limit:
                        overflow = True
                        break
                    if n_hist < cap:
                        hist[n_hist, 0] = t
                        hist[n_hist, 1] = phi
                        hist[n_hist, 2] = v
                        hist[n_hist, 3] = side
                        hist[n_hist, 4] = ground_in_piece(kind, params, t, t_left)
                        hist[n_hist, 5] = row
                    n_hist += 1
                if (row_tail and not excitation_over and phi >= phi_crit and v >= 0.0
                        and no_return(piece, phi, v, kappa2, v_crest, v_toggle[row])):
                    # past the crest, opening, and the rest of the record cannot return it
                    outcome = OUTCOME_COLLAPSE
                    final = FINAL_COLLAPSED
                    collapse_time = t
                    collapse_half = half
                    t_end = t
                    break
                continue
            if ev_kind == 1:
                s, ph_e, v_e, a_e = _locate(piece, t, phi, v, k1, s_ev, 0.0, s_lo, hh)
                t_imp = t + s
                if i_ev < n_eval:  # up to the impact: the closing mechanism
                    i_ev, extra = _record_states(piece, t, phi, v, k1, t_imp, s, requested,
                                                 i_ev)
                    n_rhs += extra
                nrow = nxt[row]
                v_after = ratio[row] * abs(v_e)
                if nrow < 0:  # the impact leaves the tabulated set: never extrapolated
                    v_after = 0.0
                new_side = side * flip[row]
                if n_imp < impacts.shape[0]:
                    impacts[n_imp, 0] = t_imp
                    impacts[n_imp, 1] = v_e
                    impacts[n_imp, 2] = v_after
                    impacts[n_imp, 3] = row
                    impacts[n_imp, 4] = nrow
                    impacts[n_imp, 5] = new_side
                    impacts[n_imp, 6] = 0.0
                n_imp += 1
                t = t_imp
                event_done = True
                if nrow < 0:
                    if n_imp <= impacts.shape[0]:
                        impacts[n_imp - 1, 6] = 1.0
                    side = 0
                    phi = 0.0
                    v = 0.0
                    final = FINAL_UNRESOLVED
                    t_end = t
                    break
                if nrow != row:  # the post mechanism's row, once per half cycle
                    row = nrow
                    (mech, phi_crit, phi_toggle, meff0, kappa2, v_crest,
                     row_tail) = _row_terms(table, row, use_tail)
                # peak rotation of the coming half cycle on a linear potential g G0 phi
                # (gravity with the vertical ground acceleration at the impact)
                g_imp = g + vertical_in_piece(kind, params, t, t_left)
                peak_next = 0.5 * meff0 * v_after * v_after / (g_imp * mech[G0])
                if peak_next < rest_rotation or n_imp >= max_impacts:
                    side = 0
                    phi = 0.0
                    v = 0.0
                    if n_imp <= impacts.shape[0]:
                        impacts[n_imp - 1, 6] = 1.0
                    if n_imp >= max_impacts and t >= t_exc:
                        final = FINAL_STALLED
                else:
                    side = new_side
                    phi = 0.0
                    v = v_after
                    half += 1
                    if half - 1 < peaks.shape[0]:
                        peaks[half - 1] = 0.0
                    else:
                        half -= 1
                # first step of the new half cycle: at most a quarter of its free duration
                # 2 m_eff v / (g G0), so that tiny half cycles are resolved
                h = max(min(h_next, 0.5 * meff0 * v_after / (g * mech[G0])), 1e-9 * tau)
                if dt_out != 0.0:
                    if n_hist >= hist_limit:
                        overflow = True
                        break
                    if n_hist < cap:
                        hist[n_hist, 0] = t
                        hist[n_hist, 1] = 0.0
                        hist[n_hist, 2] = v
                        hist[n_hist, 3] = side
                        hist[n_hist, 4] = ground_in_piece(kind, params, t, t_left)
                        hist[n_hist, 5] = row
                    n_hist += 1
                if side == 0 and row != 0:  # locked: the next onset opens row 0 (or its mirror)
                    row = np.int64(0)
                    (mech, phi_crit, phi_toggle, meff0, kappa2, v_crest,
                     row_tail) = _row_terms(table, row, use_tail)
                continue
            # collapse
            s = s_ev
            if ev_kind == 2 and 0.0 < s_ev < hh and phi < phi_crit:
                s, ph_e, v_e, a_e = _locate(piece, t, phi, v, k1, s_ev, phi_crit, 0.0, hh)
            if i_ev < n_eval:
                i_ev, extra = _record_states(piece, t, phi, v, k1, t + s, s, requested, i_ev)
                n_rhs += extra
            outcome = OUTCOME_COLLAPSE
            final = FINAL_COLLAPSED
            collapse_time = t + s
            collapse_half = half
            t = t + s
            event_done = True
            t_end = t
        if final == FINAL_COLLAPSED or final == FINAL_UNRESOLVED or overflow:
            break
    else:
        final = FINAL_MOVING if side != 0 else FINAL_REST
    if side != 0 and final == FINAL_REST and t >= t_end:
        final = FINAL_MOVING
    counters[0] = n_hist
    counters[1] = n_imp
    counters[2] = half
    counters[3] = n_steps
    counters[4] = n_rej
    counters[5] = n_rhs
    counters[6] = onset_time
    counters[7] = collapse_time
    if overflow:
        counters[8] = 1.0
    counters[9] = n_on
    return outcome, final, collapse_half, i_ev


#: Relative safety margin on the energy barrier below which "cannot reach a crest again" is
#: accepted (`table_energies`).
ENERGY_MARGIN = 1e-6


@nb.njit(cache=True, nogil=True)
def table_energies(mechs, g):
    """m_eff(0) of each row, kg m^2, and the least crest barrier over the rows,
    ``min_r g [V_r(phi_crit,r) - V_r(0)]``, J.

    Free rocking (no ground motion) keeps the energy ``1/2 m_eff(0) phi'^2`` of the undisplaced
    configuration phi = 0 (common to every row) within a half cycle and loses energy at every
    impact whose c_T <= 1; a half cycle on row r reaches its crest only with at least its
    barrier. So an impact after the excitation that leaves ``1/2 m_eff(0) phi'^2`` below the
    least barrier, on a table whose rows all have c_T <= 1, proves that no crest is reached
    again: the proof of the batches' early decision (`archquake.domains._kernels`) and of
    `archquake.mechanism.simulate`'s survival of a run cut while still rocking.
    """
    m = mechs.shape[0]
    meff0 = np.empty(m)
    barrier = math.inf
    for r in range(m):
        _ok, me, _dm, _gg, _hh = eom_terms(mechs[r], 0.0)
        meff0[r] = me
        b = g * (potential(mechs[r], mechs[r, PHI_CRIT]) - potential(mechs[r], 0.0))
        barrier = min(barrier, b)
    return meff0, barrier


@nb.njit(cache=True, nogil=True)
def last_impact_energy(impacts, n_all, t_exc, table, meff0, barrier):
    """The kinetic energy ``1/2 m_eff(0) phi'^2`` the run's last impact left, as a fraction of
    the least crest barrier (`table_energies`), where the free-rocking proof applies to
    it; NaN where it does not. ``meff0`` and ``barrier`` are `table_energies` of the `Table`
    ``table``.

    It applies when the last impact is recorded (``1 <= n_all <= impacts.shape[0]``: the run did
    not go on past its cap), came at or after the end of the excitation ``t_exc``, onto a row of
    the table (``impacts[k, 4] >= 0``), every row's impact keeps ``c_T <= 1`` (``table.ct_max``),
    and the barrier is positive; and, for a table with a row whose impact the law does not
    describe (``table.undescribed``), once such an impact has happened (the verdict is then indeterminate
    anyway: before that, an undescribed impact may still come). A fraction below
    ``1 - ENERGY_MARGIN`` proves that the arch never reaches a crest again.
    """
    if n_all < 1 or n_all > impacts.shape[0]:
        return math.nan
    k = n_all - 1
    row = int(impacts[k, 4])
    undescribed = table.undescribed
    if impacts[k, 0] < t_exc or row < 0 or table.ct_max > 1.0:
        return math.nan
    if not (math.isfinite(barrier) and barrier > 0.0):
        return math.nan
    some = False
    seen = False
    for r in range(undescribed.shape[0]):
        some = some or undescribed[r]
    for j in range(n_all):
        seen = seen or undescribed[int(impacts[j, 3])]
    if some and not seen:
        return math.nan
    rate = impacts[k, 2]
    return 0.5 * meff0[row] * rate * rate / barrier
