"""Intensity measures of a ground motion: PGA, PGV, PGD, Arias, CAV, D5-95, Sa(T), Tm.

Every motion (a `Record`, a pulse, anything that follows the
`GroundMotion` protocol) is treated as the piecewise-linear
history the integrators see: a record is linear between its samples, a pulse is sampled
finely between its breakpoints with both one-sided values kept at every jump. The integrals
below are then exact for that history (no trapezoid error on top of the sampling).

Definitions (x_g'' = a(t) in m/s^2, ground at rest at t = 0):

- PGA = max |a| (reported in g);
- v(t) = int_0^t a, PGV = max |v| (m/s), including the extremes inside a sample interval
  where a changes sign (v is quadratic there);
- d(t) = int_0^t v, PGD = max |d| at the samples (m), over the motion's duration;
- Arias intensity I_A = pi/(2 g) int a^2 dt (m/s) (Arias 1970);
- CAV = int |a| dt (m/s) (EPRI 1988, without the 5 cm/s^2 threshold);
- D5-95 = t(95 % of I_A) - t(5 % of I_A) (s) (Trifunac & Brady 1975);
- Tm = sum(C_i^2 / f_i) / sum(C_i^2) over Fourier amplitudes C_i with
  0.25 Hz <= f_i <= 20 Hz (s) (Rathje, Abrahamson & Bray 1998); the motion is padded with
  zeros to at least 20 s so that the spectrum is resolved to 0.05 Hz or finer;
- Sa(T, zeta) = omega^2 max_t |u(t)|, the pseudo-spectral acceleration of a linear
  oscillator u'' + 2 zeta omega u' + omega^2 u = -a(t), omega = 2 pi / T, at rest at t = 0,
  followed through one free period after the motion ends (the peak of a damped free
  vibration is reached within half a period). Sa(0) = PGA. Reported in g.

The oscillator is integrated exactly for piecewise-linear input (the state-transition
matrix of the oscillator augmented with the input and its slope, computed with
`scipy.linalg.expm`; the same recurrence as Nigam & Jennings 1969 without their
closed-form coefficients' cancellation at small omega dt). Each sample interval is split
into equal sub-steps no longer than T/100, which is exact for linear input and bounds the
error of reading the peak at the nodes by 1 - cos(pi/100) < 0.05 %.

Scaling: multiplying a motion by a factor s multiplies PGA, PGV, PGD, CAV and Sa by s and
Arias intensity by s^2; D5-95 and Tm do not change. `scale_to` uses this.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from functools import lru_cache

import numba as nb
import numpy as np

from archquake._kernel_cache import stamp_kernels
from archquake._validate import require_finite, require_gravity, require_positive, require_range
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import InvalidParameterError
from archquake.ranges import SPECTRUM_MIN_PERIOD_S

stamp_kernels()  # the cache checks each kernel against every source compiled into it

#: Damping ratio of the response spectrum unless stated (5 % of critical).
DEFAULT_DAMPING = 0.05

#: Frequency band of the mean period Tm, Hz (Rathje et al. 1998).
MEAN_PERIOD_BAND_HZ = (0.25, 20.0)

#: Shortest record length (s) the Fourier transform of Tm sees (zero padding): 0.05 Hz bins.
_MEAN_PERIOD_MIN_LENGTH_S = 20.0

#: Longest oscillator sub-step, as a fraction of the period.
_SUBSTEPS_PER_PERIOD = 100

#: Samples of a pulse (non-record motion) over its duration, at least.
_PULSE_SAMPLES = 8192

#: The scalable intensity measures: name -> (unit, exponent of the scale factor, meaning).
_IMS: dict[str, tuple[str, int, str]] = {
    "pga": ("g", 1, "peak ground acceleration"),
    "pgv": ("m/s", 1, "peak ground velocity"),
    "pgd": ("m", 1, "peak ground displacement"),
    "arias": ("m/s", 2, "Arias intensity"),
    "cav": ("m/s", 1, "cumulative absolute velocity"),
    "sa": ("g", 1, "5 %-damped pseudo-spectral acceleration"),
}

_IM_HELP = ("pga (g), pgv (m/s), pgd (m), arias (m/s), cav (m/s) or sa:T (g; T the period in "
            "s > 0, e.g. sa:0.5)")


# -------------------------------------------------------------------------------------
# one intensity measure, by name
# -------------------------------------------------------------------------------------
@dataclass(frozen=True)
class IntensityMeasure:
    """One scalable intensity measure, e.g. PGA or Sa(0.5 s, 5 %).

    Parameters
    ----------
    name : {'pga', 'pgv', 'pgd', 'arias', 'cav', 'sa'}
    period_s : float or None
        Oscillator period T, s (> 0), for ``'sa'`` only.
    damping : float
        Oscillator damping ratio for ``'sa'`` (default 0.05).

    Examples
    --------
    >>> im = parse_im("sa:0.5")
    >>> im.label, im.unit, im.exponent
    ('sa:0.5', 'g', 1)
    >>> parse_im("Arias").exponent
    2
    """

    name: str
    period_s: float | None = None
    damping: float = DEFAULT_DAMPING

    def __post_init__(self) -> None:
        if self.name not in _IMS:
            raise InvalidParameterError(
                f"intensity measure {self.name!r} is not one of {_IM_HELP}")
        if self.name == "sa":
            if self.period_s is None:
                raise InvalidParameterError(
                    "intensity measure sa needs a period: sa:T with T in s > 0, e.g. sa:0.5")
            object.__setattr__(self, "period_s",
                               require_positive("Sa period T", self.period_s, "s"))
        elif self.period_s is not None:
            raise InvalidParameterError(
                f"intensity measure {self.name} takes no period (only sa:T does)")
        object.__setattr__(self, "damping", _damping(self.damping))

    @property
    def label(self) -> str:
        """The text `parse_im` reads back, e.g. ``'pga'`` or ``'sa:0.5'``."""
        return f"sa:{self.period_s:g}" if self.name == "sa" else self.name

    @property
    def unit(self) -> str:
        """Unit of the value: 'g', 'm/s' or 'm'."""
        return _IMS[self.name][0]

    @property
    def exponent(self) -> int:
        """Power of the scale factor: IM(s * motion) = s**exponent * IM(motion)."""
        return _IMS[self.name][1]

    @property
    def key(self) -> str:
        """JSON key with the unit, e.g. ``'pga_g'``, ``'arias_m_s'``, ``'sa_0.5s_g'``."""
        unit = {"g": "g", "m/s": "m_s", "m": "m"}[self.unit]
        return f"sa_{self.period_s:g}s_{unit}" if self.name == "sa" else f"{self.name}_{unit}"

    @property
    def description(self) -> str:
        """Words for axis labels, e.g. 'Sa(0.5 s, 5 %) (g)'."""
        if self.name == "sa":
            return f"Sa({self.period_s:g} s, {100 * self.damping:g} %) (g)"
        return f"{_IMS[self.name][2]} ({self.unit})"

    def of(self, motion, *, g: float = STANDARD_GRAVITY) -> float:
        """Value of this measure for ``motion``, in `unit`."""
        g = require_gravity(g)
        t, a = piecewise_samples(motion)
        if self.name == "pga":
            return float(np.max(np.abs(a))) / g if a.size else 0.0
        if self.name == "pgv":
            return _pgv(t, a)
        if self.name == "pgd":
            return _pgd(t, a)
        if self.name == "arias":
            return math.pi / (2.0 * g) * float(np.sum(_sq_integrals(t, a)))
        if self.name == "cav":
            return float(np.sum(_abs_integrals(t, a)))
        return float(_spectrum(t, a, np.array([self.period_s]), self.damping)[0]) / g

    def __str__(self) -> str:
        return self.label


def parse_im(text: str | IntensityMeasure) -> IntensityMeasure:
    """Read an intensity measure from text: ``pga``, ``pgv``, ``pgd``, ``arias``, ``cav``,
    ``sa:T`` (T in s).

    Case and surrounding spaces are ignored; ``sa(0.5)`` is read as ``sa:0.5``. Anything
    else raises `InvalidParameterError` with one line listing the
    choices.
    """
    if isinstance(text, IntensityMeasure):
        return text
    if not isinstance(text, str):
        raise InvalidParameterError(f"intensity measure must be text ({_IM_HELP}), got {text!r}")
    s = text.strip().lower()
    m = re.fullmatch(r"sa\s*(?::|\(|=)\s*([^)\s]+)\s*\)?(?:\s*s)?", s)
    if m:
        try:
            period = float(m.group(1))
        except ValueError:
            period = math.nan
        if not (math.isfinite(period) and period > 0):
            raise InvalidParameterError(
                f"intensity measure {text!r}: the period of sa:T must be a number of seconds "
                f"> 0, e.g. sa:0.5")
        return IntensityMeasure("sa", period)
    if s in _IMS and s != "sa":
        return IntensityMeasure(s)
    raise InvalidParameterError(f"intensity measure {text!r} is not one of {_IM_HELP}")


def im_value(motion, im: str | IntensityMeasure, g: float = STANDARD_GRAVITY) -> float:
    """Value of one intensity measure of ``motion`` in the measure's unit (see `parse_im`).

    Examples
    --------
    >>> from archquake.ground import StepImpulse
    >>> round(im_value(StepImpulse.from_g(0.4, 0.5), "pga"), 12)
    0.4
    >>> round(im_value(StepImpulse(1.0, 0.5), "pgv"), 12)  # a * t_p
    0.5
    """
    return parse_im(im).of(motion, g=g)


def scale_to(motion, im: str | IntensityMeasure, target: float, *,
             g: float = STANDARD_GRAVITY):
    """Scale ``motion`` so that its intensity measure ``im`` equals ``target``.

    Parameters
    ----------
    motion : GroundMotion
    im : str or IntensityMeasure
        e.g. ``'pga'`` or ``'sa:0.5'``.
    target : float
        Wanted value, in the measure's unit (g, m/s or m), > 0.

    Returns
    -------
    (scaled motion, factor) : tuple
        ``motion.scaled(factor)`` and the factor s = (target / IM)^(1/exponent): linear
        measures scale with s, Arias intensity with s^2.
    """
    measure = parse_im(im)
    target = require_positive(f"target {measure.label}", target, measure.unit)
    current = measure.of(motion, g=g)
    if not current > 0:
        raise InvalidParameterError(
            f"cannot scale {getattr(motion, 'name', 'the motion')!r} to {measure.label} = "
            f"{target:g} {measure.unit}: its {measure.label} is 0")
    factor = (target / current) ** (1.0 / measure.exponent)
    return motion.scaled(factor), factor


# -------------------------------------------------------------------------------------
# all of them
# -------------------------------------------------------------------------------------
@dataclass(frozen=True)
class IntensityMeasures:
    """The intensity measures of one motion (SI, units in the field names).

    ``sa_g`` maps period (s) -> Sa(T, ``damping``) in g, for the periods asked for.
    """

    pga_g: float
    pgv_m_s: float
    pgd_m: float
    arias_m_s: float
    cav_m_s: float
    d5_95_s: float
    mean_period_s: float
    sa_g: Mapping[float, float] = field(default_factory=dict)
    damping: float = DEFAULT_DAMPING
    g_m_s2: float = STANDARD_GRAVITY

    def to_dict(self) -> dict:
        """Plain dict for JSON; Sa periods as text keys, e.g. ``{'0.5': 0.31}``."""
        return {
            "pga_g": self.pga_g,
            "pga_m_s2": self.pga_g * self.g_m_s2,
            "pgv_m_s": self.pgv_m_s,
            "pgd_m": self.pgd_m,
            "arias_m_s": self.arias_m_s,
            "cav_m_s": self.cav_m_s,
            "d5_95_s": self.d5_95_s,
            "mean_period_s": self.mean_period_s,
            "sa_damping_ratio": self.damping,
            "sa_g": {f"{p:g}": v for p, v in self.sa_g.items()},
            "g_m_s2": self.g_m_s2,
        }


def intensity_measures(motion, *, periods: Iterable[float] = (),
                       damping: float = DEFAULT_DAMPING,
                       g: float = STANDARD_GRAVITY) -> IntensityMeasures:
    """Every intensity measure of ``motion`` (see the module docstring for definitions).

    Parameters
    ----------
    motion : GroundMotion
    periods : iterable of float
        Periods T (s, >= 0) at which to report Sa(T, damping); T = 0 gives the PGA.
    damping : float
        Damping ratio of the oscillators, in [0, 1).
    g : float
        m/s^2, to express PGA and Sa in g and in the Arias intensity.
    """
    g = require_gravity(g)
    damping = _damping(damping)
    periods = _periods(periods)
    t, a = piecewise_samples(motion)
    sq = _sq_integrals(t, a)
    sa = _spectrum(t, a, periods, damping) / g if periods.size else np.empty(0)
    return IntensityMeasures(
        pga_g=float(np.max(np.abs(a))) / g,
        pgv_m_s=_pgv(t, a),
        pgd_m=_pgd(t, a),
        arias_m_s=math.pi / (2.0 * g) * float(np.sum(sq)),
        cav_m_s=float(np.sum(_abs_integrals(t, a))),
        d5_95_s=_significant_duration(t, sq, 0.05, 0.95),
        mean_period_s=_mean_period(motion, t, a),
        sa_g={float(p): float(v) for p, v in zip(periods, sa)},
        damping=damping,
        g_m_s2=g,
    )


def response_spectrum(motion, periods: Iterable[float], *, damping: float = DEFAULT_DAMPING
                      ) -> np.ndarray:
    """Pseudo-spectral acceleration omega^2 max|u| (m/s^2) at each period T (s, >= 0).

    See the module docstring for the oscillator and how it is integrated.
    """
    periods = _periods(periods)
    t, a = piecewise_samples(motion)
    return _spectrum(t, a, periods, _damping(damping))


def significant_duration(motion, start: float = 0.05, end: float = 0.95) -> float:
    """Time (s) between ``start`` and ``end`` fractions of the Arias intensity (D5-95)."""
    start = require_range("start fraction", start, 0.0, 1.0)
    end = require_range("end fraction", end, 0.0, 1.0)
    if not start < end:
        raise InvalidParameterError(f"start fraction {start:g} must be < end fraction {end:g}")
    t, a = piecewise_samples(motion)
    return _significant_duration(t, _sq_integrals(t, a), start, end)


def strong_motion_end(motion, fraction: float = 0.95, g: float = STANDARD_GRAVITY) -> float:
    """Time at which the record's Arias intensity reaches ``fraction`` of its total, s (the
    squared acceleration integrated by the trapezoidal rule; the assessment cuts records there
    for the DEM check, the code check's time-history route after it)."""
    t, a = piecewise_samples(motion)
    sq = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] ** 2 + a[:-1] ** 2) * np.diff(t))])
    return float(np.interp(fraction * sq[-1], sq, t))


