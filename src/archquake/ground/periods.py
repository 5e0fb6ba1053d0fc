"""Period grids of spectra: START:STOP:STEP with the stop included (numpy only, so that the
command line can read ``--periods`` without loading the integrators)."""

from __future__ import annotations

import math

import numpy as np

from archquake._validate import require_finite, require_positive
from archquake.errors import InvalidParameterError
from archquake.ranges import MAX_SPECTRUM_PERIODS, SPECTRUM_MIN_PERIOD_S, SPECTRUM_PERIOD_RANGE_S

#: Period grid of a spectrum unless the user gives one: start, stop, step (s).
DEFAULT_PERIOD_GRID_S = (0.0, 4.0, 0.02)


def check_periods(periods) -> np.ndarray:
    """The periods of a spectrum (s), checked: each 0 (the peak acceleration) or from
    `SPECTRUM_MIN_PERIOD_S` to the upper bound of
    `SPECTRUM_PERIOD_RANGE_S`, at most
    `MAX_SPECTRUM_PERIODS` of them.

    >>> check_periods([0.0, 0.5, 20.0]).tolist()
    [0.0, 0.5, 20.0]
    """
    try:
        p = np.atleast_1d(np.asarray(periods, dtype=float))
    except (TypeError, ValueError):
        raise InvalidParameterError("periods must be numbers of seconds") from None
    if p.ndim != 1:
        raise InvalidParameterError("periods must be a list of numbers of seconds")
    low, high = SPECTRUM_PERIOD_RANGE_S
    ok = ((p >= SPECTRUM_MIN_PERIOD_S) & (p <= high)) | (p == low)  # NaN is not ok
    if not ok.all():
        raise InvalidParameterError(
            f"periods must be {low:g} or {SPECTRUM_MIN_PERIOD_S:g} to {high:g} s, got "
            f"{float(p[~ok][0]):g}")
    if p.size > MAX_SPECTRUM_PERIODS:
        raise InvalidParameterError(f"{p.size} periods; at most {MAX_SPECTRUM_PERIODS}")
    return p


def period_grid(start: float, stop: float, step: float) -> np.ndarray:
    """Periods from ``start`` to ``stop`` inclusive every ``step`` (s).

    Parameters
    ----------
    start, stop : float
        First and last period, s, in [0, 20] with stop >= start.
    step : float
        Spacing, s (> 0); the last point is ``stop`` even when the step does not divide the range.

    Returns
    -------
    numpy.ndarray
        The periods, s.

    Examples
    --------
    >>> period_grid(0.1, 0.5, 0.2).round(12).tolist()
    [0.1, 0.3, 0.5]
    >>> period_grid(0.0, 0.25, 0.1).round(6).tolist()
    [0.0, 0.1, 0.2, 0.25]
    """
    low, high = SPECTRUM_PERIOD_RANGE_S
    start = require_finite("start period", start, "s")
    stop = require_finite("stop period", stop, "s")
    step = require_positive("period step", step, "s")
    if not low <= start <= stop <= high:
        raise InvalidParameterError(
            f"periods must satisfy {low:g} <= START <= STOP <= {high:g} s, got {start:g}:{stop:g}")
    count = math.floor((stop - start) / step * (1 + 1e-12)) + 1
    if count > MAX_SPECTRUM_PERIODS:
        raise InvalidParameterError(
            f"{start:g}:{stop:g}:{step:g} asks for {count} periods; at most "
            f"{MAX_SPECTRUM_PERIODS}: use a larger STEP")
    grid = start + step * np.arange(count)
    if stop - grid[-1] > 1e-9 * max(1.0, stop):
        grid = np.append(grid, stop)
    grid[-1] = min(grid[-1], stop)
    return check_periods(grid)


__all__ = ["DEFAULT_PERIOD_GRID_S", "check_periods", "period_grid"]
