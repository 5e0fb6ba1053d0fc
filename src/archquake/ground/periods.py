"""Period grids of spectra: START:STOP:STEP with the stop included (numpy only, so that the
command line can read ``--periods`` without loading the integrators)."""

from __future__ import annotations

import math

import numpy as np

from archquake._validate import require_finite, require_positive
from archquake.errors import InvalidParameterError
from archquake.ranges import MAX_SPECTRUM_PERIODS, SPECTRUM_PERIOD_RANGE_S

#: Period grid of a spectrum unless the user gives one: start, stop, step (s).
DEFAULT_PERIOD_GRID_S = (0.0, 4.0, 0.02)


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
    return grid


__all__ = ["DEFAULT_PERIOD_GRID_S", "period_grid"]
