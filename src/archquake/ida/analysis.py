"""Incremental dynamic analysis of an arch under a suite of records, through the sweep store.

`incremental_dynamic_analysis` runs hunt-and-fill (`archquake.ida.huntfill`) for every
record of a suite at once, in rounds: each round asks `propose_levels`
for the next levels of every record (a pure function of what the store already holds), turns each
level into a sweep case "this record scaled by this factor" (`archquake.sweeps.Case` with
an in-memory motion), and evaluates the round through `archquake.sweeps.run_sweep`: the
store skips what it holds and stores each batch as it completes, on a local pool or a Dask cluster.
An interrupted analysis rerun with the same store replays the rounds from the store and computes
only what is missing.

The rigid chain (``model="rigid"``, the default) goes through its verdict path, one threaded
batch of compiled verdicts per round and chunk (`archquake.ida.batch.evaluate_rigid_cases`,
`archquake.rigid.rigid_verdicts`); the four-link model (``model="fourlink"``) through one
compiled batch call per round and chunk (`archquake.ida.batch.evaluate_cases`); the DEM
(``model="dem"``) through `archquake.sweeps.evaluate_case` case by case.

The rigid chain's half-step guard (`archquake.rigid.verdict`) guards what the analysis
answers, the levels where each record's trace changes between survival and collapse: the levels
run at the verdict's step alone (stored with ``guard`` false in their options), and once a
record's trace has converged its deciding levels (`deciding_levels`) are rerun at half the
step (`half_step_case`: cases of their own, stored like the levels, so a resumed analysis
reads them back). A level whose two verdicts differ
is ``indeterminate``, counted as a collapse, and the trace goes on from there until every
deciding level is confirmed or indeterminate. On the bridge example under the 28 near-field
records, levels that decide nothing were rerun by the per-verdict rule without changing any
result (docs/notes/mechanism.md, "The rigid chain's step, its guard and its verdict path").

Intensity levels are in the measure's unit (`archquake.ground.measures`: g for PGA and Sa,
m/s for PGV, Arias and CAV). A level x of record r is the record scaled by
``s = (x / IM(r))^(1/k)`` (k = 1, or 2 for Arias intensity), as
`archquake.ground.measures.scale_to` scales it.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from archquake import models
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import ArchquakeError, InvalidParameterError
from archquake.ground.measures import IntensityMeasure, im_value, parse_im
from archquake.ida.huntfill import HuntFill, Interval, collapsed_at, intervals, propose_levels
from archquake.models import DEFAULT_MODEL, Model, model_of
from archquake.outcome import Outcome
from archquake.sweeps.cases import (
    ArchSpec,
    Case,
    CaseOptions,
    ExcitationKind,
    ExcitationSpec,
    motion_digest,
)
from archquake.sweeps.store import STATUS_ERROR, ResultStore

#: Default ceiling: the level at which the suite's median record has this PGA, g.
DEFAULT_CEILING_PGA_G = 5.0
#: Rounds at most (a safeguard: hunt-and-fill converges in a few tens).
MAX_ROUNDS = 200

#: Outcomes the IDA counts as collapse (the hunt, the collapse intervals and the fragility): a
#: collapse, and an indeterminate verdict (the arch is not shown to survive: the fragility is
#: then an upper bound of the four-link model's, and each record reports how many runs were
#: indeterminate, ``indeterminate_runs``).
COUNTED_AS_COLLAPSE = (Outcome.COLLAPSE.value, Outcome.INDETERMINATE.value)


@dataclass(frozen=True)
class RecordIda:
    """The IDA trace of one record.

    Attributes
    ----------
    name : str
    im_unscaled : float
        The record's intensity measure as recorded (IM units).
    levels : ndarray
        Levels run, ascending (IM units).
    factors : ndarray
        Scale factor of each level.
    outcomes : tuple of str
        ``no_hinging``, ``survives`` or ``collapse`` at each level.
    collapse_half_cycles : tuple
        Half cycle of each collapse (None for the others).
    peak_rotation : ndarray
        Largest mechanism rotation of each run, rad (for a collapse: where the run stopped).
    start, ceiling : float
        First level (PGA = lambda g) and ceiling (IM units): the suite's, or lower, just below
        the level at which the record's vertical component reaches g downward (the arch
        leaves its supports there, outside every model).
    """

    name: str
    im_unscaled: float
    levels: np.ndarray
    factors: np.ndarray
    outcomes: tuple[str, ...]
    collapse_half_cycles: tuple
    peak_rotation: np.ndarray
    start: float
    ceiling: float

    @property
    def collapsed(self) -> np.ndarray:
        """(levels,) bool: the run collapsed, or its verdict is indeterminate (counted with the
        collapses: the model cannot show the arch survives; see `COUNTED_AS_COLLAPSE`)."""
        return np.array([o in COUNTED_AS_COLLAPSE for o in self.outcomes], dtype=bool)

    @property
    def indeterminate(self) -> np.ndarray:
        """(levels,) bool: the verdict depends on an impact the law does not describe."""
        return np.array([o == Outcome.INDETERMINATE.value for o in self.outcomes], dtype=bool)

    @property
    def collapse_intervals(self) -> list[Interval]:
        """Every run of collapsing levels (the last may be open up to the ceiling)."""
        return intervals(self.levels, self.collapsed, True)

    @property
    def first_collapse(self) -> Interval | None:
        """The lowest collapse interval (``low``: lowest collapsing level, ``below``: highest
        surviving level under it), None if the record never collapses the arch up to the
        ceiling."""
        runs = self.collapse_intervals
        return runs[0] if runs else None

    @property
    def first_collapse_level(self) -> float:
        """Estimate of the first-collapse intensity: geometric midpoint of its bracket (within
        ``precision`` of the collapsing level); NaN if none up to the ceiling."""
        first = self.first_collapse
        return math.nan if first is None else first.lower_edge

    @property
    def resurrections(self) -> list[Interval]:
        """Runs of surviving levels above the first collapse (the arch stands again although a
        smaller scale of the same record collapsed it)."""
        first = self.first_collapse
        if first is None:
            return []
        return [r for r in intervals(self.levels, self.collapsed, False) if r.low > first.low]

    def collapses_at(self, level: float) -> bool:
        """Whether the trace says this record collapses the arch at ``level`` (IM units)."""
        return collapsed_at(self.levels, self.collapsed, level)

    def factor_at(self, level: float, exponent: int) -> float:
        """Scale factor of ``level``."""
        return (level / self.im_unscaled) ** (1.0 / exponent)

    def to_dict(self, unit: str) -> dict:
        first = self.first_collapse
        return {
            "record": self.name,
            f"im_unscaled_{unit}": self.im_unscaled,
            f"start_{unit}": self.start,
            f"ceiling_{unit}": self.ceiling,
            f"first_collapse_{unit}": None if first is None else first.lower_edge,
            f"first_collapse_run_{unit}": None if first is None else first.low,
            f"first_collapse_below_{unit}": None if first is None else first.below,
            "indeterminate_runs": int(self.indeterminate.sum()),
            "collapse_intervals": [r.to_dict(unit) for r in self.collapse_intervals],
            "resurrections": [r.to_dict(unit) for r in self.resurrections],
            "runs": [{f"level_{unit}": float(x), "scale": float(f), "outcome": o,
                      "collapse_half_cycle": h, "peak_rotation_rad": float(p)}
                     for x, f, o, h, p in zip(self.levels, self.factors, self.outcomes,
                                              self.collapse_half_cycles, self.peak_rotation,
                                              strict=True)],
        }


@dataclass(frozen=True)
class IdaResult:
    """Incremental dynamic analysis of one arch under a suite.

    Attributes
    ----------
    arch : ArchSpec
    model : Model
    im : IntensityMeasure
    records : tuple of RecordIda
    settings : dict
        ``ceiling_<unit>`` (IM units), precision, fill, hunt step and growth (relative),
        restitution, t_end_s.
    collapse_acceleration_g : float
        lambda (g).
    critical_rotation_rad : float
        Crest of the mechanism's potential, rad (scale of the IDA curves).
    rounds : int
        Rounds of levels, and of the guard's reruns.
    computed : int
        Cases evaluated by this call, the guard's reruns among them (the rest came from the
        store).
    total : int
        Cases of the analysis: its levels, and the guard's reruns.
    guarded : int
        Levels rerun at half the step by the rigid chain's guard (`deciding_levels`; stored
        like the levels, `half_step_case`).
    """

    arch: ArchSpec
    model: Model
    im: IntensityMeasure
    records: tuple[RecordIda, ...]
    settings: dict
    collapse_acceleration_g: float
    critical_rotation_rad: float
    rounds: int
    computed: int
    total: int
    g: float = STANDARD_GRAVITY
    store: str = ""
    motions: tuple = field(default=(), repr=False, compare=False)
    guarded: int = 0
    #: What the arch carries (None: bare).
    loads: Any = None

    @property
    def unit_key(self) -> str:
        return {"g": "g", "m/s": "m_s", "m": "m"}[self.im.unit]

    @property
    def first_collapse_levels(self) -> np.ndarray:
        """First-collapse intensity of each record (NaN: none up to its ceiling)."""
        return np.array([r.first_collapse_level for r in self.records])

    @property
    def ceiling(self) -> float:
        return float(self.settings[f"ceiling_{self.unit_key}"])

    def collapse_fraction(self, levels) -> np.ndarray:
        """Fraction of the records that collapse the arch at each level (IM units)."""
        levels = np.atleast_1d(np.asarray(levels, dtype=float))
        return np.array([np.mean([r.collapses_at(x) for r in self.records]) for x in levels])

    def stripe_levels(self, count: int = 20) -> np.ndarray:
        """``count`` levels, geometric between the smallest first level and the ceiling."""
        low = min(r.start for r in self.records)
        return np.geomspace(low, self.ceiling, count)

    def first_collapse_in(self, im: str | IntensityMeasure) -> np.ndarray:
        """The first-collapse intensity of each record expressed in another measure: the
        record scaled by its first-collapse factor, measured with ``im`` (NaN: no collapse)."""
        measure = parse_im(im)
        out = []
        for rec, motion in zip(self.records, self.motions, strict=True):
            first = rec.first_collapse
            if first is None:
                out.append(math.nan)
                continue
            factor = rec.factor_at(first.lower_edge, self.im.exponent)
            out.append(measure.of(motion, g=self.g) * factor ** measure.exponent)
        return np.array(out)

    def ceiling_in(self, im: str | IntensityMeasure) -> np.ndarray:
        """Each record's ceiling (the largest level run) expressed in another measure."""
        measure = parse_im(im)
        return np.array([measure.of(m, g=self.g) * rec.factor_at(rec.ceiling, self.im.exponent)
                         ** measure.exponent for rec, m in zip(self.records, self.motions,
                                                                strict=True)])

    def to_dict(self) -> dict:
        unit = self.unit_key
        levels = self.stripe_levels()
        first = self.first_collapse_levels
        return {
            "arch": self.arch.canonical(),
            **({} if self.loads is None else {"loads": self.loads.to_dict()}),
            "model": self.model.value,
            "im": self.im.label,
            "im_unit": self.im.unit,
            "collapse_acceleration_g": self.collapse_acceleration_g,
            "critical_rotation_rad": self.critical_rotation_rad,
            "settings": dict(self.settings),
            "records_total": len(self.records),
            "records_collapsing": int(np.sum(np.isfinite(first))),
            "records_with_resurrections": sum(1 for r in self.records if r.resurrections),
            "cases_total": self.total,
            "computed_now": self.computed,
            "already_stored": self.total - self.computed,
            "rounds": self.rounds,
            "guard_reruns": self.guarded,
            "store": self.store,
            "collapse_fraction": [{f"level_{unit}": float(x), "fraction": float(p)}
                                  for x, p in zip(levels, self.collapse_fraction(levels),
                                                  strict=True)],
            "records": [r.to_dict(unit) for r in self.records],
        }

    def write_csv(self, path: str | Path) -> Path:
        """One row per run: record, level, scale factor, outcome, half cycle, peak rotation."""
        path = Path(path)
        unit = self.unit_key
        with path.open("w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["record", f"{self.im.name}_{unit}" if self.im.name != "sa"
                        else self.im.key, "scale", "outcome", "collapse_half_cycle",
                        "peak_rotation_rad", "peak_over_critical"])
            for r in self.records:
                for x, f, o, h, p in zip(r.levels, r.factors, r.outcomes,
                                         r.collapse_half_cycles, r.peak_rotation, strict=True):
                    w.writerow([r.name, repr(float(x)), repr(float(f)), o,
                                "" if h is None else h, repr(float(p)),
                                repr(float(p) / self.critical_rotation_rad)])
        return path


