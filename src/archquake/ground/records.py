"""Recorded accelerograms: the `Record` motion and the PEER ``.AT2`` and CSV readers.

A record is a uniformly sampled ground acceleration x_g'' (m/s^2, positive towards +x, the
sign the file gives it) starting at t = 0. Between samples it is linear, outside it is zero,
exactly as the compiled evaluator (`archquake.ground._kernel.ground_acceleration`,
kind ``KIND_SAMPLED``) computes it.

Readers convert to SI at the edge: ``.AT2`` files are in g by definition of the format; CSV
files have no standard unit, so `read_csv` requires ``units`` ("g", "m/s2" or "cm/s2",
also written "gal"); a one-column file also needs its time step ``dt``. A file
that cannot be read raises `GroundMotionFormatError` with one line
naming the file, the line, what is wrong and how to fix it.
"""

from __future__ import annotations

import math
import re
import stat
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from archquake._validate import (
    require_finite,
    require_gravity,
    require_path,
    require_positive,
    require_range,
)
from archquake.constants import STANDARD_GRAVITY
from archquake.errors import GroundMotionFormatError, InvalidParameterError
from archquake.ground.base import KIND_SAMPLED
from archquake.ranges import RECORD_DT_RANGE_S, RECORD_DURATION_MAX_S, RECORD_FILE_MAX_BYTES

#: Largest allowed deviation of a CSV sample time from the uniform grid, as a fraction of dt.
SPACING_TOLERANCE = 1e-6

#: Units a CSV acceleration column may be in, and their factor to m/s^2 (None: times g).
_UNITS = {"g": None, "m/s2": 1.0, "m/s^2": 1.0, "cm/s2": 0.01, "cm/s^2": 0.01, "gal": 0.01}

#: The unit names as users write them (``_UNITS`` also takes the ``^2`` spellings).
UNITS = ("g", "m/s2", "cm/s2", "gal")

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?"
_WEST2 = re.compile(rf"NPTS\s*=\s*(?P<npts>{_NUMBER})\s*,?\s*DT\s*=\s*(?P<dt>{_NUMBER})", re.I)
_OLD = re.compile(
    rf"^\s*(?P<a>{_NUMBER})\s*,?\s*(?P<b>{_NUMBER})\s*,?\s*(?P<labels>NPTS\s*,?\s*DT|DT\s*,?\s*NPTS)\b",
    re.I,
)
_NO_HEADER = ("the file starts with numbers, but a PEER .AT2 file has four header lines (the "
              "fourth gives NPTS and DT); add them, or save it as a two-column CSV")
_UNITS_OF = re.compile(r"UNITS\s+OF\s+(?P<unit>[A-Z/0-9*^.\-]+)", re.I)


