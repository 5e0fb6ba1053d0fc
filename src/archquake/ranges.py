"""The range of every kind of value a user gives, in the user's units (g, s, m, degrees).

One place: the command line (`archquake.cli.common`) and the study files
(`archquake.geometry.spec`, `archquake.ground.spec`, `archquake.sweeps.cases`)
check against these. Ranges come from what the computation
represents without overflow or a time step below float resolution, and from what is physically
meaningful (an impact cannot create energy). Geometry's ranges (radius, depth, density,
thickness ratio, embrace, voussoirs) live with their checks in `archquake.geometry.checks`.
"""

from __future__ import annotations

from archquake.constants import STANDARD_GRAVITY

#: Gravity g, m/s^2 (the keyword ``g=`` of every function): from a small moon's to a hundred
#: times the Earth's. Outside it weights and the time scale sqrt(R/g) leave the range where
#: the linear programme and the integrators are well conditioned (g = 1e308 overflows).
GRAVITY_RANGE_MS2 = (1e-2, 1e3)
#: Pulse magnitude and domain ceiling, g (--magnitude, --max-magnitude).
MAGNITUDE_RANGE_G = (0.0, 1000.0)
#: Pulse duration t_p and period T, s (--duration, --period, --durations).
PULSE_TIME_RANGE_S = (1e-6, 1000.0)
#: End of an analysis, s (--t-end); also the latest instant --times may ask for.
T_END_RANGE_S = (0.01, 1e4)
#: How long a run goes on after the end of the excitation when no end is given, in units of
#: sqrt(R/g) (60 sqrt(R/g) = 61 s for R = 10 m): long enough for a rocking arch to come to rest
#: or to be shown unable to reach a crest again. The four-link model's default end
#: (`default_t_end`) and the rigid chain's verdict window.
RUN_TAIL = 60.0


def default_t_end(excitation_end_s, radius: float, g: float = STANDARD_GRAVITY):
    """The default end of an analysis, s: the end of the excitation plus `RUN_TAIL`
    sqrt(R/g) (the four-link model's default end, its failure domains' batch and its
    incremental dynamic analysis; the latest end of the rigid chain's run to a verdict).

    Parameters
    ----------
    excitation_end_s : float or ndarray
        End of each excitation, s.
    radius : float
        The arch's radius R, m.
    g : float
        Gravity, m/s^2.

    Returns
    -------
    ndarray
        s, the shape of ``excitation_end_s``.

    Examples
    --------
    >>> round(float(default_t_end(0.81, 10.0)), 3)
    61.399
    """
    import math

    import numpy as np

    return np.asarray(excitation_end_s, dtype=float) + RUN_TAIL * math.sqrt(radius / g)
