"""Analytical pulses: Oppenheim's step impulse and the one-cycle sine pulse.

Magnitudes are in m/s^2 (SI inside): ``StepImpulse(1.0, 0.2)`` is 1 m/s^2 = 0.102 g, not 1 g.
``from_g`` builds from multiples of g, and the repr shows both units.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum
from numbers import Real

import numpy as np

from archquake._validate import require_finite, require_gravity, require_positive
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.ground.base import KIND_SINE, KIND_STEP, GroundMotion
from archquake.ground.records import Record


def _direction(value: object) -> int:
    if isinstance(value, bool) or not isinstance(value, Real) or value not in (-1, 1):
        raise InvalidParameterError(
            f"direction must be -1 (towards -x) or +1 (towards +x), got {value!r}"
        )
    return 1 if value == 1 else -1


def _magnitude(value: object, unit: str) -> float:
    """A finite magnitude >= 0 in ``unit`` (the direction carries the sign)."""
    a = require_finite("magnitude", value, unit)
    if a < 0:
        raise InvalidParameterError(
            f"magnitude must be >= 0 {unit}, got {a:g}; use direction=+1/-1 for the sign"
        )
    return a


@dataclass(frozen=True)
class StepImpulse:
    """Oppenheim's step impulse: ``direction*a`` for ``t_p``, then ``-direction*a/2`` for
    ``2 t_p``, then rest (zero final ground velocity).

    The magnitude is in **m/s^2**, not in g: ``StepImpulse(1.0, 0.2)`` is 1 m/s^2 (0.102 g).
    Use :meth:`from_g` for a magnitude in g (``StepImpulse.from_g(1.0, 0.2)`` is 1 g); the repr
    shows both.

    Parameters
    ----------
    magnitude : float
        a, m/s^2 (>= 0).
    pulse_duration : float
        t_p, s (> 0): length of the first lobe; the whole impulse lasts 3 t_p.
    direction : {-1, +1}
        Side of the first lobe; -1 (default) drives the paper's first mechanism.

    Examples
    --------
    >>> p = StepImpulse.from_g(1.0, 0.27)
    >>> [round(float(x) / 9.80665, 3) for x in p.acceleration([0.1, 0.3, 0.9])]
    [-1.0, 0.5, 0.0]
    """

    magnitude: float
    pulse_duration: float
    direction: int = -1
    name: str = "step impulse"

    def __post_init__(self) -> None:
        object.__setattr__(self, "magnitude", _magnitude(self.magnitude, "m/s^2"))
        t_p = require_positive("pulse duration t_p", self.pulse_duration, "s")
        object.__setattr__(self, "pulse_duration", t_p)
        object.__setattr__(self, "direction", _direction(self.direction))

    @classmethod
    def from_g(cls, magnitude_g: float, duration: float, direction: int = -1, *,
               g: float = STANDARD_GRAVITY) -> StepImpulse:
        """Build from a magnitude in multiples of g (``duration`` is t_p, s)."""
        return cls(_magnitude(magnitude_g, "g") * require_gravity(g),
                   duration, direction)

    @property
    def duration(self) -> float:
        return 3.0 * self.pulse_duration

    def __repr__(self) -> str:
        return (f"StepImpulse(magnitude={self.magnitude:g} m/s^2 "
                f"({self.magnitude / STANDARD_GRAVITY:.3g} g), pulse_duration={self.pulse_duration:g} s, "
                f"direction={self.direction:+d})")

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        a = self.direction * self.magnitude
        return np.where(
            (t >= 0) & (t < self.pulse_duration), a,
            np.where((t >= self.pulse_duration) & (t < 3 * self.pulse_duration), -0.5 * a, 0.0),
        )

    def breakpoints(self) -> np.ndarray:
        return np.array([0.0, self.pulse_duration, 3.0 * self.pulse_duration])

    def kernel_spec(self) -> tuple[int, np.ndarray]:
        return KIND_STEP, np.array([self.magnitude, self.pulse_duration, float(self.direction)])

    def mirrored(self) -> StepImpulse:
        return StepImpulse(self.magnitude, self.pulse_duration, -self.direction, self.name)

    def scaled(self, factor: float) -> StepImpulse:
        f = require_finite("scale factor", factor)
        d = self.direction if f >= 0 else -self.direction
        return StepImpulse(abs(f) * self.magnitude, self.pulse_duration, d, self.name)

    def to_dict(self, *, g: float = STANDARD_GRAVITY) -> dict:
        return {"type": "step", "magnitude_m_s2": self.magnitude, "magnitude_g": self.magnitude / g,
                "duration_s": self.pulse_duration, "direction": self.direction}


@dataclass(frozen=True)
class SinePulse:
    """One full cycle of ``direction * a * sin(2 pi t / T)`` on [0, T), then rest.

    The magnitude is in **m/s^2**, not in g; :meth:`from_g` takes g.

    Parameters
    ----------
    magnitude : float
        a, m/s^2 (>= 0).
    period : float
        T, s (> 0).
    direction : {-1, +1}
        Side of the first half cycle; -1 (default) drives the paper's first mechanism.
    """

    magnitude: float
    period: float
    direction: int = -1
    name: str = "sine pulse"

    def __post_init__(self) -> None:
        object.__setattr__(self, "magnitude", _magnitude(self.magnitude, "m/s^2"))
        object.__setattr__(self, "period", require_positive("period", self.period, "s"))
        object.__setattr__(self, "direction", _direction(self.direction))

    @classmethod
    def from_g(cls, magnitude_g: float, period: float, direction: int = -1, *,
               g: float = STANDARD_GRAVITY) -> SinePulse:
        """Build from a magnitude in multiples of g."""
        return cls(_magnitude(magnitude_g, "g") * require_gravity(g),
                   period, direction)

    @property
    def duration(self) -> float:
        return self.period

    def __repr__(self) -> str:
        return (f"SinePulse(magnitude={self.magnitude:g} m/s^2 "
                f"({self.magnitude / STANDARD_GRAVITY:.3g} g), period={self.period:g} s, "
                f"direction={self.direction:+d})")

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        inside = (t >= 0) & (t < self.period)
        a = self.direction * self.magnitude
        return np.where(inside, a * np.sin(2 * math.pi * t / self.period), 0.0)

    def breakpoints(self) -> np.ndarray:
        return np.array([0.0, self.period])

    def kernel_spec(self) -> tuple[int, np.ndarray]:
        return KIND_SINE, np.array([self.magnitude, self.period, float(self.direction)])

    def mirrored(self) -> SinePulse:
        return SinePulse(self.magnitude, self.period, -self.direction, self.name)

    def scaled(self, factor: float) -> SinePulse:
        f = require_finite("scale factor", factor)
        d = self.direction if f >= 0 else -self.direction
        return SinePulse(abs(f) * self.magnitude, self.period, d, self.name)

    def to_dict(self, *, g: float = STANDARD_GRAVITY) -> dict:
        return {"type": "sine", "magnitude_m_s2": self.magnitude, "magnitude_g": self.magnitude / g,
                "period_s": self.period, "direction": self.direction}


@dataclass(frozen=True)
class RectangularPulse:
    """x_g'' = ``acceleration`` (m/s^2) for 0 <= t < ``pulse_duration`` (s), then 0: the exact
    rectangle that :meth:`sampled` approximates (its fall takes t_p / 2000)."""

    acceleration_m_s2: float
    pulse_duration: float

    @property
    def duration(self) -> float:
        return self.pulse_duration

    def acceleration(self, t):
        t = np.asarray(t, dtype=float)
        return np.where((t >= 0) & (t < self.pulse_duration), self.acceleration_m_s2, 0.0)

    def breakpoints(self) -> np.ndarray:
        return np.array([0.0, self.pulse_duration])

    def mirrored(self) -> RectangularPulse:
        return RectangularPulse(-self.acceleration_m_s2, self.pulse_duration)

    def sampled(self, samples: int = 2000) -> Record:
        """The pulse as a sampled :class:`~archquake.ground.Record` for the kernels that read
        a motion's compiled description (the DEM's): ``samples`` intervals of t_p / samples s
        at the full acceleration, so the fall to zero takes t_p / samples."""
        dt = self.pulse_duration / samples
        return Record(np.array([self.acceleration_m_s2] * (samples + 1) + [0.0, 0.0]), dt,
                      name="rectangular pulse")



class PulseFamily(str, Enum):
    """A one-parameter family of pulses: magnitude a and a duration.

    ``step``: Oppenheim's step impulse, duration = t_p (the first lobe; the impulse lasts 3 t_p).
    ``sine``: one cycle of a sine, duration = its period T.
    """

    STEP = "step"
    SINE = "sine"

    @classmethod
    def parse(cls, value: PulseFamily | str) -> PulseFamily:
        try:
            return cls(value)
        except ValueError:
            raise InvalidParameterError(
                f"pulse family must be 'step' or 'sine', got {value!r}") from None

    def motion(self, magnitude_g: float, duration: float, *, g: float = STANDARD_GRAVITY) -> GroundMotion:
        """The pulse of magnitude ``magnitude_g`` (g) and duration (s), first lobe towards -x."""
        if self is PulseFamily.STEP:
            return StepImpulse.from_g(magnitude_g, duration, g=g)
        return SinePulse.from_g(magnitude_g, duration, g=g)

    @property
    def kind(self) -> int:
        return int(self.motion(1.0, 1.0).kernel_spec()[0])

    @property
    def duration_symbol(self) -> str:
        """How the paper names the duration: ``t_p`` or ``T``."""
        return "t_p" if self is PulseFamily.STEP else "T"

    @property
    def duration_label(self) -> str:
        return ("impulse duration t_p [s]" if self is PulseFamily.STEP else "impulse period T [s]")


__all__ = ["PulseFamily", "RectangularPulse", "SinePulse", "StepImpulse"]
