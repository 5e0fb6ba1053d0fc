"""Benchmark (issue 12): arches of other shapes cost what the circular arch costs.

- the limit analysis (static LP) of a 200-voussoir semicircle on piers (4 m x 1.5 m, 8 courses
  each: 216 blocks), target < 1 s, beside the bare 200-voussoir circular arch;
- one 4 s time history of a pointed arch and of an arch on piers against the circular arch's
  (the same compiled kernel: the four-link mechanism only needs the links' masses, centroids,
  inertias and hinge points), target within 2x.

Run: .venv/bin/python benchmarks/bench_shapes.py
"""

from __future__ import annotations

import math

from timing import best_of  # benchmarks/timing.py

from archquake.geometry import Arch, OnPiers, Piers, pointed
from archquake.ground import StepImpulse
from archquake.limit import limit_analysis
from archquake.mechanism import PreparedMechanism, SolverOptions, simulate


def main() -> dict:
    circ200 = Arch(5.0, 0.75, math.pi, 200)
    piers200 = OnPiers(circ200, Piers(4.0, 1.5, 8))
    limit_analysis(circ200)  # warm the LP
    t_circ = best_of(lambda: limit_analysis(Arch(5.0, 0.75, math.pi, 200)), 3, 1)
    # a fresh chain each time: the block geometry is built inside the timing
    t_piers = best_of(lambda: limit_analysis(OnPiers(Arch(5.0, 0.75, math.pi, 200),
                                                     Piers(4.0, 1.5, 8))), 3, 1)
    lam_piers = limit_analysis(piers200).collapse_acceleration_g

    no_history = SolverOptions(output_interval=0.0)
    arches = {
        "circular (Oppenheim)": Arch(10.0, 1.5, math.radians(157.5), 7),
        "pointed, span 10 m, rise 7 m": pointed(span=10.0, rise=7.0, thickness=0.8, voussoirs=15),
        "semicircle on piers": OnPiers(Arch(5.0, 0.75, math.pi, 15), Piers(4.0, 1.5, 3)),
    }
    times = {}
    for name, arch in arches.items():
        prepared = PreparedMechanism.build(arch)
        motion = StepImpulse.from_g(2.0 * prepared.collapse_acceleration_g, 0.20)
        simulate(prepared, motion, t_end=4.0)  # compile / load the cache
        times[name] = best_of(lambda p=prepared, m=motion: simulate(p, m, t_end=4.0,
                                                                   options=no_history), 5, 100)
    base = times["circular (Oppenheim)"]
    print("limit analysis (static LP), 200 voussoirs")
    print(f"  circular arch                 {t_circ * 1e3:8.1f} ms")
    print(f"  on piers (216 blocks)         {t_piers * 1e3:8.1f} ms   lambda {lam_piers:.4f} g  "
          f"(target < 1000 ms)")
    print("one 4 s time history (a = 2 lambda, t_p = 0.2 s), no stored history")
    for name, t in times.items():
        print(f"  {name:<30s}{t * 1e3:8.3f} ms   {t / base:5.2f} x the circular arch's (target <= 2)")
    return {"limit_piers_s": t_piers, "limit_circular_s": t_circ,
            "history_ratio": {k: v / base for k, v in times.items()}}


if __name__ == "__main__":
    main()