# -------------------------------------------------------------------------------------
# the piecewise-linear history
# -------------------------------------------------------------------------------------
def piecewise_samples(motion) -> tuple[np.ndarray, np.ndarray]:
    """(t, a): non-decreasing times (s) and accelerations (m/s^2), linear between; a repeated
    time is a jump. Records give their samples; other motions are sampled between their
    breakpoints, keeping the value just before each breakpoint as well as the one at it."""
    samples = getattr(motion, "accelerations", None)
    dt = getattr(motion, "dt", None)
    if samples is not None and dt is not None:
        a = np.asarray(samples, dtype=float)
        return float(getattr(motion, "t0", 0.0)) + dt * np.arange(a.size), a
    duration = float(motion.duration)
    if not (math.isfinite(duration) and duration > 0):
        raise InvalidParameterError(
            f"intensity measures need a motion of finite duration > 0 s, got {duration!r}")
    bps = np.asarray(motion.breakpoints(), dtype=float)
    bps = np.unique(np.concatenate([[0.0, duration], bps[(bps > 0) & (bps < duration)]]))
    h = duration / _PULSE_SAMPLES
    ts, as_ = [], []
    for lo, hi in zip(bps[:-1], bps[1:]):
        n = max(16, math.ceil((hi - lo) / h))
        tk = np.linspace(lo, hi, n + 1)
        ak = np.asarray(motion.acceleration(tk), dtype=float).copy()
        ak[-1] = float(motion.acceleration(np.nextafter(hi, -np.inf)))  # left limit at hi
        ts.append(tk)
        as_.append(ak)
    return np.concatenate(ts), np.concatenate(as_)