@dataclass(frozen=True, eq=False)
class Record:
    """A recorded ground acceleration, uniformly sampled from t = 0.

    Parameters
    ----------
    accelerations : array_like, shape (n,)
        x_g'' at t = 0, dt, ..., (n-1) dt, m/s^2, positive towards +x; n >= 2, all finite.
        Stored as a read-only float64 copy.
    dt : float
        Sampling interval, s (> 0).
    name : str
        Label used in outputs (the readers use the file name without its extension).
    source : str or None
        File the record was read from (provenance only; not compared by ``==``).
    scale : float
        Factor already applied to the file's values, mirror included (provenance only; not
        compared by ``==``).
    component : str or None
        Which horizontal component of an earthquake recording this is (e.g. ``'a'``/``'b'``
        in the FEMA P695 sets, or the PEER file's azimuth); provenance only.
    metadata : dict
        Facts about the recording that travel with it (event, station, magnitude, the
        database's published PGA/PGV, ...; keys carry units); provenance only, not compared
        by ``==``.

    Notes
    -----
    ``==`` compares the motion and its name: two records are equal when they have the same
    name, dt and (bit-identical) accelerations, wherever they were read from.

    Examples
    --------
    >>> r = Record([0.0, 1.0, -2.0], 0.5, name="toy")
    >>> float(r.duration), float(r.peak)
    (1.0, 2.0)
    >>> [float(x) for x in r.acceleration([0.25, 0.75, 1.0, 1.01])]
    [0.5, -0.5, -2.0, 0.0]
    """

    accelerations: np.ndarray
    dt: float
    name: str = "record"
    source: str | None = None
    scale: float = 1.0
    component: str | None = None
    metadata: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        try:
            raw = np.asarray(self.accelerations)
            if np.iscomplexobj(raw):  # a float conversion would drop the imaginary part
                raise TypeError
            acc = np.array(raw, dtype=float)
        except (TypeError, ValueError, OverflowError):
            raise InvalidParameterError(
                "accelerations must be a 1-D sequence of real numbers (m/s^2)"
            ) from None
        if acc.ndim != 1 or acc.size < 2:
            raise InvalidParameterError(
                f"accelerations must be a 1-D sequence of at least 2 samples, got shape {acc.shape}"
            )
        bad = np.flatnonzero(~np.isfinite(acc))
        if bad.size:
            raise InvalidParameterError(
                f"accelerations must be finite (m/s^2); sample {int(bad[0])} is {acc[bad[0]]}"
            )
        acc.setflags(write=False)
        object.__setattr__(self, "accelerations", acc)
        # at most a file's largest time step; the least one a run can resolve depends on the
        # arch (simulate's check_time_resolution), finer sampled pulses are built internally
        object.__setattr__(self, "dt", require_range("record time step dt", self.dt, 0.0,
                                                     RECORD_DT_RANGE_S[1], "s",
                                                     high_open=False))
        if self.duration > RECORD_DURATION_MAX_S:
            raise InvalidParameterError(
                f"a record may last at most {RECORD_DURATION_MAX_S:g} s, this one lasts "
                f"{self.duration:g} s ({acc.size} samples at dt = {self.dt:g} s)")
        object.__setattr__(self, "scale", require_finite("record scale", self.scale))
        if not isinstance(self.name, str):
            raise InvalidParameterError(f"record name must be a string, got {self.name!r}")
        object.__setattr__(self, "metadata", dict(self.metadata or {}))

    # -- value semantics ---------------------------------------------------------------
    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Record):
            return NotImplemented
        return (
            self.name == other.name
            and self.dt == other.dt
            and np.array_equal(self.accelerations, other.accelerations)
        )

    def __hash__(self) -> int:
        return hash((self.name, self.dt, self.accelerations.tobytes()))

    def __repr__(self) -> str:
        return (
            f"Record(name={self.name!r}, points={self.points}, dt={self.dt:g} s, "
            f"duration={self.duration:g} s, peak={self.peak:.6g} m/s^2)"
        )

    # -- description -------------------------------------------------------------------
    @property
    def t0(self) -> float:
        """Time of the first sample, s: always 0 (readers shift the file's first time to 0)."""
        return 0.0

    @property
    def points(self) -> int:
        """Number of samples n."""
        return int(self.accelerations.size)

    @property
    def times(self) -> np.ndarray:
        """Sample times, s, shape (n,)."""
        return self.t0 + self.dt * np.arange(self.points)

    @property
    def duration(self) -> float:
        """Time of the last sample, (n-1) dt, s; the acceleration is zero afterwards."""
        return self.dt * (self.points - 1)

    @property
    def peak(self) -> float:
        """Peak ground acceleration max |x_g''|, m/s^2."""
        return float(np.max(np.abs(self.accelerations)))

    @property
    def time_of_peak(self) -> float:
        """Time of the first sample where |x_g''| reaches its peak, s."""
        return self.dt * int(np.argmax(np.abs(self.accelerations)))

    # -- the GroundMotion protocol -----------------------------------------------------
    def acceleration(self, t: np.ndarray | float) -> np.ndarray:
        """x_g''(t), m/s^2: linear between samples, 0 before t = 0 and after ``duration``.

        Same arithmetic as the compiled kernel (``KIND_SAMPLED``), so the two agree to
        rounding.
        """
        t = np.asarray(t, dtype=float)
        x = self.accelerations
        n = x.size
        # zero outside [t0, t0 + (n-1) dt], decided on t (not on s, whose rounding could
        # drop the last sample at t = duration)
        inside = (t >= self.t0) & (t <= self.t0 + self.dt * (n - 1))
        s_in = np.where(inside, (t - self.t0) / self.dt, 0.0)
        i = np.minimum(np.floor(s_in).astype(np.intp), n - 2)
        f = s_in - i
        value = (1.0 - f) * x[i] + f * x[i + 1]
        # the kernel returns the last sample itself at s >= n-1 (no extrapolation)
        value = np.where(s_in >= n - 1, x[n - 1], value)
        return np.where(inside, value, 0.0)

    def breakpoints(self) -> np.ndarray:
        """Every sample time, s, shape (n,): the slope of x_g'' jumps at each."""
        return self.times

    def kernel_spec(self) -> tuple[int, np.ndarray]:
        """``(KIND_SAMPLED, [t0, dt, x_0, ..., x_{n-1}])`` for the compiled evaluator."""
        params = np.empty(self.points + 2)
        params[0] = self.t0
        params[1] = self.dt
        params[2:] = self.accelerations
        return KIND_SAMPLED, params

    def mirrored(self) -> Record:
        """The same record towards the other side (every acceleration times -1)."""
        return replace(self, accelerations=-self.accelerations, scale=-self.scale)

    def scaled(self, factor: float) -> Record:
        """The record with every acceleration multiplied by ``factor`` (dimensionless)."""
        f = require_finite("scale factor", factor)
        return replace(self, accelerations=f * self.accelerations, scale=f * self.scale)

    def truncated(self, end: float) -> Record:
        """The record's samples at t <= ``end`` (s, at least the first two); the acceleration
        is zero after the last one kept. An ``end`` at or past ``duration`` keeps them all.

        Examples
        --------
        >>> r = Record([0.0, 1.0, -2.0, 0.5], 0.5, name="toy")
        >>> float(r.truncated(1.2).duration), float(r.truncated(9.0).duration)
        (1.0, 1.5)
        """
        end = require_finite("end", end)
        keep = max(2, min(self.points, int(math.floor(end / self.dt + 1e-9)) + 1))
        if keep == self.points:
            return self
        return replace(self, accelerations=self.accelerations[:keep],
                       metadata={**self.metadata, "truncated_at_s": self.dt * (keep - 1)})

    def to_dict(self, *, g: float = STANDARD_GRAVITY) -> dict:
        """Summary for JSON (the samples themselves are not included)."""
        return {
            "type": "record",
            "name": self.name,
            "source": self.source,
            "points": self.points,
            "dt_s": self.dt,
            "duration_s": self.duration,
            "pga_m_s2": self.peak,
            "pga_g": self.peak / g,
            "time_of_pga_s": self.time_of_peak,
            "scale": self.scale,
            "component": self.component,
            "metadata": dict(self.metadata),
        }


