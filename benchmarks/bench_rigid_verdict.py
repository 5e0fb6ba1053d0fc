"""Benchmark: the rigid chain's verdict path (`rigid.verdict`) against plain references
measured in the same run.

1. One 4 s history of Oppenheim's arch (R 10 m, t 1.5 m, 157.5 deg, 7 voussoirs; step 1.0 g,
   t_p = 0.20 s) at the verdict's default step (1.0e-3 s): the verdict alone
   (``rigid_verdict(..., duration=4.0, guard=False)``) against the four-link kernel
   (``simulate``, the same history; wall time best of rounds, and CPU time, the median of 11
   paired repeats, with the time per computed step) and against the recorded run at the same
   step (``simulate_rigid``, samples and the DEM's post-processing); then the same verdict run
   to its end (proven rest) with the guard.
2. The bridge (semicircle R 5 m, t 0.6 m, 15 voussoirs: 48 contact rows against Oppenheim's
   24) under five FEMA near-field records scaled to a PGA of 0.11 g, one verdict at a time on
   one thread, guard off (``rigid_verdicts(arch, [m], threads=1, guard=False)``): CPU time per
   history (median of 5) and per computed step, against Oppenheim's step measured above;
   then the same records' step means alone (a verdict's preparation, in the thread that runs
   it), compiled against the NumPy expression they equal bit for bit.
3. The Figure 5 domain under the rigid chain (step pulses, 12 durations 0.1-1.5 s, the block
   models' search: 0.01 g brackets, pulse + 6 sqrt(R/g)) through ``dem_failure_domain(...,
   model="rigid")`` (batches of verdicts, threaded over the usable cores), against the same
   search on one thread, against the recorded run at the old default step (1e-4 s) timed
   on a sample of the search's runs and extrapolated to their number, and against the
   four-link model's batch in the same search (``failure_domain(..., settings=
   DEM_DOMAIN_SETTINGS)``: the same brackets and magnitudes, its runs to rest): the pace of a
   sweep users run, where item 1 compares one history over a fixed window.

Run: PYTHONPATH=src .venv/bin/python benchmarks/bench_rigid_verdict.py  (a minute or two)
"""

from __future__ import annotations

import math
import os
import time

import numpy as np
from timing import best_of  # benchmarks/timing.py

from archquake.compare.domains import dem_failure_domain
from archquake.geometry import Arch
from archquake.ground import StepImpulse
from archquake.mechanism import PreparedMechanism, SolverOptions, simulate
from archquake.rigid import simulate_rigid
from archquake.rigid.verdict import rigid_verdict, verdict_time_step

SAMPLE = int(os.environ.get("BENCH_REFERENCE_SAMPLE", "4"))


def history() -> dict:
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    motion = StepImpulse.from_g(1.0, 0.20)
    h = verdict_time_step(arch)
    prepared = PreparedMechanism.build(arch)
    quiet = SolverOptions(output_interval=0.0)
    simulate(prepared, motion, t_end=4.0)
    rigid_verdict(arch, motion, duration=4.0)  # compile / load the cache
    simulate_rigid(arch, motion, duration=0.05, time_step=h)
    four = best_of(lambda: simulate(prepared, motion, t_end=4.0, options=quiet), 5, 10)
    verdict = best_of(lambda: rigid_verdict(arch, motion, duration=4.0, guard=False), 5, 2)
    # CPU time, median of paired repeats (the least disturbed measure on shared cores)
    verdict_cpus, four_cpus = [], []
    for _ in range(11):
        c0 = time.process_time()
        v4 = rigid_verdict(arch, motion, duration=4.0, guard=False)
        verdict_cpus.append(time.process_time() - c0)
        c0 = time.process_time()
        for _ in range(10):
            simulate(prepared, motion, t_end=4.0, options=quiet)
        four_cpus.append((time.process_time() - c0) / 10)
    verdict_cpu, four_cpu = float(np.median(verdict_cpus)), float(np.median(four_cpus))
    recorded = best_of(lambda: simulate_rigid(arch, motion, duration=4.0, time_step=h), 3, 1)
    full = rigid_verdict(arch, motion)
    to_end = best_of(lambda: rigid_verdict(arch, motion), 3, 1)
    print(f"one 4 s history, Oppenheim's arch, step 1.0 g, t_p 0.20 s, h = {h:.4g} s")
    print(f"  four-link kernel (simulate)               {four * 1e3:8.2f} ms  "
          f"(CPU median {four_cpu * 1e3:.3f} ms)")
    print(f"  rigid verdict (4 s, no guard)             {verdict * 1e3:8.2f} ms  "
          f"{verdict / four:6.1f} x four-link (CPU median {verdict_cpu * 1e3:.2f} ms, "
          f"{verdict_cpu / four_cpu:.1f} x four-link's CPU; {v4.steps} steps computed: "
          f"{verdict_cpu / max(v4.steps, 1) * 1e6:.2f} us a step; targets: 5 ms and 10 x "
          "four-link)")
    print(f"  recorded rigid run (simulate_rigid, 4 s)  {recorded * 1e3:8.2f} ms  "
          f"verdict {recorded / verdict:5.1f} x faster")
    print(f"  rigid verdict to its end ({full.outcome.value}, {full.end_time_s:.2f} s, guard "
          f"{'ran' if full.guard_ran else 'not needed'})  {to_end * 1e3:8.2f} ms")
    return {"four_link_s": four, "verdict_s": verdict, "recorded_s": recorded,
            "to_end_s": to_end, "verdict_cpu_s": verdict_cpu, "four_link_cpu_s": four_cpu,
            "step_cpu_s": verdict_cpu / max(v4.steps, 1)}