def _velocity(t: np.ndarray, a: np.ndarray) -> np.ndarray:
    h = np.diff(t)
    return np.concatenate([[0.0], np.cumsum(0.5 * h * (a[:-1] + a[1:]))])


def _pgv(t: np.ndarray, a: np.ndarray) -> float:
    v = _velocity(t, a)
    peak = float(np.max(np.abs(v)))
    # inside an interval where a changes sign, v has a stationary point at the crossing:
    # v = v_i + a_i tau*/2 with tau* = h a_i/(a_i - a_{i+1})
    a0, a1 = a[:-1], a[1:]
    cross = (a0 * a1 < 0) & (np.diff(t) > 0)
    if np.any(cross):
        h = np.diff(t)[cross]
        tau = h * a0[cross] / (a0[cross] - a1[cross])
        peak = max(peak, float(np.max(np.abs(v[:-1][cross] + 0.5 * a0[cross] * tau))))
    return peak


def _pgd(t: np.ndarray, a: np.ndarray) -> float:
    v = _velocity(t, a)
    h = np.diff(t)
    d = np.concatenate([[0.0], np.cumsum(v[:-1] * h + (2.0 * a[:-1] + a[1:]) * h * h / 6.0)])
    return float(np.max(np.abs(d)))


def _sq_integrals(t: np.ndarray, a: np.ndarray) -> np.ndarray:
    """int a^2 over each interval (exact for linear a), m^2/s^3."""
    a0, a1 = a[:-1], a[1:]
    return np.diff(t) * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0