# -------------------------------------------------------------------------------------
# readers
# -------------------------------------------------------------------------------------
def read_at2(path: str | Path, *, scale: float = 1.0, g: float = STANDARD_GRAVITY) -> Record:
    """Read a PEER NGA ``.AT2`` accelerogram (values in g) into a `Record` (m/s^2).

    The format: four header lines (database, event/station/component, a units line such as
    ``ACCELERATION TIME SERIES IN UNITS OF G``, and NPTS/DT), then the NPTS values, usually
    five per line. Both fourth-line styles are accepted::

        NPTS=  4000, DT=   .0100 SEC          (NGA-West2)
          3930   0.00500   NPTS, DT           (older NGA)

    Values may be separated by spaces or commas (a trailing comma is fine), the last line may
    be short, and the count must equal NPTS.

    Parameters
    ----------
    path : str or Path
        The file.
    scale : float
        Dimensionless factor applied to every value (e.g. 2.0 doubles the record).
    g : float
        Gravity used to convert g to m/s^2 (default: standard gravity).

    Returns
    -------
    Record
        Named after the file (without extension); ``source`` is the path.

    Raises
    ------
    GroundMotionFormatError
        Missing, empty or malformed file (one line: file, line, problem, fix).
    """
    path = require_path("path", path)
    factor = _factor(scale, g)
    lines = _read_lines(path)
    if len(lines) < 4:
        if lines and _numbers(lines[0]) is not None:
            raise _err(path, 1, _NO_HEADER)
        raise _err(path, None, f"has {len(lines)} line(s), but a PEER .AT2 file has four header "
                   "lines (the fourth gives NPTS and DT) followed by the values")
    if _numbers(lines[0]) is not None:
        raise _err(path, 1, _NO_HEADER)
    _check_at2_units(path, lines[2])
    npts, dt = _parse_npts_dt(path, lines[3])
    values: list[float] = []
    for number, text in enumerate(lines[4:], start=5):
        tokens = [tok for tok in re.split(r"[,\s]+", text.strip()) if tok]
        for tok in tokens:
            v = _to_float(tok)
            if v is None:
                raise _err(path, number, f"{tok!r} is not a number; the values after the header "
                           "must be numbers in g (e.g. 1.2345670E-02)")
            if not math.isfinite(v):
                raise _err(path, number, f"value {tok!r} is not finite; replace it by a number "
                           "(0 if the sample is missing)")
            values.append(v)
    if len(values) != npts:
        where = "is truncated" if len(values) < npts else "has extra values"
        raise _err(path, 4, f"the header says NPTS = {npts} but the file holds {len(values)} "
                   f"values; the file {where} or NPTS is wrong (fix NPTS or restore the values)")
    if npts < 2:
        raise _err(path, 4, f"NPTS = {npts}: a record needs at least 2 samples")
    return Record(np.asarray(values) * factor, dt, name=path.stem, source=str(path), scale=scale)


