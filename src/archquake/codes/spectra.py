"""Elastic response spectra of NTC 2018 §3.2 and EN 1998-1:2004 §3.2.2, and the NTC site hazard.

One `ElasticSpectrum` holds one code's elastic spectrum at one site and one limit
state. It is built by `ntc2018_spectrum` or `ec8_spectrum` from what a user reads
off the hazard map and the site survey; `ElasticSpectrum.sa` and
`ElasticSpectrum.sd` evaluate it at any periods and damping.

Both codes share one shape (a_g in m/s^2, eta = sqrt(10 / (5 + 100 xi)) >= 0.55, xi the
damping ratio):

- 0 <= T < T_B:    S_e = a_g S [1 + (T / T_B) (eta F0 - 1)]
- T_B <= T < T_C:  S_e = a_g S eta F0
- T_C <= T < T_D:  S_e = a_g S eta F0 T_C / T
- T_D <= T:        S_e = a_g S eta F0 T_C T_D / T^2

NTC 2018 eq. 3.2.2 writes the first branch as a_g S eta F0 [T/T_B + (1 - T/T_B)/(eta F0)],
the same line; EN 1998-1 eq. 3.2 writes it with F0 = 2.5. The vertical components use the same
shape: NTC eq. 3.2.8 with F_v = 1.35 F0 (a_g/g)^0.5 in place of F0 and S = S_T (Tab. 3.2.VI);
EN 1998-1 eqs. 3.8-3.11 with a_vg = 0.90 a_g (Type 1) or 0.45 a_g (Type 2) in place of a_g S
and 3.0 in place of 2.5 (Tab. 3.4).

The displacement spectrum S_De (m) is S_e (T / 2 pi)^2. NTC 2018 eqs. 3.2.10-3.2.12 continue it
beyond T_E towards the peak ground displacement d_g = 0.025 a_g S T_C T_D, reached at T_F
(Tab. 3.2.VII: T_E = 4.5, 5.0, 6.0 s on ground A, B, C-E; T_F = 10 s).

Sources: the code texts as transcribed in the project's notes on codes and spectra (NTC 2018
tables 3.2.I-VII and eqs. 3.2.0-3.2.12 read in a verified transcription; EN 1998-1 Tab. 3.2-3.3
confirmed by several independent implementations; EN 1998-1 Tab. 3.4, the vertical spectrum, by
one implementation and recall).

Examples
--------
The site of the notes' worked example (a_g = 0.25 g, F0 = 2.4, T_C* = 0.30 s, soil B):

>>> spec = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B")
>>> round(spec.S, 3), round(spec.TB, 3), round(spec.TC, 3), round(spec.TD, 2)
(1.16, 0.14, 0.42, 2.6)
>>> round(float(spec.sa([0.3])[0]) / spec.g, 3)
0.696
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from archquake._validate import require_finite, require_positive, require_range
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.ranges import (
    EC8_GROUNDS,
    EC8_SPECTRUM_TYPES,
    IMPORTANCE_RANGE,
    NOMINAL_LIFE_RANGE_YEARS,
    NTC_F0_RANGE,
    NTC_LIMIT_STATES,
    NTC_SOILS,
    NTC_TC_STAR_RANGE_S,
    NTC_TOPOGRAPHIES,
    NTC_USE_CLASSES,
    SITE_AG_RANGE_G,
    SPECTRUM_COMPONENTS,
    SPECTRUM_DAMPING_RANGE,
)

#: Damping ratio at which the codes' spectra are given (eta = 1).
REFERENCE_DAMPING = 0.05

#: Floor of the damping correction factor eta (NTC eq. 3.2.4, EN 1998-1 eq. 3.6).
ETA_MIN = 0.55

#: Codes offered.
CODES = ("ntc2018", "ec8")

# NTC 2018 Tab. 3.2.IV: soil -> (a, b, low, high) with S_S = clip(a - b F0 a_g/g, low, high),
#                              and (c, p) with C_C = c (T_C*)^p.
_NTC_SS = {
    "A": (1.00, 0.00, 1.00, 1.00),
    "B": (1.40, 0.40, 1.00, 1.20),
    "C": (1.70, 0.60, 1.00, 1.50),
    "D": (2.40, 1.50, 0.90, 1.80),
    "E": (2.00, 1.10, 1.00, 1.60),
}
_NTC_CC = {"A": (1.00, 0.0), "B": (1.10, -0.20), "C": (1.05, -0.33), "D": (1.25, -0.50),
           "E": (1.15, -0.40)}
# NTC 2018 Tab. 3.2.V: topographic amplification S_T.
_NTC_ST = {"T1": 1.0, "T2": 1.2, "T3": 1.2, "T4": 1.4}
# NTC 2018 Tab. 3.2.VII: T_E (s) by soil; T_F = 10 s.
_NTC_TE = {"A": 4.5, "B": 5.0, "C": 6.0, "D": 6.0, "E": 6.0}
_NTC_TF = 10.0
# NTC 2018 Tab. 3.2.VI: vertical T_B, T_C, T_D (s); F_v = 1.35 F0 (a_g/g)^0.5 (eq. 3.2.9).
_NTC_VERTICAL = (0.05, 0.15, 1.0)
_NTC_FV = 1.35
# NTC 2018 Tab. 3.2.I: probability of exceedance in V_R; §2.4.3: C_U by use class.
_NTC_PVR = {"SLO": 0.81, "SLD": 0.63, "SLV": 0.10, "SLC": 0.05}
_NTC_CU = {"I": 0.7, "II": 1.0, "III": 1.5, "IV": 2.0}

# EN 1998-1 Tab. 3.2 (Type 1) and 3.3 (Type 2): ground -> (S, T_B, T_C, T_D).
_EC8_HORIZONTAL = {
    1: {"A": (1.00, 0.15, 0.40, 2.0), "B": (1.20, 0.15, 0.50, 2.0), "C": (1.15, 0.20, 0.60, 2.0),
        "D": (1.35, 0.20, 0.80, 2.0), "E": (1.40, 0.15, 0.50, 2.0)},
    2: {"A": (1.00, 0.05, 0.25, 1.2), "B": (1.35, 0.05, 0.25, 1.2), "C": (1.50, 0.10, 0.25, 1.2),
        "D": (1.80, 0.10, 0.30, 1.2), "E": (1.60, 0.05, 0.25, 1.2)},
}
_EC8_F0 = 2.5
# EN 1998-1 Tab. 3.4: type -> (a_vg / a_g, T_B, T_C, T_D); plateau factor 3.0 (eqs. 3.8-3.11).
_EC8_VERTICAL = {1: (0.90, 0.05, 0.15, 1.0), 2: (0.45, 0.05, 0.15, 1.0)}
_EC8_FV = 3.0

#: d_g = 0.025 a_g S T_C T_D (NTC eq. 3.2.12; EN 1998-1 eq. 3.12).
_DG_COEFFICIENT = 0.025


def damping_factor(damping: float) -> float:
    """The damping correction eta = sqrt(10 / (5 + 100 xi)) >= 0.55 (NTC eq. 3.2.4).

    Parameters
    ----------
    damping : float
        Viscous damping ratio xi (fraction of critical, e.g. 0.05), in [0, 1).

    Returns
    -------
    float
        eta, 1 at xi = 0.05, floored at 0.55 (reached at xi = 0.2806).

    Examples
    --------
    >>> damping_factor(0.05), round(damping_factor(0.08), 4), damping_factor(0.5)
    (1.0, 0.8771, 0.55)
    """
    xi = require_range("damping", damping, *SPECTRUM_DAMPING_RANGE, low_open=False,
                       shown="[0, 1) (a ratio: 0.05 is 5 %)")
    return max(math.sqrt(10.0 / (5.0 + 100.0 * xi)), ETA_MIN)


@dataclass(frozen=True)
class ElasticSpectrum:
    """One code's elastic response spectrum at one site and limit state.

    Build it with `ntc2018_spectrum` or `ec8_spectrum`; the fields are the code's
    symbols, already evaluated (clipped, with the site's factors).

    Parameters
    ----------
    code : {'ntc2018', 'ec8'}
    component : {'horizontal', 'vertical'}
    ag : float
        a_g, peak ground acceleration on type A ground, m/s^2 (for EN 1998-1 the design value
        gamma_I a_gR).
    S : float
        Soil and topography factor (NTC S = S_S S_T; EN 1998-1 S; 1 for EN 1998-1 vertical).
    F0 : float
        Plateau amplification at the reference damping (NTC F0, or F_v for the vertical;
        EN 1998-1: 2.5 horizontal, 3.0 vertical).
    TB, TC, TD : float
        Corner periods, s.
    TE, TF : float
        Corner periods of NTC's displacement spectrum (Tab. 3.2.VII), s; ``inf`` where the
        displacement spectrum is S_e (T / 2 pi)^2 at every period.
    eta_damping_ref : float
        Damping ratio at which eta = 1 (0.05).
    avg_ratio : float
        a_vg / a_g of the EN 1998-1 vertical spectrum (Tab. 3.4); 1 otherwise. The spectrum at
        T = 0 is ``ag * avg_ratio * S``.
    g : float
        Gravity used to convert the user's multiples of g, m/s^2.
    params : dict
        What the user gave (a_g in g, F0, T_C*, soil, ...), enough to rebuild the spectrum.
    """

    code: str
    component: str
    ag: float
    S: float
    F0: float
    TB: float
    TC: float
    TD: float
    TE: float = math.inf
    TF: float = math.inf
    eta_damping_ref: float = REFERENCE_DAMPING
    avg_ratio: float = 1.0
    g: float = STANDARD_GRAVITY
    params: Mapping[str, Any] = field(default_factory=dict, compare=False, hash=False)

    def __post_init__(self) -> None:
        if self.code not in CODES:
            raise InvalidParameterError(f"code must be one of {', '.join(CODES)}, got {self.code!r}")
        _choice("component", self.component, SPECTRUM_COMPONENTS)
        for name in ("ag", "S", "F0", "TB", "TC", "TD", "avg_ratio", "g"):
            require_positive(name, getattr(self, name))
        if not self.TB < self.TC < self.TD:
            raise InvalidParameterError(
                f"corner periods must satisfy TB < TC < TD, got {self.TB:g}, {self.TC:g}, "
                f"{self.TD:g} s")
        object.__setattr__(self, "params", dict(self.params))

    # -------------------------------------------------------------------------------
    @property
    def pga(self) -> float:
        """S_e(0), the spectrum's peak ground acceleration, m/s^2."""
        return self.ag * self.avg_ratio * self.S

    @property
    def dg(self) -> float:
        """d_g = 0.025 a_g S T_C T_D, peak ground displacement, m (NTC 3.2.12, EN 1998-1 3.12)."""
        return _DG_COEFFICIENT * self.pga * self.TC * self.TD

    def sa(self, periods: float | Iterable[float] | np.ndarray,
           damping: float = REFERENCE_DAMPING) -> np.ndarray:
        """Elastic spectral acceleration S_e(T), m/s^2.

        Parameters
        ----------
        periods : float or array_like
            Periods T >= 0, s.
        damping : float
            Viscous damping ratio (0.05 for 5 %).

        Returns
        -------
        numpy.ndarray
            S_e at each period, m/s^2, shape of ``periods`` (at least 1-d).
        """
        t = _periods(periods)
        eta = damping_factor(damping)
        plateau = self.pga * eta * self.F0
        out = np.empty_like(t)
        rising = t < self.TB
        out[rising] = self.pga * (1.0 + t[rising] / self.TB * (eta * self.F0 - 1.0))
        flat = (t >= self.TB) & (t < self.TC)
        out[flat] = plateau
        falling = (t >= self.TC) & (t < self.TD)
        out[falling] = plateau * self.TC / t[falling]
        tail = t >= self.TD
        out[tail] = plateau * self.TC * self.TD / t[tail] ** 2
        return out

    def sd(self, periods: float | Iterable[float] | np.ndarray,
           damping: float = REFERENCE_DAMPING) -> np.ndarray:
        """Elastic displacement spectrum S_De(T), m.

        S_e (T / 2 pi)^2 up to T_E; between T_E and T_F NTC's line towards d_g (eq. 3.2.11),
        d_g beyond T_F. Should a_g be so large that T_D reaches T_E (a_g > 0.725 g on ground A),
        the line starts at T_D instead: the code's table does not foresee that case.

        Parameters
        ----------
        periods : float or array_like
            Periods T >= 0, s.
        damping : float
            Viscous damping ratio (0.05 for 5 %).

        Returns
        -------
        numpy.ndarray
            S_De at each period, m.
        """
        t = _periods(periods)
        eta = damping_factor(damping)
        out = self.sa(t, damping) * (t / (2.0 * math.pi)) ** 2
        if math.isfinite(self.TE):
            te = max(self.TE, self.TD)
            line = (t > te) & (t <= self.TF)
            fe = self.F0 * eta
            out[line] = self.dg * (fe + (1.0 - fe) * (t[line] - te) / (self.TF - te))
            out[t > self.TF] = self.dg
        return out

    def with_ag(self, ag: float) -> ElasticSpectrum:
        """The same site at another a_g (m/s^2), every a_g-dependent factor re-evaluated.

        NTC: S_S is re-clipped, T_D = 4 a_g/g + 1.6 and F_v follow; F0 and T_C* are held (they
        would change with the return period: iterate on `NTCHazard` for that).
        EN 1998-1: ``ag`` is the design a_g = gamma_I a_gR.

        Examples
        --------
        >>> spec = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B")
        >>> round(spec.with_ag(0.167 * spec.g).S, 3)
        1.2
        """
        ag = require_positive("ag", ag, "m/s^2")
        p = dict(self.params)
        if self.code == "ntc2018":
            return ntc2018_spectrum(ag_g=ag / self.g, f0=p["f0"], tc_star_s=p["tc_star_s"],
                                    soil=p["soil"], topography=p["topography"],
                                    component=self.component, g=self.g)
        importance = p["importance"]
        return ec8_spectrum(ag_g=ag / (self.g * importance), spectrum_type=p["spectrum_type"],
                            ground=p["ground"], importance=importance,
                            component=self.component, g=self.g)

    def companion(self, component: str) -> ElasticSpectrum:
        """The same site and a_g, the given component (``'horizontal'`` or ``'vertical'``):
        e.g. the vertical spectrum beside a horizontal one, whose PGA is a_vg (NTC: a_g S_T;
        EN 1998-1: a_vg/a_g of Tab. 3.4 times a_g).

        Examples
        --------
        >>> spec = ntc2018_spectrum(ag_g=0.25, f0=2.4, tc_star_s=0.30, soil="B")
        >>> round(spec.companion("vertical").pga / spec.g, 3)
        0.25
        """
        component = _choice("component", component, SPECTRUM_COMPONENTS)
        return replace(self, component=component).with_ag(self.ag)

    def label(self) -> str:
        """Words for a legend, e.g. ``'NTC 2018 horizontal, a_g 0.25 g, soil B, T1'``."""
        p = self.params
        if self.code == "ntc2018":
            return (f"NTC 2018 {self.component}, a_g {self.ag / self.g:.3g} g, soil {p['soil']}, "
                    f"{p['topography']}")
        return (f"EN 1998-1 Type {p['spectrum_type']} {self.component}, a_g "
                f"{self.ag / self.g:.3g} g, ground {p['ground']}")

    def to_dict(self) -> dict[str, Any]:
        """Plain values with units in the keys (what ``--json`` prints)."""
        return {
            "code": self.code,
            "component": self.component,
            "ag_g": self.ag / self.g,
            "ag_m_s2": self.ag,
            "S": self.S,
            "F0": self.F0,
            "avg_ratio": self.avg_ratio,
            "TB_s": self.TB,
            "TC_s": self.TC,
            "TD_s": self.TD,
            "TE_s": self.TE if math.isfinite(self.TE) else None,
            "TF_s": self.TF if math.isfinite(self.TF) else None,
            "eta_damping_ref": self.eta_damping_ref,
            "pga_g": self.pga / self.g,
            "plateau_g": self.pga * self.F0 / self.g,
            "dg_m": self.dg,
            "g_m_s2": self.g,
            "params": dict(self.params),
        }


# -------------------------------------------------------------------------------------
# NTC 2018
# -------------------------------------------------------------------------------------
def ntc2018_spectrum(*, ag_g: float, f0: float, tc_star_s: float, soil: str = "A",
                     topography: str = "T1", component: str = "horizontal",
                     g: float = STANDARD_GRAVITY) -> ElasticSpectrum:
    """NTC 2018 §3.2.3.2 elastic spectrum from the site's hazard and categories.

    Parameters
    ----------
    ag_g : float
        a_g on type A ground, in g (0, 3].
    f0 : float
        F0, the plateau amplification on rock, in [2.2, 4.0] (the code's minimum is 2.2).
    tc_star_s : float
        T_C*, s, in [0.05, 0.8].
    soil : {'A', 'B', 'C', 'D', 'E'}
        Subsoil category (Tab. 3.2.II).
    topography : {'T1', 'T2', 'T3', 'T4'}
        Topographic category (Tab. 3.2.III); S_T of Tab. 3.2.V (the ridge-height reduction of
        §3.2.3.2.1 is left to the user: pass T1 and an amplified a_g if needed).
    component : {'horizontal', 'vertical'}
    g : float
        Gravity, m/s^2.

    Returns
    -------
    ElasticSpectrum
        S = S_S S_T with S_S clipped to Tab. 3.2.IV's bounds; T_C = C_C T_C* (3.2.5),
        T_B = T_C / 3 (3.2.6), T_D = 4 a_g/g + 1.6 (3.2.7). Vertical: S = S_T, F_v = 1.35 F0
        (a_g/g)^0.5 (3.2.9), T_B, T_C, T_D = 0.05, 0.15, 1.0 s (Tab. 3.2.VI).

    Raises
    ------
    archquake.errors.InvalidParameterError
        An argument outside its range, or an unknown category (one line naming it).
    """
    g = require_positive("g", g, "m/s^2")
    ag_g = require_range("ag_g", ag_g, *SITE_AG_RANGE_G, high_open=False, unit="g")
    f0 = require_range("f0", f0, *NTC_F0_RANGE, low_open=False, high_open=False)
    tc_star = require_range("tc_star_s", tc_star_s, *NTC_TC_STAR_RANGE_S, low_open=False,
                            high_open=False, unit="s")
    soil = _choice("soil", soil, NTC_SOILS)
    topography = _choice("topography", topography, NTC_TOPOGRAPHIES)
    component = _choice("component", component, SPECTRUM_COMPONENTS)
    params = {"ag_g": ag_g, "f0": f0, "tc_star_s": tc_star, "soil": soil,
              "topography": topography}
    s_t = _NTC_ST[topography]
    if component == "vertical":
        tb, tc, td = _NTC_VERTICAL
        return ElasticSpectrum("ntc2018", component, ag_g * g, s_t, _NTC_FV * f0 * math.sqrt(ag_g),
                               tb, tc, td, g=g, params=params)
    s_s, c_c = ntc2018_soil_factors(soil, ag_g=ag_g, f0=f0, tc_star_s=tc_star)
    tc = c_c * tc_star
    return ElasticSpectrum("ntc2018", component, ag_g * g, s_s * s_t, f0, tc / 3.0, tc,
                           4.0 * ag_g + 1.6, _NTC_TE[soil], _NTC_TF, g=g, params=params)


def ntc2018_soil_factors(soil: str, *, ag_g: float, f0: float,
                         tc_star_s: float) -> tuple[float, float]:
    """S_S and C_C of NTC 2018 Tab. 3.2.IV, S_S clipped to the table's bounds.

    Examples
    --------
    >>> [round(x, 4) for x in ntc2018_soil_factors("B", ag_g=0.25, f0=2.4, tc_star_s=0.3)]
    [1.16, 1.3995]
    >>> ntc2018_soil_factors("D", ag_g=0.05, f0=2.4, tc_star_s=0.25)[0]   # 2.22 -> 1.80
    1.8
    """
    soil = _choice("soil", soil, NTC_SOILS)
    a, b, low, high = _NTC_SS[soil]
    s_s = min(max(a - b * f0 * ag_g, low), high)
    c, p = _NTC_CC[soil]
    return s_s, c * tc_star_s ** p


# -------------------------------------------------------------------------------------
# EN 1998-1
# -------------------------------------------------------------------------------------
def ec8_spectrum(*, ag_g: float, spectrum_type: int = 1, ground: str = "A",
                 importance: float = 1.0, component: str = "horizontal",
                 g: float = STANDARD_GRAVITY) -> ElasticSpectrum:
    """EN 1998-1:2004 §3.2.2.2 (horizontal) or §3.2.2.3 (vertical) elastic spectrum.

    Parameters
    ----------
    ag_g : float
        Reference peak ground acceleration on type A ground a_gR, in g (0, 3].
    spectrum_type : {1, 2}
        Type 1, or Type 2 where the earthquakes that dominate the hazard have M_s <= 5.5.
    ground : {'A', 'B', 'C', 'D', 'E'}
        Ground type (Tab. 3.1); S1 and S2 need a site study and are not offered.
    importance : float
        Importance factor gamma_I in [0.5, 2.0]: a_g = gamma_I a_gR.
    component : {'horizontal', 'vertical'}
    g : float
        Gravity, m/s^2.

    Returns
    -------
    ElasticSpectrum
        Recommended values of Tab. 3.2/3.3 (horizontal) or 3.4 (vertical); national annexes
        may set others. The last branch, given up to 4 s by the code, is continued beyond.

    Examples
    --------
    >>> spec = ec8_spectrum(ag_g=0.2, ground="C")
    >>> round(float(spec.sa(0.4)[0]) / spec.g, 4)       # 0.2 * 1.15 * 2.5
    0.575
    """
    g = require_positive("g", g, "m/s^2")
    ag_r = require_range("ag_g", ag_g, *SITE_AG_RANGE_G, high_open=False, unit="g")
    if spectrum_type not in EC8_SPECTRUM_TYPES:
        raise InvalidParameterError(f"spectrum_type must be 1 or 2, got {spectrum_type!r}")
    spectrum_type = int(spectrum_type)
    ground = _choice("ground", ground, EC8_GROUNDS)
    importance = require_range("importance", importance, *IMPORTANCE_RANGE, low_open=False,
                               high_open=False)
    component = _choice("component", component, SPECTRUM_COMPONENTS)
    params = {"ag_g": ag_r, "spectrum_type": spectrum_type, "ground": ground,
              "importance": importance}
    ag = importance * ag_r * g
    if component == "vertical":
        ratio, tb, tc, td = _EC8_VERTICAL[spectrum_type]
        return ElasticSpectrum("ec8", component, ag, 1.0, _EC8_FV, tb, tc, td, avg_ratio=ratio,
                               g=g, params=params)
    s, tb, tc, td = _EC8_HORIZONTAL[spectrum_type][ground]
    return ElasticSpectrum("ec8", component, ag, s, _EC8_F0, tb, tc, td, g=g, params=params)


# -------------------------------------------------------------------------------------
# NTC site hazard
# -------------------------------------------------------------------------------------
def return_period_years(limit_state: str, nominal_life_years: float = 50.0,
                        use_class: str = "II") -> float:
    """Return period T_R of NTC 2018 eq. 3.2.0, years.

    T_R = -V_R / ln(1 - P_VR), V_R = V_N C_U, P_VR of Tab. 3.2.I (SLO 81 %, SLD 63 %,
    SLV 10 %, SLC 5 %), C_U = 0.7, 1.0, 1.5, 2.0 for use classes I-IV.

    Examples
    --------
    >>> round(return_period_years("SLV"))
    475
    >>> round(return_period_years("SLD", 50, "II")), round(return_period_years("SLC"))
    (50, 975)
    """
    state = _choice("limit_state", str(limit_state).upper(), NTC_LIMIT_STATES)
    v_n = require_range("nominal_life_years", nominal_life_years, *NOMINAL_LIFE_RANGE_YEARS,
                        low_open=False, high_open=False, unit="years")
    use = _choice("use_class", str(use_class).upper(), NTC_USE_CLASSES)
    return -v_n * _NTC_CU[use] / math.log(1.0 - _NTC_PVR[state])


@dataclass(frozen=True)
class NTCHazard:
    """A site's hazard from NTC 2018 Allegato A/B: (T_R, a_g, F0, T_C*) at several T_R.

    Parameters
    ----------
    points : sequence of (float, float, float, float)
        (return period in years, a_g in g, F0, T_C* in s), at two or more distinct return
        periods (the grid gives 30, 50, 72, 101, 140, 201, 475, 975 and 2475 years); stored
        sorted by return period.

    Examples
    --------
    >>> hz = NTCHazard([(475, 0.25, 2.4, 0.30), (975, 0.32, 2.45, 0.32)])
    >>> [round(x, 4) for x in hz.at(475)]
    [0.25, 2.4, 0.3]
    >>> round(hz.at(700)[0], 4)
    0.2856
    """

    points: Sequence[tuple[float, float, float, float]]

    def __post_init__(self) -> None:
        rows = []
        for i, row in enumerate(self.points):
            if len(row) != 4:
                raise InvalidParameterError(
                    f"hazard point {i} must be (T_R years, a_g g, F0, T_C* s), got {row!r}")
            t_r = require_positive(f"hazard point {i} T_R", row[0], "years")
            ag = require_positive(f"hazard point {i} a_g", row[1], "g")
            f0 = require_positive(f"hazard point {i} F0", row[2])
            tc = require_positive(f"hazard point {i} T_C*", row[3], "s")
            rows.append((t_r, ag, f0, tc))
        rows.sort()
        if len(rows) < 2 or len({r[0] for r in rows}) != len(rows):
            raise InvalidParameterError(
                "hazard needs points at two or more distinct return periods")
        object.__setattr__(self, "points", tuple(rows))

    def at(self, return_period_years: float) -> tuple[float, float, float]:
        """(a_g in g, F0, T_C* in s) at a return period, years.

        Allegato A's interpolation, linear in log p against log T_R between the two
        neighbouring return periods: log p = log p1 + log(p2/p1) log(T_R/T_R1) / log(T_R2/T_R1).
        Outside the points' range it raises (no extrapolation).
        """
        t_r = require_finite("return_period_years", return_period_years, "years")
        lo, hi = self.points[0][0], self.points[-1][0]
        if not lo <= t_r <= hi:
            raise InvalidParameterError(
                f"return_period_years must be in [{lo:g}, {hi:g}] (the hazard's points), "
                f"got {t_r:g}")
        table = np.log(np.asarray(self.points))
        x = math.log(t_r)
        return tuple(float(np.exp(np.interp(x, table[:, 0], table[:, k]))) for k in (1, 2, 3))  # type: ignore[return-value]

    def spectrum(self, return_period: float, **site: Any) -> ElasticSpectrum:
        """`ntc2018_spectrum` at one return period (years); ``site`` its other keywords."""
        ag_g, f0, tc_star = self.at(return_period)
        return ntc2018_spectrum(ag_g=ag_g, f0=f0, tc_star_s=tc_star, **site)


# -------------------------------------------------------------------------------------
def _choice(name: str, value: object, choices: Sequence[Any]) -> Any:
    """``value`` if it is one of ``choices`` (text compared without case), else one line."""
    if isinstance(value, str):
        for c in choices:
            if isinstance(c, str) and c.lower() == value.strip().lower():
                return c
    elif value in choices:
        return value
    raise InvalidParameterError(
        f"{name} must be one of {', '.join(str(c) for c in choices)}, got {value!r}")


def _periods(periods: float | Iterable[float] | np.ndarray) -> np.ndarray:
    t = np.atleast_1d(np.asarray(periods, dtype=float)).copy()
    if t.ndim != 1 or not np.all(np.isfinite(t)) or np.any(t < 0.0):
        raise InvalidParameterError("periods must be finite numbers of seconds >= 0")
    return t


__all__ = [
    "CODES",
    "ETA_MIN",
    "REFERENCE_DAMPING",
    "ElasticSpectrum",
    "NTCHazard",
    "damping_factor",
    "ec8_spectrum",
    "ntc2018_soil_factors",
    "ntc2018_spectrum",
    "return_period_years",
]
