"""Start-up cost of the package and the command line, against ``python -c "import numpy"``.

Every row is a fresh process timed from outside, all measured in the same run so that the ratios
compare like with like: its wall time (``time.perf_counter`` around ``subprocess.run``) and its
CPU time (user + system, from ``resource.getrusage(RUSAGE_CHILDREN)``; on shared cores the CPU
time is the steadier of the two). Each row is the median over ``ARCHQUAKE_BENCH_REPEATS``
processes (default 3), but for the rows that can happen once only:

- the floor under any command that runs a kernel: ``import numba``, ``import numba,
  scipy.optimize`` (the limit analysis's linear program, which every time history needs for
  its hinges) and one kernel loaded from a warm cache;
- ``import archquake`` and ``archquake --version``: what a script or a shell loop pays;
- ``archquake warm`` into a new, empty ``NUMBA_CACHE_DIR`` (once: what ``make demo`` pays after
  the install);
- for each model (the default ``run``, the rigid chain; ``--model fourlink``; ``--model dem``): its
  first run after the warm-up (once: the first process to load the kernels from the cache) and
  its later runs in the same cache, and the ratio of the two (the first must not compile);
- ``archquake run`` with an empty cache and no warm-up (once), for comparison.

Timings are never asserted in tests; this prints them.

    .venv/bin/python benchmarks/bench_startup.py
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

PULSE = ["--pulse", "step", "--magnitude", "1.0", "--duration", "0.27", "--json"]
MODELS = {
    "archquake run": ["run", *PULSE],
    "archquake run --model fourlink": ["run", "--model", "fourlink", *PULSE],
    "archquake run --model dem": ["run", "--model", "dem", *PULSE],
}
ONE_KERNEL = ("from archquake.ground import StepImpulse\n"
              "from archquake.ground._kernel import ground_duration\n"
              "ground_duration(*StepImpulse(1.0, 0.27).kernel_spec())")


def archquake_command() -> list[str]:
    """The installed console script beside this interpreter, else ``python -m``."""
    script = Path(sys.executable).with_name("archquake")
    if script.exists():
        return [str(script)]
    return [sys.executable, "-m", "archquake.cli.main"]


def timed(argv: list[str], cache_dir: str | None = None) -> tuple[float, float]:
    """Wall and CPU time of one process, s; its failure is an error, not a fast number."""
    env = dict(os.environ)
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = cache_dir
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)} exited {done.returncode}: {done.stderr.strip()[-400:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def measure(repeats: int) -> dict[str, tuple[float, float, int]]:
    """Median (wall, CPU) of each row, s, and the number of processes behind it."""
    cli = archquake_command()
    py = sys.executable
    rows: dict[str, list[tuple[float, float]]] = {}

    def add(name: str, sample: tuple[float, float]) -> None:
        rows.setdefault(name, []).append(sample)

    cache = tempfile.mkdtemp(prefix="archquake-bench-numba-")
    empty = tempfile.mkdtemp(prefix="archquake-bench-numba-")
    try:
        add("archquake warm (empty cache)", timed([*cli, "warm"], cache))
        for name, argv in MODELS.items():
            add(f"{name} (first after warm)", timed([*cli, *argv], cache))
        # interleaved, so that a change in the machine's load touches every row alike
        for _ in range(repeats):
            add('python -c "import numpy"', timed([py, "-c", "import numpy"]))
            add('python -c "import numba"', timed([py, "-c", "import numba"]))
            add('python -c "import numba, scipy.optimize"',
                timed([py, "-c", "import numba, scipy.optimize"]))
            add("one kernel loaded from the cache", timed([py, "-c", ONE_KERNEL], cache))
            add("import archquake", timed([py, "-c", "import archquake"]))
            add("archquake --version", timed([*cli, "--version"]))
            for name, argv in MODELS.items():
                add(f"{name} (warm)", timed([*cli, *argv], cache))
        add("archquake run (empty cache, no warm-up)", timed([*cli, *MODELS["archquake run"]], empty))
    finally:
        shutil.rmtree(cache, ignore_errors=True)
        shutil.rmtree(empty, ignore_errors=True)
    return {name: (statistics.median(w for w, _ in values), statistics.median(c for _, c in values),
                   len(values)) for name, values in rows.items()}


def main() -> None:
    repeats = int(os.environ.get("ARCHQUAKE_BENCH_REPEATS", "3"))
    medians = measure(repeats)
    ref_wall, ref_cpu, _ = medians['python -c "import numpy"']
    print('start-up: fresh processes, median wall and CPU time; ratios against python -c "import numpy"')
    print(f"  (each model runs: {' '.join(PULSE)})")
    width = max(len(name) for name in medians)
    print(f"  {'':<{width}}  {'n':>2}  {'wall s':>8} {'x':>6}  {'CPU s':>8} {'x':>6}")
    order = [n for n in medians if not n.endswith(("(first after warm)", "(warm)"))]
    for model in MODELS:
        order += [f"{model} (first after warm)", f"{model} (warm)"]
    order = [n for n in order if not n.startswith("archquake run (empty")] + [
        "archquake run (empty cache, no warm-up)"]
    for name in order:
        wall, cpu, n = medians[name]
        print(f"  {name:<{width}}  {n:>2}  {wall:8.3f} {wall / ref_wall:6.1f}  "
              f"{cpu:8.3f} {cpu / ref_cpu:6.1f}")
    print("first run after the warm-up against a warm run (the first must not compile):")
    for model in MODELS:
        first, warm = medians[f"{model} (first after warm)"], medians[f"{model} (warm)"]
        print(f"  {model:<{width}}  wall {first[0] / warm[0]:5.2f} x   CPU {first[1] / warm[1]:5.2f} x")


if __name__ == "__main__":
    main()
