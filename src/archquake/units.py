"""Conversions at the edge: degrees and multiples of g live here, SI everywhere else."""

from __future__ import annotations

import math

from archquake.constants import STANDARD_GRAVITY


def deg_to_rad(degrees: float) -> float:
    """Degrees to radians."""
    return math.radians(degrees)


def rad_to_deg(radians: float) -> float:
    """Radians to degrees."""
    return math.degrees(radians)


def g_to_si(acceleration_g: float, *, g: float = STANDARD_GRAVITY) -> float:
    """Acceleration in multiples of g to m/s^2."""
    return acceleration_g * g


def si_to_g(acceleration: float, *, g: float = STANDARD_GRAVITY) -> float:
    """Acceleration in m/s^2 to multiples of g."""
    return acceleration / g


__all__ = ["deg_to_rad", "rad_to_deg", "g_to_si", "si_to_g"]
