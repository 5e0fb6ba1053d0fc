"""Benchmark: the distinct-element runs of the example bridge's assessment (``archquake assess
examples/bridge.toml``: semicircle R 5 m, t 0.6 m, 15 voussoirs, density 1800 kg/m^3, the
paper's stiffness and damping, 2.09e-6 s steps), with the contact search's broad phase
(``simulate_dem``'s default) against the exhaustive scan of every corner against every edge
(``broad_phase=False``), measured in the same run. The two give the same numbers bit for bit
(checked here); the exhaustive scan is the contact search before the broad phase, in today's
compiled loop (the step's parts were also inlined into the loop, which this ratio does not
show).

The runs are the quick assessment's two DEM checks: the step pulse (0.108 g, t_p 0.182 s, over
t_p + 3 s) and the governing record (KOCAELI-IZT_270 scaled to 0.0925 g), here over its first
8 s (the assessment runs it to 18.9 s).

CPU time (``time.process_time``), one run each after a compiling run: on shared cores CPU time
is steadier than wall time.

Run: .venv/bin/python benchmarks/bench_dem_bridge.py  (about 30 s)
"""

from __future__ import annotations

import math
import time

from archquake.dem import DemSettings, simulate_dem
from archquake.geometry import Arch
from archquake.ground.pulses import StepImpulse
from archquake.ground.suites import load_suite


def _cpu(fn):
    c0 = time.process_time()
    out = fn()
    return out, time.process_time() - c0


def main() -> None:
    arch = Arch(radius=5.0, thickness=0.6, embrace=math.pi, voussoirs=15, density=1800)
    record = load_suite("near-field-pulse").records[21]  # KOCAELI-IZT_270
    cases = [
        ("step pulse 0.108 g, t_p 0.182 s", StepImpulse.from_g(0.1084, 0.182, -1), 3.182),
        (f"record {record.name} at 0.0925 g", record.scaled(0.0925 / 0.219541), 8.0),
    ]
    simulate_dem(arch, cases[0][1], DemSettings(duration=0.01))  # compile / load the cache
    simulate_dem(arch, cases[0][1], DemSettings(duration=0.01), broad_phase=False)
    print("bridge arch (15 voussoirs), DEM at the paper's stiffness: CPU s per run")
    print(f"  {'run':38s} {'steps':>9s} {'broad phase':>12s} {'exhaustive':>11s} {'ratio':>6s}"
          f" {'us/step':>8s}  same bits")
    for name, motion, duration in cases:
        settings = DemSettings(duration=duration)
        fast, t_fast = _cpu(lambda: simulate_dem(arch, motion, settings))  # noqa: B023
        slow, t_slow = _cpu(lambda: simulate_dem(arch, motion, settings,  # noqa: B023
                                                 broad_phase=False))
        same = all(getattr(fast, k).tobytes() == getattr(slow, k).tobytes()
                   for k in ("times", "positions", "velocities", "kinetic", "strain"))
        steps = fast.n_steps + fast.settle_steps
        print(f"  {name:38s} {steps:9d} {t_fast:12.2f} {t_slow:11.2f} {t_slow / t_fast:6.2f}"
              f" {t_fast / steps * 1e6:8.2f}  {same}")


if __name__ == "__main__":
    main()
