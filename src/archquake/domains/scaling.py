"""Scale effect (paper Figure 6): exact dynamic similarity against the paper's sqrt(R) rule.

For geometrically similar arches (same t/R, embrace and voussoirs) the equation of motion
(Eq. 2) divided by the link masses reads ``R m(phi) phi'' + R/2 m'(phi) phi'^2 + g G(phi) +
x_g'' H(phi) = 0`` with m, G, H dimensionless functions of the proportions only; the impact
(c_v, Eq. 5) is scale-free too. With time measured in sqrt(R/g), nothing depends on R: the arch
k R under a pulse (a, sqrt(k) t_p) moves exactly as the arch R under (a, t_p), at sqrt(k) times
the pace. A domain therefore maps to another scale by stretching the DURATION axis by sqrt(k),
magnitudes unchanged (`similar_boundary`).

The paper states instead that the curves are "approximately scalable with the square root of the
radius": the magnitude at a given t_p multiplied by sqrt(R / R_ref) (`paper_boundary`).
Both agree where a boundary behaves like a t_p = const (short pulses: the arch needs a given
ground velocity change, which scales with sqrt(g R)); they part where the boundary flattens
towards lambda (long pulses), which no magnitude scaling can reproduce since lambda does not
depend on R. `compare_scaling` quantifies the paper's rule on computed domains.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from archquake._validate import require_positive

from .domain import FailureDomain


def similar_boundary(durations: np.ndarray, magnitudes_g: np.ndarray, factor: float
                     ) -> tuple[np.ndarray, np.ndarray]:
    """A boundary of arch R mapped exactly to arch ``factor`` * R: (durations * sqrt(factor),
    magnitudes), s and g."""
    k = require_positive("scale factor", factor)
    return np.asarray(durations, float) * math.sqrt(k), np.asarray(magnitudes_g, float).copy()


def paper_boundary(durations: np.ndarray, magnitudes_g: np.ndarray, factor: float
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The paper's approximate mapping to arch ``factor`` * R: (durations, magnitudes *
    sqrt(factor))."""
    k = require_positive("scale factor", factor)
    return np.asarray(durations, float).copy(), np.asarray(magnitudes_g, float) * math.sqrt(k)


@dataclass(frozen=True)
class ScalingComparison:
    """The paper's sqrt(R) rule against a computed domain, shape (n,) over ``durations``.

    Attributes
    ----------
    factor : float
        R_target / R_reference.
    durations : ndarray, s
    computed_first_g, computed_collapse_g : ndarray, g
        The target arch's boundaries (computed).
    paper_first_g, paper_collapse_g : ndarray, g
        The reference boundaries at the same durations times sqrt(factor).
    """

    factor: float
    durations: np.ndarray
    computed_first_g: np.ndarray
    computed_collapse_g: np.ndarray
    paper_first_g: np.ndarray
    paper_collapse_g: np.ndarray

    @staticmethod
    def _rel(paper: np.ndarray, computed: np.ndarray) -> np.ndarray:
        return (paper - computed) / computed

    @property
    def first_error(self) -> np.ndarray:
        """(paper - computed) / computed for the first-half-cycle boundary."""
        return self._rel(self.paper_first_g, self.computed_first_g)

    @property
    def collapse_error(self) -> np.ndarray:
        """(paper - computed) / computed for the governing boundary."""
        return self._rel(self.paper_collapse_g, self.computed_collapse_g)

    def to_dict(self) -> dict:
        def stats(e: np.ndarray) -> dict:
            e = e[np.isfinite(e)]
            if e.size == 0:
                return {"max_abs": None, "mean_abs": None, "min": None, "max": None}
            return {"max_abs": float(np.abs(e).max()), "mean_abs": float(np.abs(e).mean()),
                    "min": float(e.min()), "max": float(e.max())}
        return {"factor": self.factor, "first_half_cycle": stats(self.first_error),
                "collapse": stats(self.collapse_error)}


def compare_scaling(reference: FailureDomain, target: FailureDomain) -> ScalingComparison:
    """The paper's sqrt(R) rule applied to ``reference`` against the computed ``target``.

    Both domains must share their durations (compute them on the same grid).
    """
    if not np.array_equal(reference.durations, target.durations):
        raise ValueError("compare_scaling needs both domains on the same durations")
    k = target.arch.radius / reference.arch.radius
    root = math.sqrt(k)
    return ScalingComparison(k, target.durations.copy(), target.first_half_cycle_g.copy(),
                             target.collapse_g.copy(), reference.first_half_cycle_g * root,
                             reference.collapse_g * root)


__all__ = ["ScalingComparison", "compare_scaling", "paper_boundary", "similar_boundary"]
