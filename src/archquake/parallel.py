"""Parallel execution: local process pools, the cores this process may use, numba threads per
worker, and the executors a command line asks for (serial, a process pool, or a Dask cluster).

Every command that runs work in parallel (sweeps, domains, assessments, comparisons) takes its
pool and its core count from here.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import time
from collections.abc import Iterator
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from contextlib import contextmanager
from pathlib import Path

from archquake.errors import ArchquakeError, InvalidParameterError

#: Seconds to wait for a Dask scheduler to answer.
CONNECT_TIMEOUT = 10.0


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
#: four-link model and the sweep machinery; importing starts no thread). ``__main__`` is the
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
        ``"forkserver"`` or ``"spawn"`` (default `START_METHOD`); ``"fork"`` is accepted
        for measurements only (benchmarks/bench_pool.py): it is unsafe after a threaded kernel.

    Each worker runs numba's threaded kernels on its share of the cores
    (`threads_per_worker`: ``workers x threads <= cores``, not ``workers x cores``), and
    watches this process and exits once it is gone, so that no orphan keeps running or holds
    the terminal's pipes (``archquake sweep ... | tee`` then ends).

    As with any pool not started by ``fork``, a script creating one must guard its work with
    ``if __name__ == "__main__":`` (workers import the main module), and the case function must
    be importable (not defined in an interactive session). With ``forkserver`` this sets the
    process's fork-server preload to `FORKSERVER_PRELOAD` before the server starts.
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
    ``cores`` (default `usable_cores`), at least one each.

    Without the cap every worker's threaded kernels (``prange``: the domains, the IDA's batch)
    start numba's default of one thread per core, ``workers x cores`` threads on ``cores``.

    >>> threads_per_worker(2, cores=8), threads_per_worker(3, cores=8), threads_per_worker(4, cores=2)
    (4, 2, 1)
    """
    return max(1, (usable_cores() if cores is None else int(cores)) // max(1, int(workers)))


def _start_worker(parent: int, ignore_sigint: bool, workers: int = 1) -> None:
    """Worker initializer: cap numba's threads at this worker's share of the cores
    (`threads_per_worker`, never above numba's own ``NUMBA_NUM_THREADS``), optionally
    ignore SIGINT, and end when ``parent`` ends."""
    import numba

    # per thread in numba: set here, in the thread that runs the pool's tasks (a fresh worker's
    # count is numba's maximum, NUMBA_NUM_THREADS, which set_num_threads may not exceed)
    numba.set_num_threads(min(threads_per_worker(workers), numba.get_num_threads()))
    _unlink_numba_lock()
    if ignore_sigint:
        import signal

        signal.signal(signal.SIGINT, signal.SIG_IGN)
    _watch_parent(parent)


def _unlink_numba_lock() -> None:
    """Unlink the name of the semaphore numba's threading layer makes in each worker (a
    multiprocessing RLock, made under any start method whose name contains "fork"), and take
    it off the resource tracker's list. The lock is this worker's own: no other process opens
    it by name, and an unlinked semaphore lives on until the worker ends. A worker ended by
    SIGTERM (an interrupted command, `stop_workers`) runs no clean-up, and the tracker
    then warned at exit of "2 leaked semaphore objects" (and unlinked them itself)."""
    import multiprocessing.util as mp_util
    from multiprocessing import resource_tracker, synchronize

    try:
        from numba.np.ufunc import parallel as numba_parallel
    except ImportError:  # pragma: no cover - numba moved it
        return
    lock = getattr(numba_parallel, "_backend_init_process_lock", None)
    name = getattr(getattr(lock, "_semlock", None), "name", None)
    unlink = getattr(synchronize, "sem_unlink", None)  # POSIX only
    if not name or unlink is None:
        return
    for finalizer in list(getattr(mp_util, "_finalizer_registry", {}).values()):
        if getattr(finalizer, "_args", None) == (name,):
            finalizer.cancel()  # its unlink is done here
    with contextlib.suppress(OSError):
        unlink(name)
    resource_tracker.unregister(name, "semaphore")


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


@contextmanager
def interruptible_pool(workers: int) -> Iterator[ProcessPoolExecutor]:
    """A `process_pool` (not started by
    ``fork``, since by the time the records run this process has run the domains' threaded
    kernels; workers end with this process), with workers ignoring SIGINT (a Ctrl-C reaches
    the whole process group; this process alone turns it into one line and exit status 130).

    An exception here, a KeyboardInterrupt included, cancels the queued work and ends the
    workers at once instead of waiting for them: what they finished is already in the result
    store, from which a rerun resumes."""
    pool = process_pool(workers, ignore_sigint=True)
    try:
        yield pool
    except BaseException:
        stop_workers(pool)
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown(wait=True)


def stop_workers(pool: ProcessPoolExecutor) -> None:
    """Terminate ``pool``'s worker processes at once (SIGTERM), without waiting for the tasks
    they run: what an interrupted command does before it exits, so that none keeps computing
    or holds the terminal's pipes."""
    processes = getattr(pool, "_processes", None) or {}  # the executor's own table of workers
    for process in list(processes.values()):
        with contextlib.suppress(Exception):
            process.terminate()


def executor_workers(executor: Executor | None) -> int | None:
    """Parallel workers of an executor (1 for `SerialExecutor`, a pool's processes, a
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


__all__ = [
    "CONNECT_TIMEOUT",
    "FORKSERVER_PRELOAD",
    "SCHEDULER_SCHEMES",
    "START_METHOD",
    "SerialExecutor",
    "cap_workers",
    "check_scheduler",
    "executor_workers",
    "interruptible_pool",
    "open_executor",
    "process_pool",
    "stop_workers",
    "threads_per_worker",
    "usable_cores",
]