def incremental_dynamic_analysis(
    arch: ArchSpec,
    motions: Sequence[Any],
    im: str | IntensityMeasure,
    store: ResultStore,
    *,
    ceiling: float | None = None,
    precision: float = 0.02,
    fill: float = 0.10,
    hunt_step: float = 0.25,
    hunt_growth: float = 1.5,
    model: Model | str = DEFAULT_MODEL,
    options: CaseOptions | None = None,
    executor: Executor | None = None,
    workers: int | None = None,
    chunk_size: int | None = None,
    progress: Callable[[int, int, int], None] | None = None,
    loads=None,
    first_collapses: Callable[[IdaResult], None] | None = None,
) -> IdaResult:
    """Hunt-and-fill IDA of ``arch`` under every motion of ``motions``.

    Parameters
    ----------
    arch : ArchSpec
        The arch (study units: m, degrees).
    motions : sequence of GroundMotion
        The suite's records (unscaled, m/s^2), or any motions with ``scaled`` and
        ``kernel_spec`` (a step pulse as a one-record suite); names must be unique.
    im : str or IntensityMeasure
        ``pga``, ``pgv``, ``sa:T``, ``arias``, ... (`archquake.ground.measures.parse_im`).
    store : ResultStore
        Where every case is stored (and found again on a rerun).
    ceiling : float, optional
        Largest level, IM units (default: the IM of the suite's median record scaled to
        PGA = 5 g).
    precision, fill, hunt_step, hunt_growth : float
        See `archquake.ida.huntfill.HuntFill` (relative: 0.02 brackets every
        transition within 2 % of the IM).
    model : {'rigid', 'fourlink', 'dem'}
        `archquake.sweeps.Model` (default ``rigid``, the chain of rigid voussoirs;
        named as ``--model`` names it, `archquake.sweeps.model_of`).
    options : CaseOptions, optional
        Prescribed restitution and impact law (fourlink only), end time, gravity (default: none, the
        model's own, standard gravity).
    executor, workers, chunk_size
        As `archquake.sweeps.run_sweep` (default: a local process pool), except for the
        four-link model and the rigid chain: with neither ``executor`` nor ``workers`` it runs in this process
        (`SerialExecutor`: the compiled batch already spreads a round
        over all cores with threads; a pool of processes, each with as many threads,
        started afresh every round, took 1.5x as long on Oppenheim's arch under the near-field
        pulse set, docs/earthquakes.md), and its default chunk is a round's share per worker
        (one compiled call per worker and round, `round_chunk_size`).
    progress : callable, optional
        ``progress(stored, total_so_far, round)`` after every stored batch.
    loads : Loads, optional
        What the arch carries, masses that move with it (`Case`'s
        ``loads``): every model carries them, and the levels start at the loaded lambda.
    first_collapses : callable, optional
        ``first_collapses(partial)``, called once, as soon as every record's first collapse is
        settled: the analysis first runs only the levels below each record's lowest collapse
        (and, with the guard, reruns the levels that bracket it), and calls this with the
        analysis so far, an `IdaResult` whose records' first collapses are the final result's
        (``first_collapse_levels``, and each record's ``first_collapse.low`` and ``.below``);
        then it fills the levels above.
        Levels proposed in one gap never depend on another gap's outcomes, and a collapse
        above the first changes nothing below it, so the final result holds the same levels
        and outcomes as without it; only the rounds differ (``rounds``). For a caller with
        work that needs only the first collapses (a fit, a governing record to run with
        another model), started while the levels above run.

    Returns
    -------
    IdaResult
    """
    from archquake.ground.base import lift_off_factor
    from archquake.ida.batch import BATCHES
    from archquake.parallel import SerialExecutor
    from archquake.sweeps.evaluate import mechanism_limits
    from archquake.sweeps.runner import run_sweep

    measure = parse_im(im)
    options = CaseOptions() if options is None else options
    model = model_of(model)
    # the rigid chain's levels run at its step alone; the guard then checks the levels that
    # decide the result at half the step (module docstring)
    guard = models.takes(model, "guard") and options.guard
    if guard:
        options = replace(options, guard=False)
    batched = models.spec(model).batched  # one compiled, threaded call per round
    if batched and executor is None and workers is None:
        executor = SerialExecutor()
    if not motions:
        raise InvalidParameterError("the suite holds no records")
    names = [getattr(m, "name", f"motion{i}") for i, m in enumerate(motions)]
    if len(set(names)) != len(names):
        raise InvalidParameterError("record names must be unique within a suite")
    g = options.g
    # the levels start at the static collapse acceleration; no impact law is asked of the
    # block models, which run on any arch, symmetric or not
    loads = None if loads is None or loads.empty else loads
    lam, phi_crit = mechanism_limits(arch, loads)
    im0 = np.array([im_value(m, measure, g=g) for m in motions])
    pga0 = np.array([im_value(m, "pga", g=g) for m in motions])
    for name, v in zip(names, im0, strict=True):
        if not v > 0:
            raise InvalidParameterError(f"record {name!r} has {measure.label} = 0: it cannot "
                                        "be scaled to an intensity level")
    k = measure.exponent
    starts = im0 * (lam / pga0) ** k
    if ceiling is None:
        ceiling = float(np.median(im0 * (DEFAULT_CEILING_PGA_G / pga0) ** k))
    unit = {"g": "g", "m/s": "m_s", "m": "m"}[measure.unit]
    settings = {f"ceiling_{unit}": float(ceiling), "precision": precision, "fill": fill,
                "hunt_step": hunt_step, "hunt_growth": hunt_growth,
                "restitution": options.restitution, "impact": options.impact or "paper",
                "t_end_s": options.t_end_s}
    # a record's vertical scales with it: each record's levels end below the one at which its
    # vertical reaches g downward (the arch leaves its supports there, outside every model)
    ceilings = [min(float(ceiling), float(x0 * (lift_off_factor(m, g) * (1 - 1e-9)) ** k))
                for m, x0 in zip(motions, im0, strict=True)]
    hf = []
    for s, top in zip(starts, ceilings, strict=True):
        start = min(float(s), top)
        hf.append(HuntFill(start, top, precision, fill, hunt_step, hunt_growth))

    digests = [motion_digest(m) for m in motions]  # each record's id part, hashed once

    def case_of(i: int, level: float) -> Case:
        factor = (level / im0[i]) ** (1.0 / k)
        return Case(arch, ExcitationSpec(ExcitationKind.RECORD, motion=motions[i],
                                         scale=float(factor), file_sha256=digests[i]),
                    model, options, loads)

    batch: Callable[[Sequence[Case]], list[Any]] | None = BATCHES.get(model)
    runs: list[dict[float, Case]] = [{} for _ in motions]
    outcomes: list[dict[float, Any]] = [{} for _ in motions]
    checked: list[set[float]] = [set() for _ in motions]  # levels the guard has rerun
    guarded = 0
    computed = 0
    rounds = 0
    # the first phase, with a first_collapses callback: only the levels below each record's
    # lowest collapse, and (guard) the deciding levels up to it
    below_first = first_collapses is not None

    def lowest_collapse(i: int) -> float:
        return min((x for x, r in outcomes[i].items() if r.outcome in COUNTED_AS_COLLAPSE),
                   default=math.inf)

    def result() -> IdaResult:
        records = []
        for i, name in enumerate(names):
            levels = sorted(outcomes[i])
            recs = [outcomes[i][x] for x in levels]
            records.append(RecordIda(
                name=name, im_unscaled=float(im0[i]), levels=np.array(levels),
                factors=np.array([(x / im0[i]) ** (1.0 / k) for x in levels]),
                outcomes=tuple(r.outcome for r in recs),
                collapse_half_cycles=tuple(r.outputs.get("collapse_half_cycle") for r in recs),
                peak_rotation=np.array([_peak(r.outputs) for r in recs]),
                start=hf[i].start, ceiling=ceilings[i]))
        return IdaResult(arch=arch, model=model, im=measure, records=tuple(records), loads=loads,
                         settings=settings, collapse_acceleration_g=lam,
                         critical_rotation_rad=phi_crit, rounds=rounds, computed=computed,
                         total=sum(len(r) for r in runs) + guarded, g=g,
                         store=str(store.path), motions=tuple(motions), guarded=guarded)

    def run_round(cases: list[tuple[int, float, Case]], what: str) -> list[Any]:
        """Run (record, level, case) ``cases`` through the store as one round: their stored
        records, in order (an error row, or a case missing after its round, is raised)."""
        nonlocal computed
        total_so_far = sum(len(r) for r in runs) + guarded  # this round's cases included
        report = run_sweep(
            [c for _, _, c in cases], store,
            evaluate=None,
            evaluate_batch=batch,
            executor=executor, workers=workers,
            chunk_size=(round_chunk_size(len(cases), executor, workers)
                        if chunk_size is None and batched else chunk_size),
            progress=None if progress is None else _round_progress(
                progress, rounds, total_so_far, len(cases)))
        computed += report.computed
        stored = store.lookup(c.case_id for _, _, c in cases)
        out = []
        for i, x, case in cases:
            rec = stored.get(case.case_id)
            if rec is None:
                raise ArchquakeError(f"case {case.case_id} of record {names[i]!r}{what} is "
                                     "missing from the store after its round")
            if rec.status == STATUS_ERROR:
                raise ArchquakeError(f"record {names[i]!r} at {measure.label} = {x:.4g} "
                                     f"{measure.unit}{what}: {rec.error}")
            out.append(rec)
        return out

    while True:
        if rounds == MAX_ROUNDS:
            raise ArchquakeError(f"incremental dynamic analysis did not converge in "
                                 f"{MAX_ROUNDS} rounds")
        new_levels: list[tuple[int, float, Case]] = []
        for i in range(len(motions)):
            done = outcomes[i]
            levels = list(done)
            collapsed = [done[x].outcome in COUNTED_AS_COLLAPSE for x in levels]
            top = lowest_collapse(i) if below_first else math.inf
            for x in propose_levels(levels, collapsed, hf[i]):
                if x < top:
                    case = case_of(i, x)
                    runs[i][x] = case
                    new_levels.append((i, x, case))
        if not new_levels:
            pending = [(i, x) for i in range(len(motions))
                       for x in deciding_levels(outcomes[i]) if x not in checked[i]
                       and (not below_first or x <= lowest_collapse(i))] if guard else []
            if not pending:
                if below_first and first_collapses is not None:
                    below_first = False
                    first_collapses(result())
                    continue
                break
            rounds += 1
            # the reruns are cases of their own (half the step), stored as they complete: a
            # resumed analysis reads them back
            halves = [(i, x, half_step_case(runs[i][x])) for i, x in pending]
            guarded += len(halves)
            for (i, x, _), half in zip(halves, run_round(halves, ", at half the step"),
                                       strict=True):
                checked[i].add(x)
                outcomes[i][x] = guarded_record(outcomes[i][x], half)
            continue
        rounds += 1
        for (i, x, _), rec in zip(new_levels, run_round(new_levels, ""), strict=True):
            outcomes[i][x] = rec
    return result()


