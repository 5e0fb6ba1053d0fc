"""Every number De Lorenzis, DeJong & Ochsendorf (2007) state, once: value, tolerance, why that
tolerance, and where the paper states it; the arch they study and the parameters of their figures.

This module is the one home of the paper's numbers. ``archquake reproduce`` (one module per
study in `archquake.reproduce`) and the tests under ``tests/paper/`` read their values and
tolerances from here, so one number has one tolerance everywhere.

A stated number is a `PaperValue`; a comparison of archquake's two models that the paper
words without a number ("excellent agreement") is an `Agreement` with the relative or
absolute bound that reads the words. Both check a computed value and explain a miss:

>>> from archquake.validation import paper
>>> paper.ONSET_ACCELERATION.within(0.3700)
True
>>> paper.ONSET_ACCELERATION.check(0.40, "lambda")
'lambda = 0.4 g, the paper 0.37 g +/- 0.005 g (p. 2126): off by 0.03 g'

Reference: De Lorenzis L, DeJong M, Ochsendorf J (2007). Failure of masonry arches under impulse
base motion. Earthquake Engng Struct. Dyn. 36:2119-2136 (pages below are the journal's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from archquake.geometry.arch import Arch

#: The paper, for reports and docstrings.
CITATION = (
    "De Lorenzis L, DeJong M, Ochsendorf J (2007). Failure of masonry arches under impulse base "
    "motion. Earthquake Engng Struct. Dyn. 36:2119-2136."
)


@dataclass(frozen=True)
class PaperValue:
    """A number the paper states, with the tolerance archquake holds it to.

    Parameters
    ----------
    value : float
        The paper's value, in ``unit``.
    tolerance : float
        Accepted absolute difference, in ``unit`` (``|x - value| <= tolerance``).
    unit : str
        Unit as printed ("g", "s", "" for a pure number, "1/s", "Hz").
    where : str
        Page and figure of the paper.
    why : str
        Justification of the tolerance (digits given, what is read off a figure).
    stated : str
        The value as the paper writes it ("~0.86 s"); default ``value`` and ``unit``.
    """

    value: float
    tolerance: float
    unit: str
    where: str
    why: str
    stated: str = ""

    def __post_init__(self) -> None:
        if not (math.isfinite(self.value) and self.tolerance >= 0):
            raise ValueError(f"bad paper value {self.value!r} +/- {self.tolerance!r}")
        if not self.stated:
            object.__setattr__(self, "stated", self._with_unit(self.value))

    def _with_unit(self, x: float) -> str:
        return f"{x:g} {self.unit}".rstrip()

    @property
    def tolerance_text(self) -> str:
        """``"+/- 0.005 g"``: the tolerance as the report prints it."""
        return "+/- " + self._with_unit(self.tolerance)

    def within(self, x: float | None) -> bool:
        """``|x - value| <= tolerance`` (False for None or NaN)."""
        return x is not None and math.isfinite(x) and abs(x - self.value) <= self.tolerance

    def check(self, x: float | None, what: str = "archquake") -> str | None:
        """None when ``x`` is within the tolerance, otherwise one readable line saying by how
        much it misses (for an ``assert ... , message`` in a test)."""
        if self.within(x):
            return None
        off = "not computed" if x is None or not math.isfinite(x) else (
            f"off by {self._with_unit(abs(x - self.value))}")
        return (f"{what} = {self._with_unit(x) if x is not None else None}, the paper "
                f"{self._with_unit(self.value)} {self.tolerance_text} ({self.where}): {off}")


@dataclass(frozen=True)
class Agreement:
    """A comparison the paper words without a number, and the bound that reads the words.

    Parameters
    ----------
    bound : float
        Accepted difference: relative (a fraction of the reference) if ``relative``, else
        absolute in ``unit``.
    relative : bool
    unit : str
    where, why : str
        Where the paper says it; why this bound.
    stated : str
        The paper's words ("reasonably good agreement").
    """

    bound: float
    relative: bool
    unit: str
    where: str
    why: str
    stated: str

    @property
    def tolerance_text(self) -> str:
        return f"+/- {100 * self.bound:g} %" if self.relative else f"<= {self.bound:g} {self.unit}"

    def difference(self, x: float | None, reference: float | None) -> float:
        """``|x - reference|``, relative to ``|reference|`` if ``relative`` (NaN if either is
        missing)."""
        if x is None or reference is None or not (math.isfinite(x) and math.isfinite(reference)):
            return math.nan
        d = abs(x - reference)
        return d / abs(reference) if self.relative else d

    def within(self, x: float | None, reference: float | None) -> bool:
        d = self.difference(x, reference)
        return math.isfinite(d) and d <= self.bound

    def check(self, x: float | None, reference: float | None, what: str = "archquake") -> str | None:
        """None when within the bound, otherwise one readable line."""
        if self.within(x, reference):
            return None
        return (f"{what}: {x} against {reference} differ by {self.difference(x, reference):.4g}"
                f"{'' if self.relative else ' ' + self.unit}, bound {self.tolerance_text} "
                f"('{self.stated}', {self.where})")


# ----------------------------------------------------------------------------- the arch
#: Oppenheim's arch (p. 2126): radius, m; thickness ratio t/R; embrace, degrees; voussoirs
#: (7: the paper's Figures 8 to 10 draw seven).
OPPENHEIM_RADIUS_M = 10.0
OPPENHEIM_THICKNESS_RATIO = 0.15
OPPENHEIM_EMBRACE_DEG = 157.5
OPPENHEIM_VOUSSOIRS = 7
#: Masonry density of the DEM, kg/m^3 (p. 2131; it does not enter the four-link model).
DENSITY_KG_M3 = 2000.0


def oppenheim_arch(radius: float = OPPENHEIM_RADIUS_M,
                   thickness_ratio: float = OPPENHEIM_THICKNESS_RATIO,
                   embrace_deg: float = OPPENHEIM_EMBRACE_DEG,
                   voussoirs: int = OPPENHEIM_VOUSSOIRS) -> Arch:
    """Oppenheim's arch (t/R = 0.15, embrace 157.5 degrees, R = 10 m, 7 voussoirs) or a variant.

    Parameters
    ----------
    radius : float
        Centre-line radius R, m.
    thickness_ratio : float
        t/R.
    embrace_deg : float
        Embrace, degrees.
    voussoirs : int
        Number of voussoirs.

    Examples
    --------
    >>> oppenheim_arch().thickness
    1.5
    """
    return Arch(radius, thickness_ratio * radius, math.radians(embrace_deg), voussoirs)


# ----------------------------------------------------------------------------- figure parameters
#: Figure 4: step impulses of this magnitude (g) ...
FIGURE4_MAGNITUDE_G = 1.0
#: ... and these durations t_p, s (Figure 4(b), (c), (d)).
FIGURE4_DURATIONS = (0.44, 0.27, 0.20)
#: Figure 6: radii, m (t/R = 0.15, 157.5 degrees, 7 voussoirs).
FIGURE6_RADII = (1.0, 5.0, 10.0, 20.0)
#: Figure 7(a): thickness ratios t/R at 157.5 degrees.
FIGURE7_RATIOS = (0.11, 0.15, 0.17, 0.19)
#: Figure 7(b): embraces, degrees, at t/R = 0.15.
FIGURE7_EMBRACES_DEG = (142.5, 150.0, 157.5, 165.0)
#: Figure 8 (and 9): the pulse, (a in g, t_p in s) ...
FIGURE8_PULSE = (1.0, 0.20)
#: ... and the snapshot times of Figure 8, s.
FIGURE8_TIMES = (0.2, 0.5, 0.8, 1.1, 1.5, 2.22)
#: Figure 9 (the DEM's snapshots; our Figure 8 comparison), s.
FIGURE9_TIMES = (0.20, 0.50, 0.80, 1.10, 1.30, 1.80)
#: The DEM's Rayleigh damping (p. 2131): minimum damping ratio xi_min at f_min, (Hz, ratio).
DEM_DAMPING = (0.1, 1e-4)
#: The DEM's joint stiffness, Pa/m (p. 2131 prints "10^12 GPa/m"; read as Pa/m, study damping).
DEM_NORMAL_STIFFNESS_PA_M = 1e12
#: Figure 10: reduced Rayleigh damping f_min = 0.05 Hz, xi_min = 0.001 % (alpha ~ 3.14e-6 1/s,
#: beta ~ 3.18e-5 s; the paper's text repeats the first alpha, beta by mistake), ...
FIGURE10_DAMPING = (0.05, 1e-5)
#: ... the pulse (a in g, t_p in s) ...
FIGURE10_PULSE = (1.0, 0.22)
#: ... and the snapshot time, s.
FIGURE10_TIME = 1.29
#: p. 2131: the impulse magnitudes (g) of the friction demand.
FRICTION_MAGNITUDES_G = (0.5, 1.0)

# ----------------------------------------------------------------------------- stated numbers
_TWO_DIGITS = "the paper gives two digits: half a unit of the last"

#: p. 2126: the acceleration that starts hinging (equivalent static analysis).
ONSET_ACCELERATION = PaperValue(0.37, 0.005, "g", "p. 2126", _TWO_DIGITS)
#: p. 2131: friction demand of the equivalent static analysis.
STATIC_FRICTION = PaperValue(0.50, 0.005, "", "p. 2131", "the paper gives two digits",
                             stated="0.50")
#: p. 2126, Figure 4(c): first impact at t_p = 0.27 s.
FIGURE4C_FIRST_IMPACT = PaperValue(
    0.86, 0.02, "s", "p. 2126, Figure 4(c)",
    "'about 0.86 s': two digits read off Figure 4(c); 0.02 s is one line width there",
    stated="~0.86 s")
#: p. 2126, Figure 4(d): first impact at t_p = 0.20 s.
FIGURE4D_FIRST_IMPACT = PaperValue(
    0.6, 0.05, "s", "p. 2126, Figure 4(d)", "'about 0.6 s': one digit, half a unit of it",
    stated="~0.6 s")
#: p. 2131: friction to prevent sliding at a = 1.0 g (analytical).
FRICTION_1G = PaperValue(
    0.56, 0.01, "", "p. 2131",
    "'~0.56': two digits, approximate; the paper's own UDEC threshold is 0.55 (p. 2134)",
    stated="~0.56")
#: p. 2131: friction to prevent sliding at a = 0.5 g (analytical).
FRICTION_05G = PaperValue(0.509, 0.001, "", "p. 2131", "three digits given", stated="0.509")
_DEM_FRICTION_WHY = ("two digits given (half a unit: 0.005) plus the bisection's relative "
                     "precision")
#: p. 2134: the DEM (UDEC) friction threshold at a = 1.0 g.
DEM_FRICTION_1G = PaperValue(0.55, 0.01, "", "p. 2134", _DEM_FRICTION_WHY, stated="0.55 (UDEC)")
#: p. 2134: the DEM (UDEC) friction threshold at a = 0.5 g.
DEM_FRICTION_05G = PaperValue(0.51, 0.01, "", "p. 2134", _DEM_FRICTION_WHY, stated="0.51 (UDEC)")
#: p. 2131: Rayleigh coefficients of xi_min = 0.01 % at 0.1 Hz: alpha, 1/s ...
RAYLEIGH_ALPHA = PaperValue(6.28e-5, 5e-8, "1/s", "p. 2131", "the paper prints 3 digits",
                            stated="6.28e-5")
#: ... and beta, s.
RAYLEIGH_BETA = PaperValue(1.59e-4, 5e-7, "s", "p. 2131", "the paper prints 3 digits",
                           stated="1.59e-4")
#: p. 2133: vibrations above this frequency are critically damped.
CRITICAL_FREQUENCY = PaperValue(2000.0, 100.0, "Hz", "p. 2133",
                                "'>2000 Hz' (one significant digit): 5 %", stated="~2000 Hz")
#: p. 2133: Figure 10's reduced damping (the text repeats the first coefficients, so the values
#: are computed from xi_min = 0.001 % at 0.05 Hz and read by the stated critical frequency):
#: alpha, 1/s ...
REDUCED_RAYLEIGH_ALPHA = PaperValue(3.14e-6, 5e-9, "1/s", "p. 2133",
                                    "3 digits; the text's '>10 000 Hz' fixes the reading",
                                    stated="~3.14e-6")
#: ... beta, s ...
REDUCED_RAYLEIGH_BETA = PaperValue(3.18e-5, 5e-8, "s", "p. 2133",
                                   "3 digits; the text's '>10 000 Hz' fixes the reading",
                                   stated="~3.18e-5")
#: ... and the critical frequency, Hz.
REDUCED_CRITICAL_FREQUENCY = PaperValue(1e4, 500.0, "Hz", "p. 2133",
                                        "'>10 000 Hz' (one significant digit): 5 %",
                                        stated="~10 000 Hz")

# ----------------------------------------------------------------------------- worded agreements
#: p. 2132, Figure 4(b): the three-voussoir DEM against the analytical phi over the first half
#: cycle, rad.
THREE_VOUSSOIR_AGREEMENT = Agreement(
    5e-3, False, "rad", "p. 2132, Figure 4(b)",
    "contact compliance (k_n = 1e12 Pa/m) and sampling; 'excellent' taken as 5 % of a 0.1 rad "
    "rotation", "excellent agreement")
#: p. 2132, Figure 4(c), (d): the seven-voussoir DEM's first impact against the analytical one
#: (and against the paper's first-impact times).
DEM_FIRST_IMPACT_AGREEMENT = Agreement(
    0.10, True, "s", "p. 2132, Figure 4(c), (d)",
    "the hinges move in the DEM (p. 2132), so the paper calls the agreement only "
    "'reasonably good'", "reasonably good agreement before impact")
#: p. 2133, Figures 6 and 11: first-half-cycle boundaries, DEM (three voussoirs) vs analytical.
DEM_FIRST_BOUNDARY_AGREEMENT = Agreement(
    0.05, True, "g", "p. 2133, Figures 6, 11",
    "DEM search bracket plus contact compliance; 'excellent' (the paper's curves overlap)",
    "excellent agreement (no impact)")

# ----------------------------------------------------------------------------- the references
#: Minimum thickness of the semicircular arch under its own weight (Heyman, the paper's
#: refs. [1, 2]; Milankovitch 1907), t/R; not stated in the paper itself.
SEMICIRCLE_MIN_THICKNESS = PaperValue(
    0.1075, 0.001, "", "Heyman (1969), the paper's ref. [1, 2]",
    "a continuous arch: +/- 0.001 allows for the finite number of joints")


__all__ = [
    "Agreement",
    "CITATION",
    "CRITICAL_FREQUENCY",
    "DEM_DAMPING",
    "DEM_FIRST_BOUNDARY_AGREEMENT",
    "DEM_FIRST_IMPACT_AGREEMENT",
    "DEM_FRICTION_05G",
    "DEM_FRICTION_1G",
    "DEM_NORMAL_STIFFNESS_PA_M",
    "DENSITY_KG_M3",
    "FIGURE10_DAMPING",
    "FIGURE10_PULSE",
    "FIGURE10_TIME",
    "FIGURE4C_FIRST_IMPACT",
    "FIGURE4D_FIRST_IMPACT",
    "FIGURE4_DURATIONS",
    "FIGURE4_MAGNITUDE_G",
    "FIGURE6_RADII",
    "FIGURE7_EMBRACES_DEG",
    "FIGURE7_RATIOS",
    "FIGURE8_PULSE",
    "FIGURE8_TIMES",
    "FIGURE9_TIMES",
    "FRICTION_05G",
    "FRICTION_1G",
    "FRICTION_MAGNITUDES_G",
    "ONSET_ACCELERATION",
    "OPPENHEIM_EMBRACE_DEG",
    "OPPENHEIM_RADIUS_M",
    "OPPENHEIM_THICKNESS_RATIO",
    "OPPENHEIM_VOUSSOIRS",
    "PaperValue",
    "RAYLEIGH_ALPHA",
    "RAYLEIGH_BETA",
    "REDUCED_CRITICAL_FREQUENCY",
    "REDUCED_RAYLEIGH_ALPHA",
    "REDUCED_RAYLEIGH_BETA",
    "SEMICIRCLE_MIN_THICKNESS",
    "STATIC_FRICTION",
    "THREE_VOUSSOIR_AGREEMENT",
    "oppenheim_arch",
]
