"""Vectors in the plane of the arch: one meaning for each helper.

The arch lies in the x-y plane (x horizontal, y up); a rotation is counter-clockwise positive.
Every function works on the last axis of its arguments, so it takes one vector (shape (2,))
or a stack of them (shape (..., 2)).

Examples
--------
>>> import numpy as np
>>> perp(np.array([1.0, 0.0])).tolist(), float(cross(np.array([1.0, 0.0]), np.array([0.0, 2.0])))
([-0.0, 1.0], 2.0)
>>> np.round(rotation_matrix(np.pi / 2) @ np.array([1.0, 0.0]), 12).tolist()
[0.0, 1.0]
"""

from __future__ import annotations

import math

import numpy as np


def perp(v: np.ndarray) -> np.ndarray:
    """``v`` turned by +90 degrees, J v = (-v_y, v_x), shape of ``v``.

    The velocity of a point at ``r`` from a pivot turning at ``omega`` is ``omega perp(r)``;
    the moment of a force F at ``r`` is ``perp(r) . F`` (= `cross` (r, F))."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The z-component of the cross product, a_x b_y - a_y b_x, over the last axis (the moment
    of ``b`` at ``a``; > 0 if ``b`` turns counter-clockwise about the origin)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def rotation_matrix(angle: float) -> np.ndarray:
    """The 2 x 2 matrix of a counter-clockwise rotation by ``angle`` (rad)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


__all__ = ["cross", "perp", "rotation_matrix"]
