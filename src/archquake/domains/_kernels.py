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

from typing import NamedTuple

import numba as nb
import numpy as np

from archquake._kernel_cache import stamp_kernels
from archquake.mechanism._kernels import (
    ENERGY_MARGIN,
    HIST_COLUMNS,
    IMPACT_COLUMNS,
    OUTCOME_COLLAPSE,
    OUTCOME_NO_HINGING,
    OUTCOME_SURVIVES,
    S_G,
    S_MAX_IMPACTS,
    Excitation,
    Output,
    excitation_end,
    last_impact_energy,
    run_settings,
    simulate_kernel,
    table_energies,
)
from archquake.outcome import Outcome

stamp_kernels()  # the cache checks each kernel against every source compiled into it

#: First cap on impacts when deciding early.
FIRST_IMPACT_CAP = 4


class Decisions(NamedTuple):
    """What a batch returns for each of its n cases.

    Attributes
    ----------
    outcome : ndarray (n,) int64
        The kernel's outcome code.
    half : ndarray (n,) int64
        Collapse half cycle (0 if none).
    n_impacts : ndarray (n,) int64
        Impacts in the deciding run.
    runs : ndarray (n,) int64
        Kernel runs used.
    peak : ndarray (n,)
        Largest rotation of the whole run, rad (the records' batch, `archquake.ida._kernels`;
        the pulses' batch leaves it NaN).
    unseen : ndarray (n,) bool
        An impact the law does not describe happened before the verdict.
    final : ndarray (n,) int64
        How the deciding run ended (the kernel's ``FINAL_*`` code).
    fraction : ndarray (n,)
        Its last impact's energy over the least crest barrier, NaN where the proof does not
        apply (`last_impact_energy`).
    """

    outcome: np.ndarray
    half: np.ndarray
    n_impacts: np.ndarray
    runs: np.ndarray
    peak: np.ndarray
    unseen: np.ndarray
    final: np.ndarray
    fraction: np.ndarray


@nb.njit(cache=True, nogil=True)
def undescribed_seen(impacts, n_imp, undescribed):
    """True if one of the first ``n_imp`` recorded impacts is of a row whose impact the law
    does not describe."""
    for k in range(min(n_imp, impacts.shape[0])):
        if undescribed[int(impacts[k, 3])]:
            return True
    return False


@nb.njit(cache=True, nogil=True)
def _run_case(table, exc, base, t_end, early, barrier, meff0):
    """One case: the `Excitation` ``exc`` on the `Table` ``table`` with the settings ``base``
    (`archquake.mechanism._kernels.settings`) up to ``t_end`` (s), with the table's
    `table_energies` ``meff0`` and ``barrier``; returns (outcome, collapse_half_cycle,
    impacts, runs, undescribed impact seen, final state code, energy fraction of the last
    impact) of the deciding run: what
    `archquake.mechanism.simulate.conclude_run` states the verdict from, as for
    `simulate` (the fraction: `last_impact_energy`, NaN where
    its proof does not apply).

    An early run locked at its cap is accepted when the proof holds at its last impact (the
    energy never grows after the excitation, so this accepts whenever it holds at an earlier
    impact after the excitation); it is then reported ``stalled`` with that fraction (below
    ``1 - ENERGY_MARGIN``), which states ``survives``, as the full run would."""
    hist = np.zeros((1, HIST_COLUMNS))
    t_exc = excitation_end(exc.kind, exc.params)
    max_impacts = int(base[S_MAX_IMPACTS])
    cap = min(FIRST_IMPACT_CAP, max_impacts) if early else max_impacts
    runs = 0
    while True:
        impacts = np.zeros((cap, IMPACT_COLUMNS))
        peaks = np.zeros(cap + 1)
        counters = np.zeros(10)
        onsets = np.zeros((cap + 1, 2))
        outcome, final, half = simulate_kernel(table, exc, run_settings(base, t_end, cap),
                                               Output(hist, impacts, peaks, counters, onsets))
        runs += 1
        n_imp = int(counters[1])
        fraction = last_impact_energy(impacts, n_imp, t_exc, table, meff0, barrier)
        if (cap >= max_impacts or n_imp < cap
                or (outcome == OUTCOME_SURVIVES and fraction < 1.0 - ENERGY_MARGIN)):
            return (outcome, half, n_imp, runs, undescribed_seen(impacts, n_imp,
                                                                 table.undescribed),
                    final, fraction)
        cap = min(8 * cap, max_impacts)


@nb.njit(cache=True, parallel=True)
def batch_kernel(table, kind, params, base, t_end, early):
    """Run ``params.shape[0]`` cases in parallel.

    Parameters
    ----------
    table : Table
        The mechanism table (`archquake.mechanism._kernels.Table`).
    kind : int
        Ground-motion kind (step or sine).
    params : ndarray (n, 3)
        Per case ``[a (m/s^2), duration (s), direction]``.
    base : ndarray
        Gravity, tolerances, rest rotation and cap on impacts
        (`archquake.mechanism._kernels.settings`; no history).
    t_end : ndarray (n,)
        End of each analysis, s.
    early : bool
        Decide early (module docstring).

    Returns
    -------
    Decisions
        Of each case (``peak`` NaN: not computed for pulses).
    """
    n = params.shape[0]
    meff0, barrier = table_energies(table.mechs, base[S_G])
    no_tail = np.empty(0)
    # written by the parallel loop as plain arrays, wrapped at the end: numba's parallel loop
    # loses writes through an array reached from a tuple (a known limitation)
    outcome = np.zeros(n, dtype=np.int64)
    half = np.zeros(n, dtype=np.int64)
    n_impacts = np.zeros(n, dtype=np.int64)
    runs = np.zeros(n, dtype=np.int64)
    unseen = np.zeros(n, dtype=np.bool_)
    final = np.zeros(n, dtype=np.int64)
    fraction = np.full(n, np.nan)
    for i in nb.prange(n):
        o, h, m, r, u, f, e = _run_case(table, Excitation(kind, params[i], no_tail), base,
                                        t_end[i], early, barrier, meff0)
        outcome[i] = o
        half[i] = h if o == OUTCOME_COLLAPSE else 0
        n_impacts[i] = m
        runs[i] = r
        unseen[i] = u
        final[i] = f
        fraction[i] = e
    return Decisions(outcome, half, n_impacts, runs, np.full(n, np.nan), unseen, final, fraction)


#: The kernel's outcome codes as `Outcome` values.
OUTCOMES = {OUTCOME_NO_HINGING: Outcome.NO_HINGING, OUTCOME_SURVIVES: Outcome.SURVIVES,
            OUTCOME_COLLAPSE: Outcome.COLLAPSE}


def decode(codes: np.ndarray) -> np.ndarray:
    """The kernel's outcome codes (n,) as an object array of `Outcome`."""
    out = np.empty(len(codes), dtype=object)
    for i, c in enumerate(codes):
        out[i] = OUTCOMES[int(c)]
    return out


__all__ = ["ENERGY_MARGIN", "FIRST_IMPACT_CAP", "OUTCOMES", "Decisions", "batch_kernel",
           "decode", "table_energies", "undescribed_seen"]
