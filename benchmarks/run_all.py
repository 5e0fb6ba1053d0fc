"""Run every benchmark in this folder (``make bench``): each prints its own timings and its ratio
against a plain reference measured in the same run. Timings are never asserted in tests."""

from __future__ import annotations

import runpy
import sys
import time
from pathlib import Path

here = Path(__file__).resolve().parent
for path in sorted(here.glob("bench_*.py")):
    print(f"\n=== {path.name}", flush=True)
    t0 = time.perf_counter()
    try:
        runpy.run_path(str(path), run_name="__main__")
    except Exception as exc:  # report and go on with the others
        print(f"{path.name} failed: {exc!r}", file=sys.stderr)
    print(f"=== {path.name}: {time.perf_counter() - t0:.1f} s", flush=True)
