"""The analytical model beside the distinct-element model (paper pp. 2131-2135, Figures 4(b)-(d),
6, 9, 10, 11): time histories, failure domains, snapshots."""

from archquake.compare.histories import (
    ASSEMBLIES,
    FIGURE4_DURATIONS,
    HINGES,
    VOUSSOIRS,
    HistoryComparison,
    compare_history,
    default_dem_duration,
    dem_assembly,
    dem_collapse_half_cycle,
    dem_crossings,
    dem_half_cycles,
    dem_summary,
    figure4_comparisons,
    first_half_cycle_difference,
    three_voussoir_assembly,
)

__all__ = [
    "ASSEMBLIES",
    "FIGURE4_DURATIONS",
    "HINGES",
    "VOUSSOIRS",
    "HistoryComparison",
    "compare_history",
    "default_dem_duration",
    "dem_assembly",
    "dem_collapse_half_cycle",
    "dem_crossings",
    "dem_half_cycles",
    "dem_summary",
    "figure4_comparisons",
    "first_half_cycle_difference",
    "three_voussoir_assembly",
]
