"""Benchmark: what the loads cost in the statics.

- ``archquake static`` on the example bridge (R 5 m, t 0.6 m, 15 voussoirs) with 1 m of fill,
  whole process, beside the bare ``static`` (target: at most 2x);
- a 50-position traffic capacity scan of the same bridge with 0.5 m of fill and a dispersed
  axle, in the library and as the whole ``archquake capacity`` process (target: at most 2 s).

Run: .venv/bin/python benchmarks/bench_loads.py
"""

from __future__ import annotations

import math
import subprocess
import sys
import time
from pathlib import Path

from timing import best_of  # benchmarks/timing.py

from archquake.geometry import Arch
from archquake.geometry.loads import Fill, Loads, Traffic
from archquake.limit.capacity import capacity_scan

BRIDGE = ["--radius", "5", "--thickness", "0.6", "--embrace", "180", "--voussoirs", "15",
          "--density", "1800"]
EXE = str(Path(sys.executable).with_name("archquake"))


def _process(argv: list[str], repeat: int = 3) -> float:
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run([EXE, *argv], check=True, capture_output=True)
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> dict:
    bare = _process(["static", *BRIDGE, "--json"])
    fill = _process(["static", *BRIDGE, "--fill-depth", "1", "--json"])
    arch = Arch(5.0, 0.6, math.pi, 15, 1.0, 1800.0)
    loads = Loads(fill=Fill(depth=0.5))
    traffic = Traffic(100e3, 0.0, dispersion=26.57)
    capacity_scan(arch, loads, traffic, 50)  # warm scipy's import and the LP
    scan = best_of(lambda: capacity_scan(arch, loads, traffic, 50), 3, 1)
    cli = _process(["capacity", *BRIDGE, "--fill-depth", "0.5", "--axle", "100",
                    "--dispersion", "26.57", "--json"])
    print("archquake static, whole process (the bridge, 15 voussoirs)")
    print(f"  bare                  {bare:7.3f} s")
    print(f"  with 1 m of fill      {fill:7.3f} s   {fill / bare:4.2f} x (target <= 2)")
    print("traffic capacity, 50 positions")
    print(f"  library scan          {scan:7.3f} s   (target <= 2)")
    print(f"  archquake capacity    {cli:7.3f} s   whole process")
    return {"static_bare_s": bare, "static_fill_s": fill, "scan_s": scan, "capacity_cli_s": cli}


if __name__ == "__main__":
    main()
