"""Benchmark: what a record's vertical component costs, in every model, against the same history
without it, measured in the same run.

The motion: a synthetic near-field record (examples/near_field_vertical.py's MP-1.2s, PGA
0.45 g, 4.7 s at 0.005 s) on Oppenheim's arch (R 10 m, t 1.5 m, 157.5 deg, 7 voussoirs), once
alone and once with a vertical component of 1e-9 times the script's (V/H 0.8e-9): the same
history to 1e-9, so the ratio is the price of reading the vertical (the compiled kernels'
second component, the union of breakpoints, gravity g + a_v in every evaluation), not of a
different motion. Each model: CPU time, the median of paired repeats (alternating with and
without, the least disturbed measure on shared cores):

* the rigid chain's verdict path (`rigid_verdict`, its default step, 8 s window);
* the rigid chain's time stepper (`simulate_rigid`, 1e-4 s, 6 s);
* the rigid chain's event integrator (`simulate_rigid(..., solver="events")`, 6 s);
* the four-link model (`simulate`, t_end 8 s);
* the DEM (`simulate_dem`, 3 s, the default contacts).

Run: PYTHONPATH=src .venv/bin/python benchmarks/bench_vertical.py  (a few minutes)
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
from near_field_vertical import near_field  # noqa: E402

from archquake.dem import DemSettings, simulate_dem  # noqa: E402
from archquake.geometry import Arch  # noqa: E402
from archquake.ground import Record  # noqa: E402
from archquake.ground.vertical import WithVertical  # noqa: E402
from archquake.mechanism import simulate  # noqa: E402
from archquake.rigid import rigid_verdict, simulate_rigid  # noqa: E402


def paired(run, plain, up, repeats: int) -> tuple[float, float]:
    """Median CPU seconds of ``run(plain)`` and ``run(up)``, alternated ``repeats`` times."""
    run(plain), run(up)  # compile / load the caches
    a, b = [], []
    for _ in range(repeats):
        for motion, out in ((plain, a), (up, b)):
            c0 = time.process_time()
            run(motion)
            out.append(time.process_time() - c0)
    return float(np.median(a)), float(np.median(b))


def main() -> None:
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    h, both = near_field("MP-1.2s", 1.2, 2.2, 0.0, pga_g=0.45)
    tiny = WithVertical(h, Record(1e-9 * both.vertical.accelerations, h.dt, name="tiny-UP"))
    cases = (
        ("rigid verdict path", lambda m: rigid_verdict(arch, m, duration=8.0, guard=False), 9),
        ("rigid time stepper", lambda m: simulate_rigid(arch, m, duration=6.0,
                                                        time_step=1e-4), 3),
        ("rigid events", lambda m: simulate_rigid(arch, m, duration=6.0, solver="events"), 3),
        ("four-link", lambda m: simulate(arch, m, t_end=8.0), 15),
        ("DEM", lambda m: simulate_dem(arch, m, DemSettings(duration=3.0)), 3),
    )
    print(f"{h.name}: {h.points} samples at {h.dt:g} s; with a vertical of 1e-9 x V/H 0.8")
    print(f"{'model':20s} {'without (s)':>12s} {'with (s)':>10s} {'ratio':>7s}")
    for name, run, repeats in cases:
        plain, up = paired(run, h, tiny, repeats)
        print(f"{name:20s} {plain:12.4f} {up:10.4f} {up / plain:7.3f}")


if __name__ == "__main__":
    main()
