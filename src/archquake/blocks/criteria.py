"""What both block models (the distinct-element model and the rigid chain) read to classify a
run: the hinge threshold and the collapse criteria (`BlockCriteria`), the record of a run's
length and sampling (`BlockRunSettings`), and the default window of a run
(`default_window`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from archquake._validate import require_positive
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError

#: Longest simulated time a block model's run accepts, s: beyond it a run would never end.
MAX_DURATION = 1.0e6


@dataclass(frozen=True)
class BlockCriteria:
    """How a block model's samples are read: when a joint is a hinge, when the arch has
    collapsed, and whether the run stops there.

    Parameters
    ----------
    hinge_opening : float
        A joint counts as open (a hinge) when its gap exceeds this fraction of the assembly's
        reference length (the arch thickness t) (> 0).
    collapse_rotation : float
        Collapse when any block has turned by more than this, rad (> 0).
    collapse_drop : float
        Collapse when the crown point drops by more than this fraction of the reference
        length (> 0).
    stop_at_collapse : bool
        Stop the run at the first output sample that meets a collapse criterion.

    Examples
    --------
    >>> BlockCriteria(collapse_drop=0.5).to_dict()["collapse_drop"]
    0.5
    """

    hinge_opening: float = 1.0e-4
    collapse_rotation: float = 0.5 * math.pi
    collapse_drop: float = 1.0
    stop_at_collapse: bool = True

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "collapse_drop", require_positive("collapse_drop", self.collapse_drop)
        )
        object.__setattr__(
            self,
            "collapse_rotation",
            require_positive("collapse_rotation", self.collapse_rotation, "rad"),
        )
        object.__setattr__(
            self, "hinge_opening", require_positive("hinge_opening", self.hinge_opening)
        )
        object.__setattr__(self, "stop_at_collapse", bool(self.stop_at_collapse))

    def to_dict(self) -> dict:
        """The JSON keys: ``collapse_drop``, ``collapse_rotation_rad``, ``hinge_opening``."""
        return {
            "collapse_drop": self.collapse_drop,
            "collapse_rotation_rad": self.collapse_rotation,
            "hinge_opening": self.hinge_opening,
        }


@dataclass(frozen=True)
class BlockRunSettings:
    """The settings a block model's result records: its `BlockCriteria`, the run's planned
    length ``duration`` (s), its ``time_step`` (s) and ``output_interval`` (s). The
    distinct-element model records its whole `archquake.dem.DemSettings` instead (which has
    these and its contact law, damping and settling)."""

    criteria: BlockCriteria
    duration: float
    time_step: float
    output_interval: float

    def to_dict(self) -> dict:
        """``duration_s``, ``output_interval_s``, ``time_step_s``, then the criteria's keys."""
        return {"duration_s": self.duration, "output_interval_s": self.output_interval,
                "time_step_s": self.time_step, **self.criteria.to_dict()}


def block_criteria(settings: object, *, caller: str) -> BlockCriteria:
    """``settings`` as a `BlockCriteria`: itself, the default for None, or (deprecated,
    with a `DeprecationWarning`) the criteria of settings that hold some, such as a
    `archquake.dem.DemSettings`. ``caller`` names the function in the warning."""
    if settings is None:
        return BlockCriteria()
    if isinstance(settings, BlockCriteria):
        return settings
    criteria = getattr(settings, "criteria", None)
    if isinstance(criteria, BlockCriteria):
        warnings.warn(
            f"{caller}: pass the thresholds as a BlockCriteria (settings.criteria), not a "
            f"{type(settings).__name__}; this is accepted until the next release",
            DeprecationWarning, stacklevel=3)
        return criteria
    raise InvalidParameterError(
        f"{caller}: settings must be a BlockCriteria, got {type(settings).__name__}")


#: Seconds simulated after the end of the excitation, in units of sqrt(R/g), when no duration
#: is given: Oppenheim's arch at a = 1.0 g, t_p = 0.27 s collapses 2.4 s after the impulse ends
#: (3.18 s; 3.35 s under the mirror-image pulse), so 5 sqrt(R/g) (5.05 s there) covers the
#: second half cycle.
DEFAULT_TAIL = 5.0


def default_window(motion, radius: float, *, tail: float = DEFAULT_TAIL,
                   g: float = STANDARD_GRAVITY) -> float:
    """The default length of a block model's run, s: the end of the excitation (the motion's
    ``duration``, s) plus ``tail`` sqrt(R/g), R = ``radius`` (m), g in m/s^2.

    Examples
    --------
    >>> from archquake.ground import StepImpulse
    >>> round(default_window(StepImpulse.from_g(1.0, 0.27), 10.0), 3)  # ends at 3 t_p
    5.859
    """
    return float(motion.duration) + float(tail) * math.sqrt(float(radius) / g)


__all__ = ["DEFAULT_TAIL", "MAX_DURATION", "BlockCriteria", "BlockRunSettings", "block_criteria",
           "default_window"]
