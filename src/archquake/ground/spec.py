"""The excitation of a case in study units (accelerations in g, times in s): a step impulse,
a one-cycle sine pulse or a record, checked when built and turned into a
`GroundMotion`, in SI, by `ExcitationSpec.build`.

Its canonical form (`ExcitationSpec.canonical`) is the excitation's part of a sweep
case's id (`archquake.sweeps.cases`): a record enters it through its file name and the
SHA-256 of its bytes, not its directory, so moving the records folder keeps the ids and
editing a record changes them.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from enum import StrEnum
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from archquake._json import canonical_json
from archquake._validate import require_positive, require_range
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.ranges import MAGNITUDE_RANGE_G, PULSE_TIME_RANGE_S, SCALE_RANGE


class ExcitationKind(StrEnum):
    """The excitations a sweep can apply."""

    STEP = "step"
    SINE = "sine"
    RECORD = "record"



#: Units a record file's accelerations may be given in (PEER .AT2 files are always in g).
RECORD_UNITS: tuple[str, ...] = ("g", "m/s2")


@dataclass(frozen=True)
class ExcitationSpec:
    """The excitation of a case, in study units.

    Parameters
    ----------
    kind : ExcitationKind or str
        ``"step"`` (Oppenheim's impulse), ``"sine"`` (one-cycle sine pulse) or ``"record"``.
    magnitude_g : float, optional
        Pulse magnitude, multiples of g (>= 0), for ``step`` and ``sine``.
    duration_s : float, optional
        Step impulse duration t_p, s (> 0), for ``step``.
    period_s : float, optional
        Sine period T, s (> 0), for ``sine``.
    direction : {-1, +1}
        Side of the pulse's first lobe (-1, towards -x, drives the paper's first mechanism);
        for a record, -1 reverses its sign. Default -1 for pulses, +1 for records.
    file : str, optional
        Path of the record file (``record`` only); read when the case runs.
    units : {"g", "m/s2"}
        Units of the record's accelerations (``record`` only; default "g", the only units of a
        PEER ``.AT2`` file; CSV records must say).
    scale : float
        Factor applied to the record's accelerations (> 0; ``record`` only, default 1).
    file_sha256 : str, optional
        SHA-256 of the record file's bytes; computed from ``file`` when omitted.
    motion : GroundMotion, optional
        ``record`` only, instead of ``file``: a ground motion held in memory (a
        `Record` of a suite, or any motion with ``kernel_spec`` and
        ``scaled``), in m/s^2, travelling with the case to the worker. It enters the id through
        its name and the SHA-256 of its kernel description (`motion_digest`), and
        ``units`` is then "m/s2". This is the case kind "a record scaled by a factor" of
        incremental dynamic analysis (`archquake.ida`).
    vertical_ratio : float, optional
        ``step`` and ``sine`` only: the pulse's vertical part R (its shape times R a, upward;
        `StepImpulse`), in [-2, 2]; omitted or 0: none.
    """

    kind: ExcitationKind
    magnitude_g: float | None = None
    duration_s: float | None = None
    period_s: float | None = None
    direction: int | None = None
    file: str | None = None
    units: str | None = None
    scale: float | None = None
    file_sha256: str | None = field(default=None, compare=False)
    motion: Any = field(default=None, compare=False, repr=False)
    vertical_ratio: float | None = None

    def __post_init__(self) -> None:
        try:
            kind = ExcitationKind(getattr(self.kind, "value", self.kind))
        except ValueError:
            raise InvalidParameterError(
                f"excitation type must be one of {[k.value for k in ExcitationKind]}, "
                f"got {self.kind!r}"
            ) from None
        _set(self, "kind", kind)
        allowed = {ExcitationKind.STEP: {"magnitude_g", "duration_s", "direction",
                                         "vertical_ratio"},
                   ExcitationKind.SINE: {"magnitude_g", "period_s", "direction", "vertical_ratio"},
                   ExcitationKind.RECORD: {"file", "units", "scale", "direction"}}[kind]
        for name in ("magnitude_g", "duration_s", "period_s", "file", "units", "scale",
                     "vertical_ratio"):
            if getattr(self, name) is not None and name not in allowed:
                raise InvalidParameterError(f"{name} does not apply to a {kind.value} excitation")
        direction = -1 if self.direction is None and kind is not ExcitationKind.RECORD else (
            1 if self.direction is None else self.direction)
        if direction not in (-1, 1) or isinstance(direction, bool):
            raise InvalidParameterError(f"direction must be -1 or +1, got {direction!r}")
        _set(self, "direction", int(direction))
        if self.motion is not None and kind is not ExcitationKind.RECORD:
            raise InvalidParameterError(f"motion does not apply to a {kind.value} excitation")
        if kind is ExcitationKind.RECORD and self.motion is not None:
            if self.file is not None:
                raise InvalidParameterError("a record excitation takes file or motion, not both")
            if self.units not in (None, "m/s2"):
                raise InvalidParameterError(f"an in-memory motion is in m/s2, got units "
                                            f"{self.units!r}")
            _set(self, "units", "m/s2")
            scale = 1.0 if self.scale is None else self.scale
            _set(self, "scale", require_positive("scale", scale))
            if self.file_sha256 is None:
                _set(self, "file_sha256", motion_digest(self.motion))
            return
        if kind is ExcitationKind.RECORD:
            if not isinstance(self.file, str) or not self.file:
                raise InvalidParameterError("a record excitation needs file = path of the record")
            units = "g" if self.units is None else self.units
            if units not in RECORD_UNITS:
                raise InvalidParameterError(
                    f"units must be one of {list(RECORD_UNITS)}, got {units!r}")
            _set(self, "units", units)
            scale = 1.0 if self.scale is None else self.scale
            _set(self, "scale", require_range("scale", scale, *SCALE_RANGE, high_open=False))
            if self.file_sha256 is None:
                _set(self, "file_sha256", file_digest(self.file))
            return
        magnitude = require_range("magnitude_g", self.magnitude_g, *MAGNITUDE_RANGE_G, "g",
                                  low_open=False, high_open=False)
        _set(self, "magnitude_g", magnitude)
        time_name = "duration_s" if kind is ExcitationKind.STEP else "period_s"
        _set(self, time_name, require_range(time_name, getattr(self, time_name),
                                            *PULSE_TIME_RANGE_S, "s", low_open=False,
                                            high_open=False))
        if self.vertical_ratio is not None:
            _set(self, "vertical_ratio", require_range("vertical_ratio", self.vertical_ratio,
                                                       -2.0, 2.0, low_open=False,
                                                       high_open=False) or None)

    def build(self, *, g: float = STANDARD_GRAVITY):
        """The `GroundMotion` (SI)."""
        from archquake.ground.base import has_vertical
        from archquake.ground.pulses import SinePulse, StepImpulse

        assert self.direction is not None  # __post_init__ sets -1 or +1
        if self.kind is ExcitationKind.STEP:
            assert self.magnitude_g is not None and self.duration_s is not None
            return StepImpulse.from_g(self.magnitude_g, self.duration_s, self.direction, g=g,
                                      vertical=self.vertical_ratio or 0.0)
        if self.kind is ExcitationKind.SINE:
            assert self.magnitude_g is not None and self.period_s is not None
            return SinePulse.from_g(self.magnitude_g, self.period_s, self.direction, g=g,
                                    vertical=self.vertical_ratio or 0.0)
        if self.motion is not None:
            assert self.scale is not None  # __post_init__ sets it for a record
            if self.direction < 0 and has_vertical(self.motion):  # the horizontal only
                return self.motion.mirrored().scaled(self.scale)
            return self.motion.scaled(self.scale * self.direction)
        return _load_record(self, g=g)

    @property
    def record_name(self) -> str | None:
        """The record's label: its file name, or an in-memory motion's ``name``."""
        if self.file:
            return Path(self.file).name
        if self.motion is not None:
            return motion_name(self.motion)
        return None

    def canonical(self) -> dict[str, Any]:
        out: dict[str, Any] = {"type": self.kind.value, "direction": self.direction}
        if self.kind is ExcitationKind.RECORD:
            out.update(record=self.record_name, record_sha256=self.file_sha256,
                       units=self.units, scale=self.scale)
        elif self.kind is ExcitationKind.STEP:
            out.update(magnitude_g=self.magnitude_g, duration_s=self.duration_s)
        else:
            out.update(magnitude_g=self.magnitude_g, period_s=self.period_s)
        if self.vertical_ratio:  # only when given: the ids of cases without one stay
            out.update(vertical_ratio=self.vertical_ratio)
        return out

    @cached_property
    def canonical_json(self) -> str:
        """`canonical_json` of `canonical`, computed once per spec."""
        return canonical_json(self.canonical())


def file_digest(path: str | Path) -> str:
    """SHA-256 (hex) of a file's bytes; a missing file is a one-line error naming it."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError as exc:
        raise InvalidParameterError(
            f"cannot read record file {str(path)!r}: {exc.strerror}") from None


