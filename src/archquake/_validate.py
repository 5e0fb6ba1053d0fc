"""Small input checks shared by every frozen dataclass: one line, the parameter, its range."""

from __future__ import annotations

import math
from numbers import Integral, Real

from archquake.errors import InvalidParameterError


def require_finite(name: str, value: object, unit: str = "") -> float:
    """Return ``value`` as a float, or raise naming ``name`` if it is not a finite number."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise InvalidParameterError(f"{name} must be a number{_u(unit)}, got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise InvalidParameterError(f"{name} must be a finite number{_u(unit)}, got {value!r}")
    return v


def require_positive(name: str, value: object, unit: str = "") -> float:
    """A finite number > 0."""
    v = require_finite(name, value, unit)
    if v <= 0.0:
        raise InvalidParameterError(f"{name} must be > 0{_u(unit)}, got {v:g}")
    return v


def require_range(
    name: str,
    value: object,
    low: float,
    high: float,
    unit: str = "",
    *,
    low_open: bool = True,
    high_open: bool = True,
    shown: str | None = None,
) -> float:
    """A finite number inside (low, high), with open or closed ends as given.

    ``shown`` replaces the printed range when it reads better in the user's units.
    """
    v = require_finite(name, value, unit)
    ok_low = v > low if low_open else v >= low
    ok_high = v < high if high_open else v <= high
    if not (ok_low and ok_high):
        rng = shown or f"{'(' if low_open else '['}{low:g}, {high:g}{')' if high_open else ']'}"
        raise InvalidParameterError(f"{name} must be in {rng}{_u(unit)}, got {v:g}")
    return v


def require_int(name: str, value: object, minimum: int, maximum: int | None = None) -> int:
    """An integer >= minimum (and <= maximum when given)."""
    if isinstance(value, bool) or not isinstance(value, Integral):
        if isinstance(value, Real) and float(value).is_integer():
            value = int(float(value))
        else:
            raise InvalidParameterError(f"{name} must be a whole number, got {value!r}")
    v = int(value)
    if v < minimum or (maximum is not None and v > maximum):
        hi = f" and <= {maximum}" if maximum is not None else ""
        raise InvalidParameterError(f"{name} must be >= {minimum}{hi}, got {v}")
    return v


def _u(unit: str) -> str:
    return f" ({unit})" if unit else ""
