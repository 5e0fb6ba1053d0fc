"""What archquake is checked against, kept apart from the models:

- `archquake.validation.paper`: every number De Lorenzis, DeJong & Ochsendorf (2007) state,
  with its tolerance, the reason for it and its page; Oppenheim's arch; the figures' parameters;
- `archquake.validation.housner`: the closed forms of a rigid rocking block (Housner 1963);
- `archquake.validation.trl_bridges`: TRL's full-scale load tests to collapse of masonry arch
  bridges, what is published of each bridge with its source, and archquake's collapse load for
  Prestwood (docs/loads.md, "Against the full-scale tests").

``archquake reproduce`` and the tests under ``tests/paper`` read them from here.
"""

from archquake.validation.housner import (
    fall_time,
    free_rocking,
    frequency_parameter,
    onset_acceleration,
    rectangular_pulse_overturning,
    restitution,
    restitution_from_inertia,
    slenderness,
)
from archquake.validation.paper import CITATION, Agreement, PaperValue, oppenheim_arch

__all__ = [
    "Agreement",
    "CITATION",
    "PaperValue",
    "fall_time",
    "free_rocking",
    "frequency_parameter",
    "onset_acceleration",
    "oppenheim_arch",
    "rectangular_pulse_overturning",
    "restitution",
    "restitution_from_inertia",
    "slenderness",
]
