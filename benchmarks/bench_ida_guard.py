"""Benchmark: what the rigid chain's half-step guard costs an incremental dynamic analysis.

The bridge example (semicircle R = 5 m, t = 0.6 m, 15 voussoirs) under the quick assessment's
four near-field records (PGA, 5 % brackets, fill 25 %, ceiling 5 g), all in one run, CPU time of
the process (``time.process_time``, both threads: it holds on a loaded machine):

* the IDA as it runs, its deciding levels guarded (:func:`archquake.ida.analysis.deciding_levels`);
* the same IDA unguarded (``CaseOptions(guard=False)``): the plain reference;
* the verdicts of every level of that IDA with the per-verdict guard
  (:func:`archquake.rigid.rigid_verdicts`, ``guard=True``) against the same verdicts unguarded:
  what guarding every verdict would cost on these levels.

Needs the FEMA suites (``pip install 'archquake[records]'``). Run:

    .venv/bin/python benchmarks/bench_ida_guard.py
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

from archquake.ground.suites import load_suite
from archquake.ida import incremental_dynamic_analysis
from archquake.rigid import rigid_verdicts
from archquake.sweeps import ArchSpec, CaseOptions, ResultStore

BRIDGE = ArchSpec(radius=5.0, thickness_ratio=0.12, embrace_deg=180, voussoirs=15, density=1800)


def _ida(records, options: CaseOptions):
    with tempfile.TemporaryDirectory() as tmp, ResultStore(Path(tmp) / "ida.sqlite") as store:
        c0 = time.process_time()
        res = incremental_dynamic_analysis(BRIDGE, records, "pga", store, options=options,
                                           precision=0.05, fill=0.25)
        return res, time.process_time() - c0


def main() -> None:
    suite = load_suite("near-field-pulse").records
    records = tuple(suite[int(k * len(suite) / 4)] for k in range(4))
    rigid_verdicts(BRIDGE.build(), [records[0].scaled(0.01)])  # compile outside the timings
    guarded, cpu_guarded = _ida(records, CaseOptions())
    plain, cpu_plain = _ida(records, CaseOptions(guard=False))
    motions = [rec.scaled(float(f)) for r, rec in zip(plain.records, records, strict=True)
               for f in r.factors]
    arch = BRIDGE.build()
    c0 = time.process_time()
    every = rigid_verdicts(arch, motions, guard=True)
    cpu_every = time.process_time() - c0
    c0 = time.process_time()
    rigid_verdicts(arch, motions, guard=False)
    cpu_raw = time.process_time() - c0
    print(f"bridge, 4 near-field records, {guarded.total} levels (unguarded: {plain.total})")
    print(f"IDA, deciding levels guarded ({guarded.guarded} reruns): {cpu_guarded:.1f} s CPU; "
          f"unguarded {cpu_plain:.1f} s; ratio {cpu_guarded / cpu_plain:.2f}")
    print(f"first collapses guarded   {[round(float(x), 4) for x in guarded.first_collapse_levels]}")
    print(f"first collapses unguarded {[round(float(x), 4) for x in plain.first_collapse_levels]}")
    reruns = sum(v.guard_ran for v in every)
    print(f"the unguarded IDA's {len(motions)} levels with every verdict guarded ({reruns} "
          f"reruns): {cpu_every:.1f} s CPU; unguarded {cpu_raw:.1f} s; ratio "
          f"{cpu_every / cpu_raw:.2f}")


if __name__ == "__main__":
    main()
