"""Ground motions: the step impulse, the one-cycle sine pulse (and their families), recorded
accelerograms, their intensity measures and record suites."""

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
from archquake.ground.pulses import PulseFamily, SinePulse, StepImpulse
from archquake.ground.records import (
    Record,
    baseline_corrected,
    read_at2,
    read_csv,
    read_record,
    resampled,
)
from archquake.ground.suites import Suite, available_suites, load_suite

__all__ = [
    "GroundMotion",
    "IntensityMeasure",
    "IntensityMeasures",
    "PulseFamily",
    "Record",
    "SinePulse",
    "StepImpulse",
    "Suite",
    "available_suites",
    "baseline_corrected",
    "im_value",
    "intensity_measures",
    "load_suite",
    "parse_im",
    "read_at2",
    "read_csv",
    "read_record",
    "resampled",
    "response_spectrum",
    "scale_to",
]
