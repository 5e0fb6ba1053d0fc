"""Ground motions: the step impulse, the one-cycle sine pulse and recorded accelerograms."""

from archquake.ground.base import GroundMotion
from archquake.ground.pulses import SinePulse, StepImpulse

__all__ = ["GroundMotion", "SinePulse", "StepImpulse"]
