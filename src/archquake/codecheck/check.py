"""The code check of a local mechanism by kinematic analysis (NTC 2018 §8.7.1, Circolare 2019
C8.7.1.2.1; the superseded Circolare 2009 C8A.4 as an option).

Given the mechanism's capacity curve (`archquake.codecheck.kinematic.capacity_curve`), the
site's elastic spectra at the limit states (`archquake.codes.spectra`), the knowledge level
(confidence factor FC) and where the mechanism sits (at the ground, or at height Z in a
building), each limit state is checked as the code asks and reported as a **capacity a_g**: the
least peak ground acceleration on rock at which the demand reaches the capacity, the site's
spectral shape held (`with_ag`: S_S and T_D
re-evaluated, F0 and T_C* held). The ratio capacity a_g / site a_g is the code's zeta_E:
the check passes when it is at least 1.

Circolare 2019 (C8.7.1.2.1.5-8):

- SLD: the mechanism activates when the peak acceleration at its base reaches
  a0* = alpha0 g / (e* FC) (C8.7.1.8); at the ground that acceleration is a_g S, at height Z
  the simplified floor spectrum's zero-period value a_g S (1 + Z/H) (C7.2.11);
- SLV linear: a_g,SLV = q a_g,SLD with q = 2 (C8.7.1.2.1.7), a_g,SLD taken on the SLV spectrum;
- SLV and SLC nonlinear: the displacement capacity d_SLV = 0.4 d0 (d_SLC = 0.6 d0), the secant
  acceleration a(d) on the capacity curve, the period T_SLV = 1.68 pi sqrt(d_SLV/a(d_SLV))
  (C8.7.1.10; T_SLC = 1.56 pi sqrt(d_SLC/a(d_SLC)), C8.7.1.11), and the demand is the largest
  elastic spectral displacement over [T0, T_SLV] (T0 = 0: the mechanism is rigid until it
  activates) with 8 % (SLV) or 10 % (SLC) damping; at height the floor spectrum's
  S_a(T) T^2 / 4 pi^2 (C8.7.1.12 with C7.2.11). If a_g,SLV < a_g,SLD, a_g,SLD is taken.

Circolare 2009 (C8A.4, superseded; at the ground only): SLD a0* >= a_g S; SLV linear
a0* >= a_g S / q; SLV nonlinear with the linearised curve a*(d) = a0* (1 - d/d0), d_u = 0.4 d0,
d_s = 0.4 d_u, T_s = 2 pi sqrt(d_s / a*(d_s)), demand S_De(T_s) at 5 % damping <= d_u. No SLC.

Not covered: mechanisms with an elastic branch before activation (free-standing elements,
C8.7.1.6-7, C8.7.1.9) and the full floor spectra of C7.2.5-C7.2.10 (modal participation,
building damping).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from enum import StrEnum

import numpy as np
from scipy.optimize import brentq

from archquake._validate import require_positive, require_range
from archquake.codecheck.kinematic import (
    CapacityCurve,
    FourHingeMechanism,
    LoadedFourHingeMechanism,
)
from archquake.codes.spectra import ElasticSpectrum, NTCHazard, return_period_years
from archquake.errors import InvalidParameterError

#: Behaviour factor of the linear SLV check "in the absence of more accurate evaluations"
#: (C8.7.1.2.1.7).
BEHAVIOUR_FACTOR = 2.0
#: Largest capacity a_g searched, in g: above it the capacity is reported as infinite.
MAX_CAPACITY_AG_G = 5.0
#: Samples of the scan for the least a_g at which the demand reaches the capacity.
_AG_SAMPLES = 240
#: Periods sampled for the largest spectral displacement over [T0, T] (plus T itself).
_PERIOD_SAMPLES = 200


class KnowledgeLevel(StrEnum):
    """Knowledge level of the masonry (NTC 2018 §8.5.4, Circolare Tab. C8.5.IV)."""

    LC1 = "LC1"
    LC2 = "LC2"
    LC3 = "LC3"

    @property
    def confidence_factor(self) -> float:
        """FC: 1.35 (LC1), 1.20 (LC2), 1.00 (LC3)."""
        return {"LC1": 1.35, "LC2": 1.20, "LC3": 1.00}[self.value]


class Procedure(StrEnum):
    """Which Circolare: 2019 (in force) or 2009 (C8A.4, superseded)."""

    CIRC2019 = "2019"
    CIRC2009 = "2009"


@dataclass(frozen=True)
class LimitStateSpec:
    """What the 2019 nonlinear check of one limit state takes from the code."""

    fraction_of_d0: float
    period_factor: float
    damping: float


#: C8.7.1.2.1.6 and .8: d = 0.4 d0 / 0.6 d0, T = 1.68 / 1.56 pi sqrt(d/a), damping 8 % / 10 %.
NONLINEAR = {
    "SLV": LimitStateSpec(0.4, 1.68, 0.08),
    "SLC": LimitStateSpec(0.6, 1.56, 0.10),
}


#: The other component's share in the combination of the components (NTC 2018 eq. 7.3.15,
#: EN 1998-1 eq. 4.20): E_x + 0.3 E_z and 0.3 E_x + E_z.
COMBINATION_COEFFICIENT = 0.3
#: EN 1998-1 §4.3.3.5.2(1): the vertical component is taken where a_vg exceeds 0.25 g (and
#: only for the members it names), in g.
EC8_VERTICAL_THRESHOLD_G = 0.25


@dataclass(frozen=True)
class VerticalTreatment:
    """Whether the check takes the vertical component of the seismic action, and why.

    Where taken, every limit state is checked under the two combinations E_x + 0.3 E_z and
    0.3 E_x + E_z (NTC 2018 eq. 7.3.15), the vertical as a steady downward ground
    acceleration k_v g = c a_vg (c = 0.3 or 1, a_vg the site's vertical spectrum's PGA; a
    rigid mechanism has no period before it activates): every weight, hence the whole capacity
    curve a(d), is scaled by (1 - k_v) (the exact law of a no-tension mechanism loaded by its
    weights alone, `archquake.limit.limit_analysis`'s ``vertical``), d0 unchanged.

    Attributes
    ----------
    taken : bool
    reason : str
        One sentence: which clause, and why it applies or not here.
    """

    taken: bool
    reason: str

    def to_dict(self) -> dict:
        return {"taken": self.taken, "reason": self.reason,
                "combinations": (["E_x + 0.3 E_z", "0.3 E_x + E_z"] if self.taken else [])}


def vertical_treatment(spectra: Mapping[str, ElasticSpectrum], position: Position,
                       procedure: Procedure, vertical: bool | None, *,
                       thrusting: bool = True) -> VerticalTreatment:
    """As the code asks (``vertical`` None), or as the caller says (True, False).

    NTC 2018 §7.2.2 names thrusting structures and bridges among the cases where the vertical
    component must be considered: an arch (``thrusting``) is both, so the NTC check takes it;
    a block rocking on its base is not among them. EN 1998-1
    §4.3.3.5.2 asks for it only where a_vg > 0.25 g and for the members it names (horizontal
    members spanning 20 m or more, cantilevers longer than 5 m, prestressed members, beams
    supporting columns, base isolation), among which an arch is not: the EN 1998-1 check
    neglects it unless asked. Above the ground the floor spectrum (C7.2.11) is horizontal
    only, and the superseded 2009 procedure (C8A.4) has no vertical: both neglect it, and
    refuse ``vertical=True``.
    """
    codes = {sp.code for sp in spectra.values()}
    if not position.at_ground:
        if vertical:
            raise InvalidParameterError(
                "the vertical component is taken at the ground only (the C7.2.11 floor "
                "spectrum is horizontal)")
        return VerticalTreatment(False, "neglected: the mechanism sits in a building and the "
                                        "floor spectrum of C7.2.11 is horizontal only")
    if procedure is Procedure.CIRC2009:
        if vertical:
            raise InvalidParameterError(
                "the vertical component is taken with procedure 2019 only")
        return VerticalTreatment(False, "neglected: the 2009 procedure (C8A.4) has no "
                                        "vertical component")
    if vertical is True:
        return VerticalTreatment(True, "taken, as asked")
    if vertical is False:
        return VerticalTreatment(False, "neglected, as asked")
    if codes <= {"ntc2018"} and not thrusting:
        return VerticalTreatment(False, "neglected: NTC 2018 §7.2.2 asks for the vertical "
                                        "component for thrusting structures and bridges, and "
                                        "this mechanism is neither")
    if codes <= {"ntc2018"}:
        return VerticalTreatment(True, "taken: NTC 2018 §7.2.2 asks for the vertical "
                                       "component for thrusting structures and bridges, and "
                                       "an arch is one")
    avg = max((sp.companion("vertical").pga / sp.g for sp in spectra.values()), default=0.0)
    return VerticalTreatment(False, f"neglected: EN 1998-1 §4.3.3.5.2 asks for it only where "
                                    f"a_vg > {EC8_VERTICAL_THRESHOLD_G:g} g (here {avg:.3f} g) "
                                    f"and for the members it names, among which an arch is "
                                    f"not (it is taken on request)")


def _combinations(taken: bool) -> tuple[tuple[float, float], ...]:
    """(horizontal share, vertical share) of each combination checked."""
    if not taken:
        return ((1.0, 0.0),)
    return ((1.0, COMBINATION_COEFFICIENT), (COMBINATION_COEFFICIENT, 1.0))


def _gravity_factor(spectrum: ElasticSpectrum, share: float) -> float:
    """1 - k_v: the weights under a downward k_v g = ``share`` a_vg (0 where they vanish)."""
    if share == 0.0:
        return 1.0
    return max(1.0 - share * spectrum.companion("vertical").pga / spectrum.g, 0.0)


@dataclass(frozen=True)
class Position:
    """Where the mechanism sits: at the ground, or at height Z in a building.

    Parameters
    ----------
    height_m : float
        Z, height of the mechanism's base above the foundation, m (0: at the ground).
    building_height_m : float or None
        H, the building's height, m (needed when Z > 0; Z <= H).
    building_period_s : float or None
        T1, the building's fundamental period, s (needed when Z > 0).
    """

    height_m: float = 0.0
    building_height_m: float | None = None
    building_period_s: float | None = None

    def __post_init__(self) -> None:
        z = require_range("height", self.height_m, 0.0, math.inf, "m", low_open=False)
        object.__setattr__(self, "height_m", z)
        if z == 0.0:
            return
        if self.building_height_m is None or self.building_period_s is None:
            raise InvalidParameterError(
                "a mechanism at height needs the building's height H (m) and period T1 (s)")
        h = require_positive("building height", self.building_height_m, "m")
        if z > h:
            raise InvalidParameterError(
                f"height must be in [0, {h:g}] m (the building's height), got {z:g}")
        object.__setattr__(self, "building_height_m", h)
        object.__setattr__(self, "building_period_s",
                           require_positive("building period", self.building_period_s, "s"))

    @property
    def at_ground(self) -> bool:
        return self.height_m == 0.0

    def to_dict(self) -> dict:
        return {"height_m": self.height_m, "building_height_m": self.building_height_m,
                "building_period_s": self.building_period_s}


def floor_spectrum(spectrum: ElasticSpectrum, periods: np.ndarray | float,
                   position: Position) -> np.ndarray:
    """Spectral acceleration at the mechanism's base, m/s^2: the site's elastic spectrum at 5 %
    on the ground, the simplified floor spectrum of C7.2.11 at height.

    C7.2.11 with Tab. C7.2.II (a, b, a_p by T1: (0.8, 1.4, 5.0) below 0.5 s, (0.3, 1.2, 4.0)
    to 1.0 s, (0.3, 1.0, 2.5) above):
    S_a = a_g S (1 + Z/H) a_p / [1 + (a_p - 1)(1 - T/(a T1))^2] for T < a T1,
    a_g S (1 + Z/H) a_p up to b T1, a_g S (1 + Z/H) a_p / [1 + (a_p - 1)(1 - T/(b T1))^2]
    beyond; never below a_g S.

    Parameters
    ----------
    spectrum : ElasticSpectrum
    periods : float or ndarray
        s.
    position : Position

    Returns
    -------
    ndarray
        m/s^2, shape of ``periods`` (at least 1-d).
    """
    t = np.atleast_1d(np.asarray(periods, dtype=float))
    if position.at_ground:
        return spectrum.sa(t)
    assert position.building_period_s is not None and position.building_height_m is not None
    t1 = position.building_period_s
    a, b, ap = (0.8, 1.4, 5.0) if t1 < 0.5 else (0.3, 1.2, 4.0) if t1 <= 1.0 else (0.3, 1.0, 2.5)
    pga = spectrum.pga
    top = pga * (1.0 + position.height_m / position.building_height_m) * ap
    out = np.full_like(t, top)
    below = t < a * t1
    out[below] = top / (1.0 + (ap - 1.0) * (1.0 - t[below] / (a * t1)) ** 2)
    above = t >= b * t1
    out[above] = top / (1.0 + (ap - 1.0) * (1.0 - t[above] / (b * t1)) ** 2)
    return np.maximum(out, pga)


def peak_demand(spectrum: ElasticSpectrum, position: Position) -> float:
    """a_Z, the peak acceleration at the mechanism's base, m/s^2: a_g S at the ground,
    a_g S (1 + Z/H) at height (C7.2.11 at zero period)."""
    return float(floor_spectrum(spectrum, 0.0, position)[0])


def displacement_demand(spectrum: ElasticSpectrum, period: float, damping: float,
                        position: Position, *, start: float = 0.0) -> float:
    """The largest spectral displacement over [start, period], m (C8.7.1.2.1.6: the demand is
    the maximum over [T0, T_SLV], which matters for spectra that are not monotonic).

    At the ground, NTC's S_De at ``damping``; at height S_a(T) T^2 / 4 pi^2 of the floor
    spectrum (C8.7.1.12 with C7.2.11, which has no damping term).
    """
    t = np.unique(np.concatenate([np.linspace(start, period, _PERIOD_SAMPLES), [period]]))
    if position.at_ground:
        d = spectrum.sd(t, damping)
    else:
        d = floor_spectrum(spectrum, t, position) * (t / (2.0 * math.pi)) ** 2
    return float(np.max(d))


def least_ag(demand: Callable[[ElasticSpectrum], float], capacity: float,
             spectrum: ElasticSpectrum) -> float:
    """The least a_g (m/s^2) at which ``demand(spectrum.with_ag(a_g))`` reaches ``capacity``.

    The demand is scanned over a_g (the soil factor may make it non-monotonic in a_g), then the
    first crossing is refined by Brent's method to round-off. ``inf`` if the demand stays below
    the capacity up to `MAX_CAPACITY_AG_G`.
    """
    g = spectrum.g
    grid = np.geomspace(1e-4 * g, MAX_CAPACITY_AG_G * g, _AG_SAMPLES)

    def excess(ag: float) -> float:
        return demand(spectrum.with_ag(ag)) - capacity

    if excess(grid[0]) >= 0.0:
        return float(grid[0])
    for lo, hi in zip(grid[:-1], grid[1:], strict=True):
        if excess(hi) >= 0.0:
            return float(brentq(excess, lo, hi, xtol=1e-13, rtol=4 * np.finfo(float).eps,
                                maxiter=200))
    return math.inf


@dataclass(frozen=True)
class LimitStateCheck:
    """One limit state's check.

    Attributes
    ----------
    limit_state : {'SLD', 'SLV', 'SLC'}
    method : {'linear', 'nonlinear'}
    capacity_ag_g : float
        Capacity a_g, g: the least a_g at which the demand reaches the capacity.
    demand_ag_g : float
        The site's a_g at this limit state, g.
    quantity : {'acceleration', 'displacement'}
        What the capacity and demand below measure.
    capacity : float
        The mechanism's capacity, m/s^2 (acceleration) or m (displacement).
    demand : float
        The site's demand at its own a_g, same unit.
    period_s : float or None
        The period the demand is read at (T_SLV, T_SLC, T_s), s.
    damping : float or None
        Damping ratio of that demand.
    formulas : dict of str
        Where each number comes from.
    """

    limit_state: str
    method: str
    capacity_ag_g: float
    demand_ag_g: float
    quantity: str
    capacity: float
    demand: float
    period_s: float | None
    damping: float | None
    formulas: Mapping[str, str] = field(default_factory=dict)

    @property
    def ratio(self) -> float:
        """zeta_E = capacity a_g / site a_g (>= 1 passes)."""
        return self.capacity_ag_g / self.demand_ag_g

    @property
    def passes(self) -> bool:
        return self.ratio >= 1.0

    def verdict(self) -> str:
        """One line: the limit state, its ratio and whether it passes."""
        word = "passes" if self.passes else "FAILS"
        return (f"{self.limit_state} ({self.method}): capacity a_g {self.capacity_ag_g:.4f} g, "
                f"site {self.demand_ag_g:.4f} g, ratio {self.ratio:.3f}: {word}")

    def to_dict(self) -> dict:
        unit = "m_s2" if self.quantity == "acceleration" else "m"
        return {
            "limit_state": self.limit_state,
            "method": self.method,
            "capacity_ag_g": self.capacity_ag_g,
            "demand_ag_g": self.demand_ag_g,
            "ratio": self.ratio,
            "passes": self.passes,
            f"capacity_{unit}": self.capacity,
            f"demand_{unit}": self.demand,
            "period_s": self.period_s,
            "damping": self.damping,
            "formulas": dict(self.formulas),
        }


@dataclass(frozen=True)
class CodeCheck:
    """The code check of a local mechanism. Build it with `kinematic_check`.

    Attributes
    ----------
    curve : CapacityCurve
    knowledge : KnowledgeLevel
    procedure : Procedure
    position : Position
    spectra : dict of str to ElasticSpectrum
        The site's spectra by limit state.
    checks : tuple of LimitStateCheck
    """

    curve: CapacityCurve = field(repr=False)
    knowledge: KnowledgeLevel
    procedure: Procedure
    position: Position
    spectra: Mapping[str, ElasticSpectrum] = field(repr=False)
    checks: tuple[LimitStateCheck, ...]
    vertical: VerticalTreatment = VerticalTreatment(False, "neglected")

    @property
    def confidence_factor(self) -> float:
        return self.knowledge.confidence_factor

    @property
    def a0_star(self) -> float:
        """a0* = alpha0 g / (e* FC), m/s^2 (C8.7.1.3 at d = 0)."""
        return self.curve.a0_star(self.confidence_factor)

    @property
    def governing(self) -> tuple[LimitStateCheck, ...]:
        """One check per limit state: the nonlinear (displacement) check where there is one,
        the code's more accurate route, else the linear one (C8.7.1.2.1.7 is the simplified
        alternative when only alpha0 is known)."""
        out: dict[str, LimitStateCheck] = {}
        for c in self.checks:
            if c.limit_state not in out or c.method == "nonlinear":
                out[c.limit_state] = c
        return tuple(out.values())

    @property
    def passes(self) -> bool:
        """True if every limit state's governing check passes."""
        return all(c.passes for c in self.governing)

    def check(self, limit_state: str, method: str) -> LimitStateCheck:
        for c in self.checks:
            if c.limit_state == limit_state and c.method == method:
                return c
        raise KeyError(f"{limit_state} {method}")

    def to_dict(self) -> dict:
        g = self.curve.g
        return {
            "procedure": self.procedure.value,
            "knowledge": self.knowledge.value,
            "confidence_factor": self.confidence_factor,
            "position": self.position.to_dict(),
            "alpha0": self.curve.alpha0,
            "e_star": self.curve.e_star,
            "m_star_kg": self.curve.m_star_kg,
            "mass_kg": self.curve.mass_kg,
            "a0_star_g": self.a0_star / g,
            "a0_star_m_s2": self.a0_star,
            "d0_m": self.curve.d0_m,
            "passes": self.passes,
            "vertical": self.vertical.to_dict(),
            "limit_states": [{**c.to_dict(), "governing": c in self.governing}
                             for c in self.checks],
            "spectra": {k: s.to_dict() for k, s in self.spectra.items()},
            "capacity_curve": self.curve.to_dict(),
        }


