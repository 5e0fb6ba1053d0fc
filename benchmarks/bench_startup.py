"""Start-up cost of the package and the command line, against ``python -c "import numpy"``.

Every row is a fresh process timed from outside (``subprocess`` + ``time.perf_counter``), median
over a few repetitions, all measured in the same run so the ratios compare like with like:

- ``import archquake`` and ``archquake --version``: what a script or a shell loop pays before
  any work;
- ``archquake run`` first and second: the first with a new, empty ``NUMBA_CACHE_DIR`` (a fresh
  install compiles the kernels), the second in the same cache directory (it must load them);
- ``archquake run --model dem``, first and second in the same way.

Timings are never asserted in tests; this prints them. ``ARCHQUAKE_BENCH_REPEATS`` sets the
number of repetitions (default 3).

    .venv/bin/python benchmarks/bench_startup.py
"""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

RUN = ["run", "--pulse", "step", "--magnitude", "1.0", "--duration", "0.27", "--json"]
DEM = ["run", "--model", "dem", "--pulse", "step", "--magnitude", "1.0", "--duration", "0.27", "--json"]


def archquake_command() -> list[str]:
    """The installed console script beside this interpreter, else ``python -m``."""
    script = Path(sys.executable).with_name("archquake")
    if script.exists():
        return [str(script)]
    return [sys.executable, "-m", "archquake.cli.main"]


def timed(argv: list[str], cache_dir: str | None = None) -> float:
    """Wall time of one process, s; its failure is an error, not a fast number."""
    env = dict(os.environ)
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = cache_dir
    t0 = time.perf_counter()
    done = subprocess.run(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)} exited {done.returncode}: {done.stderr.strip()[-400:]}")
    return wall


def measure(repeats: int) -> dict[str, float]:
    """Median wall time of each row, s."""
    cli = archquake_command()
    py = sys.executable
    rows: dict[str, list[float]] = {
        'python -c "import numpy"': [],
        "import archquake": [],
        "archquake --version": [],
        "archquake run (first, empty cache)": [],
        "archquake run (second, same cache)": [],
        "archquake run --model dem (first, empty cache)": [],
        "archquake run --model dem (second, same cache)": [],
    }
    # interleaved, so that a change in the machine's load touches every row alike
    for _ in range(repeats):
        rows['python -c "import numpy"'].append(timed([py, "-c", "import numpy"]))
        rows["import archquake"].append(timed([py, "-c", "import archquake"]))
        rows["archquake --version"].append(timed([*cli, "--version"]))
        cache = tempfile.mkdtemp(prefix="archquake-bench-numba-")
        try:
            rows["archquake run (first, empty cache)"].append(timed([*cli, *RUN], cache))
            rows["archquake run (second, same cache)"].append(timed([*cli, *RUN], cache))
            rows["archquake run --model dem (first, empty cache)"].append(timed([*cli, *DEM], cache))
            rows["archquake run --model dem (second, same cache)"].append(timed([*cli, *DEM], cache))
        finally:
            shutil.rmtree(cache, ignore_errors=True)
    return {name: statistics.median(values) for name, values in rows.items()}


def main() -> None:
    repeats = int(os.environ.get("ARCHQUAKE_BENCH_REPEATS", "3"))
    medians = measure(repeats)
    reference = medians['python -c "import numpy"']
    print(f"start-up, median of {repeats} fresh processes each; ratio against python -c \"import numpy\"")
    print(f"  (run: {' '.join(RUN)})")
    width = max(len(name) for name in medians)
    for name, wall in medians.items():
        print(f"  {name:<{width}}  {wall:7.3f} s  {wall / reference:6.1f} x")


if __name__ == "__main__":
    main()
