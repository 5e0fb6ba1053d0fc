"""The range of every kind of value a user gives, in the user's units (g, s, m, degrees).

One place: the command line (:mod:`archquake.cli.common`) and the study files
(:mod:`archquake.sweeps.cases`) check against these. Ranges come from what the computation
represents without overflow or a time step below float resolution, and from what is physically
meaningful (an impact cannot create energy). Geometry's ranges (radius, depth, density,
thickness ratio, embrace, voussoirs) live with the Arch in :mod:`archquake.geometry.arch`.
"""

from __future__ import annotations

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
#: The analytical model's hinges (``archquake run --hinges``): ``fixed``, the paper's four-link
#: mechanism between impacts (the default); ``moving``, the chain of rigid blocks (issue 16).
HINGE_MODELS = ("fixed", "moving")
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
#: to them with a line (archquake.sweeps.runner.cap_workers).
WORKERS_RANGE = (1, 10**9)

#: Accepted suffixes by kind of output file.
FIGURE_SUFFIXES = (".png", ".pdf", ".svg")
ANIMATION_SUFFIXES = (".gif",)
CSV_SUFFIXES = (".csv",)
TABLE_SUFFIXES = (".csv", ".parquet")

__all__ = [
    "ANIMATION_SUFFIXES",
    "CSV_SUFFIXES",
    "DAMPING_FREQUENCY_RANGE_HZ",
    "DAMPING_RATIO_RANGE_PERCENT",
    "DEM_MAX_BLOCK_STEPS",
    "DEM_SECONDS_PER_BLOCK_STEP",
    "DEM_T_END_MAX_S",
    "HINGE_MODELS",
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
    "SCAN_RANGE",
    "STIFFNESS_RANGE",
    "TABLE_SUFFIXES",
    "T_END_RANGE_S",
    "WORKERS_RANGE",
]
