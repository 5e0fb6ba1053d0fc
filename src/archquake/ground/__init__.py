"""Ground motions: the step impulse, the one-cycle sine pulse, recorded accelerograms, their
intensity measures and record suites."""

from archquake.ground.base import GroundMotion
from archquake.ground.measures import (
    IntensityMeasure,
    IntensityMeasures,
    im_value,
    intensity_measures,
    parse_im,
    response_spectrum,
    scale_to,
)
from archquake.ground.pulses import SinePulse, StepImpulse
from archquake.ground.records import Record, read_at2, read_csv, read_record

__all__ = [
    "GroundMotion",
    "IntensityMeasure",
    "IntensityMeasures",
    "Record",
    "SinePulse",
    "StepImpulse",
    "im_value",
    "intensity_measures",
    "parse_im",
    "read_at2",
    "read_csv",
    "read_record",
    "response_spectrum",
    "scale_to",
]
