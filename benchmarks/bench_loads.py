"""Benchmark: what the loads cost in the statics.

- ``archquake static`` on the example bridge (R 5 m, t 0.6 m, 15 voussoirs) with 1 m of fill,
  whole process, beside the bare ``static`` (target: at most 2x);
- a 50-position traffic capacity scan of the same bridge with 0.5 m of fill and a dispersed
  axle, in the library and as the whole ``archquake capacity`` process (target: at most 2 s).

Run: .venv/bin/python benchmarks/bench_loads.py
"""

from __future__ import annotations

import math

from timing import BRIDGE_ARGS as BRIDGE  # benchmarks/timing.py
from timing import best_of
from timing import best_process as _process

from archquake.geometry import Arch
from archquake.geometry.loads import Fill, Loads, Traffic
from archquake.limit.capacity import capacity_scan


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