def deciding_levels(done: dict[float, Any]) -> list[float]:
    """The levels of one record's trace whose outcomes decide its IDA: both ends of every
    transition between levels counted as surviving and as collapsing (the first collapse's
    bracket, and every resurrection's), the lowest level if it collapses, and the highest if it
    survives. ``done`` maps a level to its stored record (``.outcome``)."""
    levels = sorted(done)
    collapsed = [done[x].outcome in COUNTED_AS_COLLAPSE for x in levels]
    out: set[float] = set()
    if levels and collapsed[0]:
        out.add(levels[0])
    if levels and not collapsed[-1]:
        out.add(levels[-1])
    for a, b, ca, cb in zip(levels[:-1], levels[1:], collapsed[:-1], collapsed[1:],
                            strict=True):
        if ca != cb:
            out.update((a, b))
    return sorted(out)


def half_step_case(case: Case) -> Case:
    """The half-step guard's rerun of a level's ``case`` (the rigid chain's verdict at its
    step, guard off): the same case at half the step, a case of its own in the store."""
    return replace(case, options=replace(case.options, step_fraction=0.5, guard=False))


def guarded_record(rec: Any, half: Any) -> Any:
    """A level's stored record (the rigid chain's verdict at its step, guard off) with the
    half-step guard's rerun ``half`` (its stored record, `half_step_case`): confirmed when
    both steps agree on survival or collapse (``no_hinging`` counts as survival), otherwise
    ``indeterminate`` (counted as collapse), with the reason naming both; a level already
    ``indeterminate`` at its step stays so."""
    outputs = dict(rec.outputs)
    first = outputs.get("outcome", rec.outcome)
    second = half.outputs.get("outcome", half.outcome)
    half_step = half.outputs["time_step_s"]
    survived = (Outcome.SURVIVES.value, Outcome.NO_HINGING.value)
    agree = (first == second or (first in survived and second in survived))
    step = outputs.get("time_step_s", 2.0 * half_step)
    outputs["guard_ran"] = True
    outputs["guard_outcome"] = second
    if first == Outcome.INDETERMINATE.value:  # undecided at the step already: stays so
        return replace(rec, outputs=outputs)
    if agree:
        outputs["verdict_reason"] = (f"{outputs.get('verdict_reason', '')} (confirmed at half "
                                     f"the step, {half_step:.3g} s)").lstrip()
        return replace(rec, outputs=outputs)
    outputs["outcome"] = Outcome.INDETERMINATE.value
    outputs["verdict_reason"] = (f"near the threshold: {first} at the step {step:.3g} s, "
                                 f"{second} at {half_step:.3g} s; a finer step or "
                                 "solver='events' decides")
    outputs["collapse_half_cycle"] = None
    return replace(rec, outcome=Outcome.INDETERMINATE.value, outputs=outputs)


