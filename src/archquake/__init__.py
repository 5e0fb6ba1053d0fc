"""archquake: masonry arches under impulse base motion and earthquakes.

Limit analysis, the four-link rocking mechanism with impacts, failure domains, the line of
thrust during motion, and a distinct-element model, after De Lorenzis, DeJong & Ochsendorf
(2007), *Failure of masonry arches under impulse base motion*, EESD 36:2119-2136.

SI units throughout (m, s, kg, rad); accelerations in m/s^2 unless a name ends in ``_g``.

The verbs and nouns of the package are one import away, and loaded only when first used
(PEP 562), so ``import archquake`` costs little more than importing numpy:

>>> import math
>>> from archquake import Arch, StepImpulse, limit_analysis, simulate
>>> arch = Arch(radius=10.0, thickness=1.5, embrace=math.radians(157.5), voussoirs=7)
>>> round(limit_analysis(arch).collapse_acceleration_g, 2)  # Oppenheim's arch, paper p. 2126
0.37
>>> simulate(arch, StepImpulse.from_g(1.0, 0.27)).outcome.value  # paper Figure 4(c)
'collapse'

``Arch``, ``limit_analysis``, ``run`` (any of the three models by its name, ``Model``, with
``RunOptions``; the default, as on the command line, is the chain of rigid voussoirs),
``simulate`` (the paper's four-link model: hinges fixed between impacts),
``simulate_rigid`` (the chain of rigid voussoirs: hinges that move), ``simulate_dem``,
``failure_domain``,
``StepImpulse``, ``SinePulse``, ``Record``, ``read_record``, ``Outcome``, ``ModelResult`` (what
the three models' results have in common), the error classes,
the `errors` module and ``g`` (standard gravity, m/s^2). Everything else lives
in its subpackage (``archquake.domains``, ``archquake.dem``, ...).
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING

from archquake import errors
from archquake._kernel_cache import ensure_cache_dir
from archquake._lazy import attach
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import (
    ArchquakeError,
    GroundMotionFormatError,
    InvalidParameterError,
    SolverError,
    StudyFileError,
    UnstableArchError,
)

__version__ = "0.1.0"

ensure_cache_dir()  # before any kernel module imports numba (see archquake._kernel_cache)

#: Standard gravity, m/s^2 (the value every function takes as its default ``g=``).
g: float = STANDARD_GRAVITY

#: Lazily loaded public names -> the module that defines (or re-exports) them. Each is imported
#: on first access only; a type checker reads the same names from the block below.
_LAZY: dict[str, str] = {
    "Arch": "archquake.geometry",
    "Face": "archquake.geometry",
    "Hinge": "archquake.geometry",
    "HingeMechanism": "archquake.geometry",
    "limit_analysis": "archquake.limit",
    "simulate": "archquake.mechanism",
    "run": "archquake.models",
    "Model": "archquake.models",
    "RunOptions": "archquake.models",
    "Outcome": "archquake.outcome",
    "ModelResult": "archquake.result",
    "simulate_dem": "archquake.dem",
    "simulate_rigid": "archquake.rigid",
    "failure_domain": "archquake.domains",
    "StepImpulse": "archquake.ground",
    "SinePulse": "archquake.ground",
    "Record": "archquake.ground",
    "read_record": "archquake.ground",
}

if TYPE_CHECKING:  # pragma: no cover - what the lazy names resolve to, for type checkers
    from archquake.dem import simulate_dem
    from archquake.domains import failure_domain
    from archquake.geometry import Arch, Face, Hinge, HingeMechanism
    from archquake.ground import Record, SinePulse, StepImpulse, read_record
    from archquake.limit import limit_analysis
    from archquake.mechanism.simulate import simulate
    from archquake.models import Model, RunOptions, run
    from archquake.outcome import Outcome
    from archquake.result import ModelResult
    from archquake.rigid import simulate_rigid


__getattr__, __dir__ = attach(sys.modules[__name__], _LAZY)


__all__ = [
    "Arch",
    "ArchquakeError",
    "Face",
    "GroundMotionFormatError",
    "Hinge",
    "HingeMechanism",
    "InvalidParameterError",
    "Model",
    "ModelResult",
    "Outcome",
    "Record",
    "RunOptions",
    "STANDARD_GRAVITY",
    "SinePulse",
    "SolverError",
    "StepImpulse",
    "StudyFileError",
    "UnstableArchError",
    "__version__",
    "errors",
    "failure_domain",
    "g",
    "limit_analysis",
    "read_record",
    "run",
    "simulate",
    "simulate_dem",
    "simulate_rigid",
]