def _abs_integrals(t: np.ndarray, a: np.ndarray) -> np.ndarray:
    """int |a| over each interval (exact for linear a, sign changes included), m/s."""
    a0, a1 = a[:-1], a[1:]
    h = np.diff(t)
    same = a0 * a1 >= 0
    denom = np.where(same, 1.0, np.abs(a0) + np.abs(a1))
    return np.where(same, 0.5 * h * (np.abs(a0) + np.abs(a1)),
                    0.5 * h * (a0 * a0 + a1 * a1) / denom)


def _significant_duration(t: np.ndarray, sq: np.ndarray, start: float, end: float) -> float:
    cum = np.concatenate([[0.0], np.cumsum(sq)])
    total = cum[-1]
    if not total > 0:
        return 0.0
    frac = cum / total
    # first time each fraction is reached (frac is non-decreasing; interpolate within a step)
    t_start = float(np.interp(start, frac, t)) if start > 0 else float(t[0])
    t_end = float(np.interp(end, frac, t))
    return t_end - t_start


def _mean_period(motion, t: np.ndarray, a: np.ndarray) -> float:
    dt = getattr(motion, "dt", None)
    if getattr(motion, "accelerations", None) is not None and dt is not None:
        x = a
    else:  # a pulse: a uniform grid fine enough for 20 Hz and for the pulse's shape
        dt = min(0.005, float(motion.duration) / 2048)
        grid = np.arange(0.0, float(motion.duration) + 0.5 * dt, dt)
        x = np.asarray(motion.acceleration(grid), dtype=float)
    n = max(x.size, math.ceil(_MEAN_PERIOD_MIN_LENGTH_S / dt))
    n = 1 << (n - 1).bit_length()
    c = np.abs(np.fft.rfft(x, n))
    f = np.fft.rfftfreq(n, dt)
    lo, hi = MEAN_PERIOD_BAND_HZ
    band = (f >= lo) & (f <= hi)
    peak = float(np.max(c[band], initial=0.0))
    if not peak > 0:  # no motion in the band: Tm is undefined
        return math.nan
    c2 = (c[band] / peak) ** 2  # Tm does not depend on the scale; a tiny one must not underflow
    return float(np.sum(c2 / f[band]) / np.sum(c2))


