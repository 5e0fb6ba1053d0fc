"""Many pulse time histories at once: a parallel numba loop over the scalar kernel.

Each case is one pulse of the family (``kind``; params ``[a, duration, direction]``) on the same
stack of packed mechanisms with its impact table
(`ImpactTable`). Every case runs
`archquake.mechanism._kernels.simulate_kernel`, the compiled path behind
`archquake.mechanism.simulate`, with no history (``dt_out = 0``): the event logic (onset,
closure and impact, rest, crest and toggle collapse) is that kernel's, unchanged.

Deciding early (``early=True``)
-------------------------------
A surviving arch rocks on for dozens of impacts until it is at rest, and that tail is most of
the cost of a survival. The batch first runs a case with a small cap on the number of impacts
(the kernel locks the arch at the cap-th impact, so the trajectory up to that impact is exactly
the full run's) and accepts the answer when the trajectory up to the cap already decides it:

* the case ended with fewer impacts than the cap (no hinging, rest, or a collapse): it is the
  full run;
* its last impact, at or after the end of the excitation, left a kinetic energy
  ``1/2 m_eff(0) phi'^2`` (of the post-impact row) below ``(1 - margin)`` times the least
  potential barrier ``g [V_r(phi_crit,r) - V_r(0)]`` over the rows r of the table, and no row's
  impact gains energy (``c_T <= 1``): from then on the arch rocks freely, its total energy (the
  kinetic energy at phi = 0, the undisplaced configuration common to every row) is conserved
  within each half cycle (Eq. 2 with x_g'' = 0) and never grows at an impact, and a half cycle
  on any row r reaches that row's crest only with at least its barrier, which is at least the
  least one: it can never reach a crest again and survives (the barrier:
  `archquake.mechanism._kernels.table_energies`, which
  `archquake.mechanism.simulate` uses for the same proof at its ``t_end``; the test
  itself: `archquake.mechanism._kernels.last_impact_energy`). A row the
  law's impacts leave (``next < 0``) stops the run and is flagged, so no motion outside the table is assumed.
  The verdict it states must not hide an undescribed impact still to come: an early survival
  is accepted only if every row's impact is described, or an undescribed impact has already
  happened (the survival is then indeterminate whatever follows).

Otherwise the case is run again with an eight times larger cap, up to the full
``max_impacts``. ``early=False`` runs every case in full. Each case returns how its deciding
run ended and its last impact's energy, from which the caller states the verdict by
`archquake.mechanism.simulate`'s own rule
(`conclude_run`: a run locked by ``max_impacts``, or cut by
``t_end`` while rocking, survives only with that proof). A test holds both modes to
`simulate` point by point.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from archquake.mechanism._kernels import (
    ENERGY_MARGIN,
    HIST_COLUMNS,
    IMPACT_COLUMNS,
    OUTCOME_COLLAPSE,
    OUTCOME_NO_HINGING,
    OUTCOME_SURVIVES,
    excitation_end,
    last_impact_energy,
    simulate_kernel,
    table_energies,
)
from archquake.outcome import Outcome

#: First cap on impacts when deciding early.
FIRST_IMPACT_CAP = 4


@nb.njit(cache=True, nogil=True)
def undescribed_seen(impacts, n_imp, undescribed):
    """True if one of the first ``n_imp`` recorded impacts is of a row whose impact the law
    does not describe."""
    for k in range(min(n_imp, impacts.shape[0])):
        if undescribed[int(impacts[k, 3])]:
            return True
    return False


@nb.njit(cache=True, nogil=True)
def _run_case(mechs, nxt, flip, ratio, kind, params, g, t_end, rtol, atol, rest_rotation,
              max_impacts, early, barrier, meff0, undescribed, ct_max):
    """One case; returns (outcome, collapse_half_cycle, impacts, runs, undescribed impact seen,
    final state code, energy fraction of the last impact) of the deciding run: what
    `archquake.mechanism.simulate.conclude_run` states the verdict from, as for
    `simulate` (the fraction: `last_impact_energy`, NaN where
    its proof does not apply).

    An early run locked at its cap is accepted when the proof holds at its last impact (the
    energy never grows after the excitation, so this accepts whenever it holds at an earlier
    impact after the excitation); it is then reported ``stalled`` with that fraction (below
    ``1 - ENERGY_MARGIN``), which states ``survives``, as the full run would."""
    hist = np.zeros((1, HIST_COLUMNS))
    t_exc = excitation_end(kind, params)
    cap = min(FIRST_IMPACT_CAP, max_impacts) if early else max_impacts
    runs = 0
    while True:
        impacts = np.zeros((cap, IMPACT_COLUMNS))
        peaks = np.zeros(cap + 1)
        counters = np.zeros(10)
        onsets = np.zeros((cap + 1, 2))
        outcome, final, half = simulate_kernel(
            mechs, nxt, flip, ratio, kind, params, g, t_end, rtol, atol, rest_rotation, cap,
            0.0, hist, impacts, peaks, counters, onsets)
        runs += 1
        n_imp = int(counters[1])
        fraction = last_impact_energy(impacts, n_imp, t_exc, meff0, barrier, ct_max, undescribed)
        if (cap >= max_impacts or n_imp < cap
                or (outcome == OUTCOME_SURVIVES and fraction < 1.0 - ENERGY_MARGIN)):
            return (outcome, half, n_imp, runs, undescribed_seen(impacts, n_imp, undescribed),
                    final, fraction)
        cap = min(8 * cap, max_impacts)


@nb.njit(cache=True, parallel=True)
def batch_kernel(mechs, nxt, flip, ratio, kind, params, g, t_end, rtol, atol, rest_rotation,
                 max_impacts, early, undescribed, ct_max, outcome, half, n_impacts, runs,
                 unseen, final, fraction):
    """Run ``params.shape[0]`` cases in parallel.

    Parameters
    ----------
    mechs, nxt, flip, ratio : the mechanism table, as `simulate_kernel`
    kind : int, ground-motion kind (step or sine)
    params : (n, 3) per case ``[a (m/s^2), duration (s), direction]``
    g, rtol, atol, rest_rotation, max_impacts : as `simulate_kernel`
    t_end : (n,) end of each analysis, s
    early : bool, decide early (module docstring)
    undescribed : (m,) bool, the law does not describe the row's impact
    ct_max : the largest kinetic-energy ratio of the rows' impacts
    outcome, half, n_impacts, runs : (n,) int64 out: outcome code, collapse half cycle (0 if
        none), impacts in the deciding run, kernel runs used
    unseen : (n,) bool out: an undescribed impact happened before the verdict
    final : (n,) int64 out: how the deciding run ended (the kernel's ``FINAL_*`` code)
    fraction : (n,) float64 out: its last impact's energy over the least crest barrier, NaN
        where the proof does not apply (`last_impact_energy`)
    """
    n = params.shape[0]
    meff0, barrier = table_energies(mechs, g)
    for i in nb.prange(n):
        o, h, m, r, u, f, e = _run_case(mechs, nxt, flip, ratio, kind, params[i], g, t_end[i],
                                        rtol, atol, rest_rotation, max_impacts, early, barrier,
                                        meff0, undescribed, ct_max)
        outcome[i] = o
        half[i] = h if o == OUTCOME_COLLAPSE else 0
        n_impacts[i] = m
        runs[i] = r
        unseen[i] = u
        final[i] = f
        fraction[i] = e


#: The kernel's outcome codes as `Outcome` values.
OUTCOMES = {OUTCOME_NO_HINGING: Outcome.NO_HINGING, OUTCOME_SURVIVES: Outcome.SURVIVES,
            OUTCOME_COLLAPSE: Outcome.COLLAPSE}


def decode(codes: np.ndarray) -> np.ndarray:
    """The kernel's outcome codes (n,) as an object array of `Outcome`."""
    out = np.empty(len(codes), dtype=object)
    for i, c in enumerate(codes):
        out[i] = OUTCOMES[int(c)]
    return out


__all__ = ["ENERGY_MARGIN", "FIRST_IMPACT_CAP", "OUTCOMES", "batch_kernel", "decode",
           "table_energies", "undescribed_seen"]
