"""Compiled evaluation of any ground motion from its ``(kind, params)`` description."""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from archquake._kernel_cache import stamp_kernels
from archquake.ground.base import KIND_SAMPLED, KIND_SAMPLED_VERTICAL, KIND_SINE, KIND_STEP

stamp_kernels()  # the cache checks each kernel against every source compiled into it


@nb.njit(cache=True, nogil=True)
def sampled_value(params, start, n, t):
    """A sampled block's value at ``t``: ``params[start:start + 2]`` = [t0, dt], then its ``n``
    samples; linear between samples, 0 outside [t0, t0 + (n-1) dt]."""
    t0, dt = params[start], params[start + 1]
    if t < t0 or t > t0 + dt * (n - 1):  # outside [t0, ground_duration]: at rest
        return 0.0
    s = (t - t0) / dt
    i = int(math.floor(s))
    if i >= n - 1:
        return params[start + 2 + n - 1]
    f = s - i
    return (1.0 - f) * params[start + 2 + i] + f * params[start + 3 + i]


@nb.njit(cache=True, nogil=True)
def _sampled_in_piece(params, start, n, t, t_left):
    """A sampled block's value at ``t`` continued over the piece that contains ``t_left``."""
    t0, dt = params[start], params[start + 1]
    s = (t_left - t0) / dt
    if s < -1e-9 or s >= n - 1 - 1e-9:
        return 0.0
    i = int(math.floor(s + 1e-9))
    if i < 0:
        i = 0
    f = (t - (t0 + i * dt)) / dt
    return (1.0 - f) * params[start + 2 + i] + f * params[start + 3 + i]


@nb.njit(cache=True, nogil=True)
def _sampled_next(params, start, n, t, eps):
    """A sampled block's smallest sample time strictly after ``t`` (inf past its end)."""
    t0, dt = params[start], params[start + 1]
    end = t0 + dt * (n - 1)
    if t + eps < t0:
        return t0
    if t + eps >= end:
        return math.inf
    i = int(math.floor((t - t0) / dt + 1e-9))
    b = t0 + (i + 1) * dt
    if b <= t + eps:
        b += dt
    return min(b, end)


@nb.njit(cache=True, nogil=True)
def _vertical_block(params):
    """Start and sample count of the vertical block of a ``KIND_SAMPLED_VERTICAL`` spec."""
    start = 3 + int(params[0])
    return start, params.shape[0] - start - 2


@nb.njit(cache=True, nogil=True)
def ground_acceleration(kind: int | np.integer, params: np.ndarray, t: float) -> float:
    """x_g''(t), m/s^2, for the motion described by ``(kind, params)``."""
    if kind == KIND_STEP or kind == KIND_SINE:
        return ground_in_piece(kind, params, t, t)  # the pulses' one definition
    if kind == KIND_SAMPLED_VERTICAL:
        return sampled_value(params, 1, int(params[0]), t)
    if kind != KIND_SAMPLED:
        raise ValueError("unknown ground-motion kind")
    # sampled, linear between samples (written out as in ground_in_piece)
    t0, dt = params[0], params[1]
    n = params.shape[0] - 2
    if t < t0 or t > t0 + dt * (n - 1):  # outside [t0, ground_duration]: at rest
        return 0.0
    s = (t - t0) / dt
    i = int(math.floor(s))
    if i >= n - 1:
        return params[2 + n - 1]
    f = s - i
    return (1.0 - f) * params[2 + i] + f * params[3 + i]


@nb.njit(cache=True, nogil=True)
def ground_duration(kind: int, params: np.ndarray) -> float:
    """Time after which x_g'' is identically zero, s."""
    if kind == KIND_STEP:
        return 3.0 * params[1]
    if kind == KIND_SINE:
        return params[1]
    if kind == KIND_SAMPLED:
        return params[0] + params[1] * (params.shape[0] - 3)
    if kind != KIND_SAMPLED_VERTICAL:
        raise ValueError("unknown ground-motion kind")
    n = int(params[0])
    start, m = _vertical_block(params)
    return max(params[1] + params[2] * (n - 1), params[start] + params[start + 1] * (m - 1))


