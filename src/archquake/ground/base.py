"""The ground-motion contract shared by the three models.

Sign convention: ``acceleration(t)`` is the horizontal ground acceleration x_g'' in m/s^2,
positive towards +x (to the right). A ground acceleration towards -x loads the arch with an
inertia force towards +x and drives the paper's first mechanism (its Figure 1; the paper
quotes the onset as "-0.37 g" for this reason). The pulses here therefore start towards -x
by default (``direction=-1``); ``mirrored()`` flips any motion.

Every motion also describes itself to the compiled kernels as ``(kind, params)``:

==========  =================================  ==========================================
kind        params (float64)                   x_g''(t)
==========  =================================  ==========================================
0 step      [a, t_p, direction(, R)]           direction*a on [0, t_p), -direction*a/2 on
                                               [t_p, 3 t_p), 0 after (Oppenheim's impulse)
1 sine      [a, T, direction(, R)]             direction*a*sin(2 pi t/T) on [0, T), 0 after
2 sampled   [t0, dt, x_0, x_1, ..., x_{N-1}]   linear between samples, 0 outside
3 sampled   [N, t0, dt, x_0, ..., x_{N-1},     the horizontal as kind 2; the upward a_v(t)
  with its  t0v, dtv, v_0, ..., v_{M-1}]       linear between its own samples v, 0 outside
  vertical
==========  =================================  ==========================================

A pulse with a vertical carries [R, c] as its fourth and fifth parameters: the upward ground
acceleration is then a_v(t) = R * direction * x_g''(t) + c, the pulse's own shape (first lobe
+1) times R a, plus a steady c m/s^2 held through the whole run.

A record with its vertical component (kind 3) keeps each component on its own time step: no
resampling, so the compiled a_v(t) is the vertical file's own linear interpolation, exactly
what the Python side (`WithVertical.vertical_acceleration`) evaluates, and the breakpoints are
the union of both components' sample times. Two components of one station share their time
step, and then the union is one grid.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, Protocol, cast, runtime_checkable

import numpy as np

from archquake.errors import InvalidParameterError

KIND_STEP = 0
KIND_SINE = 1
KIND_SAMPLED = 2
KIND_SAMPLED_VERTICAL = 3


@runtime_checkable
class GroundMotion(Protocol):
    """A horizontal ground acceleration history."""

    @property
    def name(self) -> str:
        """Label of the motion (read-only: the motions are frozen dataclasses)."""
        ...

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """Ground acceleration x_g'' at times ``t`` (s), m/s^2, positive towards +x."""
        ...

    @property
    def duration(self) -> float:
        """Time (s) after which the acceleration is identically zero."""
        ...

    def breakpoints(self) -> np.ndarray:
        """Times (s) in [0, duration] where x_g'' or its slope jumps; integrators stop there."""
        ...

    def kernel_spec(self) -> tuple[int, np.ndarray]:
        """``(kind, params)`` for the compiled evaluator (see the module docstring)."""
        ...

    def mirrored(self) -> GroundMotion:
        """The same motion towards the other side."""
        ...

    def scaled(self, factor: float) -> GroundMotion:
        """The motion with every acceleration multiplied by ``factor``."""
        ...

    def to_dict(self) -> dict:
        """Plain description for JSON (accelerations in m/s^2 and in g)."""
        ...


#: Shortest piece of a ground motion the integrators resolve, as a fraction of the larger of
#: the arch's time scale sqrt(R/g), the motion's duration and 1 s (see `time_floor`).
TIME_RESOLUTION = 1e-9

#: What each kind's shortest piece is called, for the error message.
_PIECE_NAMES = {KIND_STEP: ("pulse duration t_p", 1.0),  # pieces t_p and 2 t_p
                KIND_SINE: ("period T", 0.25),  # quarter periods (breakpoints at the extrema)
                KIND_SAMPLED: ("record time step DT", 1.0),
                KIND_SAMPLED_VERTICAL: ("record time step DT", 1.0)}


def check_motion(motion: object, needs: tuple[str, ...] | None = None) -> GroundMotion:
    """``motion`` itself if it is a ground motion (or, given ``needs``, has those attributes:
    what a model reads of it); else the one line that says what is."""
    ok = (isinstance(motion, GroundMotion) if needs is None
          else all(hasattr(motion, name) for name in needs))
    if not ok:
        raise InvalidParameterError(
            f"motion must be a ground motion from archquake.ground (StepImpulse, SinePulse or "
            f"Record), e.g. StepImpulse.from_g(1.0, 0.27) for 1.0 g during t_p = 0.27 s; got "
            f"{type(motion).__name__}")
    return cast(GroundMotion, motion)


def has_vertical(motion: object) -> bool:
    """Whether ``motion`` carries a vertical ground acceleration (a pulse's R or steady c, or
    a record's vertical component)."""
    v = getattr(motion, "vertical", 0.0)
    return (v is not None and not isinstance(v, (int, float))) or bool(
        v or getattr(motion, "steady_vertical", 0.0))


def time_floor(time_scale: float, duration: float) -> float:
    """Shortest piece of a ground motion (s) that the compiled integrators resolve.

    ``TIME_RESOLUTION * max(time_scale, duration, 1 s)``. Two resolutions set it: the kernels
    find the excitation's breakpoints with a tolerance of 1e-12 (1 + t) s (so a piece shorter
    than that is skipped, and the piece before it continued over the rest of the run: a step
    of t_p < 3e-13 s used to act forever and collapse the arch), and double precision resolves
    times near t to about 2.2e-16 t over a run of length ``duration`` + 60 ``time_scale``. The
    factor 1e-9 keeps every piece 1000 times above both; physically nothing is lost, since a
    piece that short carries an impulse of order 1e-9 of any realistic one.

    Parameters
    ----------
    time_scale : float
        sqrt(R/g) of the arch, s.
    duration : float
        The motion's duration, s.
    """
    return TIME_RESOLUTION * max(time_scale, duration, 1.0)


def check_time_resolution(kind: int, params: np.ndarray, time_scale: float) -> None:
    """Refuse a motion ``(kind, params)`` with a piece shorter than `time_floor`.

    Raises `InvalidParameterError` naming the motion's parameter
    (t_p, T or the record's DT) and its lower bound.
    """
    name, fraction = _PIECE_NAMES[kind]
    if kind == KIND_SAMPLED_VERTICAL:  # each component on its own step
        n = int(params[0])
        check_time_resolution(KIND_SAMPLED, params[1:3 + n], time_scale)
        check_time_resolution(KIND_SAMPLED, params[3 + n:], time_scale)
        return
    if kind == KIND_SAMPLED:
        value = float(params[1])
        duration = float(params[0] + params[1] * (params.shape[0] - 3))
    else:
        value = float(params[1])
        duration = value * (3.0 if kind == KIND_STEP else 1.0)
    if not math.isfinite(duration):
        raise InvalidParameterError(f"the ground motion's duration must be finite, got "
                                    f"{name} = {value:g} s")
    floor = time_floor(time_scale, duration) / fraction
    if not value >= floor:
        raise InvalidParameterError(
            f"{name} must be >= {floor:.3g} s for this arch and motion (1e-9 times the larger "
            f"of sqrt(R/g) = {time_scale:.3g} s, the motion's duration and 1 s: shorter pieces "
            f"are below the integrator's time resolution), got {value:g}")


def _vertical_extremes(kind: int, params: np.ndarray) -> tuple[float, float] | None:
    """(lowest upward ground acceleration, its steady part c), m/s^2, of a motion with a
    vertical (a record's: its lowest sample, or 0); None without one."""
    if kind == KIND_SAMPLED_VERTICAL:  # a record's vertical: its lowest sample
        return min(float(np.min(params[5 + int(params[0]):])), 0.0), 0.0
    if kind not in (KIND_STEP, KIND_SINE) or params.shape[0] <= 3:
        return None
    a, r, c = float(params[0]), float(params[3]), float(params[4])
    return c + (min(r * a, -0.5 * r * a) if kind == KIND_STEP else -abs(r) * a), c


def check_lift_off(kind: int, params: np.ndarray, g: float) -> None:
    """Refuse a motion whose vertical part reaches g downward: with g + a_v(t) <= 0 the arch
    leaves its supports, which no model here describes (the rigid-body equations assume the
    blocks stay pressed together by gravity)."""
    extremes = _vertical_extremes(kind, params)
    if extremes is None:
        return
    lowest = extremes[0]
    if g + lowest > 0.0:
        return
    if kind == KIND_SAMPLED_VERTICAL:
        raise InvalidParameterError(
            f"the vertical component reaches {-lowest / g:.3g} g downward: g + a_v <= 0 "
            "lifts the arch off its supports, outside every model; lower --scale")
    a, r, c = float(params[0]), float(params[3]), float(params[4])
    raise InvalidParameterError(
        f"the vertical ground acceleration (R = {r:g}, a = {a / g:.3g} g, steady "
        f"{c / g:.3g} g) reaches {-lowest / g:.3g} g downward: g + a_v <= 0 lifts the arch "
        "off its supports, outside every model; keep the downward vertical below g")


def lift_off_factor(motion: object, g: float) -> float:
    """The factor of ``motion.scaled`` at which its vertical reaches g downward (the arch
    leaves its supports there, `check_lift_off`); inf for a motion without a downward
    vertical. Scaling scales every acceleration, the vertical's (a pulse's steady c too).

    >>> from archquake.ground.pulses import StepImpulse
    >>> lift_off_factor(StepImpulse(2.0, 0.1, vertical=-0.5), 9.8)  # -0.5 * 2 f = -9.8
    9.8
    """
    spec = getattr(motion, "kernel_spec", None)
    if spec is None or not has_vertical(motion):
        return math.inf
    extremes = _vertical_extremes(*spec())
    if extremes is None or not extremes[0] < 0.0:
        return math.inf
    return g / -extremes[0]


def check_motion_lift_off(motion: object, g: float) -> None:
    """`check_lift_off` for any motion with a vertical: a pulse's, or a record's vertical
    component (its lowest sample)."""
    if has_vertical(motion):
        kind, params = cast(GroundMotion, motion).kernel_spec()
        check_lift_off(kind, params, g)


def motion_label(motion: GroundMotion | Mapping[str, Any]) -> str:
    """One line naming a ground motion for text output: a pulse by its kind, magnitude (g)
    and duration or period (s), and the side of its first lobe when mirrored; a record by its
    name.

    Parameters
    ----------
    motion : GroundMotion or mapping
        The motion, or its description (its ``to_dict()``, as a run's JSON output holds it
        under ``excitation``).

    Examples
    --------
    >>> from archquake.ground import StepImpulse
    >>> motion_label(StepImpulse.from_g(0.5, 0.25))
    'step a = 0.5 g, t_p = 0.25 s'
    >>> motion_label({"type": "sine", "magnitude_g": 0.4, "period_s": 1.0, "direction": 1})
    'sine a = 0.4 g, T = 1 s, first towards +x (mirrored)'
    """
    d = motion if isinstance(motion, Mapping) else motion.to_dict()
    # the default pulse's first lobe is towards -x (module docstring)
    towards = ", first towards +x (mirrored)" if d.get("direction", -1) > 0 else ""
    up = (f", vertical {d['vertical_ratio']:g} a s(t)" if d.get("vertical_ratio") else "") + (
        f", steady vertical {d['steady_vertical_g']:.3g} g" if d.get("steady_vertical_g") else "")
    if d.get("type") == "step":
        return f"step a = {d['magnitude_g']:.3g} g, t_p = {d['duration_s']:.3g} s" + towards + up
    if d.get("type") == "sine":
        return f"sine a = {d['magnitude_g']:.3g} g, T = {d['period_s']:.3g} s" + towards + up
    name = str(d.get("name", getattr(motion, "name", "record")))
    vertical = d.get("vertical")
    if isinstance(vertical, Mapping):  # a record with its vertical component
        name += f" with its vertical {vertical.get('name')} (PGA {vertical.get('pga_g', 0):.3g} g)"
    return name


def acceleration_peaks(motion: object) -> tuple[float, float] | None:
    """The largest ground acceleration towards +x and towards -x over the whole motion, m/s^2
    (each >= 0), exactly, from its ``kernel_spec`` (module docstring): the step impulse's two
    levels, the sine's magnitude both ways, a record's extreme samples (it is linear between
    them and zero outside). None for a motion that does not describe itself so, and for one with
    a vertical ground acceleration (the onset then moves with g + a_v(t)).

    >>> from archquake.ground.pulses import StepImpulse
    >>> acceleration_peaks(StepImpulse(2.0, 0.1, direction=-1))
    (1.0, 2.0)
    """
    spec = getattr(motion, "kernel_spec", None)
    if spec is None or has_vertical(motion):  # the onset moves with g + a_v(t)
        return None
    kind, params = spec()
    params = np.asarray(params, dtype=float)
    if kind == KIND_STEP:
        a = float(params[2] * params[0])
        levels = np.array([a, -0.5 * a, 0.0])
    elif kind == KIND_SINE:
        a = abs(float(params[0]))
        levels = np.array([a, -a])
    elif kind == KIND_SAMPLED:
        levels = np.r_[params[2:], 0.0]
    else:
        return None
    return max(float(levels.max()), 0.0), max(float(-levels.min()), 0.0)


__all__ = ["GroundMotion", "acceleration_peaks", "check_lift_off", "check_motion",
           "check_motion_lift_off", "has_vertical", "lift_off_factor", "motion_label",
           "KIND_STEP", "KIND_SINE", "KIND_SAMPLED", "KIND_SAMPLED_VERTICAL", "TIME_RESOLUTION",
           "check_time_resolution", "time_floor"]