def _sld(curve: CapacityCurve, spectrum: ElasticSpectrum, position: Position, fc: float,
         *, state: str = "SLD", ag_factor: float = 1.0,
         capacity_factor: float = 1.0, vertical: bool = False) -> LimitStateCheck:
    """Activation: the least a_g with a_Z(a_g) = a0* (C8.7.1.8), the a_g times ``ag_factor``
    (2019's linear SLV: a_g,SLV = q a_g,SLD), or with a_Z(a_g) = ``capacity_factor`` a0*
    (2009's linear SLV: a0* >= a_g S / q). With ``vertical``, the worse of the combinations
    (`VerticalTreatment`): a0* (1 - k_v) against the horizontal share of a_Z."""
    g = spectrum.g
    capacity = curve.a0_star(fc) * capacity_factor
    combos = _combinations(vertical)

    def demand(s: ElasticSpectrum) -> float:
        worst = 0.0
        for h_share, v_share in combos:
            factor = _gravity_factor(s, v_share)
            if factor == 0.0:
                return math.inf
            worst = max(worst, h_share * peak_demand(s, position) / factor)
        return worst

    ag = ag_factor * least_ag(demand, capacity, spectrum)
    where = "a_g S" if position.at_ground else "a_g S (1 + Z/H) (C7.2.11)"
    formulas = {"capacity": "a0* = alpha0 g / (e* FC) (C8.7.1.3)",
                "demand": f"a_Z = {where}",
                "capacity_ag": "least a_g with a_Z = a0* (C8.7.1.8)"}
    if ag_factor != 1.0:
        formulas["capacity_ag"] += f", times q = {ag_factor:g} (C8.7.1.2.1.7)"
    if capacity_factor != 1.0:
        formulas["capacity"] = f"q a0*, q = {capacity_factor:g} (C8A.4: a0* >= a_g S / q)"
        formulas["capacity_ag"] = "least a_g with a_g S = q a0*"
    if vertical:
        formulas["vertical"] = ("the worse of E_x + 0.3 E_z and 0.3 E_x + E_z (NTC 7.3.15): "
                                "a_Z share against a0* (1 - k_v), k_v = share a_vg / g")
    return LimitStateCheck(state, "linear", ag / g, spectrum.ag / g, "acceleration", capacity,
                           demand(spectrum), None, None, formulas)


