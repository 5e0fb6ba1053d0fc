"""Closed forms for a rigid rectangular block rocking on a rigid base (Housner 1963): the oracles
the distinct-element engine is held to on a single block.

A block of width ``b`` and height ``h`` rocks about a bottom corner. Its slenderness is
``alpha = atan(b / h)`` and its half-diagonal ``R = sqrt(b^2 + h^2) / 2`` (m).

Reference: Housner GW (1963). The behavior of inverted pendulum structures during earthquakes.
Bull. Seismol. Soc. Am. 53(2):403-417 (the paper's ref. [3]).

>>> round(restitution(0.4, 2.0), 4)
0.9423
>>> round(onset_acceleration(0.4, 2.0, g=9.81), 3)
1.962
"""

from __future__ import annotations

import math

from archquake.constants import STANDARD_GRAVITY


def slenderness(width: float, height: float) -> float:
    """alpha = atan(b / h), rad: the angle of the diagonal from the vertical."""
    return math.atan2(width, height)


def half_diagonal(width: float, height: float) -> float:
    """R = sqrt(b^2 + h^2) / 2, m: the distance from a corner to the centroid."""
    return 0.5 * math.hypot(width, height)


def frequency_parameter(width: float, height: float, *, g: float = STANDARD_GRAVITY) -> float:
    """p = sqrt(m g R / I_O) = sqrt(3 g / (4 R)), 1/s, for a rectangular block
    (I_O = 4 m R^2 / 3 about a corner; Housner 1963)."""
    return math.sqrt(3.0 * g / (4.0 * half_diagonal(width, height)))


def restitution_from_inertia(alpha: float, mass_radius2_over_inertia: float) -> float:
    """Housner's restitution on the angular velocity for any rigid block rocking on two corners.

    Angular momentum about the corner that strikes is conserved through the impact:
    ``omega_after / omega_before = 1 - 2 m R^2 sin^2(alpha) / I_O``.

    Parameters
    ----------
    alpha : float
        Slenderness, rad.
    mass_radius2_over_inertia : float
        m R^2 / I_O, with I_O the moment of inertia about a bottom corner (kg m^2).
    """
    return 1.0 - 2.0 * mass_radius2_over_inertia * math.sin(alpha) ** 2


def restitution(width: float, height: float) -> float:
    """Housner's restitution of a rectangular block: r = 1 - 1.5 sin^2(alpha).

    Exact for a rigid rectangle (m R^2 / I_O = 3/4 in :func:`restitution_from_inertia`), not a
    slender-block approximation.

    Parameters
    ----------
    width, height : float
        b and h, m.
    """
    return restitution_from_inertia(slenderness(width, height), 0.75)


def onset_acceleration(width: float, height: float, *, g: float = STANDARD_GRAVITY) -> float:
    """Ground acceleration that lifts the heel of a block, m/s^2: g b / h (moment balance about
    the corner, quasi-static)."""
    return g * width / height


def rectangular_pulse_overturning(width: float, height: float, duration: float, *,
                                  g: float = STANDARD_GRAVITY) -> float:
    """Least ground acceleration (m/s^2) of a rectangular pulse of ``duration`` s that overturns
    the block before any impact, linearised rocking (Housner 1963):
    ``a = g alpha / (1 - exp(-p t_p))``.

    Valid for a slender block (sin, cos linearised: alpha ~ 0.1 errs by < 0.5 %).
    """
    alpha = slenderness(width, height)
    p = frequency_parameter(width, height, g=g)
    return g * alpha / (1.0 - math.exp(-p * duration))


__all__ = [
    "frequency_parameter",
    "half_diagonal",
    "onset_acceleration",
    "rectangular_pulse_overturning",
    "restitution",
    "restitution_from_inertia",
    "slenderness",
]
