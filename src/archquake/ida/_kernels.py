"""Many scaled ground motions at once: a parallel numba loop over the scalar kernel.

Each case is one ground motion (any kind the compiled evaluator knows: a sampled record, a
step or sine pulse), already scaled, with its own end time, on one packed mechanism. Every case
runs :func:`archquake.mechanism._kernels.simulate_kernel`, the compiled path behind
:func:`archquake.mechanism.simulate`, without history, so the event logic is that kernel's.

The early decision is the failure domains' criterion (:mod:`archquake.domains._kernels`): a
surviving arch is accepted as such when an impact at or after the end of the excitation leaves a
kinetic energy below ``(1 - margin)`` of the barrier ``g [V(phi_crit) - V(0)]`` with
``c_v <= 1``: free rocking only loses energy at impacts, so the crest cannot be reached again.
A record shakes the arch through many impacts before it ends, so instead of capping the impacts
(the pulses' way, which would integrate the record again at every larger cap) the first run stops
a short window after the excitation (:func:`run_case`); the free-rocking tail to rest, which
``simulate`` integrates, is skipped.

Incremental dynamic analysis also needs the largest rotation of the whole run. Up to the
deciding impact it is the largest recorded peak; after it the arch rocks freely, every half
cycle peaks where the potential has risen by the kinetic energy left by the impact before it
(energy conservation between impacts, Eq. 2 with x_g'' = 0, the mirror mechanism having the
same potential), and impacts only remove energy, so the next half cycle's peak bounds all later
ones. It is found by bisection of ``g [V(phi) - V(0)] = 1/2 m_eff(0) phi'^2`` on ``[0, phi_crit]``.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from archquake.domains._kernels import ENERGY_MARGIN
from archquake.mechanism._kernels import (
    FINAL_MOVING,
    OUTCOME_COLLAPSE,
    OUTCOME_SURVIVES,
    excitation_end,
    simulate_kernel,
)
from archquake.mechanism.kinematics import PHI_CRIT, eom_terms, potential

#: Length of the first run after the end of the excitation, in sqrt(R/g) (several free
#: half cycles of an arch rocking near its crest).
WINDOW_TAU = 10.0
#: Bisection steps for the free-rocking peak (2^-60 of phi_crit: below round-off).
PEAK_BISECTIONS = 60


@nb.njit(cache=True, nogil=True)
def free_peak(mech, g, meff0, rate):
    """Peak rotation, rad, of a free half cycle that starts at phi = 0 with opening ``rate``
    (rad/s) and stays below the crest: the root of ``g [V(phi) - V(0)] = 1/2 m_eff(0) rate^2``."""
    energy = 0.5 * meff0 * rate * rate
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
def run_case(mech, kind, params, g, cv, t_end, window, rtol, atol, rest_rotation, max_impacts,
             early, barrier, meff0):
    """One case; returns (outcome, collapse_half_cycle, impacts, runs, peak rotation rad).

    With ``early``, the case first runs to ``min(t_end, end of excitation + window)`` (the
    trajectory up to then is exactly the full run's: the end time only stops the integration).
    A collapse, a rest or the end of hinging within it is the full run's answer; an arch still
    rocking is accepted as surviving at the first impact after the excitation whose kinetic
    energy is below the barrier (module docstring). Otherwise it is run again to ``t_end``.
    """
    hist = np.zeros((1, 5))
    t_exc = excitation_end(kind, params)
    # simulate_kernel locks the arch at a rest (and at max_impacts) but a record still acting
    # can open it again, and the new half cycle's peak is written without a bound check; at
    # most a few re-openings per piece of the excitation, so leave room for them.
    spare = 2 * params.shape[0] + 16
    t_stop = min(t_end, t_exc + window) if early else t_end
    runs = 0
    while True:
        impacts = np.zeros((max_impacts, 3))
        peaks = np.zeros(max_impacts + 1 + spare)
        counters = np.zeros(8)
        outcome, final, half = simulate_kernel(
            mech, kind, params, g, cv, t_stop, rtol, atol, rest_rotation, max_impacts, 0.0,
            hist, impacts, peaks, counters)
        runs += 1
        n_imp = int(counters[1])
        n_half = int(counters[2])
        peak = 0.0
        for k in range(min(n_half, peaks.shape[0])):
            peak = max(peak, peaks[k])
        if t_stop >= t_end or final != FINAL_MOVING:
            return outcome, half, n_imp, runs, peak
        if outcome == OUTCOME_SURVIVES and cv <= 1.0:
            for k in range(min(n_imp, max_impacts)):
                if impacts[k, 0] >= t_exc:
                    v = impacts[k, 2]
                    if 0.5 * meff0 * v * v < (1.0 - ENERGY_MARGIN) * barrier:
                        # peaks up to impact k are recorded; the free half cycle after it
                        # bounds every later one
                        peak = 0.0
                        for j in range(k + 1):
                            peak = max(peak, peaks[j])
                        peak = max(peak, free_peak(mech, g, meff0, v))
                        return outcome, half, n_imp, runs, peak
                    break
        t_stop = t_end


@nb.njit(cache=True, parallel=True)
def batch_kernel(mech, kinds, flat, offsets, g, cv, t_end, window, rtol, atol, rest_rotation,
                 max_impacts, early, outcome, half, n_impacts, runs, peak):
    """Run ``kinds.shape[0]`` cases in parallel.

    Parameters
    ----------
    mech : (30,) packed mechanism
    kinds : (n,) int64 ground-motion kind of each case
    flat : (m,) the cases' kernel parameters, concatenated; case i uses
        ``flat[offsets[i]:offsets[i + 1]]``
    offsets : (n + 1,) int64
    g, cv, rtol, atol, rest_rotation, max_impacts : as :func:`simulate_kernel`
    t_end : (n,) end of each analysis, s
    window : s, the first run of a case stops this long after the excitation (with ``early``)
    early : bool, decide early (module docstring)
    outcome, half, n_impacts, runs : (n,) int64 out;  peak : (n,) float64 out, rad
    """
    n = kinds.shape[0]
    _ok, meff0, _dm, _gg, _hh = eom_terms(mech, 0.0)
    barrier = g * (potential(mech, mech[PHI_CRIT]) - potential(mech, 0.0))
    for i in nb.prange(n):
        params = flat[offsets[i]:offsets[i + 1]]
        o, h, m, r, p = run_case(mech, kinds[i], params, g, cv, t_end[i], window, rtol, atol,
                                 rest_rotation, max_impacts, early, barrier, meff0)
        outcome[i] = o
        half[i] = h if o == OUTCOME_COLLAPSE else 0
        n_impacts[i] = m
        runs[i] = r
        peak[i] = p


__all__ = ["PEAK_BISECTIONS", "WINDOW_TAU", "batch_kernel", "free_peak", "run_case"]
