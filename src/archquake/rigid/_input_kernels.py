"""The rigid chain's ground input, compiled: the steps' mean ground accelerations of a sampled
record, and the last steps reaching the verdict's safe domain.

Both give the same bits as their NumPy expressions (`archquake.rigid.model.mean_acceleration`
on any motion, ``np.maximum.accumulate`` on the reversed steps), which the digests of the
verdicts rest on; tests/rigid/test_input_kernels.py holds them to those expressions over every
record of a suite and random records. They release the GIL, so a thread pool prepares a
history in the thread that runs it.

* `step_means` evaluates each sub-sample with the compiled evaluator of a sampled motion
  (`archquake.ground._kernel.sampled_value`, the same arithmetic as
  `archquake.ground.Record.acceleration`) and sums a step's sub-samples in NumPy's own
  order (`numpy_sum`), then divides by their number, as ``ndarray.mean`` does.
* `last_at_least` is the verdict's rest test (the largest acceleration from a step to the
  end, ``np.maximum`` folded from the last step back, below a bound) as one step index, and
  `record_last_at_least` finds that index from a record's samples, computing only the means
  of the steps next to the samples that could reach the bound.
"""

from __future__ import annotations

import math

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
    frac = sub_fractions(sub_samples)
    values = np.empty(sub_samples)
    for k in range(out.size):
        out[k] = step_mean(params, t0, h, frac, values, k)


@nb.njit(cache=True, nogil=True)
def sub_fractions(sub_samples):
    """The sub-samples' places in a step, (j + 1/2) / sub_samples, (sub_samples,)."""
    frac = np.empty(sub_samples)
    for j in range(sub_samples):
        frac[j] = (j + 0.5) / sub_samples
    return frac


@nb.njit(cache=True, nogil=True, inline="always")
def step_mean(params, t0, h, frac, values, k):
    """`step_means`'s mean of step ``k`` (``frac``: `sub_fractions`; ``values``: scratch of
    the same size), m/s^2: the same arithmetic, step by step."""
    sub_samples = frac.shape[0]
    n = params.shape[0] - 2
    if t0 + h * (k + frac[0]) > params[0] + params[1] * (n - 1):  # after the last sample
        return 0.0
    for j in range(sub_samples):
        values[j] = sampled_value(params, 0, n, t0 + h * (k + frac[j]))
    return numpy_sum(values, sub_samples) / sub_samples


@nb.njit(cache=True, nogil=True)
def step_means_into(params, t0, h, frac, values, out, k0, k1):
    """`step_means` of steps ``k0`` to ``k1 - 1`` into ``out[k0:k1]`` (the same numbers: each
    step's mean depends on its index alone), allocating nothing (``frac``: `sub_fractions`;
    ``values``: scratch of the same size)."""
    for k in range(k0, k1):
        out[k] = step_mean(params, t0, h, frac, values, k)


@nb.njit(cache=True, nogil=True)
def last_at_least(acc, lim, sign):
    """The last step k whose ``sign`` ``acc[k]`` is at least ``lim`` > 0 (-1: none), or
    ``acc.size`` if ``lim`` <= 0 (nothing is below it).

    A chain at rest from step k on stays so exactly when k is past this step for both
    directions: the largest accelerations from k to the end, each at least 0 (``np.maximum``
    folded from the last step back), are then below ``lim``."""
    if not lim > 0.0:
        return acc.size
    for k in range(acc.size - 1, -1, -1):
        if sign * acc[k] >= lim:
            return k
    return -1


#: A step's sub-samples are each at most the larger of the two samples they lie between, to
#: the rounding of the interpolation and of the sum (a few units in the last place): samples
#: below ``lim`` (1 - `SAMPLE_MARGIN`) cannot give a step mean of ``lim``.
SAMPLE_MARGIN = 1e-9


@nb.njit(cache=True, nogil=True)
def record_last_at_least(params, t0, h, frac, values, n_steps, lim, sign):
    """`last_at_least` of a sampled motion's first ``n_steps`` step means (`step_means`),
    computing only the means of the steps next to the samples that could reach ``lim``.

    A step mean of ``sign`` x >= ``lim`` needs a sample of ``sign`` x >= ``lim``
    (1 - `SAMPLE_MARGIN`) among those its sub-samples lie between (the means of zeros after
    the record are 0): so the samples are scanned from the last, and for each such sample the
    steps whose sub-samples can use it (two steps of slack either side) are computed, the
    latest first, down to the latest step found so far. The same index as `last_at_least` on
    all the means, without computing most of them."""
    if not lim > 0.0:
        return n_steps
    n = params.shape[0] - 2
    tr = params[0]
    dt = params[1]
    last = frac.shape[0] - 1
    thr = lim * (1.0 - SAMPLE_MARGIN)
    best = -1
    for i in range(n - 1, -1, -1):
        # the steps with a sub-sample between samples i - 1 and i + 1
        k_hi = int(math.ceil((tr + (i + 1) * dt - t0) / h - frac[0])) + 2
        if k_hi > n_steps - 1:
            k_hi = n_steps - 1
        if k_hi <= best:
            break  # every sample before gives steps no later than those found
        if not sign * params[2 + i] >= thr:
            continue
        k_lo = int(math.floor((tr + (i - 1) * dt - t0) / h - frac[last])) - 2
        if k_lo < best + 1:
            k_lo = best + 1
        for k in range(k_hi, k_lo - 1, -1):
            if sign * step_mean(params, t0, h, frac, values, k) >= lim:
                best = k
                break
    return best
