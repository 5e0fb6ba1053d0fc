"""TRL's full-scale load tests to collapse of masonry arch bridges (1984-94): what is published
of each bridge, with its source and how far it is to be trusted, and archquake's collapse load
for the one bridge whose geometry could be sourced (Prestwood).

Every number is a `Sourced` value: the value, its unit, where it is stated and a
confidence: ``"stated"`` (printed in TRL's own report abstract), ``"quoted"`` (stated in a later
paper that models the test, not checked against TRL's full report), ``"read"`` (our reading of
a quoted value, e.g. which span a figure dimensions), or ``"assumed"`` (no source found: a
value chosen to make the comparison possible, reported as such and bracketed). A quantity no
source we could read gives is ``None``.

The measured collapse loads are reported beside archquake's, never used to tune it: the
comparison in docs/loads.md ("Against the full-scale tests") is recomputed from this module by
tests/limit/test_trl_bridges.py.

Sources
-------
- TRL report abstracts (trl.co.uk/reports): RR110 (Page 1987, Preston and Prestwood), RR159
  (Page 1988, Torksey and Shinafoot), RR201 (Page, Strathmashie and Barlae; its year is not in
  the abstract).
- Simoncello N, Zampieri P, Gonzalez-Libreros J, Perboni S, Pellegrino C (2020). Numerical
  analysis of an FRP-strengthened masonry arch bridge. Front. Built Environ. 6:7,
  doi:10.3389/fbuil.2020.00007 (open access): Prestwood's span, rise, ring thickness and width
  (Fig. 7B), the masonry's and the fill's unit weights and the fill's friction angle (Table 4),
  the 300 mm loaded length (section "Masonry arch bridge"). Taken from a per-value
  transcription of the paper (with its figure and table for each value), not re-read from the
  paper here: to be re-checked against it, and against Page (1987), before any stricter use.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from archquake.geometry.arch import Arch
from archquake.geometry.loads import Fill, Loads, Passive, Traffic
from archquake.limit.capacity import TrafficCapacity, traffic_capacity

RR110 = ("Page J (1987). Load tests to collapse on two arch bridges at Preston, Shropshire and "
         "Prestwood, Staffordshire. TRRL Research Report 110 (abstract)")
RR159 = ("Page J (1988). Load tests to collapse on two arch bridges at Torksey and Shinafoot. "
         "TRRL Research Report 159 (abstract)")
RR201 = ("TRRL Research Report 201 (J. Page; abstract at trl.co.uk/reports/RR201): load tests "
         "to collapse on the Strathmashie and Barlae bridges")
SIMONCELLO = ("Simoncello N et al. (2020). Numerical analysis of an FRP-strengthened masonry "
              "arch bridge. Front. Built Environ. 6:7, doi:10.3389/fbuil.2020.00007")

CONFIDENCES = ("stated", "quoted", "read", "assumed")


@dataclass(frozen=True)
class Sourced:
    """A number with its unit, its source and its confidence (see the module's docstring)."""

    value: float
    unit: str
    source: str
    confidence: str = "stated"

    def __post_init__(self) -> None:
        if self.confidence not in CONFIDENCES:
            raise ValueError(f"confidence must be one of {CONFIDENCES}, got {self.confidence!r}")
        if not math.isfinite(self.value):
            raise ValueError(f"bad value {self.value!r}")


@dataclass(frozen=True)
class TrlBridge:
    """One of TRL's bridges loaded to collapse: what is published of it (None: not found).

    Lengths in m, unit weights as densities in kg/m^3, the load in kN in all over the barrel's
    width, applied on a line (or a short patch, ``load_length``) across the full width at
    ``load_at`` of the span from a springing.
    """

    name: str
    ring: str
    span: Sourced | None
    collapse_load: Sourced
    load_at: Sourced
    mode: str
    rise: Sourced | None = None
    thickness: Sourced | None = None
    width: Sourced | None = None
    fill_depth: Sourced | None = None
    masonry_density: Sourced | None = None
    fill_density: Sourced | None = None
    fill_friction: Sourced | None = None
    load_length: Sourced | None = None

    @property
    def missing(self) -> tuple[str, ...]:
        """The quantities a comparison needs that no source we read gives."""
        need = ("span", "rise", "thickness", "width", "fill_depth", "masonry_density",
                "fill_density")
        return tuple(k for k in need if getattr(self, k) is None
                     or getattr(self, k).confidence == "assumed")


#: Prestwood (Staffordshire): brick segmental ring "only 220 mm thick ... in poor
#: condition, with parapets removed and a distorted arch" (RR110).
PRESTWOOD = TrlBridge(
    name="Prestwood", ring="brick, segmental, one ring",
    span=Sourced(6.55, "m", SIMONCELLO + ", Fig. 7B (L), taken as the clear span of the "
                 "intrados", "read"),
    rise=Sourced(1.428, "m", SIMONCELLO + ", Fig. 7B (f), taken as the intrados rise", "read"),
    thickness=Sourced(0.22, "m", RR110 + "; " + SIMONCELLO + ", Fig. 7B (t)"),
    width=Sourced(3.8, "m", SIMONCELLO + ", Fig. 7B (s)", "quoted"),
    fill_depth=None,
    masonry_density=Sourced(1800.0, "kg/m^3", SIMONCELLO + ", Table 4", "quoted"),
    fill_density=Sourced(2040.0, "kg/m^3", SIMONCELLO + ", Table 4 (Mohr-Coulomb fill)",
                         "quoted"),
    fill_friction=Sourced(30.0, "deg", SIMONCELLO + ", Table 4 (with 5 kPa cohesion)",
                          "quoted"),
    load_at=Sourced(0.25, "of span", RR110 + "; " + SIMONCELLO),
    load_length=Sourced(0.3, "m", SIMONCELLO + ", section 'Masonry arch bridge' (a 300 mm "
                        "patch over the full width)", "quoted"),
    collapse_load=Sourced(228.0, "kN", RR110),
    mode="four-hinge mechanism",
)

#: The other bridges: spans, loads and modes from the reports' abstracts; no rise, fill depth
#: or width found in a source we could read.
OTHERS = (
    TrlBridge("Preston", "sandstone, elliptical, 0.36 m", None,
              Sourced(2110.0, "kN", RR110), Sourced(1 / 3, "of span", RR110),
              "crushing of the ring under the load line",
              thickness=Sourced(0.36, "m", RR110)),
    TrlBridge("Torksey", "brick, three rings", Sourced(4.90, "m", RR159),
              Sourced(1080.0, "kN", RR159), Sourced(0.25, "of span", RR159),
              "snap-through of three hinges"),
    TrlBridge("Shinafoot", "random rubble", Sourced(6.16, "m", RR159),
              Sourced(2524.0, "kN", RR159), Sourced(0.25, "of span", RR159),
              "four-hinge mechanism"),
    TrlBridge("Strathmashie", "rubble, poor, longitudinal crack",
              Sourced(9.42, "m", RR201), Sourced(1325.0, "kN", RR201),
              Sourced(0.25, "of span", RR201), "not stated in the abstract"),
    TrlBridge("Barlae", "ashlar, 29 deg skew", Sourced(8.53, "m", RR201 + " (square span)"),
              Sourced(2900.0, "kN", RR201), Sourced(0.25, "of span", RR201),
              "not stated in the abstract"),
)

BRIDGES = (PRESTWOOD, *OTHERS)

# --- the comparison's choices (stated in docs/loads.md; none is fitted to the measured load) ---

#: Prestwood's fill depth over the crown is in none of the sources read: the comparison is made
#: at these assumed depths, m (the first is the table's row, the others bracket it).
ASSUMED_FILL_DEPTHS = (0.2, 0.1, 0.3)
#: The 2:1 spread of the traffic through the fill, degrees from the vertical (as the CLI's help).
SPREAD_2_TO_1 = 26.57
#: The mobilised fraction of Rankine's K_p when passive pressure is on (Grandjean's 0.33).
PASSIVE_FRACTION = 0.33
#: Voussoirs of the ring (hinges may form every 0.24 m of the centreline).
VOUSSOIRS = 30
#: The traffic load the multiplier scales, N per m of width (only its multiplier matters).
UNIT_LOAD_N_M = 100e3


def _known(value: Sourced | None) -> float:
    """The number of a sourced value that the comparison needs (Prestwood has them all)."""
    if value is None:
        raise ValueError("this bridge lacks a value the comparison needs")
    return value.value


def prestwood_arch(voussoirs: int = VOUSSOIRS) -> Arch:
    """Prestwood's ring as a circular arch: the intrados through the springings 6.55 m apart
    and 1.428 m below the crown, so the centreline radius is the intrados's plus t/2; depth
    the 3.8 m barrel width, so the collapse load comes out in kN over the whole width."""
    span, rise, t = _known(PRESTWOOD.span), _known(PRESTWOOD.rise), _known(PRESTWOOD.thickness)
    r_intrados = (0.25 * span * span + rise * rise) / (2.0 * rise)
    half = math.asin(0.5 * span / r_intrados)
    return Arch(r_intrados + 0.5 * t, t, 2.0 * half, voussoirs, _known(PRESTWOOD.width),
                _known(PRESTWOOD.masonry_density))


def prestwood_capacity(fill_depth: float, *, spread: bool, passive: bool,
                       voussoirs: int = VOUSSOIRS) -> TrafficCapacity:
    """archquake's collapse of Prestwood under TRL's test load: a 0.3 m patch across the full
    width centred at a quarter of the clear span, on a fill ``fill_depth`` m deep over the
    crown (2040 kg/m^3), spread at 2:1 when ``spread``, with passive pressure at
    `PASSIVE_FRACTION` of K_p (phi 30 deg) when ``passive``.

    ``.collapse_load_N_m * width`` is the total load on the barrel, to set beside 228 kN.
    """
    passive_ = (Passive(PASSIVE_FRACTION, _known(PRESTWOOD.fill_friction)) if passive else None)
    loads = Loads(fill=Fill(depth=fill_depth, density=_known(PRESTWOOD.fill_density)),
                  passive=passive_)
    traffic = Traffic(UNIT_LOAD_N_M, PRESTWOOD.load_at.value * _known(PRESTWOOD.span),
                      _known(PRESTWOOD.load_length), SPREAD_2_TO_1 if spread else None)
    return traffic_capacity(prestwood_arch(voussoirs), loads, traffic)


def prestwood_total_kN(fill_depth: float, *, spread: bool, passive: bool) -> float:
    """The collapse load on the whole 3.8 m barrel width, kN."""
    cap = prestwood_capacity(fill_depth, spread=spread, passive=passive)
    return cap.collapse_load_N_m * cap.arch.depth / 1e3