#: The four-link model's impact laws (``--impact``; `archquake.mechanism.impact`).
IMPACT_LAWS = ("paper", "chain", "mirror")
#: Longest distinct-element run, s of simulated time (--t-end with --model dem, or its default):
#: the explicit DEM steps ~1e-5 s, so 120 s is already millions of steps.
DEM_T_END_MAX_S = 120.0
#: Most work of one distinct-element run: blocks x time steps (settling included). The stable
#: step shrinks about as 1/blocks (Oppenheim's arch: 8.4e-7 s with 60 voussoirs, 2.3e-8 s with
#: 2000), so the work grows as blocks^2: 2000 voussoirs for 0.1 s are 9e9 block-steps. Measured
#: cost on one core: 1 to 5 us per block-step (7 to 200 blocks), so the bound is ~10-40 min.
DEM_MAX_BLOCK_STEPS = 5e8
#: The cost per block-step quoted in the refusal, s (the low end of the measured range).
DEM_SECONDS_PER_BLOCK_STEP = 1e-6
#: Most work of one run of the chain of rigid blocks: time steps x (blocks + 1)^3. Each step
#: assembles and solves the contacts of every joint as dense matrices, so its cost grows about as
#: the cube of the blocks: measured on one core 0.4-1.1 ns per unit (15 us a step with 7 voussoirs,
#: 5.7 ms with 200, 59 ms with 400). The bound is about 20 min: 200 voussoirs for 10 s at 1e-4 s
#: pass, 2000 voussoirs for 0.1 s (8e12) do not.
RIGID_MAX_WORK = 1e12
#: The cost per unit of work quoted in the refusal, s (the high end of the measured range).
RIGID_SECONDS_PER_WORK = 1.1e-9
#: Time step of a record, s: below 1e-6 s the integration's resolution is lost, above 1 s a
#: file is not an accelerogram.
RECORD_DT_RANGE_S = (1e-6, 1.0)
#: Longest record, s: the latest end of an analysis (T_END_RANGE_S).
RECORD_DURATION_MAX_S = T_END_RANGE_S[1]
#: Largest accelerogram file read, bytes: a 10,000 s record at 1 kHz is ~10^7 samples, ~200 MB
#: of text; a larger "file" is not an accelerogram (and a device like /dev/zero never ends).
RECORD_FILE_MAX_BYTES = 256 * 10**6
#: Factor on a record's values (--scale).
SCALE_RANGE = (0.0, 1000.0)
#: Records in a selected set, and the per-event limit (--count, --max-per-event).
SELECT_COUNT_RANGE = (1, 1000)
#: Prescribed coefficient of restitution c_v (--restitution): no impact creates energy.
RESTITUTION_RANGE = (0.0, 1.0)
#: DEM joint stiffness, Pa/m (--stiffness): the explicit time step ~ sqrt(m/k) stays resolvable.
STIFFNESS_RANGE = (1e6, 1e14)
#: DEM friction coefficient tan(phi) (--friction): phi from 0.06 to 89.4 degrees.
FRICTION_RANGE = (1e-3, 100.0)
#: DEM Rayleigh damping: alpha (1/s), beta (s); beta bounds the explicit time step.
RAYLEIGH_ALPHA_RANGE = (0.0, 1e3)
RAYLEIGH_BETA_RANGE = (0.0, 1e-3)
#: UDEC's minimum-damping form (--damping F_MIN,XI_MIN): Hz and percent.
DAMPING_FREQUENCY_RANGE_HZ = (1e-3, 1e3)
DAMPING_RATIO_RANGE_PERCENT = (0.0, 100.0)
#: Domain search (--precision, g; --scan; number of --durations and of --times).
PRECISION_RANGE_G = (1e-6, 1.0)
SCAN_RANGE = (2, 1000)
MAX_DURATIONS = 1000
MAX_TIMES = 1000
#: Worker processes a command may ask for; more than the usable cores (or the work) are capped
#: to them with a line (archquake.parallel.cap_workers).
WORKERS_RANGE = (1, 10**9)

#: Site spectra (archquake.codes.spectra). Peak ground acceleration on type A ground a_g, g:
#: above 0 and up to 3 g (the national hazard maps stay below 0.5 g; the kinematic check
#: solves for a capacity a_g that may lie far above them).
SITE_AG_RANGE_G = (0.0, 3.0)
#: Where an input leaves engineering practice, it is accepted with a one-line warning naming the
#: option (the usual slip is a unit: m/s^2 typed as g, ms as s, radians as degrees): a peak
#: ground acceleration or a_g above 1.5 g (the largest recorded PGAs are about 1-3 g, design
#: values stay below 0.5 g), an arch's radius below 0.2 m, a pulse longer than 10 s (a
#: near-fault pulse lasts about 0.5-5 s; 270 s is 270 ms typed as s).
PLAUSIBLE_PGA_G = 1.5
PLAUSIBLE_RADIUS_M = 0.2
PLAUSIBLE_PULSE_S = 10.0
#: An angle of embrace in degrees up to 2 pi (6.28 degrees, rise/span below 0.014) is refused
#: as radians typed as degrees (180 degrees is 3.1416 rad); a flatter ring is a beam.
RADIANS_EMBRACE_DEG = 2.0 * 3.141592653589793
#: NTC 2018 F0, the plateau's amplification on rock: the code sets its minimum at 2.2 (§3.2.3.2.1);
#: the hazard grid holds about 2.2-3.0, the upper bound 4.0 is ours and generous.
NTC_F0_RANGE = (2.2, 4.0)
#: NTC 2018 T_C*, s: the hazard grid holds about 0.15-0.6 s; bounds ours. Up to 0.8 s,
#: T_C = C_C T_C* stays below T_D >= 1.6 s on every soil (at most 1.12 s, soil D).
NTC_TC_STAR_RANGE_S = (0.05, 0.8)
#: NTC 2018 subsoil categories (Tab. 3.2.II) and topographic categories (Tab. 3.2.III).
NTC_SOILS = ("A", "B", "C", "D", "E")
NTC_TOPOGRAPHIES = ("T1", "T2", "T3", "T4")
#: NTC 2018 limit states (Tab. 3.2.I) and use classes (§2.4.2).
NTC_LIMIT_STATES = ("SLO", "SLD", "SLV", "SLC")
NTC_USE_CLASSES = ("I", "II", "III", "IV")
#: NTC 2018 nominal life V_N, years (§2.4.1 lists 10, 50 and 100; any value in between is allowed).
NOMINAL_LIFE_RANGE_YEARS = (1.0, 1000.0)
#: EN 1998-1 ground types (Tab. 3.1; S1 and S2 need a site study and are not offered) and
#: spectrum types (§3.2.2.2).
EC8_GROUNDS = ("A", "B", "C", "D", "E")
EC8_SPECTRUM_TYPES = (1, 2)
#: EN 1998-1 importance factor gamma_I (§4.2.5: 0.8, 1.0, 1.2, 1.4 recommended); bounds ours.
IMPORTANCE_RANGE = (0.5, 2.0)
#: Components of a code spectrum.
SPECTRUM_COMPONENTS = ("horizontal", "vertical")
#: Viscous damping ratio of a spectrum (fraction of critical): eta = sqrt(10/(5+100 xi)) is
#: floored at 0.55 from xi = 28.06 % on.
SPECTRUM_DAMPING_RANGE = (0.0, 1.0)
#: Periods of a spectrum, s (--periods): 0 (the PGA) to 20 s.
SPECTRUM_PERIOD_RANGE_S = (0.0, 20.0)
#: Shortest positive period, s (1 kHz): below it a record's spectrum needs more sub-steps than
#: any record has samples (T / 100 each), and 2 pi / T overflows near 1e-308; every spectrum is
#: flat at the peak acceleration long before it.
SPECTRUM_MIN_PERIOD_S = 1e-3
#: Number of periods a spectrum may be asked at (--periods START:STOP:STEP).
MAX_SPECTRUM_PERIODS = 10000
#: Height Z of a local mechanism's base and a building's height H, m; a building's period T1, s
#: (the code check at height: C7.2.11).
MECHANISM_HEIGHT_RANGE_M = (0.0, 1000.0)
BUILDING_PERIOD_RANGE_S = (0.0, 10.0)