def _nonlinear_2019(curve: CapacityCurve, spectrum: ElasticSpectrum, position: Position,
                    fc: float, state: str, floor_ag: float,
                    vertical: bool = False) -> LimitStateCheck:
    spec = NONLINEAR[state]
    g = spectrum.g
    d = spec.fraction_of_d0 * curve.d0_m
    a = curve.acceleration_at(d, fc)
    period = spec.period_factor * math.pi * math.sqrt(d / a)
    combos = _combinations(vertical)

    def demand(s: ElasticSpectrum) -> float:
        if not vertical:
            return displacement_demand(s, period, spec.damping, position)
        worst = 0.0
        for h_share, v_share in combos:
            factor = _gravity_factor(s, v_share)
            if factor == 0.0:
                return math.inf
            # the capacity curve at weights (1 - k_v): a(d) scaled, the period lengthened
            t = period / math.sqrt(factor)
            worst = max(worst, h_share * displacement_demand(s, t, spec.damping, position))
        return worst

    ag = max(least_ag(demand, d, spectrum), floor_ag)
    eq = "C8.7.1.10" if state == "SLV" else "C8.7.1.11"
    where = ("max S_De over [0, T] (NTC 3.2.3.2.3)" if position.at_ground
             else "max S_a(T) T^2/4pi^2 over [0, T], C7.2.11 floor spectrum (C8.7.1.12)")
    formulas = {
        "capacity": f"d_{state} = {spec.fraction_of_d0:g} d0 (C8.7.1.2.1.6/8)",
        "period": f"T_{state} = {spec.period_factor:g} pi sqrt(d / a(d)) ({eq}), "
                  f"a(d) = alpha(d) g / (e* FC) (C8.7.1.3)",
        "demand": f"{where}, damping {spec.damping:.0%}",
        "capacity_ag": "least a_g with demand = capacity"
                       + ("; not below a_g,SLD (C8.7.1.2.1.6)" if state == "SLV" else ""),
    }
    if vertical:
        formulas["vertical"] = ("the worse of E_x + 0.3 E_z and 0.3 E_x + E_z (NTC 7.3.15): "
                                "a(d) times (1 - k_v), T / sqrt(1 - k_v), the horizontal "
                                "share of the displacement demand; k_v = share a_vg / g")
    return LimitStateCheck(state, "nonlinear", ag / g, spectrum.ag / g, "displacement", d,
                           demand(spectrum), period, spec.damping, formulas)


