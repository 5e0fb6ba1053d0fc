"""Benchmark: a batch of record verdicts of the default model, against the same batch run as
the verdict path ran it before, measured in the same run.

The batch: the example bridge (``Arch(5.0, 0.6, pi, 15)``), the 28 FEMA P695 near-field
records each scaled to 0.11 g PGA (one level of the bridge's IDA), ``rigid_verdicts`` with the
guard on, on 2 threads.

* **The verdict path**: each record's step means computed by the kernel as the run reaches
  them, and the last steps reaching the safe domain's bounds found from the record's samples,
  in the thread that runs it, one history a task, the longest expected first, the guard's
  reruns queued as their first runs end.
* **The reference**, the same kernel and the same verdicts: every history's step means
  prepared whole with NumPy (:func:`plain_means`, then the bounds' last steps on them) in the
  calling thread, then the kernel over 4 x threads contiguous slices of the batch; then the
  guard's reruns, prepared and run the same way.

Printed: wall and CPU time (all threads), the median of paired repeats (``BENCH_REPEATS``,
default 3), and their ratios; then the preparation alone (28 histories at the verdict step),
CPU time: NumPy, all the means compiled, and the bounds' last steps from the samples alone.
Run: PYTHONPATH=src .venv/bin/python benchmarks/bench_records_verdicts.py  (about a minute on two idle cores).
"""

from __future__ import annotations

import math
import os
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import archquake.rigid._verdict_kernels as VK
import archquake.rigid.verdict as V
from archquake.blocks.criteria import BlockCriteria
from archquake.constants import STANDARD_GRAVITY
from archquake.geometry import Arch
from archquake.ground.suites import load_suite
from archquake.rigid import _input_kernels as IK
from archquake.rigid.model import ACC_SAMPLES, SOLVER_TOLERANCE, mean_acceleration

REPEATS = int(os.environ.get("BENCH_REPEATS", "3"))
THREADS = 2
LEVEL_G = 0.11


def plain_means(motion, t0: float, h: float, n: int) -> np.ndarray:
    """The steps' mean ground accelerations by NumPy: every sub-sample, then ``mean``."""
    sub = (np.arange(ACC_SAMPLES) + 0.5) / ACC_SAMPLES
    t = t0 + h * (np.arange(n)[:, None] + sub[None, :])
    return np.asarray(motion.acceleration(t.ravel()), dtype=float).reshape(
        n, ACC_SAMPLES).mean(1)


def rest_last(acc: np.ndarray, par: np.ndarray) -> np.ndarray:
    """The four last steps reaching the safe domain's bounds (`VK.REST_LAST`) of whole means."""
    pos, neg, margin = par[VK.P_SAFE_POS], par[VK.P_SAFE_NEG], par[VK.P_REST_MARGIN]
    bounds = (pos, neg, margin * pos, margin * neg)
    return np.array([IK.last_at_least(acc, lim, 1.0 if j % 2 == 0 else -1.0)
                     for j, lim in enumerate(bounds)], np.int64)


def reference(arch, motions, threads: int) -> list[str]:
    """The batch as it ran before (module docstring): the verdicts' outcomes."""
    settings = BlockCriteria()
    model = V.rigid_model(arch)
    packed = V._packed(model, settings)
    h = V.verdict_time_step(model)
    windows = [V.default_window(arch, m, STANDARD_GRAVITY) for m in motions]

    def run(step: float, which: list[int]) -> list[dict]:
        jobs = [V._Job(model, packed, motions[i], step, windows[i], None, settings,
                       STANDARD_GRAVITY, True, SOLVER_TOLERANCE) for i in which]
        accs = [plain_means(j.motion, 0.0, step, j.n) for j in jobs]
        starts = np.zeros(len(jobs) + 1, np.int64)
        starts[1:] = np.cumsum([a.size for a in accs])
        acc = np.concatenate(accs)
        hist = VK.Histories(acc, np.stack([rest_last(a, j.par) for a, j in zip(accs, jobs)]),
                            starts, np.stack([j.par for j in jobs]), np.empty(0), acc,
                            np.empty(0), np.zeros(len(jobs) + 1, np.int64))
        outs = np.zeros((len(jobs), VK.N_OUT))
        edges = np.unique(np.linspace(0, len(jobs), min(len(jobs), 4 * threads) + 1)
                          .astype(int))
        with ThreadPoolExecutor(threads) as pool:
            list(pool.map(lambda ab: VK.verdict_batch(packed.chain, packed.frame, hist, outs,
                                                      ab[0], ab[1]),
                          zip(edges[:-1], edges[1:])))
        found = []
        for k, acc in enumerate(accs):
            vg = np.cumsum(acc) * step
            found.append(V._decode(outs[k], step,
                                   lambda s, vg=vg: 0.0 if s < 0 else float(vg[s])))
        return found

    first = run(h, list(range(len(motions))))
    rerun = [i for i, d in enumerate(first) if V._near(d)]
    second = dict(zip(rerun, run(0.5 * h, rerun)))
    return [V._verdict(d, second.get(i), h, STANDARD_GRAVITY).outcome.value for i, d in enumerate(first)]


