"""Benchmark: one 4 s time history of Oppenheim's arch (paper Figure 4(d): a = 1.0 g, t_p = 0.20 s,
two impacts in the window), compiled kernel against a plain scipy.integrate.solve_ivp version
with a Python right-hand side, measured in the same run.

Target (issue 3): under 1 ms per history and at least 50 times faster than the plain version.
Run: .venv/bin/python benchmarks/bench_history.py
"""

from __future__ import annotations

import math

from timing import best_of  # benchmarks/timing.py

from archquake.geometry import Arch
from archquake.ground import StepImpulse
from archquake.mechanism import PreparedMechanism, SolverOptions, simulate
from archquake.mechanism.reference import simulate_reference


def main() -> dict:
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    prepared = PreparedMechanism.build(arch)
    motion = StepImpulse.from_g(1.0, 0.20)
    no_history = SolverOptions(output_interval=0.0)
    simulate(prepared, motion, t_end=4.0)  # compile / load the cache
    fast = best_of(lambda: simulate(prepared, motion, t_end=4.0, options=no_history), 5, 200)
    fast_hist = best_of(lambda: simulate(prepared, motion, t_end=4.0), 5, 100)
    plain = best_of(lambda: simulate_reference(prepared, motion, t_end=4.0, rtol=1e-9), 3, 3)
    r = simulate(prepared, motion, t_end=4.0)
    ref = simulate_reference(prepared, motion, t_end=4.0, rtol=1e-9)
    print("one 4 s time history, Oppenheim's arch, step a = 1.0 g, t_p = 0.20 s")
    print(f"  outcome {r.outcome.value}, impacts at {', '.join(f'{t:.4f}' for t in r.impact_times)} s "
          f"(reference: {', '.join(f'{t:.4f}' for t in ref.impact_times)} s)")
    print(f"  compiled kernel, no history      {fast * 1e3:8.3f} ms   ({r.stats['steps']} steps)")
    print(f"  compiled kernel, with history    {fast_hist * 1e3:8.3f} ms")
    print(f"  plain solve_ivp (DOP853, Python) {plain * 1e3:8.3f} ms   ({ref.rhs_evaluations} rhs calls)")
    print(f"  speed-up: {plain / fast:6.1f} x (no history), {plain / fast_hist:6.1f} x (with history)")
    print(f"  target: < 1 ms and >= 50 x -> {'met' if fast < 1e-3 and plain / fast >= 50 else 'NOT met'}")
    return {"fast_s": fast, "fast_history_s": fast_hist, "plain_s": plain}


if __name__ == "__main__":
    main()
