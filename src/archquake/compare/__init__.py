"""The four-link model beside the distinct-element model (paper pp. 2131-2135, Figures 4(b)-(d),
6, 9, 10, 11): time histories, failure domains, snapshots.

Each name is imported from its module on first use (PEP 562), so that a command that needs one
function does not import the studies of the others."""

import sys
from typing import TYPE_CHECKING

from archquake._lazy import attach

#: Every public name -> the module that defines it.
_LAZY: dict[str, str] = {
    "ASSEMBLIES": "archquake.compare.histories",
    "DEM_DOMAIN_SETTINGS": "archquake.compare.domains",
    "DemDomain": "archquake.compare.domains",
    "DemPulseEvaluator": "archquake.compare.domains",
    "DomainComparison": "archquake.compare.domains",
    "FIGURE10_DAMPING": "archquake.compare.snapshots",
    "FIGURE10_PULSE": "archquake.compare.snapshots",
    "FIGURE10_TIME": "archquake.compare.snapshots",
    "FIGURE9_TIMES": "archquake.compare.snapshots",
    "HINGES": "archquake.compare.histories",
    "HingeComparison": "archquake.compare.snapshots",
    "HistoryComparison": "archquake.compare.histories",
    "ReducedDampingSnapshot": "archquake.compare.snapshots",
    "VOUSSOIRS": "archquake.compare.histories",
    "compare_domains": "archquake.compare.domains",
    "compare_hinges": "archquake.compare.snapshots",
    "compare_history": "archquake.compare.histories",
    "default_dem_duration": "archquake.dem.run",
    "dem_assembly": "archquake.compare.histories",
    "dem_failure_domain": "archquake.compare.domains",
    "dem_hinges": "archquake.compare.snapshots",
    "figure4_comparisons": "archquake.compare.histories",
    "first_half_cycle_difference": "archquake.compare.histories",
    "joint_displacements": "archquake.compare.snapshots",
    "reduced_damping_snapshot": "archquake.compare.snapshots",
    "three_voussoir_assembly": "archquake.compare.histories",
}

if TYPE_CHECKING:  # pragma: no cover - what the lazy names resolve to, for type checkers
    from archquake.compare.domains import (
        DEM_DOMAIN_SETTINGS,
        DemDomain,
        DemPulseEvaluator,
        DomainComparison,
        compare_domains,
        dem_failure_domain,
    )
    from archquake.compare.histories import (
        ASSEMBLIES,
        HINGES,
        VOUSSOIRS,
        HistoryComparison,
        compare_history,
        dem_assembly,
        figure4_comparisons,
        first_half_cycle_difference,
        three_voussoir_assembly,
    )
    from archquake.compare.snapshots import (
        FIGURE9_TIMES,
        FIGURE10_DAMPING,
        FIGURE10_PULSE,
        FIGURE10_TIME,
        HingeComparison,
        ReducedDampingSnapshot,
        compare_hinges,
        dem_hinges,
        joint_displacements,
        reduced_damping_snapshot,
    )
    from archquake.dem.run import default_dem_duration


__getattr__, __dir__ = attach(sys.modules[__name__], _LAZY)


__all__ = [
    "DEM_DOMAIN_SETTINGS",
    "DemDomain",
    "DemPulseEvaluator",
    "DomainComparison",
    "FIGURE10_DAMPING",
    "FIGURE10_PULSE",
    "FIGURE10_TIME",
    "FIGURE9_TIMES",
    "HingeComparison",
    "ReducedDampingSnapshot",
    "compare_domains",
    "compare_hinges",
    "dem_failure_domain",
    "dem_hinges",
    "joint_displacements",
    "reduced_damping_snapshot",
    "ASSEMBLIES",
    "HINGES",
    "VOUSSOIRS",
    "HistoryComparison",
    "compare_history",
    "default_dem_duration",
    "dem_assembly",
    "figure4_comparisons",
    "first_half_cycle_difference",
    "three_voussoir_assembly",
]
