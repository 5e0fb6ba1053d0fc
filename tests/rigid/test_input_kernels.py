"""The rigid chain's compiled ground input (:mod:`archquake.rigid._input_kernels`) against the
NumPy expressions it replaces, to the bit, and the verdicts' threads against single runs.

Oracles:

* a step's mean ground acceleration: the ``ACC_SAMPLES`` mid-point sub-samples of every step
  through :meth:`Record.acceleration` (NumPy; a sine pulse's through its own), then
  ``ndarray.mean`` (:func:`plain_means`, the expression
  :func:`~archquake.rigid.model.mean_acceleration` evaluated before it was compiled).
  Compared bit for bit (as integers): the verdicts' digests (tests/test_digest.py) rest on
  these numbers, so no tolerance;
* NumPy's own sum (``np.add.reduce`` along a row) for :func:`numpy_sum`, bit for bit, every
  count it takes;
* ``np.maximum.accumulate`` over the reversed steps (the largest ground acceleration from a
  step to the end, which the verdict's rest test compared with the safe domain's bounds) for
  :func:`last_at_least`: the same test at every step; and :func:`last_at_least` over all the
  means for :func:`record_last_at_least`, which computes a few of them;
* the verdicts with every step's mean computed before the run, for the verdicts whose kernel
  computes a record's means as the run reaches them, field for field;
* each history alone, for the threaded verdicts: a history's numbers do not depend on which
  thread runs it, nor when.
"""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from archquake.constants import STANDARD_GRAVITY as G
from archquake.geometry import Arch
from archquake.ground.pulses import SinePulse
from archquake.ground.records import Record
from archquake.ground.suites import load_suite
from archquake.rigid._input_kernels import (
    PAIRWISE_BLOCK,
    last_at_least,
    numpy_sum,
    record_last_at_least,
    sub_fractions,
)
from archquake.rigid.model import ACC_SAMPLES, mean_acceleration
from archquake.rigid.verdict import rigid_verdict, rigid_verdicts, verdict_time_step

#: The example bridge (R 5 m, t 0.6 m, a semicircle of 15 voussoirs): its verdict step.
BRIDGE = Arch(5.0, 0.6, math.pi, 15)
OPPENHEIM = Arch(10.0, 1.5, math.radians(157.5), 7)


def plain_means(motion, t0: float, h: float, n: int) -> np.ndarray:
    """The oracle: every sub-sample, evaluated by NumPy, then ``mean``."""
    sub = (np.arange(ACC_SAMPLES) + 0.5) / ACC_SAMPLES
    t = t0 + h * (np.arange(n)[:, None] + sub[None, :])
    return np.asarray(motion.acceleration(t.ravel()), dtype=float).reshape(
        n, ACC_SAMPLES).mean(1)


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    return a.shape == b.shape and np.array_equal(a.view(np.int64), b.view(np.int64))


@pytest.fixture(scope="module")
def suite_records():
    return load_suite("near-field-pulse").records


def test_step_means_of_every_suite_record_are_numpys(suite_records):
    """Every record of the FEMA P695 near-field set (28), scaled as the bridge's IDA scales
    them (to 0.11 g, and mirrored at 0.4 g: a factor not a power of 2, so its rounding shows),
    at the bridge's verdict step and the guard's half step, over the record and 2 s after
    its end (the zeros after it); a coarse step (larger than dt, straddling samples) and a
    start inside the record (as the recorded run's chunks start) on every fourth."""
    h = verdict_time_step(BRIDGE)
    for k, rec in enumerate(suite_records):
        peak_g = rec.peak / G
        for motion, step in ((rec.scaled(0.11 / peak_g), h),
                             (rec.scaled(-0.4 / peak_g), 0.5 * h)):
            n = int(math.ceil((rec.duration + 2.0) / step))
            assert same_bits(mean_acceleration(motion, 0.0, step, n),
                             plain_means(motion, 0.0, step, n)), (rec.name, step)
        if k % 4 == 0:
            motion = rec.scaled(0.37 / peak_g)
            for t0, step in ((0.0, 0.0123), (3.217, h)):
                n = int(math.ceil((rec.duration + 2.0 - t0) / step))
                assert same_bits(mean_acceleration(motion, t0, step, n),
                                 plain_means(motion, t0, step, n)), (rec.name, t0, step)


