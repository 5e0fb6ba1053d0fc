"""Evaluate many sweep cases of the four-link model in one compiled call per arch.

`evaluate_cases` is the batch function incremental dynamic analysis hands to
`archquake.sweeps.run_sweep` (``evaluate_batch=``): the cases of one round (records scaled
by factors, pulses) are grouped by arch and options, each group goes through
`archquake.ida._kernels.batch_kernel` (the compiled kernel of
`simulate`, with the failure domains' early decision), and every case
gets the summary incremental dynamic analysis reads: outcome, collapse half cycle and the largest
rotation of the run. It is a smaller summary than `archquake.sweeps.evaluate_case` stores
(no impact times, no solver counters): ``evaluator`` says which produced a row.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numba
import numpy as np

from archquake.domains._kernels import OUTCOMES
from archquake.errors import ArchquakeError, InvalidParameterError
from archquake.models import Model
from archquake.outcome import Outcome, qualify
from archquake.sweeps.cases import Case

#: The ``evaluator`` key of a batch summary.
BATCH_EVALUATOR = "ida batch (compiled, early decision)"


def evaluate_cases(cases: Sequence[Case], *, early: bool = True) -> list[Any]:
    """Outcome and peak rotation of every case, one compiled call per (arch, options) group.

    Parameters
    ----------
    cases : sequence of Case
        Four-link model cases (any excitation).
    early : bool
        Stop a surviving case once energy proves it cannot collapse any more (the peak rotation
        is still exact, see `archquake.ida._kernels`).

    Returns
    -------
    list
        Per case, in order: ``{"outcome", "collapse_half_cycle", "peak_rotation_max_rad",
        "critical_rotation_rad", "collapse_acceleration_g", "restitution_cv", "impacts",
        "kernel_runs", "t_end_s", "evaluator"}``, or the `ArchquakeError`
        refusing the case (e.g. an arch too thin to stand).
    """
    from archquake.sweeps.evaluate import prepared_mechanism

    out: list[Any] = [None] * len(cases)
    groups = _groups(cases, Model.FOURLINK, "the batch evaluator runs the four-link model", out,
                     refuse=_rigid_options)
    for (arch, options, loads), idx in groups.items():
        try:
            prepared = prepared_mechanism(arch, options.impact, loads)
        except ArchquakeError as exc:
            for i in idx:
                out[i] = exc
            continue
        results = _run_group(prepared, [cases[i] for i in idx], options, early)
        for i, r in zip(idx, results, strict=True):
            out[i] = r
    return out


def evaluate_rigid_cases(cases: Sequence[Case], *, threads: int | None = None) -> list[Any]:
    """The rigid chain's verdicts of many cases, one threaded batch per (arch, options) group
    (`archquake.rigid.rigid_verdicts`: the step scaled with the arch, the half-step
    guard, stopped at collapse or proven rest).

    Parameters
    ----------
    cases : sequence of Case
        Rigid-chain cases (any excitation); ``t_end_s`` is the run's window, s (default: the
        end of the excitation + 60 sqrt(R/g)); ``step_fraction`` the step as a fraction of
        the verdict's own (`archquake.rigid.verdict.verdict_time_step`).
    threads : int, optional
        Threads of each batch (default: the cores this process may use).

    Returns
    -------
    list
        Per case, in order: `archquake.sweeps.evaluate.rigid_summary` of its verdict, or
        the `ArchquakeError` refusing the case.
    """
    from archquake.rigid import rigid_verdicts
    from archquake.rigid.verdict import verdict_time_step
    from archquake.sweeps.evaluate import rigid_summary

    out: list[Any] = [None] * len(cases)
    groups = _groups(cases, Model.RIGID, "the rigid batch evaluator runs the rigid chain", out,
                     refuse=_fourlink_options)
    for (arch, options, loads), idx in groups.items():
        try:
            built = _body(arch, loads)
            motions = [cases[i].excitation.build(g=options.g) for i in idx]
            step = (None if options.step_fraction == 1.0 else
                    options.step_fraction * verdict_time_step(built, g=options.g))
            verdicts = rigid_verdicts(built, motions, duration=options.t_end_s, g=options.g,
                                      time_step=step, guard=options.guard, threads=threads)
        except ArchquakeError as exc:
            for i in idx:
                out[i] = exc
            continue
        for i, v in zip(idx, verdicts, strict=True):
            out[i] = rigid_summary(v)
    return out


def _groups(cases: Sequence[Case], model: Model, runs: str, out: list,
            refuse: Callable[[Case], ArchquakeError | None] | None = None
            ) -> dict[tuple, list[int]]:
    """The indices of ``cases`` by (arch, options, loads), one batch each; a case of another model is
    refused with ``runs`` (what runs which model) "... only, got ...", and a case ``refuse``
    returns an error for gets that error in ``out`` and no batch."""
    groups: dict[tuple, list[int]] = {}
    for i, case in enumerate(cases):
        if case.model is not model:
            raise InvalidParameterError(f"{runs} only, got {case.model.value!r}")
        error = None if refuse is None else refuse(case)
        if error is not None:
            out[i] = error
        else:
            groups.setdefault((case.arch, case.options, case.loads), []).append(i)
    return groups


def _body(arch, loads):
    """What the rigid chain runs for a case (``arch`` its `ArchSpec`): `rigid_body`."""
    return rigid_body(arch.build(), loads)


def rigid_body(arch, loads):
    """What the rigid chain runs for ``arch`` (an `Arch`): the arch, or with ``loads`` its
    blocks carrying them (`archquake.blocks.assembly.dem_assembly`, built once per
    (arch, loads), both frozen and compared by value).

    One object for equal inputs, so that the chain's model and its verdict arrays, memoised
    on the object (`archquake.rigid.verdict.rigid_model`), are built once too: for a
    loaded arch the onset accelerations are found by bisection, which every round of an
    incremental dynamic analysis, and every study of the same loaded arch, would repeat on a
    fresh assembly."""
    if loads is None:
        return arch
    from archquake.blocks.assembly import VOUSSOIRS, dem_assembly

    return dem_assembly(arch, VOUSSOIRS, loads=loads)


def _rigid_options(case: Case) -> ArchquakeError | None:
    """The error of a case of another model given the rigid chain's step fraction, or None."""
    if case.options.step_fraction != 1.0:
        return InvalidParameterError("step_fraction applies to model rigid only (its verdicts' "
                                     "time step)")
    return None


