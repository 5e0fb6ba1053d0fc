"""Distinct-element model speed: Oppenheim's arch, 3 s of motion at the paper's stiffness
(1e12 Pa/m) and damping (alpha = 6.28e-5, beta = 1.59e-4), a = 1 g, t_p = 0.20 s (survives,
so the whole 3 s are stepped).

Prints the wall time of the compiled run (compilation excluded: one warm-up run first), steps
per second, and the ratio against the plain-NumPy twin of the same step, measured in the same
run on a shorter stretch and extrapolated per step.

    .venv/bin/python benchmarks/bench_dem.py
"""

from __future__ import annotations

import math
import time

import numpy as np

from archquake.constants import STANDARD_GRAVITY
from archquake.dem import DemSettings, _kernels, _reference, build_arch_assembly, simulate_dem
from archquake.dem.run import _params, build_slots, neighbour_pairs, pack, stable_time_step
from archquake.geometry import Arch
from archquake.ground.pulses import StepImpulse


def main() -> None:
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    motion = StepImpulse.from_g(1.0, 0.20)
    settings = DemSettings(duration=3.0)
    simulate_dem(arch, motion, settings.with_(duration=0.01))  # compile / load the cache
    t0 = time.perf_counter()
    res = simulate_dem(arch, motion, settings)
    wall = time.perf_counter() - t0
    steps = res.n_steps + res.settle_steps
    rate = steps / wall

    # the NumPy reference, same assembly and time step, a few thousand steps
    asm = build_arch_assembly(arch)
    dt, _ = stable_time_step(asm, settings)
    pk = build_slots(pack(asm), neighbour_pairs(pack(asm), 0.4))
    par = _params(asm, settings, dt, STANDARD_GRAVITY)
    acc = np.zeros(_kernels.N_ACC)
    kind, gp = motion.kernel_spec()
    work = _kernels.scratch(pk)
    n_twin = 3000
    t1 = time.perf_counter()
    for n in range(n_twin):
        _reference.step(pk, par, acc, kind, gp, n * dt, True, False, work)
    twin_rate = n_twin / (time.perf_counter() - t1)

    print("Oppenheim's arch, 7 voussoirs, 3.0 s at k = 1e12 Pa/m, paper's Rayleigh damping")
    print(f"  time step            {res.time_step:.3e} s  (omega_max {res.omega_max:.0f} rad/s)")
    print(f"  steps                {steps} ({res.settle_steps} settling)")
    print(f"  wall time (numba)    {wall:.3f} s   outcome {res.outcome.value}")
    print(f"  steps per second     {rate:,.0f}")
    print(f"  NumPy reference      {twin_rate:,.0f} steps/s -> 3 s would take {steps / twin_rate:.0f} s")
    print(f"  speed-up             {rate / twin_rate:.0f} x")


if __name__ == "__main__":
    main()
