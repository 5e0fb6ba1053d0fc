"""Map a pure case function over cases through any ``concurrent.futures.Executor``, storing
each batch as it completes and skipping what the store already holds.

Design (the style notes' habit 11): the case function is pure (``Case -> dict``), the executor
is injected (:class:`SerialExecutor`, a ``ProcessPoolExecutor``, or Dask's
``Client(address).get_executor()``), and only the driving process writes the store. Cases
travel in chunks (one task evaluates several cases) so that millisecond cases are not swamped
by scheduling overhead; at most a few chunks per worker are in flight, so an interruption
wastes little and memory stays bounded for any study size.

If a Dask worker dies, the scheduler reruns its tasks elsewhere and each future still
completes once; the store's ``INSERT OR IGNORE`` on the case id makes a duplicate delivery
harmless in any case.
"""

from __future__ import annotations

import contextlib
import math
import multiprocessing
import os
import time
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, Executor, Future, ProcessPoolExecutor, wait
from contextlib import contextmanager
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any

from archquake.errors import ArchquakeError, InvalidParameterError
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
#: Seconds to wait for a Dask scheduler to answer.
CONNECT_TIMEOUT = 10.0
#: Chunks per worker chosen automatically, so the last few tasks balance across workers.
CHUNKS_PER_WORKER = 8
#: Seconds a Dask sweep waits with no worker in the cluster before it gives up (rows kept).
NO_WORKER_TIMEOUT = 60.0
#: Seconds between checks of the cluster's health while no task completes.
HEARTBEAT = 1.0


class ClusterLostError(ArchquakeError):
    """The Dask scheduler went away, or the cluster had no worker for too long. Every case
    that had completed is in the store; rerunning the same sweep resumes."""


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


class SerialExecutor(Executor):
    """Runs each task in the calling thread at submission (the executor for debugging, tests
    and one-core machines). ``KeyboardInterrupt`` and other non-``Exception`` errors propagate
    at once instead of being kept in the future."""

    def submit(self, fn, /, *args, **kwargs) -> Future:
        future: Future = Future()
        try:
            result = fn(*args, **kwargs)
        except Exception as exc:
            future.set_exception(exc)
        else:
            future.set_result(result)
        return future