def round_chunk_size(cases: int, executor: Executor | None, workers: int | None) -> int:
    """Cases per task of one round of the four-link model: the round split evenly over the
    workers (one task for an in-process executor).

    Each task is one call of the compiled batch, which spreads its cases over numba's threads
    itself; smaller tasks (the sweep's default, eight per worker) only leave threads idle at the
    end of each call: Oppenheim's arch under the near-field pulse set ran 101 calls of 1 to 33
    cases in 14 rounds, and its kernel time on 2 threads was 2.6 s where one call per round
    takes 2.3 s (``benchmarks/bench_ida.py``, docs/earthquakes.md)."""
    from archquake.parallel import executor_workers, usable_cores

    if workers is None:
        workers = executor_workers(executor) or usable_cores()
    return max(1, math.ceil(cases / max(1, int(workers))))


def _round_progress(progress, rounds: int, total: int, new: int):
    """The sweep's ``progress(done, total)`` of one round as the analysis's
    ``progress(stored, total_so_far, round)``."""
    return lambda done, _total: progress(total - new + done, total, rounds)


def _peak(outputs: dict) -> float:
    """Largest rotation of a run from any model's summary, rad."""
    for key in ("peak_rotation_max_rad", "max_rotation_rad"):
        if outputs.get(key) is not None:
            return float(outputs[key])
    peaks = outputs.get("peak_rotation_rad") or [0.0]
    return float(max(peaks))


__all__ = ["DEFAULT_CEILING_PGA_G", "IdaResult", "RecordIda", "deciding_levels",
           "guarded_record", "half_step_case", "incremental_dynamic_analysis",
           "round_chunk_size"]
