"""Ground motions: the step impulse, the one-cycle sine pulse (and their families), recorded
accelerograms, their intensity measures and record suites.

The intensity measures (`archquake.ground.measures`, which compiles a numba kernel) are
imported on first use (PEP 562), so that a command that only builds a motion does not import
numba."""

import sys
from typing import TYPE_CHECKING

from archquake._lazy import attach
from archquake.ground.base import GroundMotion
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

#: Names loaded on first access, and the module that defines them.
_LAZY: dict[str, str] = {
    name: "archquake.ground.measures"
    for name in ("IntensityMeasure", "IntensityMeasures", "im_value", "intensity_measures",
                 "parse_im", "response_spectrum", "scale_to")
}

if TYPE_CHECKING:  # pragma: no cover - what the lazy names resolve to, for type checkers
    from archquake.ground.measures import (
        IntensityMeasure,
        IntensityMeasures,
        im_value,
        intensity_measures,
        parse_im,
        response_spectrum,
        scale_to,
    )


__getattr__, __dir__ = attach(sys.modules[__name__], _LAZY)


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
