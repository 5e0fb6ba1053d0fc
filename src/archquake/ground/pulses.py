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


def _vertical(value: object) -> float:
    """The vertical ratio R, finite, in [-MAX_VERTICAL_RATIO, MAX_VERTICAL_RATIO]."""
    from archquake._validate import require_range

    return require_range("vertical ratio", value, -MAX_VERTICAL_RATIO, MAX_VERTICAL_RATIO,
                         low_open=False, high_open=False)


#: The largest |R| of a pulse's vertical part R a s(t).
MAX_VERTICAL_RATIO = 2.0


def _magnitude(value: object, unit: str) -> float:
    """A finite magnitude >= 0 in ``unit`` (the direction carries the sign)."""
    a = require_finite("magnitude", value, unit)
    if a < 0:
        raise InvalidParameterError(
            f"magnitude must be >= 0 {unit}, got {a:g}; use direction=+1/-1 for the sign"
        )
    return a


def _with_vertical(params: list[float], vertical: float, steady: float) -> np.ndarray:
    """A pulse's kernel parameters: [a, duration, direction], then [R, c] only when there is
    a vertical (so that a pulse without one is described as before)."""
    return np.array(params + [vertical, steady] if vertical or steady else params)


def _vertical_dict(vertical: float, steady: float, g: float) -> dict:
    return (({"vertical_ratio": vertical} if vertical else {})
            | ({"steady_vertical_m_s2": steady, "steady_vertical_g": steady / g} if steady
               else {}))


def _vertical_repr(vertical: float, steady: float) -> str:
    return ((f", vertical={vertical:g}" if vertical else "")
            + (f", steady_vertical={steady:g} m/s^2" if steady else ""))


def _steady(value: object) -> float:
    return require_finite("steady vertical", value, "m/s^2")