# -------------------------------------------------------------------------------------
# the oscillator
# -------------------------------------------------------------------------------------
def _damping(value: object) -> float:
    z = require_finite("damping ratio", value)
    if not 0.0 <= z < 1.0:
        raise InvalidParameterError(f"damping ratio must be in [0, 1), got {z:g}")
    return z


def _periods(periods: Iterable[float]) -> np.ndarray:
    try:
        p = np.atleast_1d(np.asarray(list(periods) if not np.isscalar(periods) else [periods],
                                     dtype=float))
    except (TypeError, ValueError):
        raise InvalidParameterError("periods must be numbers of seconds >= 0") from None
    if p.ndim != 1 or not np.all(np.isfinite(p)) or np.any(p < 0):
        raise InvalidParameterError(f"periods must be finite numbers of seconds >= 0, got {p}")
    if np.any((p > 0) & (p < SPECTRUM_MIN_PERIOD_S)):  # sub-steps of T/100: unbounded
        raise InvalidParameterError(
            f"periods must be 0 or at least {SPECTRUM_MIN_PERIOD_S:g} s, got "
            f"{float(p[(p > 0) & (p < SPECTRUM_MIN_PERIOD_S)][0]):g}")
    return p


@lru_cache(maxsize=8192)
def _transition(omega: float, zeta: float, h: float) -> np.ndarray:
    """2x4 coefficients c with [u, v](t+h) = c @ [u, v, a(t), a(t+h)](t) for input linear on
    [t, t+h], from the state-transition matrix of the augmented system
    z = [u, v, a, a'], z' = [[0,1,0,0], [-w^2,-2 zeta w,-1,0], [0,0,0,1], [0,0,0,0]] z.

    Kept for the next call with the same three numbers (read-only): the spectra of a suite's
    records at the same periods share their time steps, and each matrix exponential costs far
    more than the oscillator's run through a record."""
    from scipy.linalg import expm  # (lazy: keeps ``import archquake`` light)

    if h == 0.0:
        c = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]])
    else:
        m = np.array([[0.0, 1.0, 0.0, 0.0],
                      [-omega * omega, -2.0 * zeta * omega, -1.0, 0.0],
                      [0.0, 0.0, 0.0, 1.0],
                      [0.0, 0.0, 0.0, 0.0]])
        e = expm(m * h)[:2]
        # a' = (a1 - a0)/h: the columns of a0 and a1
        c = np.column_stack([e[:, 0], e[:, 1], e[:, 2] - e[:, 3] / h, e[:, 3] / h])
    c.setflags(write=False)
    return c