def motion_name(motion: Any) -> str:
    """Label of an in-memory motion: its ``name`` attribute, else its class name."""
    name = getattr(motion, "name", None)
    return name if isinstance(name, str) and name else type(motion).__name__


def motion_digest(motion: Any) -> str:
    """SHA-256 (hex) of a ground motion's compiled description (its kind and parameters, e.g.
    a record's t0, dt and samples in m/s^2): equal motions give equal digests on any machine."""
    try:
        kind, params = motion.kernel_spec()
    except AttributeError:
        raise InvalidParameterError(f"motion must be a ground motion with kernel_spec(), got "
                                    f"{type(motion).__name__}") from None
    h = hashlib.sha256(str(int(kind)).encode())
    h.update(np.ascontiguousarray(params, dtype="<f8").tobytes())
    return h.hexdigest()


def _load_record(spec: ExcitationSpec, *, g: float):
    """Read a record file into a GroundMotion in m/s^2, scaled and signed as the spec says."""
    from archquake.ground.records import read_record

    assert spec.file is not None and spec.scale is not None and spec.direction is not None
    return read_record(spec.file, units=spec.units, scale=spec.scale * spec.direction, g=g)



def _set(obj: object, name: str, value: object) -> None:
    object.__setattr__(obj, name, value)


__all__ = ["ExcitationKind", "ExcitationSpec", "RECORD_UNITS", "file_digest", "motion_digest",
           "motion_name"]