@dataclass(frozen=True)
class StepImpulse:
    """Oppenheim's step impulse: ``direction*a`` for ``t_p``, then ``-direction*a/2`` for
    ``2 t_p``, then rest (zero final ground velocity).

    The magnitude is in **m/s^2**, not in g: ``StepImpulse(1.0, 0.2)`` is 1 m/s^2 (0.102 g).
    Use `from_g` for a magnitude in g (``StepImpulse.from_g(1.0, 0.2)`` is 1 g); the repr
    shows both.

    Parameters
    ----------
    magnitude : float
        a, m/s^2 (>= 0).
    pulse_duration : float
        t_p, s (> 0): length of the first lobe; the whole impulse lasts 3 t_p.
    direction : {-1, +1}
        Side of the first lobe; -1 (default) drives the paper's first mechanism.
    vertical : float
        R: the pulse's vertical part, R a s(t) m/s^2 upward, s(t) the pulse's own shape with
        its first lobe +1 (+1 for t_p, -1/2 for 2 t_p, then 0); R may be negative, 0 (default)
        is no vertical.
    steady_vertical : float
        c, m/s^2 upward: a constant vertical ground acceleration held through the whole run
        (before, during and after the pulse), a code's pseudo-static k_v; 0 (default) is none.
        Under it the arch behaves as under gravity g + c.

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
    vertical: float = 0.0
    steady_vertical: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "magnitude", _magnitude(self.magnitude, "m/s^2"))
        t_p = require_positive("pulse duration t_p", self.pulse_duration, "s")
        object.__setattr__(self, "pulse_duration", t_p)
        object.__setattr__(self, "direction", _direction(self.direction))
        object.__setattr__(self, "vertical", _vertical(self.vertical))
        object.__setattr__(self, "steady_vertical", _steady(self.steady_vertical))

    @classmethod
    def from_g(cls, magnitude_g: float, duration: float, direction: int = -1, *,
               g: float = STANDARD_GRAVITY, vertical: float = 0.0) -> StepImpulse:
        """Build from a magnitude in multiples of g (``duration`` is t_p, s; ``vertical`` is
        the ratio R of the vertical part)."""
        return cls(_magnitude(magnitude_g, "g") * require_gravity(g),
                   duration, direction, vertical=vertical)

    @property
    def duration(self) -> float:
        return 3.0 * self.pulse_duration

    def __repr__(self) -> str:
        return (f"StepImpulse(magnitude={self.magnitude:g} m/s^2 "
                f"({self.magnitude / STANDARD_GRAVITY:.3g} g), pulse_duration={self.pulse_duration:g} s, "
                f"direction={self.direction:+d}{_vertical_repr(self.vertical, self.steady_vertical)})")

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        a = self.direction * self.magnitude
        return np.where(
            (t >= 0) & (t < self.pulse_duration), a,
            np.where((t >= self.pulse_duration) & (t < 3 * self.pulse_duration), -0.5 * a, 0.0),
        )

    def vertical_acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """The vertical ground acceleration R a s(t) + c at times ``t`` (s), m/s^2, upward."""
        return self.vertical * self.direction * self.acceleration(t) + self.steady_vertical

    def breakpoints(self) -> np.ndarray:
        return np.array([0.0, self.pulse_duration, 3.0 * self.pulse_duration])

    def kernel_spec(self) -> tuple[int, np.ndarray]:
        return KIND_STEP, _with_vertical(
            [self.magnitude, self.pulse_duration, float(self.direction)], self.vertical,
            self.steady_vertical)

    def mirrored(self) -> StepImpulse:
        return StepImpulse(self.magnitude, self.pulse_duration, -self.direction, self.name,
                           self.vertical, self.steady_vertical)

    def scaled(self, factor: float) -> StepImpulse:
        f = require_finite("scale factor", factor)
        d = self.direction if f >= 0 else -self.direction
        r = self.vertical if f >= 0 else -self.vertical  # every acceleration times f
        return StepImpulse(abs(f) * self.magnitude, self.pulse_duration, d, self.name, r,
                           f * self.steady_vertical)

    def to_dict(self, *, g: float = STANDARD_GRAVITY) -> dict:
        return {"type": "step", "magnitude_m_s2": self.magnitude, "magnitude_g": self.magnitude / g,
                "duration_s": self.pulse_duration, "direction": self.direction
                } | _vertical_dict(self.vertical, self.steady_vertical, g)


@dataclass(frozen=True)
class SinePulse:
    """One full cycle of ``direction * a * sin(2 pi t / T)`` on [0, T), then rest.

    The magnitude is in **m/s^2**, not in g; `from_g` takes g.

    Parameters
    ----------
    magnitude : float
        a, m/s^2 (>= 0).
    period : float
        T, s (> 0).
    direction : {-1, +1}
        Side of the first half cycle; -1 (default) drives the paper's first mechanism.
    vertical : float
        R: the pulse's vertical part, R a sin(2 pi t / T) m/s^2 upward on [0, T) (first half
        cycle upward for R > 0); 0 (default) is no vertical.
    steady_vertical : float
        c, m/s^2 upward, held through the whole run (as for `StepImpulse`).
    """

    magnitude: float
    period: float
    direction: int = -1
    name: str = "sine pulse"
    vertical: float = 0.0
    steady_vertical: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "magnitude", _magnitude(self.magnitude, "m/s^2"))
        object.__setattr__(self, "period", require_positive("period", self.period, "s"))
        object.__setattr__(self, "direction", _direction(self.direction))
        object.__setattr__(self, "vertical", _vertical(self.vertical))
        object.__setattr__(self, "steady_vertical", _steady(self.steady_vertical))

    @classmethod
    def from_g(cls, magnitude_g: float, period: float, direction: int = -1, *,
               g: float = STANDARD_GRAVITY, vertical: float = 0.0) -> SinePulse:
        """Build from a magnitude in multiples of g (``vertical`` is the ratio R of the
        vertical part)."""
        return cls(_magnitude(magnitude_g, "g") * require_gravity(g),
                   period, direction, vertical=vertical)

    @property
    def duration(self) -> float:
        return self.period

    def __repr__(self) -> str:
        return (f"SinePulse(magnitude={self.magnitude:g} m/s^2 "
                f"({self.magnitude / STANDARD_GRAVITY:.3g} g), period={self.period:g} s, "
                f"direction={self.direction:+d}{_vertical_repr(self.vertical, self.steady_vertical)})")

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        inside = (t >= 0) & (t < self.period)
        a = self.direction * self.magnitude
        return np.where(inside, a * np.sin(2 * math.pi * t / self.period), 0.0)

    def vertical_acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """The vertical ground acceleration R a s(t) + c at times ``t`` (s), m/s^2, upward."""
        return self.vertical * self.direction * self.acceleration(t) + self.steady_vertical

    def breakpoints(self) -> np.ndarray:
        return np.array([0.0, self.period])

    def kernel_spec(self) -> tuple[int, np.ndarray]:
        return KIND_SINE, _with_vertical(
            [self.magnitude, self.period, float(self.direction)], self.vertical,
            self.steady_vertical)

    def mirrored(self) -> SinePulse:
        return SinePulse(self.magnitude, self.period, -self.direction, self.name, self.vertical,
                         self.steady_vertical)

    def scaled(self, factor: float) -> SinePulse:
        f = require_finite("scale factor", factor)
        d = self.direction if f >= 0 else -self.direction
        r = self.vertical if f >= 0 else -self.vertical  # every acceleration times f
        return SinePulse(abs(f) * self.magnitude, self.period, d, self.name, r,
                         f * self.steady_vertical)

    def to_dict(self, *, g: float = STANDARD_GRAVITY) -> dict:
        return {"type": "sine", "magnitude_m_s2": self.magnitude, "magnitude_g": self.magnitude / g,
                "period_s": self.period, "direction": self.direction
                } | _vertical_dict(self.vertical, self.steady_vertical, g)


@dataclass(frozen=True)
class RectangularPulse:
    """x_g'' = ``acceleration`` (m/s^2) for 0 <= t < ``pulse_duration`` (s), then 0: the exact
    rectangle that `sampled` approximates (its fall takes t_p / 2000)."""

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
        """The pulse as a sampled `Record` for the kernels that read
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

    def motion(self, magnitude_g: float, duration: float, *, g: float = STANDARD_GRAVITY,
               vertical: float = 0.0) -> GroundMotion:
        """The pulse of magnitude ``magnitude_g`` (g) and duration (s), first lobe towards -x,
        with a vertical part R = ``vertical`` times its shape."""
        if self is PulseFamily.STEP:
            return StepImpulse.from_g(magnitude_g, duration, g=g, vertical=vertical)
        return SinePulse.from_g(magnitude_g, duration, g=g, vertical=vertical)

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
