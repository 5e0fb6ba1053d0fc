"""Benchmark: the rigid chain with Coulomb joints (``friction=0.6``) on the bridge example
(semicircle R 5 m, t 0.6 m, 15 voussoirs, density 1800), run to a verdict at the verdict's
step (``rigid_to_verdict``, what ``archquake assess`` runs for its sliding check): the default
solver (the exact no-slip solve, kept where every joint sticks; Gauss-Seidel with the Coulomb
clamp only where a joint slips) against the clamped Gauss-Seidel at every step
(``solver="pgs"``, the plain reference), both measured in this run. Cases: the near-field
record IMPVALL-H-E06_233 unscaled, and a step and a sine pulse of 0.15 g whose joints reach
the cone. CPU time of the process (``time.process_time``: the kernel is single-threaded, and
CPU time is less disturbed by other load than wall time), kernels compiled before timing.

Run: PYTHONPATH=src .venv/bin/python benchmarks/bench_friction.py  (about a minute)
"""

from __future__ import annotations

import math
import time

from archquake.geometry import Arch
from archquake.ground.pulses import SinePulse, StepImpulse
from archquake.ground.suites import load_suite
from archquake.rigid.run import rigid_to_verdict
from archquake.rigid.verdict import verdict_time_step

MU = 0.6


def cpu(arch, motion, h, solver) -> tuple[float, object]:
    """CPU time of one run to a verdict, s, and the run."""
    t0 = time.process_time()
    run = rigid_to_verdict(arch, motion, friction=MU, time_step=h, solver=solver)
    return time.process_time() - t0, run


def main() -> dict:
    arch = Arch(radius=5.0, thickness=0.6, embrace=math.pi, voussoirs=15, density=1800)
    h = verdict_time_step(arch)
    record = load_suite("near-field-pulse").records[0]
    cases = [(f"record {record.name} unscaled", record),
             ("step pulse 0.15 g, t_p = 0.126 s", StepImpulse.from_g(0.15, 0.1259, -1)),
             ("sine pulse 0.15 g, T = 0.316 s", SinePulse.from_g(0.15, 0.3165, -1))]
    for solver in ("direct", "pgs"):  # compile / load the cache
        rigid_to_verdict(arch, StepImpulse.from_g(0.15, 0.1, -1), friction=MU, time_step=h,
                         solver=solver)
    print(f"bridge, mu = {MU}, verdict step h = {h:.3g} s: CPU s per run to a verdict")
    out = {}
    for label, motion in cases:
        t_new, new = cpu(arch, motion, h, "direct")
        t_old, old = cpu(arch, motion, h, "pgs")
        out[label] = (t_old, t_new)
        print(f"  {label:40s} pgs {t_old:7.2f} s ({old.outcome.value}), default "
              f"{t_new:6.3f} s ({new.outcome.value}): {t_old / t_new:6.1f} times faster")
        print(f"  {'':40s} stepping alone: pgs {old.wall_s:7.2f} s, default {new.wall_s:6.3f} s "
              f"(wall): {old.wall_s / new.wall_s:6.1f} times faster")
    return out


if __name__ == "__main__":
    main()