def _nonlinear_2009(curve: CapacityCurve, spectrum: ElasticSpectrum, fc: float) -> LimitStateCheck:
    g = spectrum.g
    a0 = curve.a0_star(fc)
    d_u = 0.4 * curve.d0_m
    d_s = 0.4 * d_u
    a_s = a0 * (1.0 - d_s / curve.d0_m)
    period = 2.0 * math.pi * math.sqrt(d_s / a_s)

    def demand(s: ElasticSpectrum) -> float:
        return float(s.sd(period, 0.05)[0])

    ag = least_ag(demand, d_u, spectrum)
    formulas = {
        "capacity": "d_u* = 0.4 d0* (C8A.4.2.3)",
        "period": "T_s = 2 pi sqrt(d_s*/a_s*), d_s* = 0.4 d_u*, a_s* = a0* (1 - d_s*/d0*)",
        "demand": "S_De(T_s) at 5 % damping",
        "capacity_ag": "least a_g with S_De(T_s) = d_u*",
    }
    return LimitStateCheck("SLV", "nonlinear", ag / g, spectrum.ag / g, "displacement", d_u,
                           demand(spectrum), period, 0.05, formulas)


#: The limit states of the check (NTC 2018 Tab. 3.2.I).
LIMIT_STATES = ("SLD", "SLV", "SLC")


