"""Benchmark: the rigid-block chain (issue 16, `rigid`) against the four-link
kernel (`simulate`) on the same 4 s history as bench_history.py (Oppenheim's arch, a = 1.0 g,
t_p = 0.20 s), and its exact active-set contact solve (``solver="direct"``, the default)
against the plain projected Gauss-Seidel stepper (``solver="pgs"``), both measured in this
run, at the three time steps of the convergence table; then the semicircle of the
migration table (R 5 m, t 0.9 m, n 15: 16 joints, where Gauss-Seidel is slowest) over its
first 1.5 s; then the event-driven integration of the same model (``solver="events"``,
`rigid.events`) against the direct stepper on these histories and on three 4.5 s
histories around Oppenheim's critical step duration, with the number of joint closures
each had to resolve; then the DEM (`simulate_dem`, the paper's stiffness) on Oppenheim's
history. All rigid solvers are compiled (numba) before timing.

Run: PYTHONPATH=src .venv/bin/python benchmarks/bench_rigid_chain.py  (about a minute)
"""

from __future__ import annotations

import math
import time

from timing import best_of  # benchmarks/timing.py

from archquake.dem import simulate_dem
from archquake.dem.settings import DemSettings
from archquake.geometry import Arch
from archquake.ground import StepImpulse
from archquake.mechanism import PreparedMechanism, SolverOptions, simulate
from archquake.rigid import RigidModel, simulate_rigid


def stepping(model, motion, duration, h, solver, repeat=2):
    """Best wall time of the stepping alone (``RigidRun.wall_s``) and of the whole call, s."""
    best_step = best_call = math.inf
    run = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        run = simulate_rigid(model, motion, duration=duration, time_step=h,
                             output_interval=5e-3, solver=solver)
        best_call = min(best_call, time.perf_counter() - t0)
        best_step = min(best_step, run.wall_s)
    return best_step, best_call, run


def main() -> dict:
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    prepared = PreparedMechanism.build(arch)
    motion = StepImpulse.from_g(1.0, 0.20)
    quiet = SolverOptions(output_interval=0.0)
    simulate(prepared, motion, t_end=4.0)
    model = RigidModel.build(arch)
    for solver in ("direct", "pgs"):  # compile / load the cache
        simulate_rigid(model, motion, duration=0.05, solver=solver)
    four = best_of(lambda: simulate(prepared, motion, t_end=4.0, options=quiet), 3, 50)
    out = {"four_link_s": four}
    print("one 4 s history, Oppenheim's arch, step a = 1.0 g, t_p = 0.20 s")
    print(f"  four-link kernel (simulate)              {four * 1e3:9.3f} ms")
    print("  rigid chain: stepping (whole call), ratio to the four-link kernel; direct / plain")
    for h in (2e-4, 1e-4, 5e-5):
        row = {}
        for solver in ("pgs", "direct"):
            s, c, run = stepping(model, motion, 4.0, h, solver)
            row[solver] = s
            out[f"rigid_{solver}_{h:g}_s"] = s
            print(f"  h = {h:g} s, {solver:6s}  {s * 1e3:8.1f} ms ({c * 1e3:8.1f} ms)  "
                  f"{s / four:7.0f} x four-link, {run.max_sweeps:4d} sweeps/solves at worst")
        print(f"  h = {h:g} s: direct is {row['pgs'] / row['direct']:5.2f} times faster "
              "than the plain Gauss-Seidel stepper")
    semi = RigidModel.build(Arch(5.0, 0.9, math.radians(180.0), 15))
    pulse = StepImpulse.from_g(0.5, 0.20)
    for solver in ("pgs", "direct"):
        simulate_rigid(semi, pulse, duration=0.05, solver=solver)
    sp = stepping(semi, pulse, 1.5, 1e-4, "pgs", repeat=1)[0]
    sd = stepping(semi, pulse, 1.5, 1e-4, "direct", repeat=1)[0]
    out.update(semi_pgs_s=sp, semi_direct_s=sd)
    print("semicircle R 5 m, t 0.9 m, n 15, step 0.5 g, t_p 0.20 s, 1.5 s at h = 1e-4 s:")
    print(f"  pgs {sp * 1e3:8.1f} ms, direct {sd * 1e3:8.1f} ms: {sp / sd:5.1f} times faster")
    print("event-driven rigid chain (solver='events') against the direct stepper (h = 1e-4 s):")
    cases = [("Oppenheim 1.0 g, t_p 0.20 s, 4 s", model, motion, 4.0),
             ("semicircle n 15, 0.5 g, t_p 0.20 s, 1.5 s", semi, pulse, 1.5)]
    cases += [(f"Oppenheim 1.0 g, t_p {tp:.3f} s, 4.5 s", model, StepImpulse.from_g(1.0, tp), 4.5)
              for tp in (0.25, 0.262, 0.27)]
    simulate_rigid(model, motion, duration=0.05, solver="events")
    for name, mdl, mot, dur in cases:
        se, ce, run = stepping(mdl, mot, dur, 1e-4, "events")
        sd = stepping(mdl, mot, dur, 1e-4, "direct", repeat=1)[0]
        closures = int(run.events["counters"][3])
        key = name.split(",")[0].split()[0].lower() + "_" + name.split("t_p ")[1].split()[0]
        out[f"events_{key}_s"] = se
        out[f"events_{key}_closures"] = closures
        print(f"  {name:42s} events {se * 1e3:7.1f} ms ({ce * 1e3:7.1f} ms whole call), direct "
              f"{sd * 1e3:7.1f} ms: {sd / se:5.2f} x faster; {closures:5d} closures "
              f"({se / max(closures, 1) * 1e6:6.1f} us each), "
              f"{len(run.events['windows_s']):3d} hand-overs to the stepper; {se / four:6.0f} x "
              "four-link")
    dem = best_of(lambda: simulate_dem(arch, motion, DemSettings().with_(duration=4.0)), 1, 1)
    out["dem_s"] = dem
    print(f"DEM on Oppenheim's history, paper's stiffness {dem * 1e3:9.1f} ms "
          f"({dem / four:8.0f} x four-link, {dem / out['rigid_direct_0.0001_s']:5.1f} x the "
          "direct rigid chain at 1e-4 s)")
    return out


if __name__ == "__main__":
    main()