samples = st.lists(st.one_of(st.floats(-50.0, 50.0), st.just(0.0), st.just(-0.0),
                             st.floats(-1e-300, 1e-300), st.floats(-1e6, 1e6)),
                   min_size=2, max_size=60)


@given(samples, st.floats(1e-3, 0.05), st.floats(1e-4, 0.07), st.floats(-0.2, 1.0),
       st.integers(1, 400))
@settings(max_examples=200, deadline=None)
def test_step_means_of_random_records_are_numpys(x, dt, h, t0, n):
    """Random records (zeros of both signs, subnormal-scale and large samples), steps finer
    and coarser than dt, starts before, inside and after the record."""
    rec = Record(x, dt)
    assert same_bits(mean_acceleration(rec, t0, h, n), plain_means(rec, t0, h, n))


@given(st.floats(0.01, 3.0), st.floats(0.01, 2.0), st.sampled_from([-1, 1]),
       st.floats(1e-4, 0.07), st.floats(-0.5, 3.0), st.integers(1, 3000))
@settings(max_examples=200, deadline=None)
def test_step_means_of_sine_pulses_are_numpys(period, a_g, direction, h, t0, n):
    """A sine pulse sub-samples only the steps before its period end; the rest are the mean
    of its zeros: the same bits as every sub-sample through NumPy, steps straddling the
    period's end, starts before the pulse and after it included."""
    motion = SinePulse.from_g(a_g, period, direction)
    assert same_bits(mean_acceleration(motion, t0, h, n), plain_means(motion, t0, h, n))


@pytest.mark.parametrize("count", [1, 2, 7, 8, 9, 15, ACC_SAMPLES, 17, 24, 63, 64, 100,
                                   PAIRWISE_BLOCK])
def test_numpy_sum_is_numpys_order(count):
    """Rows of random magnitudes (1e-8 to 1e8, so the order of the additions shows in the
    last bits) and rows of negative zeros: the sum of each row as ``np.add.reduce``."""
    rng = np.random.default_rng(count)
    rows = rng.standard_normal((400, count)) * 10.0 ** rng.integers(-8, 9, (400, count))
    rows[:3] = -0.0
    want = np.add.reduce(rows, axis=1)
    got = np.array([numpy_sum(np.ascontiguousarray(r), count) for r in rows])
    assert same_bits(got, want)


def test_the_numpy_sum_differs_from_a_plain_loop():
    """The test above can fail: on these rows a left-to-right sum differs from NumPy's in the
    last bits."""
    rng = np.random.default_rng(1)
    rows = rng.standard_normal((400, ACC_SAMPLES)) * 10.0 ** rng.integers(-8, 9,
                                                                         (400, ACC_SAMPLES))
    loop = np.zeros(len(rows))
    for j in range(ACC_SAMPLES):  # one term after another
        loop = loop + rows[:, j]
    assert not same_bits(loop, np.add.reduce(rows, axis=1))


@given(st.lists(st.one_of(st.floats(-10.0, 10.0), st.just(0.0), st.just(-0.0), st.just(2.5)),
                min_size=1, max_size=200),
       st.sampled_from([2.5, 1.0, 1e-9, 0.0, -1.0]))
@settings(max_examples=300, deadline=None)
def test_the_last_step_at_least_is_the_suffix_maxima_test(values, lim):
    """A chain at rest at step k stays when the largest acceleration from k to the end, each
    at least 0 (``np.maximum.accumulate``), is below the bound, both ways: exactly when k is
    past `last_at_least`'s step. Bounds equal to some steps, at 0 and below."""
    acc = np.array(values, dtype=float)
    pos = np.maximum.accumulate(np.maximum(acc, 0.0)[::-1])[::-1]
    neg = np.maximum.accumulate(np.maximum(-acc, 0.0)[::-1])[::-1]
    k = np.arange(acc.size)
    assert np.array_equal(k > last_at_least(acc, lim, 1.0), pos < lim)
    assert np.array_equal(k > last_at_least(acc, lim, -1.0), neg < lim)


