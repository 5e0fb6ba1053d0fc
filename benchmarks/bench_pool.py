"""Start-up cost of the sweeps' process pool by start method: ``fork`` (unsafe once this process
has run a threaded kernel, so no longer used), ``forkserver`` (the default on Linux) and
``spawn`` (the fallback), against the serial executor measured in the same run.

Each row is a fresh process (so no import, compiled kernel or fork server is warm) that builds a
small sweep of the real four-link model (Oppenheim's arch, 8 step pulses), then times
:func:`archquake.sweeps.run_sweep` on 2 workers to its first stored result (the start-up a user
waits through) and to its end, then does the same with a second pool in the same process (what
a second pool pays: ``archquake assess`` opens two, a forkserver is started once per process).
The serial row times the same cases in this process. Medians over a few repetitions
(``ARCHQUAKE_BENCH_REPEATS``, default 3). Timings are printed, never asserted in tests.

    .venv/bin/python benchmarks/bench_pool.py
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

METHODS = ("fork", "forkserver", "spawn")


def timed_sweep(cases, store, executor) -> tuple[float, float]:
    """Seconds to the first stored result and to the end of ``run_sweep`` on 2 workers."""
    from archquake.sweeps import run_sweep

    first: list[float] = []
    t0 = time.perf_counter()

    def progress(done: int, total: int) -> None:
        if done and not first:
            first.append(time.perf_counter() - t0)

    run_sweep(cases, store, executor=executor, workers=2, chunk_size=1, progress=progress)
    return first[0], time.perf_counter() - t0


def child(method: str) -> None:
    """Run in a fresh process: print the JSON of the timings of ``method`` (or ``serial``)."""
    from archquake.parallel import SerialExecutor, process_pool
    from archquake.sweeps import ArchSpec, Case, ExcitationSpec, ResultStore

    arch = ArchSpec(10, 0.15, 157.5, 7)
    out: dict[str, float] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for attempt, shift in (("first", 0.0), ("second", 1.0)):  # new cases for the 2nd pool
            cases = [Case(arch, ExcitationSpec("step", magnitude_g=0.5 + 0.1 * k + shift,
                                               duration_s=0.25)) for k in range(8)]
            executor = SerialExecutor() if method == "serial" else process_pool(2, start_method=method)
            with ResultStore(Path(tmp) / f"{attempt}.sqlite") as store:
                first, whole = timed_sweep(cases, store, executor)
            executor.shutdown(wait=True)
            out[f"{attempt}_result_s"], out[f"{attempt}_all_s"] = first, whole
    print(json.dumps(out))


def measure(repeats: int) -> dict[str, dict[str, float]]:
    rows: dict[str, list[dict[str, float]]] = {m: [] for m in ("serial", *METHODS)}
    env = dict(os.environ)
    for _ in range(repeats):
        for method in rows:
            done = subprocess.run([sys.executable, __file__, "--child", method], env=env,
                                  capture_output=True, text=True, check=False)
            if done.returncode != 0:
                raise RuntimeError(f"{method}: {done.stderr.strip()[-400:]}")
            rows[method].append(json.loads(done.stdout.strip().splitlines()[-1]))
    return {m: {k: statistics.median(r[k] for r in runs) for k in runs[0]}
            for m, runs in rows.items()}


def main() -> None:
    repeats = int(os.environ.get("ARCHQUAKE_BENCH_REPEATS", "3"))
    res = measure(repeats)
    ref = res["serial"]["first_result_s"]
    print(f"sweep of 8 four-link cases on 2 workers, fresh process, median of {repeats}")
    print(f"{'executor':<12} {'1st result':>11} {'all 8':>8} {'2nd pool: 1st':>15} {'all 8':>8}"
          f"  1st result / serial's")
    for method, r in res.items():
        print(f"{method:<12} {r['first_result_s']:10.3f}s {r['first_all_s']:7.3f}s "
              f"{r['second_result_s']:14.3f}s {r['second_all_s']:7.3f}s  "
              f"{r['first_result_s'] / ref:6.1f}x")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--child":
        child(sys.argv[2])
    else:
        main()