def limit_state_spectra(hazard: NTCHazard, *, nominal_life_years: float = 50.0,
                        use_class: str = "II", **site) -> dict[str, ElasticSpectrum]:
    """The site's NTC 2018 spectra at each limit state's return period (eq. 3.2.0).

    Parameters
    ----------
    hazard : NTCHazard
        The site's (T_R, a_g, F0, T_C*) points, spanning the return periods asked for.
    nominal_life_years : float
        V_N, years.
    use_class : {'I', 'II', 'III', 'IV'}
    **site
        `ntc2018_spectrum`'s other keywords (soil, topography).

    Returns
    -------
    dict of str to ElasticSpectrum
        'SLD', 'SLV', 'SLC'.

    Raises
    ------
    InvalidParameterError
        A return period outside the hazard's points (one line naming the limit state).
    """
    out, missing = hazard_spectra(hazard, nominal_life_years=nominal_life_years,
                                  use_class=use_class, **site)
    if missing:
        state, why = next(iter(missing.items()))
        raise InvalidParameterError(f"{state} {why}")
    return out


def hazard_spectra(hazard: NTCHazard, *, nominal_life_years: float = 50.0,
                   use_class: str = "II", **site) -> tuple[dict[str, ElasticSpectrum],
                                                            dict[str, str]]:
    """The site's NTC 2018 spectra at the limit states whose return period the hazard's points
    span, and why each other limit state has none.

    Each limit state's return period T_R (eq. 3.2.0) must lie between two of the hazard's
    points, where Allegato A interpolates a_g, F0 and T_C* (linear in log p against log T_R);
    a limit state outside them has no hazard of its own and is not checked (never against
    another limit state's a_g). With V_N = 50 years and use class II the periods are 50.3
    (SLD), 474.6 (SLV) and 974.8 years (SLC): the grid's points at 50, 475 and 975 years span
    all three, points at 50 and 475 years the SLD and the SLV.

    Parameters
    ----------
    hazard, nominal_life_years, use_class, **site
        As `limit_state_spectra`.

    Returns
    -------
    (dict of str to ElasticSpectrum, dict of str to str)
        The spectra by limit state, and for each limit state without one a phrase saying why
        (``'needs the return period 975 years (...)'``).

    Examples
    --------
    >>> hz = NTCHazard([(50, 0.05, 2.5, 0.26), (475, 0.15, 2.45, 0.30)])
    >>> spectra, missing = hazard_spectra(hz, soil="B")
    >>> sorted(spectra), missing["SLC"]
    (['SLD', 'SLV'], 'needs the return period 975 years, outside the hazard points (50 to 475 years)')
    """
    out: dict[str, ElasticSpectrum] = {}
    missing: dict[str, str] = {}
    lo, hi = hazard.points[0][0], hazard.points[-1][0]
    for state in LIMIT_STATES:
        t_r = return_period_years(state, nominal_life_years, use_class)
        if not lo <= t_r <= hi:
            missing[state] = (f"needs the return period {t_r:.0f} years, outside the hazard "
                              f"points ({lo:g} to {hi:g} years)")
            continue
        try:
            out[state] = hazard.spectrum(t_r, **site)
        except InvalidParameterError as exc:
            raise InvalidParameterError(
                f"{state} at the return period {t_r:.0f} years: {exc}") from None
    return out, missing