def read_csv(path: str | Path, *, units: str, dt: float | None = None, scale: float = 1.0,
             g: float = STANDARD_GRAVITY) -> Record:
    """Read a two-column (time s, acceleration) text file into a `Record` (m/s^2).

    With ``dt`` given, the file is one column of accelerations sampled every ``dt`` seconds
    from t = 0 instead (same rules for separators, comments and one header row; exactly one
    value per row).

    Rules:

    - columns separated by a comma or by white space; a trailing comma is fine;
    - lines starting with ``#`` and blank lines are skipped; one non-numeric header row (e.g.
      ``time,acc``) is allowed before the data; a UTF-8 byte-order mark is ignored;
    - times must increase evenly (each within ``SPACING_TOLERANCE`` x dt of the uniform grid
      from the first to the last time); the first time becomes t = 0 (a file starting at
      5.0 s is shifted by -5.0 s: the analysis starts with the first sample);
    - dt is (t_last - t_first)/(n - 1), written as the shortest decimal within 1e-9 dt (so a
      column 0, 0.02, ..., 19.98 gives dt = 0.02 exactly, as an .AT2 header would).

    Parameters
    ----------
    path : str or Path
        The file.
    units : {"g", "m/s2", "cm/s2", "gal"}
        Units of the acceleration column; required (there is no safe default). ``gal`` is
        cm/s^2.
    dt : float or None
        Time step (s, > 0) of a one-column file; None (default) for a two-column file.
    scale : float
        Dimensionless factor applied to every value.
    g : float
        Gravity used when ``units="g"`` (default: standard gravity).

    Raises
    ------
    InvalidParameterError
        ``units`` missing or unknown.
    GroundMotionFormatError
        Missing, empty or malformed file (one line: file, line, problem, fix).
    """
    path = require_path("path", path)
    factor = _csv_factor(units, scale, g)
    if dt is not None:
        dt = require_positive("time step dt", dt, "s")
    lines = _read_lines(path)
    columns = 2 if dt is None else 1
    what = "time (s), acceleration" if dt is None else "acceleration (one value per row)"
    times: list[float] = []
    accs: list[float] = []
    line_of: list[int] = []
    header_seen = False
    for number, raw in enumerate(lines, start=1):
        text = raw.strip()
        if not text or text.startswith("#"):
            continue
        if "," in text:
            cells = [c.strip() for c in text.split(",")]
            while cells and cells[-1] == "":
                cells.pop()
        else:
            cells = text.split()
        parsed = [_to_float(c) for c in cells]
        if any(p is None for p in parsed):
            if not times and not header_seen:
                header_seen = True  # a column-name row such as "time,acc"
                continue
            bad = cells[[p is None for p in parsed].index(True)]
            raise _err(path, number, f"{bad!r} is not a number; after the header every row must "
                       f"be {'two numbers: ' if columns == 2 else ''}{what}")
        if len(parsed) != columns:
            if columns == 2 and len(parsed) == 1:
                raise _err(path, number, "expected 2 columns (time s, acceleration), found 1; "
                           "for a one-column file give its time step (dt=..., --dt S)")
            if columns == 1:
                raise _err(path, number, f"expected 1 column (acceleration, dt = {dt:g} s), found "
                           f"{len(parsed)}; a file with a time column is read without dt")
            raise _err(path, number, f"expected 2 columns (time s, acceleration), found "
                       f"{len(parsed)}; keep only the time and acceleration columns")
        if columns == 1:
            assert dt is not None  # one column exactly when dt is given
            parsed = [dt * len(times), parsed[0]]
        ti, a = parsed
        assert ti is not None and a is not None  # a row with a non-number raised above
        if not (math.isfinite(ti) and math.isfinite(a)):
            raise _err(path, number, f"{text!r} holds a value that is not finite; replace it "
                       "by a number")
        times.append(ti)
        accs.append(a)
        line_of.append(number)
    if len(times) < 2:
        raise _err(path, None, f"has {len(times)} data row(s); a record needs at least 2 rows "
                   f"of {what}")
    if columns == 1:
        assert dt is not None
        return Record(np.asarray(accs) * factor, dt, name=path.stem, source=str(path),
                      scale=scale)
    t = np.asarray(times)
    steps = np.diff(t)
    back = np.flatnonzero(steps <= 0)
    if back.size:
        k = int(back[0]) + 1
        raise _err(path, line_of[k], f"time {times[k]:.10g} s does not increase from "
                   f"{times[k - 1]:.10g} s on the row before (dt must be > 0); sort the rows by "
                   "time and remove duplicates")
    typical = float(np.sort(steps)[(steps.size - 1) // 2])  # lower median: an actual step
    tol = SPACING_TOLERANCE * typical
    off = np.flatnonzero(np.abs(steps - typical) > tol)  # a local jump names the culprit row
    if off.size:
        k = int(off[0]) + 1
        raise _err(path, line_of[k], f"time {times[k]:.10g} s is {steps[k - 1]:.10g} s after the "
                   f"row before, but the time step is {typical:.10g} s elsewhere; resample the "
                   "record to a constant time step")
    dt = float((t[-1] - t[0]) / (t.size - 1))
    drift = np.flatnonzero(np.abs(t - (t[0] + dt * np.arange(t.size))) > SPACING_TOLERANCE * dt)
    if drift.size:
        k = int(drift[0])
        raise _err(path, line_of[k], f"time {times[k]:.10g} s drifts off the even grid of "
                   f"dt = {dt:.10g} s; resample the record to a constant time step")
    return Record(np.asarray(accs) * factor, _tidy_dt(dt), name=path.stem, source=str(path),
                  scale=scale)


def read_record(path: str | Path, *, units: str | None = None, dt: float | None = None,
                scale: float = 1.0, g: float = STANDARD_GRAVITY) -> Record:
    """Read an accelerogram, choosing the reader by extension.

    ``.at2`` (any case) -> `read_at2` (values in g; ``units`` may be omitted or "g");
    ``.csv`` / ``.txt`` -> `read_csv` (``units`` required; ``dt`` for a one-column
    file).
    """
    path = require_path("path", path)
    ext = path.suffix.lower()
    if ext == ".at2" and dt is not None:
        raise InvalidParameterError(
            f"dt does not apply to {path.name}: a PEER .AT2 file states its own DT; leave dt unset")
    if ext == ".at2":
        if units is not None and _unit_key(units) != "g":
            raise InvalidParameterError(
                f"units={units!r} does not apply to {path.name}: PEER .AT2 files are in g by "
                "definition; leave units unset (or 'g')"
            )
        return read_at2(path, scale=scale, g=g)
    if ext in (".vt2", ".dt2"):
        kind = "velocity" if ext == ".vt2" else "displacement"
        raise _err(path, None, f"is a PEER {kind} file ({ext}); archquake needs the "
                   "acceleration file (.AT2) of the same record")
    if ext in (".csv", ".txt"):
        if units is None:
            raise InvalidParameterError(
                f"units of {path.name} must be given: 'g', 'm/s2' or 'cm/s2' (a CSV file does "
                "not say)"
            )
        return read_csv(path, units=units, dt=dt, scale=scale, g=g)
    raise _err(path, None, f"unknown extension {ext or '(none)'!r}; use .AT2 (PEER, in g) or "
               ".csv/.txt (two columns: time s, acceleration)")


# -------------------------------------------------------------------------------------
# processing
# -------------------------------------------------------------------------------------
def baseline_corrected(record: Record, *, order: int = 1) -> Record:
    """The record with a polynomial baseline removed so that its velocity has no drift.

    The ground velocity v(t) = int_0^t a (exact for the linear interpolant) is fitted by
    least squares with a polynomial q(t) = c_1 t + ... + c_{k} t^k of degree k = order + 1
    through q(0) = 0 (the ground starts at rest), and q'(t) is subtracted from the
    acceleration: order 0 removes a constant, order 1 (default) a linear trend, order 2 a
    quadratic one (the quadratic velocity fit of Boore & Bommer 2005, Soil Dyn. Earthq. Eng.
    25, section 4.3, is order 1). A polynomial baseline of degree <= ``order`` added to any
    record is removed exactly up to the fit of the record's own velocity.

    Parameters
    ----------
    record : Record
    order : int
        Degree of the polynomial removed from the acceleration, 0 to 5.

    Returns
    -------
    Record
        Same dt, name, provenance; ``metadata['baseline_order']`` says what was done.
    """
    from archquake._validate import require_int

    order = require_int("baseline order", order, 0, 5)
    t = record.times
    a = record.accelerations
    v = np.concatenate([[0.0], np.cumsum(0.5 * record.dt * (a[:-1] + a[1:]))])
    scale_t = max(record.duration, record.dt)
    s = t / scale_t  # well-conditioned basis on [0, 1]
    powers = np.arange(1, order + 2)
    basis = s[:, None] ** powers[None, :]
    coef, *_ = np.linalg.lstsq(basis, v, rcond=None)
    # q(t) = sum c_k (t/L)^k  ->  q'(t) = sum k c_k (t/L)^(k-1) / L
    dq = (powers[None, :] * s[:, None] ** (powers[None, :] - 1)) @ coef / scale_t
    meta = dict(record.metadata, baseline_order=order)
    return replace(record, accelerations=a - dq, metadata=meta)


def resampled(record: Record, dt: float, *, method: str = "polyphase") -> Record:
    """The record sampled every ``dt`` seconds from t = 0 to its duration.

    Parameters
    ----------
    record : Record
    dt : float
        New time step, s (> 0).
    method : {"polyphase", "linear"}
        ``"polyphase"`` (default): band-limited resampling with an anti-aliasing low-pass
        filter (`scipy.signal.resample_poly`, Kaiser window), for a ratio of old to new
        step that is a fraction p/q with p, q <= 1000. Use it to change the step of a
        record (and always to make it coarser: linear sampling would alias).
        ``"linear"``: samples of the record's own linear interpolant, the motion archquake
        integrates; refining by an integer factor leaves that motion unchanged.

    Returns
    -------
    Record
        floor(duration/dt) + 1 samples; ``metadata['resampled_from_dt_s']`` keeps the old step.
    """
    from fractions import Fraction

    dt = require_positive("resampling time step dt", dt, "s")
    n = int(math.floor(record.duration / dt * (1.0 + 1e-12))) + 1
    if n < 2:
        raise InvalidParameterError(
            f"resampling time step dt = {dt:g} s is longer than the record ({record.duration:g} s)")
    if method == "linear":
        values = record.acceleration(dt * np.arange(n))
    elif method == "polyphase":
        from scipy.signal import resample_poly

        ratio = Fraction(record.dt / dt).limit_denominator(1000)
        if abs(float(ratio) - record.dt / dt) > 1e-9 * record.dt / dt or ratio.numerator > 1000:
            raise InvalidParameterError(
                f"cannot resample from dt = {record.dt:g} s to {dt:g} s by a fraction p/q with "
                "p, q <= 1000; choose a step in a simple ratio to the record's, or method='linear'")
        values = resample_poly(record.accelerations, ratio.numerator, ratio.denominator)
        if values.size < n:  # (never expected; keep the length honest)
            values = np.concatenate([values, np.zeros(n - values.size)])
        values = values[:n]
    else:
        raise InvalidParameterError(
            f"resampling method must be 'polyphase' or 'linear', got {method!r}")
    meta = dict(record.metadata, resampled_from_dt_s=record.dt)
    return replace(record, accelerations=values, dt=dt, metadata=meta)


# -------------------------------------------------------------------------------------
# helpers
# -------------------------------------------------------------------------------------
def _err(path: Path, line: int | None, message: str) -> GroundMotionFormatError:
    where = f"{path}: line {line}" if line is not None else f"{path}"
    return GroundMotionFormatError(f"{where}: {message}".replace("\n", " "))


def _read_lines(path: Path) -> list[str]:
    try:
        info = path.stat()
        if not stat.S_ISREG(info.st_mode):  # a device, pipe or socket could stream forever
            kind = "a directory" if stat.S_ISDIR(info.st_mode) else "not a regular file"
            raise GroundMotionFormatError(
                f"{path}: is {kind} (a device, pipe or socket is not read); give the "
                "accelerogram file")
        if info.st_size > RECORD_FILE_MAX_BYTES:
            raise GroundMotionFormatError(
                f"{path}: is {info.st_size / 1e6:.0f} MB; an accelerogram file may hold at most "
                f"{RECORD_FILE_MAX_BYTES / 1e6:.0f} MB")
        data = path.read_bytes()
    except FileNotFoundError:
        raise GroundMotionFormatError(
            f"{path}: no such file; check the path of the accelerogram"
        ) from None
    except IsADirectoryError:
        raise GroundMotionFormatError(
            f"{path}: is a directory; give the accelerogram file"
        ) from None
    except OSError as exc:
        raise GroundMotionFormatError(f"{path}: cannot be read ({exc.strerror})") from None
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = data.decode("latin-1")  # numbers are ASCII; only comments can be non-UTF-8
    if not text.strip():
        raise GroundMotionFormatError(f"{path}: the file is empty; expected an accelerogram")
    return text.splitlines()


def _to_float(token: str) -> float | None:
    """A number token (Fortran 'D' exponents allowed), or None."""
    try:
        return float(token)
    except ValueError:
        try:
            return float(token.replace("D", "E").replace("d", "e"))
        except ValueError:
            return None


def _numbers(line: str) -> list[float] | None:
    tokens = [t for t in re.split(r"[,\s]+", line.strip()) if t]
    if not tokens:
        return None
    values = [_to_float(t) for t in tokens]
    return None if any(v is None for v in values) else values  # type: ignore[return-value]


def _check_at2_units(path: Path, line: str) -> None:
    upper = line.upper()
    for kind, ext in (("VELOCITY", ".VT2"), ("DISPLACEMENT", ".DT2")):
        if kind in upper:
            raise _err(path, 3, f"the header says this is a {kind.lower()} time series "
                       f"({ext}); archquake needs the acceleration file (.AT2, in g)")
    m = _UNITS_OF.search(line)
    if m and m.group("unit").upper().rstrip(".,") != "G":
        raise _err(path, 3, f"the header says the units are {m.group('unit')!r}, but .AT2 values "
                   "must be in g; convert the values to g (or to m/s^2 in a two-column CSV read "
                   "with units='m/s2')")


def _parse_npts_dt(path: Path, line: str) -> tuple[int, float]:
    m = _WEST2.search(line)
    if m:
        npts_text, dt_text = m.group("npts"), m.group("dt")
    else:
        m = _OLD.search(line)
        if not m:
            raise _err(path, 4, f"expected NPTS and DT, as 'NPTS=  4000, DT=   .0100 SEC' or "
                       f"'  3930   0.00500   NPTS, DT', got {line.strip()!r}")
        first_is_npts = m.group("labels").upper().lstrip().startswith("NPTS")
        npts_text, dt_text = m.group("a"), m.group("b")
        if not first_is_npts:
            npts_text, dt_text = dt_text, npts_text
    npts_value = _to_float(npts_text)
    dt = _to_float(dt_text)
    if npts_value is None or not float(npts_value).is_integer():
        raise _err(path, 4, f"NPTS must be a whole number, got {npts_text!r}")
    if dt is None or not math.isfinite(dt) or dt <= 0:
        raise _err(path, 4, f"DT must be a time step > 0 s, got {dt_text!r}")
    return int(npts_value), dt


def _unit_key(units: object) -> str:
    key = units.strip().lower().replace(" ", "") if isinstance(units, str) else None
    if key not in _UNITS:
        raise InvalidParameterError(
            f"units must be 'g', 'm/s2' or 'cm/s2' (= 'gal'), the units of the acceleration "
            f"column, got {units!r}"
        )
    return key


def _factor(scale: float, g: float) -> float:
    """Multiplier from the file's g to m/s^2 with the scale applied."""
    return require_finite("scale", scale) * require_gravity(g)


def _csv_factor(units: str, scale: float, g: float) -> float:
    per_unit = _UNITS[_unit_key(units)]
    if per_unit is None:
        return _factor(scale, g)
    return require_finite("scale", scale) * per_unit


def _tidy_dt(dt: float) -> float:
    """The shortest decimal within 1e-9 dt of ``dt`` (undoes rounding in a written time column)."""
    for digits in range(1, 16):
        candidate = float(f"{dt:.{digits}g}")
        if abs(candidate - dt) <= 1e-9 * dt:
            return candidate
    return dt


__all__ = [
    "Record",
    "SPACING_TOLERANCE",
    "UNITS",
    "baseline_corrected",
    "read_at2",
    "read_csv",
    "read_record",
    "resampled",
]
