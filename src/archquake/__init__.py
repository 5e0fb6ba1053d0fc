"""archquake: masonry arches under impulse base motion and earthquakes.

Limit analysis, the four-link rocking mechanism with impacts, failure domains, the line of
thrust during motion, and a distinct-element model, after De Lorenzis, DeJong & Ochsendorf
(2007), *Failure of masonry arches under impulse base motion*, EESD 36:2119-2136.

SI units throughout (m, s, kg, rad); accelerations in m/s^2 unless a name ends in ``_g``.
"""

from archquake.constants import STANDARD_GRAVITY
from archquake.errors import (
    ArchquakeError,
    GroundMotionFormatError,
    InvalidParameterError,
    SolverError,
    StudyFileError,
    UnstableArchError,
)
from archquake.geometry import Arch, Face, Hinge, HingeMechanism

__version__ = "0.1.0"

__all__ = [
    "STANDARD_GRAVITY",
    "Arch",
    "ArchquakeError",
    "Face",
    "GroundMotionFormatError",
    "Hinge",
    "HingeMechanism",
    "InvalidParameterError",
    "SolverError",
    "StudyFileError",
    "UnstableArchError",
    "__version__",
]