def _fourlink_options(case: Case) -> ArchquakeError | None:
    """The error of a rigid case given the four-link model's impact options, or None."""
    for key in ("restitution", "impact"):
        if getattr(case.options, key) is not None:
            return InvalidParameterError(f"{key} applies to model fourlink only; the rigid "
                                         "chain's impacts follow from its contacts")
    return None


def _run_group(prepared, cases, options, early) -> list[Any]:
    from archquake.ida._kernels import WINDOW_TAU, batch_kernel
    from archquake.mechanism import SolverOptions
    from archquake.mechanism._kernels import excitation_end
    from archquake.mechanism.simulate import conclude_run
    from archquake.ranges import default_t_end

    g = options.g
    solver = SolverOptions()
    from archquake.mechanism.impact import check_restitution

    cv = prepared.restitution_for(options.restitution)
    prescribed = check_restitution(options.restitution)
    table = prepared.kernel_table(prescribed)
    order = thread_order(len(cases), numba.get_num_threads())
    cases = [cases[j] for j in order]
    kinds, parts, results = [], [], []
    for case in cases:
        kind, params = case.excitation.build(g=g).kernel_spec()
        kinds.append(int(kind))
        parts.append(np.ascontiguousarray(params, dtype=np.float64))
    n = len(cases)
    kinds_a = np.asarray(kinds, dtype=np.int64)
    offsets = np.zeros(n + 1, dtype=np.int64)
    offsets[1:] = np.cumsum([p.size for p in parts])
    flat = np.concatenate(parts) if parts else np.zeros(0)
    t_exc = np.array([excitation_end(k, p) for k, p in zip(kinds_a, parts, strict=True)])
    if options.t_end_s is None:
        t_end = default_t_end(t_exc, prepared.mechanism.arch.radius, g)
    else:
        t_end = np.full(n, float(options.t_end_s))
    window = WINDOW_TAU * math.sqrt(prepared.mechanism.arch.radius / g)
    decided = batch_kernel(table, kinds_a, flat, offsets, solver.kernel_settings(g), t_end,
                           window, bool(early))
    outcome, half, n_imp, runs, peak, unseen, final, fraction = decided

    static_g = prepared.collapse_acceleration_g
    phi_crit = prepared.critical_rotation
    for i in range(n):
        computed = OUTCOMES[int(outcome[i])]
        # per impact: those before the verdict (none: whether the law describes the first's)
        described = (not bool(unseen[i])) if n_imp[i] else prepared.describes_impact(
            options.restitution)
        # how the run ended (cut by t_end, locked by max_impacts): simulate's own rule
        settled, _reason = conclude_run(computed, int(final[i]), impacts=int(n_imp[i]),
                                        max_impacts=int(solver.max_impacts),
                                        t_end=float(t_end[i]), excitation_end=float(t_exc[i]),
                                        energy_fraction=float(fraction[i]))
        verdict = qualify(settled, collapse_half_cycle=int(half[i]),
                          impacts=min(int(n_imp[i]), int(solver.max_impacts)),
                          impact_described=described)
        results.append({
            "outcome": verdict.value,
            "computed_outcome": computed.value,
            "collapse_half_cycle": int(half[i]) if computed is Outcome.COLLAPSE else None,
            "peak_rotation_max_rad": float(peak[i]),
            "critical_rotation_rad": phi_crit,
            "collapse_acceleration_g": static_g,
            "restitution_cv": float(cv),
            "impact_law": prepared.impact.law,
            "impact_validity": prepared.impact.validity,
            "impact_described": described,
            "impacts": int(n_imp[i]),
            "kernel_runs": int(runs[i]),
            "t_end_s": float(t_end[i]),
            "evaluator": BATCH_EVALUATOR,
        })
    out: list[Any] = [None] * n
    for k, j in enumerate(order):
        out[j] = results[k]
    return out


def thread_order(n: int, threads: int) -> list[int]:
    """The order in which to hand ``n`` cases to a ``prange`` on ``threads`` threads: numba
    gives each thread one contiguous block of the iterations (static schedule), so the cases
    are dealt out in turn (case k to block k mod threads). A round lists each record's levels
    side by side, and neighbouring levels of a record cost about the same (the arch rocks for
    about as long), so every thread gets a like share of each record instead of one thread
    getting the long records. Returns the case index at each position."""
    threads = max(1, min(int(threads), n))
    return [j for t in range(threads) for j in range(t, n, threads)]


#: The batch evaluator of each model that has one (one compiled, threaded call per batch; the
#: DEM's cases run one a process, through the sweep's executor).
BATCHES: dict[Model, Callable[..., list[Any]]] = {Model.FOURLINK: evaluate_cases,
                                                  Model.RIGID: evaluate_rigid_cases}


__all__ = ["BATCHES", "BATCH_EVALUATOR", "evaluate_cases", "evaluate_rigid_cases",
           "rigid_body", "thread_order"]
