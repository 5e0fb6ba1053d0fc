"""The paper's parametric studies: scale (Figure 6), geometry (Figure 7), impulse shape (Figure 11).

Each study computes plain `FailureDomain` objects; a geometry the
model cannot handle is reported in the case, never silently dropped: an arch that cannot stand
(`UnstableArchError`) has no domain and says why, and an arch whose
impact model gives c_v > 1 (the five momentum balances create energy; see
`archquake.mechanism.impact`) keeps its domain but is flagged, since with c_v > 1 free
rocking grows at every impact and any hinging ends in collapse given time.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from archquake.constants import STANDARD_GRAVITY
from archquake.errors import ArchquakeError
from archquake.geometry.arch import Arch
from archquake.ground.pulses import PulseFamily
from archquake.validation.paper import (
    FIGURE6_RADII,
    FIGURE7_EMBRACES_DEG,
    FIGURE7_RATIOS,
    oppenheim_arch,
)

from .domain import FIGURE5_DURATIONS, DomainSettings, FailureDomain, failure_domain

#: Figure 6: radii, m; Figure 7: thickness ratios at 157.5 degrees, and embraces (degrees) at
#: t/R = 0.15 (the paper's parameters live in `archquake.validation.paper`).
SCALE_RADII = FIGURE6_RADII
GEOMETRY_RATIOS = FIGURE7_RATIOS
GEOMETRY_EMBRACES_DEG = FIGURE7_EMBRACES_DEG
#: Figure 7's durations t_p, s.
FIGURE7_DURATIONS = tuple(np.linspace(0.05, 1.0, 30).tolist())


@dataclass(frozen=True)
class StudyCase:
    """One arch of a study: its label, the arch, its domain (None if there is none) and what
    was noticed (``problem``: why there is no domain, or a warning such as energy gain)."""

    label: str
    arch: Arch
    domain: FailureDomain | None
    problem: str | None = None

    def to_dict(self) -> dict:
        return {"label": self.label, "arch": self.arch.describe(), "problem": self.problem,
                "domain": None if self.domain is None else self.domain.to_dict(),
                "restitution_cv": None if self.domain is None else self.domain.restitution_cv}


def study_case(label: str, arch: Arch, family: PulseFamily | str, durations,
               settings: DomainSettings | None,
               *, g: float = STANDARD_GRAVITY, impact: str | None = None) -> StudyCase:
    """The domain of one arch under the impact law ``impact`` (None: "paper", as the paper's
    studies), with any problem stated."""
    try:
        dom = failure_domain(arch, family, durations, settings=settings, g=g, impact=impact, model="fourlink")
    except ArchquakeError as exc:  # e.g. UnstableArchError: the arch cannot stand
        return StudyCase(label, arch, None, str(exc))
    problem = None
    if dom.energy_gain:
        problem = (f"impact model gives c_v = {dom.restitution_cv:.4f} > 1 (energy gain at impact): "
                   "free rocking grows, so the collapse boundary is not meaningful")
    elif not dom.impact_described:
        problem = (f"impact law {dom.impact_law!r} does not describe this arch's impacts "
                   f"(validity {dom.impact_validity}): a collapse after an impact is indeterminate")
    return StudyCase(label, arch, dom, problem)


def scale_study(radii=SCALE_RADII, durations=FIGURE5_DURATIONS, *,
                family: PulseFamily | str = PulseFamily.STEP,
                settings: DomainSettings | None = None,
                g: float = STANDARD_GRAVITY) -> tuple[StudyCase, ...]:
    """Figure 6: Oppenheim's proportions at several radii (m)."""
    return tuple(study_case(f"R = {r:g} m", oppenheim_arch(radius=r), family, durations, settings,
                            g=g) for r in radii)


def geometry_study(ratios=GEOMETRY_RATIOS, embraces_deg=GEOMETRY_EMBRACES_DEG,
                   durations=FIGURE7_DURATIONS, *,
                   family: PulseFamily | str = PulseFamily.STEP,
                   settings: DomainSettings | None = None,
                   g: float = STANDARD_GRAVITY) -> tuple[tuple[StudyCase, ...], tuple[StudyCase, ...]]:
    """Figure 7: (t/R series at 157.5 degrees, embrace series at t/R = 0.15), R = 10 m, 7 voussoirs."""
    by_ratio = tuple(study_case(f"t/R = {r:g}", oppenheim_arch(thickness_ratio=r), family, durations,
                                settings, g=g) for r in ratios)
    by_embrace = tuple(study_case(f"embrace = {b:g} deg", oppenheim_arch(embrace_deg=b), family,
                                  durations, settings, g=g) for b in embraces_deg)
    return by_ratio, by_embrace


__all__ = ["GEOMETRY_EMBRACES_DEG", "GEOMETRY_RATIOS", "SCALE_RADII", "StudyCase", "geometry_study",
           "oppenheim_arch", "scale_study", "study_case"]
