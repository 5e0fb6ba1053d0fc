"""A recorded horizontal component with its vertical component: `WithVertical`.

The vertical is an upward ground acceleration a_v(t), m/s^2, read by every model as gravity
g + a_v(t). Both components keep their own samples (their own time steps) here and in the
compiled description (`KIND_SAMPLED_VERTICAL`); scaling scales both, mirroring reverses the
horizontal only (it flips the arch's side, not up and down).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from archquake._validate import require_finite, require_instance
from archquake.constants import STANDARD_GRAVITY
from archquake.ground.base import KIND_SAMPLED_VERTICAL
from archquake.ground.records import Record


@dataclass(frozen=True)
class WithVertical:
    """A record (horizontal, positive towards +x) with its vertical component (positive upward).

    Parameters
    ----------
    horizontal : Record
    vertical : Record
        The vertical ground acceleration, m/s^2, upward (PEER's ``-UP``/``-V`` files).

    Notes
    -----
    Read by the rigid chain's time stepper and verdict path through `vertical_acceleration`,
    and by the four-link model, the DEM and the rigid chain's event integrator through
    `kernel_spec` (``KIND_SAMPLED_VERTICAL``: each component on its own time step, no
    resampling, breakpoints at both components' sample times). Where a suite, the intensity
    measures or IDA read a record's description (``dt``, ``accelerations``, ``metadata``...),
    it is the horizontal's.
    """

    horizontal: Record
    vertical: Record

    def __post_init__(self) -> None:
        require_instance("horizontal", self.horizontal, Record, "a Record")
        require_instance("vertical", self.vertical, Record, "a Record")

    @property
    def name(self) -> str:
        return f"{self.horizontal.name} + {self.vertical.name} (vertical)"

    @property
    def duration(self) -> float:
        return max(self.horizontal.duration, self.vertical.duration)

    # the horizontal's description, where a suite, the intensity measures and IDA read a record
    @property
    def accelerations(self) -> np.ndarray:
        """The horizontal's samples, m/s^2 (the record's intensity measures are its)."""
        return self.horizontal.accelerations

    @property
    def dt(self) -> float:
        return self.horizontal.dt

    @property
    def t0(self) -> float:
        return self.horizontal.t0

    @property
    def points(self) -> int:
        return self.horizontal.points

    @property
    def scale(self) -> float:
        return self.horizontal.scale

    @property
    def component(self) -> str | None:
        return self.horizontal.component

    @property
    def source(self) -> str | None:
        return self.horizontal.source

    @property
    def metadata(self) -> dict:
        return self.horizontal.metadata

    @property
    def peak(self) -> float:
        return self.horizontal.peak

    @property
    def time_of_peak(self) -> float:
        return self.horizontal.time_of_peak

    def truncated(self, end: float) -> WithVertical:
        """Both components' samples at t <= ``end`` (s), `Record.truncated`."""
        return WithVertical(self.horizontal.truncated(end), self.vertical.truncated(end))

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """The horizontal ground acceleration, m/s^2 (`Record.acceleration`)."""
        return self.horizontal.acceleration(t)

    def vertical_acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """The upward ground acceleration, m/s^2."""
        return self.vertical.acceleration(t)

    def breakpoints(self) -> np.ndarray:
        return np.union1d(self.horizontal.breakpoints(), self.vertical.breakpoints())

    def kernel_spec(self) -> tuple[int, np.ndarray]:
        """``(KIND_SAMPLED_VERTICAL, [N, t0, dt, x_0..x_{N-1}, t0v, dtv, v_0..v_{M-1}])``.

        >>> both = WithVertical(Record([0.0, 1.0, 0.0], 0.5), Record([2.0, 2.0], 1.0))
        >>> kind, params = both.kernel_spec()
        >>> kind, params.tolist()
        (3, [3.0, 0.0, 0.5, 0.0, 1.0, 0.0, 0.0, 1.0, 2.0, 2.0])
        """
        h = self.horizontal.kernel_spec()[1]
        v = self.vertical.kernel_spec()[1]
        return KIND_SAMPLED_VERTICAL, np.concatenate(([float(h.size - 2)], h, v))

    def mirrored(self) -> WithVertical:
        return WithVertical(self.horizontal.mirrored(), self.vertical)

    def scaled(self, factor: float) -> WithVertical:
        f = require_finite("scale factor", factor)
        return WithVertical(self.horizontal.scaled(f), self.vertical.scaled(f))

    def to_dict(self, *, g: float = STANDARD_GRAVITY) -> dict:
        return self.horizontal.to_dict(g=g) | {"vertical": self.vertical.to_dict(g=g)}


__all__ = ["WithVertical"]
