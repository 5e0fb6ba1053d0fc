"""Benchmark: the Figure 5 failure domain of Oppenheim's arch (step impulse, both boundaries,
40 durations t_p from 0.05 to 1.5 s, brackets of 0.001 g).

Prints the wall time of :func:`archquake.domains.failure_domain` (compiled, parallel batch with
the energy-proof early stop) and of the same batch without the early stop, against a plain loop
over :func:`archquake.mechanism.reference.simulate_reference` (scipy ``solve_ivp`` with a Python
right-hand side). The plain loop is timed on a random sample of the coarse scan's cases and
extrapolated per case to the number of time histories the search ran. Run:

    .venv/bin/python benchmarks/bench_domain.py
"""

from __future__ import annotations

import math
import os
import time

import numpy as np

from archquake.domains import DomainSettings, evaluate_pulses, failure_domain, oppenheim_arch
from archquake.ground import StepImpulse
from archquake.mechanism import PreparedMechanism
from archquake.mechanism.reference import simulate_reference

SAMPLE = int(os.environ.get("BENCH_REFERENCE_SAMPLE", "12"))


def main() -> None:
    arch = oppenheim_arch()
    prepared = PreparedMechanism.build(arch)
    durations = np.linspace(0.05, 1.5, 40)
    settings = DomainSettings()
    failure_domain(prepared, "step", durations[:2], settings=DomainSettings(coarse_points=4,
                                                                          fine_points=2))  # compile
    best = math.inf
    for _ in range(3):
        t0 = time.perf_counter()
        dom = failure_domain(prepared, "step", durations, settings=settings)
        best = min(best, time.perf_counter() - t0)
    n = dom.evaluations
    print(f"failure_domain (Figure 5, 40 durations, 0.001 g): {best:.3f} s, {n} time histories, "
          f"{best / n * 1e6:.0f} us each, numba threads: {os.environ.get('NUMBA_NUM_THREADS', 'all')}")

    # the same domain under the chain impact law, its post-impact mechanisms followed over the
    # reachable set (issue 10: within 2x of the paper law's); the law and its table are solved
    # once per arch (PreparedMechanism.build, .table), timed apart and with the domain
    t0 = time.perf_counter()
    chain = PreparedMechanism.build(arch, "chain")
    rows = chain.table.size
    t_build = time.perf_counter() - t0
    best_chain = math.inf
    for _ in range(3):
        t0 = time.perf_counter()
        dom_c = failure_domain(chain, "step", durations, settings=settings)
        best_chain = min(best_chain, time.perf_counter() - t0)
    print(f"failure_domain under the chain law ({rows} mechanisms followed): {best_chain:.3f} s, "
          f"{dom_c.evaluations} time histories (+ {t_build:.3f} s to solve the law and its table "
          f"once); "
          f"{(best_chain + t_build) / best:.2f}x the paper law's (target <= 2x)")

    # the coarse scan's cases, to sample the plain loop and the no-early-stop batch on
    lam = prepared.collapse_acceleration_g
    k = np.arange(1, settings.coarse_points + 1)
    coarse = lam * (settings.max_magnitude_g / lam) ** (k / settings.coarse_points)
    a_all, d_all = (x.ravel() for x in np.meshgrid(coarse, durations))
    t0 = time.perf_counter()
    evaluate_pulses(prepared, "step", a_all, d_all, early=True)
    t_early = time.perf_counter() - t0
    t0 = time.perf_counter()
    evaluate_pulses(prepared, "step", a_all, d_all, early=False)
    t_full = time.perf_counter() - t0
    print(f"coarse scan ({a_all.size} cases): batch {t_early:.3f} s with early stop, "
          f"{t_full:.3f} s running every case to rest ({t_full / t_early:.1f}x)")

    rng = np.random.default_rng(2007)
    pick = rng.choice(a_all.size, size=SAMPLE, replace=False)
    t0 = time.perf_counter()
    for i in pick:
        simulate_reference(prepared, StepImpulse.from_g(float(a_all[i]), float(d_all[i])), rtol=1e-9)
    per_case = (time.perf_counter() - t0) / SAMPLE
    t0 = time.perf_counter()
    evaluate_pulses(prepared, "step", a_all[pick], d_all[pick], early=False)
    per_case_batch = (time.perf_counter() - t0) / SAMPLE
    extrapolated = per_case * n
    print(f"plain solve_ivp loop: {per_case * 1e3:.1f} ms per case ({SAMPLE} sampled cases), "
          f"{extrapolated:.0f} s extrapolated to {n} cases")
    print(f"same sample, compiled batch run to rest: {per_case_batch * 1e3:.2f} ms per case "
          f"({per_case / per_case_batch:.0f}x)")
    print(f"ratio plain loop / failure_domain: {extrapolated / best:.0f}x (target: domain <= 2 s; "
          f"{'met' if best <= 2.0 else 'NOT met'})")


if __name__ == "__main__":
    main()
