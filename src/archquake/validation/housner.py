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

    Exact for a rigid rectangle (m R^2 / I_O = 3/4 in `restitution_from_inertia`), not a
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


def fall_time(width: float, height: float, tilt: float, *, g: float = STANDARD_GRAVITY) -> float:
    """Exact time, s, for the block released from rest at ``tilt`` (rad, 0 < tilt < alpha) to
    fall back to upright, rocking on its corner: quadrature of the energy equation
    ``I_O theta'^2 / 2 = m g R (cos(alpha - tilt) - cos(alpha - theta))`` (I_O = 4 m R^2 / 3),
    written in w with theta = tilt - w^2 so that the integrand stays finite at the release."""
    from scipy.integrate import quad

    alpha = slenderness(width, height)
    p2 = frequency_parameter(width, height, g=g) ** 2

    def f(w: float) -> float:
        drop = math.cos(alpha - tilt) - math.cos(alpha - tilt + w * w)
        return 2.0 * w / math.sqrt(2.0 * p2 * drop)

    return float(quad(f, 0.0, math.sqrt(tilt), limit=200, epsabs=1e-13, epsrel=1e-12)[0])


def free_rocking(width: float, height: float, tilt: float, impacts: int = 2, *,
                 g: float = STANDARD_GRAVITY) -> tuple[list[float], list[float]]:
    """Free rocking released from rest at ``tilt`` (rad): the times of the first ``impacts``
    impacts (s) and the tilt reached after each (rad). Between impacts the exact motion
    (`fall_time`, twice per half cycle after the first); at each impact the angular
    velocity times `restitution`, so the energy times r^2:
    ``cos(alpha - tilt_k+1) = cos(alpha) + r^2 (cos(alpha - tilt_k) - cos(alpha))``."""
    alpha = slenderness(width, height)
    r = restitution(width, height)
    times: list[float] = []
    peaks: list[float] = []
    t = fall_time(width, height, tilt, g=g)
    th = tilt
    for _ in range(impacts):
        times.append(t)
        th = alpha - math.acos(math.cos(alpha) + r * r * (math.cos(alpha - th) - math.cos(alpha)))
        peaks.append(th)
        t += 2.0 * fall_time(width, height, th, g=g)
    return times, peaks


__all__ = [
    "fall_time",
    "free_rocking",
    "frequency_parameter",
    "half_diagonal",
    "onset_acceleration",
    "rectangular_pulse_overturning",
    "restitution",
    "restitution_from_inertia",
    "slenderness",
]
