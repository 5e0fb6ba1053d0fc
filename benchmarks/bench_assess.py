"""Benchmark: the whole ``archquake assess examples/bridge.toml`` command (default model, the
chain of rigid voussoirs; DEM check included), ``--quick`` and in full (the 28 FEMA P695
near-field pulse components), each in a fresh output folder, against a plain reference
measured in the same run: a Python process that only imports numpy (``python -c "import
numpy"``), so that the ratio says how many bare interpreter starts the command costs on this
machine, whatever its load.

Printed for each: wall time, the CPU time of the command and its child processes (user +
system: on shared cores the wall time grows with the other load, the CPU time much less), and
the ratio of wall times. Targets (docs/assess.md): at most 30 s with ``--quick`` and 120 s in
full on two idle cores. Needs the FEMA suites (``pip install 'archquake[records]'``). Run:

    .venv/bin/python benchmarks/bench_assess.py          # quick and full
    .venv/bin/python benchmarks/bench_assess.py --quick  # quick only
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "bridge.toml"


def _timed(argv: list[str]) -> tuple[float, float]:
    """Wall and CPU time (this child and its own children, user + system) of one command, s."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(argv, check=True, stdout=subprocess.DEVNULL, cwd=ROOT)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def _archquake() -> list[str]:
    exe = Path(sys.executable).with_name("archquake")
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "archquake"]


def main() -> None:
    modes = ["--quick"] if "--quick" in sys.argv[1:] else ["--quick", ""]
    ref = min(_timed([sys.executable, "-c", "import numpy"])[0] for _ in range(5))
    print(f"reference: python -c 'import numpy' {ref:.3f} s (best of 5)")
    # compile the kernels once (numba's cache), as a user's second run finds them
    with tempfile.TemporaryDirectory() as tmp:
        _timed([*_archquake(), "assess", str(EXAMPLE), "--quick", "--out", tmp])
    for mode in modes:
        with tempfile.TemporaryDirectory() as tmp:
            argv = [*_archquake(), "assess", str(EXAMPLE), "--out", tmp, *([mode] if mode else [])]
            wall, cpu = _timed(argv)
        name = "assess bridge.toml " + (mode or "(full)")
        print(f"{name}: {wall:.1f} s wall, {cpu:.1f} s CPU ({os.cpu_count()} cores), "
              f"{wall / ref:.0f}x the reference")


if __name__ == "__main__":
    main()