#: Accepted suffixes by kind of output file.
FIGURE_SUFFIXES = (".png", ".pdf", ".svg")
ANIMATION_SUFFIXES = (".gif",)
CSV_SUFFIXES = (".csv",)
TABLE_SUFFIXES = (".csv", ".parquet")

__all__ = [
    "BUILDING_PERIOD_RANGE_S",
    "MECHANISM_HEIGHT_RANGE_M",
    "SITE_AG_RANGE_G",
    "PLAUSIBLE_PGA_G",
    "PLAUSIBLE_RADIUS_M",
    "PLAUSIBLE_PULSE_S",
    "RADIANS_EMBRACE_DEG",
    "NTC_F0_RANGE",
    "NTC_TC_STAR_RANGE_S",
    "NTC_SOILS",
    "NTC_TOPOGRAPHIES",
    "NTC_LIMIT_STATES",
    "NTC_USE_CLASSES",
    "NOMINAL_LIFE_RANGE_YEARS",
    "EC8_GROUNDS",
    "EC8_SPECTRUM_TYPES",
    "IMPORTANCE_RANGE",
    "SPECTRUM_COMPONENTS",
    "SPECTRUM_DAMPING_RANGE",
    "SPECTRUM_MIN_PERIOD_S",
    "SPECTRUM_PERIOD_RANGE_S",
    "MAX_SPECTRUM_PERIODS",
    "ANIMATION_SUFFIXES",
    "CSV_SUFFIXES",
    "DAMPING_FREQUENCY_RANGE_HZ",
    "DAMPING_RATIO_RANGE_PERCENT",
    "DEM_MAX_BLOCK_STEPS",
    "DEM_SECONDS_PER_BLOCK_STEP",
    "RIGID_MAX_WORK",
    "RIGID_SECONDS_PER_WORK",
    "DEM_T_END_MAX_S",
    "IMPACT_LAWS",
    "FIGURE_SUFFIXES",
    "FRICTION_RANGE",
    "GRAVITY_RANGE_MS2",
    "MAGNITUDE_RANGE_G",
    "MAX_DURATIONS",
    "MAX_TIMES",
    "PRECISION_RANGE_G",
    "PULSE_TIME_RANGE_S",
    "RAYLEIGH_ALPHA_RANGE",
    "RAYLEIGH_BETA_RANGE",
    "RECORD_DT_RANGE_S",
    "RECORD_DURATION_MAX_S",
    "RECORD_FILE_MAX_BYTES",
    "RESTITUTION_RANGE",
    "SCALE_RANGE",
    "SELECT_COUNT_RANGE",
    "SCAN_RANGE",
    "STIFFNESS_RANGE",
    "TABLE_SUFFIXES",
    "T_END_RANGE_S",
    "WORKERS_RANGE",
]
