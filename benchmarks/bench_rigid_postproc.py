"""Benchmark: the rigid chain's post-processing (the samples -> BlockResult path,
``rigid_chain._samples_to_run``, and the verdict sweeps read), against main's per-sample
and per-joint code (:mod:`archquake.blocks._result_reference`) measured in the same run, on the
4 s history of bench_rigid_chain.py (Oppenheim's arch, step 1.0 g, t_p 0.20 s, h 1e-4 s,
output every 5e-4 s: 8001 samples), then rigid_to_verdict's whole call against its stepping.

Run: PYTHONPATH=src .venv/bin/python benchmarks/bench_rigid_postproc.py  (about 10 s)
"""

from __future__ import annotations

import math
import time
from dataclasses import fields

import numpy as np
from timing import best_of  # benchmarks/timing.py

from archquake.blocks import _result_reference as REF
from archquake.blocks import result as R
from archquake.geometry import Arch
from archquake.ground import StepImpulse
from archquake.rigid import run as RC
from archquake.rigid.run import rigid_to_verdict


def main() -> dict:
    arch = Arch(10.0, 1.5, math.radians(157.5), 7)
    motion = StepImpulse.from_g(1.0, 0.20)
    model = RC.RigidModel.build(arch)
    RC.simulate_rigid(model, motion, duration=0.05)  # compile / load the cache
    seen: dict = {}
    inner = RC._samples_to_run

    def spy(model, motion, settings, got, **kw):
        seen.update({f.name: getattr(got, f.name) for f in fields(got)}, settings=settings,
                    integrated=got, keywords=kw)
        return inner(model, motion, settings, got, **kw)

    RC._samples_to_run = spy  # type: ignore[assignment]
    try:
        run = RC.simulate_rigid(model, motion, duration=4.0)
    finally:
        RC._samples_to_run = inner  # type: ignore[assignment]
    samples = dict(seen)
    settings = samples.pop("settings")
    got, keywords = samples.pop("integrated"), samples.pop("keywords")
    res = run
    asm, pos, t = res.assembly, res.positions, res.times
    q, v = samples["q"], samples["v"]
    ug, vg = samples["ground_displacement"], samples["ground_velocity"]
    call = best_of(lambda: RC.simulate_rigid(model, motion, duration=4.0), 3)
    rows = [
        ("states (absolute)",
         lambda: RC.absolute_states(model, q, v, ug, vg),
         lambda: np.array([REF.absolute(model, a, b, u, w) for a, b, u, w in zip(q, v, ug, vg)])),
        ("joint_kinematics", lambda: R.joint_kinematics(asm, pos),
         lambda: REF.joint_kinematics(asm, pos)),
        ("collapse_time", lambda: R.collapse_time(asm, res.criteria, t, pos),
         lambda: REF.collapse_time(asm, res.criteria, t, pos)),
        ("crossings", lambda: R.crossings(t, res.rotation, res.criteria.hinge_opening),
         lambda: REF.crossings(t, res.rotation, res.criteria.hinge_opening)),
        ("hinge_sets (to_dict)", lambda: R.hinge_sets(res), lambda: REF.hinge_sets(res)),
    ]
    out = {"stepping_s": run.wall_s, "call_s": call}
    print(f"one 4 s rigid history, Oppenheim's arch, step 1.0 g, t_p 0.20 s: {t.size} samples")
    print(f"  stepping (RigidRun.wall_s) {run.wall_s * 1e3:8.1f} ms; whole simulate_rigid "
          f"{call * 1e3:8.1f} ms")
    print("  part                       new (ms)  main's code (ms)  ratio")
    for name, new, plain in rows:
        a, b = best_of(new), best_of(plain, 3)
        out[name] = (a, b)
        print(f"  {name:26s} {a * 1e3:8.2f}  {b * 1e3:16.2f}  {b / a:6.1f}")
    post = best_of(lambda: inner(model, motion, settings, got, **keywords))
    fs = best_of(lambda: run.to_dict(joint_forces=False))
    out.update(samples_to_result_s=post, to_dict_s=fs)
    print(f"  _samples_to_run (states, energies, BlockResult.from_samples) {post * 1e3:7.2f} ms")
    print(f"  RigidRun.to_dict(joint_forces=False), as sweeps call it        {fs * 1e3:7.2f} ms")
    t0 = time.perf_counter()
    verdict = rigid_to_verdict(arch, motion)
    whole = time.perf_counter() - t0
    out["verdict_s"] = (whole, verdict.wall_s)
    print(f"rigid_to_verdict ({verdict.times.size} samples, {verdict.outcome.value}): "
          f"{whole * 1e3:.1f} ms, stepping {verdict.wall_s * 1e3:.1f} ms, the rest "
          f"{(whole - verdict.wall_s) * 1e3:.1f} ms")
    return out


if __name__ == "__main__":
    main()