def timed(fn) -> tuple[float, float, object]:
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return time.perf_counter() - t0, time.process_time() - c0, out


def main() -> dict:
    arch = Arch(5.0, 0.6, math.pi, 15)
    records = load_suite("near-field-pulse").records
    motions = [r.scaled(LEVEL_G * STANDARD_GRAVITY / r.peak) for r in records]
    V.rigid_verdicts(arch, motions[:1], duration=1.0, threads=1)  # compile / load the cache
    new, old = [], []
    for _ in range(REPEATS):
        w, c, verdicts = timed(lambda: V.rigid_verdicts(arch, motions, threads=THREADS))
        new.append((w, c))
        w, c, outcomes = timed(lambda: reference(arch, motions, THREADS))
        old.append((w, c))
        if [v.outcome.value for v in verdicts] != outcomes:
            raise AssertionError("the reference's verdicts differ from the verdict path's")
    wall, cpu = np.median(new, axis=0)
    wall0, cpu0 = np.median(old, axis=0)
    load = os.getloadavg()[0]
    print(f"{len(motions)} near-field records, the example bridge, {LEVEL_G} g, guard on, "
          f"{THREADS} threads (median of {REPEATS}; load average {load:.1f}):")
    print(f"  verdict path                      wall {wall:6.2f} s  CPU {cpu:6.2f} s "
          f"({cpu / wall:.2f} cores)")
    print(f"  as before (NumPy preparation in the calling thread, contiguous slices)  "
          f"wall {wall0:6.2f} s  CPU {cpu0:6.2f} s  ->  {wall0 / wall:.2f} x wall, "
          f"{cpu0 / cpu:.2f} x CPU")
    # the preparation alone, at the verdict's step
    h = V.verdict_time_step(arch)
    ns = [int(math.ceil(V.default_window(arch, m, STANDARD_GRAVITY) / h - 1e-9))
          for m in motions]
    pars = [V._Job(V.rigid_model(arch), V._packed(V.rigid_model(arch), BlockCriteria()), m, h,
                   V.default_window(arch, m, STANDARD_GRAVITY), None, BlockCriteria(),
                   STANDARD_GRAVITY, True, SOLVER_TOLERANCE).par for m in motions]
    c0 = time.process_time()
    for m, n, par in zip(motions, ns, pars):
        rest_last(plain_means(m, 0.0, h, n), par)
    plain = time.process_time() - c0
    c0 = time.process_time()
    for m, n, par in zip(motions, ns, pars):
        rest_last(mean_acceleration(m, 0.0, h, n), par)
    compiled = time.process_time() - c0
    frac, values = IK.sub_fractions(ACC_SAMPLES), np.empty(ACC_SAMPLES)
    c0 = time.process_time()
    for m, n, par in zip(motions, ns, pars):
        bounds = (par[VK.P_SAFE_POS], par[VK.P_SAFE_NEG])
        for j, lim in enumerate(bounds + tuple(par[VK.P_REST_MARGIN] * b for b in bounds)):
            IK.record_last_at_least(m.kernel_spec()[1], 0.0, h, frac, values, n, lim,
                                    1.0 if j % 2 == 0 else -1.0)
    samples = time.process_time() - c0
    print(f"  preparation of the {len(motions)} histories at h = {h:.3g} s ({sum(ns)} steps): "
          f"NumPy CPU {plain:.2f} s, compiled {compiled:.3f} s  ->  {plain / compiled:.1f} x; "
          f"the bounds' last steps from the samples alone {samples:.4f} s")
    return {"batch_wall_s": float(wall), "batch_cpu_s": float(cpu),
            "reference_wall_s": float(wall0), "reference_cpu_s": float(cpu0),
            "prep_numpy_cpu_s": plain, "prep_compiled_cpu_s": compiled,
            "prep_samples_cpu_s": samples}


if __name__ == "__main__":
    main()
