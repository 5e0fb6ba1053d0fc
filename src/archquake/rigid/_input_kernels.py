"""The rigid chain's ground input, compiled: the steps' mean ground accelerations of a sampled
record and the verdict's suffix maxima.

Both give the same bits as their NumPy expressions (`archquake.rigid.model.mean_acceleration`
on any motion, ``np.maximum.accumulate`` on the reversed steps), which the digests of the
verdicts rest on; tests/rigid/test_input_kernels.py holds them to those expressions over every
record of a suite and random records. They release the GIL, so a thread pool prepares a
history in the thread that runs it.

* `step_means` evaluates each sub-sample with the compiled evaluator of a sampled motion
  (`archquake.ground._kernel.sampled_value`, the same arithmetic as
  `archquake.ground.Record.acceleration`) and sums a step's sub-samples in NumPy's own
  order (`numpy_sum`), then divides by their number, as ``ndarray.mean`` does.
* `suffix_maxima` is ``np.maximum`` folded from the last step back.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from archquake._kernel_cache import stamp_kernels
from archquake.ground._kernel import sampled_value

stamp_kernels()  # the cache checks each kernel against every source compiled into it

#: The block of NumPy's pairwise summation: a sum of up to this many terms is one block of
#: eight partial sums (NumPy's ``PW_BLOCKSIZE``).
PAIRWISE_BLOCK = 128


@nb.njit(cache=True, nogil=True)
def numpy_sum(values, count):
    """The sum of ``values[:count]`` (count <= `PAIRWISE_BLOCK`) in the order of
    ``np.add.reduce`` over a contiguous row: fewer than 8 terms one after another from 0.0;
    else eight partial sums ``r[j] = v[j] + v[j + 8] + ...`` over the whole blocks of eight,
    combined as ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7)), then the remainder one
    after another; and the reduction's start 0.0 added to the result."""
    if count < 8:
        res = 0.0
        for i in range(count):
            res += values[i]
        return 0.0 + res
    r0 = values[0]
    r1 = values[1]
    r2 = values[2]
    r3 = values[3]
    r4 = values[4]
    r5 = values[5]
    r6 = values[6]
    r7 = values[7]
    i = 8
    whole = count - count % 8
    while i < whole:
        r0 += values[i]
        r1 += values[i + 1]
        r2 += values[i + 2]
        r3 += values[i + 3]
        r4 += values[i + 4]
        r5 += values[i + 5]
        r6 += values[i + 6]
        r7 += values[i + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < count:
        res += values[i]
        i += 1
    return 0.0 + res


@nb.njit(cache=True, nogil=True)
def step_means(params, t0, h, sub_samples, out):
    """The mean ground acceleration of each of ``out.size`` steps of ``h`` s from ``t0`` s,
    m/s^2, into ``out``: ``sub_samples`` mid-point sub-samples a step (at
    t0 + h (k + (j + 1/2) / sub_samples)), averaged.

    Each sub-sample is the sampled evaluator's (`archquake.ground._kernel.sampled_value`,
    the arithmetic of `archquake.ground.Record.acceleration`); the fractions (j + 1/2) /
    sub_samples are computed once, and a step that starts after the record's last sample
    is 0 (the mean of zeros) without evaluating it: the same numbers, bit for bit, in about
    half the time.

    Parameters
    ----------
    params : ndarray
        A sampled motion's ``kernel_spec()`` parameters ``[t0, dt, x_0, ..., x_{N-1}]``.
    t0, h : float
        Start and step, s.
    sub_samples : int
        Sub-samples a step (at most `PAIRWISE_BLOCK`).
    out : ndarray (n,)
    """
    values = np.empty(sub_samples)
    frac = np.empty(sub_samples)
    for j in range(sub_samples):
        frac[j] = (j + 0.5) / sub_samples
    n = params.shape[0] - 2
    end = params[0] + params[1] * (n - 1)  # the last sample's time
    for k in range(out.size):
        if t0 + h * (k + frac[0]) > end:
            out[k] = 0.0
            continue
        for j in range(sub_samples):
            values[j] = sampled_value(params, 0, n, t0 + h * (k + frac[j]))
        out[k] = numpy_sum(values, sub_samples) / sub_samples


@nb.njit(cache=True, nogil=True)
def suffix_maxima(acc, pos, neg):
    """The largest ground acceleration towards +x (``pos``) and towards -x (``neg``, a
    magnitude) from each step to the last, m/s^2, at least 0, into ``pos`` and ``neg``.

    ``np.maximum(a, b)`` is ``a if a > b else b`` (of two zeros, the second, as NumPy's
    on x86; the verdict only compares these values, so the sign of a zero does not matter)."""
    run_pos = 0.0
    run_neg = 0.0
    for k in range(acc.size - 1, -1, -1):
        a = acc[k]
        p = a if a > 0.0 else 0.0
        m = -a
        q = m if m > 0.0 else 0.0
        if k == acc.size - 1:
            run_pos = p
            run_neg = q
        else:
            run_pos = run_pos if run_pos > p else p
            run_neg = run_neg if run_neg > q else q
        pos[k] = run_pos
        neg[k] = run_neg
