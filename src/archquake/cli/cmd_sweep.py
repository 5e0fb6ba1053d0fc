"""``archquake sweep STUDY.toml``: run a study's grid of cases, resumably, locally or on Dask.

The library does the work (`archquake.sweeps`); this shell reads the study, opens the
store and the executor, draws a tqdm bar on stderr, exports, and prints a summary.
"""

from __future__ import annotations

import argparse
import sys

from archquake.cli.common import (
    MODEL_HELP,
    number,
    output_file,
    path_argument,
    print_json,
    quiet_dask,
    ranged_whole,
)
from archquake.errors import ArchquakeError, ClusterLostError, InvalidParameterError
from archquake.parallel import cap_workers, check_scheduler, open_executor
from archquake.ranges import (
    TABLE_SUFFIXES,
    WORKERS_RANGE,
)
from archquake.sweeps import ResultStore, load_study, run_sweep
from archquake.sweeps.evaluate import evaluate_case
from archquake.sweeps.runner import NO_WORKER_TIMEOUT, CaseFunction


def case_function(model) -> CaseFunction:
    """The case function for ``model`` (`evaluate_case`, which runs any model through
    `archquake.models.run`). Tests replace this to inject a cheap function."""
    return evaluate_case


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "sweep",
        help="run a study file's grid of cases into a resumable SQLite store",
        description=(
            "Run every case of STUDY.toml (arches x excitations x options; magnitudes in g, "
            "angles in degrees, lengths in m) that the store does not hold yet, storing each "
            "batch as it completes. Interrupt at any time; rerunning resumes. "
            "See docs/sweeps.md for the study schema."
        ),
    )
    p.add_argument("study", type=path_argument, metavar="STUDY.toml", help="the study file")
    p.add_argument("--store", type=output_file(create_parents=True), metavar="FILE",
                   help="SQLite store (default: <study name>.sqlite beside the study file)")
    p.add_argument("--workers", type=ranged_whole(*WORKERS_RANGE), metavar="N",
                   help="local worker processes (default: all cores; 1 runs serially)")
    p.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                   help="run on the Dask cluster whose scheduler listens at this address")
    p.add_argument("--worker-wait", type=number, metavar="S", default=NO_WORKER_TIMEOUT,
                   help="with --scheduler: seconds to wait while the cluster has no worker before "
                        f"stopping (what is done is kept; default {NO_WORKER_TIMEOUT:g})")
    p.add_argument("--chunk-size", type=ranged_whole(1, 10**6), metavar="N",
                   help="cases per task (default: chosen from the number of cases and workers)")
    p.add_argument("--export", type=output_file(*TABLE_SUFFIXES), metavar="FILE",
                   help="afterwards, write the store's rows to FILE (.csv or .parquet)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    p.add_argument("--model", default=None, metavar="{rigid,fourlink,dem}",
                   help="run every case with this model instead of the study's [study] model "
                        "(default rigid): " + MODEL_HELP)
    p.add_argument("--json", action="store_true",
                   help="print a JSON summary (model, cases total, computed now, already "
                        "stored, outcomes, store path)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    if args.workers is not None and args.workers < 1:
        raise InvalidParameterError(f"--workers must be a whole number >= 1, got {args.workers}")
    if args.chunk_size is not None and args.chunk_size < 1:
        raise InvalidParameterError(
            f"--chunk-size must be a whole number >= 1, got {args.chunk_size}")
    if not 0 < args.worker_wait <= 86400:
        raise InvalidParameterError(
            f"--worker-wait must be in (0, 86400] s, got {args.worker_wait:g}")
    if args.scheduler is not None:
        check_scheduler(args.scheduler, "--scheduler")
    if args.export is not None and args.export.suffix.lower() not in (".csv", ".parquet"):
        raise InvalidParameterError(
            f"--export file must end in .csv or .parquet, got {args.export.name!r}")
    study = load_study(args.study)
    if args.model is not None:  # the same grid with another model (other case ids)
        from dataclasses import replace

        from archquake.models import model_of

        model = model_of(args.model, model_name="--model")
        study = replace(study, model=model,
                        cases=tuple(replace(c, model=model) for c in study.cases))
    evaluate = case_function(study.model)
    store_path = args.store or study.default_store
    try:
        opened = ResultStore(store_path)
    except ArchquakeError as exc:  # not a database, another schema, an unwritable place
        raise ArchquakeError(f"--store {exc}" if args.store else str(exc)) from None
    with opened as store:
        wanted = {c.case_id for c in study.cases}
        workers = args.workers
        if args.scheduler is None:
            workers, note = cap_workers(args.workers, len(wanted - store.stored_ids()))
            if note is not None:
                print(f"archquake: --workers: {note}", file=sys.stderr)
        else:
            quiet_dask()
        bar = None
        try:
            with open_executor(workers=workers, scheduler=args.scheduler) as (executor, n):
                bar = _Bar(disable=args.no_progress)
                report = run_sweep(study.cases, store, evaluate=evaluate, executor=executor,
                                   workers=n, chunk_size=args.chunk_size, progress=bar,
                                   no_worker_timeout=args.worker_wait)
        except KeyboardInterrupt:
            if bar is not None:
                bar.close()
            stored = len(store.stored_ids() & wanted)
            print(f"archquake: interrupted: {stored} of {len(wanted)} cases are stored in "
                  f"{store.path}; run the same command again to resume", file=sys.stderr)
            return 130
        except ClusterLostError as exc:
            if bar is not None:
                bar.close()
            stored = len(store.stored_ids() & wanted)
            raise ClusterLostError(f"{exc}; {stored} of {len(wanted)} cases are stored in "
                                   f"{store.path}; run the same command again to resume") from None
        bar.close()
        if args.export is not None:
            store.export(args.export)
            if store.damaged:
                print(f"archquake: --export: skipped {len(store.damaged)} damaged row"
                      f"{'s' * (len(store.damaged) != 1)} of the store (their cases are "
                      "computed again by the next run)", file=sys.stderr)
    summary = {"model": study.model.value, **report.to_dict()}
    summary["study"] = study.name
    loads = study.cases[0].loads if study.cases else None
    if loads is not None:  # [loads]: every case carries the same
        from archquake.blocks.assembly import PASSIVE_LEFT_OUT

        summary["loads"] = loads.to_dict()
        summary["passive_pressure"] = PASSIVE_LEFT_OUT
    if args.export is not None:
        summary["export"] = str(args.export)
    if args.json:
        print_json(summary)
    else:
        outcomes = ", ".join(f"{k} {v}" for k, v in report.outcomes.items()) or "none"
        print(f"{study.name} ({study.model.value} model): {report.total} cases, "
              f"{report.computed} computed now, "
              f"{report.already_stored} already stored; outcomes: {outcomes}")
        if loads is not None:
            print(f"loads: every arch carries its [loads] (the cases' ids include them); "
                  f"{summary['passive_pressure']}")
        print(f"store: {report.store}" + (f"; exported to {args.export}" if args.export else ""))
    return 0


class _Bar:
    """A tqdm bar fed by the library's ``progress(stored, total)`` callback."""

    def __init__(self, *, disable: bool):
        self._disable = disable
        self._bar = None

    def __call__(self, done: int, total: int) -> None:
        if self._bar is None:
            from tqdm import tqdm

            self._bar = tqdm(total=total, initial=done, unit="case", file=sys.stderr,
                             disable=True if self._disable else None, dynamic_ncols=True,
                             desc="sweep")
            return
        self._bar.update(done - self._bar.n)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
