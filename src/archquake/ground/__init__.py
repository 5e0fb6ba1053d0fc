"""Ground motions: the step impulse, the one-cycle sine pulse and recorded accelerograms."""

from archquake.ground.base import GroundMotion
from archquake.ground.pulses import SinePulse, StepImpulse
from archquake.ground.records import Record, read_at2, read_csv, read_record

__all__ = [
    "GroundMotion",
    "Record",
    "SinePulse",
    "StepImpulse",
    "read_at2",
    "read_csv",
    "read_record",
]
