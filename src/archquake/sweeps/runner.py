"""Map a pure case function over cases through any ``concurrent.futures.Executor``, storing
each batch as it completes and skipping what the store already holds.

Design (the style notes' habit 11): the case function is pure (``Case -> dict``), the executor
is injected (`SerialExecutor`, a ``ProcessPoolExecutor``, or Dask's
``Client(address).get_executor()``), and only the driving process writes the store. Cases
travel in chunks (one task evaluates several cases) so that millisecond cases are not swamped
by scheduling overhead; at most a few chunks per worker are in flight, so an interruption
wastes little and memory stays bounded for any study size.

If a Dask worker dies, the scheduler reruns its tasks elsewhere and each future still
completes once; the store's ``INSERT OR IGNORE`` on the case id makes a duplicate delivery
harmless in any case.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, Executor, Future, wait
from dataclasses import dataclass, field
from functools import partial
from typing import Any

from archquake.errors import ArchquakeError, ClusterLostError, InvalidParameterError
from archquake.parallel import cap_workers, executor_workers, process_pool, usable_cores
from archquake.sweeps.cases import Case
from archquake.sweeps.evaluate import ModelUnavailableError
from archquake.sweeps.store import STATUS_ERROR, STATUS_OK, CaseRecord, ResultStore, jsonable

#: A pure case function: one case in, a JSON-able summary out (``outcome`` read if present).
CaseFunction = Callable[[Case], Mapping[str, Any]]
#: A batch function: many cases in, one summary (or the ArchquakeError refusing it) per case,
#: in order (e.g. one compiled call over a whole round of incremental dynamic analysis).
BatchFunction = Callable[[Sequence[Case]], Sequence[Any]]
#: Progress callback: ``progress(stored, total)`` after every stored batch (and once at start).
Progress = Callable[[int, int], None]

#: Largest chunk chosen automatically (cases per task).
MAX_AUTO_CHUNK = 64
#: Chunks per worker chosen automatically, so the last few tasks balance across workers.
CHUNKS_PER_WORKER = 8
#: Seconds a Dask sweep waits with no worker in the cluster before it gives up (rows kept).
NO_WORKER_TIMEOUT = 60.0
#: Seconds between checks of the cluster's health while no task completes.
HEARTBEAT = 1.0


@dataclass(frozen=True)
class SweepReport:
    """What a sweep did.

    Attributes
    ----------
    total : int
        Distinct cases asked for.
    already_stored : int
        Of those, found in the store before this run (not recomputed).
    computed : int
        Evaluated and stored by this run.
    outcomes : dict
        Count of every requested case in the store by outcome (``"error"``: refused by the model).
    store : str
        Path of the store.
    """

    total: int
    already_stored: int
    computed: int
    outcomes: dict[str, int] = field(default_factory=dict)
    store: str = ""

    def to_dict(self) -> dict:
        return {"cases_total": self.total, "computed_now": self.computed,
                "already_stored": self.already_stored, "outcomes": dict(self.outcomes),
                "store": self.store}


def evaluate_chunk(evaluate: CaseFunction, cases: Sequence[Case]) -> list[CaseRecord]:
    """Evaluate cases one after another (this is the task a worker runs).

    A case the model refuses with an `ArchquakeError` (bad geometry,
    an arch that cannot stand, a solver that cannot proceed) becomes an ``"error"`` record with
    its one-line message; a missing model (`ModelUnavailableError`) and any other
    exception propagate (the first is a fault of the installation, the others are bugs).
    """
    records = []
    for case in cases:
        t0 = time.perf_counter()
        try:
            outputs = jsonable(dict(evaluate(case)))
        except ModelUnavailableError:
            raise
        except ArchquakeError as exc:
            records.append(CaseRecord(case.case_id, STATUS_ERROR, {}, None, str(exc),
                                      time.perf_counter() - t0))
            continue
        outcome = outputs.get("outcome")
        records.append(CaseRecord(case.case_id, STATUS_OK, outputs,
                                  None if outcome is None else str(outcome), None,
                                  time.perf_counter() - t0))
    return records


def evaluate_batch_chunk(evaluate_batch: BatchFunction, cases: Sequence[Case]) -> list[CaseRecord]:
    """Evaluate a chunk with one call of a batch function (the task a worker runs).

    ``evaluate_batch(cases)`` returns one item per case, in order: a summary dict, or an
    `ArchquakeError` instance for a case the model refuses (stored as
    an ``"error"`` row, as `evaluate_chunk` does). ``elapsed_s`` is the call's wall time
    shared equally between its cases.
    """
    t0 = time.perf_counter()
    results = list(evaluate_batch(list(cases)))
    if len(results) != len(cases):
        raise RuntimeError(f"batch function returned {len(results)} results for {len(cases)} "
                           "cases")
    each = (time.perf_counter() - t0) / max(1, len(cases))
    records = []
    for case, result in zip(cases, results, strict=True):
        if isinstance(result, ModelUnavailableError):
            raise result
        if isinstance(result, ArchquakeError):
            records.append(CaseRecord(case.case_id, STATUS_ERROR, {}, None, str(result), each))
            continue
        outputs = jsonable(dict(result))
        outcome = outputs.get("outcome")
        records.append(CaseRecord(case.case_id, STATUS_OK, outputs,
                                  None if outcome is None else str(outcome), None, each))
    return records


def run_sweep(
    cases: Iterable[Case],
    store: ResultStore,
    *,
    evaluate: CaseFunction | None = None,
    evaluate_batch: BatchFunction | None = None,
    executor: Executor | None = None,
    workers: int | None = None,
    chunk_size: int | None = None,
    progress: Progress | None = None,
    no_worker_timeout: float = NO_WORKER_TIMEOUT,
) -> SweepReport:
    """Evaluate every case the store does not hold yet and store each batch as it completes.

    Parameters
    ----------
    cases : iterable of Case
        Duplicates (same id) are evaluated once.
    store : ResultStore
    evaluate : callable, optional
        Pure ``Case -> dict`` (picklable for process pools and Dask). Default:
        `archquake.sweeps.evaluate.evaluate_case` (the real models).
    evaluate_batch : callable, optional
        Instead of ``evaluate``: a pure function evaluating a whole chunk in one call
        (see `evaluate_batch_chunk`); each chunk is one call.
    executor : concurrent.futures.Executor, optional
        Where chunks run. Default: a ``ProcessPoolExecutor`` with ``workers`` processes, created
        and shut down here; an injected executor is left open.
    workers : int, optional
        Parallel workers, used to size chunks and the number in flight (default: the executor's
        own count when known, else the usable cores).
    chunk_size : int, optional
        Cases per task (default: pending / (8 x workers), between 1 and 64).
    progress : callable, optional
        ``progress(stored, total)``: cases of this sweep in the store, after every batch.
    no_worker_timeout : float
        On a Dask cluster: seconds with no worker before the sweep stops with
        `ClusterLostError` (default `NO_WORKER_TIMEOUT`).

    Returns
    -------
    SweepReport

    Raises
    ------
    KeyboardInterrupt
        Propagated after storing every batch that had completed; the rest is cancelled and a
        rerun computes it.
    ClusterLostError
        The Dask scheduler was lost, or no worker was connected for ``no_worker_timeout``
        seconds; every completed batch is stored first.
    """
    if evaluate is not None and evaluate_batch is not None:
        raise InvalidParameterError("give evaluate or evaluate_batch, not both")
    if evaluate is None and evaluate_batch is None:
        from archquake.sweeps.evaluate import evaluate_case as evaluate
    by_id: dict[str, Case] = {}
    for case in cases:
        by_id.setdefault(case.case_id, case)
    stored = store.stored_ids() & by_id.keys()
    pending = [c for cid, c in by_id.items() if cid not in stored]
    total, done = len(by_id), len(stored)
    if progress is not None:
        progress(done, total)

    own = executor is None
    if workers is None:
        workers = executor_workers(executor) or usable_cores()
    workers = max(1, int(workers))
    if own:
        workers = cap_workers(workers, len(pending))[0]
    if chunk_size is None:
        per_task = math.ceil(len(pending) / (CHUNKS_PER_WORKER * workers))
        chunk_size = min(MAX_AUTO_CHUNK, max(1, per_task))
    elif isinstance(chunk_size, bool) or not isinstance(chunk_size, int) or chunk_size < 1:
        raise InvalidParameterError(f"chunk_size must be a whole number >= 1, got {chunk_size!r}")
    computed = 0
    if pending:
        if own:
            executor = process_pool(workers)
        assert executor is not None
        try:
            if evaluate is not None:
                task = partial(evaluate_chunk, evaluate)
            else:
                assert evaluate_batch is not None  # one of the two is given (checked above)
                task = partial(evaluate_batch_chunk, evaluate_batch)
            check = _cluster_check(executor, no_worker_timeout)
            for records in _map_window(executor, task, _chunks(pending, chunk_size), 2 * workers,
                                       check=check):
                computed += store.write(by_id, records)
                done += len(records)
                if progress is not None:
                    progress(done, total)
        finally:
            if own:
                executor.shutdown(wait=True, cancel_futures=True)
    return SweepReport(total=total, already_stored=len(stored), computed=computed,
                       outcomes=store.outcome_counts(by_id), store=str(store.path))


def _map_window(executor: Executor, fn: Callable, items: Iterator, window: int, *,
                check: Callable[[], None] | None = None) -> Iterator:
    """Yield ``fn(item)`` results in completion order with at most ``window`` tasks in flight.

    While nothing completes, ``check()`` runs every `HEARTBEAT` seconds and may raise
    (a lost cluster). A task cancelled by its executor (Dask cancels every task when the
    scheduler goes away) raises `ClusterLostError`. On a cluster (``check`` given), a task
    whose result cannot be read is submitted once more: a worker killed while its finished
    result was being fetched loses the result, and Dask's executor can then raise an error of
    its own instead of the task's (a ValueError from its result's unpacking); the second
    attempt either computes it or, with no worker left, waits for ``check`` to call the
    cluster lost. An error raised again by the second attempt propagates (the task's own
    errors are bugs, `evaluate_chunk`). On KeyboardInterrupt or
    ClusterLostError the tasks that had already completed are still yielded, so the consumer
    can store them, before the error propagates; tasks still in flight are cancelled.
    """
    in_flight: set[Future] = set()
    # on a cluster: each task's item and attempt, for one more attempt
    item_of: dict[Future, tuple[object, int]] = {}
    exhausted = False
    try:
        while True:
            while not exhausted and len(in_flight) < window:
                item = next(items, None)
                if item is None:
                    exhausted = True
                    break
                future = executor.submit(fn, item)
                in_flight.add(future)
                if check is not None:
                    item_of[future] = (item, 1)
            if not in_flight:
                return
            finished, in_flight = wait(in_flight, timeout=HEARTBEAT,
                                       return_when=FIRST_COMPLETED)
            if not finished and check is not None:
                check()
            for future in finished:
                if future.cancelled():
                    in_flight |= finished - {future}
                    raise ClusterLostError(
                        "a task was cancelled by the executor: the Dask scheduler went away")
                item, attempt = item_of.pop(future, (None, 0))
                if attempt == 1 and future.exception() is not None:
                    again = executor.submit(fn, item)
                    in_flight.add(again)
                    item_of[again] = (item, 2)
                    continue
                yield future.result()
    except (KeyboardInterrupt, ClusterLostError):
        # keep what already finished: hand the completed results to the consumer, then stop
        for future in [f for f in in_flight if f.done() and not f.cancelled()]:
            in_flight.discard(future)
            if future.exception() is None:
                yield future.result()
        raise
    finally:
        for future in in_flight:
            future.cancel()


def _cluster_check(executor: Executor | None, no_worker_timeout: float
                   ) -> Callable[[], None] | None:
    """For a Dask executor, a check that raises `ClusterLostError` once the scheduler
    is gone or no worker has been connected for ``no_worker_timeout`` s; None otherwise."""
    client = getattr(executor, "_client", None)
    if client is None:
        return None
    since: list[float] = []

    def check() -> None:
        if client.status in ("closed", "closing", "failed"):
            raise ClusterLostError(f"lost the Dask scheduler at {client.scheduler.address}")
        try:
            n = len(client.nthreads())
        except Exception:  # the scheduler does not answer: the next check will see it closed
            n = 0
        if n:
            since.clear()
            return
        if not since:
            since.append(time.monotonic())
        if time.monotonic() - since[0] >= no_worker_timeout:
            raise ClusterLostError(
                f"the Dask cluster at {client.scheduler.address} has had no worker for "
                f"{no_worker_timeout:g} s")

    return check


def _chunks(cases: Sequence[Case], size: int) -> Iterator[list[Case]]:
    for start in range(0, len(cases), size):
        yield list(cases[start:start + size])


__all__ = [
    "BatchFunction",
    "CaseFunction",
    "SweepReport",
    "evaluate_batch_chunk",
    "evaluate_chunk",
    "run_sweep",
]