@given(samples, st.floats(1e-3, 0.05), st.floats(1e-4, 0.07), st.floats(-0.2, 1.0),
       st.integers(1, 400), st.integers(0, 59), st.sampled_from([1.0, -1.0]),
       st.sampled_from([1.0, 1.0 + 1e-15, 1.0 - 1e-15, 0.9, 0.5, 1.1]))
@settings(max_examples=400, deadline=None)
def test_the_last_step_at_least_is_found_from_the_samples(x, dt, h, t0, n, pick, sign, factor):
    """`record_last_at_least` computes only the means next to the samples that could reach
    the bound; oracle: `last_at_least` over every mean (`mean_acceleration`). Random records,
    bounds at a sample's value (and a bit off it, where the interpolation's rounding
    decides), at a step's own mean, and where no step reaches."""
    rec = Record(x, dt)
    spec = rec.kernel_spec()[1]
    means = mean_acceleration(rec, t0, h, n)
    frac, values = sub_fractions(ACC_SAMPLES), np.empty(ACC_SAMPLES)
    bounds = [sign * x[pick % len(x)] * factor, sign * means[pick % n] * factor, 1e300]
    for lim in bounds:
        assert (record_last_at_least(spec, t0, h, frac, values, n, lim, sign)
                == last_at_least(means, lim, sign)), lim


def test_record_verdicts_computing_their_means_as_they_go_are_the_whole_means(suite_records,
                                                                                monkeypatch):
    """A record's run computes its steps' means as it reaches them, and finds the last steps
    reaching the safe domain from the samples. Oracle: the same verdicts with every mean
    computed before the run (the path of any other motion), field for field: the loaded
    bridge under a third of the near-field records at levels that collapse it, leave it
    standing, and prove its rest early."""
    import archquake.rigid.verdict as V
    from archquake.geometry.loads import Fill, Loads
    from archquake.ida.batch import rigid_body

    body = rigid_body(Arch(5.0, 0.6, math.pi, 15, density=1800.0),
                      Loads(fill=Fill(depth=1.0, density=1800.0)))
    motions = [r.scaled(level * G / r.peak) for r in suite_records[::3]
               for level in (0.15, 0.3, 0.6)]
    durations = [min(m.duration, 12.0) + 3.0 for m in motions]
    lazy = V.rigid_verdicts(body, motions, duration=durations, threads=2)
    monkeypatch.setattr(V, "Record", type("NotARecord", (), {}))  # every mean first
    whole = V.rigid_verdicts(body, motions, duration=durations, threads=2)
    assert [v.to_dict() for v in lazy] == [v.to_dict() for v in whole]
    assert {v.outcome.value for v in lazy} >= {"collapse", "survives"}


def test_threaded_record_verdicts_are_the_single_runs(suite_records):
    """Oracle: each history alone (one thread). Seven records of the near-field set on
    Oppenheim's arch at 0.8 g (onset 0.37 g: collapses and survivals, four of them rerun by
    the guard), their order reversed and on two threads: the
    jobs run longest first and the guard's reruns join the queue as their first runs end, so
    they finish in another order than the motions'; the verdicts come back in the motions'
    order, to the bit. Short windows (5 s after each record) keep it quick."""
    recs = suite_records[::4]
    motions = [r.scaled(0.8 * G / r.peak) for r in recs]
    durations = [r.duration + 5.0 for r in recs]
    batch = rigid_verdicts(OPPENHEIM, motions[::-1], duration=durations[::-1], threads=2)
    single = [rigid_verdict(OPPENHEIM, m, duration=d) for m, d in zip(motions, durations)]
    assert [b.to_dict() for b in batch[::-1]] == [s.to_dict() for s in single]
    assert any(s.guard_ran for s in single)
    assert len({s.outcome for s in single}) >= 2


def test_the_verdict_path_does_not_import_the_four_link_model():
    """The default model's verdict path loads no module of ``archquake.mechanism`` (its import
    costs the default ``archquake run`` ~50 ms)."""
    code = ("import sys, archquake.rigid.verdict; "
            "print(sorted(m for m in sys.modules if m.startswith('archquake.mechanism')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "[]"
