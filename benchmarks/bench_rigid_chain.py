"""Benchmark: the rigid-block chain (issue 16, `mechanism.rigid_chain`) against the four-link
kernel (`simulate`) on the same 4 s history as bench_history.py (Oppenheim's arch, a = 1.0 g,
t_p = 0.20 s), and against the DEM (`simulate_dem`, the paper's stiffness), measured in the same
run. The rigid chain is compiled (numba) already; the numbers say what a batched domain would
cost with it.

Run: .venv/bin/python benchmarks/bench_rigid_chain.py
"""

from __future__ import annotations

import math
import time

from archquake.dem import simulate_dem
from archquake.dem.settings import DemSettings
from archquake.geometry import Arch
from archquake.ground import StepImpulse
from archquake.mechanism import PreparedMechanism, SolverOptions, simulate
from archquake.mechanism.rigid_chain import simulate_rigid


def best_of(fn, repeat: int, number: int) -> float:
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t0) / number)
    return best


def main() -> dict:
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    prepared = PreparedMechanism.build(arch)
    motion = StepImpulse.from_g(1.0, 0.20)
    quiet = SolverOptions(output_interval=0.0)
    simulate(prepared, motion, t_end=4.0)
    simulate_rigid(arch, motion, duration=0.05)  # compile / load the cache
    four = best_of(lambda: simulate(prepared, motion, t_end=4.0, options=quiet), 3, 50)
    out = {"four_link_s": four}
    print("one 4 s history, Oppenheim's arch, step a = 1.0 g, t_p = 0.20 s")
    print(f"  four-link kernel (simulate)        {four * 1e3:9.3f} ms")
    for h, tol in ((2e-4, 1e-11), (1e-4, 1e-11), (5e-5, 1e-11), (1e-4, 1e-9)):
        rigid = best_of(lambda h=h, tol=tol: simulate_rigid(
            arch, motion, duration=4.0, time_step=h, output_interval=5e-3,
            solver_tolerance=tol), 1, 2)
        out[f"rigid_{h:g}_{tol:g}_s"] = rigid
        print(f"  rigid chain, h = {h:g} s, tol {tol:g}  {rigid * 1e3:9.1f} ms  "
              f"({rigid / four:6.0f} x)")
    dem = best_of(lambda: simulate_dem(arch, motion, DemSettings().with_(duration=4.0)), 1, 1)
    out["dem_s"] = dem
    print(f"  DEM, paper's stiffness             {dem * 1e3:9.1f} ms  ({dem / four:8.0f} x)")
    return out


if __name__ == "__main__":
    main()
