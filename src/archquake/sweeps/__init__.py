"""Parameter sweeps: frozen cases with stable ids, mapped through any executor, stored
resumably in SQLite.

>>> from archquake.sweeps import ArchSpec, Case, ExcitationSpec
>>> case = Case(ArchSpec(10, 0.15, 157.5, 7), ExcitationSpec("sine", magnitude_g=0.4, period_s=1))
>>> case.canonical()["excitation"]
{'type': 'sine', 'direction': -1, 'magnitude_g': 0.4, 'period_s': 1.0}
"""

import sys
from typing import TYPE_CHECKING

from archquake._lazy import attach

#: Public names -> their module, imported on first access (a command that needs only the
#: cases' vocabulary does not load the runner, the store and the study reader).
_LAZY: dict[str, str] = {
    **dict.fromkeys(("ArchSpec", "Case", "CaseOptions", "ExcitationKind", "ExcitationSpec"),
                    "archquake.sweeps.cases"),
    **dict.fromkeys(("ModelUnavailableError", "evaluate_case"), "archquake.sweeps.evaluate"),
    **dict.fromkeys(("SweepReport", "run_sweep"), "archquake.sweeps.runner"),
    **dict.fromkeys(("CaseRecord", "ResultStore"), "archquake.sweeps.store"),
    **dict.fromkeys(("Study", "load_study", "parse_study"), "archquake.sweeps.study"),
}

if TYPE_CHECKING:  # pragma: no cover - what the lazy names resolve to, for type checkers
    from archquake.sweeps.cases import (
        ArchSpec,
        Case,
        CaseOptions,
        ExcitationKind,
        ExcitationSpec,
    )
    from archquake.sweeps.evaluate import ModelUnavailableError, evaluate_case
    from archquake.sweeps.runner import SweepReport, run_sweep
    from archquake.sweeps.store import CaseRecord, ResultStore
    from archquake.sweeps.study import Study, load_study, parse_study

__getattr__, __dir__ = attach(sys.modules[__name__], _LAZY)

__all__ = [
    "ArchSpec",
    "Case",
    "CaseOptions",
    "CaseRecord",
    "ExcitationKind",
    "ExcitationSpec",
    "ModelUnavailableError",
    "ResultStore",
    "Study",
    "SweepReport",
    "evaluate_case",
    "load_study",
    "parse_study",
    "run_sweep",
]
