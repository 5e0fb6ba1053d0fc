"""Start-up cost of ``archquake run`` (the default model), against ``python -c "import numpy"``.

What a user waits for one verdict, from a fresh process, measured two ways:

- **warm**: ``archquake run --pulse step --magnitude 1.0 --duration 0.27`` with numba's cache
  warm, against ``python -c "import numpy"`` (the target: within 5x);
- **cold after the warm-up**: the first such run after ``archquake warm`` filled a new, empty
  ``NUMBA_CACHE_DIR`` (what a user meets after ``make demo``), against the warm runs in that
  cache (the target: within 2x; the first run must load its kernels, not compile them).

And the floor under any command that runs a compiled kernel, in the same processes' terms:
``python -c "import numba"``, and one kernel loaded from the warm cache (numba's first load
also sets up its typing and lowering registries and checks for BLAS by importing scipy.linalg:
the same cost whatever the kernel).

Every row is a fresh process timed from outside: its wall time (``time.perf_counter`` around
``subprocess.run``) and its CPU time (user + system, ``resource.getrusage(RUSAGE_CHILDREN)``;
on shared cores the CPU time is the steadier of the two). Rows that can be repeated are the
median over ``ARCHQUAKE_BENCH_REPEATS`` processes (default 5), interleaved so that a change in
the machine's load touches every row alike; the warm-up and the first run after it happen once.
Timings are never asserted in tests; this prints them. ``ARCHQUAKE_BENCH_COLD=0`` leaves out
the warm-up into a new cache and the first run after it (the warm rows then use the cache the
installed package already has, warmed by ``archquake warm``).

    .venv/bin/python benchmarks/bench_startup.py
    ARCHQUAKE_BENCH_COLD=0 .venv/bin/python benchmarks/bench_startup.py
"""

from __future__ import annotations

import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

RUN = ["run", "--pulse", "step", "--magnitude", "1.0", "--duration", "0.27"]
ONE_KERNEL = ("from archquake.ground import StepImpulse\n"
              "from archquake.ground._kernel import ground_duration\n"
              "ground_duration(*StepImpulse(1.0, 0.27).kernel_spec())")

NUMPY = 'python -c "import numpy"'
NUMBA = 'python -c "import numba"'
FLOOR = "import numba + one kernel from the cache"
WARM_UP = "archquake warm (new, empty cache)"
FIRST = "archquake run, first after the warm-up"
WARM = "archquake run, warm"


def archquake_command() -> list[str]:
    """The installed console script beside this interpreter, else ``python -m``."""
    script = Path(sys.executable).with_name("archquake")
    if script.exists():
        return [str(script)]
    return [sys.executable, "-m", "archquake.cli.main"]


def timed(argv: list[str], cache_dir: str | None) -> tuple[float, float]:
    """Wall and CPU time of one process, s, with ``NUMBA_CACHE_DIR=cache_dir`` (None: numba's
    own choice); its failure is an error, not a fast number."""
    env = dict(os.environ) if cache_dir is None else dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)} exited {done.returncode}: "
                           f"{done.stderr.strip()[-400:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def measure(repeats: int, cold: bool = True) -> dict[str, list[tuple[float, float]]]:
    """Every row's (wall, CPU) samples, s; without ``cold``, no warm-up into a new cache (nor
    the first run after it): the warm rows use numba's usual cache."""
    cli = archquake_command()
    py = sys.executable
    rows: dict[str, list[tuple[float, float]]] = {}
    cache = tempfile.mkdtemp(prefix="archquake-bench-numba-") if cold else None
    try:
        if cache is not None:
            rows[WARM_UP] = [timed([*cli, "warm"], cache)]
            rows[FIRST] = [timed([*cli, *RUN], cache)]
        else:
            timed([*cli, *RUN], cache)  # loads (or compiles, once) what the warm rows load
        for _ in range(repeats):
            for name, argv in ((NUMPY, [py, "-c", "import numpy"]),
                               (NUMBA, [py, "-c", "import numba"]),
                               (FLOOR, [py, "-c", ONE_KERNEL]),
                               (WARM, [*cli, *RUN])):
                rows.setdefault(name, []).append(timed(argv, cache))
    finally:
        if cache is not None:
            shutil.rmtree(cache, ignore_errors=True)
    return rows


def main() -> None:
    repeats = int(os.environ.get("ARCHQUAKE_BENCH_REPEATS", "5"))
    rows = measure(repeats, cold=os.environ.get("ARCHQUAKE_BENCH_COLD", "1") != "0")
    med = {name: (statistics.median(w for w, _ in s), statistics.median(c for _, c in s), len(s))
           for name, s in rows.items()}
    ref_wall, ref_cpu, _ = med[NUMPY]
    print(f"start-up of 'archquake {' '.join(RUN)}': fresh processes, median wall and CPU "
          f"time, s; x = against {NUMPY}")
    width = max(len(name) for name in med)
    print(f"  {'':<{width}}  {'n':>2}  {'wall':>7} {'x':>5}  {'CPU':>7} {'x':>5}")
    for name in (NUMPY, NUMBA, FLOOR, WARM, FIRST, WARM_UP):
        if name not in med:
            continue
        wall, cpu, n = med[name]
        print(f"  {name:<{width}}  {n:>2}  {wall:7.3f} {wall / ref_wall:5.1f}  "
              f"{cpu:7.3f} {cpu / ref_cpu:5.1f}")

    def ratio(a: str, b: str) -> str:
        return (f"wall {med[a][0] / med[b][0]:5.2f} x   CPU {med[a][1] / med[b][1]:5.2f} x")

    print("ratios (CPU is the steadier on shared cores):")
    print(f"  warm run / import numpy (target 5)              {ratio(WARM, NUMPY)}")
    print(f"  floor / import numpy (no kernel command is less) {ratio(FLOOR, NUMPY)}")
    print(f"  warm run / floor                                {ratio(WARM, FLOOR)}")
    if FIRST in med:
        print(f"  first run after the warm-up / warm (target 2)   {ratio(FIRST, WARM)}")


if __name__ == "__main__":
    main()
