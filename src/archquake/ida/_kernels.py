"""Many scaled ground motions at once: a parallel numba loop over the scalar kernel.

Each case is one ground motion (any kind the compiled evaluator knows: a sampled record, a
step or sine pulse), already scaled, with its own end time, on one stack of packed mechanisms
with its impact table (`ImpactTable`). Every case
runs `archquake.mechanism._kernels.simulate_kernel`, the compiled path behind
`archquake.mechanism.simulate`, without history, so the event logic is that kernel's.

The early decision is the failure domains' criterion (`archquake.domains._kernels`): a
surviving arch is accepted as such when an impact at or after the end of the excitation leaves a
kinetic energy below ``(1 - margin)`` of the least barrier ``g [V_r(phi_crit,r) - V_r(0)]`` over
the table's rows with every row's ``c_T <= 1``: free rocking only loses energy at impacts, so no
crest can be reached again (the proof is in `archquake.domains._kernels`).
A record shakes the arch through many impacts before it ends, so instead of capping the impacts
(the pulses' way, which would integrate the record again at every larger cap) the first run stops
a short window after the excitation (`run_case`); the free-rocking tail to rest, which
``simulate`` integrates, is skipped.

Incremental dynamic analysis also needs the largest rotation of the whole run. Up to the
deciding impact it is the largest recorded peak; after it the arch rocks freely, every half
cycle peaks where the potential of its own row has risen by the kinetic energy left by the
impact before it (energy conservation between impacts, Eq. 2 with x_g'' = 0; a row's mirror
image has the row's potential), and the free sequence is known from the table alone: the rows
follow ``next``, each impact keeps the row's ``c_T`` of the energy (`free_rocking_peak`).
Energies only decrease and a row's peak grows with the energy, so once a row comes round again
its later peaks are below its first: the largest is found among the first visit of each row.
Each peak is found by bisection of ``g [V(phi) - V(0)] = E`` on ``[0, phi_crit]``.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from archquake._kernel_cache import stamp_kernels
from archquake.domains._kernels import ENERGY_MARGIN, Decisions, table_energies, undescribed_seen
from archquake.mechanism._kernels import (
    FINAL_MOVING,
    HIST_COLUMNS,
    IMPACT_COLUMNS,
    OUTCOME_COLLAPSE,
    OUTCOME_SURVIVES,
    S_G,
    S_MAX_IMPACTS,
    Excitation,
    Output,
    excitation_end,
    last_impact_energy,
    run_settings,
    simulate_kernel,
)
from archquake.mechanism.kinematics import PHI_CRIT, potential

stamp_kernels()  # the cache checks each kernel against every source compiled into it

#: Length of the first run after the end of the excitation, in sqrt(R/g) (several free
#: half cycles of an arch rocking near its crest).
WINDOW_TAU = 10.0
#: Bisection steps for the free-rocking peak (2^-60 of phi_crit: below round-off).
PEAK_BISECTIONS = 60


@nb.njit(cache=True, nogil=True)
def free_peak(mech, g, energy):
    """Peak rotation, rad, of a free half cycle of ``mech`` that starts at phi = 0 with kinetic
    energy ``energy`` (J) and stays below the crest: the root of ``g [V(phi) - V(0)] = energy``."""
    v0 = potential(mech, 0.0)
    lo = 0.0
    hi = mech[PHI_CRIT]
    for _ in range(PEAK_BISECTIONS):
        mid = 0.5 * (lo + hi)
        if g * (potential(mech, mid) - v0) < energy:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


@nb.njit(cache=True, nogil=True)
def free_rocking_peak(table, meff0, g, row, rate):
    """The largest peak rotation, rad, of free rocking that starts on ``row`` at phi = 0 with
    opening ``rate`` (rad/s), below every crest: the rows of the `Table` ``table`` follow its
    ``nxt`` and each impact turns the closing rate (equal to the opening one: energy is
    conserved within a free half cycle) into ``ratio`` times it on the next row (module
    docstring); ``meff0``: `table_energies`, g: m/s^2."""
    mechs, nxt, ratio = table.mechs, table.nxt, table.ratio
    m = mechs.shape[0]
    seen = np.zeros(m, dtype=np.bool_)
    peak = 0.0
    v = rate
    for _ in range(m):
        if row < 0 or seen[row]:
            break
        seen[row] = True
        peak = max(peak, free_peak(mechs[row], g, 0.5 * meff0[row] * v * v))
        v = ratio[row] * v
        row = nxt[row]
    return peak


@nb.njit(cache=True, nogil=True)
def run_case(table, exc, base, t_end, window, early, barrier, meff0):
    """One case: the `Excitation` ``exc`` on the `Table` ``table`` with the settings ``base``
    (`archquake.mechanism._kernels.settings`) up to ``t_end`` (s), a first run ``window`` (s)
    past the excitation, with the table's `table_energies` ``meff0`` and ``barrier``;
    returns (outcome, collapse_half_cycle, impacts, runs, peak rotation rad, undescribed
    impact seen, final state code, energy fraction): the last two are what
    `archquake.mechanism.simulate.conclude_run` states the verdict from, as for
    `simulate` (the deciding run's end and its last impact's energy
    over the least crest barrier, `last_impact_energy`,
    NaN where the proof does not apply; an early survival: ``moving`` with the energy of the
    impact that proved it).

    With ``early``, the case first runs to ``min(t_end, end of excitation + window)`` (the
    trajectory up to then is exactly the full run's: the end time only stops the integration).
    A collapse, a rest or the end of hinging within it is the full run's answer; an arch still
    rocking is accepted as surviving at the first impact after the excitation whose kinetic
    energy is below the barrier (module docstring), if the verdict cannot still meet an
    undescribed impact (`archquake.domains._kernels`). Otherwise it is run again to
    ``t_end``.
    """
    hist = np.zeros((1, HIST_COLUMNS))
    params, undescribed, ct_max = exc.params, table.undescribed, table.ct_max
    g = base[S_G]
    max_impacts = int(base[S_MAX_IMPACTS])
    t_exc = excitation_end(exc.kind, params)
    # simulate_kernel locks the arch at a rest (and at max_impacts) but a record still acting
    # can open it again, and the new half cycle's peak is written without a bound check; at
    # most a few re-openings per piece of the excitation, so leave room for them.
    spare = 2 * params.shape[0] + 16
    t_stop = min(t_end, t_exc + window) if early else t_end
    any_undescribed = False
    for r in range(undescribed.shape[0]):
        any_undescribed = any_undescribed or undescribed[r]
    runs = 0
    while True:
        impacts = np.zeros((max_impacts, IMPACT_COLUMNS))
        peaks = np.zeros(max_impacts + 1 + spare)
        counters = np.zeros(10)
        onsets = np.zeros((max_impacts + 1 + spare, 2))
        outcome, final, half = simulate_kernel(table, exc,
                                               run_settings(base, t_stop, max_impacts),
                                               Output(hist, impacts, peaks, counters, onsets))
        runs += 1
        n_imp = int(counters[1])
        n_half = int(counters[2])
        peak = 0.0
        for k in range(min(n_half, peaks.shape[0])):
            peak = max(peak, peaks[k])
        if t_stop >= t_end or final != FINAL_MOVING:
            return (outcome, half, n_imp, runs, peak, undescribed_seen(impacts, n_imp,
                                                                       undescribed),
                    final, last_impact_energy(impacts, n_imp, t_exc, table, meff0, barrier))
        if outcome == OUTCOME_SURVIVES and ct_max <= 1.0:
            for k in range(min(n_imp, max_impacts)):
                if impacts[k, 0] >= t_exc:
                    v = impacts[k, 2]
                    row = int(impacts[k, 4])
                    seen = undescribed_seen(impacts, k + 1, undescribed)
                    if (row >= 0 and (seen or not any_undescribed)
                            and 0.5 * meff0[row] * v * v < (1.0 - ENERGY_MARGIN) * barrier):
                        # peaks up to impact k are recorded; the free rocking after it is
                        # known from the table
                        peak = 0.0
                        for j in range(k + 1):
                            peak = max(peak, peaks[j])
                        peak = max(peak, free_rocking_peak(table, meff0, g, row, v))
                        return (outcome, half, n_imp, runs, peak, seen, final,
                                0.5 * meff0[row] * v * v / barrier)
                    break
        t_stop = t_end


@nb.njit(cache=True, parallel=True)
def batch_kernel(table, kinds, flat, offsets, base, t_end, window, early):
    """Run ``kinds.shape[0]`` cases in parallel.

    Parameters
    ----------
    table : Table
        The mechanism table (`archquake.mechanism._kernels.Table`).
    kinds : ndarray (n,) int64
        Ground-motion kind of each case.
    flat : ndarray (m,)
        The cases' kernel parameters, concatenated; case i uses
        ``flat[offsets[i]:offsets[i + 1]]``.
    offsets : ndarray (n + 1,) int64
    base : ndarray
        Gravity, tolerances, rest rotation and cap on impacts
        (`archquake.mechanism._kernels.settings`; no history).
    t_end : ndarray (n,)
        End of each analysis, s.
    window : float
        S, the first run of a case stops this long after the excitation (with ``early``).
    early : bool
        Decide early (module docstring).

    Returns
    -------
    Decisions
        Of each case (`archquake.domains._kernels.Decisions`; see `run_case`).
    """
    n = kinds.shape[0]
    meff0, barrier = table_energies(table.mechs, base[S_G])
    no_tail = np.empty(0)
    # written by the parallel loop as plain arrays, wrapped at the end: numba's parallel loop
    # loses writes through an array reached from a tuple (a known limitation)
    outcome = np.zeros(n, dtype=np.int64)
    half = np.zeros(n, dtype=np.int64)
    n_impacts = np.zeros(n, dtype=np.int64)
    runs = np.zeros(n, dtype=np.int64)
    peak = np.zeros(n)
    unseen = np.zeros(n, dtype=np.bool_)
    final = np.zeros(n, dtype=np.int64)
    fraction = np.full(n, np.nan)
    for i in nb.prange(n):
        exc = Excitation(kinds[i], flat[offsets[i]:offsets[i + 1]], no_tail)
        o, h, m, r, p, u, f, e = run_case(table, exc, base, t_end[i], window, early, barrier,
                                          meff0)
        outcome[i] = o
        half[i] = h if o == OUTCOME_COLLAPSE else 0
        n_impacts[i] = m
        runs[i] = r
        peak[i] = p
        unseen[i] = u
        final[i] = f
        fraction[i] = e
    return Decisions(outcome, half, n_impacts, runs, peak, unseen, final, fraction)


__all__ = ["PEAK_BISECTIONS", "WINDOW_TAU", "batch_kernel", "free_peak", "free_rocking_peak",
           "run_case"]
