"""Many pulse time histories at once: a parallel numba loop over the scalar kernel.

Each case is one pulse of the family (``kind``; params ``[a, duration, direction]``) on the same
packed mechanism. Every case runs :func:`archquake.mechanism._kernels.simulate_kernel`, the
compiled path behind :func:`archquake.mechanism.simulate`, with no history (``dt_out = 0``):
the event logic (onset, closure and impact, rest, crest and toggle collapse) is that kernel's,
unchanged.

Deciding early (``early=True``)
-------------------------------
A surviving arch rocks on for dozens of impacts until it is at rest, and that tail is most of
the cost of a survival. The batch first runs a case with a small cap on the number of impacts
(the kernel locks the arch at the cap-th impact, so the trajectory up to that impact is exactly
the full run's) and accepts the answer when the trajectory up to the cap already decides it:

* the case ended with fewer impacts than the cap (no hinging, rest, or a collapse): it is the
  full run;
* an impact at or after the end of the excitation left a kinetic energy
  ``1/2 m_eff(0) phi'^2`` below ``(1 - margin)`` times the potential barrier
  ``g [V(phi_crit) - V(0)]`` and ``c_v <= 1``: from then on the arch rocks freely and every
  impact removes energy, so it can never reach the crest again (energy conservation between
  impacts, Eq. 2 with x_g'' = 0): it survives.

Otherwise the case is run again with an eight times larger cap, up to the full
``max_impacts``. ``early=False`` runs every case in full. A test holds both modes to
:func:`~archquake.mechanism.simulate` point by point.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from archquake.mechanism._kernels import (
    OUTCOME_COLLAPSE,
    OUTCOME_NO_HINGING,
    OUTCOME_SURVIVES,
    excitation_end,
    simulate_kernel,
)
from archquake.mechanism.kinematics import PHI_CRIT, eom_terms, potential
from archquake.outcome import Outcome

#: Relative safety margin on the energy barrier below which an early "survives" is accepted.
ENERGY_MARGIN = 1e-6
#: First cap on impacts when deciding early.
FIRST_IMPACT_CAP = 4


@nb.njit(cache=True, nogil=True)
def _run_case(mech, kind, params, g, cv, t_end, rtol, atol, rest_rotation, max_impacts,
              early, barrier, meff0):
    """One case; returns (outcome, collapse_half_cycle, impacts, runs)."""
    hist = np.zeros((1, 5))
    t_exc = excitation_end(kind, params)
    cap = min(FIRST_IMPACT_CAP, max_impacts) if early else max_impacts
    runs = 0
    while True:
        impacts = np.zeros((cap, 3))
        peaks = np.zeros(cap + 1)
        counters = np.zeros(9)
        outcome, _final, half = simulate_kernel(
            mech, kind, params, g, cv, t_end, rtol, atol, rest_rotation, cap, 0.0,
            hist, impacts, peaks, counters)
        runs += 1
        n_imp = int(counters[1])
        if cap >= max_impacts or n_imp < cap:
            return outcome, half, n_imp, runs
        if outcome == OUTCOME_SURVIVES and cv <= 1.0:
            for k in range(cap):
                if impacts[k, 0] >= t_exc:
                    v = impacts[k, 2]
                    if 0.5 * meff0 * v * v < (1.0 - ENERGY_MARGIN) * barrier:
                        return outcome, half, n_imp, runs
                    break
        cap = min(8 * cap, max_impacts)


@nb.njit(cache=True, parallel=True)
def batch_kernel(mech, kind, params, g, cv, t_end, rtol, atol, rest_rotation, max_impacts,
                 early, outcome, half, n_impacts, runs):
    """Run ``params.shape[0]`` cases in parallel.

    Parameters
    ----------
    mech : (30,) packed mechanism
    kind : int, ground-motion kind (step or sine)
    params : (n, 3) per case ``[a (m/s^2), duration (s), direction]``
    g, cv, rtol, atol, rest_rotation, max_impacts : as :func:`simulate_kernel`
    t_end : (n,) end of each analysis, s
    early : bool, decide early (module docstring)
    outcome, half, n_impacts, runs : (n,) int64 out: outcome code, collapse half cycle (0 if
        none), impacts in the deciding run, kernel runs used
    """
    n = params.shape[0]
    _ok, meff0, _dm, _gg, _hh = eom_terms(mech, 0.0)
    barrier = g * (potential(mech, mech[PHI_CRIT]) - potential(mech, 0.0))
    for i in nb.prange(n):
        o, h, m, r = _run_case(mech, kind, params[i], g, cv, t_end[i], rtol, atol, rest_rotation,
                               max_impacts, early, barrier, meff0)
        outcome[i] = o
        half[i] = h if o == OUTCOME_COLLAPSE else 0
        n_impacts[i] = m
        runs[i] = r


#: The kernel's outcome codes as :class:`~archquake.outcome.Outcome` values.
OUTCOMES = {OUTCOME_NO_HINGING: Outcome.NO_HINGING, OUTCOME_SURVIVES: Outcome.SURVIVES,
            OUTCOME_COLLAPSE: Outcome.COLLAPSE}


def decode(codes: np.ndarray) -> np.ndarray:
    """The kernel's outcome codes (n,) as an object array of :class:`~archquake.outcome.Outcome`."""
    out = np.empty(len(codes), dtype=object)
    for i, c in enumerate(codes):
        out[i] = OUTCOMES[int(c)]
    return out


def default_t_end(excitation_end_s: np.ndarray, radius: float, g: float) -> np.ndarray:
    """End of each analysis, s: the default of :func:`archquake.mechanism.simulate`
    (the end of the excitation plus 60 sqrt(R/g)); a test holds the two equal."""
    return np.asarray(excitation_end_s, dtype=float) + 60.0 * math.sqrt(radius / g)


__all__ = ["ENERGY_MARGIN", "FIRST_IMPACT_CAP", "OUTCOMES", "batch_kernel", "decode",
           "default_t_end"]
