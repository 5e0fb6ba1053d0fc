"""A recorded horizontal component with its vertical component: `WithVertical`.

The vertical is an upward ground acceleration a_v(t), m/s^2, read by the models that take it as
gravity g + a_v(t). Both components keep their own samples (their own time steps); scaling
scales both, mirroring reverses the horizontal only (it flips the arch's side, not up and down).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from archquake._validate import require_finite, require_instance
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
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
    Read by the rigid chain (its time stepper and its verdict path). A model that reads the
    motion only through its compiled description (``kernel_spec``) does not take the vertical
    of a record yet, and `kernel_spec` says so in one line rather than dropping the
    vertical silently.
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

    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """The horizontal ground acceleration, m/s^2 (`Record.acceleration`)."""
        return self.horizontal.acceleration(t)

    def vertical_acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """The upward ground acceleration, m/s^2."""
        return self.vertical.acceleration(t)

    def breakpoints(self) -> np.ndarray:
        return np.union1d(self.horizontal.breakpoints(), self.vertical.breakpoints())

    def kernel_spec(self) -> tuple[int, np.ndarray]:
        raise InvalidParameterError(
            "a record's vertical component is read by the rigid chain only (--model rigid, "
            "without --integrator events): leave "
            "--record-vertical out for this model or command")

    def mirrored(self) -> WithVertical:
        return WithVertical(self.horizontal.mirrored(), self.vertical)

    def scaled(self, factor: float) -> WithVertical:
        f = require_finite("scale factor", factor)
        return WithVertical(self.horizontal.scaled(f), self.vertical.scaled(f))

    def to_dict(self, *, g: float = STANDARD_GRAVITY) -> dict:
        return self.horizontal.to_dict(g=g) | {"vertical": self.vertical.to_dict(g=g)}


__all__ = ["WithVertical"]