@nb.njit(cache=True, nogil=True)
def _peak_displacement(a: np.ndarray, which: np.ndarray, coefs: np.ndarray, m: int,
                       tail: np.ndarray, tail_steps: int) -> float:
    """max |u| of the oscillator at rest at t = 0: interval i is split into m sub-steps with
    coefficients coefs[which[i]]; then ``tail_steps`` free steps with coefficients ``tail``."""
    u = 0.0
    v = 0.0
    peak = 0.0
    for i in range(a.size - 1):
        c = coefs[which[i]]
        a0 = a[i]
        da = (a[i + 1] - a0) / m
        for k in range(m):
            lo = a0 + k * da
            hi = a0 + (k + 1) * da
            un = c[0, 0] * u + c[0, 1] * v + c[0, 2] * lo + c[0, 3] * hi
            v = c[1, 0] * u + c[1, 1] * v + c[1, 2] * lo + c[1, 3] * hi
            u = un
            if abs(u) > peak:
                peak = abs(u)
    for _ in range(tail_steps):
        un = tail[0, 0] * u + tail[0, 1] * v
        v = tail[1, 0] * u + tail[1, 1] * v
        u = un
        if abs(u) > peak:
            peak = abs(u)
    return peak


def _spectrum(t: np.ndarray, a: np.ndarray, periods: np.ndarray, zeta: float) -> np.ndarray:
    """Pseudo-spectral acceleration (m/s^2) at each period (s); T = 0 gives max |a|."""
    out = np.empty(periods.size)
    h_all = np.diff(t)
    # intervals of (nearly) the same length share their coefficients
    h_unique, which = np.unique(np.round(h_all, 15), return_inverse=True)
    which = which.astype(np.int64).ravel()
    h_max = float(h_unique[-1]) if h_unique.size else 0.0
    for j, period in enumerate(periods):
        if period == 0.0:
            out[j] = float(np.max(np.abs(a)))
            continue
        omega = 2.0 * math.pi / period
        m = max(1, math.ceil(h_max * _SUBSTEPS_PER_PERIOD / period))
        coefs = np.stack([_transition(omega, zeta, float(h) / m) for h in h_unique])
        h_tail = period / _SUBSTEPS_PER_PERIOD
        tail = np.array(_transition(omega, zeta, h_tail))  # (a writable copy, as the kernel takes)
        peak = _peak_displacement(a, which, coefs, m, tail, _SUBSTEPS_PER_PERIOD + 1)
        out[j] = omega * omega * peak
    return out


__all__ = [
    "DEFAULT_DAMPING",
    "IntensityMeasure",
    "IntensityMeasures",
    "im_value",
    "intensity_measures",
    "parse_im",
    "piecewise_samples",
    "response_spectrum",
    "scale_to",
    "significant_duration",
]
