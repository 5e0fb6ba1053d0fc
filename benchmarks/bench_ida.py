"""Benchmark: incremental dynamic analysis of Oppenheim's arch under the 28 FEMA P695 near-field
pulse components (PGA, hunt-and-fill to 2 % of the IM, fill 10 %, ceiling 5 g), against running
the same cases one by one through :func:`archquake.mechanism.simulate` in the same run.

The IDA goes through the sweep store (a fresh SQLite file) in rounds, each round one compiled
batch (:func:`archquake.ida.batch.evaluate_cases`, numba ``prange`` over the cases, first run
stopped 10 sqrt(R/g) after the record when energy proves survival); serial executor, so the only
parallelism is numba's threads. The plain loop calls ``simulate`` (prepared mechanism reused,
no history) on exactly the scaled records the IDA ran. Also printed: the batch alone on the same
cases (no store, no rounds), on all of numba's threads and on one (what the threads bring), and
simulate's time per outcome; then the default model (the chain of rigid voussoirs, its
half-step guard on) against the four-link model on the same IDA up to 1 g (the pace of the sweep
users run with each). Needs the FEMA suites (``pip install 'archquake[records]'``). Run:

    .venv/bin/python benchmarks/bench_ida.py

The whole picture on one thread (the IDA too): ``NUMBA_NUM_THREADS=1 .venv/bin/python
benchmarks/bench_ida.py``. The machine should be otherwise idle: the ratio is a ratio of wall
times.
"""

from __future__ import annotations

import math
import os
import tempfile
import time
from collections import defaultdict
from pathlib import Path

import numba

from archquake.ground.suites import load_suite
from archquake.ida import incremental_dynamic_analysis
from archquake.ida.batch import evaluate_cases
from archquake.mechanism import PreparedMechanism, SolverOptions, simulate
from archquake.parallel import SerialExecutor
from archquake.sweeps import ArchSpec, Case, ExcitationSpec, ResultStore


def main() -> None:
    arch = ArchSpec(10, 0.15, 157.5, 7)
    suite = load_suite("near-field-pulse")
    records = suite.records
    prepared = PreparedMechanism.build(arch.build())
    with tempfile.TemporaryDirectory() as tmp:
        with ResultStore(Path(tmp) / "warm.sqlite") as store:  # compile the kernels
            incremental_dynamic_analysis(arch, records[:1], "pga", store, ceiling=1.0,
                                         precision=0.5, fill=2.0, model="fourlink",
                                         executor=SerialExecutor())
        simulate(prepared, records[0], options=SolverOptions(output_interval=0.0))
        t0 = time.perf_counter()
        with ResultStore(Path(tmp) / "ida.sqlite") as store:
            res = incremental_dynamic_analysis(arch, records, "pga", store, ceiling=5.0,
                                               precision=0.02, fill=0.10, model="fourlink",
                                               executor=SerialExecutor())
        t_ida = time.perf_counter() - t0
    cases = [Case(arch, ExcitationSpec("record", motion=m, scale=float(f)))
             for rec, m in zip(res.records, records, strict=True) for f in rec.factors]
    n = len(cases)
    print(f"IDA, {len(records)} near-field pulse components, PGA to 2 % (fill 10 %, ceiling "
          f"5 g): {n} runs in {res.rounds} rounds, {t_ida:.2f} s through the store "
          f"({t_ida / n * 1e3:.2f} ms per run; numba threads: "
          f"{os.environ.get('NUMBA_NUM_THREADS', 'all')})")

    t0 = time.perf_counter()
    batch = evaluate_cases(cases)
    t_batch = time.perf_counter() - t0
    threads = numba.get_num_threads()
    t_batch1 = math.nan
    if threads > 1:  # the same batch on one thread: what the threads bring
        numba.set_num_threads(1)
        try:
            t0 = time.perf_counter()
            evaluate_cases(cases)
            t_batch1 = time.perf_counter() - t0
        finally:
            numba.set_num_threads(threads)

    per_outcome: dict[str, float] = defaultdict(float)
    count: dict[str, int] = defaultdict(int)
    t0, c0 = time.perf_counter(), time.process_time()
    mismatches = 0
    opts = SolverOptions(output_interval=0.0)
    for case, b in zip(cases, batch, strict=True):
        t1 = time.perf_counter()
        r = simulate(prepared, case.excitation.build(), options=opts)
        per_outcome[r.outcome.value] += time.perf_counter() - t1
        count[r.outcome.value] += 1
        mismatches += r.outcome.value != b["outcome"]
    t_loop, c_loop = time.perf_counter() - t0, time.process_time() - c0
    print(f"same {n} cases one by one through simulate: {t_loop:.2f} s "
          f"({t_loop / n * 1e3:.2f} ms per run; {c_loop:.2f} s of CPU)")
    if t_loop > 1.1 * c_loop:
        print("  (the serial loop got less than 90 % of a core: other jobs share the machine, "
              "so the ratios below are unreliable)")
    print("simulate time by outcome: " + ", ".join(
        f"{k} {count[k]} runs {per_outcome[k]:.2f} s ({per_outcome[k] / count[k] * 1e3:.2f} ms "
        f"per run)" for k in sorted(count)))
    print(f"same cases in one batch call (no store, no rounds): {t_batch:.2f} s on {threads} "
          f"numba thread(s)" + ("" if math.isnan(t_batch1) else f", {t_batch1:.2f} s on 1 "
                                f"(threads bring {t_batch1 / t_batch:.2f}x)"))
    print(f"outcomes differing between the batch and simulate: {mismatches}")
    if not math.isnan(t_batch1):
        print(f"decomposition: simulate loop / 1-thread batch {t_loop / t_batch1:.2f}x (per-call "
              f"overhead and the batch's early decision) x threads {t_batch1 / t_batch:.2f}x x "
              f"store and rounds {t_batch / t_ida:.2f}x")
    print(f"ratio simulate loop / IDA: {t_loop / t_ida:.2f}x "
          f"(batch alone: {t_loop / t_batch:.2f}x; target >= 5x)")
    models_side_by_side(arch, records)


def models_side_by_side(arch: ArchSpec, records) -> None:
    """The same IDA (up to 1 g, 2 % brackets, fill 10 %) with the four-link model and with the
    default model, the chain of rigid voussoirs (guard on): wall and CPU time, runs."""
    times = {}
    for model in ("fourlink", "rigid"):
        with tempfile.TemporaryDirectory() as tmp:
            with ResultStore(Path(tmp) / "warm.sqlite") as store:  # compile / load the kernels
                incremental_dynamic_analysis(arch, records[:1], "pga", store, ceiling=1.0,
                                             precision=0.5, fill=2.0, model=model)
            t0, c0 = time.perf_counter(), time.process_time()
            with ResultStore(Path(tmp) / "ida.sqlite") as store:
                res = incremental_dynamic_analysis(arch, records, "pga", store, ceiling=1.0,
                                                   model=model)
            times[model] = (time.perf_counter() - t0, time.process_time() - c0, res.total)
    for model, (wall, cpu, runs) in times.items():
        print(f"IDA up to 1 g, {model:8s}: {wall:6.2f} s ({cpu:.2f} s of CPU), {runs} runs")
    print(f"the default model's IDA takes {times['rigid'][0] / times['fourlink'][0]:.1f}x the "
          "four-link model's")


if __name__ == "__main__":
    main()