#: The bridge's records (indices in the FEMA near-field pulse suite) and their PGA, g.
BRIDGE_RECORDS = (0, 4, 14, 20, 26)
BRIDGE_PGA_G = 0.11


def bridge(oppenheim_step_s: float) -> dict:
    from archquake.ground.measures import im_value
    from archquake.ground.suites import load_suite
    from archquake.rigid import rigid_verdicts

    arch = Arch(5.0, 0.6, math.pi, 15)
    records = load_suite("near-field-pulse").records
    motions = [records[i].scaled(BRIDGE_PGA_G / im_value(records[i], "pga"))
               for i in BRIDGE_RECORDS]
    rigid_verdicts(arch, motions[:1], threads=1, guard=False)  # compile / load the cache
    print(f"the bridge (R 5 m, t 0.6 m, 15 voussoirs), near-field records at "
          f"{BRIDGE_PGA_G} g, one thread, guard off (CPU, median of 5; the jobs' preparation "
          "included, as in Oppenheim's):")
    steps, cpu = 0, 0.0
    for i, m in zip(BRIDGE_RECORDS, motions):
        cpus = []
        for _ in range(5):
            c0 = time.process_time()
            v = rigid_verdicts(arch, [m], threads=1, guard=False)[0]
            cpus.append(time.process_time() - c0)
        c = float(np.median(cpus))
        steps += v.steps
        cpu += c
        print(f"  {records[i].name:22s} {v.outcome.value:9s} {c * 1e3:8.1f} ms  "
              f"{v.steps:6d} steps  {c / max(v.steps, 1) * 1e6:6.2f} us a step")
    per_step = cpu / max(steps, 1)
    print(f"  all five                          {cpu * 1e3:8.1f} ms  {steps:6d} steps  "
          f"{per_step * 1e6:6.2f} us a step, {per_step / oppenheim_step_s:.1f} x Oppenheim's "
          f"step (twice the rows)")
    means, plain = step_means(motions, verdict_time_step(arch))
    print(f"  the five records' step means (a verdict's preparation), compiled {means * 1e3:6.1f} ms, "
          f"NumPy's expression {plain * 1e3:6.1f} ms: {plain / means:4.1f} x faster")
    return {"bridge_cpu_s": cpu, "bridge_step_cpu_s": per_step, "step_means_cpu_s": means,
            "step_means_numpy_cpu_s": plain}


