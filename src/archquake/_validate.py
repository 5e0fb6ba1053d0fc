"""Small input checks shared by every frozen dataclass and public function: one line, the
parameter, its range (from `archquake.ranges`)."""

from __future__ import annotations

import math
import os
from enum import Enum
from numbers import Integral, Real
from pathlib import Path
from typing import Any, TypeVar

import numpy as np

from archquake.errors import InvalidParameterError, InvalidTypeError
from archquake.ranges import GRAVITY_RANGE_MS2

E = TypeVar("E", bound=Enum)


def require_finite(name: str, value: object, unit: str = "") -> float:
    """Return ``value`` as a float, or raise naming ``name`` if it is not a finite number."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise InvalidParameterError(f"{name} must be a number{_u(unit)}, got {_short(value)}")
    try:
        v = float(value)
    except (OverflowError, ValueError):
        v = math.inf
    if not math.isfinite(v):
        raise InvalidParameterError(
            f"{name} must be a finite number{_u(unit)}, got {_short(value)}")
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


def check_range(option: str, value: float, low: float, high: float, unit: str = "", *,
                low_open: bool = False, high_open: bool = False, hint: str = "") -> float:
    """``value`` of ``option`` (as the user typed it, e.g. ``--duration``) inside its range in the
    user's units, or `InvalidParameterError` naming both (``hint`` says what to do).

    The command line's wording: the unit follows the range bare (``--radius must be in
    [0.001, 10000] m, got 0``); `require_range` is the wording of arguments and study keys.
    """
    ok = (value > low if low_open else value >= low) and (value < high if high_open else value <= high)
    if not (math.isfinite(value) and ok):
        rng = _fmt_range(low, high, unit, low_open, high_open)
        raise InvalidParameterError(
            f"{option} must be in {rng}, got {value:g}" + (f"; {hint}" if hint else ""))
    return value


def check_whole(option: str, value: int, low: int, high: int, hint: str = "") -> int:
    """A whole number ``value`` of ``option`` from ``low`` to ``high`` (the command line's
    wording; `require_int` is that of arguments and study keys)."""
    if not low <= value <= high:
        raise InvalidParameterError(f"{option} must be a whole number from {low} to {high}, got "
                                    f"{value}" + (f"; {hint}" if hint else ""))
    return value


def _fmt_range(low: float, high: float, unit: str, low_open: bool, high_open: bool) -> str:
    u = f" {unit}" if unit else ""
    return f"{'(' if low_open else '['}{low:g}, {high:g}{')' if high_open else ']'}{u}"


def _u(unit: str) -> str:
    return f" ({unit})" if unit else ""


def require_gravity(value: object) -> float:
    """Gravity ``g`` in m/s^2, inside `archquake.ranges.GRAVITY_RANGE_MS2`."""
    low, high = GRAVITY_RANGE_MS2
    return require_range("g", value, low, high, "m/s^2", low_open=False, high_open=False)


def require_instance(name: str, value: object, types: type | tuple[type, ...], what: str) -> Any:
    """``value`` itself if it is an instance of ``types``; else an `InvalidTypeError`
    naming ``name`` and ``what`` it accepts (in words, e.g. "an Arch")."""
    if not isinstance(value, types):
        raise InvalidTypeError(f"{name} must be {what}, got {_short(value)}")
    return value


def require_choice(name: str, value: object, choices: type[E]) -> E:
    """The member of the enum ``choices`` that ``value`` is or names (by its value)."""
    if isinstance(value, choices):
        return value
    try:
        return choices(value)
    except (ValueError, TypeError):
        allowed = ", ".join(repr(c.value) for c in choices)
        raise InvalidParameterError(
            f"{name} must be one of {allowed}, got {_short(value)}") from None


def require_path(name: str, value: object) -> Path:
    """A file path given as ``str`` or `os.PathLike` (of ``str``), not empty."""
    if isinstance(value, (bytes, bytearray)) or not isinstance(value, (str, os.PathLike)):
        raise InvalidTypeError(f"{name} must be a path (str or pathlib.Path), got {_short(value)}")
    try:
        text = os.fspath(value)
    except TypeError:
        raise InvalidTypeError(
            f"{name} must be a path (str or pathlib.Path), got {_short(value)}") from None
    if not isinstance(text, str):
        raise InvalidTypeError(f"{name} must be a path (str or pathlib.Path), got {_short(value)}")
    if not text.strip():
        raise InvalidParameterError(f"{name} must name a file, got an empty path")
    if "\x00" in text:
        raise InvalidParameterError(f"{name} must not contain a NUL character, got {text!r}")
    return Path(text)


def _short(value: object, limit: int = 60) -> str:
    """``repr(value)`` cut to ``limit`` characters, so that the message stays one short line."""
    try:
        text = repr(value)
    except Exception:  # a hostile __repr__ must not replace the message
        text = f"<{type(value).__name__}>"
    text = text.replace("\n", " ")
    return text if len(text) <= limit else text[: limit - 3] + "..."


def require_array(name: str, value: object, unit: str = "", *, min_size: int = 1,
                  minimum: float | None = None, exclusive: bool = False) -> np.ndarray:
    """``value`` (a number or a 1-D sequence of numbers) as a 1-D float array of at least
    ``min_size`` finite values, each >= ``minimum`` (> when ``exclusive``) if given."""
    what = f"{name} must be a 1-D sequence of finite real numbers{_u(unit)}"
    try:
        raw = np.asarray(value)
        if raw.dtype.kind not in "biuf":  # complex, text, objects, ...
            raise TypeError
        arr = np.atleast_1d(raw.astype(float))
    except (TypeError, ValueError, OverflowError):
        raise InvalidParameterError(f"{what}, got {_short(value)}") from None
    if arr.ndim != 1 or arr.size < min_size:
        raise InvalidParameterError(
            f"{what} (at least {min_size}), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InvalidParameterError(f"{what}, got {_short(value)}")
    if minimum is not None:
        low = arr < minimum if not exclusive else arr <= minimum
        if np.any(low):
            sign = ">" if exclusive else ">="
            raise InvalidParameterError(
                f"{name} must hold values {sign} {minimum:g}{_u(unit)}, got "
                f"{float(arr[np.flatnonzero(low)[0]]):g}")
    return arr