@nb.njit(cache=True, nogil=True)
def ground_in_piece(kind, params, t, t_left):
    """x_g''(t) continued over the whole piece that contains ``t_left`` (so that the last stage
    of a step ending on a breakpoint sees the left limit, not the next piece's value)."""
    if kind == KIND_STEP:
        a, tp, direction = params[0], params[1], params[2]
        if t_left < 0.0:
            return 0.0
        if t_left < tp:
            return direction * a
        if t_left < 3.0 * tp:
            return -0.5 * direction * a
        return 0.0
    if kind == KIND_SINE:
        a, period, direction = params[0], params[1], params[2]
        if t_left < 0.0 or t_left >= period:
            return 0.0
        return direction * a * math.sin(2.0 * math.pi * t / period)
    if kind == KIND_SAMPLED_VERTICAL:
        return _sampled_in_piece(params, np.int64(1), int(params[0]), t, t_left)
    # a record, written out rather than through _sampled_in_piece: this is the integrators'
    # innermost call (the four-link model on a record measured up to 9 % slower through the
    # helpers)
    t0, dt = params[0], params[1]
    n = params.shape[0] - 2
    s = (t_left - t0) / dt
    if s < -1e-9 or s >= n - 1 - 1e-9:
        return 0.0
    i = int(math.floor(s + 1e-9))
    if i < 0:
        i = 0
    f = (t - (t0 + i * dt)) / dt
    return (1.0 - f) * params[2 + i] + f * params[3 + i]


@nb.njit(cache=True, nogil=True)
def vertical_in_piece(kind, params, t, t_left):
    """The upward ground acceleration a_v(t), m/s^2, like `ground_in_piece`: a pulse's
    vertical part R a s(t) (R its fourth parameter, when present) plus its steady vertical c
    (its fifth, held through the whole run); a record's vertical component, linear between its
    own samples and 0 outside them, continued over its piece that contains ``t_left``; else 0."""
    if (kind == KIND_STEP or kind == KIND_SINE) and params.shape[0] > 3:
        return params[3] * params[2] * ground_in_piece(kind, params, t, t_left) + params[4]
    if kind == KIND_SAMPLED_VERTICAL:
        start, m = _vertical_block(params)
        return _sampled_in_piece(params, start, m, t, t_left)
    return 0.0


@nb.njit(cache=True, nogil=True)
def next_breakpoint(kind, params, t):
    """Smallest breakpoint of the excitation strictly after ``t`` (inf if none)."""
    eps = 1e-12 * (1.0 + abs(t))
    if kind == KIND_STEP:
        tp = params[1]
        for b in (0.0, tp, 3.0 * tp):
            if b > t + eps:
                return b
        return math.inf
    if kind == KIND_SINE:
        period = params[1]
        for q in range(5):
            b = 0.25 * q * period
            if b > t + eps:
                return b
        return math.inf
    if kind == KIND_SAMPLED_VERTICAL:  # the union of both components' sample times
        start, m = _vertical_block(params)
        return min(_sampled_next(params, np.int64(1), int(params[0]), t, eps),
                   _sampled_next(params, start, m, t, eps))
    t0, dt = params[0], params[1]  # a record, written out as in ground_in_piece
    n = params.shape[0] - 2
    end = t0 + dt * (n - 1)
    if t + eps < t0:
        return t0
    if t + eps >= end:
        return math.inf
    i = int(math.floor((t - t0) / dt + 1e-9))
    b = t0 + (i + 1) * dt
    if b <= t + eps:
        b += dt
    return min(b, end)


def evaluate(kind: int, params: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Vectorised convenience wrapper of `ground_acceleration` (for tests and plots)."""
    t = np.atleast_1d(np.asarray(t, dtype=float))
    return np.array([ground_acceleration(kind, params, float(x)) for x in t])


def evaluate_vertical(kind: int, params: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Vectorised `vertical_in_piece` at each time's own piece (for tests and plots)."""
    t = np.atleast_1d(np.asarray(t, dtype=float))
    return np.array([vertical_in_piece(kind, params, float(x), float(x)) for x in t])
