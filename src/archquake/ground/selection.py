"""Choosing and scaling records so that their mean spectrum matches a target spectrum.

The codes accept a set of natural records when the mean of their 5 %-damped spectra (after
scaling) stays close to the site's elastic spectrum over the periods that matter:

- NTC 2018 §3.2.3.6: at every period of the interval, -10 % <= mean / target - 1 <= +30 %
  (`ntc_band`);
- EN 1998-1 §3.2.3.1.2: mean >= 0.9 target over [0.2 T1, 2 T1], and mean S_e(0) (the mean
  PGA) >= a_g S (`ec8_band`, with T = 0 on the grid).

The target enters only as numbers (an array on the grid, or a callable of the periods), so
this module does not depend on any code's spectrum.

Algorithm (a greedy ranking with swaps, after the approach of EzGM's EC8 selection, written
anew):

1. each candidate record gets its own scale factor, the one that best fits the target in the
   least-squares sense of log Sa over the grid, clipped to the allowed range (or factor 1 with
   ``common_scale``); its misfit is the RMS of log(scaled Sa / target);
2. a set of ``count`` records gets one more common factor c: the one that brings the mean
   closest to the target on average (in log) inside the factors that keep it in the band and
   every record's factor in range; if no factor keeps it in the band, the one that leaves it
   least; the set's violation is the largest log-distance by which the scaled mean leaves the
   band;
3. the first set is the best-ranked records, taken in order of misfit under the limits per
   event and per recording; ``restarts`` more start from random sets drawn with ``seed``; each
   is improved by swapping one record for one outside the set while that lowers (violation,
   then the mean's RMS log-deviation from the target); the best set found is returned.

Given the same spectra, target, options and seed the result is the same.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from archquake._validate import require_int, require_positive
from archquake.errors import InvalidParameterError
from archquake.ground.response_spectra import RecordSpectra
from archquake.ground.suites import Suite

#: NTC 2018 §3.2.3.6: the mean spectrum within -10 % / +30 % of the target.
NTC_BAND = (0.9, 1.3)
#: EN 1998-1 §3.2.3.1.2: the mean spectrum >= 0.9 target; mean PGA >= target PGA.
EC8_LOWER = 0.9
#: Range of each record's scale factor unless the user gives one.
DEFAULT_SCALE_RANGE = (0.5, 2.0)
#: Records in a set unless the user says (the codes ask for 7 to use the mean response).
DEFAULT_COUNT = 7
#: Records of one event and components of one recording a set may hold, unless the user says.
DEFAULT_MAX_PER_EVENT = 2
DEFAULT_MAX_PER_RECORDING = 1
#: Random starting sets besides the best-ranked one.
DEFAULT_RESTARTS = 20
_MAX_SWEEPS = 50


def ntc_band(periods_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """NTC 2018 §3.2.3.6 band as (lower, upper) ratios to the target at each period."""
    p = np.asarray(periods_s, dtype=float)
    return np.full(p.shape, NTC_BAND[0]), np.full(p.shape, NTC_BAND[1])


def ec8_band(periods_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """EN 1998-1 §3.2.3.1.2 as (lower, upper) ratios: 0.9 (1.0 at T = 0, the mean PGA), no upper
    bound. Put T = 0 on the grid to check the PGA condition."""
    p = np.asarray(periods_s, dtype=float)
    lower = np.where(p == 0.0, 1.0, EC8_LOWER)
    return lower, np.full(p.shape, np.inf)


@dataclass(frozen=True)
class Selection:
    """A chosen set of records, their scale factors and how the mean meets the band.

    Parameters
    ----------
    spectra : RecordSpectra
        The chosen records' spectra, already scaled (row i times ``scale_factors[i]``).
    indices : tuple of int
        Positions of the chosen records among the candidates.
    scale_factors : numpy.ndarray
        Factor on each chosen record.
    target : numpy.ndarray
        Target spectrum on the grid, m/s^2.
    lower, upper : numpy.ndarray
        Band as ratios to the target.
    compatible : bool
        Whether the scaled mean lies in the band at every period.
    violation : float
        Largest log-distance of mean/target outside the band (0 when compatible).
    excluded : dict
        Candidates left out before the search, name -> reason.
    """

    spectra: RecordSpectra
    indices: tuple[int, ...]
    scale_factors: np.ndarray
    target: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    compatible: bool
    violation: float
    excluded: dict = field(default_factory=dict, compare=False, hash=False)

    @property
    def periods_s(self) -> np.ndarray:
        return self.spectra.periods_s

    @property
    def mean(self) -> np.ndarray:
        """Mean of the scaled spectra, m/s^2."""
        return self.spectra.mean

    @property
    def ratio(self) -> np.ndarray:
        """mean / target at each period."""
        return self.mean / self.target

    def failures(self) -> list[tuple[float, float, float, float]]:
        """(period s, mean/target, lower, upper) at each period outside the band."""
        r = self.ratio
        bad = (r < self.lower * (1 - 1e-12)) | (r > self.upper * (1 + 1e-12))
        return [(float(t), float(x), float(lo), float(hi)) for t, x, lo, hi in
                zip(self.periods_s[bad], r[bad], self.lower[bad], self.upper[bad])]

    def describe_failure(self) -> str:
        """One line: where the best set leaves the band and by how much ('' if it does not)."""
        fails = self.failures()
        if not fails:
            return ""
        low = [f for f in fails if f[1] < f[2]]
        high = [f for f in fails if f[1] >= f[2]]
        parts = []
        if low:
            worst = min(low, key=lambda f: f[1] / f[2])
            parts.append(f"below the band at T = {_span(low)} s (worst {worst[1]:.2f} x target "
                         f"at {worst[0]:g} s, lower bound {worst[2]:.2f})")
        if high:
            worst = max(high, key=lambda f: f[1] / f[3])
            where = "above it" if low else "above the band"
            parts.append(f"{where} at T = {_span(high)} s (worst {worst[1]:.2f} x target at "
                         f"{worst[0]:g} s, upper bound {worst[3]:.2f})")
        return (f"no set of {len(self.indices)} records meets the band: the best mean is "
                + "; ".join(parts))

    def to_dict(self) -> dict:
        """Plain values (units in the keys) for JSON."""
        g = self.spectra.g
        rec = self.spectra.to_dict()["records"]
        for row, f, i in zip(rec, self.scale_factors, self.indices):
            row["scale_factor"] = float(f)
            row["candidate_index"] = int(i)
        return {
            "compatible": self.compatible,
            "violation_log": self.violation,
            "periods_s": self.periods_s,
            "target_sa_g": self.target / g,
            "mean_sa_g": self.mean / g,
            "ratio": self.ratio,
            "lower_ratio": self.lower,
            "upper_ratio": np.where(np.isfinite(self.upper), self.upper, np.nan),
            "records": rec,
            "excluded": dict(self.excluded),
            "damping_ratio": self.spectra.damping,
            "g_m_s2": g,
        }


def selected_suite(suite: Suite, selection: Selection) -> Suite:
    """The chosen records of ``suite`` (the candidates ``selection`` was made from, in the same
    order), each multiplied by its scale factor, as a suite for a time-history analysis.

    Raises
    ------
    archquake.errors.InvalidParameterError
        ``suite`` is not the one the selection was made from (names differ).
    """
    records = []
    for i, factor, name in zip(selection.indices, selection.scale_factors,
                               selection.spectra.names):
        if i >= len(suite) or suite[i].name != name:
            raise InvalidParameterError(
                f"the selection was not made from suite {suite.name!r}: record {name!r} is not "
                f"its record {i}")
        records.append(suite[i].scaled(float(factor)))
    return Suite(f"{suite.name}-selected", tuple(records),
                 f"{len(records)} records of {suite.name} scaled to a target spectrum",
                 suite.source, {**suite.metadata, "selected_from": suite.name})


def select_records(
    spectra: RecordSpectra,
    target: np.ndarray | Callable[[np.ndarray], np.ndarray],
    *,
    band: tuple[np.ndarray, np.ndarray] | Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
    = ntc_band,
    count: int = DEFAULT_COUNT,
    scale_range: tuple[float, float] = DEFAULT_SCALE_RANGE,
    max_per_event: int | None = DEFAULT_MAX_PER_EVENT,
    max_per_recording: int | None = DEFAULT_MAX_PER_RECORDING,
    common_scale: bool = False,
    seed: int = 0,
    restarts: int = DEFAULT_RESTARTS,
) -> Selection:
    """Choose ``count`` records of ``spectra`` and their scale factors to meet a band.

    Parameters
    ----------
    spectra : RecordSpectra
        The candidates' spectra (unscaled) on the period grid of the check.
    target : array_like, shape (m,), or callable
        Target spectrum on the grid, m/s^2, or a function of the periods (s) giving it.
    band : (lower, upper) or callable
        Ratios to the target the mean must stay within, each shape (m,) (upper may be inf), or
        a function of the periods giving them: `ntc_band` (default) or `ec8_band`.
    count : int
        Records in the set (>= 1; the codes ask for 7 to use the mean response).
    scale_range : (float, float)
        Allowed range of each record's scale factor (0 < low <= 1 <= high).
    max_per_event, max_per_recording : int or None
        Most records from one event, and components of one recording, in the set (None: no
        limit).
    common_scale : bool
        One factor for every record (keeps the records' relative spread) instead of one each.
    seed : int
        Seed of the random starting sets.
    restarts : int
        Random starting sets besides the best-ranked one (>= 0).

    Returns
    -------
    Selection
        The best set found; ``compatible`` is False (and `Selection.describe_failure`
        says where and by how much) when none of the sets tried meets the band.

    Raises
    ------
    archquake.errors.InvalidParameterError
        Fewer usable candidates than ``count`` (one line saying why), a bad option.
    """
    periods = spectra.periods_s
    tgt = np.asarray(target(periods) if callable(target) else target, dtype=float)
    if tgt.shape != periods.shape or not np.all(np.isfinite(tgt)) or np.any(tgt <= 0):
        raise InvalidParameterError(
            f"target must be {periods.size} positive finite values (one per period)")
    lower, upper = band(periods) if callable(band) else band
    lower = np.broadcast_to(np.asarray(lower, dtype=float), periods.shape).copy()
    upper = np.broadcast_to(np.asarray(upper, dtype=float), periods.shape).copy()
    if np.any(lower <= 0) or np.any(upper < lower):
        raise InvalidParameterError("band must satisfy 0 < lower <= upper at every period")
    count = require_int("count", count, 1)
    restarts = require_int("restarts", restarts, 0)
    seed = require_int("seed", seed, 0)
    lo_sf, hi_sf = (require_positive("scale_range low", scale_range[0]),
                    require_positive("scale_range high", scale_range[1]))
    if not lo_sf <= 1.0 <= hi_sf:
        raise InvalidParameterError(
            f"scale_range must satisfy 0 < low <= 1 <= high, got ({lo_sf:g}, {hi_sf:g})")
    for name, value in (("max_per_event", max_per_event), ("max_per_recording", max_per_recording)):
        if value is not None:
            require_int(name, value, 1)

    # candidates: usable over the whole grid and with a spectrum above zero everywhere
    excluded: dict[str, str] = {}
    usable = []
    for i, name in enumerate(spectra.names):
        if spectra.usable_period_s[i] < periods.max():
            excluded[name] = (f"usable only up to {spectra.usable_period_s[i]:.3g} s (lowest "
                              f"usable frequency)")
        elif np.any(spectra.sa[i] <= 0):
            excluded[name] = "zero spectral ordinate on the grid"
        else:
            usable.append(i)
    if len(usable) < count:
        raise InvalidParameterError(
            f"only {len(usable)} of {len(spectra)} records are usable over "
            f"{periods.min():g}-{periods.max():g} s, fewer than count = {count}"
            + (f" ({len(excluded)} usable only at shorter periods)" if excluded else ""))

    log_t = np.log(tgt)
    log_sa = np.log(spectra.sa)
    if common_scale:
        own = np.ones(len(spectra))
    else:
        own = np.exp(np.clip(np.mean(log_t - log_sa, axis=1), math.log(lo_sf), math.log(hi_sf)))
    misfit = np.sqrt(np.mean((log_sa + np.log(own)[:, None] - log_t) ** 2, axis=1))
    search = _Search(spectra, tgt, lower, upper, own, (lo_sf, hi_sf), count, usable,
                     max_per_event, max_per_recording)

    ranked = sorted(usable, key=lambda i: (misfit[i], i))
    first = search.greedy(ranked)
    if first is None:
        raise InvalidParameterError(
            f"no {count} records satisfy the limits of {max_per_event} per event and "
            f"{max_per_recording} per recording: lower --count or raise the limits")
    best = search.improve(first)
    rng = np.random.default_rng(seed)
    for _ in range(restarts):
        start = search.greedy([int(i) for i in rng.permutation(usable)])
        if start is None:
            continue
        found = search.improve(start)
        if found[0] < best[0]:
            best = found
    (violation, _), chosen, factor = best[0], best[1], best[2]
    factors = own[list(chosen)] * factor
    picked = spectra.subset(chosen, factors)
    mean_ratio = picked.mean / tgt
    compatible = bool(np.all(mean_ratio >= lower * (1 - 1e-12))
                      and np.all(mean_ratio <= upper * (1 + 1e-12)))
    return Selection(picked, tuple(int(i) for i in chosen), factors, tgt, lower, upper,
                     compatible, float(violation), excluded)


class _Search:
    """The set evaluation and the swap search of `select_records` (no state beyond the
    problem's data)."""

    def __init__(self, spectra: RecordSpectra, target, lower, upper, own, sf_range, count,
                 usable, max_per_event, max_per_recording):
        self.scaled = spectra.sa * own[:, None] / target  # each record's ratio to the target
        self.log_lower, self.log_upper = np.log(lower), np.log(upper)
        self.log_own = np.log(own)
        self.log_sf = (math.log(sf_range[0]), math.log(sf_range[1]))
        self.count = count
        self.events = spectra.events
        self.recordings = spectra.recordings
        self.max_event = max_per_event
        self.max_recording = max_per_recording
        self.usable = list(usable)

    def allowed(self, chosen: Sequence[int]) -> bool:
        if self.max_event is not None:
            ev = Counter(self.events[i] for i in chosen if self.events[i] is not None)
            if ev and max(ev.values()) > self.max_event:
                return False
        if self.max_recording is not None:
            rc = Counter(self.recordings[i] for i in chosen)
            if max(rc.values()) > self.max_recording:
                return False
        return True

    def greedy(self, order: Sequence[int]) -> list[int] | None:
        chosen: list[int] = []
        for i in order:
            if self.allowed([*chosen, i]):
                chosen.append(i)
                if len(chosen) == self.count:
                    return chosen
        return None

    def score(self, chosen: Sequence[int]) -> tuple[tuple[float, float], float]:
        """((violation, RMS log deviation of the mean), the common factor) of a set."""
        idx = list(chosen)
        log_r = np.log(self.scaled[idx].mean(axis=0))
        need_low = float(np.max(self.log_lower - log_r))      # log c >= need_low
        need_high = float(np.min(self.log_upper - log_r))     # log c <= need_high
        own = self.log_own[idx]
        c_low, c_high = self.log_sf[0] - own.min(), self.log_sf[1] - own.max()
        if need_low <= need_high:
            log_c = float(np.clip(-np.mean(log_r), need_low, need_high))
        else:                                                  # the minimax point
            log_c = 0.5 * (need_low + need_high)
        log_c = min(max(log_c, c_low), c_high)
        violation = max(need_low - log_c, log_c - need_high, 0.0)
        deviation = float(np.sqrt(np.mean((log_r + log_c) ** 2)))
        return (violation, deviation), math.exp(log_c)

    def improve(self, chosen: list[int]):
        best_score, best_c = self.score(chosen)
        current = list(chosen)
        for _ in range(_MAX_SWEEPS):
            improved = False
            for pos in range(len(current)):
                for cand in self.usable:
                    if cand in current:
                        continue
                    trial = current.copy()
                    trial[pos] = cand
                    if not self.allowed(trial):
                        continue
                    s, c = self.score(trial)
                    if s < best_score:
                        best_score, best_c, current, improved = s, c, trial, True
            if not improved:
                break
        return best_score, tuple(current), best_c


def _span(fails: list[tuple[float, float, float, float]]) -> str:
    periods = [f[0] for f in fails]
    return f"{min(periods):g}" if len(periods) == 1 else f"{min(periods):g}-{max(periods):g}"


__all__ = [
    "DEFAULT_COUNT",
    "DEFAULT_MAX_PER_EVENT",
    "DEFAULT_MAX_PER_RECORDING",
    "DEFAULT_RESTARTS",
    "DEFAULT_SCALE_RANGE",
    "EC8_LOWER",
    "NTC_BAND",
    "Selection",
    "ec8_band",
    "ntc_band",
    "select_records",
    "selected_suite",
]