def evaluate_chunk(evaluate: CaseFunction, cases: Sequence[Case]) -> list[CaseRecord]:
    """Evaluate cases one after another (this is the task a worker runs).

    A case the model refuses with an :class:`~archquake.errors.ArchquakeError` (bad geometry,
    an arch that cannot stand, a solver that cannot proceed) becomes an ``"error"`` record with
    its one-line message; a missing model (:class:`ModelUnavailableError`) and any other
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
    :class:`~archquake.errors.ArchquakeError` instance for a case the model refuses (stored as
    an ``"error"`` row, as :func:`evaluate_chunk` does). ``elapsed_s`` is the call's wall time
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
        :func:`archquake.sweeps.evaluate.evaluate_case` (the real models).
    evaluate_batch : callable, optional
        Instead of ``evaluate``: a pure function evaluating a whole chunk in one call
        (see :func:`evaluate_batch_chunk`); each chunk is one call.
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
        :class:`ClusterLostError` (default :data:`NO_WORKER_TIMEOUT`).

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

    While nothing completes, ``check()`` runs every :data:`HEARTBEAT` seconds and may raise
    (a lost cluster). A task cancelled by its executor (Dask cancels every task when the
    scheduler goes away) raises :class:`ClusterLostError`. On KeyboardInterrupt or
    ClusterLostError the tasks that had already completed are still yielded, so the consumer
    can store them, before the error propagates; tasks still in flight are cancelled.
    """
    in_flight: set[Future] = set()
    exhausted = False
    try:
        while True:
            while not exhausted and len(in_flight) < window:
                item = next(items, None)
                if item is None:
                    exhausted = True
                    break
                in_flight.add(executor.submit(fn, item))
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
    """For a Dask executor, a check that raises :class:`ClusterLostError` once the scheduler
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


def cap_workers(requested: int | None, pending: int) -> tuple[int, str | None]:
    """Local worker processes for ``pending`` cases: at most the usable cores, and at most the
    number of cases; with a note saying so when ``requested`` was more.

    >>> cap_workers(3, 1)
    (1, 'using 1 worker process (there is 1 case to compute), not 3')
    """
    cores = usable_cores()
    n = cores if requested is None else int(requested)
    capped = max(1, min(n, cores, pending if pending > 0 else 1))
    if requested is None or capped >= requested:
        return capped, None
    why = (f"this machine has {cores} usable core{'s' * (cores != 1)}" if capped == cores
           else f"there {'is' if pending == 1 else 'are'} {pending} case"
                f"{'s' * (pending != 1)} to compute")
    return capped, f"using {capped} worker process{'es' * (capped != 1)} ({why}), not {requested}"


#: How local worker processes start: never ``fork``. A process that has run a threaded numba
#: kernel (``prange``: the domains, the IDA's batch) holds an OpenMP/TBB thread pool, and a
#: forked child of it that runs one in turn is killed ("fork() called from a process already
#: using GNU OpenMP"). ``forkserver`` forks the workers from a clean server process started
#: once per process (benchmarks/bench_pool.py measures the start-up of each method); ``spawn``
#: where there is no forkserver (Windows, macOS without it).
START_METHOD = ("forkserver" if "forkserver" in multiprocessing.get_all_start_methods()
                else "spawn")
#: Modules the fork server imports once, so that its workers start with them loaded (the
#: analytical model and the sweep machinery; importing starts no thread). ``__main__`` is the
#: multiprocessing default, kept.
FORKSERVER_PRELOAD = ("__main__", "archquake.sweeps.runner", "archquake.sweeps.evaluate",
                      "archquake.mechanism")


def process_pool(workers: int, *, ignore_sigint: bool = False,
                 start_method: str | None = None) -> ProcessPoolExecutor:
    """A process pool whose workers start safely after threaded kernels and end when this
    process ends, however it ends (even by SIGKILL).

    Parameters
    ----------
    workers : int
        Worker processes.
    ignore_sigint : bool
        Workers ignore SIGINT: a Ctrl-C reaches the whole process group and only this process
        should turn it into one line (``archquake assess``). Default: workers take it as
        ``KeyboardInterrupt``, as Python processes do.
    start_method : str, optional
        ``"forkserver"`` or ``"spawn"`` (default :data:`START_METHOD`); ``"fork"`` is accepted
        for measurements only (benchmarks/bench_pool.py): it is unsafe after a threaded kernel.

    Each worker runs numba's threaded kernels on its share of the cores
    (:func:`threads_per_worker`: ``workers x threads <= cores``, not ``workers x cores``), and
    watches this process and exits once it is gone, so that no orphan keeps running or holds
    the terminal's pipes (``archquake sweep ... | tee`` then ends).

    As with any pool not started by ``fork``, a script creating one must guard its work with
    ``if __name__ == "__main__":`` (workers import the main module), and the case function must
    be importable (not defined in an interactive session). With ``forkserver`` this sets the
    process's fork-server preload to :data:`FORKSERVER_PRELOAD` before the server starts.
    """
    context = multiprocessing.get_context(start_method or START_METHOD)
    if isinstance(context, multiprocessing.context.ForkServerContext):
        # no effect once this process's fork server runs (it starts with the first pool)
        context.set_forkserver_preload(list(FORKSERVER_PRELOAD))
    return ProcessPoolExecutor(max_workers=workers, mp_context=context,
                               initializer=_start_worker,
                               initargs=(os.getpid(), ignore_sigint, int(workers)))


def threads_per_worker(workers: int, cores: int | None = None) -> int:
    """numba threads each of ``workers`` processes may run so that together they use at most
    ``cores`` (default :func:`usable_cores`), at least one each.

    Without the cap every worker's threaded kernels (``prange``: the domains, the IDA's batch)
    start numba's default of one thread per core, ``workers x cores`` threads on ``cores``.

    >>> threads_per_worker(2, cores=8), threads_per_worker(3, cores=8), threads_per_worker(4, cores=2)
    (4, 2, 1)
    """
    return max(1, (usable_cores() if cores is None else int(cores)) // max(1, int(workers)))


def _start_worker(parent: int, ignore_sigint: bool, workers: int = 1) -> None:
    """Worker initializer: cap numba's threads at this worker's share of the cores
    (:func:`threads_per_worker`, never above numba's own ``NUMBA_NUM_THREADS``), optionally
    ignore SIGINT, and end when ``parent`` ends."""
    import numba

    # per thread in numba: set here, in the thread that runs the pool's tasks (a fresh worker's
    # count is numba's maximum, NUMBA_NUM_THREADS, which set_num_threads may not exceed)
    numba.set_num_threads(min(threads_per_worker(workers), numba.get_num_threads()))
    if ignore_sigint:
        import signal

        signal.signal(signal.SIGINT, signal.SIG_IGN)
    _watch_parent(parent)


def _watch_parent(parent: int) -> None:
    """Exit this worker once ``parent`` (the process that made the pool) is gone: its own parent
    changes (a spawned worker's parent is ``parent``; a forkserver worker's is the server,
    which exits when ``parent`` does), or ``parent`` no longer exists."""
    import threading

    own = os.getppid()

    def gone() -> bool:
        if os.getppid() != own:
            return True
        try:
            os.kill(parent, 0)
        except ProcessLookupError:
            return True
        except PermissionError:  # the pid now belongs to another user's process
            return True
        try:  # a parent that died but is not yet reaped (a zombie) still answers kill(pid, 0);
            # its reader may be waiting for the pipe this worker holds before reaping it
            state = Path(f"/proc/{parent}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except (OSError, IndexError):
            return False  # no /proc (not Linux): the checks above stand
        return state in ("Z", "X")

    def watch() -> None:
        while not gone():
            time.sleep(0.5)
        os._exit(1)

    threading.Thread(target=watch, name="archquake-parent-watch", daemon=True).start()


def _chunks(cases: Sequence[Case], size: int) -> Iterator[list[Case]]:
    for start in range(0, len(cases), size):
        yield list(cases[start:start + size])


def executor_workers(executor: Executor | None) -> int | None:
    """Parallel workers of an executor (1 for :class:`SerialExecutor`, a pool's processes, a
    Dask cluster's threads), None if unknown or no executor."""
    if executor is None:
        return None
    if isinstance(executor, SerialExecutor):
        return 1
    if isinstance(executor, ProcessPoolExecutor):
        return executor._max_workers  # type: ignore[attr-defined]
    client = getattr(executor, "_client", None)  # distributed.ClientExecutor
    if client is not None:
        try:
            return max(1, sum(client.nthreads().values()))
        except Exception:  # a scheduler that does not answer: fall back to the default
            return None
    return getattr(executor, "_max_workers", None)


def usable_cores() -> int:
    """Cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


#: Dask's transports an address may name.
SCHEDULER_SCHEMES = ("tcp", "tls")


def check_scheduler(address: object, name: str = "scheduler") -> str:
    """A Dask scheduler address ``tcp://HOST:PORT`` (or ``tls://``), checked before any
    connection: scheme, host and a port in [1, 65535]; else one line naming ``name``."""
    from urllib.parse import urlsplit

    usage = f"{name} must be an address like tcp://HOST:PORT, got {address!r}"
    if not isinstance(address, str) or any(c.isspace() or c == "\x00" for c in address):
        raise InvalidParameterError(usage)
    try:
        parts = urlsplit(address)
        port = parts.port
    except ValueError:
        raise InvalidParameterError(usage + " (the port must be a number from 1 to 65535)"
                                    ) from None
    if parts.scheme not in SCHEDULER_SCHEMES:
        raise InvalidParameterError(
            usage + f" (the scheme must be {' or '.join(SCHEDULER_SCHEMES)})")
    if not parts.hostname or port is None or not 1 <= port <= 65535 or parts.path not in ("", "/") \
            or parts.query or parts.fragment:
        raise InvalidParameterError(usage)
    return address


@contextmanager
def open_executor(*, workers: int | None = None, scheduler: str | None = None,
                  connect_timeout: float | None = None) -> Iterator[tuple[Executor, int]]:
    """The executor a command line asks for, and its worker count; closed on exit.

    ``scheduler`` (``tcp://HOST:PORT``) connects to a running Dask scheduler; otherwise
    ``workers == 1`` runs serially and anything else uses a local process pool (default: all
    usable cores).
    """
    if scheduler is not None:
        try:
            from distributed import Client
        except ImportError:
            raise ArchquakeError("--scheduler needs Dask: pip install 'archquake[dask]'") from None
        scheduler = check_scheduler(scheduler)
        try:
            client = Client(scheduler, timeout=connect_timeout or CONNECT_TIMEOUT)
        except Exception as exc:  # noqa: BLE001  (distributed raises OSError, TimeoutError and,
            # for some unreachable hosts, errors of its own: every one means "not reached")
            reason = " ".join(str(exc).split())[:120] or type(exc).__name__
            raise ArchquakeError(f"cannot reach the Dask scheduler at {scheduler} within "
                                 f"{connect_timeout or CONNECT_TIMEOUT:g} s ({reason}); start "
                                 "one with 'dask scheduler' or check the address") from None
        try:
            n = workers or max(1, sum(client.nthreads().values()))
            yield client.get_executor(pure=False), n
        finally:
            client.close()
        return
    n = workers or usable_cores()
    if n < 1:
        raise InvalidParameterError(f"workers must be >= 1, got {n}")
    n = min(n, usable_cores())
    if n == 1:
        yield SerialExecutor(), 1
        return
    pool = process_pool(n)
    try:
        yield pool, n
    except BaseException:  # interrupted (Ctrl-C, SIGTERM) or failed: end the workers now
        stop_workers(pool)
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def stop_workers(pool: ProcessPoolExecutor) -> None:
    """Terminate ``pool``'s worker processes at once (SIGTERM), without waiting for the tasks
    they run: what an interrupted command does before it exits, so that none keeps computing
    or holds the terminal's pipes."""
    processes = getattr(pool, "_processes", None) or {}  # the executor's own table of workers
    for process in list(processes.values()):
        with contextlib.suppress(Exception):
            process.terminate()


__all__ = [
    "BatchFunction",
    "CaseFunction",
    "ClusterLostError",
    "SerialExecutor",
    "SweepReport",
    "cap_workers",
    "evaluate_batch_chunk",
    "evaluate_chunk",
    "executor_workers",
    "open_executor",
    "process_pool",
    "run_sweep",
    "threads_per_worker",
    "usable_cores",
]