def kinematic_check(curve: CapacityCurve, spectra: Mapping[str, ElasticSpectrum], *,
                    knowledge: KnowledgeLevel | str = KnowledgeLevel.LC1,
                    procedure: Procedure | str = Procedure.CIRC2019,
                    position: Position | None = None,
                    behaviour_factor: float = BEHAVIOUR_FACTOR,
                    vertical: bool | None = None) -> CodeCheck:
    """Check a local mechanism at the site's limit states (see the module docstring).

    Parameters
    ----------
    curve : CapacityCurve
        The mechanism's equivalent SDOF system and capacity curve.
    spectra : dict of str to ElasticSpectrum
        The site's elastic spectra by limit state ('SLD', 'SLV', 'SLC'); limit states not given
        are not checked.
    knowledge : {'LC1', 'LC2', 'LC3'}
        Knowledge level: FC = 1.35, 1.20, 1.00.
    procedure : {'2019', '2009'}
        The Circolare's procedure (2009: at the ground only, no SLC).
    position : Position, optional
        At the ground when not given.
    behaviour_factor : float
        q of the linear SLV check.
    vertical : bool, optional
        Take the vertical component of the seismic action (`VerticalTreatment`): None
        (default) as the code asks (`vertical_treatment`: NTC 2018 takes it for an arch,
        EN 1998-1 does not), True or False to decide. The result's ``vertical`` says which and
        why.

    Returns
    -------
    CodeCheck
    """
    try:
        knowledge = KnowledgeLevel(str(knowledge).upper())
    except ValueError:
        raise InvalidParameterError(
            f"knowledge level must be one of LC1, LC2, LC3, got {knowledge!r}") from None
    try:
        procedure = Procedure(str(procedure))
    except ValueError:
        raise InvalidParameterError(f"procedure must be 2019 or 2009, got {procedure!r}") from None
    position = Position() if position is None else position
    q = require_positive("behaviour factor", behaviour_factor)
    unknown = set(spectra) - {"SLD", "SLV", "SLC"}
    if unknown:
        raise InvalidParameterError(
            f"limit states must be SLD, SLV or SLC, got {', '.join(sorted(unknown))}")
    fc = knowledge.confidence_factor
    treatment = vertical_treatment(spectra, position, procedure, vertical,
                                   thrusting=isinstance(curve.mechanism, (FourHingeMechanism,
                                                                        LoadedFourHingeMechanism)))
    v = treatment.taken
    checks: list[LimitStateCheck] = []
    if procedure is Procedure.CIRC2009:
        if not position.at_ground:
            raise InvalidParameterError(
                "the 2009 procedure is implemented at the ground only; use procedure 2019 at height")
        if "SLD" in spectra:
            checks.append(_sld(curve, spectra["SLD"], position, fc))
        if "SLV" in spectra:
            checks.append(_sld(curve, spectra["SLV"], position, fc, state="SLV",
                               capacity_factor=q))
            checks.append(_nonlinear_2009(curve, spectra["SLV"], fc))
        return CodeCheck(curve, knowledge, procedure, position, dict(spectra), tuple(checks),
                         treatment)
    if "SLD" in spectra:
        checks.append(_sld(curve, spectra["SLD"], position, fc, vertical=v))
    for state in ("SLV", "SLC"):
        if state not in spectra:
            continue
        floor = 0.0
        if state == "SLV":
            lin = _sld(curve, spectra["SLV"], position, fc, state="SLV", ag_factor=q,
                       vertical=v)
            checks.append(lin)
            # C8.7.1.2.1.6: if a_g,SLV < a_g,SLD, a_g,SLD (activation on the same spectrum)
            floor = lin.capacity_ag_g / q * spectra["SLV"].g
        checks.append(_nonlinear_2019(curve, spectra[state], position, fc, state, floor,
                                      vertical=v))
    return CodeCheck(curve, knowledge, procedure, position, dict(spectra), tuple(checks),
                     treatment)


__all__ = [
    "BEHAVIOUR_FACTOR",
    "COMBINATION_COEFFICIENT",
    "EC8_VERTICAL_THRESHOLD_G",
    "VerticalTreatment",
    "vertical_treatment",
    "LIMIT_STATES",
    "limit_state_spectra",
    "hazard_spectra",
    "NONLINEAR",
    "CodeCheck",
    "KnowledgeLevel",
    "LimitStateCheck",
    "Position",
    "Procedure",
    "displacement_demand",
    "floor_spectrum",
    "kinematic_check",
    "least_ag",
    "peak_demand",
]
