"""Failure domains: pulse magnitudes and durations that collapse the arch (paper Figures 5-7, 11),
searched by scan and batched bisection on a compiled, parallel batch of time histories."""

from archquake.domains.batch import (
    PulseOutcomes,
    evaluate_pulses,
)
from archquake.domains.domain import (
    COLLAPSE,
    FIRST_HALF_CYCLE,
    DomainSettings,
    FailureDomain,
    NonMonotonicBand,
    failure_domain,
)
from archquake.domains.scaling import (
    ScalingComparison,
    compare_scaling,
    paper_boundary,
    similar_boundary,
)
from archquake.domains.studies import (
    StudyCase,
    geometry_study,
    oppenheim_arch,
    scale_study,
    study_case,
)
from archquake.ground.pulses import PulseFamily  # the family the domain search takes

__all__ = [
    "COLLAPSE",
    "FIRST_HALF_CYCLE",
    "DomainSettings",
    "FailureDomain",
    "NonMonotonicBand",
    "PulseFamily",
    "PulseOutcomes",
    "ScalingComparison",
    "StudyCase",
    "compare_scaling",
    "evaluate_pulses",
    "failure_domain",
    "geometry_study",
    "oppenheim_arch",
    "paper_boundary",
    "scale_study",
    "similar_boundary",
    "study_case",
]
