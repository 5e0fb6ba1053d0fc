"""Parameter sweeps: frozen cases with stable ids, mapped through any executor, stored
resumably in SQLite.

>>> from archquake.sweeps import ArchSpec, Case, ExcitationSpec
>>> case = Case(ArchSpec(10, 0.15, 157.5, 7), ExcitationSpec("sine", magnitude_g=0.4, period_s=1))
>>> case.canonical()["excitation"]
{'type': 'sine', 'direction': -1, 'magnitude_g': 0.4, 'period_s': 1.0}
"""

from archquake.sweeps.cases import (
    DEFAULT_MODEL,
    ArchSpec,
    Case,
    CaseOptions,
    ExcitationKind,
    ExcitationSpec,
    Model,
    model_of,
)
from archquake.sweeps.evaluate import ModelUnavailableError, evaluate_case, model_function
from archquake.sweeps.runner import SweepReport, run_sweep
from archquake.sweeps.store import CaseRecord, ResultStore
from archquake.sweeps.study import Study, load_study, parse_study

__all__ = [
    "ArchSpec",
    "Case",
    "CaseOptions",
    "CaseRecord",
    "ExcitationKind",
    "ExcitationSpec",
    "DEFAULT_MODEL",
    "Model",
    "model_of",
    "ModelUnavailableError",
    "ResultStore",
    "Study",
    "SweepReport",
    "evaluate_case",
    "load_study",
    "model_function",
    "parse_study",
    "run_sweep",
]