def step_means(motions, h: float) -> tuple[float, float]:
    """CPU time, s (median of 5), of the steps' mean ground accelerations of ``motions`` over
    their whole duration plus the verdict's tail, compiled (`rigid.model.mean_acceleration`),
    and of the NumPy expression it equals bit for bit (every sub-sample through
    ``Record.acceleration``, then ``mean``)."""
    from archquake.rigid.model import ACC_SAMPLES, mean_acceleration

    sub = (np.arange(ACC_SAMPLES) + 0.5) / ACC_SAMPLES
    ns = [int(math.ceil((m.duration + 6.0) / h)) for m in motions]

    def compiled() -> list:
        return [mean_acceleration(m, 0.0, h, n) for m, n in zip(motions, ns, strict=True)]

    def numpy() -> list:
        return [m.acceleration((h * (np.arange(n)[:, None] + sub[None, :])).ravel())
                .reshape(n, ACC_SAMPLES).mean(1) for m, n in zip(motions, ns, strict=True)]

    for a, b in zip(compiled(), numpy(), strict=True):
        assert np.array_equal(a, b), "the compiled step means left NumPy's bits"
    times = []
    for fn in (compiled, numpy):
        cpus = []
        for _ in range(5):
            c0 = time.process_time()
            fn()
            cpus.append(time.process_time() - c0)
        times.append(float(np.median(cpus)))
    return times[0], times[1]


def domain() -> dict:
    from archquake.compare.histories import VOUSSOIRS, dem_assembly
    from archquake.dem import DemSettings
    from archquake.domains import PulseFamily
    from archquake.domains.blocks import DOMAIN_TAIL, block_pulse_outcome

    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    durations = tuple(np.round(np.geomspace(0.1, 1.5, 12), 3))
    cores = len(os.sched_getaffinity(0))
    dem_failure_domain(arch, "step", (0.3,), model="rigid", workers=1)  # compile
    t0, c0 = time.perf_counter(), time.process_time()
    dom = dem_failure_domain(arch, "step", durations, model="rigid", workers=cores)
    threaded, cpu = time.perf_counter() - t0, time.process_time() - c0
    t0 = time.perf_counter()
    dem_failure_domain(arch, "step", durations, model="rigid", workers=1)
    single = time.perf_counter() - t0
    # the recorded run at the old default step, on a sample of (magnitude, duration) pairs
    rng = np.random.default_rng(5)
    asm = dem_assembly(arch, VOUSSOIRS)
    tail = DOMAIN_TAIL * math.sqrt(arch.radius / 9.80665)
    pairs = [(float(rng.uniform(0.4, 1.5)), float(rng.choice(durations))) for _ in range(SAMPLE)]
    t0 = time.perf_counter()
    for a, d in pairs:
        block_pulse_outcome(asm, PulseFamily.STEP.value, a, d, DemSettings(), tail, False,
                            9.80665, model="rigid")
    per_run = (time.perf_counter() - t0) / SAMPLE
    plain = per_run * dom.runs
    print(f"Figure 5 domain, rigid chain, {len(durations)} durations, {dom.runs} runs:")
    print(f"  batches of verdicts, {cores} threads      {threaded:8.2f} s  "
          f"(CPU {cpu:.2f} s over all threads: the wall time on idle cores is about "
          f"{cpu / cores:.2f} s; target 1 s on 2 cores)")
    print(f"  the same, one thread                     {single:8.2f} s  "
          f"threads {single / threaded:4.2f} x faster")
    print(f"  recorded runs at h = 1e-4 s (sampled)    {plain:8.2f} s  "
          f"({per_run:.2f} s a run)  verdicts {plain / threaded:5.1f} x faster")
    from archquake.compare.domains import DEM_DOMAIN_SETTINGS
    from archquake.domains import failure_domain

    failure_domain(arch, "step", durations, settings=DEM_DOMAIN_SETTINGS)  # compile / load
    t0, c0 = time.perf_counter(), time.process_time()
    four = failure_domain(arch, "step", durations, settings=DEM_DOMAIN_SETTINGS)
    four_s, four_cpu = time.perf_counter() - t0, time.process_time() - c0
    print(f"  four-link model, the same search         {four_s:8.2f} s  (CPU {four_cpu:.2f} s, "
          f"{four.evaluations} runs): the rigid chain takes {threaded / four_s:4.2f} x its time")
    return {"domain_s": threaded, "domain_one_thread_s": single, "domain_recorded_s": plain,
            "domain_four_link_s": four_s}


def main() -> dict:
    out = history()
    out.update(bridge(out["step_cpu_s"]))
    out.update(domain())
    return out


if __name__ == "__main__":
    main()
